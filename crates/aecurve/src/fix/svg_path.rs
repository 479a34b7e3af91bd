//! SVG path data read with the place of every number, and written back with only the
//! numbers of moved points changed.
//!
//! `fix` must not reformat what it did not fix: a path's commands, their relative or
//! absolute form, implicit repeats, separators and number style stay as they were. Only a
//! number whose value changes is replaced (a moved point's, or a relative number whose
//! reference point moved), in place. Two forms cannot carry every move and are rewritten
//! as the general command of the same form: `H`/`V` whose line is no longer horizontal or
//! vertical become `L` (`h`/`v` become `l`), and `S` whose first handle is no longer the
//! reflection of the previous one becomes `C` (`s`, `c`).

use aesthetic_curves::Point;
use std::ops::Range;

/// One command of path data (an implicit repeat is a command of its own).
#[derive(Clone, Debug)]
pub struct Cmd {
    /// The command's letter as written (or repeated).
    pub letter: char,
    /// Where the letter stands, None for an implicit repeat.
    pub letter_at: Option<usize>,
    /// The places of its numbers in the data.
    pub nums: Vec<Range<usize>>,
    /// Their values.
    pub vals: Vec<f64>,
}

impl Cmd {
    fn upper(&self) -> char {
        self.letter.to_ascii_uppercase()
    }
    fn relative(&self) -> bool {
        self.letter.is_ascii_lowercase()
    }
}

/// How many numbers each command takes.
fn arity(c: char) -> Option<usize> {
    Some(match c.to_ascii_uppercase() {
        'M' | 'L' | 'T' => 2,
        'H' | 'V' => 1,
        'C' => 6,
        'S' | 'Q' => 4,
        'A' => 7,
        'Z' => 0,
        _ => return None,
    })
}

/// The commands of path data `d`, Err naming what is not read. Arcs and quadratics are
/// refused (`fix` works on lines and cubics).
pub fn parse(d: &str) -> Result<Vec<Cmd>, String> {
    let b = d.as_bytes();
    let mut i = 0;
    let mut out: Vec<Cmd> = Vec::new();
    let mut current: Option<char> = None;
    loop {
        while i < b.len() && (b[i].is_ascii_whitespace() || b[i] == b',') {
            i += 1;
        }
        if i >= b.len() {
            break;
        }
        let c = b[i] as char;
        let (letter, letter_at) = if c.is_ascii_alphabetic() {
            i += 1;
            (c, Some(i - 1))
        } else {
            match current {
                // After a move, implicit pairs are lines of the same form.
                Some('M') => ('L', None),
                Some('m') => ('l', None),
                Some(z) if z.eq_ignore_ascii_case(&'z') => {
                    return Err(format!("a number after Z at byte {i}"))
                }
                Some(l) => (l, None),
                None => return Err("path data that does not start with a move".into()),
            }
        };
        let Some(n) = arity(letter) else {
            return Err(format!("an unknown command {letter:?}"));
        };
        if "AaQqTt".contains(letter) {
            return Err("arcs or quadratics: fix works on paths of lines and cubics".into());
        }
        if out.is_empty() && !letter.eq_ignore_ascii_case(&'m') {
            return Err("path data that does not start with a move".into());
        }
        let mut cmd = Cmd {
            letter,
            letter_at,
            nums: Vec::with_capacity(n),
            vals: Vec::with_capacity(n),
        };
        for _ in 0..n {
            while i < b.len() && (b[i].is_ascii_whitespace() || b[i] == b',') {
                i += 1;
            }
            let start = i;
            i = number_end(b, i);
            let v: f64 = d[start..i]
                .parse()
                .map_err(|_| format!("a number expected at byte {start} of the path data"))?;
            if !v.is_finite() {
                return Err(format!("a number out of range at byte {start}"));
            }
            cmd.nums.push(start..i);
            cmd.vals.push(v);
        }
        current = Some(letter);
        out.push(cmd);
    }
    Ok(out)
}

/// The end of the number starting at `i` (SVG's grammar: sign, digits, one point,
/// exponent).
fn number_end(b: &[u8], mut i: usize) -> usize {
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let mut dot = false;
    while i < b.len() && (b[i].is_ascii_digit() || (b[i] == b'.' && !dot)) {
        dot |= b[i] == b'.';
        i += 1;
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        if j < b.len() && b[j].is_ascii_digit() {
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            i = j;
        }
    }
    i
}

