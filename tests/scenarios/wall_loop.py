"""Wall following through the whole loop on the stub machine: the Pico board file, PCA9685 and HC-SR04
models, the virtual clock, main.build's runner and its follower."""

import _stub_clock as clock
import main
from scenarios import runner


class Loop(runner.Loop):
    """The Pico board's models (both PCA9685s plugged, the five sonars at 300 + 100 k mm) and, after
    build(), main.build's runner on the virtual clock."""

    def __init__(self):
        super().__init__()
        self.plug(0x40, 0x41)

    def at(self, *distances):
        """The five sonars' distances (0.1 mm): front, left front, left rear, right front, right rear."""
        for k in range(5):
            self.sonar[k].set_distance(distances[k])

    def state(self):
        f = self.r.follower
        return (f.mode_name, f.used, f.distance, f.angle, f.error, f.output, f.vx, f.vy, f.yaw, self.r.robot.mode)


def _standing():
    loop = Loop()
    loop.build().robot.stand_up()
    loop.frames(150)
    return loop


def follow_left(form=None):
    """(follow's code, state parallel at 80 mm, state nose in at 73 mm, follow_off's code, follower mode,
    robot mode, walker state, unsafe outputs after) through the loop, in `form` (None: the default)."""
    loop = _standing()
    r = loop.r
    loop.at(9000, 800, 800, 9000, 9000)
    code = r.follow("left", 800) if form is None else r.follow("left", 800, None, form)
    loop.frames(30)
    parallel = loop.state()
    loop.at(9000, 700, 760, 9000, 9000)  # 7 cm at the front sensor, nose toward the wall
    loop.frames(30)
    toward = loop.state()
    off = r.follow_off()
    bad = loop.frames(100)
    return (code, parallel, toward, off, r.follower.mode_name, r.robot.mode, r.robot.walker.state, bad)


def follow_heap(form="yaw"):
    """MicroPython only (gc.mem_alloc): (heap bytes of 300 following frames run twice in `form`, PID
    updates, follower mode, robot mode, frames held, the command (yaw rate, or crab's sideways speed) changed
    during the runs)."""
    import gc

    loop = _standing()
    r = loop.r
    f = r.follower
    loop.at(9000, 780, 800, 9000, 9000)  # 2 mm close, nose 0.6 deg in: the integral moves every update
    r.follow("left", 800, None, form)
    loop.frames(100)

    last = [f.yaw, f.vy]  # the command last seen, and how often it changed (small ints: nothing allocated)
    changes = [0]

    def run(n):
        for _ in range(n):
            r.step()
            r.wait()
            if f.yaw != last[0] or f.vy != last[1]:
                last[0] = f.yaw
                last[1] = f.vy
                changes[0] += 1

    before = f.updates
    run(300)
    gc.collect()
    gc.disable()
    a = gc.mem_alloc()
    run(300)
    heap = gc.mem_alloc() - a
    gc.enable()
    return (heap, f.updates - before, f.mode_name, r.robot.mode, r.held, changes[0] > 0)


def main_from_board_setting(form=None):
    """main.main for 300 frames with the board's follow setting (left, 120 mm, 60 mm/s, `form` unless None),
    the left wall at 115 mm: (mode, form, side, setpoint, speed, updated, distance, heading change (cdeg),
    sideways speed, robot mode)."""
    import boards.pico

    loop = Loop()
    loop.at(9000, 1150, 1150, 9000, 9000)
    setting = {"side": "left", "setpoint": 1200, "speed": 600}
    if form is not None:
        setting["form"] = form
    boards.pico.BOARD["follow"] = setting
    try:
        r = main.main(frames=300, clock=clock, boot="stand", calibrated=True)
    finally:
        boards.pico.BOARD["follow"] = None
    f = r.follower
    return (f.mode_name, f.form, f.side, f.setpoint, f.speed, f.updates > 10, f.distance, f.turned, f.vy, r.robot.mode)


def follow_refusals():
    """follow's codes relaxed and standing up, the first word of each bad call's ValueError, (mode,
    robot mode, requested speed) after, follow's code standing, (mode, robot mode) then."""
    loop = Loop()
    loop.sonar[0].set_distance(9000)  # nothing ahead
    r = loop.build()
    out = [r.follow("left", 800)]  # relaxed
    r.robot.stand_up()
    loop.frames(2)
    out.append(r.follow("right", 800))  # standing up
    for args in (("middle", 800), ("left", 0), ("left", 800, 99999), ("left", 800, None, "wave")):
        try:
            r.follow(*args)
            out.append("accepted")
        except ValueError as e:
            out.append(str(e).split(":")[0])
    loop.frames(150)
    out.append((r.follower.mode_name, r.robot.mode, r.robot.walker.req_vx))
    out.append(r.follow("right", 800))
    loop.frames(10)
    out.append((r.follower.mode_name, r.robot.mode))
    return out
