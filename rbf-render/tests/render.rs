//! Ray tracing (sampled band and proved sphere tracing), CSG and the rasterizer against analytic
//! answers, a dense ray march and each other.

use proptest::prelude::*;
use rbf_core::{Constraint, FitSettings, InterpolantView, Kernel, fit};
use rbf_render::{
    Camera, Csg, Image, Lipschitz, MeshStyle, Object, PlotSettings, Ray, RenderSettings,
    first_hits, plot_curve, render, render_framed, render_mesh, surface_bounds,
};

/// f = R³ − |x − c|³: the sphere of radius R around c.
fn sphere(centre: &[[f64; 3]; 1], radius: f64) -> InterpolantView<'_, f64, 3> {
    InterpolantView::new(Kernel::Cubic, centre, &[-1.0], radius.powi(3), [0.0; 3]).unwrap()
}

/// Black background, no floor, no shadows, one ray per pixel, white objects: lit pixels are
/// exactly the covered ones.
fn mask_settings(lipschitz: Lipschitz) -> RenderSettings {
    RenderSettings {
        samples: 1,
        shadows: false,
        ground: false,
        background: [[0.0; 3], [0.0; 3]],
        lipschitz,
        ..Default::default()
    }
}

/// The proved tracer and the default one (through the sampled band).
const MODES: [Lipschitz; 2] = [Lipschitz::Guaranteed, Lipschitz::Auto];

fn mask(image: &Image) -> Vec<bool> {
    image
        .pixels()
        .iter()
        .map(|p| p.iter().any(|&c| c > 0.0))
        .collect()
}

