// aesthetic-curves editor: every computation is a request to the local server (POST /api,
// the batch protocol; /api/region for the shaded regions; /api/export for files). The page
// only draws: curves, curvature combs, control points, regions and the curvature graph.
'use strict';

const $ = (id) => document.getElementById(id);
const view = $('view');
const ctx = view.getContext('2d');
const lcgCanvas = $('lcg');
const lctx = lcgCanvas.getContext('2d');
const kCanvas = $('kplot');
const kctx = kCanvas.getContext('2d');

// ---------- state ----------
const BOXES = {
  lac: { x0: -1, y0: -2, x1: 15, y1: 9 },
  inflection: { x0: -1, y0: -2, x1: 15, y1: 9 },
  spline: { x0: 0, y0: 0, x1: 14, y1: 10 },
  sketch: { x0: 0, y0: 0, x1: 14, y1: 10 },
  bezier: { x0: 0, y0: -1, x1: 14, y1: 9 },
};
const HINTS = {
  lac: 'Drag the three control points; move the alpha slider. Green: where the third control point may go (a LAC segment exists). Dashed blue: the rational cubic Bézier.',
  inflection: 'A segment with zero curvature at its first point: drag the three control points. Green: where the third control point may go. Dashed blue: its rational cubic.',
  spline: 'Click to add points, drag them. The pseudo-elastic spline (S2) through them, open or closed.',
  sketch: 'Draw with the mouse or a pen: the stroke becomes a G2 curve of log-aesthetic pieces (colours; circles: joints).',
  bezier: 'Drag the control points; click one to select it. Green: where the selected point keeps the curvature monotone.',
};
const state = {
  mode: 'lac',
  lac: { p: [[0, 0], [8, 0], [12, 5]], alpha: -1 },
  inflection: { p: [[0, 0], [7, 0], [12, 4]] },
  spline: { p: [[1.5, 2], [4.5, 6.5], [8, 4], [12, 7.5]], closed: false },
  sketch: { stroke: [] },
  bezier: { p: [[1, 1], [6, 1], [10, 3], [12, 7]], selected: 2 },
};
const views = JSON.parse(JSON.stringify(BOXES)); // each mode's current view (zoom, pan)
let box = views.lac;
let shown = null; // what is drawn: {curve, kappa, overlay, pieces, marks, polygon, handles}
let region = null; // {grid, rows, key}
let nurbs = null; // the curve on screen, for export
let updates = 0;
let maxServerMs = 0;
let lastServerMs = 0;
const serverMs = {}; // every server time per op (and per region kind), in order

// ---------- coordinates ----------
function scale() {
  return Math.min(view.width / (box.x1 - box.x0), view.height / (box.y1 - box.y0));
}
function toScreen(p) {
  const s = scale();
  return [(p[0] - box.x0) * s, view.height - (p[1] - box.y0) * s];
}
function toWorld(px, py) {
  const s = scale();
  return [box.x0 + px / s, box.y0 + (view.height - py) / s];
}
function eventWorld(ev) {
  const r = view.getBoundingClientRect();
  return toWorld((ev.clientX - r.left) * view.width / r.width, (ev.clientY - r.top) * view.height / r.height);
}
function viewGrid(n) {
  const s = scale();
  const w = view.width / s;
  const h = view.height / s;
  return { x0: box.x0, y0: box.y0, x1: box.x0 + w, y1: box.y0 + h, nx: n, ny: Math.round(n * h / w) };
}

// ---------- server ----------
class ApiError extends Error {
  constructor(e) { super(`${e.kind}: ${e.message}`); this.kind = e.kind; }
}
async function post(path, body) {
  const what = body.op || (body.kind ? `region.${body.kind}` : path);
  const r = await fetch(path, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body),
  });
  const st = r.headers.get('server-timing');
  const m = st && /dur=([\d.]+)/.exec(st);
  if (m) {
    lastServerMs = +m[1];
    maxServerMs = Math.max(maxServerMs, lastServerMs);
    (serverMs[what] = serverMs[what] || []).push(lastServerMs);
  }
  return r;
}
async function api(req) {
  const v = await (await post('/api', req)).json();
  if (!v.ok) throw new ApiError(v.error);
  return v.result;
}

