//! The domain picture as SVG: the triangulation, its Powell–Sabin refinement, the PS-points
//! and PS-triangles, optionally coloured by a curvature quantity (this replaces the
//! picTeX/TeXdraw export of the thesis' PS-surf).

use nalgebra::Point2;
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::ps::PsBasis;
use pssurf::ps::ps_triangles::ps_points;
use pssurf::surface::{ParametricSurface, PiecewiseSurface, Surface};
use pssurf::triangulation::Triangulation;
use svg::Document;
use svg::node::element::path::Data;
use svg::node::element::{
    Circle, Definitions, Group, LinearGradient, Path, Polygon, Rectangle as Rect, Stop, Text,
};

use crate::colormap::{ColorMap, ColorScale};
use crate::legend::{format_tick, ticks};
use crate::plot::{Range, range_scale};

/// What the domain picture shows.
#[derive(Clone, Debug)]
pub struct DomainOptions {
    /// The triangles of Δ.
    pub triangulation: bool,
    /// The refinement Δ* (split lines, dashed).
    pub refinement: bool,
    /// The PS-points of every vertex (Definition 2.19).
    pub ps_points: bool,
    /// The PS-triangles (Definition 2.20).
    pub ps_triangles: bool,
    /// Vertex numbers.
    pub vertex_labels: bool,
    /// Fill the sub-triangles by a curvature quantity (each piece with its own values).
    pub color: Option<CurvatureQuantity>,
    /// The colour map for `color`.
    pub colormap: ColorMap,
    /// The colour range for `color`.
    pub range: Range,
    /// Sampling level for `color`: each sub-triangle is split into 4^level cells.
    pub level: u32,
    /// Picture width in pixels (the height follows the domain's aspect ratio).
    pub width: f64,
    /// Curves in the parameter domain drawn over everything (traced level lines, lines of
    /// curvature, geodesics).
    pub curves: Vec<DomainCurve>,
}

/// A polyline in the parameter domain, with its colour.
#[derive(Clone, Debug, PartialEq)]
pub struct DomainCurve {
    /// The parameter points.
    pub uvs: Vec<Point2<f64>>,
    /// Whether the last point joins the first.
    pub closed: bool,
    /// The stroke colour (RGB).
    pub color: [u8; 3],
}

impl Default for DomainOptions {
    fn default() -> Self {
        DomainOptions {
            triangulation: true,
            refinement: true,
            ps_points: false,
            ps_triangles: true,
            vertex_labels: false,
            color: None,
            colormap: ColorMap::named("coolwarm").expect("built-in"),
            range: Range::Auto,
            level: 2,
            width: 800.0,
            curves: Vec::new(),
        }
    }
}

fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Maps domain points to picture coordinates (y up in the domain, down in SVG).
struct Frame {
    lo: Point2<f64>,
    hi_y: f64,
    scale: f64,
    margin: f64,
    /// The width of the drawing area.
    inner: f64,
    /// The width kept for the legend.
    legend_w: f64,
    /// The picture's height.
    height: f64,
}

impl Frame {
    fn map(&self, p: Point2<f64>) -> (f64, f64) {
        (
            self.margin + (p.x - self.lo.x) * self.scale,
            self.margin + (self.hi_y - p.y) * self.scale,
        )
    }
}

/// The domain picture of a surface as an SVG document. The triangulation, refinement,
/// PS-triangles, PS-points and labels are drawn for the PS kinds; other kinds show their
/// pieces' outlines (and the colour cells).
pub fn domain_svg(surface: &Surface, opts: &DomainOptions) -> String {
    let basis = surface.ps_basis();
    let frame = picture_frame(surface, basis.map(|b| b.ps_triangles()), opts);
    let stroke = (1.2 * frame.inner / 800.0).clamp(0.5, 2.0);
    let mut doc = Document::new()
        .set("viewBox", (0, 0, opts.width, frame.height))
        .set("width", opts.width)
        .set("height", frame.height)
        .add(
            Rect::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        );
    if let Some(q) = opts.color {
        let (group, scale) = colored_cells(surface, q, opts, &frame);
        doc = doc.add(group);
        doc = add_legend(
            doc,
            q,
            &opts.colormap,
            &scale,
            opts.width - frame.legend_w + 10.0,
            frame.margin,
            frame.height - 2.0 * frame.margin,
        );
    }
    match basis {
        Some(basis) => {
            if opts.refinement {
                doc = doc.add(refinement_layer(basis, &frame, stroke));
            }
            if opts.triangulation {
                doc = doc.add(triangulation_layer(basis.triangulation(), &frame, stroke));
            }
            if opts.ps_triangles {
                doc = doc.add(ps_triangle_layer(basis, &frame, stroke));
            }
            if opts.ps_points {
                doc = doc.add(ps_point_layer(basis, &frame, stroke));
            }
            if opts.vertex_labels {
                doc = doc.add(label_layer(basis.triangulation(), &frame, stroke));
            }
        }
        None if opts.triangulation => doc = doc.add(piece_layer(surface, &frame, stroke)),
        None => {}
    }
    if !opts.curves.is_empty() {
        doc = doc.add(curve_layer(&opts.curves, &frame, 1.5 * stroke));
    }
    doc.to_string()
}

