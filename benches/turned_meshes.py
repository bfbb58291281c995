#!/usr/bin/env python3
"""The meshes of ../shared/data/meshes, each turned by a random rotation, for `benches/corpus.py
--meshes DIR`: the same shapes on other voxel lattices (a conversion's voxels follow the
axes), as a mesh the loop was not developed on meets them.

Each mesh gets its own rotation, uniform over rotations (Shoemake's quaternion), from Python's
`random` seeded with the seed given (default 7) and the mesh's place in the list. Only the
vertex and face lines are kept. Standard library only:

    python3 benches/turned_meshes.py OUT_DIR [--seed 7] [NAME ...]
    python3 benches/corpus.py --meshes OUT_DIR NAME ...
"""
import argparse
import math
import os
import random

here = os.path.dirname(os.path.abspath(__file__))
meshes = os.path.join(os.path.dirname(os.path.dirname(here)), "shared", "data", "meshes")

CLOSED = (
    "boat boot bunny_small cat cow falconstatue fish goathead hammer hand knot koala mushroom "
    "nefertiti penguin spot stuffedtoy sword torus wingnut"
).split()


def random_rotation(rng):
    """A rotation matrix uniform over rotations: a unit quaternion from three uniform numbers."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1.0 - u1), math.sqrt(u1)
    w, x, y, z = (
        a * math.sin(2 * math.pi * u2),
        a * math.cos(2 * math.pi * u2),
        b * math.sin(2 * math.pi * u3),
        b * math.cos(2 * math.pi * u3),
    )
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]


def turn(source, target, rotation):
    """Writes the OBJ `source` turned by `rotation` to `target` (vertices and faces only)."""
    with open(source) as inp, open(target, "w") as out:
        for line in inp:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                p = [float(c) for c in parts[1:4]]
                q = [sum(r[k] * p[k] for k in range(3)) for r in rotation]
                out.write("v %.9g %.9g %.9g\n" % tuple(q))
            elif parts[0] == "f":
                out.write(line if line.endswith("\n") else line + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out")
    parser.add_argument("names", nargs="*", default=CLOSED)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for i, name in enumerate(args.names):
        rng = random.Random(args.seed * 1000 + i)
        turn(
            os.path.join(meshes, name + ".obj"),
            os.path.join(args.out, name + ".obj"),
            random_rotation(rng),
        )
        print(name)


if __name__ == "__main__":
    main()
