//! The sweep's handle positions put on the grid for a whole contour at once.
//!
//! Rounding each handle to its nearest grid point loses most of what the sweep found: with
//! a handle 50 units long, one unit changes the curvature at its end by 4 %, and every
//! handle sets the curvature at both ends of its cubic. So each cubic gets a few *states*
//! (its two handles each at one of a few candidate points: its input place, grid points
//! around the sweep's target nearest its tangent line, and one half way), and the states
//! are chosen together: the curvature jump at a join depends only on the states of the two
//! cubics it joins, so a cost summed over the joins (the number of joins not under the G2
//! threshold, then the sum of the jumps) is a chain (a cycle for a closed contour with no
//! corner) of pairwise costs, minimised exactly by dynamic programming (Viterbi). A pair that makes a join worse than the input (a larger jump, or
//! a larger angle) costs infinity, so the input's own states, always candidates, keep the
//! result no worse anywhere. A chosen state that gives its cubic more curvature extrema or
//! a new hook (the exact test, too dear to run on every state) is struck out with its near
//! twins (within two grid cells) and the chain solved again.
//!
//! The float stages' target can be a poor guide: where every small change spoils the
//! extrema rule (a round dot's quarter arcs, whose curvature wobbles by a per cent) they
//! leave a cubic alone, and the states around its input are then its only ones. So where
//! the chain leaves a smooth join not G2, the cubics at those joins get a second set of
//! states too (each handle at the grid points nearest its tangent line, up to
//! [`LINE_STEPS`] grid steps longer or shorter: a search of the lengths themselves, the
//! exact test behind it) and the chain is solved again; the result nearer G2 is kept. On
//! TeX Gyre Bonum at T = 2 this takes the joins under 1 % from 70.2 % to 76.5 % and the
//! hooked cubics from 678 to 81.

use super::{gains_extrema, max_move, worse, Ends, HarmonizeOptions};
use crate::{Point, Vec2};

/// Most rounds of striking out states with more extrema and solving again.
const STRIKE_ROUNDS: usize = 6;

/// Grid points kept per handle around its target (nearest the tangent line first).
const NEAR_TARGET: usize = 9;

/// For a cycle with no corner: most states of the cubic where it is cut tried (every
/// state of a cubic has at most 11 × 11: all of them).
const CYCLE_STARTS: usize = 121;

/// A cycle of more segments than this is solved from [`LONG_CYCLE_STARTS`] states of its
/// cut cubic (the cheapest alone first, and the input's), so that its time stays linear
/// in its length; shorter cycles (every contour of a real glyph) are solved exactly.
const LONG_CYCLE: usize = 64;

/// States of the cut cubic tried in a long cycle.
const LONG_CYCLE_STARTS: usize = 8;

/// Grid steps along its tangent a handle may take in [`line_states`], each way: fine near
/// the input, coarser further out (the tolerance on the shape lets a handle slide further
/// than at equal parameters). On C059 Italic at T = 2, handles only, by the fix's count of
/// joins under 1 %: steps 1 to 6 gave 77.3 % in 37 s, 1 to 10 79.3 % in 67 s, 1 to 14
/// 81.1 % in 122 s, these eight 81.7 % in 46 s; on Bonum 86.4, 87.7 and 87.2 % (these).
const LINE_STEPS: [usize; 8] = [1, 2, 3, 4, 6, 8, 10, 13];

/// What the chain knows: the input, the protected joins and their limits.
pub(super) struct Contour<'a> {
    /// The segments before the grid (the stage's input).
    pub input: &'a [Vec<Point>],
    /// What the tolerance allows (from the repair's original).
    pub reach: &'a super::Reach<'a>,
    /// Closed contour.
    pub closed: bool,
    /// Per join: harmonized and kept (smooth or G1).
    pub smooth: &'a [bool],
    /// Per join: the jump and angle it may not exceed.
    pub guard: &'a [(f64, f64)],
    /// Per segment: the input's interior curvature extrema.
    pub extrema_before: &'a [Option<super::Profile>],
}

