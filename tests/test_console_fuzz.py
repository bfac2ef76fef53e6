"""10,000 random and malformed lines into the console (hypothesis): every reply is one `ok` or
`err` line, never an internal error, the loop goes on, and no servo is ever driven outside its
calibrated range. CPython drives the dispatcher directly (a frame every few lines, the PCA9685
models checked then); a smaller batch goes through the line reader in the MicroPython VM."""

import ast
import json
import random
import subprocess
import sys

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hexapod_host import ROOT
from tests.console_rig import RIG, clean_stubs  # noqa: F401 (autouse fixture)

WORDS = [
    "help",
    "status",
    "stand",
    "sit",
    "relax",
    "foot",
    "nudge",
    "joint",
    "pulse",
    "get",
    "walk",
    "stop",
    "gait",
    "sonar",
    "wall",
    "pid",
    "cal",
    "trim",
    "dir",
    "range",
    "save",
    "load",
    "defaults",
]
ARGS = ["1", "2", "6", "0", "7", "-1", "coxa", "femur", "tibia", "left", "right", "off", "tripod", "wave", "ripple"]
NUMBERS = st.one_of(
    st.integers(-3000, 3000).map(str),
    st.decimals(-600, 600, places=3, allow_nan=False, allow_infinity=False).map(str),
    st.sampled_from(["1e3", "nan", "inf", "-", ".", "1.2.3", "0x10", "+5", "--1", "9" * 12, "", "1_000"]),
)
ARG = st.one_of(st.sampled_from(ARGS), NUMBERS, st.text(max_size=6))
COMMAND = st.tuples(st.sampled_from(WORDS), st.lists(ARG, max_size=5)).map(lambda t: " ".join([t[0], *t[1]]))
# Mostly commands shaped right with sensible numbers, so that the robot really moves and
# recalibrates; then anything at all.
SHAPED = st.one_of(
    st.builds(
        lambda leg, x, y, z: "foot %d %d %d %d" % (leg, x, y, z),
        st.integers(1, 6),
        st.integers(40, 260),
        st.integers(-150, 150),
        st.integers(-180, 60),
    ),
    st.builds(lambda leg, d: "nudge %d %s %s %s" % (leg, d, d, d), st.integers(1, 6), st.integers(-30, 30)),
    st.builds(
        lambda leg, j, a: "joint %d %s %d" % (leg, j, a),
        st.integers(1, 6),
        st.sampled_from(["coxa", "femur", "tibia"]),
        st.integers(-190, 190),
    ),
    st.builds(
        lambda leg, j, u: "pulse %d %s %d" % (leg, j, u),
        st.integers(1, 6),
        st.sampled_from(["coxa", "femur", "tibia"]),
        st.integers(400, 2600),
    ),
    st.builds(
        lambda leg, j, t: "trim %d %s %d" % (leg, j, t),
        st.integers(1, 6),
        st.sampled_from(["coxa", "femur", "tibia"]),
        st.integers(-350, 350),
    ),
    st.builds(
        lambda leg, j, a, b: "range %d %s %d %d" % (leg, j, a, b),
        st.integers(1, 6),
        st.sampled_from(["coxa", "femur", "tibia"]),
        st.integers(450, 1600),
        st.integers(1400, 2600),
    ),
    st.builds(
        lambda leg, j, d: "dir %d %s %d" % (leg, j, d),
        st.integers(1, 6),
        st.sampled_from(["coxa", "femur", "tibia"]),
        st.sampled_from([1, -1, 0]),
    ),
    st.builds(
        lambda a, b, c: "walk %d %d %d" % (a, b, c),
        st.integers(-350, 350),
        st.integers(-350, 350),
        st.integers(-95, 95),
    ),
    st.sampled_from(["stand", "sit", "relax", "stop", "defaults", "status", "sonar", "wall left 10", "wall off"]),
)
LINE = st.one_of(
    SHAPED, SHAPED, COMMAND, st.text(max_size=40), st.binary(max_size=40).map(lambda b: b.decode("latin-1"))
)

NS = {}


def rig():
    if not NS:
        exec(RIG, NS)  # noqa: S102 (the shared rig source)
        NS["count"] = 0
        NS["oks"] = {}
    return NS


def in_range(ns):
    r = ns["r"]
    bad = [
        (k, p)
        for k, (p, s) in enumerate(zip(r.robot.pulses, r.robot.servos, strict=True))
        if p and not s.min_us <= p <= s.max_us
    ]
    return bad


