#!/usr/bin/env python3
"""rbfsurf (the Python package) beside scipy's RBFInterpolator, through Python, in one sitting.

Workloads (the issue's): evaluation of a K = 2000 cubic interpolant at 10⁶ points; a fit of
K = 8000 points; and the same evaluation through the CLI, `rbf eval MODEL points.npy -o
values.npy` (reading and writing .npy, model file read included). Data: K scattered points in
the unit cube with values sin(2x) + y² − 0.5 + 0.3 cos z (the fixtures' function), evaluation
points uniform in the cube. Both libraries solve the same system (r³, degree 1, no smoothing);
the values are compared too.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install ./python scipy
    cargo build --release -p rbf-cli
    /tmp/venv/bin/python benches/peers/python_vs_scipy.py [--repeats 3]

Prints a table of median wall times and ratios (scipy / rbfsurf).
"""
import argparse
import os
import subprocess
import tempfile
import time

import numpy as np
from scipy.interpolate import RBFInterpolator as ScipyRBF

import rbfsurf

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
rbf = os.environ.get("RBF", os.path.join(root, "target", "release", "rbf"))


def data(k, m, seed=0):
    rng = np.random.default_rng(seed)
    y = rng.uniform(-1, 1, (k, 3))
    d = np.sin(2 * y[:, 0]) + y[:, 1] ** 2 - 0.5 + 0.3 * np.cos(y[:, 2])
    x = rng.uniform(-1, 1, (m, 3))
    return y, d, x


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rows = []

    y, d, x = data(2000, 1_000_000)
    ours, theirs = rbfsurf.RBFInterpolator(y, d), ScipyRBF(y, d, kernel="cubic")
    t_ours, a = median_time(lambda: ours(x), args.repeats)
    t_theirs, b = median_time(lambda: theirs(x), max(1, args.repeats - 2))
    agree = np.abs(a - b).max() / np.abs(b).max()
    rows.append(("evaluate K=2000 at 10^6 points (Python)", t_theirs, t_ours, agree))

    with tempfile.TemporaryDirectory() as tmp:
        model, points, values = (os.path.join(tmp, n) for n in ("m.json", "x.npy", "v.npy"))
        ours.models[0].save(model)
        np.save(points, x)
        t_cli, _ = median_time(
            lambda: subprocess.run([rbf, "eval", model, points, "-o", values], check=True),
            args.repeats,
        )
        c = np.load(values)
        rows.append(("evaluate K=2000 at 10^6 points (rbf eval, .npy)", t_theirs, t_cli, np.abs(c - b).max() / np.abs(b).max()))

    y, d, x = data(8000, 2000, seed=1)
    t_ours, f = median_time(lambda: rbfsurf.RBFInterpolator(y, d), args.repeats)
    t_theirs, g = median_time(lambda: ScipyRBF(y, d, kernel="cubic"), max(1, args.repeats - 2))
    rows.append(("fit K=8000", t_theirs, t_ours, np.abs(f(x) - g(x)).max() / np.abs(g(x)).max()))

    print(f"{'workload':52} {'scipy s':>9} {'rbfsurf s':>10} {'ratio':>7} {'max rel. diff':>14}")
    for name, s, r, diff in rows:
        print(f"{name:52} {s:9.3f} {r:10.3f} {s / r:6.1f}x {diff:14.1e}")


if __name__ == "__main__":
    main()
