//! Fairing (issue 18's goal: a 100k-vertex UPS surface in under 5 s on 2 cores): a noisy UPS
//! hexagon faired with weight 0.1 by the Hessian jumps (the thesis' energy, the default) and by
//! the thin-plate energy, at about 10k and 100k vertices.

use criterion::{Criterion, criterion_group, criterion_main};
use pssurf::ps::{Energy, FairOptions, fair};
use std::hint::black_box;

#[path = "support/noisy_wave.rs"]
mod noisy_wave;
use noisy_wave::noisy_wave;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn fairing(c: &mut Criterion) {
    let mut g = c.benchmark_group("fair");
    g.sample_size(10);
    for size in [58, 182] {
        let s = noisy_wave(size);
        let n = s.ps_basis().unwrap().triangulation().vertex_count();
        for (name, energy) in [
            ("jumps", Energy::HessianJumps),
            ("thin plate", Energy::ThinPlate),
        ] {
            let opts = FairOptions {
                weight: 0.1,
                energy,
            };
            g.bench_function(format!("{n} vertices, {name}"), |b| {
                b.iter(|| black_box(fair(&s, &opts).unwrap().energy_after))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, fairing);
criterion_main!(benches);
