//! The iterative solver gives the dense solver's interpolant, for every kernel, with λ (global
//! and per constraint) and normal constraints; it reports what it did and refuses to stop short.

use rbf_core::{Constraint, FitError, FitSettings, Kernel, SolveMethod, System};
use rbf_solve::{
    IterativeOptions, IterativeProgress, SchwarzSettings, SolveOptions, solve_iterative,
};

/// A deterministic generator, so that the clouds are the same on every run.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [
                2.0 * self.uniform() - 1.0,
                2.0 * self.uniform() - 1.0,
                2.0 * self.uniform() - 1.0,
            ];
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if l > 0.1 && l <= 1.0 {
                return [v[0] / l, v[1] / l, v[2] / l];
            }
        }
    }
}

/// Random oriented points on a bumpy sphere (normal constraints: two rows each).
fn bumpy(n: usize, seed: u64) -> Vec<Constraint<3>> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let u = rng.direction();
            let r = 1.0 + 0.1 * (5.0 * u[2]).sin() * (3.0 * u[0]).cos();
            Constraint::normal([r * u[0], r * u[1], r * u[2]], u)
        })
        .collect()
}

/// Random value constraints in the unit cube: a smooth function, scattered data.
fn scattered(n: usize, seed: u64) -> Vec<Constraint<3>> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let p = [rng.uniform(), rng.uniform(), rng.uniform()];
            let v = (3.0 * p[0]).sin() + p[1] * p[2] - 0.4;
            match v {
                v if v > 0.0 => Constraint::interior(p, v),
                v if v < 0.0 => Constraint::exterior(p, v),
                _ => Constraint::boundary(p),
            }
        })
        .collect()
}

fn tight() -> IterativeOptions {
    IterativeOptions {
        tolerance: Some(1e-11),
        schwarz: SchwarzSettings {
            inner: 64,
            extended: 160,
            coarse: 300,
            ..SchwarzSettings::default()
        },
        ..Default::default()
    }
}

/// max |f_iterative − f_dense| over random points of the box, relative to max |f_dense| there.
fn disagreement(cs: &[Constraint<3>], settings: &FitSettings, options: &IterativeOptions) -> f64 {
    let system = System::new(cs, settings).unwrap();
    let dense = rbf_solve::solve(&system, settings, &SolveOptions::default()).unwrap();
    let fast = solve_iterative(&system, settings, options, |_| {}).unwrap();
    assert_eq!(fast.report.method, SolveMethod::Iterative);
    assert!(fast.report.iterations > 0);
    let mut rng = Rng(7);
    let (mut worst, mut scale) = (0.0_f64, 0.0_f64);
    for _ in 0..400 {
        let x = [
            2.4 * rng.uniform() - 1.2,
            2.4 * rng.uniform() - 1.2,
            2.4 * rng.uniform() - 1.2,
        ];
        let a = dense.interpolant.value(&x);
        worst = worst.max((fast.interpolant.value(&x) - a).abs());
        scale = scale.max(a.abs());
    }
    worst / scale
}

#[test]
fn agrees_with_the_dense_solver_for_every_kernel_with_and_without_lambda() {
    for kernel in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
        for lambda in [0.0, 1e-4] {
            let settings = FitSettings {
                kernel: Some(kernel),
                lambda,
                ..Default::default()
            };
            let d = disagreement(&bumpy(900, 1), &settings, &tight());
            assert!(d < 1e-8, "{kernel:?} λ = {lambda}: {d:e}");
        }
    }
}

#[test]
fn agrees_with_the_dense_solver_on_scattered_values_and_per_constraint_smoothing() {
    let mut cs = scattered(1500, 3);
    for (i, c) in cs.iter_mut().enumerate() {
        c.smoothing = if i % 3 == 0 { 1e-3 } else { 0.0 };
    }
    let d = disagreement(&cs, &FitSettings::default(), &tight());
    assert!(d < 1e-8, "{d:e}");
}

#[test]
fn agrees_with_the_dense_solver_on_ten_thousand_rows() {
    let options = IterativeOptions {
        tolerance: Some(1e-10),
        ..Default::default()
    };
    let d = disagreement(&bumpy(5000, 11), &FitSettings::default(), &options);
    assert!(d < 1e-8, "{d:e}");
}

