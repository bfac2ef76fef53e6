"""The servo guard's answers for robots/default.py's own settings (hexapod.reach.find_table): made by
`python -m hexapod_host.guard_table default`, checked against the live guard by tests/test_guard_table.py.
Do not edit: run that again after changing the robot file or the guard."""

ROBOT = (
    300,
    850,
    1250,
    320,
    1300,
    282,
    -9000,
    9000,
    -9000,
    9000,
    -18000,
    0,
    875,
    -775,
    -4500,
    0,
    -775,
    -9000,
    -875,
    -775,
    -13500,
    -875,
    775,
    13500,
    0,
    775,
    9000,
    875,
    775,
    4500,
)
# (height, lift, reach disc radius of legs 1..6), 0.1 mm
DISCS = ((800, 300, (739, 725, 739, 739, 725, 739)),)
# (gait, cycle_ms, lift, step, height, reach discs x6, no-step peak cdeg a tick, servo radii x6,
# the swing's stroke gain, Q15: hexapod.budget.gain_steps)
SERVO = (
    (0, 1000, 300, 300, 800, (739, 725, 739, 739, 725, 739), 251, (121, 121, 121, 121, 121, 121), 55875),
    (1, 2220, 300, 300, 800, (739, 725, 739, 739, 725, 739), 175, (300, 300, 300, 300, 300, 300), 54353),
    (2, 2280, 300, 300, 800, (739, 725, 739, 739, 725, 739), 170, (300, 300, 300, 300, 300, 300), 54264),
    (3, 4320, 300, 300, 800, (739, 725, 739, 739, 725, 739), 176, (300, 300, 300, 300, 300, 300), 54396),
)
