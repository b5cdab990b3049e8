// gonio report: the page's logic. The data (report_data.cpp) is embedded as JSON; the per-cell
// maps are base64 float32 arrays [theta_i][phi_i][cell][channel], decoded once per case.
"use strict";
const D = JSON.parse(document.getElementById("gonio-data").textContent);
const $ = (id) => document.getElementById(id);
const decoded = new Map();

function floats(b64) {
  const s = atob(b64);
  const bytes = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) bytes[i] = s.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}
function maps(ci) {
  if (!decoded.has(ci)) {
    const out = {};
    for (const [k, v] of Object.entries(D.cases[ci].maps)) out[k] = floats(v);
    decoded.set(ci, out);
  }
  return decoded.get(ci);
}
const fmt = (v, d = 4) => (v === undefined || v === null || !isFinite(v) ? "–" : Number(v).toPrecision(d));
const state = { c: 0, t: 0, p: 0, ch: 0 };
// The decomposition's models, in order (gonio/masking/surface_point_model.cpp).
const CHAIN = ["l1", "smith_measured_ndf", "measured_g1", "measured"];

function fillSelect(el, labels, value) {
  el.innerHTML = "";
  labels.forEach((l, i) => { const o = document.createElement("option"); o.value = i; o.textContent = l; el.appendChild(o); });
  el.value = String(value);
}

// ---- the run's summary -------------------------------------------------------------------
function summary() {
  $("file").textContent = D.file;
  const a = D.attributes;
  const bits = [["gonio", a.gonio_version], ["git", a.git_hash], ["seed", D.seed], ["created", a.created_utc],
                ["config", a.config_path], ["command", a.command_line], ["MPI ranks", a.mpi_ranks],
                ["threads per rank", a.threads_per_rank]].filter((b) => b[1] !== undefined && b[1] !== "");
  $("provenance").textContent = bits.map((b) => b[0] + ": " + b[1]).join(" · ");
  const head = ["case", "material", "NDF", "masking", "models", "incidences", "rays", "surfaces", "error bars", "stopped by", "seconds"];
  const rows = D.cases.map((c) => {
    const at = c.attributes, rays = (c.runs.rays || []).reduce((s, v) => s + v, 0);
    const surfaces = Math.max(1, ...(c.runs.realisations || [1]));
    const stops = [...new Set(c.stop || [])].join(", ");
    return [c.name, at.fresnel || at.material, at.ndf, at.masking, c.models.join(", "),
            c.theta_i.length * c.phi_i.length, c.simulated ? rays.toExponential(2) : "–",
            c.simulated ? surfaces : "–", at.error_scope || "–", stops || "–",
            fmt(c.timings.wall !== undefined ? c.timings.wall : Object.values(c.timings).reduce((s, v) => s + v, 0), 3)];
  });
  $("summary").innerHTML = "<tr>" + head.map((h) => "<th>" + h + "</th>").join("") + "</tr>" +
    rows.map((r) => "<tr>" + r.map((v) => "<td>" + String(v).replace(/</g, "&lt;") + "</td>").join("") + "</tr>").join("");
  $("timings").textContent = "Phases (s): " + Object.entries(D.timings).map(([k, v]) => k + " " + fmt(v, 3)).join(", ");
}

// ---- selections -------------------------------------------------------------------------
function caseChanged() {
  const c = D.cases[state.c];
  state.t = Math.min(state.t, c.theta_i.length - 1);
  state.p = Math.min(state.p, c.phi_i.length - 1);
  state.ch = Math.min(state.ch, c.channels - 1);
  fillSelect($("theta"), c.theta_i.map((v) => v + "°"), state.t);
  fillSelect($("phi"), c.phi_i.map((v) => v + "°"), state.p);
  fillSelect($("channel"), c.wavelength.length ? c.wavelength.map((w) => w + " nm") :
             Array.from({ length: c.channels }, (_, i) => String(i)), state.ch);
  draw();
}

// Values of one map at the selected incidence and channel, per cell.
function cellValues(arr, c, n) {
  const np = c.phi_i.length, nc = c.channels, base = (state.t * np + state.p) * n, out = new Float64Array(n);
  for (let k = 0; k < n; ++k) out[k] = arr[(base + k) * nc + state.ch];
  return out;
}