#[test]
fn reports_progress_and_meets_every_row_by_direct_sums() {
    let cs = bumpy(3000, 5);
    let settings = FitSettings::default();
    let system = System::new(&cs, &settings).unwrap();
    let mut seen = Vec::new();
    let fit = solve_iterative(&system, &settings, &IterativeOptions::default(), |p| {
        seen.push(p)
    })
    .unwrap();
    // The limit left at its default: the iterative solver's own, said first.
    assert_eq!(
        seen[..2],
        [
            IterativeProgress::DefaultLimit { limit: 1e-5 },
            IterativeProgress::Preconditioning
        ]
    );
    let iterations = seen
        .iter()
        .filter(|p| matches!(p, IterativeProgress::Iteration { .. }))
        .count();
    assert_eq!(iterations, fit.report.iterations);
    let Some(IterativeProgress::Checked { residual, .. }) = seen.last() else {
        panic!("no final check: {seen:?}");
    };
    assert!(*residual <= 1e-5, "{residual:e}");
    // Every row, by a direct sum in the caller's coordinates.
    let f = &fit.interpolant;
    let hmax = system.values().iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    for (p, h) in system.points().iter().zip(system.values()) {
        assert!((f.value(p) - h).abs() <= 1e-5 * hmax);
    }
}

/// Iterations an iterative solve of `cs` to 1e-9 takes with these preconditioner settings (every
/// row then checked by direct sums), or `None` if it does not get there in 60.
fn iterations_with(cs: &[Constraint<3>], schwarz: SchwarzSettings) -> Option<usize> {
    let settings = FitSettings::default();
    let system = System::new(cs, &settings).unwrap();
    let options = IterativeOptions {
        tolerance: Some(1e-9),
        max_iterations: 60,
        allow_unconverged: true,
        schwarz,
        ..Default::default()
    };
    let fit = solve_iterative(&system, &settings, &options, |_| {}).unwrap();
    let hmax = system.values().iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let met = system
        .points()
        .iter()
        .zip(system.values())
        .all(|(p, h)| (fit.interpolant.value(p) - h).abs() <= 1e-9 * hmax);
    met.then_some(fit.report.iterations)
}

#[test]
fn a_nested_coarse_level_keeps_the_iterations_of_one_factored_whole() {
    // 12 000 rows. Two levels with one row in 24 factored whole (500 rows), as the default
    // settings have up to 10⁵ rows; two levels with only 20 coarse rows, as 4096 would be for
    // 10⁶; and three levels: the 500 rows are themselves split into subdomains over 20 coarse
    // rows, and only those 20 are factored whole; and the same with the subdomains widened
    // from 160 rows to 240.
    let cs = bumpy(6000, 13);
    let whole = SchwarzSettings {
        inner: 64,
        extended: 160,
        coarse: 500,
        levels: 2,
    };
    let starved = SchwarzSettings {
        coarse: 20,
        ..whole
    };
    let nested = SchwarzSettings {
        levels: 3,
        ..starved
    };
    let whole = iterations_with(&cs, whole).expect("a coarse level factored whole converges");
    let wide = SchwarzSettings {
        extended: 240,
        ..nested
    };
    let wide =
        iterations_with(&cs, wide).expect("wider subdomains above the nested level converge");
    let nested = iterations_with(&cs, nested).expect("the nested coarse level converges");
    assert!(
        nested <= whole + 4,
        "{nested} iterations nested, {whole} whole"
    );
    // Above a coarse level solved only approximately, subdomains half as wide again leave it
    // less (measured: 12 iterations against 25).
    assert!(
        3 * wide <= 2 * nested,
        "{wide} iterations with wider subdomains, {nested} without"
    );
    // Starved, the solve stalls (measured: still above the right-hand side after 60).
    let starved = iterations_with(&cs, starved);
    assert!(
        starved.is_none_or(|s| s >= 2 * nested),
        "{starved:?} iterations starved, {nested} nested"
    );
}

