"""What a drawn rung does, written back as Python: the meaning of the picture, for the proof that it is
the program's own logic.

LAD runs a rung left to right and top to bottom and evaluates every element on it, whatever the power
flow: each contact is read into its own variable first, then the RLO is combined (series AND, parallel
OR, NOT), boxes are called with the RLO at their rung pin, and outputs act when the RLO at them holds.
:func:`ladder_source` turns every network of a program into that form (text boxes and aliases stay as
written), so that a test can run the original and the drawing side by side on the same states.
"""

from __future__ import annotations

import ast
from itertools import count

from plcsim.frontends.python.pipeline import copy_tree
from plcsim.frontends.python.program import Program
from plcsim.ladder.model import (
    Alias,
    Block,
    Box,
    CallCoil,
    Coil,
    Compare,
    Contact,
    Fork,
    FunctionContact,
    Invert,
    Operation,
    Parallel,
    Rung,
    Series,
    TextBox,
)

PREFIX = "lad"
"""The prefix of the variables the generated code holds each RLO in (a program's own locals may not
start with it for the comparison to be meaningful; the test checks)."""


def ladder_source(program: Program, blocks: list[Block]) -> str:
    """``program``'s text with every drawn network's body replaced by what its drawing does."""
    bodies = {net.name: _network_body(net.parts) for block in blocks for net in block.networks}
    module = copy_tree(program.tree)
    for stmt in module.body:
        if isinstance(stmt, ast.FunctionDef) and stmt.name in bodies:
            stmt.body = bodies[stmt.name] or [ast.Pass()]
    return ast.unparse(ast.fix_missing_locations(module)) + "\n"


def _network_body(parts: list) -> list[ast.stmt]:
    names = count()
    body: list[ast.stmt] = []
    for part in parts:
        if isinstance(part, TextBox):
            body.extend(copy_tree(list(part.statements)))
        elif isinstance(part, Alias):
            body.append(copy_tree(part.statement))
        elif isinstance(part, Rung):
            body.extend(_Rung(names).series(part.series, None)[0])
    return body


class _Rung:
    def __init__(self, names: count):
        self.names = names

    def fresh(self) -> str:
        return f"{PREFIX}{next(self.names)}"

    def assign(self, out: list[ast.stmt], value: ast.expr) -> ast.expr:
        name = self.fresh()
        out.append(ast.Assign([ast.Name(name, ast.Store())], value))
        return ast.Name(name, ast.Load())

    def series(self, series: Series, rlo: ast.expr | None) -> tuple[list[ast.stmt], ast.expr | None]:
        """The statements that run ``series`` with ``rlo`` at its left end (None: the power rail)."""
        out: list[ast.stmt] = []
        for position, item in enumerate(series.items):
            value: ast.expr | None = None
            if isinstance(item, Contact):
                source = copy_tree(item.source)
                value = self.assign(out, ast.UnaryOp(ast.Not(), source) if item.kind == "NC" else source)
            elif isinstance(item, Compare | FunctionContact):
                value = self.assign(out, copy_tree(item.source))
            elif isinstance(item, Invert):
                inner, result = self.series(item.inner, None)
                out.extend(inner)
                value = self.assign(out, ast.UnaryOp(ast.Not(), result or ast.Constant(True)))
            elif isinstance(item, Parallel):
                results = []
                for branch in item.branches:
                    inner, result = self.series(branch, None)
                    out.extend(inner)
                    results.append(result or ast.Constant(True))
                value = self.assign(out, ast.BoolOp(ast.Or(), results) if len(results) > 1 else results[0])
            elif isinstance(item, Box):
                call = copy_tree(item.call)
                call.args = []
                keywords = [ast.keyword(item.rung_pin, rlo if rlo is not None else ast.Constant(True))]
                keywords += [ast.keyword(pin, copy_tree(source)) for pin, _, source in item.pins]
                call.keywords = keywords
                if position == len(series.items) - 1:  # Q goes nowhere: a bare call, as in the program
                    out.append(ast.Expr(call))
                    rlo = None
                else:
                    rlo = self.assign(out, call)
                continue
            elif isinstance(item, Coil):
                power = rlo if rlo is not None else ast.Constant(True)
                target = copy_tree(item.target)
                target.ctx = ast.Store()
                if item.kind == "=":
                    out.append(ast.Assign([target], power))
                else:
                    out.append(ast.If(power, [ast.Assign([target], ast.Constant(item.kind == "S"))], []))
                continue
            elif isinstance(item, Operation | CallCoil):
                statement = copy_tree(item.statement)
                out.append(statement if rlo is None else ast.If(rlo, [statement], []))
                continue
            elif isinstance(item, Fork):
                for branch in item.branches:
                    out.extend(self.series(branch, rlo)[0])
                continue
            assert value is not None
            rlo = value if rlo is None else self.assign(out, ast.BoolOp(ast.And(), [rlo, value]))
        return out, rlo
