//! Writing files so that a failure never destroys the previous version.

use std::io::{BufWriter, Write};
use std::path::Path;

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
pub fn atomic_write<E: From<std::io::Error>>(
    path: &Path,
    durability: Durability,
    fill: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let tmp = tempfile::Builder::new()
        .prefix(".pssurf-")
        .suffix(".tmp")
        .tempfile_in(dir)?;
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
    if durability == Durability::Durable {
        tmp.as_file().sync_all()?;
    }
    tmp.persist(path).map_err(|e| E::from(e.error))?;
    Ok(())
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
}
