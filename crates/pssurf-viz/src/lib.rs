//! # pssurf-viz
//!
//! Pictures and meshes of pssurf surfaces, without a GPU or a display:
//!
//! - [`colormap`]: colour maps (the seed's green–black–red with contrast C, perceptual and
//!   diverging maps, user stops) and colour scales;
//! - [`plot`](mod@plot): software rendering to PNG — shaded, curvature plots with a legend, zebra
//!   stripes and isophotes, overlays of the triangulation, refinement and control triangles;
//! - [`domain`]: the domain picture (triangulation, PS refinement, PS-points, PS-triangles) as
//!   SVG;
//! - [`export`]: meshes with curvature fields as PLY, OBJ, STL, glTF binary and VTK.
//!
//! The mathematics (curvature, sampling, fairness) lives in `pssurf::interrogate`.

pub mod camera;
pub mod colormap;
pub mod domain;
pub mod export;
pub mod import;
pub mod legend;
pub mod plot;
pub mod raster;
pub mod text;

pub use camera::{Camera, Projection};
pub use colormap::{ColorMap, ColorScale};
pub use domain::{DomainCurve, DomainOptions, domain_svg};
pub use export::{FieldMesh, MeshFormat, write_mesh};
pub use plot::{
    Overlays, Picture, PlotOptions, Polyline, Range, Shading, Show, plot, plot_surfaces,
    plot_with_lines,
};
