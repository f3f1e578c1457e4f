//! Atomic writing: the new contents go to a temporary file in the target's directory, which
//! replaces the target only once it is complete and synced.
//!
//! On Linux the temporary file has no name while it is written (`O_TMPFILE`): a process
//! killed in the middle, even by `SIGKILL`, leaves nothing. It gets a name only for the
//! instant between linking it into the directory and renaming it onto the target. Where
//! unnamed files are not available (other systems, or file systems without `O_TMPFILE`)
//! the temporary is written under that same name. The name is fixed per target,
//! `.zipmesh-<hash of the file name>.tmp` (29 bytes, so a long target name still fits), so
//! the next write to the target removes what a killed process left.
//!
//! Signal handlers call [`remove_temporaries`] so that `SIGINT` or `SIGTERM` leaves nothing
//! even where the temporary has a name.

use super::{ErrorKind, MeshFileError};
use alloc::format;
use alloc::vec::Vec;
use std::ffi::OsStr;
use std::fs;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// The named temporaries of this process, and whether [`remove_temporaries`] ran (after
/// which no new one is made). Creating, renaming and removing them happens under this lock,
/// so a signal handler never misses one.
struct Live {
    paths: Vec<PathBuf>,
    ending: bool,
}

static LIVE: Mutex<Live> = Mutex::new(Live {
    paths: Vec::new(),
    ending: false,
});

fn live() -> MutexGuard<'static, Live> {
    LIVE.lock().unwrap_or_else(|p| p.into_inner())
}

/// Removes every temporary file this process is writing and refuses new ones: what a
/// handler of `SIGINT` or `SIGTERM` calls before the process ends. A write still in
/// progress then fails with [`io::ErrorKind::Interrupted`] and leaves its target as it was.
///
/// ```
/// zipmesh::io::remove_temporaries();
/// let path = std::env::temp_dir().join("zipmesh-doc-ending.txt");
/// let e = zipmesh::io::write_atomic(&path, |_| Ok(())).unwrap_err();
/// assert!(e.to_string().contains("ending"));
/// assert!(!path.exists());
/// ```
pub fn remove_temporaries() {
    let mut live = live();
    live.ending = true;
    for p in live.paths.drain(..) {
        let _ = fs::remove_file(p);
    }
}

fn ending_error() -> io::Error {
    io::Error::new(io::ErrorKind::Interrupted, "the process is ending")
}

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
    prepare_atomic(path, fill)?.commit()
}

/// Checks, before any work, that a file can be put at `path`: its directory exists and is
/// a directory, and `path` is not itself a directory. [`prepare_atomic`] checks this first;
/// a command calls it before it reads or computes anything, so that a mistyped output fails
/// at once. (Permissions are not checked: only writing finds them.)
///
/// The error names `path` and is [`ErrorKind::IsDirectory`], [`ErrorKind::MissingDirectory`]
/// or [`ErrorKind::NotADirectory`] (the first component of the directory that exists but is
/// a file); any other failure to look is [`ErrorKind::Io`].
///
/// ```
/// use zipmesh::io::{check_target, ErrorKind};
/// let dir = std::env::temp_dir();
/// assert!(check_target(dir.join("new.obj")).is_ok());
/// let e = check_target(dir.join("zipmesh-no-such-dir").join("new.obj")).unwrap_err();
/// assert!(matches!(e.kind(), ErrorKind::MissingDirectory { .. }));
/// assert!(e.to_string().ends_with("zipmesh-no-such-dir does not exist"), "{e}");
/// assert!(matches!(check_target(&dir).unwrap_err().kind(), ErrorKind::IsDirectory));
/// ```
pub fn check_target(path: impl AsRef<Path>) -> Result<(), MeshFileError> {
    let path = path.as_ref();
    let fail = |kind| Err(MeshFileError::new(None, kind).with_path(path));
    if path.file_name().is_none() || path.is_dir() {
        return fail(ErrorKind::IsDirectory);
    }
    let dir = directory(path);
    match fs::metadata(dir) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(_) => fail(ErrorKind::NotADirectory {
            dir: dir.to_path_buf(),
        }),
        Err(e) => {
            let is_file = |a: &&Path| fs::metadata(a).is_ok_and(|m| !m.is_dir());
            match (dir.ancestors().skip(1).find(is_file), e.kind()) {
                (Some(file), _) => fail(ErrorKind::NotADirectory {
                    dir: file.to_path_buf(),
                }),
                (None, io::ErrorKind::NotFound) => fail(ErrorKind::MissingDirectory {
                    dir: dir.to_path_buf(),
                }),
                (None, _) => fail(ErrorKind::Io(e)),
            }
        }
    }
}

