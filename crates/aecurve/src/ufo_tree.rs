//! A UFO source read whole into memory, confined to its own folder, before any of it is
//! parsed.
//!
//! A UFO names its own files: `layercontents.plist` names the layers' folders, each layer's
//! `contents.plist` names its glyphs' `.glif` files. Those names are data from the file,
//! and a name such as `../../outside/O_.glif` or `/dev/zero` must not lead a reader (or
//! a writer that writes the fixed glyph back where it was read) outside the UFO. So the
//! folder is walked first, without following links: only folders and regular files, at
//! most [`MAX_DEPTH`] levels and the caller's cap of bytes in all, each file opened without
//! blocking and checked again once open. Then every entry of the two plists is checked to
//! be a plain name of the UFO's own (one path component, no `..`, not absolute) naming a
//! file that was read, and an entry that is not is an error naming the entry and the plist
//! that holds it. Only then does norad parse the font, from these bytes in memory
//! ([`norad::FontSource`]): nothing it reads can come from anywhere else.
//!
//! The bytes stay in the tree, so that `fix` writes the output from what it read: every file
//! it did not change byte for byte as it was, with its modification time.

use crate::regular_file::read_no_follow;
use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};
use std::time::SystemTime;

/// Folders nested deeper than this inside a UFO are refused (the spec's deepest is
/// `data/` with a tool's own folders below).
pub const MAX_DEPTH: usize = 8;

/// One regular file of the tree.
#[derive(Clone, Debug)]
pub struct TreeFile {
    /// Its bytes as read.
    pub bytes: Vec<u8>,
    /// Its modification time, kept on the copy written.
    pub modified: Option<SystemTime>,
}

/// A UFO folder in memory: its folders and regular files by path relative to the root.
#[derive(Clone, Debug)]
pub struct UfoTree {
    /// The folder it was read from.
    pub root: PathBuf,
    /// Every folder below the root (relative), parents before children.
    pub dirs: Vec<PathBuf>,
    /// Every regular file (relative path to its bytes).
    pub files: BTreeMap<PathBuf, TreeFile>,
}

/// A layer of the UFO: its name, its folder and its glyphs' files (relative to the root).
#[derive(Clone, Debug)]
pub struct LayerFiles {
    /// The layer's name (`public.default` for the default layer).
    pub name: String,
    /// Its folder, relative to the root.
    pub dir: PathBuf,
    /// Glyph name to the `.glif` file's path relative to the root.
    pub glyphs: BTreeMap<String, PathBuf>,
}

impl UfoTree {
    /// Read the folder at `root`: folders and regular files only (a link, pipe, device or
    /// socket anywhere is an error naming it), at most [`MAX_DEPTH`] levels and `cap` bytes
    /// in all.
    pub fn read(root: &Path, cap: u64) -> Result<UfoTree> {
        let meta = std::fs::symlink_metadata(root)
            .with_context(|| format!("reading {}", root.display()))?;
        if !meta.is_dir() {
            bail!(
                "{}: not a folder (a UFO source is a .ufo folder; links are not followed)",
                root.display()
            );
        }
        let mut tree = UfoTree {
            root: root.to_path_buf(),
            dirs: Vec::new(),
            files: BTreeMap::new(),
        };
        let mut total = 0u64;
        let mut stack = vec![PathBuf::new()];
        while let Some(rel) = stack.pop() {
            let depth = rel.components().count();
            if depth > MAX_DEPTH {
                bail!(
                    "{}: folders nested deeper than {MAX_DEPTH} levels in a UFO source",
                    root.join(&rel).display()
                );
            }
            let dir = root.join(&rel);
            let mut entries: Vec<_> = std::fs::read_dir(&dir)
                .with_context(|| format!("reading {}", dir.display()))?
                .collect::<std::io::Result<_>>()
                .with_context(|| format!("reading {}", dir.display()))?;
            entries.sort_by_key(|e| e.file_name());
            for entry in entries {
                let name = rel.join(entry.file_name());
                let path = root.join(&name);
                let meta = std::fs::symlink_metadata(&path)
                    .with_context(|| format!("reading {}", path.display()))?;
                if meta.is_dir() {
                    tree.dirs.push(name.clone());
                    stack.push(name);
                } else if meta.is_file() {
                    total += meta.len();
                    if total > cap {
                        bail!(
                            "{}: over the {} MB that are read",
                            root.display(),
                            cap / (1024 * 1024)
                        );
                    }
                    let bytes = read_no_follow(&path, cap - (total - meta.len()))?;
                    total += (bytes.len() as u64).saturating_sub(meta.len());
                    let modified = meta.modified().ok();
                    tree.files.insert(name, TreeFile { bytes, modified });
                } else {
                    bail!(
                        "{}: not a regular file (a link, pipe or device) inside the UFO \
                         source: only its own files are read",
                        path.display()
                    );
                }
            }
        }
        tree.dirs.sort();
        Ok(tree)
    }

    /// The bytes of the file at `rel`, if the tree holds it.
    pub fn get(&self, rel: &Path) -> Option<&[u8]> {
        self.files.get(rel).map(|f| f.bytes.as_slice())
    }

