// Drawing what the server computed: the stage (region, curve, comb, overlay, marks,
// handles), the curvature plot and the logarithmic curvature graph. Nothing here evaluates
// a curve: points, normals and curvatures come with the answers.

import { fmt } from './ui.js';

const PIECE_COLORS = ['#d62728', '#9467bd', '#2ca02c', '#ff7f0e', '#1f77b4', '#8c564b'];

// The region layer: one pixel per cell on a small canvas, scaled up without smoothing.
function regionImage(region) {
  if (region.image) return region.image;
  const g = region.grid;
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
  return c;
}

// The comb's tooth length per unit of curvature: 0.18 of the view's smaller side for the
// largest |κ| on screen, times 10^gain.
export function combLength(vp, shown, gain) {
  const b = vp.box;
  const g = shown.ghost;
  const kmax = Math.max(1e-12, ...shown.kappa.map(Math.abs), ...(g ? g.kappa.map(Math.abs) : []));
  return 0.18 * Math.min(b.x1 - b.x0, b.y1 - b.y0) / kmax * Math.pow(10, gain || 0);
}

// shown: {curve, kappa, normals, overlay, overlayPolygon, pieces, marks, corners, polygon,
// handles, offCurve (per handle: drawn hollow), selected, stroke}; region: {grid, rows} or null; opts: {comb, gain, fixedLength
// (the tooth length to keep, while a drag goes on), hover (an index into the curve)}.
// Returns the comb's tooth length used.
export function drawStage(vp, ctx, shown, region, opts) {
  const view = vp.canvas;
  ctx.clearRect(0, 0, view.width, view.height);
  const s = vp.scale();
  if (region) {
    const g = region.grid;
    const [x0, y1] = vp.toScreen([g.x0, g.y1]);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(regionImage(region), x0, y1, (g.x1 - g.x0) * s, (g.y1 - g.y0) * s);
  }
  if (!shown) return null;
  let used = null;
  const line = (pts, style, width, dash) => {
    if (!pts || pts.length < 2) return;
    ctx.beginPath();
    ctx.strokeStyle = style;
    ctx.lineWidth = width;
    ctx.setLineDash(dash || []);
    pts.forEach((p, i) => {
      const [x, y] = vp.toScreen(p);
      if (i) ctx.lineTo(x, y);
      else ctx.moveTo(x, y);
    });
    ctx.stroke();
    ctx.setLineDash([]);
  };
  if (shown.stroke) line(shown.stroke, '#bbb', 1.5);
  if (shown.polygon) line(shown.polygon, '#999', 1, [5, 4]);
  if (shown.overlayPolygon) line(shown.overlayPolygon, 'rgba(30, 80, 200, 0.35)', 1, [2, 4]);
  // Curvature comb: teeth along the normal, away from the centre of curvature. A ghost (the
  // comb before an outline fix) is drawn first, in grey, on the same tooth scale.
  if (shown.curve && opts.comb) {
    const c = shown.curve;
    const g = shown.ghost;
    const len = opts.fixedLength || combLength(vp, shown, opts.gain);
    used = len;
    if (g) {
      const gt = g.curve.map((p, i) => [p[0] - g.normals[i][0] * (g.kappa[i] || 0) * len, p[1] - g.normals[i][1] * (g.kappa[i] || 0) * len]);
      line(gt, '#9a9a9a', 1.2, [4, 3]);
    }
    const tips = c.map((p, i) => {
      const n = shown.normals[i];
      const k = shown.kappa[i] || 0;
      return [p[0] - n[0] * k * len, p[1] - n[1] * k * len];
    });
    ctx.strokeStyle = '#9ecae1';
    ctx.lineWidth = 1;
    ctx.beginPath();
    c.forEach((p, i) => {
      if (i % 3) return;
      const [x, y] = vp.toScreen(p);
      const [u, v] = vp.toScreen(tips[i]);
      ctx.moveTo(x, y);
      ctx.lineTo(u, v);
    });
    ctx.stroke();
    line(tips, '#6baed6', 1);
  }
  if (shown.pieces) shown.pieces.forEach((pc, i) => line(pc, PIECE_COLORS[i % PIECE_COLORS.length], 3));
  else line(shown.curve, '#d62728', 2.5);
  if (shown.overlay) line(shown.overlay, '#1f3fbf', 1.5, [7, 5]);
  for (const m of shown.marks || []) {
    const [x, y] = vp.toScreen(m);
    ctx.beginPath();
    ctx.arc(x, y, 6, 0, 2 * Math.PI);
    ctx.strokeStyle = '#000';
    ctx.lineWidth = 2;
    ctx.stroke();
  }
  // Corners of a contour: squares.
  for (const m of shown.corners || []) {
    const [x, y] = vp.toScreen(m);
    ctx.strokeStyle = '#000';
    ctx.lineWidth = 2;
    ctx.strokeRect(x - 6, y - 6, 12, 12);
  }
  // The point at fault after a failed update: a red ring around it.
  if (shown.fault) {
    const [x, y] = vp.toScreen(shown.fault);
    ctx.beginPath();
    ctx.arc(x, y, 11, 0, 2 * Math.PI);
    ctx.strokeStyle = '#d00';
    ctx.lineWidth = 2.5;
    ctx.stroke();
  }
  // Handles: filled discs; an outline's off-curve points hollow and smaller, as font
  // editors draw them.
  (shown.handles || []).forEach((p, i) => {
    const [x, y] = vp.toScreen(p);
    ctx.beginPath();
    const off = shown.offCurve && shown.offCurve[i];
    ctx.arc(x, y, off ? 4.5 : 6, 0, 2 * Math.PI);
    if (off) {
      ctx.fillStyle = 'white';
      ctx.fill();
      ctx.strokeStyle = i === shown.selected ? '#e8a33d' : '#444';
      ctx.lineWidth = 2;
      ctx.stroke();
    } else {
      ctx.fillStyle = i === shown.selected ? '#e8a33d' : '#444';
      ctx.fill();
    }
  });
  // The place on the curve the curvature plot points at.
  if (opts.hover != null && shown.curve && shown.curve[opts.hover]) {
    const [x, y] = vp.toScreen(shown.curve[opts.hover]);
    ctx.beginPath();
    ctx.arc(x, y, 8, 0, 2 * Math.PI);
    ctx.strokeStyle = '#e8a33d';
    ctx.lineWidth = 3;
    ctx.stroke();
  }
  return used;
}

