//! Keeping the mesh's topology (not in Yngve & Turk): their voxel error cannot see a gap or a
//! part thinner than a voxel, so the fitted surface may bridge two parts of the mesh that
//! nearly touch (a false handle, or two components merged) or cut through a thin part.
//!
//! Probes mark the middle of every thin gap and thin part of the mesh: from each vertex, the
//! mesh's inside test (winding numbers) is marched along the normal, outward for a gap and
//! inward for a part (and inward along the normals of the faces around a sharp vertex); where
//! it changes within `reach` (two voxels), the midpoint is a probe,
//! with its signed distance to the mesh. In every iteration of the loop, a probe on the wrong
//! side of the fitted surface becomes an exterior (gap) or interior (part) constraint beside the
//! loop's own, and a model that violates none is preferred. The returned surface is then
//! polygonized finely enough to resolve the narrowest gap found, and its genus and components
//! are compared with the mesh's.

use rayon::prelude::*;
use rbf_core::{Constraint, InterpolantView, Model};
use rbf_mesh::{
    MeshReport, PolygonizeSettings, Resolution, TriMesh, WindingTree, polygonize_continuation,
};

/// Cubes the surface may cross in the polygonization that measures its topology (about a
/// second's work for a model of a few thousand constraints).
const MAX_CUBES: f64 = 3e5;

/// The mesh's and the converted surface's topology, and the work of keeping it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TopologyReport {
    /// Genus of the mesh (Σ over components).
    pub goal_genus: i64,
    /// Connected components of the mesh.
    pub goal_components: usize,
    /// Genus of the converted surface, polygonized at `cell`; `None` if that mesh was not closed.
    pub genus: Option<i64>,
    /// Components of the converted surface.
    pub components: usize,
    /// Lattice cube of that polygonization, in the mesh's units.
    pub cell: f64,
    /// Probes found in thin gaps and thin parts of the mesh.
    pub probes: usize,
    /// Probes among the returned model's constraints.
    pub added: usize,
    /// Constraints added after the loop where the surface strayed more than a voxel from the
    /// mesh, or the mesh from the surface.
    pub polished: usize,
    /// Seconds spent finding probes and measuring the topology.
    pub seconds: f64,
}

impl TopologyReport {
    /// Whether the converted surface has the mesh's genus and components.
    pub fn agrees(&self) -> bool {
        self.genus == Some(self.goal_genus) && self.components == self.goal_components
    }

    /// How far the surface's topology is from the mesh's: the difference in genus plus the
    /// difference in components (a surface that is not closed counts as far as can be).
    pub(crate) fn difference(&self) -> u64 {
        match self.genus {
            Some(g) => {
                g.abs_diff(self.goal_genus) + self.components.abs_diff(self.goal_components) as u64
            }
            None => u64::MAX,
        }
    }
}

/// A point the surface must leave on its side: the middle of a thin gap (outside, value < 0) or
/// of a thin part (inside, value > 0), with its signed distance to the mesh as the value.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe {
    position: [f64; 3],
    value: f64,
}

/// Probes of the gaps and parts of the mesh narrower than `reach`, marched in steps of `step`
/// along [`probe_directions`] from the [`sampled_vertices`] of a lattice of cubes of side
/// `voxel` (where several share a cube, the one with the most directions), no two probes within
/// `spacing`.
pub(crate) fn thin_probes(
    mesh: &TriMesh,
    tree: &WindingTree,
    voxel: f64,
    reach: f64,
    step: f64,
    spacing: f64,
) -> Vec<Probe> {
    let directions = probe_directions(mesh);
    let origins = sampled_vertices(mesh, voxel, |v| directions[v].len());
    let found: Vec<Probe> = origins
        .par_iter()
        .map(|&v| (mesh.positions()[v], &directions[v]))
        .flat_map_iter(|(v, normals)| {
            // The vertex normal both ways (gaps and parts), the faces' inward (parts).
            normals.iter().enumerate().flat_map(move |(k, &n)| {
                let signs: &[f64] = if k == 0 { &[1.0, -1.0] } else { &[-1.0] };
                signs
                    .iter()
                    .filter_map(move |&sign| probe(tree, v, n, sign, reach, step))
            })
        })
        .collect();
    let positions: Vec<[f64; 3]> = found.iter().map(|p| p.position).collect();
    one_per_cube(&positions, spacing, |_| 0)
        .into_iter()
        .map(|i| found[i])
        .collect()
}

