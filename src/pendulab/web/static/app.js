// pendulab explorer: the page reads its state from the URL, asks the JSON API, and draws.
// Every number about the pendulum comes from /api/; the page only draws it. Between two of
// the server's animation samples the bob's angle is the cubic Hermite interpolant of theta
// and theta' there (drawing only; the server sends 16 samples a period). The lab's instruments
// (photogates, stopwatch, ruler, protractor, vectors, damping, Planet X) are static/lab.js,
// called through window.lab: on each query, on new data, each frame and each drawing.
"use strict";

const FIELDS = ["length", "amplitude", "unit", "g", "omega0", "method", "step", "t_max", "method2", "step2", "length2", "amplitude2", "g2"];
const NUMBER_FIELDS = ["length", "amplitude", "g", "omega0", "step", "t_max", "step2", "length2", "amplitude2", "g2"];
const ERROR_FIELDS = NUMBER_FIELDS.concat(["method", "method2"]);
const OPTIONAL = ["omega0", "method2", "step2", "length2", "amplitude2", "g2"];  // in the URL only when set
const PLOT_POINTS = 3000;          // theta(t): min and max of 1500 columns (more than a plot's pixels)
const MAX_PERIOD_MARKS = 12;       // dashed kT lines on theta(t), beyond which none are drawn
const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4];
const FONT = { family: "system-ui, -apple-system, Segoe UI, Roboto, DejaVu Sans, sans-serif", size: 14, color: "#1d2330" };
const COLORS = { a: "#2f6fdb", b: "#e07a1f", second: "#7a5cc9", p: "#d1495b", bracket: "#8a94a6", linear: "#b07d00", cubic: "#009e73", exact: "#1d2330", cursor: "#d1495b" };
const PLAIN_NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;
// Sliders beside the number fields: whether each moves log10 of the value (range in index.html).
const SLIDERS = { length: { log: true }, g: { log: true }, step: { log: true }, t_max: { log: true }, amplitude: { log: false } };
// A touch screen: a swipe over a plot scrolls the page; zoom only from the mode bar's button.
const TOUCH = window.matchMedia("(pointer: coarse)").matches || navigator.maxTouchPoints > 0;
const REDUCED_MOTION = window.matchMedia("(prefers-reduced-motion: reduce)").matches;

const $ = (id) => document.getElementById(id);
const LANGS = ["en", "pt"];
let lang = "en";                                  // the page's language: ?lang=, else the browser's
let langGiven = false;                            // ?lang= in the URL: kept there
let config = null;
let state = {};
let view = { exact: true, scale: false, errlog: false, second: false, side: 1, projector: false, plotkeys: false };
let sims = { a: null, b: null, second: null };  // the last good answers
let curve = null;                                 // /api/period_curve, asked once
let seq = 0;                                      // drops answers to requests that are no longer current
let timer = null;
const anim = { playing: true, t: 0, last: null, speed: 1, marks: 0, drag: null };

// ---------- words: the catalogues' web. entries (/api/config?lang=), numbers in the language's form ----------
function pickLanguage() {
  const q = new URLSearchParams(location.search).get("lang");
  if (q && LANGS.includes(q.toLowerCase())) { langGiven = true; return q.toLowerCase(); }
  // The browser's first preferred language the page has; English otherwise.
  for (const l of navigator.languages || [navigator.language || ""]) {
    const base = String(l).slice(0, 2).toLowerCase();
    if (LANGS.includes(base)) return base;
  }
  return LANGS[0];
}

/** The catalogue's entry web.<key>, its {name} fields filled from vars; a missing key is a console error and shows the key. */
function word(key, vars = {}) {
  const w = config && config.words ? config.words[key] : undefined;
  if (w === undefined) { console.error(`pendulab: no word "${key}" in the ${lang} catalogue`); return key; }
  return w.replace(/\{(\w+)\}/g, (m, k) => (k in vars ? String(vars[k]) : m));
}

/** A number's text as written in the page's language: a decimal comma in Portuguese. */
const local = (text) => (lang === "pt" ? String(text).replace(/(\d)\.(?=\d)/g, "$1,") : String(text));
/** A number as typed in the page's language, as the API and the URL read it: a Portuguese decimal comma is a point. */
const typed = (text) => (lang === "pt" ? String(text).replace(/(\d),(?=\d)/g, "$1.") : String(text));
/** x to `digits` significant digits (all of its shortest form without), in the page's language. */
const num = (x, digits) => (x === null || x === undefined ? "–" : local(digits ? x.toPrecision(digits) : String(x)));
/** A whole number with the language's thousands separator. */
const count = (n) => n.toLocaleString(lang === "pt" ? "pt-PT" : "en");

/** The static text of the page: data-word (text), data-word-aria (aria-label), data-word-title, data-word-placeholder. */
function applyWords(root = document) {
  for (const e of root.querySelectorAll("[data-word]")) e.textContent = word(e.dataset.word);
  for (const e of root.querySelectorAll("[data-word-aria]")) e.setAttribute("aria-label", word(e.dataset.wordAria));
  for (const e of root.querySelectorAll("[data-word-title]")) e.title = word(e.dataset.wordTitle);
  for (const e of root.querySelectorAll("[data-word-placeholder]")) e.placeholder = word(e.dataset.wordPlaceholder);
  document.documentElement.lang = lang;
}

// ---------- state <-> URL <-> form ----------
function readURL() {
  const q = new URLSearchParams(location.search);
  for (const k of FIELDS) state[k] = q.get(k) ?? config.defaults[k] ?? "";
  const speed = Number(q.get("speed"));
  anim.speed = SPEEDS.includes(speed) ? speed : 1;
  view.exact = q.get("exact") !== "0";
  view.scale = q.get("scale") === "1";
  view.errlog = q.get("errlog") === "1";
  view.second = q.get("second") === "1";
  view.side = q.get("side") === "left" ? -1 : 1;
  view.projector = q.get("view") === "projector";
  view.plotkeys = q.get("plotkeys") === "1";
  // prefers-reduced-motion: nothing moves until the person presses Play (or the link says so).
  anim.playing = q.has("paused") ? q.get("paused") !== "1" : !REDUCED_MOTION;
  const t = Number(q.get("t"));
  anim.t = Number.isFinite(t) && t > 0 ? t : 0;
}

function ensureOption(select, value) {
  // A method the URL names but the menu does not list (taylor:7): offered as it is; the server judges it.
  if (!value || [...select.options].some((o) => o.value === value)) return;
  const o = document.createElement("option");
  o.value = value; o.textContent = value;
  select.append(o);
}

function writeForm() {
  ensureOption($("method"), state.method);
  ensureOption($("method2"), state.method2);
  for (const k of FIELDS) $(k).value = NUMBER_FIELDS.includes(k) ? local(state[k]) : state[k];
  $("speed").value = String(anim.speed);
  for (const k of ["exact", "scale", "errlog", "second", "plotkeys"]) $(k).checked = view[k];
  showProjector();
  $("second-fields").hidden = !view.second;
  $("play").textContent = word(anim.playing ? "page.pause" : "page.play");
  markPreset();
  for (const k of Object.keys(SLIDERS)) syncSlider(k);
}

function readForm() {
  for (const k of FIELDS) state[k] = NUMBER_FIELDS.includes(k) ? typed($(k).value.trim()) : $(k).value.trim();
  for (const k of ["exact", "scale", "errlog", "second", "plotkeys"]) view[k] = $(k).checked;
}

function pageQuery() {
  const q = new URLSearchParams();
  for (const k of FIELDS) {
    if (["length2", "amplitude2", "g2"].includes(k) && !view.second) continue;
    if (state[k] !== "" || !OPTIONAL.includes(k)) q.set(k, state[k]);
  }
  if (anim.speed !== 1) q.set("speed", String(anim.speed));
  if (!view.exact) q.set("exact", "0");
  if (view.scale) q.set("scale", "1");
  if (view.errlog) q.set("errlog", "1");
  if (view.second) q.set("second", "1");
  if (view.side < 0) q.set("side", "left");
  if (view.projector) q.set("view", "projector");
  if (view.plotkeys) q.set("plotkeys", "1");
  if (!anim.playing) { q.set("paused", "1"); q.set("t", String(Number(anim.t.toPrecision(6)))); }
  if (langGiven) q.set("lang", lang);
  if (window.lab) window.lab.query(q, "url");
  return q.toString();
}

