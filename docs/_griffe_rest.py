r"""A Griffe extension for the API site (``mkdocs.yml``): plcsim's docstrings use reStructuredText habits
(``:func:`name``` roles, ``>>>`` examples, ``::`` literal blocks) that Markdown would run together;
this rewrites them as Markdown code before mkdocstrings renders them.

>>> rest_to_markdown("Run it (:func:`~plcsim.grading.grade`):\n\n>>> 1 + 1\n2\n\nDone.").splitlines()
['Run it (`plcsim.grading.grade`):', '', '```pycon', '>>> 1 + 1', '2', '```', '', 'Done.']
>>> print(rest_to_markdown("In a test file::\n\n    def test_x(plcsim_run):\n        pass\n\nEnd."))
In a test file:
<BLANKLINE>
```
def test_x(plcsim_run):
    pass
```
<BLANKLINE>
End.
"""

from __future__ import annotations

import re
import textwrap
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:mod|func|class|meth|attr|data|exc|obj|const):`~?([^`]+)`")


def rest_to_markdown(text: str) -> str:
    """The docstring ``text`` with roles as code spans, doctest and literal blocks as fenced code
    (a literal block has no language: it may be Python or a shell command)."""
    lines = _ROLE.sub(lambda m: f"`{m.group(1)}`", text).splitlines()
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith(">>>"):
            block = []
            while i < len(lines) and lines[i].strip():
                block.append(lines[i])
                i += 1
            out += ["```pycon", *textwrap.dedent("\n".join(block)).splitlines(), "```"]
            continue
        if line.rstrip().endswith("::") and i + 1 < len(lines) and not lines[i + 1].strip():
            indent = len(line) - len(line.lstrip())
            head = line.rstrip()[:-1]
            out += [head] if head.strip() != ":" else []
            j = i + 1
            block = []
            while j < len(lines) and (not lines[j].strip() or len(lines[j]) - len(lines[j].lstrip()) > indent):
                block.append(lines[j])
                j += 1
            while block and not block[-1].strip():
                block.pop()
            out += ["", "```", *textwrap.dedent("\n".join(block)).strip("\n").splitlines(), "```", ""]
            i = j
            while i < len(lines) and not lines[i].strip():
                i += 1
            continue
        out.append(line)
        i += 1
    return "\n".join(out)


class RestToMarkdown(griffe.Extension):
    """Rewrite every docstring with :func:`rest_to_markdown` once the object tree is built."""

    def on_object(self, *, obj: Any, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = rest_to_markdown(obj.docstring.value)
