//! Triangle meshes of surfaces: tessellators write into a caller-supplied [`MeshBuilder`]
//! (as lyon's geometry builders), so a renderer, an exporter or a plain [`TriMesh`] can
//! receive the output without copying.

use nalgebra::{Point2, Vector3};

/// One vertex of a tessellation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshVertex {
    /// The point on the surface.
    pub position: Vector3<f64>,
    /// The unit normal (zero where it is undefined, at a singular point).
    pub normal: Vector3<f64>,
    /// The parameter (domain point) of the vertex.
    pub uv: Point2<f64>,
}

/// Receives the vertices and triangles of a tessellation.
pub trait MeshBuilder {
    /// Called once first with the final counts, to allocate.
    fn reserve(&mut self, _vertices: usize, _triangles: usize) {}
    /// Adds a vertex and returns its index.
    fn add_vertex(&mut self, v: MeshVertex) -> u32;
    /// Adds a counter-clockwise (in the parameter domain) triangle of vertex indices.
    fn add_triangle(&mut self, a: u32, b: u32, c: u32);
}

/// An indexed triangle mesh with normals and parameters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<Vector3<f64>>,
    /// Unit vertex normals (zero where undefined).
    pub normals: Vec<Vector3<f64>>,
    /// Vertex parameters.
    pub uvs: Vec<Point2<f64>>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl MeshBuilder for TriMesh {
    fn reserve(&mut self, vertices: usize, triangles: usize) {
        self.positions.reserve(vertices);
        self.normals.reserve(vertices);
        self.uvs.reserve(vertices);
        self.triangles.reserve(triangles);
    }
    fn add_vertex(&mut self, v: MeshVertex) -> u32 {
        self.positions.push(v.position);
        self.normals.push(v.normal);
        self.uvs.push(v.uv);
        (self.positions.len() - 1) as u32
    }
    fn add_triangle(&mut self, a: u32, b: u32, c: u32) {
        self.triangles.push([a, b, c]);
    }
}

/// The unit normal of the plane through a, b, c with orientation (b − a) × (c − a), or zero
/// when the three points are (numerically) collinear.
pub fn plane_normal(a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>) -> Vector3<f64> {
    let n = (b - a).cross(&(c - a));
    let size = (b - a).norm() * (c - a).norm();
    if n.norm() > 1e-14 * size && size > 0.0 {
        n.normalize()
    } else {
        Vector3::zeros()
    }
}
