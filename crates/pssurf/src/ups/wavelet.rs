//! The UPS-spline wavelet transform by lifting (thesis section 4.5): split into the four
//! sublattices, scale, predict by subdivision, update; exactly invertible.
//!
//! One forward step turns a UPS-spline on Δ (base B) into a UPS-spline on the coarse
//! triangulation (base 2B) — the scaling coefficients — and detail (wavelet) coefficients on
//! the three other sublattices, the midpoints of the coarse edges:
//!
//! 1. **Split** the control triples by sublattice: even slots (2i, 2j) are the coarse vertices.
//! 2. **Scale** them by the inverse of the old-vertex rule (4.24), factored as in (4.57):
//!    c′1 = 2/3 c1 + 1/6 c2 + 1/6 c3, c′2 = 1/4 c′1 + 5/8 c2 + 1/8 c3,
//!    c′3 = 1/5 c′1 + 1/5 c′2 + 3/5 c3 (the extracted text prints the last weight as 1/40;
//!    3/5 is the value that makes the steps compose to (4.24)).
//! 3. **Predict** each midpoint's triple by the subdivision rule (4.26)–(4.28) from the two
//!    scaled coarse triples; the detail is the difference (Definition 4.6). Quadratics are
//!    predicted exactly, so their details vanish.
//! 4. **Update**: each detail component c_{l,j} adds k_{m,j} c_{l,j} to component j of both
//!    coarse triples it was predicted from.
//!
//! The update weights keep the average: setting one detail to one and running the scheme
//! backwards (a complementary sequence, Definition 4.8) must give coefficients summing to
//! zero. With S_{m,j} the total weight of coarse coefficient (m, j) in all predictions, that
//! sum is 1 − k_{m,j}(1 + S_{m,j}) − k_{n,j}(1 + S_{n,j}) (the scaling step keeps sums), so
//! k_{m,j} = 1 / (2 (1 + S_{m,j})) makes every complementary sequence sum to zero, whatever
//! the boundary configuration. In the interior S = 3 and k = 1/8, as in (4.51); the boundary
//! cases (the lost Figure 4.20) follow from the actual neighbourhood — see `docs/ups.md`.
//!
//! That update ([`Update::Thesis`]) keeps the average but acts on each component alone, so
//! it cannot undo what the scaling step does to noise: the inverse old-vertex rule has
//! eigenvalues 1, 2, 2 and doubles the shape noise of the coarse control triangles at every
//! level (coarse coefficients of pure noise σ: 7σ after three levels). [`Update::Stable`] is
//! the multi-wavelet update of thesis 4.5.5: every coarse component takes a combination of
//! all components of the neighbouring details, chosen per fan of triangles as the
//! smallest-norm local left inverse of subdivision under the same zero-sum condition on the
//! complementary sequences. Denoising uses it.

use std::sync::OnceLock;

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::UpsError;
use super::grid::UpsGrid;
use super::spline::Ups;
use super::subdivision::{edge_of_new_vertex, new_vertex_rule};
use crate::vector::Vector;

/// The detail coefficients of one transform step.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailLevel<V> {
    /// The finer triangulation of this step: details live on its odd slots.
    pub grid: UpsGrid,
    /// One detail triple per slot (zero on even and pseudo slots).
    pub details: Vec<[V; 3]>,
}

impl<V: Vector> DetailLevel<V> {
    /// The slots that carry details: real vertices with an odd lattice coordinate.
    pub fn detail_slots(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.grid.slots()).filter(move |&s| {
            let (i, j) = self.grid.ij(s);
            self.grid.is_real(s) && (i % 2 == 1 || j % 2 == 1)
        })
    }
}

/// A multi-level wavelet decomposition: the coarsest spline and the details of each step.
#[derive(Clone, Debug, PartialEq)]
pub struct Decomposition<V> {
    /// The scaling coefficients: the spline at the coarsest level.
    pub coarse: Ups<V>,
    /// The detail levels from the coarsest (index 0, the thesis' k = 1) to the finest.
    pub levels: Vec<DetailLevel<V>>,
    /// The update step the decomposition was made with (the inverse needs the same).
    pub update: Update,
}