/// The curves as one group of paths.
fn curve_layer(curves: &[DomainCurve], frame: &Frame, stroke: f64) -> Group {
    let mut g = Group::new()
        .set("fill", "none")
        .set("stroke-width", stroke)
        .set("stroke-linejoin", "round");
    for c in curves.iter().filter(|c| c.uvs.len() >= 2) {
        let mut data = Data::new().move_to(frame.map(c.uvs[0]));
        for p in &c.uvs[1..] {
            data = data.line_to(frame.map(*p));
        }
        if c.closed {
            data = data.close();
        }
        g = g.add(Path::new().set("d", data).set("stroke", hex(c.color)));
    }
    g
}

/// Scales the domain (and PS-triangles, which may reach outside it, when shown) into the
/// picture, leaving room for a legend.
fn picture_frame(
    surface: &Surface,
    ps_triangles: Option<&[pssurf::geometry::Triangle2]>,
    opts: &DomainOptions,
) -> Frame {
    let (mut lo, mut hi) = surface.domain_bounds();
    if opts.ps_triangles {
        for v in ps_triangles.unwrap_or(&[]).iter().flat_map(|t| t.v) {
            lo = lo.inf(&v);
            hi = hi.sup(&v);
        }
    }
    let legend_w = if opts.color.is_some() { 150.0 } else { 0.0 };
    let margin = 20.0;
    let span = (hi - lo).max().max(1e-300);
    let inner = (opts.width - 2.0 * margin - legend_w).max(50.0);
    let scale = inner / (hi.x - lo.x).max(span * 1e-3);
    Frame {
        lo,
        hi_y: hi.y,
        scale,
        margin,
        inner,
        legend_w,
        height: (2.0 * margin + (hi.y - lo.y) * scale).max(200.0),
    }
}

/// The split lines of Δ*, dashed.
fn refinement_layer(basis: &PsBasis, frame: &Frame, stroke: f64) -> Path {
    let (tri, r) = (basis.triangulation(), basis.refinement());
    let mut data = Data::new();
    for t in 0..tri.triangle_count() {
        let z = frame.map(r.z(t));
        let v = tri.triangle(t);
        for c in 0..3 {
            for end in [tri.vertex(v[c]), r.edge_point(tri, t, c)] {
                data = data.move_to(z).line_to(frame.map(end));
            }
        }
    }
    Path::new()
        .set("d", data)
        .set("fill", "none")
        .set("stroke", "#3050c0")
        .set("stroke-width", 0.6 * stroke)
        .set(
            "stroke-dasharray",
            format!("{} {}", 3.0 * stroke, 2.0 * stroke),
        )
}

/// The edges of Δ, each once.
fn triangulation_layer(tri: &Triangulation, frame: &Frame, stroke: f64) -> Path {
    let mut data = Data::new();
    for t in 0..tri.triangle_count() {
        for i in 0..3 {
            let (a, b) = tri.edge_vertices(t, i);
            if tri.is_boundary_edge(t, i) || a < b {
                data = data
                    .move_to(frame.map(tri.vertex(a)))
                    .line_to(frame.map(tri.vertex(b)));
            }
        }
    }
    Path::new()
        .set("d", data)
        .set("fill", "none")
        .set("stroke", "black")
        .set("stroke-width", stroke)
}

/// The outlines of every piece (for kinds without a triangulation).
fn piece_layer(surface: &Surface, frame: &Frame, stroke: f64) -> Group {
    let mut g = Group::new()
        .set("fill", "none")
        .set("stroke", "black")
        .set("stroke-width", stroke);
    for k in 0..surface.piece_count() {
        g = g.add(Polygon::new().set(
            "points",
            points_attr(frame, &surface.piece_shape(k).corners()),
        ));
    }
    g
}

