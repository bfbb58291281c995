#!/usr/bin/env python3
"""Closed meshes thinner than a conversion's voxels, made from signed distance functions, for
`benches/corpus.py --meshes DIR`: the shapes the corpus of ../shared/data/meshes has few of.

- bowl: a spherical shell (radius 0.9, wall 0.012: 0.85 voxel at 128) cut open at z = 0.5;
- plate4: a plate 0.02 thick (1.3 voxels) with four round holes: genus 4;
- pretzel: three overlapping rings of tubes 0.06 thick, in a row;
- fin: a disc 0.012 thick (0.73 voxel) through a ball;
- skull: a spherical shell (radius 0.9, wall 0.03: 2 voxels) with three round openings, two in
  front and one below, as a skull's bony shell has: genus 2.

Each is marching cubes of its distance function on a lattice of 400 along x (scikit-image),
decimated to 60 000 triangles (trimesh with fast_simplification). Benchmark tools only:

    python3 -m pip install numpy scikit-image trimesh fast_simplification
    python3 benches/thin_meshes.py OUT_DIR
    python3 benches/corpus.py --meshes OUT_DIR bowl plate4 pretzel fin skull
"""
import os
import sys

import numpy as np
import trimesh
from skimage.measure import marching_cubes

SAMPLES = 400


def lattice(lo, hi):
    """Sample points over the box [lo, hi], SAMPLES along x and as finely along y and z."""
    step = (hi[0] - lo[0]) / (SAMPLES - 1)
    axes = [np.arange(lo[d], hi[d] + 0.5 * step, step) for d in range(3)]
    return np.meshgrid(*axes, indexing="ij"), step, np.array(lo)


def save(out, name, inside, step, lo):
    """Writes the surface where `inside` (positive inside) is zero, outward facing."""
    v, f, _, _ = marching_cubes(inside, 0.0, spacing=(step,) * 3)
    mesh = trimesh.Trimesh(v + lo, f[:, ::-1], process=True)
    if mesh.volume < 0:
        mesh.invert()
    if len(mesh.faces) > 60000:
        mesh = mesh.simplify_quadric_decimation(face_count=60000)
    path = os.path.join(out, name + ".obj")
    mesh.export(path)
    print(f"{path}: {len(mesh.faces)} triangles, watertight {mesh.is_watertight}, "
          f"Euler number {mesh.euler_number}")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "thin-meshes"
    os.makedirs(out, exist_ok=True)

    (x, y, z), step, lo = lattice([-1.05] * 3, [1.05] * 3)
    r = np.sqrt(x * x + y * y + z * z)
    save(out, "bowl", np.minimum(0.006 - np.abs(r - 0.9), 0.5 - z), step, lo)

    (x, y, z), step, lo = lattice([-1.05, -0.75, -0.1], [1.05, 0.75, 0.1])
    plate = np.minimum(np.minimum(1.0 - np.abs(x), 0.7 - np.abs(y)), 0.01 - np.abs(z))
    for cx in (-0.6, -0.2, 0.2, 0.6):
        plate = np.minimum(plate, np.sqrt((x - cx) ** 2 + y * y) - 0.12)
    save(out, "plate4", plate, step, lo)

    (x, y, z), step, lo = lattice([-1.05, -0.45, -0.12], [1.05, 0.45, 0.12])
    rings = np.full(x.shape, -np.inf)
    for cx in (-0.6, 0.0, 0.6):
        q = np.sqrt((x - cx) ** 2 + y * y) - 0.36
        rings = np.maximum(rings, 0.06 - np.sqrt(q * q + z * z))
    save(out, "pretzel", rings, step, lo)

    (x, y, z), step, lo = lattice([-1.05, -1.05, -0.35], [1.05, 1.05, 0.35])
    disc = np.minimum(1.0 - np.sqrt(x * x + y * y), 0.006 - np.abs(z))
    ball = 0.3 - np.sqrt(x * x + y * y + z * z)
    save(out, "fin", np.maximum(disc, ball), step, lo)

    (x, y, z), step, lo = lattice([-1.05] * 3, [1.05] * 3)
    p = np.stack([x, y, z], axis=-1)
    shell = 0.015 - np.abs(np.linalg.norm(p, axis=-1) - 0.9)
    for axis in ([0.55, 0.0, 0.83], [-0.55, 0.0, 0.83], [0.0, -1.0, 0.0]):
        a = np.array(axis) / np.linalg.norm(axis)
        along = p @ a
        across = np.linalg.norm(p - along[..., None] * a, axis=-1)
        shell = np.minimum(shell, np.maximum(across - 0.25, -along))
    save(out, "skull", shell, step, lo)


if __name__ == "__main__":
    main()
