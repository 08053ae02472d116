//! Times `values_on_grid` on a 1000 × 1000 grid over a spline on N random points, for
//! profiling: `cargo run --release -p pssurf --example profile_grid -- 10000 50`.

use std::time::Instant;

use pssurf::scattered::{GradientMethod, interpolate};

#[path = "../benches/common.rs"]
mod common;

// As the CLI and the Python package: freed memory is reused, not returned to the system.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let [n, repeats] = common::count_args([10_000, 50]);
    let pts = common::random_points(n, 1);
    let z = common::franke_values(&pts);
    let f = interpolate(&pts, &z, GradientMethod::Local).expect("the fit succeeds");
    // SIDE=k in the environment: a k × k grid instead; SIDEY=m: k × m (to separate the cost
    // per grid line and triangle from the cost per point).
    let side: usize = std::env::var("SIDE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let axis: Vec<f64> = (0..side).map(|k| k as f64 / (side - 1) as f64).collect();
    let ny: usize = std::env::var("SIDEY")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(side);
    let yaxis: Vec<f64> = (0..ny).map(|k| k as f64 / (ny - 1) as f64).collect();
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t = Instant::now();
        std::hint::black_box(f.spline.values_on_grid(&axis, &yaxis, f64::NAN));
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{n} vertices, {side} x {ny} grid: best of {repeats} {:.2} ms = {:.0} M points/s",
        best * 1e3,
        (side * ny) as f64 / best / 1e6
    );
}
