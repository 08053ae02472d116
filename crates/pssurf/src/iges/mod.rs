//! IGES 5.3 import (issue 17): rational B-spline surfaces (entity 128) and curves (126),
//! transformation matrices (124), trimmed surfaces (144 with curves on surfaces 142) and
//! bounded surfaces (143 with boundaries 141), with units converted to millimetres.
//!
//! - The fixed format (`lexer`): 80-column records, the Start, Global, Directory, Parameter
//!   and Terminate sections, the Global section's delimiters (`1H,` or empty for the default),
//!   Hollerith strings that contain delimiters, `D` exponents, blank lines, and comments after
//!   a record delimiter.
//! - Surfaces become [`NurbsSurface`]s in the file's frame (transformation chains applied,
//!   coordinates scaled to millimetres), on their declared parameter range (a 128's
//!   U(0), U(1), V(0), V(1), which may be narrower than its knots). A trimmed or bounded
//!   surface is imported as its underlying surface, placed by its own transformation after
//!   the surface's, with its trimming loops kept as curves in its parameter plane (trimming
//!   is not applied: the report says so).
//! - Other entities are counted by type and listed, not refused.
//!
//! Every error names the line of the file and the reason; malformed files never panic.

mod lexer;
#[cfg(test)]
mod tests;

use std::collections::BTreeMap;

use nalgebra::{Matrix3, Point2, Vector3};
use thiserror::Error;

use crate::nurbs::{NurbsCurve, NurbsSurface};
use lexer::{Delimiters, Entry, Field, Located};

/// An IGES file that cannot be read.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("line {line}: {message}")]
pub struct IgesError {
    /// The line of the file (1-based; 0 for the file as a whole).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl IgesError {
    fn at(line: usize, message: impl Into<String>) -> Self {
        IgesError {
            line,
            message: message.into(),
        }
    }
}

/// A surface read from the file.
#[derive(Clone, Debug)]
pub struct ImportedSurface {
    /// The directory entry's sequence number (`D` line) of the 128 entity.
    pub entry: usize,
    /// A name: the entity label, or `surface D<entry>`.
    pub name: String,
    /// The surface, in millimetres, transformations applied.
    pub surface: NurbsSurface,
    /// The trimming loops (outer first) in the surface's parameter plane, when the surface is
    /// trimmed (144) or bounded (143).
    pub loops: Vec<Vec<Point2<f64>>>,
    /// Whether it is the base of a trimmed or bounded surface.
    pub trimmed: bool,
}

/// What an IGES file held.
#[derive(Clone, Debug, Default)]
pub struct IgesModel {
    /// The B-spline surfaces (128), each once.
    pub surfaces: Vec<ImportedSurface>,
    /// The B-spline curves (126) that are not parts of trimming loops, in millimetres.
    pub curves: Vec<(usize, NurbsCurve)>,
    /// Entities not imported, by type, with their counts.
    pub unknown: BTreeMap<i64, usize>,
    /// The file's unit (from the Global section) and the factor to millimetres.
    pub unit: (String, f64),
    /// The sending system (Global field 5), if given.
    pub system: String,
    /// Things the user should know (trimming not applied, loops skipped, …).
    pub warnings: Vec<String>,
}

/// The unit flag of the Global section: name and millimetres per unit.
fn unit_of(flag: i64, name: &str) -> Option<(String, f64)> {
    Some(match flag {
        1 => ("inch".into(), 25.4),
        2 => ("mm".into(), 1.0),
        3 => match name.trim().to_ascii_uppercase().as_str() {
            "IN" | "INCH" => ("inch".into(), 25.4),
            "MM" => ("mm".into(), 1.0),
            "M" => ("m".into(), 1000.0),
            "CM" => ("cm".into(), 10.0),
            "FT" => ("ft".into(), 304.8),
            _ => return None,
        },
        4 => ("ft".into(), 304.8),
        5 => ("mile".into(), 1_609_344.0),
        6 => ("m".into(), 1000.0),
        7 => ("km".into(), 1_000_000.0),
        8 => ("mil".into(), 0.0254),
        9 => ("micron".into(), 0.001),
        10 => ("cm".into(), 10.0),
        11 => ("microinch".into(), 0.0000254),
        _ => return None,
    })
}