/// Vertices of a mesh cut finer than this many to a voxel's area of its surface (half a voxel
/// apart on average) are sampled, one in each cube of half a voxel.
const FINELY_CUT: f64 = 4.0;

/// The vertices of `mesh` that the loop probes and checks from, for a lattice of cubes of side
/// `voxel`: every one; or, on a mesh cut finer than the lattice resolves ([`FINELY_CUT`]), one
/// in each cube of half a voxel (the one that ranks highest by `rank`). What is probed and
/// checked then depends on the surface, not on how finely it is cut: the Nefertiti bust cut
/// four times finer (1.12·10⁶ triangles instead of 7·10⁴, 23 vertices to a voxel's area
/// instead of 1.4) was probed from every vertex in 12.9 s instead of 1.1 s, its 1706 probes
/// (523 from the coarse mesh) took a third of the loop's 4000 constraints, and it was
/// converted in 49 s to a loop RMS of 0.30 voxel; sampled, in 31 s to 0.16. Of the corpus's
/// meshes only the hammer (5.3) and the sword (12) are cut that finely; the others at most 1.8.
pub(crate) fn sampled_vertices(
    mesh: &TriMesh,
    voxel: f64,
    rank: impl Fn(usize) -> usize,
) -> Vec<usize> {
    let area: f64 = (0..mesh.triangles().len())
        .map(|t| 0.5 * rbf_core::vec3::norm(mesh.area_vector(t)))
        .sum();
    let vertices = mesh.positions().len();
    if (vertices as f64) * voxel * voxel > FINELY_CUT * area {
        one_per_cube(mesh.positions(), 0.5 * voxel, rank)
    } else {
        (0..vertices).collect()
    }
}

/// The indices of `positions`, one in each cube of side `cube` that holds any: the one that
/// ranks highest by `rank` (the first of those that tie), in the order of their cubes' first
/// positions.
pub(crate) fn one_per_cube(
    positions: &[[f64; 3]],
    cube: f64,
    rank: impl Fn(usize) -> usize,
) -> Vec<usize> {
    let mut chosen: Vec<usize> = Vec::new();
    let mut slot = std::collections::HashMap::new();
    for (i, p) in positions.iter().enumerate() {
        let key = p.map(|c| (c / cube).floor() as i64);
        match slot.entry(key) {
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(chosen.len());
                chosen.push(i);
            }
            std::collections::hash_map::Entry::Occupied(e) => {
                let held = &mut chosen[*e.get()];
                if rank(i) > rank(*held) {
                    *held = i;
                }
            }
        }
    }
    chosen
}

/// Cosine of the angle (30°) beyond which a face's normal is probed along as well as its
/// vertex's.
const OWN_DIRECTION: f64 = 0.87;

/// The directions each vertex is probed along: its normal (both ways), and inward the normal
/// of each triangle around it more than 30° from that and from the others taken. At a sharp
/// edge the vertex normal runs along a thin part rather than across it (the rim of a blade, a
/// wall's edge), and the part between the edges was probed only where a vertex lay on a flat
/// stretch of it: with these the cow keeps its genus (3 → 1; two tunnels through thin walls
/// of its head) and the sword its one piece on a second lattice. Outward along the faces
/// too, the blocky hand of `tests/topology.rs` (fingers 0.6 voxel apart) came out bridged.
fn probe_directions(mesh: &TriMesh) -> Vec<Vec<[f64; 3]>> {
    use rbf_core::vec3::{dot, normalize};
    let mut faces: Vec<Vec<[f64; 3]>> = vec![Vec::new(); mesh.positions().len()];
    for (t, triangle) in mesh.triangles().iter().enumerate() {
        let n = normalize(mesh.area_vector(t));
        for &v in triangle {
            faces[v as usize].push(n);
        }
    }
    mesh.vertex_normals()
        .into_iter()
        .zip(faces)
        .map(|(n, faces)| {
            let mut taken = vec![normalize(n)];
            for f in faces {
                if f.iter().all(|c| c.is_finite())
                    && taken.iter().all(|&t| dot(t, f) < OWN_DIRECTION)
                {
                    taken.push(f);
                }
            }
            taken
        })
        .collect()
}

