//! `aecurve fix`'s write path probed as an attacker and an unlucky user would: a UFO's own
//! plists naming files outside it, special files, kills and a full disk during the write, a
//! file or a link at the output path, masters that leave their folder, a contour of any
//! size, SVG content that was not fixed or is not drawn, and the parts of a UFO outside the
//! spec. The invariant everywhere: nothing is read or written outside the files given, and
//! the output appears whole or not at all.

use aecurve::fix::masters::fix_designspace;
use aecurve::fix::{fix_ufo, FixOptions};
use norad::{Contour, ContourPoint, Font, Glyph, PointType};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant, SystemTime};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("write-safety-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn aecurve(args: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_aecurve"))
        .args(args)
        .output()
        .unwrap()
}

fn p(s: &str) -> &Path {
    Path::new(s)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Every file and folder below `root` (links not followed): its kind, bytes and
/// modification time, so that any change anywhere shows.
type Snapshot = BTreeMap<PathBuf, (char, Vec<u8>, Option<SystemTime>)>;

fn snapshot(root: &Path) -> Snapshot {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = e.path();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            let rel = path.strip_prefix(root).unwrap().to_path_buf();
            let modified = meta.modified().ok();
            if meta.is_dir() {
                out.insert(rel, ('d', Vec::new(), None));
                stack.push(path);
            } else if meta.is_file() {
                out.insert(rel, ('f', std::fs::read(&path).unwrap(), modified));
            } else if meta.file_type().is_symlink() {
                let to = std::fs::read_link(&path).unwrap();
                out.insert(rel, ('l', to.to_string_lossy().as_bytes().to_vec(), None));
            } else {
                out.insert(rel, ('s', Vec::new(), None));
            }
        }
    }
    out
}

fn pt(x: f64, y: f64, typ: PointType, smooth: bool) -> ContourPoint {
    ContourPoint::new(x, y, typ, smooth, None, None)
}

/// An "o" of four cubics with handles off their G2 lengths (the fix moves them), shifted by
/// `dx`.
fn o_contour(dx: f64) -> Contour {
    use PointType::{Curve, OffCurve};
    let pts = [
        (600.0, 0.0, Curve),
        (600.0, 265.0, OffCurve),
        (330.0, 400.0, OffCurve),
        (0.0, 400.0, Curve),
        (-290.0, 400.0, OffCurve),
        (-600.0, 200.0, OffCurve),
        (-600.0, 0.0, Curve),
        (-600.0, -250.0, OffCurve),
        (-360.0, -400.0, OffCurve),
        (0.0, -400.0, Curve),
        (300.0, -400.0, OffCurve),
        (600.0, -190.0, OffCurve),
    ];
    Contour::new(
        pts.iter()
            .map(|&(x, y, t)| pt(x + dx, y, t, t == Curve))
            .collect(),
        None,
    )
}

/// A UFO of `glyphs` glyphs (each an "o", named o, o1, o2, ...) and an "I" of one line
/// contour (nothing to fix).
fn source(at: &Path, glyphs: usize) -> PathBuf {
    let mut font = Font::new();
    for k in 0..glyphs {
        let name = if k == 0 {
            "o".to_string()
        } else {
            format!("o{k}")
        };
        let mut g = Glyph::new(name.as_str());
        g.contours.push(o_contour(k as f64));
        font.default_layer_mut().insert_glyph(g);
    }
    let mut i = Glyph::new("I");
    use PointType::Line;
    i.contours.push(Contour::new(
        vec![
            pt(0.0, 0.0, Line, false),
            pt(100.0, 0.0, Line, false),
            pt(100.0, 700.0, Line, false),
            pt(0.0, 700.0, Line, false),
        ],
        None,
    ));
    font.default_layer_mut().insert_glyph(i);
    font.save(at).unwrap();
    at.to_path_buf()
}

fn opts() -> FixOptions {
    FixOptions {
        tolerance: 40.0,
        grid: 1.0,
        move_points: false,
        repairs: Default::default(),
        deadline: None,
    }
}

