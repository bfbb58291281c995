//! A regular grid of values over a box, indexed `[x][y][z]` like a C-ordered NumPy array.

/// Values at voxel centres: voxel (i, j, k) is centred at `origin + voxel_size·(i, j, k)` and
/// stored at `(i·ny + j)·nz + k`.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume<T> {
    /// The centre of voxel (0, 0, 0).
    pub origin: [f64; 3],
    /// The edge length of a voxel.
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
