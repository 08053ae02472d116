//! Times the phases of fairing a noisy UPS hexagon (the `fair` bench's surface), for
//! profiling: `cargo run --release -p pssurf --example profile_fair -- SIZE [WEIGHT]` (182:
//! about 100k vertices, 577: about 1M).

use std::time::Instant;

use pssurf::ps::{Energy, FairOptions, fair};

#[path = "../benches/support/noisy_wave.rs"]
mod noisy_wave;

fn main() {
    let size: i64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(182);
    let weight: f64 = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0.1);
    let s = noisy_wave::noisy_wave(size);
    let basis = s.ps_basis().unwrap().clone();
    println!("{} vertices", basis.triangulation().vertex_count());
    let t = Instant::now();
    let q = basis.energy_matrix(Energy::HessianJumps);
    println!(
        "energy matrix: {:.3} s, {} blocks",
        t.elapsed().as_secs_f64(),
        q.block_count()
    );
    for _ in 0..2 {
        let t = Instant::now();
        let f = fair(
            &s,
            &FairOptions {
                weight,
                ..FairOptions::default()
            },
        )
        .unwrap();
        println!(
            "fair: {:.3} s ({}), residual {:.2e}, energy {:.4e} -> {:.4e}",
            t.elapsed().as_secs_f64(),
            f.solver,
            f.normal_residual,
            f.energy_before,
            f.energy_after
        );
    }
}
