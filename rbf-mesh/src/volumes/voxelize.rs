//! Voxelizing a mesh (Yngve & Turk 2002, §4.1): the fraction of each voxel inside the mesh, by
//! casting parallel rays and counting signed crossings, with supersampling so that densities vary
//! from 0 to 1 across the boundary.

use rayon::prelude::*;

use crate::{MeshError, TriMesh, Volume};

/// Settings of the voxelizer.
///
/// ```
/// let s = rbf_mesh::VoxelSettings { resolution: 64, ..Default::default() };
/// assert_eq!(s.supersampling, 4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelSettings {
    /// Voxels along the longest side of the mesh's bounding box; the other sides in proportion.
    pub resolution: usize,
    /// Empty voxels added around the bounding box on every side. 2.
    pub margin: usize,
    /// Sub-samples along each axis of a voxel (s³ per voxel, s² rays per voxel column), 1 to
    /// [`MAX_SUPERSAMPLING`]. 4.
    pub supersampling: usize,
    /// How a sample is classed inside: by ray crossings, by winding number, or `Auto` (the
    /// default: rays when the mesh is watertight).
    pub method: VoxelMethod,
    /// Bytes that the volume and its signed distance (24 a voxel) may take; a larger grid is
    /// refused before it is allocated. `None` refuses only grids beyond 2³³ voxels. The CLI and
    /// rbf-convert pass `rbf_solve::memory_budget()`, what the machine can spare.
    pub memory_limit: Option<u64>,
}

/// How the voxelizer decides what is inside.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoxelMethod {
    /// Rays for a watertight mesh, winding numbers otherwise (by [`TriMesh::check`]).
    Auto,
    /// Parallel rays along z, crossings counted with their sign: exact for watertight meshes
    /// of either orientation (inside is a non-zero count).
    Rays,
    /// Generalized winding numbers (> ½ is inside): robust to holes, overlaps and non-manifold
    /// parts. Voxels whose class differs from a neighbour's are supersampled.
    Winding,
}

impl Default for VoxelSettings {
    fn default() -> Self {
        Self {
            resolution: 128,
            margin: 2,
            supersampling: 4,
            method: VoxelMethod::Auto,
            memory_limit: None,
        }
    }
}

/// The peak memory of [`voxelize`] followed by [`crate::signed_distance`], per voxel.
const BYTES_PER_VOXEL: u64 = 24;

/// Refuses a volume of `shape` voxels that the machine cannot hold with its signed distance:
/// 24 bytes a voxel (densities, squared distances, their sources, the surface offsets, the
/// result) against `memory_limit`, and never more than 2³³ voxels. Used by the voxelizer and by
/// whoever builds such a volume another way (rbf-convert's 2D goal).
///
/// ```
/// assert!(rbf_mesh::check_volume_size([100, 100, 100], Some(1 << 30)).is_ok());
/// let e = rbf_mesh::check_volume_size([1 << 20, 1 << 20, 1], None).unwrap_err();
/// assert!(e.to_string().contains("too large"));
/// ```
pub fn check_volume_size(shape: [usize; 3], memory_limit: Option<u64>) -> Result<(), MeshError> {
    let voxels = shape.iter().try_fold(1u64, |a, &b| a.checked_mul(b as u64));
    let bytes = voxels.map_or(u64::MAX, |v| v.saturating_mul(BYTES_PER_VOXEL));
    if voxels.is_none_or(|v| v > 1 << 33) || memory_limit.is_some_and(|a| bytes > a) {
        return Err(MeshError::Invalid(format!(
            "a volume of {shape:?} voxels is too large: it needs about {} MiB{}; use a coarser resolution",
            bytes >> 20,
            memory_limit.map_or(String::new(), |a| format!(
                " but only {} MiB can be spared",
                a >> 20
            ))
        )));
    }
    Ok(())
}

/// The largest supersampling: 16³ samples per voxel already resolve a density to 1/4096.
pub const MAX_SUPERSAMPLING: usize = 16;

/// The grid a mesh is voxelized on.
pub(crate) fn voxel_grid(
    mesh: &TriMesh,
    settings: &VoxelSettings,
) -> Result<Volume<f32>, MeshError> {
    let (lo, hi) = mesh.bounding_box();
    let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    if settings.resolution == 0
        || !(1..=MAX_SUPERSAMPLING).contains(&settings.supersampling)
        || !(longest > 0.0)
    {
        return Err(MeshError::Invalid(format!(
            "cannot voxelize at resolution {} with supersampling {} (1 to {MAX_SUPERSAMPLING}) a mesh {longest} across",
            settings.resolution, settings.supersampling
        )));
    }
    let h = longest / settings.resolution as f64;
    if !(h > 0.0 && h.is_finite()) {
        // A mesh so small (subnormal) or so large that a voxel's size is 0 or infinite.
        return Err(MeshError::Invalid(format!(
            "a mesh {longest:e} across cannot be cut into voxels at resolution {}: scale it",
            settings.resolution
        )));
    }
    let m = settings.margin;
    let shape: [usize; 3] = core::array::from_fn(|d| {
        (((hi[d] - lo[d]) / h).ceil().max(1.0) as usize).saturating_add(m.saturating_mul(2))
    });
    check_volume_size(shape, settings.memory_limit)?;
    let origin = core::array::from_fn(|d| lo[d] - (m as f64 - 0.5) * h);
    Ok(Volume::filled(origin, h, shape, 0.0))
}

