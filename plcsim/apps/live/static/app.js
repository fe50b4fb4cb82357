// plcsim live panel: draws the plant's own shapes (mm, y up) as SVG and sends the student's actions.
// Plain JavaScript, no build step, no network beyond the local server (see plcsim/live/server.py).
"use strict";

const $ = (id) => document.getElementById(id);
const NS = "http://www.w3.org/2000/svg";
const page = { layout: null, state: null, ws: null, pressed: null, controls: {}, labels: new Set(), lastSaved: null };
window.plcsimLive = page; // for the browser test and the curious

// -- connection ------------------------------------------------------------------------------------
// the session's token, put in the page by the server: its WebSocket refuses a connection without it
const TOKEN = document.querySelector('meta[name="plcsim-token"]')?.content ?? "";
function connect() {
  const ws = new WebSocket(`ws://${location.host}/ws?token=${encodeURIComponent(TOKEN)}`);
  page.ws = ws;
  ws.onopen = () => setLink(true);
  ws.onclose = () => { setLink(false); setTimeout(connect, 1000); };
  ws.onmessage = (event) => {
    const m = JSON.parse(event.data);
    ({ layout: buildLayout, state: render, error: (r) => toast(r.message, true), saved: onSaved,
       ended: onEnded, digest: (r) => showDigest(r), graded: showChecks,
       downloaded: (r) => toast(`downloaded ${r.file}: STOP, load, RUN at ${(r.t_ns / 1e9).toFixed(3)} s`) })[m.type]?.(m);
  };
}
function send(message) {
  if (page.ws && page.ws.readyState === WebSocket.OPEN) page.ws.send(JSON.stringify(message));
}
function setLink(up) { const b = $("link"); b.textContent = up ? "live" : "offline"; b.className = "badge " + (up ? "on" : "off"); }
function toast(text, bad = false) {
  const t = $("toast"); t.textContent = text; t.className = "toast" + (bad ? " bad" : "");
  clearTimeout(toast.timer); toast.timer = setTimeout(() => t.classList.add("hidden"), bad ? 6000 : 3000);
}

// -- drawing ---------------------------------------------------------------------------------------
function el(tag, attrs = {}, text = null) {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== null) e.textContent = text;
  return e;
}
const flip = (y) => page.layout.bounds[1] + page.layout.bounds[3] - y; // y up (plant) -> y down (SVG)
const rgb = (c) => `rgb(${c[0]},${c[1]},${c[2]})`;
const pts = (p) => p.map(([x, y]) => `${x},${flip(y)}`).join(" ");

function fontSize() {
  const svg = $("machine"), [x0, y0, x1, y1] = page.layout.bounds;
  const scale = Math.min(svg.clientWidth / (x1 - x0), svg.clientHeight / (y1 - y0)) || 1;
  return 12 / scale; // 12 px on screen, in mm
}

function shape(d, { caption = false } = {}) {
  const [path, kind, p, color, radius, text] = d;
  let e;
  if (kind === "polygon") e = el("polygon", { points: pts(p), fill: rgb(color), stroke: "rgba(0,0,0,.35)" });
  else if (kind === "line") e = el("polyline", { points: pts(p), fill: "none", stroke: rgb(color), "stroke-width": 2.5 });
  else if (kind === "circle") e = el("circle", { cx: p[0][0], cy: flip(p[0][1]), r: radius, fill: rgb(color), stroke: "rgba(0,0,0,.35)" });
  // a label hangs centred below its point, as a recording draws it (the rigs lay their labels out for that)
  else e = el("text", { x: p[0][0], y: flip(p[0][1]) + fontSize() * 0.3, "font-size": fontSize(), "stroke-width": fontSize() / 4, fill: rgb(color), "text-anchor": "middle", "dominant-baseline": "hanging" }, text);
  if (kind !== "label") e.setAttribute("vector-effect", "non-scaling-stroke"); // a text's halo scales with the text
  e.dataset.path = path;
  const g = el("g");
  g.appendChild(e);
  if (caption && (kind === "polygon" || kind === "circle") && text && !page.labels.has(text)) {
    const x = p.reduce((a, q) => a + q[0], 0) / p.length, top = Math.max(...p.map((q) => q[1])) + radius;
    g.appendChild(el("text", { x, y: flip(top) - 3, "font-size": fontSize() * 0.8, "stroke-width": fontSize() / 5, fill: "#333", "text-anchor": "middle" }, text));
  }
  return g;
}