/// The absolute points of every command: `M L H V` their end, `C` its two handles and
/// end, `S` its first handle (the reflection it implies), second handle and end; `Z` none.
pub fn absolute(cmds: &[Cmd]) -> Vec<Vec<Point>> {
    let (mut cur, mut start) = (Point::ZERO, Point::ZERO);
    let mut last_c2: Option<Point> = None;
    let mut out = Vec::with_capacity(cmds.len());
    for c in cmds {
        let base = if c.relative() { cur } else { Point::ZERO };
        let pair = |k: usize| Point::new(base.x + c.vals[2 * k], base.y + c.vals[2 * k + 1]);
        let pts: Vec<Point> = match c.upper() {
            'M' | 'L' => vec![pair(0)],
            'C' => vec![pair(0), pair(1), pair(2)],
            'S' => {
                let r =
                    last_c2.map_or(cur, |c2| Point::new(2.0 * cur.x - c2.x, 2.0 * cur.y - c2.y));
                vec![r, pair(0), pair(1)]
            }
            'H' => vec![Point::new(base.x + c.vals[0], cur.y)],
            'V' => vec![Point::new(cur.x, base.y + c.vals[0])],
            _ => Vec::new(),
        };
        last_c2 = matches!(c.upper(), 'C' | 'S').then(|| pts[1]);
        match c.upper() {
            'M' => {
                cur = pts[0];
                start = cur;
            }
            'Z' => cur = start,
            _ => cur = *pts.last().unwrap_or(&cur),
        }
        out.push(pts);
    }
    out
}

/// An SVG subpath: its segments' control points, whether it closes (`Z`), and whether its
/// last segment is the closing line `Z` draws.
pub type SvgContour = (Vec<Vec<Point>>, bool, bool);

/// Where each point of a contour's segments comes from: (command, index in
/// [`absolute`]'s points of it).
pub type Sources = Vec<Vec<(usize, usize)>>;

/// The contours of the commands (their points from [`absolute`]) and where each point
/// comes from. A subpath that ends within its rounding of its start (relative commands
/// summed: a unit in the last written place per segment, plus float noise) ends at its
/// start; where it ends elsewhere, `Z`'s closing line is a segment (`extra`).
pub fn contours(cmds: &[Cmd], abs: &[Vec<Point>], decimals: usize) -> Vec<(SvgContour, Sources)> {
    let mut out = Vec::new();
    let mut segs: Vec<Vec<Point>> = Vec::new();
    let mut srcs: Sources = Vec::new();
    let (mut start, mut at) = (Point::ZERO, Point::ZERO);
    let (mut start_src, mut at_src) = ((0, 0), (0, 0));
    let flush =
        |segs: &mut Vec<Vec<Point>>, srcs: &mut Sources, out: &mut Vec<_>, closed, extra| {
            if !segs.is_empty() {
                out.push(((std::mem::take(segs), closed, extra), std::mem::take(srcs)));
            }
        };
    for (k, (c, p)) in cmds.iter().zip(abs).enumerate() {
        match c.upper() {
            'M' => {
                flush(&mut segs, &mut srcs, &mut out, false, false);
                (start, at) = (p[0], p[0]);
                (start_src, at_src) = ((k, 0), (k, 0));
            }
            'Z' => {
                let written = 10f64.powi(-(decimals as i32)) * (segs.len() + 1) as f64;
                let noise = (1e-9 * start.to_vec2().hypot().max(1.0)).max(written);
                if at != start && (at - start).hypot() <= noise {
                    if let Some(last) = segs.last_mut().and_then(|s| s.last_mut()) {
                        *last = start;
                    }
                    at = start;
                }
                let extra = at != start;
                if extra {
                    segs.push(vec![at, start]);
                    srcs.push(vec![at_src, start_src]);
                }
                flush(&mut segs, &mut srcs, &mut out, true, extra);
                (at, at_src) = (start, start_src);
            }
            _ => {
                let mut seg = vec![at];
                let mut src = vec![at_src];
                for (i, q) in p.iter().enumerate() {
                    seg.push(*q);
                    src.push((k, i));
                }
                at = *p.last().unwrap_or(&at);
                at_src = (k, p.len().saturating_sub(1));
                segs.push(seg);
                srcs.push(src);
            }
        }
    }
    flush(&mut segs, &mut srcs, &mut out, false, false);
    out
}

