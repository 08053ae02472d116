//! # pssurf-app
//!
//! The interactive modeller and surface-interrogation application (the thesis' PS-surf,
//! chapter 6): a scene of PS, UPS and NURPS surfaces; a 3D view drawn with wgpu (shaded,
//! curvature plots with a legend, zebra stripes, overlays) with probing and control-point
//! dragging; a domain view to select PS-triangles; numeric editing with undo/redo; and
//! algorithm panels (subdivision, wavelets, noise) that plug in through [`panels::Panel`].
//!
//! The state is in three parts: the [`document::Document`] (scene, selection, history), the
//! saved [`state::ViewState`] (display, camera, light, probe and panel settings) and the
//! [`runtime::Runtime`] (geometry cache, probe results, GPU). Views read them through a
//! [`command::ViewContext`] and ask for changes with [`command::Command`]s, which
//! [`App::apply`] applies after the frame; no view module imports `app`.

pub mod app;
pub mod cache;
pub mod camera;
pub mod command;
pub mod create;
pub mod curves;
pub mod demo;
pub mod display;
pub mod document;
pub mod domain_view;
pub mod edit;
pub mod export;
pub mod fields;
pub mod files;
pub mod gpu;
pub mod headless;
pub mod legend;
pub mod menu;
pub mod mesh_view;
pub mod panels;
pub mod probe;
pub mod properties;
pub mod runtime;
pub mod scene;
pub mod scene_tree;
pub mod shape_tools;
pub mod state;
pub mod view3d;
pub mod view_settings;

pub use app::App;
