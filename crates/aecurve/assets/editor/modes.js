// One object per editing mode: its starting view, hint and controls, the handles it drags,
// how it asks the server for its curve (update: state -> frame), and which region it shades.
// A frame is everything the page shows for one answer:
//   {shown, nurbs, numbers, verdict: [text, good], lcg: {fit, note}}
// shown: {curve, kappa, normals, overlay, overlayPolygon, pieces, marks, polygon, handles,
// selected, stroke}. Every point, normal and curvature comes from the server (`draw`).

import { api } from './api.js';
import { fmt } from './ui.js';

// Points per piece the server samples for the picture.
const DRAW = { segment: 161, overlay: 81, spline: 41, g2: 41, sketch: 51, bezier: 161, outline: 41 };

async function lcgOf(points) {
  try {
    // Every other sample is plenty for the graph (and keeps the request a few milliseconds).
    const fit = await api({ op: 'lcg.estimate', points: points.filter((_, i) => i % 2 === 0) });
    return { fit };
  } catch (e) {
    return { fit: null, note: e.message };
  }
}

// The drawing member as the stage's curve fields.
function curveOf(d) {
  return { curve: d.points, kappa: d.curvature, normals: d.normals };
}

// Split a drawing into its pieces (consecutive pieces share their joint).
function piecesOf(d) {
  const n = d.per_piece;
  const out = [];
  for (let i = 0; i < d.pieces; i++) out.push(d.points.slice(i * (n - 1), i * (n - 1) + n));
  return out;
}

const rationalVerdict = (ra) => [ra.monotone ? 'rational cubic: curvature monotone (proven)' : 'rational cubic: curvature NOT monotone', ra.monotone];

