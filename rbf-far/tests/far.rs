//! The far field against direct sums: values and gradients on random, clustered, anisotropic
//! and nearly coplanar clouds, with weights that cancel as fitted weights do; the evaluator
//! within the accuracy asked at every point, not only at its samples.

use proptest::prelude::*;
use rbf_core::{InterpolantView, Kernel, ScalarField};
use rbf_far::{Evaluator, FarField, FarFieldSettings, Method};

/// A deterministic generator.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[derive(Clone, Copy, Debug)]
enum Cloud {
    Random,
    Clustered,
    Anisotropic,
    NearlyCoplanar,
}

fn cloud(kind: Cloud, n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = Rng(seed);
    let mut u = move || rng.uniform();
    let centres: Vec<[f64; 3]> = (0..8).map(|_| [u(), u(), u()]).collect();
    (0..n)
        .map(|i| match kind {
            Cloud::Random => [u(), u(), u()],
            Cloud::Clustered => {
                let c = centres[i % 8];
                [c[0] + 0.01 * u(), c[1] + 0.01 * u(), c[2] + 0.01 * u()]
            }
            Cloud::Anisotropic => [50.0 * u(), u(), 0.02 * u()],
            Cloud::NearlyCoplanar => [u(), u(), 1e-7 * u()],
        })
        .collect()
}

/// Weights that cancel in pairs of neighbours (as a normal constraint's two rows do), on top
/// of a smooth part.
fn weights(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Rng(seed ^ 0xABCD);
    (0..n)
        .map(|i| {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            sign * (1.0 + rng.uniform()) + 0.1 * (rng.uniform() - 0.5)
        })
        .collect()
}

/// Σ|wⱼ| φ(|x − cⱼ|) at x: the size of what the sums cancel, the scale of their rounding.
fn magnitude(kernel: Kernel, centres: &[[f64; 3]], w: &[f64], x: &[f64; 3]) -> f64 {
    centres
        .iter()
        .zip(w)
        .map(|(c, w)| {
            let r = (0..3).map(|d| (x[d] - c[d]).powi(2)).sum::<f64>().sqrt();
            w.abs() * kernel.phi(r).abs()
        })
        .sum()
}

