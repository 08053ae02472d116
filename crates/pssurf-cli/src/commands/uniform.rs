//! Helpers for the commands that need a uniform (UPS) surface.

use std::path::Path;

use anyhow::{Result, bail};
use pssurf::surface::{Surface, UpsSurface};

/// The uniform form of a loaded surface, or an error explaining that the command needs one.
pub fn require<'a>(surface: &'a Surface, path: &Path, command: &str) -> Result<&'a UpsSurface> {
    match surface.uniform() {
        Some(u) => Ok(u),
        None => bail!(
            "{}: `pssurf {command}` needs a uniform (UPS) surface on a lattice polygon, and this file holds a PS surface on a general triangulation (create one with `pssurf new ups`)",
            path.display()
        ),
    }
}
