//! One module per subcommand.

pub mod approx;
pub mod curvature;
pub mod curve;
pub mod denoise;
pub mod domain;
pub mod edit;
pub mod eval;
pub mod export;
pub mod fair;
pub mod fairness;
pub mod fit;
pub mod hole;
pub mod import;
pub mod info;
pub mod mesh;
pub mod new;
pub mod noise;
pub mod plot;
pub mod probe;
pub mod showcase;
pub mod subdivide;
pub mod trace;
pub mod trace_lines;
pub mod uniform;
pub mod view;
pub mod wavelet;
