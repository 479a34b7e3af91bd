//! A model of the strokes a hand delivers through a mouse, a trackpad or a pen tablet
//! (docs/math.md §6.2), written for the tests and benches of the sketch tools. It shares
//! no code with the library.
//!
//! A stroke is an intended shape (a parametric curve, with the places where the hand
//! stops: its ends and its corners) traced in time:
//! - **speed**: the two-thirds power law of hand movement (tangential speed
//!   `v = K κ^(-1/3)`, capped), slowed to a stop at every corner and at both ends with a
//!   constant deceleration, and a dwell there (the device repeats its position);
//! - **wobble**: a slow drift of a pixel or two (two sinusoids per axis, 0.4 to 2 Hz) and
//!   a tremor of a few tenths of a pixel (8 to 12 Hz), both functions of time, so the
//!   wobble per unit of length is larger where the hand is slow;
//! - **device**: events at a fixed rate (mouse 125 Hz, trackpad 60 Hz, pen 200 Hz), the
//!   position quantized (mouse and trackpad: whole pixels; pen: 1/16 px and a sensor noise
//!   of 0.15 px);
//! - **closure**: a closed stroke ends near its start: an overshoot past it of up to 5 %
//!   of its length or a gap short of it of up to 1.5 % (about 3 % of its size: a gap of
//!   more than 5 % of the size reads as an open stroke, by design);
//! - **editor**: optionally, only events at least 2 px from the last kept one (what the
//!   editor sends), then scaled to world units (`scale` pixels per unit, an offset).

#![allow(dead_code)]

use kurbo::{Point, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// What delivers the positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Device {
    Mouse,
    Trackpad,
    Pen,
}

impl Device {
    pub const ALL: [Device; 3] = [Device::Mouse, Device::Trackpad, Device::Pen];

    fn rate(self) -> f64 {
        match self {
            Device::Mouse => 125.0,
            Device::Trackpad => 60.0,
            Device::Pen => 200.0,
        }
    }

    /// The position quantum in pixels.
    pub fn quantum(self) -> f64 {
        match self {
            Device::Mouse | Device::Trackpad => 1.0,
            Device::Pen => 1.0 / 16.0,
        }
    }
}

/// The shapes a designer draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    S,
    Arc,
    Circle,
    Egg,
    RoundedRectangle,
    L,
    V,
    Spiral,
    Wave,
}

impl Kind {
    pub const ALL: [Kind; 9] = [
        Kind::S,
        Kind::Arc,
        Kind::Circle,
        Kind::Egg,
        Kind::RoundedRectangle,
        Kind::L,
        Kind::V,
        Kind::Spiral,
        Kind::Wave,
    ];

    pub fn closed(self) -> bool {
        matches!(self, Kind::Circle | Kind::Egg | Kind::RoundedRectangle)
    }

    /// The corners drawn (where the hand stops inside the stroke).
    pub fn corners(self) -> usize {
        match self {
            Kind::L | Kind::V => 1,
            _ => 0,
        }
    }
}

/// An intended shape in pixels: a dense polyline (the ideal), its curvature at each
/// point, the indices of its corners, closed or open.
#[derive(Clone, Debug)]
pub struct Shape {
    pub kind: Kind,
    pub points: Vec<Point>,
    pub curvature: Vec<f64>,
    pub corners: Vec<usize>,
    pub closed: bool,
    /// For a rounded rectangle: its straight sides' length share, else 0.
    pub straight_share: f64,
}

impl Shape {
    /// The largest curvature of the ideal shape away from its corners.
    pub fn max_curvature(&self) -> f64 {
        self.curvature.iter().fold(0.0f64, |m, k| m.max(k.abs()))
    }

    pub fn size(&self) -> f64 {
        let (mut lo, mut hi) = (self.points[0], self.points[0]);
        for q in &self.points {
            lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
            hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
        }
        (hi - lo).hypot()
    }
}

const DENSE: usize = 4000;

