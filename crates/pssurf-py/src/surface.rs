//! `pssurf.Surface`: any surface the library has, loaded, saved, sampled and measured; and
//! the operations of uniform (UPS) surfaces: subdivision, wavelets, denoising.

use nalgebra::{Point2, Vector3};
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pssurf::interrogate::{DEFAULT_QUADRATURE_DEGREE, fairness, sample_counts, sample_patches};
use pssurf::surface::{ParametricSurface, PiecewiseSurface, Surface, UpsDecomposition, UpsSurface};
use pssurf::ups::threshold::{Shrink, ThresholdRule};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{float_rows, float64_array, points_from, rows3};
use crate::errors::{Count, check_budget, file_error, memory_budget, value_error};

/// A surface of any kind (functional or parametric PS, NURPS, UPS, Bézier, NURBS).
#[pyclass(name = "Surface", module = "pssurf._core", frozen)]
pub struct PySurface {
    surface: Surface,
}

impl PySurface {
    /// Wraps a library surface.
    pub fn new(surface: Surface) -> Self {
        PySurface { surface }
    }

    /// The uniform form, or a ValueError naming the operation that needs one.
    fn uniform(&self, what: &str) -> PyResult<&UpsSurface> {
        self.surface.uniform().ok_or_else(|| {
            value_error(format!(
                "{what} needs a uniform (UPS) surface, and this is a {} surface (make one with pssurf.ups)",
                self.surface.kind().name()
            ))
        })
    }
}

/// A sampled mesh for Python: (vertices, faces, fields).
type SampledMesh<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyDict>,
);

/// Bytes of memory per vertex while a UPS surface is built (the CLI's measured bound).
const UPS_BYTES_PER_VERTEX: u128 = 1500;

