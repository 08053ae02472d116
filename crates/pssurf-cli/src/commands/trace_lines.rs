//! `pssurf trace --curvature-lines | --asymptotic | --geodesic`: field lines (lines of
//! curvature, asymptotic lines), evenly spaced or through given points, with the umbilics
//! reported; geodesics from a point and a direction, or the shortest between two points.

use std::path::Path;

use anyhow::{Context, Result, bail};
use nalgebra::{Point2, Vector2};
use pssurf::interrogate::{
    FieldLine, FieldLineOptions, GeodesicOptions, LineEnd, LineFamily, SurfaceCurve,
    even_field_lines, find_umbilics, geodesic, shortest_geodesic, trace_field_line,
};
use pssurf::surface::{ParametricSurface, PiecewiseSurface, Surface};
use pssurf::text::Significant;
use rayon::prelude::*;

use super::trace::{Family, PALETTE, TraceArgs, write_curves};

/// Runs the field-line and geodesic modes of `pssurf trace`.
pub fn run(args: &TraceArgs) -> Result<()> {
    super::trace::check_output(args)?;
    if args.max_points == 0 || args.max_points > 100_000_000 {
        bail!("--max-points must be from 1 to 100000000");
    }
    if let Some(l) = args.length
        && !(l > 0.0 && l.is_finite())
    {
        bail!("--length must be a positive finite number");
    }
    let surface = crate::budget::load_surface(&args.surface)?;
    estimate(surface.piece_count(), args.max_points).check()?;
    if args.geodesic {
        return run_geodesic(args, &surface);
    }
    let families: Vec<LineFamily> = {
        let pair = if args.asymptotic {
            LineFamily::ASYMPTOTIC
        } else {
            LineFamily::CURVATURE
        };
        match args.family {
            Family::First => vec![pair[0]],
            Family::Second => vec![pair[1]],
            Family::Both => pair.to_vec(),
        }
    };
    let step = args.step.unwrap_or(FieldLineOptions::default().max_step);
    let smallest = FieldLineOptions::default().min_step;
    if !(step >= smallest && step <= 1.0) {
        bail!("--step must be from {smallest} (the smallest step) to 1");
    }
    let opts = FieldLineOptions {
        max_step: step,
        length: args.length.unwrap_or(f64::INFINITY),
        max_points: args.max_points.min(FieldLineOptions::default().max_points),
        ..FieldLineOptions::default()
    };
    let mut curves = Vec::new();
    let mut colors = Vec::new();
    let mut budget = args.max_points;
    for (k, family) in families.iter().enumerate() {
        let lines = match &args.from {
            Some(from) => through_points(&surface, *family, &seeds(from)?, &opts, budget)?,
            None => {
                let (lo, hi) = surface.domain_bounds();
                let spacing = (hi - lo).norm() / f64::from(args.seeds);
                let even = even_field_lines(&surface, *family, spacing, &opts, budget);
                if even.truncated {
                    eprintln!("{}: seeding cut short by --max-points", family.name());
                }
                even.lines
            }
        };
        report(*family, &lines);
        budget = budget.saturating_sub(lines.iter().map(|l| l.curve.uvs.len()).sum());
        colors.extend(std::iter::repeat_n(PALETTE[k], lines.len()));
        curves.extend(lines.into_iter().map(|l| l.curve));
    }
    if args.curvature_lines {
        report_umbilics(&surface);
    }
    write_curves(args, &surface, &curves, &colors)
}

/// Memory and output of a trace of up to `max_points` points.
fn estimate(pieces: usize, max_points: usize) -> crate::budget::Estimate {
    use crate::budget::mul;
    crate::budget::Estimate {
        what: format!("tracing curves on {pieces} pieces"),
        makes: format!("up to {max_points} points"),
        // Points (parameters, positions) and the seeding's occupancy grid.
        memory: crate::budget::base_memory()
            .saturating_add(mul(max_points as u64, 200))
            .saturating_add(mul(pieces as u64, 64)),
        output: mul(max_points as u64, 110),
    }
}

/// `u,v` as a point, or None if the text is not two numbers.
fn pair(text: &str) -> Option<(f64, f64)> {
    let (a, b) = text.split_once(',')?;
    let (a, b) = (a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?);
    (a.is_finite() && b.is_finite()).then_some((a, b))
}

fn point_arg(name: &str, text: Option<&String>) -> Result<Point2<f64>> {
    let text = text.with_context(|| format!("--geodesic needs --{name} u,v"))?;
    let (u, v) =
        pair(text).with_context(|| format!("--{name} {text}: expected two finite numbers u,v"))?;
    Ok(Point2::new(u, v))
}

/// The seeds of `--from`: one point `u,v` or the points of a CSV file.
fn seeds(from: &str) -> Result<Vec<Point2<f64>>> {
    if let Some((u, v)) = pair(from) {
        return Ok(vec![Point2::new(u, v)]);
    }
    let points = crate::points::read_points(Path::new(from), true)?;
    if points.is_empty() {
        bail!("{from}: no points");
    }
    Ok(points)
}

