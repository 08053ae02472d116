//! The interior control triangles of a filling patch (thesis 5.4.2–5.4.3). Every method keeps
//! the boundary control triangles of the fitting bitwise.

use nalgebra::Vector3;

use super::HoleError;
use crate::ps::Energy;
use crate::ps::fair::{FairOptions, fair};
use crate::surface::{Surface, UniformSurface, UpsSurface};
use crate::ups::subdivision::edge_subdivision;
use crate::ups::threshold::{Shrink, ThresholdRule};
use crate::ups::wavelet::Update;
use crate::ups::{Ups, UpsGrid};

/// How the interior control triangles are found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Interior {
    /// "Copy from initial solution": the initial solution subdivided, only the boundary
    /// replaced.
    Copy,
    /// "Average surrounding control triangles": ring by ring from the boundary inwards, each
    /// triangle the mean of its six neighbours (from the previous ring where computed, else
    /// from the initial solution), after the last step.
    Average,
    /// "Instant update": the initial solution subdivided at every step with its boundary
    /// overwritten by the latest fit (the thesis' cheap recommendation).
    Instant,
    /// "Bridging" by k-subdivision (4.37)–(4.42) between opposite boundary triangles along
    /// the three lattice directions, the three results averaged.
    Bridge,
    /// The instant update smoothed by wavelet thresholding (4.5.6) with the control
    /// triangles on and next to the boundary kept: every detail coefficient below `percent`
    /// % of its level's largest is set to zero.
    Threshold {
        /// The percentage (the thesis uses 5 or 10).
        percent: f64,
    },
    /// Constrained fairing (5.4.3): least squares on the jumps of the second derivatives
    /// across the edges of the PS refinement, boundary triangles fixed, by sparse Cholesky.
    Fair,
}

impl Interior {
    /// Every method, for comparisons.
    pub const ALL: [Interior; 6] = [
        Interior::Copy,
        Interior::Average,
        Interior::Instant,
        Interior::Bridge,
        Interior::Threshold { percent: 10.0 },
        Interior::Fair,
    ];

    /// The method's name as the CLI spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Interior::Copy => "copy",
            Interior::Average => "average",
            Interior::Instant => "instant",
            Interior::Bridge => "subdivision",
            Interior::Threshold { .. } => "threshold",
            Interior::Fair => "fair",
        }
    }

    /// The method named `name` (`subdivision` and `bridge` are the same method).
    pub fn from_name(name: &str) -> Option<Interior> {
        Some(match name {
            "copy" => Interior::Copy,
            "average" => Interior::Average,
            "instant" => Interior::Instant,
            "subdivision" | "bridge" => Interior::Bridge,
            "threshold" => Interior::Threshold { percent: 10.0 },
            "fair" => Interior::Fair,
            _ => return None,
        })
    }
}

/// The patch at refinement `level` with interior triangles by `method`, from the
/// instant-update patch (its boundary the latest fit) and the initial solution subdivided to
/// the same level.
pub(crate) fn interior(
    instant: &Ups<Vector3<f64>>,
    initial: &Ups<Vector3<f64>>,
    level: usize,
    method: Interior,
) -> Result<Ups<Vector3<f64>>, HoleError> {
    Ok(match method {
        Interior::Instant => instant.clone(),
        Interior::Copy => with_boundary_of(initial, instant, 0),
        Interior::Average => averaged(&with_boundary_of(initial, instant, 0)),
        Interior::Bridge => bridged(instant),
        Interior::Threshold { percent } => thresholded(instant, level, percent)?,
        Interior::Fair => fair_interior(instant)?,
    })
}

/// The distance (in edges) of every real slot from the boundary: 0 on it.
pub fn rings(grid: &UpsGrid) -> Vec<usize> {
    let mut ring = vec![usize::MAX; grid.slots()];
    let mut front: Vec<usize> = grid
        .real_slots()
        .into_iter()
        .filter(|&s| grid.is_boundary(s))
        .collect();
    for &s in &front {
        ring[s] = 0;
    }
    let mut r = 0;
    while !front.is_empty() {
        r += 1;
        let mut next = Vec::new();
        for &s in &front {
            for dir in 0..6 {
                if let Some(t) = grid.neighbor(s, dir)
                    && grid.is_real(t)
                    && ring[t] == usize::MAX
                {
                    ring[t] = r;
                    next.push(t);
                }
            }
        }
        front = next;
    }
    ring
}

/// `base` with the control triangles of `source` on the slots within `depth` rings of the
/// boundary.
fn with_boundary_of(
    base: &Ups<Vector3<f64>>,
    source: &Ups<Vector3<f64>>,
    depth: usize,
) -> Ups<Vector3<f64>> {
    let ring = rings(base.grid());
    let mut out = base.clone();
    for s in base.grid().real_slots() {
        if ring[s] <= depth {
            out.blocks_mut()[s] = source.blocks()[s];
        }
    }
    out
}

