"""examples/python/convert_dask.py on a 2-worker LocalCluster, run twice."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import rbfsurf
from conftest import mesh_topology, sphere_points, torus_points

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "python" / "convert_dask.py"


def test_convert_a_folder_with_dask_and_resume(tmp_path):
    meshes = tmp_path / "meshes"
    meshes.mkdir()
    p = sphere_points(120)
    rbfsurf.write_mesh(meshes / "sphere.obj", *rbfsurf.from_oriented_points(p, p).polygonize(16))
    points, normals = torus_points(24, 12)
    rbfsurf.write_mesh(meshes / "torus.ply", *rbfsurf.from_oriented_points(points, normals).polygonize(20))
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 2) for z in (0, 1)], float)
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    rbfsurf.write_mesh(meshes / "box.stl", v, f)
    (meshes / "broken.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    out = tmp_path / "models"
    command = [sys.executable, str(EXAMPLE), str(meshes), str(out), "--resolution", "24", "--workers", "2"]

    first = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert first.returncode == 1, first.stdout + first.stderr  # one mesh failed
    summary = {r["mesh"]: r for r in json.loads((out / "summary.json").read_text())}
    assert {m: r["status"] for m, r in summary.items()} == {
        "box.stl": "done", "broken.obj": "failed", "sphere.obj": "done", "torus.ply": "done"
    }
    assert "broken.obj" in summary["broken.obj"]["error"]
    assert "3 converted, 0 skipped (already done), 1 failed" in first.stdout
    for name, genus in [("sphere.obj", 0), ("torus.ply", 1), ("box.stl", 0)]:
        model = rbfsurf.load(out / f"{name}.json")
        report = json.loads((out / f"{name}.report.json").read_text())
        assert report["source"]["resolution"] == 24 and report["source"]["method"] == "iterative"
        assert report["centres"] == len(model.centres) and report["watertight"]
        V, F = model.polygonize(32, method="grid")
        assert mesh_topology(V, F) == (True, 1, 2 - 2 * genus), name
    stamps = {p.name: p.stat().st_mtime_ns for p in out.glob("*.json") if p.name != "summary.json"}

    second = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert second.returncode == 1
    assert "0 converted, 3 skipped (already done), 1 failed" in second.stdout, second.stdout
    assert {p.name: p.stat().st_mtime_ns for p in out.glob("*.json") if p.name != "summary.json"} == stamps
    skipped = {r["mesh"]: r for r in json.loads((out / "summary.json").read_text())}
    assert skipped["torus.ply"]["centres"] == summary["torus.ply"]["centres"], "filled from the report"

    # Other settings, or a changed mesh, are not the finished work: converted again.
    (meshes / "broken.obj").unlink()
    third = subprocess.run(command[:-3] + ["20", "--workers", "2"], capture_output=True, text=True, timeout=600)
    assert third.returncode == 0, third.stdout + third.stderr
    assert "3 converted, 0 skipped (already done), 0 failed" in third.stdout, third.stdout
    assert json.loads((out / "box.stl.report.json").read_text())["source"]["resolution"] == 20
