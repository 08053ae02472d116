//! The showcase's `index.html`.

use std::fmt::Write;

use pssurf_viz::ColorScale;

use super::Row;
use super::experiment::{LEVELS, NOISE};

fn scale_text(s: &ColorScale) -> String {
    match *s {
        ColorScale::Contrast { c } => format!("contrast C = {c:.4}"),
        ColorScale::Linear { lo, hi } => format!("range [{lo:.4}, {hi:.4}]"),
    }
}

/// The page: the experiment, the gallery with one row per surface, the numbers, the basis
/// function and the domain pictures.
pub fn page(
    rows: &[Row],
    basis: &[String],
    k: &ColorScale,
    h: &ColorScale,
    seconds: f64,
) -> String {
    let mut s = String::new();
    s.push_str(HEAD);
    introduction(&mut s, k, h);
    numbers(&mut s, rows);
    gallery(&mut s, rows);
    basis_function(&mut s, basis);
    domain(&mut s);
    footer(&mut s, seconds);
    s
}

/// The document's head (title and style sheet) and the opening of its body.
const HEAD: &str = r#"<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>pssurf showcase: curvature plots of denoised UPS surfaces</title>
<style>
body { font-family: system-ui, sans-serif; margin: 2em; color: #222; max-width: 1500px; }
table { border-collapse: collapse; margin: 1em 0; }
td, th { border: 1px solid #ccc; padding: 0.3em 0.6em; text-align: right; }
th { background: #f3f3f3; } td:first-child, th:first-child { text-align: left; }
.row { display: grid; grid-template-columns: repeat(4, 1fr); gap: 6px; margin-bottom: 1.5em; }
.row img { width: 100%; border: 1px solid #ddd; }
figure { margin: 0; } figcaption { font-size: 0.85em; color: #555; }
.best { font-weight: bold; }
</style></head><body>
"#;

/// The heading and the experiment's description, with the shared scales of K and H.
fn introduction(s: &mut String, k: &ColorScale, h: &ColorScale) {
    let _ = write!(
        s,
        r#"<h1>Curvature plots of denoised uniform Powell–Sabin surfaces</h1>
<p>The experiment of Maes, Vanraes, Dierckx and Bultheel, <i>Curvature plots of Powell–Sabin
spline surfaces</i>, section 4: a smooth uniform PS (UPS) surface is subdivided {LEVELS} times,
uniform noise of amplitude {NOISE} is added to every control point, and the noise is removed by
thresholding the UPS wavelet coefficients over {LEVELS} levels. It is hard to see by eye which
denoised surface is closest to the original; the curvature plots, and the numbers below, tell.</p>
<p>Curvature colours use the seed's map: green for negative, black for zero, red for positive,
after κ<sub>norm</sub> = sign(κ)(1 − e<sup>−C|κ|</sup>). All plots of a quantity share the
original surface's scale (Gaussian: {ks}; mean: {hs}), so equal colours mean equal values.
Zebra stripes kink across the edges of the PS refinement, where a C¹ surface's curvature jumps.</p>
"#,
        ks = scale_text(k),
        hs = scale_text(h)
    );
}

/// The index of the denoised row (the third on) with the smallest `f`; 0 when there is none.
fn best_row(rows: &[Row], f: impl Fn(&Row) -> f64) -> usize {
    (2..rows.len())
        .min_by(|&a, &b| f(&rows[a]).total_cmp(&f(&rows[b])))
        .unwrap_or(0)
}

/// The numbers: a table row per surface, the best denoised errors in bold, and a note.
fn numbers(s: &mut String, rows: &[Row]) {
    let best_h = best_row(rows, |r| r.comparison.mean_curvature_rms);
    let best_p = best_row(rows, |r| r.comparison.position_rms);
    let _ = write!(
        s,
        "<h2>Numbers</h2>\n<table>\n<tr><th>surface</th><th>coefficients zeroed</th><th>RMS distance to the original</th>\
         <th>RMS error of H</th><th>RMS error of K</th><th>∫ H² dA</th><th>∫ |K| dA</th><th>thin-plate energy</th></tr>\n"
    );
    for (k, r) in rows.iter().enumerate() {
        table_row(s, r, k == best_p, k == best_h);
    }
    let _ = writeln!(
        s,
        "</table>\n<p>Errors are root-mean-square differences from the original at 4000 random parameter points \
         (bold: the smallest among the denoised surfaces). The integrals are exact Gauss quadrature on every PS \
         sub-triangle. Position errors hardly move under denoising: the thesis' wavelet scaling step amplifies the \
         noise that stays in the coarse control triangles (see docs/ups.md); curvature is where denoising shows.</p>"
    );
}

/// One surface's row of the numbers table, its best position and H errors in bold.
fn table_row(s: &mut String, r: &Row, best_position: bool, best_mean_curvature: bool) {
    let c = &r.comparison;
    let mark = |b: bool| if b { " class=\"best\"" } else { "" };
    let _ = writeln!(
        s,
        "<tr><td>{}</td><td>{}</td><td{}>{:.3e}</td><td{}>{:.4}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td></tr>",
        r.title,
        r.zeroed_percent
            .map_or("—".to_string(), |z| format!("{z:.1} %")),
        mark(best_position),
        c.position_rms,
        mark(best_mean_curvature),
        c.mean_curvature_rms,
        c.gaussian_rms,
        c.fairness.mean_squared,
        c.fairness.gaussian_abs,
        c.fairness.thin_plate,
    );
}

/// The gallery: a heading and a row of four pictures (shaded, K, H, zebra) per surface.
fn gallery(s: &mut String, rows: &[Row]) {
    let _ = writeln!(s, "<h2>Gallery</h2>");
    for r in rows {
        let _ = writeln!(s, "<h3>{}</h3>\n<div class=\"row\">", r.title);
        for (p, cap) in r.pictures.iter().zip([
            "shaded",
            "Gaussian curvature K",
            "mean curvature H",
            "zebra stripes",
        ]) {
            let _ = writeln!(
                s,
                "<figure><img src=\"{p}\" alt=\"{} — {cap}\"><figcaption>{cap}</figcaption></figure>",
                r.title
            );
        }
        let _ = writeln!(s, "</div>");
    }
}

/// The basis function's section: what it is, its three pictures and its domain picture.
fn basis_function(s: &mut String, basis: &[String]) {
    let _ = writeln!(
        s,
        "<h2>A PS B-spline basis function</h2>\n<p>The curvature of one normalized PS B-spline basis function \
         (seed 000, Figure 4): a C¹ piecewise quadratic whose curvature jumps across the PS refinement.</p>\n<div class=\"row\">"
    );
    for (p, cap) in basis.iter().zip([
        "shaded",
        "Gaussian curvature K (own scale)",
        "mean curvature H (own scale)",
    ]) {
        let _ = writeln!(
            s,
            "<figure><img src=\"{p}\" alt=\"basis function — {cap}\"><figcaption>{cap}</figcaption></figure>"
        );
    }
    let _ = writeln!(
        s,
        "<figure><img src=\"domain_basis.svg\" alt=\"its domain\"><figcaption>its domain: triangulation, PS refinement, \
         PS-points and PS-triangles</figcaption></figure></div>"
    );
}

/// The domain section: the original surface's domain coloured by mean curvature.
fn domain(s: &mut String) {
    let _ = writeln!(
        s,
        "<h2>Domain</h2>\n<div class=\"row\"><figure><img \
         src=\"domain_original.svg\" alt=\"domain of the original surface\"><figcaption>the original surface's domain \
         (after subdivision), coloured by mean curvature piece by piece</figcaption></figure></div>"
    );
}

/// The footer with the time the showcase took, and the end of the document.
fn footer(s: &mut String, seconds: f64) {
    let _ = writeln!(
        s,
        "<p><small>Made by <code>pssurf showcase</code> in {seconds:.1} s.</small></p>\n</body></html>"
    );
}
