"""hexapod.tick.Robot._output_plain's frame (body pose -> six leg IKs -> joint limits -> 18 servo pulses)
compiled by MicroPython's viper emitter: the same integer steps as the plain code, as machine code
(docs/viper.md lists every viper twin). Imported by tick.py only on MicroPython, and only if the
port has viper (CircuitPython has not).

`output(robot)` fills robot._angles and robot._pulses and, only when every leg solved inside its
limits and every pulse fell inside its servo's range, copies them to robot.angles and
robot.pulses and returns 0. Otherwise it returns 1 and the caller runs the plain code, which
finds the same refusal and records it (fault counters, excess): a held frame is rare, and so
only one copy of that bookkeeping exists. Every value stays below 2**30 as in the plain code;
tests/test_tick_viper.py proves both give the same frames, on the host VM and the emulated Pico.
"""

import micropython
from micropython import const

from hexapod._body_viper import posed
from hexapod._leg_viper import solve

# hexapod.leg's result slots, copied (viper folds only a module's own consts); tests/test_viper_twins.py
# checks each against the name after its #.
_G_T1 = const(10)  # hexapod.leg.G_T1
_G_T2 = const(11)  # hexapod.leg.G_T2
_G_T3 = const(12)  # hexapod.leg.G_T3


@micropython.viper
def output(robot) -> int:
    """The frame's angles and pulses, as Robot._output_plain makes them: 0 when sent to robot.angles and
    robot.pulses, 1 when something was refused (nothing copied: the caller runs the plain code)."""
    # ptr32 loads are unsigned on a 64-bit VM: (v ^ sb) - sb sign-extends there, and is v on a board.
    sb = 1
    sb <<= 31  # at run time: the folded constant 1 << 31 is no small int on a 32-bit port
    w = robot.walker
    fx = ptr32(w.fx)  # noqa: F821 (the walker's feet are array("i"))
    fy = ptr32(w.fy)  # noqa: F821
    fz = ptr32(w.fz)  # noqa: F821
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
        x = (fx[i] ^ sb) - sb
        y = (fy[i] ^ sb) - sb
        z = (fz[i] ^ sb) - sb
        if not level:
            xyz[0] = x
            xyz[1] = y
            xyz[2] = z
            posed(body, xyz)
            x = int(xyz[0])
            y = int(xyz[1])
            z = int(xyz[2])
        dx = x - ((mx[i] ^ sb) - sb)
        dy = y - ((my[i] ^ sb) - sb)
        c = (mc[i] ^ sb) - sb
        s = (ms[i] ^ sb) - sb
        # mul_q15(dx, c) + mul_q15(dy, s) and mul_q15(dy, c) - mul_q15(dx, s), written out as in
        # _walk_viper.stance: a call costs ~5 us, and one shared helper made the tick 0.16 ms slower
        # (measured on the Pico).
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
        cal = ptr32(servos[k].cal)  # noqa: F821 (centre_us, direction, us_per_degree, min_us, max_us)
        us = cal[0] + ((cal[1] ^ sb) - sb) * ((((a[k] ^ sb) - sb) * cal[2] + 5000) // 10000)
        if us < cal[3] or us > cal[4]:
            return 1
        p[k] = us
    angles = robot.angles
    pulses = robot.pulses
    for k in range(18):
        angles[k] = (a[k] ^ sb) - sb
        pulses[k] = (p[k] ^ sb) - sb
    return 0
