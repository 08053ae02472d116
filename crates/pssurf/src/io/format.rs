//! The pssurf surface file format, version 1 (described in `docs/format.md`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use nalgebra::{Point2, Vector3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::geometry::Triangle2;
use crate::ps::net::Weighted;
use crate::ps::{Nurps, PsBasis, PsError, PsRefinement, PsSpline, PsTriangleChoice, SplitRule};
use crate::surface::{PsSurface, Surface, UpsSurface};
use crate::triangulation::{Triangulation, TriangulationError};
use crate::ups::{Lattice, LatticePolygon, Ups, UpsGrid, fixed_ps_triangle};

/// The format version this build writes and reads.
pub const FORMAT_VERSION: u32 = 1;

/// The format's name, the value of the `format` field.
const FORMAT_NAME: &str = "pssurf";

/// What is wrong with a file's contents; `at` is a JSON path such as `domain.triangles[5]`.
#[derive(Debug, Error, PartialEq)]
pub enum FormatError {
    /// Not valid JSON, or a field of the wrong shape (with the position serde_json found).
    #[error("line {line}, column {column}: {message}")]
    Syntax {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What serde_json reported.
        message: String,
    },
    /// The `format` field is missing or is not "pssurf".
    #[error("not a pssurf surface file (the field \"format\" must be \"pssurf\")")]
    NotPssurf,
    /// A version this build cannot read.
    #[error("format version {0} is not supported (this build reads version {FORMAT_VERSION})")]
    UnsupportedVersion(u64),
    /// The contents are well-formed but invalid.
    #[error("{at}: {message}")]
    Invalid {
        /// Where, as a JSON path.
        at: String,
        /// What is wrong.
        message: String,
    },
}

/// A file could not be read or written.
#[derive(Debug, Error)]
pub enum FileError {
    /// The operating system refused.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The contents are invalid.
    #[error("{}: {source}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: FormatError,
    },
}

#[derive(Deserialize)]
struct Header {
    format: Option<String>,
    version: Option<u64>,
}

