"""tools/mutants.py (`make mutants`): its list is current (every planted text found exactly once),
bad lists are refused with the entry and the reason named, and a planted bug in the scratch copy
is caught while the checkout stays untouched."""

import hashlib
import os
import subprocess
import sys

import pytest

from hexapod_host import ROOT

sys.path.insert(0, os.path.join(ROOT, "tools"))
import mutants  # noqa: E402

LIST = os.path.join(ROOT, "tools", "mutants.toml")


def test_every_mutant_text_is_found_exactly_once():
    ms = mutants.load(LIST)
    assert len(ms) >= 20
    for m in ms:
        with open(os.path.join(ROOT, m["file"])) as f:
            assert f.read().count(m["find"]) == 1, m["id"]
        for t in m["tests"]:
            assert os.path.isfile(os.path.join(ROOT, t)), (m["id"], t)


GOOD = 'id = "a"\narea = "pid"\nfile = "f.py"\nfind = "x"\nreplace = "y"\ntests = ["tests/test_pid.py"]\n'


@pytest.mark.parametrize(
    "body, why",
    [
        (GOOD.replace('id = "a"\n', ""), "mutant 1 (no id): missing id"),
        (GOOD.replace('area = "pid"\n', ""), "mutant 1 (a): missing area"),
        (GOOD.replace('tests = ["tests/test_pid.py"]\n', ""), "mutant 1 (a): missing tests"),
        (GOOD + 'colour = "red"\n', "mutant 1 (a): unknown field colour, allowed "),
        (GOOD.replace('replace = "y"', 'replace = "x"'), "mutant 1 (a): find and replace are the same text"),
        (GOOD.replace('["tests/test_pid.py"]', "[]"), "mutant 1 (a): tests must be a non-empty list"),
        (GOOD.replace('["tests/test_pid.py"]', '["test_pid.py"]'), "mutant 1 (a): tests must be a non-empty list"),
        (GOOD + "equivalent = true\n", "mutant 1 (a): an equivalent mutant needs a why"),
    ],
)
def test_a_bad_list_is_refused_naming_the_entry(tmp_path, body, why):
    p = tmp_path / "m.toml"
    p.write_text("[[mutant]]\n" + body)
    with pytest.raises(ValueError) as e:
        mutants.load(str(p))
    assert str(e.value).startswith(why)


def test_a_repeated_id_is_refused(tmp_path):
    p = tmp_path / "m.toml"
    p.write_text("[[mutant]]\n" + GOOD + "[[mutant]]\n" + GOOD)
    with pytest.raises(ValueError, match=r"mutant 2 \(a\): id used twice"):
        mutants.load(str(p))


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def test_a_planted_sign_flip_is_caught_in_the_copy_and_the_checkout_is_untouched(tmp_path):
    pid = os.path.join(ROOT, "firmware", "hexapod", "pid.py")
    before = digest(pid)
    out = tmp_path / "r.json"
    cmd = [sys.executable, os.path.join(ROOT, "tools", "mutants.py"), "--only", "pid-derivative-sign"]
    proc = subprocess.run([*cmd, "--jobs", "1", "--json", str(out)], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr  # 1 of 1 caught: score 1.0 >= 0.95
    assert '"caught": 1' in proc.stdout and digest(pid) == before
    bad = subprocess.run([*cmd[:2], "--only", "no-such-mutant"], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "unknown id no-such-mutant" in bad.stderr
