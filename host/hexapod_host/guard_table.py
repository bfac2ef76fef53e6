"""The guard table of a robot file (hexapod.reach.find_table): the live guard's answers for its own
settings, written as robots/NAME_guard.py. Run after changing a robot file or the guard:

    .venv/bin/python -m hexapod_host.guard_table default > robots/default_guard.py

tests/test_guard_table.py checks the shipped table against the live guard, entry by entry.
"""

import sys

from hexapod import budget, reach
from hexapod.body import Body
from hexapod.gait import NAMES, swing_stance_ticks
from hexapod.reach import robot_key
from hexapod.walk import Walker


def live_entries(geometry):
    """(discs, servo) rows the table holds, each found by the live guard (level body, the robot
    file's height, the walker's default lift and step, each gait at its robot file's cycle)."""
    w = Walker(geometry)
    body = Body(geometry)
    lift = w.lift
    step = w.step
    height = geometry.body_height
    rho = [0] * 6
    reach.disc_radii(w, body, lift, rho)
    discs = [(height, lift, tuple(rho))]
    servo = []
    for gait in range(len(NAMES)):
        cycle = geometry.gait_cycle_ms[gait]
        swing, stance = swing_stance_ticks(gait, cycle, [0, 0])
        caps = [rho[i] if rho[i] < step else step for i in range(6)]
        srho = [0] * 6
        peak = reach.servo_radii(w, body, swing, stance, lift, geometry.servo_step, caps, srho)
        for _ in budget.gain_steps(w, swing, [0, 0]):
            pass
        servo.append((gait, cycle, lift, step, height, tuple(rho), peak, tuple(srho), w.next_gain))
    return discs, servo


def table_text(robot_module):
    """robots/NAME_guard.py's text for a robot file module."""
    from hexapod import geometry as geo

    g = geo.load(robot_module)
    discs, servo = live_entries(g)
    lines = [
        '"""The servo guard\'s answers for robots/%s.py\'s own settings (hexapod.reach.find_table): made by' % g.name,
        "`python -m hexapod_host.guard_table %s`, checked against the live guard by tests/test_guard_table.py."
        % g.name,
        'Do not edit: run that again after changing the robot file or the guard."""',
        "",
        "ROBOT = %r" % (robot_key(g),),
        "# (height, lift, reach disc radius of legs 1..6), 0.1 mm",
        "DISCS = (",
    ]
    lines += ["    %r," % (row,) for row in discs]
    lines += [
        ")",
        "# (gait, cycle_ms, lift, step, height, reach discs x6, no-step peak cdeg a tick, servo radii x6,",
        "# the swing's stroke gain, Q15: hexapod.budget.gain_steps)",
        "SERVO = (",
    ]
    lines += ["    %r," % (row,) for row in servo]
    lines += [")", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    name = sys.argv[1] if len(sys.argv) > 1 else "default"
    sys.stdout.write(table_text(__import__("robots." + name, None, None, ("NAME",))))
