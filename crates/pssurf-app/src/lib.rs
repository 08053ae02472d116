//! # pssurf-app
//!
//! The interactive modeller and surface-interrogation application (the thesis' PS-surf,
//! chapter 6): a scene of PS, UPS and NURPS surfaces; a 3D view drawn with wgpu (shaded,
//! curvature plots with a legend, zebra stripes, overlays) with probing and control-point
//! dragging; a domain view to select PS-triangles; numeric editing with undo/redo; and
//! algorithm panels (subdivision, wavelets, noise) that plug in through [`panels::Panel`].

pub mod app;
pub mod camera;
pub mod create;
pub mod demo;
pub mod display;
pub mod document;
pub mod domain_view;
pub mod edit;
pub mod export;
pub mod gpu;
pub mod headless;
pub mod panels;
pub mod probe;
pub mod properties;
pub mod scene;
pub mod scene_tree;
pub mod view3d;

pub use app::App;