export const MODES = {
  g2: {
    box: { x0: 0, y0: 0, x1: 14, y1: 10 },
    hint: 'Click to add a point, click on the curve to insert one, drag to move (Shift: snap the move, or the segment to the previous point, to horizontal or vertical). Select a point: Delete removes it, C (or Alt+click) makes it a corner or smooth again, x and y take typed coordinates, span α the α of the span from it (empty: that of the curve). Ctrl+Z undo, Ctrl+Shift+Z redo.',
    controls: ['closed-box', 'g2-alpha-box', 'point-box', 'remove-point', 'clear'],
    addsPoints: true,
    initial: () => ({ p: [[1.5, 2], [4.5, 6.5], [8, 4], [12, 7.5]], corners: [], spanAlphas: [], closed: false, alpha: -1, selected: -1 }),
    handles: (st) => st.p,
    async update(st) {
      const { p, closed, alpha } = st;
      const corners = (st.corners || []).filter((i) => i < p.length);
      const base = { handles: p, selected: st.selected, corners: corners.map((i) => p[i]) };
      if (p.length < (closed ? 3 : 2)) {
        return { shown: base, nurbs: null, numbers: [['points', 'points', p.length]], verdict: ['add points by clicking'], lcg: { fit: null, note: 'add points' } };
      }
      // The spans whose α the user set ([start point, α] pairs); the others take the curve's.
      const spans = closed ? p.length : p.length - 1;
      const own = st.spanAlphas.filter(([i]) => i < spans);
      const req = { op: 'spline.lac', points: p, closed, corners, alpha, draw: DRAW.g2 };
      if (own.length) {
        req.alphas = Array.from({ length: spans }, (_, k) => (own.find(([i]) => i === k) || [k, alpha])[1]);
      }
      const r = await api(req);
      const pieces = piecesOf(r.drawing);
      // Where each piece starts: joints inside a span (an inflection) are marked.
      const inner = r.segments.slice(1).filter((g, i) => g.span === r.segments[i].span).map((g) => g.control[0]);
      return {
        shown: Object.assign(curveOf(r.drawing), base, { pieces, marks: inner, spans: r.segments.map((g) => g.span), alphas: r.segments.map((g) => g.alpha) }),
        nurbs: r.drawing.nurbs,
        numbers: [
          ['points', 'points', p.length],
          ['pieces', 'pieces (inflection halves)', `${r.segments.length} (${r.segments.filter((g) => g.kind === 'lac_inflection').length})`],
          ['corners', 'corners', corners.length],
          ['alpha', 'alpha', own.length ? `${alpha} (${own.length} span${own.length > 1 ? 's' : ''} their own)` : alpha],
          ['g2', 'G2 at every smooth point', r.g2 ? 'yes' : 'no'],
          ['max_curvature_jump', 'largest curvature jump (cubics)', r.max_cubic_jump],
          ['inflections', 'inflections', r.inflections],
          ['curvature_extrema', 'curvature extrema', r.curvature_extrema],
          ['iterations', 'Newton steps', r.iterations],
        ],
        verdict: [r.all_monotone ? 'every piece: curvature monotone (proven)' : 'some piece is NOT proven monotone', r.all_monotone],
        lcg: { fit: null, note: own.length ? "each piece has its span's log-aesthetic α (the curve's, or the span's own): the graph of each is a line of that slope" : 'one log-aesthetic α for every piece: the graph of each is a line of that slope' },
      };
    },
    region: () => null,
  },

  lac: {
    box: { x0: -1, y0: -2, x1: 15, y1: 9 },
    hint: 'Drag the three control points; move the alpha slider. Green: where the third control point may go (a LAC segment exists). Dashed blue: the rational cubic Bézier.',
    controls: ['alpha-box', 'region-box'],
    polygon: true,
    initial: () => ({ p: [[0, 0], [8, 0], [12, 5]], alpha: -1 }),
    handles: (st) => st.p,
    async update(st) {
      const { p, alpha } = st;
      const seg = await api({ op: 'lac.segment', alpha, control: p, samples: 2, draw: DRAW.segment });
      const [ra, lcg] = await Promise.all([
        api({ op: 'lac.rational_approx', alpha, control: p, draw: DRAW.overlay }).catch((e) => ({ error: e })),
        lcgOf(seg.drawing.points),
      ]);
      return {
        shown: Object.assign(curveOf(seg.drawing), {
          overlay: ra.error ? null : ra.drawing.points,
          overlayPolygon: ra.error ? null : ra.control_points,
          handles: p,
          polygon: p,
        }),
        nurbs: ra.error ? null : ra.drawing.nurbs,
        numbers: [
          ['alpha', 'alpha', alpha],
          ['arc_length', 'arc length', seg.arc_length],
          ['curvature_start', 'curvature at P0', seg.curvature_start],
          ['curvature_end', 'curvature at P2', seg.curvature_end],
          ['lambda', 'Λ', seg.lambda],
          ['lcg_alpha', 'LCG slope (from samples)', lcg.fit ? lcg.fit.alpha : '—'],
          ['rational_error', 'rational cubic: max error', ra.error ? ra.error.kind : ra.max_error],
        ],
        verdict: ra.error ? [`LAC curvature is monotone by construction; no rational cubic: ${ra.error.message}`, true] : rationalVerdict(ra),
        lcg,
      };
    },
    region: (st, grid) => ({ kind: 'lac', alpha: st.alpha, control: st.p, grid: grid(128), key: [st.p[0], st.p[1], st.alpha] }),
  },

  inflection: {
    box: { x0: -1, y0: -2, x1: 15, y1: 9 },
    hint: 'A segment with zero curvature at its first point: drag the three control points. Green: where the third control point may go. Dashed blue: its rational cubic.',
    controls: ['region-box'],
    polygon: true,
    initial: () => ({ p: [[0, 0], [7, 0], [12, 4]] }),
    handles: (st) => st.p,
    async update(st, env) {
      const { p } = st;
      // The rational cubic of an inflection segment takes a while (~0.1 s): only when the
      // drag ends.
      const seg = await api({ op: 'lac.inflection_segment', control: p, samples: 2, rational: !env.dragging, draw: DRAW.segment });
      const ra = seg.rational || null;
      const lcg = await lcgOf(seg.drawing.points.slice(8));
      return {
        shown: Object.assign(curveOf(seg.drawing), {
          handles: p,
          polygon: p,
          overlay: ra ? ra.drawing.points : null,
          overlayPolygon: ra ? ra.control_points : null,
          marks: [seg.drawing.points[0]],
        }),
        nurbs: ra ? ra.drawing.nurbs : null,
        numbers: [
          ['alpha', 'alpha (from the triangle)', seg.alpha],
          ['arc_length', 'arc length', seg.arc_length],
          ['curvature_end', 'curvature at P2', seg.curvature_end],
          ['lcg_alpha', 'LCG slope (from samples)', lcg.fit ? lcg.fit.alpha : '—'],
          ['rational_error', 'rational cubic: max error', ra ? ra.max_error : '…'],
        ],
        verdict: ra ? rationalVerdict(ra) : ['LAC segment: curvature monotone by construction (its rational cubic when the drag ends)', true],
        lcg,
      };
    },
    region: (st, grid) => ({ kind: 'inflection', control: st.p, grid: grid(128), key: [st.p[0], st.p[1]] }),
  },

  spline: {
    box: { x0: 0, y0: 0, x1: 14, y1: 10 },
    hint: 'Click to add points, drag them. The pseudo-elastic spline (S2) through them, open or closed: G1 (its curvature steps at every point; the G2 spline is the first mode).',
    controls: ['closed-box', 'add-point', 'remove-point', 'clear'],
    addsPoints: true,
    initial: () => ({ p: [[1.5, 2], [4.5, 6.5], [8, 4], [12, 7.5]], closed: false }),
    handles: (st) => st.p,
    async update(st) {
      const { p, closed } = st;
      const note = { fit: null, note: 'the spline is not one monotone piece' };
      if (p.length < (closed ? 3 : 2)) {
        return { shown: { handles: p }, nurbs: null, numbers: [['points', 'points', p.length]], verdict: ['add points by clicking'], lcg: note };
      }
      const r = await api({ op: 'spline.pseudo_elastic', points: p, closed, draw: DRAW.spline });
      return {
        shown: Object.assign(curveOf(r.drawing), { handles: p }),
        nurbs: r.drawing.nurbs,
        numbers: [
          ['points', 'points', p.length],
          ['length', 'length', r.length],
          ['area', closed ? 'enclosed area' : 'area to the chord', r.area],
          ['energy', 'pseudo-energy Σ l J', r.energy],
          ['mode', 'mode', r.mode],
        ],
        verdict: [`${r.segments.length} Hermite spans, G1 at every point`],
        lcg: note,
      };
    },
    region: () => null,
  },

  sketch: {
    box: { x0: 0, y0: 0, x1: 14, y1: 10 },
    hint: 'Draw with the mouse or a pen: the stroke becomes a contour of fair runs, G2 curves of log-aesthetic pieces and straight lines (colours; circles: joints; squares: corners). A stroke that ends at its start closes.',
    controls: ['clear', 'sketch-tolerance-box'],
    draws: true,
    initial: () => ({ stroke: [], tolerance: null, resolution: null }),
    handles: () => [],
    async update(st) {
      const s = st.stroke;
      if (s.length < 8) {
        return { shown: { stroke: s }, nurbs: null, numbers: [['pieces', 'pieces', 0]], verdict: ['draw a stroke'], lcg: { fit: null, note: 'draw a stroke' } };
      }
      const req = { op: 'sketch.contour', points: s, draw: DRAW.sketch };
      // One screen pixel in world units: the stroke is never taken as finer than that.
      if (st.resolution > 0) req.resolution = st.resolution;
      if (st.tolerance > 0) req.tolerance = st.tolerance;
      const r = await api(req);
      // The tolerance box shows the default it used while none is set.
      const box = globalThis.document?.getElementById('sketch-tolerance');
      if (box) box.placeholder = st.tolerance > 0 ? 'auto' : `auto: ${fmt(r.tolerance, 3)}`;
      const curves = r.runs.filter((u) => u.kind === 'curve');
      const segments = curves.flatMap((u) => u.segments);
      // Joints: where pieces meet inside a curve run, and the smooth (G2) joins of a
      // straight run with a curve (the corners are drawn apart).
      const joints = curves.flatMap((u) => u.segments.slice(1).map((g) => g.control[0]))
        .concat((r.smooth_joins || []).map((j) => j.point));
      const corners = r.corners.map((k) => k.point);
      const g2 = curves.every((u) => u.g2);
      const monotone = curves.every((u) => u.all_monotone);
      const jump = curves.reduce((m, u) => Math.max(m, u.max_curvature_jump ?? 0), 0);
      const lines = r.runs.length - curves.length;
      return {
        shown: Object.assign(curveOf(r.drawing), { pieces: piecesOf(r.drawing), marks: joints, corners, stroke: s }),
        nurbs: r.drawing.nurbs,
        numbers: [
          ['pieces', 'pieces', r.pieces],
          ['runs', 'runs (lines)', `${r.runs.length} (${lines})`],
          ['corners', 'corners', r.corners.length],
          ['smooth_joins', 'smooth joins (line to curve, G2)', (r.smooth_joins || []).length],
          ['closed', 'closed', !r.closed ? 'no' : !r.seam ? 'yes'
            : r.seam.angle_degrees < 1e-6 && r.seam.curvature_jump < 1e-6 ? 'yes, G2 at the seam'
              : `yes, seam ${fmt(r.seam.angle_degrees, 1)}°, jump ${fmt(r.seam.curvature_jump, 2)}`],
          ['max_deviation', 'max deviation', r.max_deviation],
          ['tolerance', st.tolerance > 0 ? 'tolerance (set)' : 'tolerance (auto: from the noise)', r.tolerance],
          ['g2', 'G2 inside the runs and at smooth joins', g2 && (r.smooth_joins || []).every((j) => j.curvature_jump < 1e-9) ? 'yes' : 'no'],
          ['max_curvature_jump', 'largest curvature jump', jump],
          // A piece whose points fit a wide range of alpha as closely (nearly circular or
          // straight, or few points) shows its alpha as "~": the stroke does not pin it.
          ['alphas', segments.some((g) => g.alpha_determined === false) ? 'alphas (~: the stroke does not pin it)' : 'alphas',
            segments.map((g) => (g.alpha_determined === false ? '~' : '') + fmt(g.alpha, 2)).join(' ') || '—'],
        ],
        verdict: [monotone ? 'every piece: curvature monotone (proven)' : 'some piece is NOT monotone', monotone],
        lcg: { fit: null, note: 'one graph per piece: see the alphas' },
      };
    },
    region: () => null,
  },

  bezier: {
    box: { x0: 0, y0: -1, x1: 14, y1: 9 },
    hint: 'Drag the control points; click one to select it; click the canvas to add a point there (+ point adds one a step on). Green: where the selected point keeps the curvature monotone.',
    controls: ['region-box', 'add-point', 'remove-point'],
    polygon: true,
    addsPoints: true,
    minPoints: 3,
    maxPoints: 21,
    initial: () => ({ p: [[1, 1], [6, 1], [10, 3], [12, 7]], selected: 2 }),
    handles: (st) => st.p,
    async update(st) {
      const { p } = st;
      const r = await api({ op: 'bezier.curvature_monotone', control_points: p, draw: DRAW.bezier });
      const lcg = await lcgOf(r.drawing.points);
      return {
        shown: Object.assign(curveOf(r.drawing), { handles: p, polygon: p, marks: r.drawing.marks, selected: st.selected }),
        nurbs: r.drawing.nurbs,
        numbers: [
          ['degree', 'degree', p.length - 1],
          ['extrema', 'curvature extrema inside', r.extrema.length],
          ['trend', 'trend', r.trend || '—'],
          ['test_degree', 'degree of the dκ/ds test', r.test_degree],
        ],
        verdict: [r.monotone ? 'curvature monotone (exact test)' : 'curvature NOT monotone (circles: extrema)', r.monotone],
        lcg,
      };
    },
    region: (st, grid) => ({ kind: 'bezier', control_points: st.p, index: st.selected, grid: grid(82), key: [st.p, st.selected] }),
  },
};

