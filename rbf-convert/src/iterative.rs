//! The iterative conversion of Yngve & Turk (2002), §3–§5: voxelize the mesh, then fit,
//! measure the two-way error between the goal's and the current surface's boundary voxels, and
//! add constraints where it is largest, until the surface is within a voxel of the goal.

use std::collections::HashMap;
use std::time::Instant;

use rayon::prelude::*;
use rbf_core::{Constraint, FitSettings, Model};
use rbf_mesh::{
    TriMesh, Volume, VoxelMethod, VoxelSettings, WindingTree, classify_blocks, has_other_neighbour,
    signed_distance, squared_distance_transform, voxelize,
};

use crate::nearest::VoxelBins;
use crate::{ConvertError, poisson_subset};

/// Every parameter of the paper, with its value as the default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterativeSettings {
    /// Voxels along the longest side of the mesh's bounding box.
    pub resolution: usize,
    /// Empty voxels around the box.
    pub margin: usize,
    /// Sub-samples per voxel axis for the densities.
    pub supersampling: usize,
    /// Inside test of the voxelizer (rays for watertight meshes, winding numbers otherwise).
    pub voxel_method: VoxelMethod,
    /// Boundary constraints placed before the first fit (§5.1): 50.
    pub initial_constraints: usize,
    /// Stop when the maximum error is at most this many voxels (§5.4): 1.
    pub target_error: f64,
    /// Stop after this many iterations without improvement (§5.4): 4.
    pub patience: usize,
    /// Stop after this many iterations (§5.4): 30.
    pub max_iterations: usize,
    /// Stop at this many constraints (§5.4): 5000.
    pub max_constraints: usize,
    /// Spacing of the coarse evaluation lattice in voxels (§5.2): 4.
    pub coarse_step: usize,
    /// Blocks within this many voxels of the goal's boundary are evaluated finely (§5.2): 8.
    pub shell: f64,
    /// Candidates nearer than this many voxels to a constraint are discarded (§5.3): 1.
    pub min_spacing: f64,
    /// Candidates with less than this fraction of the iteration's maximum error are
    /// discarded (§5.3): 0.5.
    pub error_fraction: f64,
    /// Regularization λ of every fit (Yngve & Turk 2002, §6.3).
    pub lambda: f64,
    /// Blocks of the shell whose corners agree in sign and stand farther from f = 0 than 1.5
    /// half-diagonals of the block, by the first-order estimate |f| / |∇f| at every corner, are
    /// filled without evaluating them voxel by voxel: every point of a block is within half a
    /// diagonal of a corner (not in the paper, whose thick shell took most of its time). true.
    pub gradient_skip: bool,
    /// At most this fraction of the current constraint count is added in one iteration (not in
    /// the paper, which adds every candidate that survives pruning: near the end that can
    /// triple the count in one step). 0.3.
    pub max_growth: f64,
}

impl Default for IterativeSettings {
    fn default() -> Self {
        Self {
            resolution: 128,
            margin: 3,
            supersampling: 4,
            voxel_method: VoxelMethod::Auto,
            initial_constraints: 50,
            target_error: 1.0,
            patience: 4,
            max_iterations: 30,
            max_constraints: 5000,
            coarse_step: 4,
            shell: 8.0,
            min_spacing: 1.0,
            error_fraction: 0.5,
            lambda: 0.0,
            max_growth: 0.3,
            gradient_skip: true,
        }
    }
}

/// Constraint counts, boundary errors and timings of one fit-and-refine iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterationReport {
    /// 1-based iteration.
    pub iteration: usize,
    /// Boundary constraints fitted this iteration.
    pub boundary: usize,
    /// Interior constraints fitted this iteration.
    pub interior: usize,
    /// Exterior constraints fitted this iteration.
    pub exterior: usize,
    /// Two-way Hausdorff error between the boundary voxels, in voxels (equation 6).
    pub max_error: f64,
    /// Root-mean-square of the same errors, in voxels.
    pub rms_error: f64,
    /// Seconds solving this iteration's fit.
    pub fit_seconds: f64,
    /// Seconds evaluating f over the volume.
    pub evaluate_seconds: f64,
    /// Seconds computing distances and errors.
    pub distance_seconds: f64,
    /// Seconds choosing new constraints.
    pub select_seconds: f64,
}