/// The directory a file at `path` goes in (`.` for a bare file name).
fn directory(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// The first half of [`write_atomic`]: the complete, synced contents in a temporary file,
/// not yet in place. [`PendingFile::commit`] puts it in place; dropping it leaves the
/// target as it was. A command does what may still fail (printing its report) in between.
///
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-pending-{}.txt", std::process::id()));
/// let pending = zipmesh::io::prepare_atomic(&path, |w| w.write_all(b"new")).unwrap();
/// assert!(!path.exists());
/// drop(pending);
/// assert!(!path.exists());
/// zipmesh::io::prepare_atomic(&path, |w| w.write_all(b"new")).unwrap().commit().unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"new");
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn prepare_atomic<F>(path: impl AsRef<Path>, fill: F) -> Result<PendingFile, MeshFileError>
where
    F: FnOnce(&mut BufWriter<fs::File>) -> io::Result<()>,
{
    let path = path.as_ref();
    check_target(path)?;
    let err = |e| MeshFileError::io(path, e);
    let name = path
        .file_name()
        .ok_or_else(|| err(io::Error::new(io::ErrorKind::InvalidInput, "no file name")))?;
    let dir = directory(path);
    let temp = dir.join(temp_name(name));
    let (file, named) = match unnamed::create(dir, &temp) {
        Some(file) => (file, false),
        None => (create_named(&temp).map_err(err)?, true),
    };
    let mut pending = PendingFile {
        target: path.to_path_buf(),
        temp,
        named,
        file: None,
    };
    let mut w = BufWriter::with_capacity(1 << 16, file);
    fill(&mut w).map_err(err)?;
    let file = w.into_inner().map_err(|e| err(e.into_error()))?;
    file.sync_all().map_err(err)?;
    pending.file = Some(file);
    Ok(pending)
}

/// Where an atomic write to `path` puts its temporary file while it has a name: in the same
/// directory, `.zipmesh-<16 hex digits>.tmp`, the same for every write to `path`. The next
/// write to `path` removes a file left there by a killed process.
///
/// ```
/// let t = zipmesh::io::temporary_path("out/mesh.obj");
/// assert_eq!(t.parent(), Some(std::path::Path::new("out")));
/// assert_eq!(t.file_name().unwrap().len(), 29);
/// assert_eq!(t, zipmesh::io::temporary_path("out/mesh.obj"));
/// ```
pub fn temporary_path(path: impl AsRef<Path>) -> PathBuf {
    let path = path.as_ref();
    let name = path.file_name().unwrap_or_default();
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.join(temp_name(name)),
        _ => PathBuf::from(temp_name(name)),
    }
}

/// The temporary's name for a target named `name`: fixed per target and short.
fn temp_name(name: &OsStr) -> alloc::string::String {
    let hash = xxhash_rust::xxh3::xxh3_64(name.as_encoded_bytes());
    format!(".zipmesh-{hash:016x}.tmp")
}

/// Creates the named temporary `temp`, first removing one a killed run left.
fn create_named(temp: &Path) -> io::Result<fs::File> {
    let mut live = live();
    if live.ending {
        return Err(ending_error());
    }
    remove_stale(temp)?;
    let file = fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(temp)?;
    live.paths.push(temp.to_path_buf());
    Ok(file)
}

