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
