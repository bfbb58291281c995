//! A regular grid of values over a box, indexed `[x][y][z]` like a C-ordered NumPy array.

/// Values at voxel centres: voxel (i, j, k) is centred at `origin + voxel_size·(i, j, k)` and
/// stored at `(i·ny + j)·nz + k`.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume<T> {
    /// The centre of voxel (0, 0, 0).
    pub origin: [f64; 3],
    /// Edge length of a (cubic) voxel, in the mesh's or model's units.
    pub voxel_size: f64,
    /// Voxels along x, y, z.
    pub shape: [usize; 3],
    /// The values, x slowest, z fastest.
    pub data: Vec<T>,
}

impl<T: Copy> Volume<T> {
    /// A volume filled with `value`.
    pub fn filled(origin: [f64; 3], voxel_size: f64, shape: [usize; 3], value: T) -> Self {
        Self {
            origin,
            voxel_size,
            shape,
            data: vec![value; shape[0] * shape[1] * shape[2]],
        }
    }

    /// The index of voxel (i, j, k) in `data`.
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (i * self.shape[1] + j) * self.shape[2] + k
    }

    /// The value at voxel (i, j, k).
    pub fn get(&self, i: usize, j: usize, k: usize) -> T {
        self.data[self.index(i, j, k)]
    }

    /// The centre of voxel (i, j, k).
    pub fn centre(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        [
            self.origin[0] + self.voxel_size * i as f64,
            self.origin[1] + self.voxel_size * j as f64,
            self.origin[2] + self.voxel_size * k as f64,
        ]
    }
}

/// True when one of the six face neighbours of voxel (i, j, k) in a grid of `shape` has a
/// different class than it, with `class(i, j, k)` giving the class of a voxel: a boundary voxel.
///
/// ```
/// let inside = |i: usize, _: usize, _: usize| i < 2;
/// assert!(rbf_mesh::has_other_neighbour([4, 1, 1], (1, 0, 0), inside));
/// assert!(!rbf_mesh::has_other_neighbour([4, 1, 1], (0, 0, 0), inside));
/// ```
#[doc(hidden)]
pub fn has_other_neighbour(
    shape: [usize; 3],
    (i, j, k): (usize, usize, usize),
    class: impl Fn(usize, usize, usize) -> bool,
) -> bool {
    let here = class(i, j, k);
    let [nx, ny, nz] = shape;
    (i > 0 && class(i - 1, j, k) != here)
        || (i + 1 < nx && class(i + 1, j, k) != here)
        || (j > 0 && class(i, j - 1, k) != here)
        || (j + 1 < ny && class(i, j + 1, k) != here)
        || (k > 0 && class(i, j, k - 1) != here)
        || (k + 1 < nz && class(i, j, k + 1) != here)
}

/// Classifies every voxel of a grid of `shape`, block by block in parallel: `classify(index,
/// lo, hi)` gets a block's index (in blocks) and its voxel range [lo, hi) and returns one class
/// per voxel in x, y, z order (z fastest). The result is in C order over the whole grid.
///
/// ```
/// let inside = rbf_mesh::classify_blocks([5, 3, 2], 2, |_, lo, hi| {
///     let n = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
///     vec![lo[0] >= 2; n]
/// });
/// assert_eq!(inside.len(), 30);
/// assert_eq!(inside.iter().filter(|&&b| b).count(), 18);
/// ```
#[doc(hidden)]
pub fn classify_blocks(
    shape: [usize; 3],
    block: usize,
    classify: impl Fn([usize; 3], [usize; 3], [usize; 3]) -> Vec<bool> + Sync,
) -> Vec<bool> {
    use rayon::prelude::*;
    let b = block.max(1);
    let [nx, ny, nz] = shape;
    let blocks = [nx.div_ceil(b), ny.div_ceil(b), nz.div_ceil(b)];
    let range = |i: usize| -> ([usize; 3], [usize; 3], [usize; 3]) {
        let bi = [
            i / (blocks[1] * blocks[2]),
            (i / blocks[2]) % blocks[1],
            i % blocks[2],
        ];
        let lo: [usize; 3] = core::array::from_fn(|d| bi[d] * b);
        (bi, lo, core::array::from_fn(|d| (lo[d] + b).min(shape[d])))
    };
    let results: Vec<Vec<bool>> = (0..blocks[0] * blocks[1] * blocks[2])
        .into_par_iter()
        .map(|i| {
            let (bi, lo, hi) = range(i);
            classify(bi, lo, hi)
        })
        .collect();
    let mut out = vec![false; nx * ny * nz];
    for (i, values) in results.into_iter().enumerate() {
        let (_, lo, hi) = range(i);
        let mut v = values.into_iter();
        for x in lo[0]..hi[0] {
            for y in lo[1]..hi[1] {
                for z in lo[2]..hi[2] {
                    out[(x * ny + y) * nz + z] = v.next().unwrap_or(false);
                }
            }
        }
    }
    out
}

impl Volume<f32> {
    /// The volume as a NumPy `.npy` file (version 1.0, little-endian `float32`, C order,
    /// shape `(nx, ny, nz)`), which `numpy.load` reads as an array indexed `[x][y][z]`.
    ///
    /// ```
    /// let v = rbf_mesh::Volume::filled([0.0; 3], 1.0, [2, 3, 4], 0.5_f32);
    /// let bytes = v.to_npy();
    /// assert_eq!(&bytes[..6], b"\x93NUMPY");
    /// assert_eq!((bytes.len() - 24 * 4) % 64, 0);
    /// ```
    pub fn to_npy(&self) -> Vec<u8> {
        let mut out = crate::files::npy_preamble("<f4", &self.shape);
        out.reserve(4 * self.data.len());
        for v in &self.data {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out
    }
}
