//! f at a model's own centres by the symmetric tiles (`par_values_at_centres`) against the
//! plain compensated sums, on random clouds of every size around the lane and tile widths.

use proptest::prelude::*;
use rbf_core::{InterpolantView, Kernel};

use crate::support::kernel;

fn cloud<const D: usize>() -> impl Strategy<Value = (Vec<[f64; D]>, Vec<f64>)> {
    // Sizes from 2048 centres (below, the function is the reference itself), across the lane
    // (8) and tile (512) boundaries, a ragged last tile included.
    prop_oneof![2048usize..2100, 2500usize..2600].prop_flat_map(|n| {
        (
            prop::collection::vec(prop::array::uniform::<_, D>(-1.0..1.0f64), n),
            prop::collection::vec(-1.0..1.0f64, n),
        )
    })
}

/// Every row against `par_values_compensated` at the centres, within a few ulps of the sum of
/// the terms' sizes (|φ| ≤ 50 in the cube [−1, 1]^D for every kernel: r³ ≤ (2√3)³ ≈ 41.6).
fn agrees<const D: usize>(
    points: &[[f64; D]],
    weights: &[f64],
    k: Kernel,
) -> Result<(), TestCaseError> {
    let f = InterpolantView::new(k, points, weights, 0.25, [0.5; D]).expect("matching lengths");
    let n = points.len();
    let (mut fast, mut reference) = (vec![0.0; n], vec![0.0; n]);
    f.par_values_at_centres(&mut fast).expect("output length");
    f.par_values_compensated(points, &mut reference)
        .expect("output length");
    let scale = 50.0 * weights.iter().map(|w| w.abs()).sum::<f64>() + 1.0;
    for i in 0..n {
        let err = (fast[i] - reference[i]).abs();
        prop_assert!(
            err <= 1e-14 * scale,
            "{k:?}, {n} centres, row {i}: {} against {}",
            fast[i],
            reference[i]
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn every_row_matches_the_direct_sums_in_3d((points, weights) in cloud::<3>(), k in kernel()) {
        agrees(&points, &weights, k)?;
    }

    #[test]
    fn every_row_matches_the_direct_sums_in_2d((points, weights) in cloud::<2>(), k in kernel()) {
        agrees(&points, &weights, k)?;
    }
}

#[test]
fn a_wrong_output_length_is_refused() {
    let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[1.0], 0.0, [0.0; 3])
        .expect("one centre");
    assert!(f.par_values_at_centres(&mut [0.0; 2]).is_err());
}
