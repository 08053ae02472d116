//! Reading and changing one vertex's control triangle, for every surface kind. A change
//! updates only the Bézier nets of the vertex's molecule (local control).

use nalgebra::Vector3;
use pssurf::ps::net::Weighted;
use pssurf::surface::{PsSurface, Surface, UpsSurface};

/// The three control points of a vertex (Definition 2.23) and, for NURPS, their weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexControl {
    /// The control points in space (for a functional surface (X_ij, Y_ij, c_ij): only the
    /// heights can change).
    pub points: [Vector3<f64>; 3],
    /// The weights of a rational surface.
    pub weights: Option<[f64; 3]>,
    /// True for a functional surface z = s(x, y).
    pub functional: bool,
}

/// The number of vertices (control triangles) of a surface.
pub fn vertex_count(s: &Surface) -> usize {
    s.general().basis().triangulation().vertex_count()
}

/// The control triangle of vertex `i`.
pub fn vertex_control(s: &Surface, i: usize) -> VertexControl {
    let g = s.general();
    VertexControl {
        points: g.control_points()[i],
        weights: match g {
            PsSurface::Rational(n) => Some(n.weights()[i]),
            _ => None,
        },
        functional: matches!(g, PsSurface::Functional(_)),
    }
}

/// Replaces the control triangle of vertex `i` (for a functional surface only the heights
/// are used). Weights must be positive and everything finite.
pub fn set_vertex_control(s: &mut Surface, i: usize, c: &VertexControl) -> Result<(), String> {
    if i >= vertex_count(s) {
        return Err(format!("there is no vertex {i}"));
    }
    if !c.points.iter().all(|p| p.iter().all(|x| x.is_finite())) {
        return Err("control points must be finite numbers".into());
    }
    if let Some(w) = c.weights
        && !w.iter().all(|w| *w > 0.0 && w.is_finite())
    {
        return Err("weights must be positive".into());
    }
    let heights = c.points.map(|p| p.z);
    let weights = c.weights.unwrap_or([1.0; 3]);
    match s {
        Surface::General(g) => set_general(g, i, c, heights, weights),
        Surface::Uniform(u, general) => {
            let slot = u.grid().real_slots()[i];
            match u {
                UpsSurface::Functional(f) => f.blocks_mut()[slot] = heights,
                UpsSurface::Parametric(p) => p.blocks_mut()[slot] = c.points,
                UpsSurface::Rational(r) => {
                    r.blocks_mut()[slot] = std::array::from_fn(|j| Weighted {
                        point: c.points[j],
                        weight: weights[j],
                    })
                }
            }
            match general.get_mut() {
                Some(g) => set_general(g, i, c, heights, weights),
                None => Ok(()),
            }
        }
    }
}

fn set_general(
    g: &mut PsSurface,
    i: usize,
    c: &VertexControl,
    heights: [f64; 3],
    weights: [f64; 3],
) -> Result<(), String> {
    match g {
        PsSurface::Functional(f) => f.set_coefficients(i, heights),
        PsSurface::Parametric(p) => p.set_coefficients(i, c.points),
        PsSurface::Rational(n) => n.set_vertex(i, c.points, weights),
    }
    .map_err(|e| e.to_string())
}