/// Replace `key`'s string in a plist's text (the `<string>` after `<key>key</key>`).
fn set_plist_string(file: &Path, key: &str, value: &str) {
    let text = std::fs::read_to_string(file).unwrap();
    let at = text.find(&format!("<key>{key}</key>")).unwrap();
    let s = at + text[at..].find("<string>").unwrap() + "<string>".len();
    let e = s + text[s..].find("</string>").unwrap();
    let out = format!("{}{}{}", &text[..s], value, &text[e..]);
    std::fs::write(file, out).unwrap();
}

/// Names no staging folder is left behind in `dir` (the hidden `.NAME.aecurve-*` ones).
fn no_staging_left(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        assert!(!name.contains(".aecurve-"), "staging left: {name}");
    }
}

/// A `contents.plist` entry `../../outside/O_.glif`, and a `layercontents.plist` entry
/// naming a folder outside the UFO: `check` and `fix` refuse them by name before reading,
/// and nothing outside (the attacker's glif, the victim's file) is read into the output or
/// changed; no output appears.
#[test]
fn plist_entries_that_leave_the_ufo_are_refused() {
    let dir = scratch("leave");
    let ufo = source(&dir.join("src.ufo"), 1);
    let outside = dir.join("outside");
    std::fs::create_dir_all(&outside).unwrap();
    std::fs::copy(ufo.join("glyphs/o.glif"), outside.join("O_.glif")).unwrap();
    std::fs::write(outside.join("victim.txt"), "user data").unwrap();
    set_plist_string(
        &ufo.join("glyphs/contents.plist"),
        "o",
        "../../outside/O_.glif",
    );
    let before = snapshot(&dir);
    let out = dir.join("out.ufo");
    let run = aecurve(&[p("fix"), &ufo, p("-o"), &out]);
    assert!(!run.status.success());
    let why = stderr(&run);
    assert!(
        why.contains("../../outside/O_.glif") && why.contains("contents.plist"),
        "{why}"
    );
    let check = aecurve(&[p("check"), &ufo]);
    assert!(!check.status.success());
    assert!(
        stderr(&check).contains("../../outside/O_.glif"),
        "{}",
        stderr(&check)
    );
    assert_eq!(snapshot(&dir), before, "something changed");
    // The layer folder: a second layer whose folder is outside.
    let ufo2 = source(&dir.join("src2.ufo"), 1);
    let lc = ufo2.join("layercontents.plist");
    let text = std::fs::read_to_string(&lc).unwrap();
    let text = text.replace(
        "</array>\n</array>",
        "</array>\n<array><string>evil</string><string>../../outside-layer</string></array>\n</array>",
    );
    assert!(text.contains("outside-layer"), "{text}");
    std::fs::write(&lc, text).unwrap();
    std::fs::create_dir_all(dir.join("outside-layer")).unwrap();
    std::fs::copy(
        ufo2.join("glyphs/contents.plist"),
        dir.join("outside-layer/contents.plist"),
    )
    .unwrap();
    let before = snapshot(&dir);
    let run = aecurve(&[p("fix"), &ufo2, p("-o"), &dir.join("out2.ufo")]);
    assert!(!run.status.success());
    assert!(
        stderr(&run).contains("../../outside-layer"),
        "{}",
        stderr(&run)
    );
    assert_eq!(snapshot(&dir), before, "something changed");
    no_staging_left(&dir);
}

