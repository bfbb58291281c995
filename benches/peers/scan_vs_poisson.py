#!/usr/bin/env python3
"""Scans to surfaces: `rbf reconstruct` beside Open3D's screened Poisson pipeline (and
pymeshlab's, when installed), on the same simulated scans, in one sitting.

Each scan is made from a closed mesh of ../shared/data/meshes (or of the folder in the
environment variable MESHES_DIR: `benches/thin_meshes.py` makes one), seeded (`--seed`, 11 by
default) and repeatable:

- N points spread by area with an uneven density (a smooth random field over the object makes
  some regions up to four times as dense as others);
- holes: the points within 4 % of the diagonal of three random surface points are removed;
- Gaussian noise of σ = NOISE × the diagonal along every axis;
- outliers: 0.2 % more points, uniform in the box grown by a tenth;
- with `--sparse S`, only the share S of the points on one half (beyond the middle of the
  longest side) is kept, as if that half were scanned from farther away;
- with `--slices K`, a scan in lines instead of the spread and holes above: the points on K
  sweeps of parallel planes (each sweep in a random direction), `--slice-gap` (1 % of the
  diagonal by default) apart, as a stack of contours or a line scanner's profiles give them;
- with `--views K`, a scanner's sight instead of the spread, holes and axis-wise noise above:
  the points that K views from above see (orthographic depth maps around the object, 15–60°
  above the horizon of +y, so the underside and the deep concavities go unseen; grazing faces
  beyond 75° dropped; density by the cosine of the angle of view), points seen from several
  views kept once per view, and the noise along each view's line of sight;
- with `--misaligned M` beside `--views`, each view registered with an error: moved by a random
  offset (σ = M × the diagonal along every axis) and turned by a random angle (σ = M radians
  about a random axis through the object's centre), so that where views overlap the scan lies
  in two or more layers a few tenths of a percent apart, as scans merged from several
  registrations do.

No normals are given to either tool. Open3D (as its users run it): statistical outliers (20
neighbours, 2 deviations), normals from 20 neighbours, oriented by its tangent-plane MST,
screened Poisson at depth 9 (10 from 5·10⁵ points); pymeshlab: the same steps through MeshLab's
filters. rbf: `rbf reconstruct` with every default.

Measured against the true mesh, each from 10⁵ points spread by area on both surfaces: Chamfer
distance (the mean of the two mean nearest distances) and two-way Hausdorff, in % of the
diagonal; F-score at 0.5 % and 1 % of the diagonal (with `--exact`, also from the distances of
the same samples to the other surface's nearest triangles); the share of normals flipped (Open3D: its
oriented normals at the scan's points; rbf: the model's outward normal −∇f at the clean points;
both against the true face normals); watertight, components, genus (of the largest component);
wall time and peak memory of the whole tool (reading and writing included).

    python3 -m venv /tmp/scan-venv && /tmp/scan-venv/bin/pip install numpy scipy trimesh networkx open3d pymeshlab
    apt-get install libusb-1.0-0    # Open3D's wheel loads it (an ImportError without it)
    cargo build --release -p rbf-cli
    /tmp/scan-venv/bin/python benches/peers/scan_vs_poisson.py [--points 100000]
        [--noise 0 0.002 0.005 0.01] [--sparse 0.08 | --views 8 [--misaligned 0.001] | --slices 1 [--slice-gap 0.01]] [--seed 11] [--tools rbf open3d meshlab] [--exact]
        [MESH ...]

Prints one JSON line per scan and tool, then a Markdown table.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import trimesh
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
meshes_dir = os.environ.get("MESHES_DIR") or os.path.join(root, "..", "shared", "data", "meshes")
rbf = os.environ.get("RBF", os.path.join(root, "target", "release", "rbf"))
DEFAULT_MESHES = ["bunny_small", "spot", "cow", "knot", "torus", "koala"]


def with_outliers(mesh, noisy, rng):
    """The cloud: `noisy` with 0.2 % more points uniform in the box grown by a tenth, shuffled;
    which of its points are real, and the shuffle."""
    n = len(noisy)
    m = max(1, int(0.002 * n))
    grow = 0.1 * mesh.extents
    outliers = rng.uniform(mesh.bounds[0] - grow, mesh.bounds[1] + grow, size=(m, 3))
    real = np.concatenate([np.ones(n, bool), np.zeros(m, bool)])
    order = rng.permutation(n + m)
    return np.vstack([noisy, outliers])[order], real[order], order


def simulate(mesh, n, noise, seed, sparse=None):
    """(points, clean points, true normals of the clean points, mask of real points).

    With `sparse`, only that share of the points beyond the middle of the longest side is kept
    (one half scanned from farther away): n counts the points before."""
    rng = np.random.default_rng(seed)
    diag = float(np.linalg.norm(mesh.extents))
    lo = mesh.bounds[0]
    # Uneven density: accept each candidate with a probability from a smooth random field.
    k = rng.normal(size=(4, 3)) * 2.0 * np.pi / diag
    phase = rng.uniform(0, 2 * np.pi, 4)
    pts, normals = np.empty((0, 3)), np.empty((0, 3))
    holes, _ = trimesh.sample.sample_surface(mesh, 3, seed=int(rng.integers(1 << 31)))
    while len(pts) < n:
        p, faces = trimesh.sample.sample_surface(mesh, 2 * n, seed=int(rng.integers(1 << 31)))
        field = np.mean(np.sin((p - lo) @ k.T + phase), axis=1)  # in [-1, 1]
        keep = rng.uniform(size=len(p)) < 0.25 + 0.75 * (field + 1) / 2
        near_hole = np.min(np.linalg.norm(p[:, None, :] - holes[None], axis=2), axis=1)
        keep &= near_hole > 0.04 * diag
        pts = np.vstack([pts, p[keep]])
        normals = np.vstack([normals, mesh.face_normals[faces[keep]]])
    clean, normals = pts[:n], normals[:n]
    if sparse is not None:
        axis = int(np.argmax(mesh.extents))
        middle = 0.5 * (mesh.bounds[0][axis] + mesh.bounds[1][axis])
        keep = (clean[:, axis] < middle) | (rng.uniform(size=n) < sparse)
        clean, normals, n = clean[keep], normals[keep], int(keep.sum())
    noisy = clean + rng.normal(size=clean.shape) * noise * diag
    cloud, real, order = with_outliers(mesh, noisy, rng)
    return cloud, clean, normals, real, order


def simulate_slices(mesh, n, noise, seed, sweeps, gap):
    """Like `simulate`, but the points lie on `sweeps` sets of parallel planes `gap` × the
    diagonal apart (each set in a random direction): n of them, evenly along the lines."""
    rng = np.random.default_rng(seed)
    diag = float(np.linalg.norm(mesh.extents))
    # Bands 4 % of the gap wide keep about 4 % of the candidates.
    candidates, faces = trimesh.sample.sample_surface(mesh, 30 * n,
                                                      seed=int(rng.integers(1 << 31)))
    on_line = np.zeros(len(candidates), bool)
    for direction in rng.normal(size=(sweeps, 3)):
        t = candidates @ (direction / np.linalg.norm(direction)) / (gap * diag)
        on_line |= np.abs(t - np.round(t)) < 0.02
    pick = rng.permutation(np.flatnonzero(on_line))[:n]
    clean, normals = candidates[pick], mesh.face_normals[faces[pick]]
    noisy = clean + rng.normal(size=clean.shape) * noise * diag
    cloud, real, order = with_outliers(mesh, noisy, rng)
    return cloud, clean, normals, real, order


def simulate_views(mesh, n, noise, seed, views, misaligned=0.0):
    """Like `simulate`, but what a scanner sees from `views` directions above the object, each
    view registered with an error of `misaligned` (a share of the diagonal, and radians)."""
    rng = np.random.default_rng(seed)
    errors = np.random.default_rng(seed + 1)
    diag = float(np.linalg.norm(mesh.extents))
    candidates, faces = trimesh.sample.sample_surface(mesh, 40 * n, seed=int(rng.integers(1 << 31)))
    face_normals = mesh.face_normals[faces]
    pixel = diag / 500.0
    turn = rng.uniform(0, 2 * np.pi)
    seen_points, seen_normals, seen_rays = [], [], []
    for v in range(views):
        azimuth = turn + 2 * np.pi * v / views
        elevation = np.radians(rng.uniform(15, 60))
        # The direction the view looks along (from the scanner toward the object), y up.
        d = -np.array([np.cos(elevation) * np.cos(azimuth), np.sin(elevation),
                       np.cos(elevation) * np.sin(azimuth)])
        a = np.cross(d, [0.0, 1.0, 0.0])
        a /= np.linalg.norm(a)
        b = np.cross(d, a)
        facing = -(face_normals @ d)
        u = np.floor(candidates @ a / pixel).astype(np.int64)
        w = np.floor(candidates @ b / pixel).astype(np.int64)
        u -= u.min()
        w -= w.min()
        cell = u * (w.max() + 1) + w
        depth = candidates @ d
        front = np.full(cell.max() + 1, np.inf)
        np.minimum.at(front, cell, depth)
        visible = (depth <= front[cell] + 1.5 * pixel) & (facing > np.cos(np.radians(75)))
        visible &= rng.uniform(size=len(candidates)) < facing
        seen = candidates[visible]
        if misaligned > 0:
            axis = errors.normal(size=3)
            turn_by = trimesh.transformations.rotation_matrix(
                errors.normal() * misaligned, axis / np.linalg.norm(axis), mesh.centroid)[:3, :3]
            centre = mesh.centroid
            seen = (seen - centre) @ turn_by.T + centre + errors.normal(size=3) * misaligned * diag
        seen_points.append(seen)
        seen_normals.append(face_normals[visible])
        seen_rays.append(np.broadcast_to(d, (int(visible.sum()), 3)))
    clean = np.vstack(seen_points)
    normals = np.vstack(seen_normals)
    rays = np.vstack(seen_rays)
    pick = rng.permutation(len(clean))[:n]
    clean, normals, rays = clean[pick], normals[pick], rays[pick]
    n = len(clean)
    noisy = clean + rays * rng.normal(size=(n, 1)) * noise * diag
    cloud, real, order = with_outliers(mesh, noisy, rng)
    return cloud, clean, normals, real, order


def timed(command):
    """Runs a command under /usr/bin/time: (result fields, wall seconds, peak MiB)."""
    with tempfile.NamedTemporaryFile(suffix=".time") as f:
        t = time.perf_counter()
        done = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", f.name, *command],
                              capture_output=True, text=True)
        seconds = time.perf_counter() - t
        peak = int(open(f.name).read().split()[-1]) / 1024
    r = dict(seconds=round(seconds, 2), peak_MiB=round(peak))
    if done.returncode != 0:
        r["error"] = done.stderr.strip()[-300:]
    return r


def run_rbf(cloud_path, out_dir):
    mesh_path = os.path.join(out_dir, "rbf.ply")
    model_path = os.path.join(out_dir, "rbf.json")
    r = timed([rbf, "reconstruct", cloud_path, "-o", mesh_path, "--model", model_path, "-q"])
    return dict(r, mesh=mesh_path, model=model_path)


# Open3D and pymeshlab run in a child process each, so that their time and peak memory are
# measured like rbf's.
OPEN3D = r"""
import sys, numpy as np, open3d as o3d
cloud, out, normals_out, depth = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(np.load(cloud)))
pcd, kept = pcd.remove_statistical_outlier(nb_neighbors=20, std_ratio=2.0)
pcd.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(knn=20))
pcd.orient_normals_consistent_tangent_plane(20)
mesh, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=depth)
o3d.io.write_triangle_mesh(out, mesh)
np.save(normals_out, np.column_stack([np.array(kept, float), np.asarray(pcd.normals)]))
"""

MESHLAB = r"""
import sys, numpy as np, pymeshlab
cloud, out, depth = sys.argv[1], sys.argv[2], int(sys.argv[3])
ms = pymeshlab.MeshSet()
ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.load(cloud)))
ms.compute_selection_point_cloud_outliers(propthreshold=0.8, knearest=20)
ms.meshing_remove_selected_vertices()
ms.compute_normal_for_point_clouds(k=20, smoothiter=0)
ms.generate_surface_reconstruction_screened_poisson(depth=depth)
ms.save_current_mesh(out)
"""


def run_child(script, args):
    return timed([sys.executable, "-c", script, *args])


def pieces_and_genus(mesh):
    """Connected pieces (by shared vertices) and the genus of the largest, from Euler's formula
    (None if it is open): cheap on meshes of thousands of crumbs, where splitting is not."""
    faces = mesh.faces
    n = len(mesh.vertices)
    edges = np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    face_label = labels[faces[:, 0]]
    counts = np.bincount(face_label)
    largest = int(np.argmax(counts))
    f = faces[face_label == largest]
    v = len(np.unique(f))
    e = len(np.unique(np.sort(np.vstack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1),
                      axis=0))
    # A piece with boundary edges (an edge in one face) has no genus to speak of.
    edge_faces = np.unique(np.sort(np.vstack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1),
                           axis=0, return_counts=True)[1]
    genus = int(round((2 - (v - e + len(f))) / 2)) if np.all(edge_faces == 2) else None
    return int(np.count_nonzero(counts)), genus


def surface_metrics(path, truth, truth_samples, diag, exact=False):
    mesh = trimesh.load(path, force="mesh", process=True)
    if len(mesh.faces) == 0:
        return dict(error="empty mesh")
    components, genus = pieces_and_genus(mesh)
    samples, _ = trimesh.sample.sample_surface(mesh, len(truth_samples), seed=7)
    d_to_truth, _ = cKDTree(truth_samples).query(samples)
    d_to_mesh, _ = cKDTree(samples).query(truth_samples)
    out = dict(
        chamfer_pct=round(100 * 0.5 * (d_to_truth.mean() + d_to_mesh.mean()) / diag, 4),
        hausdorff_pct=round(100 * max(d_to_truth.max(), d_to_mesh.max()) / diag, 3),
        watertight=bool(mesh.is_watertight),
        components=components,
        genus=genus,
    )
    for tau in (0.005, 0.01):
        precision = float(np.mean(d_to_truth < tau * diag))
        recall = float(np.mean(d_to_mesh < tau * diag))
        f = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
        out[f"f_score_{tau * 100:g}pct"] = round(f, 4)
    if exact:
        # The same samples, each measured to the other surface's nearest triangle rather than
        # to its nearest sample: no grain of the other surface's sampling (10^5 samples lie some
        # tenths of a percent of the diagonal apart) in the distances.
        _, to_mesh, _ = trimesh.proximity.closest_point(mesh, truth_samples)
        _, to_truth, _ = trimesh.proximity.closest_point(truth, samples)
        for tau in (0.005, 0.01):
            precision = float(np.mean(to_truth < tau * diag))
            recall = float(np.mean(to_mesh < tau * diag))
            f = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
            out[f"f_score_{tau * 100:g}pct_exact"] = round(f, 5)
    return out


def flipped_rbf(model_path, clean, normals, out_dir):
    pts = os.path.join(out_dir, "clean.npy")
    grads = os.path.join(out_dir, "grads.npy")
    np.save(pts, clean)
    subprocess.run([rbf, "eval", model_path, pts, "--gradient", "-o", grads], check=True,
                   capture_output=True)
    g = np.load(grads)[:, 1:4]
    return float(np.mean(np.sum(-g * normals, axis=1) < 0))


def flipped_open3d(path, order, real, normals):
    data = np.load(path)
    kept, n = data[:, 0].astype(int), data[:, 1:4]
    original = order[kept]  # index into [clean points, outliers]
    is_real = original < len(normals)
    dots = np.sum(n[is_real] * normals[original[is_real]], axis=1)
    return float(np.mean(dots < 0))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("meshes", nargs="*", default=DEFAULT_MESHES)
    ap.add_argument("--points", type=int, default=100_000)
    ap.add_argument("--noise", type=float, nargs="+", default=[0.0, 0.002, 0.005])
    ap.add_argument("--depth", type=int, default=None, help="Poisson depth (9, 10 from 5e5)")
    ap.add_argument("--seed", type=int, default=11,
                    help="seed of the simulated scans (11: the README's tables)")
    ap.add_argument("--sparse", type=float, default=None,
                    help="keep only this share of the points on one half of each object")
    ap.add_argument("--views", type=int, default=None,
                    help="simulate a scanner's sight from this many views above the object")
    ap.add_argument("--misaligned", type=float, default=0.0,
                    help="with --views: each view registered with this error (a share of the "
                         "diagonal, and radians)")
    ap.add_argument("--slices", type=int, default=None,
                    help="simulate a scan in lines: this many sweeps of parallel planes")
    ap.add_argument("--slice-gap", type=float, default=0.01,
                    help="the planes' spacing with --slices, a share of the diagonal")
    ap.add_argument("--exact", action="store_true",
                    help="also F-scores by exact distances to each surface's triangles "
                         "(f_score_*_exact; slower)")
    ap.add_argument("--tools", nargs="+", default=["rbf", "open3d", "meshlab"],
                    help="which tools to run (rbf, open3d, meshlab)")
    args = ap.parse_args()
    if sum(x is not None for x in (args.views, args.sparse, args.slices)) > 1:
        ap.error("--views, --sparse and --slices are ways to simulate a scan: give one")
    if args.slices is not None and (args.slices < 1 or not args.slice_gap > 0):
        ap.error("--slices needs at least one sweep and a --slice-gap above 0")
    if args.views is not None and args.views < 1:
        ap.error("--views needs at least one view")
    if args.misaligned and args.views is None:
        ap.error("--misaligned moves the views of --views: give both")
    depth = args.depth or (10 if args.points >= 500_000 else 9)
    try:
        import pymeshlab  # noqa: F401
        have_meshlab = True
    except ImportError:
        have_meshlab = False
    rows = []
    for name in args.meshes:
        truth = trimesh.load(os.path.join(meshes_dir, name + ".obj"), force="mesh")
        diag = float(np.linalg.norm(truth.extents))
        truth_samples, _ = trimesh.sample.sample_surface(truth, 100_000, seed=3)
        for noise in args.noise:
            out_dir = tempfile.mkdtemp(prefix=f"scan-{name}-")
            if args.slices:
                cloud, clean, normals, real, order = simulate_slices(
                    truth, args.points, noise, args.seed, args.slices, args.slice_gap)
            elif args.views:
                cloud, clean, normals, real, order = simulate_views(
                    truth, args.points, noise, args.seed, args.views, args.misaligned)
            else:
                cloud, clean, normals, real, order = simulate(truth, args.points, noise,
                                                              seed=args.seed, sparse=args.sparse)
            cloud_path = os.path.join(out_dir, "cloud.npy")
            np.save(cloud_path, cloud)
            scan = dict(mesh=name, points=len(cloud), noise_pct=100 * noise)
            tools = [name for key, name in [("rbf", "rbf reconstruct"),
                                            ("open3d", "Open3D Poisson"),
                                            ("meshlab", "pymeshlab Poisson")]
                     if key in args.tools and (key != "meshlab" or have_meshlab)]
            for tool in tools:
                if tool == "rbf reconstruct":
                    r = run_rbf(cloud_path, out_dir)
                    path = r.get("mesh")
                elif tool == "Open3D Poisson":
                    path = os.path.join(out_dir, "open3d.ply")
                    nrm = os.path.join(out_dir, "open3d-normals.npy")
                    r = run_child(OPEN3D, [cloud_path, path, nrm, str(depth)])
                else:
                    path = os.path.join(out_dir, "meshlab.ply")
                    r = run_child(MESHLAB, [cloud_path, path, str(depth)])
                if "error" not in r:
                    r.update(surface_metrics(path, truth, truth_samples, diag, args.exact))
                    if tool == "rbf reconstruct":
                        r["flipped"] = flipped_rbf(r["model"], clean, normals, out_dir)
                    elif tool == "Open3D Poisson":
                        r["flipped"] = flipped_open3d(nrm, order, real, normals)
                if tool == "rbf reconstruct":
                    r.pop("mesh")
                    r.pop("model")
                row = dict(scan, tool=tool, **r)
                rows.append(row)
                print(json.dumps(row), flush=True)
    keys = ["mesh", "noise_pct", "tool", "seconds", "peak_MiB", "chamfer_pct", "hausdorff_pct",
            "f_score_0.5pct", "f_score_1pct", "flipped", "watertight", "components", "genus"]
    if args.exact:
        keys.insert(keys.index("f_score_1pct") + 1, "f_score_0.5pct_exact")
    print("\n| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for r in rows:
        cells = [r.get("error", "")[:60] if k == "seconds" and "error" in r else r.get(k, "")
                 for k in keys]
        print("| " + " | ".join(str(c) for c in cells) + " |")


if __name__ == "__main__":
    main()
