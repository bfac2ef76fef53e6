"""hexapod.tick.Robot._output's frame (body pose -> six leg IKs -> joint limits -> 18 servo pulses)
compiled by MicroPython's viper emitter: the same integer steps as the plain code, as machine code.
Imported by tick.py only on MicroPython, and only if the port has viper (CircuitPython has not).

`output(robot)` fills robot._angles and robot._pulses and, only when every leg solved inside its
limits and every pulse fell inside its servo's range, copies them to robot.angles and
robot.pulses and returns 0. Otherwise it returns 1 and the caller runs the plain code, which
finds the same refusal and records it (fault counters, excess): a held frame is rare, and so
only one copy of that bookkeeping exists. Every value stays below 2**30 as in the plain code;
tests/test_tickfast.py proves both give the same frames, on the host VM and the emulated Pico.
"""

from array import array

import micropython
from micropython import const

from hexapod._ikfast import _isqrt, solve
from hexapod.fixmath import _SIN

_G_T1 = const(10)  # hexapod.leg's result slots (viper folds only local consts)
_G_T2 = const(11)
_G_T3 = const(12)
_REPLAN = const(64)  # hexapod.walk.REPLAN_STEP
_STOPPING = const(3)  # hexapod.walk.STOPPING
_FINE_TICK = const(320)  # hexapod.body.FINE * gait.TICK_MS
_TICK_MS = const(20)  # hexapod.gait.TICK_MS
_SPEED_STEP = const(40)  # hexapod.walk.SPEED_STEP
_YAW_STEP = const(100)  # hexapod.walk.YAW_STEP
_DEG360 = const(3600000)  # hexapod.walk._DEG360
_REANCHOR = const(4194304)  # hexapod.walk._REANCHOR

_SIN_WORDS = array("i", _SIN)  # Q15, 0..90 degrees: no negative word (viper's ptr32 loads are unsigned)


@micropython.viper
def _mq(a: int, q: int) -> int:
    """hexapod.fixmath.mul_q15: a * q / 2**15 rounded, |a| < 2**29, |q| <= 2**15."""
    if a < 0:
        a = 0 - a
        return 0 - ((a >> 15) * q + (((a & 32767) * q + 16384) >> 15))
    return (a >> 15) * q + (((a & 32767) * q + 16384) >> 15)


