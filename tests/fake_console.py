"""A stand-in board console for the jog tool's tests: docs/console.md's jog and calibration lines,
answered with the real core (hexapod.leg IK/FK, hexapod.servo) on the default robot and its
calibration file. It starts standing, every foot at (130, 0, -80) mm in its leg frame. It also
serves a pseudo-terminal (serve_pty) so `hexapod jog --port` can open it like a board."""

import contextlib
import os
import threading

import robots.default
from hexapod import robotcal
from hexapod.leg import OK, Leg, describe
from hexapod.servo import ServoMap
from hexapod.units import format_fixed, parse_fixed

JOINTS = ("coxa", "femur", "tibia")
NEUTRAL = (1300, 0, -800)  # 0.1 mm, leg frame


class FakeConsole:
    def __init__(self):
        r = robots.default
        self.leg = Leg(coxa=r.COXA, femur=r.FEMUR, tibia=r.TIBIA, femur_offset=r.FEMUR_OFFSET, limits=r.LIMITS)
        maps = robotcal.servo_maps(robotcal.load("default"))
        self.cal = [[m.centre_us, 0, m.direction, m.min_us, m.max_us] for m in maps]
        self.ref = [m.ref_cdeg for m in maps]
        self.angles = [0] * 18
        self.driven = [True] * 18
        out = [0, 0, 0]
        assert self.leg.ik(*NEUTRAL, out) == OK
        for k in range(6):
            self.angles[3 * k : 3 * k + 3] = out
        self.saved = None
        self.lines = []

    def servo(self, k):
        c, t, d, lo, hi = self.cal[k]
        return ServoMap(centre_us=max(lo, min(hi, c + t)), direction=d, min_us=lo, max_us=hi, ref_cdeg=self.ref[k])

    def pulse_of(self, k, cdeg):
        return self.servo(k).raw(cdeg)

    def leg_line(self, n):
        k = 3 * (n - 1)
        a = self.angles[k : k + 3]
        pulses = [self.pulse_of(k + j, a[j]) if self.driven[k + j] else 0 for j in range(3)]
        foot = [0, 0, 0]
        self.leg.fk(a[0], a[1], a[2], foot)
        return "ok leg %d angles %s pulses %d %d %d foot %s" % (
            n,
            " ".join(format_fixed(v, 2) for v in a),
            *pulses,
            " ".join(format_fixed(v, 1) for v in foot),
        )

    def cal_line(self, n, j):
        k = 3 * (n - 1) + JOINTS.index(j)
        c, t, d, lo, hi = self.cal[k]
        ref = format_fixed(self.ref[k], 2)
        return "ok leg %d joint %s centre_us %d ref_deg %s trim %d dir %d min_us %d max_us %d" % (
            n,
            j,
            c,
            ref,
            t,
            d,
            lo,
            hi,
        )

    def set_angles(self, k, angles, who):
        """Accept the angles (cdeg) of servos k.. when every pulse is in range; else an err line."""
        for j, a in enumerate(angles):
            p = self.pulse_of(k + j, a)
            lo, hi = self.cal[k + j][3], self.cal[k + j][4]
            if not lo <= p <= hi:
                return "err %s: %d is outside leg %d %s's %d..%d us" % (who, p, k // 3 + 1, JOINTS[(k + j) % 3], lo, hi)
        for j, a in enumerate(angles):
            self.angles[k + j] = a
            self.driven[k + j] = True
        return None

    def request(self, line):
        self.lines.append(line)
        w = line.split()
        try:
            return self.do(w)
        except (ValueError, IndexError) as err:
            return "err %s: %s" % (w[0] if w else "", err)

    def do(self, w):
        cmd, args = w[0], w[1:]
        if cmd in ("stand", "sit", "relax", "stop"):
            return "ok mode %s" % {"stand": "moving", "sit": "moving", "relax": "relaxed", "stop": "standing"}[cmd]
        if cmd == "save":
            self.saved = [row[:] for row in self.cal]
            return "ok saved hexapod_cal.txt crc 1a2b"
        if cmd == "status":
            return "ok frames 100 held 0 overruns 0 mode jog"
        n = int(args[0])
        if not 1 <= n <= 6:
            raise ValueError("leg %r: allowed 1..6" % args[0])
        k = 3 * (n - 1)
        if cmd == "get" and len(args) == 1:
            return self.leg_line(n)
        if cmd in ("foot", "nudge") and len(args) == 4:
            v = [parse_fixed(a, 1) for a in args[1:]]
            if cmd == "nudge":
                if not all(self.driven[k : k + 3]):
                    return "err nudge: leg %d has a limp servo (foot first)" % n
                foot = [0, 0, 0]
                self.leg.fk(*self.angles[k : k + 3], foot)
                v = [foot[i] + v[i] for i in range(3)]
            out = [0, 0, 0]
            code = self.leg.ik(*v, out)
            if code != OK:
                return "err %s: %s" % (cmd, describe(code, self.leg.excess))
            return self.set_angles(k, out, cmd) or self.leg_line(n)
        j = JOINTS.index(args[1])
        if cmd == "joint" and len(args) == 3:
            a = list(self.angles[k : k + 3])
            a[j] = parse_fixed(args[2], 2)
            code = self.leg.accept(*a, [0, 0, 0])
            if code != OK:
                return "err joint: %s" % describe(code, self.leg.excess)
            return self.set_angles(k + j, [a[j]], "joint") or self.leg_line(n)
        if cmd == "pulse" and len(args) == 3:
            us = int(args[2])
            lo, hi = self.cal[k + j][3], self.cal[k + j][4]
            if not lo <= us <= hi:
                return "err pulse: %d is outside leg %d %s's %d..%d us" % (us, n, args[1], lo, hi)
            self.angles[k + j] = self.servo(k + j).angle(us)
            self.driven[k + j] = True
            return self.leg_line(n)
        if cmd == "cal" and len(args) == 2:
            return self.cal_line(n, args[1])
        if cmd in ("trim", "dir") and len(args) == 3:
            self.cal[k + j][1 if cmd == "trim" else 2] = int(args[2])
            return self.cal_line(n, args[1])
        return "err unknown command %r (help lists them)" % cmd


def serve_pty(console):
    """Answer console lines on a new pseudo-terminal; returns (slave path, stop())."""
    import tty

    master, slave = os.openpty()
    tty.setraw(slave)
    path = os.ttyname(slave)
    stopping = []

    def loop():
        buf = b""
        while not stopping:
            try:
                data = os.read(master, 256)
            except OSError:
                return
            buf += data
            while b"\n" in buf:
                raw, buf = buf.split(b"\n", 1)
                line = raw.decode(errors="replace").strip()
                if line and not stopping:
                    os.write(master, (console.request(line) + "\r\n").encode())

    t = threading.Thread(target=loop, daemon=True)
    t.start()

    def stop():
        stopping.append(1)
        for fd in (slave, master):
            with contextlib.suppress(OSError):
                os.close(fd)

    return path, stop