/// A parametric curve sampled densely, its curvature by the analytic-free three-point
/// circle (the samples are dense and exact).
fn sampled(f: impl Fn(f64) -> Point, closed: bool) -> (Vec<Point>, Vec<f64>) {
    let n = DENSE;
    let pts: Vec<Point> = (0..=n).map(|k| f(k as f64 / n as f64)).collect();
    let mut kappa = vec![0.0; pts.len()];
    for i in 0..pts.len() {
        let (a, b) = if i == 0 || i == n {
            if !closed {
                continue;
            }
            (pts[n - 1], pts[1])
        } else {
            (pts[i - 1], pts[i + 1])
        };
        kappa[i] = menger(a, pts[i], b);
    }
    if !closed {
        kappa[0] = kappa[1];
        kappa[n] = kappa[n - 1];
    }
    (pts, kappa)
}

/// The signed curvature of the circle through three points.
fn menger(a: Point, b: Point, c: Point) -> f64 {
    let cross = (b - a).cross(c - b);
    2.0 * cross / ((b - a).hypot() * (c - b).hypot() * (c - a).hypot())
}

/// A polyline with corners: its points every pixel or so, zero curvature, corner indices.
fn polyline(vertices: &[Point]) -> (Vec<Point>, Vec<f64>, Vec<usize>) {
    let mut pts = vec![vertices[0]];
    let mut corners = vec![];
    for (k, w) in vertices.windows(2).enumerate() {
        let n = ((w[1] - w[0]).hypot() / 0.5).ceil() as usize;
        for j in 1..=n {
            pts.push(w[0].lerp(w[1], j as f64 / n as f64));
        }
        if k + 2 < vertices.len() {
            corners.push(pts.len() - 1);
        }
    }
    let kappa = vec![0.0; pts.len()];
    (pts, kappa, corners)
}

/// A random shape of `kind`, `size` pixels across or so.
pub fn shape(kind: Kind, rng: &mut ChaCha8Rng) -> Shape {
    let size = rng.random_range(180.0..520.0);
    let rot = rng.random_range(-0.3..0.3) + if rng.random_bool(0.5) { 0.0 } else { PI };
    let mirror = rng.random_bool(0.5);
    let mut straight_share = 0.0;
    let (pts, kappa, corners) = match kind {
        Kind::S => {
            // A cubic Bézier S: one inflection, curvature peaks in its two bowls.
            let h = rng.random_range(0.25..0.6);
            let (a, b) = (rng.random_range(0.6..1.1), rng.random_range(0.6..1.1));
            let c = [
                Point::new(0.0, 0.0),
                Point::new(size * a, 0.0),
                Point::new(size * (1.0 - b) * h, size * 0.8),
                Point::new(size * h + size * 0.2, size * 0.8),
            ];
            let (p, k) = sampled(|t| cubic(&c, t), false);
            (p, k, vec![])
        }
        Kind::Arc => {
            let sweep = rng.random_range(70f64..260.0).to_radians();
            let r = size / 2.0;
            let (p, k) = sampled(
                |t| Point::new(r * (t * sweep).cos(), r * (t * sweep).sin()),
                false,
            );
            (p, k, vec![])
        }
        Kind::Circle => {
            let r = size / 2.0;
            let (p, k) = sampled(
                |t| Point::new(r * (2.0 * PI * t).cos(), r * (2.0 * PI * t).sin()),
                true,
            );
            (p, k, vec![])
        }
        Kind::Egg => {
            let (a, b, e) = (
                size / 2.0,
                size * rng.random_range(0.3..0.42),
                rng.random_range(0.1..0.25),
            );
            let (p, k) = sampled(
                |t| {
                    let u = 2.0 * PI * t;
                    Point::new(a * u.cos(), b * u.sin() * (1.0 + e * u.cos()))
                },
                true,
            );
            (p, k, vec![])
        }
        Kind::RoundedRectangle => {
            let (w, h) = (size * 0.8, size * rng.random_range(0.4..0.65));
            let r = rng.random_range(0.12..0.3) * h;
            let (p, k, share) = rounded_rectangle(w, h, r);
            straight_share = share;
            (p, k, vec![])
        }
        Kind::L => {
            let (a, b) = (
                size * rng.random_range(0.4..0.7),
                size * rng.random_range(0.3..0.7),
            );
            let turn = rng.random_range(75f64..105.0).to_radians();
            let v = [
                Point::new(0.0, a),
                Point::ORIGIN,
                Point::new(b * (PI - turn).cos(), b * (PI - turn).sin()),
            ];
            polyline(&v)
        }
        Kind::V => {
            let (a, b) = (
                size * rng.random_range(0.45..0.7),
                size * rng.random_range(0.45..0.7),
            );
            let open = rng.random_range(25f64..70.0).to_radians();
            let v = [
                Point::new(-a * (open / 2.0).sin(), a * (open / 2.0).cos()),
                Point::ORIGIN,
                Point::new(b * (open / 2.0).sin(), b * (open / 2.0).cos()),
            ];
            polyline(&v)
        }
        Kind::Spiral => {
            // An Archimedean spiral of 1.25 to 2 turns, from a radius of a tenth.
            let turns = rng.random_range(1.25..2.0);
            let r = size / 2.0;
            let (p, k) = sampled(
                |t| {
                    let u = 2.0 * PI * turns * t;
                    let rad = r * (0.12 + 0.88 * t);
                    Point::new(rad * u.cos(), rad * u.sin())
                },
                false,
            );
            (p, k, vec![])
        }
        Kind::Wave => {
            let periods = rng.random_range(1.0..2.5);
            let amp = size * rng.random_range(0.08..0.2);
            let (p, k) = sampled(
                |t| Point::new(size * t, amp * (2.0 * PI * periods * t).sin()),
                false,
            );
            (p, k, vec![])
        }
    };
    let (s, c) = (rot.sin(), rot.cos());
    let sign = if mirror { -1.0 } else { 1.0 };
    let points = pts
        .iter()
        .map(|q| Point::new(c * q.x - s * sign * q.y, s * q.x + c * sign * q.y))
        .collect();
    Shape {
        kind,
        points,
        curvature: kappa.iter().map(|k| k * sign).collect(),
        corners,
        closed: kind.closed(),
        straight_share,
    }
}

