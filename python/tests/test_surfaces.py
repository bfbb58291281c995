"""Implicit surfaces from constraints and meshes: fits, polygons, pictures, volumes, sessions."""

import numpy as np
import pytest

import rbfsurf
from conftest import mesh_topology, sphere_points, torus_lattice, torus_points


def test_torus_from_oriented_points_polygonizes_watertight_genus_1():
    points, normals = torus_points()
    model = rbfsurf.from_oriented_points(points, normals)
    assert model.report["rows"] == 2 * len(points)
    assert np.abs(model(points)).max() < 1e-6
    V, F = model.polygonize(64)
    closed, components, chi = mesh_topology(V, F)
    assert closed and components == 1
    assert chi == 0, "genus 1: V - E + F = 0"
    # Vertices on f = 0 (to the polygonizer's root tolerance) and near the true torus.
    g = np.linalg.norm(model.gradient(V), axis=1)
    assert (np.abs(model(V)) / g).max() < 1e-5
    tube = np.hypot(np.hypot(V[:, 0], V[:, 1]) - 1.0, V[:, 2])
    assert np.abs(tube - 0.4).max() < 0.02
    # The grid method finds the same surface.
    V2, F2 = model.polygonize(48, method="grid")
    assert mesh_topology(V2, F2) == (True, 1, 0)


def test_fit_takes_every_constraint_kind_in_2d_and_3d():
    m = rbfsurf.fit(
        boundary=[[1, 0], [-1, 0]],
        normals=([[0, 1], [0, -1]], [[0, 1], [0, -1]]),
        interior=([[0, 0]], [2.0]),
        exterior=[[3, 3]],
        kernel="thin_plate_spline",
    )
    assert m.dim == 2 and m.kernel == "thin_plate_spline"
    assert np.allclose(m([[1, 0], [0, 0], [3, 3], [0, 1]]), [0, 2, -1, 0], atol=1e-9)
    p = sphere_points(100)
    m3 = rbfsurf.fit(normals=(p, p), exterior=([[0, 0, 3]], -5.0), smoothing=1e-6)
    assert m3.dim == 3 and len(m3.centres) == 201 and len(m3.weights) == 201
    assert m3([[0, 0, 0]])[0] > 0 > m3([[0, 0, 1.5]])[0]
    fast = rbfsurf.fit(normals=(p, p), method="fast")
    assert fast.report["method"] == "iterative" and fast.report["iterations"] > 0
    x = np.random.default_rng(0).uniform(-1.2, 1.2, (200, 3))
    dense = rbfsurf.fit(normals=(p, p), method="dense")
    assert np.abs(fast(x) - dense(x)).max() < 1e-6


def test_large_oriented_clouds_go_to_the_iterative_solver():
    p = sphere_points(3000)  # 6000 rows, above the dense limit
    m = rbfsurf.from_oriented_points(p, p)
    assert m.report["method"] == "iterative"
    sample = p[::37]
    assert np.abs(m(sample)).max() < 1e-5


def test_render_is_a_picture_of_the_surface():
    p = sphere_points(200)
    image = rbfsurf.from_oriented_points(p, p).render(96, 64, samples=1)
    assert image.shape == (64, 96, 3) and image.dtype == np.uint8
    centre = image[28:36, 44:52].astype(float).mean(axis=(0, 1))
    corner = image[:4, :4].astype(float).mean(axis=(0, 1))
    assert np.abs(centre - corner).max() > 20, "the sphere stands out of the background"