#[pymethods]
impl PySurface {
    /// The kind: "functional", "parametric", "nurps", "ups-functional", … .
    #[getter]
    fn kind(&self) -> &'static str {
        self.surface.kind().name()
    }

    /// The number of polynomial (or rational) pieces.
    #[getter]
    fn piece_count(&self) -> usize {
        self.surface.piece_count()
    }

    /// The parameter domain's bounding box ((umin, vmin), (umax, vmax)).
    #[getter]
    fn bounds(&self) -> ((f64, f64), (f64, f64)) {
        let (a, b) = self.surface.domain_bounds();
        ((a.x, a.y), (b.x, b.y))
    }

    /// Writes the surface (atomically) to `path`; the format follows the extension.
    fn save(&self, py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = path_argument(path)?;
        py.detach(|| pssurf::io::save(&self.surface, &path))
            .map_err(file_error)
    }

    /// Points of the surface at parameters `uv` of shape (n, 2) (any array-like): shape
    /// (n, 3), NaN outside the domain.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        uv: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let uv = float64_array(uv, "uv")?;
        let uv: PyReadonlyArray2<'_, f64> = uv
            .extract()
            .map_err(|_| value_error("uv must have shape (n, 2)"))?;
        let uv = points_from(&uv, "uv")?;
        let flat = py.detach(|| evaluate_points(&self.surface, &uv));
        float_rows(py, flat, 3)
    }

    /// A triangle mesh sampled piece by piece (2^level steps per piece side):
    /// (vertices (n, 3), faces (m, 3), fields) with fields "normal" (n, 3), "uv" (n, 2),
    /// "piece" (n,), and, with curvature, "K", "H", "k1", "k2" (n,).
    #[pyo3(signature = (level = Count(3), curvature = true))]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        level: Count<u32>,
        curvature: bool,
    ) -> PyResult<SampledMesh<'py>> {
        let Count(level) = level;
        let counts = sample_counts(self.surface.piece_kind(), self.surface.piece_count(), level)
            .filter(|c| c.vertices <= u32::MAX as u64)
            .ok_or_else(|| value_error(format!("level {level} makes more than 2³² vertices")))?;
        check_budget(
            &format!("sampling at level {level}"),
            counts.vertices as u128 * 120 + counts.triangles as u128 * 24,
        )?;
        let s = py.detach(|| sample_patches(&self.surface, level, curvature));
        let m = &s.mesh;
        let vertices = float_rows(py, flatten3(&m.positions), 3)?;
        let faces = rows3(
            py,
            m.triangles.iter().flat_map(|t| t.map(i64::from)).collect(),
        )?;
        let fields = PyDict::new(py);
        fields.set_item("normal", float_rows(py, flatten3(&m.normals), 3)?)?;
        let uv: Vec<f64> = m.uvs.iter().flat_map(|p| [p.x, p.y]).collect();
        fields.set_item("uv", float_rows(py, uv, 2)?)?;
        let piece: Vec<i64> = s.patch.iter().map(|&p| i64::from(p)).collect();
        fields.set_item("piece", PyArray1::from_vec(py, piece))?;
        if curvature {
            let column = |f: fn(&pssurf::interrogate::PrincipalCurvatures) -> f64| {
                PyArray1::from_vec(py, s.curvature.iter().map(f).collect())
            };
            fields.set_item("K", column(|c| c.gaussian))?;
            fields.set_item("H", column(|c| c.mean))?;
            fields.set_item("k1", column(|c| c.k1))?;
            fields.set_item("k2", column(|c| c.k2))?;
        }
        Ok((vertices, faces, fields))
    }

    /// The fairness numbers: area, ∫H², ∫K, ∫|K|, ∫(κ1² + κ2²), thin-plate energy.
    fn fairness<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let f = py.detach(|| fairness(&self.surface, DEFAULT_QUADRATURE_DEGREE));
        let i = f.integrals;
        let d = PyDict::new(py);
        d.set_item("area", i.area)?;
        d.set_item("mean_squared", i.mean_squared)?;
        d.set_item("gaussian", i.gaussian)?;
        d.set_item("gaussian_abs", i.gaussian_abs)?;
        d.set_item("principal_squared", i.principal_squared)?;
        d.set_item("thin_plate", i.thin_plate)?;
        d.set_item("singular_nodes", f.singular_nodes)?;
        Ok(d)
    }

    /// The UPS surface after `times` steps of √3-free dyadic subdivision (thesis 4.3): the
    /// same surface on a lattice twice as fine per step.
    fn subdivide(&self, py: Python<'_>, times: Count<u32>) -> PyResult<PySurface> {
        let Count(times) = times;
        let u = self.uniform("subdivide")?;
        let vertices = (u.grid().vertex_count() as u128)
            .checked_shl(2 * times.min(60))
            .unwrap_or(u128::MAX);
        check_budget(
            &format!("{times} subdivision steps"),
            vertices.saturating_mul(UPS_BYTES_PER_VERTEX),
        )?;
        let out = py.detach(|| u.subdivide_times(times as usize));
        Ok(PySurface::new(Surface::try_from(out).map_err(value_error)?))
    }

    /// The wavelet decomposition over `levels` levels (thesis 4.5).
    fn wavelet(&self, py: Python<'_>, levels: Count<u32>) -> PyResult<Wavelet> {
        let Count(levels) = levels;
        check_levels(levels)?;
        let u = self.uniform("wavelet")?;
        let d = py
            .detach(|| u.wavelet_transform(levels))
            .map_err(value_error)?;
        Ok(Wavelet { decomposition: d })
    }

    /// Denoising by wavelet thresholding over `levels` levels (thesis 4.5.6). `threshold`:
    /// "universal", "sure", "gcv", a number (absolute) or "5%" (of each level's largest
    /// coefficient); `mode`: "soft" or "hard".
    #[pyo3(signature = (levels, threshold = None, mode = "soft"))]
    fn denoise(
        &self,
        py: Python<'_>,
        levels: Count<u32>,
        threshold: Option<&Bound<'_, PyAny>>,
        mode: &str,
    ) -> PyResult<PySurface> {
        let Count(levels) = levels;
        check_levels(levels)?;
        let u = self.uniform("denoise")?;
        let rule = threshold.map_or(Ok(ThresholdRule::Universal), threshold_rule)?;
        let mode = match mode {
            "soft" => Shrink::Soft,
            "hard" => Shrink::Hard,
            _ => {
                return Err(value_error(format!(
                    "mode must be \"soft\" or \"hard\", not {mode:?}"
                )));
            }
        };
        let (out, _) = py
            .detach(|| u.denoise(levels, |_, _| rule, mode))
            .map_err(value_error)?;
        Ok(PySurface::new(Surface::try_from(out).map_err(value_error)?))
    }

    fn __repr__(&self) -> String {
        format!(
            "<pssurf.Surface {} with {} pieces>",
            self.surface.kind().name(),
            self.surface.piece_count()
        )
    }
}