    /// The UFO's layers and their glyph files as its plists name them, every entry checked
    /// to be a plain name of a file of the tree. A UFO 2 (no `layercontents.plist`) has
    /// the one layer `glyphs`.
    pub fn layers(&self) -> Result<Vec<LayerFiles>> {
        let lc = Path::new("layercontents.plist");
        let pairs: Vec<(String, String)> = match self.get(lc) {
            None => vec![("public.default".into(), "glyphs".into())],
            Some(bytes) => {
                let v: Vec<Vec<String>> = plist::from_bytes(bytes).map_err(|e| {
                    anyhow::anyhow!("{}: not a list of [name, folder] pairs: {e}", self.at(lc))
                })?;
                let mut out = Vec::with_capacity(v.len());
                for pair in v {
                    let [name, dir]: [String; 2] = pair.try_into().map_err(|p: Vec<String>| {
                        anyhow::anyhow!("{}: an entry of {} strings, not 2", self.at(lc), p.len())
                    })?;
                    out.push((name, dir));
                }
                out
            }
        };
        let mut layers = Vec::with_capacity(pairs.len());
        for (name, dir) in pairs {
            let dir = self.plain_name(&dir, lc, "layer folder")?;
            if !self.dirs.contains(&dir) {
                bail!(
                    "{}: the layer {name:?} names the folder {:?}, which the UFO does not hold",
                    self.at(lc),
                    dir.display()
                );
            }
            let contents = dir.join("contents.plist");
            let Some(bytes) = self.get(&contents) else {
                bail!(
                    "{}: missing (the layer {name:?}'s glyph list)",
                    self.at(&contents)
                );
            };
            let entries: BTreeMap<String, String> = plist::from_bytes(bytes).map_err(|e| {
                anyhow::anyhow!(
                    "{}: not a dictionary of glyph files: {e}",
                    self.at(&contents)
                )
            })?;
            let mut glyphs = BTreeMap::new();
            for (glyph, file) in entries {
                let file = dir.join(self.plain_name(&file, &contents, "glyph file")?);
                if !self.files.contains_key(&file) {
                    bail!(
                        "{}: glyph {glyph:?} names {:?}, which the UFO does not hold",
                        self.at(&contents),
                        file.display()
                    );
                }
                glyphs.insert(glyph, file);
            }
            layers.push(LayerFiles { name, dir, glyphs });
        }
        Ok(layers)
    }

    /// `entry` of the plist at `plist` as a path: one plain component, or an error naming
    /// the entry and the plist.
    fn plain_name(&self, entry: &str, plist: &Path, what: &str) -> Result<PathBuf> {
        let p = Path::new(entry);
        let mut comps = p.components();
        match (comps.next(), comps.next()) {
            (Some(Component::Normal(c)), None) if !entry.contains(['/', '\\', '\0']) => {
                Ok(PathBuf::from(c))
            }
            _ => bail!(
                "{}: the {what} {entry:?} is not a name inside the UFO (a path that leaves \
                 it, or a folder below): refused, nothing outside a UFO is read or written",
                self.at(plist)
            ),
        }
    }

    /// A path of the tree for a message.
    fn at(&self, rel: &Path) -> String {
        self.root.join(rel).display().to_string()
    }

    /// The font, parsed by norad from the tree's bytes (every plist entry checked first).
    pub fn font(&self) -> Result<norad::Font> {
        self.layers()?;
        let source = TreeSource(self);
        crate::contained::contained(|| {
            norad::Font::load_from_source(&norad::DataRequest::all(), &source).map_err(|e| {
                match self.first_bad_glif() {
                    Some((file, why)) => anyhow::anyhow!(
                        "not a readable UFO: {} cannot be read ({why}); fix or remove that \
                         glyph file",
                        self.at(&file)
                    ),
                    None => anyhow::anyhow!("not a readable UFO: {}", error_chain(&e)),
                }
            })
        })
    }

    /// The first `.glif` file of the tree that norad does not parse, and why.
    fn first_bad_glif(&self) -> Option<(PathBuf, String)> {
        self.files
            .iter()
            .filter(|(p, _)| p.extension().is_some_and(|e| e == "glif"))
            .find_map(|(p, f)| {
                norad::Glyph::parse_raw(&f.bytes)
                    .err()
                    .map(|e| (p.clone(), error_chain(&e)))
            })
    }
}

/// An error and its sources, one after the other.
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut src = e.source();
    while let Some(inner) = src {
        s.push_str(": ");
        s.push_str(&inner.to_string());
        src = inner.source();
    }
    s
}

/// The tree as norad's source: it reads only what the tree holds.
struct TreeSource<'a>(&'a UfoTree);

impl norad::FontSource for TreeSource<'_> {
    fn try_read(&self, path: &Path) -> Option<std::io::Result<Vec<u8>>> {
        self.0.get(path).map(|b| Ok(b.to_vec()))
    }

    fn list_dir(&self, path: &Path) -> std::io::Result<Vec<norad::DirEntry>> {
        let t = self.0;
        let child = |p: &Path| p.parent() == Some(path);
        let name = |p: &Path| PathBuf::from(p.file_name().unwrap_or_default());
        let mut out: Vec<norad::DirEntry> = (t.dirs.iter().filter(|p| child(p)))
            .map(|p| norad::DirEntry::Dir(name(p)))
            .collect();
        out.extend((t.files.keys().filter(|p| child(p))).map(|p| norad::DirEntry::File(name(p))));
        Ok(out)
    }
}
