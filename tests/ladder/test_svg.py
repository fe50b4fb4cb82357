"""The ladder picture: what it shows (operands, coils, boxes with their parameters, text boxes), the
notebook's ``_repr_svg_``, PNG through the same drawing, and the commands that write it."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import pytest

from exercises import get
from plcsim.apps.cli import main
from plcsim.ladder.view import Ladder


def _texts(svg: str) -> list[str]:
    root = ET.fromstring(svg)
    return [el.text or "" for el in root.iter("{http://www.w3.org/2000/svg}text")]


def test_the_4_3_7_reference_shows_its_four_networks_with_every_operand_and_the_timer_box():
    exercise = get("4.3.7")
    svg = Ladder(exercise.reference.program(), exercise.tag_table()).svg()
    texts = _texts(svg)
    assert [t for t in texts if t.startswith("Network")] == [
        "Network 1: Rung 1: an object at S1 sets D1.",
        "Network 2: Rung 2: TON_A(IN := D1 AND NOT S2, PT := 10 s); its Q sets ALARM.",
        "Network 3: Rung 3: S2 OR TON_A.Q OR ALARM resets D1 (every scan while ALARM is TRUE).",
        "Network 4: Rung 4: ACK resets ALARM.",
    ]
    for operand in ['"S1"', '"D1"', '"S2"', '"TON_A"', '"TON_A".Q', '"ALARM"', '"ACK"', "T#10s"]:
        assert operand in texts, operand
    assert {"TON", "IN", "PT", "Q", "ET", "S", "R"} <= set(texts)
    assert 'data-tag="TON_A.Q"' in svg  # a page can open the operand in its watch table


def test_a_text_box_shows_the_program_s_lines_and_why_there_is_no_rung():
    svg = Ladder.from_source("def OB1(t):\n    for i in range(3):\n        t.N = t.N + i\n").svg()
    texts = _texts(svg)
    assert "for i in range(3):" in texts and "    t.N = t.N + i" in texts
    assert any(t.startswith("no rung: a for statement") for t in texts)


def test_a_notebook_shows_the_svg_and_png_is_the_same_drawing():
    picture = Ladder.from_source('def OB1(t):\n    t.LED = P(t.S1, "M1") or t.LED\n')
    assert picture._repr_svg_() == picture.svg()
    pytest.importorskip("resvg_py")
    png = picture.png()
    assert png.startswith(b"\x89PNG")
    width = int(re.search(r'width="(\d+)"', picture.svg()).group(1))
    assert int.from_bytes(png[16:20], "big") == int(width * 1.5)


def test_plcsim_ladder_and_show_ladder_write_the_picture(tmp_path, capsys):
    out = tmp_path / "r.svg"
    path = get("4.3.12").reference.path
    assert main(["ladder", str(path), "--exercise", "4.3.12", "-o", str(out)]) == 0
    assert "TON" in _texts(out.read_text(encoding="utf-8"))
    shown = tmp_path / "s.svg"
    assert main(["show", "4.3.7", "--ladder", "wrong-scan-order", "-o", str(shown)]) == 0
    title = _texts(shown.read_text(encoding="utf-8"))[0]
    assert title.startswith("4.3.7") and "wrong-scan-order" in title
    assert main(["ladder", str(tmp_path / "x.il")]) != 0
    assert ".il program" in capsys.readouterr().err
