//! Energies of PS-splines as quadratic forms in their control values, assembled exactly.
//!
//! A PS-spline is quadratic on each of the six pieces of every triangle (thesis section
//! 2.4), so its Hessian is constant on each piece and linear in the nine control values of
//! the triangle's vertices (through the Bézier net, (2.54)–(2.60)). Two energies follow:
//!
//! - [`Energy::ThinPlate`]: ∫_Ω s_xx² + 2 s_xy² + s_yy², the thin-plate energy (thesis
//!   5.4.3 uses its parametric form for fairing). Zero exactly on linear functions.
//! - [`Energy::HessianJumps`]: Σ over the interior edges e of Δ* of
//!   w_e ‖∇²s|_left − ∇²s|_right‖²_F with w_e = min(1, 4 (A_left + A_right) / |e|²): every
//!   jump weighs alike, except across edges of pieces thin across them (4A < |e|²), whose
//!   jumps are down-weighted in proportion to their thinness, so that slivers of the
//!   refinement do not dominate. (A first weight, |e|² / (A_left + A_right), the scaling of
//!   ∫ ‖∇³s‖², did the opposite on slivers and was replaced.) Zero exactly on quadratics, so
//!   minimising it reproduces them.
//!
//! Both are sums of squares of linear functions of the control values: the matrices are
//! symmetric positive semi-definite, and exact up to rounding (no quadrature).
//!
//! A PS-spline is C¹, so across an edge with unit normal n its gradient is continuous and
//! so is every second derivative along the edge: the Hessian jumps by α n nᵀ, whose
//! Frobenius norm² (weights 1, 2, 1 of xx, xy, yy) is α² with α = nᵀ[∇²s]n. Each jump is
//! therefore one square, that of the jump of the second derivative across the edge,
//! computed from the two pieces' second derivatives in the direction n.

use super::PsBasis;
use super::net::{NET_LEN, SUB_ORDINATES};
use crate::sparse::{Block3Matrix, ElementMatrix};

/// Which energy of a PS-spline to assemble (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Energy {
    /// ∫ s_xx² + 2 s_xy² + s_yy²: bending; its minimisers reproduce linear functions.
    ThinPlate,
    /// Σ_e w_e ‖[∇²s]_e‖²: the jumps of the Hessian across the edges of Δ*; its minimisers
    /// reproduce quadratics.
    HessianJumps,
}

/// The Frobenius weights of the Hessian's entries (xx, xy, yy): ‖H‖²_F = H_xx² + 2 H_xy² +
/// H_yy².
const FROBENIUS: [f64; 3] = [1.0, 2.0, 1.0];

/// The constant Hessian of one piece of a triangle, as linear functions of the triangle's
/// nine control values (index 3c + j for corner c's control value j).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PieceHessian {
    /// The piece's area.
    pub area: f64,
    /// Coefficients of s_xx, s_xy and s_yy.
    pub rows: [[f64; 9]; 3],
}

impl PsBasis {
    /// The Hessians of the six pieces of triangle `t`, in the order of
    /// [`PsRefinement::sub_triangles`](super::PsRefinement::sub_triangles). On a piece with
    /// barycentric coordinates τ and ordinates b_ij (b_ij = b_ji for the multi-index
    /// e_i + e_j), s = Σ_ij b_ij τ_i τ_j, so ∇²s = 2 Σ_ij b_ij ∇τ_i ∇τ_jᵀ.
    pub fn piece_hessians(&self, t: usize) -> [PieceHessian; 6] {
        let stencil = self.stencil(t);
        let pieces = self.refinement().sub_triangles(self.triangulation(), t);
        std::array::from_fn(|k| {
            let piece = &pieces[k];
            let g = piece
                .bary_map()
                .expect("pieces of a valid PS refinement are not degenerate")
                .g;
            // Ordinate positions b200, b110, b101, b020, b011, b002 → index pairs.
            const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
            let mut rows = [[0.0; 9]; 3];
            for (entry, (a, b)) in [(0, 0), (0, 1), (1, 1)].into_iter().enumerate() {
                let mut weights = [0.0; NET_LEN];
                for (slot, &(i, j)) in PAIRS.iter().enumerate() {
                    let sym = g[i][a] * g[j][b] + g[j][a] * g[i][b];
                    weights[SUB_ORDINATES[k][slot]] = if i == j { sym } else { 2.0 * sym };
                }
                let coeffs = stencil.transpose(weights);
                for c in 0..3 {
                    for j in 0..3 {
                        rows[entry][3 * c + j] = coeffs[c][j];
                    }
                }
            }
            PieceHessian {
                area: piece.area(),
                rows,
            }
        })
    }

