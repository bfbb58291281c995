//! Normals and their orientation against shapes whose true outward normals are known: spheres,
//! a torus (not convex, genus 1), two separate pieces, a thin plate (two sheets a few spacings
//! apart), with noise, flipped given normals, and outliers.

use proptest::prelude::*;
use rbf_cloud::{
    Neighbours, PointTree, estimate_normals, normal_of, orient_normals, statistical_outliers,
};

/// A small deterministic generator (xorshift), so that the tests need no random crate.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.next().max(1e-300), self.next());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// Fibonacci points on a sphere of `radius` at `centre`, with their outward normals.
fn sphere(n: usize, centre: [f64; 3], radius: f64) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let t = 2.399_963_229_728_653 * i as f64;
            let s = (1.0 - z * z).sqrt();
            let u = [s * t.cos(), s * t.sin(), z];
            (
                [
                    centre[0] + radius * u[0],
                    centre[1] + radius * u[1],
                    centre[2] + radius * u[2],
                ],
                u,
            )
        })
        .unzip()
}

/// Random points on a torus around z (radii 1 and 0.35), with their outward normals.
fn torus(n: usize, rng: &mut Rng) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let (big, small) = (1.0, 0.35);
    let mut out = (Vec::new(), Vec::new());
    while out.0.len() < n {
        let (u, v) = (
            rng.next() * std::f64::consts::TAU,
            rng.next() * std::f64::consts::TAU,
        );
        // Uniform in area: accept v with probability proportional to the local radius.
        if rng.next() * (big + small) > big + small * v.cos() {
            continue;
        }
        let normal = [v.cos() * u.cos(), v.cos() * u.sin(), v.sin()];
        out.0.push([
            (big + small * v.cos()) * u.cos(),
            (big + small * v.cos()) * u.sin(),
            small * v.sin(),
        ]);
        out.1.push(normal);
    }
    out
}

/// The closed surface of a box of sides 1 × 1 × `thickness`, sampled on grids of `spacing`,
/// with its outward normals.
fn plate(thickness: f64, spacing: f64) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let mut out = (Vec::new(), Vec::new());
    let m = (1.0 / spacing).round() as usize;
    let h = ((thickness / spacing).round() as usize).max(1);
    for a in 0..=m {
        let x = a as f64 / m as f64;
        for b in 0..=m {
            let y = b as f64 / m as f64;
            out.0.push([x, y, 0.0]);
            out.1.push([0.0, 0.0, -1.0]);
            out.0.push([x, y, thickness]);
            out.1.push([0.0, 0.0, 1.0]);
        }
        // The four sides, between the sheets.
        for c in 1..h {
            let z = thickness * c as f64 / h as f64;
            for (p, n) in [
                ([x, 0.0, z], [0.0, -1.0, 0.0]),
                ([x, 1.0, z], [0.0, 1.0, 0.0]),
                ([0.0, x, z], [-1.0, 0.0, 0.0]),
                ([1.0, x, z], [1.0, 0.0, 0.0]),
            ] {
                out.0.push(p);
                out.1.push(n);
            }
        }
    }
    out
}

fn share_outward(normals: &[[f64; 3]], truth: &[[f64; 3]]) -> f64 {
    let good = normals
        .iter()
        .zip(truth)
        .filter(|(n, t)| n[0] * t[0] + n[1] * t[1] + n[2] * t[2] > 0.0)
        .count();
    good as f64 / truth.len() as f64
}

fn oriented(points: &[[f64; 3]], k: usize) -> (Vec<[f64; 3]>, usize) {
    let near = Neighbours::new(points, k);
    let normals = estimate_normals(points, &near);
    let o = orient_normals(points, &normals, &near);
    (o.normals, o.components)
}

#[test]
fn sphere_normals_are_radial_and_outward() {
    let (points, truth) = sphere(3000, [0.2, -0.1, 0.4], 2.0);
    let near = Neighbours::new(&points, 12);
    let normals = estimate_normals(&points, &near);
    let aligned = normals
        .iter()
        .zip(&truth)
        .filter(|(n, t)| (n[0] * t[0] + n[1] * t[1] + n[2] * t[2]).abs() > 0.99)
        .count();
    assert_eq!(aligned, points.len());
    let o = orient_normals(&points, &normals, &near);
    assert_eq!(share_outward(&o.normals, &truth), 1.0);
    assert_eq!(o.components, 1);
}

#[test]
fn a_torus_is_oriented_outward_everywhere() {
    let (points, truth) = torus(6000, &mut Rng(7));
    let (normals, components) = oriented(&points, 12);
    assert_eq!(components, 1);
    let share = share_outward(&normals, &truth);
    assert!(share >= 0.995, "{share}");
}

