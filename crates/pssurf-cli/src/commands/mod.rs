//! One module per subcommand.

pub mod denoise;
pub mod eval;
pub mod fit;
pub mod info;
pub mod new;
pub mod noise;
pub mod subdivide;
pub mod uniform;
pub mod wavelet;
