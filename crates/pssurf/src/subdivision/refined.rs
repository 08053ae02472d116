//! A control mesh with a subdivision scheme applied a number of times (issue 20, part 6): what
//! the application shows as a mesh object and a scene file records, the refined mesh being
//! recomputed from the control mesh, never stored.

use nalgebra::Vector3;

use super::mesh::{MAX_TRIANGLES, Mesh, MeshError};
use super::surfaces::SurfaceScheme;

/// A control mesh and the subdivision that refines it.
#[derive(Clone, Debug, PartialEq)]
pub struct RefinedMesh {
    /// The mesh as read (any triangle soup with valid indices and finite positions; the
    /// schemes need it manifold, see [`Mesh::topology`]).
    pub control: Mesh,
    /// The scheme.
    pub scheme: SurfaceScheme,
    /// How many steps of it (0: the control mesh itself).
    pub times: u32,
}

impl RefinedMesh {
    /// The control mesh itself, not subdivided.
    pub fn new(control: Mesh) -> Self {
        RefinedMesh {
            control,
            scheme: SurfaceScheme::Loop,
            times: 0,
        }
    }

    /// The number of triangles after the steps (each multiplies them by 4, or by 3 for √3),
    /// as a float so that absurd requests do not overflow.
    pub fn triangles_after(&self) -> f64 {
        (self.scheme).triangles_after(self.control.triangles.len(), self.times)
    }

    /// The refined mesh: the control mesh after `times` steps of the scheme. The control mesh
    /// is checked first ([`Mesh::check`]); the schemes also need it manifold and consistently
    /// oriented, and the result within [`MAX_TRIANGLES`].
    pub fn refine(&self) -> Result<Mesh, MeshError> {
        self.control.check()?;
        let after = self.triangles_after();
        if after > MAX_TRIANGLES as f64 {
            return Err(MeshError::TooLarge(after.min(usize::MAX as f64) as usize));
        }
        let mut mesh = self.control.clone();
        for _ in 0..self.times {
            mesh = self.scheme.step(&mesh)?;
        }
        Ok(mesh)
    }
}

impl Mesh {
    /// Checks what every use of a mesh needs, without the manifold checks of
    /// [`Mesh::topology`]: at least one triangle and at most [`MAX_TRIANGLES`], every index
    /// naming a vertex, every coordinate finite and within ±`MAX_COORDINATE`.
    pub fn check(&self) -> Result<(), MeshError> {
        let t = self.triangles.len();
        if t == 0 {
            return Err(MeshError::Empty);
        }
        if t > MAX_TRIANGLES {
            return Err(MeshError::TooLarge(t));
        }
        if let Some(v) = self.positions.iter().position(|p| {
            !p.iter()
                .all(|c| c.is_finite() && c.abs() <= crate::limits::MAX_COORDINATE)
        }) {
            return Err(MeshError::NotFinite(v));
        }
        let n = self.positions.len();
        for (k, tri) in self.triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
                return Err(MeshError::BadIndex {
                    triangle: k,
                    vertex: v,
                    count: n,
                });
            }
        }
        Ok(())
    }

    /// Unit vertex normals: the sum of the (area-weighted) normals of the triangles around
    /// each vertex, normalised; zero where they cancel or no triangle uses the vertex.
    /// Indices must be valid ([`Mesh::check`]).
    pub fn vertex_normals(&self) -> Vec<Vector3<f64>> {
        let mut n = vec![Vector3::zeros(); self.positions.len()];
        for t in &self.triangles {
            let [a, b, c] = t.map(|v| self.positions[v as usize]);
            let f = (b - a).cross(&(c - a));
            for &v in t {
                n[v as usize] += f;
            }
        }
        n.into_iter()
            .map(|v| v.try_normalize(0.0).unwrap_or_default())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refining_counts_and_checks() {
        let octahedron = RefinedMesh {
            control: Mesh::octahedron(),
            scheme: SurfaceScheme::Loop,
            times: 2,
        };
        assert_eq!(octahedron.triangles_after(), 128.0);
        let m = octahedron.refine().unwrap();
        assert_eq!(m.triangles.len(), 128);
        // A closed mesh: V − E + F = 2 with E = 3F/2.
        assert_eq!(m.positions.len(), 2 + 128 / 2);
        let sqrt3 = RefinedMesh {
            scheme: SurfaceScheme::Sqrt3,
            ..octahedron.clone()
        };
        assert_eq!(sqrt3.refine().unwrap().triangles.len(), 72);
        // No steps: the control mesh itself, even when it is not manifold.
        let mut fin = Mesh::octahedron();
        fin.triangles.push([0, 2, 5]);
        assert!(fin.topology().is_err());
        assert_eq!(RefinedMesh::new(fin.clone()).refine().unwrap(), fin);
        // Absurd requests and bad meshes are errors, not panics.
        let absurd = RefinedMesh {
            times: u32::MAX,
            ..octahedron.clone()
        };
        assert!(matches!(absurd.refine(), Err(MeshError::TooLarge(_))));
        let mut bad = Mesh::octahedron();
        bad.triangles.push([0, 1, 9]);
        assert!(matches!(bad.check(), Err(MeshError::BadIndex { .. })));
        bad.triangles.pop();
        bad.positions[3].x = f64::NAN;
        assert_eq!(bad.check(), Err(MeshError::NotFinite(3)));
        assert_eq!(Mesh::default().check(), Err(MeshError::Empty));
    }

    #[test]
    fn vertex_normals_of_the_octahedron_point_outwards() {
        let m = Mesh::octahedron();
        for (p, n) in m.positions.iter().zip(m.vertex_normals()) {
            assert!((n - p).norm() < 1e-15, "{n} at {p}");
        }
    }
}