    /// The matrix Q of `energy` over the control values: E(s) = cᵀ Q c, with c the
    /// control values in vertex order (three per vertex).
    pub fn energy_matrix(&self, energy: Energy) -> Block3Matrix {
        self.energy_matrix_with(energy, ThinPieces::Kept)
    }

    /// The Hessian-jump energy for fitting data (gradients of an interpolant, smoothing
    /// fits): jumps at needle-shaped, sliver and small pieces (thin against their triangle)
    /// fade out (`ThinPieces::Faded`).
    /// There values fixed by the data force second derivatives of the order of the data's
    /// deviation from a quadratic divided by the piece's thickness², and minimising their
    /// squares bends the gradients of every nearby vertex (errors of 1e6 on jittered grids
    /// whose boundary rows are nearly collinear, where Delaunay leaves slivers along the
    /// hull) or, next to the data's terms, makes the system singular in rounding.
    pub fn faded_jump_energy_matrix(&self) -> Block3Matrix {
        self.energy_matrix_with(Energy::HessianJumps, ThinPieces::Faded)
    }

    fn energy_matrix_with(&self, energy: Energy, thin: ThinPieces) -> Block3Matrix {
        let tri = self.triangulation();
        let mut q = Block3Matrix::with_pattern(tri.vertex_count(), |i, out| {
            for &t in tri.molecule(i) {
                out.extend(tri.triangle(t as usize).map(|v| v as u32));
                if energy == Energy::HessianJumps {
                    for e in 0..3 {
                        if let Some(n) = tri.neighbor(t as usize, e) {
                            out.extend(tri.triangle(n).map(|v| v as u32));
                        }
                    }
                }
            }
        });
        // Ranges of vertices in parallel, each adding the elements of the triangles whose
        // smallest vertex is in it: the rows are what the ranges own, so this holds for any
        // triangle order (Delaunay triangulations come in a spatial one, a user's in any),
        // and with vertices in a spatial order most blocks fall in the range's own rows.
        q.add_elements_by_range(2048, |range, add| {
            let mut add = |e: &Element| add(&e.vertices[..e.len], &e.matrix);
            for i in range {
                for t in tri.molecule(i).iter().map(|&t| t as usize) {
                    if tri.triangle(t).into_iter().min() != Some(i) {
                        continue;
                    }
                    match energy {
                        Energy::ThinPlate => add(&self.thin_plate_element(t)),
                        Energy::HessianJumps => self.jump_elements(t, thin, &mut add),
                    }
                }
            }
        });
        q
    }

    /// The terms of `energy` that involve the triangles `ts` (sorted), each once, passed to
    /// `add(vertices, matrix)` with the matrix over three control values per vertex (in the
    /// vertices' order): for local assembly, when only the control values of some vertices
    /// vary (all of whose molecule triangles are in `ts`).
    pub(crate) fn local_energy_elements(
        &self,
        energy: Energy,
        ts: &[usize],
        mut add: impl FnMut(&[usize], &ElementMatrix),
    ) {
        let tri = self.triangulation();
        let mut give = |e: &Element| add(&e.vertices[..e.len], &e.matrix);
        for &t in ts {
            match energy {
                Energy::ThinPlate => give(&self.thin_plate_element(t)),
                Energy::HessianJumps => {
                    let side = PsSide::new(self, t, ThinPieces::Kept);
                    give(&self.inner_jump_element(&side));
                    for c in 0..3 {
                        let Some(n) = tri.neighbor(t, super::refinement::edge_to_local(c)) else {
                            continue;
                        };
                        // Each shared edge once: from the smaller triangle when both are
                        // in the set, always when the neighbour is not.
                        if n < t && ts.binary_search(&n).is_ok() {
                            continue;
                        }
                        give(&self.cross_edge_element(&side, c, n));
                    }
                }
            }
        }
    }

    /// ∫ over triangle t of ‖∇²s‖²_F: Σ over its pieces of area × ‖H‖²_F.
    fn thin_plate_element(&self, t: usize) -> Element {
        let mut e = Element::new(&self.triangulation().triangle(t));
        for piece in self.piece_hessians(t) {
            for (r, row) in piece.rows.iter().enumerate() {
                e.add_square(piece.area * FROBENIUS[r], &row[..]);
            }
        }
        e.mirrored()
    }

