//! The pssurf surface file format, version 1 (described in `docs/format.md`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use nalgebra::{Point2, Vector3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::bezier::{BezierTriangle, RationalBezierTriangle};
use crate::geometry::Triangle2;
use crate::nurbs::NurbsSurface;
use crate::ps::net::Weighted;
use crate::ps::{Nurps, PsBasis, PsError, PsRefinement, PsSpline, PsTriangleChoice, SplitRule};
use crate::surface::{Surface, UpsSurface};
use crate::triangulation::{Triangulation, TriangulationError};
use crate::ups::{Lattice, LatticePolygon, Ups, UpsGrid, fixed_ps_triangle};

mod binary;

/// The format version this build writes and reads.
pub const FORMAT_VERSION: u32 = 1;

/// The format's name, the value of the `format` field.
pub(crate) const FORMAT_NAME: &str = "pssurf";

/// The `kind` of a curve file (`super::curve_file`), which a surface reader names as such.
pub const CURVE_KIND: &str = "curve";

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
    /// Another pssurf file (or another program's), named by its `format` field.
    #[error("not a surface file: its \"format\" is {0:?}{hint}", hint = foreign_hint(.0))]
    Foreign(String),
    /// A version this build cannot read.
    #[error("format version {0} is not supported (this build reads version {FORMAT_VERSION})")]
    UnsupportedVersion(u64),
    /// The file is not UTF-8 text (nor, for a surface, a binary `.psb` file).
    #[error(
        "is not UTF-8 text (pssurf files are JSON text; surfaces may also be binary .psb files)"
    )]
    NotText,
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
    /// The operating system refused (the cause in words, without the OS error number).
    #[error("{}: {}", path.display(), super::io_cause(cause))]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause (part of this error's message, so not repeated as its `source`).
        cause: std::io::Error,
    },
    /// The contents are invalid.
    #[error("{}: {cause}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// The cause (part of this error's message, so not repeated as its `source`).
        cause: FormatError,
    },
}

#[derive(Deserialize)]
pub(crate) struct Header {
    format: Option<String>,
    version: Option<u64>,
    kind: Option<serde_json::Value>,
}

#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(rename_all = "snake_case")]
enum Kind {
    Functional,
    Parametric,
    Nurps,
    Bezier,
    RationalBezier,
    Nurbs,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Functional => "functional",
            Kind::Parametric => "parametric",
            Kind::Nurps => "nurps",
            Kind::Bezier => "bezier",
            Kind::RationalBezier => "rational_bezier",
            Kind::Nurbs => "nurbs",
        }
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct DomainSection {
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
struct UniformSection {
    base: f64,
    origin: [f64; 2],
    polygon: Vec<[i64; 2]>,
}

/// A triangular Bézier patch: its domain triangle, degree, ordinates in storage order
/// ([`crate::bezier::index`]) and, for a rational patch, one weight per ordinate.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BezierSection {
    triangle: [[f64; 2]; 3],
    degree: usize,
    points: Vec<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
}

