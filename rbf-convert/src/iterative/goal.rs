//! The goal of the iterative conversion (Yngve & Turk 2002, §4–§5): a volume of the shape's
//! inside, its signed distance and boundary voxels, and what the loop asks of it: where to put
//! the first constraints (§5.1), where f is positive (§5.2), the two-way boundary error
//! (equation 7) and the next constraints (§5.3). A 2D goal is a volume one voxel thick in z.

use std::collections::HashMap;

use rayon::prelude::*;
use rbf_core::Constraint;
use rbf_mesh::{
    Volume, WindingTree, classify_blocks, has_other_neighbour, signed_distance,
    squared_distance_transform,
};

use super::nearest::VoxelBins;
use crate::{ConvertError, IterativeSettings, poisson_subset};

/// The first `D` coordinates of a goal point: the model's point (z dropped in 2D).
fn flat<const D: usize>(p: [f64; 3]) -> [f64; D] {
    core::array::from_fn(|d| p[d])
}

/// A model's point as a goal point (z = 0 in 2D, where the goal's one voxel layer lies).
fn lift<const D: usize>(p: [f64; D]) -> [f64; 3] {
    core::array::from_fn(|d| if d < D { p[d] } else { 0.0 })
}

/// The largest and the root-mean-square error of an iteration, in voxels.
pub(crate) fn summary(errors: &[(usize, f64, bool)]) -> (f64, f64) {
    let max = errors.iter().map(|e| e.1).fold(0.0, f64::max);
    let rms = (errors.iter().map(|e| e.1 * e.1).sum::<f64>() / errors.len().max(1) as f64).sqrt();
    (max, rms)
}

/// The goal volume and what is known of it.
pub(crate) struct Goal {
    /// Voxels along x, y, z (z is 1 for a 2D goal).
    pub(crate) shape: [usize; 3],
    /// The centre of voxel (0, 0, 0).
    origin: [f64; 3],
    /// The edge of a voxel, in model units.
    pub(crate) h: f64,
    /// Signed distance to the goal surface, in voxels, positive inside.
    sd: Vec<f64>,
    /// Boundary voxels of the goal.
    boundary: Vec<usize>,
    /// Distance from each voxel to the nearest goal boundary voxel, in voxels.
    to_boundary: Vec<f64>,
    /// The mesh, for placing boundary constraints exactly on it; `None` for a goal given only
    /// by its inside (the 2D conversion), placed by the densities alone.
    mesh: Option<WindingTree>,
}

impl Goal {
    /// The goal from the mesh's densities, the class of each voxel centre (density 1 inside)
    /// and the mesh.
    pub(crate) fn new(
        density: &Volume<f32>,
        centres: &Volume<f32>,
        mesh: Option<WindingTree>,
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
            return Err(ConvertError::EmptyGoal);
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

    /// The mesh's winding tree, when the goal was made from a mesh.
    pub(crate) fn tree(&self) -> Option<&WindingTree> {
        self.mesh.as_ref()
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
        let on_mesh = (self.mesh.as_ref()).and_then(|m| m.closest_point(centre, 2.0 * self.h));
        if let Some((q, _)) = on_mesh {
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
        match (self.mesh.as_ref()).and_then(|m| m.closest_point(p, reach)) {
            Some((_, d)) if self.sd[v] >= 0.0 => d,
            Some((_, d)) => -d,
            None => self.sd[v] * self.h,
        }
    }

    /// §5.1: Poisson-disk boundary constraints on the goal boundary, and for each an interior
    /// or exterior constraint at the end of the longer gradient path of sd.
    pub(crate) fn initial<const D: usize>(
        &self,
        settings: &IterativeSettings,
    ) -> Vec<Constraint<D>> {
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
                constraints.push(Constraint::boundary(flat(p)));
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
                let p = flat(self.point(ev));
                constraints.push(if value > 0.0 {
                    Constraint::interior(p, value)
                } else {
                    Constraint::exterior(p, value)
                });
            }
        }
        constraints
    }

