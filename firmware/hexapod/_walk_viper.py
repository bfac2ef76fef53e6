"""hexapod.walk.Walker's per-tick steps compiled by MicroPython's viper emitter: the same integer
steps, as machine code (docs/viper.md lists every viper twin). Imported by walk.py only on
MicroPython, and only if the port has viper (CircuitPython has not).

begin: the velocity ramp and the lift test; aim: the swing aim and carry; swings: every swing
foot one tick on, landed; stance and move: the body's move with the stance feet read back;
rescale: a new command scaled into the reach discs. The walker's state is array("i"), read and
written through ptr32. Every value stays below 2**30 as in the plain code, and
tests/test_tick_viper.py (and tests/test_rescale.py for rescale) proves each equal to it, on the
host VM and the emulated Pico.
"""

import micropython
from micropython import const

from hexapod._fixmath_viper import SIN_Q15, isqrt, mul_q15, sin
from hexapod.budget import off_band

# Copied from the plain modules (viper folds only a module's own consts); tests/test_viper_twins.py
# checks each against the expression after its #.
_REPLAN = const(64)  # hexapod.walk.REPLAN_STEP
_STOPPING = const(3)  # hexapod.walk.STOPPING
_FINE_TICK = const(320)  # hexapod.body.FINE * hexapod.gait.TICK_MS
_TICK_MS = const(20)  # hexapod.gait.TICK_MS
_SPEED_STEP = const(40)  # hexapod.walk.SPEED_STEP
_YAW_STEP = const(100)  # hexapod.walk.YAW_STEP
_DEG360 = const(3600000)  # hexapod.walk._DEG360
_REANCHOR = const(4194304)  # hexapod.walk._REANCHOR
_HALF_TURN = const(9000)  # hexapod.walk._HALF_TURN
_ONE = const(32768)  # hexapod.fixmath.ONE
_SLACK = const(16)  # hexapod.walk.STANCE_SLACK
_EASE = const(300)  # hexapod.budget.SWING_EASE
_EASE_DEAD = const(16)  # hexapod.budget.EASE_DEAD


