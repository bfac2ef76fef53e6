"""Planted bugs (mutants) against the tests that should catch them: `make mutants` (issue 24).

Each mutant is one textual change to one file (the text must occur exactly once) and the tests
that cover that code. For each, a scratch copy of the tree gets the change, those tests run there
(pytest -x, fixed order), and the mutant is caught when they fail. Prints one line per mutant and
the score; exits 1 when a mutant survives. `python tools/mutants.py NAME...` runs only those.

A mutant that survives is either a hole in the tests or an equivalent change (say which, here).
"""

import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (name, file, text, replacement, tests)
MUTANTS = [
    (
        "calibrate-waits-for-a-frame",
        "firmware/hexapod/tick.py",
        "            self.pulses[k] = p\n            self.frame.write_frame(self.pulses)\n",
        "            self.pulses[k] = p\n",
        ["tests/test_tick_jog.py"],
    ),
    (
        "refused-trim-recorded",
        "firmware/console.py",
        "        r = self.robot\n        code = r.calibrate(k, self.base[k][0] + trim, direction, lo, hi)\n",
        "        r = self.robot\n        self.trims[k] = trim\n"
        "        code = r.calibrate(k, self.base[k][0] + trim, direction, lo, hi)\n",
        ["tests/test_console_refusals.py"],
    ),
    (
        "refused-load-not-rolled-back",
        "firmware/console.py",
        "                for j in range(k):\n",
        "                for j in range(0):\n",
        ["tests/test_console_refusals.py"],
    ),
    (
        "pid-kp-before-ki-checked",
        "firmware/console.py",
        '            kp = self._num("kp", args[0], 3, 0, top, "")\n',
        '            kp = self._num("kp", args[0], 3, 0, top, "")\n            p.kp = kp\n',
        ["tests/test_console_refusals.py"],
    ),
    (
        "cal-source-file-after-failed-save",
        "firmware/console.py",
        "            crc = self.store.save(self.rows())\n",
        '            self.cal_source = "file"\n            crc = self.store.save(self.rows())\n',
        ["tests/test_console_refusals.py"],
    ),
    (
        "calstore-no-read-back",
        "firmware/calstore.py",
        "        if self._read(self.tmp) != text:\n",
        "        if False:\n",
        ["tests/test_console_refusals.py", "tests/test_calstore.py"],
    ),
    (
        "sim-no-contact-check",
        "host/hexapod_host/wall/sim.py",
        "            if near and body.touches([walls[k] for k in near]) >= 0:\n",
        "            if False:\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "sim-prefilter-one-sided",
        "host/hexapod_host/wall/sim.py",
        "        if lo < 10.0 and hi > -10.0:\n",
        "        if lo < 10.0 and hi > 10.0:\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "sim-no-sonar-noise",
        "host/hexapod_host/wall/sim.py",
        "            noise = rng.gauss(0.0, NOISE_MM) if disturb else 0.0\n",
        "            noise = rng.gauss(0.0, NOISE_MM) * 0 if disturb else 0.0\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "sim-no-dropouts",
        "host/hexapod_host/wall/sim.py",
        "            drop = rng.random() < DROPOUT if disturb else False\n",
        "            drop = rng.random() < 0 if disturb else False\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "sim-no-heading-slip",
        "host/hexapod_host/wall/sim.py",
        "            slip = rng.gauss(0.0, slip_sd) if disturb else 0.0\n",
        "            slip = rng.gauss(0.0, slip_sd) * 0 if disturb else 0.0\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "sim-body-by-command-not-feet",
        "host/hexapod_host/wall/physics.py",
        "        moved = b.move(self.old, speed, slip)\n",
        "        moved = b.move(self.old, 1.0, slip)\n",
        ["tests/test_wall_rules.py"],
    ),
    (
        "follow-no-dead-end",
        "firmware/hexapod/follow.py",
        "                if self._turn > CORNER_TURN * 100 or self._turn < -CORNER_TURN * 100:\n",
        "                if False:\n",
        ["tests/test_follow.py"],
    ),
    (
        "follow-odometry-sign-flipped",
        "firmware/hexapod/follow.py",
        "        self._adr += self._away * d  #",
        "        self._adr -= self._away * d  #",
        ["tests/test_follow.py"],
    ),
    (
        "follow-sensor-change-drops-the-integral",
        "firmware/hexapod/follow.py",
        "            self.pid.reset(True)\n",
        "            self.pid.reset()\n",
        ["tests/test_follow.py"],
    ),
    (
        "follow-sensor-change-keeps-the-derivative",
        "firmware/hexapod/follow.py",
        "            self.pid.reset(True)\n",
        "            pass\n",
        ["tests/test_follow.py"],
    ),
]


def scratch_copy():
    d = tempfile.mkdtemp(prefix="hexapod-mutants-")
    skip = shutil.ignore_patterns(".venv", ".git", ".hypothesis", ".ruff_cache", "__pycache__", "*.png")
    for name in os.listdir(ROOT):
        src = os.path.join(ROOT, name)
        if name in (".venv", ".git", ".hypothesis", ".ruff_cache"):
            continue
        if name == "build":
            os.symlink(os.path.realpath(src), os.path.join(d, name))
        elif os.path.isdir(src):
            shutil.copytree(src, os.path.join(d, name), ignore=skip, symlinks=True)
        else:
            shutil.copy2(src, os.path.join(d, name))
    return d


def run(mutant, tree):
    name, path, text, new, tests = mutant
    target = os.path.join(tree, path)
    with open(target) as f:
        original = f.read()
    if original.count(text) != 1:
        return "stale (its text occurs %d times in %s)" % (original.count(text), path)
    with open(target, "w") as f:
        f.write(original.replace(text, new))
    try:
        env = dict(os.environ, PYTHONPATH=os.path.join(tree, "host"))
        cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p", "no:randomly", *tests]
        proc = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    finally:
        with open(target, "w") as f:
            f.write(original)
    if proc.returncode == 0:
        return "SURVIVED"
    failed = [x.split(" - ")[0][7:] for x in proc.stdout.splitlines() if x.startswith("FAILED ")]
    return "caught by " + (failed[0] if failed else "exit %d" % proc.returncode)


def main(names):
    chosen = [m for m in MUTANTS if not names or m[0] in names]
    tree = scratch_copy()
    caught = 0
    try:
        for m in chosen:
            verdict = run(m, tree)
            caught += verdict.startswith("caught")
            print("%-36s %s" % (m[0], verdict), flush=True)
    finally:
        shutil.rmtree(tree)
    print("caught %d of %d mutants (%.0f %%)" % (caught, len(chosen), 100.0 * caught / max(1, len(chosen))))
    return 0 if caught == len(chosen) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
