//! Times `interpolate` (the scattered-data fit) on N random points, repeated R times, for
//! profiling: `cargo run --release -p pssurf --example profile_fit -- 10000 200
//! [--global | --jumps] [--circumscribed]` (the last: PS-triangles for evaluation, as the Python interpolant).

use std::sync::Arc;
use std::time::Instant;

use nalgebra::Point2;
use pssurf::prelude::*;
use pssurf::scattered::{
    GradientMethod, NEAR_DUPLICATE, data_basis_with, estimate_gradients_by, hermite_data,
    hermite_spline_with, interpolate_with, merge_near_duplicates,
};

#[path = "../benches/common.rs"]
mod common;

// As the CLI and the Python package: freed memory is reused, not returned to the system.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let [n, repeats] = common::count_args([10_000, 50]);
    let method = if std::env::args().any(|a| a == "--global") {
        GradientMethod::Global
    } else if std::env::args().any(|a| a == "--jumps") {
        GradientMethod::Jumps
    } else {
        GradientMethod::Local
    };
    let choice = if std::env::args().any(|a| a == "--circumscribed") {
        PsTriangleChoice::Circumscribed
    } else {
        PsTriangleChoice::Optimal
    };
    let pts = common::random_points(n, 1);
    let z = common::franke_values(&pts);
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t = Instant::now();
        let f = interpolate_with(&pts, &z, method, &choice).expect("the fit succeeds");
        best = best.min(t.elapsed().as_secs_f64());
        std::hint::black_box(f);
    }
    println!("{n} points: best of {repeats} fits {:.2} ms", best * 1e3);
    phases(&pts, &z, repeats, method, &choice);
}

/// The best time of each phase of `interpolate`, run one after the other as it does.
fn phases(
    pts: &[Point2<f64>],
    z: &[f64],
    repeats: usize,
    method: GradientMethod,
    choice: &PsTriangleChoice,
) {
    let mut best = [f64::INFINITY; 7];
    let names = [
        "checks",
        "merge",
        "order",
        "delaunay",
        "basis",
        "gradients",
        "hermite nets",
    ];
    for _ in 0..repeats {
        let mut lap = Lap::new();
        pssurf::triangulation::check_coordinates(pts).unwrap();
        assert!(pssurf::triangulation::duplicate_points(pts).is_none());
        lap.mark(&mut best[0]);
        let data = merge_near_duplicates(pts, z, NEAR_DUPLICATE);
        lap.mark(&mut best[1]);
        let order = pssurf::triangulation::morton_order(&data.points);
        let ordered: Vec<Point2<f64>> = order.iter().map(|&k| data.points[k as usize]).collect();
        let zz: Vec<f64> = order.iter().map(|&k| data.values[k as usize]).collect();
        lap.mark(&mut best[2]);
        let tri = Triangulation::delaunay(ordered).unwrap();
        lap.mark(&mut best[3]);
        let basis = Arc::new(data_basis_with(tri, SplitRule::Incenter, choice).unwrap());
        lap.mark(&mut best[4]);
        let (g, _) = estimate_gradients_by(&basis, &zz, method).unwrap();
        lap.mark(&mut best[5]);
        let data = hermite_data(&zz, &g);
        std::hint::black_box(hermite_spline_with(basis, &data, choice).unwrap());
        lap.mark(&mut best[6]);
    }
    for (name, t) in names.iter().zip(best) {
        println!("  {name:<18} {:7.2} ms", t * 1e3);
    }
}

/// Laps of a stopwatch, each kept as the best seen.
struct Lap(Instant);

impl Lap {
    fn new() -> Self {
        Lap(Instant::now())
    }
    fn mark(&mut self, best: &mut f64) {
        *best = best.min(self.0.elapsed().as_secs_f64());
        self.0 = Instant::now();
    }
}
