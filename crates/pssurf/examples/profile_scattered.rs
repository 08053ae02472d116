//! Times `map_scattered` (1M random queries) and `morton_order` alone on a spline over N
//! random points: `cargo run --release -p pssurf --example profile_scattered -- 10000 20`.

use std::time::Instant;

use nalgebra::Point2;
use pssurf::scattered::{GradientMethod, interpolate};
use pssurf::triangulation::morton_order;

fn main() {
    let mut args = std::env::args().skip(1).map(|s| s.parse::<usize>().ok());
    let n = args.next().flatten().unwrap_or(10_000);
    let repeats = args.next().flatten().unwrap_or(20);
    let mut s = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut random =
        |k: usize| -> Vec<Point2<f64>> { (0..k).map(|_| Point2::new(next(), next())).collect() };
    let pts = random(n);
    let z: Vec<f64> = pts
        .iter()
        .map(|p| (3.0 * p.x).sin() * (2.0 * p.y).cos())
        .collect();
    let f = interpolate(&pts, &z, GradientMethod::Local).expect("the fit succeeds");
    f.spline.basis().triangulation().prepare_locator();
    let queries = random(1_000_000);
    let (mut all, mut order) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..repeats {
        let t = Instant::now();
        std::hint::black_box(f.spline.map_scattered(&queries, |ev, p| ev.value(p)));
        all = all.min(t.elapsed().as_secs_f64());
        let t = Instant::now();
        std::hint::black_box(morton_order(&queries));
        order = order.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{n} vertices, 1M queries: map_scattered {:.1} ms ({:.1} M/s), of which morton_order {:.1} ms",
        all * 1e3,
        1e-3 / all * 1e3,
        order * 1e3
    );
}
