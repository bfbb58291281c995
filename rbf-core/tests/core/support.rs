//! Generators shared by the tests.

use proptest::prelude::*;
use rbf_core::{Constraint, Kernel};

/// Points of a jittered grid in [−1, 1]ᴰ: `n` of the cells of a grid of side `side`, each moved
/// at most 0.3 cell from its centre, so any two points are at least 0.4 cell apart.
pub fn jittered<const D: usize>(n: usize) -> impl Strategy<Value = Vec<[f64; D]>> {
    let side = (n as f64).powf(1.0 / D as f64).ceil() as usize + 1;
    let cells = side.pow(D as u32);
    (
        Just(()).prop_perturb(move |_, mut rng| {
            let mut order: Vec<usize> = (0..cells).collect();
            for i in (1..cells).rev() {
                let j = (rng.next_u64() % (i as u64 + 1)) as usize;
                order.swap(i, j);
            }
            order.truncate(n);
            order
        }),
        proptest::collection::vec(proptest::array::uniform::<_, D>(-0.3..0.3_f64), n),
    )
        .prop_map(move |(order, jitter)| {
            order
                .iter()
                .zip(jitter)
                .map(|(&cell, j)| {
                    let mut c = cell;
                    core::array::from_fn(|d| {
                        let i = c % side;
                        c /= side;
                        ((i as f64 + 0.5 + j[d]) / side as f64) * 2.0 - 1.0
                    })
                })
                .collect()
        })
}

/// Value constraints at well-spaced points, values in [−1, 1] with at least one non-zero.
pub fn value_constraints<const D: usize>(
    min: usize,
    max: usize,
) -> impl Strategy<Value = Vec<Constraint<D>>> {
    (min..=max).prop_flat_map(|n| {
        (
            jittered::<D>(n),
            proptest::collection::vec(-1.0..1.0_f64, n),
            proptest::collection::vec(0..3_u8, n),
        )
            .prop_map(|(points, values, kinds)| {
                points
                    .into_iter()
                    .zip(values)
                    .zip(kinds)
                    .enumerate()
                    .map(|(i, ((p, v), k))| match (i, k) {
                        (0, _) | (_, 0) => Constraint::interior(p, v.abs() + 0.1),
                        (_, 1) => Constraint::exterior(p, -(v.abs() + 0.1)),
                        _ => Constraint::boundary(p),
                    })
                    .collect()
            })
    })
}

/// The kernels, each paired with a dimension where it is at home.
pub fn kernel() -> impl Strategy<Value = Kernel> {
    prop_oneof![
        Just(Kernel::Cubic),
        Just(Kernel::Linear),
        Just(Kernel::ThinPlate)
    ]
}

/// A rotation matrix from Euler angles.
pub fn rotation(a: f64, b: f64, c: f64) -> [[f64; 3]; 3] {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sc, cc) = c.sin_cos();
    let rz = [[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]];
    let ry = [[cb, 0.0, sb], [0.0, 1.0, 0.0], [-sb, 0.0, cb]];
    let rx = [[1.0, 0.0, 0.0], [0.0, cc, -sc], [0.0, sc, cc]];
    mul(mul(rz, ry), rx)
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// R x.
pub fn rotate(r: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|i| (0..3).map(|k| r[i][k] * x[k]).sum())
}

/// max |hᵢ| of constraints.
pub fn max_value<const D: usize>(cs: &[Constraint<D>]) -> f64 {
    cs.iter().fold(0.0, |m, c| m.max(c.value.abs()))
}
