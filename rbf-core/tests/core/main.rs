//! Integration tests of rbf-core, in one binary.

mod bound;
mod errors;
mod figures;
mod model_file;
mod precision;
mod properties;
mod support;
#[cfg(feature = "rayon")]
mod symmetric;