/// The update step of the lifting scheme. Both keep perfect reconstruction, exact
/// prediction of quadratics and zero-sum complementary sequences (Property 4.3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Update {
    /// The thesis' update (4.51): component j of a coarse triple takes k_j times component j
    /// of each neighbouring detail ([`fan_update_weights`]). Not stable: noise in the coarse
    /// control triangles doubles at every level.
    #[default]
    Thesis,
    /// The multi-wavelet update (thesis 4.5.5), [`stable_update_matrix`]: noise keeps its
    /// size from level to level, so the coarse part of a noisy surface is smoother than it.
    Stable,
}

/// `U[r][d][q]`: the weight of component q of the detail at the midpoint of the edge in
/// direction d ([`super::grid::NEIGHBORS`]) in the update of component r of the coarse triple.
pub type UpdateMatrix = [[[f64; 3]; 6]; 3];

/// The scaling step: the triples c̃ with old_vertex_rule(c̃) = c, by undoing the factored
/// steps of (4.24) in reverse order.
#[inline]
pub(crate) fn unscale<V: Vector>(c: [V; 3]) -> [V; 3] {
    let [p1, p2, p3] = c;
    let c3 = (p3 - p1 * 0.2 - p2 * 0.2) * (5.0 / 3.0);
    let c2 = (p2 - p1 * 0.25 - c3 * 0.125) * 1.6;
    let c1 = (p1 - c2 * (1.0 / 6.0) - c3 * (1.0 / 6.0)) * 1.5;
    [c1, c2, c3]
}

/// The factored old-vertex rule (4.57); equal to [`old_vertex_rule`] up to rounding.
#[inline]
pub(crate) fn scale<V: Vector>(c: [V; 3]) -> [V; 3] {
    let [c1, c2, c3] = c;
    let p1 = c1 * (2.0 / 3.0) + c2 * (1.0 / 6.0) + c3 * (1.0 / 6.0);
    let p2 = p1 * 0.25 + c2 * 0.625 + c3 * 0.125;
    let p3 = p1 * 0.2 + p2 * 0.2 + c3 * 0.6;
    [p1, p2, p3]
}

/// The update weights k_{m,j} for every slot of the coarse grid (see the module docs),
/// from each vertex's fan of triangles ([`fan_update_weights`]).
pub fn update_weights(_fine: &UpsGrid, coarse: &UpsGrid) -> Vec<[f64; 3]> {
    (0..coarse.slots())
        .into_par_iter()
        .with_min_len(4096)
        .map(|s| {
            if coarse.is_real(s) {
                fan_update_weights(&coarse.sectors(s))
            } else {
                [0.0; 3]
            }
        })
        .collect()
}

impl<V: Vector + Default> Ups<V> {
    /// One forward lifting step with the thesis' update ([`Ups::wavelet_step_with`]).
    pub fn wavelet_step(&self) -> Result<(Ups<V>, DetailLevel<V>), UpsError> {
        self.wavelet_step_with(Update::Thesis)
    }

    /// One forward lifting step: the coarse spline (scaling coefficients) and the details.
    pub fn wavelet_step_with(&self, update: Update) -> Result<(Ups<V>, DetailLevel<V>), UpsError> {
        let fine = self.grid();
        let coarse = fine.coarsened().ok_or(UpsError::TooManyLevels {
            requested: 1,
            available: 0,
        })?;
        let blocks = self.blocks();
        // Split and scale.
        let mut low: Vec<[V; 3]> = (0..coarse.slots())
            .into_par_iter()
            .with_min_len(4096)
            .map(|s| {
                if !coarse.is_real(s) {
                    return [V::default(); 3];
                }
                let (i, j) = coarse.ij(s);
                unscale(blocks[fine.slot(2 * i, 2 * j)])
            })
            .collect();
        // Predict.
        let [n0, _] = fine.dims();
        let mut details = vec![[V::default(); 3]; fine.slots()];
        details.par_chunks_mut(n0).enumerate().for_each(|(j, row)| {
            for (i, d) in row.iter_mut().enumerate() {
                if (i % 2 == 0 && j % 2 == 0) || !fine.is_real(fine.slot(i, j)) {
                    continue;
                }
                let (a, b, shift) = edge_of_new_vertex(i, j);
                let p = new_vertex_rule(
                    low[coarse.slot(a.0, a.1)],
                    low[coarse.slot(b.0, b.1)],
                    shift,
                );
                let c = blocks[fine.slot(i, j)];
                *d = [c[0] - p[0], c[1] - p[1], c[2] - p[2]];
            }
        });
        // Update.
        apply_update(fine, &coarse, &details, update, &mut low, 1.0);
        Ok((
            Ups::from_parts(coarse, low),
            DetailLevel {
                grid: fine.clone(),
                details,
            },
        ))
    }