/// The segments on the grid, chosen among each cubic's states around `target` (the
/// sweep's float result) to minimise the sum of the jumps at the smooth joins, none worse
/// than `contour.guard` and no cubic with more extrema than the input; where that leaves a
/// smooth join not G2, solved again with [`line_states`] added at the cubics it joins, and
/// the result nearer G2 ([`super::Shortfall`]) kept.
pub(super) fn place(
    contour: &Contour,
    target: &[Vec<Point>],
    opts: &HarmonizeOptions,
) -> Vec<Vec<Point>> {
    let n = contour.input.len();
    let states: Vec<Vec<Vec<Point>>> = (0..n)
        .map(|i| states_of(contour, i, &target[i], opts))
        .collect();
    let first = place_among(contour, states.clone(), opts);
    let touch = short_of_g2(contour, &first, opts.g2_jump);
    if opts.grid <= 0.0 || !touch.iter().any(|t| *t) {
        return first;
    }
    let mut states = states;
    for (s, i) in states.iter_mut().zip(0..).filter(|(_, i)| touch[*i]) {
        for q in line_states(contour, i, opts) {
            if !s.contains(&q) {
                s.push(q);
            }
        }
    }
    let second = place_among(contour, states, opts);
    let shortfall = |pts: &[Vec<Point>]| {
        super::Shortfall::at_joins(pts, contour.closed, contour.smooth, opts.g2_jump)
    };
    if shortfall(&second) < shortfall(&first) {
        second
    } else {
        first
    }
}

/// Per segment: whether it is at a smooth join of `pts` whose jump is not under `g2`.
fn short_of_g2(contour: &Contour, pts: &[Vec<Point>], g2: f64) -> Vec<bool> {
    let st = super::states(pts, contour.closed);
    let mut touch = vec![false; pts.len()];
    for (j, a, b) in super::joins(pts.len(), contour.closed) {
        if contour.smooth[j] && st[j].0 >= g2 {
            touch[a] = true;
            touch[b] = true;
        }
    }
    touch
}

/// [`place`] among given states. The chain's table of pair costs is computed once: a
/// state struck out (it gains extrema, or is a near twin of one that does) costs infinity
/// from then on instead of leaving the list.
fn place_among(
    contour: &Contour,
    states: Vec<Vec<Vec<Point>>>,
    opts: &HarmonizeOptions,
) -> Vec<Vec<Point>> {
    let n = contour.input.len();
    let mut chain = Chain::new(contour, &states, opts);
    let chosen = |pick: &[usize]| -> Vec<Vec<Point>> {
        pick.iter()
            .enumerate()
            .map(|(i, &s)| states[i][s].clone())
            .collect()
    };
    for round in 0..=STRIKE_ROUNDS {
        let pick = chain.best();
        let mut struck = false;
        for i in 0..n {
            let s = pick[i];
            if s != 0 && gains_extrema(&states[i][s], contour.extrema_before[i]) {
                // The state and its near twins (within two grid cells: the others around
                // the same target spoil the same way), or in the last round every state
                // but the input.
                let bad = &states[i][s];
                let near = 2.0 * opts.grid;
                for (k, q) in states[i].iter().enumerate().skip(1) {
                    if round == STRIKE_ROUNDS || max_move(q, bad) <= near {
                        chain.unaries[i][k] = f64::INFINITY;
                    }
                }
                struck = true;
            }
        }
        if !struck {
            return chosen(&pick);
        }
    }
    // The last round left only input states where it struck: solved once more.
    chosen(&chain.best())
}

/// A cubic's states: its two handles at each of their candidates, where the outline stays
/// within the tolerance of the original ([`super::Reach::allows`]); the input first. A line
/// or a cubic the sweep left alone has the input only.
fn states_of(
    contour: &Contour,
    i: usize,
    target: &[Point],
    opts: &HarmonizeOptions,
) -> Vec<Vec<Point>> {
    let input = &contour.input[i];
    if input.len() != 4 {
        return vec![input.to_vec()];
    }
    if input[..] == target[..] {
        return line_states(contour, i, opts);
    }
    let (reach, original) = (contour.reach, &contour.reach.original[i]);
    // A handle alone may move 9/4 T; both together further where their moves cancel (the
    // joint stage's targets can): the target's own distance and two cells more.
    let lone = reach.handle_radius(i, input, true);
    let radius = |k: usize| lone.max((target[k] - original[k]).hypot() + 2.0 * opts.grid);
    let starts = handle_candidates(
        (input[1], target[1]),
        input[0],
        (original[1], radius(1)),
        opts,
    );
    let ends = handle_candidates(
        (input[2], target[2]),
        input[3],
        (original[2], radius(2)),
        opts,
    );
    let mut out = vec![input.to_vec()];
    for &a in &starts {
        for &b in &ends {
            let q = vec![input[0], a, b, input[3]];
            if q != out[0] && reach.allows(i, &q) {
                out.push(q);
            }
        }
    }
    out
}