    /// Passes to `add` the Hessian jumps of triangle t: across its six inner edges (one
    /// element), and across each edge of Δ it shares with a triangle of larger index (one
    /// element each, over the four vertices of the two triangles).
    fn jump_elements(&self, t: usize, thin: ThinPieces, add: &mut impl FnMut(&Element)) {
        let tri = self.triangulation();
        let side = PsSide::new(self, t, thin);
        add(&self.inner_jump_element(&side));
        for c in 0..3 {
            let Some(n) = tri.neighbor(t, super::refinement::edge_to_local(c)) else {
                continue;
            };
            if n < t {
                continue;
            }
            add(&self.cross_edge_element(&side, c, n));
        }
    }

    /// The Hessian jumps across the six inner edges of a triangle (one element).
    fn inner_jump_element(&self, side: &PsSide) -> Element {
        let mut inner = Element::new(&side.vertices);
        for k in 0..6 {
            // Piece k and piece k + 1 share the edge from Z to their common corner
            // (R_c for k = 2c, V_{c+1} for k = 2c + 1).
            let next = (k + 1) % 6;
            let edge = side.pieces[k].v[1] - side.pieces[k].v[2];
            let w = side.shape[k].min(side.shape[next])
                * jump_weight(edge.norm_squared(), side.areas[k] + side.areas[next]);
            let normal = unit_normal(edge);
            let a = side.second_derivative(k, normal);
            let b = side.second_derivative(next, normal);
            let jump: [f64; 9] = std::array::from_fn(|m| a[m] - b[m]);
            inner.add_square(w, &jump);
        }
        inner.mirrored()
    }

    /// The jumps across PS edge c of a triangle (V_c → V_{c+1}) into its neighbour n: the
    /// segments V_c R_c (piece 2c of t) and R_c V_{c+1} (piece 2c + 1).
    fn cross_edge_element(&self, side: &PsSide, c: usize, n: usize) -> Element {
        let v = side.vertices;
        let other = PsSide::new(self, n, side.thin);
        let vn = other.vertices;
        // In n the shared edge runs V_{c+1} → V_c: it is n's PS edge c' with V'_{c'} = V_{c+1}.
        let cn = (0..3)
            .find(|&k| vn[k] == v[(c + 1) % 3] && vn[(k + 1) % 3] == v[c])
            .expect("neighbours share the edge in opposite directions");
        let opposite = vn[(cn + 2) % 3];
        let vertices = [v[0], v[1], v[2], opposite];
        // Columns of n's corners in the element: its corners are V_{c+1}, V_c and `opposite`.
        let col_of_n: [usize; 3] =
            std::array::from_fn(|k| vertices.iter().position(|&x| x == vn[k]).unwrap());
        let mut e = Element::new(&vertices);
        // Piece 2c of t (V_c, R, Z) meets piece 2c' + 1 of n (R, V_c, Z'); piece 2c + 1 of t
        // meets piece 2c' of n.
        for (mine, theirs) in [(2 * c, 2 * cn + 1), (2 * c + 1, 2 * cn)] {
            let edge = side.pieces[mine].v[1] - side.pieces[mine].v[0];
            let w = side.shape[mine].min(other.shape[theirs])
                * jump_weight(edge.norm_squared(), side.areas[mine] + other.areas[theirs]);
            let normal = unit_normal(edge);
            let a = side.second_derivative(mine, normal);
            let b = other.second_derivative(theirs, normal);
            let mut jump = [0.0; 12];
            jump[..9].copy_from_slice(&a);
            for k in 0..3 {
                for j in 0..3 {
                    jump[3 * col_of_n[k] + j] -= b[3 * k + j];
                }
            }
            e.add_square(w, &jump);
        }
        e.mirrored()
    }
}

/// What the Hessian jumps need of one triangle: its vertices, its stencil, its six pieces
/// with their areas and barycentric gradients.
struct PsSide {
    vertices: [usize; 3],
    /// How thin pieces weigh.
    thin: ThinPieces,
    /// The pieces' weights in the jump energy: 1, or with [`ThinPieces::Faded`] their
    /// [`shape_weight`].
    shape: [f64; 6],
    stencil: super::net::NetStencil,
    pieces: [crate::geometry::Triangle2; 6],
    areas: [f64; 6],
    gradients: [[nalgebra::Vector2<f64>; 3]; 6],
}