// ---------- curve helpers ----------
// Cubic Bernstein basis and its first two derivatives at t.
function bern3(t) {
  const u = 1 - t;
  return [
    [u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t],
    [-3 * u * u, 3 * u * u - 6 * u * t, 6 * u * t - 3 * t * t, 3 * t * t],
    [6 * u, -12 * u + 6 * t, 6 * u - 12 * t, 6 * t],
  ];
}
// Point, derivative and curvature of a rational cubic (weights default 1).
function rationalCubicAt(P, W, t) {
  const [b, d1, d2] = bern3(t);
  const sum = (B, f) => B.reduce((a, bi, i) => a + bi * f(i), 0);
  const w = sum(b, (i) => W[i]), w1 = sum(d1, (i) => W[i]), w2 = sum(d2, (i) => W[i]);
  const A = [0, 1].map((k) => sum(b, (i) => W[i] * P[i][k]));
  const A1 = [0, 1].map((k) => sum(d1, (i) => W[i] * P[i][k]));
  const A2 = [0, 1].map((k) => sum(d2, (i) => W[i] * P[i][k]));
  const p = A.map((a) => a / w);
  const v = [0, 1].map((k) => (A1[k] - w1 * p[k]) / w);
  const a = [0, 1].map((k) => (A2[k] - 2 * w1 * v[k] - w2 * p[k]) / w);
  const sp = Math.hypot(v[0], v[1]);
  const kappa = sp > 0 ? (v[0] * a[1] - v[1] * a[0]) / (sp * sp * sp) : 0;
  return { p, kappa };
}
function sampleCubic(P, W, n, out) {
  W = W || [1, 1, 1, 1];
  for (let i = out.curve.length ? 1 : 0; i <= n; i++) {
    const r = rationalCubicAt(P, W, i / n);
    out.curve.push(r.p);
    out.kappa.push(r.kappa);
  }
  return out;
}
// De Casteljau point of a polynomial Bézier of any degree, and its curvature by derivatives.
function bezierAt(P, t) {
  let q = P.map((p) => p.slice());
  const levels = [q];
  while (q.length > 1) {
    q = q.slice(1).map((p, i) => [q[i][0] + t * (p[0] - q[i][0]), q[i][1] + t * (p[1] - q[i][1])]);
    levels.push(q);
  }
  const n = P.length - 1;
  const L1 = levels[n - 1]; // two points
  const v = [n * (L1[1][0] - L1[0][0]), n * (L1[1][1] - L1[0][1])];
  let a = [0, 0];
  if (n >= 2) {
    const L2 = levels[n - 2];
    a = [0, 1].map((k) => n * (n - 1) * (L2[2][k] - 2 * L2[1][k] + L2[0][k]));
  }
  const sp = Math.hypot(v[0], v[1]);
  return { p: q[0], kappa: sp > 0 ? (v[0] * a[1] - v[1] * a[0]) / (sp * sp * sp) : 0 };
}
// One NURBS of cubic pieces (C0 at the joints, each piece rational): weights of each piece
// scaled so that the shared control point has one weight.
function cubicsToNurbs(pieces) {
  const cps = [];
  const ws = [];
  const knots = [0, 0, 0, 0];
  pieces.forEach((pc, k) => {
    let W = pc.W || [1, 1, 1, 1];
    if (k > 0) {
      const s = ws[ws.length - 1] / W[0];
      W = W.map((w) => w * s);
    }
    const from = k === 0 ? 0 : 1;
    for (let i = from; i < 4; i++) {
      cps.push(pc.P[i]);
      ws.push(W[i]);
    }
    knots.push(k + 1, k + 1, k + 1);
  });
  knots.push(pieces.length);
  return { degree: 3, knots, control_points: cps, weights: ws };
}
function hermiteToBezier(s) {
  return [s.p0, [s.p0[0] + s.d0[0] / 3, s.p0[1] + s.d0[1] / 3], [s.p1[0] - s.d1[0] / 3, s.p1[1] - s.d1[1] / 3], s.p1];
}

// ---------- numbers ----------
function fmt(x, d = 4) {
  if (typeof x !== 'number') return String(x);
  if (Number.isInteger(x) && Math.abs(x) < 1e9) return String(x);
  const a = Math.abs(x);
  return a >= 1e4 || a < 1e-3 ? x.toExponential(2) : x.toFixed(d);
}
function setNumbers(rows) {
  const t = $('numbers');
  t.innerHTML = '';
  for (const [key, label, value] of rows) {
    const tr = document.createElement('tr');
    tr.innerHTML = `<td>${label}</td><td id="n-${key}">${typeof value === 'number' ? fmt(value) : value}</td>`;
    t.appendChild(tr);
  }
}
function setVerdict(text, good) {
  const v = $('verdict');
  v.textContent = text;
  v.className = good === undefined ? '' : good ? 'yes' : 'no';
}
function setStatus(text, error) {
  const s = $('status');
  s.textContent = text;
  s.className = error ? 'error' : '';
}