// The hemisphere maps: simulated orders, models, and the differences in standard errors.
function mapSet(c, m, n) {
  const get = (k) => (m[k] ? cellValues(m[k], c, n) : null);
  const list = [];
  const l1 = get("l1"), l2 = get("l2plus");
  let linf = null;
  if (l1 && l2) linf = l1.map((v, k) => v + l2[k]);
  if (l1) list.push({ key: "l1", title: "simulated L1", v: l1, brdf: true });
  if (l2) list.push({ key: "l2plus", title: "simulated L2+", v: l2, brdf: true });
  if (linf) list.push({ key: "linf", title: "simulated L∞", v: linf, brdf: true });
  const t = get("t");
  if (t) list.push({ key: "t", title: "simulated T (below, mirrored)", v: t, brdf: true });
  for (const name of c.models) {
    const mv = get("model_" + name);
    if (!mv) continue;
    list.push({ key: "model_" + name, title: "model " + name, v: mv, brdf: true });
    const every = c.compared_with[name] === "linf";
    const sim = every ? linf : l1, err = every ? get("linf_stderr") : get("l1_stderr");
    if (!sim || !err) continue;
    const merr = get("model_" + name + "_stderr");
    const s = sim.map((v, k) => {
      const e = Math.sqrt(err[k] * err[k] + (merr ? merr[k] * merr[k] : 0));
      return e > 0 ? (v - mv[k]) / e : NaN;
    });
    list.push({ key: "sigma_" + name, title: (every ? "L∞" : "L1") + " − " + name + " (σ)", v: s, brdf: false });
    // A model of every order that knows its single scattering: its L2+ against simulated L2+.
    const m2 = get("model_" + name + "_l2plus"), e2 = get("l2plus_stderr");
    if (every && m2 && l2 && e2) {
      const me2 = get("model_" + name + "_l2plus_stderr");
      list.push({ key: "sigma2_" + name, title: "L2+ − " + name + " L2+ (σ)", brdf: false,
                  v: l2.map((v, k) => {
                    const e = Math.sqrt(e2[k] * e2[k] + (me2 ? me2[k] * me2[k] : 0));
                    return e > 0 ? (v - m2[k]) / e : NaN;
                  }) });
    }
  }
  // Fits of this case (gonio fit): (data - fit) / sigma per cell.
  (D.fits || []).forEach((f, i) => {
    if (f.case !== c.name) return;
    if (!decoded.has("fit" + i)) decoded.set("fit" + i, floats(f.residuals));
    const v = cellValues(decoded.get("fit" + i), c, n);
    list.push({ key: "fit_" + i, title: "fit " + f.fit.model + " (" + f.fit.data + "): (data − fit)/σ", v, brdf: false });
  });
  // The decomposition's steps per cell (when the case has the chain's models), in 1/sr.
  const chain = CHAIN.map((n) => get("model_" + n));
  if (chain.every((v) => v)) {
    const names = ["NDF fidelity", "G1 depends on m", "masking–shadowing correlation"];
    for (let k = 1; k < chain.length; ++k)
      list.push({ key: "step_" + k, title: "step: " + names[k - 1], v: chain[k].map((x, c) => x - chain[k - 1][c]),
                  brdf: false, diff: true });
  }
  return { list, l1, linf };
}

function drawMaps(c, set, sensor) {
  const P = sensor.pixels, pc = sensor.pixel_cell;
  const container = $("maps");
  const keys = set.list.map((e) => e.key).join(",");
  if (container.dataset.keys !== keys) {
    container.innerHTML = "";
    for (const e of set.list) { const d = document.createElement("div"); d.id = "map-" + e.key; d.className = "plot"; container.appendChild(d); }
    container.dataset.keys = keys;
  }
  let lo = Infinity, hi = -Infinity;
  for (const e of set.list) if (e.brdf) for (const v of e.v) if (v > 0) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!(hi > 0)) { lo = 1e-3; hi = 1; }
  lo = Math.max(lo, hi * 1e-6);
  for (const e of set.list) {
    const z = [], raw = [];
    for (let r = 0; r < P; ++r) {
      const zr = new Array(P), rr = new Array(P);
      for (let q = 0; q < P; ++q) {
        const k = pc[r * P + q];
        if (k < 0) { zr[q] = null; rr[q] = null; continue; }
        const v = e.v[k];
        rr[q] = v;
        zr[q] = e.brdf ? (v > 0 ? Math.log10(Math.max(v, lo)) : null) : e.diff ? v : (isFinite(v) ? Math.max(-5, Math.min(5, v)) : null);
      }
      z.push(zr); raw.push(rr);
    }
    let span = 5;
    if (e.diff) { span = 0; for (const v of e.v) if (isFinite(v)) span = Math.max(span, Math.abs(v)); span = span || 1; }
    const trace = {
      type: "heatmap", z, customdata: raw, hoverongaps: false,
      hovertemplate: e.brdf ? "f = %{customdata:.4g} 1/sr<extra></extra>"
                            : e.diff ? "Δf = %{customdata:.3g} 1/sr<extra></extra>" : "%{customdata:.2f} σ<extra></extra>",
      colorscale: e.brdf ? "Viridis" : "RdBu", reversescale: !e.brdf,
      zmin: e.brdf ? Math.log10(lo) : -span, zmax: e.brdf ? Math.log10(hi) : span,
      colorbar: { thickness: 10, title: { text: e.brdf ? "log₁₀ f" : e.diff ? "Δf" : "σ", side: "right" } },
    };
    const layout = {
      title: { text: e.title, font: { size: 13 } }, margin: { l: 10, r: 10, t: 30, b: 10 }, height: 330,
      xaxis: { visible: false, scaleanchor: "y" }, yaxis: { visible: false },
    };
    Plotly.react("map-" + e.key, [trace], layout, { displayModeBar: false, responsive: true });
  }
}

