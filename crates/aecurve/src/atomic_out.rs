//! Output that appears whole or not at all, only where the user said.
//!
//! A command that writes a file or a folder (a fixed UFO, a designspace and its masters, an
//! SVG, a report page) builds it in a staging folder, a hidden sibling of the output made
//! fresh for this run (`.NAME.aecurve-XXXXXX`), and moves it into place when every byte is
//! written and synced. The move is one `rename`: the output appears complete, or, after a
//! kill, a full disk or a write error at any moment before it, does not appear at all (the
//! staging folder is removed on every error; only a kill can leave it, never the output).
//!
//! - The output is refused when anything exists at its path (a dangling link included)
//!   unless `--overwrite` says so; the move itself refuses to replace what appeared during
//!   the run (Linux's `renameat2(RENAME_NOREPLACE)`), and with `--overwrite` the previous
//!   output is swapped out in the same step (`RENAME_EXCHANGE`) and removed after. A link
//!   given as the output is never followed: it is what gets replaced.
//! - Folders the output's path needs and that do not exist are made inside the staging
//!   folder and moved in with it: a failed run leaves none of them.
//! - Nothing is written inside an input (an output inside the UFO being read is refused),
//!   and nothing outside the output's own path: the files written beside it (a
//!   designspace's masters) must be plain relative paths below the output's folder.
//!
//! A designspace is several outputs (its file and its masters): each is moved in as one
//! step, the masters first and the designspace last, so a designspace never names a master
//! that is not there; when the output's folder is new, it is the one step.

use anyhow::{bail, Context, Result};
use std::path::{Component, Path, PathBuf};

/// A staged output: where to build it, and how it is moved into place.
pub struct Staging {
    /// The existing folder the output is moved into (canonical).
    base: PathBuf,
    /// The output relative to `base` (plain components).
    output_rel: PathBuf,
    /// Everything written beside the output (relative to `base`), the output last.
    entries: Vec<PathBuf>,
    /// The staging folder, a sibling inside `base`.
    dir: Option<tempfile::TempDir>,
    /// Whether an existing output is replaced.
    overwrite: bool,
}

impl Staging {
    /// A staging folder for the output at `output`, checked against the inputs it must not
    /// be inside (nor contain), and refused when the output exists and `overwrite` is off.
    pub fn new(output: &Path, overwrite: bool, inputs: &[&Path]) -> Result<Staging> {
        let (base, output_rel) = split_existing(output)?;
        let target = base.join(&output_rel);
        let exists = std::fs::symlink_metadata(&target).is_ok();
        if exists && !overwrite {
            bail!(
                "{}: already exists; nothing is replaced unless --overwrite is given",
                output.display()
            );
        }
        for input in inputs {
            let Ok(input) = std::fs::canonicalize(input) else {
                continue;
            };
            if target != input && target.starts_with(&input) {
                bail!(
                    "{}: inside the input {}; the output is written beside its input, \
                     never inside it",
                    output.display(),
                    input.display()
                );
            }
            if target != input && input.starts_with(&target) {
                bail!(
                    "{}: holds the input {}; choose an output that does not contain it",
                    output.display(),
                    input.display()
                );
            }
        }
        let name = output_rel
            .components()
            .next()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .unwrap_or_default();
        let dir = tempfile::Builder::new()
            .prefix(&format!(".{name}.aecurve-"))
            .tempdir_in(&base)
            .with_context(|| format!("making a staging folder in {}", base.display()))?;
        Ok(Staging {
            base,
            entries: vec![output_rel.clone()],
            output_rel,
            dir: Some(dir),
            overwrite,
        })
    }

    /// The staging folder.
    fn root(&self) -> &Path {
        self.dir.as_ref().map(|d| d.path()).unwrap_or(Path::new(""))
    }

    /// Where to build the output (in the staging folder; its parent folders exist).
    pub fn output(&self) -> Result<PathBuf> {
        self.staged(&self.output_rel)
    }