/// The commands' points (as [`absolute`] gives them) with the fixed contours' points put
/// where they come from.
pub fn moved_points(abs: &[Vec<Point>], fixed: &[(SvgContour, Sources)]) -> Vec<Vec<Point>> {
    let mut new = abs.to_vec();
    for ((segs, ..), srcs) in fixed {
        for (seg, src) in segs.iter().zip(srcs) {
            for (p, &(k, i)) in seg.iter().zip(src) {
                new[k][i] = *p;
            }
        }
    }
    new
}

/// The path data with the commands' points moved to `new` (per command, as [`absolute`]
/// gives them; `old` is what it gives for the data as read), only the numbers that change
/// replaced; `decimals` places for moved numbers (trailing zeros dropped).
pub fn rewrite(
    d: &str,
    cmds: &[Cmd],
    (old, new): (&[Vec<Point>], &[Vec<Point>]),
    decimals: usize,
    number: impl Fn(f64, usize) -> String,
) -> String {
    let mut edits: Vec<(Range<usize>, String)> = Vec::new();
    let (mut cur, mut cur_old) = (Point::ZERO, Point::ZERO);
    let (mut start, mut start_old) = (Point::ZERO, Point::ZERO);
    // The previous cubic's second handle (new), for `S`'s reflection.
    let mut last_c2: Option<Point> = None;
    let mut letter_needed = false;
    let tiny = 0.5 * 10f64.powi(-(decimals as i32));
    for (k, c) in cmds.iter().enumerate() {
        let (o, n) = (&old[k], &new[k]);
        let moved = o != n || cur != cur_old;
        // A command that follows a rewritten one in an implicit repeat needs its letter.
        if letter_needed && c.letter_at.is_none() {
            let at = c.nums.first().map_or(d.len(), |r| r.start);
            edits.push((at..at, c.letter.to_string()));
        }
        letter_needed = false;
        let rel = c.relative();
        let base = if rel { cur } else { Point::ZERO };
        let fmt_pair = |p: Point| {
            format!(
                "{} {}",
                number(p.x - base.x, decimals),
                number(p.y - base.y, decimals)
            )
        };
        let upper = c.upper();
        let reflected = match last_c2 {
            Some(c2) => Point::new(2.0 * cur.x - c2.x, 2.0 * cur.y - c2.y),
            None => cur,
        };
        let general = match upper {
            'H' => moved && (n[0].y - cur.y).abs() > tiny,
            'V' => moved && (n[0].x - cur.x).abs() > tiny,
            'S' => moved && (n[0] - reflected).hypot() > tiny && n.len() == 3,
            _ => false,
        };
        if general {
            // Rewritten whole as the general command of the same form.
            let letter = match (upper, rel) {
                ('S', false) => 'C',
                ('S', true) => 'c',
                (_, false) => 'L',
                (_, true) => 'l',
            };
            let body: Vec<String> = n.iter().map(|p| fmt_pair(*p)).collect();
            let from = c.letter_at.unwrap_or_else(|| c.nums[0].start);
            let to = c.nums.last().map_or(from + 1, |r| r.end);
            edits.push((from..to, format!("{letter}{}", body.join(" "))));
            letter_needed = true;
        } else if moved {
            let vals: Vec<f64> = match upper {
                'H' => vec![n[0].x - base.x],
                'V' => vec![n[0].y - base.y],
                'S' => n[n.len() - 2..]
                    .iter()
                    .flat_map(|p| [p.x - base.x, p.y - base.y])
                    .collect(),
                _ => n
                    .iter()
                    .flat_map(|p| [p.x - base.x, p.y - base.y])
                    .collect(),
            };
            for ((range, &old_v), v) in c.nums.iter().zip(&c.vals).zip(vals) {
                if (v - old_v).abs() > tiny {
                    edits.push((range.clone(), number(v, decimals)));
                }
            }
        }
        match upper {
            'M' => {
                (cur, cur_old) = (n[0], o[0]);
                (start, start_old) = (cur, cur_old);
                last_c2 = None;
            }
            'Z' => {
                (cur, cur_old) = (start, start_old);
                last_c2 = None;
            }
            'C' | 'S' => {
                last_c2 = Some(n[n.len() - 2]);
                (cur, cur_old) = (n[n.len() - 1], o[o.len() - 1]);
            }
            _ => {
                last_c2 = None;
                (cur, cur_old) = (n[0], o[0]);
            }
        }
    }
    apply(d, edits)
}