// ---------- the update loop: one request chain at a time, the latest state wins ----------
let busy = false;
let dirty = false;
function requestUpdate() {
  clearTimeout(regionTimer);
  if (busy) {
    dirty = true;
    return;
  }
  busy = true;
  dirty = false;
  const mode = state.mode;
  update(mode)
    .then(() => setStatus(`server ${fmt(lastServerMs, 2)} ms (largest so far ${fmt(maxServerMs, 2)} ms)`))
    .catch((e) => {
      shown = { handles: handles(), polygon: polygon() };
      nurbs = null;
      setNumbers([['error', 'error', e.kind || 'error']]);
      setVerdict(e.message, false);
      setStatus(e.message, true);
      drawLcg(null);
    })
    .finally(() => {
      busy = false;
      updates += 1;
      document.body.dataset.updates = String(updates);
      draw();
      if (dirty) requestUpdate();
      else regionUpdate();
    });
}
function handles() {
  const m = state.mode;
  if (m === 'sketch') return [];
  return state[m].p;
}
function polygon() {
  const m = state.mode;
  return m === 'lac' || m === 'inflection' || m === 'bezier' ? state[m].p : null;
}

async function update(mode) {
  if (mode === 'lac') return updateLac();
  if (mode === 'inflection') return updateInflection();
  if (mode === 'spline') return updateSpline();
  if (mode === 'sketch') return updateSketch();
  return updateBezier();
}

async function lcgOf(points) {
  try {
    // Every other sample is plenty for the graph (and keeps the request a few milliseconds).
    const r = await api({ op: 'lcg.estimate', points: points.filter((_, i) => i % 2 === 0) });
    drawLcg(r);
    return r;
  } catch (e) {
    drawLcg(null, e.message);
    return null;
  }
}

async function updateLac() {
  const { p, alpha } = state.lac;
  const seg = await api({ op: 'lac.segment', alpha, control: p, samples: 240 });
  const [ra, lcg] = await Promise.all([
    api({ op: 'lac.rational_approx', alpha, control: p }).catch((e) => ({ error: e })),
    lcgOf(seg.points),
  ]);
  const overlay = ra.error ? null : sampleCubic(ra.control_points, ra.weights, 160, { curve: [], kappa: [] }).curve;
  shown = { curve: seg.points, kappa: seg.curvature, overlay, handles: p, polygon: p, overlayPolygon: ra.error ? null : ra.control_points };
  nurbs = ra.error ? null : { degree: 3, knots: [0, 0, 0, 0, 1, 1, 1, 1], control_points: ra.control_points, weights: ra.weights };
  setNumbers([
    ['alpha', 'alpha', alpha],
    ['arc_length', 'arc length', seg.arc_length],
    ['curvature_start', 'curvature at P0', seg.curvature_start],
    ['curvature_end', 'curvature at P2', seg.curvature_end],
    ['lambda', 'Λ', seg.lambda],
    ['lcg_alpha', 'LCG slope (from samples)', lcg ? lcg.alpha : '—'],
    ['rational_error', 'rational cubic: max error', ra.error ? ra.error.kind : ra.max_error],
  ]);
  if (ra.error) setVerdict(`LAC curvature is monotone by construction; no rational cubic: ${ra.error.message}`, true);
  else setVerdict(ra.monotone ? 'rational cubic: curvature monotone (proven)' : 'rational cubic: curvature NOT monotone', ra.monotone);
}

async function updateInflection() {
  const { p } = state.inflection;
  // The rational cubic of an inflection segment takes a while (~0.1 s): only when the
  // drag ends.
  const seg = await api({ op: 'lac.inflection_segment', control: p, samples: 240, rational: !drag });
  const ra = seg.rational || { control_points: null, weights: null, max_error: '…', monotone: undefined };
  const lcg = await lcgOf(seg.points.slice(8));
  shown = {
    curve: seg.points, kappa: seg.curvature, handles: p, polygon: p,
    overlay: ra.control_points ? sampleCubic(ra.control_points, ra.weights, 160, { curve: [], kappa: [] }).curve : null,
    overlayPolygon: ra.control_points, marks: [seg.points[0]],
  };
  nurbs = ra.control_points ? { degree: 3, knots: [0, 0, 0, 0, 1, 1, 1, 1], control_points: ra.control_points, weights: ra.weights } : null;
  setNumbers([
    ['alpha', 'alpha (from the triangle)', seg.alpha],
    ['arc_length', 'arc length', seg.arc_length],
    ['curvature_end', 'curvature at P2', seg.curvature_end],
    ['lcg_alpha', 'LCG slope (from samples)', lcg ? lcg.alpha : '—'],
    ['rational_error', 'rational cubic: max error', ra.max_error],
  ]);
  if (!ra.control_points) setVerdict('LAC segment: curvature monotone by construction (its rational cubic when the drag ends)', true);
  else setVerdict(ra.monotone ? 'rational cubic: curvature monotone (proven)' : 'rational cubic: curvature NOT monotone', ra.monotone);
}