    /// One inverse step with the thesis' update ([`Ups::wavelet_inverse_step_with`]).
    pub fn wavelet_inverse_step(coarse: &Ups<V>, level: &DetailLevel<V>) -> Ups<V> {
        Self::wavelet_inverse_step_with(coarse, level, Update::Thesis)
    }

    /// One inverse step: undo the update, add the predictions, scale back.
    pub fn wavelet_inverse_step_with(
        coarse: &Ups<V>,
        level: &DetailLevel<V>,
        update: Update,
    ) -> Ups<V> {
        let fine = &level.grid;
        let cgrid = coarse.grid();
        let mut low = coarse.blocks().to_vec();
        apply_update(fine, cgrid, &level.details, update, &mut low, -1.0);
        let [n0, _] = fine.dims();
        let mut out = vec![[V::default(); 3]; fine.slots()];
        out.par_chunks_mut(n0).enumerate().for_each(|(j, row)| {
            for (i, c) in row.iter_mut().enumerate() {
                let s = fine.slot(i, j);
                if !fine.is_real(s) {
                    continue;
                }
                *c = if i % 2 == 0 && j % 2 == 0 {
                    scale(low[cgrid.slot(i / 2, j / 2)])
                } else {
                    let (a, b, shift) = edge_of_new_vertex(i, j);
                    let p = new_vertex_rule(
                        low[cgrid.slot(a.0, a.1)],
                        low[cgrid.slot(b.0, b.1)],
                        shift,
                    );
                    let d = level.details[s];
                    [p[0] + d[0], p[1] + d[1], p[2] + d[2]]
                };
            }
        });
        Ups::from_parts(fine.clone(), out)
    }

    /// The f-level forward transform of the thesis ([`Update::Thesis`]).
    pub fn wavelet_transform(&self, levels: u32) -> Result<Decomposition<V>, UpsError> {
        self.wavelet_transform_with(levels, Update::Thesis)
    }

    /// The f-level forward transform: `levels` lifting steps, each on the previous low-pass
    /// spline. Fails when the triangulation cannot be coarsened that often.
    pub fn wavelet_transform_with(
        &self,
        levels: u32,
        update: Update,
    ) -> Result<Decomposition<V>, UpsError> {
        let available = self.grid().coarsening_levels();
        if levels > available {
            return Err(UpsError::TooManyLevels {
                requested: levels,
                available,
            });
        }
        let mut coarse = self.clone();
        let mut out = Vec::with_capacity(levels as usize);
        for _ in 0..levels {
            let (c, d) = coarse.wavelet_step_with(update)?;
            coarse = c;
            out.push(d);
        }
        out.reverse();
        Ok(Decomposition {
            coarse,
            levels: out,
            update,
        })
    }
}