@settings(max_examples=200, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
@given(st.lists(LINE, min_size=50, max_size=50))
def ten_thousand_lines(lines):
    ns = rig()
    con = ns["con"]
    for k, line in enumerate(lines):
        frames = ns["r"].frames
        reply = con.do(line)
        if reply is not None and reply.startswith("#"):
            reply = reply.split(" ", 1)[1]  # a tagged line ('#12 get 2': random text can make one)
        if reply and reply.startswith("ok"):
            ns["oks"][line.split()[0]] = ns["oks"].get(line.split()[0], 0) + 1
        if reply is not None:
            assert reply == "ok" or reply.startswith(("ok ", "err ")), (line, reply)
            assert "\n" not in reply and "internal error" not in reply, (line, reply)
        else:
            assert not line.replace("\t", " ").split()
        assert in_range(ns) == [], line
        if k % 2 == 1:
            ns["frames"](1)
            assert ns["r"].frames == frames + 1
            assert ns["unsafe"]() == [], line
        ns["count"] += 1
    con.do("wall off")
    con.do("stop")
    r = ns["r"]
    for _ in range(400):  # let moves finish, so the next example can jog and recalibrate
        if r.robot.mode != 2 and r.robot.mode != 4:  # tick.MOVING, tick.WALKING
            break
        ns["frames"](1)
        assert ns["unsafe"]() == []
    if r.robot.mode == 5 and ns["count"] % 100 == 0:  # every other example from a jog: feet placed
        # where a stand can start from (a leg left behind its coxa or at a limit refuses `stand`,
        # naming the leg), so that the next example may stand up and walk
        for leg in range(1, 7):
            con.do("foot %d 130 0 -80" % leg)
    if ns["count"] % 200 == 0 and con.do("stand").startswith("ok"):
        # every fourth example starts standing, so walks are tried from there whatever the lines
        # before left behind (the coverage check below must not hang on the examples' order)
        for _ in range(400):
            if r.robot.mode != 2:  # tick.MOVING
                break
            ns["frames"](1)
            assert ns["unsafe"]() == []


def _vm_batch(seed, n):
    rnd = random.Random(seed)
    out = bytearray()
    for _ in range(n):
        kind = rnd.random()
        if kind < 0.5:
            w = rnd.choice(WORDS)
            args = [
                rnd.choice(
                    ARGS + [str(rnd.randint(-400, 2600)), "%d.%d" % (rnd.randint(-300, 300), rnd.randint(0, 99))]
                )
                for _ in range(rnd.randint(0, 4))
            ]
            out += (" ".join([w, *args])).encode()
        elif kind < 0.8:
            out += bytes(rnd.randint(32, 126) for _ in range(rnd.randint(0, 120)))
        else:
            out += bytes(rnd.randint(0, 255) for _ in range(rnd.randint(0, 60)))
        out += rnd.choice([b"\n", b"\r\n", b"\r"])
    return bytes(out)


def test_random_bytes_through_the_reader_in_the_vm(mp):
    data = _vm_batch(8, 600)
    src = (
        RIG
        + """
data = %r
reader.feed(data)
bad = []
n0 = r.frames
while reader.pos < len(data):
    frames(1)
    bad += unsafe()
frames(2)
def untagged(x):  # a random '#12 ' starts a tagged request: its reply is '#12 ok ...'
    return x.split(" ", 1)[1] if x.startswith("#") and " " in x else x
odd = [x for x in map(untagged, REPLIES) if not (x == "ok" or x.startswith("ok ") or x.startswith("err "))]
print(repr((r.frames - n0 > 0, bad, odd, [x for x in REPLIES if "internal" in x], len(REPLIES))))
"""
        % (data,)
    )
    ran, bad, not_replies, internal, n = ast.literal_eval(mp.run(src, heapsize="4m").strip().splitlines()[-1])
    assert ran and bad == [] and not_replies == [] and internal == []
    assert n >= 300  # blank lines get no reply; a random \n or \r inside a line ends it


def run_property():
    """The 10,000 lines in this process: [lines run, accepted commands by word, ticks, frames]."""
    NS.clear()
    ten_thousand_lines()
    r = NS["r"]
    return [NS["count"], NS["oks"], r.robot.ticks, r.frames]


def test_the_property_really_runs_ten_thousand_lines():
    # In a fresh interpreter: what the examples reach must not depend on what other tests left in
    # this process (under xdist it did: 0 accepted walks or stands after some orders; the leak
    # itself is issue 24's).
    code = "import hexapod_host, json\nfrom tests import test_console_fuzz as t\nprint(json.dumps(t.run_property()))"
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-3000:]
    count, oks, ticks, frames = json.loads(proc.stdout.strip().splitlines()[-1])
    assert count == 10000
    # the lines reached deep states: jogs, walks and recalibrations happened
    assert (
        min(oks.get(w, 0) for w in ("foot", "nudge", "joint", "pulse", "trim", "range", "dir", "walk", "stand")) >= 5
    ), sorted(oks.items())
    assert ticks == frames