fn cubic(c: &[Point; 4], t: f64) -> Point {
    let u = 1.0 - t;
    let v = c[0].to_vec2() * (u * u * u)
        + c[1].to_vec2() * (3.0 * u * u * t)
        + c[2].to_vec2() * (3.0 * u * t * t)
        + c[3].to_vec2() * (t * t * t);
    v.to_point()
}

/// A rounded rectangle `w` by `h` with corner radius `r`, counterclockwise from the
/// middle of its bottom side; the share of its length that is straight.
fn rounded_rectangle(w: f64, h: f64, r: f64) -> (Vec<Point>, Vec<f64>, f64) {
    let (sx, sy) = (w - 2.0 * r, h - 2.0 * r);
    let arc = PI / 2.0 * r;
    let total = 2.0 * (sx + sy) + 4.0 * arc;
    let n = DENSE;
    let mut pts = Vec::with_capacity(n + 1);
    let mut kappa = Vec::with_capacity(n + 1);
    for k in 0..=n {
        let mut s = (k as f64 / n as f64 * total + sx / 2.0) % total;
        // Sides and arcs in order: bottom, arc, right, arc, top, arc, left, arc.
        let legs = [sx, arc, sy, arc, sx, arc, sy, arc];
        let centres = [
            Point::new(w / 2.0 - r, r),
            Point::new(w / 2.0 - r, h - r),
            Point::new(-w / 2.0 + r, h - r),
            Point::new(-w / 2.0 + r, r),
        ];
        let starts = [
            Point::new(-w / 2.0 + r, 0.0),
            Point::new(w / 2.0, r),
            Point::new(w / 2.0 - r, h),
            Point::new(-w / 2.0, h - r),
        ];
        let dirs = [
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(0.0, -1.0),
        ];
        let mut i = 0;
        while s > legs[i] && i < 7 {
            s -= legs[i];
            i += 1;
        }
        let q = i / 2;
        if i % 2 == 0 {
            pts.push(starts[q] + dirs[q] * s);
            kappa.push(0.0);
        } else {
            let a0 = -PI / 2.0 + q as f64 * PI / 2.0;
            let a = a0 + s / r;
            pts.push(centres[q] + Vec2::new(a.cos(), a.sin()) * r);
            kappa.push(1.0 / r);
        }
    }
    (pts, kappa, 2.0 * (sx + sy) / total)
}

