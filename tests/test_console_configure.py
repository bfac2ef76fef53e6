"""The console stays within its frame while a gait is being checked (issue 22, point 3): `gait G`
runs the servo guard in the frames' slack (Robot.set_gait wait=False), its reply comes when the
guard is done, and a `status` sent meanwhile is answered in the very next frame.

The robot here has no guard table (robots/default_guard.py answers a gait at its own cycle
without solving): the worst case, every gait change solved live. Bound per frame, worked by
hand: two solves for the configure (tests/test_tick_configure.py) and none for the line.
"""

from console_rig import RIG

COUNT = """
class Count:
    n = 0
    on = True

def counted(inner):
    def ik(x, y, z, out, i=0):
        if Count.on:
            Count.n += 1
        return inner(x, y, z, out, i)
    return ik

for leg in r.robot.geometry.legs:
    leg.ik = counted(leg.ik)
inner_output = r.robot._output_plain

def quiet():
    # the frame's own six solves (the plain output calls leg.ik) are not the configure's
    Count.on = False
    code = inner_output()
    Count.on = True
    return code

r.robot._output_plain = quiet
r.robot._table = r.robot.walker.table = None  # no guard table: every gait solved live
"""

SCRIPT = """
frames(150)
print(repr(say("stand")))
frames(150)
print(repr(say("walk 40 0 0")))
before = len(REPLIES)
reader.feed(b"gait ripple\\n")
Count.n = 0
frames(1)
print(repr([Count.n, len(REPLIES) - before, r.robot.configuring()]))
reader.feed(b"status\\n")
Count.n = 0
frames(1)
print(repr([Count.n, REPLIES[-1][:10], r.robot.configuring(), r.robot.gait]))
worst = 0
n = 0
def gait_replied():
    for line in REPLIES[before + 1:]:
        if "gait" in line:
            return True
    return False

while not gait_replied() and n < 4000:
    Count.n = 0
    frames(1)
    n += 1
    if Count.n > worst:
        worst = Count.n
    if n % 40 == 0:
        reader.feed(b"walk 40 0 0\\n")  # the driver keeps walking (the console's walk timeout is 1 s)
        frames(1)
        n += 1
print(repr([worst, n, REPLIES[before + 1:]]))
print(repr(say("gait")))
"""


def test_a_status_during_a_gait_change_is_answered_in_the_next_frame(both_runtimes):
    cp, mp = both_runtimes(RIG + COUNT + SCRIPT, heapsize="4m")
    assert cp == mp
    rows = [eval(line) for line in cp.splitlines()]  # noqa: S307 (our own reprs)
    assert rows[0] == "ok mode moving" and rows[1].startswith("ok ")
    solves, replies, configuring = rows[2]
    assert solves <= 2 and replies == 0 and configuring  # taken, no reply yet: it is being checked
    solves, status, configuring, gait = rows[3]
    assert solves <= 2 and status == "ok frames " and configuring and gait == 0  # still the tripod
    worst, n, later = rows[4]
    assert worst <= 2  # every frame of the check
    assert 100 < n < 4000
    assert [line for line in later if "gait" in line] == ["ok gait ripple"]
    assert rows[5] == "ok gait ripple"


TAGGED = """
frames(150)
say("stand")
frames(150)
before = len(REPLIES)
reader.feed(b"#5 gait ripple\\n")
n = 0
while not any(x.startswith("#5 ok") or x.startswith("#5 err") for x in REPLIES[before:]) and n < 4000:
    frames(1)
    n += 1
print(repr(REPLIES[before:]))
"""


def test_a_tagged_gait_change_says_working_then_its_late_reply_carries_the_tag(both_runtimes):
    # The link (docs/console.md, "Request tags") pairs the reply checked over frames with its request.
    cp, mp = both_runtimes(RIG + COUNT + TAGGED, heapsize="4m")
    assert cp == mp
    assert eval(cp.splitlines()[-1]) == ["#5 working", "#5 ok gait ripple"]  # noqa: S307 (our own repr)
