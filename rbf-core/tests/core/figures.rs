//! The examples of Turk & O'Brien (2002) that can be checked in numbers.

use rbf_core::{Constraint, FitSettings, Interpolant, fit};

use rbf_core::shapes::tetrahedron;

/// Where f changes sign along the ray from the origin in direction `d` (bisection).
fn crossing(f: &Interpolant<f64, 3>, d: [f64; 3]) -> f64 {
    let (mut lo, mut hi) = (0.0, 10.0);
    assert!(f.value(&d.map(|c| c * hi)) < 0.0, "no crossing along {d:?}");
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if f.value(&d.map(|c| c * mid)) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn directions(n: usize) -> impl Iterator<Item = [f64; 3]> {
    rbf_core::shapes::fibonacci_sphere(n).into_iter()
}

fn radii(f: &Interpolant<f64, 3>) -> (f64, f64) {
    directions(500)
        .map(|d| crossing(f, d))
        .fold((f64::INFINITY, 0.0_f64), |(a, b), r| (a.min(r), b.max(r)))
}

#[test]
fn figure_2_tetrahedron_around_an_interior_point_is_nearly_a_sphere() {
    let mut cs: Vec<Constraint<3>> = tetrahedron().map(Constraint::boundary).to_vec();
    cs.push(Constraint::interior([0.0; 3], 1.0));
    let f = fit(&cs, &FitSettings::default()).unwrap().interpolant;
    assert!(f.value(&[0.0; 3]) > 0.0);
    for d in directions(50) {
        assert!(f.value(&d.map(|c| c * 10.0)) < 0.0, "far away is outside");
    }
    let (lo, hi) = radii(&f);
    // Passes through the unit-radius corners, and bulges less than 10 % between them.
    assert!(lo > 0.95 && hi < 1.1, "radius {lo}…{hi}");
    assert!((hi - lo) / lo < 0.1, "radius {lo}…{hi}");
}

#[test]
fn section_5_start_of_a_sculpting_session_is_nearly_a_sphere() {
    let mut cs: Vec<Constraint<3>> = tetrahedron().map(Constraint::boundary).to_vec();
    for i in 0..8 {
        let c = |b: usize| if i >> b & 1 == 1 { 3.0 } else { -3.0 };
        cs.push(Constraint::exterior([c(0), c(1), c(2)], -1.0));
    }
    let f = fit(&cs, &FitSettings::default()).unwrap().interpolant;
    assert!(f.value(&[0.0; 3]) > 0.0, "the centre is inside");
    for c in &cs[4..] {
        assert!((f.value(&c.position) + 1.0).abs() < 1e-12);
    }
    let (lo, hi) = radii(&f);
    assert!((hi - lo) / lo < 0.02, "radius {lo}…{hi}");
}

#[test]
fn figure_5_normal_constraints_bend_a_curve() {
    // Six boundary points on a circle; normal constraints point outward. Rotating one normal
    // changes the curve near it (Turk & O'Brien 2002, Figure 5) and only a little elsewhere.
    let circle: Vec<[f64; 2]> = (0..6)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / 6.0;
            [t.cos(), t.sin()]
        })
        .collect();
    let make = |tilt: f64| -> Vec<Constraint<2>> {
        circle
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let n = if i == 1 {
                    let (s, c) = tilt.sin_cos();
                    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
                } else {
                    p
                };
                Constraint::normal(p, n)
            })
            .collect()
    };
    let a = fit(&make(0.0), &FitSettings::default())
        .unwrap()
        .interpolant;
    let b = fit(&make(0.8), &FitSettings::default())
        .unwrap()
        .interpolant;
    for p in &circle {
        assert!(a.value(p).abs() < 1e-10 && b.value(p).abs() < 1e-10);
    }
    // The curve's normal (−∇f) at the tilted point turns toward the new normal, by a good part
    // of the 0.8 rad but not beyond; with the untilted constraint it is the circle's normal.
    let angle_of = |v: [f64; 2]| v[1].atan2(v[0]);
    let normal_angle = |f: &rbf_core::Interpolant<f64, 2>| {
        let g = f.gradient(&circle[1]);
        angle_of([-g[0], -g[1]]) - angle_of(circle[1])
    };
    assert!(normal_angle(&a).abs() < 1e-6, "{}", normal_angle(&a));
    let turned = normal_angle(&b);
    assert!(turned > 0.3 && turned < 0.8, "turned by {turned}");
    // Points far from the edited constraint barely move: f at the opposite point's neighbours.
    let far = [(-circle[1][0]) * 1.05, (-circle[1][1]) * 1.05];
    assert!((a.value(&far) - b.value(&far)).abs() < 0.2 * a.value(&far).abs());
}