/// How a stroke is delivered.
#[derive(Clone, Debug)]
pub struct Hand {
    pub device: Device,
    /// Pixels per world unit of the delivered points.
    pub scale: f64,
    /// Keep only events at least 2 px from the last kept one (the editor's filter).
    pub editor: bool,
    /// The largest speed, pixels per second.
    pub speed: f64,
    /// The drift's amplitude in pixels.
    pub drift: f64,
}

impl Hand {
    /// A random hand for a device.
    pub fn random(device: Device, rng: &mut ChaCha8Rng) -> Hand {
        Hand {
            device,
            scale: if rng.random_bool(0.5) {
                1.0
            } else {
                rng.random_range(20.0..80.0)
            },
            editor: rng.random_bool(0.5),
            speed: rng.random_range(300.0..1400.0),
            drift: rng.random_range(0.3..2.0),
        }
    }
}

/// A stroke: the delivered points (world units) and the shape in the same units.
pub struct Stroke {
    pub points: Vec<Point>,
    pub shape: Shape,
    pub hand: Hand,
}

/// The arc length along a polyline at each of its points.
fn lengths(pts: &[Point]) -> Vec<f64> {
    let mut s = vec![0.0];
    for w in pts.windows(2) {
        s.push(s.last().unwrap() + (w[1] - w[0]).hypot());
    }
    s
}

/// The point at arc length `s` (clamped) of a polyline with its `lengths`.
fn at_length(pts: &[Point], len: &[f64], s: f64) -> Point {
    let total = *len.last().unwrap();
    let s = s.clamp(0.0, total);
    let i = match len.binary_search_by(|v| v.partial_cmp(&s).unwrap()) {
        Ok(i) => return pts[i],
        Err(i) => i.clamp(1, len.len() - 1),
    };
    let t = (s - len[i - 1]) / (len[i] - len[i - 1]).max(1e-300);
    pts[i - 1].lerp(pts[i], t)
}

