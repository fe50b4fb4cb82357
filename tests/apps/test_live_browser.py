"""The live panel in a real browser: headless Chromium (Debian's, driven by playwright; no browser download).

A click on the PANEL rig's button TL lights the lamp within the next frames; letting go puts it out; the saved
scenario replays to the trace digest the page showed. Where no browser can be had, the test says so and is skipped.
"""

from __future__ import annotations

import os
import shutil

import pytest

from plcsim.apps.live import Recording
from plcsim.apps.live.build import Target
from plcsim.apps.live.session import PANEL_DEMO

CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
LAMP = 'circle[data-path="panel/lamps/LED"]'
LAMP_OFF = "rgb(70,70,70)"  # plants.components.draw.LAMP_OFF
FRAMES = 2
"""The lamp must be drawn lit within this many frames after the first frame that shows the press recorded (the
press is applied at the next step, 20 ms of wall time at most later; frames go out at 25 a second)."""
WATCH_FRAMES = f"""() => {{
    window.plcsimLive.seen = [];
    window.plcsimLive.onFrame = (s) => window.plcsimLive.seen.push(
        [s.actions.length, document.querySelector('{LAMP}').getAttribute('fill') !== '{LAMP_OFF}']);
}}"""


def _chromium() -> str:
    path = os.environ.get("PLCSIM_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None or not os.path.isfile(path):  # (CI names the system's usual Chrome, which may be absent)
        pytest.skip(f"no Chromium at {path or 'PATH'} (Debian: apt-get install chromium; or set PLCSIM_CHROMIUM)")
    return path


@pytest.fixture
def browser():
    executable = _chromium()
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (the test extra has it)")
    with sync_api.sync_playwright() as p:
        try:
            chromium = p.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
        except sync_api.Error as exc:
            pytest.skip(f"Chromium at {executable} does not start headless: {str(exc).splitlines()[0]}")
        yield chromium
        chromium.close()


def paused_and_saved(page, screenshot) -> dict:
    """Pause the page's simulation, save the session (the digest is then of a standing simulation), take a
    screenshot; what the page saved."""
    page.click("#run")
    page.wait_for_function("window.plcsimLive.state.paused === true")
    page.click("#save")
    page.wait_for_function("window.plcsimLive.lastSaved !== null", timeout=10_000)
    page.screenshot(path=str(screenshot))
    return page.evaluate("window.plcsimLive.lastSaved")


EVIL_PAGE = """<!doctype html><title>another site</title><script>
const base = "127.0.0.1:{port}", out = {{}};
fetch(`http://${{base}}/api/scenario.toml`, {{ mode: "no-cors" }}).catch(() => {{}});
fetch(`http://${{base}}/api/save`, {{ method: "POST", mode: "no-cors" }}).catch(() => {{}});
window.result = new Promise((resolve) => {{
  const ws = new WebSocket(`ws://${{base}}/ws?token={token}`);  // even holding the token
  ws.onopen = () => {{
    out.ws = "open";
    ws.send(JSON.stringify({{ op: "do", verb: "press", target: "TL" }}));
    ws.send(JSON.stringify({{ op: "scan" }}));
    ws.send(JSON.stringify({{ op: "save" }}));
    setTimeout(() => resolve(out), 1000);
  }};
  ws.onclose = () => {{ out.ws = out.ws || "refused"; setTimeout(() => resolve(out), 500); }};
}});
</script>"""


def test_another_sites_page_and_a_rebinding_page_cannot_reach_the_session(tmp_path):
    """In the browser a teacher uses: a page of another site opens a WebSocket to the session (browsers let any page
    open one) and fetches the old writing route; a page whose name is rebound to 127.0.0.1 loads the panel's page.
    Neither drives, reads or writes anything, in a browser without Chromium's recent Local Network Access checks
    (Firefox has none; against the server before these checks the page pressed TL and wrote the file)."""
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (the test extra has it)")
    from plcsim.apps.live.server import open_live

    saved = tmp_path / "saved.toml"
    panel = open_live("PANEL", PANEL_DEMO, port=0, paused=True, save_scenario=saved)
    rebinding = "--host-resolver-rules=MAP evil.example 127.0.0.1"
    unguarded = "--disable-features=LocalNetworkAccessChecks"  # Chromium's own check: the server must not need it
    try:
        with sync_api.sync_playwright() as p:
            chromium = p.chromium.launch(executable_path=_chromium(), args=[*CHROMIUM_ARGS, rebinding, unguarded])
            page = chromium.new_page()
            evil = EVIL_PAGE.format(port=panel.port, token=panel.token)
            page.route("http://evil.example/", lambda route: route.fulfill(content_type="text/html", body=evil))
            page.goto("http://evil.example/")
            result = page.evaluate("window.result")
            rebound = page.goto(f"http://evil.example:{panel.port}/")
            rebound_status, rebound_text = rebound.status, page.inner_text("body")
            chromium.close()
    finally:
        panel.stop()
    assert result == {"ws": "refused"}
    assert panel.session.recorded == [] and not saved.exists()
    assert rebound_status == 403 and "127.0.0.1" in rebound_text


def test_a_click_lights_the_lamp_and_the_saved_session_replays(browser, tmp_path):
    from plcsim.apps.live.server import open_live

    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    panel = open_live("PANEL", program, port=0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.wait_for_selector(LAMP)
        assert page.get_attribute(LAMP, "fill") == LAMP_OFF
        button = page.locator('#controls button[data-control="TL"]')
        box = button.bounding_box()
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.evaluate(WATCH_FRAMES)
        page.mouse.down()
        page.wait_for_function(
            f"document.querySelector('{LAMP}').getAttribute('fill') !== '{LAMP_OFF}'", timeout=10_000
        )
        seen = page.evaluate("window.plcsimLive.seen")
        recorded = next(i for i, (actions, _) in enumerate(seen) if actions)
        lit = next(i for i, (_, on) in enumerate(seen) if on)
        assert lit - recorded <= FRAMES, f"the lamp was drawn lit {lit - recorded} frames after the press: {seen}"
        assert page.locator('tr[data-tag="LED"] .dot.true').count() == 1  # the watch table shows LED TRUE
        page.mouse.up()
        page.wait_for_function(
            f"document.querySelector('{LAMP}').getAttribute('fill') === '{LAMP_OFF}'", timeout=10_000
        )
        page.click("#save")
        page.wait_for_function("window.plcsimLive.lastSaved !== null", timeout=10_000)
        saved = page.evaluate("window.plcsimLive.lastSaved")
        shown = page.inner_text("#digest")
        page.screenshot(path=str(tmp_path / "panel.png"))
    finally:
        panel.stop()
    assert errors == []
    assert saved["digest"][:16] in shown
    rec = Recording.from_toml(saved["toml"], "saved from the page")
    assert [(a.verb, a.target) for a in rec.actions] == [("press", "TL"), ("release", "TL")]
    sim = Target.find("PANEL").simulation(program, rec.scenario(), seed=rec.seed)
    sim.run()
    assert sim.now == saved["t_ns"]
    assert sim.trace.digest() == saved["digest"]
    lit = sim.trace.intervals("LED")
    assert len(lit) == 1 and lit[0][0] >= rec.actions[0].t.lo_ns  # the replay lights the lamp once, after the press


def test_parts_faults_and_the_watch_table_from_the_page_replay(browser, tmp_path):
    from plcsim.apps.live.server import open_live

    program = tmp_path / "belt.py"
    program.write_text(
        "def OB1(t):\n    if t.S1:\n        t.D1 = True\n    if t.S2:\n        t.D1 = False\n", encoding="utf-8"
    )
    panel = open_live("CONV1", program, port=0, speed=2.0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.click('[data-station="S1"]')  # the station's marker on the drawing
        part = page.locator('#machine [data-part="p1"]')
        part.wait_for(timeout=10_000)
        page.wait_for_function("window.plcsimLive.state.watch.D1 === true", timeout=10_000)  # S1 started the belt
        part.click()  # the part's menu
        page.click('#part-menu button:text("jam")')
        page.wait_for_function("window.plcsimLive.state.events.some((e) => e.includes('scenario jam p1'))")
        page.select_option("#fault-verb", "stick")
        page.select_option("#fault-signal", "S2")
        page.select_option("#fault-value", "true")
        page.click("#fault-apply")
        page.locator('#faults .chip:text("S2")').wait_for(timeout=10_000)
        page.wait_for_function("window.plcsimLive.state.watch.D1 === false", timeout=10_000)  # S2 'seen': stop
        page.fill('tr[data-tag="D1"] input', "1")
        page.click('tr[data-tag="D1"] button:text("force")')
        page.locator('tr[data-tag="D1"].forced').wait_for(timeout=10_000)
        saved = paused_and_saved(page, tmp_path / "conv1.png")
    finally:
        panel.stop()
    assert errors == []
    rec = Recording.from_toml(saved["toml"], "saved from the page")
    assert [(a.verb, a.target) for a in rec.actions] == [
        ("place", "p1"),
        ("jam", "p1"),
        ("stick", "S2"),
        ("force", "D1"),
    ]
    sim = Target.find("CONV1").simulation(program, rec.scenario(), seed=rec.seed)
    sim.run()
    assert sim.trace.digest() == saved["digest"]
    assert sim.cpu.forces == {"D1": True}


def test_the_sorters_own_verbs_and_a_coloured_part_from_the_page_replay(browser, tmp_path):
    """4.3.17 live: daylight on the colour sensor from the 'Machine' card, then a red part (properties typed as
    ``colour=2``); the saved session holds both and replays to the page's digest."""
    from plcsim.apps.live.server import open_live

    program = "exercises/solutions/4_3_17/reference.py"
    panel = open_live("4.3.17", program, port=0, speed=2.0)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(panel.url)
        page.locator("#rig-card").wait_for(timeout=10_000)  # shown: the rig brings verbs
        # daylight first: applied while the part is being measured, it could change the colour the program sees,
        # and when that happens would depend on how fast the browser is (the session paces to the wall clock)
        page.select_option("#rig-verb", "set_ambient")
        page.select_option("#rig-target", "FARBA")
        page.fill('#rig-args input[data-arg="offset"]', "1500")
        page.click("#rig-apply")
        page.wait_for_function("window.plcsimLive.state.events.some((e) => e.includes('scenario set_ambient FARBA'))")
        page.fill("#part-props", "colour=2")
        page.click('[data-station="OS1"]')
        page.locator('#machine [data-part="p1"]').wait_for(timeout=10_000)
        page.wait_for_function("window.plcsimLive.state.watch['DATA.POZ2_DETEKCIA'] === 2", timeout=20_000)
        saved = paused_and_saved(page, tmp_path / "sort.png")
    finally:
        panel.stop()
    assert errors == []
    target = Target.find("4.3.17")
    rec = Recording.from_toml(saved["toml"], "saved from the page", target.verbs())
    assert [(a.verb, a.target) for a in rec.actions] == [("set_ambient", "FARBA"), ("place", "p1")]
    assert rec.actions[1].args["properties"] == {"colour": 2} and rec.actions[0].args == {"offset": 1500}
    sim = target.simulation(program, rec.scenario(), seed=rec.seed)
    sim.run()
    assert sim.trace.digest() == saved["digest"]
