//! Evaluation in f32 (as on a Cortex-M4F) against f64.

use rbf_core::{FitSettings, InterpolantView, Kernel, fit};

#[test]
fn f32_values_match_f64_to_f32_precision() {
    // 100 oriented points on a sphere, fitted in f64.
    let cs = rbf_core::shapes::sphere(100);
    let f64_model = fit(&cs, &FitSettings::default()).unwrap().interpolant;
    let f32_model = f64_model.cast::<f32>();
    let (wide, narrow) = (f64_model.view(), f32_model.view());
    let eps = f32::EPSILON as f64;
    for i in 0..500 {
        let x = [
            ((i * 7) % 23) as f64 / 10.0 - 1.1,
            ((i * 11) % 19) as f64 / 8.0 - 1.1,
            ((i * 13) % 17) as f64 / 7.0 - 1.1,
        ];
        let exact = wide.value(&x);
        let single = narrow.value(&x.map(|v| v as f32)) as f64;
        // Rounding error of a sum is bounded by (terms) · ε · Σ|terms|; the sum of the magnitudes
        // of its terms (and of their sensitivity to the rounding of x, |x| ≤ 2) is what f32
        // precision means here.
        let magnitude: f64 = f64_model
            .centres()
            .iter()
            .zip(f64_model.weights())
            .map(|(c, w)| {
                let r = ((0..3).map(|d| (x[d] - c[d]).powi(2)).sum::<f64>()).sqrt();
                // The term and its change when x is rounded to f32 (relative error ε in x).
                (w * Kernel::Cubic.phi(r)).abs() + (w * Kernel::Cubic.dphi(r)).abs() * 2.0
            })
            .sum::<f64>()
            + f64_model.constant().abs()
            + (0..3)
                .map(|d| (f64_model.linear()[d] * x[d]).abs())
                .sum::<f64>();
        assert!(
            (exact - single).abs() <= 16.0 * eps * magnitude,
            "at {x:?}: f64 {exact}, f32 {single}, bound {}",
            16.0 * eps * magnitude
        );
    }
}

#[test]
fn a_model_in_static_arrays_evaluates_without_allocation() {
    static CENTRES: [[f32; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    static WEIGHTS: [f32; 3] = [1.0, -0.5, -0.5];
    const MODEL: InterpolantView<'static, f32, 2> =
        match InterpolantView::new(Kernel::ThinPlate, &CENTRES, &WEIGHTS, 0.25, [0.5, 0.5]) {
            Ok(m) => m,
            Err(_) => panic!("lengths differ"),
        };
    let expected = {
        let phi = |r: f64| if r > 0.0 { r * r * r.ln() } else { 0.0 };
        let x = [0.3_f64, 0.4];
        let d = |c: [f64; 2]| ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)).sqrt();
        phi(d([0.0, 0.0])) - 0.5 * phi(d([1.0, 0.0])) - 0.5 * phi(d([0.0, 1.0]))
            + 0.25
            + 0.5 * 0.3
            + 0.5 * 0.4
    };
    let mut out = [0.0_f32; 1];
    MODEL.values(&[[0.3, 0.4]], &mut out).unwrap();
    assert!((out[0] as f64 - expected).abs() < 1e-6);
    assert!((MODEL.value(&[0.3, 0.4]) as f64 - expected).abs() < 1e-6);
}

#[test]
fn batch_values_equal_pointwise_values() {
    let centres: Vec<[f64; 3]> = (0..37)
        .map(|i| [i as f64 * 0.1, (i % 5) as f64, 1.0])
        .collect();
    let weights: Vec<f64> = (0..37).map(|i| (i as f64 - 18.0) / 7.0).collect();
    for k in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
        let f = InterpolantView::new(k, &centres, &weights, 0.5, [1.0, -2.0, 0.5]).unwrap();
        let points: Vec<[f64; 3]> = (0..29).map(|i| [i as f64 * 0.13, 0.7, -0.2]).collect();
        let mut out = vec![0.0; points.len()];
        f.values(&points, &mut out).unwrap();
        for (p, v) in points.iter().zip(&out) {
            assert!((f.value(p) - v).abs() <= 1e-12 * (1.0 + v.abs()), "{k:?}");
        }
        assert!(f.values(&points, &mut out[1..]).is_err());
        let mut grads = vec![[0.0; 3]; points.len()];
        f.values_and_gradients(&points, &mut out, &mut grads)
            .unwrap();
        for ((p, v), g) in points.iter().zip(&out).zip(&grads) {
            let (v1, g1) = f.value_and_gradient(p);
            assert!((v1 - v).abs() <= 1e-12 * (1.0 + v.abs()), "{k:?}");
            for d in 0..3 {
                assert!((g1[d] - g[d]).abs() <= 1e-12 * (1.0 + g[d].abs()), "{k:?}");
            }
        }
    }
}
