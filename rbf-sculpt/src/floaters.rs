//! Floaters (Witkin & Heckbert 1994), as Turk & O'Brien (2002), §5, use them: particles that stick
//! to the zero set of f, repel each other to spread evenly, split where they are too sparse and die
//! where they are too dense, so that a near-constant density holds as the surface changes.

use std::collections::HashMap;

use rbf_core::InterpolantView;

/// How floaters behave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloaterSettings {
    /// Desired distance between neighbours.
    pub spacing: f64,
    /// Fraction of the repulsion applied per step.
    pub step: f64,
    /// Newton steps toward f = 0 after each move.
    pub projections: usize,
}

impl FloaterSettings {
    /// Settings for a model of this size (bounding-box diagonal): spacing 1/20 of it.
    ///
    /// ```
    /// let s = rbf_sculpt::FloaterSettings::for_size(2.0);
    /// assert!((s.spacing - 0.1).abs() < 1e-12);
    /// ```
    pub fn for_size(diagonal: f64) -> Self {
        Self {
            spacing: diagonal / 20.0,
            step: 0.25,
            projections: 4,
        }
    }
}

/// A population of floaters on a surface.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_sculpt::{FloaterSettings, Floaters};
/// // The unit sphere, f = 1 − r³.
/// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let mut floaters = Floaters::new(&f, &[[1.0, 0.0, 0.0]], FloaterSettings { spacing: 0.3, step: 0.25, projections: 4 });
/// floaters.settle(&f, 300);
/// // About 4π / (0.3² · √3/2) ≈ 160 floaters, all on the sphere.
/// assert!(floaters.len() > 100 && floaters.len() < 260, "{}", floaters.len());
/// assert!(floaters.points().iter().all(|p| (p.iter().map(|x| x * x).sum::<f64>().sqrt() - 1.0).abs() < 1e-6));
/// ```
#[derive(Clone, Debug)]
pub struct Floaters {
    points: Vec<[f64; 3]>,
    settings: FloaterSettings,
    round: u64,
}

/// Energy of a floater at ideal spacing (hexagonal neighbours), for σ = spacing / 2.
fn ideal_energy() -> f64 {
    6.0 * (-2.0_f64).exp() + 6.0 * (-6.0_f64).exp()
}

impl Floaters {
    /// Floaters starting at `seeds` moved onto the surface.
    pub fn new(
        f: &InterpolantView<'_, f64, 3>,
        seeds: &[[f64; 3]],
        settings: FloaterSettings,
    ) -> Self {
        let mut floaters = Self {
            points: seeds.to_vec(),
            settings,
            round: 0,
        };
        floaters.project(f);
        floaters
    }