// The plane of incidence: cells crossed by phi_i (negative theta_o, towards the light) and by
// phi_i + 180 (positive, the specular side).
function drawPlane(c, m, set, sensor) {
  const n = sensor.cells, phi = c.phi_i[state.p];
  const sides = [{ at: (phi + 180) % 360, sign: 1 }, { at: phi % 360, sign: -1 }];
  const cells = [], xs = [];
  const seen = new Set();
  for (const s of sides)
    for (let k = 0; k < n; ++k) {
      if (sensor.phi_min[k] <= s.at && s.at < sensor.phi_max[k] && !seen.has(k)) {
        seen.add(k); cells.push(k); xs.push(s.sign * 0.5 * (sensor.theta_min[k] + sensor.theta_max[k]));
      }
    }
  const order = xs.map((x, i) => i).sort((a, b) => xs[a] - xs[b]);
  const X = order.map((i) => xs[i]), C = order.map((i) => cells[i]);
  const traces = [];
  const get = (k) => (m[k] ? cellValues(m[k], c, n) : null);
  const l1err = get("l1_stderr"), linferr = get("linf_stderr");
  if (set.l1) traces.push({ x: X, y: C.map((k) => set.l1[k]), name: "simulated L1", mode: "markers",
    error_y: { type: "data", array: C.map((k) => (l1err ? l1err[k] : 0)), visible: true } });
  if (set.linf) traces.push({ x: X, y: C.map((k) => set.linf[k]), name: "simulated L∞", mode: "markers",
    error_y: linferr ? { type: "data", array: C.map((k) => linferr[k]), visible: true } : undefined });
  for (const name of c.models) {
    const mv = get("model_" + name);
    if (mv) traces.push({ x: X, y: C.map((k) => mv[k]), name: "model " + name, mode: "lines" });
  }
  Plotly.react("plane", traces, {
    margin: { t: 20 }, xaxis: { title: "θo (°), negative towards the light" },
    yaxis: { title: "f (1/sr)", type: "log" }, legend: { orientation: "h" },
  }, { displaylogo: false, responsive: true });
}

// A per-incidence quantity [theta_i][phi_i][channel] along theta_i at the selected phi_i, channel.
function alongTheta(c, values) {
  const np = c.phi_i.length, nc = c.channels;
  return c.theta_i.map((_, t) => values[(t * np + state.p) * nc + state.ch]);
}

function drawAlbedo(c) {
  const a = c.albedos, traces = [];
  const line = (key, name, errKey) => {
    if (!a[key]) return;
    const tr = { x: c.theta_i, y: alongTheta(c, a[key]), name, mode: "lines+markers" };
    if (errKey && a[errKey]) tr.error_y = { type: "data", array: alongTheta(c, a[errKey]), visible: true };
    traces.push(tr);
  };
  line("l1_albedo", "simulated L1", "l1_albedo_stderr");
  line("l2plus_albedo", "simulated L2+", "l2plus_albedo_stderr");
  line("linf_albedo", "simulated L∞", "linf_albedo_stderr");
  line("transmitted_albedo", "simulated T", "transmitted_albedo_stderr");
  for (const name of c.models) line("model_" + name + "_albedo", "model " + name, "model_" + name + "_albedo_stderr");
  for (const name of c.models)
    if (c.compared_with[name] === "linf") line("model_" + name + "_l2plus_albedo", "model " + name + " L2+");
  const x = c.theta_i[state.t];
  Plotly.react("albedo", traces, {
    margin: { t: 20 }, xaxis: { title: "θi (°)" }, yaxis: { title: "albedo" }, legend: { orientation: "h" },
    shapes: [{ type: "line", x0: x, x1: x, yref: "paper", y0: 0, y1: 1, line: { dash: "dot", color: "#888" } }],
  }, { displaylogo: false, responsive: true });
}

