//! Hole filling (issue 18's goal: the sphere example to a 1e-4 relative tolerance in under
//! 1 s): both triangles of the NURPS sphere's gap, to the default tolerances (1e-4 of the
//! model size, 0.25°), with the instant update and with constrained fairing.

use criterion::{Criterion, criterion_group, criterion_main};
use pssurf::hole::examples::sphere_hole;
use pssurf::hole::{FillOptions, Interior, fill_hole};
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn sphere(c: &mut Criterion) {
    let mut g = c.benchmark_group("hole_sphere");
    g.sample_size(10);
    for interior in [Interior::Instant, Interior::Fair] {
        g.bench_function(interior.name(), |b| {
            b.iter(|| {
                let ex = sphere_hole(1.0).unwrap();
                for hole in ex.holes {
                    let opts = FillOptions {
                        interior,
                        ..FillOptions::default()
                    };
                    black_box(fill_hole(hole, &opts).unwrap());
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, sphere);
criterion_main!(benches);
