// The viewport: which world box the canvas shows, and the maps between world and screen.

export class Viewport {
  constructor(canvas, box) {
    this.canvas = canvas;
    this.box = box; // {x0, y0, x1, y1}, mutated by pan and zoom
  }

  scale() {
    const b = this.box;
    return Math.min(this.canvas.width / (b.x1 - b.x0), this.canvas.height / (b.y1 - b.y0));
  }

  toScreen(p) {
    const s = this.scale();
    return [(p[0] - this.box.x0) * s, this.canvas.height - (p[1] - this.box.y0) * s];
  }

  toWorld(px, py) {
    const s = this.scale();
    return [this.box.x0 + px / s, this.box.y0 + (this.canvas.height - py) / s];
  }

  // Canvas pixel of a pointer event.
  eventPixel(ev) {
    const r = this.canvas.getBoundingClientRect();
    return [(ev.clientX - r.left) * this.canvas.width / r.width, (ev.clientY - r.top) * this.canvas.height / r.height];
  }

  // The world size of one step of the pointer (a CSS pixel): the finest a hand's stroke
  // on this view can be.
  pointerResolution() {
    const r = this.canvas.getBoundingClientRect();
    return (r.width > 0 ? this.canvas.width / r.width : 1) / this.scale();
  }

  eventWorld(ev) {
    return this.toWorld(...this.eventPixel(ev));
  }

  // Page coordinates of a world point.
  pageOf(p) {
    const r = this.canvas.getBoundingClientRect();
    const [x, y] = this.toScreen(p);
    return [r.left + x * r.width / this.canvas.width, r.top + y * r.height / this.canvas.height];
  }

  // The grid of a region request over what is visible, n cells across.
  grid(n) {
    const s = this.scale();
    const w = this.canvas.width / s;
    const h = this.canvas.height / s;
    return { x0: this.box.x0, y0: this.box.y0, x1: this.box.x0 + w, y1: this.box.y0 + h, nx: n, ny: Math.round(n * h / w) };
  }

  pan(dx, dy) {
    const b = this.box;
    b.x0 += dx;
    b.x1 += dx;
    b.y0 += dy;
    b.y1 += dy;
  }

  // Zoom by f about the world point c.
  zoom(c, f) {
    const b = this.box;
    b.x0 = c[0] + (b.x0 - c[0]) * f;
    b.x1 = c[0] + (b.x1 - c[0]) * f;
    b.y0 = c[1] + (b.y0 - c[1]) * f;
    b.y1 = c[1] + (b.y1 - c[1]) * f;
  }

  // Show all of pts with a margin.
  fit(pts) {
    if (pts.length < 2) return false;
    let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    for (const p of pts) {
      x0 = Math.min(x0, p[0]);
      x1 = Math.max(x1, p[0]);
      y0 = Math.min(y0, p[1]);
      y1 = Math.max(y1, p[1]);
    }
    const m = 0.12 * Math.max(x1 - x0, y1 - y0, 1e-9);
    Object.assign(this.box, { x0: x0 - m, y0: y0 - m, x1: x1 + m, y1: y1 + m });
    return true;
  }
}