/// A triangle projected on the xy plane, ready for ray tests.
struct Projected {
    /// Corners in xy, ordered counter-clockwise.
    xy: [[f64; 2]; 3],
    z: [f64; 3],
    /// The edge functions' canonical orientation: edge e is (xy[e], xy[(e+1)%3]).
    area: f64,
    /// +1 if the triangle faces +z (a ray going up leaves the solid), −1 otherwise.
    sign: i32,
}

/// The signed area test of p against edge a→b, computed with the corners in a fixed order so
/// that two triangles sharing the edge get exactly opposite values.
fn edge_function(a: ([f64; 2], u32), b: ([f64; 2], u32), p: [f64; 2]) -> f64 {
    let ((a, ia), (b, ib)) = (a, b);
    let (u, v, flip) = if ia < ib { (a, b, 1.0) } else { (b, a, -1.0) };
    flip * ((v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]))
}

/// Whether an edge owns points exactly on it (a top-left rule, so that a ray through an edge
/// shared by two triangles counts once).
fn owns_edge(a: [f64; 2], b: [f64; 2]) -> bool {
    b[1] < a[1] || (b[1] == a[1] && b[0] > a[0])
}

/// For each triangle whose xy shadow covers the ray at `p`: (z of the crossing, sign).
fn hit(t: &Projected, ids: [u32; 3], p: [f64; 2]) -> Option<f64> {
    let mut w = [0.0; 3];
    for e in 0..3 {
        let (a, b) = (t.xy[e], t.xy[(e + 1) % 3]);
        let f = edge_function((a, ids[e]), (b, ids[(e + 1) % 3]), p);
        if f < 0.0 || (f == 0.0 && !owns_edge(a, b)) {
            return None;
        }
        w[(e + 2) % 3] = f;
    }
    Some((w[0] * t.z[0] + w[1] * t.z[1] + w[2] * t.z[2]) / t.area)
}

