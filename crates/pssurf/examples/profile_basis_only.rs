//! Builds the basis and nets on a random-order 1M-vertex Delaunay mesh, for profiling:
//! `cargo run --release -p pssurf --example profile_basis_only`.

use std::sync::Arc;
use std::time::Instant;

use pssurf::prelude::*;

#[path = "../benches/common.rs"]
mod common;

fn main() {
    let n = 1_000_000;
    let pts = common::random_points(n, 1);
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