function buildLayout(layout) {
  page.layout = layout;
  const [x0, y0, x1, y1] = layout.bounds, svg = $("machine");
  svg.setAttribute("viewBox", `${x0} ${y0} ${x1 - x0} ${y1 - y0}`);
  svg.style.height = `${Math.max(160, Math.min(460, svg.clientWidth * (y1 - y0) / (x1 - x0)))}px`;
  $("title").textContent = layout.title;
  $("subtitle").textContent = `${layout.program} · scenario ${layout.scenario} · seed ${layout.seed}`;
  document.title = `plcsim live · ${layout.title}`;
  page.labels = new Set(layout.static.filter((d) => d[1] === "label").map((d) => d[5]));
  // the fixed names above everything (a piston's plate must not hide the name of the barrier beside it)
  const isLabel = (d) => d[1] === "label";
  $("static").replaceChildren(...layout.static.filter((d) => !isLabel(d)).map((d) => shape(d)));
  $("labels").replaceChildren(...layout.static.filter(isLabel).map((d) => shape(d)));
  page.controls = Object.fromEntries(layout.controls.map((c) => [c.name, c]));
  buildStations(layout);
  buildControls(layout);
  buildFaults(layout);
  buildRigVerbs(layout);
  buildWatch(layout);
  $("controls-card").classList.toggle("hidden", layout.controls.length === 0);
  $("parts-card").classList.toggle("hidden", layout.stations.length === 0);
  $("grade").classList.toggle("hidden", !layout.graded);
}

function showChecks(r) {
  $("checks-card").classList.remove("hidden");
  $("checks-time").textContent = `(at ${(r.t_ns / 1e9).toFixed(3)} s)`;
  $("checks").replaceChildren(...r.results.map((c) => {
    const li = document.createElement("li");
    li.className = c.passed ? "pass" : "fail";
    li.textContent = `${c.passed ? "✓" : "✗"} ${c.title}` + (c.passed ? "" : ` — ${c.message}`);
    return li;
  }));
}

function buildStations(layout) {
  const g = $("stations");
  g.replaceChildren();
  for (const s of layout.stations) {
    const y = flip(s.y), marker = el("g", { class: "station" });
    marker.dataset.station = s.name;
    marker.appendChild(el("polygon", { points: `${s.x},${y - 2} ${s.x - 4},${y - 9} ${s.x + 4},${y - 9}`, fill: "#74c0fc" }));
    marker.appendChild(el("title", {}, `place a part at ${s.name}${s.doc ? ": " + s.doc : ""}`));
    g.appendChild(marker);
  }
  const list = $("stations-list");
  list.replaceChildren(...layout.stations.map((s) => button(`place at ${s.name}`, () => placeAt(s.name), s.doc)));
}

function button(text, onclick, title = "") {
  const b = document.createElement("button");
  b.textContent = text; b.title = title;
  if (onclick) b.addEventListener("click", onclick);
  return b;
}

// -- the operator's controls -----------------------------------------------------------------------
function buildControls(layout) {
  $("controls").replaceChildren(...layout.controls.map((c) => {
    const b = button(c.name, null, `${c.kind}: ${c.doc}`);
    b.dataset.control = c.name;
    b.addEventListener("pointerdown", (e) => { e.preventDefault(); controlDown(c.name); });
    return b;
  }));
}
function controlOn(name) {  // a plant's button or switch is a sensor; an HMI control is a tag in the watch table
  const c = page.controls[name];
  return c.kind.startsWith("hmi") ? !!page.state?.watch?.[name] : !!page.state?.sensors?.[name];
}
function controlDown(name) {
  const c = page.controls[name], on = controlOn(name);
  if (c.kind === "hmi switch") return send({ op: "write", target: name, text: on ? "0" : "1" });
  if (c.kind === "hmi button") { page.pressed = name; return send({ op: "write", target: name, text: "1" }); }
  if (c.kind === "switch") return send({ op: "toggle", target: name });
  if ($("latch").checked || (on && page.pressed !== name)) {
    return on ? send({ op: "release", target: name }) : send({ op: "do", verb: "press", target: name });
  }
  page.pressed = name;
  send({ op: "do", verb: "press", target: name });
}
function controlUp() {
  if (!page.pressed) return;
  const c = page.controls[page.pressed];
  send(c.kind === "hmi button" ? { op: "write", target: page.pressed, text: "0" } : { op: "release", target: page.pressed });
  page.pressed = null;
}
window.addEventListener("pointerup", controlUp);
window.addEventListener("pointercancel", controlUp);

