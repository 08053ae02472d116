//! Builds the basis and nets on a random-order 1M-vertex Delaunay mesh, for profiling:
//! `cargo run --release -p pssurf --example profile_basis_only`.

use std::sync::Arc;
use std::time::Instant;

use nalgebra::Point2;
use pssurf::prelude::*;

fn main() {
    let n = 1_000_000;
    let mut s: u64 = 0x9E3779B97F4A7C15;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let pts: Vec<Point2<f64>> = (0..n).map(|_| Point2::new(next(), next())).collect();
    let tri = Triangulation::delaunay(pts).unwrap();
    tri.spatial_order();
    for _ in 0..3 {
        let t = tri.clone();
        let start = Instant::now();
        let basis = Arc::new(PsBasis::optimal(t).unwrap());
        let spline = PsSpline::new(basis, vec![[0.5f64; 3]; n]).unwrap();
        println!("basis + nets: {:.3} s", start.elapsed().as_secs_f64());
        std::hint::black_box(spline);
    }
}