/// The goal volume, every iteration's figures, and which iteration's model was returned.
#[derive(Clone, Debug, PartialEq)]
pub struct IterativeReport {
    /// Voxels along x, y, z of the goal volume, margin included.
    pub shape: [usize; 3],
    /// Edge length of a voxel, in the mesh's units.
    pub voxel_size: f64,
    /// Whether the mesh passed the watertightness check (else winding numbers were used).
    pub watertight: bool,
    /// Every iteration run, in order (the first has `iteration` 1).
    pub iterations: Vec<IterationReport>,
    /// The iteration whose model is returned (lowest maximum, then RMS error).
    pub best: usize,
}

/// Converts a mesh by the iterative method; `progress` hears of every iteration.
pub fn convert_iterative(
    mesh: &TriMesh,
    settings: &IterativeSettings,
    mut progress: impl FnMut(&IterationReport),
) -> Result<(Model<3>, IterativeReport), ConvertError> {
    let watertight = mesh.check().is_watertight();
    let density = voxelize(
        mesh,
        &VoxelSettings {
            resolution: settings.resolution,
            margin: settings.margin,
            supersampling: settings.supersampling,
            method: settings.voxel_method,
            memory_limit: rbf_solve::memory_budget(),
        },
    )
    .map_err(|e| ConvertError::Mesh(e.to_string()))?;
    // The goal's inside is the class of each voxel's centre, the same test the current surface
    // gets, so that the mesh itself would score zero; the densities give sub-voxel distances.
    let centres = voxelize(
        mesh,
        &VoxelSettings {
            resolution: settings.resolution,
            margin: settings.margin,
            supersampling: 1,
            method: settings.voxel_method,
            memory_limit: rbf_solve::memory_budget(),
        },
    )
    .map_err(|e| ConvertError::Mesh(e.to_string()))?;
    let goal = Goal::new(&density, &centres, WindingTree::new(mesh))?;
    let fit_settings = FitSettings {
        lambda: settings.lambda,
        ..Default::default()
    };
    let mut constraints = goal.initial(settings);
    let mut report = IterativeReport {
        shape: density.shape,
        voxel_size: density.voxel_size,
        watertight,
        iterations: Vec::new(),
        best: 0,
    };
    let mut best: Option<(f64, f64, Model<3>)> = None;
    let mut since_best = 0;
    for iteration in 1..=settings.max_iterations {
        let t = Instant::now();
        let fit = rbf_solve::fit(&constraints, &fit_settings)?;
        let fit_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let inside = goal.evaluate(&fit.interpolant.view(), settings);
        let evaluate_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let errors = goal.errors(&inside);
        let (max_error, rms_error) = summary(&errors);
        let distance_seconds = t.elapsed().as_secs_f64();
        let model = Model {
            constraints: constraints.clone(),
            settings: fit_settings,
            interpolant: fit.interpolant,
            report: Some(fit.report),
        };
        let better = best
            .as_ref()
            .is_none_or(|(m, r, _)| (max_error, rms_error) < (*m, *r));
        if better {
            best = Some((max_error, rms_error, model));
            report.best = iteration;
            since_best = 0;
        } else {
            since_best += 1;
        }
        let count = |k| {
            constraints
                .iter()
                .filter(|c: &&Constraint<3>| c.kind == k)
                .count()
        };
        let (boundary, interior, exterior) = (
            count(rbf_core::ConstraintKind::Boundary),
            count(rbf_core::ConstraintKind::Interior),
            count(rbf_core::ConstraintKind::Exterior),
        );
        let t = Instant::now();
        let done = max_error <= settings.target_error
            || since_best >= settings.patience
            || iteration == settings.max_iterations
            || constraints.len() >= settings.max_constraints;
        let added = if done {
            0
        } else {
            goal.refine(&errors, &mut constraints, settings)
        };
        let it = IterationReport {
            iteration,
            boundary,
            interior,
            exterior,
            max_error,
            rms_error,
            fit_seconds,
            evaluate_seconds,
            distance_seconds,
            select_seconds: t.elapsed().as_secs_f64(),
        };
        progress(&it);
        report.iterations.push(it);
        if done || added == 0 {
            break;
        }
    }
    let (_, _, model) = best.ok_or(ConvertError::Mesh("no iteration ran".into()))?;
    Ok((model, report))
}

