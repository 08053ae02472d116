//! Helpers for the commands that need a uniform (UPS) surface.

use std::path::Path;

use anyhow::{Result, bail};
use pssurf::surface::{Surface, UpsSurface};

use crate::budget::{Estimate, base_memory, count, mul};

/// The uniform form of a loaded surface, or an error explaining that the command needs one.
pub fn require<'a>(surface: &'a Surface, path: &Path, command: &str) -> Result<&'a UpsSurface> {
    match surface.uniform() {
        Some(u) => Ok(u),
        None => bail!(
            "{}: `pssurf {command}` needs a uniform (UPS) surface on a lattice polygon, and this file holds {} (create one with `pssurf new ups`)",
            path.display(),
            held(surface)
        ),
    }
}

/// What a file holds, for the message above: "a NURBS surface", "a functional PS surface on a
/// general triangulation", …
fn held(surface: &Surface) -> String {
    let kind = surface.kind();
    let article = |s: &str| match s.chars().next() {
        Some('a' | 'e' | 'i' | 'o' | 'u') => "an",
        _ => "a",
    };
    let what = if surface.ps_basis().is_some() {
        format!("{kind} surface on a general triangulation")
    } else {
        kind.to_string()
    };
    format!("{} {what}", article(&what))
}

/// What creating a UPS surface of `vertices` vertices on a block matrix of `slots` slots costs:
/// at most 1,500 bytes of memory per vertex while it is built and written (measured 900 for
/// `new ups`, 1,300 for `subdivide`) plus 3 per slot, and 300 bytes of file per vertex
/// (measured 248).
pub fn creation_estimate(what: String, vertices: u128, slots: u128) -> Estimate {
    let v = u64::try_from(vertices).unwrap_or(u64::MAX);
    let s = u64::try_from(slots).unwrap_or(u64::MAX);
    Estimate {
        what,
        makes: format!("{} vertices", count(v)),
        memory: base_memory()
            .saturating_add(mul(v, 1500))
            .saturating_add(mul(s, 3)),
        output: mul(v, 300),
    }
}