fn front_camera(size: u32) -> Camera {
    Camera {
        eye: [0.0, 0.0, 5.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        fov_degrees: 30.0,
        width: size,
        height: size,
    }
}

fn white(shape: Csg) -> Object {
    Object {
        shape,
        colour: [1.0; 3],
        reflectivity: 0.0,
    }
}

#[test]
fn a_sphere_covers_its_analytic_disc_to_a_pixel() {
    for mode in MODES {
        sphere_covers_its_disc(mode);
    }
}

fn sphere_covers_its_disc(mode: Lipschitz) {
    let c = [[0.0; 3]];
    let models = [sphere(&c, 1.0)];
    let camera = front_camera(101);
    let (image, stats) = render(
        &models,
        &[white(Csg::Model(0))],
        &camera,
        &mask_settings(mode),
    )
    .unwrap();
    assert_eq!(stats.guaranteed, mode == Lipschitz::Guaranteed);
    let covered = mask(&image);
    // The sphere subtends asin(1/5) from the eye; a pixel spans about fov/101.
    let rim = (1.0_f64 / 5.0).asin();
    let pixel = 30.0_f64.to_radians() / 101.0;
    let mut wrong_far_from_rim = 0;
    for y in 0..101 {
        for x in 0..101 {
            let ray = camera.ray(x as f64 + 0.5, y as f64 + 0.5);
            let angle = (-ray.direction[2]).clamp(-1.0, 1.0).acos();
            let inside = angle < rim;
            if inside != covered[y * 101 + x] && (angle - rim).abs() > pixel {
                wrong_far_from_rim += 1;
            }
        }
    }
    assert_eq!(wrong_far_from_rim, 0);
    assert!(covered.iter().filter(|&&c| c).count() > 1000);
}

#[test]
fn union_intersection_and_difference_follow_the_masks() {
    for mode in MODES {
        csg_follows_the_masks(mode);
    }
}

fn csg_follows_the_masks(mode: Lipschitz) {
    let (ca, cb) = ([[0.0; 3]], [[1.0, 0.0, 0.0]]);
    let models = [sphere(&ca, 1.0), sphere(&cb, 1.2)];
    let camera = front_camera(81);
    let settings = mask_settings(mode);
    let shot = |shape: Csg| {
        mask(
            &render(&models, &[white(shape)], &camera, &settings)
                .unwrap()
                .0,
        )
    };
    let a = shot(Csg::Model(0));
    let b = shot(Csg::Model(1));
    let union = shot(Csg::Union(vec![Csg::Model(0), Csg::Model(1)]));
    let both = shot(Csg::Intersection(vec![Csg::Model(0), Csg::Model(1)]));
    let cut = shot(Csg::Difference(
        Box::new(Csg::Model(0)),
        Box::new(Csg::Model(1)),
    ));
    let count = |m: &[bool]| m.iter().filter(|&&x| x).count();
    for i in 0..a.len() {
        assert_eq!(union[i], a[i] || b[i], "union at pixel {i}");
        assert!(
            !both[i] || (a[i] && b[i]),
            "intersection covers pixel {i} that an operand misses"
        );
        assert!(!cut[i] || a[i], "difference outside A at pixel {i}");
        assert!(
            !a[i] || b[i] || cut[i],
            "difference lost pixel {i} that B does not touch"
        );
    }
    // Where B holds A's whole depth, the difference removes A.
    let removed = (0..a.len()).filter(|&i| a[i] && !cut[i]).count();
    assert!(removed > 50, "{removed}");
    assert!(count(&both) > 100 && count(&both) < count(&a));
}

/// A blob fitted through random points around an interior point.
fn blob(points: &[[f64; 3]]) -> Vec<Constraint<3>> {
    let mut c: Vec<Constraint<3>> = points.iter().map(|&p| Constraint::boundary(p)).collect();
    c.push(Constraint::interior([0.0; 3], 1.0));
    c
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]
    /// Every hit is on the surface, and f < 0 everywhere on the ray before it (no ray passes
    /// through the surface); rays that miss never see f ≥ 0 inside the traced box.
    #[test]
    fn hits_lie_on_the_surface_and_no_ray_passes_through(
        directions in proptest::collection::vec(proptest::array::uniform3(-1.0..1.0_f64), 6..12),
        origin_angle in 0.0..std::f64::consts::TAU,
    ) {
        let points: Vec<[f64; 3]> = directions
            .iter()
            .map(|d| {
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-3);
                let r = 0.6 + 0.4 * (d[0] * 3.0).sin().abs();
                [r * d[0] / n, r * d[1] / n, r * d[2] / n]
            })
            .collect();
        let Ok(fitted) = fit(&blob(&points), &FitSettings::default()) else {
            return Ok(()); // a degenerate draw (two points too close)
        };
        let f = fitted.interpolant.view();
        // Only closed surfaces (f < 0 all around): an open one is cut by the traced box, and
        // rays that enter the box inside the solid hit the cut, not the surface.
        let closed = rbf_core::shapes::fibonacci_sphere(64)
            .into_iter()
            .all(|d| f.value(&d.map(|c| 4.0 * c)) < 0.0);
        prop_assume!(closed);
        let eye = [4.0 * origin_angle.cos(), 1.0, 4.0 * origin_angle.sin()];
        let camera = Camera { eye, target: [0.0; 3], up: [0.0, 1.0, 0.0], fov_degrees: 40.0, width: 24, height: 24 };
        let rays: Vec<Ray> = (0..24 * 24).map(|i| camera.ray((i % 24) as f64 + 0.5, (i / 24) as f64 + 0.5)).collect();
        let settings = RenderSettings { lipschitz: Lipschitz::Guaranteed, ..Default::default() };
        let hits = first_hits(&[f], &Csg::Model(0), &rays, &settings).unwrap();
        prop_assert!(hits.iter().any(|h| h.is_some()));
        // The traced box, as the tracer finds it: a piece of surface wholly outside it (a
        // detached bubble far from the centres) is cut, as documented.
        let (lo, hi) = f.surface_box(0.05);
        for (ray, hit) in rays.iter().zip(&hits) {
            let at = |t: f64| [0, 1, 2].map(|d| ray.origin[d] + t * ray.direction[d]);
            let (mut enter, mut leave) = (0.0_f64, f64::INFINITY);
            for d in 0..3 {
                let (a, b) = ((lo[d] - ray.origin[d]) / ray.direction[d], (hi[d] - ray.origin[d]) / ray.direction[d]);
                enter = enter.max(a.min(b));
                leave = leave.min(a.max(b));
            }
            let end = hit.unwrap_or(leave.max(enter));
            if let Some(t) = hit {
                let (v, g) = f.value_and_gradient(&at(*t));
                let slope = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
                let distance = v.abs() / slope;
                let facing = -(g[0] * ray.direction[0] + g[1] * ray.direction[1] + g[2] * ray.direction[2]) / slope;
                // Within 1e-4 of the model's size at worst (grazing rays); to rounding where
                // the ray meets the surface at less than 60° from its normal.
                prop_assert!(distance < 2e-4, "hit {distance} from the surface");
                prop_assert!(facing.abs() < 0.5 || distance < 1e-9, "hit {distance} from the surface, facing {facing}");
            }
            for k in 0..2000 {
                let t = enter + (end - enter) * k as f64 / 2000.0;
                prop_assert!(f.value(&at(t)) < 0.0 || (end - t) < 1e-4, "f ≥ 0 at t = {t} before the hit at {end}");
            }
        }
    }
}

