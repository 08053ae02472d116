//! Hole specifications: the boundary curves of a hole with the normals of the surrounding
//! surfaces, `kind: "hole"` (`docs/holes.md`).
//!
//! ```json
//! {"format": "pssurf", "version": 1, "kind": "hole", "curves": [
//!   {"degree": 2, "points": [[0,0,0], [1,0,0], [2,0,0]], "normal": [0, 0, 1]},
//!   {"degree": 1, "knots": [0,0,1,1], "points": [[2,0,0], [1,2,0]],
//!    "normals": {"degree": 1, "points": [[0,0,1], [0,0.2,1]]}},
//!   …]}
//! ```
//!
//! Each curve is a curve section of a curve file (Bézier without knots, B-spline or NURBS
//! with them) and has either one `normal` for its whole length or `normals`, a curve section
//! whose points are normal vectors, on the same parameter interval.

use nalgebra::Vector3;
use serde::Deserialize;

use super::curve_file::{CurveSection, curve_from_section};
use super::format::{FormatError, check_header, invalid, syntax};
use crate::hole::{NormalField, NurbsBoundary};

/// The kind name of hole specifications.
pub const HOLE_KIND: &str = "hole";

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HoleCurve {
    degree: usize,
    #[serde(default)]
    knots: Option<Vec<f64>>,
    points: Vec<[f64; 3]>,
    #[serde(default)]
    weights: Option<Vec<f64>>,
    #[serde(default)]
    normal: Option<[f64; 3]>,
    #[serde(default)]
    normals: Option<CurveSection>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HoleFileV1 {
    #[allow(dead_code)] // checked by check_header
    format: String,
    #[allow(dead_code)] // checked by check_header
    version: u64,
    kind: String,
    curves: Vec<HoleCurve>,
}

/// The most curves a specification may list (a hole has 2 to 6).
const MAX_CURVES: usize = 64;

/// Reads the boundary curves of a hole specification, validating every curve.
pub fn hole_from_json(text: &str) -> Result<Vec<NurbsBoundary>, FormatError> {
    check_header(text)?;
    let file: HoleFileV1 = serde_json::from_str(text).map_err(syntax)?;
    if file.kind != HOLE_KIND {
        return Err(invalid(
            "kind",
            format!("\"{}\" is not a hole specification", file.kind),
        ));
    }
    if file.curves.len() > MAX_CURVES {
        return Err(invalid(
            "curves",
            format!("{} curves, at most 6 bound a hole", file.curves.len()),
        ));
    }
    file.curves
        .into_iter()
        .enumerate()
        .map(|(k, c)| {
            let at = format!("curves[{k}]");
            let curve = curve_from_section(
                CurveSection {
                    degree: c.degree,
                    knots: c.knots,
                    points: c.points,
                    weights: c.weights,
                },
                &at,
            )?;
            let normals = match (c.normal, c.normals) {
                (Some(n), None) => {
                    let n = Vector3::from(n);
                    if !(n.iter().all(|x| x.is_finite()) && n.norm() > 0.0) {
                        return Err(invalid(
                            format!("{at}.normal"),
                            "a normal must be a finite non-zero vector",
                        ));
                    }
                    NormalField::Constant(n)
                }
                (None, Some(s)) => {
                    NormalField::Curve(curve_from_section(s, &format!("{at}.normals"))?)
                }
                _ => {
                    return Err(invalid(
                        at,
                        "give either \"normal\" (one vector) or \"normals\" (a curve of vectors)",
                    ));
                }
            };
            Ok(NurbsBoundary { curve, normals })
        })
        .collect()
}
