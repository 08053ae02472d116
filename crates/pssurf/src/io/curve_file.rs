//! Curve files: one NURBS (or Bézier) space curve in the pssurf format, `kind: "curve"`
//! (`docs/format.md`). A Bézier curve is the same section without knots.

use std::path::Path;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::format::{
    CURVE_KIND, FORMAT_NAME, FileError, FormatError, check_header, invalid, read_text_limited,
    syntax,
};
use crate::nurbs::{NurbsCurve, NurbsError};

/// The `curve` section: a degree, control points, optional knots (absent: a Bézier curve on
/// [0, 1], degree = points − 1) and optional weights (a rational curve).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CurveSection {
    pub(crate) degree: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) knots: Option<Vec<f64>>,
    pub(crate) points: Vec<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) weights: Option<Vec<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurveFileV1 {
    format: String,
    version: u64,
    kind: String,
    curve: CurveSection,
}

/// Whether `text` is a pssurf file of kind "curve" (by its header only).
pub fn is_curve(text: &str) -> bool {
    #[derive(Deserialize)]
    struct Kind {
        format: Option<String>,
        kind: Option<serde_json::Value>,
    }
    serde_json::from_str::<Kind>(text).is_ok_and(|k| {
        k.format.as_deref() == Some(FORMAT_NAME)
            && k.kind.as_ref().and_then(|v| v.as_str()) == Some(CURVE_KIND)
    })
}

/// Reads a curve from the text of a curve file, validating everything.
pub fn curve_from_json(text: &str) -> Result<NurbsCurve, FormatError> {
    check_header(text)?;
    let file: CurveFileV1 = serde_json::from_str(text).map_err(syntax)?;
    if file.kind != CURVE_KIND {
        return Err(invalid("kind", format!("\"{}\" is not a curve", file.kind)));
    }
    curve_from_section(file.curve, "curve")
}

/// The curve of a `curve` section found at `at` (e.g. `curves[2].normals`), validated.
pub(crate) fn curve_from_section(c: CurveSection, at: &str) -> Result<NurbsCurve, FormatError> {
    let points: Vec<Vector3<f64>> = c
        .points
        .iter()
        .map(|p| Vector3::new(p[0], p[1], p[2]))
        .collect();
    let knots = match c.knots {
        Some(k) => k,
        None => {
            if points.len() != c.degree + 1 {
                return Err(invalid(
                    format!("{at}.points"),
                    format!(
                        "a Bézier curve of degree {} has {} points, not {} (or give knots)",
                        c.degree,
                        c.degree + 1,
                        points.len()
                    ),
                ));
            }
            let mut k = vec![0.0; c.degree + 1];
            k.extend(std::iter::repeat_n(1.0, c.degree + 1));
            k
        }
    };
    NurbsCurve::try_new(c.degree, knots, points, c.weights).map_err(|e| {
        let place = match &e {
            NurbsError::Knots { .. } => format!("{at}.knots"),
            NurbsError::Count { what, .. } if *what == "weights" => format!("{at}.weights"),
            NurbsError::Count { .. } => format!("{at}.points"),
            NurbsError::Point(i) => format!("{at}.points[{i}]"),
            NurbsError::Weight(i, _) => format!("{at}.weights[{i}]"),
        };
        invalid(place, e)
    })
}

/// The text of a curve file holding `c` (knots always written).
pub fn curve_to_json(c: &NurbsCurve) -> String {
    let file = CurveFileV1 {
        format: FORMAT_NAME.to_string(),
        version: super::FORMAT_VERSION as u64,
        kind: CURVE_KIND.to_string(),
        curve: CurveSection {
            degree: c.knot_vector().degree(),
            knots: Some(c.knot_vector().knots().to_vec()),
            points: c.points().iter().map(|p| [p.x, p.y, p.z]).collect(),
            weights: c.is_rational().then(|| c.weights().to_vec()),
        },
    };
    serde_json::to_string(&file).expect("finite numbers serialise")
}

/// Reads and validates a curve file of at most `max_bytes` bytes.
pub fn load_curve_limited(path: &Path, max_bytes: u64) -> Result<NurbsCurve, FileError> {
    let text = read_text_limited(path, max_bytes)?;
    curve_from_json(&text).map_err(|cause| FileError::Format {
        path: path.to_path_buf(),
        cause,
    })
}

/// Writes a curve file atomically and durably.
pub fn save_curve(c: &NurbsCurve, path: &Path) -> Result<(), FileError> {
    let text = curve_to_json(c);
    super::atomic_write_bytes(path, super::Durability::Durable, text.as_bytes()).map_err(|cause| {
        FileError::Io {
            path: path.to_path_buf(),
            cause,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle_quarter() -> NurbsCurve {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        NurbsCurve::try_new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![Vector3::x(), Vector3::new(1.0, 1.0, 0.0), Vector3::y()],
            Some(vec![1.0, s, 1.0]),
        )
        .unwrap()
    }

    #[test]
    fn a_curve_reads_back_exactly_and_a_bezier_curve_needs_no_knots() {
        let c = circle_quarter();
        let text = curve_to_json(&c);
        assert!(is_curve(&text));
        assert_eq!(curve_from_json(&text).unwrap(), c);
        let bezier = r#"{"format":"pssurf","version":1,"kind":"curve",
            "curve":{"degree":2,"points":[[1,0,0],[1,1,0],[0,1,0]],"weights":[1,0.7071067811865476,1]}}"#;
        let b = curve_from_json(bezier).unwrap();
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            assert!((b.point(t).unwrap().norm() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn bad_curve_files_name_the_field() {
        let cases = [
            (
                r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":2,"points":[[0,0,0],[1,0,0]]}}"#,
                "curve.points",
            ),
            (
                r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":1,"knots":[0,1,0],"points":[[0,0,0],[1,0,0]]}}"#,
                "curve.knots",
            ),
            (
                r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":1,"points":[[0,0,0],[1,0,0]],"weights":[1,-1]}}"#,
                "curve.weights[1]",
            ),
            (
                r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":1,"points":[[0,0,0],[1e300,0,0]]}}"#,
                "curve.points[1]",
            ),
            (
                r#"{"format":"pssurf","version":1,"kind":"nurbs","curve":{"degree":1,"points":[[0,0,0],[1,0,0]]}}"#,
                "kind",
            ),
            (
                r#"{"format":"pssurf","version":2,"kind":"curve","curve":{}}"#,
                "version 2",
            ),
        ];
        for (text, want) in cases {
            let e = curve_from_json(text).unwrap_err().to_string();
            assert!(e.contains(want), "{text}: {e}");
        }
        // A surface reader names a curve file as such.
        let e = super::super::from_json_str(&curve_to_json(&circle_quarter()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("a curve file"), "{e}");
    }
}
