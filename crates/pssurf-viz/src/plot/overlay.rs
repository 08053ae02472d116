//! Overlay lines drawn over a surface: the triangulation, the PS refinement, piece outlines,
//! the boundary and the control net, sampled on the surface. They are grouped by overlay
//! cell (a triangle of Δ for the PS kinds, a piece otherwise) so that a local edit redraws
//! only the cells it touches.

use nalgebra::{Point2, Vector3};
use pssurf::surface::{
    ControlId, ControlNet, Cursor, ParametricSurface, PiecewiseSurface, Surface,
};

use super::{Overlays, Polyline};

/// The overlay lines of a surface, sampled finely enough for `level`: those of every cell
/// ([`cell_overlay`]), then the control net ([`control_net_overlay`]).
pub fn overlay_lines(surface: &Surface, overlays: &Overlays, level: u32) -> Vec<Polyline> {
    let mut out: Vec<Polyline> = (0..overlay_cells(surface))
        .flat_map(|t| cell_overlay(surface, overlays, level, t))
        .collect();
    if overlays.control {
        out.extend(control_net_overlay(surface));
    }
    if overlays.combs {
        out.extend(comb_overlay(surface));
    }
    out
}

/// Samples per boundary side of a comb.
const COMB_TEETH: usize = 60;

/// The curvature combs of the boundary sides: each tooth a short segment, and the envelope
/// of the tips (pssurf::interrogate::comb); the longest tooth a tenth of the surface's size.
pub fn comb_overlay(surface: &Surface) -> Vec<Polyline> {
    use pssurf::interrogate::comb::{boundary_combs, comb_scale_for};
    let unit = boundary_combs(surface, COMB_TEETH, 1.0);
    // The diagonal of the bounding box of the boundary points.
    let (lo, hi) = unit.iter().flatten().fold(
        (
            nalgebra::Vector3::repeat(f64::INFINITY),
            nalgebra::Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), t| (lo.inf(&t.point), hi.sup(&t.point)),
    );
    let size = (hi - lo).norm().max(1e-300);
    let scale = comb_scale_for(&unit, 0.1 * size);
    let mut out = Vec::new();
    for side in boundary_combs(surface, COMB_TEETH, scale) {
        for t in &side {
            out.push(Polyline {
                points: vec![t.point, t.tip],
                color: [120, 120, 200],
                thickness: 1,
            });
        }
        out.push(Polyline {
            points: side.iter().map(|t| t.tip).collect(),
            color: [30, 30, 140],
            thickness: 2,
        });
    }
    out
}

/// The number of overlay cells: the triangles of Δ for the PS kinds (each holding the six
/// pieces of its split), every piece for other kinds.
pub fn overlay_cells(surface: &Surface) -> usize {
    match surface.ps_basis() {
        Some(b) => b.triangulation().triangle_count(),
        None => surface.piece_count(),
    }
}

/// The overlay cell that holds piece `k` (see [`overlay_cells`]).
pub fn cell_of_piece(surface: &Surface, k: usize) -> usize {
    match surface.ps_basis() {
        Some(_) => k / 6,
        None => k,
    }
}

/// The pieces of overlay cell `t` (see [`overlay_cells`]).
pub fn cell_pieces(surface: &Surface, t: usize) -> std::ops::Range<usize> {
    match surface.ps_basis() {
        Some(_) => 6 * t..6 * t + 6,
        None => t..t + 1,
    }
}

/// The lines drawn over overlay cell `t`. For the PS kinds: its triangulation edges (an
/// interior edge by the one of its two triangles whose first vertex has the smaller index),
/// its boundary edges, its PS split lines; for other kinds the outline of the piece. They
/// depend only on the surface over the cell, so a local edit changes only the lines of the
/// cells it touches; how many lines there are depends only on the structure and `overlays`.
pub fn cell_overlay(surface: &Surface, overlays: &Overlays, level: u32, t: usize) -> Vec<Polyline> {
    let steps = (2usize << level.min(6)).max(4);
    let along = |a: Point2<f64>, b: Point2<f64>, cursor: &mut Cursor| -> Vec<Vector3<f64>> {
        (0..=steps)
            .filter_map(|k| {
                let t = k as f64 / steps as f64;
                let p = Point2::from(a.coords * (1.0 - t) + b.coords * t);
                surface.jet_with(p, cursor).ok().map(|j| j.jet.value)
            })
            .collect()
    };
    let Some(basis) = surface.ps_basis() else {
        return piece_outline(surface, overlays, t, along);
    };
    let tri = basis.triangulation();
    let mut out = Vec::new();
    let mut c = Cursor(t);
    if overlays.wire || overlays.boundary {
        for i in 0..3 {
            let boundary = tri.is_boundary_edge(t, i);
            let (a, b) = tri.edge_vertices(t, i);
            let draw = (overlays.wire && (boundary || a < b)) || (overlays.boundary && boundary);
            if draw {
                out.push(edge_line(
                    along(tri.vertex(a), tri.vertex(b), &mut c),
                    boundary && overlays.boundary,
                ));
            }
        }
    }
    if overlays.refinement {
        let r = basis.refinement();
        let z = r.z(t);
        let v = tri.triangle(t);
        for k in 0..3 {
            for end in [tri.vertex(v[k]), r.edge_point(tri, t, k)] {
                out.push(Polyline {
                    points: along(z, end, &mut c),
                    color: [30, 60, 200],
                    thickness: 1,
                });
            }
        }
    }
    out
}

/// An edge of the wireframe, heavy when it is drawn as boundary.
fn edge_line(points: Vec<Vector3<f64>>, heavy: bool) -> Polyline {
    Polyline {
        points,
        color: if heavy { [0, 0, 0] } else { [40, 40, 40] },
        thickness: if heavy { 2 } else { 1 },
    }
}

/// The outline of piece `k` of a surface without a triangulation (a single Bézier triangle:
/// every edge is boundary).
fn piece_outline(
    surface: &Surface,
    overlays: &Overlays,
    k: usize,
    along: impl Fn(Point2<f64>, Point2<f64>, &mut Cursor) -> Vec<Vector3<f64>>,
) -> Vec<Polyline> {
    if !(overlays.wire || overlays.boundary) {
        return Vec::new();
    }
    let corners = surface.piece_shape(k).corners();
    let mut c = Cursor::default();
    (0..corners.len())
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            edge_line(along(a, b, &mut c), overlays.boundary)
        })
        .collect()
}

/// The colour of control-net lines.
const CONTROL_COLOR: [u8; 3] = [230, 120, 0];

/// The control net as polylines ([`ControlNet::control_polylines`]).
pub fn control_net_overlay(surface: &Surface) -> Vec<Polyline> {
    surface
        .control_polylines()
        .iter()
        .map(|line| Polyline {
            points: line
                .iter()
                .map(|&id| surface.control_point(id).expect("id of the net").position)
                .collect(),
            color: CONTROL_COLOR,
            thickness: 1,
        })
        .collect()
}

/// The control group of control point `id` (a PS vertex's control triangle) as a closed
/// polyline; a single point for a group of one.
pub fn control_overlay(surface: &Surface, id: ControlId) -> Polyline {
    let group = surface.control_group(id);
    let mut points: Vec<Vector3<f64>> = group
        .clone()
        .map(|i| {
            surface
                .control_point(ControlId(i))
                .expect("id in range")
                .position
        })
        .collect();
    if points.len() > 1 {
        points.push(points[0]);
    }
    Polyline {
        points,
        color: CONTROL_COLOR,
        thickness: 1,
    }
}