def box_mesh(lo=-0.5, hi=0.5):
    v = np.array([[x, y, z] for x in (lo, hi) for y in (lo, hi) for z in (lo, hi)], float)
    f = np.array(
        [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    )
    return v, f


def test_voxels_and_signed_distance_of_a_box():
    v, f = box_mesh()
    assert mesh_topology(v, f)[0], "the test box is closed and outward"
    g = rbfsurf.voxelize(v, f, resolution=20)
    assert g.values.dtype == np.float32 and g.values.ndim == 3
    assert abs(g.values.sum() * g.voxel_size**3 - 1.0) < 0.02
    d = rbfsurf.signed_distance(v, f, resolution=20)
    i, j, k = np.round((np.zeros(3) - d.origin) / d.voxel_size).astype(int)
    assert abs(d.values[i, j, k] - 0.5) < 0.75 * d.voxel_size, "centre: 0.5 inside"
    assert d.values[0, 0, 0] < 0


def test_convert_a_mesh_both_ways_and_mesh_files(tmp_path):
    points, normals = torus_points(24, 12)
    torus = rbfsurf.from_oriented_points(points, normals)
    V, F = torus.polygonize(24)
    path = tmp_path / "torus.obj"
    rbfsurf.write_mesh(path, V, F)
    V2, F2 = rbfsurf.read_mesh(path)
    # The same triangles, whatever the vertex order the reader chose.
    corners = lambda V, F: np.sort(np.round(V[F].mean(axis=1), 9), axis=0)  # noqa: E731
    assert V2.shape == V.shape and np.allclose(corners(V2, F2), corners(V, F), atol=1e-6)
    by_normals = rbfsurf.convert(V, F, method="normals", max_constraints=600)
    m, report = rbfsurf.convert(V, F, method="iterative", resolution=32, return_report=True)
    assert report["watertight"] and report["max_error_voxels"] < 2.0
    # The topology check: the torus mesh's genus 1 and one component, kept.
    assert (report["mesh_genus"], report["mesh_components"]) == (1, 1)
    assert (report["genus"], report["components"], report["topology_kept"]) == (1, 1, True)
    for model in (by_normals, m):
        W, G = model.polygonize(32, method="grid")
        assert mesh_topology(W, G) == (True, 1, 0)


def test_session_takes_the_sculpt_command_language():
    s = rbfsurf.Session()
    assert len(s) == 12
    assert s.run("add 0 0 1.3").startswith("item 12 added; 13 items")
    assert s.run("# a comment") == ""
    before = s.model()([[0, 0, 1.3]])[0]
    assert abs(before) < 1e-9
    s.run("undo")
    assert len(s) == 12
    with pytest.raises(rbfsurf.RbfError, match="usage: add X Y Z"):
        s.run("add 0 0")
    answers = s.run_script("add 0 0 1.3\nnormal 12\n")
    assert len(answers) == 2 and len(s) == 14
    with pytest.raises(rbfsurf.RbfError, match="line 2"):
        s.run_script("undo\nmove 999 0 0 0\n")
    # A session opened on a model keeps its surface.
    model = s.model()
    edited = rbfsurf.Session(model)
    x = np.random.default_rng(0).uniform(-1.5, 1.5, (100, 3))
    assert np.abs(edited.model()(x) - model(x)).max() < 1e-9
    assert "undo" in rbfsurf.Session.COMMANDS


def test_reconstruct_a_scan_without_normals():
    points = torus_lattice(3000)
    vertices, faces, model, report = rbfsurf.reconstruct(points, resolution=64, return_report=True)
    assert report["normals_estimated"] and report["within_tolerance"]
    assert (report["watertight"], report["genus"], report["components"]) == (True, 1, 1)
    assert vertices.shape[1] == 3 and faces.shape[1] == 3 and faces.max() < len(vertices)
    assert model([[1.0, 0.0, 0.0]])[0] > 0 > model([[0.0, 0.0, 0.0]])[0]
    assert report["outside_added"] >= 0 and report["bubbles_dropped"] >= 0
    # A clean scan is not checked by lines of sight (noisy ones are); its 3000 points all carry
    # constraints, so none is left to make the spread finer where sheets run close.
    assert report["reversed_by_sight"] == 0
    assert report["added_where_sheets_close"] == 0 and report["centres"] <= 3000
    assert report["neighbours"] == 16 and not report["smoothed"]


def test_reconstruct_a_torus_scanned_in_slices():
    # 13 circles' pairs in planes z = const 0.06 apart, 0.005 apart along each: 16 neighbours
    # lie along one circle, so the neighbourhoods grow until they span the slices.
    rings = []
    for k in range(13):
        z = -0.36 + 0.06 * k
        across = np.sqrt(0.16 - z * z)
        for r in (1 - across, 1 + across):
            u = np.linspace(0, 2 * np.pi, int(2 * np.pi * r / 0.005), endpoint=False)
            rings.append(np.column_stack([r * np.cos(u), r * np.sin(u), np.full(len(u), z)]))
    points = np.vstack(rings)
    _, _, model, report = rbfsurf.reconstruct(points, resolution=64, return_report=True)
    assert report["neighbours"] > 16
    assert (report["watertight"], report["genus"], report["components"]) == (True, 1, 1)
    assert model([[1.0, 0.0, 0.0]])[0] > 0 > model([[0.0, 0.0, 0.0]])[0]


def test_reconstruct_estimates_given_normals_of_zero_length():
    points = torus_lattice(3000)
    _, _, model, report = rbfsurf.reconstruct(
        points, np.zeros_like(points), resolution=64, return_report=True
    )
    assert report["normals_estimated"] and report["normals_filled"] == 0
    assert (report["watertight"], report["genus"], report["components"]) == (True, 1, 1)
    with pytest.raises(rbfsurf.RbfError, match=r"point 5 = \[1e\+?300"):
        bad = points.copy()
        bad[5] = [1e300, 0.0, 0.0]
        rbfsurf.reconstruct(bad, resolution=64)


def test_reconstruct_drops_repeated_points_and_says_so():
    points = torus_lattice(3000)
    twice = np.vstack([points, points[::-1]])
    _, _, model, report = rbfsurf.reconstruct(twice, resolution=64, return_report=True)
    _, _, once, report_once = rbfsurf.reconstruct(points, resolution=64, return_report=True)
    assert (report["points"], report["duplicates"], report_once["duplicates"]) == (6000, 3000, 0)
    assert report["centres"] == report_once["centres"]
    x = np.random.default_rng(1).uniform(-1.5, 1.5, (50, 3))
    assert np.abs(model(x) - once(x)).max() < 1e-9 * max(1.0, np.abs(once(x)).max())


def test_reconstruct_a_scan_with_holes_and_uneven_density():
    n = 9000
    points = torus_lattice(n)
    keep = (points[:, 0] > 0) | (np.arange(n) % 3 == 0)
    for hole in ([1.4, 0.0, 0.0], [-0.6, 0.0, 0.3]):
        keep &= np.linalg.norm(points - hole, axis=1) > 0.25
    vertices, faces, _, report = rbfsurf.reconstruct(
        points[keep], resolution=64, return_report=True
    )
    assert (report["watertight"], report["genus"], report["components"]) == (True, 1, 1)
    # Every vertex near the torus, the holes closed smoothly.
    tube = np.hypot(np.hypot(vertices[:, 0], vertices[:, 1]) - 1, vertices[:, 2])
    assert np.abs(tube - 0.4).max() < 0.05


def test_reconstruct_trims_to_the_points_and_refuses_a_bad_distance():
    points = torus_lattice(3000)
    # Only the upper half of the torus is scanned: trimmed, the lower half is gone.
    upper = points[points[:, 2] > 0.05]
    vertices, _, _, report = rbfsurf.reconstruct(
        upper, resolution=48, trim=0.1, return_report=True
    )
    assert not report["watertight"]
    assert vertices[:, 2].min() > -0.1
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(rbfsurf.RbfError, match="trim"):
            rbfsurf.reconstruct(upper, trim=bad)


def test_reconstruct_smooths_a_noisy_scan_and_refuses_a_bad_smoothing():
    points = torus_lattice(12000)
    sigma = 0.004 * np.linalg.norm([2.8, 2.8, 0.8])
    noisy = points + np.random.default_rng(5).normal(scale=sigma, size=points.shape)
    vertices, _, _, report = rbfsurf.reconstruct(noisy, resolution=64, return_report=True)
    assert report["lambda"] > 0 and 9000 <= report["centres"] <= 10000 and report["smoothed"]
    assert (report["watertight"], report["genus"], report["components"]) == (True, 1, 1)
    # The surface passes through the middle of the noise, not through its extremes.
    tube = np.hypot(np.hypot(vertices[:, 0], vertices[:, 1]) - 1, vertices[:, 2])
    assert np.sqrt(np.mean((tube - 0.4) ** 2)) < sigma / 2
    for bad in (0.0, -1e-4, float("nan"), float("inf")):
        with pytest.raises(rbfsurf.RbfError, match="smoothing"):
            rbfsurf.reconstruct(noisy, smoothing=bad)


def test_reconstruct_refuses_a_flat_cloud():
    flat = np.c_[np.arange(400) % 20, np.arange(400) // 20, np.zeros(400)].astype(float)
    with pytest.raises(rbfsurf.RbfError, match="lie on a plane"):
        rbfsurf.reconstruct(flat)