    /// Where to build a file or folder at `rel` relative to the output's folder (a
    /// designspace's master): `rel` must be a plain relative path below that folder, and
    /// nothing may exist there unless `--overwrite` was given.
    pub fn beside(&mut self, rel: &str) -> Result<PathBuf> {
        let rel_path = Path::new(rel);
        if rel.is_empty()
            || !rel_path
                .components()
                .all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
        {
            bail!(
                "{rel:?}: not a path below the output's folder (it leaves it or is absolute); \
                 nothing is written outside the output's folder"
            );
        }
        let folder = self.output_rel.parent().unwrap_or(Path::new(""));
        let clean: PathBuf = rel_path
            .components()
            .filter(|c| matches!(c, Component::Normal(_)))
            .collect();
        let full = folder.join(clean);
        if full == self.output_rel || self.entries.contains(&full) {
            bail!("{rel:?}: written twice (the output, or another entry at the same path)");
        }
        if !self.overwrite && std::fs::symlink_metadata(self.base.join(&full)).is_ok() {
            bail!(
                "{}: already exists; nothing is replaced unless --overwrite is given",
                self.base.join(&full).display()
            );
        }
        let at = self.staged(&full)?;
        let last = self.entries.len() - 1;
        self.entries.insert(last, full);
        Ok(at)
    }

    /// The staging path of `rel`, its parent folders made.
    fn staged(&self, rel: &Path) -> Result<PathBuf> {
        let at = self.root().join(rel);
        if let Some(parent) = at.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("making {}", parent.display()))?;
        }
        Ok(at)
    }

    /// Sync what was built and move it into place: every entry as one rename each (the
    /// output last); on an error the entries already moved are moved back and the error
    /// names the output. The staging folder (and a replaced previous output) is removed.
    pub fn commit(mut self) -> Result<()> {
        sync_tree(self.root())?;
        let units = self.units();
        let mut done: Vec<(PathBuf, bool)> = Vec::new();
        for unit in &units {
            let from = self.root().join(unit);
            let to = self.base.join(unit);
            let replace = self.overwrite && std::fs::symlink_metadata(&to).is_ok();
            let moved = if replace {
                exchange(&from, &to)
            } else {
                rename_new(&from, &to)
            };
            if let Err(e) = moved {
                for (unit, replaced) in done.iter().rev() {
                    let (from, to) = (self.root().join(unit), self.base.join(unit));
                    let _ = if *replaced {
                        exchange(&from, &to)
                    } else {
                        rename_new(&to, &from)
                    };
                }
                return Err(e).with_context(|| format!("moving {} into place", to.display()));
            }
            done.push((unit.clone(), replace));
        }
        sync_dir(&self.base);
        if let Some(dir) = self.dir.take() {
            dir.close()
                .with_context(|| "removing the staging folder (the output is in place)")?;
        }
        Ok(())
    }

    /// The steps of the move: per entry, its first path component below `base` that does
    /// not exist there yet (a new folder moves in with everything in it), or the entry
    /// itself; each once, the output's last.
    fn units(&self) -> Vec<PathBuf> {
        let mut units: Vec<PathBuf> = Vec::new();
        for entry in &self.entries {
            let mut unit = PathBuf::new();
            for c in entry.components() {
                unit.push(c);
                if std::fs::symlink_metadata(self.base.join(&unit)).is_err() {
                    break;
                }
            }
            units.retain(|u| u != &unit);
            units.push(unit);
        }
        units
    }
}

