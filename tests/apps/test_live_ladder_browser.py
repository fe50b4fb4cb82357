"""The live page's Program card in a real browser (Debian's Chromium through playwright): the running
program's ladder with power flow; pressing a button turns its contact and the coil it drives green, and a
click on a contact's tag puts it into the watch table. Screenshots of three machines with the card open."""

from __future__ import annotations

import pytest
from test_live_browser import browser  # noqa: F401 - the fixture: Chromium or a skip

from plcsim.apps.live.session import PANEL_DEMO

CONTACT = '#ladder g.contact[data-operand="TL"]'
COIL = '#ladder g.coil[data-operand="LED"]'


def test_pressing_a_button_turns_its_contact_and_the_coil_green_and_a_click_watches_the_tag(browser, tmp_path):  # noqa: F811
    from plcsim.apps.live.server import open_live

    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    panel = open_live("PANEL", program, port=0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.wait_for_selector(CONTACT, timeout=10_000)
        assert page.get_attribute(CONTACT, "data-power") == "false"
        assert page.get_attribute(COIL, "data-power") == "false"
        button = page.locator('#controls button[data-control="TL"]')
        box = button.bounding_box()
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.mouse.down()
        page.wait_for_function(
            f"document.querySelector('{CONTACT}')?.dataset.power === 'true'"
            f" && document.querySelector('{COIL}')?.dataset.power === 'true'",
            timeout=10_000,
        )
        green = page.evaluate(f"getComputedStyle(document.querySelector('{CONTACT} line:nth-of-type(3)')).stroke")
        assert green == "rgb(26, 154, 26)"
        page.screenshot(path=str(tmp_path / "panel-program-card.png"))
        page.mouse.up()
        page.wait_for_function(f"document.querySelector('{COIL}')?.dataset.power === 'false'", timeout=10_000)
        page.click(f"{CONTACT} text.operand")
        page.wait_for_function("window.plcsimLive.state.watch.TL !== undefined", timeout=10_000)
        assert page.locator('#watch tr[data-tag="TL"]').count() == 1
    finally:
        panel.stop()
    assert errors == []


@pytest.mark.parametrize(("target", "name"), [("4.3.7", "conveyor"), ("4.3.17", "sorter")])
def test_the_program_card_shows_the_machine_s_program(browser, tmp_path, target, name):  # noqa: F811
    from exercises import get
    from plcsim.apps.live.server import open_live

    panel = open_live(target, get(target).reference.path, port=0, scenario=get(target).scenarios[0].name)
    try:
        page = browser.new_page(viewport={"width": 1500, "height": 1100})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.wait_for_selector("#ladder g.network", timeout=10_000)
        page.wait_for_timeout(1500)
        networks = page.locator("#ladder g.network").count()
        page.screenshot(path=str(tmp_path / f"{name}-program-card.png"))
    finally:
        panel.stop()
    assert errors == []
    assert networks == len(get(target).reference.program().tasks["OB1"].networks)


def test_a_saved_program_file_is_offered_for_download_and_runs_without_ending_the_session(browser, tmp_path):  # noqa: F811
    import os

    from plcsim.apps.live.server import open_live

    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    panel = open_live("PANEL", program, port=0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.wait_for_selector(COIL, timeout=10_000)
        assert page.locator("#program-changed.hidden").count() == 1
        program.write_text("def OB1(t):\n    t.LED = not t.TL\n", encoding="utf-8")
        os.utime(program, ns=(1, 1))
        page.wait_for_selector("#program-changed:not(.hidden)", timeout=10_000)
        page.click("#download")
        page.wait_for_function(f"document.querySelector('{COIL}')?.dataset.power === 'true'", timeout=10_000)
        page.wait_for_selector("#program-changed.hidden", state="attached", timeout=10_000)
        assert page.get_attribute(CONTACT, "data-power") == "true"  # now an NC contact: TL released, it passes
        assert page.locator(f"{CONTACT} line").count() == 5  # the NC contact's slash: two wires, two bars, one slash
        page.screenshot(path=str(tmp_path / "after-download.png"))
        actions = page.evaluate("window.plcsimLive.state.actions")
    finally:
        panel.stop()
    assert errors == []
    assert any(a.startswith("download the program lamp.py") for a in actions)


def test_an_instruction_list_shows_its_lines_with_the_accumulator(browser, tmp_path):  # noqa: F811
    from exercises import get
    from plcsim.apps.live.server import open_live

    panel = open_live("T-01", get("T-01").reference.path, port=0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.wait_for_selector("#ladder svg.il g.il-line", timeout=10_000)
        lines = page.locator("#ladder g.il-line").count()
        page.screenshot(path=str(tmp_path / "il-program-card.png"))
    finally:
        panel.stop()
    assert errors == []
    assert lines == 4  # LD, OR, ANC, WR: every instruction of the pass, none of the declarations