/// The threshold rule from Python: a name, a number, or "p%".
fn threshold_rule(t: &Bound<'_, PyAny>) -> PyResult<ThresholdRule> {
    if let Ok(v) = t.extract::<f64>() {
        return if v >= 0.0 && v.is_finite() {
            Ok(ThresholdRule::Absolute(v))
        } else {
            Err(value_error(format!(
                "threshold must be finite and ≥ 0, not {v}"
            )))
        };
    }
    let s: String = t.extract()?;
    match s.as_str() {
        "universal" => Ok(ThresholdRule::Universal),
        "sure" => Ok(ThresholdRule::Sure),
        "gcv" => Ok(ThresholdRule::Gcv),
        _ => s
            .strip_suffix('%')
            .and_then(|p| p.trim().parse::<f64>().ok())
            .filter(|p| (0.0..=100.0).contains(p))
            .map(ThresholdRule::PercentOfMax)
            .ok_or_else(|| {
                value_error(format!(
                    "threshold must be \"universal\", \"sure\", \"gcv\", a number or \"p%\", not {s:?}"
                ))
            }),
    }
}

/// Wavelet levels must lie in 1…40, as the CLI's `--levels` (the grid halves per level).
fn check_levels(levels: u32) -> PyResult<()> {
    if (1..=40).contains(&levels) {
        Ok(())
    } else {
        Err(value_error(format!("levels must be in 1…40, not {levels}")))
    }
}

/// A UPS wavelet decomposition: the coarse surface and the detail coefficients per level.
#[pyclass(module = "pssurf._core", frozen)]
pub struct Wavelet {
    decomposition: UpsDecomposition,
}

#[pymethods]
impl Wavelet {
    /// The number of detail levels.
    #[getter]
    fn levels(&self) -> usize {
        self.decomposition.levels()
    }

    /// The coarsest surface.
    fn coarse(&self) -> PyResult<PySurface> {
        Ok(PySurface::new(
            Surface::try_from(self.decomposition.coarse()).map_err(value_error)?,
        ))
    }

    /// The surface rebuilt from the coarse one and every detail.
    fn reconstruct(&self) -> PyResult<PySurface> {
        Ok(PySurface::new(
            Surface::try_from(self.decomposition.reconstruct()).map_err(value_error)?,
        ))
    }

    /// The detail coefficients of `level` (0 = coarsest) and coordinate `component`.
    fn coefficients<'py>(
        &self,
        py: Python<'py>,
        level: Count<usize>,
        component: Count<usize>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (Count(level), Count(component)) = (level, component);
        if level >= self.decomposition.levels() {
            return Err(value_error(format!(
                "level {level} does not exist (there are {})",
                self.decomposition.levels()
            )));
        }
        let width = match self.decomposition {
            UpsDecomposition::Functional(_) => 1,
            UpsDecomposition::Parametric(_) => 3,
        };
        if component >= width {
            return Err(value_error(format!(
                "component {component} does not exist (there are {width})"
            )));
        }
        Ok(PyArray1::from_vec(
            py,
            self.decomposition.coefficients(level, component),
        ))
    }
}

/// Points at parameters, NaN outside, in parallel.
fn evaluate_points(surface: &Surface, uv: &[Point2<f64>]) -> Vec<f64> {
    use rayon::prelude::*;
    uv.par_chunks(4096)
        .flat_map_iter(|chunk| {
            let mut cursor = surface.cursor_near(chunk[0]);
            chunk
                .iter()
                .map(move |&p| {
                    surface
                        .jet_with(p, &mut cursor)
                        .map_or([f64::NAN; 3], |j| j.jet.value.into())
                })
                .collect::<Vec<[f64; 3]>>()
        })
        .flatten()
        .collect()
}

