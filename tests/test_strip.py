"""serial.strip: the docstrings out of what a CircuitPython drive gets, every other line in place.

The expected texts are written by hand; for the firmware's own files the oracle is CPython's
ast.get_docstring (not the module's own search): the stripped tree must be the source's with each
docstring a `pass`, every statement on its original line and column."""

import ast
import glob
import os

import pytest

from hexapod_host import FIRMWARE, ROOT
from hexapod_host.serial import strip

SOURCE = '''"""Module doc,
two lines."""

import sys

X = "not a docstring"


class Leg:
    """Class doc."""

    def pulse_us(self, a):
        """Method doc
        on three
        lines."""
        s = "a string, not first"
        return a + 1  # a comment stays


def coxa():
    "single quotes"


def femur():
    return 1
'''

EXPECTED = """pass


import sys

X = "not a docstring"


class Leg:
    pass

    def pulse_us(self, a):
        pass


        s = "a string, not first"
        return a + 1  # a comment stays


def coxa():
    pass


def femur():
    return 1
"""


def test_docstrings_become_pass_and_every_line_keeps_its_number():
    assert strip.docstrings(SOURCE) == EXPECTED


def test_a_source_without_docstrings_is_unchanged():
    text = "def f(a):\n    x = 'doc?'\n    return x\n"
    assert strip.docstrings(text) == text


def test_a_docstring_sharing_its_last_line_is_refused_by_name():
    text = 'def f():\n    """a\n    b"""; x = 1\n    return x\n'
    with pytest.raises(ValueError, match="hexapod/leg.py: its docstrings could not be taken out"):
        strip.docstrings(text, "hexapod/leg.py")


def _oracle(text):
    """The source's tree with each docstring (as ast.get_docstring finds it) a pass."""
    tree = ast.parse(text)
    for node in ast.walk(tree):
        kinds = (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)
        if isinstance(node, kinds) and ast.get_docstring(node, clean=False) is not None:
            node.body[0] = ast.Pass(lineno=node.body[0].lineno, col_offset=node.body[0].col_offset)
    return tree


def _starts(tree):
    return [(type(n).__name__, n.lineno, n.col_offset) for n in ast.walk(tree) if hasattr(n, "lineno")]


FILES = sorted(glob.glob(os.path.join(FIRMWARE, "**", "*.py"), recursive=True))
FILES += sorted(glob.glob(os.path.join(ROOT, "boards", "*.py")) + glob.glob(os.path.join(ROOT, "robots", "*.py")))


def test_every_firmware_file_stripped_is_the_same_program_on_the_same_lines():
    assert len(FILES) > 40
    saved = 0
    for path in FILES:
        with open(path) as f:
            text = f.read()
        out = strip.docstrings(text, path)
        want = _oracle(text)
        got = ast.parse(out)
        assert ast.dump(got) == ast.dump(want), path
        assert _starts(got) == _starts(want), path
        assert out.count("\n") == text.count("\n"), path
        saved += len(text) - len(out)
    assert saved > 50000  # the docstrings are a fifth of the firmware's source (96 KB of 461 KB, 2026-11-27)