// ---------- outline mode ----------
// A contour of an existing outline (pasted SVG path data, or a dropped SVG, font or DXF
// file; the server reads them): its control points as handles, shared on-curve points
// moving both segments, re-checked on every drag.

// The editing state of one contour of an outline.check drawing: unique points `p`, each
// segment as indices into it (consecutive segments share their joint; a closed contour's
// last end is its first start), and the segments' weights.
export function contourState(c) {
  const p = [];
  const segs = [];
  const weights = [];
  c.segments.forEach((s, k) => {
    const idx = [];
    s.control_points.forEach((q, j) => {
      if (j === 0 && k > 0) {
        idx.push(p.length - 1);
        return;
      }
      idx.push(p.length);
      p.push(q);
    });
    segs.push(idx);
    weights.push(s.weights);
  });
  if (c.closed && segs.length > 1) {
    const last = segs[segs.length - 1];
    const e = last[last.length - 1];
    const size = Math.max(1, ...p.map((q) => Math.hypot(q[0], q[1])));
    if (Math.hypot(p[e][0] - p[0][0], p[e][1] - p[0][1]) <= 1e-9 * size && e === p.length - 1) {
      last[last.length - 1] = 0;
      p.pop();
    }
  }
  return { p, segs, weights, closed: c.closed };
}