$("machine").addEventListener("pointerdown", (e) => {
  const control = e.target.closest("[data-control]"), station = e.target.closest("[data-station]");
  const part = e.target.closest("[data-part]");
  if (control) { e.preventDefault(); controlDown(control.dataset.control); }
  else if (station) placeAt(station.dataset.station);
  else if (part) partMenu(part.dataset.part, e.clientX, e.clientY);
});

// -- parts and faults --------------------------------------------------------------------------------
const PART_VERBS = [["remove", "remove"], ["jam", "jam"], ["unjam", "free"], ["knock_off", "knock off"]];
function partMenu(name, x, y) {
  let menu = $("part-menu");
  if (!menu) { menu = document.createElement("div"); menu.id = "part-menu"; menu.className = "card"; document.body.appendChild(menu); }
  menu.style.cssText = `position:fixed;left:${x}px;top:${y}px;display:flex;gap:4px;z-index:5`;
  menu.replaceChildren(document.createTextNode(name + " "), ...PART_VERBS.map(([verb, text]) =>
    button(text, () => { send({ op: "do", verb, target: name }); menu.remove(); })));
  setTimeout(() => window.addEventListener("pointerdown", (e) => { if (!menu.contains(e.target)) menu.remove(); }, { once: true }), 0);
}
let lastParts = {};  // the parts on the machine now (the rig verbs that act on a part offer them)
function renderParts(parts) {
  lastParts = parts;
  const names = Object.values(parts);
  const key = names.join(",");
  if (key === renderParts.key) return;
  renderParts.key = key;
  $("parts").replaceChildren(...names.map((name) => {
    const row = document.createElement("div"); row.className = "part";
    const b = document.createElement("b"); b.textContent = name;
    row.append(b, ...PART_VERBS.map(([verb, text]) => button(text, () => send({ op: "do", verb, target: name }))));
    return row;
  }));
}

// a part's properties as typed ("colour=2 size=big"): numbers and true/false as such, the rest as text
function typed(text) {
  const t = text.trim();
  if (t === "true" || t === "false") return t === "true";
  return t !== "" && !isNaN(Number(t)) ? Number(t) : t;
}
function properties(text) {
  const out = {};
  for (const item of text.split(/[\s,]+/).filter(Boolean)) {
    const [key, ...rest] = item.split("=");
    if (key && rest.length) out[key] = typed(rest.join("="));
  }
  return out;
}
function placeAt(station) {
  send({ op: "do", verb: "place", args: { station, ...properties($("part-props").value) } });
}

// -- the rig's and the controller's own verbs (set the ambient light, fail the compressor, an interrupt) --
function buildRigVerbs(layout) {
  const verbs = layout.rig_verbs || [];
  $("rig-card").classList.toggle("hidden", verbs.length === 0);
  const select = $("rig-verb");
  select.replaceChildren(...verbs.map((v) => new Option(v.caption, v.verb)));
  const chosen = () => verbs.find((v) => v.verb === select.value);
  const targets = () => {
    const v = chosen();
    const names = v.targets === "parts" ? Object.values(lastParts) : v.targets;
    $("rig-target").replaceChildren(...names.map((n) => new Option(n, n)));
    const free = v.targets.length === 0;  // no list (a time of day): the target is typed
    $("rig-target").classList.toggle("hidden", free);
    $("rig-target-text").classList.toggle("hidden", !free);
    $("rig-target-text").placeholder = v.role;
  };
  const form = () => {
    const v = chosen();
    if (!v) return;
    select.title = v.doc;
    targets();
    $("rig-args").replaceChildren(...v.args.map((name) => {
      const input = document.createElement("input"); input.placeholder = name; input.dataset.arg = name; input.size = 8;
      return input;
    }));
  };
  select.onchange = form;
  // a verb on a part offers the parts on the machine now (they come and go while the page is open)
  $("rig-target").onfocus = () => { if (chosen()?.targets === "parts") targets(); };
  form();
  $("rig-apply").onclick = () => {
    const v = chosen();
    const target = v.targets.length === 0 ? $("rig-target-text").value : $("rig-target").value;
    const args = {};
    for (const input of $("rig-args").querySelectorAll("input")) if (input.value !== "") args[input.dataset.arg] = typed(input.value);
    send({ op: "do", verb: v.verb, target, args });
  };
}

