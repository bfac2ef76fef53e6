"""What the view draws from: a Source steps the robot (or reads it) one frame at a time and
describes where it is in a plain dict, the same keys for every source (docs/view.md).

snapshot() keys, units as the view shows them (mm, degrees, rad for the body's yaw):

    frame         frames since the source started (int)
    time_s        the source's own clock, s
    pulses        the 18 pulse widths sent, us (0: none yet), legs 1-6 x coxa, femur, tibia
    angles        the 18 joint angles they stand for, cdeg (inverse servo maps)
    legs          per leg its coxa axis, femur joint, knee and foot, [x, y, z] mm, body frame (FK)
    stance        per leg, True when its foot is on the ground
    body          {"x", "y", "yaw"}: the body centre in the world, mm and rad; "z": coxa height
                  above the ground, mm
    distances     the five sonars' last readings, mm (None when not ok), drivers.hcsr04 order
    sonar_status  the five sonars' status names (hexapod.sensors.STATUS_NAMES)
    mode          the robot's mode name (hexapod.tick.MODE_NAMES)
    follow        the wall follower: mode, side, setpoint_mm, error_mm, output_dps, sensor_state
    counters      frames, held, overruns, bus_failed, reinit, sonar_faults
    extra         what only this source knows (the simulator: the trial, the true wall distance)

describe() holds what does not change while the page is open: the sonars' mounts [x, y mm,
heading rad] ("sensors"), the body's half length and width ("body_half"), the sonars' brackets
from the body's edge [x1, y1, x2, y2] ("brackets"), and for a simulated room its walls and finish.
"""

from hexapod_host.wall.room import grounded


class Source:
    """The interface: a source for the view. `steppable` sources (a simulator) can be paused and
    stepped by the page; a live board cannot and only reports."""

    name = "source"
    frame_s = 0.02  # one frame of the board's loop
    steppable = False

    def describe(self):
        raise NotImplementedError

    def step(self):
        """Advance one frame (a simulator) or take in what arrived (a board)."""
        raise NotImplementedError

    def snapshot(self):
        raise NotImplementedError

    def done(self):
        """True when there is nothing more to step (the simulator: the trial is over)."""
        return False

    def restart(self):
        """Start over (the simulator: its next trial). A live board has nothing to restart."""

    def close(self):
        """Let go of what the source holds (a process, a serial port)."""


def pose(body, pulses):
    """The snapshot's pulses, angles, legs and stance from 18 pulses (us), through a
    hexapod_host.wall.room.Body (the board's servo maps, the robot file's legs): the wall
    simulator's own path from pulses to feet. None while some leg has no pulse yet."""
    if not all(pulses[3 * i] for i in range(6)):
        return None
    angles = body.joint_angles(pulses)
    legs = body.leg_points(angles)
    feet = [leg[3] for leg in legs]
    return {
        "pulses": list(pulses),
        "angles": angles,
        "legs": [[list(p) for p in leg] for leg in legs],
        "stance": grounded(feet),
    }
