//! Issue 19: commands write binary surface files when the output ends in `.psb`; every such
//! file loads again and evaluates exactly as the JSON file of the same surface; broken binary
//! files are refused with one line and a non-zero exit.

mod common;

use common::*;

#[test]
fn psb_outputs_are_binary_and_load_again() {
    let d = tmp();
    let (json, bin) = (d.path().join("f.json"), d.path().join("f.psb"));
    let data = example("franke.csv");
    ok_report(&["fit", &data, "-o", &s(&json)]);
    ok_report(&["fit", &data, "-o", &s(&bin)]);
    let bytes = std::fs::read(&bin).unwrap();
    assert_eq!(&bytes[..7], b"PSSURFB");
    assert!(bytes.len() < std::fs::metadata(&json).unwrap().len() as usize);
    assert!(ok(&["info", &s(&bin)]).contains("valid"));
    assert_eq!(
        ok(&["eval", &s(&bin), "--grid", "7x5"]),
        ok(&["eval", &s(&json), "--grid", "7x5"])
    );
    // A UPS surface through subdivision, binary in and out.
    let (ups, fine) = (d.path().join("u.psb"), d.path().join("fine.psb"));
    ok_report(&[
        "new",
        "ups",
        "--sides",
        "6",
        "--size",
        "3",
        "--height",
        "x*y",
        "-o",
        &s(&ups),
    ]);
    ok_report(&["subdivide", &s(&ups), "--times", "2", "-o", &s(&fine)]);
    assert!(ok(&["info", &s(&fine)]).contains("uniform (UPS)"));
}

#[test]
fn broken_binary_files_give_one_line() {
    let d = tmp();
    let bin = d.path().join("f.psb");
    ok_report(&["fit", &example("franke.csv"), "-o", &s(&bin)]);
    let good = std::fs::read(&bin).unwrap();
    let cut = d.path().join("cut.psb");
    std::fs::write(&cut, &good[..good.len() - 100]).unwrap();
    let e = fails(&["info", &s(&cut)]);
    assert!(e.contains("cut.psb") && e.contains("truncated"), "{e}");
    assert_eq!(e.trim().lines().count(), 1, "{e}");
    let mut flipped = good.clone();
    let last = flipped.len() - 20;
    flipped[last] ^= 1;
    let bad = d.path().join("bad.psb");
    std::fs::write(&bad, &flipped).unwrap();
    let e = fails(&["eval", &s(&bad), "--grid", "2x2"]);
    assert!(e.contains("checksum"), "{e}");
}