/// Random oriented points on a wavy sphere (`torus` false) or a torus, fitted with normal
/// constraints: 2 × `count` rows.
fn random_model(count: usize, torus: bool, seed: u64) -> rbf_core::Interpolant<f64, 3> {
    let mut state = seed;
    let mut uniform = move || {
        // SplitMix64.
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    };
    let tau = std::f64::consts::TAU;
    let constraints: Vec<Constraint<3>> = (0..count)
        .map(|_| {
            let (u, v) = (tau * uniform(), tau * uniform());
            let (p, n) = if torus {
                let (big, small) = (1.0, 0.4);
                let ring = big + small * v.cos();
                (
                    [ring * u.cos(), small * v.sin(), ring * u.sin()],
                    [v.cos() * u.cos(), v.sin(), v.cos() * u.sin()],
                )
            } else {
                let z = 2.0 * uniform() - 1.0;
                let r = (1.0 - z * z).sqrt();
                let d = [r * u.cos(), r * u.sin(), z];
                let radius = 1.0 + 0.15 * (3.0 * d[0]).sin() * (2.0 * d[1]).cos();
                (d.map(|c| radius * c), d)
            };
            Constraint::normal(p, n)
        })
        .collect();
    fit(&constraints, &FitSettings::default())
        .unwrap()
        .interpolant
}

/// The first zero of f along each ray by 4000 equal steps through the ball of radius 1.6 around
/// the origin (a dense march, with no bound; all points evaluated together), refined by
/// bisection; and whether a ray that does not cross came within `near` of the surface
/// (|f|/|∇f| < near at its sample closest to zero).
fn dense_march(
    f: &InterpolantView<'_, f64, 3>,
    rays: &[Ray],
    near: f64,
) -> Vec<(Option<f64>, bool)> {
    const STEPS: usize = 4000;
    let span = |ray: &Ray| {
        // |o + t d|² = 1.6² with |d| = 1.
        let b: f64 = (0..3).map(|d| ray.origin[d] * ray.direction[d]).sum();
        let c: f64 = (0..3).map(|d| ray.origin[d] * ray.origin[d]).sum::<f64>() - 1.6 * 1.6;
        let disc = b * b - c;
        (disc > 0.0).then(|| (-b - disc.sqrt(), -b + disc.sqrt()))
    };
    let at = |ray: &Ray, t: f64| [0, 1, 2].map(|d| ray.origin[d] + t * ray.direction[d]);
    let mut points = Vec::new();
    for ray in rays {
        let (a, b) = span(ray).unwrap_or((0.0, 0.0));
        points.extend((0..=STEPS).map(|k| at(ray, a + (b - a) * k as f64 / STEPS as f64)));
    }
    let mut values = vec![0.0; points.len()];
    f.values(&points, &mut values).unwrap();
    rays.iter()
        .zip(values.chunks(STEPS + 1))
        .map(|(ray, v)| {
            let Some((a, b)) = span(ray) else {
                return (None, false);
            };
            let t_of = |k: usize| a + (b - a) * k as f64 / STEPS as f64;
            if let Some(k) = v.iter().position(|&x| x >= 0.0) {
                let (mut lo, mut hi) = (t_of(k.saturating_sub(1)), t_of(k));
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if f.value(&at(ray, mid)) >= 0.0 {
                        hi = mid
                    } else {
                        lo = mid
                    }
                }
                return (Some(hi), false);
            }
            let closest = (0..=STEPS).max_by(|&i, &j| v[i].total_cmp(&v[j])).unwrap();
            let (value, g) = f.value_and_gradient(&at(ray, t_of(closest)));
            let slope = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            (None, value.abs() < near * slope)
        })
        .collect()
}