/// The worst error of values and gradients at the targets, relative to the magnitude there.
fn worst_relative_error(
    kernel: Kernel,
    centres: &[[f64; 3]],
    w: &[f64],
    targets: &[[f64; 3]],
    order: usize,
) -> (f64, f64) {
    let settings = FarFieldSettings {
        order,
        leaf: 16,
        target_leaf: 16,
        ..FarFieldSettings::default()
    };
    let field = FarField::new(kernel, centres, &settings);
    let charges = field.charges(w).unwrap();
    let (mut v, mut g) = (vec![0.0; targets.len()], vec![[0.0; 3]; targets.len()]);
    field
        .values_and_gradients(&charges, targets, &mut v, &mut g)
        .unwrap();
    let mut only = vec![0.0; targets.len()];
    field.values(&charges, targets, &mut only).unwrap();
    let direct = InterpolantView::new(kernel, centres, w, 0.0, [0.0; 3]).unwrap();
    let (mut dv, mut dg) = (vec![0.0; targets.len()], vec![[0.0; 3]; targets.len()]);
    direct
        .values_and_gradients(targets, &mut dv, &mut dg)
        .unwrap();
    let (mut value_error, mut gradient_error) = (0.0_f64, 0.0_f64);
    for (i, x) in targets.iter().enumerate() {
        let m = magnitude(kernel, centres, w, x);
        // The extent of the cloud turns the value's scale into the gradient's.
        let extent = centres
            .iter()
            .map(|c| (0..3).map(|d| (x[d] - c[d]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max)
            .max(1e-300);
        assert_eq!(v[i], only[i], "values alone and with gradients agree");
        value_error = value_error.max((v[i] - dv[i]).abs() / m);
        for d in 0..3 {
            gradient_error = gradient_error.max((g[i][d] - dg[i][d]).abs() * extent / m);
        }
    }
    (value_error, gradient_error)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// At order 12 the far field's error is within 1e-9 of what the sums cancel (Σ|wⱼ|φ), for
    /// values and gradients, whatever the cloud's shape; at order 8 within 1e-3 for values and
    /// 1e-2 for gradients (measured: up to 3e-11 at order 12; at order 8, 4.3e-5 for values
    /// and 2.3e-3 for gradients of r on a clustered cloud, seed 196).
    #[test]
    fn far_field_matches_direct_sums(
        kind in prop::sample::select(vec![
            Cloud::Random, Cloud::Clustered, Cloud::Anisotropic, Cloud::NearlyCoplanar,
        ]),
        kernel in prop::sample::select(vec![Kernel::Cubic, Kernel::Linear]),
        seed in 0u64..1000,
    ) {
        // A random cloud fills space: it needs more centres before clusters pay for proxies.
        let n = if matches!(kind, Cloud::Random) { 12_000 } else { 3000 };
        let centres = cloud(kind, n, seed);
        let w = weights(centres.len(), seed);
        // Targets: some centres, and points around the cloud.
        let mut targets: Vec<[f64; 3]> = centres.iter().step_by(7).copied().collect();
        targets.extend(cloud(Cloud::Random, 200, seed + 1).iter().map(|p| [2.0 * p[0] - 0.5, 2.0 * p[1] - 0.5, p[2]]));
        let (v12, g12) = worst_relative_error(kernel, &centres, &w, &targets, 12);
        prop_assert!(v12 <= 1e-9 && g12 <= 1e-9, "{kind:?} {kernel:?}: order 12 values {v12:e}, gradients {g12:e}");
        let (v8, g8) = worst_relative_error(kernel, &centres, &w, &targets, 8);
        prop_assert!(v8 <= 1e-3 && g8 <= 1e-2, "{kind:?} {kernel:?}: order 8 values {v8:e}, gradients {g8:e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    /// The product at the centres, taken by the dual traversal (grids on the targets' side
    /// too), is within 1e-9 of what the sums cancel at order 12 and 1e-3 at order 8 on every
    /// kind of cloud; taken at a few rows only, it is the same as taken at all; and so are sums
    /// at as many other points, which take the dual traversal with a tree over them.
    #[test]
    fn the_product_at_the_centres_matches_direct_sums(
        kind in prop::sample::select(vec![
            Cloud::Random, Cloud::Clustered, Cloud::Anisotropic, Cloud::NearlyCoplanar,
        ]),
        kernel in prop::sample::select(vec![Kernel::Cubic, Kernel::Linear]),
        seed in 0u64..1000,
    ) {
        let n = if matches!(kind, Cloud::Random) { 12_000 } else { 6000 };
        let centres = cloud(kind, n, seed);
        let w = weights(n, seed);
        let direct = InterpolantView::new(kernel, &centres, &w, 0.0, [0.0; 3]).unwrap();
        for (order, bound) in [(12, 1e-9), (8, 1e-3)] {
            let settings = FarFieldSettings { order, leaf: 16, ..FarFieldSettings::default() };
            let field = FarField::new(kernel, &centres, &settings);
            let charges = field.charges(&w).unwrap();
            let mut all = vec![0.0; n];
            field.self_values(&charges, &mut all).unwrap();
            let rows = field.sample_rows(200);
            prop_assert!(rows.len() >= 200 && rows.iter().all(|&r| r < n));
            let mut some = vec![0.0; rows.len()];
            field.self_values_at(&charges, &rows, &mut some).unwrap();
            for (&r, v) in rows.iter().zip(&some) {
                prop_assert_eq!(*v, all[r]);
            }
            for i in (0..n).step_by(11) {
                let m = magnitude(kernel, &centres, &w, &centres[i]);
                let error = (all[i] - direct.value(&centres[i])).abs() / m;
                prop_assert!(error <= bound, "{kind:?} {kernel:?} order {order}, row {i}: {error:e}");
            }
            // As many other points: the dual traversal with a tree of its own over them.
            let others: Vec<[f64; 3]> = centres.iter().map(|c| [c[0] + 1e-3, c[1] - 2e-3, c[2] + 1e-3]).collect();
            let mut at_others = vec![0.0; n];
            field.values(&charges, &others, &mut at_others).unwrap();
            for i in (0..n).step_by(11) {
                let m = magnitude(kernel, &centres, &w, &others[i]);
                let error = (at_others[i] - direct.value(&others[i])).abs() / m;
                prop_assert!(error <= bound, "{kind:?} {kernel:?} order {order}, point {i}: {error:e}");
            }
        }
    }
}

#[test]
fn no_rows_measure_nothing_and_claim_no_error() {
    let centres = cloud(Cloud::Random, 3000, 4);
    let w = weights(3000, 4);
    let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings::default());
    let charges = field.charges(&w).unwrap();
    field.self_values_at(&charges, &[], &mut []).unwrap();
    assert_eq!(field.product_error(&w, &[], &[]), None);
    assert!(field.sample_rows(0).is_empty());
    // Calibrated at no rows, no far field is trusted.
    assert!(rbf_far::calibrated_product(Kernel::Cubic, &centres, &w, 1.0, 0, 0).is_none());
    // A row out of range is refused, not read.
    assert!(field.self_values_at(&charges, &[3000], &mut [0.0]).is_err());
}

#[test]
fn far_field_is_exact_for_clusters_it_never_approximates() {
    // Fewer centres than any cluster's proxies: every sum is direct, to rounding.
    let centres = cloud(Cloud::Random, 40, 3);
    let w = weights(40, 3);
    let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings::default());
    let mut out = vec![0.0; 40];
    field
        .self_values(&field.charges(&w).unwrap(), &mut out)
        .unwrap();
    let direct = InterpolantView::new(Kernel::Cubic, &centres, &w, 0.0, [0.0; 3]).unwrap();
    for (c, o) in centres.iter().zip(&out) {
        assert!((direct.value(c) - o).abs() <= 1e-12 * magnitude(Kernel::Cubic, &centres, &w, c));
    }
}

/// The product at the centres (targets grouped by the field's own leaves, as the solver takes
/// it) is as accurate as evaluation at any points: within 1e-9 of Σ|wⱼ|φ at order 12.
#[test]
fn self_values_match_direct_sums_at_the_centres() {
    let centres = cloud(Cloud::Anisotropic, 5000, 9);
    let w = weights(5000, 9);
    let settings = FarFieldSettings {
        order: 12,
        ..FarFieldSettings::default()
    };
    let field = FarField::new(Kernel::Cubic, &centres, &settings);
    let mut far = vec![0.0; 5000];
    field
        .self_values(&field.charges(&w).unwrap(), &mut far)
        .unwrap();
    let direct = InterpolantView::new(Kernel::Cubic, &centres, &w, 0.0, [0.0; 3]).unwrap();
    let mut exact = vec![0.0; 5000];
    direct.values(&centres, &mut exact).unwrap();
    for (i, c) in centres.iter().enumerate().step_by(13) {
        let m = magnitude(Kernel::Cubic, &centres, &w, c);
        assert!(
            (far[i] - exact[i]).abs() <= 1e-9 * m,
            "{} {}",
            far[i],
            exact[i]
        );
    }
}

#[test]
fn evaluator_meets_the_accuracy_at_every_point() {
    let centres = cloud(Cloud::Clustered, 25_000, 5);
    let w: Vec<f64> = weights(25_000, 5).iter().map(|x| x * 1e-3).collect();
    let f = InterpolantView::new(Kernel::Cubic, &centres, &w, 0.5, [1.0, -2.0, 0.25]).unwrap();
    // Few points go through the treecode, more than centres through the dual traversal (and
    // the treecode for gradients).
    for n in [4000, 30_000] {
        evaluator_meets_the_accuracy_at(f, &cloud(Cloud::Random, n, 6));
    }
}

fn evaluator_meets_the_accuracy_at(f: InterpolantView<'_, f64, 3>, points: &[[f64; 3]]) {
    let accuracy = 1e-8;
    let evaluator = Evaluator::new(f, points, accuracy);
    assert!(
        matches!(evaluator.method(), Method::FarField { .. }),
        "{:?}",
        evaluator.method()
    );
    let (mut v, mut g) = (vec![0.0; points.len()], vec![[0.0; 3]; points.len()]);
    evaluator
        .values_and_gradients(points, &mut v, &mut g)
        .unwrap();
    let mut alone = vec![0.0; points.len()];
    evaluator.values(points, &mut alone).unwrap();
    let mut exact = vec![0.0; points.len()];
    f.par_values_compensated(points, &mut exact).unwrap();
    for (kind, got) in [("with gradients", &v), ("alone", &alone)] {
        let worst = got
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            worst <= accuracy,
            "{} points, values {kind}: worst error {worst:e} above the accuracy {accuracy:e}",
            points.len()
        );
    }
    // The coarse field, of lower order, within a thousand times the accuracy at every point.
    let Method::FarField { order, .. } = evaluator.method() else {
        unreachable!()
    };
    assert!(evaluator.coarse().is_none(), "kept only when asked for");
    let evaluator = Evaluator::with_coarse(f, points, accuracy);
    let (coarse, stated) = evaluator
        .coarse()
        .expect("a coarse field below the fine one");
    assert!(stated <= 2e3 * accuracy);
    let mut rough = vec![0.0; points.len()];
    coarse.field_values(points, &mut rough).unwrap();
    let worst = rough
        .iter()
        .zip(&exact)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst <= stated && worst > accuracy,
        "coarse field (the fine one is of order {order}): worst error {worst:e}, stated {stated:e}"
    );
    // The affine part is added to values and gradients.
    let (dv, dg) = f.value_and_gradient(&points[17]);
    assert!((v[17] - dv).abs() <= accuracy);
    assert!((0..3).all(|d| (g[17][d] - dg[d]).abs() <= 1e-6 * (1.0 + dg[d].abs())));
}

