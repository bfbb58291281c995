#!/usr/bin/env python3
"""Large point sets: `rbf fit --greedy` beside ferreus-rbf (fast multipole, domain
decomposition, FGMRES), on the shared peers' surface problem.

The problem is `surface_problem(N)` of ../shared/peers/ferreus/problems.py: N/2 points on a
bumpy sphere (value 0) and N/2 moved 0.01 inward along the true normal (value 0.01), so that f
approximates the signed distance near the surface. ferreus-rbf interpolates every point (cubic,
linear drift, relative tolerance 1e-6, the tuned domain decomposition of the shared README);
rbf fits a greedy subset until every point is met within the tolerance. Both are then measured
the same way: |f| at 20 000 fresh points of the true surface, which is (to first order) how far
the zero set lies from it.

    pip install ferreus-rbf
    cargo build --release -p rbf-cli
    python3 benches/peers/large_n.py [N]
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
sys.path.insert(0, os.path.join(root, "..", "shared", "peers", "ferreus"))
import problems  # noqa: E402

N = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
P, v = problems.surface_problem(N)
Q, _ = problems._surface(problems._dirs(np.random.default_rng(2024), 20_000))
rbf = os.path.join(root, "target", "release", "rbf")
tmp = tempfile.mkdtemp()
records = []


def report(name, seconds, f, centres):
    err = np.abs(f)
    rec = dict(tool=name, N=N, seconds=round(seconds, 3), centres=centres,
               max_error=float(err.max()), rms_error=float(np.sqrt(np.mean(err ** 2))))
    records.append(rec)
    print(json.dumps(rec), flush=True)


# rbf: greedy subsets at two tolerances (fractions of the box's longest side, about 2.2).
points = os.path.join(tmp, "points.txt")
np.savetxt(points, np.column_stack([P, v]), fmt="%.12f")
np.savetxt(os.path.join(tmp, "queries.txt"), Q, fmt="%.12f")
for tol in ["1e-4", "1e-5"]:
    model = os.path.join(tmp, f"rbf-{tol}.json")
    t = time.perf_counter()
    subprocess.run([rbf, "fit", points, "-o", model, "--greedy", "--tolerance", tol,
                    "--max-centres", "20000", "-q"], check=True)
    seconds = time.perf_counter() - t
    out = subprocess.run([rbf, "eval", model, os.path.join(tmp, "queries.txt")],
                         check=True, capture_output=True, text=True).stdout
    f = np.array([float(x) for x in out.split()])
    centres = len(json.load(open(model))["centres"])
    report(f"rbf fit --greedy --tolerance {tol} (incl. reading {N} lines)", seconds, f, centres)

# ferreus-rbf, every point a centre.
try:
    import ferreus_rbf as fr
    from ferreus_rbf.config import DDMParams, Params, SizePolicy
    from ferreus_rbf.interpolant_config import (Drift, FittingAccuracy, FittingAccuracyType,
                                                InterpolantSettings, RBFKernelType)
except ImportError:
    print("ferreus-rbf is not installed (pip install ferreus-rbf)", file=sys.stderr)
    sys.exit(0)
settings = InterpolantSettings(RBFKernelType.Cubic, drift=Drift.Linear,
                               fitting_accuracy=FittingAccuracy(1e-6, FittingAccuracyType.Relative))
params = Params(RBFKernelType.Cubic, ddm_params=DDMParams(256, 32, 128, SizePolicy.Fixed(4096)))
t = time.perf_counter()
model = fr.RBFInterpolator(P, v, settings, params=params)
seconds = time.perf_counter() - t
f = np.asarray(model.evaluate(Q)).ravel()
report("ferreus-rbf 0.3, tuned DDM, tol 1e-6", seconds, f, N)