// Load an outline (req: {path} | {svg} | {file: {name, base64}}) into the mode's state: the
// shape `shape` (an index into the file's shapes) and its contour `contour`; with
// `firstDrawn`, the first shape that has segments when `shape` has none (a font's empty
// .notdef or space).
export async function loadOutline(st, req, shape, contour, firstDrawn) {
  let r = await api(Object.assign({ op: 'outline.check', shape, draw: 2 }, req));
  const drawn = (a) => (a.drawing ? a.drawing.contours : []).length > 0;
  if (!drawn(r) && firstDrawn && r.shape_segments) {
    const first = r.shape_segments.findIndex((n) => n > 0);
    if (first >= 0 && first !== shape) {
      shape = first;
      r = await api(Object.assign({ op: 'outline.check', shape, draw: 2 }, req));
    }
  }
  const contours = r.drawing ? r.drawing.contours : [];
  if (!contours.length) {
    const name = r.shape_names ? r.shape_names[shape] : 'this shape';
    throw new Error(`${name} has nothing to check (no contour with segments): pick another`);
  }
  const k = Math.min(contour, contours.length - 1);
  Object.assign(st, contourState(contours[k]), {
    source: req,
    names: r.shape_names,
    shape,
    contour: k,
    contours: contours.length,
    name: r.drawing.name,
  });
}

