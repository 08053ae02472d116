//! Times the phases of building a PS basis and its Bézier nets on a large random Delaunay
//! triangulation: `cargo run --release -p pssurf --example profile_basis -- 1000000`.

use std::sync::Arc;
use std::time::Instant;

use nalgebra::Point2;
use pssurf::prelude::*;
use pssurf::ps::PsRefinement;
use pssurf::ps::ps_triangles::{ps_points, ps_triangles};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let sorted = std::env::args().any(|a| a == "--sorted");
    // A deterministic low-discrepancy point set (no randomness crate needed here).
    let pts: Vec<Point2<f64>> = (0..n)
        .map(|k| {
            let k = k as f64 + 0.5;
            Point2::new(
                (k * 0.754_877_666_246_692_7).fract(),
                (k * 0.569_840_290_998_053_2).fract(),
            )
        })
        .collect();
    // With --sorted, the points come in the order of a space-filling curve (as scanned or
    // gridded data usually do); by default their order is scattered.
    let pts: Vec<Point2<f64>> = if sorted {
        pssurf::triangulation::morton_order(&pts)
            .into_iter()
            .map(|i| pts[i as usize])
            .collect()
    } else {
        pts
    };
    let t0 = Instant::now();
    let tri = Triangulation::delaunay(pts).expect("points triangulate");
    println!(
        "delaunay + validation     {:8.3} s  ({} triangles)",
        t0.elapsed().as_secs_f64(),
        tri.triangle_count()
    );
    let t = Instant::now();
    let refinement = PsRefinement::new(&tri, SplitRule::Incenter).unwrap();
    println!(
        "refinement                {:8.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let total: usize = (0..tri.vertex_count())
        .map(|i| ps_points(&tri, &refinement, i).len())
        .sum();
    println!(
        "PS-points (sequential)    {:8.3} s  ({:.1} per vertex)",
        t.elapsed().as_secs_f64(),
        total as f64 / n as f64
    );
    let t = Instant::now();
    let _ = ps_triangles(&tri, &refinement, &PsTriangleChoice::Optimal).unwrap();
    println!(
        "optimal PS-triangles      {:8.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let basis =
        Arc::new(PsBasis::with_refinement(tri, refinement, &PsTriangleChoice::Optimal).unwrap());
    println!(
        "basis (incl. triangles)   {:8.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let s = PsSpline::new(basis.clone(), vec![[0.5f64; 3]; n]).unwrap();
    println!(
        "nets                      {:8.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let b2 = PsBasis::optimal(basis.triangulation().clone()).unwrap();
    let _ = PsSpline::new(Arc::new(b2), vec![[0.5f64; 3]; n]).unwrap();
    println!(
        "basis + nets, end to end  {:8.3} s",
        t.elapsed().as_secs_f64()
    );
    std::hint::black_box(s);
}
