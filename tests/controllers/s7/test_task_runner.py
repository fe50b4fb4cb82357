"""The scheduling half of the CPU declares the state it uses: an attribute it reads or writes without a
declaration is a test failure, not a surprise for the next reader."""

from __future__ import annotations

import ast
import inspect

from plcsim.controllers.s7.cpu import CPU
from plcsim.controllers.s7.execution import TaskRunner


def test_task_runner_uses_only_attributes_it_declares_and_the_cpu_sets_them():
    tree = ast.parse(inspect.getsource(TaskRunner))
    used = {
        node.attr
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self"
    }
    declared = set(TaskRunner.__annotations__)
    methods = {name for name, value in vars(TaskRunner).items() if callable(value)}
    assert used - declared - methods == set()
    cpu = CPU(program="def OB1(t):\n    pass\n")
    assert [name for name in declared if not hasattr(cpu, name)] == []