/// `low[m][j] += sign · k[m][j] · d[l][j]` (thesis) or `low[m][r] += sign · Σ_q U[r][d][q]
/// d[l][q]` (stable) for every detail slot l and both coarse slots m it was predicted from —
/// gathered per coarse slot: the details that update coarse vertex (i, j) sit at the
/// midpoints (2i, 2j) + d of its six edges. Parallel over rows.
fn apply_update<V: Vector>(
    fine: &UpsGrid,
    coarse: &UpsGrid,
    details: &[[V; 3]],
    update: Update,
    low: &mut [[V; 3]],
    sign: f64,
) {
    let [c0, _] = coarse.dims();
    let [f0, f1] = fine.dims();
    low.par_chunks_mut(c0).enumerate().for_each(|(j, row)| {
        for (i, c) in row.iter_mut().enumerate() {
            let m = coarse.slot(i, j);
            if !coarse.is_real(m) {
                continue;
            }
            if update == Update::Stable {
                let u = stable_update_for(&coarse.sectors(m));
                let mut add = [V::zero(); 3];
                for (dir, d) in super::grid::NEIGHBORS.iter().enumerate() {
                    let (a, b) = (2 * i as i64 + d[0], 2 * j as i64 + d[1]);
                    if a < 0 || b < 0 || a as usize >= f0 || b as usize >= f1 {
                        continue;
                    }
                    let f = fine.slot(a as usize, b as usize);
                    if fine.is_real(f) {
                        for (r, acc) in add.iter_mut().enumerate() {
                            for q in 0..3 {
                                *acc += details[f][q] * u[r][dir][q];
                            }
                        }
                    }
                }
                for r in 0..3 {
                    c[r] += add[r] * sign;
                }
                continue;
            }
            let k = fan_update_weights(&coarse.sectors(m));
            let mut sum = [V::zero(); 3];
            for d in super::grid::NEIGHBORS {
                let (a, b) = (2 * i as i64 + d[0], 2 * j as i64 + d[1]);
                if a < 0 || b < 0 || a as usize >= f0 || b as usize >= f1 {
                    continue;
                }
                let f = fine.slot(a as usize, b as usize);
                if fine.is_real(f) {
                    for q in 0..3 {
                        sum[q] += details[f][q];
                    }
                }
            }
            for q in 0..3 {
                c[q] += sum[q] * (sign * k[q]);
            }
        }
    });
}

impl<V: Vector + Default> Decomposition<V> {
    /// The inverse transform: the spline at the finest level.
    pub fn reconstruct(&self) -> Ups<V> {
        let mut s = self.coarse.clone();
        for level in &self.levels {
            s = Ups::wavelet_inverse_step_with(&s, level, self.update);
        }
        s
    }

    /// The number of detail coefficients (scalars) in all levels.
    pub fn detail_count(&self) -> usize {
        self.levels
            .iter()
            .map(|l| 3 * V::DIM * l.detail_slots().count())
            .sum()
    }
}

/// The update weights k_j of a coarse vertex whose surrounding sectors (see
/// [`UpsGrid::sectors`]) are `sectors`: the closed form behind [`update_weights`] for one
/// vertex, used to tabulate the boundary cases.
///
/// An edge leaving the vertex in direction d (a [`super::grid::NEIGHBORS`] index) takes the
/// vertex as V_i of the rule (4.26)–(4.28) for d ∈ {0, 2, 4} (shift d/2) and as V_j for
/// d ∈ {3, 5, 1} (shift ((d + 3) mod 6)/2); as V_i it contributes 3/4 to components σ(1) and
/// σ(2), as V_j 1 to σ(0) and 1/4 to σ(1), σ(2). Then k_j = 1/(2(1 + S_j)).
pub fn fan_update_weights(sectors: &[bool; 6]) -> [f64; 3] {
    let mut s = [0.0f64; 3];
    for d in 0..6 {
        if !(sectors[d] || sectors[(d + 5) % 6]) {
            continue; // no triangle beside this edge
        }
        if d % 2 == 0 {
            let shift = d / 2;
            s[(1 + shift) % 3] += 0.75;
            s[(2 + shift) % 3] += 0.75;
        } else {
            let shift = ((d + 3) % 6) / 2;
            s[shift % 3] += 1.0;
            s[(1 + shift) % 3] += 0.25;
            s[(2 + shift) % 3] += 0.25;
        }
    }
    s.map(|x| 0.5 / (1.0 + x))
}

/// [`stable_update_matrix`] of a fan, computed once for each of the 64 sector patterns.
fn stable_update_for(sectors: &[bool; 6]) -> &'static UpdateMatrix {
    static TABLE: OnceLock<Vec<UpdateMatrix>> = OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..64usize)
            .map(|m| stable_update_matrix(&std::array::from_fn(|k| m & (1 << k) != 0)))
            .collect()
    });
    let mask = (0..6)
        .filter(|&k| sectors[k])
        .fold(0usize, |m, k| m | (1 << k));
    &table[mask]
}

