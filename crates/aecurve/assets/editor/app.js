// aesthetic-curves editor: the page asks the local server for everything it shows (api.js)
// and only draws (draw.js). This module holds the state, the update loop, the interaction
// and the export; each mode's requests live in modes.js.
//
// The update loop runs one request chain at a time and the latest state wins; an answer is
// applied only if its mode is still the one on screen, so a curve is never drawn, numbered
// or exported under another mode's name.

import { api, post, timing } from './api.js';
import { drawCurvature, drawLcg, drawStage } from './draw.js';
import { contourState, fontSource, loadOutline, MODES, outlineSegments } from './modes.js';
import { $, fmt, setNumbers, setStatus, setVerdict } from './ui.js';
import { Viewport } from './view.js';

const view = $('view');
const ctx = view.getContext('2d');

// ---------- state ----------
const state = { mode: 'lac' };
for (const [m, def] of Object.entries(MODES)) state[m] = def.initial();
const views = {}; // each mode's current view (zoom, pan)
for (const [m, def] of Object.entries(MODES)) views[m] = Object.assign({}, def.box);
const vp = new Viewport(view, views.lac);
let frame = null; // the answer on screen: {mode, shown, nurbs, ...}
let region = null; // {grid, rows, key, mode}
let updates = 0;

const mode = () => MODES[state.mode];
const edited = () => state[state.mode];
const handles = () => mode().handles(edited());

// ---------- drawing ----------
// A local picture of what is being edited, before its answer arrives (a stroke as drawn).
let pending = null;
function draw() {
  const shown = pending || (frame && frame.mode === state.mode ? frame.shown : { handles: handles() });
  const reg = region && region.mode === state.mode && $('region').checked ? region : null;
  drawStage(vp, ctx, shown, reg, { comb: $('comb').checked });
  drawCurvature($('kplot'), shown);
}

function show(f) {
  frame = f;
  pending = null;
  setNumbers(f.numbers);
  setVerdict(...f.verdict);
  drawLcg($('lcg'), f.lcg.fit);
  $('lcg-note').textContent = f.lcg.note || '';
}

