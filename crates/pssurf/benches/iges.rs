//! IGES import (issue 17's goal: a 10 MB file in under 1 s): a file of 300 rational bicubic
//! surfaces with 20 × 20 nets (about 10 MB) written here, then read and turned into NURBS
//! surfaces.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pssurf::iges::read_iges;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The parameter text of a rational bicubic 128 entity with an n × n net.
fn surface_params(n: usize, seed: usize) -> String {
    let knots: Vec<String> = (0..n + 4)
        .map(|i| format!("{}.", i.saturating_sub(3).min(n - 3)))
        .collect();
    let mut f = vec![
        "128".to_string(),
        (n - 1).to_string(),
        (n - 1).to_string(),
        "3".into(),
        "3".into(),
        "0".into(),
        "0".into(),
        "0".into(),
        "0".into(),
        "0".into(),
    ];
    f.extend(knots.iter().cloned());
    f.extend(knots.iter().cloned());
    for k in 0..n * n {
        f.push(format!("{:.15}", 0.5 + ((k * 7 + seed) % 11) as f64 / 10.0));
    }
    for k in 0..n * n {
        let (i, j) = (k % n, k / n);
        let z = ((i + seed) as f64 * 0.7).sin() * (j as f64 * 0.5).cos();
        f.push(format!("{:.15}", i as f64 * 1.0001));
        f.push(format!("{:.15}", j as f64 * 0.9999));
        f.push(format!("{z:.15}"));
    }
    f.extend([
        "0.".into(),
        format!("{}.", n - 3),
        "0.".into(),
        format!("{}.", n - 3),
    ]);
    f.join(",") + ";"
}

/// A whole IGES file of `count` surfaces.
fn file(count: usize) -> String {
    let rec = |out: &mut String, body: &str, letter: char, k: usize| {
        out.push_str(&format!("{body:<72}{letter}{k:>7}\n"));
    };
    let mut out = String::new();
    rec(&mut out, "pssurf benchmark", 'S', 1);
    rec(&mut out, ",,6Hpssurf,,,,,,,,,,1.,2,2HMM;", 'G', 1);
    let (mut dirs, mut params) = (Vec::new(), Vec::new());
    for s in 0..count {
        let de = 2 * s + 1;
        let start = params.len() + 1;
        let text = surface_params(20, s);
        for chunk in text.as_bytes().chunks(64) {
            params.push(format!("{:<64}{de:>8}", String::from_utf8_lossy(chunk)));
        }
        let lines = params.len() + 1 - start;
        dirs.push(format!("{:>8}{start:>8}{:>56}", 128, "00000000"));
        dirs.push(format!("{:>8}{:>16}{lines:>8}{:>40}", 128, 0, 0));
    }
    for (k, d) in dirs.iter().enumerate() {
        rec(&mut out, d, 'D', k + 1);
    }
    for (k, p) in params.iter().enumerate() {
        rec(&mut out, p, 'P', k + 1);
    }
    rec(&mut out, "S      1", 'T', 1);
    out
}

fn import(c: &mut Criterion) {
    let text = file(300);
    assert_eq!(read_iges(&text).unwrap().surfaces.len(), 300);
    let mut g = c.benchmark_group("iges_import");
    g.sample_size(10);
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.bench_function(
        format!("{:.1} MB, 300 bicubic surfaces", text.len() as f64 / 1e6),
        |b| b.iter(|| black_box(read_iges(&text).unwrap())),
    );
    g.finish();
}

criterion_group!(benches, import);
criterion_main!(benches);
