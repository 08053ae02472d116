//! How a mesh object is drawn (issue 20, part 6): the refined mesh with its vertex normals (so
//! zebra stripes and shading read the same as on a surface), coloured in a curvature plot by
//! the discrete curvatures per vertex, with its edges and its control mesh as overlays.

use pssurf::interrogate::{CurvatureQuantity, PrincipalCurvatures};
use pssurf::subdivision::Mesh;

use crate::display::{
    DisplaySettings, EDGE_COLOR, GpuVertex, LineVertex, MeshLayout, ObjectMesh, Placement, ViewMode,
};
use crate::scene::{DiscreteCurvature, MeshShape, SceneObject};

/// The colour of the control mesh's edges (the control-net colour of surfaces).
pub const CONTROL_MESH_COLOR: [u8; 4] = [230, 120, 0, 255];

/// The drawable form of a mesh object. It has no parameters: `uvs` stays empty, which is how
/// picking tells a mesh from a surface.
pub fn mesh_object_mesh(o: &SceneObject, m: &MeshShape, settings: &DisplaySettings) -> ObjectMesh {
    let placement = Placement::of(o);
    let color = o.material.color();
    let vertices: Vec<GpuVertex> = (m.refined.positions.iter())
        .zip(&m.normals)
        .map(|(p, n)| placement.vertex(p, n, color))
        .collect();
    let indices: Vec<u32> = m.refined.triangles.iter().flatten().copied().collect();
    let values = match settings.mode {
        ViewMode::Curvature(q) => match &m.curvature {
            Ok(c) => discrete_quantity(c, q),
            Err(_) => vec![f64::NAN; vertices.len()],
        },
        _ => Vec::new(),
    };
    let mut lines = Vec::new();
    if settings.edges_shown() {
        edge_lines(&m.refined, &placement, EDGE_COLOR, &mut lines);
    }
    if settings.overlays.control && m.recipe.times > 0 {
        edge_lines(
            &m.recipe.control,
            &placement,
            CONTROL_MESH_COLOR,
            &mut lines,
        );
    }
    ObjectMesh {
        vertices,
        indices,
        uvs: Vec::new(),
        layout: MeshLayout {
            level: 0,
            kind: None,
            cell_lines: vec![0, lines.len()],
            control_lines: None,
        },
        lines,
        values,
    }
}

/// A curvature quantity per vertex from the discrete Gaussian and mean curvatures
/// (`PrincipalCurvatures::from_gaussian_mean`). NaN where they are (boundary).
pub fn discrete_quantity(c: &DiscreteCurvature, q: CurvatureQuantity) -> Vec<f64> {
    (c.gaussian.iter().zip(&c.mean))
        .map(|(&k, &h)| PrincipalCurvatures::from_gaussian_mean(k, h).get(q))
        .collect()
}

/// Appends every edge of a mesh once, as line segments in `color`.
fn edge_lines(mesh: &Mesh, placement: &Placement, color: [u8; 4], out: &mut Vec<LineVertex>) {
    let mut edges: Vec<(u32, u32)> = (mesh.triangles.iter())
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    out.reserve(2 * edges.len());
    for (a, b) in edges {
        for v in [a, b] {
            out.push(LineVertex {
                position: placement.point(&mesh.positions[v as usize]),
                color,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// κ1, κ2 from K and H are the roots of κ² − 2Hκ + K = 0, so they give K and H back.
    #[test]
    fn principal_curvatures_give_k_and_h_back() {
        let c = DiscreteCurvature {
            gaussian: vec![2.0, -3.0, 0.25, 1.0],
            mean: vec![1.5, 0.5, -1.0, 1.0],
        };
        let k1 = discrete_quantity(&c, CurvatureQuantity::K1);
        let k2 = discrete_quantity(&c, CurvatureQuantity::K2);
        let abs = discrete_quantity(&c, CurvatureQuantity::Absolute);
        for i in 0..4 {
            assert!(k1[i] >= k2[i]);
            assert!((k1[i] * k2[i] - c.gaussian[i]).abs() < 1e-14);
            assert!((0.5 * (k1[i] + k2[i]) - c.mean[i]).abs() < 1e-15);
            assert!((abs[i] - k1[i].abs() - k2[i].abs()).abs() < 1e-15);
        }
    }
}
