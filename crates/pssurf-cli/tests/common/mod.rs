//! Helpers shared by the end-to-end tests of the `pssurf` binary.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn pssurf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pssurf"))
        .args(args)
        .output()
        .expect("runs")
}

pub fn ok(args: &[&str]) -> String {
    let out = pssurf(args);
    assert!(
        out.status.success(),
        "pssurf {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a command that must succeed; its standard error (the report).
pub fn ok_report(args: &[&str]) -> String {
    let out = pssurf(args);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "pssurf {args:?} failed: {err}");
    err
}

pub fn fails(args: &[&str]) -> String {
    let out = pssurf(args);
    assert!(!out.status.success(), "pssurf {args:?} should fail");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        !err.contains("panicked"),
        "panic instead of an error: {err}"
    );
    err
}

pub fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/data")
        .join(name)
        .display()
        .to_string()
}

pub fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

pub fn s(p: &Path) -> String {
    p.display().to_string()
}

/// Parses a .npy file independently of the writer: magic, header dict, little-endian f64 data.
pub fn read_npy(path: &Path) -> (Vec<usize>, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    let (major, header_len, start) = match bytes[6] {
        1 => (1, u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        v => (
            v,
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
            12,
        ),
    };
    assert!(major >= 1);
    let header = std::str::from_utf8(&bytes[start..start + header_len]).unwrap();
    assert!(header.contains("'descr': '<f8'"), "{header}");
    assert!(header.contains("'fortran_order': False"), "{header}");
    let shape_txt = &header[header.find("'shape': (").unwrap() + 10..];
    let shape: Vec<usize> = shape_txt[..shape_txt.find(')').unwrap()]
        .split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| t.trim().parse().unwrap())
        .collect();
    let data: Vec<f64> = bytes[start + header_len..]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(data.len(), shape.iter().product::<usize>());
    (shape, data)
}

/// A UPS surface made by `pssurf new ups --sides … --size … --height …` as `dir/name`.
pub fn new_ups(dir: &Path, name: &str, sides: u32, size: u32, height: &str) -> PathBuf {
    let p = dir.join(name);
    let (sides, size) = (sides.to_string(), size.to_string());
    ok(&[
        "new",
        "ups",
        "--sides",
        &sides,
        "--size",
        &size,
        "--height",
        height,
        "-o",
        &s(&p),
    ]);
    p
}

pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// A command line for a report, each argument cut to 40 characters.
pub fn short_args(args: &[String]) -> String {
    args.iter()
        .map(|a| match a.char_indices().nth(40) {
            Some((k, _)) => format!("{}…", &a[..k]),
            None => a.clone(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}
