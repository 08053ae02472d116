//! The normalized PS B-spline basis {B_i^j} of S_2^1(Δ*) (thesis section 2.3.2, Dierckx).

use nalgebra::{Point2, Vector2};
use rayon::prelude::*;

use super::PsError;
use super::net::{self, NET_LEN, NetStencil, SUB_ORDINATES};
use super::ps_triangles::{PsTriangleChoice, ps_triangles};
use super::refinement::{PsRefinement, SplitRule};
use crate::geometry::{Bary, BaryMap, Triangle2, midpoint};
use crate::triangulation::{Location, Triangulation};
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
    /// Gradients of the barycentric coordinates of each triangle of Δ.
    grads: Vec<[Vector2<f64>; 3]>,
}

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
        let grads = (0..tri.triangle_count())
            .into_par_iter()
            .with_min_len(1024)
            .map(|t| {
                tri.triangle_geometry(t)
                    .bary_map()
                    .expect("validated triangle")
                    .g
            })
            .collect();
        Ok(PsBasis {
            tri,
            refinement,
            ps_tris,
            ps_maps,
            grads,
        })
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
        let vi = self.tri.vertex(i);
        self.ps_tris[i]
            .v
            .map(|q| f + fx * (q.x - vi.x) + fy * (q.y - vi.y))
    }

    /// The conversion coefficients from control values to the 19 Bézier ordinates of
    /// triangle `t` ((2.54)–(2.60); see [`net`]).
    pub fn stencil(&self, t: usize) -> NetStencil {
        let v = self.tri.triangle(t);
        let z = self.refinement.z(t);
        let rows = std::array::from_fn(|c| {
            let vi = self.tri.vertex(v[c]);
            let map = &self.ps_maps[v[c]];
            let r_next = self.refinement.edge_point(&self.tri, t, c);
            let r_prev = self.refinement.edge_point(&self.tri, t, (c + 2) % 3);
            [
                map.c,
                map.apply(midpoint(vi, r_next)),
                map.apply(midpoint(vi, r_prev)),
                map.apply(midpoint(vi, z)),
            ]
        });
        NetStencil {
            rows,
            lambda: self.refinement.lambda(t),
            z: self.refinement.z_bary(t),
        }
    }

    /// The Bézier net of triangle `t` for per-vertex control values.
    pub fn net<T: net::Combine>(&self, t: usize, ctrl: &[[T; 3]]) -> [T; NET_LEN] {
        let v = self.tri.triangle(t);
        self.stencil(t).apply([ctrl[v[0]], ctrl[v[1]], ctrl[v[2]]])
    }

    /// Where `p` lies in Δ*, searching from triangle `hint` (any triangle; 0 is fine).
    #[inline]
    pub fn locate(&self, p: Point2<f64>, hint: usize) -> Option<SubLocation> {
        let loc = self.tri.locate_from(p, hint)?;
        Some(self.sub_locate(loc))
    }

    /// Refines a location in Δ to the sub-triangle of Δ* containing the point, with the
    /// barycentric coordinates there. With ρ_i = τ_i / a_i, the point lies in the sector
    /// (V_e, V_{e+1}, Z) opposite the vertex with the smallest ρ; the segment Z R_e splits the
    /// sector into the two sub-triangles.
    #[inline]
    pub fn sub_locate(&self, loc: Location) -> SubLocation {
        let t = loc.triangle;
        let tau = loc.bary;
        let a = self.refinement.z_bary(t);
        let g = &self.grads[t];
        let rho = [tau[0] / a[0], tau[1] / a[1], tau[2] / a[2]];
        let k = if rho[0] <= rho[1] && rho[0] <= rho[2] {
            0
        } else if rho[1] <= rho[2] {
            1
        } else {
            2
        };
        let e = (k + 1) % 3;
        let e1 = (k + 2) % 3;
        let mz = rho[k];
        let gz = g[k] / a[k];
        let me = tau[e] - a[e] * mz;
        let me1 = tau[e1] - a[e1] * mz;
        let ge = g[e] - gz * a[e];
        let ge1 = g[e1] - gz * a[e1];
        let l = self.refinement.lambda(t)[e];
        let (sub, s1, s2, g1, g2) = if me * (1.0 - l) >= me1 * l {
            let s2 = me1 / (1.0 - l);
            let g2 = ge1 / (1.0 - l);
            (2 * e, me - l * s2, s2, ge - g2 * l, g2)
        } else {
            let s1 = me / l;
            let g1 = ge / l;
            (
                2 * e + 1,
                s1,
                me1 - (1.0 - l) * s1,
                g1,
                ge1 - g1 * (1.0 - l),
            )
        };
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
            // Push the ordinate weights back through the stencil (its transpose).
            let st = self.stencil(t);
            let mut wv = weights;
            // ω, θ and r depend on w, u, v: distribute their weights first.
            for c in 0..3 {
                wv[net::w(c)] += wv[net::OM] * st.z[c];
            }
            for c in 0..3 {
                let d = (c + 1) % 3;
                let l = st.lambda[c];
                wv[net::u(c)] += wv[net::r(c)] * l;
                wv[net::v(d)] += wv[net::r(c)] * (1.0 - l);
                wv[net::w(c)] += wv[net::th(c)] * l;
                wv[net::w(d)] += wv[net::th(c)] * (1.0 - l);
            }
            for c in 0..3 {
                let rows = st.rows[c];
                let idx = [net::s(c), net::u(c), net::v(c), net::w(c)];
                for (row, &k) in rows.iter().zip(&idx) {
                    for j in 0..3 {
                        out[v[c]][j] += wv[k] * row[j];
                    }
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
