#!/usr/bin/env python3
"""The peer of `rbf mesh`: sample a model on the full lattice with scipy, then run
scikit-image's marching cubes on it.

Reads the model and lattice that `peer-compare --mesh` writes to the temporary directory
(rbf-torus3000.json, rbf-torus3000-lattice.json): the same interpolant (centres, weights,
linear part) and the same number of cubes along each axis over the same box. Prints records in
the format of ../shared/peers/compare.py.

    cargo run --release -p rbf-benches --bin peer-compare -- --fit 0 --eval 0 --mesh
    python3 benches/peers/sample_and_march.py
"""
import json
import os
import tempfile
import time

import numpy as np
from scipy.spatial.distance import cdist
from skimage.measure import marching_cubes

tmp = tempfile.gettempdir()
model = json.load(open(os.path.join(tmp, "rbf-torus3000.json")))
lattice = json.load(open(os.path.join(tmp, "rbf-torus3000-lattice.json")))
C = np.array(model["centres"])
w = np.array(model["weights"])
a, b = model["constant"], np.array(model["linear"])
cells = lattice["cells"]
h = lattice["cell_size"]
origin = lattice["origin"]
axes = [origin[d] + np.arange(cells[d] + 1) * h for d in range(3)]
X, Y, Z = np.meshgrid(*axes, indexing="ij")
P = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)

t0 = time.perf_counter()
values = np.empty(len(P))
chunk = 20000
for s in range(0, len(P), chunk):
    r = cdist(P[s:s + chunk], C)
    values[s:s + chunk] = (r ** 3) @ w + a + P[s:s + chunk] @ b
t1 = time.perf_counter()
volume = values.reshape(X.shape)
verts, faces, _, _ = marching_cubes(volume, level=0.0, spacing=(h, h, h))
t2 = time.perf_counter()
print(f"# {len(P)} lattice points x {len(C)} centres; {len(faces)} triangles")
print(json.dumps({"records": [
    {"id": "mc_scipy_sample[K=3000,n=256]", "median_s": t1 - t0, "threads": "numpy"},
    {"id": "mc_skimage_march[K=3000,n=256]", "median_s": t2 - t1, "threads": 1},
    {"id": "mc_scipy_sample_and_march[K=3000,n=256]", "median_s": t2 - t0, "threads": "numpy"},
]}))