/// Entries naming `/dev/zero` and a pipe (outside the UFO, and inside it): refused at
/// once, never opened (before, `check` grew to 12 GB on the first and blocked for ever on
/// the second).
#[cfg(unix)]
#[test]
fn special_files_named_by_a_plist_are_refused_at_once() {
    let dir = scratch("special");
    for (k, entry) in ["/dev/zero", "../../pipe", "pipe.glif"].iter().enumerate() {
        let ufo = source(&dir.join(format!("src{k}.ufo")), 1);
        let fifo = if entry.starts_with("../") {
            dir.join("pipe")
        } else {
            ufo.join("glyphs/pipe.glif")
        };
        if !fifo.exists() && entry.contains("pipe") {
            assert!(Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success());
        }
        set_plist_string(&ufo.join("glyphs/contents.plist"), "o", entry);
        for cmd in ["check", "fix"] {
            let started = Instant::now();
            let mut child = Command::new(env!("CARGO_BIN_EXE_aecurve"))
                .args([cmd, ufo.to_str().unwrap()])
                .args(if cmd == "fix" {
                    vec![
                        "-o".to_string(),
                        dir.join(format!("o{k}.ufo")).display().to_string(),
                    ]
                } else {
                    vec![]
                })
                .stderr(std::process::Stdio::piped())
                .stdout(std::process::Stdio::null())
                .spawn()
                .unwrap();
            let status = loop {
                if let Some(s) = child.try_wait().unwrap() {
                    break s;
                }
                if started.elapsed() > Duration::from_secs(20) {
                    let _ = child.kill();
                    panic!("{cmd} on an entry {entry:?} did not finish (blocked?)");
                }
                std::thread::sleep(Duration::from_millis(20));
            };
            assert!(!status.success(), "{cmd} {entry}");
            let mut why = String::new();
            use std::io::Read;
            child
                .stderr
                .take()
                .unwrap()
                .read_to_string(&mut why)
                .unwrap();
            assert!(
                why.contains(entry) || why.contains("not a regular file"),
                "{cmd} {entry}: {why}"
            );
            assert!(started.elapsed() < Duration::from_secs(10));
        }
        assert!(!dir.join(format!("o{k}.ufo")).exists());
    }
}

/// A run killed at many moments (while reading, fixing, writing the staging folder, moving
/// it in): the output is either absent or whole (every file of a complete run's output,
/// with the same bytes), never partial.
#[cfg(unix)]
#[test]
fn a_kill_at_any_moment_leaves_no_output_or_a_whole_one() {
    let dir = scratch("kill");
    let ufo = source(&dir.join("src.ufo"), 300);
    // A large data file makes the write a long part of the run.
    std::fs::create_dir_all(ufo.join("data/com.example.tool")).unwrap();
    std::fs::write(
        ufo.join("data/com.example.tool/blob.bin"),
        vec![7u8; 8 << 20],
    )
    .unwrap();
    let full = dir.join("full.ufo");
    let started = Instant::now();
    assert!(aecurve(&[p("fix"), &ufo, p("-o"), &full]).status.success());
    let whole = started.elapsed();
    let reference = snapshot(&full);
    let strip = |s: Snapshot| -> BTreeMap<PathBuf, (char, Vec<u8>)> {
        s.into_iter().map(|(k, (c, b, _))| (k, (c, b))).collect()
    };
    let reference = strip(reference);
    let (mut absent, mut complete) = (0, 0);
    for k in 0..16 {
        let out = dir.join(format!("out{k}.ufo"));
        // From the start to three times a whole run (the other tests load the machine).
        let delay = whole.mul_f64(k as f64 / 15.0 * 3.0);
        let mut child = Command::new(env!("CARGO_BIN_EXE_aecurve"))
            .args(["fix", ufo.to_str().unwrap(), "-o", out.to_str().unwrap()])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill();
        let _ = child.wait();
        if out.exists() {
            assert_eq!(
                strip(snapshot(&out)),
                reference,
                "a partial output after {delay:?}"
            );
            complete += 1;
        } else {
            absent += 1;
        }
    }
    eprintln!("kills: {absent} left no output, {complete} a whole one, none a partial one");
    assert!(absent > 0, "no kill came early enough to test");
}

/// A full disk (`ulimit -f`: the write past the limit fails): no output, and with
/// `--overwrite` the previous output is still there, whole.
#[cfg(unix)]
#[test]
fn a_full_disk_leaves_no_output_or_the_previous_one() {
    let dir = scratch("full-disk");
    let ufo = source(&dir.join("src.ufo"), 3);
    std::fs::create_dir_all(ufo.join("data")).unwrap();
    std::fs::write(ufo.join("data/blob.bin"), vec![1u8; 400 << 10]).unwrap();
    let out = dir.join("out.ufo");
    let limited = |extra: &str| {
        let script = format!(
            "ulimit -f 200; exec '{}' fix '{}' -o '{}' {extra}",
            env!("CARGO_BIN_EXE_aecurve"),
            ufo.display(),
            out.display()
        );
        Command::new("bash").args(["-c", &script]).output().unwrap()
    };
    assert!(!limited("").status.success());
    assert!(!out.exists(), "a partial output after a full disk");
    // The previous output stays when the replacement cannot be written.
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("previous.txt"), "previous").unwrap();
    assert!(!limited("--overwrite").status.success());
    assert_eq!(
        std::fs::read_to_string(out.join("previous.txt")).unwrap(),
        "previous"
    );
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
}

