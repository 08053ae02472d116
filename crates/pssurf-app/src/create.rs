//! The "New surface" dialog: a UPS patch on a standard 3–6-sided lattice polygon interpolating
//! a height formula (like `pssurf new ups`), a graph quadric z = a x² + b xy + c y²
//! (reproduced exactly by PS-splines), or a cylinder, cone or sphere as exact NURPS patches
//! (like `pssurf new cylinder|cone|sphere`, thesis 3.6).

use nalgebra::Point2;
use pssurf::expr::HeightFunction;
use pssurf::ps::quadrics::{MAX_SECTORS, Quadric};
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface_from_formula};

use crate::command::{Command, FrameTarget, Shape, ViewContext};
use crate::scene::SceneObject;

/// The dialog's state.
#[derive(Clone, Debug, PartialEq)]
pub struct NewSurface {
    /// Whether the window is open.
    pub open: bool,
    /// Formula or quadric.
    pub shape: Shape,
    /// Sides of the standard polygon (3–6).
    pub sides: usize,
    /// Triangles along a side.
    pub size: i64,
    /// The polygon's side length (the lattice base is side / size).
    pub side_length: f64,
    /// The height formula.
    pub formula: String,
    /// The quadric's a, b, c.
    pub quadric: [f64; 3],
    /// Functional, parametric or NURPS.
    pub kind: GraphKind,
    /// The radius of a cylinder, cone (its base) or sphere.
    pub radius: f64,
    /// The height of a cylinder or cone.
    pub height: f64,
    /// The sphere's patches around each hemisphere.
    pub sectors: usize,
    /// The last problem, shown in the dialog.
    pub error: Option<String>,
}

impl Default for NewSurface {
    fn default() -> Self {
        NewSurface {
            open: false,
            shape: Shape::Formula,
            sides: 6,
            size: 4,
            side_length: 1.0,
            formula: "0.3*sin(3*x)*cos(2*y)".into(),
            quadric: [0.5, 0.0, 0.5],
            kind: GraphKind::Parametric,
            radius: 1.0,
            height: 2.0,
            sectors: 6,
            error: None,
        }
    }
}

impl NewSurface {
    /// The height formula of a UPS graph surface (a graph quadric's as a formula; the formula
    /// field for every other shape).
    pub fn height(&self) -> String {
        match self.shape {
            Shape::Quadric => {
                let [a, b, c] = self.quadric;
                format!("({a})*x^2 + ({b})*x*y + ({c})*y^2")
            }
            _ => self.formula.clone(),
        }
    }

    /// The closed quadric of a cylinder, cone or sphere shape.
    pub fn quadric(&self) -> Option<Quadric> {
        let (radius, height) = (self.radius, self.height);
        match self.shape {
            Shape::Cylinder => Some(Quadric::Cylinder { radius, height }),
            Shape::Cone => Some(Quadric::Cone { radius, height }),
            Shape::Sphere => Some(Quadric::Sphere {
                radius,
                sectors: self.sectors,
            }),
            Shape::Formula | Shape::Quadric => None,
        }
    }

    /// A name for the new object (for a closed quadric, its group's name).
    pub fn name(&self) -> String {
        let polygon = ["triangle", "rhombus", "pentagon", "hexagon"][self.sides.clamp(3, 6) - 3];
        if let Some(q) = self.quadric() {
            return q.name().to_string();
        }
        match self.shape {
            Shape::Formula => format!("UPS {polygon}"),
            Shape::Quadric => {
                let [a, _, c] = self.quadric;
                let kind = if a * c > 0.0 {
                    "elliptic paraboloid"
                } else if a * c < 0.0 {
                    "hyperbolic paraboloid"
                } else {
                    "parabolic cylinder"
                };
                format!("{kind} ({polygon})")
            }
            _ => unreachable!("closed quadrics are named above"),
        }
    }

