"""hexapod.sensors: the contract's names and codes, the mounts check, the sonar ring as a frame
sensor, and a new kind of frame sensor plugged into the Runner beside the sonars."""

from array import array

from hexapod import robotcal, sensors

# The whole loop (runner, main, the stub machine) is imported by the functions that run it: the
# contract's checks run in the VM's small default heap.


def contract():
    s = sensors
    return (
        s.SENSOR_NAMES,
        (s.FRONT, s.LEFT_FRONT, s.LEFT_REAR, s.RIGHT_FRONT, s.RIGHT_REAR),
        s.STATUS_NAMES,
        (s.OK, s.OUT_OF_RANGE, s.NO_ECHO, s.STUCK, s.TOO_CLOSE, s.WAIT, s.PENDING),
        s.NO_DISTANCE,
        s.MIN_RANGE,
    )


def mounts_checked(cases):
    """check_mounts' message for each mounts value, None where accepted."""
    out = []
    for m in cases:
        try:
            sensors.check_mounts(m)
            out.append(None)
        except ValueError as e:
            out.append(str(e))
    return out


def robot_mounts_are_the_default():
    return robotcal.sensor_mounts(robotcal.load("default")) == sensors.DEFAULT_MOUNTS


class Ring:
    """A round robin that reports, per tick, (index, status, distance) from a script."""

    def __init__(self, script):
        self.script = script
        self.n = 0

    def tick(self, dist, status):
        i, st, d = self.script[self.n % len(self.script)]
        self.n += 1
        if i >= 0:
            status[i] = st
            dist[i] = d if st == sensors.OK else sensors.NO_DISTANCE
        return i


def ring_frames(script, n):
    """Sonars over a scripted ring: (index, faults) after each of n frames, then the distances and statuses."""
    s = sensors.Sonars(Ring(script))
    out = []
    for t in range(n):
        out.append((s.frame(20 * t), s.faults))
    return (out, s.distances, s.status)


class Battery:
    """A battery monitor that is not there yet: a frame sensor the Runner asks beside the sonars."""

    def __init__(self, log):
        self.log = log
        self.faults = 0
        self.mv = array("i", [0])
        self.frames = 0

    def frame(self, now_ms):
        self.frames += 1
        self.mv[0] = 7400 - (now_ms & 0xFF)
        if self.log is not None:
            self.log.append(("battery", now_ms))
        return 0


class Logged:
    """The sonar ring main.build made, noting in log when a frame asked it."""

    def __init__(self, ring, log):
        self.ring = ring
        self.split = ring.split
        self.log = log

    def tick(self, dist, status):
        import _stub_clock as clock

        self.log.append(("sonar", clock.ticks_ms()))
        return self.ring.tick(dist, status)


def _with_battery(log, logged):
    import _stub_clock as clock
    from runner import Runner
    from scenarios.runner import Loop

    loop = Loop()
    loop.plug(0x40, 0x41)
    r0 = loop.build()
    sonars = sensors.Sonars(Logged(r0.sonars.ring, log)) if logged else r0.sonars
    battery = Battery(log if logged else None)
    loop.r = Runner(r0.robot.geometry, r0.robot.servos, r0.bank, sonars, clock, others=(battery,))
    loop.r.robot.stand_up()
    return loop, sonars, battery


def extra_sensor(n):
    """n frames with a Battery beside the logged sonars: what was asked, in which order."""
    from hexapod import tick

    log = []
    loop, sonars, battery = _with_battery(log, True)
    r = loop.r
    loop.frames(n)
    return (
        battery.frames,
        r.frames,
        log[:4],
        [k for k, _ in log].count("sonar"),
        sonars.faults,
        r.sonar_faults,
        r.distances is sonars.distances,
        r.robot.mode == tick.STANDING,
        r.sonars is sonars and r.others == (battery,),
    )


def extra_sensor_heap(settle, n):
    """MicroPython only: heap bytes of n frames with a Battery beside the sonars, after settle
    frames; and how many frames the battery was asked."""
    from scenarios.heap import heap_bytes

    loop, sonars, battery = _with_battery(None, False)
    loop.frames(settle)
    r = loop.r

    def run(k):
        for _ in range(k):
            r.step()
            r.wait()

    return (heap_bytes(run, n), battery.frames)


def console_sonar(frames):
    """The console's `sonar` reply on the stub board (scenarios.console_rig) after `frames` frames."""
    from scenarios.console_rig import Board

    b = Board()
    b.frames(frames)
    return b.say("sonar")
