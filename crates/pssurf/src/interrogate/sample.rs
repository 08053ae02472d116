//! Sampling a piecewise surface patch by patch: a triangle mesh with exact points, normals
//! and curvature at its vertices, for plots and export.

use nalgebra::{Point2, Vector3};
use rayon::prelude::*;

use super::curvature::{CurvatureQuantity, FundamentalForms, PrincipalCurvatures};
use crate::mesh::TriMesh;
use crate::surface::{PieceFrame, PieceKind, PiecewiseSurface};

/// A surface sampled piece by piece.
///
/// Each piece is covered by a regular grid of n = 2^level steps per side: a triangular piece
/// (a PS sub-triangle) gets (n + 1)(n + 2)/2 vertices and n² triangles, a rectangular piece
/// (n + 1)² vertices and 2n² triangles. Vertices on the edges between pieces appear once per
/// piece, each with its own piece's curvature: a C¹ PS surface has continuous points and normals there, but its
/// curvature jumps, and the plots must show it.
#[derive(Clone, Debug, Default)]
pub struct SampledSurface {
    /// Points, unit normals (zero at singular points), parameters and triangles. Triangles
    /// are counter-clockwise in the parameter domain, so they face along the normal
    /// s_u × s_v.
    pub mesh: TriMesh,
    /// The piece each vertex was evaluated on.
    pub patch: Vec<u32>,
    /// The curvature values at each vertex (NaN at singular points); empty when not
    /// requested.
    pub curvature: Vec<PrincipalCurvatures>,
}

/// The number of grid steps per side of a piece at `level`.
fn steps(level: u32) -> usize {
    1usize << level
}

/// The vertex count of one piece of shape `kind` sampled at `level`.
pub fn vertices_per_piece(kind: PieceKind, level: u32) -> usize {
    let n = steps(level);
    match kind {
        PieceKind::Triangle => (n + 1) * (n + 2) / 2,
        PieceKind::Rectangle => (n + 1) * (n + 1),
    }
}

/// The triangle count of one piece of shape `kind` sampled at `level`.
pub fn triangles_per_piece(kind: PieceKind, level: u32) -> usize {
    let n = steps(level);
    match kind {
        PieceKind::Triangle => n * n,
        PieceKind::Rectangle => 2 * n * n,
    }
}

/// The vertex and triangle counts of a sampled surface (see [`SampledSurface`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleCounts {
    /// Mesh vertices (shared edges counted once per piece).
    pub vertices: u64,
    /// Mesh triangles.
    pub triangles: u64,
}

/// The counts of sampling `pieces` pieces of shape `kind` at `level`, without allocating;
/// `None` when they do not fit in 64 bits. Commands check these against their memory budget
/// before calling [`sample_patches`].
pub fn sample_counts(kind: PieceKind, pieces: usize, level: u32) -> Option<SampleCounts> {
    let n = 1u128.checked_shl(level).filter(|&n| n <= 1 << 40)?;
    let (v, t) = match kind {
        PieceKind::Triangle => ((n + 1) * (n + 2) / 2, n * n),
        PieceKind::Rectangle => ((n + 1) * (n + 1), 2 * n * n),
    };
    let p = pieces as u128;
    Some(SampleCounts {
        vertices: u64::try_from(v.checked_mul(p)?).ok()?,
        triangles: u64::try_from(t.checked_mul(p)?).ok()?,
    })
}

/// Sample `surface` at `level` (see [`SampledSurface`]), with curvature when asked. Runs in
/// parallel over the pieces.
///
/// # Panics
/// If the mesh would have more than 2³² vertices (level too high for the surface).
pub fn sample_patches<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    level: u32,
    with_curvature: bool,
) -> SampledSurface {
    sample_with(surface, level, with_curvature, surface.piece_count(), |j| j)
}