/// Vectors as a flat row-major list.
fn flatten3(v: &[Vector3<f64>]) -> Vec<f64> {
    v.iter().flat_map(|p| [p.x, p.y, p.z]).collect()
}

/// Memory per byte of a surface file while it is loaded (the CLI's measured bound).
const LOAD_BYTES_PER_FILE_BYTE: u64 = 8;

/// The most a pipe or device (whose size is unknown) may deliver before it is refused.
const STREAM_LIMIT: u64 = 256 << 20;

/// Reads a surface file (JSON or binary, told apart by its first bytes), validating
/// everything. A regular file whose loading would exceed the memory budget is refused by
/// `MemoryError` before reading; a pipe or device (an endless one such as /dev/zero) after
/// 256 MiB, by `OSError`.
#[pyfunction]
pub fn load(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<PySurface> {
    let path = path_argument(path)?;
    let limit = match std::fs::metadata(&path) {
        Ok(meta) if meta.is_file() => {
            check_budget(
                &format!("loading {}", path.display()),
                meta.len() as u128 * LOAD_BYTES_PER_FILE_BYTE as u128,
            )?;
            memory_budget() / LOAD_BYTES_PER_FILE_BYTE
        }
        _ => STREAM_LIMIT,
    };
    let s = py
        .detach(|| pssurf::io::load_limited(&path, limit))
        .map_err(file_error)?;
    Ok(PySurface::new(s))
}

/// A UPS surface on a standard lattice polygon (3 = triangle, 4 = rhombus, 5 = pentagon,
/// 6 = hexagon, `size` triangles per side) interpolating the graph z = height(x, y), a
/// formula in x and y (thesis (4.9)); `kind` "parametric" or "functional".
#[pyfunction]
#[pyo3(signature = (sides, size, height = "0", kind = "parametric", base = 1.0))]
pub fn ups(
    py: Python<'_>,
    sides: Count<usize>,
    size: Count<i64>,
    height: &str,
    kind: &str,
    base: f64,
) -> PyResult<PySurface> {
    let (Count(sides), Count(size)) = (sides, size);
    use pssurf::expr::HeightFunction;
    use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface_from_formula};
    let kind = match kind {
        "parametric" => GraphKind::Parametric,
        "functional" => GraphKind::Functional,
        _ => {
            return Err(value_error(format!(
                "kind must be \"parametric\" or \"functional\", not {kind:?}"
            )));
        }
    };
    if !(base > 0.0 && base.is_finite()) {
        return Err(value_error(format!(
            "base must be finite and > 0, not {base}"
        )));
    }
    let polygon = LatticePolygon::standard(sides, size).map_err(value_error)?;
    check_budget(
        &format!(
            "a UPS surface with {} vertices",
            polygon.lattice_point_count()
        ),
        polygon
            .lattice_point_count()
            .saturating_mul(UPS_BYTES_PER_VERTEX)
            .saturating_add(polygon.block_slots().saturating_mul(3)),
    )?;
    let f = HeightFunction::parse(height).map_err(value_error)?;
    let lattice = Lattice {
        base,
        origin: Point2::origin(),
    };
    let surface = py.detach(|| {
        let grid = UpsGrid::new(lattice, polygon).map_err(|e| e.to_string())?;
        graph_surface_from_formula(grid, kind, &f).map_err(|e| e.to_string())
    });
    Ok(PySurface::new(
        Surface::try_from(surface.map_err(value_error)?).map_err(value_error)?,
    ))
}

/// A file path given as Python's `open` takes one: str, bytes or os.PathLike (through
/// `os.fsdecode`; anything else is its TypeError).
fn path_argument(path: &Bound<'_, PyAny>) -> PyResult<std::path::PathBuf> {
    let os = path.py().import("os")?;
    os.call_method1("fsdecode", (path,))?.extract()
}