/// Reads an IGES file's text.
pub fn read_iges(text: &str) -> Result<IgesModel, IgesError> {
    let sections = lexer::sections(text)?;
    let delimiters = if sections.global.is_empty() {
        Delimiters::default()
    } else {
        lexer::global_delimiters(&sections.global)?
    };
    let global = if sections.global.is_empty() {
        Vec::new()
    } else {
        lexer::fields(&sections.global, 72, delimiters)?
    };
    let mut model = IgesModel {
        unit: ("mm".into(), 1.0),
        ..Default::default()
    };
    model.warnings.extend(sections.miscount.clone());
    let text_at = |k: usize| match global.get(k).map(|f| &f.field) {
        Some(Field::Text(s)) => s.clone(),
        _ => String::new(),
    };
    model.system = text_at(4);
    let flag = match global.get(13).map(|f| &f.field) {
        Some(Field::Number(x)) => *x as i64,
        _ => 2,
    };
    match unit_of(flag, &text_at(14)) {
        Some(u) => model.unit = u,
        None => model.warnings.push(format!(
            "unknown unit (flag {flag}, name `{}`): coordinates taken as millimetres",
            text_at(14)
        )),
    }
    let entries = lexer::directory(&sections.directory)?;
    let file = File {
        entries,
        parameter: &sections.parameter,
        delimiters,
        scale: model.unit.1,
    };
    file.import(&mut model)?;
    // Checked last, so that a file cut inside its data is named by the line where it breaks.
    if !sections.terminated {
        return Err(IgesError::at(
            0,
            "the file ends without its Terminate record (truncated?)",
        ));
    }
    Ok(model)
}

/// The parsed directory with access to each entity's parameters.
struct File<'a> {
    entries: Vec<Entry>,
    parameter: &'a [lexer::Record<'a>],
    delimiters: Delimiters,
    scale: f64,
}

/// An affine map x ↦ R x + t.
/// Where a trimmed surface (144 or 143) places its base surface: its transformation and its
/// trimming loops in the parameter plane.
type Placement = (Affine, Vec<Vec<Point2<f64>>>);

#[derive(Clone, Copy, PartialEq)]
struct Affine {
    r: Matrix3<f64>,
    t: Vector3<f64>,
}

impl Affine {
    fn identity() -> Self {
        Affine {
            r: Matrix3::identity(),
            t: Vector3::zeros(),
        }
    }

    fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.r * p + self.t
    }

    /// self ∘ inner.
    fn then_outer(&self, outer: &Affine) -> Affine {
        Affine {
            r: outer.r * self.r,
            t: outer.r * self.t + outer.t,
        }
    }
}

/// The fields of one entity as numbers (empty fields as `None`).
struct Params {
    fields: Vec<Located>,
    /// The entity's directory line, for messages about missing fields.
    line: usize,
}

impl Params {
    fn line_of(&self, k: usize) -> usize {
        self.fields.get(k).map_or(self.line, |f| f.line)
    }

    fn real(&self, k: usize) -> Result<f64, IgesError> {
        match self.fields.get(k).map(|f| &f.field) {
            Some(Field::Number(x)) => Ok(*x),
            Some(Field::Empty) => Ok(0.0),
            Some(Field::Text(_)) => Err(IgesError::at(
                self.line_of(k),
                format!("parameter {k} is a string where a number is expected"),
            )),
            None => Err(IgesError::at(
                self.line_of(k),
                format!(
                    "the entity has {} parameters, {} expected at least",
                    self.fields.len(),
                    k + 1
                ),
            )),
        }
    }

    /// Field `k` when it is a number (not empty, not missing).
    fn number(&self, k: usize) -> Option<f64> {
        match self.fields.get(k).map(|f| &f.field) {
            Some(Field::Number(x)) => Some(*x),
            _ => None,
        }
    }

    fn int(&self, k: usize) -> Result<i64, IgesError> {
        let x = self.real(k)?;
        if x.fract() != 0.0 || x.abs() > 1e12 {
            return Err(IgesError::at(
                self.line_of(k),
                format!("parameter {k} is {x}, an integer is expected"),
            ));
        }
        Ok(x as i64)
    }