/// Samples only the listed pieces, in that order, exactly as [`sample_patches`] samples them:
/// slot j of the result (its vertices `j·m .. (j+1)·m` with m = [`vertices_per_piece`], its
/// triangles `j·t .. (j+1)·t` with t = [`triangles_per_piece`], indices relative to the
/// result) is piece `pieces[j]`. After an edit of control points (which changes only the
/// pieces of their support, [`crate::surface::ControlNet::support`]) this re-tessellates just
/// the pieces that changed.
///
/// # Panics
/// If a piece index is out of range, or as [`sample_patches`].
pub fn sample_pieces<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    level: u32,
    with_curvature: bool,
    pieces: &[usize],
) -> SampledSurface {
    let count = surface.piece_count();
    assert!(
        pieces.iter().all(|&k| k < count),
        "piece index out of range ({count} pieces)"
    );
    sample_with(surface, level, with_curvature, pieces.len(), |j| pieces[j])
}

/// Samples `slots` pieces, slot j being piece `piece(j)`.
fn sample_with<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    level: u32,
    with_curvature: bool,
    slots: usize,
    piece: impl Fn(usize) -> usize + Sync,
) -> SampledSurface {
    let n = steps(level);
    let kind = surface.piece_kind();
    let per_vertex = vertices_per_piece(kind, level);
    let per_triangle = triangles_per_piece(kind, level);
    let total = slots * per_vertex;
    assert!(
        total <= u32::MAX as usize,
        "too many vertices ({total}) for 32-bit indices"
    );

    let mut out = SampledSurface {
        mesh: TriMesh {
            positions: vec![Vector3::zeros(); total],
            normals: vec![Vector3::zeros(); total],
            uvs: vec![Point2::origin(); total],
            triangles: vec![[0; 3]; slots * per_triangle],
        },
        patch: vec![0; total],
        curvature: if with_curvature {
            vec![PrincipalCurvatures::UNDEFINED; total]
        } else {
            Vec::new()
        },
    };
    let local = match kind {
        PieceKind::Triangle => grid_triangles(n),
        PieceKind::Rectangle => rectangle_triangles(n),
    };
    // One optional curvature slice per slot, so that both cases share one parallel loop.
    let curvature: Vec<Option<&mut [PrincipalCurvatures]>> = if with_curvature {
        out.curvature.chunks_mut(per_vertex).map(Some).collect()
    } else {
        (0..slots).map(|_| None).collect()
    };
    let mesh = &mut out.mesh;
    mesh.positions
        .par_chunks_mut(per_vertex)
        .zip(mesh.normals.par_chunks_mut(per_vertex))
        .zip(mesh.uvs.par_chunks_mut(per_vertex))
        .zip(out.patch.par_chunks_mut(per_vertex))
        .zip(mesh.triangles.par_chunks_mut(per_triangle))
        .zip(curvature)
        .enumerate()
        .for_each(
            |(j, (((((positions, normals), uvs), patch), triangles), curvature))| {
                let chunk = PatchChunk {
                    positions,
                    normals,
                    uvs,
                    patch,
                    triangles,
                    curvature,
                };
                fill_patch(surface, piece(j), n, &local, (j * per_vertex) as u32, chunk)
            },
        );
    out
}

/// The part of the output arrays that belongs to one piece.
struct PatchChunk<'a> {
    positions: &'a mut [Vector3<f64>],
    normals: &'a mut [Vector3<f64>],
    uvs: &'a mut [Point2<f64>],
    patch: &'a mut [u32],
    triangles: &'a mut [[u32; 3]],
    curvature: Option<&'a mut [PrincipalCurvatures]>,
}