    /// The new objects: one UPS surface, or the patches of a closed quadric grouped under its
    /// name.
    pub fn objects(&self) -> Result<Vec<SceneObject>, String> {
        let Some(q) = self.quadric() else {
            return Ok(vec![SceneObject::new(self.name(), self.build()?)]);
        };
        let patches = q.nurps_patches().map_err(|e| e.to_string())?;
        Ok(patches
            .into_iter()
            .enumerate()
            .map(|(k, p)| {
                let mut o = SceneObject::new(format!("{} {}", q.name(), k + 1), Surface::Nurps(p));
                o.group = q.name().to_string();
                o
            })
            .collect())
    }

    /// Builds the UPS surface of a formula or graph quadric: the standard polygon centred at
    /// the origin.
    pub fn build(&self) -> Result<Surface, String> {
        if !(3..=6).contains(&self.sides) {
            return Err("the polygon must have 3 to 6 sides".into());
        }
        if !(1..=200).contains(&self.size) {
            return Err("give 1 to 200 triangles per side".into());
        }
        if !(self.side_length.is_finite() && self.side_length > 0.0) {
            return Err("the side length must be positive".into());
        }
        let polygon = LatticePolygon::standard(self.sides, self.size).map_err(|e| e.to_string())?;
        let base = self.side_length / self.size as f64;
        let at = |origin| Lattice { base, origin };
        let grid =
            UpsGrid::new(at(Point2::origin()), polygon.clone()).map_err(|e| e.to_string())?;
        // Centre the polygon's bounding box at the origin.
        let (lo, hi) = grid_bounds(&grid);
        let grid = UpsGrid::new(at(Point2::from(-(lo.coords + hi.coords) / 2.0)), polygon)
            .map_err(|e| e.to_string())?;
        let f = HeightFunction::parse(&self.height()).map_err(|e| e.to_string())?;
        let ups = graph_surface_from_formula(grid, self.kind, &f).map_err(|e| e.to_string())?;
        Surface::try_from(ups).map_err(|e| e.to_string())
    }
}

/// The bounding box of a grid's polygon (that of its corners).
fn grid_bounds(grid: &UpsGrid) -> (Point2<f64>, Point2<f64>) {
    let corners = grid.polygon().vertices().iter();
    let points: Vec<Point2<f64>> = corners.map(|&c| grid.lattice().point(c)).collect();
    let lo = points.iter().fold(points[0], |a, p| a.inf(p));
    let hi = points.iter().fold(points[0], |a, p| a.sup(p));
    (lo, hi)
}

impl NewSurface {
    /// Opens the dialog on a shape.
    pub fn open(&mut self, shape: Shape) {
        self.shape = shape;
        self.open = true;
    }

    /// Asks to add the dialog's surface to the scene (one undoable edit, selected and
    /// framed) and closes the dialog; a problem stays in the dialog instead.
    pub fn create(&mut self, cx: &mut ViewContext<'_>) {
        let objects = match self.objects() {
            Ok(o) => o,
            Err(e) => {
                self.error = Some(e);
                return;
            }
        };
        self.error = None;
        self.open = false;
        cx.emit(Command::Add(objects));
        cx.emit(Command::Frame(FrameTarget::All));
    }

    /// Draws the dialog when open.
    pub fn window(&mut self, ctx: &egui::Context, cx: &mut ViewContext<'_>) {
        if !self.open {
            return;
        }
        let mut open = true;
        let mut go = false;
        egui::Window::new("New surface")
            .open(&mut open)
            .resizable(false)
            .show(ctx, |ui| go = self.fields(ui));
        if go {
            self.create(cx);
        }
        if !open {
            self.open = false;
        }
    }