/// A file created at the output path while `fix` works is not replaced (the move into
/// place refuses it), and a dangling link given as the output is not followed: its target
/// is not created, with or without `--overwrite` (then the link itself is replaced).
#[cfg(unix)]
#[test]
fn the_output_path_is_never_followed_or_replaced_unasked() {
    let dir = scratch("output-path");
    let ufo = source(&dir.join("src.ufo"), 400);
    let out = dir.join("out.svg");
    let svg = dir.join("in.svg");
    std::fs::write(
        &svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0C0 265 270 400 600 400C890 \
         400 1200 200 1200 0\"/></svg>",
    )
    .unwrap();
    // A link to a file that does not exist, as the output.
    let target = dir.join("target.svg");
    std::os::unix::fs::symlink(&target, &out).unwrap();
    let run = aecurve(&[p("fix"), &svg, p("-o"), &out]);
    assert!(!run.status.success());
    assert!(stderr(&run).contains("already exists"), "{}", stderr(&run));
    assert!(!target.exists());
    let run = aecurve(&[p("fix"), &svg, p("-o"), &out, p("--overwrite")]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(!target.exists(), "the link was followed");
    assert!(!std::fs::symlink_metadata(&out)
        .unwrap()
        .file_type()
        .is_symlink());
    // A file appears at a UFO's output path during the run.
    let out = dir.join("out.ufo");
    let child = Command::new(env!("CARGO_BIN_EXE_aecurve"))
        .args(["fix", ufo.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(150));
    std::fs::write(&out, "mine").unwrap();
    let done = child.wait_with_output().unwrap();
    assert!(
        !done.status.success(),
        "fix replaced a file made during the run"
    );
    assert!(stderr(&done).contains("appeared"), "{}", stderr(&done));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "mine");
    no_staging_left(&dir);
}

/// Masters whose paths leave the designspace's folder are refused before anything is
/// written; an output inside the source UFO is refused; a new output folder appears with
/// everything in it or not at all.
#[test]
fn masters_and_outputs_stay_where_they_belong() {
    let dir = scratch("masters");
    let src = dir.join("src/a/b/c");
    std::fs::create_dir_all(&src).unwrap();
    source(&src.join("A.ufo"), 1);
    source(&dir.join("src/Up.ufo"), 1);
    let ds = |files: [&str; 2]| {
        format!(
            "<?xml version='1.0'?><designspace format=\"4.1\"><axes><axis tag=\"wght\" \
             name=\"Weight\" minimum=\"0\" maximum=\"1\" default=\"0\"/></axes><sources>\
             <source filename=\"{}\"><location><dimension name=\"Weight\" xvalue=\"0\"/>\
             </location></source><source filename=\"{}\"><location><dimension \
             name=\"Weight\" xvalue=\"1\"/></location></source></sources></designspace>",
            files[0], files[1]
        )
    };
    std::fs::write(src.join("Up.designspace"), ds(["A.ufo", "../../../Up.ufo"])).unwrap();
    let before = snapshot(&dir);
    let run = aecurve(&[
        p("fix"),
        &src.join("Up.designspace"),
        p("-o"),
        &dir.join("out/x/Up.designspace"),
    ]);
    assert!(!run.status.success());
    assert!(stderr(&run).contains("../../../Up.ufo"), "{}", stderr(&run));
    assert_eq!(snapshot(&dir), before);
    // Inside the input.
    let run = aecurve(&[
        p("fix"),
        &src.join("A.ufo"),
        p("-o"),
        &src.join("A.ufo/inner.ufo"),
    ]);
    assert!(!run.status.success());
    assert!(
        stderr(&run).contains("inside the input"),
        "{}",
        stderr(&run)
    );
    assert_eq!(snapshot(&dir), before);
    // A good designspace into a new folder: all of it appears, in the new folder only.
    std::fs::create_dir_all(src.join("masters")).unwrap();
    source(&src.join("masters/B.ufo"), 1);
    std::fs::write(src.join("Good.designspace"), ds(["A.ufo", "masters/B.ufo"])).unwrap();
    let d = fix_designspace(
        &src.join("Good.designspace"),
        &dir.join("out/new/Good.designspace"),
        &opts(),
        false,
    )
    .unwrap();
    assert_eq!(d.masters.len(), 2);
    for f in [
        "Good.designspace",
        "A.ufo/glyphs/o.glif",
        "masters/B.ufo/glyphs/o.glif",
    ] {
        assert!(dir.join("out/new").join(f).exists(), "{f}");
    }
    no_staging_left(&dir.join("out"));
}

/// A contour of 10,000 points is listed with its size at once; one of 900 points (300
/// segments, near the most `fix` repairs) finishes within 10 s (about 4 s alone on a
/// 2-core machine: the other tests run beside it).
#[test]
fn a_contour_of_any_size_is_bounded() {
    let dir = scratch("big");
    for (points, repaired) in [(10_000usize, false), (900, true)] {
        let mut font = Font::new();
        let mut g = Glyph::new("big");
        let m = points / 3;
        let mut pts = Vec::new();
        let at = |k: usize| {
            let t = std::f64::consts::TAU * k as f64 / m as f64;
            let r = 5000.0 * (1.0 + 0.05 * (7.0 * t).sin());
            (r * t.cos(), r * t.sin())
        };
        for k in 0..m {
            let (a, b, prev, next) = (at(k), at(k + 1), at(k + m - 1), at(k + 2));
            let f = 1.0 + 0.2 * ((k * 7919 % 13) as f64 / 6.0 - 1.0);
            pts.push(pt(a.0.round(), a.1.round(), PointType::Curve, true));
            pts.push(pt(
                (a.0 + (b.0 - prev.0) / 6.0 * f).round(),
                (a.1 + (b.1 - prev.1) / 6.0 * f).round(),
                PointType::OffCurve,
                false,
            ));
            pts.push(pt(
                (b.0 - (next.0 - a.0) / 6.0).round(),
                (b.1 - (next.1 - a.1) / 6.0).round(),
                PointType::OffCurve,
                false,
            ));
        }
        pts.rotate_left(1);
        g.contours.push(Contour::new(pts, None));
        font.default_layer_mut().insert_glyph(g);
        let src = dir.join(format!("b{points}.ufo"));
        font.save(&src).unwrap();
        let started = Instant::now();
        let (fixes, _) =
            fix_ufo(&src, &dir.join(format!("o{points}.ufo")), &opts(), false).unwrap();
        let took = started.elapsed();
        assert!(took < Duration::from_secs(10), "{points} points: {took:?}");
        let result = &fixes[0].result;
        if repaired {
            assert!(result.is_ok(), "{result:?}");
        } else {
            let why = result.as_ref().err().unwrap();
            assert!(why.contains(&format!("{} segments", points / 3)), "{why}");
        }
    }
}

/// The parts of a UFO outside what norad models come back as they were: a UFO 2 stays a
/// UFO 2, a README, a tool's folder and `.DS_Store` are copied, an unknown font-info key
/// is kept; every file but the changed glyphs' has its bytes and modification time; in
/// the changed glyph only the lines of moved points differ.
#[test]
fn fix_writes_back_only_the_moved_points() {
    let dir = scratch("as-it-was");
    let ufo = source(&dir.join("src.ufo"), 2);
    std::fs::write(ufo.join("README.txt"), "read me").unwrap();
    std::fs::write(ufo.join(".DS_Store"), [0u8, 1, 2]).unwrap();
    std::fs::create_dir_all(ufo.join("com.example.tool")).unwrap();
    std::fs::write(ufo.join("com.example.tool/state.json"), "{}").unwrap();
    let info = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<plist version=\"1.0\">\n<dict>\n\
                \t<key>familyName</key>\n\t<string>T</string>\n\t<key>com.example.unknownKey</key>\n\
                \t<integer>7</integer>\n</dict>\n</plist>\n";
    std::fs::write(ufo.join("fontinfo.plist"), info).unwrap();
    // A UFO 2: format 2 in metainfo, no layercontents.plist.
    let meta = std::fs::read_to_string(ufo.join("metainfo.plist")).unwrap();
    std::fs::write(
        ufo.join("metainfo.plist"),
        meta.replace("<integer>3</integer>", "<integer>2</integer>"),
    )
    .unwrap();
    std::fs::remove_file(ufo.join("layercontents.plist")).unwrap();
    // Older modification times than the run's, so that a rewrite would show.
    let old = SystemTime::now() - Duration::from_secs(86_400);
    for (rel, _) in snapshot(&ufo).iter().filter(|(_, v)| v.0 == 'f') {
        let f = std::fs::File::options()
            .write(true)
            .open(ufo.join(rel))
            .unwrap();
        f.set_modified(old).unwrap();
    }
    let out = dir.join("out.ufo");
    let (fixes, counts) = fix_ufo(&ufo, &out, &opts(), false).unwrap();
    assert!(counts.changed_segments > 0, "{counts:?}");
    let (a, b) = (snapshot(&ufo), snapshot(&out));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    let changed: Vec<&PathBuf> = a.keys().filter(|k| a[*k] != b[*k]).collect();
    assert_eq!(
        changed,
        vec![
            &PathBuf::from("glyphs/o.glif"),
            &PathBuf::from("glyphs/o1.glif")
        ]
    );
    let moved: usize = fixes
        .iter()
        .filter(|f| f.glyph == "o")
        .filter_map(|f| Some((f.input.as_ref()?, f.result.as_ref().ok()?)))
        .map(|(c, h)| {
            (c.segments.iter().flatten())
                .zip(h.segments.iter().flatten())
                .filter(|(x, y)| x != y)
                .count()
        })
        .sum();
    let (x, y) = (
        String::from_utf8(a[&PathBuf::from("glyphs/o.glif")].1.clone()).unwrap(),
        String::from_utf8(b[&PathBuf::from("glyphs/o.glif")].1.clone()).unwrap(),
    );
    let differ = x.lines().zip(y.lines()).filter(|(l, m)| l != m).count();
    assert_eq!(x.lines().count(), y.lines().count());
    assert!(
        differ > 0 && differ <= moved,
        "{differ} lines differ, {moved} points moved"
    );
    for (l, m) in x.lines().zip(y.lines()).filter(|(l, m)| l != m) {
        assert!(l.trim_start().starts_with("<point") && m.trim_start().starts_with("<point"));
    }
    // The output reads back in norad as a UFO 2 would (upconverted in memory).
    assert!(Font::load(&out).is_ok());
    // With on-curve points moving too (each shared by two segments): written once each,
    // and the file still reads.
    let out2 = dir.join("out2.ufo");
    let moving = FixOptions {
        move_points: true,
        ..opts()
    };
    let (_, counts) = fix_ufo(&ufo, &out2, &moving, false).unwrap();
    assert!(counts.changed_segments > 0);
    let font = Font::load(&out2).unwrap();
    assert_eq!(font.default_layer().len(), 3);
}

/// A UFO's composites are checked through their components (as a font reader draws
/// them); a missing base and a component that names itself are listed.
#[test]
fn ufo_composites_are_checked_through_their_components() {
    let dir = scratch("composites");
    let mut font = Font::new();
    let mut o = Glyph::new("o");
    o.contours.push(o_contour(0.0));
    let mut oo = Glyph::new("oo");
    let t = |dx: f64| norad::AffineTransform {
        x_scale: 1.0,
        xy_scale: 0.0,
        yx_scale: 0.0,
        y_scale: 1.0,
        x_offset: dx,
        y_offset: 0.0,
    };
    oo.components
        .push(norad::Component::new("o".parse().unwrap(), t(0.0), None));
    oo.components
        .push(norad::Component::new("o".parse().unwrap(), t(1500.0), None));
    let mut missing = Glyph::new("missing");
    missing.components.push(norad::Component::new(
        "nothere".parse().unwrap(),
        t(0.0),
        None,
    ));
    let mut selfish = Glyph::new("selfish");
    selfish.components.push(norad::Component::new(
        "selfish".parse().unwrap(),
        t(0.0),
        None,
    ));
    for g in [o, oo, missing, selfish] {
        font.default_layer_mut().insert_glyph(g);
    }
    let src = dir.join("c.ufo");
    font.save(&src).unwrap();
    let o = aecurve::outline_io::read(&src).unwrap();
    let shape = |n: &str| o.shapes.iter().find(|s| s.name == n).unwrap();
    assert_eq!(shape("oo").contours.len(), 2);
    assert_eq!(shape("oo").contours[1].segments.len(), 4);
    let why = |n: &str| {
        (o.unreadable.iter().find(|u| u.0 == n))
            .map(|u| u.1.clone())
            .unwrap_or_default()
    };
    assert!(
        why("missing").contains("\"nothere\" is missing"),
        "{:?}",
        o.unreadable
    );
    assert!(
        why("selfish").contains("names itself"),
        "{:?}",
        o.unreadable
    );
}

/// SVG write-back touches only what it fixed: a path whose fix improves nothing keeps its
/// `d` byte for byte; in a fixed path only numbers change (commands, relative form, `H`,
/// `V`, `s` and separators as they were); paths not drawn (in `<clipPath>`, `<defs>`,
/// `<metadata>`, hidden) and a foreign namespace's `d` are left and listed.
#[test]
fn svg_fix_touches_only_what_it_fixed() {
    let dir = scratch("svg");
    let o = "m600,0c0,265-270,400-600,400s-600-200-600-400c0-250 240-400 600-400h10v5c300 0 590 \
             205 590 395z";
    let g2 = "M0 0H500V500H0Z";
    let text = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:o=\"urn:other\" viewBox=\"-700 -500 \
         1400 1000\">\n<metadata><o:path d=\"{o}\"/></metadata>\n<defs><path id=\"d\" \
         d=\"{o}\"/></defs>\n<clipPath id=\"c\"><path d=\"{o}\"/></clipPath>\n\
         <path id=\"hidden\" style=\"display:none\" d=\"{o}\"/>\n\
         <path id=\"square\" d=\"{g2}\"/>\n<path id=\"o\" o:d=\"{o}\" d=\"{o}\"/>\n</svg>\n"
    );
    let src = dir.join("in.svg");
    std::fs::write(&src, &text).unwrap();
    let out = dir.join("out.svg");
    let (fixes, counts) = aecurve::fix::fix_svg(
        &src,
        &out,
        &FixOptions {
            grid: 1e-4,
            ..opts()
        },
        false,
    )
    .unwrap();
    assert!(counts.changed_segments > 0, "{counts:?}");
    let written = std::fs::read_to_string(&out).unwrap();
    // Only the last path's d changed.
    let last_d = text.rfind(&format!(" d=\"{o}\"")).unwrap() + 4;
    assert_eq!(&written[..last_d], &text[..last_d]);
    let tail = &text[last_d + o.len()..];
    assert!(written.ends_with(tail));
    let new_d = &written[last_d..written.len() - tail.len()];
    assert_ne!(new_d, o);
    // The same commands in the same order and form (relative stays relative, h and v
    // stay), but an `s` whose first handle no longer mirrors the one before, which must be
    // written as `c`.
    let letters = |d: &str| {
        d.chars()
            .filter(|c| c.is_ascii_alphabetic())
            .map(|c| if c == 's' { 'c' } else { c })
            .collect::<String>()
    };
    assert_eq!(letters(new_d), letters(o), "{new_d}");
    assert!(new_d.contains("h10v5"), "{new_d}");
    // Numbers of points that did not move are the input's text: the start and the third
    // cubic's (`c0-250 240-400 600-400`), whose points stayed.
    assert!(new_d.starts_with("m600,0c0,"), "{new_d}");
    for name in ["d", "c", "hidden"] {
        let listed = fixes.iter().any(|f| {
            (f.glyph == name || f.glyph.starts_with("path "))
                && f.result
                    .as_ref()
                    .is_err_and(|e| e.contains("left as it is"))
        });
        assert!(listed, "{name} not listed as left");
    }
}

