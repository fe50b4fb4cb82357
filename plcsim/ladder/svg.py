"""Drawing networks as LAD in SVG, as the course's figures and TIA Portal's editor show them.

Each network: its number and title, its comment, then its rungs from the left power rail: contacts with
the operand above, boxes with the instance above and the parameters at their pins, coils at the path's
end, parallel branches opening and closing, and text boxes for what has no rung. With a
:class:`~plcsim.ladder.monitor.PowerFlow` the picture is TIA's online view: a path with power green and
solid, one without blue and dashed, values beside box pins. An operand that names a tag carries
``data-tag`` so that a page can open it in a watch table.
"""

from __future__ import annotations

import html
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from plcsim.ladder.model import (
    Box,
    CallCoil,
    Coil,
    Compare,
    Contact,
    Element,
    Fork,
    FunctionContact,
    Invert,
    Network,
    Operation,
    Parallel,
    Rung,
    Series,
    TextBox,
)

ROW = 56
"""Height of one row of a rung: the power line runs at ROW/2 from the row's top."""
CELL = 96
"""Width of a contact or coil cell."""
PIN = 18
"""Vertical distance between two pins of a box."""
BOX_SIDE = 78
"""Width left of a box for its input operands (and right of it for its outputs)."""
BOX_W = 72
MARGIN = 16
RAIL = 24
FONT = "font-family:Segoe UI,Helvetica,Arial,sans-serif"
MONO = "font-family:Consolas,Menlo,monospace"
POWER = "#1a9a1a"
NO_POWER = "#2b5fd9"
INK = "#222"
LINE_H = 15

Flow = Callable[[Any], tuple[bool | None, bool | None]]
"""For an element: (power at its left, power at its right); None where not monitored."""
Values = Callable[[str, str], str | None]
"""For a box's instance and a pin: the value to show beside it, or None."""


@dataclass
class Drawing:
    """An element laid out: its size and how to draw it with its power line at (x, y)."""

    width: int
    height: int
    draw: Callable[[list[str], int, int], None]
    """``draw(out, x, y)``: append SVG with the left end of the power line at (x, y), y = top + ROW/2."""