function writeURL() { history.replaceState(null, "", "?" + pageQuery()); }

// The amplitude as the server reads it (the key convertAmplitude compares); requests send
// the text as typed with its unit, so an error echoes what the person typed.
function apiAmplitude() {
  const a = state.amplitude;
  return state.unit === "deg" && PLAIN_NUMBER.test(a) ? a + "deg" : a;
}

function apiQuery(which, extra = {}) {
  const method = which === "b" ? state.method2 : state.method;
  const step = which === "b" && state.step2 ? state.step2 : state.step;
  const q = new URLSearchParams({
    length: state.length, amplitude: state.amplitude, unit: state.unit, g: state.g, method, step, t_max: state.t_max, ...extra,
  });
  q.set("lang", lang);  // the flags' words, and a refusal's (the CSV itself has none)
  if (state.omega0) q.set("omega0", state.omega0);
  if (window.lab) window.lab.query(q, which);  // damping, drag, mass; Planet X's g
  return q.toString();
}

function secondQuery() {
  // The second pendulum: its own length, amplitude (in the first one's unit) and g; empty ones are the first's.
  const q = new URLSearchParams({
    length: state.length2 || state.length, amplitude: state.amplitude2 || state.amplitude, unit: state.unit,
    g: state.g2 || state.g, t_max: state.t_max, lang,
  });
  if (window.lab) window.lab.query(q, "second");
  return q.toString();
}

// ---------- talking to the API ----------
function schedule(delay = 200) {
  clearTimeout(timer);
  timer = setTimeout(update, delay);
}

async function getJSON(url) {
  const r = await fetch(url);
  let body = null;
  try { body = await r.json(); } catch (e) { body = { error: { message: word("page.server-answered", { status: r.status }) } }; }
  return { ok: r.ok, body };
}

/** An error of a request about another field set (the comparison, the second pendulum), on its own field. */
function renamed(err, names, key) {
  const e = err || {};
  return { ...e, field: names[e.field] || e.field, message: word(key, { message: e.message || word("page.unknown-error") }) };
}

async function update() {
  readForm();
  writeURL();
  markPreset();
  const my = ++seq;
  const amplitudeQuery = apiAmplitude();
  $("status").textContent = word("page.simulating");
  document.body.classList.add("busy");
  let ra, rb = null, rs = null;
  try {
    const pa = getJSON("/api/simulate?" + apiQuery("a", { points: PLOT_POINTS }));
    const pb = state.method2 ? getJSON("/api/simulate?" + apiQuery("b", { points: PLOT_POINTS })) : null;
    const ps = view.second ? getJSON("/api/motion?" + secondQuery()) : null;
    ra = await pa;
    rb = pb ? await pb : null;
    rs = ps ? await ps : null;
  } catch (e) {
    if (my === seq) showError({ message: word("page.no-server") });
    return;
  }
  if (my !== seq) return;
  document.body.classList.remove("busy");
  if (!ra.ok) { showError(ra.body.error); return; }
  if (rb && !rb.ok) { showError(renamed(rb.body.error, { step: "step2", method: "method2" }, "page.second-method-error")); return; }
  if (rs && !rs.ok) {
    const names = state.length2 || state.amplitude2 || state.g2 ? { length: "length2", amplitude: "amplitude2", g: "g2" } : {};
    showError(renamed(rs.body.error, names, "page.second-pendulum-error"));
    return;
  }
  clearError();
  sims = { a: ra.body, b: rb ? rb.body : null, second: rs ? rs.body : null };
  sims.a.amplitudeQuery = amplitudeQuery;
  $("csv").href = "/api/trajectory.csv?" + apiQuery("a", { columns: "all" });
  $("csv").setAttribute("aria-disabled", "false");
  $("csv2").hidden = !sims.b;
  if (sims.b) $("csv2").href = "/api/trajectory.csv?" + apiQuery("b", { columns: "all" });
  const s = sims.a;
  const thinned = s.thinning === "none" ? word("page.every-step") : word("page.columns", { columns: count(s.columns) });
  $("status").textContent = word("page.steps-of", { n: count(s.n_steps), method: s.input.method, thinned });
  const tEnd = s.frames.t[s.frames.t.length - 1];
  if (anim.t > tEnd) anim.t = 0;
  $("cursor").max = String(tEnd);
  if (window.lab) window.lab.data();
  renderFlags();
  renderPeriods();
  tick();
  renderAnimNote();
  // The plots after the numbers and the swing: the period is on the page before plotly starts.
  await nextFrame();
  await plotlyReady;
  if (my !== seq) return;
  renderTheta();
  await nextFrame();  // the angle plot painted before the other six are drawn (each takes a frame or more)
  if (my !== seq) return;
  renderPhase();
  renderError();
  renderEnergy();
  renderEstimates();
  renderRatio();
  updateConvergence(my);
  document.body.dataset.shown = "1";  // the first render is done: what tests wait for, in any language
}

const nextFrame = () => new Promise((resolve) => requestAnimationFrame(() => resolve()));
// plotly.js loads async (index.html), while the first requests run: only the plots wait for it.
const plotlyReady = new Promise((resolve) => {
  const tag = document.querySelector('script[src$="plotly.min.js"]');
  if (window.Plotly || !tag) resolve(); else tag.addEventListener("load", () => resolve());
});

async function updateConvergence(my) {
  if (sims.a.launch) {  // the estimates time a release at rest
    renderConvergence(null, { message: word("page.rest-needed") });
    return;
  }
  const T = sims.a.period.period;
  // Steps from T/30 down to T/30000, four per decade, plus the steps in use.
  const steps = [];
  for (let k = 0; k <= 12; k++) steps.push(T / Math.pow(10, 1.5 + k / 4));
  const ask = (method, h) => getJSON("/api/convergence?" + new URLSearchParams({
    length: state.length, amplitude: state.amplitude, unit: state.unit, g: state.g, method, lang,
    steps: steps.concat([h]).map((x) => x.toPrecision(6)).join(","),
  }).toString());
  let ra, rb = null;
  try {
    const pa = ask(state.method, sims.a.input.step);
    const pb = sims.b ? ask(state.method2, sims.b.input.step) : null;
    ra = await pa;
    rb = pb ? await pb : null;
  } catch (e) { return; }
  if (my !== seq) return;
  renderConvergence(ra.ok ? ra.body : null, ra.ok ? null : ra.body.error, rb && rb.ok ? rb.body : null);
}

function clearFieldErrors() {
  for (const k of ERROR_FIELDS) {
    $(k).removeAttribute("aria-invalid");
    const hint = $(k).dataset.hint;
    if (hint) $(k).setAttribute("aria-describedby", hint); else $(k).removeAttribute("aria-describedby");
    $(k + "-error").hidden = true;
    $(k + "-error").textContent = "";
  }
  $("error").hidden = true;
}

function showError(err) {
  document.body.classList.remove("busy");
  clearFieldErrors();
  let message = err && err.message ? err.message : word("page.unknown-error");
  const field = err && err.field && ERROR_FIELDS.includes(err.field) ? err.field : null;
  // English reads 3,5 as no number (Portuguese as 3.5): say how to write it.
  if (lang === "en" && field && /^\s*[+-]?\d+,\d+\s*$/.test($(field).value)) message += ` (${word("page.decimal-point", { text: $(field).value.trim().replace(",", ".") })})`;
  if (field) {
    // The message right under its field, and announced with it.
    const input = $(field), box = $(field + "-error");
    box.textContent = message;
    box.hidden = false;
    input.setAttribute("aria-invalid", "true");
    input.setAttribute("aria-describedby", [field + "-error", input.dataset.hint].filter(Boolean).join(" "));
  } else {
    $("error").textContent = message;
    $("error").hidden = false;
  }
  $("status").textContent = word("page.stale");
  $("main").classList.add("stale");
  $("csv").setAttribute("aria-disabled", "true");
  document.body.dataset.shown = "1";
}

function clearError() {
  clearFieldErrors();
  $("main").classList.remove("stale");
}

// ---------- numbers ----------
// Numbers a person reads, in the page's language (fix, sci, shown); short() is also a value put back in a field.
const fix = (x, d = 12) => num(x, d);
const sci = (x) => (x === null || x === undefined ? "–" : x === 0 ? "0" : local(x.toExponential(2)));
const short = (x) => String(Number(x.toPrecision(12)));
const shown = (x) => local(short(x));
const label = (s) => word("page.run", { method: s.input.method, h: shown(s.input.step) });
/** An estimate's linear or cubic (or its error, `cubic_error`, `cubic_relative`) with only the digits that are right (the server's `shown`). */
const right = (e, k) => (e.shown[k] === null ? "–" : local(e.shown[k].replace("<= ", "≤ ")));

