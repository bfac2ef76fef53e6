"""Walker._rescale and Walker._aim_at against the plain forms they replaced (hexapod/walk.py's
_rescale, half_stance, _outward and _aim_at as they were at c39d877, kept here as the reference), and
hexapod/_fixmath_viper.py's sin against fixmath.sin, on drawn cases. Runs on CPython, in the VM and on
the emulated Pico (which gets the scenarios package on its filesystem)."""

from scenarios.lcg import Lcg

import robots.default as robot_file
from hexapod import fixmath, geometry, walk
from hexapod.fixmath import cos, isqrt, mul_q15, sin


def half_stance(self, i, vx, vy, w):
    self.aim_for(vx, vy, w)
    self.target(i, self._xy)
    dx = (self._xy[0] - self.nx[i]) >> 4
    dy = (self._xy[1] - self.ny[i]) >> 4
    return isqrt(dx * dx + dy * dy)


def outward(self, i):
    g = self.geometry
    mx = g.mount_x[i]
    my = g.mount_y[i]
    tx = self._xy[0] >> 4
    ty = self._xy[1] >> 4
    sx = (self.nx[i] >> 4 << 1) - tx
    sy = (self.ny[i] >> 4 << 1) - ty
    a = isqrt((tx - mx) * (tx - mx) + (ty - my) * (ty - my))
    b = isqrt((sx - mx) * (sx - mx) + (sy - my) * (sy - my))
    return (a if a > b else b) - g.neutral_reach