/// The default tracer (sampled band, exact confirmation) finds the first hit a dense march
/// finds on models fitted to random points, and misses where it misses; only rays that graze
/// the surface (within 1e-3 of it) may disagree.
#[test]
fn renders_of_random_point_models_hit_where_a_dense_march_hits() {
    for (count, torus, seed) in [(300, false, 1), (300, true, 2), (500, false, 3)] {
        let model = random_model(count, torus, seed);
        let f = model.view();
        let size = 16;
        for (eye, up) in [
            ([0.3, 1.2, 4.0], [0.0, 1.0, 0.0]),
            ([3.5, -0.4, -1.5], [0.0, 0.0, 1.0]),
        ] {
            let camera = Camera {
                eye,
                target: [0.0; 3],
                up,
                fov_degrees: 40.0,
                width: size,
                height: size,
            };
            let rays: Vec<Ray> = (0..size * size)
                .map(|i| camera.ray((i % size) as f64 + 0.37, (i / size) as f64 + 0.61))
                .collect();
            let hits = first_hits(&[f], &Csg::Model(0), &rays, &RenderSettings::default()).unwrap();
            let (mut hit_count, mut grazing) = (0, 0);
            let march = dense_march(&f, &rays, 1e-3);
            for (hit, &(reference, grazed)) in hits.iter().zip(&march) {
                match (hit, reference) {
                    (Some(t), Some(r)) => {
                        hit_count += 1;
                        assert!(
                            (t - r).abs() < 1e-6,
                            "hit at {t}, the march at {r} ({count}, {torus})"
                        );
                    }
                    (None, None) => {}
                    _ if grazed => grazing += 1,
                    _ => panic!("{hit:?} where the march finds {reference:?} ({count}, {torus})"),
                }
            }
            assert!(hit_count > 30, "{hit_count}");
            assert!(grazing <= 2, "{grazing} grazing rays disagree");
        }
    }
}

#[test]
fn the_mesh_rasterizer_and_the_tracer_agree_on_a_sphere() {
    let c = [[0.0; 3]];
    let models = [sphere(&c, 1.0)];
    let camera = front_camera(81);
    let traced = mask(
        &render(
            &models,
            &[white(Csg::Model(0))],
            &camera,
            &mask_settings(Lipschitz::Auto),
        )
        .unwrap()
        .0,
    );
    let mesh = rbf_mesh::TriMesh::icosphere(5);
    let image = render_mesh(
        &mesh,
        &camera,
        MeshStyle::Smooth,
        [1.0; 3],
        &mask_settings(Lipschitz::Auto),
    )
    .unwrap();
    let drawn = mask(&image);
    let differ = traced.iter().zip(&drawn).filter(|(a, b)| a != b).count();
    let disc = traced.iter().filter(|&&x| x).count();
    // The polyhedron's silhouette lies inside the sphere's by its sagitta: a thin ring.
    assert!(differ * 50 < disc, "{differ} of {disc} pixels differ");
}

#[test]
fn a_plot_draws_the_curve_through_its_boundary_constraints() {
    let constraints = [
        Constraint::boundary([1.0, 0.0]),
        Constraint::boundary([0.0, 1.0]),
        Constraint::boundary([-1.0, 0.0]),
        Constraint::boundary([0.0, -1.0]),
        Constraint::interior([0.0, 0.0], 1.0),
    ];
    let f = fit(&constraints, &FitSettings::default())
        .unwrap()
        .interpolant;
    let settings = PlotSettings {
        width: 200,
        height: 200,
        bounds: Some(([-2.0, -2.0], [2.0, 2.0])),
        ..Default::default()
    };
    let image = plot_curve(&f.view(), &constraints, &settings).unwrap();
    let dark = |x: f64, y: f64| {
        let (px, py) = (
            ((x + 2.0) / 4.0 * 200.0) as u32,
            ((2.0 - y) / 4.0 * 200.0) as u32,
        );
        image.get(px.min(199), py.min(199)).iter().all(|&c| c < 0.3)
    };
    // On the curve, at the boundary constraints; far from it, white.
    for c in &constraints[..4] {
        assert!(dark(c.position[0], c.position[1]), "{:?}", c.position);
    }
    assert!(!dark(1.8, 1.8) && !dark(0.5, 0.2));
    let with_map = plot_curve(
        &f.view(),
        &constraints,
        &PlotSettings {
            colour_map: true,
            ..settings
        },
    )
    .unwrap();
    // Inside is warm: more red than blue.
    let p = with_map.get(115, 90);
    assert!(p[0] > p[2], "{p:?}");
}