/// A cubic's states from its input alone: its handles at the grid points nearest their
/// tangent lines, [`LINE_STEPS`] grid steps longer or shorter, where the outline
/// stays within the tolerance; the input first. For a cubic the float stages left alone,
/// and at the joins their target leaves short of G2.
fn line_states(contour: &Contour, i: usize, opts: &HarmonizeOptions) -> Vec<Vec<Point>> {
    let input = &contour.input[i];
    let mut out = vec![input.to_vec()];
    if input.len() != 4 || opts.grid <= 0.0 {
        return out;
    }
    let along = |anchor: Point, handle: Point| -> Vec<Point> {
        let dir = unit(handle - anchor);
        let mut c = vec![handle];
        for k in LINE_STEPS {
            for sign in [-1.0, 1.0] {
                let q = handle + dir * (sign * k as f64 * opts.grid);
                let q = Point::new(
                    (q.x / opts.grid).round() * opts.grid,
                    (q.y / opts.grid).round() * opts.grid,
                );
                if !c.contains(&q) && q != anchor {
                    c.push(q);
                }
            }
        }
        c
    };
    let (starts, ends) = (along(input[0], input[1]), along(input[3], input[2]));
    for &a in &starts {
        for &b in &ends {
            let q = vec![input[0], a, b, input[3]];
            if q != out[0] && contour.reach.allows(i, &q) {
                out.push(q);
            }
        }
    }
    out
}

/// Where one handle may go: its input place first; without a grid the target and half way
/// to it; on a grid the [`NEAR_TARGET`] grid points of the 9 × 9 around the target nearest
/// the handle's tangent line (the line through its anchor and its input place), and the
/// grid point half way nearest it; all within `radius` of the original place (the most a
/// handle alone may move, or the target's distance: the cubic's states are checked whole
/// after).
fn handle_candidates(
    (input, target): (Point, Point),
    anchor: Point,
    (original, radius): (Point, f64),
    opts: &HarmonizeOptions,
) -> Vec<Point> {
    let mut out = vec![input];
    if target == input {
        return out;
    }
    let within = |q: Point| (q - original).hypot() <= radius;
    let half = input + (target - input) * 0.5;
    if opts.grid <= 0.0 {
        out.extend([target, half].into_iter().filter(|q| within(*q)));
        return out;
    }
    let dir = unit(input - anchor);
    let off_line = |q: Point| dir.cross(q - anchor).abs();
    let rank = |around: Point, radius: i32, keep: usize, out: &mut Vec<Point>| {
        let g = opts.grid;
        let (cx, cy) = ((around.x / g).round(), (around.y / g).round());
        let mut near: Vec<(f64, f64, Point)> = Vec::new();
        for dx in -radius..=radius {
            for dy in -radius..=radius {
                let q = Point::new((cx + dx as f64) * g, (cy + dy as f64) * g);
                if within(q) && !out.contains(&q) {
                    near.push((off_line(q), (q - around).hypot(), q));
                }
            }
        }
        near.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        out.extend(near.into_iter().take(keep).map(|x| x.2));
    };
    rank(target, 4, NEAR_TARGET, &mut out);
    rank(half, 1, 1, &mut out);
    out
}

fn unit(v: Vec2) -> Vec2 {
    let l = v.hypot();
    if l > 0.0 {
        v / l
    } else {
        v
    }
}

/// The state per segment minimising the chain's cost (see the module documentation).
#[cfg(test)]
fn best_states(
    contour: &Contour,
    states: &[Vec<Vec<Point>>],
    opts: &HarmonizeOptions,
) -> Vec<usize> {
    Chain::new(contour, states, opts).best()
}

/// The chain's costs over the candidate states.
struct Chain<'a> {
    contour: &'a Contour<'a>,
    states: &'a [Vec<Vec<Point>>],
    /// Every state's [`Ends`], once.
    ends: Vec<Vec<Ends>>,
    /// Every state's [`Chain::unary`], once.
    unaries: Vec<Vec<f64>>,
    tol: f64,
    /// A jump under this is G2 ([`HarmonizeOptions::g2_jump`]).
    g2: f64,
    /// Per join j (after segment j): [`Chain::pair`] for every pair of states, row by
    /// row of segment j's states, once (a cycle is solved from up to [`CYCLE_STARTS`]
    /// states and would ask each pair that often).
    pairs: Vec<Vec<f64>>,
}