@micropython.viper
def begin(walker) -> int:
    """Walker.update's start: one tick of the velocity ramp to walker.goal (Walker._ramp); 1 when the
    ramped velocity is zero, plus 2 << i for every leg i due to lift (Walker._lift_all's test:
    in stance at its start phase)."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    c = ptr32(walker.goal)  # noqa: F821
    v = ptr32(walker.vel)  # noqa: F821
    r = 1
    for k in range(3):
        step = _YAW_STEP if k == 2 else _SPEED_STEP
        vk = (v[k] ^ sb) - sb
        d = ((c[k] ^ sb) - sb) - vk
        if d > step:
            d = step
        elif d < 0 - step:
            d = 0 - step
        vk += d
        v[k] = vk
        if vk:
            r = 0
    su = ptr32(walker.su)  # noqa: F821
    start = ptr32(walker.clock.start)  # noqa: F821
    phase = int(walker.phase)
    for i in range(6):
        if ((su[i] ^ sb) - sb) < 0 and phase == start[i]:
            r |= 2 << i
    return r


@micropython.viper
def aim(walker) -> int:
    """Walker._aim_swings: _aim for the command (made again only when it changed, by Walker._aim_at)
    and the ground's move over one swing into _carry (Walker._carry_for)."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    c = ptr32(walker.cmd)  # noqa: F821
    vx = (c[0] ^ sb) - sb
    vy = (c[1] ^ sb) - sb
    w = (c[2] ^ sb) - sb
    clock = walker.clock
    key = ptr32(walker._aim_key)  # noqa: F821
    st = int(clock.stance_ticks)
    if key[0] != c[0] or key[1] != c[1] or key[2] != c[2] or ((key[3] ^ sb) - sb) != st:
        key[0] = vx
        key[1] = vy
        key[2] = w
        key[3] = st
        walker._aim_at(vx, vy, w)
    ms = int(clock.swing_ticks) * _TICK_MS
    k = ptr32(walker._carry)  # noqa: F821
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
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    su = ptr32(walker.su)  # noqa: F821 (a viper built-in; the walker's state is array("i"))
    nxs = ptr32(walker.nx)  # noqa: F821
    nys = ptr32(walker.ny)  # noqa: F821
    rhos = ptr32(walker.rho)  # noqa: F821
    fxs = ptr32(walker.fx)  # noqa: F821
    fys = ptr32(walker.fy)  # noqa: F821
    sxs = ptr32(walker.sx)  # noqa: F821
    sys_ = ptr32(walker.sy)  # noqa: F821
    a = ptr32(walker._aim)  # noqa: F821
    a0 = (a[0] ^ sb) - sb
    a1 = (a[1] ^ sb) - sb
    a2 = (a[2] ^ sb) - sb
    a3 = (a[3] ^ sb) - sb
    k = ptr32(walker._carry)  # noqa: F821
    k0 = (k[0] ^ sb) - sb
    k1 = (k[1] ^ sb) - sb
    k2 = (k[2] ^ sb) - sb
    tab = ptr16(SIN_Q15)  # noqa: F821
    smax = ptr32(walker.swing_max)  # noqa: F821
    gain = int(walker.stroke_gain)
    geo = walker.geometry
    reach = int(geo.neutral_reach)
    mxs = geo.mount_x
    mys = geo.mount_y
    srho = walker.srho
    airborne = 0
    for i in range(lo, hi):
        u = (su[i] ^ sb) - sb
        if u < 0:
            continue
        u += 1
        nx = (nxs[i] ^ sb) - sb
        ny = (nys[i] ^ sb) - sb
        r = rhos[i]
        sx = (sxs[i] ^ sb) - sb
        sy = (sys_[i] ^ sb) - sb
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
        t0 = t1 = c0 = c1 = c2 = c3 = rx = ry = st = budgeted = 0
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
                # x = S + C uu / w + (T - S - C) st, the carry C turning from lift-off's to touch-down's;
                # then y (one loop: the code once, for a smaller module).
                for axis in range(2):
                    if axis == 0:
                        lo = c0
                        d = c2 - c0
                        s0 = sx
                        tn = t0
                    else:
                        lo = c1
                        d = c3 - c1
                        s0 = sy
                        tn = t1
                    m = d if d >= 0 else 0 - d
                    e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                    cc = lo + (e if d >= 0 else 0 - e)
                    m = cc if cc >= 0 else 0 - cc
                    e = (m >> 15) * frac + (((m & 32767) * frac + 16384) >> 15)
                    v = s0 + (e if cc >= 0 else 0 - e)
                    d = tn - s0 - cc
                    m = d if d >= 0 else 0 - d
                    e = (m >> 15) * st + (((m & 32767) * st + 16384) >> 15)
                    v += e if d >= 0 else 0 - e
                    if axis == 0:
                        x = v
                    else:
                        y = v
            # Walker._in_reach: onto the disc of radius r (0.1 mm) around neutral when outside it.
            dx = (x - nx) >> 4
            dy = (y - ny) >> 4
            e2 = dx * dx + dy * dy
            if e2 > r * r:
                e = int(isqrt(e2))
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
                if not budgeted:
                    # hexapod.budget.in_budget: the stroke D shortened until |C + D gain| fits the budget
                    # (budget.eased); a touch-down point moved goes round once more (reach, carries).
                    budgeted = 1
                    dx = (t0 - sx - c2) >> 4
                    dy = (t1 - sy - c3) >> 4
                    bx = dx * gain >> 15
                    by = dy * gain >> 15
                    b = int(isqrt(bx * bx + by * by))
                    if b:
                        al = ((c2 >> 4) * bx + (c3 >> 4) * by) // b
                        bx = c2 >> 4
                        by = c3 >> 4
                        m = (sx >> 4) - int(mxs[i])
                        e = (sy >> 4) - int(mys[i])
                        e = int(isqrt(m * m + e * e)) - reach
                        if e < 0:
                            e = 0 - e
                        e -= int(srho[i]) + _EASE_DEAD
                        v = (smax[i] ^ sb) - sb
                        if e > 0:
                            v = v * _EASE // (_EASE + e)
                        v = v * v - (bx * bx + by * by - al * al)
                        if v > 0:
                            v = int(isqrt(v)) - al
                        else:
                            v = 0
                        if v < b:
                            if v < 0:
                                v = 0
                            x = sx + c2 + ((dx * v // b) << 4)
                            y = sy + c3 + ((dy * v // b) << 4)
                            continue
                stage = 1
            elif stage == 1:
                # How far the plan moved since the last tick, fine (0 when steady).
                rx = x - ((fxs[i] ^ sb) - sb)
                ry = y - ((fys[i] ^ sb) - sb)
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
        t = ptr32(walker._xy)  # noqa: F821
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
            fz = ptr32(walker.fz)  # noqa: F821
            fz[i] = int(walker.ground) + (m >> 15) * h + (((m & 32767) * h + 16384) >> 15)
            su[i] = u
            airborne += 1
            continue
        # Landed (Walker._swing): pinned where it is, in the ground frame (Walker._to_ground).
        su[i] = -1
        fz = ptr32(walker.fz)  # noqa: F821
        fz[i] = int(walker.ground)
        cd = (int(walker.psi) + 50) // 100
        c = int(sin(cd + 9000))
        s = int(sin(cd))
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
        px = ptr32(walker.px)  # noqa: F821
        py = ptr32(walker.py)  # noqa: F821
        px[i] = int(walker.bx) + xc - ys
        py[i] = int(walker.by) + xs + yc
        if still and int(walker.state) == _STOPPING and x == nx and y == ny:
            done = ptr32(walker.done)  # noqa: F821
            done[i] = 1
    return airborne


@micropython.viper
def stance(walker, bx: int, by: int, cd: int) -> int:
    """hexapod.walk.Walker._stance: the stance feet at body (bx, by) (fine) turned cd (cdeg) into
    ax, ay; 1 + the first leg whose foot would leave its reach disc (and move away from neutral) or go
    further outside its ease band (hexapod.budget.off_band), else 0."""
    c = int(sin(cd + 9000))  # fixmath.cos
    s = int(sin(cd))
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    su = ptr32(walker.su)  # noqa: F821
    px = ptr32(walker.px)  # noqa: F821
    py = ptr32(walker.py)  # noqa: F821
    nx = ptr32(walker.nx)  # noqa: F821
    ny = ptr32(walker.ny)  # noqa: F821
    fx = ptr32(walker.fx)  # noqa: F821
    fy = ptr32(walker.fy)  # noqa: F821
    rho = ptr32(walker.rho)  # noqa: F821
    out_x = ptr32(walker.ax)  # noqa: F821
    out_y = ptr32(walker.ay)  # noqa: F821
    for i in range(6):
        if ((su[i] ^ sb) - sb) >= 0:
            continue
        x = ((px[i] ^ sb) - sb) - bx
        y = ((py[i] ^ sb) - sb) - by
        # mul_q15(x, c) + mul_q15(y, s) and mul_q15(y, c) - mul_q15(x, s), written out as in
        # _tick_viper.output: a call costs ~5 us, and one shared helper made the tick 0.16 ms slower
        # (measured on the Pico).
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
        n0 = (nx[i] ^ sb) - sb
        n1 = (ny[i] ^ sb) - sb
        dx = (ax - n0) >> 4
        dy = (ay - n1) >> 4
        r = rho[i]
        if dx * dx + dy * dy > r * r:
            ox = (((fx[i] ^ sb) - sb) - n0) >> 4
            oy = (((fy[i] ^ sb) - sb) - n1) >> 4
            if dx * dx + dy * dy > ox * ox + oy * oy:
                return i + 1
        out_x[i] = ax
        out_y[i] = ay
        # The ease band in plain code: written out here it took 290 more bytes of the board's heap.
        if int(off_band(walker, i)):
            return i + 1
    return 0


@micropython.viper
def move(walker) -> int:
    """hexapod.walk.Walker._move_body: the body's move this tick at walker.vel in the ground frame
    (with its remainder carries), the stance feet read back (stance() below), or held."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    v = ptr32(walker.vel)  # noqa: F821
    v0 = (v[0] ^ sb) - sb
    v1 = (v[1] ^ sb) - sb
    dpsi = ((v[2] ^ sb) - sb) << 1  # cdeg/s over 20 ms, in ANGLE_UNIT (1e-4 degree)
    psi = int(walker.psi)
    cd = (psi + (dpsi >> 1) + 50) // 100
    c = int(sin(cd + 9000))
    s = int(sin(cd))
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
    i = int(stance(walker, bx, by, (psi + 50) // 100))
    if i:
        walker._maybe_lift(i - 1, -1)  # counted, and that foot may lift early (plain code)
        return 0
    walker.cx = cx
    walker.cy = cy
    walker.psi = psi
    su = ptr32(walker.su)  # noqa: F821
    fx = ptr32(walker.fx)  # noqa: F821
    fy = ptr32(walker.fy)  # noqa: F821
    ax = ptr32(walker.ax)  # noqa: F821
    ay = ptr32(walker.ay)  # noqa: F821
    for i in range(6):
        if ((su[i] ^ sb) - sb) < 0:
            fx[i] = ax[i]
            fy[i] = ay[i]
    if bx > _REANCHOR or bx < 0 - _REANCHOR or by > _REANCHOR or by < 0 - _REANCHOR:
        px = ptr32(walker.px)  # noqa: F821
        py = ptr32(walker.py)  # noqa: F821
        for i in range(6):
            px[i] = ((px[i] ^ sb) - sb) - bx
            py[i] = ((py[i] ^ sb) - sb) - by
        bx = 0
        by = 0
    walker.bx = bx
    walker.by = by
    return 0


@micropython.viper
def rescale(walker) -> int:
    """hexapod.walk.Walker._rescale: the command scaled (scale_permille, cmd) until every half
    stance fits its disc and no tripod stance foot reaches past stance_out_max; the stance discs;
    each try's aim made as Walker.aim_for makes it (same key, same _aim)."""
    sb = 1
    sb <<= 31  # (v ^ sb) - sb sign-extends a ptr32 load (unsigned on a 64-bit VM); on a board it is v
    clock = walker.clock
    st = int(clock.stance_ticks)
    vx = int(walker.req_vx)
    vy = int(walker.req_vy)
    w = int(walker.req_yaw)
    half_ms = st * _TICK_MS >> 1
    turn = w * half_ms // 1000
    k = 1000
    if turn > _HALF_TURN:
        k = _HALF_TURN * 1000 // turn
    elif turn < 0 - _HALF_TURN:
        k = _HALF_TURN * 1000 // (0 - turn)
    g = walker.geometry
    out_max = 0
    if st * 2 <= int(clock.cycle_ticks):
        out_max = int(g.stance_out_max)
    reach = int(g.neutral_reach)
    far = (out_max + reach + 1) * (out_max + reach + 1)
    mx = g.mount_x
    my = g.mount_y
    srho = walker.srho
    step = int(walker.step)
    nx = ptr32(walker.nx)  # noqa: F821
    ny = ptr32(walker.ny)  # noqa: F821
    rho = ptr32(walker.rho)  # noqa: F821
    a = ptr32(walker._aim)  # noqa: F821
    key = ptr32(walker._aim_key)  # noqa: F821
    xy = ptr32(walker._xy)  # noqa: F821
    tx = (xy[0] ^ sb) - sb
    ty = (xy[1] ^ sb) - sb
    while k > 0:
        cx = vx * k // 1000
        cy = vy * k // 1000
        cw = w * k // 1000
        if ((key[0] ^ sb) - sb) != cx or ((key[1] ^ sb) - sb) != cy or ((key[2] ^ sb) - sb) != cw or key[3] != st:
            # Walker._aim_at: the turn and the chord of half a stance.
            key[0] = cx
            key[1] = cy
            key[2] = cw
            key[3] = st
            turn = cw * half_ms // 1000
            cx = cx * half_ms * 16 // 1000
            cy = cy * half_ms * 16 // 1000
            if turn == 0:  # no turn: Walker._aim_at's values without its four sines
                a[0] = _ONE
                a[1] = 0
                a[2] = int(mul_q15(cx, _ONE))
                a[3] = int(mul_q15(cy, _ONE))
            else:
                a[0] = int(sin(turn + 9000))
                a[1] = int(sin(turn))
                c = int(sin((turn >> 1) + 9000))
                s = int(sin(turn >> 1))
                a[2] = int(mul_q15(cx, c)) - int(mul_q15(cy, s))
                a[3] = int(mul_q15(cx, s)) + int(mul_q15(cy, c))
        c = (a[0] ^ sb) - sb
        s = (a[1] ^ sb) - sb
        worst = -1
        for i in range(6):
            x = (nx[i] ^ sb) - sb
            m = x if x >= 0 else 0 - x
            xc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
            xs = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
            if x < 0:
                xc = 0 - xc
                xs = 0 - xs
            y = (ny[i] ^ sb) - sb
            m = y if y >= 0 else 0 - y
            yc = (m >> 15) * c + (((m & 32767) * c + 16384) >> 15)
            ys = (m >> 15) * s + (((m & 32767) * s + 16384) >> 15)
            if y < 0:
                yc = 0 - yc
                ys = 0 - ys
            tx = xc - ys + ((a[2] ^ sb) - sb)
            ty = xs + yc + ((a[3] ^ sb) - sb)
            dx = (tx - x) >> 4
            dy = (ty - y) >> 4
            d2 = dx * dx + dy * dy
            lim = (rho[i] ^ sb) - sb
            if step < lim:
                lim = step
            m = int(srho[i])
            if m < lim:
                lim = m
            if lim < 0 or d2 > lim * (lim + 2):
                m = k * lim // int(isqrt(d2))
                if worst < 0 or m < worst:
                    worst = m
            if out_max > 0:
                m = int(mx[i])
                n = int(my[i])
                dx = (tx >> 4) - m
                dy = (ty >> 4) - n
                d2 = dx * dx + dy * dy
                dx = (x >> 4 << 1) - (tx >> 4) - m
                dy = (y >> 4 << 1) - (ty >> 4) - n
                if dx * dx + dy * dy > d2:
                    d2 = dx * dx + dy * dy
                if d2 >= far:
                    m = k * out_max // (int(isqrt(d2)) - reach)
                    if worst < 0 or m < worst:
                        worst = m
        if worst < 0:
            break
        if worst >= k:
            k = worst - 1
        else:
            k = worst
    xy[0] = tx
    xy[1] = ty
    if k < 0:
        k = 0
    sr = ptr32(walker.stance_rho)  # noqa: F821
    for i in range(6):
        r = (rho[i] ^ sb) - sb
        lim = r
        if step < lim:
            lim = step
        m = int(srho[i])
        if m > 0 and m < lim:
            lim = m
        lim += _SLACK
        sr[i] = lim if lim < r else r
    walker.scale_permille = k
    cmd = ptr32(walker.cmd)  # noqa: F821
    cmd[0] = vx * k // 1000
    cmd[1] = vy * k // 1000
    cmd[2] = w * k // 1000
    return k
