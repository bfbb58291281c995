//! Property tests of the interpolant (with rbf-core's dense solver).

use proptest::prelude::*;
use rbf_core::{Constraint, FitSettings, Kernel, System, fit, insert_knot};

use crate::support::{jittered, kernel, max_value, rotate, rotation, value_constraints};

fn settings(kernel: Kernel) -> FitSettings {
    FitSettings {
        kernel: Some(kernel),
        ..Default::default()
    }
}

/// max over constraints of |f(cᵢ) − hᵢ| / max |h|.
fn interpolation_error<const D: usize>(cs: &[Constraint<D>], k: Kernel) -> f64 {
    let f = fit(cs, &settings(k))
        .expect("well-spaced constraints fit")
        .interpolant;
    cs.iter()
        .map(|c| (f.value(&c.position) - c.value).abs())
        .fold(0.0, f64::max)
        / max_value(cs)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn interpolates_exactly_in_3d(cs in value_constraints::<3>(5, 300), k in kernel()) {
        let e = interpolation_error(&cs, k);
        prop_assert!(e <= 1e-9, "relative error {e:e} with {} constraints, {k:?}", cs.len());
    }

    #[test]
    fn interpolates_exactly_in_2d(cs in value_constraints::<2>(4, 300), k in kernel()) {
        let e = interpolation_error(&cs, k);
        prop_assert!(e <= 1e-9, "relative error {e:e} with {} constraints, {k:?}", cs.len());
    }

    #[test]
    fn assembled_matrix_is_symmetric(cs in value_constraints::<3>(5, 60), k in kernel(), lambda in 0.0..0.1_f64) {
        let s = FitSettings { lambda, ..settings(k) };
        let sys = System::new(&cs, &s).unwrap();
        let n = sys.rows();
        let mut cols = vec![vec![0.0; n]; n];
        for (j, col) in cols.iter_mut().enumerate() {
            sys.kernel_column(j, 0..n, col);
        }
        for i in 0..n {
            for j in 0..n {
                prop_assert_eq!(cols[i][j], cols[j][i]);
            }
        }
    }

    #[test]
    fn knot_insertion_leaves_f_unchanged(
        cs in value_constraints::<3>(8, 80),
        start in proptest::array::uniform3(-1.0..1.0_f64),
        probes in jittered::<3>(20),
    ) {
        let s = FitSettings::default();
        let before = fit(&cs, &s).unwrap().interpolant;
        let mut more = cs.clone();
        let Ok(p) = insert_knot(&mut more, &before.view(), start) else {
            // No surface reachable from this start; nothing to insert.
            return Ok(());
        };
        // A knot on top of an existing constraint would be a coincident point, not a new one.
        prop_assume!(cs.iter().all(|c| {
            let d: f64 = (0..3).map(|i| (c.position[i] - p[i]).powi(2)).sum();
            d.sqrt() > 1e-3
        }));
        let after = fit(&more, &s).unwrap().interpolant;
        let scale = probes.iter().map(|x| before.value(x).abs()).fold(0.0, f64::max).max(max_value(&cs));
        for x in &probes {
            let (a, b) = (before.value(x), after.value(x));
            prop_assert!((a - b).abs() <= 1e-8 * scale, "f changed from {a} to {b} at {x:?}");
        }
    }

    /// Batches run eight points at a time, a short last block padded: whatever the batch and
    /// the point's place in it, its value and gradient come out bit for bit the same, and equal
    /// to the one-point calls (so nothing downstream depends on how points were grouped).
    #[test]
    fn a_point_evaluates_the_same_in_any_batch(
        cs in value_constraints::<3>(5, 40),
        k in kernel(),
        points in proptest::collection::vec(proptest::array::uniform3(-1.5..1.5_f64), 1..30),
        split in 0..30_usize,
    ) {
        let f = fit(&cs, &settings(k)).unwrap().interpolant;
        let view = f.view();
        let n = points.len();
        let (mut values, mut also, mut grads) = (vec![0.0; n], vec![0.0; n], vec![[0.0; 3]; n]);
        view.values(&points, &mut values).unwrap();
        view.values_and_gradients(&points, &mut also, &mut grads).unwrap();
        let split = split % n;
        for part in [&points[..split], &points[split..]] {
            let offset = if part.is_empty() || part.as_ptr() == points.as_ptr() { 0 } else { split };
            let (mut v, mut g) = (vec![0.0; part.len()], vec![[0.0; 3]; part.len()]);
            view.values_and_gradients(part, &mut v, &mut g).unwrap();
            for (i, p) in part.iter().enumerate() {
                let (one, one_gradient) = view.value_and_gradient(p);
                prop_assert_eq!(one.to_bits(), values[offset + i].to_bits());
                prop_assert_eq!(one.to_bits(), also[offset + i].to_bits());
                prop_assert_eq!(one.to_bits(), v[i].to_bits());
                for d in 0..3 {
                    prop_assert_eq!(one_gradient[d].to_bits(), grads[offset + i][d].to_bits());
                    prop_assert_eq!(one_gradient[d].to_bits(), g[i][d].to_bits());
                }
            }
        }
    }

    #[test]
    fn gradient_and_hessian_match_central_differences(
        cs in value_constraints::<3>(5, 40),
        k in kernel(),
        x in proptest::array::uniform3(-1.2..1.2_f64),
    ) {
        let f = fit(&cs, &settings(k)).unwrap().interpolant;
        // Difference formulas need f smooth around x: keep away from the centres, where the
        // r and r² log r kernels are not twice differentiable.
        prop_assume!(f.centres().iter().all(|c| {
            (0..3).map(|d| (c[d] - x[d]).powi(2)).sum::<f64>().sqrt() > 0.05
        }));
        let (v, g, h) = f.value_gradient_hessian(&x);
        let (v2, g2) = f.value_and_gradient(&x);
        prop_assert_eq!(v, v2);
        let e = 1e-5;
        let size = 1.0 + v.abs() + g.iter().map(|c| c.abs()).sum::<f64>();
        for d in 0..3 {
            let mut xp = x;
            let mut xm = x;
            xp[d] += e;
            xm[d] -= e;
            let fd = (f.value(&xp) - f.value(&xm)) / (2.0 * e);
            prop_assert!((fd - g[d]).abs() <= 1e-5 * size, "∂f/∂x{d}: {fd} vs {}", g[d]);
            prop_assert!((g2[d] - g[d]).abs() <= 1e-12 * size);
            let (gp, gm) = (f.gradient(&xp), f.gradient(&xm));
            let hsize = size + h.iter().flatten().map(|c| c.abs()).sum::<f64>();
            for c in 0..3 {
                let fd = (gp[c] - gm[c]) / (2.0 * e);
                prop_assert!((fd - h[c][d]).abs() <= 1e-4 * hsize, "H[{c}][{d}]: {fd} vs {}", h[c][d]);
                prop_assert_eq!(h[c][d], h[d][c]);
            }
        }
    }

    #[test]
    fn invariant_under_rotation_and_translation(
        cs in value_constraints::<3>(5, 80),
        k in kernel(),
        angles in proptest::array::uniform3(0.0..6.3_f64),
        shift in proptest::array::uniform3(-50.0..50.0_f64),
        probes in jittered::<3>(20),
    ) {
        let r = rotation(angles[0], angles[1], angles[2]);
        let moved: Vec<Constraint<3>> = cs
            .iter()
            .map(|c| Constraint { position: add(rotate(&r, c.position), shift), ..*c })
            .collect();
        let f = fit(&cs, &settings(k)).unwrap().interpolant;
        let g = fit(&moved, &settings(k)).unwrap().interpolant;
        let scale = probes.iter().map(|x| f.value(x).abs()).fold(max_value(&cs), f64::max);
        for x in &probes {
            let (a, b) = (f.value(x), g.value(&add(rotate(&r, *x), shift)));
            prop_assert!((a - b).abs() <= 1e-8 * scale, "{a} vs {b}");
        }
    }

    #[test]
    fn scaling_the_constraints_scales_the_function(
        cs in value_constraints::<3>(5, 80),
        k in kernel(),
        log_s in -6.0..6.0_f64,
        probes in jittered::<3>(20),
    ) {
        let s = 10f64.powf(log_s);
        let scaled: Vec<Constraint<3>> =
            cs.iter().map(|c| Constraint { position: c.position.map(|v| v * s), ..*c }).collect();
        let f = fit(&cs, &settings(k)).unwrap().interpolant;
        let g = fit(&scaled, &settings(k)).unwrap().interpolant;
        let scale = probes.iter().map(|x| f.value(x).abs()).fold(max_value(&cs), f64::max);
        for x in &probes {
            // With λ = 0 the interpolant of the scaled data is f(x / s).
            let (a, b) = (f.value(x), g.value(&x.map(|v| v * s)));
            prop_assert!((a - b).abs() <= 1e-8 * scale, "{a} vs {b} at scale {s:e}");
        }
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