async function updateSpline() {
  const { p, closed } = state.spline;
  if (p.length < (closed ? 3 : 2)) {
    shown = { handles: p };
    nurbs = null;
    setNumbers([['points', 'points', p.length]]);
    setVerdict('add points by clicking');
    drawLcg(null, 'the spline is not one monotone piece');
    return;
  }
  const r = await api({ op: 'spline.pseudo_elastic', points: p, closed });
  const out = { curve: [], kappa: [] };
  const pieces = r.segments.map((s) => ({ P: hermiteToBezier(s) }));
  for (const pc of pieces) sampleCubic(pc.P, null, 40, out);
  shown = { curve: out.curve, kappa: out.kappa, handles: p };
  nurbs = cubicsToNurbs(pieces);
  setNumbers([
    ['points', 'points', p.length],
    ['length', 'length', r.length],
    ['area', closed ? 'enclosed area' : 'area to the chord', r.area],
    ['energy', 'pseudo-energy Σ l J', r.energy],
    ['mode', 'mode', r.mode],
  ]);
  setVerdict(`${r.segments.length} Hermite spans, G1 at every point`);
  drawLcg(null, 'the spline is not one monotone piece');
}

async function updateSketch() {
  const s = state.sketch.stroke;
  if (s.length < 8) {
    shown = { stroke: s };
    nurbs = null;
    setNumbers([['pieces', 'pieces', 0]]);
    setVerdict('draw a stroke');
    drawLcg(null, 'draw a stroke');
    return;
  }
  const r = await api({ op: 'sketch.fit', points: s });
  const out = { curve: [], kappa: [] };
  const pieces = [];
  const colored = [];
  for (const seg of r.segments) {
    const P = seg.rational.control_points;
    const W = seg.rational.weights;
    pieces.push({ P, W });
    const one = sampleCubic(P, W, 50, { curve: [], kappa: [] });
    colored.push(one.curve);
    sampleCubic(P, W, 50, out);
  }
  const joints = r.segments.map((g) => g.control[0]).concat([r.segments[r.segments.length - 1].control[2]]);
  shown = { curve: out.curve, kappa: out.kappa, pieces: colored, marks: joints, stroke: s };
  nurbs = cubicsToNurbs(pieces);
  setNumbers([
    ['pieces', 'pieces', r.segments.length],
    ['max_deviation', 'max deviation', r.max_deviation],
    ['tolerance', 'tolerance', r.tolerance],
    ['g2', 'G2', r.g2 ? 'yes' : 'no'],
    ['max_curvature_jump', 'largest curvature jump', r.max_curvature_jump ?? 0],
    ['alphas', 'alphas', r.segments.map((g) => fmt(g.alpha, 2)).join(' ')],
  ]);
  setVerdict(r.all_monotone ? 'every piece: curvature monotone (proven)' : 'some piece is NOT monotone', r.all_monotone);
  drawLcg(null, 'one graph per piece: see the alphas');
}

async function updateBezier() {
  const { p } = state.bezier;
  const r = await api({ op: 'bezier.curvature_monotone', control_points: p });
  const out = { curve: [], kappa: [] };
  for (let i = 0; i <= 240; i++) {
    const q = bezierAt(p, i / 240);
    out.curve.push(q.p);
    out.kappa.push(q.kappa);
  }
  shown = { curve: out.curve, kappa: out.kappa, handles: p, polygon: p, marks: r.extrema.map((t) => bezierAt(p, t).p) };
  const n = p.length - 1;
  nurbs = { degree: n, knots: Array(n + 1).fill(0).concat(Array(n + 1).fill(1)), control_points: p, weights: p.map(() => 1) };
  setNumbers([
    ['degree', 'degree', n],
    ['extrema', 'curvature extrema inside', r.extrema.length],
    ['trend', 'trend', r.trend || '—'],
    ['test_degree', 'degree of the dκ/ds test', r.test_degree],
  ]);
  setVerdict(r.monotone ? 'curvature monotone (exact test)' : 'curvature NOT monotone (circles: extrema)', r.monotone);
  await lcgOf(out.curve);
}

// Regions follow the editing: after every answered update, when what they depend on changed
// (the LAC and inflection regions take about a millisecond, the Bezier one about ten), with at
// most one region request in flight; the latest state wins.
let regionTimer = null;
let regionBusy = false;
let regionAgain = false;
function regionUpdate() {
  clearTimeout(regionTimer);
  regionTimer = setTimeout(regionCompute, 0);
}
async function regionCompute() {
  if (!$('region').checked) return;
  if (regionBusy) {
    regionAgain = true;
    return;
  }
  let req;
  if (state.mode === 'lac') {
    req = { kind: 'lac', alpha: state.lac.alpha, control: state.lac.p, grid: viewGrid(128) };
    req.key = JSON.stringify([state.mode, state.lac.p[0], state.lac.p[1], state.lac.alpha, box]);
  } else if (state.mode === 'inflection') {
    req = { kind: 'inflection', control: state.inflection.p, grid: viewGrid(128) };
    req.key = JSON.stringify([state.mode, state.inflection.p[0], state.inflection.p[1], box]);
  } else if (state.mode === 'bezier') {
    req = { kind: 'bezier', control_points: state.bezier.p, index: state.bezier.selected, grid: viewGrid(82) };
    req.key = JSON.stringify([state.mode, state.bezier.p, state.bezier.selected, box]);
  } else {
    return;
  }
  if (region && region.key === req.key) return;
  regionBusy = true;
  let v;
  try {
    v = await (await post('/api/region', req)).json();
  } finally {
    regionBusy = false;
    if (regionAgain) {
      regionAgain = false;
      regionUpdate();
    }
  }
  if (!v.ok) return;
  region = { grid: req.grid, rows: v.result.rows, key: req.key, mode: state.mode };
  document.body.dataset.region = String(v.result.rows.join('').split('1').length - 1);
  document.body.dataset.regionFor = req.kind === 'bezier' ? `bezier:${req.index}` : req.kind;
  draw();
}

