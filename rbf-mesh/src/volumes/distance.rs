//! Exact Euclidean distance transforms (Felzenszwalb & Huttenlocher 2012): separable, linear
//! time, for any initial cost, and the signed distance of a voxelized mesh
//! (Yngve & Turk 2002, §4.2).

use rayon::prelude::*;

use crate::Volume;

/// Scratch space for [`line`].
struct Scratch {
    v: Vec<usize>,
    z: Vec<f64>,
    out: Vec<f64>,
    out_source: Vec<u32>,
    f: Vec<f64>,
    source: Vec<u32>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Self {
            v: vec![0; n],
            z: vec![0.0; n + 1],
            out: vec![0.0; n],
            out_source: vec![0; n],
            f: vec![0.0; n],
            source: vec![0; n],
        }
    }
}

/// The 1D transform d(p) = min_q ((p − q)² + f(q)) of one line, in place, carrying along
/// `source[q]` (which original voxel each minimum comes from).
fn line(f: &mut [f64], source: &mut [u32], s: &mut Scratch) {
    let (v, z, out, out_source) = (&mut s.v, &mut s.z, &mut s.out, &mut s.out_source);
    let n = f.len();
    let mut k = 0;
    // The first finite parabola starts the lower envelope.
    let Some(first) = f.iter().position(|x| x.is_finite()) else {
        return;
    };
    v[0] = first;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in first + 1..n {
        if !f[q].is_finite() {
            continue;
        }
        // Drop parabolas of the envelope that the new one hides (z[0] = −∞ stops at k = 0).
        let mut s;
        loop {
            let p = v[k];
            s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
            if s > z[k] {
                break;
            }
            k -= 1;
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate().take(n) {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as f64 - v[k] as f64;
        *o = d * d + f[v[k]];
        out_source[q] = source[v[k]];
    }
    f.copy_from_slice(&out[..n]);
    source.copy_from_slice(&out_source[..n]);
}

/// Replaces `cost` (shape [nx, ny, nz], C order, in voxel units squared; ∞ where there is no
/// source) with min over voxels q of |p − q|² + cost(q), exactly, in O(voxels).
///
/// ```
/// let mut cost = vec![f64::INFINITY; 5 * 1 * 1];
/// cost[1] = 0.0;
/// rbf_mesh::squared_distance_transform([5, 1, 1], &mut cost);
/// assert_eq!(cost, vec![1.0, 0.0, 1.0, 4.0, 9.0]);
/// ```
#[doc(hidden)]
pub fn squared_distance_transform(shape: [usize; 3], cost: &mut [f64]) {
    let mut source: Vec<u32> = (0..cost.len() as u32).collect();
    transform(shape, cost, &mut source);
}

/// [`squared_distance_transform`], also giving for each voxel the index of the voxel its
/// minimum comes from (a feature transform).
fn transform(shape: [usize; 3], cost: &mut [f64], source: &mut [u32]) {
    let [nx, ny, nz] = shape;
    if nx * ny * nz == 0 || cost.len() != nx * ny * nz || source.len() != cost.len() {
        return;
    }
    let longest = nx.max(ny).max(nz);
    let scratch = || Scratch::new(longest);
    // Along z: contiguous lines.
    cost.par_chunks_mut(nz)
        .zip(source.par_chunks_mut(nz))
        .for_each_init(scratch, |s, (l, src)| line(l, src, s));
    // Along y and x: gather each line, transform it, scatter it back.
    cost.par_chunks_mut(ny * nz)
        .zip(source.par_chunks_mut(ny * nz))
        .for_each_init(scratch, |s, (slab, src)| {
            for k in 0..nz {
                let (mut f, mut g) = (std::mem::take(&mut s.f), std::mem::take(&mut s.source));
                for j in 0..ny {
                    f[j] = slab[j * nz + k];
                    g[j] = src[j * nz + k];
                }
                line(&mut f[..ny], &mut g[..ny], s);
                for j in 0..ny {
                    slab[j * nz + k] = f[j];
                    src[j * nz + k] = g[j];
                }
                (s.f, s.source) = (f, g);
            }
        });
    // Along x, in batches of lines so that the gathered copies stay small.
    const BATCH: usize = 4096;
    let columns = ny * nz;
    for first in (0..columns).step_by(BATCH) {
        let batch = first..(first + BATCH).min(columns);
        let lines: Vec<(Vec<f64>, Vec<u32>)> = batch
            .clone()
            .into_par_iter()
            .map_init(scratch, |s, c| {
                let mut f: Vec<f64> = (0..nx).map(|i| cost[i * columns + c]).collect();
                let mut g: Vec<u32> = (0..nx).map(|i| source[i * columns + c]).collect();
                line(&mut f, &mut g, s);
                (f, g)
            })
            .collect();
        for (c, (f, g)) in batch.zip(lines) {
            for i in 0..nx {
                cost[i * columns + c] = f[i];
                source[i * columns + c] = g[i];
            }
        }
    }
}

/// The signed distance to the surface of a voxelized mesh, positive inside, in the mesh's
/// units. Voxels with partial density, or next to a voxel of the other class, are boundary
/// voxels; the surface is placed in each at (density − ½) of a voxel beyond its centre (toward
/// outside). Every voxel finds its nearest boundary voxel exactly (a feature transform) and adds
/// that offset. Inside is density ≥ ½.
///
/// ```
/// # use rbf_mesh::{TriMesh, VoxelSettings, voxelize, signed_distance};
/// let cube = TriMesh::new(
///     vec![[0.,0.,0.],[1.,0.,0.],[1.,1.,0.],[0.,1.,0.],[0.,0.,1.],[1.,0.,1.],[1.,1.,1.],[0.,1.,1.]],
///     vec![[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[1,2,6],[1,6,5],[2,3,7],[2,7,6],[3,0,4],[3,4,7]],
/// ).unwrap();
/// let v = voxelize(&cube, &VoxelSettings { resolution: 20, ..Default::default() }).unwrap();
/// let sd = signed_distance(&v);
/// // Voxel (11, 11, 11) is centred at 0.475 on each axis: 0.475 from the nearest faces.
/// let c = sd.get(11, 11, 11);
/// assert!((c - 0.475).abs() < 0.01, "{c}");
/// ```
pub fn signed_distance(density: &Volume<f32>) -> Volume<f32> {
    let [nx, ny, nz] = density.shape;
    let inside = |d: f32| d >= 0.5;
    let mut cost = vec![f64::INFINITY; density.data.len()];
    let mut offset = vec![0.0_f32; density.data.len()];
    for i in 0..nx {
        for j in 0..ny {
            for k in 0..nz {
                let at = density.index(i, j, k);
                let d = density.data[at];
                let edge = crate::has_other_neighbour(density.shape, (i, j, k), |a, b, c| {
                    inside(density.get(a, b, c))
                });
                if (d > 0.0 && d < 1.0) || edge {
                    cost[at] = 0.0;
                    offset[at] = (d - 0.5).clamp(-0.5, 0.5);
                }
            }
        }
    }
    let mut source: Vec<u32> = (0..cost.len() as u32).collect();
    transform(density.shape, &mut cost, &mut source);
    let h = density.voxel_size;
    let data = cost
        .iter()
        .zip(&source)
        .zip(&density.data)
        .map(|((&c, &q), &d)| {
            if !c.is_finite() {
                return if inside(d) {
                    f32::INFINITY
                } else {
                    f32::NEG_INFINITY
                };
            }
            // Inside, the surface lies `offset` beyond the nearest boundary voxel; outside,
            // `offset` short of it.
            let to_seed = c.sqrt();
            let o = f64::from(offset[q as usize]);
            let distance = if inside(d) {
                to_seed + o
            } else {
                (to_seed - o).max(0.0)
            };
            ((if inside(d) { distance } else { -distance }) * h) as f32
        })
        .collect();
    Volume {
        origin: density.origin,
        voxel_size: h,
        shape: density.shape,
        data,
    }
}