class LadderSvg:
    """Lays out and draws networks; ``flow`` and ``values`` (from monitoring) colour and annotate them."""

    def __init__(self, flow: Flow | None = None, values: Values | None = None):
        self.flow = flow
        self.values = values

    # -- the whole picture ---------------------------------------------------------------------------

    def render(self, networks: Iterable[Network], title: str = "") -> str:
        out: list[str] = []
        y = MARGIN
        width = 480
        if title:
            out.append(_text(MARGIN, y + 14, title, size=15, weight="bold"))
            y += 28
        for net in networks:
            y, used = self._network(out, net, y)
            width = max(width, used)
        height = y + MARGIN
        head = (
            f'<svg xmlns="http://www.w3.org/2000/svg" class="ladder" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" style="background:#fff;{FONT}">'
        )
        return head + "".join(out) + "</svg>"

    def _network(self, out: list[str], net: Network, y: int) -> tuple[int, int]:
        label = f"  ({net.label}:)" if net.label else ""
        out.append(f'<g class="network" data-network="{html.escape(net.name)}">')
        heading = f"Network {net.number}: {net.title}{label}"
        out.append(_text(MARGIN, y + 14, heading, size=13, weight="bold"))
        y += 22
        width = 2 * MARGIN + 8 * len(heading)
        for line in _wrap(net.comment, 110):
            out.append(_text(MARGIN + 4, y + 11, line, size=11, color="#666", style="italic"))
            width = max(width, 2 * MARGIN + 6 * len(line))
            y += LINE_H
        y += 6
        for part in net.parts:
            if isinstance(part, Rung):
                drawing = self.series(part.series)
                top = y
                rail_h = max(drawing.height, ROW)
                rail = POWER if self.flow is not None else INK  # the left rail always carries power
                out.append(_line(MARGIN, top, MARGIN, top + rail_h, rail, 3))
                drawing.draw(out, MARGIN, top + ROW // 2)
                width = max(width, MARGIN + drawing.width + MARGIN)
                y += rail_h + 8
            elif isinstance(part, TextBox):
                y, used = self._text_box(out, part, y)
                width = max(width, used)
        out.append(_line(MARGIN, y + 4, MARGIN + 300, y + 4, "#ccc", 1))
        out.append("</g>")
        return y + 14, width

    def _text_box(self, out: list[str], box: TextBox, y: int) -> tuple[int, int]:
        lines = box.text.splitlines()
        width = max(320, 16 + 7 * max((len(line) for line in lines), default=0))
        height = 10 + LINE_H * len(lines) + 22
        out.append(
            f'<rect class="scl" x="{MARGIN}" y="{y}" width="{width}" height="{height}" fill="#f6f6ee" stroke="#999"/>'
        )
        out.append(_text(MARGIN + width - 36, y + 13, "SCL", size=10, color="#999"))
        for i, line in enumerate(lines):
            out.append(_text(MARGIN + 8, y + 20 + i * LINE_H, line, size=12, mono=True, space=True))
        note = f"no rung: {box.reason}"
        out.append(_text(MARGIN + 8, y + height - 8, note, size=10, color="#888", style="italic"))
        return y + height + 8, MARGIN + width + MARGIN

    # -- elements ---------------------------------------------------------------------------------

    def element(self, item: Element) -> Drawing:
        if isinstance(item, Contact | Coil | CallCoil):
            return self.symbol(item)
        if isinstance(item, Compare | FunctionContact | Box | Operation):
            return self.box(item)
        if isinstance(item, Invert):
            return self.series(Series((*item.inner.items, _NOT)), item)
        if isinstance(item, Parallel | Fork):
            return self.branches(item)
        raise TypeError(item)

    def series(self, series: Series, owner: Any = None) -> Drawing:
        parts = [self.element(item) for item in series.items]
        width = sum(p.width for p in parts) or CELL // 2
        height = max((p.height for p in parts), default=ROW)

        def draw(out: list[str], x: int, y: int) -> None:
            if not parts:
                out.append(_line(x, y, x + width, y, self._colour(owner, False)))
            for part in parts:
                part.draw(out, x, y)
                x += part.width

        return Drawing(width, height, draw)

    def branches(self, item: Parallel | Fork) -> Drawing:
        parts = [self.series(b) for b in item.branches]
        closes = isinstance(item, Parallel)
        inner = max(p.width for p in parts)
        width = inner + 24
        height = sum(p.height for p in parts)

        def draw(out: list[str], x: int, y: int) -> None:
            top = y
            power_in, _ = self._flow(item)
            for i, part in enumerate(parts):
                branch_in = power_in
                colour = self._colour_value(branch_in)
                if i:
                    out.append(_line(x + 8, top - parts[i - 1].height, x + 8, top, colour, dash=branch_in is False))
                out.append(_line(x, top, x + 8, top, colour, dash=branch_in is False)) if i == 0 else None
                part.draw(out, x + 8, top)
                end = x + 8 + part.width
                branch_out = self._branch_out(item.branches[i])
                if closes:
                    join = x + width - 8
                    out.append(_line(end, top, join, top, self._colour_value(branch_out), dash=branch_out is False))
                    if i == 0:
                        _, power_out = self._flow(item)
                        out.append(
                            _line(join, top, x + width, top, self._colour_value(power_out), dash=power_out is False)
                        )
                    if i:
                        _, power_out = self._flow(item)
                        out.append(
                            _line(
                                x + width - 8,
                                top - parts[i - 1].height,
                                x + width - 8,
                                top,
                                self._colour_value(power_out),
                                dash=power_out is False,
                            )
                        )
                top += part.height

        return Drawing(width, height, draw)

    def symbol(self, item: Contact | Coil | CallCoil) -> Drawing:
        cell = max(CELL, _text_width(item.operand, 11) + 16, _text_width(getattr(item, "memory", ""), 10) + 16)

        def draw(out: list[str], x: int, y: int) -> None:
            power_in, power_out = self._flow(item)
            kind = "contact" if isinstance(item, Contact) else "coil"
            lit_now = power_out if isinstance(item, Contact) else power_in
            state = "" if lit_now is None else f' data-power="{str(bool(lit_now)).lower()}"'
            out.append(f'<g class="{kind}" data-operand="{html.escape(tag_of(item.operand))}"{state}>')
            mid = x + cell // 2
            left, right = mid - 11, mid + 11
            before = self._colour_value(power_in)
            after = self._colour_value(power_out if isinstance(item, Contact) else power_in)
            out.append(_line(x, y, left, y, before, dash=power_in is False))
            out.append(_line(right, y, x + cell, y, after, dash=power_out is False))
            lit = after if isinstance(item, Contact) else (POWER if power_in else INK if power_in is None else NO_POWER)
            if isinstance(item, Contact):
                out.append(_line(left, y - 11, left, y + 11, lit, 2))
                out.append(_line(right, y - 11, right, y + 11, lit, 2))
                mark = {"NO": "", "NC": "/", "P": "P", "N": "N"}.get(item.kind, item.kind)
                if item.kind == "NC":
                    out.append(_line(left + 4, y + 9, right - 4, y - 9, lit, 1.5))
                elif mark:
                    out.append(_text(mid, y + 4, mark, size=11, anchor="middle", color=lit, weight="bold"))
                if item.memory:
                    out.append(_operand(mid, y + 26, item.memory, size=10))
            else:
                out.append(f'<path d="M{left + 4},{y - 11} Q{left - 3},{y} {left + 4},{y + 11}" {_stroke(lit, 2)}/>')
                out.append(f'<path d="M{right - 4},{y - 11} Q{right + 3},{y} {right - 4},{y + 11}" {_stroke(lit, 2)}/>')
                mark = {"=": "", "S": "S", "R": "R"}.get(item.kind, item.kind)
                if mark:
                    out.append(_text(mid, y + 4, mark, size=9 if len(mark) > 1 else 11, anchor="middle", color=lit))
                if power_in:
                    out.append(f'<circle class="lit" cx="{mid}" cy="{y}" r="5" fill="{POWER}" opacity="0.35"/>')
            out.append(_operand(mid, y - 16, item.operand))
            out.append("</g>")

        return Drawing(cell, ROW + (10 if isinstance(item, Contact) and item.memory else 0), draw)

    def box(self, item: Compare | FunctionContact | Box | Operation) -> Drawing:
        name, instance, power_pins, inputs, outputs = _box_parts(item)
        rows = 1 + max(len(inputs), len(outputs))
        body = 22 + rows * PIN
        left = max(BOX_SIDE // 2, max((_text_width(v, 10) for _, v in inputs), default=0) + 22)
        right = max(BOX_SIDE // 2, max((_text_width(v, 10) for _, v in outputs), default=0) + 22)
        box_w = max(BOX_W, _text_width(name, 11) + 16, _text_width(instance, 11) - 2 * BOX_SIDE // 3)
        width = left + box_w + right
        height = max(ROW, body + 24)

        def draw(out: list[str], x: int, y: int) -> None:
            power_in, power_out = self._flow(item)
            bx = x + left
            top = y - 24
            out.append(_line(x, y, bx, y, self._colour_value(power_in), dash=power_in is False))
            out.append(_line(bx + box_w, y, x + width, y, self._colour_value(power_out), dash=power_out is False))
            edge = POWER if power_out else NO_POWER if power_out is False else INK
            out.append(
                f'<rect x="{bx}" y="{top}" width="{box_w}" height="{body}" fill="#fff" stroke="{edge}" '
                f'stroke-width="1.5"/>'
            )
            out.append(_text(bx + box_w // 2, top + 13, name, size=11, anchor="middle", weight="bold"))
            if instance:
                out.append(_operand(bx + box_w // 2, top - 5, instance, size=11))
            out.append(_text(bx + 4, y + 4, power_pins[0], size=9))
            out.append(_text(bx + box_w - 4, y + 4, power_pins[1], size=9, anchor="end"))
            live = self._value(instance, power_pins[1])
            if live is not None:
                out.append(_text(bx + box_w + 4, y + 13, live, size=9, color=POWER))
            for row, (pin, value) in enumerate(inputs, start=1):
                pin_y = y + row * PIN
                out.append(_line(bx - 10, pin_y, bx, pin_y, INK))
                out.append(_text(bx + 4, pin_y + 4, pin, size=9))
                out.append(_operand(bx - 12, pin_y + 4, value, size=10, anchor="end"))
                live = self._value(instance, pin)
                if live is not None:
                    out.append(_text(bx - 12, pin_y + 14, live, size=9, anchor="end", color=POWER))
            for row, (pin, value) in enumerate(outputs, start=1):
                out_y = y + row * PIN
                out.append(_text(bx + box_w - 4, out_y + 4, pin, size=9, anchor="end"))
                out.append(_line(bx + box_w, out_y, bx + box_w + 10, out_y, INK))
                shown = value or self._value(instance, pin) or ""
                colour = INK if value else POWER
                out.append(
                    _operand(bx + box_w + 12, out_y + 4, shown, size=10, anchor="start")
                    if value
                    else _text(bx + box_w + 12, out_y + 4, shown, size=10, color=colour)
                )

        return Drawing(width, height, draw)

    # -- power flow ------------------------------------------------------------------------------------

    def _flow(self, item: Any) -> tuple[bool | None, bool | None]:
        return self.flow(item) if self.flow is not None else (None, None)

    def _branch_out(self, series: Series) -> bool | None:
        return self._flow(series.items[-1])[1] if series.items else self._flow(series)[0]

    def _value(self, instance: str, pin: str) -> str | None:
        return self.values(instance, pin) if self.values is not None and instance else None

    def _colour(self, item: Any, right: bool) -> str:
        return self._colour_value(self._flow(item)[1 if right else 0])

    @staticmethod
    def _colour_value(power: bool | None) -> str:
        return INK if power is None else POWER if power else NO_POWER


_NOT = Contact("NOT", "", None)  # type: ignore[arg-type]
"""The NOT contact that closes an inverted group (drawn only)."""


def _box_parts(item: Any) -> tuple[str, str, tuple[str, str], list[tuple[str, str]], list[tuple[str, str]]]:
    """(name, instance, the pins on the power row (left, right), input pins, output pins) of a box."""
    if isinstance(item, Compare):
        return f"CMP {item.op}", "", ("", ""), [("IN1", item.left), ("IN2", item.right)], []
    if isinstance(item, FunctionContact):
        return item.name, "", ("", ""), list(item.pins), []
    if isinstance(item, Box):
        first, *rest = item.outputs or ("",)
        return (
            item.instruction,
            item.instance,
            (item.rung_pin, first),
            [(p, v) for p, v, _ in item.pins],
            [(o, "") for o in rest],
        )
    return item.name, "", ("EN", "ENO"), list(item.inputs), list(item.outputs)


def tag_of(operand: str) -> str:
    """The watch-table name of an operand as shown (``"DATA".POZ1`` -> ``DATA.POZ1``); empty for a local
    or a constant."""
    if not operand.startswith('"'):
        return ""
    return operand.replace('"', "")


def _operand(x: float, y: float, text: str, size: int = 11, anchor: str = "middle") -> str:
    tag = tag_of(text)
    attrs = f' class="operand" data-tag="{html.escape(tag)}" style="cursor:pointer"' if tag else ""
    head = f'<text x="{x}" y="{y}" font-size="{size}" text-anchor="{anchor}" fill="{INK}"{attrs}>'
    return f"{head}{html.escape(text)}</text>"


def _text(
    x: float,
    y: float,
    text: str,
    *,
    size: int = 11,
    anchor: str = "start",
    color: str = INK,
    weight: str = "normal",
    style: str = "normal",
    mono: bool = False,
    space: bool = False,
) -> str:
    family = f' style="{MONO}"' if mono else ""
    keep = ' xml:space="preserve"' if space else ""
    return (
        f'<text x="{x}" y="{y}" font-size="{size}" text-anchor="{anchor}" fill="{color}" font-weight="{weight}" '
        f'font-style="{style}"{family}{keep}>{html.escape(text)}</text>'
    )


def _stroke(colour: str, width: float = 1.5) -> str:
    return f'fill="none" stroke="{colour}" stroke-width="{width}"'


def _line(x1: float, y1: float, x2: float, y2: float, colour: str = INK, width: float = 1.5, dash: bool = False) -> str:
    dashes = ' stroke-dasharray="5,3"' if dash else ""
    return f'<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="{colour}" stroke-width="{width}"{dashes}/>'


def _text_width(text: str, size: int) -> int:
    """About how wide ``text`` is drawn at ``size`` px (for layout; sans-serif averages 0.6 em)."""
    return int(len(text) * size * 0.6)


def _wrap(text: str, width: int) -> list[str]:
    lines: list[str] = []
    for paragraph in text.split("\n"):
        words, line = paragraph.split(), ""
        for word in words:
            if line and len(line) + 1 + len(word) > width:
                lines.append(line)
                line = word
            else:
                line = f"{line} {word}".strip()
        if line:
            lines.append(line)
    return lines


def render_svg(
    networks: Iterable[Network], title: str = "", flow: Flow | None = None, values: Values | None = None
) -> str:
    """The SVG picture of ``networks`` (with power flow and box values when monitoring)."""
    return LadderSvg(flow, values).render(networks, title)