// ---------- drawing ----------
function draw() {
  drawCurvature();
  ctx.clearRect(0, 0, view.width, view.height);
  const s = scale();
  if (region && region.mode === state.mode && $('region').checked) {
    // One pixel per cell on a small canvas, scaled up without smoothing: no seams.
    const g = region.grid;
    if (!region.image) {
      const c = document.createElement('canvas');
      c.width = g.nx;
      c.height = g.ny;
      const cx = c.getContext('2d');
      const img = cx.createImageData(g.nx, g.ny);
      region.rows.forEach((row, i) => {
        for (let k = 0; k < row.length; k++) {
          const o = ((g.ny - 1 - i) * g.nx + k) * 4;
          if (row[k] === '1') {
            img.data[o] = 46;
            img.data[o + 1] = 160;
            img.data[o + 2] = 67;
            img.data[o + 3] = 48;
          }
        }
      });
      cx.putImageData(img, 0, 0);
      region.image = c;
    }
    const [x0, y1] = toScreen([g.x0, g.y1]);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(region.image, x0, y1, (g.x1 - g.x0) * s, (g.y1 - g.y0) * s);
  }
  if (!shown) return;
  const line = (pts, style, width, dash) => {
    if (!pts || pts.length < 2) return;
    ctx.beginPath();
    ctx.strokeStyle = style;
    ctx.lineWidth = width;
    ctx.setLineDash(dash || []);
    pts.forEach((p, i) => {
      const [x, y] = toScreen(p);
      if (i) ctx.lineTo(x, y);
      else ctx.moveTo(x, y);
    });
    ctx.stroke();
    ctx.setLineDash([]);
  };
  if (shown.stroke) line(shown.stroke, '#bbb', 1.5);
  if (shown.polygon) line(shown.polygon, '#999', 1, [5, 4]);
  if (shown.overlayPolygon) line(shown.overlayPolygon, 'rgba(30, 80, 200, 0.35)', 1, [2, 4]);
  // Curvature comb: teeth along the normal, away from the centre of curvature.
  if (shown.curve && $('comb').checked) {
    const c = shown.curve;
    const kmax = Math.max(1e-12, ...shown.kappa.map(Math.abs));
    const len = 0.18 * Math.min(box.x1 - box.x0, box.y1 - box.y0) / kmax;
    const tips = c.map((p, i) => {
      const a = c[Math.max(0, i - 1)];
      const b = c[Math.min(c.length - 1, i + 1)];
      const dx = b[0] - a[0], dy = b[1] - a[1];
      const l = Math.hypot(dx, dy) || 1;
      const k = shown.kappa[i] || 0;
      return [p[0] + dy / l * k * len, p[1] - dx / l * k * len];
    });
    ctx.strokeStyle = '#9ecae1';
    ctx.lineWidth = 1;
    ctx.beginPath();
    c.forEach((p, i) => {
      if (i % 3) return;
      const [x, y] = toScreen(p);
      const [u, v] = toScreen(tips[i]);
      ctx.moveTo(x, y);
      ctx.lineTo(u, v);
    });
    ctx.stroke();
    line(tips, '#6baed6', 1);
  }
  const colors = ['#d62728', '#9467bd', '#2ca02c', '#ff7f0e', '#1f77b4', '#8c564b'];
  if (shown.pieces) shown.pieces.forEach((pc, i) => line(pc, colors[i % colors.length], 3));
  else line(shown.curve, '#d62728', 2.5);
  if (shown.overlay) line(shown.overlay, '#1f3fbf', 1.5, [7, 5]);
  for (const m of shown.marks || []) {
    const [x, y] = toScreen(m);
    ctx.beginPath();
    ctx.arc(x, y, 6, 0, 2 * Math.PI);
    ctx.strokeStyle = '#000';
    ctx.lineWidth = 2;
    ctx.stroke();
  }
  (shown.handles || []).forEach((p, i) => {
    const [x, y] = toScreen(p);
    ctx.beginPath();
    ctx.arc(x, y, 6, 0, 2 * Math.PI);
    const sel = state.mode === 'bezier' && i === state.bezier.selected;
    ctx.fillStyle = sel ? '#e8a33d' : '#444';
    ctx.fill();
  });
}