    /// The dialog's fields; returns whether Create was clicked.
    fn fields(&mut self, ui: &mut egui::Ui) -> bool {
        let d = self;
        ui.horizontal(|ui| {
            ui.radio_value(&mut d.shape, Shape::Formula, "height formula");
            ui.radio_value(&mut d.shape, Shape::Quadric, "graph quadric");
            ui.radio_value(&mut d.shape, Shape::Cylinder, "cylinder");
            ui.radio_value(&mut d.shape, Shape::Cone, "cone");
            ui.radio_value(&mut d.shape, Shape::Sphere, "sphere");
        });
        if d.shape.is_solid_quadric() {
            d.quadric_fields(ui);
            if let Some(e) = &d.error {
                ui.colored_label(egui::Color32::from_rgb(190, 30, 30), e);
            }
            return ui.button("Create").clicked();
        }
        egui::Grid::new("new surface")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label("polygon");
                egui::ComboBox::from_label("sides")
                    .selected_text(format!("{} sides", d.sides))
                    .show_ui(ui, |ui| {
                        for n in 3..=6 {
                            ui.selectable_value(&mut d.sides, n, format!("{n} sides"));
                        }
                    });
                ui.end_row();
                let l = ui.label("triangles per side");
                ui.add(egui::DragValue::new(&mut d.size).range(1..=200))
                    .labelled_by(l.id);
                ui.end_row();
                let rule = crate::fields::Rule::Within(1e-6, 1e6);
                let side = &mut d.side_length;
                let outcome = crate::fields::labelled(ui, "side length", side, rule, 0.01);
                if let Some(m) = outcome.refusal() {
                    d.error = Some(m);
                }
                ui.end_row();
                match d.shape {
                    Shape::Quadric => {
                        for (k, name) in ["a (x²)", "b (xy)", "c (y²)"].iter().enumerate() {
                            let rule = crate::fields::Rule::Within(-1e12, 1e12);
                            let x = &mut d.quadric[k];
                            let outcome = crate::fields::labelled(ui, name, x, rule, 0.01);
                            if let Some(m) = outcome.refusal() {
                                d.error = Some(m);
                            }
                            ui.end_row();
                        }
                    }
                    _ => {
                        let l = ui.label("z =");
                        ui.text_edit_singleline(&mut d.formula)
                            .labelled_by(l.id)
                            .on_hover_text(
                                "x, y, numbers, + - * / ^, sin cos tan exp ln sqrt abs, PI, E",
                            );
                        ui.end_row();
                    }
                }
                ui.label("kind");
                ui.horizontal(|ui| {
                    ui.radio_value(&mut d.kind, GraphKind::Parametric, "parametric");
                    ui.radio_value(&mut d.kind, GraphKind::Functional, "functional");
                    ui.radio_value(&mut d.kind, GraphKind::Rational, "NURPS");
                });
                ui.end_row();
            });
        if d.shape == Shape::Quadric {
            ui.weak(format!("z = {}", d.height()));
        }
        if let Some(e) = &d.error {
            ui.colored_label(egui::Color32::from_rgb(190, 30, 30), e);
        }
        ui.button("Create").clicked()
    }
}

impl NewSurface {
    /// The fields of a cylinder, cone or sphere, and what the result will be.
    fn quadric_fields(&mut self, ui: &mut egui::Ui) {
        let d = self;
        egui::Grid::new("new quadric")
            .num_columns(2)
            .show(ui, |ui| {
                let rule = crate::fields::Rule::Within(1e-6, 1e6);
                let outcome = crate::fields::labelled(ui, "radius", &mut d.radius, rule, 0.01);
                if let Some(m) = outcome.refusal() {
                    d.error = Some(m);
                }
                ui.end_row();
                if d.shape == Shape::Sphere {
                    let l = ui.label("sectors");
                    ui.add(egui::DragValue::new(&mut d.sectors).range(3..=MAX_SECTORS))
                        .labelled_by(l.id)
                        .on_hover_text("patches around each hemisphere: more, thinner gaps");
                } else {
                    let h = &mut d.height;
                    let outcome = crate::fields::labelled(ui, "height", h, rule, 0.01);
                    if let Some(m) = outcome.refusal() {
                        d.error = Some(m);
                    }
                }
                ui.end_row();
            });
        let what = match d.quadric() {
            Some(q @ Quadric::Sphere { sectors, .. }) => format!(
                "{} NURPS patches, exact; two bands {:.3e} high next to the equator stay open                  (no rational quadratic triangles close a sphere)",
                2 * sectors,
                q.gap()
            ),
            Some(Quadric::Cylinder { .. }) => "8 NURPS patches, exact and closed".into(),
            Some(Quadric::Cone { .. }) => "6 NURPS patches meeting at the apex, exact".into(),
            None => String::new(),
        };
        ui.weak(what);
    }
}