// Whether the outline came from a font or a DXF drawing (coordinates with y up, on a font's
// 1-unit grid for a font) rather than SVG path data (y down).
export function fontSource(st) {
  const name = st.source && st.source.file ? st.source.file.name : '';
  return /\.(ttf|otf|dxf)$/i.test(name);
}

// The off-curve points of a contour (every control point but a segment's ends), drawn
// apart from the on-curve ones.
function offCurve(st) {
  const on = new Set(st.segs.flatMap((idx) => [idx[0], idx[idx.length - 1]]));
  return st.p.map((_, i) => !on.has(i));
}

export function outlineSegments(st) {
  return st.segs.map((idx, k) => ({ control_points: idx.map((i) => st.p[i]), weights: st.weights[k] }));
}

export const OUTLINE = {
  box: { x0: -1, y0: -2, x1: 15, y1: 9 },
  hint: 'Paste SVG path data (Load) or drop an SVG, a font or a DXF file; pick a path or glyph and a contour. Circles: curvature extrema, inflections, near-breaks and curvature jumps at smooth joins. Drag any point: the contour is re-checked. Fix: smooth joins towards G2 and hooks removed within the tolerance (the comb before the fix stays in grey); Save .glif or Export SVG writes the contour.',
  controls: ['outline-box'],
  polygon: true,
  initial: () => Object.assign(
    contourState({
      closed: true,
      segments: [
        { control_points: [[1, 1], [5, 0], [9, 0.5], [12, 2]], weights: [1, 1, 1, 1] },
        { control_points: [[12, 2], [14, 3], [13, 6], [11, 7]], weights: [1, 1, 1, 1] },
        { control_points: [[11, 7], [8, 8.5], [4, 8.5], [1.5, 6]], weights: [1, 1, 1, 1] },
        { control_points: [[1.5, 6], [0, 4.5], [0, 2.5], [1, 1]], weights: [1, 1, 1, 1] },
      ],
    }),
    { source: null, names: ['sample'], shape: 0, contour: 0, contours: 1, name: 'sample' },
  ),
  handles: (st) => st.p,
  async update(st) {
    const r = await api({ op: 'outline.check', segments: outlineSegments(st), closed: st.closed, draw: DRAW.outline });
    const k = r.shapes[0].contours[0];
    const d = r.drawing.contours[0].drawing;
    const marks = [];
    k.segments.forEach((s) => {
      for (const e of s.extrema.concat(s.inflections)) marks.push(e.point);
    });
    for (const j of k.joins) if (j.near_break || (j.g1 && j.g2 === false)) marks.push(j.point);
    const bad = k.segments.filter((s) => s.monotone === false).length;
    const curved = k.segments.filter((s) => s.monotone !== undefined).length;
    const breaks = k.joins.filter((j) => j.near_break).length;
    const jumps = k.joins.filter((j) => j.g1 && j.g2 === false).length;
    const polygon = st.closed ? st.p.concat([st.p[0]]) : st.p;
    return {
      shown: Object.assign(curveOf(d), { handles: st.p, offCurve: offCurve(st), polygon, marks, ghost: st.ghost || null }),
      nurbs: null,
      numbers: [
        ['outline', 'outline', `${st.name} (contour ${st.contour + 1} of ${st.contours})`],
        ['segments', 'segments', k.segments.length],
        ['not_monotone', 'curved segments not monotone', `${bad} of ${curved}`],
        ['near_breaks', 'joins almost smooth (near-breaks)', breaks],
        ['curvature_jumps', 'G1 joins with a curvature jump', jumps],
        ['findings', 'findings', r.findings.length],
      ],
      verdict: bad || breaks
        ? [`${bad} segment(s) with curvature NOT monotone, ${breaks} near-break(s): ${r.findings[0] ? r.findings[0].message : ''}`, false]
        : ['every curved segment has monotone curvature (exact test); no near-breaks', true],
      lcg: { fit: null, note: 'the logarithmic curvature graph is for single segments: not drawn for outlines' },
    };
  },
  region: () => null,
};

MODES.outline = OUTLINE;

