//! Times one far-field product at the centres for N points on a bumpy sphere (random weights):
//!
//!     cargo run --release -p rbf-far --example scale -- N order theta
use std::error::Error;
use std::time::Instant;

use rbf_core::{InterpolantView, Kernel};
use rbf_far::{FarField, FarFieldSettings};

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [n, order, theta] = args.as_slice() else {
        return Err("usage: scale N ORDER THETA".into());
    };
    let n: usize = n.parse()?;
    let settings = FarFieldSettings {
        order: order.parse()?,
        theta: theta.parse()?,
        ..FarFieldSettings::default()
    };
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let centres: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let t = golden * i as f64;
            let s = 1.0 + 0.1 * (5.0 * z.acos()).sin() * (3.0 * t).cos();
            [s * r * t.cos(), s * r * t.sin(), s * z]
        })
        .collect();
    let weights: Vec<f64> = (0..n)
        .map(|i| ((i * 7919 % 1000) as f64 - 499.5) / 500.0)
        .collect();
    let t = Instant::now();
    let field = FarField::new(Kernel::Cubic, &centres, &settings);
    let charges = field.charges(&weights)?;
    let setup = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut out = vec![0.0; n];
    field.self_values(&charges, &mut out)?;
    let product = t.elapsed().as_secs_f64();
    let t = Instant::now();
    field.self_values(&charges, &mut out)?;
    let again = t.elapsed().as_secs_f64();
    let rows: Vec<usize> = (0..500).map(|i| i * n / 500).collect();
    let at: Vec<[f64; 3]> = rows.iter().map(|&i| centres[i]).collect();
    let mut exact = vec![0.0; rows.len()];
    InterpolantView::new(Kernel::Cubic, &centres, &weights, 0.0, [0.0; 3])?
        .par_values_compensated(&at, &mut exact)?;
    let size = exact.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let error = rows
        .iter()
        .zip(&exact)
        .fold(0.0_f64, |m, (&i, e)| m.max((out[i] - e).abs()));
    println!(
        "N {n}: setup {setup:.2} s, first product {product:.2} s, next {again:.2} s, \
         error {:.1e} of the largest value (500 rows)",
        error / size
    );
    Ok(())
}
