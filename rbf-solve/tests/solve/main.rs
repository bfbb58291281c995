//! Integration tests of rbf-solve, in one binary.

mod greedy;
mod iterative;
mod limits;
mod scipy;
mod strategies;