function buildFaults(layout) {
  const verb = $("fault-verb");
  verb.replaceChildren(...Object.entries(layout.faults).map(([v, text]) => new Option(text, v)));
  verb.onchange = () => faultSignals(layout);
  faultSignals(layout);
  $("fault-apply").onclick = () => {
    const v = verb.value, args = {};
    if (v === "stick") args.value = $("fault-value").value === "true";
    if (v === "shift") args.mm = Number($("fault-mm").value);
    send({ op: "do", verb: v, target: $("fault-signal").value, args });
  };
  $("faults-card").classList.toggle("hidden", layout.wired.length === 0);
}
function faultSignals(layout) {
  const v = $("fault-verb").value;
  const names = v === "shift" ? layout.sensors : v.endsWith("motor") ? layout.motors : layout.wired;
  $("fault-signal").replaceChildren(...names.map((n) => new Option(n, n)));
  $("fault-value").classList.toggle("hidden", v !== "stick");
  $("fault-mm").classList.toggle("hidden", v !== "shift");
}

// -- watch table -------------------------------------------------------------------------------------
function buildWatch(layout) {
  $("watch").replaceChildren(...layout.watch.map((name) => {
    const tr = document.createElement("tr"); tr.dataset.tag = name;
    const input = document.createElement("input"); input.placeholder = "value";
    const write = (force) => { if (input.value !== "") send({ op: "write", target: name, text: input.value, force }); };
    input.addEventListener("keydown", (e) => { if (e.key === "Enter") write(false); });
    const cells = [name, "", input, null].map((c) => { const td = document.createElement("td"); if (c instanceof Node) td.appendChild(c); else if (c) td.textContent = c; return td; });
    cells[1].className = "value";
    const unforce = button("unforce", () => send({ op: "do", verb: "unforce", target: name }));
    unforce.className = "unforce hidden";
    cells[3].append(button("write", () => write(false), "write once"), button("force", () => write(true), "force"), unforce);
    tr.append(...cells);
    return tr;
  }));
}
function showValue(td, value) {
  if (typeof value === "boolean") {
    td.innerHTML = `<span class="dot ${value}"></span>${value ? "TRUE" : "FALSE"}`;
  } else td.textContent = value === null ? "—" : String(value);
}

// -- each frame --------------------------------------------------------------------------------------
function render(s) {
  page.state = s;
  if (!page.layout) return;
  const mode = $("mode"); mode.textContent = s.mode; mode.className = "badge " + s.mode;
  $("time").textContent = s.time;
  $("scans").textContent = s.scans;
  $("pace").textContent = s.paused ? "paused" : `${s.speed === null ? "as fast as possible" : "×" + s.speed} (now ×${s.actual_speed.toFixed(2)})`;
  $("run").textContent = s.paused ? "Run" : "Pause";
  $("run").classList.toggle("on", s.paused);
  const speed = $("speed");
  if (document.activeElement !== speed) speed.value = s.speed === null ? "max" : String(s.speed);
  updateDynamic(s);
  for (const b of $("controls").children) b.classList.toggle("on", controlOn(b.dataset.control));
  for (const tr of $("watch").children) {
    const name = tr.dataset.tag, forced = name in s.forces;
    showValue(tr.children[1], s.watch[name]);
    tr.classList.toggle("forced", forced);
    tr.querySelector(".unforce").classList.toggle("hidden", !forced);
  }
  renderParts(s.parts);
  $("faults").replaceChildren(...s.faults.map((f) => {
    const chip = document.createElement("span"); chip.className = "chip"; chip.textContent = `${f} ✕`;
    chip.title = "clear this fault"; chip.onclick = () => send({ op: "do", verb: "clear", target: f });
    return chip;
  }));
  list("diagnostics", s.diagnostics); list("events", s.events); list("actions", s.actions);
  const err = $("error"); err.classList.toggle("hidden", !s.error); err.textContent = s.error || "";
  refreshLadder(`${s.t_ns}/${s.actions.length}/${s.mode}`);
  $("program-changed").classList.toggle("hidden", !s.program_changed);
  page.showDownload();
  $("download").classList.toggle("on", !!s.program_changed);
  page.onFrame?.(s); // a hook for the browser test: called after each frame is drawn
}
// the moving shapes are kept and updated in place (a shape under the pointer stays the same element)
function updateDynamic(s) {
  const dyn = $("dynamic"), seen = new Set();
  const byPath = page.dynamic || (page.dynamic = new Map());
  for (const d of s.dynamic) {
    const key = d[0] + "|" + d[1], sig = JSON.stringify(d);
    seen.add(key);
    const old = byPath.get(key);
    if (old && old.sig === sig) continue;
    const g = shape(d, { caption: true }), segments = d[0].split("/");
    const control = segments.find((seg) => seg in page.controls);
    if (control) { g.dataset.control = control; g.classList.add("clickable"); }
    if (segments[0] === "parts" && s.parts[segments[1]]) { g.dataset.part = s.parts[segments[1]]; g.classList.add("clickable"); }
    if (old) {
      old.g.replaceChildren(...g.childNodes);
      for (const a of ["data-control", "data-part", "class"]) g.hasAttribute(a) ? old.g.setAttribute(a, g.getAttribute(a)) : old.g.removeAttribute(a);
      old.sig = sig;
    } else {
      dyn.appendChild(g);
      byPath.set(key, { g, sig });
    }
  }
  for (const [key, item] of byPath) if (!seen.has(key)) { item.g.remove(); byPath.delete(key); }
}
function list(id, items) {
  const key = items.join("\n"), ol = $(id);
  if (ol.dataset.key === key) return;
  ol.dataset.key = key;
  ol.replaceChildren(...items.slice().reverse().map((t) => { const li = document.createElement("li"); li.textContent = t; li.title = t; return li; }));
}

