// aesthetic-curves editor: the page asks the local server for everything it shows (api.js)
// and only draws (draw.js). This module holds the state, the update loop, the interaction
// and the export; each mode's requests live in modes.js.
//
// The update loop runs one request chain at a time and the latest state wins; an answer is
// applied only if its mode is still the one on screen, so a curve is never drawn, numbered
// or exported under another mode's name.

import { api, post, timing } from './api.js';
import { combLength, curvatureIndexAt, drawCurvature, drawLcg, drawStage } from './draw.js';
import { contourState, fontSource, loadOutline, MODES, outlineSegments } from './modes.js';
import { $, fmt, setNumbers, setStatus, setVerdict } from './ui.js';
import { Viewport } from './view.js';

const view = $('view');
const ctx = view.getContext('2d');

// ---------- state ----------
const state = { mode: 'g2' };
for (const [m, def] of Object.entries(MODES)) state[m] = def.initial();
const views = {}; // each mode's current view (zoom, pan)
for (const [m, def] of Object.entries(MODES)) views[m] = Object.assign({}, def.box);
const vp = new Viewport(view, views.g2);
let frame = null; // the answer on screen: {mode, shown, nurbs, ...}
let region = null; // {grid, rows, key, mode}
let updates = 0;

const mode = () => MODES[state.mode];
const edited = () => state[state.mode];
const handles = () => mode().handles(edited());

// ---------- drawing ----------
// A local picture of what is being edited, before its answer arrives (a stroke as drawn).
let pending = null;
// The comb's tooth length held while a drag goes on (so teeth compare), and the sample of
// the curve under the pointer (on the stage or the curvature plot).
let heldComb = null;
let hover = null;
function draw() {
  const shown = pending || (frame && frame.mode === state.mode ? frame.shown : { handles: handles() });
  const reg = region && region.mode === state.mode && $('region').checked ? region : null;
  const gain = +$('comb-gain').value;
  drawStage(vp, ctx, shown, reg, { comb: $('comb').checked, gain, fixedLength: drag && !drag.pan ? heldComb : null, hover });
  drawCurvature($('kplot'), shown, hover);
}

// Canvases take the size the layout gives them (the window's), in CSS pixels.
function fitCanvases() {
  for (const c of [view, $('kplot')]) {
    const w = Math.max(100, Math.round(c.clientWidth)), h = Math.max(60, Math.round(c.clientHeight));
    if (c.width !== w || c.height !== h) {
      c.width = w;
      c.height = h;
    }
  }
  draw();
}
new ResizeObserver(fitCanvases).observe(view);

function show(f) {
  frame = f;
  pending = null;
  setNumbers(f.numbers);
  setVerdict(...f.verdict);
  drawLcg($('lcg'), f.lcg.fit);
  // No graph (splines, sketches, outlines): the note alone, not an empty box above it.
  $('lcg').hidden = !f.lcg.fit;
  $('lcg-note').textContent = f.lcg.note || '';
}

// ---------- the update loop ----------
let busy = false;
let dirty = false;
const lastGood = {}; // each mode's state at its last answered update
const lastFrame = {}; // each mode's last answer, shown again when an update fails

