"""The tests run on the installed wheel: importing the source folder would test nothing."""

import os
from pathlib import Path

import numpy as np
import pytest

import rbfsurf

SOURCE = Path(__file__).resolve().parents[1]


def test_the_installed_package_is_tested():
    installed = Path(rbfsurf.__file__).resolve()
    assert SOURCE not in installed.parents, f"rbfsurf imported from the source tree: {installed}"
    assert "site-packages" in installed.parts


def torus_points(n_major=40, n_minor=20, R=1.0, r=0.4):
    """Oriented points on a torus around z: points and outward normals."""
    u, v = np.meshgrid(
        np.linspace(0, 2 * np.pi, n_major, endpoint=False),
        np.linspace(0, 2 * np.pi, n_minor, endpoint=False),
        indexing="ij",
    )
    u, v = u.ravel(), v.ravel()
    normals = np.c_[np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)]
    centre = np.c_[R * np.cos(u), R * np.sin(u), np.zeros_like(u)]
    return centre + r * normals, normals


def torus_lattice(n):
    """n points spread over a torus around z (radii 1 and 0.4) by a golden-ratio lattice."""
    golden = 0.5 * (5**0.5 - 1)
    u = 2 * np.pi * np.arange(n) / n
    v = 2 * np.pi * ((np.arange(n) * golden) % 1.0)
    r = 1 + 0.4 * np.cos(v)
    return np.c_[r * np.cos(u), r * np.sin(u), 0.4 * np.sin(v)]


def sphere_points(n):
    """Fibonacci points on the unit sphere (their own outward normals)."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    t = np.pi * (1 + 5**0.5) * i
    s = np.sqrt(1 - z * z)
    return np.c_[s * np.cos(t), s * np.sin(t), z]


def mesh_topology(vertices, faces):
    """(watertight and consistently oriented, components, Euler characteristic)."""
    faces = np.asarray(faces)
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    # Each directed edge once, and its reverse once: closed and consistently oriented.
    keys = directed[:, 0] * len(vertices) + directed[:, 1]
    reverse = directed[:, 1] * len(vertices) + directed[:, 0]
    unique_directed = len(np.unique(keys)) == len(keys)
    paired = np.array_equal(np.sort(keys), np.sort(reverse))
    edges = len(keys) // 2
    parent = np.arange(len(vertices))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in directed:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb
    used = np.unique(faces)
    components = len({find(v) for v in used})
    chi = len(used) - edges + len(faces)
    return unique_directed and paired, components, chi


@pytest.fixture
def rbf_binary():
    """The `rbf` command the CI built (RBF=path), for the tests that hand files to it."""
    path = os.environ.get("RBF")
    if not path:
        pytest.skip("set RBF to the rbf binary (CI does)")
    return path
