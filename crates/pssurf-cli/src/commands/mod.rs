//! One module per subcommand.

pub mod curvature;
pub mod denoise;
pub mod domain;
pub mod eval;
pub mod export;
pub mod fairness;
pub mod fit;
pub mod info;
pub mod new;
pub mod noise;
pub mod plot;
pub mod showcase;
pub mod subdivide;
pub mod trace;
pub mod uniform;
pub mod view;
pub mod wavelet;
