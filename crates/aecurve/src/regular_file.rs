//! Regular files read safely: refused unless regular, opened without blocking (a pipe
//! named as a file never hangs the reader), checked again once open (it may have been
//! replaced), and read to a cap.

use anyhow::{bail, Context, Result};
use std::path::Path;

/// The bytes of a regular file, at most `cap` of them: anything else (a pipe, a device, a
/// socket) is refused before it is opened, the file is opened without blocking and checked
/// again once open (it may have been replaced), and the read stops at the cap.
pub fn read_regular_file(path: &Path, cap: u64) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).with_context(|| format!("reading {}", path.display()))?;
    if !meta.is_file() {
        bail!(
            "{}: not a regular file (a pipe, device or socket?): only files are read",
            path.display()
        );
    }
    if meta.len() > cap {
        bail!(
            "{}: {} bytes, over the {} MB that are read",
            path.display(),
            meta.len(),
            cap / (1024 * 1024)
        );
    }
    open_and_read(path, cap, false)
}

/// [`read_regular_file`] for a file inside a folder being read whole: a link is not
/// followed (opened with `O_NOFOLLOW`, it is refused).
pub fn read_no_follow(path: &Path, cap: u64) -> Result<Vec<u8>> {
    open_and_read(path, cap, true)
}

/// Open without blocking (and without following a link when `no_follow`), check the open
/// file is regular, read at most `cap` bytes.
fn open_and_read(path: &Path, cap: u64, no_follow: bool) -> Result<Vec<u8>> {
    use std::io::Read;
    let what = || format!("reading {}", path.display());
    let mut opts = std::fs::OpenOptions::new();
    opts.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        let link = if no_follow { libc::O_NOFOLLOW } else { 0 };
        opts.custom_flags(libc::O_NONBLOCK | link);
    }
    #[cfg(not(unix))]
    let _ = no_follow;
    let file = opts.open(path).with_context(what)?;
    let meta = file.metadata().with_context(what)?;
    if !meta.is_file() {
        bail!("{}: not a regular file once opened", path.display());
    }
    let mut data = Vec::with_capacity(meta.len().min(cap) as usize);
    file.take(cap + 1)
        .read_to_end(&mut data)
        .with_context(what)?;
    if data.len() as u64 > cap {
        bail!(
            "{}: over the {} MB that are read",
            path.display(),
            cap / (1024 * 1024)
        );
    }
    Ok(data)
}
