//! The normalized PS B-spline basis {B_i^j} of S_2^1(Δ*) (thesis section 2.3.2, Dierckx).

use nalgebra::{Point2, Vector2};
use rayon::prelude::*;

use super::PsError;
use super::net::{self, NET_LEN, NetStencil, SUB_ORDINATES};
use super::ps_triangles::{PsTriangleChoice, ps_triangles};
use super::refinement::{PsRefinement, SplitRule};
use crate::geometry::{Bary, BaryMap, Triangle2, midpoint};
use crate::triangulation::{INSIDE_TOLERANCE, Location, Triangulation};
use crate::vector::Vector;

/// The PS B-spline basis on a triangulation: the triangulation Δ, its PS-refinement Δ*, and
/// the PS-triangle t_i(Q_i1, Q_i2, Q_i3) of every vertex, which fixes the triplets
/// (α_ij, β_ij, γ_ij) (2.37)–(2.40) and with them the basis functions B_i^j.
///
/// With PS-points inside the PS-triangles the basis is a convex partition of unity
/// (2.32)–(2.33) and B_i^j vanishes outside the molecule M_i.
#[derive(Clone, Debug)]
pub struct PsBasis {
    tri: Triangulation,
    refinement: PsRefinement,
    ps_tris: Vec<Triangle2>,
    ps_maps: Vec<BaryMap>,
    /// Per triangle of Δ, what evaluation needs, precomputed so that locating a point in
    /// Δ* takes no division.
    geom: Vec<EvalGeom>,
}

/// The per-triangle data of the evaluation hot path: the barycentric map about V_0
/// (τ_1 = g_1·(p − V_0), τ_2 = g_2·(p − V_0), τ_0 = 1 − τ_1 − τ_2), Z's coordinates a_i and
/// their inverses, and λ_c, 1/λ_c, 1/(1 − λ_c) of the edge points.
#[derive(Clone, Copy, Debug, PartialEq)]
struct EvalGeom {
    origin: [f64; 2],
    /// ∇τ_0, ∇τ_1, ∇τ_2.
    g: [[f64; 2]; 3],
    a: [f64; 3],
    inv_a: [f64; 3],
    lambda: [f64; 3],
    inv_lambda: [f64; 3],
    inv_rest: [f64; 3],
}

impl EvalGeom {
    fn new(tri: &Triangulation, refinement: &PsRefinement, t: usize) -> Self {
        let m = tri
            .triangle_geometry(t)
            .bary_map()
            .expect("validated triangle");
        let a = refinement.z_bary(t);
        let l = refinement.lambda(t);
        EvalGeom {
            origin: [m.origin.x, m.origin.y],
            g: [
                [-m.g[1].x - m.g[2].x, -m.g[1].y - m.g[2].y],
                [m.g[1].x, m.g[1].y],
                [m.g[2].x, m.g[2].y],
            ],
            a,
            inv_a: a.map(|x| 1.0 / x),
            lambda: l,
            inv_lambda: l.map(|x| 1.0 / x),
            inv_rest: l.map(|x| 1.0 / (1.0 - x)),
        }
    }

    /// Barycentric coordinates of p.
    #[inline(always)]
    fn bary(&self, p: Point2<f64>) -> Bary {
        let (x, y) = (p.x - self.origin[0], p.y - self.origin[1]);
        let t1 = self.g[1][0] * x + self.g[1][1] * y;
        let t2 = self.g[2][0] * x + self.g[2][1] * y;
        [1.0 - t1 - t2, t1, t2]
    }

    /// Gradient of barycentric coordinate i.
    #[inline(always)]
    fn grad(&self, i: usize) -> Vector2<f64> {
        Vector2::new(self.g[i][0], self.g[i][1])
    }
}

/// Steps of the evaluation walk before falling back to the triangulation's locator.
const MAX_WALK: usize = 64;

/// Where a domain point lies in Δ*: the triangle of Δ, which of its six sub-triangles, the
/// barycentric coordinates there and the sub-triangle's unit directions d_x, d_y (2.18)–(2.19).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubLocation {
    /// The triangle of Δ.
    pub triangle: usize,
    /// The sub-triangle 0..6: (V_c, R_c, Z) is 2c, (R_c, V_{c+1}, Z) is 2c + 1.
    pub sub: usize,
    /// Barycentric coordinates in the sub-triangle.
    pub bary: Bary,
    /// ∂(bary)/∂x.
    pub dx: Bary,
    /// ∂(bary)/∂y.
    pub dy: Bary,
}

impl PsBasis {
    /// The basis with split points by `rule` and PS-triangles by `choice`.
    pub fn new(
        tri: Triangulation,
        rule: SplitRule,
        choice: &PsTriangleChoice,
    ) -> Result<Self, PsError> {
        let refinement = PsRefinement::new(&tri, rule)?;
        Self::with_refinement(tri, refinement, choice)
    }