/// The PS-triangles t_i.
fn ps_triangle_layer(basis: &PsBasis, frame: &Frame, stroke: f64) -> Group {
    let mut g = Group::new()
        .set("fill", "none")
        .set("stroke", "#d06000")
        .set("stroke-width", 0.7 * stroke);
    for t in basis.ps_triangles() {
        g = g.add(Polygon::new().set("points", points_attr(frame, &t.v)));
    }
    g
}

/// The PS-points of every vertex.
fn ps_point_layer(basis: &PsBasis, frame: &Frame, stroke: f64) -> Group {
    let tri = basis.triangulation();
    let mut g = Group::new().set("fill", "#008040");
    for i in 0..tri.vertex_count() {
        for p in ps_points(tri, basis.refinement(), i) {
            let (x, y) = frame.map(p);
            g = g.add(
                Circle::new()
                    .set("cx", x)
                    .set("cy", y)
                    .set("r", 1.6 * stroke),
            );
        }
    }
    g
}

/// Vertex numbers.
fn label_layer(tri: &Triangulation, frame: &Frame, stroke: f64) -> Group {
    let mut g = Group::new()
        .set("font-family", "monospace")
        .set("font-size", 10.0 * stroke)
        .set("fill", "#800000");
    for i in 0..tri.vertex_count() {
        let (x, y) = frame.map(tri.vertex(i));
        g = g.add(
            Text::new(i.to_string())
                .set("x", x + 2.0 * stroke)
                .set("y", y - 2.0 * stroke),
        );
    }
    g
}

/// An SVG `points` attribute.
fn points_attr(frame: &Frame, pts: &[Point2<f64>]) -> String {
    pts.iter()
        .map(|&v| {
            let (x, y) = frame.map(v);
            format!("{x:.3},{y:.3}")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Small filled triangles coloured by the quantity, piece by piece.
fn colored_cells(
    surface: &Surface,
    q: CurvatureQuantity,
    opts: &DomainOptions,
    frame: &Frame,
) -> (Group, ColorScale) {
    let s = sample_patches(surface, opts.level, true);
    let values = s.quantity(q);
    let (lo, hi) = surface.domain_bounds();
    let scale = range_scale(opts.range, &opts.colormap, q, &values, (hi - lo).norm());
    let mut g = Group::new().set("stroke-width", 0.3);
    for t in &s.mesh.triangles {
        let [a, b, c] = t.map(|k| k as usize);
        let v = (values[a] + values[b] + values[c]) / 3.0;
        let color = hex(opts.colormap.at(scale.position(v)));
        let pts: Vec<String> = [a, b, c]
            .iter()
            .map(|&k| {
                let (x, y) = frame.map(s.mesh.uvs[k]);
                format!("{x:.2},{y:.2}")
            })
            .collect();
        // The stroke in the fill colour hides hairline seams between cells.
        g = g.add(
            Polygon::new()
                .set("points", pts.join(" "))
                .set("fill", color.clone())
                .set("stroke", color),
        );
    }
    (g, scale)
}

fn add_legend(
    doc: Document,
    q: CurvatureQuantity,
    map: &ColorMap,
    scale: &ColorScale,
    x: f64,
    y: f64,
    h: f64,
) -> Document {
    let mut grad = LinearGradient::new()
        .set("id", "legend")
        .set("x1", 0)
        .set("y1", 1)
        .set("x2", 0)
        .set("y2", 0);
    for k in 0..=16 {
        let t = k as f64 / 16.0;
        grad = grad.add(
            Stop::new()
                .set("offset", t)
                .set("stop-color", hex(map.at(t))),
        );
    }
    let (bar_y, bar_h) = (y + 30.0, (h - 40.0).max(20.0));
    let mut g = Group::new()
        .set("font-family", "sans-serif")
        .set("font-size", 12)
        .add(Text::new(q.titled()).set("x", x).set("y", y + 12.0))
        .add(
            Rect::new()
                .set("x", x)
                .set("y", bar_y)
                .set("width", 16)
                .set("height", bar_h)
                .set("fill", "url(#legend)")
                .set("stroke", "black"),
        );
    let ticks = ticks(scale);
    let step = if ticks.len() > 1 {
        ticks[1].0 - ticks[0].0
    } else {
        1.0
    };
    for (v, t) in ticks {
        let ty = bar_y + (1.0 - t) * bar_h;
        g = g
            .add(
                Path::new()
                    .set(
                        "d",
                        Data::new().move_to((x + 16.0, ty)).line_to((x + 21.0, ty)),
                    )
                    .set("stroke", "black"),
            )
            .add(
                Text::new(format_tick(v, step))
                    .set("x", x + 24.0)
                    .set("y", ty + 4.0),
            );
    }
    doc.add(Definitions::new().add(grad)).add(g)
}
