//! Greedy fitting: every constraint met within the tolerance, checked here independently of
//! the report; the full fit when nothing may be left out; bad input named as by `fit`.

use rbf_core::{Constraint, FitError, FitSettings, Interpolant};
use rbf_solve::{GreedySettings, fit, fit_greedy};

/// `n` oriented points on a bumpy sphere (normals of the unit sphere, which is all the fit
/// needs: it interpolates them).
fn bumpy(n: usize) -> Vec<Constraint<3>> {
    rbf_core::shapes::fibonacci_sphere(n)
        .into_iter()
        .map(|u| {
            let s = 1.0 + 0.15 * (3.0 * u[0]).sin() * (2.0 * u[1]).cos();
            Constraint::normal(u.map(|x| s * x), u)
        })
        .collect()
}

/// The largest |f − h| / |∇f| over every row of the constraints, as a fraction of the box.
fn worst_miss(f: &Interpolant<f64, 3>, cs: &[Constraint<3>]) -> f64 {
    let system = rbf_core::System::new(cs, &FitSettings::default()).unwrap();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in system.points() {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    system
        .points()
        .iter()
        .zip(system.values())
        .map(|(p, h)| {
            let (v, g) = f.value_and_gradient(p);
            (v - h).abs() / (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt() / longest
        })
        .fold(0.0, f64::max)
}

#[test]
fn every_constraint_is_met_within_the_tolerance_with_a_fraction_of_them() {
    let cs = bumpy(6000);
    for tolerance in [1e-3, 1e-4] {
        let settings = GreedySettings {
            tolerance,
            ..Default::default()
        };
        let (f, report) = fit_greedy(&cs, &FitSettings::default(), &settings, |_| {}).unwrap();
        assert!(report.converged, "{tolerance}: {report:?}");
        assert!(report.used.len() < cs.len() / 10, "{}", report.used.len());
        let miss = worst_miss(&f.interpolant, &cs);
        assert!(miss <= tolerance, "{tolerance}: missed by {miss}");
        // The report's own figure agrees with the independent one.
        let last = report.rounds.last().unwrap();
        assert!(
            (last.max_error - miss).abs() <= 1e-3 * tolerance,
            "{last:?} vs {miss}"
        );
        assert_eq!(last.constraints, report.used.len());
    }
    // Without the greedy loop, the first subset alone misses by far more.
    let (f, _) = fit_greedy(
        &cs,
        &FitSettings::default(),
        &GreedySettings {
            max_constraints: 100,
            ..Default::default()
        },
        |_| {},
    )
    .unwrap();
    assert!(worst_miss(&f.interpolant, &cs) > 1e-3);
}

#[test]
fn with_no_tolerance_and_room_for_all_it_is_the_full_fit() {
    let cs = bumpy(300);
    let settings = GreedySettings {
        tolerance: 0.0,
        initial: 20,
        max_constraints: usize::MAX,
        ..Default::default()
    };
    let (g, report) = fit_greedy(&cs, &FitSettings::default(), &settings, |_| {}).unwrap();
    // Every constraint, each once (in the order the rounds took them).
    let mut used = report.used.clone();
    used.sort_unstable();
    assert_eq!(used, (0..300).collect::<Vec<_>>());
    assert!(report.rounds.len() > 3, "{report:?}");
    let full = fit(&cs, &FitSettings::default()).unwrap();
    for p in [[0.0, 0.0, 0.0], [0.3, -0.2, 0.9], [1.5, 0.0, 0.0]] {
        let (a, b) = (g.interpolant.value(&p), full.interpolant.value(&p));
        assert!((a - b).abs() < 1e-8 * a.abs().max(1.0), "{a} vs {b}");
    }
}

#[test]
fn a_lone_interior_constraint_is_always_in_the_first_subset() {
    // Boundary constraints only, but for the centre: the spread subset would miss it, and a
    // fit of boundary constraints alone is f ≡ 0.
    let mut cs: Vec<Constraint<3>> = bumpy(500)
        .into_iter()
        .map(|c| Constraint::boundary(c.position))
        .collect();
    cs.push(Constraint::interior([0.0; 3], 1.0));
    let (f, report) = fit_greedy(
        &cs,
        &FitSettings::default(),
        &GreedySettings::default(),
        |_| {},
    )
    .unwrap();
    assert!(report.used.contains(&500));
    assert!(f.interpolant.value(&[0.0; 3]) > 0.5);
}

#[test]
fn bad_constraints_are_named_before_any_fit() {
    let mut cs = bumpy(200);
    cs[117].position[1] = f64::NAN;
    let e = fit_greedy(
        &cs,
        &FitSettings::default(),
        &GreedySettings::default(),
        |_| {},
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            FitError::NonFinite {
                constraint: 117,
                ..
            }
        ),
        "{e}"
    );
    let mut cs = bumpy(200);
    cs[150].position = cs[3].position;
    let e = fit_greedy(
        &cs,
        &FitSettings::default(),
        &GreedySettings::default(),
        |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, FitError::Coincident { .. }), "{e}");
}