    /// Exterior constraints where f is positive outside the volume, which the loop's voxels
    /// never see: the cubic kernel's f grows like r times a function of the direction far from
    /// its centres, and a long, thin shape whose constraints lie mostly inside it can leave that
    /// positive along its length, a second sheet a few lengths off. Rays from the volume's
    /// centre (128 directions, 32 in 2D) are sampled from just outside it to a hundred times as
    /// far as where they leave it; on each ray where f > 0, at the nearest such sample, f is
    /// asked to be minus the distance to the goal boundary. At most [`FAR_FIXES`] rays, at least
    /// 25° apart, the nearest first; none when the far field is negative everywhere, as it is
    /// for most shapes.
    pub(crate) fn far_field_fixes<const D: usize>(
        &self,
        f: &rbf_core::InterpolantView<'_, f64, D>,
    ) -> Vec<Constraint<D>> {
        let extent: [f64; 3] = core::array::from_fn(|d| (self.shape[d] - 1) as f64);
        let centre = extent.map(|e| 0.5 * e);
        let half_diagonal = 0.5 * extent.iter().map(|e| e * e).sum::<f64>().sqrt();
        let flat_goal = self.shape[2] == 1;
        let directions = if flat_goal {
            circle_directions(32)
        } else {
            rbf_core::shapes::fibonacci_sphere(128)
        };
        // (radius, direction) of the nearest positive sample on each ray.
        let mut positive: Vec<(f64, [f64; 3])> = directions
            .iter()
            .filter_map(|&u| {
                // Where the ray leaves the volume.
                let exit = (0..3)
                    .filter(|&d| u[d] != 0.0 && extent[d] > 0.0)
                    .map(|d| 0.5 * extent[d] / u[d].abs())
                    .fold(half_diagonal, f64::min);
                if !(exit > 0.0) {
                    return None;
                }
                FAR_RADII.iter().find_map(|&r| {
                    let at = self.point(core::array::from_fn(|d| centre[d] + r * exit * u[d]));
                    (f.value(&flat(at)) > 0.0).then_some((r * exit, u))
                })
            })
            .collect();
        positive.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut chosen: Vec<[f64; 3]> = Vec::new();
        let mut constraints = Vec::new();
        let apart = 25f64.to_radians().cos();
        for (r, u) in positive {
            let dot = |v: &[f64; 3]| (0..3).map(|d| u[d] * v[d]).sum::<f64>();
            if chosen.len() == FAR_FIXES || chosen.iter().any(|v| dot(v) > apart) {
                continue;
            }
            chosen.push(u);
            let at: [f64; 3] = core::array::from_fn(|d| centre[d] + r * u[d]);
            let distance = (self.boundary.iter())
                .map(|&v| dist(self.coords(v).map(|x| x as f64), at))
                .fold(f64::INFINITY, f64::min);
            if distance.is_finite() && distance > 0.0 {
                constraints.push(Constraint::exterior(
                    flat(self.point(at)),
                    -distance * self.h,
                ));
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
            // The volume's edge, on the axes it spans (a 2D goal is one voxel thick in z).
            let at_edge =
                (0..3).any(|d| self.shape[d] > 1 && (c[d] == 0 || c[d] + 1 == self.shape[d]));
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
    pub(crate) fn evaluate<const D: usize>(
        &self,
        f: &rbf_core::InterpolantView<'_, f64, D>,
        settings: &IterativeSettings,
    ) -> Vec<bool> {
        let s = settings.coarse_step.max(1);
        let [nx, ny, nz] = self.shape;
        let blocks = [nx.div_ceil(s), ny.div_ceil(s), nz.div_ceil(s)];
        let corner = |b: usize, d: usize| (b * s).min(self.shape[d] - 1);
        let cn = [blocks[0] + 1, blocks[1] + 1, blocks[2] + 1];
        let coarse_points: Vec<[f64; D]> = (0..cn[0] * cn[1] * cn[2])
            .map(|i| {
                let b = [i / (cn[1] * cn[2]), (i / cn[2]) % cn[1], i % cn[2]];
                flat(self.point(core::array::from_fn(|d| corner(b[d], d) as f64)))
            })
            .collect();
        let mut coarse = vec![0.0; coarse_points.len()];
        let mut gradients = vec![[0.0; D]; coarse_points.len()];
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
                    coarse[c].abs() > reach * g.iter().map(|x| x * x).sum::<f64>().sqrt()
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
                        points.push(flat(self.point([i as f64, j as f64, k as f64])));
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
    pub(crate) fn errors(&self, inside: &[bool]) -> Vec<(usize, f64, bool)> {
        let current = boundary_voxels(self.shape, inside);
        let to_current = VoxelBins::new(self.shape, &current).distances(self.shape, &self.boundary);
        let mut errors: Vec<(usize, f64, bool)> = self
            .boundary
            .iter()
            .zip(to_current)
            .map(|(&v, d)| (v, d, true))
            .collect();
        // A current boundary voxel is at most its distance to the goal's surface (the signed
        // distance from the densities) plus a voxel from the goal's boundary voxels, wherever
        // the goal has them. Where a part thinner than a voxel passes between voxel centres the
        // goal has none, and the distance to the nearest would count a surface hugging that part
        // as several voxels off.
        errors.extend(
            current
                .iter()
                .map(|&v| (v, self.to_boundary[v].min(self.sd[v].abs() + 1.0), false)),
        );
        errors
    }

    /// §5.3: new constraints at the largest errors, pruned. Returns how many were added.
    ///
    /// The paper takes only errors of at least half the largest. Where those lie where no
    /// constraint may go (within the spacing of others, as on a blade a few voxels thick), that
    /// adds almost nothing and the loop starves while the rest of the surface is still off: so
    /// once the loop has `stalled` (its last iteration made no progress), if that adds fewer
    /// than a twentieth of the constraints there are, every error above the target is a
    /// candidate, largest first.
    pub(crate) fn refine<const D: usize>(
        &self,
        errors: &[(usize, f64, bool)],
        constraints: &mut Vec<Constraint<D>>,
        settings: &IterativeSettings,
        stalled: bool,
    ) -> usize {
        let (max, _) = summary(errors);
        let mut grid = Spacing::new(settings.min_spacing);
        for c in constraints.iter() {
            grid.add(self.to_voxels(lift(c.position)));
        }
        let mut added: Vec<([f64; 3], f64)> = Vec::new();
        let growth = (settings.max_growth * constraints.len() as f64).max(1.0);
        let limit = settings
            .max_constraints
            .min(constraints.len().saturating_add(growth as usize));
        let starving = if stalled {
            (constraints.len() / 20).max(1)
        } else {
            0
        };
        for cut in [settings.error_fraction * max, settings.target_error] {
            if added.len() >= starving && cut < settings.error_fraction * max {
                break;
            }
            let mut candidates: Vec<&(usize, f64, bool)> =
                errors.iter().filter(|e| e.1 >= cut && e.1 > 0.0).collect();
            // Largest error first; in a tie, the goal's boundary first.
            candidates.sort_by(|a, b| b.1.total_cmp(&a.1).then(b.2.cmp(&a.2)));
            for &&(v, error, from_goal) in &candidates {
                if constraints.len() >= limit {
                    break;
                }
                let at = self.coords(v).map(|x| x as f64);
                if added.iter().any(|(p, e)| dist(*p, at) < 2.0 * e) {
                    continue;
                }
                let constraint = if from_goal {
                    Constraint::boundary(flat(self.surface_point(v)))
                } else {
                    let p = self.point(at);
                    let value = self.signed_distance(v, p);
                    if value == 0.0 {
                        continue;
                    }
                    if value > 0.0 {
                        Constraint::interior(flat(p), value)
                    } else {
                        Constraint::exterior(flat(p), value)
                    }
                };
                let pv = self.to_voxels(lift(constraint.position));
                if !grid.free(pv, settings.min_spacing) {
                    continue;
                }
                grid.add(pv);
                added.push((at, error));
                constraints.push(constraint);
            }
        }
        added.len()
    }
}

/// Where [`Goal::far_field_fixes`] samples its rays, in multiples of the distance from the
/// volume's centre to where the ray leaves it.
const FAR_RADII: [f64; 7] = [1.1, 1.5, 3.0, 6.0, 12.0, 30.0, 100.0];

/// The most far-field constraints one call of [`Goal::far_field_fixes`] (one round of settling)
/// adds.
const FAR_FIXES: usize = 8;

/// `n` unit vectors spread evenly over the circle in the xy-plane.
fn circle_directions(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let a = core::f64::consts::TAU * i as f64 / n as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;
    use rbf_core::{ConstraintKind, InterpolantView, Kernel};

    /// The goal of a ball of radius 1 in a 24³ volume over [−1.2, 1.2]³.
    fn ball() -> Goal {
        let h = 0.1;
        let mut density = Volume::filled([-1.15; 3], h, [24; 3], 0.0_f32);
        for v in 0..density.data.len() {
            let [i, j, k] = [v / 576, (v / 24) % 24, v % 24];
            let c = density.centre(i, j, k);
            let r2: f64 = c.iter().map(|x| x * x).sum();
            density.data[v] = if r2 < 1.0 { 1.0 } else { 0.0 };
        }
        Goal::new(&density, &density, None).unwrap()
    }

    #[test]
    fn a_negative_far_field_asks_for_nothing() {
        // f = 1 − |x|³: the ball itself.
        let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
        assert!(ball().far_field_fixes(&f).is_empty());
    }

    #[test]
    fn a_positive_far_field_is_asked_negative_where_it_is_positive() {
        // f = x − 2: positive beyond the plane x = 2, past the volume on the +x side only.
        let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[0.0], -2.0, [1.0, 0.0, 0.0])
            .unwrap();
        let goal = ball();
        let fixes = goal.far_field_fixes(&f);
        assert!(!fixes.is_empty() && fixes.len() <= FAR_FIXES, "{fixes:?}");
        let units: Vec<[f64; 3]> = fixes
            .iter()
            .map(|c| {
                let r = c.position.iter().map(|x| x * x).sum::<f64>().sqrt();
                c.position.map(|x| x / r)
            })
            .collect();
        for (c, u) in fixes.iter().zip(&units) {
            assert_eq!(c.kind, ConstraintKind::Exterior);
            assert!(f.value(&c.position) > 0.0, "{c:?}");
            assert!(
                c.position.iter().any(|x| x.abs() > 1.2),
                "{c:?} inside the volume"
            );
            // Minus the distance to the ball, within a voxel and a half.
            let r = c.position.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((c.value + (r - 1.0)).abs() < 0.15, "{c:?}");
            assert!(u[0] > 0.0, "{c:?}");
        }
        // Spread: no two within 25° of each other.
        for (i, a) in units.iter().enumerate() {
            for b in &units[..i] {
                let cos: f64 = (0..3).map(|d| a[d] * b[d]).sum();
                assert!(cos <= 25f64.to_radians().cos(), "{a:?} and {b:?}");
            }
        }
    }

    #[test]
    fn a_far_field_positive_every_way_gets_the_most_fixes_one_round_adds() {
        // f = |x|³ − 8: positive everywhere beyond radius 2.
        let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[1.0], -8.0, [0.0; 3]).unwrap();
        let fixes = ball().far_field_fixes(&f);
        // As many as one round may add, each where f is positive, outside the volume.
        assert_eq!(fixes.len(), FAR_FIXES);
        for c in &fixes {
            assert!(f.value(&c.position) > 0.0, "{c:?}");
            assert!(
                c.position.iter().any(|x| x.abs() > 1.2),
                "{c:?} inside the volume"
            );
        }
    }
}