#[test]
fn evaluator_sums_small_models_directly() {
    let centres = cloud(Cloud::Random, 100, 1);
    let w = weights(100, 1);
    let f = InterpolantView::new(Kernel::Cubic, &centres, &w, 0.0, [0.0; 3]).unwrap();
    let points = cloud(Cloud::Random, 5000, 2);
    let evaluator = Evaluator::new(f, &points, 1e-6);
    assert_eq!(evaluator.method(), Method::Direct);
    let mut out = vec![0.0; 3];
    assert!(
        evaluator.values(&points, &mut out).is_err(),
        "a short output is refused"
    );
}

#[test]
fn wrong_lengths_and_foreign_charges_are_refused() {
    let centres = cloud(Cloud::Random, 3000, 4);
    let w = weights(3000, 4);
    let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings::default());
    assert_eq!(field.charges(&w[..10]).unwrap_err().what, "weights");
    let other = FarField::new(Kernel::Cubic, &centres[..500], &FarFieldSettings::default());
    let foreign = other.charges(&w[..500]).unwrap();
    let mut out = vec![0.0; 3000];
    assert_eq!(
        field.self_values(&foreign, &mut out).unwrap_err().what,
        "charges"
    );
    let charges = field.charges(&w).unwrap();
    assert_eq!(
        field.self_values(&charges, &mut out[..5]).unwrap_err().what,
        "output"
    );
    let (mut v, mut g) = (vec![0.0; 2], vec![[0.0; 3]; 3]);
    let two = [[0.0; 3]; 2];
    assert_eq!(
        field
            .values_and_gradients(&charges, &two, &mut v, &mut g)
            .unwrap_err()
            .what,
        "gradients"
    );
}

