//! Measures the far field on a saved 3D model: time per product at the centres and the worst
//! error against compensated direct sums at sampled centres, for the orders and θ given.
//!
//!     cargo run --release -p rbf-far --example probe -- model.json [order theta leaf]...
use std::time::Instant;

use rbf_core::AnyModel;
use rbf_far::{FarField, FarFieldSettings};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let text = std::fs::read_to_string(&args[0]).expect("a model file");
    let AnyModel::Three(model) = AnyModel::from_json(&text).expect("a model") else {
        panic!("a 3D model")
    };
    let f = model.interpolant.view();
    let (c, w) = (f.centres(), f.weights());
    let sample: Vec<usize> = (0..2000).map(|i| (i * 7919) % c.len()).collect();
    let targets: Vec<[f64; 3]> = sample.iter().map(|&i| c[i]).collect();
    let mut exact = vec![0.0; targets.len()];
    let sums = rbf_core::InterpolantView::new(f.kernel(), c, w, 0.0, [0.0; 3]).unwrap();
    sums.par_values_compensated(&targets, &mut exact).unwrap();
    let t = Instant::now();
    let mut direct = vec![0.0; c.len()];
    sums.par_values(c, &mut direct).unwrap();
    println!("direct product: {:.2} s", t.elapsed().as_secs_f64());
    let wsum: f64 = w.iter().map(|x| x.abs()).sum();
    println!("K = {}, Σ|w| = {wsum:.3e}", c.len());
    for spec in args[1..].chunks(3) {
        let settings = FarFieldSettings {
            order: spec[0].parse().unwrap(),
            theta: spec[1].parse().unwrap(),
            leaf: spec[2].parse().unwrap(),
            target_leaf: spec[2].parse().unwrap(),
        };
        let t = Instant::now();
        let field = FarField::new(f.kernel(), c, &settings);
        let build = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let charges = field.charges(w);
        let charge = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut out = vec![0.0; c.len()];
        field.self_values(&charges, &mut out);
        let product = t.elapsed().as_secs_f64();
        let worst = sample
            .iter()
            .zip(&exact)
            .map(|(&i, e)| (out[i] - e).abs())
            .fold(0.0, f64::max);
        println!(
            "order {} θ {} leaf {}: build {build:.2} s, charges {charge:.2} s, product {product:.2} s, worst error {worst:.2e}",
            settings.order, settings.theta, settings.leaf
        );
    }
}
