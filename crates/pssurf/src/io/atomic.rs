//! Writing files so that a failure never destroys the previous version.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporary files being written right now, so that a program interrupted by a signal
/// can remove them ([`remove_pending_temp_files`]).
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Keeps a temporary file's path in [`PENDING`] while it lives.
struct Pending(PathBuf);

impl Pending {
    fn new(path: &Path) -> Pending {
        if let Ok(mut p) = PENDING.lock() {
            p.push(path.to_path_buf());
        }
        Pending(path.to_path_buf())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        if let Ok(mut p) = PENDING.lock()
            && let Some(k) = p.iter().position(|q| *q == self.0)
        {
            p.swap_remove(k);
        }
    }
}

/// Removes the temporary files of writes still in progress; returns how many. For a signal
/// handler (SIGINT, SIGTERM) that is about to end the program: the files being replaced are
/// untouched, and no `.pssurf-*.tmp` file is left behind.
pub fn remove_pending_temp_files() -> usize {
    let Ok(mut p) = PENDING.lock() else {
        return 0;
    };
    let removed = p.iter().filter(|q| std::fs::remove_file(q).is_ok()).count();
    p.clear();
    removed
}

/// The cause of a failed read or write in a few words for a message, without the OS error
/// number: `no space left on the device`, `the folder does not exist`.
pub fn io_cause(e: &std::io::Error) -> String {
    match e.raw_os_error() {
        Some(28) => "no space left on the device".into(),
        Some(13) => "permission denied".into(),
        Some(30) => "the file system is read-only".into(),
        Some(122) => "the disk quota is exceeded".into(),
        Some(2) => "no such file or folder".into(),
        Some(20) => "a part of the path is not a folder".into(),
        Some(21) => "it is a folder".into(),
        _ => {
            let text = e.to_string();
            match text.find(" (os error") {
                Some(k) => text[..k].to_string(),
                None => text,
            }
        }
    }
}

/// How much a write must survive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Durability {
    /// Replace atomically (temporary file + rename): a failed write never leaves a partial
    /// file or destroys the previous one. For regenerable outputs (tables, meshes, images).
    Atomic,
    /// Atomic, and the data is flushed to the disk (fsync) before the rename, so that it
    /// also survives a power failure. For surface files, the user's source of truth.
    Durable,
}

/// Writes `path` through `fill` into a temporary file in the same directory, then renames it
/// over `path`. If `fill` or any write fails, `path` is left untouched and the temporary file
/// is removed.
///
/// What is at `path` is never replaced by something else: a symbolic link keeps pointing
/// where it did (the file it points to is replaced atomically; a dangling link is an
/// error), and a special file (a device such as `/dev/null` or `/dev/stdout`, a FIFO, a
/// socket) is written into directly, as a stream. A directory is an error.
pub fn atomic_write<E: From<std::io::Error>>(
    path: &Path,
    durability: Durability,
    fill: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let path = match target(path)? {
        Target::Stream => return write_stream(path, fill),
        Target::File(p) => p,
    };
    let path = path.as_path();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let tmp = tempfile::Builder::new()
        .prefix(".pssurf-")
        .suffix(".tmp")
        .tempfile_in(dir)?;
    let _pending = Pending::new(tmp.path());
    // Temporary files are private (0600); the result should have the permissions of the
    // file it replaces, or the usual 0644 for a new file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(path)
            .map(|m| m.permissions().mode() & 0o7777)
            .unwrap_or(0o644);
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))?;
    }
    {
        let mut w = BufWriter::with_capacity(1 << 20, tmp.as_file());
        fill(&mut w)?;
        w.flush()?;
    }
    // A full disk may show only when the data is flushed to it (delayed allocation): sync
    // before the rename in both modes, so that such a failure keeps the old file.
    match durability {
        Durability::Atomic => tmp.as_file().sync_data()?,
        Durability::Durable => tmp.as_file().sync_all()?,
    }
    tmp.persist(path).map_err(|e| E::from(e.error))?;
    Ok(())
}

/// Where a write to a path goes.
enum Target {
    /// Replace this regular file (or create it) atomically.
    File(PathBuf),
    /// Write into the existing special file as a stream.
    Stream,
}

/// Resolves what is at `path` (module docs of [`atomic_write`]).
fn target(path: &Path) -> std::io::Result<Target> {
    use std::io::{Error, ErrorKind};
    // `out.json/` names a directory, whatever is there (the system would say "Not a
    // directory" of a file, or create nothing useful).
    if path.as_os_str().to_string_lossy().ends_with('/') {
        return Err(Error::new(
            ErrorKind::IsADirectory,
            if path.is_dir() {
                "is a directory".to_string()
            } else {
                "ends with `/`, so it names a directory; give a file name".to_string()
            },
        ));
    }
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        // Nothing there yet: the directory must exist.
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
            && !dir.is_dir()
        {
            let what = if dir.exists() {
                format!("{} is not a directory", dir.display())
            } else {
                format!("the directory {} does not exist", dir.display())
            };
            return Err(Error::new(ErrorKind::NotFound, what));
        }
        return Ok(Target::File(path.to_path_buf()));
    };
    if meta.file_type().is_symlink() {
        return match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Err(Error::new(ErrorKind::IsADirectory, "is a directory")),
            Ok(m) if m.is_file() => Ok(Target::File(std::fs::canonicalize(path)?)),
            // A link to a device or a pipe (/dev/stdout): write into it.
            Ok(_) => Ok(Target::Stream),
            // A link to a file not there yet: create the file it names.
            Err(_) => link_end(path).map(Target::File),
        };
    }
    if meta.is_dir() {
        return Err(Error::new(ErrorKind::IsADirectory, "is a directory"));
    }
    if meta.is_file() {
        Ok(Target::File(path.to_path_buf()))
    } else {
        Ok(Target::Stream)
    }
}

