"""Tables for the terminal that never cut a name: a table where it fits, a list where it does not.

A student reads tag names, exercise numbers and file names off these tables and types them back; an
ellipsis (``OS2_Detekc…``) or a name broken over two lines makes that impossible. :func:`print_records`
prints a table whose cells wrap only between words, and only when every word still fits whole in its
column; otherwise (a narrow terminal, a long name) it prints the same records as a list, one block per
record and one line per field, which fits any width.

>>> from rich.console import Console
>>> rows = [["OS2_Detekcia_Farba", "light barrier before the colour sensor", "Bool"]]
>>> print_records(Console(width=100), ["tag", "comment", "type"], rows, title="I/O")
                                     I/O
┏━━━━━━━━━━━━━━━━━━━━┳━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━┳━━━━━━┓
┃ tag                ┃ comment                                ┃ type ┃
┡━━━━━━━━━━━━━━━━━━━━╇━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━╇━━━━━━┩
│ OS2_Detekcia_Farba │ light barrier before the colour sensor │ Bool │
└────────────────────┴────────────────────────────────────────┴──────┘
>>> print_records(Console(width=24), ["tag", "comment", "type"], rows, title="I/O")
I/O
OS2_Detekcia_Farba
  comment: light barrier
  before the colour
  sensor
  type: Bool
"""

from __future__ import annotations

import io
from collections.abc import Sequence

from rich.cells import cell_len
from rich.console import Console
from rich.padding import Padding
from rich.table import Table
from rich.text import Text


def print_records(console: Console, columns: Sequence[str], rows: Sequence[Sequence[str]], *, title: str = "") -> None:
    """Print ``rows`` (plain text, never markup) under ``columns`` as a table if every word fits whole in
    it at the console's width, else as a list headed by each row's first cell."""
    widths = _longest_words(columns, rows)
    table = Table(title=Text(title) if title else None)
    for name, width in zip(columns, widths, strict=True):
        table.add_column(Text(name), overflow="fold", min_width=width)
    for row in rows:
        table.add_row(*(Text(str(cell)) for cell in row))
    if sum(widths) + 3 * len(widths) + 1 <= console.width and _whole(table, console.width):
        console.print(table)
        return
    if title:
        console.print(Text(title, style="bold"))
    for row in rows:
        console.print(Text(str(row[0]), style="bold"), soft_wrap=True)
        for name, cell in zip(columns[1:], row[1:], strict=True):
            if str(cell):
                console.print(Padding(Text(f"{name}: {cell}"), (0, 0, 0, 2), expand=False))


def _longest_words(columns: Sequence[str], rows: Sequence[Sequence[str]]) -> list[int]:
    """Each column's longest word (in terminal cells): the narrowest it can be with every word whole."""
    return [
        max(cell_len(word) for text in (name, *(str(row[k]) for row in rows)) for word in [*text.split(), ""])
        for k, name in enumerate(columns)
    ]


def _whole(table: Table, width: int) -> bool:
    """Whether rich draws ``table`` at ``width`` without cropping its right edge (its column layout can ask
    for a cell or two more than the words need)."""
    probe = Console(width=width, file=io.StringIO(), color_system=None, highlight=False)
    probe.print(table)
    rows = [line.rstrip() for line in probe.file.getvalue().splitlines()]
    return all(line[-1] in "┓┃┫┩│┤┘" for line in rows if line and line[0] in "┏┃┣┡│├└")