function drawLedger(c) {
  const a = c.albedos, traces = [];
  for (const [key, name] of [["ledger_absorbed", "absorbed"], ["ledger_lost", "lost"],
                             ["ledger_capped", "capped (bounce limit)"], ["ledger_unaccounted", "unaccounted"]]) {
    if (!a[key]) continue;
    const tr = { x: c.theta_i, y: alongTheta(c, a[key]), name, mode: "lines+markers" };
    if (a[key + "_stderr"]) tr.error_y = { type: "data", array: alongTheta(c, a[key + "_stderr"]), visible: true };
    traces.push(tr);
  }
  Plotly.react("ledger", traces, {
    margin: { t: 20 }, xaxis: { title: "θi (°)" }, yaxis: { title: "fraction of the incident power" },
    legend: { orientation: "h" },
  }, { displaylogo: false, responsive: true });
}

function drawNdf(c) {
  const nd = c.ndf, traces = [];
  traces.push({ x: nd.target.theta, y: nd.target.phi0, name: "target, φ 0°", mode: "lines" });
  traces.push({ x: nd.target.theta, y: nd.target.phi90, name: "target, φ 90°", mode: "lines", line: { dash: "dash" } });
  if (nd.measured) {
    traces.push({ x: nd.measured.theta, y: nd.measured.phi0, name: "surface, φ 0°", mode: "lines" });
    traces.push({ x: nd.measured.theta, y: nd.measured.phi90, name: "surface, φ 90°", mode: "lines", line: { dash: "dash" } });
  }
  $("ndf-note").textContent = "Target: " + nd.target_description + ". " +
    (nd.measured ? "Surface: the facet NDF of " + nd.measured_file + " (the first surface)." : nd.measured_note + ".");
  Plotly.react("ndf", traces, {
    margin: { t: 20 }, xaxis: { title: "θm (°)" }, yaxis: { title: "D(m) (1/sr)", type: "log" },
    legend: { orientation: "h" },
  }, { displaylogo: false, responsive: true });
}

// The decomposition of simulated L1 - Model L1 (when the case has the chain's models).
function drawDecomposition(c) {
  const a = c.albedos, has = a.l1_albedo && CHAIN.every((m) => a["model_" + m + "_albedo"]);
  for (const id of ["decomposition-title", "decomposition-note", "decomposition"]) $(id).style.display = has ? "" : "none";
  if (!has) return;
  const val = (k) => alongTheta(c, a[k]), err = (k) => (a[k] ? alongTheta(c, a[k]) : c.theta_i.map(() => 0));
  const sim = val("l1_albedo"), simErr = err("l1_albedo_stderr");
  const steps = [["NDF fidelity", "l1", "smith_measured_ndf"], ["G1 depends on m", "smith_measured_ndf", "measured_g1"],
                 ["masking–shadowing correlation", "measured_g1", "measured"]];
  const traces = steps.map(([name, lo, hi]) => {
    const a0 = val("model_" + lo + "_albedo"), a1 = val("model_" + hi + "_albedo");
    const e0 = err("model_" + lo + "_albedo_stderr"), e1 = err("model_" + hi + "_albedo_stderr");
    return { type: "bar", name, x: c.theta_i, y: a1.map((v, t) => v - a0[t]),
             error_y: { type: "data", array: e1.map((v, t) => Math.hypot(v, e0[t])), visible: true } };
  });
  const meas = val("model_measured_albedo"), measErr = err("model_measured_albedo_stderr");
  traces.push({ type: "bar", name: "left (simulated − measured)", x: c.theta_i, y: sim.map((v, t) => v - meas[t]),
                error_y: { type: "data", array: simErr.map((v, t) => Math.hypot(v, measErr[t])), visible: true } });
  const l1 = val("model_l1_albedo");
  traces.push({ type: "scatter", mode: "markers", name: "simulated L1 − Model L1", x: c.theta_i,
                y: sim.map((v, t) => v - l1[t]), marker: { symbol: "diamond", size: 10, color: "#000" },
                error_y: { type: "data", array: simErr, visible: true } });
  Plotly.react("decomposition", traces, {
    barmode: "group", margin: { t: 20 }, xaxis: { title: "θi (°)" }, yaxis: { title: "albedo difference" },
    legend: { orientation: "h" },
  }, { displaylogo: false, responsive: true });
}

