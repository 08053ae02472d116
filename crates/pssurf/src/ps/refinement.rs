//! The Powell–Sabin refinement Δ* of a triangulation (Definition 2.16).

use nalgebra::Point2;

use rayon::prelude::*;

use super::PsError;
use crate::geometry::{Triangle2, orient_exact};
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
            .into_par_iter()
            .with_min_len(1024)
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
        let z_bary: Vec<[f64; 3]> = z
            .par_iter()
            .enumerate()
            .with_min_len(1024)
            .map(|(t, &p)| {
                let b = tri.triangle_geometry(t).bary(p);
                if b.iter().all(|&x| x > STRICT) {
                    Ok(b)
                } else {
                    Err(PsError::SplitPointOutside { triangle: t })
                }
            })
            .collect::<Result<_, _>>()?;
        let lambda = (0..tri.triangle_count())
            .into_par_iter()
            .with_min_len(1024)
            .map(|t| {
                let mut l = [0.5; 3];
                for (c, lc) in l.iter_mut().enumerate() {
                    if let Some(mu) = edge_parameter(tri, &z, t, c)? {
                        *lc = 1.0 - mu;
                    }
                }
                Ok(l)
            })
            .collect::<Result<_, PsError>>()?;
        let refinement = PsRefinement {
            rule: None,
            z,
            z_bary,
            lambda,
        };
        // Margins on the split points alone do not keep every piece away from zero area
        // (an edge point 1e-9 from a vertex with Z close to that edge): check the pieces with
        // the test that evaluation uses.
        if let Some(t) = (0..tri.triangle_count())
            .into_par_iter()
            .with_min_len(1024)
            .find_first(|&t| {
                refinement
                    .sub_triangles(tri, t)
                    .iter()
                    .any(|piece| piece.is_degenerate())
            })
        {
            return Err(PsError::DegeneratePiece { triangle: t });
        }
        Ok(refinement)
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
        between(
            tri.vertex(v[c]),
            tri.vertex(v[(c + 1) % 3]),
            self.lambda[t][c],
        )
    }

    /// The six sub-triangles of `t` in Δ*, in the order (V_c, R_c, Z), (R_c, V_{c+1}, Z)
    /// for c = 0, 1, 2 (all counter-clockwise).
    pub fn sub_triangles(&self, tri: &Triangulation, t: usize) -> [Triangle2; 6] {
        let corners = tri.triangle(t).map(|i| tri.vertex(i));
        let z = self.z[t];
        let l = self.lambda[t];
        let r: [Point2<f64>; 3] =
            std::array::from_fn(|c| between(corners[c], corners[(c + 1) % 3], l[c]));
        std::array::from_fn(|k| {
            let c = k / 2;
            if k % 2 == 0 {
                Triangle2::new(corners[c], r[c], z)
            } else {
                Triangle2::new(r[c], corners[(c + 1) % 3], z)
            }
        })
    }
}

/// The point λ a + (1 − λ) b: an edge point, computed by this one expression wherever it is
/// needed so that every use gets the same bits.
#[inline]
fn between(a: Point2<f64>, b: Point2<f64>, l: f64) -> Point2<f64> {
    Point2::from(a.coords * l + b.coords * (1.0 - l))
}

/// Where the segment joining the split points of triangle `t` and its neighbour across edge
/// `c` crosses that edge: R = V_c + μ (V_{c+1} − V_c). `None` on the boundary. The value is
/// computed once per edge — by the triangle with the smaller index — so that both triangles
/// see exactly the same point.
fn edge_parameter(
    tri: &Triangulation,
    z: &[Point2<f64>],
    t: usize,
    c: usize,
) -> Result<Option<f64>, PsError> {
    let Some(s) = tri.neighbor(t, edge_to_local(c)) else {
        return Ok(None);
    };
    let v = tri.triangle(t);
    let (a, b) = (v[c], v[(c + 1) % 3]);
    let (first, second, from, to) = if t < s { (t, s, a, b) } else { (s, t, b, a) };
    let (pa, pb) = (tri.vertex(from), tri.vertex(to));
    // Adaptive-precision orientations: their signs are exact, and their values accurate
    // where rounded ones would be noise (split points of slivers lie almost on the edge).
    let (oa, ob) = (
        orient_exact(z[first], z[second], pa),
        orient_exact(z[first], z[second], pb),
    );
    let mu = oa / (oa - ob);
    if !(oa * ob < 0.0 && mu > STRICT && mu < 1.0 - STRICT) {
        return Err(PsError::EdgePointOutside {
            triangle: t.min(s),
            neighbor: t.max(s),
            edge: (from, to),
        });
    }
    Ok(Some(if t < s { mu } else { 1.0 - mu }))
}

/// The triangulation's local index (the edge opposite a vertex) of PS edge `c` (V_c → V_{c+1}).
#[inline]
pub fn edge_to_local(c: usize) -> usize {
    (c + 2) % 3
}
