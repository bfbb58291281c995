//! Measures the far field on a saved 3D model: time per product at the centres and the worst
//! error against compensated direct sums at sampled centres, for the orders and θ given.
//!
//!     cargo run --release -p rbf-far --example probe -- model.json [order theta leaf]...
use std::error::Error;
use std::time::Instant;

use rbf_core::{AnyModel, InterpolantView};
use rbf_far::{FarField, FarFieldSettings};

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .ok_or("usage: probe MODEL.json [ORDER THETA LEAF]...")?;
    let AnyModel::Three(model) = AnyModel::from_json(&std::fs::read_to_string(path)?)? else {
        return Err("the model is not 3D".into());
    };
    let f = model.interpolant.view();
    let (c, w) = (f.centres(), f.weights());
    let sample: Vec<usize> = (0..2000).map(|i| (i * 7919) % c.len().max(1)).collect();
    let targets: Vec<[f64; 3]> = sample.iter().map(|&i| c[i]).collect();
    let mut exact = vec![0.0; targets.len()];
    let sums = InterpolantView::new(f.kernel(), c, w, 0.0, [0.0; 3])?;
    sums.par_values_compensated(&targets, &mut exact)?;
    if c.len() <= 300_000 {
        let t = Instant::now();
        let mut direct = vec![0.0; c.len()];
        sums.par_values_at_centres(&mut direct)?;
        println!("direct product: {:.2} s", t.elapsed().as_secs_f64());
    }
    let wsum: f64 = w.iter().map(|x| x.abs()).sum();
    println!("K = {}, Σ|w| = {wsum:.3e}", c.len());
    for spec in args[1..].chunks_exact(3) {
        let settings = FarFieldSettings {
            order: spec[0].parse()?,
            theta: spec[1].parse()?,
            leaf: spec[2].parse()?,
            ..FarFieldSettings::default()
        };
        let t = Instant::now();
        let field = FarField::new(f.kernel(), c, &settings);
        let build = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let charges = field.charges(w)?;
        let charge = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut out = vec![0.0; c.len()];
        field.self_values(&charges, &mut out)?;
        let product = t.elapsed().as_secs_f64();
        let t = Instant::now();
        field.self_values(&charges, &mut out)?;
        let again = t.elapsed().as_secs_f64();
        let worst = sample
            .iter()
            .zip(&exact)
            .map(|(&i, e)| (out[i] - e).abs())
            .fold(0.0, f64::max);
        println!(
            "order {} θ {} leaf {}: build {build:.2} s, charges {charge:.2} s, first product {product:.2} s, next {again:.2} s, worst error {worst:.2e}",
            settings.order, settings.theta, settings.leaf
        );
    }
    Ok(())
}