// -- toolbar -----------------------------------------------------------------------------------------
$("run").onclick = () => send({ op: page.state?.paused ? "resume" : "pause" });
$("scan").onclick = () => send({ op: "scan" });
$("speed").onchange = (e) => send({ op: "speed", value: e.target.value === "max" ? null : Number(e.target.value) });
$("cpu-stop").onclick = () => send({ op: "do", verb: "stop_cpu" });
$("cpu-run").onclick = () => send({ op: "do", verb: "start_cpu" });
$("cpu-power").onclick = () => send({ op: "do", verb: "power_cycle" });
$("save").onclick = () => send({ op: "save" });
$("download").onclick = () => send({ op: "download" });
page.showDownload = () => $("download").classList.toggle("hidden", !String(page.layout?.program || "").endsWith(".py"));
$("grade").onclick = () => send({ op: "grade" });
$("end").onclick = () => { if (confirm("End the session? It is saved as a scenario.")) send({ op: "end" }); };
window.addEventListener("keydown", (e) => {
  if (e.key === " " && !(e.target instanceof HTMLInputElement)) { e.preventDefault(); $("run").click(); }
});
window.addEventListener("resize", () => {
  if (!page.layout) return;
  page.dynamic?.forEach((item) => item.g.remove()); page.dynamic = null;
  buildLayout(page.layout);
});

// -- the Program card: the ladder of the running program, refetched with the frames ----------------------
const ladder = { shown: false, busy: false, seen: -1, at: 0 };
page.ladder = ladder;
async function refreshLadder(version) {
  if (ladder.busy || version === ladder.seen || performance.now() - ladder.at < 100) return;
  ladder.busy = true; ladder.at = performance.now();
  try {
    const response = await fetch("/api/ladder.svg", { cache: "no-store" });
    if (!response.ok) { $("program-card").classList.add("hidden"); ladder.shown = false; return; }
    $("ladder").innerHTML = await response.text(); // drawn by the server from the program, every text escaped
    ladder.seen = version; ladder.shown = true; $("program-card").classList.remove("hidden");
    page.onLadder?.();
  } catch (e) { /* the server is away: the next frame tries again */ } finally { ladder.busy = false; }
}
$("ladder").addEventListener("click", (e) => {
  const tag = e.target.closest?.("[data-tag]")?.dataset.tag;
  if (!tag || !page.layout) return;
  if (!page.layout.watch.includes(tag)) { page.layout.watch.push(tag); buildWatch(page.layout); send({ op: "watch", target: tag }); }
  const row = [...$("watch").children].find((tr) => tr.dataset.tag === tag);
  row?.scrollIntoView({ block: "nearest" }); row?.classList.add("picked"); setTimeout(() => row?.classList.remove("picked"), 1500);
  row?.querySelector("input")?.focus();
});

function showDigest(r) { $("digest").textContent = `digest ${r.digest.slice(0, 16)} at ${(r.t_ns / 1e9).toFixed(3)} s`; }
function download(name, text) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type: "text/plain" }));
  a.download = name; a.click(); URL.revokeObjectURL(a.href);
}
function onSaved(r) {
  page.lastSaved = r; showDigest(r);
  if (r.path) toast(`saved ${r.actions} actions to ${r.path}`);
  else { download("live-session.toml", r.toml); toast(`saved ${r.actions} actions (live-session.toml)`); }
}
function onEnded(r) {
  page.lastSaved = r; showDigest(r);
  toast(r.path ? `session ended; scenario saved to ${r.path}` : "session ended");
  if (!r.path) download("live-session.toml", r.toml);
}

connect();