impl PsSide {
    fn new(basis: &PsBasis, t: usize, thin: ThinPieces) -> Self {
        let pieces = basis.refinement().sub_triangles(basis.triangulation(), t);
        let size = basis.triangulation().triangle_geometry(t).diameter();
        PsSide {
            vertices: basis.triangulation().triangle(t),
            stencil: basis.stencil(t),
            areas: std::array::from_fn(|k| pieces[k].area()),
            thin,
            shape: std::array::from_fn(|k| match thin {
                ThinPieces::Kept => 1.0,
                ThinPieces::Faded => shape_weight(&pieces[k], size),
            }),
            gradients: std::array::from_fn(|k| {
                pieces[k]
                    .bary_map()
                    .expect("pieces of a valid PS refinement are not degenerate")
                    .g
            }),
            pieces,
        }
    }

    /// nᵀ ∇²s n on piece k, as a linear function of the triangle's nine control values
    /// (index 3c + j): with p_i = ∇τ_i · n, s_nn = 2 Σ_i b_ii p_i² + 4 Σ_{i<j} b_ij p_i p_j.
    fn second_derivative(&self, k: usize, n: nalgebra::Vector2<f64>) -> [f64; 9] {
        const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
        let p: [f64; 3] = std::array::from_fn(|i| self.gradients[k][i].dot(&n));
        let mut weights = [0.0; NET_LEN];
        for (slot, &(i, j)) in PAIRS.iter().enumerate() {
            let factor = if i == j { 2.0 } else { 4.0 };
            weights[SUB_ORDINATES[k][slot]] = factor * p[i] * p[j];
        }
        let coeffs = self.stencil.transpose(weights);
        std::array::from_fn(|m| coeffs[m / 3][m % 3])
    }
}

/// The unit normal of an edge with direction `d` (nonzero).
fn unit_normal(d: nalgebra::Vector2<f64>) -> nalgebra::Vector2<f64> {
    nalgebra::Vector2::new(-d.y, d.x) / d.norm()
}

/// The weight of a Hessian jump across an edge of length² `len2` between two pieces of
/// total area `area`: 1, down-weighted in proportion to the pieces' thinness across the
/// edge when 4 × area < len2 (module docs).
fn jump_weight(len2: f64, area: f64) -> f64 {
    (4.0 * area / len2).min(1.0)
}

/// How the jumps at thin pieces weigh in the Hessian-jump energy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ThinPieces {
    /// Like all others (up to the thinness across the edge of the module docs).
    Kept,
    /// Also multiplied by the smaller [`shape_weight`] of the two pieces.
    Faded,
}

/// The weight of the jumps at a piece of a triangle of diameter `size`: 1, unless the
/// piece's smallest height is less than [`THIN`] × the triangle's diameter (a needle, a
/// sliver, or a small piece where a split point lies near a corner); then (ratio / THIN)⁴:
/// the squared jumps there, and their rounding errors, grow like ratio⁻⁴, and the weight
/// keeps them of the size of the others'. Measuring the height against the piece's own
/// longest side missed small pieces of good shape: next to boundary slivers a split point
/// 1e-8 from a corner made pieces 1e-8 across whose jumps weighed 1e11 times the others,
/// and their rounding alone moved the gradients of quadratics by 2e-7.
fn shape_weight(t: &crate::geometry::Triangle2, size: f64) -> f64 {
    let ratio = t.min_height() / t.diameter().max(size);
    (ratio / THIN).min(1.0).powi(4)
}

/// A piece's smallest height over its triangle's diameter below which its jumps fade
/// ([`ThinPieces::Faded`]).
const THIN: f64 = 0.05;

/// One element's local matrix over its vertices' control values.
struct Element {
    vertices: [usize; 4],
    len: usize,
    matrix: ElementMatrix,
}

impl Element {
    fn new(vertices: &[usize]) -> Self {
        let mut v = [0; 4];
        v[..vertices.len()].copy_from_slice(vertices);
        Element {
            vertices: v,
            len: vertices.len(),
            matrix: [[0.0; 12]; 12],
        }
    }

    /// Adds w aaᵀ for the row vector `a` over the element's values, to the lower triangle
    /// only ([`mirrored`](Self::mirrored) completes the matrix).
    fn add_square(&mut self, w: f64, a: &[f64]) {
        for (r, &ar) in a.iter().enumerate() {
            if ar == 0.0 {
                continue;
            }
            let war = w * ar;
            for (c, &ac) in a[..=r].iter().enumerate() {
                self.matrix[r][c] += war * ac;
            }
        }
    }

