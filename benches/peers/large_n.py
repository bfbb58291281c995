#!/usr/bin/env python3
"""Large systems solved whole: `rbf fit --method fast` beside ferreus-rbf (fast multipole,
domain decomposition, FGMRES), on the shared peers' surface problem, in one sitting.

The problem is `surface_problem(N)` of ../shared/peers/ferreus/problems.py: N/2 points on a
bumpy sphere (value 0) and N/2 moved 0.01 inward along the true normal (value 0.01). Both tools
interpolate every point with r³ and a linear polynomial. rbf runs with its defaults (a residual
of 1e-5 of max|h|, at every row by a product or by GMRES's recurrence certified at sampled rows;
from 4·10⁵ rows, through the far field, certified at sampled rows), then at ferreus-rbf's accuracy (--max-residual 1e-4); ferreus-rbf
for its relative
tolerance 1e-6 with the tuned domain decomposition of ../shared/peers/README.md. Both are then
checked the same way: f at 2000 sampled rows by direct sums in numpy (float64), against h.

    pip install numpy ferreus-rbf
    cargo build --release -p rbf-cli
    python3 benches/peers/large_n.py [N ...]        # default 100000

Prints one JSON line per tool and N: seconds (wall, the whole command for rbf, reading the
.npy file included), peak resident memory, and the worst sampled residual relative to max|h|.
"""
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
sys.path.insert(0, os.path.join(root, "..", "shared", "peers", "ferreus"))
import problems  # noqa: E402

rbf = os.environ.get("RBF", os.path.join(root, "target", "release", "rbf"))
tmp = tempfile.mkdtemp()


def direct(centres, weights, constant, linear, x):
    """f(x) = Σ wⱼ |x − cⱼ|³ + constant + linear·x, in chunks of 64 points."""
    out = np.empty(len(x))
    for s in range(0, len(x), 64):
        d = np.linalg.norm(x[s:s + 64, None, :] - centres[None, :, :], axis=2)
        out[s:s + 64] = (d ** 3) @ weights + constant + x[s:s + 64] @ linear
    return out


def worst_miss(f_rows, h):
    return float(np.max(np.abs(f_rows - h)) / np.max(np.abs(h)))


def run(n):
    P, h = problems.surface_problem(n)
    rows = np.random.default_rng(1).choice(n, size=2000, replace=False)
    path = os.path.join(tmp, f"surface-{n}.npy")
    np.save(path, np.column_stack([P, h]))
    for extra in ([], ["--max-residual", "1e-4"]):
        model = os.path.join(tmp, f"rbf-{n}.json")
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        t = time.perf_counter()
        subprocess.run([rbf, "fit", path, "-o", model, "--method", "fast", "-q", *extra],
                       check=True)
        seconds = time.perf_counter() - t
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        m = json.load(open(model))
        f = direct(np.array(m["centres"]), np.array(m["weights"]), m["constant"],
                   np.array(m["linear"]), P[rows])
        print(json.dumps(dict(tool=" ".join(["rbf fit --method fast", *extra]), N=n,
                              seconds=round(seconds, 2),
                              peak_MiB=round(max(peak, before) / 1024),
                              iterations=m["report"].get("iterations"),
                              worst_sampled_residual=worst_miss(f, h[rows]))), flush=True)
    try:
        import ferreus_rbf as fr
        from ferreus_rbf.config import DDMParams, Params, SizePolicy
        from ferreus_rbf.interpolant_config import (Drift, FittingAccuracy,
                                                    FittingAccuracyType, InterpolantSettings,
                                                    RBFKernelType)
    except ImportError:
        print("ferreus-rbf is not installed (pip install ferreus-rbf)", file=sys.stderr)
        return
    settings = InterpolantSettings(
        RBFKernelType.Cubic, drift=Drift.Linear,
        fitting_accuracy=FittingAccuracy(1e-6, FittingAccuracyType.Relative))
    params = Params(RBFKernelType.Cubic,
                    ddm_params=DDMParams(256, 32, 128, SizePolicy.Fixed(4096)))
    t = time.perf_counter()
    fitted = fr.RBFInterpolator(P, h, settings, params=params)
    seconds = time.perf_counter() - t
    f = np.asarray(fitted.evaluate(P[rows])).ravel()
    print(json.dumps(dict(tool="ferreus-rbf 0.3, tuned DDM, tol 1e-6", N=n,
                          seconds=round(seconds, 2),
                          process_peak_MiB=round(
                              resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024),
                          worst_sampled_residual=worst_miss(f, h[rows]))), flush=True)


for n in [int(a) for a in sys.argv[1:]] or [100_000]:
    run(n)
