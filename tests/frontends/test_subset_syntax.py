"""The subset is a whitelist of syntax: anything not listed is refused, with the student-friendly reason
for the common refusals and a plain one for the rest (issue 9)."""

from __future__ import annotations

import ast

import pytest

from plcsim import Program
from plcsim.core.errors import ProgramError, SubsetError
from plcsim.frontends.python.subset import ALLOWED_NODES


@pytest.mark.parametrize(
    ("body", "words"),
    [
        pytest.param(
            "try:\n        pass\n    except* ValueError:\n        pass", "TryStar syntax is not part", id="try-star"
        ),
        pytest.param("x = f'{t.TL}'", "f-strings are not part", id="f-string"),
        pytest.param("x = {1, 2}", "sets are not part", id="set"),
        pytest.param("x = [1] @ [2]", "the @ operator", id="matmul"),
        pytest.param("x = [*t.ARR]", "* unpacking", id="starred"),
        pytest.param("x: int = 3", "annotated assignments", id="annassign"),
        pytest.param("del t.LED", "del is not part", id="del"),
        pytest.param("assert t.TL", "assert is not part", id="assert"),
        pytest.param("with t.TL:\n        pass", "with is not part", id="with"),
        pytest.param("x = (i for i in range(3))", "generator expressions", id="genexp"),
        pytest.param("x = {i: i for i in range(3)}", "comprehensions", id="dictcomp"),
        pytest.param("x = (yield 1)", "yield is not part", id="yield"),
        pytest.param("raise ValueError", "raise is not part", id="raise"),
        pytest.param("nonlocal x", "nonlocal is not allowed", id="nonlocal"),
    ],
)
def test_syntax_outside_the_whitelist_is_refused_with_its_line(body, words):
    with pytest.raises(SubsetError) as info:
        Program.from_source(f"def OB1(t):\n    {body}\n", "lab.py")
    assert str(info.value).startswith("lab.py, line 2:"), str(info.value)
    assert words in str(info.value)


def test_an_async_network_is_refused():
    with pytest.raises(SubsetError, match=r"lab.py, line 1: async functions are not part"):
        Program.from_source("async def OB1(t):\n    pass\n", "lab.py")


def test_the_whitelist_holds_no_construct_that_binds_names_behind_the_compilers_back():
    # each of these binds a name or runs code in a way the store rewriter does not see
    unseen = {
        ast.NamedExpr,
        ast.comprehension,
        ast.ExceptHandler,
        ast.withitem,
        ast.match_case,
        ast.Lambda,
        ast.ClassDef,
        ast.Global,
        ast.Nonlocal,
        ast.Import,
        ast.ImportFrom,
        ast.AnnAssign,
        ast.Starred,
        ast.Yield,
        ast.Await,
        ast.JoinedStr,
    }
    assert not unseen & ALLOWED_NODES


def test_what_the_plc_subset_uses_is_accepted():
    source = """
N = Int(0)
ARR = DB(A=Array(0, 3, Int))
def OB1(t):
    x = 1
    x += 2
    if t.TL and not t.LED or x > 2:
        t.N = -x if x else abs(x)
    elif 1 <= x < 5:
        pass
    for i in range(4):
        if i == 2:
            continue
        t.ARR.A[i] = i * 2 // 1 % 5 - (i << 1 >> 1) | 1 & 3 ^ 2
    while x > 0:
        x -= 1
        break
    d = {"a": 1}
    s = "text"[1:3]
    y = [1, 2][0] + (3, 4)[1] + d["a"] + len(s) + 2**3
    t.N = y if y is not None and y in (13, 14) else 0
"""
    Program.from_source(source, "lab.py")


FIRST_BY_LINE = """import os


def helper(t):
    t.LED = abs(-1)


def OB1(t):
    t.LED = t.TL
    y = t.__class__
    x = [i for i in range(3)]
"""


@pytest.mark.parametrize(
    ("source", "line", "words"),
    [
        pytest.param(FIRST_BY_LINE, 1, "import", id="import-before-comprehension"),
        pytest.param(
            FIRST_BY_LINE.replace("import os", ""), 10, "attribute .__class__", id="dunder-before-comprehension"
        ),
        pytest.param(
            "def OB1(t):\n    t.LED = nope\n    x = [i for i in range(3)]\n",
            2,
            "unknown name 'nope'",
            id="name-before-syntax",
        ),
        pytest.param(
            "def OB1(t):\n    x = [i for i in range(3)]\n    t.LED = nope\n",
            2,
            "comprehensions",
            id="syntax-before-name",
        ),
    ],
)
def test_a_file_with_several_violations_is_refused_at_the_first_by_line(source, line, words):
    # A student reads from the top: the error names the first violation, not the last one the walk met.
    with pytest.raises(ProgramError) as info:
        Program.from_source(source, "lab.py")
    assert str(info.value).startswith(f"lab.py, line {line}:"), str(info.value)
    assert words in str(info.value)
