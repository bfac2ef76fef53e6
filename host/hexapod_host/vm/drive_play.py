# A driver's command stream on the kinematic walker (robots/default.py on a FrameBuffer), the same
# source on CPython and in the MicroPython VM (hexapod_host.drives.play puts COMMANDS, GAIT and
# TICKS in front of it). Stands up, switches to GAIT, then runs TICKS 20 ms ticks; before tick k
# every line with t_ms <= 20 k not yet taken is asked as the console asks it (set_gait wait=False,
# then walk or stop). Prints integers only, one line per tick:
#   T held dbx dby dpsi psi vx vy yaw gait margin
# held 1 when the walker held the body this tick; dbx, dby the body's move in the walker's ground
# frame (body.FINE units: 1/16 of 0.1 mm) and dpsi its turn (1e-4 degree), psi the heading before
# the tick (1e-4 degree); vx vy yaw the scaled command in force (0.1 mm/s, cdeg/s); gait the gait
# walked; margin the body centre's distance inside the planned stance feet's polygon (0.1 mm,
# hexapod.stability). And "R line what code" for a command the robot refused, "F code" for a frame
# held back, "E" at the end. COMMANDS rows: (line, t_ms, vx, vy, yaw, gait or -1, stop).
import standing

import robots.default as d
from hexapod import geometry, tick
from hexapod.body import FINE_SHIFT
from hexapod.stability import support_margin

DEG360 = 3600000  # the walker's heading unit (1e-4 degree) per turn


def ask(robot, command):
    """One stream line asked as the console asks it (a gait first, wait=False, then walk or stop);
    returns what was refused, [(what, code)] (hexapod_host.physics.drive asks the same way)."""
    _, _, vx, vy, yaw, gait, stop = command
    refused = []
    if gait >= 0 and gait != robot.gait:
        code = robot.set_gait(gait, wait=False)
        if code:
            refused.append(("gait", code))
    code = robot.stop() if stop else robot.walk(vx, vy, yaw)
    if code:
        refused.append(("stop" if stop else "walk", code))
    return refused


def play(commands, gait, ticks):
    g = geometry.load(d)
    robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
    w = robot.walker
    now = 20 * standing.stand(robot, lambda n: robot.tick(20 * n))
    if gait != robot.gait:
        code = robot.set_gait(gait)
        if code:
            print("R 0 gait %d" % code)
    xs = [0] * 6
    ys = [0] * 6
    down = [False] * 6
    nxt = 0
    for k in range(ticks):
        while nxt < len(commands) and commands[nxt][1] <= 20 * k:
            for what, code in ask(robot, commands[nxt]):
                print("R %d %s %d" % (commands[nxt][0], what, code))
            nxt += 1
        held0 = w.held
        bx = w.bx
        by = w.by
        psi = w.psi
        # A stance foot's ground-frame place moves only when the walker moves its origin to the
        # body (walk._REANCHOR, after ~26 m): then by the body's place, which this adds back.
        j = 0
        while j < 5 and w.su[j] >= 0:
            j += 1
        px = w.px[j]
        py = w.py[j]
        code = robot.tick(now)
        now += 20
        if code:
            print("F %d" % code)
        dbx = w.bx + px - w.px[j] - bx
        dby = w.by + py - w.py[j] - by
        dpsi = w.psi - psi
        if dpsi > DEG360 // 2:
            dpsi -= DEG360
        elif dpsi < -DEG360 // 2:
            dpsi += DEG360
        for i in range(6):
            xs[i] = w.fx[i] >> FINE_SHIFT
            ys[i] = w.fy[i] >> FINE_SHIFT
            down[i] = w.su[i] < 0
        c = w.cmd
        print(
            "T %d %d %d %d %d %d %d %d %d %d"
            % (w.held - held0, dbx, dby, dpsi, psi, c[0], c[1], c[2], w.clock.gait, support_margin(xs, ys, down))
        )
    print("E")


if __name__ == "__main__":
    play(COMMANDS, GAIT, TICKS)  # noqa: F821 (put in front of this source by hexapod_host.drives.play)
