#!/usr/bin/env python3
"""Whole real meshes by normal constraints: every vertex of a closed mesh becomes a normal
constraint (two rows), fitted with every default by `rbf convert MESH --method normals`.

The meshes of ../shared/data/meshes have at most 35 002 vertices; the goal is stated at 5·10⁴.
So each mesh named is also refined to 5·10⁴ vertices the way a scanned mesh is made: one Loop
subdivision, then quadric edge-collapse decimation to 10⁵ triangles (pymeshlab, from PyPI; a
benchmark tool, never a dependency of rbf). The refined meshes keep the originals' shape and
topology and get the uneven triangles of a decimated mesh.

    cargo build --release -p rbf-cli
    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pymeshlab
    /tmp/venv/bin/python benches/whole_meshes.py [--meshes DIR] [NAME ...]

Prints a Markdown table: vertices, rows, wall time and peak memory of the whole command
(/usr/bin/time), iterations and the residual rbf reports.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
rbf = os.environ.get("RBF", os.path.join(root, "target", "release", "rbf"))


def refine(source, target, faces=100_000):
    """Loop subdivision once, then quadric decimation to `faces` triangles."""
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(source)
    ms.meshing_surface_subdivision_loop(iterations=1, threshold=pymeshlab.PercentageValue(0.1))
    ms.meshing_decimation_quadric_edge_collapse(targetfacenum=faces, preservetopology=True)
    ms.save_current_mesh(target)
    return ms.current_mesh().vertex_number()


def convert(path, out_dir):
    """Runs `rbf convert --method normals` under /usr/bin/time; returns the table's cells."""
    model = os.path.join(out_dir, "model.json")
    run = subprocess.run(
        ["/usr/bin/time", "-f", "TIME %e %M", rbf, "convert", path, "--method", "normals",
         "-o", model],
        capture_output=True, text=True)
    err = run.stderr
    time_line = re.search(r"TIME ([0-9.]+) ([0-9]+)", err)
    summary = re.search(r"(\d+) rows, residual ([0-9.e+-]+), (\d+) iterations", err)
    if run.returncode != 0 or not time_line or not summary:
        return dict(failed=err.strip().splitlines()[-1] if err.strip() else run.returncode)
    return dict(rows=int(summary.group(1)), residual=summary.group(2),
                iterations=int(summary.group(3)), seconds=float(time_line.group(1)),
                gigabytes=int(time_line.group(2)) / 1e6)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshes", default=os.path.join(root, "..", "shared", "data", "meshes"))
    parser.add_argument("names", nargs="*", default=["falconstatue", "hammer", "nefertiti"])
    args = parser.parse_args()
    print("| mesh | vertices | rows | time | peak | iterations | residual (of max\\|h\\|) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as out_dir:
        for name in args.names:
            source = os.path.join(args.meshes, name + ".obj")
            refined = os.path.join(out_dir, name + "-50k.obj")
            vertices = refine(source, refined)
            for label, path, count in [(name, source, None), (name + ", refined", refined, vertices)]:
                cells = convert(path, out_dir)
                if "failed" in cells:
                    print(f"| {label} | {count or ''} | | failed: {cells['failed']} | | | |")
                    continue
                count = count or cells["rows"] // 2
                print(f"| {label} | {count} | {cells['rows']} | {cells['seconds']:.1f} s | "
                      f"{cells['gigabytes']:.2f} GB | {cells['iterations']} | {cells['residual']} |")
                sys.stdout.flush()


if __name__ == "__main__":
    main()
