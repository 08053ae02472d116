//! Times `map_scattered` (1M random queries) and `morton_order` alone on a spline over N
//! random points: `cargo run --release -p pssurf --example profile_scattered -- 10000 20`.

use std::time::Instant;

use pssurf::scattered::{GradientMethod, interpolate};
use pssurf::triangulation::morton_order;

#[path = "../benches/common.rs"]
mod common;

// As the CLI and the Python package: freed memory is reused, not returned to the system.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    let [n, repeats] = common::count_args([10_000, 20]);
    let pts = common::random_points(n, 1);
    let z = common::franke_values(&pts);
    let f = interpolate(&pts, &z, GradientMethod::Local).expect("the fit succeeds");
    f.spline.basis().triangulation().prepare_locator();
    let queries = common::random_points(1_000_000, 2);
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
