"""Planted bugs, one at a time, in a scratch copy of the tree: which does the suite catch?

    python tools/mutants.py [--list tools/mutants.toml] [--only ID ...] [--jobs N] [--json OUT]

Each mutant in the list (TOML, [[mutant]] tables) names a file, an exact text found once in it, its
replacement and the test files that guard it. The tool copies the tree (sources only) into one
scratch directory per job, applies each mutant alone, runs its tests there with pytest (-x, the
first failure is enough) and restores the file. A mutant is:
- caught:   its tests failed;
- survived: its tests passed (the bug went unnoticed: a test is missing);
- stale:    its text is no longer in the file, or found more than once (the list needs updating);
- equivalent mutants (`equivalent = true`, with `why`) are run and reported but left out of the score.
Score = caught / (caught + survived) over the non-equivalent mutants. Exit 0 when the score reaches
--goal (default 0.95), 1 when it does not, 2 on a bad list. `make mutants` runs it.
"""

import argparse
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COPY = ("firmware", "host", "boards", "robots", "tests", "pyproject.toml")
SKIP = shutil.ignore_patterns("__pycache__", "node_modules", "*.pyc", ".hypothesis")
FIELDS = {"id", "file", "find", "replace", "tests", "equivalent", "why", "area"}


def load(path):
    """The mutant list, checked: a list of dicts; ValueError naming the first bad entry."""
    with open(path, "rb") as f:
        data = tomllib.load(f)
    mutants = data.get("mutant", [])
    seen = set()
    for k, m in enumerate(mutants):
        where = "mutant %d (%s)" % (k + 1, m.get("id", "no id"))
        missing = {"id", "file", "find", "replace", "tests", "area"} - set(m)
        if missing:
            raise ValueError("%s: missing %s" % (where, ", ".join(sorted(missing))))
        extra = set(m) - FIELDS
        if extra:
            allowed = ", ".join(sorted(FIELDS))
            raise ValueError("%s: unknown field %s, allowed %s" % (where, ", ".join(sorted(extra)), allowed))
        if m["id"] in seen:
            raise ValueError("%s: id used twice" % where)
        seen.add(m["id"])
        if m["find"] == m["replace"]:
            raise ValueError("%s: find and replace are the same text" % where)
        if not m["tests"] or not all(isinstance(t, str) and t.startswith("tests/") for t in m["tests"]):
            raise ValueError("%s: tests must be a non-empty list of paths under tests/" % where)
        if m.get("equivalent") and not m.get("why"):
            raise ValueError("%s: an equivalent mutant needs a why" % where)
    return mutants


def scratch_tree(dest):
    """A copy of the tree's sources in dest (the build's Pico image linked, not copied)."""
    for name in COPY:
        src = os.path.join(ROOT, name)
        if os.path.isdir(src):
            shutil.copytree(src, os.path.join(dest, name), ignore=SKIP, symlinks=True)
        else:
            shutil.copy(src, dest)
    image = os.path.join(ROOT, "build", "pico-firmware")
    if os.path.isdir(image):
        os.makedirs(os.path.join(dest, "build"))
        os.symlink(image, os.path.join(dest, "build", "pico-firmware"))
    modules = os.path.join(ROOT, "host", "pico", "node_modules")
    if os.path.isdir(modules):
        os.symlink(modules, os.path.join(dest, "host", "pico", "node_modules"))


def run_one(m, tree, python, timeout):
    """Apply m in tree, run its tests, restore: (status, seconds, last lines of output)."""
    path = os.path.join(tree, m["file"])
    with open(path) as f:
        text = f.read()
    n = text.count(m["find"])
    if n != 1:
        return "stale", 0.0, "found %d times in %s" % (n, m["file"])
    with open(path, "w") as f:
        f.write(text.replace(m["find"], m["replace"]))
    env = dict(os.environ, PYTHONPATH=os.path.join(tree, "host"), PYTHONDONTWRITEBYTECODE="1")
    cmd = [python, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "-p", "no:randomly", "-n", "0", *m["tests"]]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True, timeout=timeout)
        status = "survived" if proc.returncode == 0 else ("caught" if proc.returncode == 1 else "error")
        tail = (proc.stdout + proc.stderr).strip().splitlines()[-3:]
    except subprocess.TimeoutExpired:
        status, tail = "caught", ["timed out after %d s (a hang counts as caught)" % timeout]
    finally:
        with open(path, "w") as f:
            f.write(text)
    return status, time.monotonic() - t0, "\n".join(tail)