#[test]
fn bad_requests_are_errors() {
    let c = [[0.0; 3]];
    let models = [sphere(&c, 1.0)];
    let mut camera = front_camera(8);
    assert!(
        render(
            &models,
            &[white(Csg::Model(3))],
            &camera,
            &mask_settings(Lipschitz::Auto)
        )
        .is_err()
    );
    assert!(
        render(
            &models,
            &[white(Csg::Union(vec![]))],
            &camera,
            &mask_settings(Lipschitz::Auto)
        )
        .is_err()
    );
    assert!(render(&models, &[], &camera, &mask_settings(Lipschitz::Auto)).is_err());
    camera.width = 0;
    assert!(
        render(
            &models,
            &[white(Csg::Model(0))],
            &camera,
            &mask_settings(Lipschitz::Auto)
        )
        .is_err()
    );
    // A mesh with an index out of range or a NaN vertex cannot reach render_mesh: TriMesh
    // refuses it.
    assert!(rbf_mesh::TriMesh::new(vec![[0.0; 3]], vec![[0, 1, 2]]).is_err());
    assert!(rbf_mesh::TriMesh::new(vec![[f64::NAN; 3]; 3], vec![[0, 1, 2]]).is_err());
}

#[test]
fn render_framed_is_surface_bounds_then_render() {
    // Two spheres cut from one another: the framed render reuses its tracers' cells for the
    // box at 512 pixels (the lattice of surface_bounds) and builds them twice at other sizes;
    // either way, the same camera and the same pixels as the two calls.
    let (a, b) = ([[0.0; 3]], [[0.6, 0.2, 0.0]]);
    let models = [sphere(&a, 1.0), sphere(&b, 0.7)];
    let objects = [Object::new(
        Csg::Difference(Box::new(Csg::Model(0)), Box::new(Csg::Model(1))),
        0,
    )];
    let settings = RenderSettings {
        samples: 1,
        ..Default::default()
    };
    for (width, height) in [(512, 24), (64, 48)] {
        let aim = |lo, hi| Camera::orbit(lo, hi, 30.0, 20.0, width, height);
        let (lo, hi) = surface_bounds(&models, &objects, &settings).unwrap();
        let camera = aim(lo, hi);
        let (image, _) = render(&models, &objects, &camera, &settings).unwrap();
        let (framed, _, framed_camera) =
            render_framed(&models, &objects, &settings, (width, height), aim).unwrap();
        assert_eq!(framed_camera.eye, camera.eye, "{width} × {height}");
        assert_eq!(framed.to_srgb8(), image.to_srgb8(), "{width} × {height}");
    }
}

/// The sphere f = R³ − |x|³ whose coarse field is f − `error`, a smaller sphere, said to err
/// by `error`: as a far field's coarse companion may.
struct WithCoarse<'a> {
    exact: InterpolantView<'a, f64, 3>,
    coarse: InterpolantView<'a, f64, 3>,
    error: f64,
}

impl rbf_core::ScalarField<3> for WithCoarse<'_> {
    fn direct(&self) -> InterpolantView<'_, f64, 3> {
        self.exact
    }

    fn field_values(
        &self,
        points: &[[f64; 3]],
        out: &mut [f64],
    ) -> Result<(), rbf_core::LengthMismatch> {
        self.exact.values(points, out)
    }

    fn field_values_and_gradients(
        &self,
        points: &[[f64; 3]],
        values: &mut [f64],
        gradients: &mut [[f64; 3]],
    ) -> Result<(), rbf_core::LengthMismatch> {
        self.exact.values_and_gradients(points, values, gradients)
    }

    fn coarse(&self) -> Option<(&dyn rbf_core::ScalarField<3>, f64)> {
        Some((&self.coarse, self.error))
    }
}

