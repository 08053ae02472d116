//! Statistics and timing of the optimal PS-triangle kernel on the PS-point sets of a random
//! Delaunay mesh: `cargo run --release -p pssurf --example profile_ps_triangles`.

use std::time::Instant;

use nalgebra::Point2;
use pssurf::geometry::{convex_hull, min_enclosing_triangle};
use pssurf::prelude::*;
use pssurf::ps::PsRefinement;
use pssurf::ps::ps_triangles::ps_points;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    let pts: Vec<Point2<f64>> = (0..n)
        .map(|k| {
            let k = k as f64 + 0.5;
            Point2::new(
                (k * 0.754_877_666_246_692_7).fract(),
                (k * 0.569_840_290_998_053_2).fract(),
            )
        })
        .collect();
    let tri = Triangulation::delaunay(pts).unwrap();
    let refinement = PsRefinement::new(&tri, SplitRule::Incenter).unwrap();
    let sets: Vec<Vec<Point2<f64>>> = (0..n).map(|i| ps_points(&tri, &refinement, i)).collect();
    let mut hist = [0usize; 40];
    for s in &sets {
        hist[convex_hull(s).len().min(39)] += 1;
    }
    println!(
        "hull sizes: {:?}",
        hist.iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .collect::<Vec<_>>()
    );
    let t = Instant::now();
    let mut acc = 0.0;
    for s in &sets {
        acc += convex_hull(s).len() as f64;
    }
    println!(
        "hulls:     {:.0} ns per set",
        t.elapsed().as_nanos() as f64 / n as f64
    );
    let t = Instant::now();
    for s in &sets {
        acc += min_enclosing_triangle(s).unwrap().area();
    }
    println!(
        "triangles: {:.0} ns per set (incl. hull)  [{acc:.3}]",
        t.elapsed().as_nanos() as f64 / n as f64
    );
}