fn remove_stale(temp: &Path) -> io::Result<()> {
    match fs::remove_file(temp) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

/// Complete contents waiting to replace their target (see [`prepare_atomic`]).
///
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join(format!("zipmesh-doc-pending2-{}.txt", std::process::id()));
/// let pending = zipmesh::io::prepare_atomic(&path, |w| w.write_all(b"x")).unwrap();
/// assert_eq!(pending.target(), path.as_path());
/// pending.commit().unwrap();
/// std::fs::remove_file(&path).unwrap();
/// ```
#[derive(Debug)]
pub struct PendingFile {
    target: PathBuf,
    /// The temporary's name: where it is written when `named`, else where it is linked.
    temp: PathBuf,
    named: bool,
    file: Option<fs::File>,
}

impl PendingFile {
    /// The file this will replace.
    ///
    /// ```
    /// let p = zipmesh::io::prepare_atomic(std::env::temp_dir().join("zipmesh-doc-t.txt"), |_| Ok(())).unwrap();
    /// assert!(p.target().ends_with("zipmesh-doc-t.txt"));
    /// ```
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Puts the contents in place: renames the temporary onto the target. On failure the
    /// target is as it was and no temporary is left.
    ///
    /// ```
    /// let path = std::env::temp_dir().join(format!("zipmesh-doc-commit-{}.txt", std::process::id()));
    /// zipmesh::io::prepare_atomic(&path, |_| Ok(())).unwrap().commit().unwrap();
    /// assert_eq!(std::fs::read(&path).unwrap(), b"");
    /// std::fs::remove_file(&path).unwrap();
    /// ```
    pub fn commit(mut self) -> Result<(), MeshFileError> {
        let file = self.file.take();
        let mut live = live();
        let result = match (&file, self.named) {
            _ if live.ending => Err(ending_error()),
            (_, true) => fs::rename(&self.temp, &self.target),
            (Some(file), false) => link_and_rename(file, &self.temp, &self.target),
            (None, false) => Err(io::Error::other("nothing was written")),
        };
        if result.is_err() {
            let _ = remove_stale(&self.temp);
        }
        live.paths.retain(|p| *p != self.temp);
        self.named = false;
        result.map_err(|e| MeshFileError::io(&self.target, e))
    }
}

/// Gives the unnamed `file` the name `temp`, then renames that onto `target` (a link
/// cannot replace an existing file). The caller holds the lock of the live temporaries.
fn link_and_rename(file: &fs::File, temp: &Path, target: &Path) -> io::Result<()> {
    remove_stale(temp)?;
    unnamed::link(file, temp)?;
    fs::rename(temp, target)
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if self.named {
            let mut live = live();
            let _ = fs::remove_file(&self.temp);
            live.paths.retain(|p| *p != self.temp);
        }
    }
}

#[cfg(target_os = "linux")]
mod unnamed {
    use std::fs;
    use std::os::fd::AsRawFd;
    use std::path::Path;

    /// An unnamed file in `dir` (`O_TMPFILE`) that [`link`] can name later, or `None` where
    /// the file system cannot make one. A stale `temp` of a killed run is removed first.
    pub(super) fn create(dir: &Path, temp: &Path) -> Option<fs::File> {
        use rustix::fs::{openat, Mode, OFlags, CWD};
        let flags = OFlags::WRONLY | OFlags::TMPFILE | OFlags::CLOEXEC;
        let fd = openat(CWD, dir, flags, Mode::from_raw_mode(0o666)).ok()?;
        let file = fs::File::from(fd);
        // Naming it goes through /proc; without /proc, write under a name instead.
        fs::metadata(proc_path(&file)).ok()?;
        super::remove_stale(temp).ok()?;
        Some(file)
    }

    /// Links the unnamed `file` into its directory as `temp`.
    pub(super) fn link(file: &fs::File, temp: &Path) -> std::io::Result<()> {
        use rustix::fs::{linkat, AtFlags, CWD};
        linkat(CWD, proc_path(file), CWD, temp, AtFlags::SYMLINK_FOLLOW)?;
        Ok(())
    }

    fn proc_path(file: &fs::File) -> alloc::string::String {
        alloc::format!("/proc/self/fd/{}", file.as_raw_fd())
    }
}

#[cfg(not(target_os = "linux"))]
mod unnamed {
    use std::fs;
    use std::path::Path;

    /// No unnamed files here: the temporary is written under its name.
    pub(super) fn create(_dir: &Path, _temp: &Path) -> Option<fs::File> {
        None
    }

    pub(super) fn link(_file: &fs::File, _temp: &Path) -> std::io::Result<()> {
        Err(std::io::Error::other("no unnamed files on this system"))
    }
}