/// The fraction of each voxel inside the mesh. With rays (the default for watertight meshes):
/// s² rays along z through each voxel column, crossings counted with the sign of the triangle
/// they pass (a non-zero winding rule along the ray), s sub-samples along z per voxel. With
/// winding numbers (the default otherwise), see [`VoxelMethod::Winding`].
///
/// ```
/// # use rbf_mesh::{TriMesh, VoxelSettings, voxelize};
/// let cube = TriMesh::new(
///     vec![[0.,0.,0.],[1.,0.,0.],[1.,1.,0.],[0.,1.,0.],[0.,0.,1.],[1.,0.,1.],[1.,1.,1.],[0.,1.,1.]],
///     vec![[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[1,2,6],[1,6,5],[2,3,7],[2,7,6],[3,0,4],[3,4,7]],
/// ).unwrap();
/// let v = voxelize(&cube, &VoxelSettings { resolution: 10, ..Default::default() }).unwrap();
/// let inside: f32 = v.data.iter().sum();
/// assert!((inside - 1000.0).abs() < 1e-3); // the unit cube is 10³ voxels
/// ```
pub fn voxelize(mesh: &TriMesh, settings: &VoxelSettings) -> Result<Volume<f32>, MeshError> {
    let method = match settings.method {
        VoxelMethod::Auto if mesh.check().is_watertight() => VoxelMethod::Rays,
        VoxelMethod::Auto => VoxelMethod::Winding,
        m => m,
    };
    if method == VoxelMethod::Winding {
        return voxelize_winding(mesh, settings);
    }
    let mut volume = voxel_grid(mesh, settings)?;
    let s = settings.supersampling;
    let h = volume.voxel_size;
    let [nx, ny, nz] = volume.shape;
    // Sub-sample offsets inside a voxel, in voxel units from its centre.
    let offsets: Vec<f64> = (0..s).map(|i| (i as f64 + 0.5) / s as f64 - 0.5).collect();
    let ray_x = |i: usize, a: usize| volume.origin[0] + h * (i as f64 + offsets[a]);
    let ray_y = |j: usize, b: usize| volume.origin[1] + h * (j as f64 + offsets[b]);
    // Rays form a regular grid of nx·s × ny·s; bin each triangle into the rays it may cover.
    let (rx, ry) = (nx * s, ny * s);
    let to_ray = |v: f64, o: f64| ((v - o) / h * s as f64 + 0.5 * s as f64 - 0.5).floor();
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); rx * ry];
    let mut projected = Vec::with_capacity(mesh.triangles().len());
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let c = mesh.corners(t);
        let area =
            (c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[1][1] - c[0][1]) * (c[2][0] - c[0][0]);
        if area == 0.0 {
            projected.push(None);
            continue;
        }
        // Counter-clockwise in xy; a triangle facing +z is counter-clockwise already.
        let (order, sign) = if area > 0.0 {
            ([0, 1, 2], 1)
        } else {
            ([0, 2, 1], -1)
        };
        projected.push(Some((
            Projected {
                xy: order.map(|i| [c[i][0], c[i][1]]),
                z: order.map(|i| c[i][2]),
                area: area.abs(),
                sign,
            },
            order.map(|i| tri[i]),
        )));
        let span = |d: usize, rays: usize| {
            let lo = c.iter().map(|p| p[d]).fold(f64::INFINITY, f64::min);
            let hi = c.iter().map(|p| p[d]).fold(f64::NEG_INFINITY, f64::max);
            let first = to_ray(lo, volume.origin[d]).max(0.0) as usize;
            let last = (to_ray(hi, volume.origin[d]) + 1.0).clamp(0.0, rays as f64 - 1.0) as usize;
            (first, last)
        };
        let ((x0, x1), (y0, y1)) = (span(0, rx), span(1, ry));
        for x in x0..=x1 {
            for y in y0..=y1 {
                bins[x * ry + y].push(t as u32);
            }
        }
    }
    let weight = 1.0 / (s * s * s) as f32;
    volume
        .data
        .par_chunks_mut(ny * nz)
        .enumerate()
        .for_each(|(i, slab)| {
            let mut crossings: Vec<(f64, i32)> = Vec::new();
            for a in 0..s {
                let x = ray_x(i, a);
                for j in 0..ny {
                    for b in 0..s {
                        let y = ray_y(j, b);
                        crossings.clear();
                        for &t in &bins[(i * s + a) * ry + j * s + b] {
                            if let Some((p, ids)) = &projected[t as usize]
                                && let Some(z) = hit(p, *ids, [x, y])
                            {
                                crossings.push((z, p.sign));
                            }
                        }
                        if crossings.is_empty() {
                            continue;
                        }
                        crossings.sort_by(|p, q| p.0.total_cmp(&q.0));
                        // Walk up the ray: below a crossing facing −z we enter the solid.
                        let mut winding = 0;
                        let mut next = 0;
                        for k in 0..nz {
                            for &o in &offsets {
                                let z = volume.origin[2] + h * (k as f64 + o);
                                while next < crossings.len() && crossings[next].0 < z {
                                    winding -= crossings[next].1;
                                    next += 1;
                                }
                                // Inside for either orientation: an inside-out mesh
                                // counts −1 where an outward one counts +1.
                                if winding != 0 {
                                    slab[j * nz + k] += weight;
                                }
                            }
                        }
                    }
                }
            }
        });
    Ok(volume)
}

/// Voxelizes by generalized winding numbers: each centre is classified, and voxels with a
/// neighbour of the other class get the fraction of their s³ sub-samples that are inside.
fn voxelize_winding(mesh: &TriMesh, settings: &VoxelSettings) -> Result<Volume<f32>, MeshError> {
    let mut volume = voxel_grid(mesh, settings)?;
    let tree = crate::WindingTree::new(mesh);
    let [_, ny, nz] = volume.shape;
    let coords = |p: usize| (p / (ny * nz), (p / nz) % ny, p % nz);
    let inside = tree.classify_grid(volume.origin, volume.voxel_size, volume.shape);
    let s = settings.supersampling;
    let offsets: Vec<f64> = (0..s).map(|i| (i as f64 + 0.5) / s as f64 - 0.5).collect();
    let h = volume.voxel_size;
    let volume_ref = &volume;
    let data: Vec<f32> = (0..inside.len())
        .into_par_iter()
        .map(|p| {
            let (i, j, k) = coords(p);
            let class = inside[p];
            let boundary = crate::has_other_neighbour(volume_ref.shape, (i, j, k), |a, b, c| {
                inside[(a * ny + b) * nz + c]
            });
            if !boundary {
                return if class { 1.0 } else { 0.0 };
            }
            let c = volume_ref.centre(i, j, k);
            let mut count = 0;
            for &a in &offsets {
                for &b in &offsets {
                    for &o in &offsets {
                        let q = [c[0] + a * h, c[1] + b * h, c[2] + o * h];
                        count += usize::from(tree.winding_number(q) > 0.5);
                    }
                }
            }
            count as f32 / (s * s * s) as f32
        })
        .collect();
    volume.data = data;
    Ok(volume)
}