@micropython.viper
def _sin(cdeg: int) -> int:
    """hexapod.fixmath.sin: Q15 sine of cdeg (|cdeg| < 2**29)."""
    a = cdeg - (cdeg // 36000) * 36000
    neg = 0
    if a >= 18000:
        neg = 1
        a -= 18000
    if a > 9000:
        a = 18000 - a
    i = a // 25
    f = a - i * 25
    tab = ptr32(_SIN_WORDS)  # noqa: F821 (a viper built-in)
    s = tab[i]
    if f:
        s += ((tab[i + 1] - s) * f + 12) // 25
    if neg:
        return 0 - s
    return s


@micropython.viper
def settled(body) -> int:
    """hexapod.body.Body.settled: 1 when the pose has reached its target, else 0."""
    p = body.pose
    t = body.target
    for k in range(9):
        if int(p[k]) != int(t[k]):
            return 0
    return 1


@micropython.viper
def begin(walker) -> int:
    """Walker.update's start: one tick of the velocity ramp (Walker._ramp); returns 1 when the
    ramped velocity is zero, plus 2 << i for every leg i due to lift (Walker._lift_all's test:
    in stance at its start phase)."""
    c = walker.cmd
    v = walker.vel
    r = 1
    for k in range(3):
        step = _YAW_STEP if k == 2 else _SPEED_STEP
        d = int(c[k]) - int(v[k])
        if d > step:
            d = step
        elif d < 0 - step:
            d = 0 - step
        d += int(v[k])
        v[k] = d
        if d:
            r = 0
    su = walker.su
    start = walker.clock.start
    phase = int(walker.phase)
    for i in range(6):
        if int(su[i]) < 0 and phase == int(start[i]):
            r |= 2 << i
    return r


@micropython.viper
def aim(walker) -> int:
    """Walker._aim_swings: _aim for the command (made again only when it changed, by Walker._aim_at)
    and the ground's move over one swing into _carry (Walker._carry_for)."""
    c = walker.cmd
    vx = int(c[0])
    vy = int(c[1])
    w = int(c[2])
    clock = walker.clock
    key = walker._aim_key
    st = int(clock.stance_ticks)
    if int(key[0]) != vx or int(key[1]) != vy or int(key[2]) != w or int(key[3]) != st:
        key[0] = vx
        key[1] = vy
        key[2] = w
        key[3] = st
        walker._aim_at(vx, vy, w)
    ms = int(clock.swing_ticks) * _TICK_MS
    k = walker._carry
    k[0] = 0 - (vx * ms * 16 // 1000)
    k[1] = 0 - (vy * ms * 16 // 1000)
    # The turn in Q15 radians: cdeg * pi / 18000 * 2**15 = cdeg * 5.71935.
    k[2] = (w * ms // 1000) * 5719 // 1000
    return 0


@micropython.viper
def swings(walker, lo: int, hi: int, w: int, still: int) -> int:
    """hexapod.walk.Walker._swing_all over legs lo..hi-1: each swing foot (su >= 0) one tick on
    (Walker._swing_step, the touch-down point into walker._xy), landed as Walker._swing lands it;
    returns how many are still in the air."""
    su = walker.su
    nxs = walker.nx
    nys = walker.ny
    rhos = walker.rho
    fxs = walker.fx
    fys = walker.fy
    a = walker._aim
    a0 = int(a[0])
    a1 = int(a[1])
    a2 = int(a[2])
    a3 = int(a[3])
    k = walker._carry
    k0 = int(k[0])
    k1 = int(k[1])
    k2 = int(k[2])
    tab = ptr32(_SIN_WORDS)  # noqa: F821 (a viper built-in)
    airborne = 0
    for i in range(lo, hi):
        u = int(su[i])
        if u < 0:
            continue
        u += 1
        nx = int(nxs[i])
        ny = int(nys[i])
        r = int(rhos[i])
        sx = int(walker.sx[i])
        sy = int(walker.sy[i])
        # Every mul_q15 below written out: a viper call costs ~5 us on the Pico, its body < 1 us.
        m = nx if nx >= 0 else 0 - nx
        xc = (m >> 15) * a0 + (((m & 32767) * a0 + 16384) >> 15)
        xs = (m >> 15) * a1 + (((m & 32767) * a1 + 16384) >> 15)
        if nx < 0:
            xc = 0 - xc
            xs = 0 - xs
        m = ny if ny >= 0 else 0 - ny
        yc = (m >> 15) * a0 + (((m & 32767) * a0 + 16384) >> 15)
        ys = (m >> 15) * a1 + (((m & 32767) * a1 + 16384) >> 15)
        if ny < 0:
            yc = 0 - yc
            ys = 0 - ys
        x = xc - ys + a2  # Walker.target
        y = xs + yc + a3
        t0 = t1 = c0 = c1 = c2 = c3 = rx = ry = st = 0
        # Four points go through the one reach clamp below: the touch-down point (stage 0), the
        # plan at the last tick u - 1 (1) and at u (2), and the re-aimed foot (3). The plan is
        # written once, for both ticks.
        stage = 0
        while True:
            if stage == 1 or stage == 2:
                uu = u - 2 + stage
                # trajectory.swing_stroke: the stroke fraction st and uu / w, Q15.
                n = w - 2 if w > 3 else w
                kk = uu - 1 if w > 3 else uu
                if kk >= n:
                    st = 32768
                elif kk <= 0:
                    st = 0
                else:
                    # fixmath.sin of sin90(2 kk - n, n) (cdeg), written out.
                    g = (((kk << 1) - n) * 18000 + n) // (n << 1)
                    g -= (g // 36000) * 36000
                    neg = g >= 18000
                    if neg:
                        g -= 18000
                    if g > 9000:
                        g = 18000 - g
                    j = g // 25
                    f = g - j * 25
                    h = tab[j]
                    if f:
                        h += ((tab[j + 1] - h) * f + 12) // 25
                    if neg:
                        h = 0 - h
                    st = (32768 + h + 1) >> 1
                frac = (uu << 15) // w
                # x = S + C uu / w + (T - S - C) st, the carry C turning from lift-off's to touch-down's.
                d = c2 - c0
                m = d if d >= 0 else 0 - d
                e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                cx = c0 + (e if d >= 0 else 0 - e)
                d = c3 - c1
                m = d if d >= 0 else 0 - d
                e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                cy = c1 + (e if d >= 0 else 0 - e)
                m = cx if cx >= 0 else 0 - cx
                e = (m >> 15) * frac + (((m & 32767) * frac + 16384) >> 15)
                x = sx + (e if cx >= 0 else 0 - e)
                d = t0 - sx - cx
                m = d if d >= 0 else 0 - d
                e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                x += e if d >= 0 else 0 - e
                m = cy if cy >= 0 else 0 - cy
                e = (m >> 15) * frac + (((m & 32767) * frac + 16384) >> 15)
                y = sy + (e if cy >= 0 else 0 - e)
                d = t1 - sy - cy
                m = d if d >= 0 else 0 - d
                e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                y += e if d >= 0 else 0 - e
            # Walker._in_reach: onto the disc of radius r (0.1 mm) around neutral when outside it.
            dx = (x - nx) >> 4
            dy = (y - ny) >> 4
            e2 = dx * dx + dy * dy
            if e2 > r * r:
                e = int(_isqrt(e2))
                x = nx + ((dx * r // e) << 4)
                y = ny + ((dy * r // e) << 4)
            if stage == 0:
                t0 = x
                t1 = y
                # Walker.carry_at at lift-off (sx, sy) and at touch-down (t0, t1).
                c0 = k0 + (((sy >> 4) * k2) >> 11)
                c1 = k1 - (((sx >> 4) * k2) >> 11)
                c2 = k0 + (((t1 >> 4) * k2) >> 11)
                c3 = k1 - (((t0 >> 4) * k2) >> 11)
                stage = 1
            elif stage == 1:
                # How far the plan moved since the last tick, fine (0 when steady).
                rx = x - int(fxs[i])
                ry = y - int(fys[i])
                stage = 2
            elif stage == 2 and (rx or ry):
                # The foot moves as the new plan does, plus at most _REPLAN a tick toward it.
                if 0 < st < 32768:
                    rx -= _REPLAN if rx > _REPLAN else (0 - _REPLAN if rx < 0 - _REPLAN else rx)
                    ry -= _REPLAN if ry > _REPLAN else (0 - _REPLAN if ry < 0 - _REPLAN else ry)
                x -= rx
                y -= ry
                stage = 3
            else:
                break
        t = walker._xy
        t[0] = t0
        t[1] = t1
        fxs[i] = x
        fys[i] = y
        if u < w:
            # trajectory.swing_shape's height fraction (the arch squared) times the lift.
            tt = (u << 1) - w
            # fixmath.sin of sin90(w - |tt|, w) (cdeg), written out.
            g = ((w - tt if tt >= 0 else w + tt) * 18000 + w) // (w << 1)
            g -= (g // 36000) * 36000
            neg = g >= 18000
            if neg:
                g -= 18000
            if g > 9000:
                g = 18000 - g
            j = g // 25
            f = g - j * 25
            h = tab[j]
            if f:
                h += ((tab[j + 1] - h) * f + 12) // 25
            if neg:
                h = 0 - h
            h = (h >> 15) * h + (((h & 32767) * h + 16384) >> 15)
            m = int(walker.lift) << 4
            walker.fz[i] = int(walker.ground) + (m >> 15) * h + (((m & 32767) * h + 16384) >> 15)
            su[i] = u
            airborne += 1
            continue
        # Landed (Walker._swing): pinned where it is, in the ground frame (Walker._to_ground).
        su[i] = -1
        walker.fz[i] = walker.ground
        cd = (int(walker.psi) + 50) // 100
        c = int(_sin(cd + 9000))
        s = int(_sin(cd))
        m = x if x >= 0 else 0 - x
        xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if x < 0:
            xc = 0 - xc
            xs = 0 - xs
        m = y if y >= 0 else 0 - y
        yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if y < 0:
            yc = 0 - yc
            ys = 0 - ys
        walker.px[i] = int(walker.bx) + xc - ys
        walker.py[i] = int(walker.by) + xs + yc
        if still and int(walker.state) == _STOPPING and x == nx and y == ny:
            walker.done[i] = 1
    return airborne


@micropython.viper
def stance(walker, bx: int, by: int, cd: int) -> int:
    """hexapod.walk.Walker._stance: the stance feet at body (bx, by) (fine) turned cd (cdeg) into
    ax, ay; 1 when a foot would leave its stance_rho disc (and move away from neutral), else 0."""
    c = int(_sin(cd + 9000))  # fixmath.cos
    s = int(_sin(cd))
    su = walker.su
    px = walker.px
    py = walker.py
    nx = walker.nx
    ny = walker.ny
    fx = walker.fx
    fy = walker.fy
    rho = walker.stance_rho
    out_x = walker.ax
    out_y = walker.ay
    for i in range(6):
        if int(su[i]) >= 0:
            continue
        x = int(px[i]) - bx
        y = int(py[i]) - by
        # _mq(x, c) + _mq(y, s) and _mq(y, c) - _mq(x, s), written out as in output(): a call costs
        # ~5 us, and one shared helper made the tick 0.16 ms slower (measured on the Pico).
        m = x if x >= 0 else 0 - x
        xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if x < 0:
            xc = 0 - xc
            xs = 0 - xs
        m = y if y >= 0 else 0 - y
        yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if y < 0:
            yc = 0 - yc
            ys = 0 - ys
        ax = xc + ys
        ay = yc - xs
        n0 = int(nx[i])
        n1 = int(ny[i])
        dx = (ax - n0) >> 4
        dy = (ay - n1) >> 4
        r = int(rho[i])
        if dx * dx + dy * dy > r * r:
            ox = (int(fx[i]) - n0) >> 4
            oy = (int(fy[i]) - n1) >> 4
            if dx * dx + dy * dy > ox * ox + oy * oy:
                return 1
        out_x[i] = ax
        out_y[i] = ay
    return 0


@micropython.viper
def move(walker) -> int:
    """hexapod.walk.Walker._move_body: the body's move this tick at walker.vel in the ground frame
    (with its remainder carries), the stance feet read back (stance() below), or held."""
    v = walker.vel
    v0 = int(v[0])
    v1 = int(v[1])
    dpsi = int(v[2]) << 1  # cdeg/s over 20 ms, in ANGLE_UNIT (1e-4 degree)
    psi = int(walker.psi)
    cd = (psi + (dpsi >> 1) + 50) // 100
    c = int(_sin(cd + 9000))
    s = int(_sin(cd))
    # The body's velocity in the ground frame (mul_q15 written out), then this tick's move (fine).
    m = v0 if v0 >= 0 else 0 - v0
    xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
    xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
    if v0 < 0:
        xc = 0 - xc
        xs = 0 - xs
    m = v1 if v1 >= 0 else 0 - v1
    yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
    ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
    if v1 < 0:
        yc = 0 - yc
        ys = 0 - ys
    n = (xc - ys) * _FINE_TICK + int(walker.cx)
    mx = n // 1000
    cx = n - mx * 1000
    n = (xs + yc) * _FINE_TICK + int(walker.cy)
    my = n // 1000
    cy = n - my * 1000
    psi += dpsi
    if psi >= _DEG360:
        psi -= _DEG360
    elif psi < 0:
        psi += _DEG360
    if not (mx or my or dpsi):
        walker.cx = cx
        walker.cy = cy
        return 0
    bx = int(walker.bx) + mx
    by = int(walker.by) + my
    if int(stance(walker, bx, by, (psi + 50) // 100)):
        walker.held = int(walker.held) + 1
        return 0
    walker.cx = cx
    walker.cy = cy
    walker.psi = psi
    su = walker.su
    fx = walker.fx
    fy = walker.fy
    ax = walker.ax
    ay = walker.ay
    for i in range(6):
        if int(su[i]) < 0:
            fx[i] = ax[i]
            fy[i] = ay[i]
    if bx > _REANCHOR or bx < 0 - _REANCHOR or by > _REANCHOR or by < 0 - _REANCHOR:
        px = walker.px
        py = walker.py
        for i in range(6):
            px[i] = int(px[i]) - bx
            py[i] = int(py[i]) - by
        bx = 0
        by = 0
    walker.bx = bx
    walker.by = by
    return 0


@micropython.viper
def _posed(body, xyz) -> int:
    """Body.to_leg's pose part: the foot xyz[0:3] (fine) moved back through the body's pose, in place."""
    p = body.pose
    tr = body.trig
    cx = int(p[6]) << 4
    cy = int(p[7]) << 4
    cz = int(p[8]) << 4
    x = int(xyz[0]) - (cx + (int(p[0]) << 4))
    y = int(xyz[1]) - (cy + (int(p[1]) << 4))
    z = int(xyz[2]) - (cz + (int(p[2]) << 4))
    c = int(tr[4])
    s = int(tr[5])
    a = int(_mq(x, c)) + int(_mq(y, s))
    y = int(_mq(y, c)) - int(_mq(x, s))
    x = a
    c = int(tr[2])
    s = int(tr[3])
    a = int(_mq(x, c)) - int(_mq(z, s))
    z = int(_mq(x, s)) + int(_mq(z, c))
    x = a
    c = int(tr[0])
    s = int(tr[1])
    a = int(_mq(y, c)) + int(_mq(z, s))
    z = int(_mq(z, c)) - int(_mq(y, s))
    y = a
    xyz[0] = x + cx
    xyz[1] = y + cy
    xyz[2] = z + cz
    return 0


@micropython.viper
def output(robot) -> int:
    """The frame's angles and pulses, as Robot._output makes them: 0 when sent to robot.angles and
    robot.pulses, 1 when something was refused (nothing copied: the caller runs the plain code)."""
    # ptr32 loads are unsigned on a 64-bit VM: (v ^ sb) - sb sign-extends there, and is v on a board.
    sb = 1
    sb <<= 31  # at run time: the folded constant 1 << 31 is no small int on a 32-bit port
    w = robot.walker
    fx = w.fx
    fy = w.fy
    fz = w.fz
    body = robot.body
    level = bool(body.level)
    mx = ptr32(body.mx)  # noqa: F821 (a viper built-in; Body keeps the mounts in array("i"))
    my = ptr32(body.my)  # noqa: F821
    mc = ptr32(body.mc)  # noqa: F821
    ms = ptr32(body.ms)  # noqa: F821
    legs = robot.geometry.legs
    xyz = robot._leg
    a = ptr32(robot._angles)  # noqa: F821 (Robot's scratch, array("i"))
    for i in range(6):
        # Body.to_leg: the foot (fine, body frame) into leg i's frame (0.1 mm, rounded).
        x = int(fx[i])
        y = int(fy[i])
        z = int(fz[i])
        if not level:
            xyz[0] = x
            xyz[1] = y
            xyz[2] = z
            _posed(body, xyz)
            x = int(xyz[0])
            y = int(xyz[1])
            z = int(xyz[2])
        dx = x - ((mx[i] ^ sb) - sb)
        dy = y - ((my[i] ^ sb) - sb)
        c = (mc[i] ^ sb) - sb
        s = (ms[i] ^ sb) - sb
        # _mq(dx, c) + _mq(dy, s) and _mq(dy, c) - _mq(dx, s), written out as in stance(): a call
        # costs ~5 us, and one shared helper made the tick 0.16 ms slower (measured on the Pico).
        m = dx if dx >= 0 else 0 - dx
        xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if dx < 0:
            xc = 0 - xc
            xs = 0 - xs
        m = dy if dy >= 0 else 0 - dy
        yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
        ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
        if dy < 0:
            yc = 0 - yc
            ys = 0 - ys
        lx = (xc + ys + 8) >> 4
        ly = (yc - xs + 8) >> 4
        lz = (z + 8) >> 4
        # Leg.ik's solve and limit check.
        leg = legs[i]
        g = leg._g
        if int(solve(lx, ly, lz, g)):
            return 1
        gw = ptr32(g)  # noqa: F821 (Leg._g is an array("i"))
        t1 = (gw[_G_T1] ^ sb) - sb
        t2 = (gw[_G_T2] ^ sb) - sb
        t3 = (gw[_G_T3] ^ sb) - sb
        lim = leg.limits
        if t1 < int(lim[0]) or t1 > int(lim[1]) or t2 < int(lim[2]) or t2 > int(lim[3]):
            return 1
        if t3 < int(lim[4]) or t3 > int(lim[5]):
            return 1
        k = 3 * i
        a[k] = t1
        a[k + 1] = t2
        a[k + 2] = t3
    p = ptr32(robot._pulses)  # noqa: F821 (Robot's scratch, array("i"))
    servos = robot.servos
    for k in range(18):
        # hexapod.servo.ServoMap.pulse, read from the maps every frame (they may be swapped or
        # recalibrated between ticks); floor division as in the plain code (viper's // floors too).
        sm = servos[k]
        us = int(sm.centre_us) + int(sm.direction) * ((((a[k] ^ sb) - sb) * int(sm.us_per_degree) + 5000) // 10000)
        if us < int(sm.min_us) or us > int(sm.max_us):
            return 1
        p[k] = us
    angles = robot.angles
    pulses = robot.pulses
    for k in range(18):
        angles[k] = (a[k] ^ sb) - sb
        pulses[k] = (p[k] ^ sb) - sb
    return 0