#[test]
fn a_coarse_field_steers_but_hits_stay_on_the_exact_surface() {
    // The coarse sphere is smaller by 1/3 of a fine cell (|∇f| = 3 on the unit sphere; fine
    // cells are about 0.017 here), then by a tenth of the radius. Rays that graze the exact
    // sphere miss the coarse one: only the stated error, added to the band's and to the cells'
    // intervals (cells the coarse sphere leaves would be skipped), sends them to the exact
    // Newton steps that hit.
    for error in [0.017, 0.3] {
        coarse_sphere_hits(error);
    }
}

fn coarse_sphere_hits(error: f64) {
    let centre = [[0.0; 3]];
    let model = WithCoarse {
        exact: sphere(&centre, 1.0),
        coarse: InterpolantView::new(Kernel::Cubic, &centre, &[-1.0], 1.0 - error, [0.0; 3])
            .unwrap(),
        error,
    };
    let rays: Vec<Ray> = (0..400)
        .map(|i| {
            // Aimed at 0.95 to 0.9999 of the radius off the axis, around it.
            let (r, a) = (0.95 + 0.0499 * (i as f64 / 399.0), i as f64 * 2.399);
            Ray {
                origin: [r * a.cos(), r * a.sin(), 5.0],
                direction: [0.0, 0.0, -1.0],
            }
        })
        .collect();
    let hits = first_hits(&[model], &Csg::Model(0), &rays, &RenderSettings::default()).unwrap();
    for (ray, hit) in rays.iter().zip(hits) {
        let (x, y) = (ray.origin[0], ray.origin[1]);
        let depth = (1.0 - x * x - y * y).sqrt();
        let t = hit.unwrap_or_else(|| panic!("the ray through ({x}, {y}) missed the sphere"));
        assert!(
            (t - (5.0 - depth)).abs() < 1e-6,
            "coarse error {error}: the ray through ({x}, {y}) hit at {t}, not {}",
            5.0 - depth
        );
    }
}

#[test]
fn edge_rays_agree_with_supersampling_everywhere() {
    // Extra rays go only where neighbours differ and do not show one smooth surface; the
    // image is that of a render at twice the size (whose pixel centres are the extra rays)
    // averaged in blocks of 2 × 2, within a few levels of 255 at every pixel. Two spheres, one
    // before the other: silhouettes against the sky and against each other.
    let (a, b) = ([[0.0; 3]], [[0.9, 0.5, 0.9]]);
    let models = [sphere(&a, 1.0), sphere(&b, 0.6)];
    let objects = [Object::new(Csg::Model(0), 0), Object::new(Csg::Model(1), 1)];
    let size = 96;
    let camera = |side: u32| Camera {
        width: side,
        height: side,
        ..Camera::orbit([-1.0; 3], [1.0; 3], 30.0, 20.0, side, side)
    };
    // No floor and no shadows (their edges would take extra rays too).
    let settings = |samples| RenderSettings {
        samples,
        shadows: false,
        ground: false,
        ..Default::default()
    };
    let (image, stats) = render(&models, &objects, &camera(size), &settings(2)).unwrap();
    let (large, _) = render(&models, &objects, &camera(2 * size), &settings(1)).unwrap();
    // Rays are counted per solid: two per pixel, and 2 × 4 more in each edge pixel (at the
    // silhouettes, about 500 of them; shading alone would add 1000 more).
    let pixels = u64::from(size * size);
    let edges = (stats.rays - 2 * pixels) / 8;
    assert!(edges <= pixels / 16, "{edges} edge pixels");
    let srgb = |c: [f32; 3]| c.map(|v| f64::from(v).clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0);
    let mut worst = 0.0_f64;
    for y in 0..size {
        for x in 0..size {
            let mut mean = [0.0_f32; 3];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let c = large.get(2 * x + dx, 2 * y + dy);
                (0..3).for_each(|d| mean[d] += 0.25 * c[d]);
            }
            let (p, q) = (srgb(image.get(x, y)), srgb(mean));
            worst = (0..3).map(|d| (p[d] - q[d]).abs()).fold(worst, f64::max);
        }
    }
    assert!(
        worst <= 3.0,
        "a pixel {worst:.1} levels from the supersampled image"
    );
}
