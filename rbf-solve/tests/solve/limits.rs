//! Sizes that would not fit are refused before anything is allocated.

use rbf_core::FitError;

#[test]
fn a_system_too_large_for_memory_is_refused_with_its_size() {
    let e = rbf_solve::check_fits(10_000_000, 1).unwrap_err();
    let FitError::TooLarge { rows, bytes, .. } = e else {
        panic!("{e}")
    };
    assert_eq!(rows, 10_000_000);
    assert_eq!(bytes, 800_000_000_000_000);
    let message = e.to_string();
    assert!(
        message.contains("MiB") && message.contains("10000000 rows"),
        "{message}"
    );
}

#[test]
fn a_system_that_fits_is_accepted() {
    assert!(rbf_solve::check_fits(1000, 2).is_ok());
}

#[test]
fn fitting_a_system_too_large_for_memory_fails_before_allocating() {
    use rbf_core::{Constraint, FitSettings};
    let cs: Vec<Constraint<3>> = (0..200_000_u64)
        .map(|i| {
            let p = [
                (i % 100) as f64,
                ((i / 100) % 100) as f64,
                (i / 10_000) as f64,
            ];
            if i == 0 {
                Constraint::interior(p, 1.0)
            } else {
                Constraint::boundary(p)
            }
        })
        .collect();
    // The dense solver refuses 320 GB before allocating (`fit` would solve iteratively).
    let settings = FitSettings::default();
    let system = rbf_core::System::new(&cs, &settings).unwrap();
    let e = rbf_solve::solve(&system, &settings, &rbf_solve::SolveOptions::default()).unwrap_err();
    assert!(matches!(e, FitError::TooLarge { rows: 200_000, .. }), "{e}");
}