def main(argv=None):
    p = argparse.ArgumentParser(description="Planted bugs, one at a time: caught or survived.")
    p.add_argument("--list", default=os.path.join(ROOT, "tools", "mutants.toml"))
    p.add_argument("--only", nargs="*", default=None, help="ids to run (default: all)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--json", default=None, help="write the results here")
    p.add_argument("--goal", type=float, default=0.95)
    p.add_argument("--timeout", type=int, default=900, help="seconds a mutant's tests may take")
    a = p.parse_args(argv)
    try:
        mutants = load(a.list)
    except (OSError, ValueError, tomllib.TOMLDecodeError) as e:
        print("mutants: %s: %s" % (a.list, e), file=sys.stderr)
        return 2
    if a.only is not None:
        unknown = sorted(set(a.only) - {m["id"] for m in mutants})
        if unknown:
            print("mutants: unknown id %s; see %s" % (", ".join(unknown), a.list), file=sys.stderr)
            return 2
        mutants = [m for m in mutants if m["id"] in a.only]
    jobs = max(1, min(a.jobs, len(mutants)))
    results = {}
    with tempfile.TemporaryDirectory(prefix="mutants-") as tmp:
        trees = []
        for j in range(jobs):
            t = os.path.join(tmp, "t%d" % j)
            os.makedirs(t)
            scratch_tree(t)
            trees.append(t)
        free = list(trees)
        with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
            pending = {}
            todo = list(mutants)
            done = 0
            while todo or pending:
                while todo and free:
                    m = todo.pop(0)
                    tree = free.pop()
                    pending[pool.submit(run_one, m, tree, sys.executable, a.timeout)] = (m, tree)
                fin, _ = concurrent.futures.wait(pending, return_when=concurrent.futures.FIRST_COMPLETED)
                for fut in fin:
                    m, tree = pending.pop(fut)
                    free.append(tree)
                    results[m["id"]] = fut.result()
                    done += 1
                    status, secs, _ = results[m["id"]]
                    print("[%3d/%d] %-9s %-34s %5.0f s" % (done, len(mutants), status, m["id"], secs), flush=True)
    rows = []
    for m in mutants:
        status, secs, tail = results[m["id"]]
        rows.append(
            {
                "id": m["id"],
                "area": m["area"],
                "file": m["file"],
                "status": status,
                "equivalent": bool(m.get("equivalent")),
                "seconds": round(secs, 1),
                "tests": m["tests"],
                "detail": tail if status != "caught" else "",
            }
        )
    scored = [r for r in rows if not r["equivalent"] and r["status"] in ("caught", "survived")]
    caught = sum(r["status"] == "caught" for r in scored)
    score = caught / len(scored) if scored else 0.0
    summary = {
        "mutants": len(rows),
        "caught": caught,
        "survived": [r["id"] for r in scored if r["status"] == "survived"],
        "stale": [r["id"] for r in rows if r["status"] == "stale"],
        "error": [r["id"] for r in rows if r["status"] == "error"],
        "equivalent": [r["id"] for r in rows if r["equivalent"]],
        "score": round(score, 4),
        "goal": a.goal,
    }
    print(json.dumps(summary, indent=1))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"summary": summary, "mutants": rows}, f, indent=1)
    return 0 if score >= a.goal and not summary["stale"] and not summary["error"] else 1


if __name__ == "__main__":
    sys.exit(main())