/// Ring-by-ring averaging of the six neighbours (5.4.2, Figure 5.13).
fn averaged(start: &Ups<Vector3<f64>>) -> Ups<Vector3<f64>> {
    let grid = start.grid().clone();
    let ring = rings(&grid);
    let deepest = grid
        .real_slots()
        .iter()
        .map(|&s| ring[s])
        .max()
        .unwrap_or(0);
    let mut out = start.clone();
    for r in 1..=deepest {
        let updates: Vec<(usize, [Vector3<f64>; 3])> = grid
            .real_slots()
            .into_iter()
            .filter(|&s| ring[s] == r)
            .map(|s| {
                let mut sum = [Vector3::zeros(); 3];
                let mut count = 0.0;
                for dir in 0..6 {
                    if let Some(t) = grid.neighbor(s, dir).filter(|&t| grid.is_real(t)) {
                        for (acc, c) in sum.iter_mut().zip(out.blocks()[t]) {
                            *acc += c;
                        }
                        count += 1.0;
                    }
                }
                (s, sum.map(|v| v / count))
            })
            .collect();
        for (s, c) in updates {
            out.blocks_mut()[s] = c;
        }
    }
    out
}

/// The control triangle scaled by `k` about its centroid: the inverse of k-subdivision at
/// l = 0, which shrinks it by 1/k ((4.37)–(4.39) with l = 0).
fn scaled_up(c: [Vector3<f64>; 3], k: usize) -> [Vector3<f64>; 3] {
    let g = (c[0] + c[1] + c[2]) / 3.0;
    c.map(|p| g + (p - g) * k as f64)
}

/// Bridging (5.4.2, Figure 5.16): for each lattice direction, each run of interior vertices
/// between two boundary vertices L and R at distance k gets the triangles of k-subdivision of
/// the edge L R, after scaling L's and R's triangles up by k; the three directions are
/// averaged.
fn bridged(patch: &Ups<Vector3<f64>>) -> Ups<Vector3<f64>> {
    let grid = patch.grid();
    let mut sum = vec![[Vector3::zeros(); 3]; grid.slots()];
    let mut count = vec![0.0f64; grid.slots()];
    let interior = |s: usize| grid.is_real(s) && !grid.is_boundary(s);
    for dir in 0..3 {
        for left in grid.real_slots() {
            if !grid.is_boundary(left) {
                continue;
            }
            let mut run = Vec::new();
            let mut s = left;
            let right = loop {
                match grid.neighbor(s, dir).filter(|&t| grid.is_real(t)) {
                    Some(t) if interior(t) => {
                        run.push(t);
                        s = t;
                    }
                    Some(t) => break Some(t),
                    None => break None,
                }
            };
            let Some(right) = right.filter(|_| !run.is_empty()) else {
                continue;
            };
            let k = run.len() + 1;
            let bridge = edge_subdivision(
                scaled_up(patch.blocks()[left], k),
                scaled_up(patch.blocks()[right], k),
                k,
                dir,
            );
            for (l, &s) in run.iter().enumerate() {
                for (acc, c) in sum[s].iter_mut().zip(bridge[l + 1]) {
                    *acc += c;
                }
                count[s] += 1.0;
            }
        }
    }
    let mut out = patch.clone();
    for s in grid.real_slots() {
        if interior(s) && count[s] > 0.0 {
            out.blocks_mut()[s] = sum[s].map(|v| v / count[s]);
        }
    }
    out
}

/// Wavelet thresholding of the interior (5.4.2), the two outer rings restored.
fn thresholded(
    patch: &Ups<Vector3<f64>>,
    levels: usize,
    percent: f64,
) -> Result<Ups<Vector3<f64>>, HoleError> {
    if levels == 0 {
        return Ok(patch.clone());
    }
    let surface = UpsSurface::Parametric(patch.clone());
    // The thesis' transform, as 5.4.2 uses it.
    let (smooth, _) = surface
        .denoise_with(
            levels as u32,
            |_, _| ThresholdRule::PercentOfMax(percent),
            Shrink::Hard,
            Update::Thesis,
        )
        .map_err(HoleError::Ups)?;
    let UpsSurface::Parametric(smooth) = smooth else {
        unreachable!("a parametric surface stays parametric")
    };
    Ok(with_boundary_of(&smooth, patch, 1))
}

/// Constrained fairing (5.4.3) of the interior with weight 0: the fairest patch with these
/// boundary triangles.
pub(crate) fn fair_interior(patch: &Ups<Vector3<f64>>) -> Result<Ups<Vector3<f64>>, HoleError> {
    let grid = patch.grid();
    if grid.real_slots().iter().all(|&s| grid.is_boundary(s)) {
        return Ok(patch.clone());
    }
    let s = Surface::Uniform(
        UniformSurface::new(UpsSurface::Parametric(patch.clone()))
            .map_err(|e| HoleError::Fair(e.to_string()))?,
    );
    let faired = fair(
        &s,
        &FairOptions {
            weight: 0.0,
            energy: Energy::HessianJumps,
        },
    )
    .map_err(|e| HoleError::Fair(e.to_string()))?;
    match faired.surface {
        Surface::Uniform(u) => match u.ups() {
            UpsSurface::Parametric(p) => Ok(p.clone()),
            _ => unreachable!("fairing keeps the kind"),
        },
        _ => unreachable!("fairing keeps the kind"),
    }
}

#[cfg(test)]
pub(crate) fn bridged_for_tests(patch: &Ups<Vector3<f64>>) -> Ups<Vector3<f64>> {
    bridged(patch)
}