impl<'a> Chain<'a> {
    /// The state per segment minimising the chain's cost (see the module documentation).
    fn best(&self) -> Vec<usize> {
        let n = self.states.len();
        let free = |j: usize| !self.contour.smooth[j];
        // A join where the chain may be cut: a corner, or (open) the contour's ends.
        let start = if !self.contour.closed {
            Some(0)
        } else {
            (0..n).find(|&j| free(j)).map(|j| (j + 1) % n)
        };
        let order_from = |s: usize| -> Vec<usize> { (0..n).map(|k| (s + k) % n).collect() };
        match start {
            Some(s) => self.solve(&order_from(s), None).1,
            None => {
                // A cycle: cut at the cubic with the fewest states, each of them tried (the
                // cheapest alone first, at most CYCLE_STARTS: exact up to that many).
                let first = (0..n).min_by_key(|&i| self.live(i)).unwrap_or(0);
                let order = order_from(first);
                let mut firsts: Vec<usize> = (0..self.states[first].len()).collect();
                let own = &self.unaries[first];
                firsts.sort_by(|&x, &y| own[x].total_cmp(&own[y]));
                firsts.retain(|&x| x == 0 || own[x].is_finite());
                // A long cycle tries fewer starts (each is a pass over the whole contour).
                let starts = if n > LONG_CYCLE {
                    LONG_CYCLE_STARTS
                } else {
                    CYCLE_STARTS
                };
                firsts.truncate(starts);
                if !firsts.contains(&0) {
                    firsts.push(0);
                }
                self.best_cycle(&order, &firsts)
            }
        }
    }

    /// How many of segment `i`'s states are not struck out.
    fn live(&self, i: usize) -> usize {
        self.unaries[i].iter().filter(|u| u.is_finite()).count()
    }

