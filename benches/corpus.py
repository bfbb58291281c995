#!/usr/bin/env python3
"""The conversion corpus: every mesh of ../shared/data/meshes converted by `rbf convert` at one
resolution, then measured against the mesh itself, in one table.

For each mesh: the whole command's wall time, the constraints of the kept model (rows: a normal
constraint counts two), the loop's own voxel errors (max / RMS over boundary voxels, as `rbf
convert` prints them; "(rival)" where the loop fell short and its rival, normal constraints at
the mesh's vertices, was kept, with the rival's errors), the two-way
distance between the model's surface and the mesh (`rbf compare --voxels N --json`: mean, RMS
and Hausdorff in voxels of the same grid), and the genus and components of the model's surface
against the mesh's, as `rbf convert` measured them and again on `rbf mesh`'s lattice at four
times the resolution (written after the first when they differ). Meshes that are open or
broken get what rbf answered (its error, or what it did to close them). The last column says whether the conversion meets every goal of the
corpus: topology kept, two-way Hausdorff ≤ 1.5 voxels, RMS ≤ 0.25 voxel (the worse direction),
≤ 30 s, ≤ 4000 constraints.

    cargo build --release -p rbf-cli
    python3 benches/corpus.py [--resolution 128] [--meshes DIR] [NAME ...]

Prints one JSON line per mesh as it goes (to stderr), then a Markdown table (stdout). Needs
only the Python standard library.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
rbf = os.environ.get("RBF", os.path.join(root, "target", "release", "rbf"))

GOALS = dict(hausdorff=1.5, rms=0.25, seconds=30.0, constraints=4000)


def convert(path, resolution, out_dir):
    """Runs `rbf convert` and `rbf compare` on one mesh; returns a dict of what they said."""
    name = os.path.splitext(os.path.basename(path))[0]
    model = os.path.join(out_dir, name + ".json")
    report = os.path.join(out_dir, name + "-report.json")
    start = time.perf_counter()
    done = subprocess.run(
        [rbf, "convert", path, "-o", model, "--resolution", str(resolution),
         "--report", report, "-q"],
        capture_output=True, text=True)
    row = dict(mesh=name, seconds=round(time.perf_counter() - start, 2))
    if done.returncode != 0:
        row["answer"] = " ".join(done.stderr.split())[:160]
        return row
    with open(report) as f:
        r = json.load(f)
    with open(model) as f:
        # Rows of the system: a normal constraint (the loop's rival) is two.
        row["constraints"] = sum(2 if c["kind"] == "normal" else 1
                                 for c in json.load(f)["constraints"])
    best = next(i for i in r["iterations"] if i["iteration"] == r["best_iteration"])
    rival = r.get("rival") or {}
    if rival.get("kept"):
        best = rival
        row["rival"] = True
    row["loop_max"] = round(best["max_error_voxels"], 2)
    row["loop_rms"] = round(best["rms_error_voxels"], 2)
    topology = r.get("topology") or {}
    row["genus"] = topology.get("genus")
    row["components"] = topology.get("components")
    row["mesh_genus"] = topology.get("mesh_genus")
    row["mesh_components"] = topology.get("mesh_components")
    compared = subprocess.run(
        [rbf, "compare", model, path, "--voxels", str(resolution), "--json", "-q"],
        capture_output=True, text=True)
    if compared.returncode == 0:
        c = json.loads(compared.stdout)
        ways = [c["mesh_to_surface"]["voxels"], c["surface_to_mesh"]["voxels"]]
        row["mean"] = round(max(w["mean"] for w in ways), 3)
        row["rms"] = round(max(w["rms"] for w in ways), 3)
        row["hausdorff"] = round(max(w["max"] for w in ways), 2)
    else:
        row["answer"] = " ".join(compared.stderr.split())[:160]
    # The topology again on a lattice of its own: `rbf mesh` at four times the resolution, over
    # the model's box (a different lattice from the one `rbf convert` measured on). A part or
    # a gap finer than both lattices can show on one and not the other; the goal asks both.
    fine = os.path.join(out_dir, name + "-fine.ply")
    meshed = subprocess.run(
        [rbf, "mesh", model, "-o", fine, "--resolution", str(4 * resolution), "-q"],
        capture_output=True, text=True)
    checked = subprocess.run([rbf, "check", fine, "--json", "-q"], capture_output=True,
                             text=True) if meshed.returncode == 0 else meshed
    if checked.returncode == 0:
        c = json.loads(checked.stdout)
        row["fine_genus"], row["fine_components"] = c["genus"], c["components"]
    goal = (row["mesh_genus"], row["mesh_components"])
    kept = ((row["genus"], row["components"]) == goal
            and (row.get("fine_genus"), row.get("fine_components")) == goal)
    row["goals"] = bool(
        kept and row.get("hausdorff", 1e9) <= GOALS["hausdorff"]
        and row.get("rms", 1e9) <= GOALS["rms"] and row["seconds"] <= GOALS["seconds"]
        and row["constraints"] <= GOALS["constraints"])
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="meshes by name (default: every .obj)")
    ap.add_argument("--resolution", type=int, default=128)
    ap.add_argument("--meshes", default=os.path.join(root, "..", "shared", "data", "meshes"))
    args = ap.parse_args()
    names = args.names or sorted(os.path.splitext(f)[0] for f in os.listdir(args.meshes)
                                 if f.endswith(".obj"))
    out_dir = tempfile.mkdtemp(prefix="rbf-corpus-")
    rows = []
    for name in names:
        row = convert(os.path.join(args.meshes, name + ".obj"), args.resolution, out_dir)
        rows.append(row)
        print(json.dumps(row), file=sys.stderr, flush=True)
    print(f"| mesh | time (s) | constraints | loop max / RMS | mean / RMS / Hausdorff to the mesh "
          f"| genus, pieces (mesh's) | all goals |")
    print("|---|---:|---:|---|---|---|---|")
    for r in rows:
        if "constraints" not in r:
            print(f"| {r['mesh']} | {r['seconds']} | | | | {r['answer']} | |")
            continue
        topology = (f"{r['genus']}, {r['components']} ({r['mesh_genus']}, "
                    f"{r['mesh_components']})")
        fine = (r.get("fine_genus"), r.get("fine_components"))
        if fine != (r["genus"], r["components"]):
            topology += f"; at {4 * args.resolution}: {fine[0]}, {fine[1]}"
        distances = (f"{r['mean']} / {r['rms']} / {r['hausdorff']}" if "hausdorff" in r
                     else r.get("answer", ""))
        rival = " (rival)" if r.get("rival") else ""
        print(f"| {r['mesh']} | {r['seconds']} | {r['constraints']} | {r['loop_max']} / "
              f"{r['loop_rms']}{rival} | {distances} | {topology} | {'yes' if r['goals'] else 'no'} |")
    met = sum(r.get("goals", False) for r in rows)
    converted = sum("constraints" in r for r in rows)
    print(f"\n{met} of {converted} converted meshes meet every goal (voxels of a grid of "
          f"{args.resolution} along the longest side; goals: topology kept, Hausdorff ≤ "
          f"{GOALS['hausdorff']}, RMS ≤ {GOALS['rms']}, ≤ {GOALS['seconds']:g} s, ≤ "
          f"{GOALS['constraints']} constraints).")


if __name__ == "__main__":
    main()
