// pendulab explorer: the page reads its state from the URL, asks the JSON API, and draws.
// It computes nothing about the pendulum itself: every number shown comes from /api/.
// Between two of the server's animation samples the bob's angle is the cubic Hermite
// interpolant of theta and theta' there (drawing only; the server sends 16 samples a period).
"use strict";

const FIELDS = ["length", "amplitude", "unit", "g", "method", "step", "t_max", "method2", "step2"];
const NUMBER_FIELDS = ["length", "amplitude", "g", "step", "t_max", "step2"];
const PLOT_POINTS = 3000;          // theta(t): min and max of 1500 columns (more than a plot's pixels)
const MAX_PERIOD_MARKS = 12;       // dashed kT lines on theta(t), beyond which none are drawn
const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4];
const FONT = { family: "system-ui, -apple-system, Segoe UI, Roboto, DejaVu Sans, sans-serif", size: 12, color: "#1d2330" };
const COLORS = { a: "#2f6fdb", b: "#e07a1f", p: "#d1495b", bracket: "#8a94a6", linear: "#e69f00", cubic: "#009e73", exact: "#1d2330", cursor: "#d1495b" };
const PLAIN_NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;
// Sliders beside the number fields: whether each moves log10 of the value (range in index.html).
const SLIDERS = { length: { log: true }, g: { log: true }, step: { log: true }, t_max: { log: true }, amplitude: { log: false } };

const $ = (id) => document.getElementById(id);
let config = null;
let state = {};
let view = { exact: true, scale: false };
let sims = { a: null, b: null };  // the last good /api/simulate answers
let seq = 0;                        // drops answers to requests that are no longer current
let timer = null;
const anim = { playing: true, t: 0, last: null, speed: 1, marks: 0, drag: null };

// ---------- state <-> URL <-> form ----------
function readURL() {
  const q = new URLSearchParams(location.search);
  for (const k of FIELDS) state[k] = q.get(k) ?? config.defaults[k] ?? "";
  const speed = Number(q.get("speed"));
  anim.speed = SPEEDS.includes(speed) ? speed : 1;
  view.exact = q.get("exact") !== "0";
  view.scale = q.get("scale") === "1";
  anim.playing = q.get("paused") !== "1";
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
  for (const k of FIELDS) $(k).value = state[k];
  $("speed").value = String(anim.speed);
  $("exact").checked = view.exact;
  $("scale").checked = view.scale;
  $("play").textContent = anim.playing ? "Pause" : "Play";
  markPreset();
  for (const k of Object.keys(SLIDERS)) syncSlider(k);
}

function readForm() {
  for (const k of FIELDS) state[k] = $(k).value.trim();
  view.exact = $("exact").checked;
  view.scale = $("scale").checked;
}

function pageQuery() {
  const q = new URLSearchParams();
  for (const k of FIELDS) if (state[k] !== "" || !["method2", "step2"].includes(k)) q.set(k, state[k]);
  if (anim.speed !== 1) q.set("speed", String(anim.speed));
  if (!view.exact) q.set("exact", "0");
  if (view.scale) q.set("scale", "1");
  if (!anim.playing) { q.set("paused", "1"); q.set("t", String(Number(anim.t.toPrecision(6)))); }
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
  return new URLSearchParams({
    length: state.length, amplitude: state.amplitude, unit: state.unit, g: state.g, method, step, t_max: state.t_max, ...extra,
  }).toString();
}

// ---------- talking to the API ----------
function schedule(delay = 250) {
  clearTimeout(timer);
  timer = setTimeout(update, delay);
}

async function getJSON(url) {
  const r = await fetch(url);
  let body = null;
  try { body = await r.json(); } catch (e) { body = { error: { message: `server answered ${r.status}` } }; }
  return { ok: r.ok, body };
}

