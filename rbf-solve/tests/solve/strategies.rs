//! Every factorization gives the same interpolant, and large fits interpolate exactly.

use proptest::prelude::*;
use rbf_core::{Constraint, FitSettings, Kernel, SolveMethod, System};
use rbf_solve::{SolveOptions, Strategy};

use rbf_core::shapes::sphere;

fn solve(cs: &[Constraint<3>], s: &FitSettings, strategy: Strategy) -> rbf_core::Fit<3> {
    let system = System::new(cs, s).unwrap();
    rbf_solve::solve(
        &system,
        s,
        &SolveOptions {
            strategy,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn cholesky_lblt_lu_and_the_core_solver_agree() {
    for kernel in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
        for lambda in [0.0, 1e-3] {
            let cs = sphere(150);
            let s = FitSettings {
                kernel: Some(kernel),
                lambda,
                ..Default::default()
            };
            let reference = rbf_core::fit(&cs, &s).unwrap().interpolant;
            for strategy in [Strategy::Auto, Strategy::Lblt, Strategy::Lu] {
                let fit = solve(&cs, &s, strategy);
                for i in 0..50 {
                    let x = [
                        (i as f64 * 0.37).sin() * 1.3,
                        (i as f64 * 0.71).cos(),
                        0.02 * i as f64 - 0.5,
                    ];
                    let (a, b) = (reference.value(&x), fit.interpolant.value(&x));
                    assert!(
                        (a - b).abs() <= 1e-8 * (1.0 + a.abs()),
                        "{kernel:?} λ={lambda} {strategy:?}: {a} vs {b}"
                    );
                }
            }
        }
    }
}

#[test]
fn auto_uses_cholesky_for_definite_kernels_and_falls_back_otherwise() {
    let cs = sphere(100);
    let cubic = solve(&cs, &FitSettings::default(), Strategy::Auto);
    assert_eq!(cubic.report.method, SolveMethod::ProjectedCholesky);
    // φ = r is conditionally negative definite: still Cholesky, of the negated block.
    let s = FitSettings {
        kernel: Some(Kernel::Linear),
        ..Default::default()
    };
    assert_eq!(
        solve(&cs, &s, Strategy::Auto).report.method,
        SolveMethod::ProjectedCholesky
    );
    // Smoothing has the kernel's sign (−λ for r, as scipy's `smoothing` with its −r), so even a
    // large λ keeps the negated block definite, and the surface tends to the best affine fit.
    let s = FitSettings {
        kernel: Some(Kernel::Linear),
        lambda: 10.0,
        ..Default::default()
    };
    let fit = solve(&cs, &s, Strategy::Auto);
    assert_eq!(fit.report.method, SolveMethod::ProjectedCholesky);
    assert!(fit.report.residual < 1e-9);
    let heavier = FitSettings { lambda: 1e4, ..s };
    let smooth = solve(&cs, &heavier, Strategy::Auto).interpolant;
    let exact = solve(&cs, &FitSettings { lambda: 0.0, ..s }, Strategy::Auto).interpolant;
    // Exact: 0 on the sphere; heavily smoothed: nearly the constant mean of the values (½).
    let on = cs[0].position;
    assert!(exact.value(&on).abs() < 1e-9);
    assert!(
        (smooth.value(&on) - 0.5).abs() < 0.05,
        "{}",
        smooth.value(&on)
    );
}

#[test]
fn the_report_is_honest() {
    let cs = sphere(400);
    let fit = solve(&cs, &FitSettings::default(), Strategy::Auto);
    let f = &fit.interpolant;
    // The residual reported is the one measured here, on the returned interpolant.
    let system = System::new(&cs, &FitSettings::default()).unwrap();
    let measured = system.relative_residual(f);
    assert!((fit.report.residual - measured).abs() <= 1e-3 * measured.max(1e-16));
    assert!(fit.report.condition > 1.0 && fit.report.condition.is_finite());
    assert_eq!(fit.report.rows, 800);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn large_random_sets_interpolate_exactly(
        n in 200..700_usize,
        seed in 0..1000_u64,
        k in prop_oneof![Just(Kernel::Cubic), Just(Kernel::Linear), Just(Kernel::ThinPlate)],
    ) {
        // Points on a jittered grid with random values.
        let side = (n as f64).cbrt().ceil() as usize + 1;
        let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let cs: Vec<Constraint<3>> = (0..n)
            .map(|i| {
                let cell = [i % side, (i / side) % side, i / (side * side)];
                let p = cell.map(|c| (c as f64 + 0.5 + 0.6 * (next() - 0.5)) / side as f64);
                let v = next() * 2.0 - 1.0;
                if i == 0 || v > 0.3 { Constraint::interior(p, v.abs() + 0.1) }
                else if v < -0.3 { Constraint::exterior(p, v) }
                else { Constraint::boundary(p) }
            })
            .collect();
        let s = FitSettings { kernel: Some(k), ..Default::default() };
        let f = rbf_solve::fit(&cs, &s).unwrap().interpolant;
        let hmax = cs.iter().fold(0.0_f64, |m, c| m.max(c.value.abs()));
        let mut values = vec![0.0; n];
        let points: Vec<[f64; 3]> = cs.iter().map(|c| c.position).collect();
        f.view().par_values(&points, &mut values).unwrap();
        for (c, v) in cs.iter().zip(&values) {
            prop_assert!((v - c.value).abs() <= 1e-9 * hmax, "{v} vs {} ({k:?}, n = {n})", c.value);
            prop_assert!((f.value(&c.position) - v).abs() <= 1e-12 * hmax.max(v.abs()));
        }
    }
}