    /// The element with its upper triangle copied from the lower one.
    fn mirrored(mut self) -> Self {
        let n = 3 * self.len;
        for r in 0..n {
            for c in r + 1..n {
                self.matrix[r][c] = self.matrix[c][r];
            }
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ps::{Hermite, PsSpline, PsTriangleChoice, SplitRule};
    use crate::test_util::meshes::catalogue;
    use crate::test_util::*;
    use std::sync::Arc;

    /// The Hermite PS-spline of the quadratic with coefficients c, and its control values.
    fn quadratic_spline(basis: &Arc<PsBasis>, c: &[f64; 6]) -> Vec<[f64; 3]> {
        let data: Vec<Hermite<f64>> = basis
            .triangulation()
            .vertices()
            .iter()
            .map(|p| Hermite {
                value: c[0]
                    + c[1] * p.x
                    + c[2] * p.y
                    + c[3] * p.x * p.x
                    + c[4] * p.x * p.y
                    + c[5] * p.y * p.y,
                dx: c[1] + 2.0 * c[3] * p.x + c[4] * p.y,
                dy: c[2] + c[4] * p.x + 2.0 * c[5] * p.y,
            })
            .collect();
        PsSpline::hermite(basis.clone(), &data)
            .unwrap()
            .coefficients()
            .to_vec()
    }

    #[test]
    fn energies_of_quadratics_are_their_closed_forms() {
        let mut r = rng(81);
        for (name, t) in catalogue(4) {
            for rule in [SplitRule::Incenter, SplitRule::Centroid] {
                let Ok(b) = PsBasis::new(t.clone(), rule, &PsTriangleChoice::Optimal) else {
                    continue;
                };
                let b = Arc::new(b);
                let area = b.triangulation().area();
                let thin = b.energy_matrix(Energy::ThinPlate);
                let jumps = b.energy_matrix(Energy::HessianJumps);
                for _ in 0..3 {
                    let c: [f64; 6] = std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0));
                    let ctrl = quadratic_spline(&b, &c);
                    // f_xx = 2 c3, f_xy = c4, f_yy = 2 c5.
                    let exact = area * (4.0 * c[3] * c[3] + 2.0 * c[4] * c[4] + 4.0 * c[5] * c[5]);
                    // Rounding bound: the form with absolute values, cᵀ|Q|c.
                    let e = thin.quadratic_form(&ctrl);
                    let bound = absolute_form(&thin, &ctrl);
                    assert!(
                        (e - exact).abs() <= 1e-14 * bound,
                        "{name}: {e} vs {exact} (bound {bound})"
                    );
                    let ej = jumps.quadratic_form(&ctrl);
                    let bound = absolute_form(&jumps, &ctrl);
                    assert!(
                        ej.abs() <= 1e-14 * bound,
                        "{name}: jump energy {ej} (bound {bound})"
                    );
                }
            }
        }
    }

