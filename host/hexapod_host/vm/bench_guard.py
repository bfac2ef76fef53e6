# Runs inside the MicroPython VM: times the walker's servo speed guard (reach.servo_radii, what
# Walker.configure runs) for each "gait,cycle_ms" case given. Prints one JSON line per case.
# Arguments: [module dir to put first on sys.path (the .mpy build)] [cases "g,c;g,c;..."]
import json
import sys
import time

if sys.argv[1]:
    sys.path.insert(0, sys.argv[1])

import robots.default as robot_file  # noqa: E402
from hexapod import geometry, reach, tick  # noqa: E402
from hexapod.gait import swing_stance_ticks  # noqa: E402

g = geometry.load(robot_file)
robot = tick.Robot(g, tick.default_servos(g), tick.FrameBuffer())
w = robot.walker
caps = [w.rho[i] if w.rho[i] < w.step else w.step for i in range(6)]
for case in sys.argv[2].split(";"):
    gait, cycle = [int(v) for v in case.split(",")]
    ticks = swing_stance_ticks(gait, cycle, [0, 0])
    out = [0] * 6
    t0 = time.ticks_us()
    reach.servo_radii(w, w.pose_body, ticks[0], ticks[1], w.lift, g.servo_step, caps, out)
    us = time.ticks_diff(time.ticks_us(), t0)
    print(json.dumps({"gait": gait, "cycle_ms": cycle, "ms": us // 1000, "radii": out}))
