// pendulab explorer, the lab: a photogate on each pendulum, a stopwatch, step buttons, velocity
// and acceleration vectors, a ruler and a protractor to drag, damping, drag and mass, the
// energies in J with the heat, and Planet X (a hidden g to find by timing).
// Loaded after app.js; it reads app.js's globals (sims, anim, view, state, stateAt, draw, tick,
// setPlaying, schedule, writeURL, word, local, typed, short, rulerText, niceCeil, ERROR_FIELDS, $).
//
// The photogates time the simulation's own data, never the frames drawn: the crossings of the
// bottom are computed once per answer from the samples the server sent (the cubic Hermite
// interpolant of theta and theta' between two samples, the same curve the animation draws),
// and each frame shows the last period completed at the time shown. So the reading is the
// same at any speed, with any frame dropped.
"use strict";

window.lab = (() => {
  const FIELDS = ["damping", "drag", "mass"];
  const TOLERANCE = 2;          // Planet X: a typed g within this many % of the hidden one is right
  const FLASH_MS = 120;         // a gate's beam is lit this long after the bob crosses it
  const TURN = 2 * Math.PI;
  const lab = {
    gates: [[], []],            // per pendulum: crossings {t, dir, period}
    shown: [-1, -1],            // the crossing each gate shows
    lit: [0, 0],
    watch: { running: false, elapsed: 0, last: null },
    planet: null,               // { seed, g } on Planet X
    show: { vectors: false, ruler: false, protractor: false },
    ruler: null, protractor: null, drag: null, geo: null,
  };

  // ---------- the crossings of the bottom, from the samples (theta = 0 modulo a turn) ----------
  function hermite(a, b, d, s) {
    const s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * a.theta + (s3 - 2 * s2 + s) * d * a.omega + (-2 * s3 + 3 * s2) * b.theta + (s3 - s2) * d * b.omega;
  }

  /** Every time the bob passes the bottom, with its direction and the period since the last pass the same way. */
  function crossings(fr) {
    const out = [];
    if (!fr || !(fr.per_period >= 8)) return out;  // too coarse to interpolate: the animation jumps (app.js says so)
    const ts = fr.t, th = fr.theta, om = fr.omega;
    const last = { 1: null, "-1": null };
    for (let i = 0; i + 1 < ts.length; i++) {
      if (th[i] === null || th[i + 1] === null || om[i] === null || om[i + 1] === null) break;
      const a = { theta: th[i], omega: om[i] }, b = { theta: th[i + 1], omega: om[i + 1] };
      const lo = Math.min(a.theta, b.theta), hi = Math.max(a.theta, b.theta);
      for (let k = Math.ceil(lo / TURN); k <= Math.floor(hi / TURN); k++) {
        const y = k * TURN;
        if ((a.theta - y < 0) === (b.theta - y < 0)) continue;  // touches without crossing
        const d = ts[i + 1] - ts[i], up = b.theta > a.theta;
        let s0 = 0, s1 = 1;  // bisection on the interpolant: 50 halvings, below a nanosecond
        for (let it = 0; it < 50; it++) {
          const m = 0.5 * (s0 + s1);
          if ((hermite(a, b, d, m) < y) === up) s0 = m; else s1 = m;
        }
        const t = ts[i] + 0.5 * (s0 + s1) * d, dir = up ? 1 : -1;
        const prev = last[dir];
        out.push({ t, dir, period: prev === null ? null : t - prev });
        last[dir] = t;
      }
    }
    return out;
  }

  /** The index of the last crossing at or before time t (-1: none yet). */
  function lastAt(list, t) {
    let lo = -1, hi = list.length;
    while (hi - lo > 1) { const m = (lo + hi) >> 1; if (list[m].t <= t) lo = m; else hi = m; }
    return lo;
  }

  function gateText(i, c) {
    const name = word(i === 0 ? "lab.gate1" : "lab.gate2");
    if (!c || c.period === null) return `${name}: ${word("lab.gate-waiting")}`;
    const sim = i === 0 ? sims.a : sims.second;
    const agm = i === 0 ? sim.period.period : sim.period;
    const text = `${name}: ${word("lab.gate-period", { period: local(c.period.toFixed(4)) })}`;
    return lab.planet ? text : `${text} · ${word("lab.gate-agm", { period: local(agm.toFixed(4)) })}`;
  }

  function showGates() {
    const boxes = [$("gate"), $("gate2")];
    for (const i of [0, 1]) {
      const box = boxes[i];
      const on = i === 0 ? !!sims.a : !!sims.second;
      if (i === 1) $("gate2-row").hidden = !on;
      if (!on) { box.dataset.period = ""; continue; }
      const list = lab.gates[i];
      let j = lastAt(list, anim.t);
      while (j >= 0 && list[j].period === null) j--;
      const c = j >= 0 ? list[j] : null;
      if (lastAt(list, anim.t) !== lab.shown[i]) { lab.shown[i] = lastAt(list, anim.t); lab.lit[i] = performance.now(); }
      box.textContent = gateText(i, c);
      box.dataset.period = c ? String(c.period) : "";
      box.dataset.t = c ? String(c.t) : "";  // the pass that ended the period shown
    }
    const damped = sims.a && (sims.a.input.damping || sims.a.input.drag);
    const note = $("lab-damped");
    note.hidden = !damped || lab.planet !== null;
    if (!note.hidden) {
      const p = $("gate").dataset.period;
      note.textContent = word("lab.gate-damped", { agm: local(sims.a.period.period.toFixed(4)),
        period: p ? local(Number(p).toFixed(4)) : "–" });
    }
  }

  // ---------- the stopwatch: the simulation's time between Start and Stop ----------
  function runWatch() {
    const w = lab.watch;
    if (w.running && sims.a) {
      const f = sims.a.frames.t, tEnd = f[f.length - 1];
      let dt = anim.t - w.last;
      if (dt < -0.5 * tEnd) dt += tEnd;  // the animation went round to 0
      if (dt > 0) w.elapsed += dt;
    }
    w.last = anim.t;
    $("watch").textContent = `${local(w.elapsed.toFixed(2))} s`;
  }

  // ---------- the energies in J: the page's energyOf (in m g l) times m g l; the heat E0 - E ----------
  function energies() {
    const s = sims.a, box = $("lab-energy");
    if (!s) return;
    const { length: l, g, mass: m, amplitude: a } = s.input;
    const damped = s.input.damping || s.input.drag;
    // theta'' of the undamped pendulum between the samples; linear theta' where it is damped.
    const st = energyOf(stateAt(s.frames, anim.t, s.frames.theta, s.frames.omega, damped ? null : g / l), s);
    const mgl = m * g * l, E0 = mgl * energyOf({ theta: a, omega: s.launch ? s.launch.omega0 : 0 }, s).E;
    const K = st ? mgl * st.K : null, U = st ? mgl * st.U : null;
    const rows = { K, U, E: K === null ? null : K + U, Q: K === null ? null : E0 - (K + U) };
    const top = 1.1 * Math.max(E0, ...Object.values(rows).filter((x) => x !== null));
    for (const [k, x] of Object.entries(rows)) {
      box.querySelector(`[data-bar="${k}"]`).style.width = x === null || !(top > 0) ? "0" : `${Math.min(100, Math.max(0, 100 * x / top)).toFixed(1)}%`;
      box.querySelector(`[data-value="${k}"]`).textContent = x === null ? "–" : `${local(x.toPrecision(4))} J`;
    }
  }

  // ---------- drawing: the gates' beams, the ruler, the protractor; the vectors over the bob ----------
  function beam(g, pv, R, lit) {
    g.strokeStyle = lit ? "#d1495b" : "rgba(209, 73, 91, .55)"; g.lineWidth = lit ? 3 : 1.5; g.setLineDash([3, 3]);
    g.beginPath(); g.moveTo(pv.x - 22, pv.y + R); g.lineTo(pv.x + 22, pv.y + R); g.stroke(); g.setLineDash([]);
    g.fillStyle = "#39425a"; g.fillRect(pv.x - 26, pv.y + R - 6, 4, 12); g.fillRect(pv.x + 22, pv.y + R - 6, 4, 12);
  }

  /** The ruler's length (m) and size on screen: a round length that fits 80 % of the width. */
  function rulerSize(geo) {
    const perM = geo.radii[0] / geo.lengths[0];
    let L = niceCeil(geo.lengths[0]);
    while (L * perM > 0.8 * geo.W) L = niceCeil(L / 2.01);
    return { L, px: L * perM };
  }

  function drawRuler(g, geo) {
    const { L, px } = rulerSize(geo);
    const r = lab.ruler || (lab.ruler = { x: 10, y: geo.H - 34 });
    g.fillStyle = "rgba(255, 236, 170, .85)"; g.strokeStyle = "#8a6d1a"; g.lineWidth = 1;
    g.fillRect(r.x, r.y, px, 22); g.strokeRect(r.x, r.y, px, 22);
    g.beginPath();
    for (let k = 0; k <= 10; k++) { const x = r.x + px * k / 10; g.moveTo(x, r.y); g.lineTo(x, r.y + (k % 5 ? 6 : 10)); }
    g.stroke();
    g.fillStyle = "#5a4510"; g.font = "11px system-ui, sans-serif"; g.textAlign = "right";
    g.fillText(rulerText(L), r.x + px - 3, r.y + 19); g.textAlign = "left";
    r.w = px; r.h = 22;
  }

  function drawProtractor(g, geo) {
    const p = lab.protractor || (lab.protractor = { x: geo.pivots[0].x, y: geo.pivots[0].y });
    p.r = Math.max(40, Math.min(90, 0.6 * geo.radii[0]));
    g.fillStyle = "rgba(170, 210, 255, .35)"; g.strokeStyle = "#2f6fdb"; g.lineWidth = 1;
    // Angles from the downward vertical, as theta: the lower half disc, -90 to 90 degrees.
    g.beginPath(); g.moveTo(p.x + p.r, p.y); g.arc(p.x, p.y, p.r, 0, Math.PI); g.closePath(); g.fill(); g.stroke();
    g.beginPath();
    for (let deg = -90; deg <= 90; deg += 5) {
      const a = deg * Math.PI / 180, len = deg % 30 === 0 ? 12 : deg % 10 === 0 ? 8 : 4;
      g.moveTo(p.x + p.r * Math.sin(a), p.y + p.r * Math.cos(a));
      g.lineTo(p.x + (p.r - len) * Math.sin(a), p.y + (p.r - len) * Math.cos(a));
    }
    g.stroke();
    g.fillStyle = "#1d4fa8"; g.font = "10px system-ui, sans-serif"; g.textAlign = "center";
    for (const deg of [-60, -30, 0, 30, 60]) {
      const a = deg * Math.PI / 180;
      g.fillText(`${Math.abs(deg)}°`, p.x + (p.r - 22) * Math.sin(a), p.y + (p.r - 22) * Math.cos(a) + 3);
    }
    g.textAlign = "left";
  }

  function arrow(g, x, y, dx, dy, color, text) {
    const n = Math.hypot(dx, dy);
    if (!(n > 2)) return;
    const ux = dx / n, uy = dy / n;
    g.strokeStyle = color; g.fillStyle = color; g.lineWidth = 2.5;
    g.beginPath(); g.moveTo(x, y); g.lineTo(x + dx, y + dy); g.stroke();
    g.beginPath(); g.moveTo(x + dx, y + dy); g.lineTo(x + dx - 9 * ux + 4.5 * uy, y + dy - 9 * uy - 4.5 * ux);
    g.lineTo(x + dx - 9 * ux - 4.5 * uy, y + dy - 9 * uy + 4.5 * ux); g.closePath(); g.fill();
    g.font = "bold 12px system-ui, sans-serif"; g.fillText(text, x + dx + 4 * ux + 3, y + dy + 4 * uy + 4);
  }

  /** v = l theta' along the tangent; a = l theta'' along it and l theta'^2 towards the pivot.
   * Drawn over sqrt(l/g) (v) and l/g (a): both arrows as long as the swing's amplitude at most. */
  function drawVectors(g, geo) {
    const s = sims.a;
    const { length: l, g: gr, damping, drag } = s.input;
    const st = stateAt(s.frames, anim.t, s.frames.theta, s.frames.omega, damping || drag ? null : gr / l);
    if (!st || st.theta === null) return;
    const th = geo.side * st.theta, w = geo.side * st.omega;
    const acc = -gr / l * Math.sin(th) - damping * w - drag * w * Math.abs(w);
    const pv = geo.pivots[0], R = geo.radii[0], tau = Math.sqrt(l / gr);
    const bx = pv.x + R * Math.sin(th), by = pv.y + R * Math.cos(th);
    const tx = Math.cos(th), ty = -Math.sin(th);  // the direction of increasing theta on screen
    arrow(g, bx, by, R * w * tau * tx, R * w * tau * ty, "#009e73", word("lab.velocity"));
    const at = R * acc * tau * tau, ac = R * w * w * tau * tau;
    arrow(g, bx, by, at * tx - ac * Math.sin(th), at * ty - ac * Math.cos(th), "#b3261e", word("lab.acceleration"));
  }

  // ---------- dragging the ruler and the protractor (before app.js's drag of the bob) ----------
  function point(ev) {
    const r = $("canvas").getBoundingClientRect();
    return { x: ev.clientX - r.left, y: ev.clientY - r.top };
  }

  function hit(p) {
    const r = lab.ruler, q = lab.protractor;
    if (lab.show.ruler && r && p.x >= r.x && p.x <= r.x + r.w && p.y >= r.y - 4 && p.y <= r.y + r.h + 4) return "ruler";
    if (lab.show.protractor && q && Math.hypot(p.x - q.x, p.y - q.y) <= q.r && p.y >= q.y - 6) return "protractor";
    return null;
  }

  function setupDrag() {
    const c = $("canvas");
    c.addEventListener("pointerdown", (ev) => {
      const p = point(ev), what = hit(p);
      if (!what) return;
      ev.stopImmediatePropagation();  // the tool, not the bob
      ev.preventDefault();
      const o = lab[what];
      lab.drag = { what, dx: p.x - o.x, dy: p.y - o.y };
      c.setPointerCapture(ev.pointerId);
    }, { capture: true });
    c.addEventListener("pointermove", (ev) => {
      if (!lab.drag) return;
      ev.stopImmediatePropagation();
      const p = point(ev), o = lab[lab.drag.what];
      o.x = p.x - lab.drag.dx; o.y = p.y - lab.drag.dy;
      draw();
    }, { capture: true });
    const end = (ev) => { if (lab.drag) { ev.stopImmediatePropagation(); lab.drag = null; } };
    c.addEventListener("pointerup", end, { capture: true });
    c.addEventListener("pointercancel", end, { capture: true });
  }

  // ---------- step forward and back ----------
  function stepBy(sign) {
    if (!sims.a) return;
    if (anim.playing) setPlaying(false);
    const f = sims.a.frames.t, tEnd = f[f.length - 1];
    const d = $("lab-by").value === "step" ? sims.a.input.step : anim.speed / 60;
    anim.t = Math.min(tEnd, Math.max(0, anim.t + sign * d));
    tick();
    writeURL();
  }

  // ---------- Planet X: g from a seed, never shown, never in the URL ----------
  /** g in [2, 25) m/s^2, to 0.01, from the seed's FNV-1a hash (the same g for the same link). */
  function planetG(seed) {
    let h = 0x811c9dc5;
    for (const ch of String(seed)) { h ^= ch.codePointAt(0); h = Math.imul(h, 0x01000193) >>> 0; }
    return Math.round((2 + 23 * h / 4294967296) * 100) / 100;
  }

  function setPlanet(seed) {
    lab.planet = seed === null ? null : { seed, g: planetG(seed) };
    document.body.classList.toggle("planet", lab.planet !== null);
    $("g").disabled = lab.planet !== null;
    $("planet-go").hidden = lab.planet !== null;
    $("planet-leave").hidden = lab.planet === null;
    $("planet-form").hidden = lab.planet === null;
    $("planet-result").textContent = "";
  }

  function checkPlanet() {
    const text = $("planet-g").value.trim().replace(",", ".");
    const x = Number(text);
    const out = $("planet-result");
    if (!text || !(x > 0) || !Number.isFinite(x)) { out.textContent = word("lab.planet-bad"); out.dataset.right = ""; return; }
    const right = Math.abs(x - lab.planet.g) <= TOLERANCE / 100 * lab.planet.g;
    out.textContent = word(right ? "lab.planet-right" : "lab.planet-wrong", { g: local(String(x)), tolerance: local(String(TOLERANCE)) });
    out.dataset.right = right ? "1" : "0";
  }

  // ---------- the hooks app.js calls ----------
  /** Add the lab's parameters to a query: `which` is "a", "b" (the simulations), "second" or "url". */
  function query(q, which) {
    if (which !== "second") {
      for (const k of FIELDS) {
        const v = typed($(k).value.trim());
        if (v !== "") q.set(k, v);
      }
    }
    if (which === "url") {
      for (const k of ["vectors", "ruler", "protractor"]) if (lab.show[k]) q.set(k, "1");
      if (lab.planet) { q.delete("g"); q.set("planet", lab.planet.seed); }
    } else if (lab.planet && (which !== "second" || !state.g2)) {
      q.set("g", String(lab.planet.g));
    }
  }

  function data() {
    lab.gates = [crossings(sims.a && sims.a.frames), crossings(sims.second && sims.second.frames)];
    lab.shown = [-1, -1];
    frame();
  }

  function frame() {
    showGates();
    runWatch();
    energies();
  }

  function drawUnder(g, geo) {
    lab.geo = geo;
    const lit = (i) => performance.now() - lab.lit[i] < FLASH_MS;
    if (sims.a) beam(g, geo.pivots[0], geo.radii[0], lit(0));
    if (sims.a && sims.second && geo.pivots[1]) beam(g, geo.pivots[1], geo.radii[1], lit(1));
    if (!sims.a) return;
    if (lab.show.protractor) drawProtractor(g, geo);
    if (lab.show.ruler) drawRuler(g, geo);
  }

  function drawOver(g, geo) {
    if (lab.show.vectors && sims.a) drawVectors(g, geo);
  }

  function init() {
    const q = new URLSearchParams(location.search);
    for (const k of FIELDS) $(k).value = local(q.get(k) || "");
    for (const k of ["vectors", "ruler", "protractor"]) { lab.show[k] = q.get(k) === "1"; $("lab-" + k).checked = lab.show[k]; }
    const seed = q.get("planet");
    setPlanet(seed && /^[A-Za-z0-9]{1,12}$/.test(seed) ? seed : null);
    ERROR_FIELDS.push(...FIELDS);  // a 422 naming one of them shows under its field
    for (const k of FIELDS) $(k).addEventListener("input", () => schedule());
    for (const k of ["vectors", "ruler", "protractor"]) {
      $("lab-" + k).addEventListener("change", () => { lab.show[k] = $("lab-" + k).checked; writeURL(); draw(); });
    }
    $("lab-back").addEventListener("click", () => stepBy(-1));
    $("lab-forward").addEventListener("click", () => stepBy(1));
    $("watch-start").addEventListener("click", () => {
      lab.watch.running = !lab.watch.running;
      lab.watch.last = anim.t;
      $("watch-start").textContent = word(lab.watch.running ? "lab.stop" : "lab.start");
    });
    $("watch-reset").addEventListener("click", () => { lab.watch.elapsed = 0; lab.watch.last = anim.t; runWatch(); });
    $("planet-go").addEventListener("click", () => { setPlanet(String(Math.floor(1e4 + 9e4 * Math.random()))); schedule(0); });
    $("planet-leave").addEventListener("click", () => { setPlanet(null); schedule(0); });
    $("planet-form").addEventListener("submit", (ev) => { ev.preventDefault(); checkPlanet(); });
    setupDrag();
    // Open on a screen wide enough for it beside the swing, or where the link uses the lab.
    const used = FIELDS.concat(["vectors", "ruler", "protractor", "planet"]).some((k) => q.has(k));
    if (used || window.matchMedia("(min-width: 761px)").matches) $("lab-details").open = true;
  }

  document.addEventListener("DOMContentLoaded", init);
  return { query, data, frame, draw: drawUnder, drawOver, planetG, state: () => lab };
})();