    /// How many floaters there are.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Their positions.
    pub fn points(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// The settings in force, with the spacing last set by [`Floaters::set_spacing`].
    pub fn settings(&self) -> FloaterSettings {
        self.settings
    }

    /// Changes the desired spacing.
    pub fn set_spacing(&mut self, spacing: f64) {
        self.settings.spacing = spacing;
    }

    /// Outward unit normals (−∇f / |∇f|) at the floaters.
    pub fn normals(&self, f: &InterpolantView<'_, f64, 3>) -> Vec<[f64; 3]> {
        self.points
            .iter()
            .map(|p| {
                let g = f.gradient(p);
                let n = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt().max(1e-300);
                g.map(|v| -v / n)
            })
            .collect()
    }

    /// Runs `rounds` rounds of repulsion, projection and population control.
    pub fn settle(&mut self, f: &InterpolantView<'_, f64, 3>, rounds: usize) {
        for _ in 0..rounds {
            self.step(f);
        }
    }

    /// Newton steps toward f = 0; floaters where ∇f vanishes or that do not converge die.
    fn project(&mut self, f: &InterpolantView<'_, f64, 3>) {
        let reach = 4.0 * self.settings.spacing;
        self.points.retain_mut(|p| {
            let start = *p;
            for _ in 0..self.settings.projections.max(1) * 3 {
                let (v, g) = f.value_and_gradient(p);
                let g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
                if !(g2 > 0.0) {
                    return false;
                }
                for d in 0..3 {
                    p[d] -= v * g[d] / g2;
                }
                if (v * v / g2).sqrt() < 1e-12 * (1.0 + reach) {
                    break;
                }
            }
            let moved = (0..3)
                .map(|d| (p[d] - start[d]).powi(2))
                .sum::<f64>()
                .sqrt();
            let v = f.value(p);
            let g = f.gradient(p);
            let g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
            moved < reach * 4.0 && g2 > 0.0 && (v * v / g2).sqrt() < 1e-9 * (1.0 + reach)
        });
    }

    /// One round: repel, project, then split the sparse and kill the crowded.
    pub fn step(&mut self, f: &InterpolantView<'_, f64, 3>) {
        self.round += 1;
        let sigma = 0.5 * self.settings.spacing;
        let cell = 3.0 * sigma;
        let key = |p: &[f64; 3]| p.map(|v| (v / cell).floor() as i64);
        let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (i, p) in self.points.iter().enumerate() {
            grid.entry(key(p)).or_default().push(i);
        }
        let n = self.points.len();
        let mut energy = vec![0.0; n];
        let mut force = vec![[0.0; 3]; n];
        for i in 0..n {
            let p = self.points[i];
            let k = key(&p);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(list) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                            continue;
                        };
                        for &j in list {
                            if j == i {
                                continue;
                            }
                            let r: [f64; 3] = core::array::from_fn(|d| p[d] - self.points[j][d]);
                            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                            if r2 > cell * cell {
                                continue;
                            }
                            let e = (-r2 / (2.0 * sigma * sigma)).exp();
                            energy[i] += e;
                            for d in 0..3 {
                                force[i][d] += r[d] * e;
                            }
                        }
                    }
                }
            }
        }
        // Move along the tangent plane, at most half a σ.
        for i in 0..n {
            let g = f.gradient(&self.points[i]);
            let g2 = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).max(1e-300);
            let mut v = force[i].map(|x| x * self.settings.step);
            let along = (v[0] * g[0] + v[1] * g[1] + v[2] * g[2]) / g2;
            for d in 0..3 {
                v[d] -= along * g[d];
            }
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            let cap = 0.5 * sigma;
            let scale = if len > cap { cap / len } else { 1.0 };
            for d in 0..3 {
                self.points[i][d] += v[d] * scale;
            }
        }
        // Population: split the lonely, kill the crowded (at most one of any close pair).
        let ideal = ideal_energy();
        let mut dead = vec![false; n];
        let mut born = Vec::new();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| energy[b].total_cmp(&energy[a]));
        for &i in &order {
            if energy[i] > 1.9 * ideal && !dead[i] {
                // Spare the neighbours of one that dies this round.
                let p = self.points[i];
                let k = key(&p);
                let neighbour_dead = (-1..=1).any(|dx| {
                    (-1..=1).any(|dy| {
                        (-1..=1).any(|dz| {
                            grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                                .is_some_and(|l| {
                                    l.iter().any(|&j| {
                                        dead[j]
                                            && (0..3)
                                                .map(|d| (p[d] - self.points[j][d]).powi(2))
                                                .sum::<f64>()
                                                < 4.0 * sigma * sigma
                                    })
                                })
                        })
                    })
                });
                if !neighbour_dead {
                    dead[i] = true;
                }
            } else if energy[i] < 0.45 * ideal {
                // Split along a tangent direction that turns from round to round.
                let p = self.points[i];
                let g = f.gradient(&p);
                let a = self.round as f64 * 2.399 + i as f64;
                let axis = [a.cos(), a.sin(), (0.7 * a).cos()];
                let t = [
                    g[1] * axis[2] - g[2] * axis[1],
                    g[2] * axis[0] - g[0] * axis[2],
                    g[0] * axis[1] - g[1] * axis[0],
                ];
                let len = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                if len > 0.0 {
                    born.push(core::array::from_fn(|d| p[d] + 0.6 * sigma * t[d] / len));
                }
            }
        }
        let mut i = 0;
        self.points.retain(|_| {
            i += 1;
            !dead[i - 1]
        });
        self.points.extend(born);
        self.project(f);
    }
}