#[test]
fn separate_pieces_are_oriented_each_from_its_own_seed() {
    let (mut points, mut truth) = sphere(1500, [0.0; 3], 1.0);
    let (p2, t2) = sphere(800, [5.0, 0.0, 0.0], 0.5);
    points.extend(p2);
    truth.extend(t2);
    let (normals, components) = oriented(&points, 10);
    assert_eq!(components, 2);
    assert_eq!(share_outward(&normals, &truth), 1.0);
}

#[test]
fn a_thin_plate_keeps_its_two_sides_apart() {
    // The sheets are 2.5 spacings apart and 16 neighbours reach across: a normal carried
    // across such an edge would come out with the wrong sign, and the tree must not follow
    // those edges. (Corners and edges of the box, where normals are undefined, are among the
    // 1% allowed.)
    let (points, truth) = plate(0.05, 0.02);
    let (normals, components) = oriented(&points, 16);
    assert_eq!(
        components, 1,
        "the neighbour graph reaches across the plate"
    );
    let share = share_outward(&normals, &truth);
    assert!(share >= 0.99, "{share}");
}

#[test]
fn flipped_given_normals_are_found_and_fixed() {
    let (points, truth) = sphere(2000, [0.0; 3], 1.0);
    let mut rng = Rng(3);
    let given: Vec<[f64; 3]> = truth
        .iter()
        .map(|t| {
            if rng.next() < 0.3 {
                [-t[0], -t[1], -t[2]]
            } else {
                *t
            }
        })
        .collect();
    let wrong = given
        .iter()
        .zip(&truth)
        .filter(|(g, t)| g[0] * t[0] + g[1] * t[1] + g[2] * t[2] < 0.0)
        .count();
    let o = orient_normals(&points, &given, &Neighbours::new(&points, 10));
    assert_eq!(o.flipped, wrong);
    assert_eq!(share_outward(&o.normals, &truth), 1.0);
}

/// `count` points in random directions, 1.5 to 3.5 from the origin.
fn outliers_around_the_unit_sphere(rng: &mut Rng, count: usize) -> Vec<[f64; 3]> {
    (0..count)
        .map(|_| {
            let d = [rng.normal(), rng.normal(), rng.normal()];
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let s = 1.5 + 2.0 * rng.next();
            [s * d[0] / r, s * d[1] / r, s * d[2] / r]
        })
        .collect()
}

#[test]
fn far_outliers_are_flagged_and_the_surface_is_kept() {
    let (mut points, _) = sphere(5000, [0.0; 3], 1.0);
    let mut rng = Rng(11);
    points.extend(outliers_around_the_unit_sphere(&mut rng, 50));
    let flags = statistical_outliers(&Neighbours::new(&points, 20), 2.0);
    let caught = flags[5000..].iter().filter(|&&f| f).count();
    let lost = flags[..5000].iter().filter(|&&f| f).count();
    assert!(caught >= 45, "{caught} of 50 outliers flagged");
    assert!(lost <= 50, "{lost} surface points flagged");
}

#[test]
fn a_sparsely_scanned_half_is_not_taken_for_outliers() {
    // One hemisphere scanned at a twentieth of the other's density, and 20 outliers around.
    let (dense, _) = sphere(20_000, [0.0; 3], 1.0);
    let mut rng = Rng(5);
    let mut points: Vec<[f64; 3]> = dense
        .into_iter()
        .filter(|p| p[2] < 0.0 || rng.next() < 1.0 / 20.0)
        .collect();
    let surface = points.len();
    let sparse = points.iter().filter(|p| p[2] >= 0.0).count();
    points.extend(outliers_around_the_unit_sphere(&mut rng, 20));
    let flags = statistical_outliers(&Neighbours::new(&points, 20), 2.5);
    let caught = flags[surface..].iter().filter(|&&f| f).count();
    let lost = (0..surface)
        .filter(|&i| flags[i] && points[i][2] >= 0.0)
        .count();
    assert!(caught >= 18, "{caught} of 20 outliers flagged");
    assert!(
        lost * 50 <= sparse,
        "{lost} of the sparse half's {sparse} points flagged"
    );
}