/// The edits applied (each a range and its new text), a separator added where a new
/// number would run into its neighbour.
fn apply(d: &str, mut edits: Vec<(Range<usize>, String)>) -> String {
    edits.sort_by_key(|e| (e.0.start, e.0.end));
    let b = d.as_bytes();
    let mut out = String::with_capacity(d.len() + 16);
    let mut at = 0;
    for (range, text) in edits {
        out.push_str(&d[at..range.start]);
        let before = out.as_bytes().last().copied();
        let first = text.as_bytes().first().copied();
        let joins = |x: Option<u8>| x.is_some_and(|x| x.is_ascii_digit() || x == b'.');
        if joins(before) && (joins(first) || (first == Some(b'.'))) {
            out.push(' ');
        }
        out.push_str(&text);
        let next = b.get(range.end).copied();
        let last = text.as_bytes().last().copied();
        if joins(next) && (joins(last) || text.contains('.') && next == Some(b'.')) {
            out.push(' ');
        }
        at = range.end;
    }
    out.push_str(&d[at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(v: f64, k: usize) -> String {
        let s = format!("{v:.k$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    }

    /// Every command form read to the same absolute points as kurbo reads them.
    #[test]
    fn absolute_points_are_kurbos() {
        let d = "m10 20h30v-5c1 2 3 4 5 6s7-8 9 10l-3-3L1.5.5zM0 0 5 5 6 7H2V3C1,1,2,2,3,3S4 4 5 5zm1 1 2 2";
        let cmds = parse(d).unwrap();
        let ours: Vec<Point> = absolute(&cmds).into_iter().flatten().collect();
        let mut theirs = Vec::new();
        for el in kurbo::BezPath::from_svg(d).unwrap().elements() {
            match *el {
                kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) => theirs.push(p),
                kurbo::PathEl::CurveTo(a, b, p) => theirs.extend([a, b, p]),
                _ => {}
            }
        }
        assert_eq!(ours.len(), theirs.len());
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((*a - *b).hypot() < 1e-12, "{a:?} {b:?}");
        }
    }

    #[test]
    fn only_moved_numbers_change_and_forms_stay() {
        let d = "M10,20 h30 v-5 c1 2 3 4 5 6 s7-8 9 10 z";
        let cmds = parse(d).unwrap();
        let old = absolute(&cmds);
        // Nothing moved: the same text.
        assert_eq!(rewrite(d, &cmds, (&old, &old), 4, num), d);
        // The cubic's first handle moves: only its two relative numbers change.
        let mut new = old.clone();
        new[3][0].x += 0.25;
        let out = rewrite(d, &cmds, (&old, &new), 4, num);
        assert_eq!(out, "M10,20 h30 v-5 c1.25 2 3 4 5 6 s7-8 9 10 z");
        // The h line's end moves up: it becomes l, and v's numbers follow their new start.
        let mut new = old.clone();
        new[1][0].y += 1.0;
        let out = rewrite(d, &cmds, (&old, &new), 4, num);
        assert!(out.starts_with("M10,20 l30 1 v-6 "), "{out}");
        let back = absolute(&parse(&out).unwrap());
        assert_eq!(back[1][0], new[1][0]);
        assert_eq!(back[2][0], new[2][0]);
    }

    #[test]
    fn numbers_do_not_run_together() {
        let d = "M1.5.5L2-3";
        let cmds = parse(d).unwrap();
        let old = absolute(&cmds);
        let mut new = old.clone();
        new[0][0] = Point::new(1.0, 0.7);
        new[1][0] = Point::new(2.0, 3.0);
        let out = rewrite(d, &cmds, (&old, &new), 4, num);
        let back = absolute(&parse(&out).unwrap());
        assert_eq!(back, new, "{out}");
    }
}
