"""Writes joystick.jsonl, the shipped joystick session: `python -m hexapod_host.drives.make_joystick`
(prints the stream; tests/test_drives.py checks the shipped file is exactly this output).

A person with a stick, 40 s, seed 22 (random.Random: the same file on every Python 3): a sequence
of moves, each 0.6-2.5 s, the stick read and sent every 20-100 ms (10-50 commands a second) with a
little hand tremor (+-1.5 mm/s, +-0.5 deg/s) while it is off centre:
- ramp: from where the stick is to a new point, linearly over the move;
- reverse: the stick flicked through the centre to the opposite side;
- swap: forward turned into sideways (or back), the same speed;
- spin: turn in place at 15-30 deg/s either way;
- stop: the stick let go (`stop`), 0.6-1.5 s standing.
The stick's reach is 80 mm/s and 30 deg/s: more than any gait accepts, so the walker's own scaling
(docs/physics.md "Servo speed guard") decides the commanded speed, as it would on the robot.
"""

import json
import math
import random

SEED = 22
SECONDS = 40
SPEED = 80.0  # mm/s at full stick
TURN = 30.0  # deg/s at full stick
KINDS = ("ramp", "ramp", "reverse", "swap", "spin", "stop")


def _point(rng):
    """A new stick position: (vx, vy mm/s, yaw deg/s), mostly forward-ish, sometimes crabbing."""
    a = rng.uniform(-3.14159, 3.14159) if rng.random() < 0.4 else rng.uniform(-0.6, 0.6)
    r = rng.uniform(0.3, 1.0) * SPEED
    return (r * math.cos(a), r * math.sin(a), rng.uniform(-0.3, 0.3) * TURN)


def lines(seed=SEED, seconds=SECONDS):
    """The stream's lines (dicts)."""
    rng = random.Random(seed)
    out = []
    t = 0
    here = (0.0, 0.0, 0.0)
    while t < seconds * 1000:
        kind = KINDS[rng.randrange(len(KINDS))] if t else "ramp"
        length = rng.randrange(600, 2501, 20)
        if kind == "stop":
            out.append({"t_ms": t, "stop": True})
            t += rng.randrange(600, 1501, 20)
            here = (0.0, 0.0, 0.0)
            continue
        if kind == "ramp":
            goal = _point(rng)
        elif kind == "reverse":
            goal = (-here[0], -here[1], -here[2]) if any(here) else _point(rng)
        elif kind == "swap":
            goal = (-here[1], here[0], here[2]) if any(here) else _point(rng)
        else:
            goal = (0.0, 0.0, rng.choice((-1, 1)) * rng.uniform(0.5, 1.0) * TURN)
        start = here if kind == "ramp" else goal
        end = t + length
        while t < end:
            f = 1.0 - (end - t) / length
            v = [start[k] + (goal[k] - start[k]) * f for k in range(3)]
            v[0] += rng.uniform(-1.5, 1.5)
            v[1] += rng.uniform(-1.5, 1.5)
            v[2] += rng.uniform(-0.5, 0.5)
            line = {"t_ms": t}
            for key, val, unit in (("vx", v[0], 1), ("vy", v[1], 1), ("yaw", v[2], 2)):
                val = round(max(-SPEED, min(SPEED, val)) if key != "yaw" else max(-TURN, min(TURN, val)), unit)
                if val:
                    line[key] = val
            out.append(line)
            t += rng.randrange(20, 101, 20)
        here = goal
    out.append({"t_ms": t, "stop": True})
    return out


def main():
    for line in lines():
        print(json.dumps(line, separators=(",", ":")))


if __name__ == "__main__":
    main()
