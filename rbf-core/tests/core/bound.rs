//! The guaranteed bounds over a ball hold at every point that dense sampling tries.

use proptest::prelude::*;
use rbf_core::{FitSettings, fit};

use crate::support::{kernel, value_constraints};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]
    #[test]
    fn ball_bounds_hold_everywhere_in_the_ball(
        constraints in value_constraints::<3>(6, 30),
        k in kernel(),
        centre in proptest::array::uniform3(-1.5..1.5_f64),
        radius in 0.01..1.0_f64,
        directions in proptest::collection::vec(proptest::array::uniform3(-1.0..1.0_f64), 400),
    ) {
        let settings = FitSettings { kernel: Some(k), ..Default::default() };
        let model = fit(&constraints, &settings).unwrap().interpolant;
        let f = model.view();
        let bound = f.ball_bound(&centre, radius);
        let mut steepest: f64 = 0.0;
        for d in &directions {
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
            // Points spread through the ball's volume and on its surface.
            let s = radius * len.min(1.0) / len;
            let p = [centre[0] + s * d[0], centre[1] + s * d[1], centre[2] + s * d[2]];
            let (v, g) = f.value_and_gradient(&p);
            let slope = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            steepest = steepest.max(slope);
            let tol = 1e-9 * (1.0 + bound.value.abs() + v.abs());
            prop_assert!((v - bound.value).abs() <= bound.change + tol,
                "|f(p) − f(c)| = {} > {}", (v - bound.value).abs(), bound.change);
            if bound.one_sign() {
                prop_assert_eq!(v > 0.0, bound.value > 0.0);
            }
        }
        prop_assert!(steepest <= bound.lipschitz * (1.0 + 1e-9) + 1e-9,
            "sampled slope {steepest} above the bound {}", bound.lipschitz);
    }
}