/// The shape traced by the hand: delivered points in world units.
pub fn stroke(shape: Shape, hand: Hand, rng: &mut ChaCha8Rng) -> Stroke {
    let len = lengths(&shape.points);
    let total = *len.last().unwrap();
    // Where the hand stops, as arc lengths.
    let mut stops: Vec<f64> = shape.corners.iter().map(|&i| len[i]).collect();
    stops.push(0.0);
    let mut end = total;
    if shape.closed {
        end = total * (1.0 + rng.random_range(-0.015..0.05));
    } else {
        stops.push(total);
    }
    if shape.closed {
        stops.push(end);
    }
    stops.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let k_power = hand.speed * 0.06;
    let decel = rng.random_range(2500.0..6000.0);
    let curvature_at = |s: f64| {
        let s = s.rem_euclid(total + 1e-9);
        let i = match len.binary_search_by(|v| v.partial_cmp(&s).unwrap()) {
            Ok(i) | Err(i) => i.min(len.len() - 1),
        };
        shape.curvature[i].abs()
    };
    let speed_at = |s: f64| {
        let k = curvature_at(s).max(1e-9);
        let mut v = (k_power * k.powf(-1.0 / 3.0)).min(hand.speed);
        for &q in &stops {
            v = v.min((2.0 * decel * (s - q).abs()).sqrt() + 15.0);
        }
        v
    };
    let point_at = |s: f64| {
        if s <= total {
            at_length(&shape.points, &len, s)
        } else {
            at_length(&shape.points, &len, s - total)
        }
    };
    // Wobble: slow drift and tremor, functions of time.
    let phase: Vec<f64> = (0..8).map(|_| rng.random_range(0.0..2.0 * PI)).collect();
    let freq = [
        rng.random_range(0.4..1.0),
        rng.random_range(1.0..2.0),
        rng.random_range(0.4..1.0),
        rng.random_range(1.0..2.0),
        rng.random_range(8.0..12.0),
        rng.random_range(8.0..12.0),
    ];
    let tremor = rng.random_range(0.1..0.4);
    let wobble = |t: f64| {
        let d = hand.drift * 0.5;
        Vec2::new(
            d * (2.0 * PI * freq[0] * t + phase[0]).sin()
                + d * (2.0 * PI * freq[1] * t + phase[1]).sin()
                + tremor * (2.0 * PI * freq[4] * t + phase[4]).sin(),
            d * (2.0 * PI * freq[2] * t + phase[2]).sin()
                + d * (2.0 * PI * freq[3] * t + phase[3]).sin()
                + tremor * (2.0 * PI * freq[5] * t + phase[5]).sin(),
        )
    };
    let dt_event = 1.0 / hand.device.rate();
    let sub = 20;
    let q = hand.device.quantum();
    let device = |p: Point| Point::new((p.x / q).round() * q, (p.y / q).round() * q);
    let offset = Vec2::new(rng.random_range(0.0..800.0), rng.random_range(0.0..600.0));
    let mut events = vec![];
    let (mut s, mut t) = (0.0, 0.0);
    let mut stop_i = 1; // the next stop after the start
    let mut dwell = rng.random_range(0.03..0.12);
    loop {
        let mut pos = point_at(s) + offset + wobble(t);
        if hand.device == Device::Pen {
            pos += Vec2::new(gauss(rng, 0.15), gauss(rng, 0.15));
        }
        events.push(device(pos));
        if s >= end {
            break;
        }
        // Advance one event's time, in small steps.
        for _ in 0..sub {
            let h = dt_event / sub as f64;
            s += speed_at(s) * h;
            if stop_i < stops.len() && s >= stops[stop_i] {
                s = stops[stop_i];
                // Dwell at the stop: the device repeats its (wobbling) position.
                let n = (dwell / dt_event) as usize;
                for _ in 0..n {
                    t += dt_event;
                    events.push(device(point_at(s) + offset + wobble(t)));
                }
                dwell = rng.random_range(0.03..0.12);
                stop_i += 1;
                break;
            }
        }
        s = s.min(end);
        t += dt_event;
        if events.len() > 200_000 {
            break;
        }
    }
    let kept = if hand.editor {
        let mut out = vec![events[0]];
        for &e in &events[1..] {
            if (e - *out.last().unwrap()).hypot() >= 2.0 {
                out.push(e);
            }
        }
        out
    } else {
        events
    };
    let world = |p: Point| ((p.to_vec2() - offset) / hand.scale).to_point();
    let points = kept.into_iter().map(world).collect();
    let shape = Shape {
        points: shape
            .points
            .iter()
            .map(|p| (p.to_vec2() / hand.scale).to_point())
            .collect(),
        curvature: shape.curvature.iter().map(|k| k * hand.scale).collect(),
        ..shape
    };
    Stroke {
        points,
        shape,
        hand,
    }
}

fn gauss(rng: &mut ChaCha8Rng, sigma: f64) -> f64 {
    let u: f64 = rng.random_range(1e-12..1.0);
    let v: f64 = rng.random_range(0.0..1.0);
    sigma * (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
}

/// The `n`-th stroke of `kind` from a fixed seed: device and hand drawn at random.
pub fn nth(kind: Kind, n: u64) -> Stroke {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5EED_0000 + n * 31 + kind as u64);
    let device = Device::ALL[rng.random_range(0..3)];
    let shape = shape(kind, &mut rng);
    let hand = Hand::random(device, &mut rng);
    stroke(shape, hand, &mut rng)
}

/// A stroke of `kind` by `device` with about `target` points (every event delivered, in
/// pixels): the hand's speed is tuned to the count (for the benches).
pub fn with_points(kind: Kind, device: Device, target: usize, seed: u64) -> Stroke {
    let mut speed = 600.0;
    let mut best: Option<Stroke> = None;
    for _ in 0..8 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let shape = shape(kind, &mut rng);
        let hand = Hand {
            device,
            scale: 1.0,
            editor: false,
            speed,
            drift: 1.0,
        };
        let s = stroke(shape, hand, &mut rng);
        let n = s.points.len();
        let off = |s: &Stroke| (s.points.len() as f64 / target as f64).ln().abs();
        if best.as_ref().is_none_or(|b| off(&s) < off(b)) {
            best = Some(s);
        }
        if (n as f64 / target as f64 - 1.0).abs() < 0.05 {
            break;
        }
        speed *= n as f64 / target as f64;
    }
    best.unwrap()
}
