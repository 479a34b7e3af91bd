//! Every command of the README's "Command line" section runs as written: each exits 0 and
//! writes the files it names. The commands are read from README.md itself, so the README
//! and this test cannot drift apart. They run in a scratch folder holding a copy of the
//! repository's `examples/`, as a user who pasted them in a clone would.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The lines of the first ```sh block after the "## Command line" heading, comments cut.
fn readme_commands() -> Vec<String> {
    let text = std::fs::read_to_string(format!("{ROOT}/README.md")).expect("README.md");
    let section = text
        .split("\n## Command line")
        .nth(1)
        .expect("README has a '## Command line' section");
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .expect("the section has a ```sh block");
    block
        .lines()
        .map(|l| strip_comment(l).trim().to_string())
        .filter(|l| !l.is_empty())
        .collect()
}

/// The line without a trailing `# comment` (a `#` outside quotes after white space).
fn strip_comment(line: &str) -> &str {
    let mut quoted = false;
    let mut prev_space = true;
    for (i, c) in line.char_indices() {
        match c {
            '"' => quoted = !quoted,
            '#' if !quoted && prev_space => return &line[..i],
            _ => {}
        }
        prev_space = c.is_whitespace();
    }
    line
}

/// Words of a command line: double quotes group, `<` and `>` redirect.
struct Parsed {
    words: Vec<String>,
    stdin: Option<String>,
    stdout: Option<String>,
}

fn parse(line: &str) -> Parsed {
    let mut words = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut any = false;
    for c in line.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                any = true;
            }
            c if c.is_whitespace() && !quoted => {
                if any {
                    words.push(std::mem::take(&mut cur));
                    any = false;
                }
            }
            c => {
                cur.push(c);
                any = true;
            }
        }
    }
    assert!(!quoted, "unbalanced quotes in: {line}");
    if any {
        words.push(cur);
    }
    let mut out = Parsed {
        words: Vec::new(),
        stdin: None,
        stdout: None,
    };
    let mut it = words.into_iter();
    while let Some(w) = it.next() {
        match w.as_str() {
            "<" => out.stdin = it.next(),
            ">" => out.stdout = it.next(),
            _ => out.words.push(w),
        }
    }
    out
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

#[test]
fn readme_command_line_section_runs_as_written() {
    let commands = readme_commands();
    assert!(
        commands.len() >= 15,
        "only {} commands found",
        commands.len()
    );
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy_dir(&PathBuf::from(ROOT).join("examples"), &dir.join("examples"));
    let mut failures = Vec::new();
    for line in &commands {
        // Pasted as is: no placeholder syntax such as `[--closed]` or `<FILE>`.
        assert!(
            !line.contains("[-") && !line.contains("DIR") && !line.contains("FILE"),
            "placeholder syntax in a command meant to be pasted: {line}"
        );
        let p = parse(line);
        assert_eq!(
            p.words[0], "aecurve",
            "every command starts with aecurve: {line}"
        );
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_aecurve"));
        cmd.args(&p.words[1..]).current_dir(&dir);
        cmd.stdin(match &p.stdin {
            Some(f) => Stdio::from(std::fs::File::open(dir.join(f)).expect(f)),
            None => Stdio::null(),
        });
        let started = std::time::Instant::now();
        let out = cmd.output().expect("run aecurve");
        let secs = started.elapsed().as_secs_f64();
        if let Some(f) = &p.stdout {
            std::fs::write(dir.join(f), &out.stdout).unwrap();
        }
        println!("{secs:6.2} s  exit {:?}  {line}", out.status.code());
        if !out.status.success() {
            failures.push(format!(
                "{line}\n  stderr: {}",
                String::from_utf8_lossy(&out.stderr)
            ));
            continue;
        }
        // Every file it was told to write is there and not empty.
        for (i, w) in p.words.iter().enumerate() {
            if matches!(w.as_str(), "-o" | "--output" | "--map" | "--curvature-plot") {
                let path = dir.join(&p.words[i + 1]);
                let len = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
                if len == 0 {
                    failures.push(format!("{line}\n  did not write {}", path.display()));
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "failed:\n{}", failures.join("\n"));
}

#[test]
fn comment_and_word_splitting() {
    assert_eq!(
        strip_comment(r#"aecurve x "a # b"   # note"#).trim(),
        r#"aecurve x "a # b""#
    );
    let p = parse(r#"aecurve lac --control "0,0 1,0 1,1" < in.jsonl > out.jsonl"#);
    assert_eq!(p.words, ["aecurve", "lac", "--control", "0,0 1,0 1,1"]);
    assert_eq!(p.stdin.as_deref(), Some("in.jsonl"));
    assert_eq!(p.stdout.as_deref(), Some("out.jsonl"));
}
