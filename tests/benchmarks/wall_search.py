"""Time of ``lammps.census.candidates`` (the contact search of ``Census``: Verlet lists of sphere pairs and of
wall elements, whose wall part is ``walls.search.near_elements``), with a skin of 0.3 mm, for N spheres of radius
1 mm over a triangulated floor of 2 K^2 triangles:

    python tests/benchmarks/wall_search.py [N] [K]        # defaults 20000 50: 5,000 triangles

Prints the best of three list builds (after one that compiles), the sphere pairs included."""
import sys
import time

import numpy as np

from dem_contact.lammps.census import candidates
from dem_contact.walls import MeshWall, pack


def floor(k, side=0.1):
    xs = np.linspace(0.0, side, k + 1)
    v = np.array([[a, b, 0.0] for b in xs for a in xs])
    t = []
    for j in range(k):
        for i in range(k):
            a = j * (k + 1) + i
            t += [[a, a + 1, a + k + 2], [a, a + k + 2, a + k + 1]]
    return MeshWall(v, np.array(t))


def main(n=20000, k=50):
    walls, _ = pack([floor(k)])
    rng = np.random.default_rng(0)
    r = np.full(n, 1e-3)
    x = np.column_stack([rng.uniform(0.0, 0.1, (n, 2)), rng.uniform(0.0005, 0.02, n)])
    tag = np.arange(n, dtype=np.int64) + 1
    candidates(10, 10, x, r, tag, walls, 1e-3, 3e-4)
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        _, hits = candidates(n, n, x, r, tag, walls, 1e-3, 3e-4)
        best = min(best, time.perf_counter() - t0)
    print(f"{n} spheres, {2 * k * k} triangles, {len(hits)} wall candidates: {best * 1e3:.1f} ms per list build")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