function renderFlags() {
  // At the top of the results (the first thing on a phone): what is wrong, in words.
  const box = $("flags");
  box.textContent = "";
  let n = 0;
  for (const k of ["a", "b"]) {
    const s = sims[k];
    if (!s) continue;
    for (const f of s.flags.notes) {
      const p = document.createElement("p");
      p.className = f.severity;
      p.dataset.kind = f.kind;
      const b = document.createElement("b");
      b.textContent = `${word("flag." + f.severity)} (${label(s)}): `;
      p.append(b, document.createTextNode(f.text + "."));
      box.append(p);
      n++;
    }
  }
  box.hidden = n === 0;
}

function tableFor(s, suffix) {
  const wrap = document.createElement("div");
  wrap.className = "estimates" + (s.flags.trustworthy ? "" : " untrusted");
  const cap = document.createElement("p");
  cap.className = "caption";
  cap.textContent = label(s) + (s.flags.trustworthy ? "" : " — " + word("page.flagged"));
  const t = document.createElement("table");
  const head = document.createElement("thead"), hr = document.createElement("tr");
  for (const key of ["page.from-simulation", "page.estimate-s", "page.error-s", "page.relative"]) {
    const th = document.createElement("th");
    th.scope = "col";
    th.textContent = word(key);
    hr.append(th);
  }
  head.append(hr);
  t.append(head);
  const body = document.createElement("tbody");
  const sub = " [t<sub>j</sub>, t<sub>j+1</sub>]";
  const rows = [["bracket", word("page.bracket-row"), sub], ["linear", word("page.linear-row"), ""], ["cubic", word("page.cubic-row"), ""]];
  const p = s.period, e = p.estimate;
  for (const [k, name, after] of rows) {
    const tr = document.createElement("tr");
    const cells = ["–", "–", "–"];
    if (e) {
      const err = k === "bracket" ? e.errors.bracket_mid : e.errors[k];
      cells[0] = k === "bracket" ? `[${shown(e.bracket[0])}${lang === "pt" ? ";" : ","} ${shown(e.bracket[1])}]` : right(e, k);
      cells[1] = k === "bracket" ? sci(err) : right(e, k + "_error");
      cells[2] = k === "bracket" ? sci(err / p.period) : right(e, k + "_relative");
    }
    const first = document.createElement("td");
    first.textContent = name;
    first.insertAdjacentHTML("beforeend", after);
    tr.append(first);
    ["est", "err", "rel"].forEach((pre, i) => {
      const td = document.createElement("td");
      td.id = `${pre}${suffix}-${k}`;
      td.textContent = cells[i];
      tr.append(td);
    });
    body.append(tr);
  }
  t.append(body);
  const note = document.createElement("p");
  note.className = "note";
  note.textContent = e
    ? word("page.estimate-note", { j: e.j, estimate: sci(e.cubic_error_estimate) })
    : word("page.no-period", { reason: p.reason });
  wrap.append(cap, t, note);
  return wrap;
}

function renderPeriods() {
  const p = sims.a.period;
  const L = sims.a.launch;
  $("period-label").textContent = !L ? word("page.period-agm")
    : L.circulates ? word("page.period-turn") : word("page.period-launched", { angle: num(L.turning_angle_deg, 6) });
  $("period-agm").textContent = fix(p.period);
  // The strip under the swing (a phone's first screen, the projector): the period and the simulation's estimate.
  $("strip-period").textContent = fix(p.period);
  $("strip-estimate").textContent = p.estimate ? `${right(p.estimate, "cubic")} s` : word("page.strip-none");
  $("period-small").textContent = fix(p.small_angle_period);
  $("period2-line").hidden = !sims.second;
  if (sims.second) {
    $("period2-agm").textContent = fix(sims.second.period);
    $("period2-alpha").textContent = shown(sims.second.amplitude_deg);
  }
  const box = $("tables");
  box.textContent = "";
  box.append(tableFor(sims.a, ""));
  if (sims.b) box.append(tableFor(sims.b, "2"));
}

// ---------- plots ----------
function plotConfig() {
  // No cloud buttons, no logo; on a touch screen the bar stays shown (its zoom button is the
  // only way to zoom) and a swipe scrolls the page.
  return {
    displaylogo: false, showSendToCloud: false, showEditInChartStudio: false, showLink: false,
    responsive: true, scrollZoom: false, displayModeBar: TOUCH || view.plotkeys ? true : "hover",
    modeBarButtonsToRemove: ["lasso2d", "select2d", "sendDataToCloud", "editInChartStudio"],
    locale: lang, locales: { [lang]: { dictionary: plotlyWords() } },
  };
}

/** Plotly's own words (its mode bar's buttons, its notes), from the catalogue's web.plotly. entries. */
const PLOTLY_WORDS = {
  "Autoscale": "autoscale", "Box Select": "box-select", "Lasso Select": "lasso-select",
  "Compare data on hover": "compare", "Show closest data on hover": "closest",
  "Double-click on legend to isolate one trace": "isolate", "Double-click to zoom back out": "zoom-back",
  "Download plot as a PNG": "png", "Download plot as a png": "png", "Download plot": "download", "Pan": "pan",
  "Reset axes": "reset-axes", "Reset view": "reset-view", "Reset": "reset", "Toggle Spike Lines": "spikes",
  "Zoom": "zoom", "Zoom in": "zoom-in", "Zoom out": "zoom-out",
  "Taking snapshot - this may take a few seconds": "snapshot", "Snapshot succeeded": "snapshot-done",
  "Sorry, there was a problem downloading your snapshot!": "snapshot-failed",
};
function plotlyWords() {
  return Object.fromEntries(Object.entries(PLOTLY_WORDS).map(([k, v]) => [k, word("plotly." + v)]));
}

// The mode bar (at the top right) shares the top row with the title, which starts at the
// left: on a narrow plot or with a long title the bar would cover the title's end. There the
// title moves down below the bar, and the plot area with it by as much.
const TITLE_GAP = 3;

function plot(id, traces, lay) {
  const gd = $(id);
  if (!window.Plotly) return Promise.resolve();  // a redraw asked for before plotly.js came: update() draws it
  return Plotly.react(id, traces, lay, plotConfig()).then(() => fitTitle(gd)).then(() => clearModeBar(gd)).then(() => {
    if (!gd.dataset.hooked) {  // the cursor's place follows every redraw (zoom, resize)
      gd.dataset.hooked = "1";
      gd.on("plotly_afterplot", () => { measure(gd); moveCursors(); plotKeys(gd); });
      if (id === "plot-theta") gd.on("plotly_relayout", zoomTheta);
    }
    measure(gd);
    moveCursors();
    plotKeys(gd);
  });
}

// The mode bar's buttons (7 a plot) are out of the tab order unless the reader asks for them
// (Show: the plots' buttons by keyboard): Tab goes from control to control, not through 49 buttons.
function plotKeys(gd) {
  for (const b of gd.querySelectorAll(".modebar-btn")) b.tabIndex = view.plotkeys ? 0 : -1;
}

// ---------- projector mode: the swing and the period alone, large, full screen where allowed ----------
function showProjector() {
  document.documentElement.classList.toggle("projector", view.projector);
  $("projector").setAttribute("aria-pressed", String(view.projector));
  $("projector").textContent = word(view.projector ? "page.projector-leave" : "page.projector");
}

async function setProjector(on) {
  view.projector = on;
  showProjector();
  writeURL();
  const root = document.documentElement;
  try {
    if (on && root.requestFullscreen && !document.fullscreenElement) await root.requestFullscreen();
    if (!on && document.fullscreenElement) await document.exitFullscreen();
  } catch (e) { /* refused (an iframe, a policy): the layout alone */ }
  relayout();
}

function relayout() {
  // The canvas and the plots take their new sizes (plots hidden in the projector are resized when shown again).
  tick();
  if (!view.projector && window.Plotly) for (const gd of document.querySelectorAll(".js-plotly-plot")) Plotly.Plots.resize(gd);
}