// The fits of the case: parameters with their errors, chi2/dof.
function drawFits(c) {
  const rows = (D.fits || []).filter((f) => f.case === c.name);
  $("fits-section").style.display = rows.length ? "" : "none";
  const t = $("fits");
  t.innerHTML = "<tr><th>file</th><th>model</th><th>data</th><th>loss</th><th>parameters (Ceres σ; bootstrap σ)</th><th>χ²/dof</th></tr>";
  for (const f of rows) {
    const ps = Object.entries(f.parameters).map(([k, p]) =>
      k + " = " + fmt(p.value, 5) + " ± " + fmt(p.stderr, 2) + (p.stderr_bootstrap !== undefined ? "; " + fmt(p.stderr_bootstrap, 2) : ""));
    const tr = document.createElement("tr");
    for (const v of [f.file, f.fit.model + (f.fit.with !== "none" ? " + " + f.fit.with : ""), f.fit.data, f.fit.loss, ps.join(", "), fmt(f.fit.chi2_per_dof, 4)]) {
      const td = document.createElement("td"); td.textContent = v; tr.appendChild(td);
    }
    t.appendChild(tr);
  }
}

function draw() {
  const c = D.cases[state.c], sensor = D.sensors[c.sensor], m = maps(state.c);
  $("incidence").textContent = c.name + " at θi " + c.theta_i[state.t] + "°, φi " + c.phi_i[state.p] + "°";
  const set = mapSet(c, m, sensor.cells);
  drawMaps(c, set, sensor);
  drawPlane(c, m, set, sensor);
  drawAlbedo(c);
  drawLedger(c);
  drawNdf(c);
  drawDecomposition(c);
  drawFits(c);
  document.body.dataset.drawn = c.name + "|" + state.t + "|" + state.p + "|" + state.ch;
}

