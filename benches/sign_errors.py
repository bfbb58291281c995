#!/usr/bin/env python3
"""Where a model's inside disagrees with a closed mesh's: the regions of a grid where f has the
wrong sign, largest first, with where they are and what they are.

A handle or a piece that a model of a mesh (or of a scan of it) has and the mesh has not is
a region of wrong sign: a film or bridge where f > 0 outside the mesh, a tunnel or a gap where
f < 0 inside it. The genus and F-score say that something is wrong; this says where.

    cargo build --release -p rbf-cli
    rbf reconstruct scan.npy -o scan.ply --model scan.json
    python3 benches/sign_errors.py scan.json mesh.obj [--resolution 256] [--regions 15]

Voxels whose centre lies within `--margin` voxels of the mesh (0.6 by default) are not
counted: there the sign of a surface that passes within a voxel is a matter of where in the
voxel it passes. Each region is printed with its voxels, its centre, its depth (the largest
distance of its voxels from the mesh, in voxels), its kind, and what setting it right would
do to the topology of the model's inside on the grid: the change of its Euler characteristic
(components − handles + cavities), found on a box around the region alone, since only the
cells that touch the region change. A false handle (a bridge or a tunnel) shows as −1, a
false piece or cavity as +1; regions that change nothing are misplaced surface. Needs numpy,
scipy and scikit-image; `rbf voxelize` gives the mesh's signed distances and `rbf eval` the
model's values.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy import ndimage
from skimage.measure import euler_number

here = os.path.dirname(os.path.abspath(__file__))
rbf = os.environ.get("RBF", os.path.join(os.path.dirname(here), "target", "release", "rbf"))


def signed_distances(mesh, resolution, out):
    """The mesh's signed distance (positive inside) at voxel centres, with the grid's origin
    and voxel size."""
    path = os.path.join(out, "mesh.npy")
    subprocess.run([rbf, "voxelize", mesh, "-o", path, "--resolution", str(resolution),
                    "--signed-distance", "-q"], check=True)
    with open(os.path.join(out, "mesh.json")) as f:
        meta = json.load(f)
    return np.load(path), np.array(meta["origin"]), meta["voxel_size"]


def model_values(model, points, out):
    """f of the model at `points`."""
    at, values = os.path.join(out, "points.npy"), os.path.join(out, "values.npy")
    np.save(at, points)
    subprocess.run([rbf, "eval", model, at, "-o", values, "-q"], check=True)
    return np.load(values)


def euler_change(inside, truth, region, box):
    """The Euler characteristic of `inside` minus that of `inside` with `region` set to
    `truth`, both counted on `box` (slices around the region, a voxel beyond it at least)."""
    now = inside[box]
    fixed = now.copy()
    fixed[region[box]] = truth[box][region[box]]
    return euler_number(now, connectivity=1) - euler_number(fixed, connectivity=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", help="model file (rbf fit, convert or reconstruct --model)")
    parser.add_argument("mesh", help="the closed mesh it should match")
    parser.add_argument("--resolution", type=int, default=256,
                        help="voxels along the mesh's longest side (default 256)")
    parser.add_argument("--margin", type=float, default=0.6,
                        help="voxels around the mesh left out (default 0.6)")
    parser.add_argument("--regions", type=int, default=15, help="regions printed (default 15)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as out:
        distance, origin, h = signed_distances(args.mesh, args.resolution, out)
        index = np.indices(distance.shape).reshape(3, -1).T
        centres = origin + (index + 0.5) * h
        f = model_values(args.model, centres, out).reshape(distance.shape)
    print(f"Euler characteristic on the grid: the model's inside {euler_number(f > 0, 1)}, "
          f"the mesh's {euler_number(distance > 0, 1)}")
    margin = args.margin * h
    wrong = ((distance > margin) & (f < 0)) | ((distance < -margin) & (f > 0))
    labels, count = ndimage.label(wrong)
    print(f"grid {distance.shape}, voxel {h:.4g}: {int(wrong.sum())} voxels of wrong sign "
          f"in {count} regions")
    if count == 0:
        return 0
    sizes = ndimage.sum(wrong, labels, range(1, count + 1))
    boxes = ndimage.find_objects(labels)
    inside, truth = f > 0, distance > 0
    changes = {}
    for r in range(count):
        box = tuple(slice(max(b.start - 2, 0), b.stop + 2) for b in boxes[r])
        changes[r] = euler_change(inside, truth, labels == r + 1, box) if sizes[r] else 0
    topological = [r for r in range(count) if changes[r] != 0]
    print(f"{len(topological)} of them change the topology: Euler characteristic "
          f"{sum(changes.values()):+d} in all")
    for r in np.argsort(-sizes)[: args.regions]:
        voxels = labels == r + 1
        in_mesh = (distance[voxels] > 0).mean()
        kind = ("f < 0 inside the mesh (a tunnel or gap)" if in_mesh > 0.5
                else "f > 0 outside the mesh (a film, bridge or piece)")
        centre = centres[voxels.ravel()].mean(axis=0)
        depth = np.abs(distance[voxels]).max() / h
        print(f"{int(sizes[r]):7d} voxels at {np.array2string(centre, precision=3)}, "
              f"{depth:.1f} voxels deep: {kind}; Euler {changes[r]:+d}")
    print("changing the topology:")
    for r in sorted(topological, key=lambda r: -sizes[r]):
        voxels = labels == r + 1
        centre = centres[voxels.ravel()].mean(axis=0)
        in_mesh = (distance[voxels] > 0).mean()
        print(f"{int(sizes[r]):7d} voxels at {np.array2string(centre, precision=3)}: "
              f"{'f < 0 inside' if in_mesh > 0.5 else 'f > 0 outside'}, Euler {changes[r]:+d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