    /// The default basis: incentre split and optimal PS-triangles.
    pub fn optimal(tri: Triangulation) -> Result<Self, PsError> {
        Self::new(tri, SplitRule::Incenter, &PsTriangleChoice::Optimal)
    }

    /// The basis on a given refinement.
    pub fn with_refinement(
        tri: Triangulation,
        refinement: PsRefinement,
        choice: &PsTriangleChoice,
    ) -> Result<Self, PsError> {
        let ps_tris = ps_triangles(&tri, &refinement, choice)?;
        // Each PS-triangle's map about its vertex V_i: τ = α_i + β_i (x − x_i) + γ_i (y − y_i).
        let ps_maps = ps_tris
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let vi = tri.vertex(i);
                t.bary_map()
                    .map(|m| m.with_origin(vi, t.bary(vi)))
                    .ok_or(PsError::DegeneratePsTriangle { vertex: i })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let geom = (0..tri.triangle_count())
            .into_par_iter()
            .with_min_len(1024)
            .map(|t| EvalGeom::new(&tri, &refinement, t))
            .collect();
        Ok(PsBasis {
            tri,
            refinement,
            ps_tris,
            ps_maps,
            geom,
        })
    }

    /// The basis on the same triangulation and refinement with the PS-triangles chosen by
    /// `choice` (e.g. the optimal ones for a basis built with circumscribed ones).
    pub fn with_ps_triangles(&self, choice: &PsTriangleChoice) -> Result<Self, PsError> {
        Self::with_refinement(self.tri.clone(), self.refinement.clone(), choice)
    }

    /// The triangulation Δ.
    pub fn triangulation(&self) -> &Triangulation {
        &self.tri
    }

    /// The PS-refinement Δ*.
    pub fn refinement(&self) -> &PsRefinement {
        &self.refinement
    }

    /// The number of basis functions, 3n = dim S_2^1(Δ*).
    pub fn dimension(&self) -> usize {
        3 * self.tri.vertex_count()
    }

    /// The PS-triangle t_i of vertex i (counter-clockwise).
    pub fn ps_triangle(&self, i: usize) -> &Triangle2 {
        &self.ps_tris[i]
    }

    /// All PS-triangles.
    pub fn ps_triangles(&self) -> &[Triangle2] {
        &self.ps_tris
    }

    /// The PS-triangle points Q_i1, Q_i2, Q_i3 (Definition 2.21): the (x, y) of the control
    /// points of a functional PS-spline surface (Definition 2.23).
    pub fn control_xy(&self, i: usize) -> [Point2<f64>; 3] {
        self.ps_tris[i].v
    }

    /// α_i: the barycentric coordinates of V_i w.r.t. t_i (2.37).
    pub fn alpha(&self, i: usize) -> [f64; 3] {
        self.ps_maps[i].c
    }

    /// β_i = ∂(barycentric coordinates w.r.t. t_i)/∂x (2.38).
    pub fn beta(&self, i: usize) -> [f64; 3] {
        self.ps_maps[i].dx()
    }

    /// γ_i = ∂(barycentric coordinates w.r.t. t_i)/∂y (2.39).
    pub fn gamma(&self, i: usize) -> [f64; 3] {
        self.ps_maps[i].dy()
    }

    /// The B-spline coefficients of the Hermite interpolant (2.42)–(2.45) at vertex i from
    /// the value f and the partial derivatives f_x, f_y there. Since the control triangle is
    /// the tangent plane at V_i (Property 2.3) and c_ij sits above Q_ij, the solution of the
    /// 3 × 3 system (2.45) is c_ij = f + f_x (X_ij − x_i) + f_y (Y_ij − y_i).
    pub fn hermite_coefficients<V: Vector>(&self, i: usize, f: V, fx: V, fy: V) -> [V; 3] {
        self.hermite_map(i)
            .map(|[one, dx, dy]| f * one + fx * dx + fy * dy)
    }

    /// The matrix of [`hermite_coefficients`](Self::hermite_coefficients): row j is
    /// (1, X_ij − x_i, Y_ij − y_i), so that c_ij = row_j · (f, f_x, f_y).
    pub fn hermite_map(&self, i: usize) -> [[f64; 3]; 3] {
        let vi = self.tri.vertex(i);
        self.ps_tris[i].v.map(|q| [1.0, q.x - vi.x, q.y - vi.y])
    }

