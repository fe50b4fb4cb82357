"""Static types of a program's expressions, from the tag table: what the rewrite and the analysis ask.

:class:`Typing` knows the root tag schema and which tags alias memory; it types an expression as a data
type, an instance type or None (unknown), and reports an unknown tag or member at load time with the
nearest names, before the program runs.
"""

from __future__ import annotations

import ast
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.s7.instructions import BOOL_RESULTS, block_named
from plcsim.core.errors import UnknownTagError, did_you_mean
from plcsim.frontends.python.subset import place
from plcsim.tags.memory import parse_address
from plcsim.tags.table import FBType
from plcsim.tags.types import ArrayType, Bool, StructType, Time


@dataclass
class Typing:
    """What the compiler knows statically: the root tag schema and which tags alias memory.

    ``aliased`` names root tags (``"POM"``) and members of non-optimized DBs (``"DATA.INT_1"``)
    whose bytes another tag shares; stores into them must go through byte memory.
    """

    root: StructType
    aliased: frozenset[str] = frozenset()
    filename: str = "<program>"
    root_params: dict[str, str] = field(default_factory=dict)
    aliases: Mapping[str, str] = field(default_factory=dict)
    """Other names of the table's tags (:attr:`~plcsim.tags.table.TagTable.aliases`), searched by the hints."""

    def type_of(self, node: ast.expr, env: dict[str, Any]) -> Any:
        """The static type of an expression: a DataType, an FB instance type, or None when unknown."""
        if isinstance(node, ast.Name):
            return env.get(node.id)
        if isinstance(node, ast.Constant):
            return Bool if isinstance(node.value, bool) else None
        if isinstance(node, ast.Attribute):
            base = self.type_of(node.value, env)
            return self.member_type(base, node.attr, node)
        if isinstance(node, ast.Subscript):
            base = self.type_of(node.value, env)
            if isinstance(base, ArrayType):
                return base.element
            if base is self.root and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, str):
                return self.root_item_type(node.slice.value, node)
            return None
        if isinstance(node, ast.Compare):
            return Bool
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return Bool
        if isinstance(node, ast.BoolOp):
            return Bool if all(self.type_of(v, env) is Bool for v in node.values) else None
        if isinstance(node, ast.IfExp):
            body, orelse = self.type_of(node.body, env), self.type_of(node.orelse, env)
            return body if body is orelse else None
        if isinstance(node, ast.Call):
            func = node.func
            if isinstance(func, ast.Name) and func.id in BOOL_RESULTS:
                return Bool
            if isinstance(func, ast.Attribute):
                base = self.type_of(func.value, env)
                if isinstance(base, FBType) and func.attr in instance_boxes(base):
                    return Bool
        return None

    def member_type(self, base: Any, attr: str, node: ast.AST) -> Any:
        """The type of ``base.attr``; an unknown tag or member is a load-time error with suggestions."""
        if isinstance(base, StructType):
            member = base.members.get(attr)
            if member is None:
                what = "no tag" if base is self.root else f"{base.name} has no member"
                raise UnknownTagError(f"{place(self.filename, node)}: {what} {attr!r}{self.hint(attr, base)}")
            return member.type
        if isinstance(base, FBType):
            block = block_named(base.name)
            members = block.readable if block is not None else {}
            if attr in instance_boxes(base):
                return None
            if attr not in members:
                boxes = sorted(instance_boxes(base))
                raise UnknownTagError(
                    f"{place(self.filename, node)}: a {base.name} instance has no member {attr!r}"
                    f"{did_you_mean(attr, list(members) + boxes)} (members: {', '.join(members)}; "
                    f"boxes: {', '.join(boxes)})"
                )
            kind = members[attr]
            return Bool if kind == "Bool" else Time if kind == "Time" else None
        return None

    def root_item_type(self, key: str, node: ast.AST) -> Any:
        """The type of ``t["NAME"]`` or ``t["%MW10"]``."""
        if key in self.root.members:
            return self.root.members[key].type
        if key.lstrip().startswith("%"):
            return parse_address(key).default_type()
        raise UnknownTagError(f"{place(self.filename, node)}: no tag {key!r}{self.hint(key, self.root)}")

    def hint(self, name: str, base: StructType) -> str:
        """The did-you-mean of an unknown tag or member: the names nearest to ``name``, the table's aliases among
        them, an alias named with the tag it stands for."""
        if base is self.root:
            others = {a: t for a, t in self.aliases.items() if "." not in t}
        else:
            others = {
                a.partition(".")[2]: t.partition(".")[2]
                for a, t in self.aliases.items()
                if a.partition(".")[0] == base.name and "." in t
            }
        hint = did_you_mean(name, [*base.members, *others])
        for alias, target in others.items():
            hint = hint.replace(repr(alias), f"{alias!r} (= {target})")
        return hint


def instance_boxes(fb: FBType) -> tuple[str, ...]:
    """The box methods of an instance type (none for a type plcsim does not describe)."""
    block = block_named(fb.name)
    return block.boxes if block is not None else ()


def safe_type(typing: Typing, node: ast.expr, env: dict[str, Any]) -> Any:
    """The static type of ``node``, or None where an unknown tag makes it unknown (no error)."""
    try:
        return typing.type_of(node, env)
    except UnknownTagError:
        return None