fn summary(errors: &[(usize, f64, bool)]) -> (f64, f64) {
    let max = errors.iter().map(|e| e.1).fold(0.0, f64::max);
    let rms = (errors.iter().map(|e| e.1 * e.1).sum::<f64>() / errors.len().max(1) as f64).sqrt();
    (max, rms)
}

/// The goal volume and what is known of it.
struct Goal {
    shape: [usize; 3],
    origin: [f64; 3],
    h: f64,
    /// Signed distance to the goal surface, in voxels, positive inside.
    sd: Vec<f64>,
    /// Boundary voxels of the goal.
    boundary: Vec<usize>,
    /// Distance from each voxel to the nearest goal boundary voxel, in voxels.
    to_boundary: Vec<f64>,
    /// The mesh, for placing boundary constraints exactly on it.
    mesh: WindingTree,
}

impl Goal {
    /// The goal from the mesh's densities, the class of each voxel centre (density 1 inside)
    /// and the mesh.
    fn new(
        density: &Volume<f32>,
        centres: &Volume<f32>,
        mesh: WindingTree,
    ) -> Result<Self, ConvertError> {
        let shape = density.shape;
        let inside: Vec<bool> = centres.data.iter().map(|&d| d >= 0.5).collect();
        // Densities whose class agrees with the centres', for a signed distance of the same sign.
        let mut density = density.clone();
        for (d, &i) in density.data.iter_mut().zip(&inside) {
            *d = if i { d.max(0.5) } else { d.min(0.499) };
        }
        let density = &density;
        if !inside.iter().any(|&b| b) {
            return Err(ConvertError::Mesh(
                "no voxel is inside the mesh: it is flat or open, or the resolution is too coarse to hold its interior".into(),
            ));
        }
        let sd_volume = signed_distance(density);
        let h = density.voxel_size;
        let sd: Vec<f64> = sd_volume.data.iter().map(|&v| v as f64 / h).collect();
        let boundary = boundary_voxels(shape, &inside);
        let to_boundary = distance_to(shape, &boundary);
        Ok(Self {
            shape,
            origin: density.origin,
            h,
            sd,
            boundary,
            to_boundary,
            mesh,
        })
    }