function fitTitle(gd) {
  // A title wider than its plot (a long run's, on a narrow screen) is set smaller, down to 12 px.
  const title = gd.querySelector(".gtitle");
  if (!title) return;
  const t = title.getBoundingClientRect(), g = gd.getBoundingClientRect();
  const room = g.right - 8 - t.left, size = gd._fullLayout.title.font.size;
  if (t.width <= room || size <= 12) return;
  return Plotly.relayout(gd, { "title.font.size": Math.max(12, Math.floor(size * room / t.width)) });
}

function clearModeBar(gd) {
  const title = gd.querySelector(".gtitle"), bar = gd.querySelector(".modebar");
  if (!title || !bar || !bar.getBoundingClientRect().width) return;  // no bar (hidden until hover)
  const t = title.getBoundingClientRect(), b = bar.getBoundingClientRect();
  if (t.right < b.left - TITLE_GAP || t.top >= b.bottom) return;  // beside it or below it already
  const shift = b.bottom + TITLE_GAP - t.top;
  const L = gd._fullLayout;
  return Plotly.relayout(gd, {
    "title.y": L.title.y - shift / L.height,
    "margin.t": L.margin.t + shift,
  });
}

function layout(title, xtitle, ytitle, extra = {}) {
  return {
    title: { text: title, font: { size: 15 }, x: 0.01, xanchor: "left", y: 0.97, yanchor: "top" },
    font: FONT, margin: { l: 70, r: 14, t: 46, b: 52 }, paper_bgcolor: "#fff", plot_bgcolor: "#fff",
    separators: lang === "pt" ? ", " : ".,",  // the decimal mark and the thousands separator of the ticks and hovers
    dragmode: TOUCH ? false : "zoom", hovermode: TOUCH ? false : "closest",
    xaxis: { title: { text: xtitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc", automargin: true, tickfont: { size: 13 } },
    yaxis: { title: { text: ytitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc", automargin: true, exponentformat: "e", tickfont: { size: 13 } },
    legend: { orientation: "h", x: 0, y: -0.3, yanchor: "top", font: { size: 13 } }, showlegend: false, ...extra,
  };
}

function twoLines(traces) {
  // A legend only when there is something to tell apart, below the plot.
  return traces.length > 1 ? { showlegend: true, margin: { l: 70, r: 14, t: 46, b: 110 } } : {};
}

function renderTheta() {
  const s = sims.a;
  const T = s.period.period;
  const shapes = [];
  const annotations = [];
  const marks = Math.floor(s.input.t_max / T);
  if (marks <= MAX_PERIOD_MARKS) {
    for (let k = 1; k <= marks; k++) {
      shapes.push({ type: "line", x0: k * T, x1: k * T, yref: "paper", y0: 0, y1: 1, line: { dash: "dot", color: COLORS.p, width: 1 } });
      annotations.push({ x: k * T, yref: "paper", y: 1, text: k === 1 ? "T" : `${k}T`, showarrow: false, yanchor: "bottom", font: { color: COLORS.p, size: 12 } });
    }
  }
  anim.marks = marks <= MAX_PERIOD_MARKS ? marks : 0;
  const traces = [{ x: s.t, y: s.theta, mode: "lines", line: { color: COLORS.a, width: 1.6 }, name: label(s),
    hovertemplate: "t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" }];
  if (view.exact) {
    traces.push({ x: s.exact.t, y: s.exact.theta, mode: "lines", line: { color: COLORS.exact, width: 1.2, dash: "dash" },
      name: word("page.exact-motion"), hovertemplate: word("page.exact") + "<br>t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" });
  }
  if (sims.b) {
    traces.push({ x: sims.b.t, y: sims.b.theta, mode: "lines", line: { color: COLORS.b, width: 1.4 }, name: label(sims.b),
      hovertemplate: "t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" });
  }
  const title = marks <= MAX_PERIOD_MARKS ? word("page.angle") : word("page.angle-periods", { marks: count(marks), period: num(T, 6) });
  plot("plot-theta", traces, layout(title, "t (s)", "θ (rad)", { shapes, annotations, ...twoLines(traces) }));
}

// Zoom on θ(t) fetches finer data: the server keeps each column's min and max over 0..t_max,
// so a run to the window's end with more columns gives the window about PLOT_POINTS of its own.
async function zoomTheta(ev) {
  if (!sims.a) return;
  const range = ev["xaxis.range"] || [ev["xaxis.range[0]"], ev["xaxis.range[1]"]];
  if (ev["xaxis.autorange"]) { if (sims.zoomed) { sims.zoomed = false; renderTheta(); } return; }
  if (range[0] === undefined || range[1] === undefined) return;
  const s = sims.a, tMax = s.input.t_max;
  const t0 = Math.max(0, Math.min(range[0], range[1])), t1 = Math.min(tMax, Math.max(range[0], range[1]));
  if (!(t1 > t0) || !(t1 > 2 * s.input.step) || s.thinning === "none") return;
  const points = Math.min(config.limits.max_points, Math.ceil(PLOT_POINTS * t1 / (t1 - t0)));
  if (points <= PLOT_POINTS && t1 >= tMax) return;  // the whole run: nothing finer to fetch
  const my = seq;
  const r = await getJSON("/api/simulate?" + apiQuery("a", { points, t_max: String(t1) }));
  if (my !== seq || !r.ok) return;
  const gd = $("plot-theta"), z = r.body;
  const update = { x: [z.t], y: [z.theta] }, traces = [0];
  if (view.exact) { update.x.push(z.exact.t); update.y.push(z.exact.theta); traces.push(1); }
  sims.zoomed = true;
  await Plotly.restyle(gd, update, traces);
  const inView = z.t.filter((t) => t >= t0 && t <= t1).length;
  $("status").textContent = word("page.zoomed", { t: shown(t1), points: count(inView) });
}

function renderPhase() {
  const s = sims.a;
  const a = s.input.amplitude;
  // On a second line: a legend entry wider than the plot is cut off at its right (a phone, 1024 px).
  const orbits = (x) => (x.phase.orbits > 1 ? "<br>" + word("page.stretches", { orbits: x.phase.orbits, t: shown(x.phase.t_last) }) : "");
  const traces = [];
  traces.push({ x: s.phase.theta, y: s.phase.omega, mode: "lines", connectgaps: false, line: { color: COLORS.a, width: 1.6 },
    name: label(s) + orbits(s), hovertemplate: "θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" });
  if (sims.b) {
    traces.push({ x: sims.b.phase.theta, y: sims.b.phase.omega, mode: "lines", connectgaps: false, line: { color: COLORS.b, width: 1.4 },
      name: label(sims.b) + orbits(sims.b), hovertemplate: "θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" });
  }
  if (view.exact && s.exact_phase) {
    // The exact orbit over the simulated one: the closed curve the simulation should stay on.
    traces.push({ x: s.exact_phase.theta, y: s.exact_phase.omega, mode: "lines", line: { color: COLORS.exact, width: 1.2, dash: "dash" },
      name: word("page.exact-orbit"), hovertemplate: word("page.exact") + "<br>θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" });
  }
  const lines = traces.length;
  // P: the release, (α, 0) at rest or (α, θ′₀) for a launch.
  const w0 = s.launch ? s.launch.omega0 : 0;
  traces.push({ x: [a], y: [w0], mode: "markers", marker: { symbol: "circle-open", size: 16, line: { width: 2.5, color: COLORS.p } },
    name: "P = (α, θ′₀)", showlegend: false, hovertemplate: "P = (α, θ′₀)<br>α = %{x:.6f} rad<br>θ′₀ = %{y:.6f} rad/s<extra></extra>" });
  // One method has no legend: the title says which stretch of time the sampled orbits span.
  const title = s.phase.orbits > 1 ? word("page.phase-periods", { orbits: s.phase.orbits, t: shown(s.phase.t_last) }) : word("page.phase");
  plot("plot-phase", traces, layout(title, "θ (rad)", "θ′ (rad/s)", {
    annotations: [{ x: a, y: w0, text: "P", showarrow: true, arrowhead: 0, ax: 22, ay: -22, font: { color: COLORS.p } }],
    ...twoLines(traces.slice(0, lines)),
  }));
}

/** One line per simulation shown (a, then the comparison b), in its method's colour. */
function methodLines(xOf, yOf, hovertemplate) {
  return [["a", COLORS.a], ["b", COLORS.b]].filter(([k]) => sims[k]).map(([k, color]) => ({
    x: xOf(sims[k]), y: yOf(sims[k]), mode: "lines", line: { color, width: 1.4 }, name: label(sims[k]), hovertemplate,
  }));
}

function renderError() {
  const log = view.errlog;
  // On a log scale |error|: one diverging method does not flatten the others.
  const y = (s) => (log ? s.error.theta.map((v) => (v === null || v === 0 ? null : Math.abs(v))) : s.error.theta);
  const traces = methodLines((s) => s.error.t, y, log ? "t = %{x:.4f} s<br>|θ − θ_exact| = %{y:.3e} rad<extra></extra>"
    : "t = %{x:.4f} s<br>θ − θ_exact = %{y:.3e} rad<extra></extra>");
  const per = sims.a.error.per_period;
  const extra = log ? { yaxis: { type: "log", title: { text: word("page.error-abs-axis") }, gridcolor: "#eef1f5", exponentformat: "power", automargin: true, tickfont: { size: 13 } } } : {};
  plot("plot-error", traces, layout(word(log ? "page.error-log" : "page.error-plot"),
    word("page.per-period", { samples: num(per, 3) }), word("page.error-axis"), { ...extra, ...twoLines(traces) }));
}

function renderEnergy() {
  const traces = methodLines((s) => s.energy.t, (s) => s.energy.drift, "t = %{x:.4f} s<br>(E − E₀)/(mgl) = %{y:.3e}<extra></extra>");
  plot("plot-energy", traces, layout(word("page.energy-plot"), "t (s)", word("page.drift"), twoLines(traces)));
}

function renderEstimates() {
  // Each method's three estimates minus the AGM period: three places on the axis, the
  // second method's markers (open, orange) just right of the first's.
  const T = sims.a.period.period;
  const traces = [];
  const two = !!(sims.b && sims.b.period.estimate);
  for (const [k, dx, faint] of [["a", two ? -0.12 : 0, false], ["b", 0.12, true]]) {
    const s = sims[k];
    const e = s ? s.period.estimate : null;
    if (!e) continue;
    const half = (e.bracket[1] - e.bracket[0]) / 2;
    const open = faint ? "-open" : "";
    const color = (c) => (faint ? COLORS.b : c);
    const [br, li, cu, er] = [word("page.bracket"), word("page.linear"), word("page.inverse-cubic"), word("page.error-word")];
    traces.push(
      { x: [dx], y: [e.bracket_mid - T], mode: "markers", name: `${s.input.method} ${br}`, marker: { color: color(COLORS.bracket), size: 9, symbol: "line-ew-open" },
        error_y: { type: "data", array: [half], color: color(COLORS.bracket), thickness: 2, width: 8 }, hovertemplate: `${s.input.method} ${br} [${shown(e.bracket[0])}${lang === "pt" ? ";" : ","} ${shown(e.bracket[1])}] s<extra></extra>` },
      { x: [1 + dx], y: [e.linear - T], mode: "markers", name: `${s.input.method} ${li}`, marker: { color: color(COLORS.linear), size: 11, symbol: "circle" + open, line: { width: 2, color: color(COLORS.linear) } },
        hovertemplate: `${s.input.method} ${li} ${right(e, "linear")} s<br>${er} %{y:.3e} s<extra></extra>` },
      { x: [2 + dx], y: [e.cubic - T], mode: "markers", name: `${s.input.method} ${cu}`, marker: { color: color(COLORS.cubic), size: 11, symbol: "diamond" + open, line: { width: 2, color: color(COLORS.cubic) } },
        error_y: { type: "data", array: [Math.abs(e.cubic_error_estimate || 0)], color: color(COLORS.cubic) }, hovertemplate: `${s.input.method} ${cu} ${right(e, "cubic")} s<br>${er} %{y:.3e} s<extra></extra>` },
    );
  }
  if (!traces.length) {
    plot("plot-estimates", [], layout(word("page.estimates-plot"), "", word("page.estimate-axis"), {
      annotations: [{ text: word("page.no-period-plot"), showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }));
    return;
  }
  const who = two ? ": " + word("page.filled-open", { a: sims.a.input.method, b: sims.b.input.method }) : "";
  plot("plot-estimates", traces, layout(word("page.estimates-t", { period: num(T, 10) }), word("page.estimate") + who, word("page.estimate-axis"), {
    xaxis: { tickvals: [0, 1, 2], ticktext: [word("page.bracket"), word("page.linear"), word("page.cubic")], range: [-0.5, 2.5], tickfont: { size: 13 },
      automargin: true, zeroline: false, showgrid: false, title: { text: word("page.estimate") + who, font: { size: 13 } } },
    shapes: [{ type: "line", xref: "paper", x0: 0, x1: 1, y0: 0, y1: 0, line: { color: COLORS.exact, width: 1.5, dash: "dash" } }],
    annotations: [{ xref: "paper", x: 1, y: 0, text: word("page.agm-period"), showarrow: false, xanchor: "right", yanchor: "bottom", font: { size: 12 } }],
  }));
}

function renderConvergence(body, err, body2) {
  if (!body) {
    plot("plot-convergence", [], layout(word("page.convergence-plot"), "h (s)", word("page.abs-error-s"), {
      annotations: [{ text: err ? err.message : word("page.no-data"), showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }));
    return;
  }
  const rows = body.rows.filter((r) => r.estimate);
  if (!rows.length) { renderConvergence(null, { message: word("page.no-period-steps") }); return; }
  const series = (rs, key, name, color, symbol) => {
    const pts = rs.filter((r) => r.estimate && r.estimate.errors[key] > 0);
    return { x: pts.map((r) => r.step), y: pts.map((r) => r.estimate.errors[key]), mode: "lines+markers", name,
      line: { color, width: 2 }, marker: { color, size: 7, symbol }, hovertemplate: `${name}<br>h = %{x:.3e} s<br>|error| = %{y:.3e} s<extra></extra>` };
  };
  const two = body2 !== null;
  const tag = (m) => (two ? ` (${m})` : "");
  const traces = [
    series(rows, "bracket_mid", word("page.bracket-midpoint") + tag(body.method), COLORS.bracket, "square"),
    series(rows, "cubic", word("page.inverse-cubic") + tag(body.method), COLORS.cubic, "diamond"),
    series(rows, "linear", word("page.linear") + tag(body.method), COLORS.linear, "circle-open"),
  ];
  traces[2].line.dash = "dash";
  if (two) {
    const rows2 = body2.rows.filter((r) => r.estimate);
    const c2 = series(rows2, "cubic", `${word("page.inverse-cubic")} (${body2.method})`, COLORS.b, "diamond-open");
    const l2 = series(rows2, "linear", `${word("page.linear")} (${body2.method})`, COLORS.b, "circle-open");
    l2.line.dash = "dot";
    traces.push(c2, l2);
  }
  // A reference line of slope p = the method's order, through the cubic error at the largest step.
  const first = rows.find((r) => r.estimate.errors.cubic > 0);
  if (first && rows.length > 1) {
    const h0 = first.step, e0 = first.estimate.errors.cubic, h1 = rows[rows.length - 1].step;
    traces.push({ x: [h0, h1], y: [e0, e0 * Math.pow(h1 / h0, body.order)], mode: "lines", name: word("page.slope", { order: body.order }),
      line: { color: "#b8c0cc", dash: "dash", width: 1.5 }, hoverinfo: "skip" });
  }
  const h = sims.a ? sims.a.input.step : null;
  const gd = $("plot-convergence");
  const xs = traces.flatMap((t) => t.x).concat(h ? [h] : []), ys = traces.flatMap((t) => t.y);
  plot("plot-convergence", traces, layout(word("page.convergence-of", { methods: body.method + (two ? ", " + body2.method : "") }), "h (s)", word("page.abs-estimate-error"), {
    xaxis: { type: "log", title: { text: "h (s)" }, gridcolor: "#eef1f5", exponentformat: "power", automargin: true, tickfont: { size: 13 },
      ...logTicks(xs, gd.clientWidth - 90, 56) },
    yaxis: { type: "log", title: { text: word("page.abs-estimate-error") }, gridcolor: "#eef1f5", exponentformat: "power", automargin: true, tickfont: { size: 13 },
      ...logTicks(ys, gd.clientHeight - 170, 30) },
    showlegend: true, margin: { l: 70, r: 14, t: 46, b: two ? 150 : 110 },
    shapes: h ? [{ type: "line", x0: h, x1: h, yref: "paper", y0: 0, y1: 1, line: { color: COLORS.p, dash: "dot", width: 1 } }] : [],
    annotations: h ? [{ x: Math.log10(h), yref: "paper", y: 1, text: word("page.h-in-use"), showarrow: false, yanchor: "bottom", font: { color: COLORS.p, size: 12 } }] : [],
  }));
}

// Labels on a log axis: plotly's own choice labels 2 and 5 between the decades, and on a
// narrow plot "5" runs into "10⁻³" ("10⁻⁴" then "2" reads as "10⁻⁴²"). Here: decades only,
// every k-th where the axis is too short for each one to have `room` pixels; 1, 2, 5 only
// over less than two decades, where there is room for them.
function logTicks(values, length, room) {
  const v = values.filter((x) => x > 0);
  if (!v.length) return {};
  const decades = Math.log10(Math.max(...v) / Math.min(...v)) + 0.5;  // plotly pads the range
  if (decades < 2) return { dtick: "D2" };
  return { dtick: Math.max(1, Math.ceil(decades / Math.max(1, Math.floor(length / room)))) };
}

async function renderRatio() {
  // T(α)/T0 from 0 to 179°: the AGM ratio, the classical approximations, this pendulum on it.
  if (!curve) {
    const r = await getJSON("/api/period_curve");
    if (!r.ok) return;
    curve = r.body;
  }
  const x = curve.amplitude_deg;
  const traces = [{ x, y: curve.period_ratio, mode: "lines", name: "AGM", line: { color: COLORS.exact, width: 2.5 },
    hovertemplate: "α = %{x}°<br>T/T0 = %{y:.6f}<extra></extra>" }];
  const dashes = ["dash", "dot", "dashdot", "longdash", "longdashdot"];
  const colors = ["#8a94a6", "#e69f00", "#009e73", "#cc79a7", "#56b4e9"];
  curve.approximations.forEach((a, i) => traces.push({ x, y: a.ratio, mode: "lines", name: a.label,
    line: { color: colors[i % colors.length], width: 1.6, dash: dashes[i % dashes.length] }, hovertemplate: `${a.label}<br>α = %{x}°<br>T/T0 = %{y:.5f}<extra></extra>` }));
  const mark = (p, color, name) => ({ x: [p.amplitude_deg], y: [p.period / p.small_angle_period], mode: "markers", name,
    marker: { color, size: 12, line: { color: "#fff", width: 1.5 } }, hovertemplate: `${name}<br>α = %{x:.4g}°<br>T/T0 = %{y:.6f}<extra></extra>` });
  const p = sims.a.period, L = sims.a.launch;
  // A launched pendulum sits on the curve at its turning angle; one that goes round is not on it.
  if (!L) traces.push(mark(p, COLORS.p, word("page.this-pendulum")));
  else if (!L.circulates) traces.push(mark({ amplitude_deg: L.turning_angle_deg, period: p.period, small_angle_period: p.small_angle_period }, COLORS.p, word("page.this-pendulum")));
  if (sims.second) traces.push(mark(sims.second, COLORS.second, word("page.second-pendulum")));
  // The legend inside, top left: below 90° every curve is near 1, the corner is empty.
  plot("plot-ratio", traces, layout(word("page.ratio-plot"), word("page.alpha-deg"), "T / T₀", {
    showlegend: true, margin: { l: 70, r: 14, t: 46, b: 52 },
    legend: { x: 0.01, y: 0.99, xanchor: "left", yanchor: "top", bgcolor: "rgba(255,255,255,0.85)", font: { size: 12 } },
    xaxis: { title: { text: word("page.alpha-deg") }, range: [0, 180], dtick: 30, gridcolor: "#eef1f5", automargin: true, tickfont: { size: 13 } },
    yaxis: { title: { text: "T / T₀" }, range: [0.9, 4.2], gridcolor: "#eef1f5", automargin: true, tickfont: { size: 13 } },
  }));
}

// ---------- the time cursor over the plots: an element moved each frame, no plotly redraw ----------
function stateAt(fr, t, theta = fr.theta, omega = fr.omega, c = null) {
  // The state at time t: the samples, cubic Hermite in between (theta' is the derivative of
  // theta; with c = g/l, theta'' = -c sin(theta) that of theta', else theta' is linear).
  // Coarser than 8 samples a period: the nearest sample, at its time.
  const ts = fr.t, n = ts.length;
  if (!n) return null;
  let lo = 0, hi = n - 1;
  if (t <= ts[0]) hi = 0;
  else if (t >= ts[n - 1]) lo = n - 1;
  else while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (ts[mid] <= t) lo = mid; else hi = mid; }
  const pick = (i) => (theta[i] === null ? null : { t: ts[i], theta: theta[i], omega: omega[i] });
  if (lo === hi || hi === 0 || lo === n - 1) return pick(lo === n - 1 ? lo : hi);
  if (!(fr.per_period >= 8)) return pick(t - ts[lo] < ts[hi] - t ? lo : hi);
  const [a, b] = [pick(lo), pick(hi)];
  if (!a || !b || a.omega === null || b.omega === null) return null;
  const d = ts[hi] - ts[lo], s = (t - ts[lo]) / d, s2 = s * s, s3 = s2 * s;
  const h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const th = h00 * a.theta + h10 * d * a.omega + h01 * b.theta + h11 * d * b.omega;
  const om = c === null ? a.omega + s * (b.omega - a.omega)
    : h00 * a.omega - h10 * d * c * Math.sin(a.theta) + h01 * b.omega - h11 * d * c * Math.sin(b.theta);
  return { t, theta: th, omega: om };
}

const CURSOR_PLOTS = { "plot-theta": "line", "plot-error": "line", "plot-energy": "line", "plot-phase": "dot" };
const geom = {};  // per plot: its axes' offsets in the card, read once per redraw, never per frame

function measure(gd) {
  const kind = CURSOR_PLOTS[gd.id];
  if (!kind) return;
  const L = gd._fullLayout;
  let el = gd.parentElement.querySelector(".cursor-" + kind);
  if (!el) {
    el = document.createElement("div");
    el.className = "cursor-" + kind;
    el.setAttribute("aria-hidden", "true");
    gd.parentElement.append(el);
  }
  if (!L || !L.xaxis || !L.xaxis._length) { geom[gd.id] = null; el.hidden = true; return; }
  const xa = L.xaxis, ya = L.yaxis;
  geom[gd.id] = { el, kind, xa, ya, left: gd.offsetLeft + xa._offset, top: gd.offsetTop + ya._offset, w: xa._length, h: ya._length };
  if (kind === "line") el.style.height = ya._length + "px";
}

function moveCursors() {
  $("cursor").value = String(anim.t);
  if (!sims.a) return;
  const t = anim.t;
  for (const id of Object.keys(CURSOR_PLOTS)) {
    const g = geom[id];
    if (!g) continue;
    let x, y;
    if (g.kind === "line") { x = g.xa.l2p(t); y = 0; }
    else {
      const st = stateAt(sims.a.frames, t);
      x = st ? g.xa.l2p(st.theta) : NaN;
      y = st ? g.ya.l2p(st.omega) : NaN;
    }
    const inside = x >= 0 && x <= g.w && y >= 0 && y <= g.h;
    if (g.el.hidden === inside) g.el.hidden = !inside;
    if (inside) g.el.style.transform = `translate(${(g.left + x).toFixed(1)}px, ${(g.top + y).toFixed(1)}px)`;
  }
}

function renderAnimNote() {
  const f = sims.a.frames;
  $("anim-note").textContent = f.per_period >= 8 ? ""
    : word("page.too-fast", { samples: num(f.per_period, 2) });
}

// ---------- energies of the first pendulum now, in m g l: K = l θ′²/(2g), U = 1 − cos θ ----------
// Here, not from the server: the bars need K and U apart at each frame's interpolated state, the stream has only E − E₀ at its samples (K + U − 1 is engine.fold.energy).
// The page's one energy formula: lab.js's energies in J are these times m g l.
function energyOf(st, s) {
  if (!st || st.theta === null || st.omega === null) return null;
  const K = st.omega * st.omega * s.input.length / (2 * s.input.g), U = 1 - Math.cos(st.theta);
  return { K, U, E: K + U };
}

function renderBars() {
  const s = sims.a, box = $("energy-bars");
  if (!s) return;
  const c = s.input.g / s.input.length;
  const ex = s.exact_frames ? energyOf(stateAt(s.frames, anim.t, s.exact_frames.theta, s.exact_frames.omega, c), s) : null;
  const sm = energyOf(stateAt(s.frames, anim.t, s.frames.theta, s.frames.omega, c), s);
  const rows = [["exact", ex], ["sim", sm]];
  if (!box.dataset.built) {
    // A table of bars: K, U, E down, the exact motion and the simulation across.
    box.dataset.built = "1";
    const head = (text) => { const e = document.createElement("span"); e.className = "head"; e.textContent = text; return e; };
    box.append(head("m g l"), head(word("page.exact")), head(word("page.simulated")));
    for (const [k, name, color] of [["K", "page.kinetic", "#e07a1f"], ["U", "page.potential", "#2f6fdb"], ["E", "page.total", "#1d2330"]]) {
      const label = document.createElement("span");
      label.textContent = word(name);
      box.append(label);
      for (const [who] of rows) {
        const cell = document.createElement("span");
        cell.className = "cell";
        const bar = document.createElement("span");
        bar.className = "bar";
        const fill = document.createElement("span");
        fill.style.background = color;
        fill.id = `bar-${who}-${k}`;
        bar.append(fill);
        const v = document.createElement("span");
        v.className = "v";
        v.id = `val-${who}-${k}`;
        cell.append(bar, v);
        box.append(cell);
      }
    }
  }
  // The bars' full width: above the largest energy of a swing (2 m g l), or of this launch.
  const top = Math.max(2.2, 1.1 * (ex ? ex.E : 0));
  for (const [who, e] of rows) {
    for (const k of ["K", "U", "E"]) {
      const x = e ? e[k] : null;
      $(`bar-${who}-${k}`).style.width = x === null ? "0" : `${Math.min(100, Math.max(0, 100 * x / top)).toFixed(1)}%`;
      $(`val-${who}-${k}`).textContent = x === null ? "–" : local(x.toFixed(3));
    }
  }
}

// ---------- animation ----------
function niceCeil(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const m of [1, 2, 5, 10]) if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10 * p;
}

function rulerText(len) {
  return len >= 1 ? `${shown(len)} m` : len >= 1e-3 ? `${shown(len * 1e3)} mm` : `${local(len.toExponential(0))} m`;
}

function draw() {
  const c = $("canvas");
  const dpr = window.devicePixelRatio || 1;
  // The canvas's shape is the style's (420:340, or the projector's height): the drawing fits it.
  const W = c.clientWidth || 420, H = c.clientHeight || Math.round(W * 340 / 420);
  if (c.width !== Math.round(W * dpr) || c.height !== Math.round(H * dpr)) { c.width = Math.round(W * dpr); c.height = Math.round(H * dpr); }
  const fs = view.projector ? 24 : 13;  // the canvas's text in px: 24 px on a projector
  const g = c.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, W, H);
  const s = sims.a;
  const two = !!(s && sims.second);
  // One pivot, or two side by side.
  const pivots = two ? [{ x: W * 0.27, y: H / 2 }, { x: W * 0.73, y: H / 2 }] : [{ x: W / 2, y: H / 2 }];
  const Rmax = two ? Math.min(H / 2 - 22, W * 0.23 - 14) : H / 2 - 26;
  const lengths = s ? [s.input.length].concat(two ? [sims.second.length] : []) : [1];
  let radii = lengths.map(() => Rmax), ruler = null;
  if (s && view.scale) {
    // To scale: one scale for both, the ruler a fixed length on screen (Rmax) of a round length.
    const L = niceCeil(Math.max(...lengths));
    radii = lengths.map((l) => Rmax * l / L);
    ruler = { px: Rmax, text: rulerText(L) };
  }
  pivots.forEach((pv, i) => {
    g.strokeStyle = "#d5dbe5"; g.setLineDash([4, 5]); g.lineWidth = 1;
    g.beginPath(); g.arc(pv.x, pv.y, radii[i], 0, 2 * Math.PI); g.stroke();
    g.setLineDash([]);
  });
  if (ruler) {
    g.strokeStyle = "#39425a"; g.fillStyle = "#39425a"; g.lineWidth = 2;
    const y = H - 10;
    g.beginPath(); g.moveTo(W - 10 - ruler.px, y); g.lineTo(W - 10, y);
    g.moveTo(W - 10 - ruler.px, y - 5); g.lineTo(W - 10 - ruler.px, y + 3); g.moveTo(W - 10, y - 5); g.lineTo(W - 10, y + 3); g.stroke();
    g.font = `${fs - 1}px system-ui, sans-serif`; g.textAlign = "right";
    g.fillText(word("page.ruler", { length: ruler.text }), W - 10, y - 8); g.textAlign = "left";
  }
  if (!s) return null;
  const side = view.side;
  // The turning angles: ±α from rest, ±(2 asin k) for a launch that swings, none for one that goes round.
  const L = s.launch;
  const a = anim.drag !== null ? Math.abs(anim.drag) : L ? L.turning_angle : s.input.amplitude;
  const pv = pivots[0], R = radii[0];
  g.strokeStyle = "rgba(209, 73, 91, .35)"; g.lineWidth = 1;
  if (a !== null) for (const sg of [-1, 1]) { g.beginPath(); g.moveTo(pv.x, pv.y); g.lineTo(pv.x + R * Math.sin(sg * a), pv.y + R * Math.cos(sg * a)); g.stroke(); }
  if (window.lab) window.lab.draw(g, { W, H, pivots, radii, lengths });  // gates, ruler, protractor (under the bobs)
  const bobs = [];
  let st = null;
  if (anim.drag !== null) bobs.push({ theta: anim.drag, color: COLORS.a, pv, R, t: 0 });
  else {
    st = stateAt(s.frames, anim.t);
    bobs.push({ theta: st ? side * st.theta : null, color: COLORS.a, pv, R, t: st ? st.t : anim.t });
    if (sims.b) { const sb = stateAt(sims.b.frames, anim.t); bobs.push({ theta: sb ? side * sb.theta : null, color: COLORS.b, pv, R, ghost: true }); }
    if (two) {
      const s2 = stateAt(sims.second.frames, anim.t);
      bobs.push({ theta: s2 ? side * s2.theta : null, color: COLORS.second, pv: pivots[1], R: radii[1] });
    }
  }
  for (const b of bobs.slice().reverse()) {
    if (b.theta === null) continue;
    const bx = b.pv.x + b.R * Math.sin(b.theta), by = b.pv.y + b.R * Math.cos(b.theta);
    g.globalAlpha = b.ghost ? 0.75 : 1;
    g.strokeStyle = b.ghost ? COLORS.b : "#39425a"; g.lineWidth = 2.5;
    g.beginPath(); g.moveTo(b.pv.x, b.pv.y); g.lineTo(bx, by); g.stroke();
    g.fillStyle = b.color; g.beginPath(); g.arc(bx, by, 12, 0, 2 * Math.PI); g.fill();
    g.globalAlpha = 1;
  }
  for (const p of pivots) { g.fillStyle = "#39425a"; g.beginPath(); g.arc(p.x, p.y, 4.5, 0, 2 * Math.PI); g.fill(); }
  if (window.lab && anim.drag === null) window.lab.drawOver(g, { W, H, pivots, radii, lengths, side });  // vectors
  g.fillStyle = "#454e62"; g.font = `${fs}px system-ui, sans-serif`;
  g.fillText(`l = ${shown(s.input.length)} m`, 10, 1.4 * fs);
  g.fillText(`α = ${shown(anim.drag !== null ? Math.abs(anim.drag) * 180 / Math.PI : s.input.amplitude_deg)}°`, 10, 2.7 * fs);
  if (two) {
    g.fillStyle = COLORS.second; g.textAlign = "right";
    g.fillText(`l₂ = ${shown(sims.second.length)} m`, W - 10, 1.4 * fs);
    g.fillText(`α₂ = ${shown(sims.second.amplitude_deg)}°`, W - 10, 2.7 * fs);
    g.textAlign = "left";
  }
  const main = bobs[0];
  $("clock").textContent = main.theta === null ? `t = ${local(main.t.toFixed(3))} s   ${word("page.blown-up")}`
    : `t = ${local(main.t.toFixed(3))} s   θ = ${local((main.theta * 180 / Math.PI).toFixed(2))}°`;
  return st;
}

function frame(ts) {
  if (anim.last !== null && anim.playing && sims.a && anim.drag === null) {
    const f = sims.a.frames.t;
    const tEnd = f[f.length - 1];
    anim.t += ((ts - anim.last) / 1000) * anim.speed;
    if (anim.t > tEnd) anim.t = tEnd > 0 ? anim.t % tEnd : 0;
    tick();
  }
  anim.last = ts;
  requestAnimationFrame(frame);
}

/** Everything that follows the time: the swing, the lab's instruments, the bars, the plots' cursors. */
function tick() {
  draw();
  if (window.lab) window.lab.frame();
  renderBars();
  moveCursors();
}

function setPlaying(on) {
  anim.playing = on;
  $("play").textContent = word(on ? "page.pause" : "page.play");
  writeURL();
}

// Drag the bob: the angle from the pivot's downward vertical becomes the amplitude, and the
// side it was dragged to the side it is released from (the motion from -α is the mirror image).
function canvasPoint(ev) {
  const r = $("canvas").getBoundingClientRect();
  return { x: ev.clientX - r.left, y: ev.clientY - r.top, W: r.width, H: r.height };
}

function pivotOf(p) {
  return sims.second ? { x: p.W * 0.27, y: p.H / 2, R: Math.min(p.H / 2 - 22, p.W * 0.23 - 14) } : { x: p.W / 2, y: p.H / 2, R: p.H / 2 - 26 };
}

function dragAngle(ev) {
  const p = canvasPoint(ev), pv = pivotOf(p);
  const a = Math.atan2(p.x - pv.x, p.y - pv.y);
  const lim = 179.9 * Math.PI / 180;
  return Math.max(-lim, Math.min(a, lim));
}

function setupDrag() {
  const c = $("canvas");
  c.addEventListener("pointerdown", (ev) => {
    if (!sims.a) return;
    const p = canvasPoint(ev), pv = pivotOf(p);
    const st = stateAt(sims.a.frames, anim.t);
    if (!st) return;
    const th = view.side * st.theta;
    const bx = pv.x + pv.R * Math.sin(th), by = pv.y + pv.R * Math.cos(th);
    if (Math.hypot(p.x - bx, p.y - by) > 30 && !view.scale) return;
    anim.drag = dragAngle(ev);
    c.setPointerCapture(ev.pointerId);
    draw();
  });
  c.addEventListener("pointermove", (ev) => { if (anim.drag !== null) { anim.drag = dragAngle(ev); draw(); } });
  const end = () => {
    if (anim.drag === null) return;
    const a = Math.abs(anim.drag);
    view.side = anim.drag < 0 ? -1 : 1;
    anim.drag = null;
    $("amplitude").value = local($("unit").value === "deg" ? String(Number((a * 180 / Math.PI).toFixed(1))) : String(Number(a.toFixed(4))));
    syncSlider("amplitude");
    anim.t = 0;
    schedule(0);
  };
  c.addEventListener("pointerup", end);
  c.addEventListener("pointercancel", end);
}

// ---------- controls ----------
function markPreset() {
  const g = Number(typed($("g").value));
  for (const b of $("g-presets").children) b.classList.toggle("active", Number(b.dataset.g) === g);
  $("g-hint").hidden = $("g").value.trim() !== "";
}

function syncSlider(k) {
  const sl = $(k + "-slider");
  const text = typed($(k).value.trim());
  if (!PLAIN_NUMBER.test(text)) return;
  let x = Number(text);
  if (k === "amplitude" && $("unit").value === "rad") x = x * 180 / Math.PI;
  if (SLIDERS[k].log) { if (!(x > 0)) return; x = Math.log10(x); }
  sl.value = String(x);
}

function fromSlider(k) {
  const x = Number($(k + "-slider").value);
  if (k === "amplitude") return $("unit").value === "rad" ? String(Number((x * Math.PI / 180).toFixed(4))) : String(x);
  return String(Number(Math.pow(10, x).toPrecision(2)));
}

function convertAmplitude() {
  // Convert the shown amplitude with the server's own reading of it (the last good answer).
  const now = $("unit").value, was = now === "deg" ? "rad" : "deg";
  const text = typed($("amplitude").value.trim());
  const asSent = was === "deg" && PLAIN_NUMBER.test(text) ? text + "deg" : text;
  if (sims.a && asSent === sims.a.amplitudeQuery) {
    $("amplitude").value = local(short(now === "deg" ? sims.a.input.amplitude_deg : sims.a.input.amplitude));
  }
}

function addMethods(select, methods, group = null) {
  // The registry's methods as /api/config lists them: the named ones, then the family taylor:P.
  const parent = group ? document.createElement("optgroup") : select;
  if (group) { parent.label = group; select.append(parent); }
  for (const m of methods) {
    const o = document.createElement("option");
    o.value = m.name;
    o.textContent = word(m.order === 1 ? "page.euler" : "page.order", { name: m.name, order: m.order });
    o.title = m.description;
    parent.append(o);
  }
}

async function init() {
  lang = pickLanguage();
  config = (await getJSON("/api/config?lang=" + lang)).body;
  applyWords();
  document.title = word("page.title");
  for (const o of $("speed").options) o.textContent = `${local(o.value)}×`;
  $("lang").value = lang;
  $("lang").addEventListener("change", () => {
    // The page in the other language: its words are read once, at load; the URL keeps the choice.
    langGiven = true; lang = $("lang").value;
    location.search = "?" + pageQuery();
  });
  for (const sel of [$("method"), $("method2")]) {
    addMethods(sel, config.methods);
    addMethods(sel, config.family || [], word("page.taylor-family"));
  }
  for (const [name, g] of Object.entries(config.g_presets)) {
    const b = document.createElement("button");
    b.type = "button"; b.dataset.g = g; b.textContent = word(`page.preset.${name}`);
    b.title = `g = ${local(g)} m/s²`;
    b.addEventListener("click", () => { $("g").value = local(String(g)); syncSlider("g"); schedule(0); });
    $("g-presets").append(b);
  }
  for (const k of ERROR_FIELDS) { const d = $(k).getAttribute("aria-describedby"); if (d) $(k).dataset.hint = d; }
  readURL();
  writeForm();
  for (const k of NUMBER_FIELDS) {
    $(k).addEventListener("input", () => { if (SLIDERS[k]) syncSlider(k); schedule(); });
  }
  for (const k of Object.keys(SLIDERS)) {
    $(k + "-slider").addEventListener("input", () => { $(k).value = local(fromSlider(k)); schedule(150); });
  }
  for (const k of ["method", "method2"]) $(k).addEventListener("change", () => schedule(0));
  $("unit").addEventListener("change", () => { convertAmplitude(); syncSlider("amplitude"); schedule(0); });
  $("projector").addEventListener("click", () => setProjector(!view.projector));
  document.addEventListener("fullscreenchange", () => { if (!document.fullscreenElement && view.projector) setProjector(false); });
  $("plotkeys").addEventListener("change", () => {
    readForm(); writeURL();
    if (sims.a) { renderTheta(); renderPhase(); renderError(); renderEnergy(); renderEstimates(); renderRatio(); updateConvergence(seq); }
  });
  for (const k of ["exact", "scale", "errlog"]) {
    $(k).addEventListener("change", () => {
      readForm(); writeURL();
      if (sims.a) { renderTheta(); renderPhase(); renderError(); draw(); }
    });
  }
  $("second").addEventListener("change", () => {
    $("second-fields").hidden = !$("second").checked;
    if ($("second").checked && !$("length2").value) { $("length2").value = $("length").value; $("amplitude2").value = $("amplitude").value; }
    schedule(0);
  });
  $("inputs").addEventListener("submit", (ev) => { ev.preventDefault(); schedule(0); });
  $("play").addEventListener("click", () => setPlaying(!anim.playing));
  $("speed").addEventListener("change", () => { anim.speed = Number($("speed").value); writeURL(); });
  $("cursor").addEventListener("input", () => {
    anim.t = Number($("cursor").value);
    if (anim.playing) setPlaying(false); else writeURL();
    tick();
  });
  $("copy-link").addEventListener("click", async () => {
    try { await navigator.clipboard.writeText(location.href); $("copy-link").textContent = word("page.link-copied"); }
    catch (e) { window.prompt(word("page.copy-prompt"), location.href); }
    setTimeout(() => { $("copy-link").textContent = word("page.copy-link"); }, 1500);
  });
  setupDrag();
  window.addEventListener("resize", () => { tick(); });
  requestAnimationFrame(frame);
  update();
}

document.addEventListener("DOMContentLoaded", init);