#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(rename_all = "lowercase")]
enum Kind {
    Functional,
    Parametric,
    Nurps,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Domain {
    vertices: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    split: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    split_points: Option<Vec<[f64; 2]>>,
}

/// The uniform structure of a UPS surface: its lattice and polygon. The vertices must be the
/// polygon's lattice points in block-matrix order (by rows of constant j, then i).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Uniform {
    base: f64,
    origin: [f64; 2],
    polygon: Vec<[i64; 2]>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileV1 {
    format: String,
    version: u64,
    kind: Kind,
    domain: Domain,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ps_triangles: Option<Vec<[[f64; 2]; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    control: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    control_points: Option<Vec<[[f64; 3]; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    uniform: Option<Uniform>,
}

fn syntax(e: serde_json::Error) -> FormatError {
    FormatError::Syntax {
        line: e.line(),
        column: e.column(),
        message: strip_position(&e.to_string()),
    }
}

/// serde_json appends " at line L column C"; the position is reported separately.
fn strip_position(s: &str) -> String {
    match s.rfind(" at line ") {
        Some(k) => s[..k].to_string(),
        None => s.to_string(),
    }
}

fn invalid(at: impl Into<String>, message: impl std::fmt::Display) -> FormatError {
    FormatError::Invalid {
        at: at.into(),
        message: message.to_string(),
    }
}

/// Reads a surface from the text of a file, validating everything; the error names the
/// first problem and where it is.
pub fn from_json_str(text: &str) -> Result<Surface, FormatError> {
    let header: Header = serde_json::from_str(text).map_err(syntax)?;
    if header.format.as_deref() != Some(FORMAT_NAME) {
        return Err(FormatError::NotPssurf);
    }
    match header.version {
        Some(v) if v == FORMAT_VERSION as u64 => {}
        Some(v) => return Err(FormatError::UnsupportedVersion(v)),
        None => return Err(invalid("version", "missing field `version`")),
    }
    let file: FileV1 = serde_json::from_str(text).map_err(syntax)?;
    if file.uniform.is_some() {
        return build_uniform(file).map(Surface::from);
    }
    build(file).map(Surface::from)
}

fn build(file: FileV1) -> Result<PsSurface, FormatError> {
    let n = file.domain.vertices.len();
    for (i, v) in file.domain.vertices.iter().enumerate() {
        if !v.iter().all(|x| x.is_finite()) {
            return Err(invalid(
                format!("domain.vertices[{i}]"),
                "coordinates must be finite",
            ));
        }
    }
    let vertices: Vec<Point2<f64>> = file
        .domain
        .vertices
        .iter()
        .map(|v| Point2::new(v[0], v[1]))
        .collect();
    let tri = Triangulation::try_new(vertices, file.domain.triangles.clone())
        .map_err(triangulation_error)?;
    let refinement = match (&file.domain.split, &file.domain.split_points) {
        (Some(_), Some(_)) => {
            return Err(invalid(
                "domain",
                "give either `split` or `split_points`, not both",
            ));
        }
        (_, Some(points)) => {
            let z = points.iter().map(|p| Point2::new(p[0], p[1])).collect();
            PsRefinement::with_points(&tri, z)
        }
        (rule, None) => {
            let rule = match rule.as_deref() {
                None | Some("incenter") => SplitRule::Incenter,
                Some("centroid") => SplitRule::Centroid,
                Some(other) => {
                    return Err(invalid(
                        "domain.split",
                        format!("unknown split rule `{other}`; use \"incenter\" or \"centroid\""),
                    ));
                }
            };
            PsRefinement::new(&tri, rule)
        }
    }
    .map_err(ps_error)?;
    let choice = match &file.ps_triangles {
        None => PsTriangleChoice::Optimal,
        Some(list) => PsTriangleChoice::Given(
            list.iter()
                .map(|t| {
                    Triangle2::new(
                        Point2::new(t[0][0], t[0][1]),
                        Point2::new(t[1][0], t[1][1]),
                        Point2::new(t[2][0], t[2][1]),
                    )
                })
                .collect(),
        ),
    };
    let basis = Arc::new(PsBasis::with_refinement(tri, refinement, &choice).map_err(ps_error)?);
    let only = |present: bool, field: &str, kinds: &str| {
        if present {
            Err(invalid(
                field,
                format!("only {kinds} surfaces have `{field}`"),
            ))
        } else {
            Ok(())
        }
    };
    let need = |field: &str| {
        invalid(
            field,
            format!("missing field `{field}` for a {:?} surface", file.kind).to_lowercase(),
        )
    };
    let surface = match file.kind {
        Kind::Functional => {
            only(
                file.control_points.is_some(),
                "control_points",
                "parametric and nurps",
            )?;
            only(file.weights.is_some(), "weights", "nurps")?;
            let c = file.control.ok_or_else(|| need("control"))?;
            check_count("control", c.len(), n)?;
            PsSurface::Functional(PsSpline::new(basis, c).map_err(ps_error)?)
        }
        Kind::Parametric | Kind::Nurps => {
            only(file.control.is_some(), "control", "functional")?;
            let c = file.control_points.ok_or_else(|| need("control_points"))?;
            check_count("control_points", c.len(), n)?;
            let pts: Vec<[Vector3<f64>; 3]> = c
                .iter()
                .map(|t| t.map(|p| Vector3::new(p[0], p[1], p[2])))
                .collect();
            if file.kind == Kind::Parametric {
                only(file.weights.is_some(), "weights", "nurps")?;
                PsSurface::Parametric(PsSpline::new(basis, pts).map_err(ps_error)?)
            } else {
                let w = file.weights.ok_or_else(|| need("weights"))?;
                check_count("weights", w.len(), n)?;
                PsSurface::Rational(Nurps::new(basis, pts, w).map_err(ps_error)?)
            }
        }
    };
    Ok(surface)
}

/// Rebuilds a UPS surface, checking that the general description is exactly its uniform
/// triangulation with the fixed PS-triangles.
fn build_uniform(file: FileV1) -> Result<UpsSurface, FormatError> {
    let u = file.uniform.as_ref().expect("checked by the caller");
    if !(u.base > 0.0 && u.base.is_finite() && u.origin.iter().all(|x| x.is_finite())) {
        return Err(invalid(
            "uniform.base",
            "the base must be a positive finite number and the origin finite",
        ));
    }
    let polygon =
        LatticePolygon::new(u.polygon.clone()).map_err(|e| invalid("uniform.polygon", e))?;
    let lattice = Lattice {
        base: u.base,
        origin: Point2::new(u.origin[0], u.origin[1]),
    };
    let grid = UpsGrid::new(lattice, polygon).map_err(|e| invalid("uniform", e))?;
    let slots = grid.real_slots();
    let n = slots.len();
    check_count("domain.vertices", file.domain.vertices.len(), n)?;
    let tol = 1e-9 * u.base;
    for (k, (&s, v)) in slots.iter().zip(&file.domain.vertices).enumerate() {
        let lp = grid.lattice_point(s);
        let p = lattice.point(lp);
        if !((p.x - v[0]).abs() <= tol && (p.y - v[1]).abs() <= tol) {
            return Err(invalid(
                format!("domain.vertices[{k}]"),
                format!(
                    "expected the lattice point ({}, {}) at ({}, {}) of the uniform triangulation",
                    lp[0], lp[1], p.x, p.y
                ),
            ));
        }
    }
    let mut index = vec![usize::MAX; grid.slots()];
    for (k, &s) in slots.iter().enumerate() {
        index[s] = k;
    }
    let key = |t: [usize; 3]| {
        let mut t = t;
        t.sort_unstable();
        t
    };
    let mut expected: Vec<[usize; 3]> = grid
        .triangle_slots()
        .into_iter()
        .map(|t| key(t.map(|s| index[s])))
        .collect();
    let mut given: Vec<[usize; 3]> = file.domain.triangles.iter().map(|&t| key(t)).collect();
    expected.sort_unstable();
    given.sort_unstable();
    if expected != given {
        return Err(invalid(
            "domain.triangles",
            "not the triangles of the uniform triangulation of the polygon",
        ));
    }
    if file.domain.split_points.is_some()
        || file
            .domain
            .split
            .as_deref()
            .is_some_and(|s| s != "incenter")
    {
        return Err(invalid(
            "domain.split",
            "uniform surfaces use the incentre split (the angle bisectors, Definition 4.3)",
        ));
    }
    if let Some(list) = &file.ps_triangles {
        check_count("ps_triangles", list.len(), n)?;
        for (k, (t, &s)) in list.iter().zip(&slots).enumerate() {
            let q = fixed_ps_triangle(&lattice, lattice.point(grid.lattice_point(s)));
            let same = (0..3)
                .all(|m| (q.v[m].x - t[m][0]).abs() <= tol && (q.v[m].y - t[m][1]).abs() <= tol);
            if !same {
                return Err(invalid(
                    format!("ps_triangles[{k}]"),
                    "uniform surfaces use the fixed PS-triangles t(6) (Property 4.1)",
                ));
            }
        }
    }
    let finite = |field: &str, vals: &mut dyn Iterator<Item = (usize, usize, bool)>| {
        for (i, j, ok) in vals {
            if !ok {
                return Err(invalid(format!("{field}[{i}][{j}]"), "not a finite number"));
            }
        }
        Ok(())
    };
    match file.kind {
        Kind::Functional => {
            let c = file
                .control
                .ok_or_else(|| invalid("control", "missing field `control`"))?;
            check_count("control", c.len(), n)?;
            finite(
                "control",
                &mut c
                    .iter()
                    .enumerate()
                    .flat_map(|(i, t)| (0..3).map(move |j| (i, j, t[j].is_finite()))),
            )?;
            Ok(UpsSurface::Functional(
                Ups::from_vertices(grid, c).map_err(|e| invalid("control", e))?,
            ))
        }
        Kind::Parametric | Kind::Nurps => {
            let c = file
                .control_points
                .ok_or_else(|| invalid("control_points", "missing field `control_points`"))?;
            check_count("control_points", c.len(), n)?;
            finite(
                "control_points",
                &mut c.iter().enumerate().flat_map(|(i, t)| {
                    (0..3).map(move |j| (i, j, t[j].iter().all(|x| x.is_finite())))
                }),
            )?;
            let pts: Vec<[Vector3<f64>; 3]> = c
                .iter()
                .map(|t| t.map(|p| Vector3::new(p[0], p[1], p[2])))
                .collect();
            if file.kind == Kind::Parametric {
                Ok(UpsSurface::Parametric(
                    Ups::from_vertices(grid, pts).map_err(|e| invalid("control_points", e))?,
                ))
            } else {
                let w = file
                    .weights
                    .ok_or_else(|| invalid("weights", "missing field `weights`"))?;
                check_count("weights", w.len(), n)?;
                Ok(UpsSurface::Rational(Ups::rational(grid, pts, w).map_err(
                    |e| match e {
                        crate::ups::UpsError::Ps(pe) => ps_error(pe),
                        e => invalid("weights", e),
                    },
                )?))
            }
        }
    }
}

fn check_count(field: &str, found: usize, n: usize) -> Result<(), FormatError> {
    if found == n {
        Ok(())
    } else {
        Err(invalid(
            field,
            format!("expected one entry per vertex ({n}), found {found}"),
        ))
    }
}

fn triangulation_error(e: TriangulationError) -> FormatError {
    use TriangulationError as E;
    let at = match &e {
        E::NonFiniteVertex(i) | E::UnusedVertex(i) => format!("domain.vertices[{i}]"),
        E::DuplicateVertex { second, .. } => format!("domain.vertices[{second}]"),
        E::NonManifoldVertex { vertex } => format!("domain.vertices[{vertex}]"),
        E::IndexOutOfRange { triangle, .. }
        | E::RepeatedVertex { triangle }
        | E::DegenerateTriangle { triangle }
        | E::InconsistentOrientation { triangle, .. }
        | E::DuplicateTriangle { triangle, .. }
        | E::NonManifoldEdge { triangle, .. }
        | E::NonConforming { triangle, .. } => format!("domain.triangles[{triangle}]"),
        E::NoTriangles | E::TooLarge(_) | E::CollinearPoints => "domain.triangles".to_string(),
    };
    invalid(at, e)
}

fn ps_error(e: PsError) -> FormatError {
    let at = match &e {
        PsError::SplitPointOutside { triangle } => format!("domain.split_points[{triangle}]"),
        PsError::EdgePointOutside { triangle, .. } => format!("domain.triangles[{triangle}]"),
        PsError::DegeneratePsTriangle { vertex } | PsError::PsPointOutside { vertex, .. } => {
            format!("ps_triangles[{vertex}]")
        }
        PsError::NonFiniteCoefficient { vertex, index } => format!("control[{vertex}][{index}]"),
        PsError::InvalidWeight { vertex, index, .. } => format!("weights[{vertex}][{index}]"),
        PsError::WrongCount { what, .. } => what.to_string(),
        PsError::OutsideDomain { .. } => "domain".to_string(),
    };
    invalid(at, e)
}

/// The file text of a surface. The PS-triangles are always written explicitly, so that a
/// file means the same surface whatever version of the optimiser reads it; a uniform
/// surface also gets its `uniform` section.
pub fn to_json_string(surface: &Surface) -> String {
    let file = match surface {
        Surface::General(s) => general_file(s),
        Surface::Uniform(u, _) => uniform_file(u),
    };
    let mut text = serde_json::to_string(&file).expect("finite numbers serialise");
    text.push('\n');
    text
}

fn points3(c: &[[Vector3<f64>; 3]]) -> Vec<[[f64; 3]; 3]> {
    c.iter().map(|t| t.map(|p| [p.x, p.y, p.z])).collect()
}

fn general_file(surface: &PsSurface) -> FileV1 {
    let basis = surface.basis();
    let tri = basis.triangulation();
    let refinement = basis.refinement();
    let (split, split_points) = match refinement.rule() {
        Some(SplitRule::Incenter) => (Some("incenter".to_string()), None),
        Some(SplitRule::Centroid) => (Some("centroid".to_string()), None),
        None => (
            None,
            Some(
                refinement
                    .split_points()
                    .iter()
                    .map(|p| [p.x, p.y])
                    .collect(),
            ),
        ),
    };
    let mut file = FileV1 {
        format: FORMAT_NAME.to_string(),
        version: FORMAT_VERSION as u64,
        kind: Kind::Functional,
        domain: Domain {
            vertices: tri.vertices().iter().map(|v| [v.x, v.y]).collect(),
            triangles: tri
                .triangles()
                .iter()
                .map(|t| t.map(|v| v as usize))
                .collect(),
            split,
            split_points,
        },
        ps_triangles: Some(
            basis
                .ps_triangles()
                .iter()
                .map(|t| t.v.map(|p| [p.x, p.y]))
                .collect(),
        ),
        control: None,
        control_points: None,
        weights: None,
        uniform: None,
    };
    match surface {
        PsSurface::Functional(s) => file.control = Some(s.coefficients().to_vec()),
        PsSurface::Parametric(s) => {
            file.kind = Kind::Parametric;
            file.control_points = Some(points3(s.coefficients()));
        }
        PsSurface::Rational(s) => {
            file.kind = Kind::Nurps;
            file.control_points = Some(points3(s.points()));
            file.weights = Some(s.weights().to_vec());
        }
    }
    file
}

fn uniform_file(u: &UpsSurface) -> FileV1 {
    let grid = u.grid();
    let lattice = *grid.lattice();
    let slots = grid.real_slots();
    let mut index = vec![usize::MAX; grid.slots()];
    for (k, &s) in slots.iter().enumerate() {
        index[s] = k;
    }
    let points: Vec<Point2<f64>> = slots
        .iter()
        .map(|&s| lattice.point(grid.lattice_point(s)))
        .collect();
    let mut file = FileV1 {
        format: FORMAT_NAME.to_string(),
        version: FORMAT_VERSION as u64,
        kind: Kind::Functional,
        domain: Domain {
            vertices: points.iter().map(|p| [p.x, p.y]).collect(),
            triangles: grid
                .triangle_slots()
                .into_iter()
                .map(|t| t.map(|s| index[s]))
                .collect(),
            split: Some("incenter".into()),
            split_points: None,
        },
        ps_triangles: Some(
            points
                .iter()
                .map(|&p| fixed_ps_triangle(&lattice, p).v.map(|q| [q.x, q.y]))
                .collect(),
        ),
        control: None,
        control_points: None,
        weights: None,
        uniform: Some(Uniform {
            base: lattice.base,
            origin: [lattice.origin.x, lattice.origin.y],
            polygon: grid.polygon().vertices().to_vec(),
        }),
    };
    match u {
        UpsSurface::Functional(s) => file.control = Some(s.vertex_values()),
        UpsSurface::Parametric(s) => {
            file.kind = Kind::Parametric;
            file.control_points = Some(points3(&s.vertex_values()));
        }
        UpsSurface::Rational(s) => {
            let v: Vec<[Weighted<Vector3<f64>>; 3]> = s.vertex_values();
            file.kind = Kind::Nurps;
            file.control_points = Some(points3(
                &v.iter().map(|t| t.map(|w| w.point)).collect::<Vec<_>>(),
            ));
            file.weights = Some(v.iter().map(|t| t.map(|w| w.weight)).collect());
        }
    }
    file
}

/// Reads and validates a surface file.
pub fn load(path: &Path) -> Result<Surface, FileError> {
    let text = std::fs::read_to_string(path).map_err(|source| FileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    from_json_str(&text).map_err(|source| FileError::Format {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes a surface file atomically and durably (a failure leaves any previous file intact).
pub fn save(surface: &Surface, path: &Path) -> Result<(), FileError> {
    let text = to_json_string(surface);
    super::atomic_write_bytes(path, super::Durability::Durable, text.as_bytes()).map_err(|source| {
        FileError::Io {
            path: path.to_path_buf(),
            source,
        }
    })
}
