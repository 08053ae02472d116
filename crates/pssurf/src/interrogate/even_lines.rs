//! Evenly spaced field lines (Jobard and Lefer, "Creating evenly-spaced streamlines of
//! arbitrary density", 1997), in the parameter domain: a line is traced from a seed until it
//! comes within half the spacing of another line; new seeds are taken at the spacing on both
//! sides of every accepted line, and kept only if no line passes within the spacing; a final
//! sweep over a lattice of the domain seeds what the lines' neighbourhoods did not reach
//! (regions cut off by umbilics, jumps or the boundary).

use std::collections::HashMap;

use nalgebra::{Point2, Vector2};

use super::field_lines::{FieldLine, FieldLineOptions, LineFamily, trace_guarded};
use crate::surface::ParametricSurface;

/// Evenly spaced lines of one family.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EvenLines {
    /// The lines, in the order they were traced.
    pub lines: Vec<FieldLine>,
    /// The points in all lines.
    pub points: usize,
    /// Whether the point limit stopped the seeding before the domain was covered.
    pub truncated: bool,
}

/// Points of the accepted lines, hashed by cells of the spacing.
struct Occupancy {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<Point2<f64>>>,
}

impl Occupancy {
    fn key(&self, p: Point2<f64>) -> (i64, i64) {
        (
            (p.x / self.cell).floor() as i64,
            (p.y / self.cell).floor() as i64,
        )
    }

    /// Whether a stored point lies within `d` (at most the cell size) of `p`.
    fn near(&self, p: Point2<f64>, d: f64) -> bool {
        let (i, j) = self.key(p);
        (-1..=1).any(|di| {
            (-1..=1).any(|dj| {
                self.cells
                    .get(&(i + di, j + dj))
                    .is_some_and(|v| v.iter().any(|q| (q - p).norm() < d))
            })
        })
    }

    /// Stores the polyline's points, with extra points so that none is more than a quarter of
    /// the cell from the next.
    fn insert(&mut self, uvs: &[Point2<f64>]) {
        for w in uvs.windows(2) {
            let n = ((w[1] - w[0]).norm() / (0.25 * self.cell)).ceil().max(1.0) as usize;
            for i in 0..n {
                self.add(w[0] + (w[1] - w[0]) * (i as f64 / n as f64));
            }
        }
        if let Some(p) = uvs.last() {
            self.add(*p);
        }
    }

    fn add(&mut self, p: Point2<f64>) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push(p);
    }
}

/// Whether `p` comes within `d` of the walk's own earlier points, leaving out the stretch
/// within 4d of arc behind it (a spiral around an umbilic or a focus).
fn spirals(p: Point2<f64>, walked: &[Point2<f64>], d: f64) -> bool {
    let mut behind = 0.0;
    let mut previous = p;
    for q in walked.iter().rev() {
        behind += (previous - q).norm();
        previous = *q;
        if behind > 4.0 * d && (p - q).norm() < d {
            return true;
        }
    }
    false
}

/// Lines of `family` spaced about `spacing` apart in the parameter domain, with at most
/// `max_points` points in all.
pub fn even_field_lines<S: ParametricSurface + ?Sized>(
    surface: &S,
    family: LineFamily,
    spacing: f64,
    opts: &FieldLineOptions,
    max_points: usize,
) -> EvenLines {
    let mut out = EvenLines::default();
    if !(spacing > 0.0 && spacing.is_finite()) {
        return out;
    }
    let mut occupied = Occupancy {
        cell: spacing,
        cells: HashMap::new(),
    };
    let (lo, hi) = surface.domain_bounds();
    // Points no farther apart than a quarter of the spacing, so the guard sees every approach.
    let opts = &FieldLineOptions {
        max_step: opts.max_step.min(0.25 * spacing / (hi - lo).norm()),
        ..*opts
    };
    let mut next = 0;
    let try_seed = |seed: Point2<f64>, out: &mut EvenLines, occupied: &mut Occupancy| {
        if out.points >= max_points {
            out.truncated = true;
            return;
        }
        if occupied.near(seed, spacing) || surface.jet(seed).is_err() {
            return;
        }
        let line = {
            let occ = &*occupied;
            trace_guarded(surface, family, seed, opts, &mut |p, walked| {
                occ.near(p, 0.5 * spacing) || spirals(p, walked, 0.5 * spacing)
            })
        };
        if let Ok(line) = line
            && line.curve.uvs.len() >= 2
        {
            occupied.insert(&line.curve.uvs);
            if line.curve.closed {
                occupied.insert(&[*line.curve.uvs.last().unwrap(), line.curve.uvs[0]]);
            }
            out.points += line.curve.uvs.len();
            out.lines.push(line);
        }
    };
    try_seed(
        Point2::from((lo.coords + hi.coords) * 0.5),
        &mut out,
        &mut occupied,
    );
    let lattice = |i: usize, j: usize| {
        Point2::new(
            lo.x + spacing * (i as f64 + 0.5),
            lo.y + spacing * (j as f64 + 0.5),
        )
    };
    let (ni, nj) = (
        ((hi.x - lo.x) / spacing).ceil() as usize,
        ((hi.y - lo.y) / spacing).ceil() as usize,
    );
    let mut sweep = 0;
    loop {
        // Seeds beside the lines already traced, in the order they were traced.
        while next < out.lines.len() && !out.truncated {
            let uvs = out.lines[next].curve.uvs.clone();
            next += 1;
            let mut since = f64::INFINITY;
            for w in uvs.windows(2) {
                since += (w[1] - w[0]).norm();
                if since < 0.5 * spacing {
                    continue;
                }
                since = 0.0;
                let t = w[1] - w[0];
                let Some(n) = Vector2::new(-t.y, t.x).try_normalize(0.0) else {
                    continue;
                };
                for side in [1.0, -1.0] {
                    try_seed(w[0] + n * (side * spacing), &mut out, &mut occupied);
                }
            }
        }
        if out.truncated {
            return out;
        }
        // The lattice sweep: the first free lattice point seeds a new line, whose
        // neighbours are then seeded as above.
        let before = out.lines.len();
        while sweep < ni * nj && out.lines.len() == before {
            try_seed(lattice(sweep % ni, sweep / ni), &mut out, &mut occupied);
            sweep += 1;
        }
        if out.lines.len() == before {
            return out;
        }
    }
}