/// Found by the far_field fuzz target: a field of no centres evaluated somewhere panicked
/// (the root of an empty tree); it sums to zero, like the direct view. Odd settings (order 0,
/// θ = 0, leaves of 0) are taken too.
#[test]
fn an_empty_field_and_odd_settings_evaluate_without_panicking() {
    let targets = [[0.5, -1.0, 2.0], [0.0; 3]];
    let (mut v, mut g) = (vec![1.0; 2], vec![[1.0; 3]; 2]);
    let empty = FarField::new(Kernel::Cubic, &[], &FarFieldSettings::default());
    let charges = empty.charges(&[]).unwrap();
    empty.values(&charges, &targets, &mut v).unwrap();
    assert_eq!(v, [0.0, 0.0]);
    empty
        .values_and_gradients(&charges, &targets, &mut v, &mut g)
        .unwrap();
    assert_eq!(g, [[0.0; 3]; 2]);
    let centres = cloud(Cloud::Random, 300, 7);
    let w = weights(300, 7);
    let odd = FarFieldSettings {
        order: 0,
        theta: 0.0,
        leaf: 0,
        target_leaf: 0,
    };
    let field = FarField::new(Kernel::Cubic, &centres, &odd);
    let charges = field.charges(&w).unwrap();
    field.values(&charges, &targets, &mut v).unwrap();
    let mut exact = vec![0.0; 2];
    InterpolantView::new(Kernel::Cubic, &centres, &w, 0.0, [0.0; 3])
        .unwrap()
        .values(&targets, &mut exact)
        .unwrap();
    for (a, b) in v.iter().zip(&exact) {
        assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} against {b}");
    }
}
