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
def _sin90(t: int, s: int) -> int:
    """hexapod.trajectory.sin90: sin(t 90 / s degrees) in Q15."""
    return int(_sin((t * 18000 + s) // (s << 1)))


@micropython.viper
def _clamp(xy, nx: int, ny: int, r: int) -> int:
    """Walker._swing_step's reach clamp: the point xy[0:2] (fine) pulled onto the disc of radius
    r (0.1 mm) around (nx, ny) when outside it, in place."""
    x = int(xy[0])
    y = int(xy[1])
    dx = (x - nx) >> 4
    dy = (y - ny) >> 4
    e2 = dx * dx + dy * dy
    if e2 > r * r:
        e = int(_isqrt(e2))
        x = nx + ((dx * r // e) << 4)
        y = ny + ((dy * r // e) << 4)
    xy[0] = x
    xy[1] = y
    return 0


@micropython.viper
def _stroke(u: int, w: int) -> int:
    """hexapod.trajectory.swing_stroke's stroke fraction at tick u of w, Q15."""
    n = w - 2 if w > 3 else w
    k = u - 1 if w > 3 else u
    if k >= n:
        return 32768
    if k <= 0:
        return 0
    return (32768 + int(_sin90((k << 1) - n, n)) + 1) >> 1


@micropython.viper
def _bounded(d: int) -> int:
    """d limited to -_REPLAN.._REPLAN."""
    if d > _REPLAN:
        return _REPLAN
    if d < 0 - _REPLAN:
        return 0 - _REPLAN
    return d


@micropython.viper
def _plan_at(walker, i: int, u: int, w: int) -> int:
    """Walker._swing_at: the swing planned from leg i's lift-off to walker._xy (carries in
    walker._cv) at tick u of w, inside the reach disc, into walker._plan; returns the stroke (Q15)."""
    cv = walker._cv
    c0 = int(cv[0])
    c1 = int(cv[1])
    t = walker._xy
    sx = int(walker.sx[i])
    sy = int(walker.sy[i])
    st = int(_stroke(u, w))
    frac = (u << 15) // w
    cx = c0 + int(_mq(int(cv[2]) - c0, st))
    cy = c1 + int(_mq(int(cv[3]) - c1, st))
    xy = walker._plan
    xy[0] = sx + int(_mq(cx, frac)) + int(_mq(int(t[0]) - sx - cx, st))
    xy[1] = sy + int(_mq(cy, frac)) + int(_mq(int(t[1]) - sy - cy, st))
    _clamp(xy, int(walker.nx[i]), int(walker.ny[i]), int(walker.rho[i]))
    return st


@micropython.viper
def swing(walker, i: int, w: int) -> int:
    """hexapod.walk.Walker._swing_step: leg i's swing foot at its next tick u of w into
    fx, fy, fz[i], the touch-down point into walker._xy; returns u."""
    u = int(walker.su[i]) + 1
    nx = int(walker.nx[i])
    ny = int(walker.ny[i])
    r = int(walker.rho[i])
    a = walker._aim
    a0 = int(a[0])
    a1 = int(a[1])
    t = walker._xy
    t[0] = int(_mq(nx, a0)) - int(_mq(ny, a1)) + int(a[2])  # Walker.target
    t[1] = int(_mq(nx, a1)) + int(_mq(ny, a0)) + int(a[3])
    _clamp(t, nx, ny, r)
    t0 = int(t[0])
    t1 = int(t[1])
    # trajectory.swing_shape's height fraction (its forward fraction is not used here).
    tt = (u << 1) - w
    h = int(_sin90(w - tt if tt >= 0 else w + tt, w))
    lifted = int(_mq(h, h))
    sx = int(walker.sx[i])
    sy = int(walker.sy[i])
    k = walker._carry
    k0 = int(k[0])
    k1 = int(k[1])
    k2 = int(k[2])
    # carry_at at lift-off (sx, sy) and at touch-down (t0, t1), into _cv as the plain code has them.
    cv = walker._cv
    cv[0] = k0 + (((sy >> 4) * k2) >> 11)
    cv[1] = k1 - (((sx >> 4) * k2) >> 11)
    cv[2] = k0 + (((t1 >> 4) * k2) >> 11)
    cv[3] = k1 - (((t0 >> 4) * k2) >> 11)
    # The plan at the last tick (u - 1), against where the foot is: nonzero when re-aimed.
    xy = walker._plan
    _plan_at(walker, i, u - 1, w)
    rx = int(xy[0]) - int(walker.fx[i])
    ry = int(xy[1]) - int(walker.fy[i])
    st = int(_plan_at(walker, i, u, w))
    if rx or ry:
        # Walker._swing_step: the foot moves as the new plan does, plus at most _REPLAN a tick.
        if 0 < st < 32768:
            rx -= int(_bounded(rx))
            ry -= int(_bounded(ry))
        xy[0] = int(xy[0]) - rx
        xy[1] = int(xy[1]) - ry
        _clamp(xy, nx, ny, r)
    walker.fx[i] = xy[0]
    walker.fy[i] = xy[1]
    walker.fz[i] = int(walker.ground) + int(_mq(int(walker.lift) << 4, lifted))
    return u


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
def _solved(leg, lx: int, ly: int, lz: int) -> int:
    """Leg.ik's solve and limit check: 0 with the angles in leg._g's result slots, 1 when refused."""
    gbuf = leg._g
    if int(solve(lx, ly, lz, gbuf)):
        return 1
    # Read back as objects: a ptr32 load of a negative angle is unsigned on a 64-bit VM.
    t1 = int(gbuf[_G_T1])
    t2 = int(gbuf[_G_T2])
    t3 = int(gbuf[_G_T3])
    lim = leg.limits
    if t1 < int(lim[0]) or t1 > int(lim[1]) or t2 < int(lim[2]) or t2 > int(lim[3]):
        return 1
    if t3 < int(lim[4]) or t3 > int(lim[5]):
        return 1
    return 0


@micropython.viper
def output(robot) -> int:
    """The frame's angles and pulses, as Robot._output makes them: 0 when sent to robot.angles and
    robot.pulses, 1 when something was refused (nothing copied: the caller runs the plain code)."""
    w = robot.walker
    fx = w.fx
    fy = w.fy
    fz = w.fz
    body = robot.body
    level = bool(body.level)
    mx = body.mx
    my = body.my
    mc = body.mc
    ms = body.ms
    legs = robot.geometry.legs
    xyz = robot._leg
    a = robot._angles
    for i in range(6):
        # Body.to_leg: the foot (fine, body frame) into leg i's frame (0.1 mm, rounded).
        xyz[0] = fx[i]
        xyz[1] = fy[i]
        xyz[2] = fz[i]
        if not level:
            _posed(body, xyz)
        dx = int(xyz[0]) - int(mx[i])
        dy = int(xyz[1]) - int(my[i])
        c = int(mc[i])
        s = int(ms[i])
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
        lz = (int(xyz[2]) + 8) >> 4
        leg = legs[i]
        if int(_solved(leg, lx, ly, lz)):
            return 1
        g = leg._g
        k = 3 * i
        a[k] = g[_G_T1]
        a[k + 1] = g[_G_T2]
        a[k + 2] = g[_G_T3]
    p = robot._pulses
    servos = robot.servos
    for k in range(18):
        # hexapod.servo.ServoMap.pulse, read from the maps every frame (they may be swapped or
        # recalibrated between ticks); floor division as in the plain code (viper's // floors too).
        sm = servos[k]
        us = int(sm.centre_us) + int(sm.direction) * ((int(a[k]) * int(sm.us_per_degree) + 5000) // 10000)
        if us < int(sm.min_us) or us > int(sm.max_us):
            return 1
        p[k] = us
    angles = robot.angles
    pulses = robot.pulses
    for k in range(18):
        angles[k] = a[k]
        pulses[k] = p[k]
    return 0