async function update() {
  readForm();
  writeURL();
  markPreset();
  const my = ++seq;
  const amplitudeQuery = apiAmplitude();
  $("status").textContent = "Simulating…";
  document.body.classList.add("busy");
  let ra, rb = null;
  try {
    const pa = getJSON("/api/simulate?" + apiQuery("a", { points: PLOT_POINTS }));
    const pb = state.method2 ? getJSON("/api/simulate?" + apiQuery("b", { points: PLOT_POINTS })) : null;
    ra = await pa;
    rb = pb ? await pb : null;
  } catch (e) {
    if (my === seq) showError({ message: "the pendulab server does not answer: is `pendulab serve` still running?" });
    return;
  }
  if (my !== seq) return;
  document.body.classList.remove("busy");
  if (!ra.ok) { showError(ra.body.error); return; }
  if (rb && !rb.ok) {
    const e = rb.body.error || {};
    showError({ ...e, field: { step: "step2", method: "method2" }[e.field] || e.field, message: "second method: " + e.message });
    return;
  }
  clearError();
  sims = { a: ra.body, b: rb ? rb.body : null };
  sims.a.amplitudeQuery = amplitudeQuery;
  $("csv").href = "/api/trajectory.csv?" + apiQuery("a");
  $("csv").setAttribute("aria-disabled", "false");
  const s = sims.a;
  const thinned = s.thinning === "none" ? "every step plotted" : `θ(t): min and max of each of ${s.columns} columns`;
  $("status").textContent = `${s.n_steps.toLocaleString("en")} steps of ${s.input.method}; ${thinned}.`;
  const tEnd = s.frames.t[s.frames.t.length - 1];
  if (anim.t > tEnd) anim.t = 0;
  $("cursor").max = String(tEnd);
  renderFlags();
  renderPeriods();
  renderTheta();
  renderPhase();
  renderError();
  renderEnergy();
  renderEstimates();
  renderAnimNote();
  draw();
  updateCursor(true);
  updateConvergence(my);
}

async function updateConvergence(my) {
  const s = sims.a;
  const T = s.period.period;
  // Steps from T/30 down to T/30000, four per decade, plus the step in use.
  const steps = [];
  for (let k = 0; k <= 12; k++) steps.push(T / Math.pow(10, 1.5 + k / 4));
  steps.push(s.input.step);
  const q = new URLSearchParams({
    length: state.length, amplitude: state.amplitude, unit: state.unit, g: state.g, method: state.method,
    steps: steps.map((h) => h.toPrecision(6)).join(","),
  });
  let res;
  try { res = await getJSON("/api/convergence?" + q.toString()); } catch (e) { return; }
  if (my !== seq) return;
  renderConvergence(res.ok ? res.body : null, res.ok ? null : res.body.error);
}

function showError(err) {
  document.body.classList.remove("busy");
  for (const k of NUMBER_FIELDS.concat(["method", "method2"])) $(k).classList.remove("invalid");
  if (err && err.field && $(err.field)) $(err.field).classList.add("invalid");
  const e = $("error");
  e.textContent = err && err.message ? err.message : "unknown error";
  e.hidden = false;
  $("status").textContent = "Results below are from the last valid input.";
  $("results").classList.add("stale");
  $("results").setAttribute("aria-disabled", "true");
  $("csv").setAttribute("aria-disabled", "true");
}

function clearError() {
  for (const k of NUMBER_FIELDS.concat(["method", "method2"])) $(k).classList.remove("invalid");
  $("error").hidden = true;
  $("results").classList.remove("stale");
  $("results").removeAttribute("aria-disabled");
}

// ---------- numbers ----------
const fix = (x, d = 12) => (x === null || x === undefined ? "–" : x.toPrecision(d));
const sci = (x) => (x === null || x === undefined ? "–" : x === 0 ? "0" : x.toExponential(2));
const short = (x) => String(Number(x.toPrecision(12)));
const label = (s) => `${s.input.method}, h = ${short(s.input.step)} s`;

function renderFlags() {
  const box = $("flags");
  box.textContent = "";
  const all = [];
  for (const k of ["a", "b"]) {
    const s = sims[k];
    if (s) for (const w of s.flags.warnings) all.push([label(s), w]);
  }
  box.hidden = all.length === 0;
  for (const [who, w] of all) {
    const p = document.createElement("p");
    const b = document.createElement("b");
    b.textContent = "Not the pendulum's motion (" + who + "): ";
    p.append(b, document.createTextNode(w + "."));
    box.append(p);
  }
}