/// Mutated UFOs and designspaces (plists naming odd paths, damaged bytes, links): `fix`
/// never creates or changes anything outside its output, and the output is absent or a
/// UFO norad reads.
#[cfg(unix)]
#[test]
fn mutated_sources_never_write_outside_the_output() {
    use rand::{Rng, SeedableRng};
    let odd = [
        "../x.glif",
        "../../outside/victim.txt",
        "/etc/hostname",
        "/dev/zero",
        "glyphs/o.glif",
        "./o.glif",
        "..",
        ".",
        "",
        "o.glif/",
        "sub/o.glif",
        "o.glif\u{0}",
        "very/../../o.glif",
        "\\..\\x.glif",
    ];
    let dir = scratch("fuzz");
    let outside = dir.join("outside");
    std::fs::create_dir_all(&outside).unwrap();
    std::fs::write(outside.join("victim.txt"), "user data").unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(66);
    let (mut refused, mut written) = (0, 0);
    for case in 0..120 {
        let work = dir.join(format!("case{case}"));
        std::fs::create_dir_all(&work).unwrap();
        let ufo = source(&work.join("src.ufo"), 2);
        match rng.random_range(0..6) {
            0 => set_plist_string(
                &ufo.join("glyphs/contents.plist"),
                "o",
                odd[rng.random_range(0..odd.len())],
            ),
            1 => {
                let lc = ufo.join("layercontents.plist");
                let t = std::fs::read_to_string(&lc).unwrap();
                let to = odd[rng.random_range(0..odd.len())];
                std::fs::write(
                    &lc,
                    t.replace("<string>glyphs</string>", &format!("<string>{to}</string>")),
                )
                .unwrap();
            }
            2 => {
                // Damaged bytes in a glif or a plist.
                let files = [
                    "glyphs/o.glif",
                    "glyphs/contents.plist",
                    "layercontents.plist",
                    "metainfo.plist",
                ];
                let f = ufo.join(files[rng.random_range(0..files.len())]);
                let mut b = std::fs::read(&f).unwrap();
                for _ in 0..rng.random_range(1..8) {
                    let i = rng.random_range(0..b.len());
                    b[i] = rng.random();
                }
                std::fs::write(&f, b).unwrap();
            }
            3 => {
                // A link inside the UFO, to a file outside.
                let _ = std::fs::remove_file(ufo.join("glyphs/o.glif"));
                std::os::unix::fs::symlink(outside.join("victim.txt"), ufo.join("glyphs/o.glif"))
                    .unwrap();
            }
            4 => {
                // The output named through odd paths.
                let _ = std::fs::write(work.join("note"), "x");
            }
            _ => {
                let f = ufo.join("glyphs/o.glif");
                let b = std::fs::read(&f).unwrap();
                std::fs::write(&f, &b[..rng.random_range(0..b.len())]).unwrap();
            }
        }
        let outputs = [
            "out.ufo",
            "src.ufo/in.ufo",
            "src.ufo",
            "note/x.ufo",
            "a/b/out.ufo",
        ];
        let rel = outputs[rng.random_range(0..outputs.len())];
        let out = work.join(rel);
        let before = snapshot(&dir);
        let result = fix_ufo(&ufo, &out, &opts(), false);
        let mut after = snapshot(&dir);
        match &result {
            Ok(_) => {
                written += 1;
                assert!(
                    Font::load(&out).is_ok(),
                    "case {case}: an output norad cannot read"
                );
                let out_rel = out.strip_prefix(&dir).unwrap().to_path_buf();
                after.retain(|k, _| !k.starts_with(&out_rel));
                // Folders the output's path needed are new too.
                let mut a = out_rel.parent();
                while let Some(p) = a.filter(|p| !p.as_os_str().is_empty()) {
                    if !before.contains_key(p) {
                        after.remove(p);
                    }
                    a = p.parent();
                }
            }
            Err(_) => refused += 1,
        }
        assert_eq!(
            after,
            before,
            "case {case} ({rel}): {result:?}",
            result = result.as_ref().err()
        );
    }
    assert!(
        refused > 0 && written > 0,
        "{refused} refused, {written} written"
    );
}