/// The path that a chain of symbolic links ends at, when that end does not exist yet (its
/// directory must).
fn link_end(path: &Path) -> std::io::Result<PathBuf> {
    use std::io::{Error, ErrorKind};
    let mut at = path.to_path_buf();
    for _ in 0..40 {
        let next = std::fs::read_link(&at)?;
        at = match at.parent() {
            Some(dir) if next.is_relative() => dir.join(next),
            _ => next,
        };
        if std::fs::symlink_metadata(&at).is_err() {
            return match at.parent() {
                Some(dir) if dir.as_os_str().is_empty() || dir.is_dir() => Ok(at),
                _ => Err(Error::new(
                    ErrorKind::NotFound,
                    format!(
                        "is a symbolic link to {}, in a directory that does not exist",
                        at.display()
                    ),
                )),
            };
        }
    }
    Err(Error::new(
        ErrorKind::InvalidInput,
        "is a loop of symbolic links",
    ))
}

/// Writes into an existing special file (device, FIFO, socket) without replacing it.
fn write_stream<E: From<std::io::Error>>(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let file = std::fs::OpenOptions::new().write(true).open(path)?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    fill(&mut w)?;
    w.flush()?;
    // Errors a device reports only at the end (a full disk behind a FIFO reader, NFS).
    w.get_ref().sync_data().or_else(ignore_unsupported)?;
    Ok(())
}

/// `fsync` on a pipe, terminal or character device fails with EINVAL (nothing to sync):
/// not an error.
fn ignore_unsupported(e: std::io::Error) -> std::io::Result<()> {
    if e.kind() == std::io::ErrorKind::InvalidInput || e.raw_os_error() == Some(22) {
        Ok(())
    } else {
        Err(e)
    }
}

/// Writes `bytes` to `path` atomically (see [`atomic_write`]).
pub fn atomic_write_bytes(
    path: &Path,
    durability: Durability,
    bytes: &[u8],
) -> std::io::Result<()> {
    atomic_write(path, durability, |w| w.write_all(bytes))
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::PermissionsExt;

    #[test]
    fn new_files_are_readable_and_replaced_files_keep_their_permissions() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        atomic_write_bytes(&path, Durability::Atomic, b"one").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o7777;
        assert_eq!(mode(&path), 0o644);
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o640)).unwrap();
        atomic_write_bytes(&path, Durability::Durable, b"two").unwrap();
        assert_eq!(mode(&path), 0o640);
        assert_eq!(std::fs::read(&path).unwrap(), b"two");
    }

    #[test]
    fn symbolic_links_and_special_files_are_never_replaced() {
        let dir = tempfile::tempdir().unwrap();
        // A link to a file: the link stays, the file it points to gets the content.
        let file = dir.path().join("real.txt");
        std::fs::write(&file, b"old").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(&file, &link).unwrap();
        atomic_write_bytes(&link, Durability::Atomic, b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&file).unwrap(), b"new");
        // A link to a file not there yet: the file is created, the link kept. A link into a
        // missing directory, or a loop: an error, and the link is left alone.
        let dangling = dir.path().join("dangling.txt");
        std::os::unix::fs::symlink("created.txt", &dangling).unwrap();
        atomic_write_bytes(&dangling, Durability::Atomic, b"x").unwrap();
        assert_eq!(std::fs::read(dir.path().join("created.txt")).unwrap(), b"x");
        assert!(
            std::fs::symlink_metadata(&dangling)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        let nowhere = dir.path().join("nowhere.txt");
        std::os::unix::fs::symlink(dir.path().join("no/dir.txt"), &nowhere).unwrap();
        let e = atomic_write_bytes(&nowhere, Durability::Atomic, b"x").unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        let looped = dir.path().join("loop.txt");
        std::os::unix::fs::symlink("loop.txt", &looped).unwrap();
        let e = atomic_write_bytes(&looped, Durability::Atomic, b"x").unwrap_err();
        assert!(e.to_string().contains("loop"), "{e}");
        // A FIFO is written into, and is still a FIFO afterwards.
        use std::os::unix::fs::FileTypeExt;
        let fifo = dir.path().join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        let has_fifo = made.is_ok_and(|s| s.success());
        if has_fifo {
            let reader = {
                let fifo = fifo.clone();
                std::thread::spawn(move || std::fs::read(fifo).unwrap())
            };
            atomic_write_bytes(&fifo, Durability::Durable, b"through").unwrap();
            assert_eq!(reader.join().unwrap(), b"through");
            assert!(
                std::fs::symlink_metadata(&fifo)
                    .unwrap()
                    .file_type()
                    .is_fifo()
            );
        } else {
            eprintln!("skipped the FIFO case: mkfifo is not available");
        }
        // A directory and a missing directory: clear errors, nothing left behind.
        let e = atomic_write_bytes(dir.path(), Durability::Atomic, b"x").unwrap_err();
        assert!(e.to_string().contains("directory"), "{e}");
        let e = atomic_write_bytes(&dir.path().join("no/such.txt"), Durability::Atomic, b"x")
            .unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(
            left.len(),
            6 + usize::from(has_fifo),
            "real, link, dangling, created, nowhere, loop (, pipe): {left:?}"
        );
    }
}