// ---------- the update loop ----------
let busy = false;
let dirty = false;
let drag = null; // {index}, {stroke: true} or {pan: world point}
function requestUpdate() {
  clearTimeout(regionTimer);
  if (busy) {
    dirty = true;
    return;
  }
  busy = true;
  dirty = false;
  const m = state.mode;
  MODES[m].update(edited(), { dragging: !!drag })
    .then((f) => {
      if (state.mode !== m) return; // the mode changed meanwhile: its own update follows
      show(Object.assign({ mode: m }, f));
      setStatus(`server ${fmt(timing.last, 2)} ms (largest so far ${fmt(timing.max, 2)} ms)`);
    })
    .catch((e) => {
      if (state.mode !== m) return;
      show({
        mode: m,
        shown: { handles: handles(), polygon: MODES[m].polygon ? handles() : null },
        nurbs: null,
        numbers: [['error', 'error', e.kind || 'error']],
        verdict: [e.message, false],
        lcg: { fit: null },
      });
      setStatus(e.message, true);
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

// Regions follow the editing: after every answered update, when what they depend on changed
// (the LAC and inflection regions take about a millisecond, the Bézier one about ten), with
// at most one region request in flight; the latest state wins.
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
  const m = state.mode;
  const req = MODES[m].region(edited(), (n) => vp.grid(n));
  if (!req) return;
  req.key = JSON.stringify([m, req.key, vp.box]);
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
  if (!v.ok || state.mode !== m) return;
  region = { grid: req.grid, rows: v.result.rows, key: req.key, mode: m };
  document.body.dataset.region = String(v.result.rows.join('').split('1').length - 1);
  document.body.dataset.regionFor = req.kind === 'bezier' ? `bezier:${req.index}` : req.kind;
  draw();
}

// ---------- interaction ----------
// Undo: the edited mode's state before each edit (Ctrl+Z).
const history = [];
function remember(m = state.mode) {
  history.push({ mode: m, data: JSON.parse(JSON.stringify(state[m])) });
  if (history.length > 200) history.shift();
}
function syncControls() {
  if (state.mode === 'lac') {
    $('alpha').value = state.lac.alpha;
    $('alpha-value').textContent = state.lac.alpha.toFixed(2);
  }
  if (state.mode === 'spline') $('closed').checked = state.spline.closed;
  if (state.mode === 'outline') syncOutline();
}
function undo() {
  for (let i = history.length - 1; i >= 0; i--) {
    if (history[i].mode === state.mode) {
      state[state.mode] = history.splice(i, 1)[0].data;
      syncControls();
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
  const [x, y] = vp.eventPixel(ev);
  let best = -1, bd = 12;
  handles().forEach((p, i) => {
    const [u, v] = vp.toScreen(p);
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
  const m = mode();
  if (ev.button === 2 || ev.button === 1 || ev.shiftKey) {
    drag = { pan: vp.eventWorld(ev) };
    return;
  }
  if (m.draws) {
    remember();
    edited().stroke = [vp.eventWorld(ev)];
    drag = { stroke: true };
    pending = { stroke: edited().stroke };
    draw();
    return;
  }
  const i = nearestHandle(ev);
  if (i >= 0) {
    remember();
    drag = { index: i };
    if ('selected' in edited()) {
      edited().selected = i;
      if (frame && frame.mode === state.mode) frame.shown.selected = i;
      draw();
    }
    return;
  }
  if (m.addsPoints) {
    remember();
    edited().p.push(vp.eventWorld(ev));
    drag = { index: edited().p.length - 1 };
    requestUpdate();
  }
});
view.addEventListener('pointermove', (ev) => {
  if (!drag) return;
  const w = vp.eventWorld(ev);
  if (drag.pan) {
    // Keep the grabbed world point under the pointer.
    vp.pan(drag.pan[0] - w[0], drag.pan[1] - w[1]);
    draw();
    return;
  }
  if (drag.stroke) {
    const s = edited().stroke;
    const last = s[s.length - 1];
    if (Math.hypot(w[0] - last[0], w[1] - last[1]) * vp.scale() >= 2) {
      s.push(w);
      draw();
    }
    return;
  }
  edited().p[drag.index] = w;
  requestUpdate();
});
const endDrag = () => {
  if (!drag) return;
  const panned = drag.pan;
  drag = null;
  if (panned) regionUpdate();
  else requestUpdate();
};
view.addEventListener('pointerup', endDrag);
view.addEventListener('pointercancel', endDrag);
// Wheel: zoom about the pointer.
view.addEventListener('wheel', (ev) => {
  ev.preventDefault();
  vp.zoom(vp.eventWorld(ev), Math.pow(1.0015, ev.deltaY));
  draw();
  regionUpdate();
}, { passive: false });
// Fit the view to what is drawn.
function fitView() {
  const shown = frame && frame.mode === state.mode ? frame.shown : {};
  if (vp.fit([].concat(shown.curve || [], handles(), shown.stroke || []))) {
    draw();
    regionUpdate();
  }
}

$('alpha').addEventListener('pointerdown', () => remember());
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
  const p = edited().p;
  const last = p[p.length - 1];
  p.push([Math.min(vp.box.x1 - 1, last[0] + 1.5), last[1]]);
  requestUpdate();
});
$('remove-point').addEventListener('click', () => {
  remember();
  const st = edited();
  if (st.p.length > (mode().minPoints || 0)) st.p.pop();
  if ('selected' in st) st.selected = Math.min(st.selected, st.p.length - 1);
  requestUpdate();
});
$('clear').addEventListener('click', () => {
  remember();
  const st = edited();
  if (mode().draws) st.stroke = [];
  else st.p = [];
  requestUpdate();
});
for (const b of document.querySelectorAll('#modes button')) {
  b.addEventListener('click', () => setMode(b.dataset.mode));
}
$('sketch-tolerance').addEventListener('change', () => {
  const v = parseFloat($('sketch-tolerance').value);
  edited().tolerance = v > 0 ? v : null;
  requestUpdate();
});
const OPTIONAL = ['alpha-box', 'closed-box', 'region-box', 'add-point', 'remove-point', 'clear', 'outline-box', 'sketch-tolerance-box'];
function setMode(m) {
  state.mode = m;
  vp.box = views[m];
  region = null;
  pending = null;
  for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('active', b.dataset.mode === m);
  for (const id of OPTIONAL) $(id).classList.toggle('hidden', !MODES[m].controls.includes(id));
  $('hint').textContent = MODES[m].hint;
  syncControls();
  draw();
  requestUpdate();
}

// ---------- outline mode: loading ----------
// The shape and contour pickers show what the loaded outline holds.
function syncOutline() {
  const st = state.outline;
  const opts = (sel, labels, chosen) => {
    sel.replaceChildren(...labels.map((t, i) => {
      const o = document.createElement('option');
      o.value = String(i);
      o.textContent = t;
      o.selected = i === chosen;
      return o;
    }));
  };
  opts($('outline-shape'), st.names, st.shape);
  opts($('outline-contour'), Array.from({ length: st.contours }, (_, i) => String(i + 1)), st.contour);
}
async function outlineLoad(req, shape, contour, firstDrawn) {
  const st = JSON.parse(JSON.stringify(state.outline));
  st.ghost = null;
  $('outline-tolerance').value = '';
  try {
    await loadOutline(st, req, shape, contour, firstDrawn);
  } catch (e) {
    setStatus(`could not load: ${e.message}`, true);
    return;
  }
  // Undo restores the outline mode's previous contour, whatever mode it was loaded from.
  remember('outline');
  state.outline = st;
  syncOutline();
  frame = null;
  if (state.mode !== 'outline') setMode('outline');
  const b = st.p.reduce((a, q) => [Math.min(a[0], q[0]), Math.min(a[1], q[1]), Math.max(a[2], q[0]), Math.max(a[3], q[1])], [Infinity, Infinity, -Infinity, -Infinity]);
  vp.fit([[b[0], b[1]], [b[2], b[3]]]);
  requestUpdate();
}
// ---------- outline mode: fix and save ----------
// The tolerance box shows the default for the contour: 0.5 % of its size (at least 1 unit on
// a font's grid).
function outlineTolerance(st) {
  const v = parseFloat($('outline-tolerance').value);
  if (v > 0) return v;
  const xs = st.p.map((q) => q[0]), ys = st.p.map((q) => q[1]);
  const size = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
  const t = fontSource(st) ? Math.max(1, Math.round(0.005 * size)) : Number((0.005 * size).toPrecision(2));
  $('outline-tolerance').value = String(t);
  return t;
}
async function outlineFix() {
  const st = state.outline;
  const tolerance = outlineTolerance(st);
  let r;
  try {
    r = await api({ op: 'outline.fix', segments: outlineSegments(st), closed: st.closed, tolerance, grid: fontSource(st) ? 1 : 0 });
  } catch (e) {
    setStatus(`fix failed: ${e.message}`, true);
    return;
  }
  if (state.mode !== 'outline' || state.outline !== st) return;
  const smooth = r.joins.filter((j) => j.smooth && j.jump);
  const under = (k) => smooth.filter((j) => j.jump[k] < 0.01).length;
  remember('outline');
  const ghost = frame && frame.mode === 'outline' ? { curve: frame.shown.curve, kappa: frame.shown.kappa, normals: frame.shown.normals } : null;
  Object.assign(st, contourState({ closed: r.closed, segments: r.segments.map((s) => ({ control_points: s.control_points, weights: s.control_points.map(() => 1) })) }), { ghost: st.ghost || ghost });
  const note = `fixed: ${r.changed_segments} segment(s) changed, ${r.bumps_removed} hook(s) removed; smooth joins under a 1 % curvature jump ${under(0)} → ${under(1)} of ${smooth.length}; no point moved more than ${fmt(r.max_moved, 3)} (tolerance ${tolerance})`;
  setStatus(note);
  // Kept for the page (and the tests) after the re-check's own status replaces it.
  $('hint').textContent = note;
  document.body.dataset.fixed = note;
  requestUpdate();
}
$('outline-fix').addEventListener('click', outlineFix);

// The contour as text a designer's tools read: SVG path data (y flipped back for a font or a
// drawing, so the file shows it upright) and a UFO .glif (font units as they are).
function contourSvg(st) {
  const flip = fontSource(st);
  const q = (p) => `${fmt(p[0], 6)} ${fmt(flip ? -p[1] : p[1], 6)}`;
  let d = '';
  st.segs.forEach((idx, k) => {
    const pts = idx.map((i) => st.p[i]);
    if (k === 0) d += `M ${q(pts[0])}`;
    d += pts.length === 4 ? ` C ${q(pts[1])} ${q(pts[2])} ${q(pts[3])}` : pts.length === 3 ? ` Q ${q(pts[1])} ${q(pts[2])}` : ` L ${q(pts[pts.length - 1])}`;
  });
  if (st.closed) d += ' Z';
  const xs = st.p.map((p) => p[0]), ys = st.p.map((p) => (flip ? -p[1] : p[1]));
  const [x0, y0] = [Math.min(...xs), Math.min(...ys)];
  const [w, h] = [Math.max(...xs) - x0 || 1, Math.max(...ys) - y0 || 1];
  const pad = 0.05 * Math.max(w, h);
  return `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${fmt(x0 - pad, 6)} ${fmt(y0 - pad, 6)} ${fmt(w + 2 * pad, 6)} ${fmt(h + 2 * pad, 6)}">\n  <path fill="none" stroke="black" stroke-width="${fmt(0.004 * Math.max(w, h), 3)}" d="${d}"/>\n</svg>\n`;
}
function contourGlif(st) {
  const name = String(st.name || 'contour').replace(/[&<>"]/g, '_');
  const pts = [];
  const n = st.segs.length;
  st.segs.forEach((idx, k) => {
    const c = idx.map((i) => st.p[i]);
    // Smooth where the tangent breaks by at most 0.5° (what fix takes as smooth).
    const next = st.segs[(k + 1) % n].map((i) => st.p[i]);
    const a = [c[c.length - 1][0] - c[c.length - 2][0], c[c.length - 1][1] - c[c.length - 2][1]];
    const b = [next[1][0] - next[0][0], next[1][1] - next[0][1]];
    const joined = st.closed || k < n - 1;
    const smooth = joined && Math.abs(Math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])) <= 0.5 * Math.PI / 180;
    const type = c.length === 4 ? 'curve' : c.length === 3 ? 'qcurve' : 'line';
    c.slice(1, -1).forEach((p) => pts.push(`      <point x="${fmt(p[0], 6)}" y="${fmt(p[1], 6)}"/>`));
    pts.push(`      <point x="${fmt(c[c.length - 1][0], 6)}" y="${fmt(c[c.length - 1][1], 6)}" type="${type}"${smooth ? ' smooth="yes"' : ''}/>`);
  });
  if (!st.closed) {
    const p0 = st.p[st.segs[0][0]];
    pts.unshift(`      <point x="${fmt(p0[0], 6)}" y="${fmt(p0[1], 6)}" type="move"/>`);
  } else {
    // A closed contour starts at its first on-curve point: the last point written is it.
    pts.unshift(pts.pop());
  }
  return `<?xml version="1.0" encoding="UTF-8"?>\n<glyph name="${name}" format="2">\n  <outline>\n    <contour>\n${pts.join('\n')}\n    </contour>\n  </outline>\n</glyph>\n`;
}
function download(text, filename, type) {
  const blob = new Blob([text], { type });
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setStatus(`saved ${filename} (${blob.size} bytes)`);
  document.body.dataset.exported = `${filename}:${blob.size}`;
}
$('outline-save-glif').addEventListener('click', () => {
  const st = state.outline;
  download(contourGlif(st), `${String(st.name || 'contour').replace(/[^\w.-]/g, '_')}.glif`, 'application/xml');
});

// A file: SVG as text, fonts and DXF as base64 (the server reads every one).
async function outlineFile(file) {
  if (file.size > 3 * 1024 * 1024) {
    setStatus(`${file.name}: larger than 3 MB`, true);
    return;
  }
  if (/\.svg$/i.test(file.name)) {
    await outlineLoad({ svg: await file.text() }, 0, 0, true);
    return;
  }
  const bytes = new Uint8Array(await file.arrayBuffer());
  let bin = '';
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  await outlineLoad({ file: { name: file.name, base64: btoa(bin) } }, 0, 0, true);
}
$('outline-load').addEventListener('click', () => outlineLoad({ path: $('outline-path').value }, 0, 0));
$('outline-file').addEventListener('change', () => {
  const f = $('outline-file').files[0];
  if (f) outlineFile(f);
});
$('outline-shape').addEventListener('change', () => {
  const st = state.outline;
  if (st.source) outlineLoad(st.source, +$('outline-shape').value, 0);
});
$('outline-contour').addEventListener('change', () => {
  const st = state.outline;
  if (st.source) outlineLoad(st.source, st.shape, +$('outline-contour').value);
});
view.addEventListener('dragover', (ev) => ev.preventDefault());
view.addEventListener('drop', (ev) => {
  ev.preventDefault();
  const f = ev.dataTransfer && ev.dataTransfer.files[0];
  if (f) outlineFile(f);
});
syncOutline();

// ---------- export ----------
// CAD geometry of a LAC or inflection-end segment: rational cubics within 1e-7 of its size
// (G2, every piece proven curvature-monotone), not the single cubic drawn as the overlay.
// Other modes export the curve on screen, as the server sent it with its answer.
async function cadSpline(m) {
  if (m !== 'lac' && m !== 'inflection') {
    return { nurbs: frame && frame.mode === m ? frame.nurbs : null, note: '' };
  }
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
  const m = state.mode;
  if (m === 'outline') {
    // The edited or fixed contour itself: as SVG path data (DXF and STEP are for curves drawn here).
    if (format !== 'svg') {
      setStatus('an outline is saved as SVG (Export SVG) or as a UFO .glif (Save .glif)', true);
      return;
    }
    const st = state.outline;
    download(contourSvg(st), `${String(st.name || 'contour').replace(/[^\w.-]/g, '_')}.svg`, 'image/svg+xml');
    return;
  }
  let cad;
  try {
    cad = await cadSpline(m);
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
  if (state.mode !== m) return; // switched away meanwhile: no file under the wrong name
  const blob = await r.blob();
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = `${m}.${format}`;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setStatus(`exported ${a.download} (${blob.size} bytes${cad.note})`);
  document.body.dataset.exported = `${format}:${blob.size}`;
}
$('export-svg').addEventListener('click', () => exportAs('svg'));
$('export-dxf').addEventListener('click', () => exportAs('dxf'));
$('export-step').addEventListener('click', () => exportAs('step'));
$('fit').addEventListener('click', fitView);
$('undo').addEventListener('click', undo);

// ---------- hooks for the end-to-end tests ----------
window.__editor = {
  state,
  updates: () => updates,
  idle: () => !busy && !dirty && !drag && !regionBusy,
  maxServerMs: () => timing.max,
  serverMs: () => JSON.parse(JSON.stringify(timing.perOp)),
  // Page coordinates of handle i of the current mode.
  screenOf: (i) => vp.pageOf(handles()[i]),
  view: () => Object.assign({}, vp.box),
  // Page coordinates of a world point.
  pageOf: (p) => vp.pageOf(p),
  // Which mode the answer on screen belongs to.
  frameMode: () => (frame ? frame.mode : null),
};

setMode('lac');