// Curvature against arc length (chord sums of the drawn samples); joints as grey lines.
function drawCurvature() {
  kctx.clearRect(0, 0, kCanvas.width, kCanvas.height);
  if (!shown || !shown.curve || shown.curve.length < 2) return;
  const c = shown.curve;
  const s = [0];
  for (let i = 1; i < c.length; i++) s.push(s[i - 1] + Math.hypot(c[i][0] - c[i - 1][0], c[i][1] - c[i - 1][1]));
  const k = shown.kappa;
  const total = s[s.length - 1] || 1;
  let lo = Math.min(0, ...k), hi = Math.max(0, ...k);
  if (hi - lo < 1e-12) hi = lo + 1;
  const W = kCanvas.width, H = kCanvas.height, m = 22;
  const px = (x) => m + x / total * (W - 2 * m);
  const py = (y) => H - m - (y - lo) / (hi - lo) * (H - 2 * m);
  kctx.strokeStyle = '#ccc';
  kctx.beginPath();
  kctx.moveTo(m, py(0));
  kctx.lineTo(W - m, py(0));
  kctx.stroke();
  if (shown.pieces) {
    let acc = 0;
    kctx.strokeStyle = '#bbb';
    kctx.setLineDash([3, 3]);
    for (const pc of shown.pieces.slice(0, -1)) {
      for (let i = 1; i < pc.length; i++) acc += Math.hypot(pc[i][0] - pc[i - 1][0], pc[i][1] - pc[i - 1][1]);
      kctx.beginPath();
      kctx.moveTo(px(acc), m);
      kctx.lineTo(px(acc), H - m);
      kctx.stroke();
    }
    kctx.setLineDash([]);
  }
  kctx.strokeStyle = '#d62728';
  kctx.lineWidth = 1.5;
  kctx.beginPath();
  k.forEach((v, i) => (i ? kctx.lineTo(px(s[i]), py(v)) : kctx.moveTo(px(s[i]), py(v))));
  kctx.stroke();
  kctx.lineWidth = 1;
  kctx.fillStyle = '#222';
  kctx.font = '11px sans-serif';
  kctx.fillText(`κ from ${fmt(Math.min(...k), 3)} to ${fmt(Math.max(...k), 3)}`, m, 14);
  kctx.fillText('arc length', W / 2 - 25, H - 6);
}

function drawLcg(fit, note) {
  lctx.clearRect(0, 0, lcgCanvas.width, lcgCanvas.height);
  $('lcg-note').textContent = note || '';
  if (!fit || !fit.graph || fit.graph.length < 2) return;
  const g = fit.graph;
  const xs = g.map((p) => p[0]);
  const ys = g.map((p) => p[1]);
  const n = g.length;
  const mx = xs.reduce((a, b) => a + b) / n;
  const my = ys.reduce((a, b) => a + b) / n;
  const b = my - fit.alpha * mx;
  const x0 = Math.min(...xs), x1 = Math.max(...xs);
  const y0 = Math.min(...ys, fit.alpha * x0 + b, fit.alpha * x1 + b);
  const y1 = Math.max(...ys, fit.alpha * x0 + b, fit.alpha * x1 + b);
  const W = lcgCanvas.width, H = lcgCanvas.height, m = 30;
  const px = (x) => m + (x - x0) / Math.max(1e-12, x1 - x0) * (W - 2 * m);
  const py = (y) => H - m - (y - y0) / Math.max(1e-12, y1 - y0) * (H - 2 * m);
  lctx.strokeStyle = '#333';
  lctx.strokeRect(m, m, W - 2 * m, H - 2 * m);
  lctx.fillStyle = '#1f77b4';
  g.forEach((p) => lctx.fillRect(px(p[0]) - 1.5, py(p[1]) - 1.5, 3, 3));
  lctx.strokeStyle = '#d62728';
  lctx.lineWidth = 1.5;
  lctx.beginPath();
  lctx.moveTo(px(x0), py(fit.alpha * x0 + b));
  lctx.lineTo(px(x1), py(fit.alpha * x1 + b));
  lctx.stroke();
  lctx.fillStyle = '#222';
  lctx.font = '12px sans-serif';
  lctx.fillText('log ρ', W / 2 - 15, H - 8);
  lctx.fillText(`slope α = ${fmt(fit.alpha, 3)}`, m + 6, m + 16);
  lctx.save();
  lctx.translate(12, H / 2 + 40);
  lctx.rotate(-Math.PI / 2);
  lctx.fillText('log(ρ ds/dρ)', 0, 0);
  lctx.restore();
}

