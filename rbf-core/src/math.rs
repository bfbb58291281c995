//! The one place where rbf-core does float math beyond `+ - * /`.
//!
//! Square roots are correctly rounded by IEEE 754, so the hardware instruction (with `std`) and
//! libm's software routine (without it) give the same bits; the hardware one also vectorizes.
//! Logarithms always go through libm, so the std and no_std builds agree bit for bit.

#[cfg(feature = "std")]
#[inline(always)]
pub(crate) fn sqrt(x: f64) -> f64 {
    x.sqrt()
}

#[cfg(not(feature = "std"))]
#[inline(always)]
pub(crate) fn sqrt(x: f64) -> f64 {
    libm::sqrt(x)
}

#[cfg(feature = "std")]
#[inline(always)]
pub(crate) fn sqrtf(x: f32) -> f32 {
    x.sqrt()
}

#[cfg(not(feature = "std"))]
#[inline(always)]
pub(crate) fn sqrtf(x: f32) -> f32 {
    libm::sqrtf(x)
}

#[inline(always)]
pub(crate) fn ln(x: f64) -> f64 {
    libm::log(x)
}

#[inline(always)]
pub(crate) fn lnf(x: f32) -> f32 {
    libm::logf(x)
}

#[cfg(feature = "alloc")]
/// x raised to a small non-negative integer power.
#[inline]
pub(crate) fn powi(x: f64, n: i32) -> f64 {
    let mut r = 1.0;
    for _ in 0..n {
        r *= x;
    }
    r
}

#[cfg(feature = "alloc")]
/// Sine and cosine of x (radians), through libm in every build.
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

#[cfg(feature = "alloc")]
/// The fractional part of x, with the sign of x (as `f64::fract`).
#[inline]
pub(crate) fn fract(x: f64) -> f64 {
    x - libm::trunc(x)
}
