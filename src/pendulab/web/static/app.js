// pendulab explorer: the page reads its state from the URL, asks the JSON API, and draws.
// It computes nothing about the pendulum itself: every number shown comes from /api/.
"use strict";

const FIELDS = ["length", "amplitude", "unit", "g", "method", "step", "t_max"];
const PLOT_POINTS = 3000;
const PLOT_CONFIG = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ["lasso2d", "select2d"] };
const FONT = { family: "system-ui, -apple-system, Segoe UI, Roboto, DejaVu Sans, sans-serif", size: 12, color: "#1d2330" };
const COLORS = { theta: "#2f6fdb", phase: "#2f6fdb", p: "#d1495b", bracket: "#8a94a6", linear: "#e69f00", cubic: "#009e73", exact: "#1d2330" };
const PLAIN_NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

const $ = (id) => document.getElementById(id);
let config = null;
let state = {};
let sim = null;                 // the last good /api/simulate answer
let seq = 0;                    // drops answers to requests that are no longer current
let timer = null;
const anim = { playing: true, t: 0, last: null, speed: 1 };

// ---------- state <-> URL <-> form ----------
function readURL() {
  const q = new URLSearchParams(location.search);
  for (const k of FIELDS) state[k] = q.get(k) ?? config.defaults[k];
  const speed = Number(q.get("speed"));
  anim.speed = [0.1, 0.25, 0.5, 1, 2, 4].includes(speed) ? speed : 1;
}

function writeForm() {
  for (const k of FIELDS) $(k).value = state[k];
  $("speed").value = String(anim.speed);
  markPreset();
}

function readForm() {
  for (const k of FIELDS) state[k] = $(k).value.trim();
}

function pageQuery() {
  const q = new URLSearchParams();
  for (const k of FIELDS) q.set(k, state[k]);
  if (anim.speed !== 1) q.set("speed", String(anim.speed));
  return q.toString();
}

function apiAmplitude() {
  const a = state.amplitude;
  return state.unit === "deg" && PLAIN_NUMBER.test(a) ? a + "deg" : a;
}

function apiQuery(extra = {}) {
  const q = new URLSearchParams({
    length: state.length, amplitude: apiAmplitude(), g: state.g,
    method: state.method, step: state.step, t_max: state.t_max, ...extra,
  });
  return q.toString();
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
  history.replaceState(null, "", "?" + pageQuery());
  markPreset();
  const my = ++seq;
  const amplitudeQuery = apiAmplitude();
  $("status").textContent = "Simulating…";
  let res;
  try {
    res = await getJSON("/api/simulate?" + apiQuery({ points: PLOT_POINTS }));
  } catch (e) {
    if (my === seq) showError({ message: "the pendulab server does not answer: is `pendulab serve` still running?" });
    return;
  }
  if (my !== seq) return;
  if (!res.ok) { showError(res.body.error); return; }
  clearError();
  sim = res.body;
  sim.amplitudeQuery = amplitudeQuery;
  $("csv").href = "/api/trajectory.csv?" + apiQuery();
  $("csv").setAttribute("aria-disabled", "false");
  const thinned = sim.stride > 1 ? `, every ${sim.stride}th of ${sim.n_steps + 1} plotted` : "";
  $("status").textContent = `${sim.n_steps.toLocaleString("en")} steps of ${sim.input.method}${thinned}.`;
  renderPeriods(sim.period);
  renderTheta(sim);
  renderPhase(sim);
  renderEstimates(sim.period);
  if (anim.t > sim.t[sim.t.length - 1]) anim.t = 0;
  draw();
  updateConvergence(my);
}

async function updateConvergence(my) {
  const T = sim.period.exact;
  // Steps from T/30 down to T/30000, four per decade, plus the step in use.
  const steps = [];
  for (let k = 0; k <= 12; k++) steps.push(T / Math.pow(10, 1.5 + k / 4));
  steps.push(sim.input.step);
  const q = new URLSearchParams({
    length: state.length, amplitude: apiAmplitude(), g: state.g, method: state.method,
    steps: steps.map((h) => h.toPrecision(6)).join(","),
  });
  let res;
  try { res = await getJSON("/api/convergence?" + q.toString()); } catch (e) { return; }
  if (my !== seq) return;
  renderConvergence(res.ok ? res.body : null, res.ok ? null : res.body.error);
}