/// Evaluates piece `k` on its grid of `n` steps per side; its first vertex has index `base`.
fn fill_patch<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    k: usize,
    n: usize,
    local: &[[u32; 3]],
    base: u32,
    mut out: PatchChunk<'_>,
) {
    let frame = surface
        .piece_shape(k)
        .frame()
        .expect("pieces of a valid surface are non-degenerate");
    let inv = 1.0 / n as f64;
    let mut v = 0;
    let mut put = |at: crate::surface::PiecePoint| {
        let jet = surface.piece_jet(k, &at);
        out.positions[v] = jet.value;
        out.uvs[v] = at.uv;
        out.patch[v] = k as u32;
        if let Some(curv) = out.curvature.as_deref_mut() {
            (curv[v], out.normals[v]) = PrincipalCurvatures::from_jet(&jet)
                .unwrap_or((PrincipalCurvatures::UNDEFINED, Vector3::zeros()));
        } else {
            out.normals[v] =
                FundamentalForms::from_jet(&jet).map_or(Vector3::zeros(), |f| f.normal);
        }
        v += 1;
    };
    let flip = match frame {
        PieceFrame::Triangle { triangle, .. } => {
            for j in 0..=n {
                for i in 0..=n - j {
                    put(frame.at_bary([(n - i - j) as f64 * inv, i as f64 * inv, j as f64 * inv]));
                }
            }
            triangle.det() < 0.0
        }
        PieceFrame::Rectangle { .. } => {
            for j in 0..=n {
                for i in 0..=n {
                    put(frame.at_st(i as f64 * inv, j as f64 * inv));
                }
            }
            false
        }
    };
    for (t, l) in out.triangles.iter_mut().zip(local) {
        *t = if flip {
            [base + l[0], base + l[2], base + l[1]]
        } else {
            [base + l[0], base + l[1], base + l[2]]
        };
    }
}

/// The triangles of the regular grid with n steps on the reference triangle, as local vertex
/// indices (rows of constant j, i increasing), counter-clockwise in (i, j).
fn grid_triangles(n: usize) -> Vec<[u32; 3]> {
    let row_start = |j: usize| (j * (2 * n + 3 - j) / 2) as u32;
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        let (r0, r1) = (row_start(j), row_start(j + 1));
        for i in 0..n - j {
            let (a, b, c) = (r0 + i as u32, r0 + i as u32 + 1, r1 + i as u32);
            out.push([a, b, c]);
            if i + 1 < n - j {
                out.push([b, r1 + i as u32 + 1, c]);
            }
        }
    }
    out
}

/// The triangles of the regular (n + 1) × (n + 1) grid on the unit square (rows of constant
/// j, i increasing), two per cell, counter-clockwise in (i, j).
fn rectangle_triangles(n: usize) -> Vec<[u32; 3]> {
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut out = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            out.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            out.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    out
}

impl SampledSurface {
    /// Appends `other` (another surface's samples) as more vertices and triangles, for
    /// pictures of several surfaces; piece numbers keep their own surface's meaning.
    pub fn append(&mut self, other: SampledSurface) {
        let offset = self.mesh.positions.len() as u32;
        self.mesh.positions.extend(other.mesh.positions);
        self.mesh.normals.extend(other.mesh.normals);
        self.mesh.uvs.extend(other.mesh.uvs);
        self.mesh
            .triangles
            .extend(other.mesh.triangles.iter().map(|t| t.map(|k| k + offset)));
        self.patch.extend(other.patch);
        self.curvature.extend(other.curvature);
    }

    /// One curvature quantity per vertex (NaN at singular points).
    ///
    /// # Panics
    /// If the surface was sampled without curvature.
    pub fn quantity(&self, q: CurvatureQuantity) -> Vec<f64> {
        assert_eq!(
            self.curvature.len(),
            self.mesh.positions.len(),
            "sampled without curvature"
        );
        self.curvature.par_iter().map(|c| c.get(q)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_triangles_cover_the_reference_triangle_once() {
        for n in [1usize, 2, 3, 8] {
            let t = grid_triangles(n);
            assert_eq!(t.len(), n * n);
            // Vertex (i, j) of local index v; every triangle has positive area 1/2 in (i, j).
            let mut ij = Vec::new();
            for j in 0..=n {
                for i in 0..=n - j {
                    ij.push((i as f64, j as f64));
                }
            }
            for tri in &t {
                let [a, b, c] = tri.map(|k| ij[k as usize]);
                let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
                assert!((area - 1.0).abs() < 1e-12, "n {n}: {tri:?}");
            }
        }
    }
}