    fn coords(&self, v: usize) -> [usize; 3] {
        let [_, ny, nz] = self.shape;
        [v / (ny * nz), (v / nz) % ny, v % nz]
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[0] * self.shape[1] + c[1]) * self.shape[2] + c[2]
    }

    /// The model-space point at fractional voxel coordinates.
    fn point(&self, c: [f64; 3]) -> [f64; 3] {
        core::array::from_fn(|d| self.origin[d] + self.h * c[d])
    }

    /// ∇sd at a voxel by central differences (one-sided at the border), in voxels per voxel.
    fn gradient(&self, c: [usize; 3]) -> [f64; 3] {
        core::array::from_fn(|d| {
            let mut lo = c;
            let mut hi = c;
            if c[d] > 0 {
                lo[d] -= 1;
            }
            if c[d] + 1 < self.shape[d] {
                hi[d] += 1;
            }
            let span = (hi[d] - lo[d]).max(1) as f64;
            (self.sd[self.index(hi)] - self.sd[self.index(lo)]) / span
        })
    }

    /// The goal surface near boundary voxel v: the point of the mesh nearest to the voxel's
    /// centre (within two voxels), else, with the sub-voxel precision of the densities as in the
    /// paper, the centre moved along ∇sd to where sd = 0 (at most one voxel).
    fn surface_point(&self, v: usize) -> [f64; 3] {
        let c = self.coords(v);
        let centre = self.point(c.map(|x| x as f64));
        if let Some((q, _)) = self.mesh.closest_point(centre, 2.0 * self.h) {
            return q;
        }
        let g = self.gradient(c);
        let g2: f64 = g.iter().map(|x| x * x).sum();
        // One Newton step toward sd = 0, moving at most one voxel.
        let step = if g2 > 0.0 { -self.sd[v] / g2 } else { 0.0 };
        let length = (step * step * g2).sqrt();
        let scale = if length > 1.0 { step / length } else { step };
        self.point(core::array::from_fn(|d| c[d] as f64 + scale * g[d]))
    }

    /// The goal's signed distance at voxel v (centre p), positive inside: the distance to the
    /// mesh itself, signed by the voxel's class (the paper's sd_goal from densities when the
    /// mesh is farther than the volume is wide).
    fn signed_distance(&self, v: usize, p: [f64; 3]) -> f64 {
        let reach = self.h * self.shape.iter().sum::<usize>() as f64;
        match self.mesh.closest_point(p, reach) {
            Some((_, d)) if self.sd[v] >= 0.0 => d,
            Some((_, d)) => -d,
            None => self.sd[v] * self.h,
        }
    }

    /// §5.1: Poisson-disk boundary constraints on the goal boundary, and for each an interior
    /// or exterior constraint at the end of the longer gradient path of sd.
    fn initial(&self, settings: &IterativeSettings) -> Vec<Constraint<3>> {
        let centres: Vec<[f64; 3]> = self
            .boundary
            .iter()
            .map(|&v| self.coords(v).map(|x| x as f64))
            .collect();
        let chosen = poisson_subset(&centres, settings.initial_constraints);
        let mut constraints = Vec::new();
        let mut grid = Spacing::new(settings.min_spacing);
        for &i in &chosen {
            let v = self.boundary[i];
            let p = self.surface_point(v);
            let pv = self.to_voxels(p);
            if grid.free(pv, settings.min_spacing) {
                grid.add(pv);
                constraints.push(Constraint::boundary(p));
            }
            let (end, length_up) = self.walk(self.coords(v), 1.0);
            let (end_down, length_down) = self.walk(self.coords(v), -1.0);
            let end = if length_down > length_up {
                end_down
            } else {
                end
            };
            let e = self.index(end);
            let ev = end.map(|x| x as f64);
            let value = self.signed_distance(e, self.point(ev));
            if value != 0.0 && grid.free(ev, settings.min_spacing) {
                grid.add(ev);
                let p = self.point(ev);
                constraints.push(if value > 0.0 {
                    Constraint::interior(p, value)
                } else {
                    Constraint::exterior(p, value)
                });
            }
        }
        constraints
    }

    /// Follows ∇sd (direction +1 uphill, −1 downhill) voxel by voxel to a local extremum or the
    /// volume's edge; returns the end and the path length (the edge counts as longest).
    fn walk(&self, start: [usize; 3], direction: f64) -> ([usize; 3], f64) {
        let mut c = start;
        let mut length = 0.0;
        for _ in 0..(self.shape.iter().sum::<usize>() * 2) {
            let mut best = c;
            let mut best_value = direction * self.sd[self.index(c)];
            for n in 0..27 {
                let off = [n % 3, (n / 3) % 3, n / 9];
                let next: Option<[usize; 3]> = (0..3)
                    .map(|d| {
                        (c[d] + off[d])
                            .checked_sub(1)
                            .filter(|&x| x < self.shape[d])
                    })
                    .collect::<Option<Vec<usize>>>()
                    .map(|v| [v[0], v[1], v[2]]);
                if let Some(q) = next {
                    let value = direction * self.sd[self.index(q)];
                    if value > best_value {
                        best_value = value;
                        best = q;
                    }
                }
            }
            if best == c {
                break;
            }
            length += (0..3)
                .map(|d| (best[d] as f64 - c[d] as f64).powi(2))
                .sum::<f64>()
                .sqrt();
            c = best;
            let at_edge = (0..3).any(|d| c[d] == 0 || c[d] + 1 == self.shape[d]);
            if at_edge {
                return (c, f64::INFINITY);
            }
        }
        (c, length)
    }

    fn to_voxels(&self, p: [f64; 3]) -> [f64; 3] {
        core::array::from_fn(|d| (p[d] - self.origin[d]) / self.h)
    }

    /// §5.2: inside (f > 0) at every voxel: sampled at every `coarse_step`-th voxel, and voxel by
    /// voxel in blocks whose corners disagree or that lie within `shell` voxels of the goal.
    fn evaluate(
        &self,
        f: &rbf_core::InterpolantView<'_, f64, 3>,
        settings: &IterativeSettings,
    ) -> Vec<bool> {
        let s = settings.coarse_step.max(1);
        let [nx, ny, nz] = self.shape;
        let blocks = [nx.div_ceil(s), ny.div_ceil(s), nz.div_ceil(s)];
        let corner = |b: usize, d: usize| (b * s).min(self.shape[d] - 1);
        let cn = [blocks[0] + 1, blocks[1] + 1, blocks[2] + 1];
        let coarse_points: Vec<[f64; 3]> = (0..cn[0] * cn[1] * cn[2])
            .map(|i| {
                let b = [i / (cn[1] * cn[2]), (i / cn[2]) % cn[1], i % cn[2]];
                self.point(core::array::from_fn(|d| corner(b[d], d) as f64))
            })
            .collect();
        let mut coarse = vec![0.0; coarse_points.len()];
        let mut gradients = vec![[0.0; 3]; coarse_points.len()];
        // Equal lengths by construction.
        let _ = f.par_values_and_gradients(&coarse_points, &mut coarse, &mut gradients);
        // How far, in model units, f must be from zero at every corner for a block to be skipped.
        let reach = 1.5 * 0.5 * (3.0_f64).sqrt() * s as f64 * self.h;
        classify_blocks(self.shape, s, |bi, lo, hi| {
            let corners = (0..8).map(|k| {
                let c = [bi[0] + (k & 1), bi[1] + ((k >> 1) & 1), bi[2] + (k >> 2)];
                (c[0] * cn[1] + c[1]) * cn[2] + c[2]
            });
            let positive = corners.clone().filter(|&c| coarse[c] > 0.0).count();
            let clear = settings.gradient_skip
                && corners.clone().all(|c| {
                    let g = gradients[c];
                    coarse[c].abs() > reach * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt()
                });
            let centre = core::array::from_fn(|d| (lo[d] + hi[d]) / 2);
            let near = self.to_boundary[self.index(centre)] <= settings.shell + s as f64;
            let count = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
            if (!near || clear) && (positive == 0 || positive == 8) {
                return vec![positive == 8; count];
            }
            let mut points = Vec::with_capacity(count);
            for i in lo[0]..hi[0] {
                for j in lo[1]..hi[1] {
                    for k in lo[2]..hi[2] {
                        points.push(self.point([i as f64, j as f64, k as f64]));
                    }
                }
            }
            let mut values = vec![0.0; count];
            let _ = f.values(&points, &mut values);
            values.into_iter().map(|v| v > 0.0).collect()
        })
    }

    /// Equation (7)'s errors: (voxel, error in voxels, is a goal boundary voxel) for every goal
    /// boundary voxel (its distance to the current boundary) and every current boundary voxel
    /// (its distance to the goal boundary).
    fn errors(&self, inside: &[bool]) -> Vec<(usize, f64, bool)> {
        let current = boundary_voxels(self.shape, inside);
        let to_current = VoxelBins::new(self.shape, &current).distances(self.shape, &self.boundary);
        let mut errors: Vec<(usize, f64, bool)> = self
            .boundary
            .iter()
            .zip(to_current)
            .map(|(&v, d)| (v, d, true))
            .collect();
        errors.extend(current.iter().map(|&v| (v, self.to_boundary[v], false)));
        errors
    }

    /// §5.3: new constraints at the largest errors, pruned. Returns how many were added.
    fn refine(
        &self,
        errors: &[(usize, f64, bool)],
        constraints: &mut Vec<Constraint<3>>,
        settings: &IterativeSettings,
    ) -> usize {
        let (max, _) = summary(errors);
        let mut candidates: Vec<&(usize, f64, bool)> = errors
            .iter()
            .filter(|e| e.1 >= settings.error_fraction * max && e.1 > 0.0)
            .collect();
        // Largest error first; in a tie, the goal's boundary first.
        candidates.sort_by(|a, b| b.1.total_cmp(&a.1).then(b.2.cmp(&a.2)));
        let mut grid = Spacing::new(settings.min_spacing);
        for c in constraints.iter() {
            grid.add(self.to_voxels(c.position));
        }
        let mut added: Vec<([f64; 3], f64)> = Vec::new();
        let growth = (settings.max_growth * constraints.len() as f64).max(1.0);
        let limit = settings
            .max_constraints
            .min(constraints.len().saturating_add(growth as usize));
        for &&(v, error, from_goal) in &candidates {
            if constraints.len() >= limit {
                break;
            }
            let at = self.coords(v).map(|x| x as f64);
            if added.iter().any(|(p, e)| dist(*p, at) < 2.0 * e) {
                continue;
            }
            let constraint = if from_goal {
                let p = self.surface_point(v);
                Constraint::boundary(p)
            } else {
                let p = self.point(at);
                let value = self.signed_distance(v, p);
                if value == 0.0 {
                    continue;
                }
                if value > 0.0 {
                    Constraint::interior(p, value)
                } else {
                    Constraint::exterior(p, value)
                }
            };
            let pv = self.to_voxels(constraint.position);
            if !grid.free(pv, settings.min_spacing) {
                continue;
            }
            grid.add(pv);
            added.push((at, error));
            constraints.push(constraint);
        }
        added.len()
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>()).sqrt()
}