// ---- a gonio masking file ------------------------------------------------------------------
const M = { c: 0, i: 0, p: 0 };
function maskingCase() {
  const c = D.cases[M.c];
  const inc = [];
  c.theta_i.forEach((t) => c.phi_i.forEach((p) => inc.push("θi " + t + "°, φi " + p + "°")));
  M.i = Math.min(M.i, Math.max(0, inc.length - 1));
  M.p = Math.min(M.p, c.phi_o.length - 1);
  fillSelect($("m-incidence"), inc.length ? inc : ["(no incidence in the config)"], M.i);
  fillSelect($("m-phi"), c.phi_o.map((p) => p + "°"), M.p);
  drawMasking();
}
function drawMasking() {
  const c = D.cases[M.c], v = c.values, np = c.phi_o.length, nt = c.theta_o.length;
  $("m-ndf").textContent = c.ndf + " · " + c.surface;
  const col = (arr) => c.theta_o.map((_, t) => arr[t * np + M.p]);
  const cfg = { displaylogo: false, responsive: true };
  Plotly.react("m-g1", [
    { x: c.theta_o, y: col(v.g1_projected), name: "measured", mode: "markers",
      error_y: { type: "data", array: col(v.g1_projected_stderr), visible: true } },
    { x: c.theta_o, y: col(v.g1_smith_ndf), name: "Smith, analytic NDF", mode: "lines" },
    { x: c.theta_o, y: col(v.g1_smith_surface), name: "Smith, D_s", mode: "lines", line: { dash: "dash" } },
  ], { margin: { t: 30 }, title: { text: "G1(wo), projected-area average", font: { size: 13 } },
       xaxis: { title: "θo (°)" }, yaxis: { title: "G1" }, legend: { orientation: "h" } }, cfg);
  const cosv = c.theta_o.map((t) => Math.cos(t * Math.PI / 180));
  Plotly.react("m-furnace", [
    { x: c.theta_o, y: col(v.furnace).map((f, t) => (f == null ? null : f / cosv[t])), name: "furnace / cos θo", mode: "markers",
      error_y: { type: "data", array: col(v.furnace_stderr).map((e, t) => (e == null ? null : e / cosv[t])), visible: true } },
  ], { margin: { t: 30 }, title: { text: "weak white furnace: ∫G1⟨wo,m⟩D_s dm / cos θo (1 exactly)", font: { size: 13 } },
       xaxis: { title: "θo (°)" }, yaxis: { title: "ratio" },
       shapes: [{ type: "line", xref: "paper", x0: 0, x1: 1, y0: 1, y1: 1, line: { dash: "dot", color: "#888" } }] }, cfg);
  const nh = c.height_lower_edge.length;
  const heights = [];
  for (let h = 0; h < nh; ++h)
    heights.push({ x: c.theta_o, y: c.theta_o.map((_, t) => v.g1_height[(t * np + M.p) * nh + h]),
                   name: "quantile " + (h + 1) + "/" + nh, mode: "lines+markers" });
  Plotly.react("m-height", heights, { margin: { t: 30 }, title: { text: "G1(wo) by the point's height", font: { size: 13 } },
       xaxis: { title: "θo (°)" }, yaxis: { title: "G1" }, legend: { orientation: "h" } }, cfg);
  // G2 in the plane of incidence: dphi 0 (towards the light, plotted negative) and 180.
  const n2t = c.g2_theta_o.length, n2p = c.g2_dphi.length, base = M.i * n2t * n2p;
  const side = (dphi) => c.g2_dphi.indexOf(dphi);
  const plane = (arr) => {
    const xs = [], ys = [];
    for (const [dp, sign] of [[0, -1], [180, 1]]) {
      const p = side(dp);
      if (p < 0) continue;
      for (let t = 0; t < n2t; ++t) { xs.push(sign * c.g2_theta_o[t]); ys.push(arr[base + t * n2p + p]); }
    }
    const order = xs.map((_, k) => k).sort((a, b) => xs[a] - xs[b]);
    return { x: order.map((k) => xs[k]), y: order.map((k) => ys[k]) };
  };
  const traces = [];
  if (c.theta_i.length) {
    const m = plane(v.g2), e = plane(v.g2_stderr);
    traces.push({ ...m, name: "measured", mode: "markers", error_y: { type: "data", array: e.y, visible: true } });
    for (const [k, name, dash] of [["g2_smith_uncorrelated_surface", "Smith uncorrelated (D_s)", "dot"],
                                   ["g2_smith_height_correlated_surface", "Smith height-correlated (D_s)", "solid"],
                                   ["g2_smith_height_direction_correlated_surface", "Smith height-direction (D_s)", "dash"],
                                   ["g2_smith_height_correlated_ndf", "Smith height-correlated (analytic)", "dashdot"]])
      traces.push({ ...plane(v[k]), name, mode: "lines", line: { dash } });
  }
  Plotly.react("m-g2", traces, { margin: { t: 30 }, title: { text: "G2(wi, wo) in the plane of incidence", font: { size: 13 } },
       xaxis: { title: "θo (°), negative towards the light" }, yaxis: { title: "G2" }, legend: { orientation: "h" } }, cfg);
  document.body.dataset.drawn = c.name + "|" + M.i + "|" + M.p;
}
function maskingPage() {
  $("file").textContent = D.file;
  $("provenance").textContent = Object.entries(D.attributes).map(([k, v]) => k + ": " + v).join(" · ");
  document.querySelector(".result-only").style.display = "none";
  $("masking").style.display = "";
  fillSelect($("m-case"), D.cases.map((c) => c.name), 0);
  $("m-case").addEventListener("change", (e) => { M.c = +e.target.value; maskingCase(); });
  $("m-incidence").addEventListener("change", (e) => { M.i = +e.target.value; drawMasking(); });
  $("m-phi").addEventListener("change", (e) => { M.p = +e.target.value; drawMasking(); });
  maskingCase();
}

// ---- a result file ---------------------------------------------------------------------------
function resultPage() {
  summary();
  fillSelect($("case"), D.cases.map((c) => c.name), 0);
  $("case").addEventListener("change", (e) => { state.c = +e.target.value; caseChanged(); });
  $("theta").addEventListener("change", (e) => { state.t = +e.target.value; draw(); });
  $("phi").addEventListener("change", (e) => { state.p = +e.target.value; draw(); });
  $("channel").addEventListener("change", (e) => { state.ch = +e.target.value; draw(); });
  if (D.images.length) {
    for (const im of D.images) {
      const fig = document.createElement("figure");
      fig.innerHTML = "<img alt=''><figcaption class='note'></figcaption>";
      fig.querySelector("img").src = im.src;
      fig.querySelector("figcaption").textContent = im.name;
      $("images").appendChild(fig);
    }
  } else {
    $("images-section").style.display = "none";
  }
  caseChanged();
}

if (D.kind === "masking") maskingPage(); else resultPage();