#[test]
fn degenerate_clouds_do_not_panic() {
    for points in [
        vec![],
        vec![[1.0, 2.0, 3.0]],
        vec![[0.0; 3]; 5],
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
    ] {
        let near = Neighbours::new(&points, 8);
        let normals = estimate_normals(&points, &near);
        let o = orient_normals(&points, &normals, &near);
        assert_eq!(o.normals.len(), points.len());
        assert_eq!(statistical_outliers(&near, 2.0).len(), near.len());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Neighbourhoods of some points only are the rows every point's would have, and the
    /// normal of one neighbourhood is the one estimated with all: what the noise measurement
    /// relies on when it grows neighbourhoods on a sample.
    #[test]
    fn some_points_neighbourhoods_are_those_of_all(
        seed in 1u64..1_000_000,
        k in 1usize..40,
        step in 1usize..9,
    ) {
        let mut rng = Rng(seed);
        // Points on a grid (ties in distance) and random ones, a few of them coincident.
        let mut points: Vec<[f64; 3]> = (0..300)
            .map(|i| if i % 3 == 0 {
                [(i % 7) as f64, (i / 7 % 5) as f64, 0.0]
            } else {
                [rng.next(), rng.next(), rng.next()]
            })
            .collect();
        points[17] = points[16];
        let tree = PointTree::new(&points);
        let all = Neighbours::with_tree(&tree, &points, k);
        let normals = estimate_normals(&points, &all);
        let which: Vec<usize> = (0..points.len()).step_by(step).collect();
        let some = Neighbours::of_some(&tree, &points, &which, k);
        prop_assert_eq!(some.len(), which.len());
        prop_assert_eq!(some.k(), all.k());
        for (r, &i) in which.iter().enumerate() {
            prop_assert_eq!(some.of(r), all.of(i));
            prop_assert_eq!(some.distances_of(r), all.distances_of(i));
            prop_assert_eq!(normal_of(&points, i, some.of(r)), normals[i]);
        }
    }

    /// Rotated, scaled, moved and noisy spheres come out outward (noise up to 1% of the radius).
    #[test]
    fn noisy_moved_spheres_come_out_outward(
        seed in 1u64..1_000_000,
        scale in 0.01f64..100.0,
        offset in prop::array::uniform3(-50.0f64..50.0),
        noise in 0.0f64..0.01,
    ) {
        let (unit, truth) = sphere(2500, [0.0; 3], 1.0);
        let mut rng = Rng(seed);
        // A random rotation from a random unit quaternion.
        let q = [rng.normal(), rng.normal(), rng.normal(), rng.normal()];
        let l = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        let [w, x, y, z] = q.map(|v| v / l);
        let r = [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)],
            [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)],
            [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
        ];
        let turn = |v: &[f64; 3]| -> [f64; 3] {
            core::array::from_fn(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
        };
        let points: Vec<[f64; 3]> = unit
            .iter()
            .map(|p| {
                let jitter = [rng.normal(), rng.normal(), rng.normal()];
                let q = turn(&[p[0] + noise * jitter[0], p[1] + noise * jitter[1], p[2] + noise * jitter[2]]);
                core::array::from_fn(|d| offset[d] + scale * q[d])
            })
            .collect();
        let truth: Vec<[f64; 3]> = truth.iter().map(turn).collect();
        let (normals, components) = oriented(&points, 12);
        prop_assert_eq!(components, 1);
        let share = share_outward(&normals, &truth);
        prop_assert!(share >= 0.995, "{}", share);
    }
}

/// A sphere whose given normals all point in, but whose farthest point's normal is nearly
/// tangent (as noise leaves it): the piece still comes out pointing out as a whole.
#[test]
fn a_piece_points_out_as_a_whole_whatever_its_seed_normal() {
    let (mut points, truth) = sphere(2000, [0.0; 3], 1.0);
    let mut given: Vec<[f64; 3]> = truth.iter().map(|t| [-t[0], -t[1], -t[2]]).collect();
    // The farthest point from the centroid, with a normal a hair outward of tangent.
    points[0] = truth[0].map(|c| 1.01 * c);
    let t = truth[0];
    let tangent = if t[0].abs() < 0.9 {
        [0.0, -t[2], t[1]]
    } else {
        [-t[1], t[0], 0.0]
    };
    let length = (tangent[0].powi(2) + tangent[1].powi(2) + tangent[2].powi(2)).sqrt();
    given[0] = core::array::from_fn(|k| tangent[k] / length + 0.01 * t[k]);
    let o = orient_normals(&points, &given, &Neighbours::new(&points, 10));
    let outward = o.normals[1..]
        .iter()
        .zip(&truth[1..])
        .filter(|(n, t)| n[0] * t[0] + n[1] * t[1] + n[2] * t[2] > 0.0)
        .count();
    assert_eq!(outward, truth.len() - 1);
}