/// The update of [`Update::Stable`] for a coarse vertex whose fan is `sectors`.
///
/// With any update U the coarse triple is a linear function a_r · c of the fine control
/// values around the vertex — its own triple (unscaled), its neighbours' triples (through
/// the predictions) and the six details — and a_r is a left inverse of subdivision whatever
/// U is. U is the choice that minimises Σ_r ‖a_r‖² (the variance of the coarse coefficients
/// for white noise on the fine ones), subject to the condition of the thesis' update: for
/// every detail (d, q), `Σ_r U[r][d][q] (1 + S_r) = ½`, S_r the total prediction weight of
/// component r ([`fan_update_weights`] = ½ / (1 + S_r)), so that with the other end of the
/// edge every complementary sequence sums to zero. In closed form, with M the columns of
/// the details' functionals, H = MᵀM, b_r = Mᵀe_r (e_r the unscaling row), w_r = 1 + S_r:
/// u_r = −H⁻¹b_r + (w_r / Σw²) (½ + H⁻¹ Σ_s w_s b_s).
pub fn stable_update_matrix(sectors: &[bool; 6]) -> UpdateMatrix {
    let unit = |k: usize| -> [f64; 3] { std::array::from_fn(|i| if i == k { 1.0 } else { 0.0 }) };
    // us[r][k]: component r of the unscaled unit triple e_k.
    let us: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|k| unscale(unit(k))[r]));
    let edges: Vec<usize> = (0..6)
        .filter(|&d| sectors[d] || sectors[(d + 5) % 6])
        .collect();
    let mut u = [[[0.0; 3]; 6]; 3];
    let nc = 3 * edges.len();
    if nc == 0 {
        return u;
    }
    // pm[e][q][k] / po[e][q][k]: weight of raw component k of this vertex's / the other end's
    // triple in the prediction of component q of the detail on edge e ([`fan_update_weights`]
    // has the orientation: this vertex is V_i for even d, V_j for odd d).
    let mut pm = vec![[[0.0; 3]; 3]; edges.len()];
    let mut po = pm.clone();
    for (e, &d) in edges.iter().enumerate() {
        let (first, shift) = if d % 2 == 0 {
            (true, d / 2)
        } else {
            (false, ((d + 3) % 6) / 2)
        };
        for k in 0..3 {
            let (s, z) = (unscale(unit(k)), [0.0; 3]);
            let mine = if first {
                new_vertex_rule(s, z, shift)
            } else {
                new_vertex_rule(z, s, shift)
            };
            let other = if first {
                new_vertex_rule(z, s, shift)
            } else {
                new_vertex_rule(s, z, shift)
            };
            for q in 0..3 {
                pm[e][q][k] = mine[q];
                po[e][q][k] = other[q];
            }
        }
    }
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let h = DMatrix::from_fn(nc, nc, |c1, c2| {
        let ((e1, q1), (e2, q2)) = ((c1 / 3, c1 % 3), (c2 / 3, c2 % 3));
        let mut v = dot(&pm[e1][q1], &pm[e2][q2]);
        if e1 == e2 {
            v += dot(&po[e1][q1], &po[e1][q2]);
            if q1 == q2 {
                v += 1.0;
            }
        }
        v
    });
    let b: [DVector<f64>; 3] =
        std::array::from_fn(|r| DVector::from_fn(nc, |c, _| -dot(&pm[c / 3][c % 3], &us[r])));
    let w = fan_update_weights(sectors).map(|k| 0.5 / k);
    let ww: f64 = w.iter().map(|x| x * x).sum();
    let chol = h.cholesky().expect("MᵀM = I + GᵀG is positive definite");
    let hb: [DVector<f64>; 3] = std::array::from_fn(|r| chol.solve(&b[r]));
    let mut mix = DVector::from_element(nc, 0.5);
    for s in 0..3 {
        mix += &hb[s] * w[s];
    }
    for r in 0..3 {
        let ur = &mix * (w[r] / ww) - &hb[r];
        for (e, &d) in edges.iter().enumerate() {
            for q in 0..3 {
                u[r][d][q] = ur[3 * e + q];
            }
        }
    }
    u
}
