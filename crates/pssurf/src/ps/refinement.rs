//! The Powell–Sabin refinement Δ* of a triangulation (Definition 2.16).

use nalgebra::Point2;

use super::PsError;
use crate::geometry::{Triangle2, orient};
use crate::triangulation::Triangulation;

/// How to choose the interior split point Z_j of each triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SplitRule {
    /// The incentre: always valid — the segment joining the incentres of two neighbours
    /// crosses their common edge strictly between its end points (Definition 2.16).
    #[default]
    Incenter,
    /// The centroid: may fail on some triangulations (then an error names the edge).
    Centroid,
}

/// Margin keeping the split points away from the end points of edges and triangles: the
/// edge point R must satisfy ε < μ < 1 − ε along its edge.
const STRICT: f64 = 1e-10;

/// A PS-refinement: for each triangle ρ_j its interior point Z_j, and for each of its edges
/// the edge point R (where Z_j Z_l crosses an interior edge, the midpoint of a boundary edge).
///
/// Edge `c` of a triangle (V_0, V_1, V_2) runs from V_c to V_{c+1}; its split point is
/// R_c = λ_c V_c + (1 − λ_c) V_{c+1} (2.50)–(2.52), and Z = a_0 V_0 + a_1 V_1 + a_2 V_2 (2.53).
#[derive(Clone, Debug, PartialEq)]
pub struct PsRefinement {
    rule: Option<SplitRule>,
    z: Vec<Point2<f64>>,
    z_bary: Vec<[f64; 3]>,
    lambda: Vec<[f64; 3]>,
}

impl PsRefinement {
    /// The refinement with split points chosen by `rule`.
    pub fn new(tri: &Triangulation, rule: SplitRule) -> Result<Self, PsError> {
        let z = (0..tri.triangle_count())
            .map(|t| {
                let g = tri.triangle_geometry(t);
                match rule {
                    SplitRule::Incenter => g.incenter(),
                    SplitRule::Centroid => g.centroid(),
                }
            })
            .collect();
        let mut r = Self::with_points(tri, z)?;
        r.rule = Some(rule);
        Ok(r)
    }

    /// The rule the split points came from, `None` when they were given.
    pub fn rule(&self) -> Option<SplitRule> {
        self.rule
    }

    /// The refinement with user-given interior points, one per triangle, each strictly inside.
    pub fn with_points(tri: &Triangulation, z: Vec<Point2<f64>>) -> Result<Self, PsError> {
        if z.len() != tri.triangle_count() {
            return Err(PsError::WrongCount {
                what: "split points",
                expected: tri.triangle_count(),
                found: z.len(),
            });
        }
        let mut z_bary = Vec::with_capacity(z.len());
        for (t, &p) in z.iter().enumerate() {
            let b = tri.triangle_geometry(t).bary(p);
            if !b.iter().all(|&x| x > STRICT) {
                return Err(PsError::SplitPointOutside { triangle: t });
            }
            z_bary.push(b);
        }
        let mut lambda = vec![[0.5; 3]; z.len()];
        for t in 0..tri.triangle_count() {
            let v = tri.triangle(t);
            for c in 0..3 {
                let Some(s) = tri.neighbor(t, edge_to_local(c)) else {
                    continue; // boundary edge: the midpoint
                };
                let (a, b) = (tri.vertex(v[c]), tri.vertex(v[(c + 1) % 3]));
                let (oa, ob) = (orient(z[t], z[s], a), orient(z[t], z[s], b));
                let mu = oa / (oa - ob);
                if !(mu > STRICT && mu < 1.0 - STRICT) {
                    return Err(PsError::EdgePointOutside {
                        triangle: t,
                        neighbor: s,
                        edge: (v[c], v[(c + 1) % 3]),
                    });
                }
                lambda[t][c] = 1.0 - mu;
            }
        }
        Ok(PsRefinement {
            rule: None,
            z,
            z_bary,
            lambda,
        })
    }

    /// The interior points Z_j.
    pub fn split_points(&self) -> &[Point2<f64>] {
        &self.z
    }

    /// Z_j of triangle `t`.
    pub fn z(&self, t: usize) -> Point2<f64> {
        self.z[t]
    }

    /// (a_0, a_1, a_2): the barycentric coordinates of Z_j (2.53).
    pub fn z_bary(&self, t: usize) -> [f64; 3] {
        self.z_bary[t]
    }

    /// λ_c of the three edges of triangle `t` (R_c = λ_c V_c + (1 − λ_c) V_{c+1}).
    pub fn lambda(&self, t: usize) -> [f64; 3] {
        self.lambda[t]
    }

    /// The edge point R_c of edge `c` of triangle `t`.
    pub fn edge_point(&self, tri: &Triangulation, t: usize, c: usize) -> Point2<f64> {
        let v = tri.triangle(t);
        let l = self.lambda[t][c];
        let (a, b) = (tri.vertex(v[c]), tri.vertex(v[(c + 1) % 3]));
        Point2::from(a.coords * l + b.coords * (1.0 - l))
    }

    /// The six sub-triangles of `t` in Δ*, in the order (V_c, R_c, Z), (R_c, V_{c+1}, Z)
    /// for c = 0, 1, 2 (all counter-clockwise).
    pub fn sub_triangles(&self, tri: &Triangulation, t: usize) -> [Triangle2; 6] {
        let v = tri.triangle(t);
        let z = self.z[t];
        std::array::from_fn(|k| {
            let c = k / 2;
            let r = self.edge_point(tri, t, c);
            if k % 2 == 0 {
                Triangle2::new(tri.vertex(v[c]), r, z)
            } else {
                Triangle2::new(r, tri.vertex(v[(c + 1) % 3]), z)
            }
        })
    }
}

/// The triangulation's local index (the edge opposite a vertex) of PS edge `c` (V_c → V_{c+1}).
#[inline]
pub fn edge_to_local(c: usize) -> usize {
    (c + 2) % 3
}