// ---------- interaction ----------
let drag = null; // {index}, {stroke: true} or {pan: world point}
// Undo: the edited mode's state before each edit (Ctrl+Z).
const history = [];
function remember() {
  history.push({ mode: state.mode, data: JSON.parse(JSON.stringify(state[state.mode])) });
  if (history.length > 200) history.shift();
}
function undo() {
  for (let i = history.length - 1; i >= 0; i--) {
    if (history[i].mode === state.mode) {
      state[state.mode] = history.splice(i, 1)[0].data;
      if (state.mode === 'lac') {
        $('alpha').value = state.lac.alpha;
        $('alpha-value').textContent = state.lac.alpha.toFixed(2);
      }
      if (state.mode === 'spline') $('closed').checked = state.spline.closed;
      requestUpdate();
      return;
    }
  }
}
document.addEventListener('keydown', (ev) => {
  if ((ev.ctrlKey || ev.metaKey) && ev.key === 'z') {
    ev.preventDefault();
    undo();
  }
  if (ev.key === 'f' && !(ev.target instanceof HTMLInputElement)) fitView();
});
function nearestHandle(ev) {
  const r = view.getBoundingClientRect();
  const x = (ev.clientX - r.left) * view.width / r.width;
  const y = (ev.clientY - r.top) * view.height / r.height;
  let best = -1, bd = 12;
  handles().forEach((p, i) => {
    const [u, v] = toScreen(p);
    const d = Math.hypot(u - x, v - y);
    if (d < bd) {
      bd = d;
      best = i;
    }
  });
  return best;
}
view.addEventListener('contextmenu', (ev) => ev.preventDefault());
view.addEventListener('pointerdown', (ev) => {
  view.setPointerCapture(ev.pointerId);
  const m = state.mode;
  if (ev.button === 2 || ev.button === 1 || ev.shiftKey) {
    drag = { pan: eventWorld(ev) };
    return;
  }
  if (m === 'sketch') {
    remember();
    state.sketch.stroke = [eventWorld(ev)];
    drag = { stroke: true };
    shown = { stroke: state.sketch.stroke };
    draw();
    return;
  }
  const i = nearestHandle(ev);
  if (i >= 0) {
    remember();
    drag = { index: i };
    if (m === 'bezier') {
      state.bezier.selected = i;
      draw();
    }
    return;
  }
  if (m === 'spline') {
    remember();
    state.spline.p.push(eventWorld(ev));
    drag = { index: state.spline.p.length - 1 };
    requestUpdate();
  }
});
view.addEventListener('pointermove', (ev) => {
  if (!drag) return;
  const w = eventWorld(ev);
  if (drag.pan) {
    // Keep the grabbed world point under the pointer.
    const dx = drag.pan[0] - w[0];
    const dy = drag.pan[1] - w[1];
    box.x0 += dx;
    box.x1 += dx;
    box.y0 += dy;
    box.y1 += dy;
    draw();
    return;
  }
  if (drag.stroke) {
    const s = state.sketch.stroke;
    const last = s[s.length - 1];
    if (Math.hypot(w[0] - last[0], w[1] - last[1]) * scale() >= 2) {
      s.push(w);
      draw();
    }
    return;
  }
  state[state.mode].p[drag.index] = w;
  requestUpdate();
});
const endDrag = () => {
  if (!drag) return;
  const panned = drag.pan;
  drag = null;
  if (panned) regionUpdate();
  else requestUpdate();
};
// Wheel: zoom about the pointer.
view.addEventListener('wheel', (ev) => {
  ev.preventDefault();
  const c = eventWorld(ev);
  const f = Math.pow(1.0015, ev.deltaY);
  box.x0 = c[0] + (box.x0 - c[0]) * f;
  box.x1 = c[0] + (box.x1 - c[0]) * f;
  box.y0 = c[1] + (box.y0 - c[1]) * f;
  box.y1 = c[1] + (box.y1 - c[1]) * f;
  draw();
  regionUpdate();
}, { passive: false });
// Fit the view to what is drawn.
function fitView() {
  const pts = [].concat((shown && shown.curve) || [], handles(), (shown && shown.stroke) || []);
  if (pts.length < 2) return;
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const p of pts) {
    x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]);
    y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
  }
  const m = 0.12 * Math.max(x1 - x0, y1 - y0, 1e-9);
  Object.assign(box, { x0: x0 - m, y0: y0 - m, x1: x1 + m, y1: y1 + m });
  draw();
  regionUpdate();
}
view.addEventListener('pointerup', endDrag);
view.addEventListener('pointercancel', endDrag);