// What a failed update means for the designer, and what to do about it (the server's own
// message goes to the status line).
function advice(e, m, kept) {
  const what = {
    no_convergence: m === 'g2'
      ? 'No G2 curve goes through these points here.'
      : 'No fair curve was found for this input.',
    no_segment: 'No curve of this alpha fits between these points.',
    degenerate: 'Two points coincide or the points lie on a line.',
    invalid_input: 'This input cannot be used.',
    timeout: 'This took too long to answer.',
  }[e.kind] || 'This could not be drawn.';
  const todo = {
    no_convergence: 'Move the marked point back a little, add a point between far-apart ones, or try another alpha.',
    no_segment: 'Move the marked point, or change alpha.',
    degenerate: 'Move one of the points apart.',
    timeout: 'Use fewer points, or a larger tolerance.',
  }[e.kind] || '';
  const shown = kept ? ' The last good curve is shown.' : '';
  return `${what} ${todo}${shown}`;
}
let released = false; // a point drag just ended: its last update may still be on the way
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
      lastGood[m] = JSON.parse(JSON.stringify(state[m]));
      lastFrame[m] = Object.assign({ mode: m }, f);
      show(lastFrame[m]);
      setStatus(`server ${fmt(timing.last, 2)} ms (largest so far ${fmt(timing.max, 2)} ms)`);
    })
    .catch((e) => {
      if (state.mode !== m) return;
      // A dragged LAC or inflection point leaving the existence region stays at its edge:
      // the last position that had a segment.
      if (((drag && drag.index != null) || released) && lastGood[m] && (m === 'lac' || m === 'inflection') && (e.kind === 'no_segment' || e.kind === 'degenerate')) {
        state[m] = JSON.parse(JSON.stringify(lastGood[m]));
        setStatus(`held at the edge of the existence region (${e.kind === 'degenerate' ? 'a flat triangle' : 'no segment beyond it'})`);
        document.body.dataset.held = String(+(document.body.dataset.held || 0) + 1);
        draw();
        return;
      }
      // The last good curve stays on screen, with the points as they are now and the one
      // being moved marked; the message says once, in a designer's words, what to do.
      const last = lastFrame[m];
      const fault = drag && drag.index != null ? drag.index : (state[m] && state[m].selected != null ? state[m].selected : null);
      const now = handles();
      show({
        mode: m,
        shown: Object.assign({}, last ? last.shown : {}, {
          handles: now,
          polygon: MODES[m].polygon ? now : last && last.shown.polygon,
          fault: fault != null ? now[fault] : null,
        }),
        nurbs: last ? last.nurbs : null,
        numbers: last ? last.numbers : [['error', 'error', e.kind || 'error']],
        verdict: [advice(e, m, last != null), false],
        lcg: last ? last.lcg : { fit: null },
      });
      document.body.dataset.kept = String(+(document.body.dataset.kept || 0) + (last ? 1 : 0));
      // The server's own words once, in the status line; the verdict says what to do.
      setStatus(e.message, true);
    })
    .finally(() => {
      busy = false;
      if (!dirty) released = false;
      saveSession();
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
    // `key` is the page's own (which state the region is for): the server takes only the
    // request's fields.
    const { key: _key, ...body } = req;
    v = await (await post('/api/region', body)).json();
  } finally {
    regionBusy = false;
    if (regionAgain) {
      regionAgain = false;
      regionUpdate();
    }
  }
  if (state.mode !== m) return;
  if (!v.ok) {
    // Said, not swallowed: a region the server refuses (over its work budget, a bad field).
    setStatus(`region: ${v.error.message}`, true);
    return;
  }
  region = { grid: req.grid, rows: v.result.rows, key: req.key, mode: m };
  document.body.dataset.region = String(v.result.rows.join('').split('1').length - 1);
  document.body.dataset.regionFor = req.kind === 'bezier' ? `bezier:${req.index}` : req.kind;
  draw();
}

// ---------- interaction ----------
// Undo and redo: the edited mode's state before each edit (Ctrl+Z), and what undo took back
// (Ctrl+Shift+Z or Ctrl+Y); a new edit clears the redo list.
const history = [];
const redoList = [];
function remember(m = state.mode) {
  history.push({ mode: m, data: JSON.parse(JSON.stringify(state[m])) });
  if (history.length > 200) history.shift();
  redoList.length = 0;
}
function syncControls() {
  if (state.mode === 'lac') {
    $('alpha').value = state.lac.alpha;
    $('alpha-value').value = state.lac.alpha;
  }
  if (state.mode === 'spline' || state.mode === 'g2') $('closed').checked = state[state.mode].closed;
  if (state.mode === 'g2') {
    $('g2-alpha').value = state.g2.alpha;
    $('g2-alpha-range').value = state.g2.alpha;
    syncPoint();
  }
  if (state.mode === 'outline') syncOutline();
}
function swap(from, to) {
  for (let i = from.length - 1; i >= 0; i--) {
    if (from[i].mode === state.mode) {
      to.push({ mode: state.mode, data: JSON.parse(JSON.stringify(state[state.mode])) });
      state[state.mode] = from.splice(i, 1)[0].data;
      syncControls();
      requestUpdate();
      return;
    }
  }
}
const undo = () => swap(history, redoList);
const redo = () => swap(redoList, history);
const typing = (ev) => ev.target instanceof HTMLInputElement || ev.target instanceof HTMLTextAreaElement;
document.addEventListener('keydown', (ev) => {
  const mod = ev.ctrlKey || ev.metaKey;
  if (mod && (ev.key === 'y' || (ev.key.toLowerCase() === 'z' && ev.shiftKey))) {
    ev.preventDefault();
    redo();
    return;
  }
  if (mod && ev.key === 'z') {
    ev.preventDefault();
    undo();
    return;
  }
  if (typing(ev)) return;
  if (ev.key === 'f') fitView();
  if (state.mode === 'g2' && (ev.key === 'Delete' || ev.key === 'Backspace')) {
    ev.preventDefault();
    removePoint();
  }
  if (state.mode === 'g2' && ev.key === 'c') toggleCorner(state.g2.selected);
});