/// The line of `family` through each seed (in parallel), up to `budget` points in all.
fn through_points(
    surface: &Surface,
    family: LineFamily,
    seeds: &[Point2<f64>],
    opts: &FieldLineOptions,
    budget: usize,
) -> Result<Vec<FieldLine>> {
    let traced: Vec<_> = seeds
        .par_iter()
        .map(|p| trace_field_line(surface, family, *p, opts))
        .collect();
    let mut lines = Vec::new();
    let mut failed = Vec::new();
    let mut used = 0;
    for (k, t) in traced.into_iter().enumerate() {
        match t {
            Ok(line) if used + line.curve.uvs.len() <= budget => {
                used += line.curve.uvs.len();
                lines.push(line);
            }
            Ok(_) => {
                eprintln!(
                    "{}: lines after seed {k} left out by --max-points",
                    family.name()
                );
                break;
            }
            Err(e) => failed.push((k, e)),
        }
    }
    if let Some((k, e)) = failed.first() {
        eprintln!(
            "{}: {} of {} seeds start no line (seed {k}: {e})",
            family.name(),
            failed.len(),
            seeds.len()
        );
    }
    Ok(lines)
}

/// One line per family: lines, closed ones, points, and why the lines ended.
fn report(family: LineFamily, lines: &[FieldLine]) {
    let closed = lines.iter().filter(|l| l.curve.closed).count();
    let points: usize = lines.iter().map(|l| l.curve.uvs.len()).sum();
    let mut ends: Vec<(LineEnd, usize)> = Vec::new();
    for l in lines.iter().filter(|l| !l.curve.closed) {
        for e in l.ends {
            match ends.iter_mut().find(|(x, _)| *x == e) {
                Some((_, n)) => *n += 1,
                None => ends.push((e, 1)),
            }
        }
    }
    let ends: Vec<String> = ends
        .iter()
        .map(|(e, n)| format!("{n} {}", e.name()))
        .collect();
    eprintln!(
        "{}: {} lines, {closed} closed, {points} points; ends: {}",
        family.name(),
        lines.len(),
        if ends.is_empty() {
            "none".to_string()
        } else {
            ends.join(", ")
        }
    );
}

fn report_umbilics(surface: &Surface) {
    let u = find_umbilics(surface);
    let shown: Vec<String> = u
        .points
        .iter()
        .take(5)
        .map(|p| format!("({}, {})", Significant(p.uv.x, 6), Significant(p.uv.y, 6)))
        .collect();
    eprintln!(
        "umbilics: {}{}{}",
        u.points.len(),
        if shown.is_empty() {
            String::new()
        } else {
            format!(
                " at {}{}",
                shown.join(", "),
                if u.points.len() > 5 { ", …" } else { "" }
            )
        },
        if u.umbilic_pieces.is_empty() {
            String::new()
        } else {
            format!(
                "; {} pieces umbilic throughout (spherical or flat)",
                u.umbilic_pieces.len()
            )
        }
    );
}

fn run_geodesic(args: &TraceArgs, surface: &Surface) -> Result<()> {
    let from = point_arg("from", args.from.as_ref())?;
    let opts = GeodesicOptions {
        max_points: args.max_points,
        ..GeodesicOptions::default()
    };
    let curve: SurfaceCurve = if args.to.is_some() {
        if args.dir.is_some() || args.length.is_some() {
            bail!("--geodesic with --to finds the shortest geodesic: leave out --dir and --length");
        }
        let to = point_arg("to", args.to.as_ref())?;
        let g = shortest_geodesic(surface, from, to, &opts)?;
        eprintln!(
            "shortest geodesic: length {}{}; lattice path {}, relaxed polyline {}",
            Significant(g.length, 12),
            if g.exact {
                " (a geodesic ending at the target)"
            } else {
                " (the relaxed polyline: shooting did not converge)"
            },
            Significant(g.lattice_length, 8),
            Significant(g.relaxed_length, 10),
        );
        g.curve
    } else {
        let (du, dv) = args
            .dir
            .as_deref()
            .and_then(pair)
            .context("--geodesic needs --to u,v, or --dir du,dv with --length L")?;
        let length = args.length.context("--geodesic --dir needs --length L")?;
        let g = geodesic(surface, from, Vector2::new(du, dv), length, &opts)?;
        eprintln!(
            "geodesic: length {}, {} points, ended at {}",
            Significant(g.length, 12),
            g.curve.uvs.len(),
            match g.end {
                pssurf::interrogate::GeodesicEnd::Length => "the length asked for",
                pssurf::interrogate::GeodesicEnd::Boundary => "the domain's boundary",
                pssurf::interrogate::GeodesicEnd::Singular => "a singular point",
                pssurf::interrogate::GeodesicEnd::Limit => "the point limit",
            }
        );
        g.curve
    };
    write_curves(args, surface, &[curve], &[PALETTE[1]])
}
