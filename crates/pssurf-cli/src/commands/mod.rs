//! One module per subcommand.

pub mod eval;
pub mod fit;
pub mod info;