// ---------- the G2 spline: points, corners, the selected point ----------
function syncPoint() {
  const st = state.g2;
  const q = st.p[st.selected];
  for (const id of ['point-x', 'point-y', 'point-corner']) $(id).disabled = !q;
  $('point-x').value = q ? String(+q[0].toPrecision(10)) : '';
  $('point-y').value = q ? String(+q[1].toPrecision(10)) : '';
  $('point-corner').checked = !!q && st.corners.includes(st.selected);
  // The last point of an open curve starts no span.
  const starts = !!q && (st.closed || st.selected < st.p.length - 1);
  $('point-alpha').disabled = !starts;
  const own = st.spanAlphas.find(([i]) => i === st.selected);
  $('point-alpha').value = starts && own ? String(own[1]) : '';
}
// The span from point i takes α `v` (null: the curve's again).
function setSpanAlpha(i, v) {
  const st = state.g2;
  st.spanAlphas = st.spanAlphas.filter(([k]) => k !== i);
  if (v !== null) st.spanAlphas = st.spanAlphas.concat([[i, v]]).sort((a, b) => a[0] - b[0]);
}
function select(i) {
  const st = edited();
  if (!('selected' in st)) return;
  st.selected = i;
  if (frame && frame.mode === state.mode) frame.shown.selected = i;
  if (state.mode === 'g2') syncPoint();
  draw();
}
function toggleCorner(i) {
  const st = state.g2;
  if (!(i >= 0 && i < st.p.length)) return;
  remember();
  st.corners = st.corners.includes(i) ? st.corners.filter((k) => k !== i) : st.corners.concat([i]).sort((a, b) => a - b);
  syncPoint();
  requestUpdate();
}
// Insert a point at index i (corners after it move up by one; both halves of the span it
// splits keep that span's α).
function insertPoint(i, w) {
  const st = state.g2;
  st.p.splice(i, 0, w);
  st.corners = st.corners.map((k) => (k >= i ? k + 1 : k));
  const split = st.spanAlphas.find(([k]) => k === i - 1);
  st.spanAlphas = st.spanAlphas.map(([k, a]) => [k >= i ? k + 1 : k, a]);
  if (split) setSpanAlpha(i, split[1]);
  st.selected = i;
}
function removePoint() {
  remember();
  const st = edited();
  if (state.mode === 'g2') {
    const i = st.selected >= 0 && st.selected < st.p.length ? st.selected : st.p.length - 1;
    if (i < 0) return;
    st.p.splice(i, 1);
    st.corners = st.corners.filter((k) => k !== i).map((k) => (k > i ? k - 1 : k));
    // The two spans at the point become one, with the first one's α.
    st.spanAlphas = st.spanAlphas.filter(([k]) => k !== i).map(([k, a]) => [k > i ? k - 1 : k, a]);
    st.selected = Math.min(i, st.p.length - 1);
    syncPoint();
  } else {
    if (st.p.length > (mode().minPoints || 0)) st.p.pop();
    if ('selected' in st) st.selected = Math.min(st.selected, st.p.length - 1);
  }
  requestUpdate();
}
// Which span of the G2 spline passes within 8 pixels of the pointer, and where.
function spanUnder(ev) {
  if (!frame || frame.mode !== 'g2' || !frame.shown.curve || !frame.shown.spans) return null;
  const best = nearestOnScreen(ev, frame.shown.curve, 8);
  if (best < 0) return null;
  const per = frame.shown.pieces[0].length - 1;
  const piece = Math.min(Math.floor(best / per), frame.shown.spans.length - 1);
  return frame.shown.spans[piece];
}
// Shift while dragging a G2 point: the move snapped to horizontal or vertical from where the
// drag began, or the segment from the previous point made horizontal or vertical, whichever
// is nearer.
function snapped(w, from, prev) {
  const opts = [[w[0], from[1]], [from[0], w[1]]];
  if (prev) opts.push([w[0], prev[1]], [prev[0], w[1]]);
  return opts.reduce((a, b) => (Math.hypot(a[0] - w[0], a[1] - w[1]) <= Math.hypot(b[0] - w[0], b[1] - w[1]) ? a : b));
}
for (const id of ['point-x', 'point-y']) {
  $(id).addEventListener('change', () => {
    const st = state.g2;
    const q = st.p[st.selected];
    const v = parseFloat($(id).value);
    if (!q || !Number.isFinite(v)) return;
    remember();
    q[id === 'point-x' ? 0 : 1] = v;
    requestUpdate();
  });
}
$('point-corner').addEventListener('change', () => toggleCorner(state.g2.selected));
$('point-alpha').addEventListener('change', () => {
  const st = state.g2;
  if (!(st.selected >= 0 && st.selected < st.p.length)) return;
  const typed = $('point-alpha').value.trim();
  const v = parseFloat(typed);
  if (typed !== '' && !Number.isFinite(v)) return;
  remember();
  setSpanAlpha(st.selected, typed === '' ? null : Math.max(-5, Math.min(5, v)));
  syncPoint();
  requestUpdate();
});
const setG2Alpha = (v) => {
  if (!Number.isFinite(v)) return;
  state.g2.alpha = Math.max(-5, Math.min(5, v));
  $('g2-alpha').value = state.g2.alpha;
  $('g2-alpha-range').value = state.g2.alpha;
  requestUpdate();
};
$('g2-alpha-range').addEventListener('pointerdown', () => remember());
$('g2-alpha-range').addEventListener('input', () => setG2Alpha(+$('g2-alpha-range').value));
$('g2-alpha').addEventListener('change', () => {
  remember();
  setG2Alpha(parseFloat($('g2-alpha').value));
});
// The index of the world point of `pts` nearest the pointer on screen, within `radius`
// pixels; -1 when none is.
function nearestOnScreen(ev, pts, radius) {
  const [x, y] = vp.eventPixel(ev);
  let best = -1, bd = radius;
  pts.forEach((p, i) => {
    const [u, v] = vp.toScreen(p);
    const d = Math.hypot(u - x, v - y);
    if (d < bd) {
      bd = d;
      best = i;
    }
  });
  return best;
}
const nearestHandle = (ev) => nearestOnScreen(ev, handles(), 12);
view.addEventListener('contextmenu', (ev) => ev.preventDefault());
view.addEventListener('pointerdown', (ev) => {
  view.setPointerCapture(ev.pointerId);
  const m = mode();
  const i = m.draws ? -1 : nearestHandle(ev);
  // Shift on a G2 point snaps its move; elsewhere Shift (or the right or middle button) pans.
  if (ev.button === 2 || ev.button === 1 || (ev.shiftKey && !(state.mode === 'g2' && i >= 0))) {
    drag = { pan: vp.eventWorld(ev) };
    return;
  }
  holdComb();
  if (m.draws) {
    remember();
    edited().stroke = [vp.eventWorld(ev)];
    edited().resolution = vp.pointerResolution();
    drag = { stroke: true };
    pending = { stroke: edited().stroke };
    draw();
    return;
  }
  if (i >= 0) {
    if (state.mode === 'g2' && ev.altKey) {
      select(i);
      toggleCorner(i);
      return;
    }
    remember();
    const p = edited().p;
    drag = { index: i, from: p[i].slice(), prev: i > 0 ? p[i - 1].slice() : null };
    if ('selected' in edited()) select(i);
    return;
  }
  if (state.mode === 'g2') {
    const span = spanUnder(ev);
    remember();
    if (span != null) insertPoint(span + 1, vp.eventWorld(ev));
    else insertPoint(state.g2.p.length, vp.eventWorld(ev));
    drag = { index: state.g2.selected, from: vp.eventWorld(ev), prev: null };
    syncPoint();
    requestUpdate();
    return;
  }
  if (m.addsPoints && edited().p.length < (m.maxPoints || Infinity)) {
    remember();
    edited().p.push(vp.eventWorld(ev));
    drag = { index: edited().p.length - 1 };
    if ('selected' in edited()) select(edited().p.length - 1);
    requestUpdate();
  }
});
// The comb's scale at the start of a drag, kept until it ends.
function holdComb() {
  const shown = frame && frame.mode === state.mode ? frame.shown : null;
  heldComb = shown && shown.curve ? combLength(vp, shown, +$('comb-gain').value) : null;
}
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
  edited().p[drag.index] = ev.shiftKey && state.mode === 'g2' ? snapped(w, drag.from, drag.prev) : w;
  if (state.mode === 'g2') syncPoint();
  requestUpdate();
});
// Hover: the place on the curve and on the curvature plot, linked.
view.addEventListener('pointermove', (ev) => {
  if (drag || !frame || frame.mode !== state.mode || !frame.shown.curve) return;
  const i = nearestOnScreen(ev, frame.shown.curve, 12);
  const best = i < 0 ? null : i;
  if (best !== hover) {
    hover = best;
    draw();
  }
});
$('kplot').addEventListener('pointermove', (ev) => {
  if (!frame || frame.mode !== state.mode) return;
  const r = $('kplot').getBoundingClientRect();
  hover = curvatureIndexAt($('kplot'), frame.shown, (ev.clientX - r.left) * $('kplot').width / r.width);
  document.body.dataset.hover = String(hover);
  draw();
});
$('kplot').addEventListener('pointerleave', () => {
  hover = null;
  draw();
});
const endDrag = () => {
  if (!drag) return;
  const panned = drag.pan;
  released = drag.index != null;
  drag = null;
  heldComb = null;
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
  $('alpha-value').value = state.lac.alpha;
  requestUpdate();
});
// Typed: any alpha the library builds (|alpha| up to 1e6), beyond the slider's -5..5.
$('alpha-value').addEventListener('change', () => {
  const v = parseFloat($('alpha-value').value);
  if (!Number.isFinite(v) || Math.abs(v) > 1e6) {
    setStatus('alpha must be a number within ±1e6', true);
    return;
  }
  remember();
  state.lac.alpha = v;
  $('alpha').value = v;
  requestUpdate();
});
$('closed').addEventListener('change', () => {
  remember();
  edited().closed = $('closed').checked;
  requestUpdate();
});
$('comb').addEventListener('change', draw);
$('comb-gain').addEventListener('input', () => {
  saveSession();
  draw();
});
$('region').addEventListener('change', () => {
  region = null;
  draw();
  regionUpdate();
});
// "+ point": one more point a step (0.15 of the view) on from the last along the last side,
// or turned from it by 45° at a time until it lands inside the view and away from the
// points already there. Clicking the canvas adds a point where it is clicked.
$('add-point').addEventListener('click', () => {
  const p = edited().p;
  if (p.length >= (mode().maxPoints || Infinity)) {
    setStatus(`at most ${mode().maxPoints} points`, true);
    return;
  }
  remember();
  const b = vp.box;
  const size = Math.min(b.x1 - b.x0, b.y1 - b.y0);
  const last = p[p.length - 1] || [(b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2];
  const prev = p[p.length - 2] || [last[0] - 1, last[1]];
  const a0 = Math.atan2(last[1] - prev[1], last[0] - prev[0]);
  const ok = (q) => q[0] > b.x0 + 0.08 * size && q[0] < b.x1 - 0.08 * size && q[1] > b.y0 + 0.08 * size && q[1] < b.y1 - 0.08 * size
    && p.every((v) => Math.hypot(v[0] - q[0], v[1] - q[1]) > 0.05 * size);
  const at = (a) => [last[0] + 0.15 * size * Math.cos(a), last[1] + 0.15 * size * Math.sin(a)];
  const turns = [0, 1, -1, 2, -2, 3, -3, 4].map((k) => a0 + k * Math.PI / 4);
  const q = turns.map(at).find(ok) || [(b.x0 + b.x1) / 2 + 0.05 * size * p.length, (b.y0 + b.y1) / 2];
  p.push(q);
  if ('selected' in edited()) edited().selected = p.length - 1;
  requestUpdate();
});
$('remove-point').addEventListener('click', removePoint);
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
const OPTIONAL = ['alpha-box', 'g2-alpha-box', 'point-box', 'closed-box', 'region-box', 'add-point', 'remove-point', 'clear', 'outline-box', 'sketch-tolerance-box'];
function setMode(m) {
  state.mode = m;
  hover = null;
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
  // The glyph list, filtered by the search box (a font has thousands of names).
  const q = $('outline-search').value.trim().toLowerCase();
  const sel = $('outline-shape');
  const keep = st.names.map((t, i) => [t, i]).filter(([t, i]) => !q || i === st.shape || t.toLowerCase().includes(q));
  sel.replaceChildren(...keep.map(([t, i]) => {
    const o = document.createElement('option');
    o.value = String(i);
    o.textContent = t;
    o.selected = i === st.shape;
    return o;
  }));
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
$('outline-search').addEventListener('input', () => {
  const st = state.outline;
  syncOutline();
  // The best match is loaded: the name itself, then the name in any case, then the first
  // that starts with the text, then the first that holds it.
  const raw = $('outline-search').value.trim();
  const q = raw.toLowerCase();
  if (!q || !st.source) return;
  const tests = [(t) => t === raw, (t) => t.toLowerCase() === q, (t) => t.toLowerCase().startsWith(q), (t) => t.toLowerCase().includes(q)];
  for (const test of tests) {
    const i = st.names.findIndex(test);
    if (i >= 0) {
      if (i !== st.shape) outlineLoad(st.source, i, 0);
      return;
    }
  }
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
$('redo').addEventListener('click', redo);

// ---------- the session: kept across a reload, saved to and loaded from a file ----------
// Every mode's points and options, the view of each, the current mode, the comb's gain and
// the loaded outline (with its file, when the browser's storage holds it).
const SESSION = 'aesthetic-curves-session';
function sessionOf() {
  return { version: 1, mode: state.mode, states: Object.fromEntries(Object.keys(MODES).map((m) => [m, state[m]])), views, gain: +$('comb-gain').value };
}
function saveSession() {
  try {
    localStorage.setItem(SESSION, JSON.stringify(sessionOf()));
  } catch {
    // Over the storage quota (a large font): keep everything but the outline's file.
    try {
      const s = sessionOf();
      s.states.outline = Object.assign({}, s.states.outline, { source: null });
      localStorage.setItem(SESSION, JSON.stringify(s));
    } catch {
      // no storage: nothing kept
    }
  }
}
// Apply a saved session (from storage or a file); false when it is not one.
function applySession(s) {
  if (!s || s.version !== 1 || !s.states || !MODES[s.mode]) return false;
  for (const m of Object.keys(MODES)) {
    if (s.states[m] && typeof s.states[m] === 'object') state[m] = Object.assign(MODES[m].initial(), s.states[m]);
  }
  for (const m of Object.keys(MODES)) if (s.views && s.views[m]) views[m] = Object.assign({}, MODES[m].box, s.views[m]);
  if (Number.isFinite(s.gain)) $('comb-gain').value = s.gain;
  frame = null;
  setMode(s.mode);
  return true;
}
$('session-save').addEventListener('click', () => {
  download(JSON.stringify(sessionOf(), null, 1), 'aesthetic-curves-session.json', 'application/json');
});
$('session-file').addEventListener('change', async () => {
  const f = $('session-file').files[0];
  if (!f) return;
  let s = null;
  try {
    s = JSON.parse(await f.text());
  } catch {
    s = null;
  }
  if (!applySession(s)) setStatus(`${f.name}: not a session file of this editor`, true);
  else setStatus(`session loaded from ${f.name}`);
});

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
  // The G2 spline's answer on screen: its pieces' spans, and the page coordinates of the
  // middle sample of piece k.
  spans: () => (frame && frame.shown.spans ? frame.shown.spans.slice() : null),
  // What the answer on screen draws: its pieces (a kept curve after a failure too) and the
  // point marked at fault.
  shownSummary: () => (frame ? { pieces: frame.shown.pieces ? frame.shown.pieces.length : 0, fault: frame.shown.fault || null } : null),
  // ... and each piece's α.
  alphas: () => (frame && frame.shown.alphas ? frame.shown.alphas.slice() : null),
  pieceMiddle: (k) => {
    const pc = frame.shown.pieces[k];
    return vp.pageOf(pc[Math.floor(pc.length / 2)]);
  },
};

let restored = false;
try {
  restored = applySession(JSON.parse(localStorage.getItem(SESSION) || 'null'));
} catch {
  restored = false;
}
if (!restored) setMode('g2');
fitCanvases();