/// A tensor-product NURBS surface: degrees [p, q], knot vectors [U, V], the net's size
/// [n_u, n_v], the control points row by row (P_ij at i·n_v + j, i along u) and, for a
/// rational surface, one weight per point.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct NurbsSection {
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    counts: [usize; 2],
    points: Vec<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileV1 {
    format: String,
    version: u64,
    kind: Kind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    domain: Option<DomainSection>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ps_triangles: Option<Vec<[[f64; 2]; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    control: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    control_points: Option<Vec<[[f64; 3]; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    uniform: Option<UniformSection>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bezier: Option<BezierSection>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    nurbs: Option<NurbsSection>,
}

impl FileV1 {
    /// An empty file of `kind`, to be filled by a writer.
    fn new(kind: Kind) -> Self {
        FileV1 {
            format: FORMAT_NAME.to_string(),
            version: FORMAT_VERSION as u64,
            kind,
            domain: None,
            ps_triangles: None,
            control: None,
            control_points: None,
            weights: None,
            uniform: None,
            bezier: None,
            nurbs: None,
        }
    }

    /// The fields present, by name, for the rule that a file holds only its kind's fields.
    fn present_fields(&self) -> [(&'static str, bool); 8] {
        [
            ("domain", self.domain.is_some()),
            ("ps_triangles", self.ps_triangles.is_some()),
            ("control", self.control.is_some()),
            ("control_points", self.control_points.is_some()),
            ("weights", self.weights.is_some()),
            ("uniform", self.uniform.is_some()),
            ("bezier", self.bezier.is_some()),
            ("nurbs", self.nurbs.is_some()),
        ]
    }
}

pub(crate) fn syntax(e: serde_json::Error) -> FormatError {
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

pub(crate) fn invalid(at: impl Into<String>, message: impl std::fmt::Display) -> FormatError {
    FormatError::Invalid {
        at: at.into(),
        message: message.to_string(),
    }
}

/// Reads a surface from the text of a file, validating everything; the error names the
/// first problem and where it is.
pub fn from_json_str(text: &str) -> Result<Surface, FormatError> {
    let header = check_header(text)?;
    if header.kind.as_ref().and_then(|k| k.as_str()) == Some(CURVE_KIND) {
        return Err(invalid(
            "kind",
            "\"curve\": a curve file, not a surface (`pssurf info` reads it)",
        ));
    }
    let file: FileV1 = serde_json::from_str(text).map_err(syntax)?;
    build(file)
}

/// Checks the `format` and `version` fields common to surface and curve files.
pub(crate) fn check_header(text: &str) -> Result<Header, FormatError> {
    // A list (e.g. the quality report of `pssurf fill-hole`) has no `format` field; serde
    // would read it as the header's fields in order and complain about their types.
    if text
        .trim_start_matches('\u{feff}')
        .trim_start()
        .starts_with('[')
    {
        return Err(FormatError::NotPssurf);
    }
    let header: Header = serde_json::from_str(text).map_err(syntax)?;
    match header.format.as_deref() {
        Some(FORMAT_NAME) => {}
        Some(other) => return Err(FormatError::Foreign(other.to_string())),
        None => return Err(FormatError::NotPssurf),
    }
    match header.version {
        Some(v) if v == FORMAT_VERSION as u64 => Ok(header),
        Some(v) => Err(FormatError::UnsupportedVersion(v)),
        None => Err(invalid("version", "missing field `version`")),
    }
}

/// The one builder: check which fields the kind allows, read the structure (a general basis,
/// a uniform grid, or a Bézier triangle), read and check the control data against it, and
/// assemble the surface.
fn build(mut file: FileV1) -> Result<Surface, FormatError> {
    check_fields(&file)?;
    match file.kind {
        Kind::Bezier | Kind::RationalBezier => build_bezier(&file),
        Kind::Nurbs => build_nurbs(&file),
        _ => {
            let structure = match &file.uniform {
                Some(u) => Structure::Uniform(read_uniform(u, &file)?),
                None => Structure::General(read_basis(&file)?),
            };
            let control = read_ps_control(&mut file, structure.vertex_count())?;
            structure.surface(control)
        }
    }
}

/// Refuses fields that belong to other kinds and reports missing ones.
fn check_fields(file: &FileV1) -> Result<(), FormatError> {
    let (required, allowed): (&[&str], &[&str]) = match file.kind {
        Kind::Functional => (&["domain", "control"], &["ps_triangles", "uniform"]),
        Kind::Parametric => (&["domain", "control_points"], &["ps_triangles", "uniform"]),
        Kind::Nurps => (
            &["domain", "control_points", "weights"],
            &["ps_triangles", "uniform"],
        ),
        Kind::Bezier | Kind::RationalBezier => (&["bezier"], &[]),
        Kind::Nurbs => (&["nurbs"], &[]),
    };
    for (field, present) in file.present_fields() {
        // The general form of a uniform surface follows from its `uniform` section.
        let implied = field == "domain" && file.uniform.is_some();
        if present && !required.contains(&field) && !allowed.contains(&field) {
            return Err(invalid(
                field,
                format!("a {} surface has no field `{field}`", file.kind.name()),
            ));
        }
        if !present && required.contains(&field) && !implied {
            return Err(invalid(
                field,
                format!("missing field `{field}` for a {} surface", file.kind.name()),
            ));
        }
    }
    Ok(())
}

/// The structure that control values are attached to.
enum Structure {
    General(Arc<PsBasis>),
    Uniform(UpsGrid),
}

/// The control data of a PS-type file, checked for count and finiteness.
enum PsControl {
    Heights(Vec<[f64; 3]>),
    Points(Vec<[Vector3<f64>; 3]>),
    Weighted(Vec<[Vector3<f64>; 3]>, Vec<[f64; 3]>),
}

impl Structure {
    fn vertex_count(&self) -> usize {
        match self {
            Structure::General(b) => b.triangulation().vertex_count(),
            Structure::Uniform(g) => g.vertex_count(),
        }
    }

    fn surface(self, control: PsControl) -> Result<Surface, FormatError> {
        Ok(match (self, control) {
            (Structure::General(b), PsControl::Heights(c)) => {
                Surface::Functional(PsSpline::new(b, c).map_err(ps_error)?)
            }
            (Structure::General(b), PsControl::Points(c)) => {
                Surface::Parametric(PsSpline::new(b, c).map_err(ps_error)?)
            }
            (Structure::General(b), PsControl::Weighted(c, w)) => {
                Surface::Nurps(Nurps::new(b, c, w).map_err(ps_error)?)
            }
            (Structure::Uniform(g), PsControl::Heights(c)) => {
                Surface::try_from(UpsSurface::Functional(
                    Ups::from_vertices(g, c).map_err(|e| invalid("control", e))?,
                ))
                .map_err(|e| invalid("control", e))?
            }
            (Structure::Uniform(g), PsControl::Points(c)) => {
                Surface::try_from(UpsSurface::Parametric(
                    Ups::from_vertices(g, c).map_err(|e| invalid("control_points", e))?,
                ))
                .map_err(|e| invalid("control_points", e))?
            }
            (Structure::Uniform(g), PsControl::Weighted(c, w)) => Surface::try_from(
                UpsSurface::Rational(Ups::rational(g, c, w).map_err(|e| match e {
                    crate::ups::UpsError::Ps(pe) => ps_error(pe),
                    e => invalid("weights", e),
                })?),
            )
            .map_err(|e| invalid("control_points", e))?,
        })
    }
}

/// Reads `control`, `control_points` and `weights` as the kind requires (presence was
/// checked before), one triple per vertex, all finite, weights positive.
/// The arrays are moved out of `file` (no copy of what may be most of the memory).
fn read_ps_control(file: &mut FileV1, n: usize) -> Result<PsControl, FormatError> {
    let finite = |field: &str, i: usize, j: usize, ok: bool| {
        if ok {
            Ok(())
        } else {
            Err(invalid(
                format!("{field}[{i}][{j}]"),
                "not a finite number within ±1e60",
            ))
        }
    };
    if file.kind == Kind::Functional {
        let c = file.control.take().expect("checked by check_fields");
        check_count("control", c.len(), n)?;
        for (i, t) in c.iter().enumerate() {
            for j in 0..3 {
                finite("control", i, j, crate::limits::value_ok(t[j]))?;
            }
        }
        return Ok(PsControl::Heights(c));
    }
    let c = file.control_points.take().expect("checked by check_fields");
    check_count("control_points", c.len(), n)?;
    for (i, t) in c.iter().enumerate() {
        for j in 0..3 {
            finite(
                "control_points",
                i,
                j,
                t[j].iter().all(|&x| crate::limits::value_ok(x)),
            )?;
        }
    }
    // (Same size and alignment: the collect reuses the allocation.)
    let points: Vec<[Vector3<f64>; 3]> = c
        .into_iter()
        .map(|t| t.map(|p| Vector3::new(p[0], p[1], p[2])))
        .collect();
    if file.kind == Kind::Parametric {
        return Ok(PsControl::Points(points));
    }
    let w = file.weights.take().expect("checked by check_fields");
    check_count("weights", w.len(), n)?;
    for (i, t) in w.iter().enumerate() {
        for j in 0..3 {
            if !crate::limits::weight_ok(t[j]) {
                return Err(invalid(
                    format!("weights[{i}][{j}]"),
                    PsError::InvalidWeight {
                        vertex: i,
                        index: j,
                        weight: t[j],
                    },
                ));
            }
        }
    }
    Ok(PsControl::Weighted(points, w))
}

/// The general PS basis of a file: triangulation, refinement, PS-triangles.
fn read_basis(file: &FileV1) -> Result<Arc<PsBasis>, FormatError> {
    let domain = file.domain.as_ref().expect("checked by check_fields");
    for (i, v) in domain.vertices.iter().enumerate() {
        if !v.iter().all(|x| x.is_finite()) {
            return Err(invalid(
                format!("domain.vertices[{i}]"),
                "coordinates must be finite",
            ));
        }
    }
    let vertices: Vec<Point2<f64>> = domain
        .vertices
        .iter()
        .map(|v| Point2::new(v[0], v[1]))
        .collect();
    let tri =
        Triangulation::try_new(vertices, domain.triangles.clone()).map_err(triangulation_error)?;
    let refinement = read_refinement(domain, &tri)?;
    let choice = match &file.ps_triangles {
        None => PsTriangleChoice::Optimal,
        Some(list) => PsTriangleChoice::Given(list.iter().map(|&t| triangle2(t)).collect()),
    };
    Ok(Arc::new(
        PsBasis::with_refinement(tri, refinement, &choice).map_err(ps_error)?,
    ))
}

/// The PS refinement from `split` or `split_points`.
fn read_refinement(
    domain: &DomainSection,
    tri: &Triangulation,
) -> Result<PsRefinement, FormatError> {
    match (&domain.split, &domain.split_points) {
        (Some(_), Some(_)) => Err(invalid(
            "domain",
            "give either `split` or `split_points`, not both",
        )),
        (_, Some(points)) => {
            let z = points.iter().map(|p| Point2::new(p[0], p[1])).collect();
            PsRefinement::with_points(tri, z).map_err(ps_error)
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
            PsRefinement::new(tri, rule).map_err(ps_error)
        }
    }
}

fn triangle2(t: [[f64; 2]; 3]) -> Triangle2 {
    Triangle2::new(
        Point2::new(t[0][0], t[0][1]),
        Point2::new(t[1][0], t[1][1]),
        Point2::new(t[2][0], t[2][1]),
    )
}

/// The uniform grid of a UPS file, checking that the general description is exactly its
/// uniform triangulation with the incentre split and the fixed PS-triangles.
fn read_uniform(u: &UniformSection, file: &FileV1) -> Result<UpsGrid, FormatError> {
    if !(u.base > 0.0 && u.base.is_finite() && u.origin.iter().all(|x| x.is_finite())) {
        return Err(invalid(
            "uniform.base",
            "the base must be a positive finite number and the origin finite",
        ));
    }
    let polygon =
        LatticePolygon::new(u.polygon.clone()).map_err(|e| invalid("uniform.polygon", e))?;
    // One control entry per lattice point of the polygon: counted from its corners before
    // the lattice is built (a 9 KB file naming a polygon of 1e9 lattice points took 62 s
    // and 6 GB to be refused for its 61 control entries).
    let (field, found) = match (&file.control, &file.control_points) {
        (Some(c), _) => ("control", c.len()),
        (None, Some(c)) => ("control_points", c.len()),
        (None, None) => return Err(invalid("control_points", "missing")),
    };
    let expected = polygon.lattice_point_count();
    if expected != found as u128 {
        return Err(invalid(
            field,
            format!("expected one entry per vertex ({expected}), found {found}"),
        ));
    }
    let lattice = Lattice {
        base: u.base,
        origin: Point2::new(u.origin[0], u.origin[1]),
    };
    let grid = UpsGrid::new(lattice, polygon).map_err(|e| invalid("uniform", e))?;
    debug_assert_eq!(grid.vertex_count() as u128, expected, "Pick's theorem");
    // A uniform file may leave out its general form (binary files do): the lattice and the
    // polygon determine it. When it is given, it must be exactly that.
    if let Some(domain) = file.domain.as_ref() {
        check_uniform_vertices(&grid, domain)?;
        check_uniform_triangles(&grid, domain)?;
        check_uniform_split(domain)?;
    }
    if let Some(list) = &file.ps_triangles {
        check_uniform_ps_triangles(&grid, list)?;
    }
    Ok(grid)
}

/// The tolerance for lattice coordinates written as decimals.
fn lattice_tolerance(grid: &UpsGrid) -> f64 {
    1e-9 * grid.lattice().base
}

fn check_uniform_vertices(grid: &UpsGrid, domain: &DomainSection) -> Result<(), FormatError> {
    let slots = grid.real_slots();
    check_count("domain.vertices", domain.vertices.len(), slots.len())?;
    let (lattice, tol) = (grid.lattice(), lattice_tolerance(grid));
    for (k, (&s, v)) in slots.iter().zip(&domain.vertices).enumerate() {
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
    Ok(())
}

fn check_uniform_triangles(grid: &UpsGrid, domain: &DomainSection) -> Result<(), FormatError> {
    let index = vertex_index(grid);
    let key = |mut t: [usize; 3]| {
        t.sort_unstable();
        t
    };
    let mut expected: Vec<[usize; 3]> = grid
        .triangle_slots()
        .into_iter()
        .map(|t| key(t.map(|s| index[s])))
        .collect();
    let mut given: Vec<[usize; 3]> = domain.triangles.iter().map(|&t| key(t)).collect();
    expected.sort_unstable();
    given.sort_unstable();
    if expected != given {
        return Err(invalid(
            "domain.triangles",
            "not the triangles of the uniform triangulation of the polygon",
        ));
    }
    Ok(())
}

fn check_uniform_split(domain: &DomainSection) -> Result<(), FormatError> {
    if domain.split_points.is_some() || domain.split.as_deref().is_some_and(|s| s != "incenter") {
        return Err(invalid(
            "domain.split",
            "uniform surfaces use the incentre split (the angle bisectors, Definition 4.3)",
        ));
    }
    Ok(())
}

fn check_uniform_ps_triangles(grid: &UpsGrid, list: &[[[f64; 2]; 3]]) -> Result<(), FormatError> {
    let slots = grid.real_slots();
    check_count("ps_triangles", list.len(), slots.len())?;
    let (lattice, tol) = (grid.lattice(), lattice_tolerance(grid));
    for (k, (t, &s)) in list.iter().zip(&slots).enumerate() {
        let q = fixed_ps_triangle(lattice, lattice.point(grid.lattice_point(s)));
        let same =
            (0..3).all(|m| (q.v[m].x - t[m][0]).abs() <= tol && (q.v[m].y - t[m][1]).abs() <= tol);
        if !same {
            return Err(invalid(
                format!("ps_triangles[{k}]"),
                "uniform surfaces use the fixed PS-triangles t(6) (Property 4.1)",
            ));
        }
    }
    Ok(())
}

/// For each slot of the grid, the index of its real vertex (`usize::MAX` for pseudo-slots).
fn vertex_index(grid: &UpsGrid) -> Vec<usize> {
    let mut index = vec![usize::MAX; grid.slots()];
    for (k, s) in grid.real_slots().into_iter().enumerate() {
        index[s] = k;
    }
    index
}

/// A Bézier or rational Bézier triangle.
fn build_bezier(file: &FileV1) -> Result<Surface, FormatError> {
    let b = file.bezier.as_ref().expect("checked by check_fields");
    let rational = file.kind == Kind::RationalBezier;
    match (&b.weights, rational) {
        (Some(_), false) => {
            return Err(invalid(
                "bezier.weights",
                "a bezier surface has no weights (use the kind \"rational_bezier\")",
            ));
        }
        (None, true) => {
            return Err(invalid(
                "bezier.weights",
                "missing field `weights` for a rational_bezier surface",
            ));
        }
        _ => {}
    }
    if !b.triangle.iter().flatten().all(|&x| {
        x.is_finite()
            && (x == 0.0
                || (crate::limits::MIN_COORDINATE..=crate::limits::MAX_COORDINATE)
                    .contains(&x.abs()))
    }) {
        return Err(invalid(
            "bezier.triangle",
            "coordinates must be finite, and 0 or between 1e-42 and 1e60 in magnitude",
        ));
    }
    if b.degree > MAX_BEZIER_DEGREE {
        return Err(invalid(
            "bezier.degree",
            format!("the degree must be at most {MAX_BEZIER_DEGREE}"),
        ));
    }
    let points: Vec<Vector3<f64>> = b
        .points
        .iter()
        .map(|p| Vector3::new(p[0], p[1], p[2]))
        .collect();
    let domain = triangle2(b.triangle);
    let bezier_error = |e: crate::bezier::BezierError| {
        use crate::bezier::BezierError as E;
        let at = match &e {
            E::NonFiniteOrdinate(i) => format!("bezier.points[{i}]"),
            E::InvalidWeight(i) => format!("bezier.weights[{i}]"),
            E::DegenerateDomain => "bezier.triangle".to_string(),
            _ => "bezier".to_string(),
        };
        invalid(at, e)
    };
    Ok(match &b.weights {
        None => Surface::Bezier(
            BezierTriangle::try_new(domain, b.degree, points).map_err(bezier_error)?,
        ),
        Some(w) => Surface::RationalBezier(
            RationalBezierTriangle::try_new(domain, b.degree, points, w.clone())
                .map_err(bezier_error)?,
        ),
    })
}

/// A NURBS surface (validated by [`NurbsSurface::try_new`]; the size is checked first, so
/// that a file cannot ask for more points than it holds).
fn build_nurbs(file: &FileV1) -> Result<Surface, FormatError> {
    let n = file.nurbs.as_ref().expect("checked by check_fields");
    let expected = n.counts[0].checked_mul(n.counts[1]);
    if expected != Some(n.points.len()) {
        return Err(invalid(
            "nurbs.points",
            format!(
                "{} points for a {} × {} net",
                n.points.len(),
                n.counts[0],
                n.counts[1]
            ),
        ));
    }
    let points = n
        .points
        .iter()
        .map(|p| Vector3::new(p[0], p[1], p[2]))
        .collect();
    NurbsSurface::try_new(
        n.degree,
        n.knots.clone(),
        n.counts,
        points,
        n.weights.clone(),
    )
    .map(Surface::Nurbs)
    .map_err(|e| {
        use crate::nurbs::NurbsError as E;
        let at = match &e {
            E::Knots { direction, .. } => format!("nurbs.knots ({direction})"),
            E::Count { what, .. } if *what == "weights" => "nurbs.weights".to_string(),
            E::Count { .. } => "nurbs.points".to_string(),
            E::Point(i) => format!("nurbs.points[{i}]"),
            E::Weight(i, _) => format!("nurbs.weights[{i}]"),
        };
        invalid(at, e)
    })
}

/// The highest Bézier degree a file may have (evaluation costs O(m³) per point).
const MAX_BEZIER_DEGREE: usize = 30;

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
        E::NonFiniteVertex(i) | E::CoordinateOutOfRange(i) | E::UnusedVertex(i) => {
            format!("domain.vertices[{i}]")
        }
        E::DuplicateVertex { second, .. } => format!("domain.vertices[{second}]"),
        E::NonManifoldVertex { vertex } => format!("domain.vertices[{vertex}]"),
        E::IndexOutOfRange { triangle, .. }
        | E::RepeatedVertex { triangle }
        | E::DegenerateTriangle { triangle }
        | E::InconsistentOrientation { triangle, .. }
        | E::DuplicateTriangle { triangle, .. }
        | E::NonManifoldEdge { triangle, .. }
        | E::NonConforming { triangle, .. } => format!("domain.triangles[{triangle}]"),
        E::NoTriangles | E::TooLarge(_) | E::CollinearPoints | E::NearlyCollinearPoints { .. } => {
            "domain.triangles".to_string()
        }
    };
    invalid(at, e)
}

fn ps_error(e: PsError) -> FormatError {
    let at = match &e {
        PsError::SplitPointOutside { triangle } => format!("domain.split_points[{triangle}]"),
        PsError::EdgePointOutside { triangle, .. } | PsError::DegeneratePiece { triangle } => {
            format!("domain.triangles[{triangle}]")
        }
        PsError::DegeneratePsTriangle { vertex }
        | PsError::PsTriangleOutOfRange { vertex }
        | PsError::PsPointOutside { vertex, .. } => {
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
    let mut text = serde_json::to_string(&document(surface)).expect("finite numbers serialise");
    text.push('\n');
    text
}

/// The document of a surface, as both encodings write it.
fn document(surface: &Surface) -> FileV1 {
    match surface {
        Surface::Uniform(u) => uniform_file(u.ups()),
        Surface::Bezier(b) => bezier_file(b.domain(), b.degree(), b.points(), None),
        Surface::RationalBezier(b) => {
            bezier_file(b.domain(), b.degree(), b.points(), Some(b.weights()))
        }
        Surface::Nurbs(n) => nurbs_file(n),
        general => general_file(general),
    }
}

fn points3(c: &[[Vector3<f64>; 3]]) -> Vec<[[f64; 3]; 3]> {
    c.iter().map(|t| t.map(|p| [p.x, p.y, p.z])).collect()
}

/// Writes the control values of a PS kind into the file.
fn put_control(file: &mut FileV1, control: PsControl) {
    match control {
        PsControl::Heights(c) => file.control = Some(c),
        PsControl::Points(p) => file.control_points = Some(points3(&p)),
        PsControl::Weighted(p, w) => {
            file.control_points = Some(points3(&p));
            file.weights = Some(w);
        }
    }
}

fn general_file(surface: &Surface) -> FileV1 {
    let basis = surface.ps_basis().expect("a PS kind");
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
    let (kind, control) = match surface {
        Surface::Functional(s) => (
            Kind::Functional,
            PsControl::Heights(s.coefficients().to_vec()),
        ),
        Surface::Parametric(s) => (
            Kind::Parametric,
            PsControl::Points(s.coefficients().to_vec()),
        ),
        Surface::Nurps(s) => (
            Kind::Nurps,
            PsControl::Weighted(s.points().to_vec(), s.weights().to_vec()),
        ),
        _ => unreachable!("general_file is called for the general PS kinds"),
    };
    let mut file = FileV1::new(kind);
    file.domain = Some(DomainSection {
        vertices: tri.vertices().iter().map(|v| [v.x, v.y]).collect(),
        triangles: tri
            .triangles()
            .iter()
            .map(|t| t.map(|v| v as usize))
            .collect(),
        split,
        split_points,
    });
    file.ps_triangles = Some(
        basis
            .ps_triangles()
            .iter()
            .map(|t| t.v.map(|p| [p.x, p.y]))
            .collect(),
    );
    put_control(&mut file, control);
    file
}

fn uniform_file(u: &UpsSurface) -> FileV1 {
    let grid = u.grid();
    let lattice = *grid.lattice();
    let slots = grid.real_slots();
    let index = vertex_index(grid);
    let points: Vec<Point2<f64>> = slots
        .iter()
        .map(|&s| lattice.point(grid.lattice_point(s)))
        .collect();
    let (kind, control) = match u {
        UpsSurface::Functional(s) => (Kind::Functional, PsControl::Heights(s.vertex_values())),
        UpsSurface::Parametric(s) => (Kind::Parametric, PsControl::Points(s.vertex_values())),
        UpsSurface::Rational(s) => {
            let v: Vec<[Weighted<Vector3<f64>>; 3]> = s.vertex_values();
            (
                Kind::Nurps,
                PsControl::Weighted(
                    v.iter().map(|t| t.map(|w| w.point)).collect(),
                    v.iter().map(|t| t.map(|w| w.weight)).collect(),
                ),
            )
        }
    };
    let mut file = FileV1::new(kind);
    file.domain = Some(DomainSection {
        vertices: points.iter().map(|p| [p.x, p.y]).collect(),
        triangles: grid
            .triangle_slots()
            .into_iter()
            .map(|t| t.map(|s| index[s]))
            .collect(),
        split: Some("incenter".into()),
        split_points: None,
    });
    file.ps_triangles = Some(
        points
            .iter()
            .map(|&p| fixed_ps_triangle(&lattice, p).v.map(|q| [q.x, q.y]))
            .collect(),
    );
    file.uniform = Some(UniformSection {
        base: lattice.base,
        origin: [lattice.origin.x, lattice.origin.y],
        polygon: grid.polygon().vertices().to_vec(),
    });
    put_control(&mut file, control);
    file
}

fn bezier_file(
    triangle: &Triangle2,
    degree: usize,
    points: &[Vector3<f64>],
    weights: Option<&[f64]>,
) -> FileV1 {
    let mut file = FileV1::new(if weights.is_some() {
        Kind::RationalBezier
    } else {
        Kind::Bezier
    });
    file.bezier = Some(BezierSection {
        triangle: triangle.v.map(|p| [p.x, p.y]),
        degree,
        points: points.iter().map(|p| [p.x, p.y, p.z]).collect(),
        weights: weights.map(<[f64]>::to_vec),
    });
    file
}

fn nurbs_file(n: &NurbsSurface) -> FileV1 {
    let mut file = FileV1::new(Kind::Nurbs);
    let [u, v] = n.knot_vectors();
    file.nurbs = Some(NurbsSection {
        degree: n.degree(),
        knots: [u.knots().to_vec(), v.knots().to_vec()],
        counts: n.counts(),
        points: n.points().iter().map(|p| [p.x, p.y, p.z]).collect(),
        weights: n.is_rational().then(|| n.weights().to_vec()),
    });
    file
}

/// Reads and validates a surface file.
pub fn load(path: &Path) -> Result<Surface, FileError> {
    load_limited(path, u64::MAX)
}

/// Reads and validates a surface file of at most `max_bytes` bytes; a longer one (or an
/// endless stream such as `/dev/zero`) is refused after reading that much, so that memory
/// stays bounded whatever `path` is.
pub fn load_limited(path: &Path, max_bytes: u64) -> Result<Surface, FileError> {
    let contents = match read_limited(path, max_bytes)? {
        Contents::Binary(file, layout) => (file, layout),
        Contents::Text(text) => {
            return from_json_str(&text).map_err(|cause| FileError::Format {
                path: path.to_path_buf(),
                cause,
            });
        }
    };
    let (reader, layout) = contents;
    binary::read(reader, layout, path, max_bytes)
}

/// A surface file opened and recognised by its first bytes.
enum Contents {
    /// A binary file (its magic number read; positioned after it) and its layout version.
    Binary(std::io::BufReader<std::fs::File>, u8),
    /// The whole text of a JSON file.
    Text(String),
}

/// Opens `path`; a binary surface file is left open after its magic number, anything else is
/// read as text of at most `max_bytes` bytes.
fn read_limited(path: &Path, max_bytes: u64) -> Result<Contents, FileError> {
    use std::io::Read;
    let io = |cause| FileError::Io {
        path: path.to_path_buf(),
        cause,
    };
    let file = open_file(path)?;
    let mut reader = std::io::BufReader::new(file);
    let mut head = Vec::with_capacity(binary::MAGIC.len());
    (&mut reader)
        .take(binary::MAGIC.len() as u64)
        .read_to_end(&mut head)
        .map_err(io)?;
    if head.len() == binary::MAGIC.len() && head.starts_with(binary::MAGIC_PREFIX) {
        let layout = head[7];
        if !binary::LAYOUTS.contains(&layout) {
            return Err(FileError::Format {
                path: path.to_path_buf(),
                cause: invalid(
                    "magic number",
                    format!(
                        "binary layout version {layout} is not supported (this build reads versions {} and {})",
                        binary::LAYOUTS[0],
                        binary::LAYOUTS[1]
                    ),
                ),
            });
        }
        return Ok(Contents::Binary(reader, layout));
    }
    let text = text_limited(path, head.as_slice().chain(reader), max_bytes)?;
    Ok(Contents::Text(text))
}

/// Opens a file for reading, refusing directories with a clear message.
fn open_file(path: &Path) -> Result<std::fs::File, FileError> {
    let io = |cause| FileError::Io {
        path: path.to_path_buf(),
        cause,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    if file.metadata().is_ok_and(|m| m.is_dir()) {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            "is a directory",
        )));
    }
    Ok(file)
}

/// The text of a file of at most `max_bytes` bytes (a longer one, or an endless stream, is
/// refused after reading that much), which must be UTF-8.
pub(crate) fn read_text_limited(path: &Path, max_bytes: u64) -> Result<String, FileError> {
    text_limited(path, open_file(path)?, max_bytes)
}

/// The UTF-8 text of `reader` (the contents of `path`), at most `max_bytes` bytes.
fn text_limited(
    path: &Path,
    reader: impl std::io::Read,
    max_bytes: u64,
) -> Result<String, FileError> {
    use std::io::Read;
    let io = |cause| FileError::Io {
        path: path.to_path_buf(),
        cause,
    };
    let mut bytes = Vec::new();
    reader
        .take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!("longer than the {max_bytes} bytes allowed"),
        )));
    }
    let mut text = String::from_utf8(bytes).map_err(|_| FileError::Format {
        path: path.to_path_buf(),
        cause: FormatError::NotText,
    })?;
    // A byte-order mark (some Windows editors write one) is not part of the JSON.
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(text)
}