/// The output's nearest existing folder (canonical) and the output's path below it (plain
/// components only: a `..` after the existing part is refused, not resolved).
fn split_existing(output: &Path) -> Result<(PathBuf, PathBuf)> {
    let Some(name) = output.file_name() else {
        bail!("{}: not a file or folder name to write", output.display());
    };
    let mut rel = vec![PathBuf::from(name)];
    let mut folder = output.parent().unwrap_or(Path::new(""));
    loop {
        let probe = if folder.as_os_str().is_empty() {
            Path::new(".")
        } else {
            folder
        };
        if std::fs::metadata(probe).is_ok_and(|m| m.is_dir()) {
            let base = std::fs::canonicalize(probe)
                .with_context(|| format!("reading {}", probe.display()))?;
            let rel: PathBuf = rel.iter().rev().collect();
            return Ok((base, rel));
        }
        if std::fs::symlink_metadata(probe).is_ok() {
            bail!(
                "{}: not a folder, so {} cannot be written",
                probe.display(),
                output.display()
            );
        }
        match folder.components().next_back() {
            Some(Component::Normal(c)) => rel.push(PathBuf::from(c)),
            _ => bail!(
                "{}: its folder {} does not exist and is not a plain path to make",
                output.display(),
                folder.display()
            ),
        }
        folder = folder.parent().unwrap_or(Path::new(""));
    }
}

/// Write a new file (never an existing one, never through a link) with `bytes`, synced;
/// its modification time set to `modified` when given.
pub fn write_new(path: &Path, bytes: &[u8], modified: Option<std::time::SystemTime>) -> Result<()> {
    use std::io::Write;
    let what = || format!("writing {}", path.display());
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
        .with_context(what)?;
    file.write_all(bytes).with_context(what)?;
    if let Some(m) = modified {
        file.set_modified(m).with_context(what)?;
    }
    Ok(())
}

/// fsync every file and folder below `root` (the rename that publishes them comes after).
fn sync_tree(root: &Path) -> Result<()> {
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in
            std::fs::read_dir(&dir).with_context(|| format!("reading {}", dir.display()))?
        {
            let path = entry
                .with_context(|| format!("reading {}", dir.display()))?
                .path();
            let meta = std::fs::symlink_metadata(&path)?;
            if meta.is_dir() {
                stack.push(path);
            } else if meta.is_file() {
                std::fs::File::open(&path)
                    .and_then(|f| f.sync_all())
                    .with_context(|| format!("syncing {}", path.display()))?;
            }
        }
        sync_dir(&dir);
    }
    Ok(())
}

/// fsync a folder (its entries); where a folder cannot be opened for it, nothing.
fn sync_dir(dir: &Path) {
    if let Ok(f) = std::fs::File::open(dir) {
        let _ = f.sync_all();
    }
}

/// Move `from` to `to`, failing if anything exists at `to` (atomically on Linux).
fn rename_new(from: &Path, to: &Path) -> Result<()> {
    #[cfg(target_os = "linux")]
    {
        renameat2(from, to, libc::RENAME_NOREPLACE).map_err(|e| {
            if e.kind() == std::io::ErrorKind::AlreadyExists {
                anyhow::anyhow!(
                    "{}: appeared while the output was being written; nothing replaced",
                    to.display()
                )
            } else {
                anyhow::Error::new(e)
            }
        })
    }
    #[cfg(not(target_os = "linux"))]
    {
        if std::fs::symlink_metadata(to).is_ok() {
            bail!(
                "{}: appeared while the output was being written; nothing replaced",
                to.display()
            );
        }
        std::fs::rename(from, to).map_err(anyhow::Error::new)
    }
}

/// Swap `from` and `to` (both exist), atomically on Linux.
fn exchange(from: &Path, to: &Path) -> Result<()> {
    #[cfg(target_os = "linux")]
    {
        renameat2(from, to, libc::RENAME_EXCHANGE).map_err(anyhow::Error::new)
    }
    #[cfg(not(target_os = "linux"))]
    {
        let aside = from.with_extension("previous");
        std::fs::rename(to, &aside)?;
        std::fs::rename(from, to)?;
        std::fs::rename(&aside, from)?;
        Ok(())
    }
}

#[cfg(target_os = "linux")]
fn renameat2(from: &Path, to: &Path, flags: libc::c_uint) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| {
        std::ffi::CString::new(p.as_os_str().as_bytes())
            .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidInput, "a NUL in a path"))
    };
    let (a, b) = (c(from)?, c(to)?);
    // SAFETY: two NUL-terminated paths that live across the call; AT_FDCWD for both.
    let r = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            flags,
        )
    };
    if r == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}