/// Voxels with a face neighbour of the other class.
fn boundary_voxels(shape: [usize; 3], inside: &[bool]) -> Vec<usize> {
    let [_, ny, nz] = shape;
    (0..inside.len())
        .into_par_iter()
        .filter(|&v| {
            let c = (v / (ny * nz), (v / nz) % ny, v % nz);
            has_other_neighbour(shape, c, |i, j, k| inside[(i * ny + j) * nz + k])
        })
        .collect()
}

/// Exact distance (in voxels) from every voxel to the nearest of `sources`.
fn distance_to(shape: [usize; 3], sources: &[usize]) -> Vec<f64> {
    let mut cost = vec![f64::INFINITY; shape[0] * shape[1] * shape[2]];
    for &s in sources {
        cost[s] = 0.0;
    }
    squared_distance_transform(shape, &mut cost);
    cost.into_iter().map(f64::sqrt).collect()
}

/// A spatial hash of constraint positions (in voxels) for the spacing rule.
struct Spacing {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<[f64; 3]>>,
}

impl Spacing {
    fn new(cell: f64) -> Self {
        Self {
            cell: cell.max(1e-9),
            cells: HashMap::new(),
        }
    }
    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|x| (x / self.cell).floor() as i64)
    }
    fn add(&mut self, p: [f64; 3]) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push(p);
    }
    fn free(&self, p: [f64; 3], spacing: f64) -> bool {
        let k = self.key(p);
        let reach = (spacing / self.cell).ceil() as i64;
        for dx in -reach..=reach {
            for dy in -reach..=reach {
                for dz in -reach..=reach {
                    if let Some(list) = self.cells.get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                        && list.iter().any(|q| dist(*q, p) < spacing)
                    {
                        return false;
                    }
                }
            }
        }
        true
    }
}