/// The two encodings of a surface file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceEncoding {
    /// The JSON document (`.json` and any other extension).
    Json,
    /// The same document with its large arrays as little-endian binary chunks (`.psb`;
    /// docs/format.md, "Binary files").
    Binary,
}

impl SurfaceEncoding {
    /// The encoding a path's extension asks for: `.psb` is binary, anything else JSON.
    pub fn for_path(path: &Path) -> Self {
        match path.extension() {
            Some(e) if e.eq_ignore_ascii_case(BINARY_EXTENSION) => SurfaceEncoding::Binary,
            _ => SurfaceEncoding::Json,
        }
    }
}

/// True when `path` is a regular file that starts with the magic number of a binary surface
/// file (false when it cannot be read, and for pipes and devices, which are not opened here so
/// that their bytes are left for the reader: loading says what is wrong).
pub fn is_binary_surface_file(path: &Path) -> bool {
    use std::io::Read;
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return false;
    }
    let mut head = Vec::with_capacity(binary::MAGIC.len());
    std::fs::File::open(path)
        .and_then(|f| f.take(binary::MAGIC.len() as u64).read_to_end(&mut head))
        .is_ok_and(|_| head.len() == binary::MAGIC.len() && head.starts_with(binary::MAGIC_PREFIX))
}