    fn new(
        contour: &'a Contour<'a>,
        states: &'a [Vec<Vec<Point>>],
        opts: &HarmonizeOptions,
    ) -> Chain<'a> {
        let mut chain = Chain {
            contour,
            states,
            ends: (states.iter())
                .map(|s| s.iter().map(|q| Ends::of(q)).collect())
                .collect(),
            unaries: Vec::new(),
            tol: opts.tolerance,
            g2: opts.g2_jump,
            pairs: Vec::new(),
        };
        chain.unaries = (0..states.len())
            .map(|i| (0..states[i].len()).map(|s| chain.unary(i, s)).collect())
            .collect();
        chain.pairs = super::joins(states.len(), contour.closed)
            .map(|join| {
                let (na, nb) = (states[join.1].len(), states[join.2].len());
                (0..na * nb)
                    .map(|k| chain.pair(join, k / nb, k % nb))
                    .collect()
            })
            .collect();
        chain
    }

    /// [`Chain::pair`] of the join after segment `a`, from the table.
    fn pair_of(&self, a: usize, sa: usize, sb: usize) -> f64 {
        self.pair_row(a, sa)[sb]
    }

    /// The row of the join after segment `a` for its state `sa`: [`Chain::pair`] with
    /// every state of the next segment.
    fn pair_row(&self, a: usize, sa: usize) -> &[f64] {
        let nb = self.states[(a + 1) % self.states.len()].len();
        &self.pairs[a][sa * nb..(sa + 1) * nb]
    }

    /// A state's own cost: a tie-break towards less movement (far below any jump that
    /// matters).
    fn unary(&self, i: usize, s: usize) -> f64 {
        1e-9 * max_move(&self.contour.input[i], &self.states[i][s]) / self.tol.max(1e-300)
    }

    /// The cost of join `j` between states `sa` of segment `a` and `sb` of segment `b`:
    /// its jump, plus one where that is not under the G2 threshold (so the chain makes as
    /// many joins G2 as it can first, then the jumps small); infinity where it is worse
    /// than allowed; nothing at a corner.
    fn pair(&self, (j, a, b): (usize, usize, usize), sa: usize, sb: usize) -> f64 {
        let state = self.ends[a][sa].join_fast(&self.ends[b][sb]);
        let moved = sa != 0 || sb != 0;
        if moved && worse(state, self.contour.guard[j]) {
            return f64::INFINITY;
        }
        if !self.contour.smooth[j] {
            return 0.0;
        }
        match state.0 {
            j if j.is_nan() => 0.0,
            j if j < self.g2 => j,
            j => 1.0 + j,
        }
    }

    /// Viterbi along `order` (segments in contour order; the join after `order[k]` links
    /// it to `order[k + 1]`), the first segment's state fixed to `first` when given, and
    /// then the join closing the cycle counted too. The cost and the state per segment
    /// (indexed by segment).
    fn solve(&self, order: &[usize], first: Option<usize>) -> (f64, Vec<usize>) {
        let n = order.len();
        let mut cost: Vec<f64> = (0..self.states[order[0]].len())
            .map(|s| match first {
                Some(f) if f != s => f64::INFINITY,
                _ => self.unaries[order[0]][s],
            })
            .collect();
        let mut back: Vec<Vec<usize>> = Vec::with_capacity(n);
        for k in 1..n {
            let (a, b) = (order[k - 1], order[k]);
            let nb = self.states[b].len();
            let own = &self.unaries[b];
            let mut next = vec![f64::INFINITY; nb];
            let mut from = vec![0usize; nb];
            // Row by row of the pair table (sa ascending: the first of equal costs kept).
            for (sa, &ca) in cost.iter().enumerate() {
                if !ca.is_finite() {
                    continue;
                }
                let row = self.pair_row(a, sa);
                for sb in 0..nb {
                    let c = ca + row[sb] + own[sb];
                    if c < next[sb] {
                        next[sb] = c;
                        from[sb] = sa;
                    }
                }
            }
            cost = next;
            back.push(from);
        }
        // The closing join of a cycle (a closed contour with no corner).
        if let Some(f) = first {
            let last = order[n - 1];
            for (s, c) in cost.iter_mut().enumerate() {
                *c += self.pair_of(last, s, f);
            }
        }
        let (mut s, total) = cost
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .map_or((0, f64::INFINITY), |(s, c)| (s, *c));
        let mut pick = vec![0; n];
        for k in (0..n).rev() {
            pick[order[k]] = s;
            if k > 0 {
                s = back[k - 1][s];
            }
        }
        if !total.is_finite() {
            // No finite chain (cannot happen: the input's states are never worse).
            return (total, vec![0; n]);
        }
        (total, pick)
    }

    /// The cheapest cycle over the cut cubic's states `firsts` (in the order whose first
    /// of equal costs wins): each start's open chain (the closing join left out: a lower
    /// bound of its cycle, as no cost is negative) from one backward pass, the starts
    /// solved cheapest bound first, and none whose bound exceeds the best cycle found
    /// (beyond rounding) is solved: the same answer as solving every start.
    fn best_cycle(&self, order: &[usize], firsts: &[usize]) -> Vec<usize> {
        let bounds = self.open_chain_costs(order, firsts);
        let mut by_bound: Vec<usize> = (0..firsts.len()).collect();
        by_bound.sort_by(|&x, &y| bounds[x].total_cmp(&bounds[y]));
        let mut best: Option<(f64, usize, Vec<usize>)> = None;
        for i in by_bound {
            if let Some((b, ..)) = &best {
                if bounds[i] > b + 1e-12 * (1.0 + b.abs()) {
                    break;
                }
            }
            let (c, pick) = self.solve(order, Some(firsts[i]));
            let better = match &best {
                None => true,
                Some((b, j, _)) => c.total_cmp(b).is_lt() || (c.total_cmp(b).is_eq() && i < *j),
            };
            if better {
                best = Some((c, i, pick));
            }
        }
        best.map_or_else(|| vec![0; order.len()], |x| x.2)
    }

    /// For each of `firsts` (a state of `order[0]`), the cost of the best open chain along
    /// `order` starting there: a backward pass of the chain's costs.
    fn open_chain_costs(&self, order: &[usize], firsts: &[usize]) -> Vec<f64> {
        let n = order.len();
        let last = order[n - 1];
        // The best cost from position k to the end, per state at k.
        let mut to_go: Vec<f64> = self.unaries[last].clone();
        for k in (0..n - 1).rev() {
            let a = order[k];
            let states: Vec<usize> = if k == 0 {
                firsts.to_vec()
            } else {
                (0..self.states[a].len()).collect()
            };
            let mut here = vec![f64::INFINITY; self.states[a].len()];
            for sa in states {
                let rest = (self.pair_row(a, sa).iter())
                    .zip(&to_go)
                    .map(|(p, g)| p + g)
                    .fold(f64::INFINITY, f64::min);
                here[sa] = self.unaries[a][sa] + rest;
            }
            to_go = here;
        }
        firsts.iter().map(|&f| to_go[f]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::harmonize::{joins, states};

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// The cost of one choice of states, computed join by join from the control points
    /// (not through the chain): what brute force minimises.
    fn cost_of(c: &Contour, pts: &[Vec<Point>], g2: f64) -> f64 {
        let after = states(pts, c.closed);
        let mut sum = 0.0;
        for (j, a, b) in joins(pts.len(), c.closed) {
            if !c.smooth[j] {
                continue;
            }
            let moved = pts[a] != c.input[a] || pts[b] != c.input[b];
            if moved && worse(after[j], c.guard[j]) {
                return f64::INFINITY;
            }
            sum += if after[j].0 < g2 {
                after[j].0
            } else {
                1.0 + after[j].0
            };
        }
        sum
    }

    /// An arc of three cubics with jumpy joins, open and closed into a loop with a
    /// corner and without one: the chain's choice costs exactly what the best of every
    /// combination of states costs (brute force over all of them), and is one of them.
    #[test]
    fn the_chain_finds_the_cheapest_combination_of_states() {
        let segs = vec![
            vec![p(0.0, 0.0), p(40.0, 0.0), p(77.0, 17.0), p(100.0, 40.0)],
            vec![
                p(100.0, 40.0),
                p(121.0, 61.0),
                p(130.0, 88.0),
                p(130.0, 120.0),
            ],
            vec![
                p(130.0, 120.0),
                p(130.0, 166.0),
                p(96.0, 190.0),
                p(60.0, 190.0),
            ],
        ];
        // Targets: every handle moved a little along its tangent (what a sweep gives).
        let target: Vec<Vec<Point>> = segs
            .iter()
            .map(|s| {
                vec![
                    s[0],
                    s[0] + (s[1] - s[0]) * 1.06,
                    s[3] + (s[2] - s[3]) * 0.93,
                    s[3],
                ]
            })
            .collect();
        let opts = HarmonizeOptions {
            tolerance: 4.0,
            grid: 1.0,
            ..Default::default()
        };
        for (closed, smooth) in [
            (false, vec![true, true]),
            (true, vec![true, true, false]),
            (true, vec![true, true, true]),
        ] {
            let before = states(&segs, closed);
            let guard: Vec<(f64, f64)> = before
                .iter()
                .zip(&smooth)
                .map(|(&(j, a), &s)| (if s { j } else { f64::INFINITY }, a))
                .collect();
            let none = vec![Some((0, false)); 3];
            let reach = super::super::Reach {
                original: &segs,
                tolerance: opts.tolerance,
            };
            let c = Contour {
                input: &segs,
                reach: &reach,
                closed,
                smooth: &smooth,
                guard: &guard,
                extrema_before: &none,
            };
            let st: Vec<Vec<Vec<Point>>> = (0..3)
                .map(|i| states_of(&c, i, &target[i], &opts))
                .collect();
            // Every state keeps its cubic's outline within the tolerance (the sound bound;
            // and, for every fifth, the sampled distance between the shapes).
            for (i, s) in st.iter().enumerate() {
                for (k, q) in s.iter().enumerate() {
                    assert!(crate::bezier::outline_distance(&segs[i], q) <= opts.tolerance);
                    assert!(
                        k % 5 != 0
                            || crate::bezier::sampled_shape_distance(&segs[i], q) <= opts.tolerance
                    );
                }
            }
            assert!(
                st.iter().all(|s| s.len() > 4),
                "{:?}",
                st.iter().map(Vec::len).collect::<Vec<_>>()
            );
            let pick = best_states(&c, &st, &opts);
            let chosen: Vec<Vec<Point>> = (0..3).map(|i| st[i][pick[i]].clone()).collect();
            let mut best = f64::INFINITY;
            for x in 0..st[0].len() {
                for y in 0..st[1].len() {
                    for z in 0..st[2].len() {
                        let pts = vec![st[0][x].clone(), st[1][y].clone(), st[2][z].clone()];
                        best = best.min(cost_of(&c, &pts, opts.g2_jump));
                    }
                }
            }
            let got = cost_of(&c, &chosen, opts.g2_jump);
            // The chain's tie-break on movement is 1e-9 of a jump: equal within that.
            assert!(
                got <= best + 1e-8,
                "closed {closed} {smooth:?}: {got} vs {best}"
            );
            assert!(
                got <= cost_of(&c, &segs, opts.g2_jump),
                "no better than the input"
            );
        }
    }
}