$('alpha').addEventListener('pointerdown', remember);
$('alpha').addEventListener('keydown', (ev) => {
  if (ev.key.startsWith('Arrow')) remember();
});
$('alpha').addEventListener('input', () => {
  state.lac.alpha = +$('alpha').value;
  $('alpha-value').textContent = state.lac.alpha.toFixed(2);
  requestUpdate();
});
$('closed').addEventListener('change', () => {
  remember();
  state.spline.closed = $('closed').checked;
  requestUpdate();
});
$('comb').addEventListener('change', draw);
$('region').addEventListener('change', () => {
  region = null;
  draw();
  regionUpdate();
});
$('add-point').addEventListener('click', () => {
  remember();
  const p = state[state.mode].p;
  const last = p[p.length - 1];
  p.push([Math.min(box.x1 - 1, last[0] + 1.5), last[1]]);
  requestUpdate();
});
$('remove-point').addEventListener('click', () => {
  remember();
  const p = state[state.mode].p;
  if (p.length > (state.mode === 'bezier' ? 3 : 0)) p.pop();
  if (state.mode === 'bezier') state.bezier.selected = Math.min(state.bezier.selected, p.length - 1);
  requestUpdate();
});
$('clear').addEventListener('click', () => {
  remember();
  if (state.mode === 'spline') state.spline.p = [];
  if (state.mode === 'sketch') state.sketch.stroke = [];
  requestUpdate();
});
for (const b of document.querySelectorAll('#modes button')) {
  b.addEventListener('click', () => setMode(b.dataset.mode));
}
function setMode(m) {
  state.mode = m;
  box = views[m];
  region = null;
  shown = null;
  for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('active', b.dataset.mode === m);
  const show = (id, on) => $(id).classList.toggle('hidden', !on);
  show('alpha-box', m === 'lac');
  show('closed-box', m === 'spline');
  show('region-box', m === 'lac' || m === 'inflection' || m === 'bezier');
  show('add-point', m === 'spline' || m === 'bezier');
  show('remove-point', m === 'spline' || m === 'bezier');
  show('clear', m === 'spline' || m === 'sketch');
  $('hint').textContent = HINTS[m];
  draw();
  requestUpdate();
}

// ---------- export ----------
// CAD geometry of a LAC or inflection-end segment: rational cubics within 1e-7 of its size
// (G2, every piece proven curvature-monotone), not the single cubic drawn as the overlay.
async function cadSpline() {
  const m = state.mode;
  if (m !== 'lac' && m !== 'inflection') return { nurbs, note: '' };
  const p = state[m].p;
  const size = Math.max(...p.map((q) => Math.hypot(q[0] - p[0][0], q[1] - p[0][1])));
  const tolerance = 1e-7 * size;
  const r = m === 'lac'
    ? await api({ op: 'lac.rational_approx', alpha: state.lac.alpha, control: p, tolerance })
    : await api({ op: 'lac.inflection_segment', control: p, samples: 2, tolerance });
  const sp = r.spline;
  return {
    nurbs: { degree: sp.degree, knots: sp.knots, control_points: sp.control_points, weights: sp.weights },
    note: `, ${sp.pieces} rational cubic(s) within ${fmt(sp.max_error, 2)}`,
  };
}

async function exportAs(format) {
  let cad;
  try {
    cad = await cadSpline();
  } catch (e) {
    setStatus(`export failed: ${e.message}`, true);
    return;
  }
  if (!cad.nurbs) {
    setStatus('nothing to export', true);
    return;
  }
  const r = await post('/api/export', Object.assign({ format }, cad.nurbs));
  if (!r.ok || (r.headers.get('content-type') || '').startsWith('application/json')) {
    const v = await r.json().catch(() => null);
    setStatus(`export failed: ${v && v.error ? v.error.message : r.status}`, true);
    return;
  }
  const blob = await r.blob();
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = `${state.mode}.${format}`;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setStatus(`exported ${a.download} (${blob.size} bytes${cad.note})`);
  document.body.dataset.exported = `${format}:${blob.size}`;
}
$('export-svg').addEventListener('click', () => exportAs('svg'));
$('fit').addEventListener('click', fitView);
$('undo').addEventListener('click', undo);
$('export-dxf').addEventListener('click', () => exportAs('dxf'));
$('export-step').addEventListener('click', () => exportAs('step'));

// ---------- hooks for the end-to-end tests ----------
window.__editor = {
  state,
  updates: () => updates,
  idle: () => !busy && !dirty && !drag && !regionBusy,
  maxServerMs: () => maxServerMs,
  serverMs: () => JSON.parse(JSON.stringify(serverMs)),
  // Page coordinates of handle i of the current mode.
  screenOf: (i) => {
    const r = view.getBoundingClientRect();
    const [x, y] = toScreen(handles()[i]);
    return [r.left + x * r.width / view.width, r.top + y * r.height / view.height];
  },
  // Page coordinates of a world point.
  view: () => Object.assign({}, box),
  pageOf: (p) => {
    const r = view.getBoundingClientRect();
    const [x, y] = toScreen(p);
    return [r.left + x * r.width / view.width, r.top + y * r.height / view.height];
  },
};

setMode('lac');