/// The extension of binary surface files.
pub const BINARY_EXTENSION: &str = "psb";

/// Writes `surface` in `encoding` to `w`.
pub fn write_surface(
    surface: &Surface,
    encoding: SurfaceEncoding,
    w: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    match encoding {
        SurfaceEncoding::Json => w.write_all(to_json_string(surface).as_bytes()),
        SurfaceEncoding::Binary => binary::write(document(surface), w),
    }
}

/// Writes a surface file atomically and durably (a failure leaves any previous file intact),
/// in the encoding its extension asks for ([`SurfaceEncoding::for_path`]).
pub fn save(surface: &Surface, path: &Path) -> Result<(), FileError> {
    let encoding = SurfaceEncoding::for_path(path);
    super::atomic_write(path, super::Durability::Durable, |w| {
        write_surface(surface, encoding, w)
    })
    .map_err(|cause| FileError::Io {
        path: path.to_path_buf(),
        cause,
    })
}

/// What a file of another `format` is, for [`FormatError::Foreign`].
fn foreign_hint(format: &str) -> &'static str {
    match format {
        "pssurf-wavelet" => {
            " (wavelet coefficients as `pssurf wavelet -o` writes them: a report, not read back)"
        }
        "pssurf-scene" => " (a scene of several surfaces: `pssurf info` lists them)",
        _ => " (pssurf surface files have \"pssurf\")",
    }
}
