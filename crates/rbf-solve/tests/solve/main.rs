//! Integration tests of rbf-solve, in one binary.

mod limits;
mod scipy;
mod strategies;
