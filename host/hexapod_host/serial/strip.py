"""Docstrings out of a source that a board compiles at import (CircuitPython's drive).

A board that compiles `.py` holds the whole parse tree of a module while it compiles it, and a
docstring is a string object in that tree: on a Feather's 171 KB heap that is room the deploy
needs (docs/flashing.md, "CircuitPython's heap"). The bytecode is the same without them: neither
MicroPython nor CircuitPython keeps a docstring (no `__doc__`), and nothing here reads one.

Each docstring becomes `pass` followed by the newlines it spanned, so every other line keeps its
number: a traceback on the board names the line of the source in the repository.
"""

import ast


def docstring_nodes(tree):
    """The docstring expressions of a module, its classes and functions (ast.Expr of a str
    constant, first statement of its body)."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                found.append(first)
    return found


def _offset(lines, lineno, col):
    """Character offset of (1-based line, UTF-8 byte column) in the joined lines."""
    start = sum(len(line) for line in lines[: lineno - 1])
    return start + len(lines[lineno - 1].encode()[:col].decode())


def shape(tree):
    """What a tree compiles from: its nodes without end positions, and where each statement and
    expression starts (line, column), in walk order."""
    starts = [(type(n).__name__, n.lineno, n.col_offset) for n in ast.walk(tree) if hasattr(n, "lineno")]
    return ast.dump(tree, include_attributes=False), starts


def docstrings(text, name="<source>"):
    """text with every docstring replaced by `pass` and the newlines it spanned (line numbers
    kept). SyntaxError (naming name) for a source that does not parse; ValueError if the result
    is not the same program (its tree, docstrings as `pass`, and every start position)."""
    tree = ast.parse(text, name)
    nodes = docstring_nodes(tree)
    lines = text.splitlines(keepends=True)
    out = text
    for node in sorted(nodes, key=lambda n: (n.lineno, n.col_offset), reverse=True):  # last first: offsets hold
        start = _offset(lines, node.lineno, node.col_offset)
        end = _offset(lines, node.end_lineno, node.end_col_offset)
        out = out[:start] + "pass" + "\n" * (node.end_lineno - node.lineno) + out[end:]
    for node in nodes:  # the tree the result must have: the docstrings' places taken by a pass each
        node.__class__ = ast.Pass
        del node.value
    try:
        same = shape(ast.parse(out, name)) == shape(tree)
    except SyntaxError:
        same = False
    if not same:
        raise ValueError("%s: its docstrings could not be taken out leaving the same program" % name)
    return out