// The arc length at each sample of a drawn curve (chord sums).
export function arcLengths(c) {
  const s = [0];
  for (let i = 1; i < c.length; i++) s.push(s[i - 1] + Math.hypot(c[i][0] - c[i - 1][0], c[i][1] - c[i - 1][1]));
  return s;
}

// The sample of the curvature plot under the pixel x of its canvas.
export function curvatureIndexAt(canvas, shown, x) {
  if (!shown || !shown.curve || shown.curve.length < 2) return null;
  const s = arcLengths(shown.curve);
  const total = s[s.length - 1] || 1;
  const m = 22;
  const at = (x - m) / (canvas.width - 2 * m) * total;
  let best = 0;
  s.forEach((v, i) => {
    if (Math.abs(v - at) < Math.abs(s[best] - at)) best = i;
  });
  return best;
}

// Curvature against arc length (chord sums of the samples); joints of pieces as grey lines;
// the sample `hover` (the place under the pointer on the stage) marked.
export function drawCurvature(canvas, shown, hover) {
  const kctx = canvas.getContext('2d');
  kctx.clearRect(0, 0, canvas.width, canvas.height);
  if (!shown || !shown.curve || shown.curve.length < 2) return;
  const s = arcLengths(shown.curve);
  const k = shown.kappa;
  const total = s[s.length - 1] || 1;
  let lo = Math.min(0, ...k), hi = Math.max(0, ...k);
  if (hi - lo < 1e-12) hi = lo + 1;
  const W = canvas.width, H = canvas.height, m = 22;
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
  if (hover != null && k[hover] != null) {
    kctx.fillStyle = '#e8a33d';
    kctx.beginPath();
    kctx.arc(px(s[hover]), py(k[hover]), 5, 0, 2 * Math.PI);
    kctx.fill();
  }
  kctx.fillStyle = '#222';
  kctx.font = '11px sans-serif';
  kctx.fillText(`κ from ${fmt(Math.min(...k), 3)} to ${fmt(Math.max(...k), 3)}`, m, 14);
  kctx.fillText('arc length', W / 2 - 25, H - 6);
}

// The graph of lcg.estimate (points and its fitted line), or nothing.
export function drawLcg(canvas, fit) {
  const lctx = canvas.getContext('2d');
  lctx.clearRect(0, 0, canvas.width, canvas.height);
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
  const W = canvas.width, H = canvas.height, m = 30;
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