function showError(err) {
  for (const k of FIELDS) $(k).classList.remove("invalid");
  if (err && err.field && $(err.field)) $(err.field).classList.add("invalid");
  const e = $("error");
  e.textContent = err ? err.message : "unknown error";
  e.hidden = false;
  $("status").textContent = "";
  $("csv").setAttribute("aria-disabled", "true");
}

function clearError() {
  for (const k of FIELDS) $(k).classList.remove("invalid");
  $("error").hidden = true;
}

// ---------- numbers ----------
const fix = (x, d = 12) => (x === null || x === undefined ? "–" : x.toPrecision(d));
const sci = (x) => (x === null || x === undefined ? "–" : x === 0 ? "0" : x.toExponential(2));
const short = (x) => String(Number(x.toPrecision(12)));

function renderPeriods(p) {
  $("period-exact").textContent = fix(p.exact);
  $("period-small").textContent = fix(p.small_angle);
  const e = p.estimate;
  const set = (id, v) => { $(id).textContent = v; };
  if (!e) {
    for (const k of ["bracket", "linear", "cubic"]) { set("est-" + k, "–"); set("err-" + k, "–"); set("rel-" + k, "–"); }
    $("estimate-note").textContent = "No period from this simulation: " + p.reason;
    return;
  }
  set("est-bracket", `[${short(e.bracket[0])}, ${short(e.bracket[1])}]`);
  set("est-linear", fix(e.linear));
  set("est-cubic", fix(e.cubic));
  for (const [k, err] of [["bracket", e.errors.bracket_mid], ["linear", e.errors.linear], ["cubic", e.errors.cubic]]) {
    set("err-" + k, sci(err));
    set("rel-" + k, err === null ? "–" : sci(err / p.exact));
  }
  $("estimate-note").textContent =
    `Sign change of θ′ at step j = ${e.j} (h = ${short(e.step)} s). Bracket error: of its midpoint. ` +
    `Interpolation error estimate of p(0), from a 5th node: ${sci(e.cubic_error_estimate)} s.`;
}

