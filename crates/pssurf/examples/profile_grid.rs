//! Times `values_on_grid` on a 1000 × 1000 grid over a spline on N random points, for
//! profiling: `cargo run --release -p pssurf --example profile_grid -- 10000 50`.

use std::time::Instant;

use nalgebra::Point2;
use pssurf::scattered::{GradientMethod, interpolate};

fn main() {
    let mut args = std::env::args().skip(1).map(|s| s.parse::<usize>().ok());
    let n = args.next().flatten().unwrap_or(10_000);
    let repeats = args.next().flatten().unwrap_or(50);
    let mut s = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let pts: Vec<Point2<f64>> = (0..n).map(|_| Point2::new(next(), next())).collect();
    let z: Vec<f64> = pts
        .iter()
        .map(|p| (3.0 * p.x).sin() * (2.0 * p.y).cos())
        .collect();
    let f = interpolate(&pts, &z, GradientMethod::Local).expect("the fit succeeds");
    let axis: Vec<f64> = (0..1000).map(|k| k as f64 / 999.0).collect();
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t = Instant::now();
        std::hint::black_box(f.spline.values_on_grid(&axis, &axis, f64::NAN));
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{n} vertices, 1000 x 1000 grid: best of {repeats} {:.2} ms = {:.0} M points/s",
        best * 1e3,
        1.0 / best
    );
}
