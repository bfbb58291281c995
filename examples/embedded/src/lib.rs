//! A model on a microcontroller: `model.rs` was written by
//! `rbf export model.json --format rust -o src/model.rs` and is evaluated by rbf-core without
//! an allocator or std. CI builds this crate for `thumbv7em-none-eabihf` (Cortex-M4F).
//!
//! ```
//! // The blob of Turk & O'Brien 2002, Figure 2: inside at its centre, outside far away.
//! assert!(rbf_embedded_example::inside([0.0, 0.0, 0.0]));
//! assert!(!rbf_embedded_example::inside([2.0, 0.0, 0.0]));
//! ```
#![no_std]

// Written by `rbf export`: kept exactly as generated.
#[rustfmt::skip]
mod model;

pub use model::MODEL;

/// f at p: positive inside the surface, negative outside.
pub fn value(p: [f64; 3]) -> f64 {
    MODEL.value(&p)
}

/// Whether p is inside the surface.
pub fn inside(p: [f64; 3]) -> bool {
    value(p) > 0.0
}

/// On bare metal nothing can be reported: stop.
#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