/// The probe from vertex v along normal n, outward (`sign` 1) or inward (−1), if the mesh's
/// inside changes within `reach`.
fn probe(
    tree: &WindingTree,
    v: [f64; 3],
    n: [f64; 3],
    sign: f64,
    reach: f64,
    step: f64,
) -> Option<Probe> {
    let at = |t: f64| -> [f64; 3] { core::array::from_fn(|d| v[d] + sign * t * n[d]) };
    let inside = |t: f64| tree.winding_number(at(t)) > 0.5;
    let start_inside = sign < 0.0;
    if inside(0.25 * step) != start_inside {
        return None; // a normal that does not leave the surface cleanly (a sharp crease)
    }
    let (lo, hi) = first_change(inside, start_inside, reach, step, 8)?;
    // The gap (or part) ends at about (lo + hi) / 2: its middle is halfway there.
    let half = 0.25 * (lo + hi);
    if inside(half) != start_inside {
        return None;
    }
    let (_, distance) = tree.closest_point(at(half), hi)?;
    (distance > 0.05 * step).then_some(Probe {
        position: at(half),
        value: if start_inside { distance } else { -distance },
    })
}

/// Where `inside(t)` first differs from `start` for t in steps of `step` up to `reach`: the
/// bracket (lo, hi) around the change, narrowed by `halvings` bisections; `None` if it does
/// not change. The march of the probes here and of the rival's slabs.
pub(crate) fn first_change(
    inside: impl Fn(f64) -> bool,
    start: bool,
    reach: f64,
    step: f64,
    halvings: usize,
) -> Option<(f64, f64)> {
    let count = (reach / step).ceil() as usize;
    let k = (1..=count).find(|&k| inside(k as f64 * step) != start)?;
    let (mut lo, mut hi) = ((k - 1) as f64 * step, k as f64 * step);
    for _ in 0..halvings {
        let mid = 0.5 * (lo + hi);
        if inside(mid) == start {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((lo, hi))
}

/// How many probes are violated (on the wrong side of f's surface), and those of them not
/// within a tenth of a voxel of a constraint already there, as constraints.
pub(crate) fn fixes(
    f: &InterpolantView<'_, f64, 3>,
    probes: &[Probe],
    constraints: &[Constraint<3>],
    voxel: f64,
) -> (usize, Vec<Constraint<3>>) {
    let points: Vec<[f64; 3]> = probes.iter().map(|p| p.position).collect();
    let mut values = vec![0.0; points.len()];
    // Equal lengths by construction.
    let _ = f.par_values(&points, &mut values);
    let near = 0.1 * voxel;
    let mut taken = std::collections::HashSet::new();
    let key = |p: [f64; 3]| p.map(|c| (c / near).floor() as i64);
    for c in constraints {
        taken.insert(key(c.position));
    }
    let violated: Vec<&Probe> = probes
        .iter()
        .zip(values)
        .filter(|(p, v)| (p.value < 0.0 && *v >= 0.0) || (p.value > 0.0 && *v <= 0.0))
        .map(|(p, _)| p)
        .collect();
    let new = violated
        .iter()
        .filter(|p| taken.insert(key(p.position)))
        .map(|p| {
            if p.value > 0.0 {
                Constraint::interior(p.position, p.value)
            } else {
                Constraint::exterior(p.position, p.value)
            }
        })
        .collect();
    (violated.len(), new)
}

/// The mesh's topology (from its `checked` report) and the model's: the model polygonized
/// finely enough to resolve the narrowest gap or part among `probes`; and that polygonization.
pub(crate) fn measure(
    mesh: &TriMesh,
    checked: &MeshReport,
    model: &Model<3>,
    probes: &[Probe],
    voxel: f64,
    added: usize,
) -> (TopologyReport, Option<TriMesh>) {
    let start = std::time::Instant::now();
    let cell = measure_cell(mesh, probes, voxel);
    let (genus, components, surface) = surface_topology(model, cell, voxel);
    let report = TopologyReport {
        goal_genus: checked.genus.unwrap_or(0),
        goal_components: checked.components,
        genus,
        components,
        cell,
        probes: probes.len(),
        added,
        polished: 0,
        seconds: start.elapsed().as_secs_f64(),
    };
    (report, surface)
}

/// The cube of [`measure`]'s polygonization: half a voxel, or finer to put two cubes across the
/// narrowest gap or part found (down to a quarter voxel), as long as the surface crosses at most
/// [`MAX_CUBES`] cubes.
pub(crate) fn measure_cell(mesh: &TriMesh, probes: &[Probe], voxel: f64) -> f64 {
    let narrowest = probes
        .iter()
        .map(|p| 2.0 * p.value.abs())
        .fold(f64::INFINITY, f64::min);
    let area: f64 = (0..mesh.triangles().len())
        .map(|t| 0.5 * rbf_core::vec3::norm(mesh.area_vector(t)))
        .sum();
    let affordable = (area / MAX_CUBES).sqrt();
    (0.5 * narrowest)
        .clamp(0.25 * voxel, 0.5 * voxel)
        .max(affordable.min(0.5 * voxel))
}

/// Genus and components of the model's surface, polygonized by continuation from its boundary
/// constraints at `cell`.
fn surface_topology(
    model: &Model<3>,
    cell: f64,
    voxel: f64,
) -> (Option<i64>, usize, Option<TriMesh>) {
    // Vertices where f's linear interpolation along each crossed edge is zero: the topology of
    // f's signs at the lattice points, within a small fraction of a cube of the surface (0.15
    // at most in rbf-mesh's tests; the polish asks only whether they are a voxel off), in about
    // half the time of root finding (the falcon statue at cubes of 0.27 voxel: 2.6–3.0 s
    // instead of 5.0–5.4 for each of its three measures).
    let settings = PolygonizeSettings {
        resolution: Resolution::CellSize(cell),
        root_iterations: 0,
        simplify: false,
        ..Default::default()
    };
    let f = model.interpolant.view();
    // Seeds on every component: the constraints on the surface, and the vertices of a grid
    // polygonization of the whole box at two voxels (which finds pieces that touch no
    // constraint, such as a stray blob, down to about that size).
    let mut seeds = rbf_mesh::surface_seeds(model);
    let coarse = PolygonizeSettings {
        resolution: Resolution::CellSize(2.0 * voxel),
        root_iterations: 0,
        simplify: false,
        ..Default::default()
    };
    if let Ok((mesh, _)) = rbf_mesh::polygonize_grid(&f, &coarse) {
        seeds.extend(mesh.positions().iter().step_by(8));
    }
    match polygonize_continuation(&f, &seeds, &settings) {
        Ok((mesh, _)) => match mesh.closed_topology() {
            Some((genus, components)) => (Some(genus), components, Some(mesh)),
            None => {
                let r = mesh.check();
                (r.genus, r.components, Some(mesh))
            }
        },
        Err(_) => (None, 0, None),
    }
}

/// The model's surface polygonized at `cell` by continuation from its boundary constraints and
/// `seeds` only (without the search of the whole box that [`measure`] makes for stray pieces):
/// for where it strays from the mesh, not for its topology.
pub(crate) fn surface_near(model: &Model<3>, cell: f64, seeds: &[[f64; 3]]) -> Option<TriMesh> {
    let settings = PolygonizeSettings {
        resolution: Resolution::CellSize(cell),
        root_iterations: 0,
        simplify: false,
        ..Default::default()
    };
    let mut all = rbf_mesh::surface_seeds(model);
    all.extend_from_slice(seeds);
    polygonize_continuation(&model.interpolant.view(), &all, &settings)
        .ok()
        .map(|(mesh, _)| mesh)
}

#[cfg(test)]
mod tests {
    use super::{TopologyReport, one_per_cube, probe_directions, sampled_vertices};
    use rbf_mesh::TriMesh;

    #[test]
    fn one_vertex_per_cube_the_highest_ranked_whatever_the_tessellation() {
        let positions = [
            [0.1, 0.1, 0.1],
            [0.2, 0.3, 0.4],
            [1.5, 0.2, 0.2],
            [0.9, 0.9, 0.9],
        ];
        // Cubes of side 1: the first, second and fourth share one; the second ranks highest.
        let rank = [1, 3, 0, 2];
        assert_eq!(one_per_cube(&positions, 1.0, |i| rank[i]), vec![1, 2]);
        assert_eq!(one_per_cube(&positions, 1.0, |_| 0), vec![0, 2]);
        // A sphere cut four times finer has four times the vertices, and as many cubes.
        let (coarse, fine) = (TriMesh::icosphere(4), TriMesh::icosphere(5));
        assert!(fine.positions().len() > 3 * coarse.positions().len());
        let per_cube = |m: &TriMesh| one_per_cube(m.positions(), 0.2, |_| 0).len() as f64;
        let (a, b) = (per_cube(&coarse), per_cube(&fine));
        assert!((b / a - 1.0).abs() < 0.05, "{a} cubes against {b}");
        // Against a lattice of 0.1 (the unit sphere's area is 4π: 1257 voxels' worth), the
        // coarse sphere (2562 vertices) is not cut finer than it resolves and keeps every
        // vertex; the fine one (10242, 8 to a voxel's area) is sampled, one per half voxel.
        assert_eq!(
            sampled_vertices(&coarse, 0.1, |_| 0).len(),
            coarse.positions().len()
        );
        let sampled = sampled_vertices(&fine, 0.1, |_| 0).len();
        assert_eq!(sampled, one_per_cube(fine.positions(), 0.05, |_| 0).len());
        assert!(sampled < fine.positions().len() * 3 / 5, "{sampled}");
    }

    #[test]
    fn a_sharp_vertex_is_probed_along_its_faces_too() {
        // A tetrahedron: every vertex is sharp, its three faces each more than 30° from its
        // normal; an icosphere's vertices are smooth, its faces within 30° of their normals.
        let tetrahedron = TriMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
        .unwrap();
        let directions = probe_directions(&tetrahedron);
        assert!(directions.iter().all(|d| d.len() == 4), "{directions:?}");
        // Each face normal of the corner at the origin is an axis, pointing out.
        let corner = &directions[0];
        for axis in 0..3 {
            assert!(corner[1..].iter().any(|n| (n[axis] + 1.0).abs() < 1e-12));
        }
        let smooth = probe_directions(&TriMesh::icosphere(3));
        assert!(smooth.iter().all(|d| d.len() == 1));
    }

    fn report(genus: Option<i64>, components: usize) -> TopologyReport {
        TopologyReport {
            goal_genus: 2,
            goal_components: 1,
            genus,
            components,
            cell: 0.1,
            probes: 0,
            added: 0,
            polished: 0,
            seconds: 0.0,
        }
    }

    #[test]
    fn difference_counts_handles_and_pieces_either_way() {
        assert_eq!(report(Some(2), 1).difference(), 0);
        assert!(report(Some(2), 1).agrees());
        // A handle gained or lost, a piece gained: each counts one.
        assert_eq!(report(Some(3), 1).difference(), 1);
        assert_eq!(report(Some(1), 1).difference(), 1);
        assert_eq!(report(Some(1), 2).difference(), 2);
        assert_eq!(report(Some(0), 3).difference(), 4);
        // A surface that did not close is farther than any closed one.
        assert!(report(None, 1).difference() > report(Some(40), 9).difference());
    }
}