function tableFor(s, suffix) {
  const wrap = document.createElement("div");
  wrap.className = "estimates" + (s.flags.trustworthy ? "" : " untrusted");
  const cap = document.createElement("p");
  cap.className = "caption";
  cap.textContent = label(s) + (s.flags.trustworthy ? "" : " — flagged: see the warning");
  const t = document.createElement("table");
  t.innerHTML = "<thead><tr><th>From the simulation</th><th>Estimate (s)</th><th>|Error| (s)</th><th>Rel.</th></tr></thead>";
  const body = document.createElement("tbody");
  const rows = [["bracket", "Bracket [t<sub>j</sub>, t<sub>j+1</sub>]"], ["linear", "Linear interp."], ["cubic", "Inverse cubic p(0)"]];
  const p = s.period, e = p.estimate;
  for (const [k, name] of rows) {
    const tr = document.createElement("tr");
    const cells = ["–", "–", "–"];
    if (e) {
      const err = k === "bracket" ? e.errors.bracket_mid : e.errors[k];
      cells[0] = k === "bracket" ? `[${short(e.bracket[0])}, ${short(e.bracket[1])}]` : fix(e[k]);
      cells[1] = sci(err);
      cells[2] = err === null ? "–" : sci(err / p.period);
    }
    tr.innerHTML = `<td>${name}</td>`;
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
    ? `Sign change of θ′ at step j = ${e.j}. Bracket error: of its midpoint. Error estimate of p(0) from a 5th node: ${sci(e.cubic_error_estimate)} s.`
    : "No period from this simulation: " + p.reason;
  wrap.append(cap, t, note);
  return wrap;
}

function renderPeriods() {
  const p = sims.a.period;
  $("period-exact").textContent = fix(p.period);
  $("period-small").textContent = fix(p.small_angle);
  const box = $("tables");
  box.textContent = "";
  box.append(tableFor(sims.a, ""));
  if (sims.b) box.append(tableFor(sims.b, "2"));
}

// ---------- plots ----------
function plotConfig() {
  // On a narrow screen the toolbar would cover the title: none there (pinch and drag still zoom).
  return { displaylogo: false, responsive: true, displayModeBar: window.innerWidth >= 700 ? "hover" : false,
    modeBarButtonsToRemove: ["lasso2d", "select2d"] };
}

// The mode bar (on hover, at the top right) shares the top row with the title, which starts
// at the left: on a narrow plot or with a long title the bar would cover the title's end.
// There the title moves down below the bar, and the plot area with it by as much.
const TITLE_GAP = 3;

function plot(id, traces, lay) {
  return Plotly.react(id, traces, lay, plotConfig()).then(() => clearModeBar($(id)));
}

function clearModeBar(gd) {
  const title = gd.querySelector(".gtitle"), bar = gd.querySelector(".modebar");
  if (!title || !bar || !bar.getBoundingClientRect().width) return;  // no bar (a narrow screen)
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
    title: { text: title, font: { size: 13 }, x: 0.01, xanchor: "left", y: 0.97, yanchor: "top" },
    font: FONT, margin: { l: 62, r: 12, t: 44, b: 46 }, paper_bgcolor: "#fff", plot_bgcolor: "#fff",
    xaxis: { title: { text: xtitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc", automargin: true },
    yaxis: { title: { text: ytitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc", automargin: true, exponentformat: "e" },
    legend: { orientation: "h", x: 0, y: -0.3, yanchor: "top", font: { size: 11 } }, showlegend: false, ...extra,
  };
}

function cursorShape(t) {
  return { type: "line", x0: t, x1: t, yref: "paper", y0: 0, y1: 1, line: { color: COLORS.cursor, width: 1.5 } };
}

function twoMethods(traces) {
  // A legend only when there is something to tell apart, below the plot.
  return traces.length > 1 ? { showlegend: true, margin: { l: 62, r: 12, t: 44, b: 96 } } : {};
}

function renderTheta() {
  const s = sims.a;
  const T = s.period.period;
  const shapes = [cursorShape(anim.t)];
  const annotations = [];
  const marks = Math.floor(s.input.t_max / T);
  if (marks <= MAX_PERIOD_MARKS) {
    for (let k = 1; k <= marks; k++) {
      shapes.push({ type: "line", x0: k * T, x1: k * T, yref: "paper", y0: 0, y1: 1, line: { dash: "dot", color: COLORS.p, width: 1 } });
      annotations.push({ x: k * T, yref: "paper", y: 1, text: k === 1 ? "T" : `${k}T`, showarrow: false, yanchor: "bottom", font: { color: COLORS.p, size: 11 } });
    }
  }
  anim.marks = marks <= MAX_PERIOD_MARKS ? marks : 0;
  const traces = [{ x: s.t, y: s.theta, mode: "lines", line: { color: COLORS.a, width: 1.6 }, name: label(s),
    hovertemplate: "t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" }];
  if (view.exact) {
    traces.push({ x: s.exact.t, y: s.exact.theta, mode: "lines", line: { color: COLORS.exact, width: 1.2, dash: "dash" },
      name: "exact motion", hovertemplate: "exact<br>t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" });
  }
  if (sims.b) {
    traces.push({ x: sims.b.t, y: sims.b.theta, mode: "lines", line: { color: COLORS.b, width: 1.4 }, name: label(sims.b),
      hovertemplate: "t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" });
  }
  const title = marks <= MAX_PERIOD_MARKS ? "Angle θ(t)" : `Angle θ(t): ${marks.toLocaleString("en")} periods of T = ${T.toPrecision(6)} s`;
  plot("plot-theta", traces, layout(title, "t (s)", "θ (rad)", { shapes, annotations, ...twoMethods(traces) }));
}

function renderPhase() {
  const s = sims.a;
  const a = s.input.amplitude;
  // On a second line: a legend entry wider than the plot is cut off at its right (a phone, 1024 px).
  const orbits = (x) => (x.phase.orbits > 1 ? `<br>${x.phase.orbits} one-period stretches, 0 to ${short(x.phase.t_last)} s` : "");
  const traces = [
    { x: s.phase.theta, y: s.phase.omega, mode: "lines", connectgaps: false, line: { color: COLORS.a, width: 1.6 },
      name: label(s) + orbits(s), hovertemplate: "θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" },
  ];
  if (sims.b) {
    traces.push({ x: sims.b.phase.theta, y: sims.b.phase.omega, mode: "lines", connectgaps: false, line: { color: COLORS.b, width: 1.4 },
      name: label(sims.b) + orbits(sims.b), hovertemplate: "θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" });
  }
  traces.push({ x: [a], y: [0], mode: "markers", marker: { symbol: "circle-open", size: 16, line: { width: 2.5, color: COLORS.p } },
    name: "P = (α, 0)", showlegend: false, hovertemplate: "P = (α, 0)<br>α = %{x:.6f} rad<extra></extra>" });
  const st = stateAt(s.frames, anim.t);
  traces.push({ x: [st ? st.theta : null], y: [st ? st.omega : null], mode: "markers", marker: { color: COLORS.cursor, size: 9 },
    name: "now", showlegend: false, hoverinfo: "skip" });
  anim.phaseCursor = traces.length - 1;
  // One method has no legend: the title says which stretch of time the sampled orbits span.
  const title = s.phase.orbits > 1 ? `Phase portrait: ${s.phase.orbits} periods sampled, 0 to ${short(s.phase.t_last)} s` : "Phase portrait (θ, θ′)";
  plot("plot-phase", traces, layout(title, "θ (rad)", "θ′ (rad/s)", {
    annotations: [{ x: a, y: 0, text: "P", showarrow: true, arrowhead: 0, ax: 22, ay: -22, font: { color: COLORS.p } }],
    ...twoMethods(traces.slice(0, -2)),
  }));
}

/** One line per simulation shown (a, then the comparison b), in its method's colour. */
function methodLines(xOf, yOf, hovertemplate) {
  return [["a", COLORS.a], ["b", COLORS.b]].filter(([k]) => sims[k]).map(([k, color]) => ({
    x: xOf(sims[k]), y: yOf(sims[k]), mode: "lines", line: { color, width: 1.4 }, name: label(sims[k]), hovertemplate,
  }));
}

function renderError() {
  const traces = methodLines((s) => s.error.t, (s) => s.error.theta, "t = %{x:.4f} s<br>θ − θ_exact = %{y:.3e} rad<extra></extra>");
  const per = sims.a.error.per_period;
  plot("plot-error", traces, layout("Global error θ_sim − θ_exact", `t (s): ${per.toPrecision(3)} samples a period`, "error (rad)", {
    shapes: [cursorShape(anim.t)], ...twoMethods(traces),
  }));
}

function renderEnergy() {
  const traces = methodLines((s) => s.energy.t, (s) => s.energy.drift, "t = %{x:.4f} s<br>(E − E₀)/(mgl) = %{y:.3e}<extra></extra>");
  plot("plot-energy", traces, layout("Energy drift (E − E₀)/(m g l)", "t (s)", "drift", {
    shapes: [cursorShape(anim.t)], ...twoMethods(traces),
  }));
}

function renderEstimates() {
  const p = sims.a.period;
  const e = p.estimate;
  const T = p.period;
  if (!e) {
    plot("plot-estimates", [], layout("Period estimates − exact T", "", "estimate − T (s)", {
      annotations: [{ text: "no period from this simulation", showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }));
    return;
  }
  const half = (e.bracket[1] - e.bracket[0]) / 2;
  const traces = [
    { x: ["bracket"], y: [e.bracket_mid - T], mode: "markers", marker: { color: COLORS.bracket, size: 9, symbol: "line-ew-open" },
      error_y: { type: "data", array: [half], color: COLORS.bracket, thickness: 2, width: 10 }, hovertemplate: `bracket [${e.bracket[0]}, ${e.bracket[1]}] s<extra></extra>` },
    { x: ["linear"], y: [e.linear - T], mode: "markers", marker: { color: COLORS.linear, size: 11 }, hovertemplate: `linear ${e.linear} s<br>error %{y:.3e} s<extra></extra>` },
    { x: ["cubic p(0)"], y: [e.cubic - T], mode: "markers", marker: { color: COLORS.cubic, size: 11, symbol: "diamond" },
      error_y: { type: "data", array: [Math.abs(e.cubic_error_estimate || 0)], color: COLORS.cubic }, hovertemplate: `cubic ${e.cubic} s<br>error %{y:.3e} s<extra></extra>` },
  ];
  plot("plot-estimates", traces, layout(`Period estimates − exact T = ${T.toPrecision(10)} s`, "", "estimate − T (s)", {
    shapes: [{ type: "line", xref: "paper", x0: 0, x1: 1, y0: 0, y1: 0, line: { color: COLORS.exact, width: 1.5, dash: "dash" } }],
    annotations: [{ xref: "paper", x: 1, y: 0, text: "exact (AGM)", showarrow: false, xanchor: "right", yanchor: "bottom", font: { size: 11 } }],
  }));
}

function renderConvergence(body, err) {
  if (!body) {
    plot("plot-convergence", [], layout("Period error vs step h", "h (s)", "|error| (s)", {
      annotations: [{ text: err ? err.message : "no data", showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }));
    return;
  }
  const rows = body.rows.filter((r) => r.estimate);
  if (!rows.length) { renderConvergence(null, { message: "no period from any of these steps" }); return; }
  const series = (key, name, color, symbol) => {
    const pts = rows.filter((r) => r.estimate.errors[key] > 0);
    return { x: pts.map((r) => r.step), y: pts.map((r) => r.estimate.errors[key]), mode: "lines+markers", name,
      line: { color, width: 2 }, marker: { color, size: 7, symbol }, hovertemplate: `${name}<br>h = %{x:.3e} s<br>|error| = %{y:.3e} s<extra></extra>` };
  };
  const traces = [
    series("bracket_mid", "bracket midpoint", COLORS.bracket, "square"),
    series("cubic", "inverse cubic", COLORS.cubic, "diamond"),
    series("linear", "linear", COLORS.linear, "circle-open"),
  ];
  traces[2].line.dash = "dash";
  // A reference line of slope p = the method's order, through the cubic error at the largest step.
  const first = rows.find((r) => r.estimate.errors.cubic > 0);
  if (first && rows.length > 1) {
    const h0 = first.step, e0 = first.estimate.errors.cubic, h1 = rows[rows.length - 1].step;
    traces.push({ x: [h0, h1], y: [e0, e0 * Math.pow(h1 / h0, body.order)], mode: "lines", name: `slope ${body.order}`,
      line: { color: "#b8c0cc", dash: "dash", width: 1.5 }, hoverinfo: "skip" });
  }
  const h = sims.a ? sims.a.input.step : null;
  const gd = $("plot-convergence");
  const xs = traces.flatMap((t) => t.x).concat(h ? [h] : []), ys = traces.flatMap((t) => t.y);
  plot("plot-convergence", traces, layout(`Period error vs step h (${body.method})`, "h (s)", "|estimate − T| (s)", {
    xaxis: { type: "log", title: { text: "h (s)" }, gridcolor: "#eef1f5", exponentformat: "power", automargin: true,
      ...logTicks(xs, gd.clientWidth - 90, 56) },
    yaxis: { type: "log", title: { text: "|estimate − T| (s)" }, gridcolor: "#eef1f5", exponentformat: "power", automargin: true,
      ...logTicks(ys, gd.clientHeight - 160, 30) },
    showlegend: true, margin: { l: 62, r: 12, t: 44, b: 96 },
    shapes: h ? [{ type: "line", x0: h, x1: h, yref: "paper", y0: 0, y1: 1, line: { color: COLORS.p, dash: "dot", width: 1 } }] : [],
    annotations: h ? [{ x: Math.log10(h), yref: "paper", y: 1, text: "h in use", showarrow: false, yanchor: "bottom", font: { color: COLORS.p, size: 11 } }] : [],
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

// ---------- the time cursor: animation, theta(t), error, energy and phase portrait together ----------
function stateAt(fr, t) {
  // The simulation's state at time t: its own samples, cubic Hermite in between (theta' is
  // the derivative of theta). Coarser than 8 samples a period: the nearest sample, at its time.
  const ts = fr.t, n = ts.length;
  if (!n) return null;
  let lo = 0, hi = n - 1;
  if (t <= ts[0]) hi = 0;
  else if (t >= ts[n - 1]) lo = n - 1;
  else while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (ts[mid] <= t) lo = mid; else hi = mid; }
  const pick = (i) => (fr.theta[i] === null ? null : { t: ts[i], theta: fr.theta[i], omega: fr.omega[i] });
  if (lo === hi || hi === 0 || lo === n - 1) return pick(lo === n - 1 ? lo : hi);
  if (!(fr.per_period >= 8)) return pick(t - ts[lo] < ts[hi] - t ? lo : hi);
  const [a, b] = [pick(lo), pick(hi)];
  if (!a || !b || a.omega === null || b.omega === null) return null;
  const d = ts[hi] - ts[lo], s = (t - ts[lo]) / d, s2 = s * s, s3 = s2 * s;
  const theta = (2 * s3 - 3 * s2 + 1) * a.theta + (s3 - 2 * s2 + s) * d * a.omega + (-2 * s3 + 3 * s2) * b.theta + (s3 - s2) * d * b.omega;
  return { t, theta, omega: a.omega + s * (b.omega - a.omega) };
}

let lastMarks = 0;
function updateCursor(force = false) {
  const now = performance.now();
  if (!force && now - lastMarks < 150) return;
  lastMarks = now;
  $("cursor").value = String(anim.t);
  if (!sims.a) return;
  const t = anim.t;
  for (const id of ["plot-theta", "plot-error", "plot-energy"]) {
    const gd = $(id);
    if (gd && gd.layout && gd.layout.shapes && gd.layout.shapes.length) Plotly.relayout(gd, { "shapes[0].x0": t, "shapes[0].x1": t });
  }
  const st = stateAt(sims.a.frames, t);
  const gd = $("plot-phase");
  if (gd && gd.data && anim.phaseCursor !== undefined) {
    Plotly.restyle(gd, { x: [[st ? st.theta : null]], y: [[st ? st.omega : null]] }, [anim.phaseCursor]);
  }
}

function renderAnimNote() {
  const f = sims.a.frames;
  $("anim-note").textContent = f.per_period >= 8 ? ""
    : `The swing is faster than the animation can show (${f.per_period.toPrecision(2)} samples a period): it jumps between the simulation's states at their times.`;
}

// ---------- animation ----------
function niceLength(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const m of [5, 2, 1]) if (m * p <= x) return m * p;
  return p;
}

function draw() {
  const c = $("canvas");
  const dpr = window.devicePixelRatio || 1;
  const W = c.clientWidth || 420, H = Math.round(W * 340 / 420);
  if (c.width !== Math.round(W * dpr)) { c.width = Math.round(W * dpr); c.height = Math.round(H * dpr); }
  const g = c.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, W, H);
  const px = W / 2, py = H / 2, Rmax = H / 2 - 26;
  const s = sims.a;
  let R = Rmax, ruler = null;
  if (s && view.scale) {
    // To scale: metres to pixels by a round factor, with a ruler of a round length.
    const l = s.input.length;
    const mPerPx = Math.pow(10, Math.ceil(Math.log10(l / Rmax)));
    R = l / mPerPx;
    const len = niceLength(l);
    ruler = { px: len / mPerPx, text: len >= 1 ? `${short(len)} m` : len >= 1e-3 ? `${short(len * 1e3)} mm` : `${len.toExponential(0)} m` };
  }
  g.strokeStyle = "#d5dbe5"; g.setLineDash([4, 5]); g.lineWidth = 1;
  g.beginPath(); g.arc(px, py, R, 0, 2 * Math.PI); g.stroke();
  g.setLineDash([]);
  if (ruler) {
    g.strokeStyle = "#39425a"; g.fillStyle = "#39425a"; g.lineWidth = 2;
    g.beginPath(); g.moveTo(W - 12 - ruler.px, H - 14); g.lineTo(W - 12, H - 14); g.stroke();
    g.font = "11px system-ui, sans-serif"; g.textAlign = "right";
    g.fillText(ruler.text, W - 12, H - 20); g.textAlign = "left";
  }
  if (!s) return;
  const a = anim.drag !== null ? anim.drag : s.input.amplitude;
  g.strokeStyle = "rgba(209, 73, 91, .35)"; g.lineWidth = 1;
  for (const sg of [-1, 1]) { g.beginPath(); g.moveTo(px, py); g.lineTo(px + R * Math.sin(sg * a), py + R * Math.cos(sg * a)); g.stroke(); }
  const bobs = [];
  if (anim.drag !== null) bobs.push({ theta: anim.drag, color: COLORS.a, t: 0 });
  else {
    const st = stateAt(s.frames, anim.t);
    bobs.push({ theta: st ? st.theta : null, color: COLORS.a, t: st ? st.t : anim.t });
    if (sims.b) { const sb = stateAt(sims.b.frames, anim.t); bobs.push({ theta: sb ? sb.theta : null, color: COLORS.b, t: anim.t, ghost: true }); }
  }
  for (const b of bobs.slice().reverse()) {
    if (b.theta === null) continue;
    const bx = px + R * Math.sin(b.theta), by = py + R * Math.cos(b.theta);
    g.globalAlpha = b.ghost ? 0.75 : 1;
    g.strokeStyle = b.ghost ? COLORS.b : "#39425a"; g.lineWidth = 2.5;
    g.beginPath(); g.moveTo(px, py); g.lineTo(bx, by); g.stroke();
    g.fillStyle = b.color; g.beginPath(); g.arc(bx, by, 13, 0, 2 * Math.PI); g.fill();
    g.globalAlpha = 1;
  }
  g.fillStyle = "#39425a"; g.beginPath(); g.arc(px, py, 4.5, 0, 2 * Math.PI); g.fill();
  g.fillStyle = "#5d6678"; g.font = "12px system-ui, sans-serif";
  g.fillText(`l = ${short(s.input.length)} m`, 10, 18);
  g.fillText(`α = ${short(anim.drag !== null ? anim.drag * 180 / Math.PI : s.input.amplitude_deg)}°`, 10, 34);
  const main = bobs[0];
  $("clock").textContent = main.theta === null ? `t = ${main.t.toFixed(3)} s   θ: not a number (blown up)`
    : `t = ${main.t.toFixed(3)} s   θ = ${(main.theta * 180 / Math.PI).toFixed(2)}°`;
}

function frame(ts) {
  if (anim.last !== null && anim.playing && sims.a && anim.drag === null) {
    const f = sims.a.frames.t;
    const tEnd = f[f.length - 1];
    anim.t += ((ts - anim.last) / 1000) * anim.speed;
    if (anim.t > tEnd) anim.t = tEnd > 0 ? anim.t % tEnd : 0;
    draw();
    updateCursor();
  }
  anim.last = ts;
  requestAnimationFrame(frame);
}

function setPlaying(on) {
  anim.playing = on;
  $("play").textContent = on ? "Pause" : "Play";
  writeURL();
}

// Drag the bob: the angle from the pivot's downward vertical becomes the amplitude.
function canvasPoint(ev) {
  const r = $("canvas").getBoundingClientRect();
  return { x: ev.clientX - r.left, y: ev.clientY - r.top, W: r.width, H: r.width * 340 / 420 };
}

function dragAngle(ev) {
  const p = canvasPoint(ev);
  const a = Math.abs(Math.atan2(p.x - p.W / 2, p.y - p.H / 2));
  return Math.min(a, 179.9 * Math.PI / 180);
}

function setupDrag() {
  const c = $("canvas");
  c.addEventListener("pointerdown", (ev) => {
    if (!sims.a) return;
    const p = canvasPoint(ev);
    const st = stateAt(sims.a.frames, anim.t);
    if (!st) return;
    const R = p.H / 2 - 26;
    const bx = p.W / 2 + R * Math.sin(st.theta), by = p.H / 2 + R * Math.cos(st.theta);
    if (Math.hypot(p.x - bx, p.y - by) > 30 && !view.scale) return;
    anim.drag = dragAngle(ev);
    c.setPointerCapture(ev.pointerId);
    draw();
  });
  c.addEventListener("pointermove", (ev) => { if (anim.drag !== null) { anim.drag = dragAngle(ev); draw(); } });
  const end = () => {
    if (anim.drag === null) return;
    const a = anim.drag;
    anim.drag = null;
    $("amplitude").value = $("unit").value === "deg" ? String(Number((a * 180 / Math.PI).toFixed(1))) : String(Number(a.toFixed(4)));
    syncSlider("amplitude");
    anim.t = 0;
    schedule(0);
  };
  c.addEventListener("pointerup", end);
  c.addEventListener("pointercancel", end);
}

// ---------- controls ----------
function markPreset() {
  const g = Number($("g").value);
  for (const b of $("g-presets").children) b.classList.toggle("active", Number(b.dataset.g) === g);
}

function syncSlider(k) {
  const sl = $(k + "-slider");
  const text = $(k).value.trim();
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
  const text = $("amplitude").value.trim();
  const asSent = was === "deg" && PLAIN_NUMBER.test(text) ? text + "deg" : text;
  if (sims.a && asSent === sims.a.amplitudeQuery) {
    $("amplitude").value = short(now === "deg" ? sims.a.input.amplitude_deg : sims.a.input.amplitude);
  }
}

function addMethods(select, methods, group = null) {
  // The registry's methods as /api/config lists them: the named ones, then the family taylor:P.
  const parent = group ? document.createElement("optgroup") : select;
  if (group) { parent.label = group; select.append(parent); }
  for (const m of methods) {
    const o = document.createElement("option");
    o.value = m.name;
    o.textContent = `${m.name} (order ${m.order})`;
    o.title = m.description;
    if (m.order === 1) o.textContent = `${m.name}: Euler (order 1)`;
    parent.append(o);
  }
}

async function init() {
  config = (await getJSON("/api/config")).body;
  for (const sel of [$("method"), $("method2")]) {
    addMethods(sel, config.methods);
    addMethods(sel, config.family || [], "Taylor method of order P");
  }
  for (const [name, g] of Object.entries(config.g_presets)) {
    const b = document.createElement("button");
    b.type = "button"; b.dataset.g = g; b.textContent = name[0].toUpperCase() + name.slice(1);
    b.title = `g = ${g} m/s²`;
    b.addEventListener("click", () => { $("g").value = String(g); syncSlider("g"); schedule(0); });
    $("g-presets").append(b);
  }
  readURL();
  writeForm();
  for (const k of NUMBER_FIELDS) {
    $(k).addEventListener("input", () => { if (SLIDERS[k]) syncSlider(k); schedule(); });
  }
  for (const k of Object.keys(SLIDERS)) {
    $(k + "-slider").addEventListener("input", () => { $(k).value = fromSlider(k); schedule(150); });
  }
  for (const k of ["method", "method2"]) $(k).addEventListener("change", () => schedule(0));
  $("unit").addEventListener("change", () => { convertAmplitude(); syncSlider("amplitude"); schedule(0); });
  for (const k of ["exact", "scale"]) {
    $(k).addEventListener("change", () => {
      readForm(); writeURL();
      if (sims.a) { renderTheta(); draw(); }
    });
  }
  $("inputs").addEventListener("submit", (ev) => { ev.preventDefault(); schedule(0); });
  $("play").addEventListener("click", () => setPlaying(!anim.playing));
  $("speed").addEventListener("change", () => { anim.speed = Number($("speed").value); writeURL(); });
  $("cursor").addEventListener("input", () => {
    anim.t = Number($("cursor").value);
    if (anim.playing) setPlaying(false); else writeURL();
    draw();
    updateCursor(true);
  });
  $("copy-link").addEventListener("click", async () => {
    try { await navigator.clipboard.writeText(location.href); $("copy-link").textContent = "Link copied"; }
    catch (e) { window.prompt("Copy this link:", location.href); }
    setTimeout(() => { $("copy-link").textContent = "Copy link to this view"; }, 1500);
  });
  setupDrag();
  window.addEventListener("resize", draw);
  requestAnimationFrame(frame);
  update();
}

document.addEventListener("DOMContentLoaded", init);