#[test]
fn a_model_of_the_constraints_used_reads_back_as_the_same_function() {
    // The subset's own bounding box is smaller than the whole set's, so its default normal
    // offset would differ: the report's constraints carry the offsets they were fitted with.
    let cs = bumpy(2000);
    let settings = FitSettings::default();
    let (fit, report) = fit_greedy(&cs, &settings, &GreedySettings::default(), |_| {}).unwrap();
    assert_eq!(report.constraints.len(), report.used.len());
    let model = rbf_core::Model {
        constraints: report.constraints,
        settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    };
    let rbf_core::AnyModel::Three(back) = rbf_core::AnyModel::from_json(&model.to_json()).unwrap()
    else {
        panic!("a 3D model reads back as 3D");
    };
    for p in [[0.0, 0.0, 0.0], [0.5, 0.5, 0.5], [2.0, 0.0, 0.0]] {
        assert_eq!(back.interpolant.value(&p), model.interpolant.value(&p));
    }
}

/// One normal in a hundred reversed, as a scan's estimated normals leave a few: a plain greedy
/// fit takes them all (they are the worst met) and folds the surface around each; told to
/// skip contradicted constraints, it takes only those its first spread held, and the surface
/// stays negative just outside and positive just inside every other reversed point.
#[test]
fn contradicted_normals_are_skipped_when_asked() {
    let mut cs = bumpy(3000);
    let reversed: Vec<usize> = (0..cs.len()).step_by(100).collect();
    for &i in &reversed {
        cs[i].normal = cs[i].normal.map(|x| -x);
    }
    let run = |skip: bool| {
        let settings = GreedySettings {
            tolerance: 2e-3,
            skip_contradicted: skip,
            ..Default::default()
        };
        fit_greedy(&cs, &FitSettings::default(), &settings, |_| {}).unwrap()
    };
    let taken = |used: &[usize]| reversed.iter().filter(|i| used.contains(i)).count();
    let (_, plain) = run(false);
    let (fit, skipping) = run(true);
    assert!(skipping.converged);
    // The plain fit takes every reversed normal; the skipping one only those of its first
    // spread (taken before any surface could contradict them), and reports the rest.
    assert_eq!(taken(&plain.used), reversed.len());
    assert!(taken(&skipping.used) <= reversed.len() / 4);
    assert_eq!(
        taken(&skipping.used) + skipping.contradicted,
        reversed.len()
    );
    for &i in reversed.iter().filter(|i| !skipping.used.contains(i)) {
        // The true outward normal is the point's direction from the origin.
        let p = cs[i].position;
        let outside = p.map(|x| 1.05 * x);
        let inside = p.map(|x| 0.95 * x);
        assert!(fit.interpolant.value(&outside) < 0.0, "outside {i}");
        assert!(fit.interpolant.value(&inside) > 0.0, "inside {i}");
    }
}

/// With λ > 0 the surface misses the constraints it takes on purpose; when only those miss,
/// there is nothing left to add, and the fit stops there (not converged) instead of fitting
/// the same subset again for ever, as it did.
#[test]
fn a_smoothing_fit_stops_when_only_its_own_centres_miss() {
    // A sphere with one point pulled out to a spike: the smoothing passes under the spike (the
    // first constraint, always among the first subset) and near every other point.
    let mut cs: Vec<Constraint<3>> = rbf_core::shapes::fibonacci_sphere(400)
        .into_iter()
        .map(|u| Constraint::normal(u, u))
        .collect();
    cs[0].position = cs[0].position.map(|x| 1.3 * x);
    let settings = FitSettings {
        lambda: 1e-3,
        ..Default::default()
    };
    let greedy = GreedySettings {
        tolerance: 0.01,
        ..Default::default()
    };
    let (_, report) = fit_greedy(&cs, &settings, &greedy, |_| {}).unwrap();
    assert!(!report.converged);
    assert!(report.used.contains(&0) && report.used.len() < cs.len());
    let last = report.rounds.last().unwrap();
    assert!(last.max_error > 0.01, "{last:?}");
}