#[test]
fn a_problem_that_does_not_converge_in_the_cap_is_an_error() {
    let cs = bumpy(2000, 9);
    let settings = FitSettings {
        max_residual: 1e-13,
        ..Default::default()
    };
    let system = System::new(&cs, &settings).unwrap();
    let options = IterativeOptions {
        max_iterations: 2,
        ..Default::default()
    };
    match solve_iterative(&system, &settings, &options, |_| {}) {
        Err(FitError::NotConverged {
            iterations,
            residual,
            tolerance,
        }) => {
            assert_eq!(iterations, 2);
            assert_eq!(tolerance, 1e-13);
            assert!(residual > tolerance);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

#[test]
fn a_flat_patch_or_a_tiny_system_still_solves() {
    // Value constraints on a plane and one point off it: the subdomains on the plane are flat.
    let mut cs: Vec<Constraint<3>> = (0..400)
        .map(|i| Constraint::boundary([(i % 20) as f64 * 0.05, (i / 20) as f64 * 0.05, 0.0]))
        .collect();
    cs.push(Constraint::interior([0.5, 0.5, -0.3], 1.0));
    let d = disagreement(&cs, &FitSettings::default(), &tight());
    assert!(d < 1e-8, "{d:e}");
    let d = disagreement(
        &rbf_core::shapes::tetrahedron_blob(),
        &FitSettings::default(),
        &tight(),
    );
    assert!(d < 1e-8, "{d:e}");
}

#[test]
fn a_duplicate_among_a_hundred_thousand_points_is_named_by_index() {
    let mut cs = scattered(100_000, 21);
    cs[77_777].position = cs[31_337].position;
    cs[77_777].value = cs[31_337].value;
    cs[77_777].kind = cs[31_337].kind;
    match rbf_solve::fit(&cs, &FitSettings::default()) {
        Err(FitError::Coincident { first, second, .. }) => {
            assert_eq!((first.constraint, second.constraint), (31_337, 77_777));
        }
        other => panic!("expected Coincident, got {other:?}"),
    }
}

/// 2·10⁴ rows with the products through the far field: the fit meets its tolerance by direct
/// sums at every row (measured here, outside the solver), as the solver's certification at
/// sampled rows claimed.
#[test]
fn far_field_products_reach_the_tolerance_at_every_row() {
    let cs = bumpy(10_000, 77);
    let settings = FitSettings {
        max_residual: 1e-4,
        ..FitSettings::default()
    };
    let system = System::new(&cs, &settings).unwrap();
    let options = IterativeOptions {
        far_field_rows: 10_000,
        ..IterativeOptions::default()
    };
    let mut orders = Vec::new();
    let fit = solve_iterative(&system, &settings, &options, |p| {
        if let IterativeProgress::FarField { order } = p {
            orders.push(order);
        }
    })
    .unwrap();
    assert_eq!(orders.len(), 1, "the far field was chosen once");
    assert!(fit.report.residual <= 1e-4, "{:?}", fit.report);
    let measured = system.relative_residual(&fit.interpolant);
    assert!(measured <= 1e-4, "residual {measured:e} at some row");
    assert!(
        measured <= 1.01 * fit.report.residual,
        "the report ({:e}) does not understate the residual ({measured:e})",
        fit.report.residual
    );
}

/// Through the far field too, a limit left at its default is raised to the iterative solver's
/// (1e-5) and said; the fit meets it at every row (measured here by direct sums). A limit the
/// caller set is kept and nothing is raised.
#[test]
fn the_default_limit_through_the_far_field_is_the_iterative_solvers() {
    let cs = bumpy(10_000, 77);
    let settings = FitSettings::default();
    let system = System::new(&cs, &settings).unwrap();
    let options = IterativeOptions {
        far_field_rows: 10_000,
        ..IterativeOptions::default()
    };
    let mut limits = Vec::new();
    let fit = solve_iterative(&system, &settings, &options, |p| {
        if let IterativeProgress::DefaultLimit { limit } = p {
            limits.push(limit);
        }
    })
    .unwrap();
    assert_eq!(limits, [1e-5]);
    let measured = system.relative_residual(&fit.interpolant);
    assert!(measured <= 1e-5, "residual {measured:e} at some row");
    // A limit the caller set (here looser, as a fit that needs only 1e-4 would) is kept.
    let asked = FitSettings {
        max_residual: 1e-4,
        ..settings
    };
    let mut raised = false;
    let fit = solve_iterative(&system, &asked, &options, |p| {
        raised |= matches!(p, IterativeProgress::DefaultLimit { .. });
    })
    .unwrap();
    assert!(!raised, "a limit the caller set is kept");
    assert!(system.relative_residual(&fit.interpolant) <= 1e-4);
}

/// With exact products, the last check takes the recurrence's residual certified by direct
/// sums at sampled rows instead of a product at every row: the residual it reports still holds
/// at every row (measured here) and overstates it by little.
#[test]
fn a_residual_taken_from_the_recurrence_holds_at_every_row() {
    for (cs, max_residual) in [(bumpy(4000, 3), 1e-6), (scattered(6000, 4), 1e-9)] {
        let settings = FitSettings {
            max_residual,
            ..FitSettings::default()
        };
        let system = System::new(&cs, &settings).unwrap();
        let mut last = None;
        let options = IterativeOptions::default().with_limit_given(true);
        let fit = solve_iterative(&system, &settings, &options, |p| {
            if let IterativeProgress::Checked {
                from_recurrence, ..
            } = p
            {
                last = Some(from_recurrence);
            }
        })
        .unwrap();
        assert_eq!(last, Some(true), "the last check took no product");
        let measured = system.relative_residual(&fit.interpolant);
        assert!(
            measured <= max_residual,
            "residual {measured:e} at some row"
        );
        assert!(
            measured <= fit.report.residual && fit.report.residual <= 1.1 * measured,
            "reported {:e}, measured {measured:e}",
            fit.report.residual
        );
    }
    // Near the rounding floor the recurrence runs far ahead of the truth (it claims 6e-15 where
    // every product of the iterate gives 7e-12): its claim is refused, and what is returned,
    // if anything, is what a product measures.
    let cs = bumpy(4000, 3);
    let settings = FitSettings {
        max_residual: 1e-12,
        ..FitSettings::default()
    };
    let system = System::new(&cs, &settings).unwrap();
    let options = IterativeOptions::default().with_limit_given(true);
    let mut taken = false;
    let solved = solve_iterative(&system, &settings, &options, |p| {
        if let IterativeProgress::Checked {
            from_recurrence, ..
        } = p
        {
            taken |= from_recurrence;
        }
    });
    assert!(!taken, "the recurrence's claim was refused");
    match solved {
        Ok(fit) => {
            let measured = system.relative_residual(&fit.interpolant);
            assert!(
                measured <= 4.0 * fit.report.residual,
                "reported {:e}, measured {measured:e}",
                fit.report.residual
            );
        }
        Err(FitError::NotConverged { .. }) => {}
        Err(other) => panic!("{other}"),
    }
}

/// Inexact Krylov: once the residual is small, products go through cheaper far fields, and the
/// fit still meets the default tolerance at every row (measured here by direct sums), in no
/// more iterations than with exact products.
#[test]
fn relaxed_products_keep_the_tolerance_at_every_row() {
    let cs = scattered(20_000, 8);
    let settings = FitSettings::default();
    let system = System::new(&cs, &settings).unwrap();
    let solve = |relaxed_rows: usize| {
        let options = IterativeOptions {
            relaxed_rows,
            ..IterativeOptions::default()
        };
        let mut relaxed = None;
        let fit = solve_iterative(&system, &settings, &options, |p| {
            if let IterativeProgress::Relaxed { products, of } = p {
                relaxed = Some((products, of));
            }
        })
        .unwrap();
        (fit, relaxed)
    };
    let (fit, relaxed) = solve(10_000);
    let (products, of) = relaxed.expect("some products were relaxed");
    assert!(products > 0 && products < of, "{products} of {of}");
    let measured = system.relative_residual(&fit.interpolant);
    assert!(
        measured <= settings.max_residual,
        "residual {measured:e} at some row"
    );
    let (exact, none) = solve(usize::MAX);
    assert!(none.is_none());
    assert!(
        fit.report.iterations <= exact.report.iterations + 1,
        "{} iterations relaxed, {} exact",
        fit.report.iterations,
        exact.report.iterations
    );
}

/// A limit below what double precision allows: the solve stalls at the rounding floor of its
/// products; by default it is accepted there (and says so), and the floor it claims holds at
/// every row; a caller who insists on the limit gets the error.
#[test]
fn a_stall_at_the_rounding_floor_is_accepted_and_said_unless_the_limit_is_insisted_on() {
    let cs = bumpy(3000, 5);
    let settings = FitSettings {
        max_residual: 1e-15,
        ..FitSettings::default()
    };
    let system = System::new(&cs, &settings).unwrap();
    let mut floors = Vec::new();
    let fit = solve_iterative(&system, &settings, &IterativeOptions::default(), |p| {
        if let IterativeProgress::RoundingFloor { residual, floor } = p {
            floors.push((residual, floor));
        }
    })
    .unwrap();
    assert_eq!(floors.len(), 1, "the stall was reported once");
    let (residual, floor) = floors[0];
    assert!(residual <= floor && floor < 1e-6, "{residual:e} {floor:e}");
    let measured = system.relative_residual(&fit.interpolant);
    assert!(
        measured <= floor,
        "measured {measured:e} above the floor {floor:e}"
    );
    assert!(
        measured > 1e-15,
        "the limit was indeed out of reach ({measured:e})"
    );
    let insist = IterativeOptions {
        accept_rounding_floor: false,
        ..IterativeOptions::default()
    };
    assert!(matches!(
        solve_iterative(&system, &settings, &insist, |_| {}),
        Err(FitError::NotConverged { .. })
    ));
}
