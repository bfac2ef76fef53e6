"""Request tags on the board's console (docs/console.md "Request tags"; issue 21 items 2 and 3): a
tagged request's reply carries its tag, a slow command says `working` first, the tag's `#` starts
the request on a clean line whatever was half-typed before it, and echoing the tag copies no
reply. Runs on CPython and in the MicroPython VM, with the same transcript on both."""

from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)

LEG_1_RELAXED = "ok leg 1 angles 0.00 0.00 0.00 pulses 0 0 0 foot 240.0 0.0 32.0"
BAD_TAG = "err bad tag %r: allowed '#' and 1..9 digits, then a space and the command"


def run(rt, steps):
    """tests/scenarios/console_rig.py steps() on a fresh board: ("lines", bytes, frames=3),
    ("do", line) or ("mode",) each."""
    steps = [s + (3,) if s[0] == "lines" and len(s) == 2 else s for s in steps]
    return rt.call("scenarios.console_rig:steps", steps)


def test_tagged_replies_and_a_clean_line(rt):
    got = run(
        rt,
        [
            ("lines", b"#7 get 1\n"),
            ("lines", b"sta#8 get 1\n"),  # half-typed text before the tag: dropped, not run
            ("lines", b"walk 100 0 0#9 status\n"),
            ("lines", b"\x01\x02\x03#10 get 1\n"),  # stray bytes (a flash tool's raw REPL keys)
            ("lines", b"#11 gait wave\n"),
            ("lines", b"gait ripple\n"),  # untagged: one line, as before
            ("lines", b"#12\n"),
            ("lines", b"#1a get 1\n"),
            ("lines", b"#1234567890 get 1\n"),
            ("lines", b"#13 jump\n"),
            ("lines", b"#14 get\x03 1\n"),
            ("lines", b"#15 get 1 " + b"x" * 90 + b"\n"),
            ("lines", b"#16\tget 1\r\n"),
            ("do", "#17 get 1"),
            ("do", "get 1"),
            ("mode",),
        ],
    )
    w = got[2][0].split()
    got[2] = w[w.index("mode") : w.index("mode") + 2]
    assert got == [
        ["#7 " + LEG_1_RELAXED],
        ["#8 " + LEG_1_RELAXED],
        ["mode", "relaxed"],
        ["#10 " + LEG_1_RELAXED],
        ["#11 working", "#11 ok gait wave"],
        ["ok gait ripple"],
        ["#12 err nothing after the tag (a tagged request is '#N command ...')"],
        [BAD_TAG % "#1a"],
        [BAD_TAG % "#1234567890"],
        ["#13 err unknown command 'jump' (help lists them)"],
        ["#14 err non-text byte 0x03 in line (allowed: printable ASCII)"],
        ["#15 err line too long (at most 95 characters)"],
        ["#16 " + LEG_1_RELAXED],
        "#17 " + LEG_1_RELAXED,
        LEG_1_RELAXED,
        0,  # tick.RELAXED: nothing of the dropped text ran
    ]


def test_a_slow_command_says_working_first_only_when_tagged(rt):
    # save and sonar: their modules' imports first, a frame each (Console._waiting)
    steps = [("lines", b"stand\n", 300), ("lines", b"#1 sit\n"), ("lines", b"#2 save\n", 5)]
    steps.append(("lines", b"#3 sonar\n", 4))
    got = run(rt, steps)
    assert got[0] == ["ok mode moving"]  # untagged: one line, as before
    assert got[1] == ["#1 working", "#1 ok mode moving"]
    assert got[2] == ["#2 working", "#2 err save: no calibration file on this board"]  # the rig has no file
    # fast: no working line (its reply after its modules' imports, a frame each: Console._waiting)
    assert len(got[3]) == 1 and got[3][0].startswith("#3 ok front ")


def test_a_multi_line_reply_carries_its_tag_on_every_line(rt):
    got = run(rt, [("lines", b"#21 selftest\n", 12), ("lines", b"#22 selftest\n", 1), ("lines", b"#23 get 1\n", 1)])
    first = got[0]
    assert len(first) == 16 and all(x.startswith(("#21 ok ", "#21 err ")) for x in first), first  # 15 checks + end
    assert first[-1].split()[2] == "selftest"
    # A new line cuts a reply short: its end line, under its own tag, comes before the new reply.
    cut = got[1] + got[2]
    assert any(x.startswith("#22 err selftest") and "cut short" in x for x in cut), cut
    assert cut[-1] == "#23 " + LEG_1_RELAXED
    assert [x for x in cut if x.startswith("#22 err selftest")][0] == cut[-2]


def test_the_tag_echo_copies_no_reply(mp):
    """A tagged frame allocates what the untagged one does plus the tag's word in the line's split
    (64-128 bytes measured: a command word is an existing qstr, the tag a new string): the reply
    goes out as print's two arguments, never as a new string. A copied status reply would cost
    about 300 bytes more (its ~270 characters)."""
    lines = (b"status\n", b"#7 status\n", b"#123456789 status\n", b"get 2\n", b"#7 get 2\n")
    heap = mp.call("scenarios.console_rig:frame_heap", lines)
    status, tagged, long_tag, get2, tagged_get2 = heap
    assert 0 <= tagged - status <= 128 and 0 <= long_tag - status <= 128, (status, tagged, long_tag)
    assert 0 <= tagged_get2 - get2 <= 128, (get2, tagged_get2)