    #[test]
    fn energies_match_piecewise_second_derivatives_of_random_splines() {
        let mut r = rng(82);
        let mut total_faded = 0;
        for (name, t) in catalogue(3) {
            let b = Arc::new(PsBasis::optimal(t.clone()).unwrap());
            let n = b.triangulation().vertex_count();
            let ctrl: Vec<[f64; 3]> = (0..n)
                .map(|_| std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0)))
                .collect();
            let s = PsSpline::new(b.clone(), ctrl.clone()).unwrap();
            // Second derivatives from the evaluated jets at each piece's centroid.
            let mut thin = 0.0;
            let mut jumps = 0.0;
            // The interpolation energy: each jump also weighted by the smaller of
            // min(1, 20 h / D)⁴ of its two pieces (h the piece's smallest height, D the
            // diameter of its triangle).
            let mut faded = 0.0;
            let fade = |p: &crate::geometry::Triangle2, tr: usize| {
                let sides = [p.v[1] - p.v[0], p.v[2] - p.v[1], p.v[0] - p.v[2]];
                let longest = sides.iter().map(|d| d.norm()).fold(0.0, f64::max);
                let height = 2.0 * p.area().abs() / longest;
                let t = b
                    .triangulation()
                    .triangle(tr)
                    .map(|v| b.triangulation().vertex(v));
                let diameter = [(0, 1), (1, 2), (2, 0)]
                    .iter()
                    .map(|&(i, j)| (t[i] - t[j]).norm())
                    .fold(0.0, f64::max);
                (20.0 * height / diameter).min(1.0).powi(4)
            };
            let mut faded_pieces = 0;
            let hess = |tr: usize, k: usize| {
                let piece = b.sub_triangle(tr, k);
                let jet = s.jet_on_patch(crate::ps::PatchId::new(tr, k), piece.centroid());
                [jet.dxx, jet.dxy, jet.dyy]
            };
            let tri = b.triangulation();
            for tr in 0..tri.triangle_count() {
                let pieces = b.refinement().sub_triangles(tri, tr);
                for k in 0..6 {
                    let h = hess(tr, k);
                    thin += pieces[k].area() * (h[0] * h[0] + 2.0 * h[1] * h[1] + h[2] * h[2]);
                    let next = (k + 1) % 6;
                    let hn = hess(tr, next);
                    let len2 = (pieces[k].v[1] - pieces[k].v[2]).norm_squared();
                    let w = (4.0 * (pieces[k].area() + pieces[next].area()) / len2).min(1.0);
                    jumps += w * sq_frob(h, hn);
                    faded += fade(&pieces[k], tr).min(fade(&pieces[next], tr)) * w * sq_frob(h, hn);
                    faded_pieces += usize::from(fade(&pieces[k], tr) < 1.0);
                }
                for c in 0..3 {
                    let Some(n) = tri.neighbor(tr, crate::ps::refinement::edge_to_local(c)) else {
                        continue;
                    };
                    if n < tr {
                        continue;
                    }
                    // Find the neighbour's pieces touching each segment by their shared edge points.
                    let np = b.refinement().sub_triangles(tri, n);
                    for mine in [2 * c, 2 * c + 1] {
                        let (a0, a1) = (pieces[mine].v[0], pieces[mine].v[1]);
                        let theirs = (0..6)
                            .find(|&k| {
                                let (b0, b1) = (np[k].v[0], np[k].v[1]);
                                let close = |p: nalgebra::Point2<f64>, q: nalgebra::Point2<f64>| {
                                    (p - q).norm() <= 1e-12 * (1.0 + p.coords.norm())
                                };
                                close(b0, a1) && close(b1, a0)
                            })
                            .unwrap_or_else(|| panic!("{name}: no matching piece"));
                        let w = (4.0 * (pieces[mine].area() + np[theirs].area())
                            / (a1 - a0).norm_squared())
                        .min(1.0);
                        let square = sq_frob(hess(tr, mine), hess(n, theirs));
                        jumps += w * square;
                        faded += fade(&pieces[mine], tr).min(fade(&np[theirs], n)) * w * square;
                    }
                }
            }
            let q_thin = b.energy_matrix(Energy::ThinPlate).quadratic_form(&ctrl);
            let q_jump = b.energy_matrix(Energy::HessianJumps).quadratic_form(&ctrl);
            let q_faded = b.faded_jump_energy_matrix().quadratic_form(&ctrl);
            assert!(
                (q_faded - faded).abs() <= 1e-10 * faded,
                "{name}: {q_faded} vs {faded}"
            );
            total_faded += faded_pieces;
            assert!(
                (q_thin - thin).abs() <= 1e-10 * thin,
                "{name}: {q_thin} vs {thin}"
            );
            assert!(
                (q_jump - jumps).abs() <= 1e-10 * jumps,
                "{name}: {q_jump} vs {jumps}"
            );
        }
        assert!(total_faded > 0, "some pieces are thin enough to fade");
    }

    /// Σ |Q_ab| |c_a| |c_b|: the size of the terms whose sum is cᵀQc.
    fn absolute_form(q: &crate::sparse::Block3Matrix, c: &[[f64; 3]]) -> f64 {
        let abs: Vec<[f64; 3]> = c.iter().map(|x| x.map(f64::abs)).collect();
        let mut sum = 0.0;
        for (i, j, b) in q.blocks() {
            for r in 0..3 {
                for k in 0..3 {
                    let t = b[r][k].abs() * abs[i][r] * abs[j][k];
                    sum += if i == j { t } else { 2.0 * t };
                }
            }
        }
        sum
    }

    fn sq_frob(a: [f64; 3], b: [f64; 3]) -> f64 {
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        d[0] * d[0] + 2.0 * d[1] * d[1] + d[2] * d[2]
    }
}
