//! The settings of the iterative conversion (Yngve & Turk 2002, §4–§5), every one of the
//! paper's parameters with its value as the default.

use rbf_mesh::VoxelMethod;

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
    /// And when the RMS of those errors is at most this many voxels (not in the paper): 0.3.
    /// Its maximum within a voxel, a loop whose RMS is still high has a surface that lies a
    /// voxel off in many places, and ends about a quarter voxel from the mesh on the whole.
    pub target_rms: f64,
    /// Stop after this many iterations without progress (§5.4): 4. Progress is a better model
    /// or an error below every one before (the maximum, or the RMS by a hundredth): the loop
    /// does not stop while its errors still fall.
    pub patience: usize,
    /// Stop after this many iterations (§5.4): 30.
    pub max_iterations: usize,
    /// Stop at this many constraints: 4000 (the paper's §5.4 says 5000; on the repository's
    /// meshes at 128 voxels 4000 keep the surface within 1.5 voxels of the mesh, 0.25 RMS).
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
    /// For a closed mesh, keep its genus and components: constraints at the middle of the
    /// mesh's gaps and parts thinner than two voxels wherever the surface puts them on the
    /// wrong side, then the topology measured (not in the paper). true.
    pub keep_topology: bool,
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
            target_rms: 0.3,
            patience: 4,
            max_iterations: 30,
            max_constraints: 4000,
            coarse_step: 4,
            shell: 8.0,
            min_spacing: 1.0,
            error_fraction: 0.5,
            lambda: 0.0,
            max_growth: 0.3,
            gradient_skip: true,
            keep_topology: true,
        }
    }
}