    /// The conversion coefficients from control values to the 19 Bézier ordinates of
    /// triangle `t` ((2.54)–(2.60); see [`net`]).
    pub fn stencil(&self, t: usize) -> NetStencil {
        let v = self.tri.triangle(t);
        let rows = std::array::from_fn(|c| {
            let (vi, ends) = self.corner_edges(t, c);
            let map = &self.ps_maps[v[c]];
            let [u, v, w] = ends.map(|e| map.apply(midpoint(vi, e)));
            [map.c, u, v, w]
        });
        NetStencil {
            rows,
            lambda: self.refinement.lambda(t),
            z: self.refinement.z_bary(t),
        }
    }

    /// Corner c of triangle `t` and the far ends of the three edges of Δ* from it whose
    /// midpoints carry the net's ordinates next to it: R_c, R_{c−1} and Z (the order of
    /// [`NetStencil::rows`]).
    fn corner_edges(&self, t: usize, c: usize) -> (Point2<f64>, [Point2<f64>; 3]) {
        let vi = self.tri.vertex(self.tri.triangle(t)[c]);
        let ends = [
            self.refinement.edge_point(&self.tri, t, c),
            self.refinement.edge_point(&self.tri, t, (c + 2) % 3),
            self.refinement.z(t),
        ];
        (vi, ends)
    }

    /// The Bézier net of triangle `t` of the Hermite interpolant (2.30) with data `data(i)`
    /// at vertex i, straight from the data: the ordinates next to V_i lie on its tangent
    /// plane, f_i + ∇f_i · (P − V_i) at the domain points P = V_i and the midpoints of V_i R
    /// and V_i Z — what [`net`](Self::net) gives from the coefficients (2.45) on any
    /// PS-triangle, without them and their rounding.
    pub fn hermite_net<V: Vector>(
        &self,
        t: usize,
        data: impl Fn(usize) -> super::Hermite<V>,
    ) -> [V; NET_LEN] {
        let v = self.tri.triangle(t);
        let corners = std::array::from_fn(|c| {
            let (vi, ends) = self.corner_edges(t, c);
            let h = data(v[c]);
            // The tangent plane at the midpoint of V_i and each end.
            let [u, v, w] = ends.map(|e| {
                let half = 0.5 * (e - vi);
                h.value + h.dx * half.x + h.dy * half.y
            });
            [h.value, u, v, w]
        });
        net::complete_net(
            corners,
            self.refinement.lambda(t),
            self.refinement.z_bary(t),
        )
    }

    /// The Bézier net of triangle `t` for per-vertex control values.
    pub fn net<T: net::Combine>(&self, t: usize, ctrl: &[[T; 3]]) -> [T; NET_LEN] {
        self.net_with(t, |i| ctrl[i])
    }

    /// The Bézier net of triangle `t` with the control values of vertex i given by `ctrl(i)`
    /// (for control values not stored as one slice).
    pub fn net_with<T: net::Combine>(
        &self,
        t: usize,
        ctrl: impl Fn(usize) -> [T; 3],
    ) -> [T; NET_LEN] {
        let v = self.tri.triangle(t);
        self.stencil(t).apply(v.map(ctrl))
    }

    /// Where `p` lies in Δ*, walking from triangle `hint` (any triangle; a nearby one makes
    /// it fast), or `None` outside the domain.
    #[inline(always)]
    pub fn locate(&self, p: Point2<f64>, hint: usize) -> Option<SubLocation> {
        let mut t = hint.min(self.geom.len() - 1);
        for _ in 0..MAX_WALK {
            let tau = self.geom[t].bary(p);
            let (mut i, mut m) = (0, tau[0]);
            if tau[1] < m {
                (i, m) = (1, tau[1]);
            }
            if tau[2] < m {
                (i, m) = (2, tau[2]);
            }
            if m >= -INSIDE_TOLERANCE {
                return Some(self.sub_locate_in(t, tau));
            }
            match self.tri.neighbor(t, i) {
                Some(n) => t = n,
                None => break,
            }
        }
        self.locate_exhaustive(p)
    }

    /// The barycentric coordinates of `p` in triangle `t` of Δ, as [`PsBasis::locate`]
    /// computes them.
    #[inline]
    pub(crate) fn triangle_bary(&self, t: usize, p: Point2<f64>) -> Bary {
        self.geom[t].bary(p)
    }

    /// The walk left the domain or took too long: ask the triangulation's R-tree.
    #[cold]
    #[inline(never)]
    fn locate_exhaustive(&self, p: Point2<f64>) -> Option<SubLocation> {
        let loc = self.tri.locate_exhaustive(p)?;
        Some(self.sub_locate(loc))
    }

    /// Where `p` lies in Δ*, or for a point outside the domain by at most `max_distance`,
    /// where it lies in the extension of the nearest triangle's pieces (barycentric
    /// coordinates slightly negative).
    pub fn locate_near(&self, p: Point2<f64>, max_distance: f64) -> Option<SubLocation> {
        self.locate_any(p).or_else(|| {
            let (t, _) = self.tri.nearest_triangle(p, max_distance)?;
            Some(self.sub_locate_in(t, self.geom[t].bary(p)))
        })
    }