// ---------- plots ----------
function layout(title, xtitle, ytitle, extra = {}) {
  return {
    title: { text: title, font: { size: 14 }, x: 0.02, xanchor: "left" },
    font: FONT, margin: { l: 64, r: 16, t: 40, b: 48 }, paper_bgcolor: "#fff", plot_bgcolor: "#fff",
    xaxis: { title: { text: xtitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc" },
    yaxis: { title: { text: ytitle }, gridcolor: "#eef1f5", zerolinecolor: "#c9d0dc" },
    legend: { orientation: "h", y: -0.22, x: 0 }, showlegend: false, ...extra,
  };
}

function renderTheta(s) {
  const T = s.period.exact;
  const shapes = [];
  const annotations = [];
  for (let k = 1; k * T <= s.input.t_max; k++) {
    shapes.push({ type: "line", x0: k * T, x1: k * T, yref: "paper", y0: 0, y1: 1, line: { dash: "dot", color: COLORS.p, width: 1 } });
    annotations.push({ x: k * T, yref: "paper", y: 1, text: k === 1 ? "T" : `${k}T`, showarrow: false, yanchor: "bottom", font: { color: COLORS.p } });
  }
  Plotly.react("plot-theta", [
    { x: s.t, y: s.theta, mode: "lines", line: { color: COLORS.theta, width: 2 }, name: "θ(t)", hovertemplate: "t = %{x:.4f} s<br>θ = %{y:.6f} rad<extra></extra>" },
  ], layout("Angle θ(t)", "t (s)", "θ (rad)", { shapes, annotations }), PLOT_CONFIG);
}

function renderPhase(s) {
  const a = s.input.amplitude;
  Plotly.react("plot-phase", [
    { x: s.theta, y: s.omega, mode: "lines", line: { color: COLORS.phase, width: 2 }, name: "(θ, θ′)", hovertemplate: "θ = %{x:.5f} rad<br>θ′ = %{y:.5f} rad/s<extra></extra>" },
    { x: [a], y: [0], mode: "markers", marker: { symbol: "circle-open", size: 16, line: { width: 2.5, color: COLORS.p } }, name: "P = (α, 0)", hovertemplate: "P = (α, 0)<br>α = %{x:.6f} rad<extra></extra>" },
  ], layout("Phase portrait (θ, θ′)", "θ (rad)", "θ′ (rad/s)", {
    annotations: [{ x: a, y: 0, text: "P = (α, 0)", showarrow: true, arrowhead: 0, ax: 34, ay: -26, font: { color: COLORS.p } }],
  }), PLOT_CONFIG);
}

function renderEstimates(p) {
  const e = p.estimate;
  const T = p.exact;
  if (!e) {
    Plotly.react("plot-estimates", [], layout("Period estimates − exact T", "", "estimate − T (s)", {
      annotations: [{ text: "no period from this simulation", showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }), PLOT_CONFIG);
    return;
  }
  const half = (e.bracket[1] - e.bracket[0]) / 2;
  const traces = [
    { x: ["bracket [t<sub>j</sub>, t<sub>j+1</sub>]"], y: [e.bracket_mid - T], mode: "markers", marker: { color: COLORS.bracket, size: 9, symbol: "line-ew-open" },
      error_y: { type: "data", array: [half], color: COLORS.bracket, thickness: 2, width: 10 }, hovertemplate: `bracket [${e.bracket[0]}, ${e.bracket[1]}] s<extra></extra>` },
    { x: ["linear"], y: [e.linear - T], mode: "markers", marker: { color: COLORS.linear, size: 11 }, hovertemplate: `linear ${e.linear} s<br>error %{y:.3e} s<extra></extra>` },
    { x: ["cubic p(0)"], y: [e.cubic - T], mode: "markers", marker: { color: COLORS.cubic, size: 11, symbol: "diamond" },
      error_y: { type: "data", array: [Math.abs(e.cubic_error_estimate || 0)], color: COLORS.cubic }, hovertemplate: `cubic ${e.cubic} s<br>error %{y:.3e} s<extra></extra>` },
  ];
  Plotly.react("plot-estimates", traces, layout(`Period estimates − exact T = ${T.toPrecision(10)} s`, "", "estimate − T (s)", {
    shapes: [{ type: "line", xref: "paper", x0: 0, x1: 1, y0: 0, y1: 0, line: { color: COLORS.exact, width: 1.5, dash: "dash" } }],
    annotations: [{ xref: "paper", x: 1, y: 0, text: "exact (AGM)", showarrow: false, xanchor: "right", yanchor: "bottom", font: { size: 11 } }],
    yaxis: { title: { text: "estimate − T (s)" }, gridcolor: "#eef1f5", zeroline: false, exponentformat: "e" },
  }), PLOT_CONFIG);
}

function renderConvergence(body, err) {
  if (!body) {
    Plotly.react("plot-convergence", [], layout("Period error vs step h", "h (s)", "|error| (s)", {
      annotations: [{ text: err ? err.message : "no data", showarrow: false, xref: "paper", yref: "paper", x: 0.5, y: 0.5 }],
      xaxis: { visible: false }, yaxis: { visible: false },
    }), PLOT_CONFIG);
    return;
  }
  const rows = body.rows.filter((r) => r.estimate);
  if (!rows.length) { renderConvergence(null, { message: "no period from any of these steps" }); return; }
  const series = (key, name, color, symbol) => {
    const pts = rows.filter((r) => r.estimate.errors[key] > 0);
    return { x: pts.map((r) => r.step), y: pts.map((r) => r.estimate.errors[key]), mode: "lines+markers", name,
      line: { color, width: 2 }, marker: { color, size: 7, symbol }, hovertemplate: `${name}<br>h = %{x:.3e} s<br>|error| = %{y:.3e} s<extra></extra>` };
  };
  // Cubic first, linear dashed on top: where the Taylor error dominates the two coincide.
  const traces = [
    series("bracket_mid", "bracket midpoint", COLORS.bracket, "square"),
    series("cubic", "inverse cubic p(0)", COLORS.cubic, "diamond"),
    series("linear", "linear", COLORS.linear, "circle-open"),
  ];
  traces[2].line.dash = "dash";
  // A reference line of slope p = the method's order, through the cubic error at the largest step.
  const first = rows.find((r) => r.estimate.errors.cubic > 0);
  if (first && rows.length > 1) {
    const h0 = first.step, e0 = first.estimate.errors.cubic, h1 = rows[rows.length - 1].step;
    traces.push({ x: [h0, h1], y: [e0, e0 * Math.pow(h1 / h0, body.order)], mode: "lines", name: `slope ${body.order} (order of ${body.method})`,
      line: { color: "#b8c0cc", dash: "dash", width: 1.5 }, hoverinfo: "skip" });
  }
  const h = sim ? sim.input.step : null;
  Plotly.react("plot-convergence", traces, layout(`Period error vs step h (${body.method})`, "h (s)", "|estimate − T| (s)", {
    xaxis: { type: "log", title: { text: "h (s)" }, gridcolor: "#eef1f5", exponentformat: "power" },
    yaxis: { type: "log", title: { text: "|estimate − T| (s)" }, gridcolor: "#eef1f5", exponentformat: "power" },
    showlegend: true, legend: { x: 1, xanchor: "right", y: 0.02, yanchor: "bottom", bgcolor: "rgba(255,255,255,.85)", font: { size: 11 } },
    shapes: h ? [{ type: "line", x0: h, x1: h, yref: "paper", y0: 0, y1: 1, line: { color: COLORS.p, dash: "dot", width: 1 } }] : [],
    annotations: h ? [{ x: Math.log10(h), yref: "paper", y: 1, text: "h in use", showarrow: false, yanchor: "bottom", font: { color: COLORS.p, size: 11 } }] : [],
  }), PLOT_CONFIG);
}

// ---------- animation ----------
function thetaAt(s, t) {
  // Linear interpolation between the (thinned) simulated points: drawing only.
  const ts = s.t, th = s.theta;
  let lo = 0, hi = ts.length - 1;
  if (t <= ts[0]) return th[0];
  if (t >= ts[hi]) return th[hi];
  while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (ts[mid] <= t) lo = mid; else hi = mid; }
  const w = (t - ts[lo]) / (ts[hi] - ts[lo]);
  return th[lo] + w * (th[hi] - th[lo]);
}

function draw() {
  const c = $("canvas");
  const dpr = window.devicePixelRatio || 1;
  const W = c.clientWidth || 420, H = Math.round(W * 340 / 420);
  if (c.width !== Math.round(W * dpr)) { c.width = Math.round(W * dpr); c.height = Math.round(H * dpr); }
  const g = c.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, W, H);
  const px = W / 2, py = H / 2, R = H / 2 - 26;
  // The bob's circle and the amplitude rays.
  g.strokeStyle = "#d5dbe5"; g.setLineDash([4, 5]); g.lineWidth = 1;
  g.beginPath(); g.arc(px, py, R, 0, 2 * Math.PI); g.stroke();
  g.setLineDash([]);
  if (!sim) return;
  const a = sim.input.amplitude;
  g.strokeStyle = "rgba(209, 73, 91, .35)";
  for (const s of [-1, 1]) { g.beginPath(); g.moveTo(px, py); g.lineTo(px + R * Math.sin(s * a), py + R * Math.cos(s * a)); g.stroke(); }
  g.beginPath(); g.arc(px, py, 34, Math.PI / 2 - a, Math.PI / 2 + a); g.stroke();
  const th = thetaAt(sim, anim.t);
  const bx = px + R * Math.sin(th), by = py + R * Math.cos(th);
  // Rod, pivot, bob.
  g.strokeStyle = "#39425a"; g.lineWidth = 2.5;
  g.beginPath(); g.moveTo(px, py); g.lineTo(bx, by); g.stroke();
  g.fillStyle = "#39425a"; g.beginPath(); g.arc(px, py, 4.5, 0, 2 * Math.PI); g.fill();
  const grad = g.createRadialGradient(bx - 4, by - 4, 2, bx, by, 15);
  grad.addColorStop(0, "#7fa8f0"); grad.addColorStop(1, "#2f6fdb");
  g.fillStyle = grad; g.beginPath(); g.arc(bx, by, 14, 0, 2 * Math.PI); g.fill();
  g.fillStyle = "#5d6678"; g.font = "12px system-ui, sans-serif";
  g.fillText(`l = ${short(sim.input.length)} m`, 10, 18);
  g.fillText(`α = ${short(sim.input.amplitude_deg)}°`, 10, 34);
  $("clock").textContent = `t = ${anim.t.toFixed(2)} s   θ = ${(th * 180 / Math.PI).toFixed(1)}°`;
}

function frame(ts) {
  if (anim.last !== null && anim.playing && sim) {
    const tEnd = sim.t[sim.t.length - 1];
    anim.t += ((ts - anim.last) / 1000) * anim.speed;
    if (anim.t > tEnd) anim.t = tEnd > 0 ? anim.t % tEnd : 0;
  }
  anim.last = ts;
  if (anim.playing) draw();
  requestAnimationFrame(frame);
}

// ---------- controls ----------
function markPreset() {
  const g = Number($("g").value);
  for (const b of $("g-presets").children) b.classList.toggle("active", Number(b.dataset.g) === g);
}

function convertAmplitude() {
  // Convert the shown amplitude with the server's own reading of it (the last good answer).
  const now = $("unit").value, was = now === "deg" ? "rad" : "deg";
  const text = $("amplitude").value.trim();
  const asSent = was === "deg" && PLAIN_NUMBER.test(text) ? text + "deg" : text;
  if (sim && asSent === sim.amplitudeQuery) {
    $("amplitude").value = short(now === "deg" ? sim.input.amplitude_deg : sim.input.amplitude);
  }
}

async function init() {
  config = (await getJSON("/api/config")).body;
  for (const m of config.methods) {
    const o = document.createElement("option");
    o.value = m.name; o.textContent = `${m.name} (order ${m.order})`;
    $("method").append(o);
  }
  for (const [name, g] of Object.entries(config.g_presets)) {
    const b = document.createElement("button");
    b.type = "button"; b.dataset.g = g; b.textContent = name[0].toUpperCase() + name.slice(1);
    b.title = `g = ${g} m/s²`;
    b.addEventListener("click", () => { $("g").value = String(g); schedule(0); });
    $("g-presets").append(b);
  }
  readURL();
  writeForm();
  for (const k of ["length", "amplitude", "g", "step", "t_max"]) $(k).addEventListener("input", () => schedule());
  $("method").addEventListener("change", () => schedule(0));
  $("unit").addEventListener("change", () => { convertAmplitude(); schedule(0); });
  $("inputs").addEventListener("submit", (ev) => { ev.preventDefault(); schedule(0); });
  $("play").addEventListener("click", () => {
    anim.playing = !anim.playing;
    $("play").textContent = anim.playing ? "Pause" : "Play";
  });
  $("speed").addEventListener("change", () => {
    anim.speed = Number($("speed").value);
    history.replaceState(null, "", "?" + pageQuery());
  });
  $("copy-link").addEventListener("click", async () => {
    try { await navigator.clipboard.writeText(location.href); $("copy-link").textContent = "Link copied"; }
    catch (e) { window.prompt("Copy this link:", location.href); }
    setTimeout(() => { $("copy-link").textContent = "Copy link to this view"; }, 1500);
  });
  window.addEventListener("resize", draw);
  requestAnimationFrame(frame);
  update();
}

document.addEventListener("DOMContentLoaded", init);