    /// A count: an integer from `lo` to `hi`.
    fn count(&self, k: usize, lo: i64, hi: i64) -> Result<usize, IgesError> {
        let n = self.int(k)?;
        if n < lo || n > hi {
            return Err(IgesError::at(
                self.line_of(k),
                format!("parameter {k} is {n}, expected {lo} to {hi}"),
            ));
        }
        Ok(n as usize)
    }
}

/// The most control points of one B-spline (a guard against absurd counts).
const MAX_NET: usize = 10_000_000;

impl File<'_> {
    /// The entry with directory sequence number `de` (odd, 1-based).
    fn entry(&self, de: usize, from: usize) -> Result<&Entry, IgesError> {
        if de == 0 || de.is_multiple_of(2) || de / 2 >= self.entries.len() {
            return Err(IgesError::at(
                from,
                format!(
                    "pointer {de} names no directory entry (odd numbers 1 to {})",
                    2 * self.entries.len() - 1
                ),
            ));
        }
        Ok(&self.entries[de / 2])
    }

    /// The parameters of entry `e`, checked to start with its type. The record runs from its
    /// first Parameter line for the directory's line count, clamped to the section, and on
    /// over further lines that point back to the same entry (some writers miscount); the
    /// record delimiter ends it in any case.
    fn params(&self, e: &Entry) -> Result<Params, IgesError> {
        let first = e.parameter;
        let n = self.parameter.len();
        if first == 0 || first > n {
            return Err(IgesError::at(
                e.line,
                format!(
                    "the parameter data pointer {first} lies outside the Parameter section (1–{n})"
                ),
            ));
        }
        let mut last = (first + e.parameter_lines.max(1) - 1).min(n);
        let back = |r: &lexer::Record<'_>| {
            r.text
                .get(64..72)
                .and_then(|t| t.trim().parse::<usize>().ok())
        };
        while last < n && back(&self.parameter[last]) == Some(e.de) {
            last += 1;
        }
        let fields = lexer::fields(&self.parameter[first - 1..last], 64, self.delimiters)?;
        let p = Params {
            fields,
            line: e.line,
        };
        if p.int(0)? != e.kind {
            return Err(IgesError::at(
                p.line_of(0),
                format!(
                    "the parameter data starts with type {}, the directory says {}",
                    p.int(0)?,
                    e.kind
                ),
            ));
        }
        Ok(p)
    }

    /// The transformation of entry `e` (its chain of 124 entities), with the unit scale.
    fn transform(&self, e: &Entry) -> Result<Affine, IgesError> {
        let mut m = Affine::identity();
        let mut next = e.transform;
        let mut from = e.line;
        for _ in 0..64 {
            if next == 0 {
                return Ok(m);
            }
            let t = self.entry(next, from)?;
            if t.kind != 124 {
                return Err(IgesError::at(
                    t.line,
                    format!(
                        "the transformation pointer names an entity of type {}",
                        t.kind
                    ),
                ));
            }
            let p = self.params(t)?;
            let mut r = Matrix3::zeros();
            let mut tr = Vector3::zeros();
            for i in 0..3 {
                for j in 0..3 {
                    r[(i, j)] = p.real(1 + 4 * i + j)?;
                }
                tr[i] = p.real(4 + 4 * i)?;
            }
            m = m.then_outer(&Affine { r, t: tr });
            from = t.line;
            next = t.transform;
        }
        Err(IgesError::at(
            e.line,
            "the transformation chain does not end (a cycle?)",
        ))
    }

    /// A 128 entity as a NURBS surface in millimetres, transformed by its own chain and then
    /// by `outer` (the transformation of a trimmed or bounded surface on it), on its declared
    /// parameter range; with `false` when that range is not a rectangle inside the knot
    /// domain and the whole knot domain was kept.
    fn surface(&self, e: &Entry, outer: &Affine) -> Result<(NurbsSurface, bool), IgesError> {
        let p = self.params(e)?;
        let (k1, k2) = (
            p.count(1, 0, MAX_NET as i64)?,
            p.count(2, 0, MAX_NET as i64)?,
        );
        let (m1, m2) = (p.count(3, 1, 15)?, p.count(4, 1, 15)?);
        let polynomial = p.int(7)? == 1;
        let (nu, nv) = (k1 + 1, k2 + 1);
        if nu.checked_mul(nv).is_none_or(|n| n > MAX_NET) {
            return Err(IgesError::at(
                e.line,
                format!("a {nu} × {nv} net is too large"),
            ));
        }
        let mut k = 10;
        let mut reals = |n: usize| -> Result<Vec<f64>, IgesError> {
            let v = (k..k + n)
                .map(|i| p.real(i))
                .collect::<Result<Vec<f64>, _>>()?;
            k += n;
            Ok(v)
        };
        let ku = reals(k1 + m1 + 2)?;
        let kv = reals(k2 + m2 + 2)?;
        let w = reals(nu * nv)?;
        let xyz = reals(3 * nu * nv)?;
        // U(0), U(1), V(0), V(1) follow the control points.
        let range = (k..k + 4)
            .map(|i| p.number(i))
            .collect::<Option<Vec<f64>>>();
        let map = self.transform(e)?.then_outer(outer);
        // IGES lists u fastest; our nets run along v fastest (P_ij at i·n_v + j).
        let mut points = vec![Vector3::zeros(); nu * nv];
        let mut weights = vec![1.0; nu * nv];
        for j in 0..nv {
            for i in 0..nu {
                let s = j * nu + i;
                let q = Vector3::new(xyz[3 * s], xyz[3 * s + 1], xyz[3 * s + 2]);
                points[i * nv + j] = map.apply(&q) * self.scale;
                weights[i * nv + j] = w[s];
            }
        }
        let weights = (!polynomial || weights.iter().any(|&x| x != weights[0])).then_some(weights);
        let whole = NurbsSurface::try_new([m1, m2], [ku, kv], [nu, nv], points, weights)
            .map_err(|err| IgesError::at(e.line, format!("surface (128): {err}")))?;
        let Some(r) = range else {
            return Ok((whole, true));
        };
        Ok(match whole.restricted([r[0], r[1]], [r[2], r[3]]) {
            Some(s) => (s, true),
            None => (whole, false),
        })
    }

    /// A 126 entity as a NURBS curve (model coordinates, or parameter-plane ones when
    /// `parameter_space`).
    fn curve(&self, e: &Entry, parameter_space: bool) -> Result<NurbsCurve, IgesError> {
        let p = self.params(e)?;
        let k = p.count(1, 0, MAX_NET as i64)?;
        let m = p.count(2, 1, 15)?;
        let polynomial = p.int(5)? == 1;
        let n = k + 1;
        let mut at = 7;
        let mut reals = |count: usize| -> Result<Vec<f64>, IgesError> {
            let v = (at..at + count)
                .map(|i| p.real(i))
                .collect::<Result<Vec<f64>, _>>()?;
            at += count;
            Ok(v)
        };
        let knots = reals(k + m + 2)?;
        let w = reals(n)?;
        let xyz = reals(3 * n)?;
        let (map, scale) = if parameter_space {
            (Affine::identity(), 1.0)
        } else {
            (self.transform(e)?, self.scale)
        };
        let points = (0..n)
            .map(|i| map.apply(&Vector3::new(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2])) * scale)
            .collect();
        let weights = (!polynomial || w.iter().any(|&x| x != w[0])).then_some(w);
        NurbsCurve::try_new(m, knots, points, weights)
            .map_err(|err| IgesError::at(e.line, format!("curve (126): {err}")))
    }

    /// The points of a parameter-space curve (126, 110 line, 102 composite of these),
    /// sampled; `None` for a kind that is not supported.
    fn polyline(
        &self,
        de: usize,
        from: usize,
        depth: usize,
    ) -> Result<Option<Vec<Point2<f64>>>, IgesError> {
        let e = self.entry(de, from)?;
        if depth > 16 {
            return Err(IgesError::at(e.line, "composite curves nested too deeply"));
        }
        Ok(match e.kind {
            126 => {
                let c = self.curve(e, true)?;
                let (a, b) = c.domain();
                let n = 8 * c.points().len().max(4);
                Some(
                    (0..=n)
                        .filter_map(|i| c.point(a + (b - a) * i as f64 / n as f64))
                        .map(|p| Point2::new(p.x, p.y))
                        .collect(),
                )
            }
            110 => {
                let p = self.params(e)?;
                Some(vec![
                    Point2::new(p.real(1)?, p.real(2)?),
                    Point2::new(p.real(4)?, p.real(5)?),
                ])
            }
            102 => {
                let p = self.params(e)?;
                let n = p.count(1, 0, 100_000)?;
                let mut out: Vec<Point2<f64>> = Vec::new();
                for k in 0..n {
                    let child = p.count(2 + k, 1, i64::MAX)?;
                    match self.polyline(child, p.line_of(2 + k), depth + 1)? {
                        Some(part) => out.extend(part),
                        None => return Ok(None),
                    }
                }
                Some(out)
            }
            _ => None,
        })
    }

    /// Imports every entity into `model`.
    fn import(&self, model: &mut IgesModel) -> Result<(), IgesError> {
        // Per base surface: the transformation of the (first) trimmed or bounded surface on it,
        // and the loops.
        let mut trimmed: BTreeMap<usize, Placement> = BTreeMap::new();
        let mut placed_twice = Vec::new();
        let mut in_loops = std::collections::BTreeSet::new();
        let mut skipped_loops = 0;
        // Trimmed (144) and bounded (143) surfaces: their base surfaces and loops.
        for e in &self.entries {
            match e.kind {
                144 => {
                    let p = self.params(e)?;
                    let base = p.count(1, 1, i64::MAX)?;
                    let inner = p.count(3, 0, 1_000_000)?;
                    let mut b = Vec::new();
                    let outer = p.int(4)?;
                    if outer > 0 {
                        b.push(outer as usize);
                    }
                    for i in 0..inner {
                        b.push(p.count(5 + i, 1, i64::MAX)?);
                    }
                    let map = self.transform(e)?;
                    let loops = self.loops_142(&b, e.line, &mut in_loops, &mut skipped_loops)?;
                    if let Some(kept) = place(&mut trimmed, base, map, e.de, &mut placed_twice) {
                        kept.extend(loops);
                    }
                }
                143 => {
                    let p = self.params(e)?;
                    let base = p.count(2, 1, i64::MAX)?;
                    let n = p.count(3, 0, 1_000_000)?;
                    let map = self.transform(e)?;
                    let mut loops = Vec::new();
                    // 141 boundaries: their parameter-space curves.
                    for i in 0..n {
                        let b = p.count(4 + i, 1, i64::MAX)?;
                        let be = self.entry(b, p.line_of(4 + i))?;
                        if be.kind != 141 {
                            skipped_loops += 1;
                            continue;
                        }
                        let bp = self.params(be)?;
                        let curves = bp.count(4, 0, 1_000_000)?;
                        let mut lp: Vec<Point2<f64>> = Vec::new();
                        let mut ok = true;
                        // Each boundary curve: model curve, sense, k parameter curves.
                        let mut at = 5;
                        for _ in 0..curves {
                            let _model = bp.int(at)?;
                            let _sense = bp.int(at + 1)?;
                            let kp = bp.count(at + 2, 0, 1_000)?;
                            for j in 0..kp {
                                let c = bp.count(at + 3 + j, 1, i64::MAX)?;
                                in_loops.insert(c);
                                match self.polyline(c, bp.line_of(at + 3 + j), 0)? {
                                    Some(pts) => lp.extend(pts),
                                    None => ok = false,
                                }
                            }
                            ok &= kp > 0;
                            at += 3 + kp;
                        }
                        if ok && lp.len() >= 2 {
                            loops.push(lp);
                        } else {
                            skipped_loops += 1;
                        }
                    }
                    if let Some(kept) = place(&mut trimmed, base, map, e.de, &mut placed_twice) {
                        kept.extend(loops);
                    }
                }
                _ => {}
            }
        }
        if !placed_twice.is_empty() {
            model.warnings.push(format!(
                "{} trimmed or bounded surfaces place a surface a second time with another transformation, not imported: {}",
                placed_twice.len(),
                placed_twice.join(", ")
            ));
        }
        if skipped_loops > 0 {
            model.warnings.push(format!(
                "{skipped_loops} trimming loops were not kept (no parameter-space curve of a supported type)"
            ));
        }
        let mut whole_domain = Vec::new();
        for (k, e) in self.entries.iter().enumerate() {
            let de = 2 * k + 1;
            match e.kind {
                128 => {
                    let (outer, loops) = match trimmed.remove(&de) {
                        Some((map, loops)) => (map, Some(loops)),
                        None => (Affine::identity(), None),
                    };
                    let (surface, in_range) = self.surface(e, &outer)?;
                    if !in_range {
                        whole_domain.push(format!("D{de}"));
                    }
                    model.surfaces.push(ImportedSurface {
                        entry: de,
                        name: if e.label.is_empty() {
                            format!("surface D{de}")
                        } else {
                            format!("{} (D{de})", e.label)
                        },
                        surface,
                        trimmed: loops.is_some(),
                        loops: loops.unwrap_or_default(),
                    });
                }
                126 if !in_loops.contains(&de) => {
                    model.curves.push((de, self.curve(e, false)?));
                }
                126 | 124 | 144 | 142 | 143 | 141 | 102 | 110 => {}
                other => *model.unknown.entry(other).or_default() += 1,
            }
        }
        if !whole_domain.is_empty() {
            model.warnings.push(format!(
                "{} surfaces declare a parameter range that is not a rectangle inside their knot domain; the whole knot domain is imported: {}{}",
                whole_domain.len(),
                whole_domain[..whole_domain.len().min(5)].join(", "),
                if whole_domain.len() > 5 { ", …" } else { "" }
            ));
        }
        if !trimmed.is_empty() {
            let bases: Vec<String> = trimmed.keys().take(5).map(|b| format!("D{b}")).collect();
            model.warnings.push(format!(
                "{} trimmed or bounded surfaces stand on a surface that is not a B-spline surface (128), not imported: {}{}",
                trimmed.len(),
                bases.join(", "),
                if trimmed.len() > 5 { ", …" } else { "" }
            ));
        }
        if model.surfaces.iter().any(|s| s.trimmed) {
            model.warnings.push(
                "trimmed surfaces are imported whole: trimming is not applied to the display (the loops are kept as curves)".into(),
            );
        }
        Ok(())
    }

    /// The parameter-space loops of 142 entities (curves on surfaces).
    fn loops_142(
        &self,
        boundaries: &[usize],
        from: usize,
        in_loops: &mut std::collections::BTreeSet<usize>,
        skipped: &mut usize,
    ) -> Result<Vec<Vec<Point2<f64>>>, IgesError> {
        let mut out = Vec::new();
        for &b in boundaries {
            let e = self.entry(b, from)?;
            if e.kind != 142 {
                *skipped += 1;
                continue;
            }
            let p = self.params(e)?;
            let bptr = p.int(3)?;
            let cptr = p.int(4)?;
            if cptr > 0 {
                in_loops.insert(cptr as usize);
            }
            if bptr <= 0 {
                *skipped += 1;
                continue;
            }
            in_loops.insert(bptr as usize);
            mark_children(self, bptr as usize, in_loops);
            match self.polyline(bptr as usize, p.line_of(3), 0)? {
                Some(pts) if pts.len() >= 2 => out.push(pts),
                _ => *skipped += 1,
            }
        }
        Ok(out)
    }
}

/// Records that the trimmed or bounded surface `de` stands on `base`, placed by `map`: its
/// loops, to be extended, or `None` (noted in `twice`) when another one already placed `base`
/// with a different transformation (the first placement is imported).
fn place<'m>(
    trimmed: &'m mut BTreeMap<usize, Placement>,
    base: usize,
    map: Affine,
    de: usize,
    twice: &mut Vec<String>,
) -> Option<&'m mut Vec<Vec<Point2<f64>>>> {
    let (first, loops) = trimmed.entry(base).or_insert((map, Vec::new()));
    if *first != map {
        twice.push(format!("D{de}"));
        return None;
    }
    Some(loops)
}

/// Marks the components of a composite curve as parts of a loop.
fn mark_children(file: &File<'_>, de: usize, set: &mut std::collections::BTreeSet<usize>) {
    let Ok(e) = file.entry(de, 0) else { return };
    if e.kind != 102 {
        return;
    }
    if let Ok(p) = file.params(e) {
        let n = p.count(1, 0, 100_000).unwrap_or(0);
        for k in 0..n {
            if let Ok(c) = p.count(2 + k, 1, i64::MAX) {
                set.insert(c);
                mark_children(file, c, set);
            }
        }
    }
}