    /// Where `p` lies in Δ*, for a point unrelated to the previous one (starts from the
    /// triangulation's bucket grid).
    pub fn locate_any(&self, p: Point2<f64>) -> Option<SubLocation> {
        self.locate(p, self.tri.start_triangle(p))
    }

    /// Refines a location in Δ to the sub-triangle of Δ* containing the point.
    #[inline]
    pub fn sub_locate(&self, loc: Location) -> SubLocation {
        self.sub_locate_in(loc.triangle, loc.bary)
    }

    /// The sub-triangle of triangle `t` containing the point with barycentric coordinates τ,
    /// and the coordinates there. With ρ_i = τ_i / a_i, the point lies in the sector
    /// (V_e, V_{e+1}, Z) opposite the vertex with the smallest ρ (there μ_Z = min ρ); the
    /// segment Z R_e splits the sector into the two sub-triangles. Only multiplications by
    /// precomputed inverses are needed.
    #[inline(always)]
    fn sub_locate_in(&self, t: usize, tau: Bary) -> SubLocation {
        let g = &self.geom[t];
        let rho = [
            tau[0] * g.inv_a[0],
            tau[1] * g.inv_a[1],
            tau[2] * g.inv_a[2],
        ];
        // Branch-free selections: which sub-triangle a grid point falls in changes too often
        // for branch prediction.
        let k01 = if rho[1] < rho[0] { 1 } else { 0 };
        let k = if rho[2] < rho[k01] { 2 } else { k01 };
        const NEXT: [usize; 3] = [1, 2, 0];
        let e = NEXT[k];
        let e1 = NEXT[e];
        let mz = rho[k];
        let gz = g.grad(k) * g.inv_a[k];
        let me = tau[e] - g.a[e] * mz;
        let me1 = tau[e1] - g.a[e1] * mz;
        let ge = g.grad(e) - gz * g.a[e];
        let ge1 = g.grad(e1) - gz * g.a[e1];
        let l = g.lambda[e];
        // Both halves' coordinates, blended by the side of the segment Z R_e.
        let first = if me * (1.0 - l) >= me1 * l { 1.0 } else { 0.0 };
        let s2a = me1 * g.inv_rest[e];
        let g2a = ge1 * g.inv_rest[e];
        let s1b = me * g.inv_lambda[e];
        let g1b = ge * g.inv_lambda[e];
        let (s1, s2) = (
            first * (me - l * s2a) + (1.0 - first) * s1b,
            first * s2a + (1.0 - first) * (me1 - (1.0 - l) * s1b),
        );
        let g1 = (ge - g2a * l) * first + g1b * (1.0 - first);
        let g2 = g2a * first + (ge1 - g1b * (1.0 - l)) * (1.0 - first);
        let sub = 2 * e + 1 - first as usize;
        SubLocation {
            triangle: t,
            sub,
            bary: [s1, s2, mz],
            dx: [g1.x, g2.x, gz.x],
            dy: [g1.y, g2.y, gz.y],
        }
    }

    /// The sub-triangle `sub` of triangle `t` with its barycentric map (for one-sided
    /// evaluation on a chosen patch).
    pub fn sub_triangle(&self, t: usize, sub: usize) -> Triangle2 {
        self.refinement.sub_triangles(&self.tri, t)[sub]
    }

    /// The integrals ∫_Ω B_i^j (Example 2.1 generalised): by (2.62) each sub-triangle
    /// contributes A(ρ*)/6 to each of its six ordinates, and each ordinate depends linearly on
    /// the control values through the net stencil.
    pub fn basis_integrals(&self) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.tri.vertex_count()];
        for t in 0..self.tri.triangle_count() {
            let weights = self.ordinate_integral_weights(t);
            let v = self.tri.triangle(t);
            let k = self.stencil(t).transpose(weights);
            for c in 0..3 {
                for j in 0..3 {
                    out[v[c]][j] += k[c][j];
                }
            }
        }
        out
    }

    /// The weight of each of the 19 ordinates of triangle `t` in ∫ s: Σ over the
    /// sub-triangles containing it of A(ρ*)/6 (2.62).
    pub fn ordinate_integral_weights(&self, t: usize) -> [f64; NET_LEN] {
        let mut w = [0.0; NET_LEN];
        for (sub, g) in self
            .refinement
            .sub_triangles(&self.tri, t)
            .iter()
            .enumerate()
        {
            let a = g.area() / 6.0;
            for &k in &SUB_ORDINATES[sub] {
                w[k] += a;
            }
        }
        w
    }
}
