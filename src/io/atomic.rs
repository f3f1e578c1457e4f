//! Atomic writing: a temporary file next to the target, renamed into place.

use super::MeshFileError;
use alloc::format;
use std::fs;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};

/// Writes a file atomically: `fill` writes into a new temporary file in the directory of
/// `path`, which is flushed, synced and then renamed onto `path`.
///
/// If creating, filling, syncing or renaming fails, the temporary file is removed and the
/// error returned; an existing file at `path` is left as it was, and nothing is created.
///
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-atomic-{}.txt", std::process::id()));
/// zipmesh::io::write_atomic(&path, |w| w.write_all(b"hello")).unwrap();
/// let failed = zipmesh::io::write_atomic(&path, |w| {
///     w.write_all(b"partial")?;
///     Err(std::io::Error::other("stop"))
/// });
/// assert!(failed.is_err());
/// assert_eq!(std::fs::read(&path).unwrap(), b"hello");
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn write_atomic<F>(path: impl AsRef<Path>, fill: F) -> Result<(), MeshFileError>
where
    F: FnOnce(&mut BufWriter<fs::File>) -> io::Result<()>,
{
    let path = path.as_ref();
    let err = |e| MeshFileError::io(path, e);
    let name = path
        .file_name()
        .ok_or_else(|| err(io::Error::new(io::ErrorKind::InvalidInput, "no file name")))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let (file, tmp) = create_temp(dir, name).map_err(err)?;
    let guard = TempGuard(Some(tmp));
    let mut w = BufWriter::with_capacity(1 << 16, file);
    fill(&mut w).map_err(err)?;
    let file = w.into_inner().map_err(|e| err(e.into_error()))?;
    file.sync_all().map_err(err)?;
    drop(file);
    let tmp = guard.path();
    fs::rename(tmp, path).map_err(err)?;
    guard.disarm();
    Ok(())
}

/// Creates a fresh temporary file next to the target: `.NAME.PID.N.tmp`.
fn create_temp(dir: &Path, name: &std::ffi::OsStr) -> io::Result<(fs::File, PathBuf)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut last = None;
    for _ in 0..16 {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".{}.{n}.tmp", std::process::id()));
        let tmp = dir.join(tmp_name);
        match fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((f, tmp)),
            // A stale file of a crashed run with the same pid: try the next number.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| io::Error::other("no temporary file name available")))
}

/// Removes the temporary file when dropped, unless it was renamed into place.
struct TempGuard(Option<PathBuf>);

impl TempGuard {
    fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new(""))
    }

    fn disarm(mut self) {
        self.0 = None;
    }
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = fs::remove_file(p);
        }
    }
}