def plain_rescale(self):
    vx = self.req_vx
    vy = self.req_vy
    w = self.req_yaw
    half_ms = self.clock.stance_ticks * 20 >> 1
    turn = w * half_ms // 1000
    k = 1000
    if turn > 9000 or turn < -9000:
        k = 9000 * 1000 // (turn if turn > 0 else -turn)
    g = self.geometry
    three = self.clock.stance_ticks * 2 <= self.clock.cycle_ticks
    tries = 0
    while k > 0:
        tries += 1
        worst = -1
        for i in range(6):
            e = half_stance(self, i, vx * k // 1000, vy * k // 1000, w * k // 1000)
            lim = self.rho[i] if self.rho[i] < self.step else self.step
            if self.srho[i] < lim:
                lim = self.srho[i]
            if e > lim:
                kk = k * lim // e
                if worst < 0 or kk < worst:
                    worst = kk
            out = outward(self, i) if three else 0
            if out > g.stance_out_max > 0:
                kk = k * g.stance_out_max // out
                if worst < 0 or kk < worst:
                    worst = kk
        if worst < 0:
            break
        k = worst - 1 if worst >= k else worst
    if k < 0:
        k = 0
    for i in range(6):
        lim = self.rho[i] if self.rho[i] < self.step else self.step
        if 0 < self.srho[i] < lim:
            lim = self.srho[i]
        lim += 16
        self.stance_rho[i] = lim if lim < self.rho[i] else self.rho[i]
    self.scale_permille = k
    self.cmd[0] = vx * k // 1000
    self.cmd[1] = vy * k // 1000
    self.cmd[2] = w * k // 1000
    return tries


def plain_aim_at(self, vx, vy, w):
    half_ms = self.clock.stance_ticks * 20 >> 1
    turn = w * half_ms // 1000
    a = self._aim
    a[0] = cos(turn)
    a[1] = sin(turn)
    sx = vx * half_ms * 16 // 1000
    sy = vy * half_ms * 16 // 1000
    c = cos(turn >> 1)
    s = sin(turn >> 1)
    a[2] = mul_q15(sx, c) - mul_q15(sy, s)
    a[3] = mul_q15(sx, s) + mul_q15(sy, c)


def _state(w):
    return (w.scale_permille, list(w.cmd), list(w.stance_rho), list(w._aim), list(w._aim_key), list(w._xy))


def rescales(cases, fast):
    """((count, slowed, far, turned, many, zero, differ), the first three differences): _rescale against
    plain_rescale on drawn commands, gaits, cycle times, steps, discs and outward limits. fast False:
    the plain code (CPython's and CircuitPython's) on a MicroPython with viper too."""
    draw = Lcg().draw
    saved = walk._rescale_fast
    if not fast:
        walk._rescale_fast = None
    try:
        return _rescales(cases, draw)
    finally:
        walk._rescale_fast = saved


def _rescales(cases, draw):
    G = geometry.load(robot_file)
    w = walk.Walker(G)
    count = differ = slowed = far = turned = many = zero = 0
    samples = []
    NX = list(w.nx)
    NY = list(w.ny)
    for n in range(cases):
        w.clock.set(draw(2) % 4, 500 + draw(12) % 4000)
        w.step = 50 + draw(10) % 551
        # One case in four: feet farther than 2**15 fine units (204.8 mm) from the body's centre.
        for i in range(6):
            w.nx[i] = NX[i] * (3 if n % 4 == 1 else 1) + draw(8) - 128
            w.ny[i] = NY[i] * (3 if n % 4 == 1 else 1) + draw(8) - 128
        for i in range(6):
            # Mostly discs as a pose gives them (10..80 mm), now and then none or a tiny one.
            w.rho[i] = draw(10) % (8, 30, 1024)[draw(2) % 3] if draw(6) == 0 else 100 + draw(10) % 700
            w.srho[i] = (0, 1, 600)[draw(2) % 3] if draw(6) == 0 else 100 + draw(9)
        G.stance_out_max = (0, 10, 2000)[draw(2) % 3] if draw(2) == 0 else 10 + draw(7)
        # Speeds up to the limits, often small ones (found in one try), now and then none at all.
        w.req_vx = (draw(13) % 6001 - 3000) >> (draw(4) % 8)
        w.req_vy = (draw(13) % 6001 - 3000) >> (draw(4) % 8)
        w.req_yaw = (draw(15) % 18001 - 9000) >> (0 if draw(1) else draw(4) % 14)
        if n % 17 == 0:
            w.req_vx = w.req_vy = 0
        if n % 3 == 0:  # the scratch and aim as any earlier tick or try left them
            w.aim_for(draw(8), draw(8), draw(8))
            w._xy[0] = draw(16)
            w._xy[1] = draw(16)
        keep = (list(w._aim), list(w._aim_key), list(w._xy))
        tries = plain_rescale(w)
        want = _state(w)
        w._aim[:] = walk._words(6)
        for j in range(4):
            w._aim[j] = keep[0][j]
            w._aim_key[j] = keep[1][j]
        w._xy[0] = keep[2][0]
        w._xy[1] = keep[2][1]
        w.scale_permille = -7
        w._rescale()
        got = _state(w)
        if got != want:
            differ += 1
            if differ < 4:
                samples.append((n, want, got))
        count += 1
        slowed += w.scale_permille < 1000
        zero += w.scale_permille == 0
        many += tries >= 3
        half_ms = w.clock.stance_ticks * 10
        turned += w.req_yaw * half_ms // 1000 > 9000 or w.req_yaw * half_ms // 1000 < -9000
        three = w.clock.stance_ticks * 2 <= w.clock.cycle_ticks
        if three and G.stance_out_max > 0 and w.scale_permille > 0:
            # the outward limit set the scale: the plain form without it would have scaled less
            o = G.stance_out_max
            G.stance_out_max = 0
            plain_rescale(w)
            far += w.scale_permille > want[0]
            G.stance_out_max = o
    return (count, slowed, far, turned, many, zero, differ), samples


def aims(cases):
    """(count, odd, differ): Walker._aim_at against plain_aim_at on drawn commands."""
    draw = Lcg().draw
    w = walk.Walker(geometry.load(robot_file))
    count = differ = odd = 0
    for _ in range(cases):
        w.clock.set(draw(2) % 4, 500 + draw(12) % 4000)
        vx = (draw(13) % 6001 - 3000) >> (draw(4) % 8)
        vy = (draw(13) % 6001 - 3000) >> (draw(4) % 8)
        yaw = (draw(15) % 18001 - 9000) >> (draw(4) % 14)
        plain_aim_at(w, vx, vy, yaw)
        want = list(w._aim)
        for j in range(4):
            w._aim[j] = draw(16)
        w._aim_at(vx, vy, yaw)
        differ += list(w._aim) != want
        odd += (yaw * w.clock.stance_ticks * 10 // 1000) % 2 == 1 and yaw < 0
        count += 1
    return (count, odd, differ)


def sines(cases):
    """(count, differ, walk.sin is the viper sin): MicroPython with viper only."""
    from hexapod._fixmath_viper import sin as _sin

    draw = Lcg().draw
    count = differ = 0
    for n in range(cases):
        c = (draw(30) - (1 << 29)) >> (n % 30) if n % 3 else n * 25 - 45000 + (n >> 1) % 3 - 1
        differ += _sin(c) != fixmath.sin(c)
        count += 1
    return (count, differ, walk.sin is _sin)


def rescale_fast():
    """repr of walk._rescale_fast (None where there is no viper rescale)."""
    return repr(walk._rescale_fast)


def bad_commands(commands):
    """The name each bad Walker.command is refused by ("ACCEPTED" if not), and whether the walker is unchanged."""
    w = walk.Walker(geometry.load(robot_file))
    for i in range(6):
        w.rho[i] = 500
    w.command(800, 0, 300)
    before = (w.state, list(w.cmd), w.scale_permille, w.req_vx, w.req_vy, w.req_yaw)
    out = []
    for args in commands:
        try:
            w.command(*args)
            out.append("ACCEPTED")
        except ValueError as e:
            out.append(str(e).split(":")[0])
    out.append((w.state, list(w.cmd), w.scale_permille, w.req_vx, w.req_vy, w.req_yaw) == before)
    return out


def roots(cases):
    """(count, wrong, gaitswitch's and stability's isqrt are the viper one) over the squares' edges
    k^2 - 1, k^2 (k up to 2**15), drawn n < 2**30 and n <= 0, each root checked against
    x^2 <= n < (x + 1)^2 (0 for n <= 0), the plain and (where there is one) the viper root."""
    from hexapod import gaitswitch, stability

    try:
        from hexapod._fixmath_viper import isqrt as _isqrt
    except ImportError:  # a MicroPython without viper
        _isqrt = None
    draw = Lcg().draw
    count = wrong = 0
    for j in range(cases):
        k = j * 32768 // cases + 1
        for n in (k * k - 1, k * k, draw(30) >> (j % 30), -j):
            for root in (isqrt, _isqrt):
                if root is None or n >= 1 << 30:
                    continue
                x = root(n)
                wrong += (x != 0) if n <= 0 else not (x * x <= n < (x + 1) * (x + 1))
                count += 1
    return (count, wrong, gaitswitch.isqrt is _isqrt and stability.isqrt is _isqrt)
