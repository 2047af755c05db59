"""Which wall elements are near which spheres: the wall search of the LAMMPS plugin's wall step
(``lammps.wall_kernel``), of ``Census`` (``lammps.census``) and of the batch face, over the packed walls of
``table.pack``.

An unbounded element (``contract.bounds``: a plane, a cylinder; one per wall) is tested against every
sphere. A bounded one (a mesh's triangle) is listed in the cells of a grid over the spheres' centres that
its box, grown by the largest radius + skin, overlaps, and tested against the spheres of those cells only
(cell lists: Allen & Tildesley, Computer Simulation of Liquids, 1987, sec. 5.3.2), so the search costs
about the same with a mesh of thousands of triangles as with a plane.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import table as W


@njit(inline="always", cache=True)
def _bounded(walls, w):
    """Whether wall w's elements are bounded (all or none of them are, and a wall has at least one:
    ``contract``)."""
    b = W.bounds(walls, w, 0)
    return (math.isfinite(b[0]) and math.isfinite(b[1]) and math.isfinite(b[2]) and math.isfinite(b[3])
            and math.isfinite(b[4]) and math.isfinite(b[5]))


@njit(cache=True)
def near_elements(n, x, radius, walls, skin):
    """int64[k, 3] rows (i, w, e): the elements e of walls w whose surface is closer than radius[i] + skin
    to the centre of sphere i (i < n; ``contract.distance``), in the order of i, then w, then e."""
    nw = W.count(walls)
    if n == 0 or nw == 0:
        return np.empty((0, 3), dtype=np.int64)
    reach = skin
    for i in range(n):
        reach = max(reach, radius[i] + skin)
    # the grid over the centres: cells of side reach, coarser where the spheres are sparse (at most 4 n + 1000
    # cells)
    # (a centre that is not finite is near nothing)
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    for i in range(n):
        if math.isfinite(x[i, 0]) and math.isfinite(x[i, 1]) and math.isfinite(x[i, 2]):
            for d in range(3):
                lo[d] = min(lo[d], x[i, d])
                hi[d] = max(hi[d], x[i, d])
    if not lo[0] <= hi[0]:
        return np.empty((0, 3), dtype=np.int64)
    cell = reach
    dims = np.empty(3, dtype=np.int64)
    while True:
        for d in range(3):
            dims[d] = int(min((hi[d] - lo[d]) / cell, 4.0 * n + 1000.0)) + 1
        if dims[0] * dims[1] * dims[2] <= 4 * n + 1000:
            break
        cell *= 1.25
    d1 = dims[1]
    d2 = dims[2]
    ncell = dims[0] * d1 * d2
    which = np.full(n, -1, dtype=np.int64)
    for i in range(n):
        if math.isfinite(x[i, 0]) and math.isfinite(x[i, 1]) and math.isfinite(x[i, 2]):
            cx = min(int((x[i, 0] - lo[0]) / cell), dims[0] - 1)
            cy = min(int((x[i, 1] - lo[1]) / cell), d1 - 1)
            cz = min(int((x[i, 2] - lo[2]) / cell), d2 - 1)
            which[i] = (cx * d1 + cy) * d2 + cz
    bounded = np.zeros(nw, dtype=np.bool_)
    for w in range(nw):
        bounded[w] = _bounded(walls, w)
    # the bounded elements of each cell (counting sort, in the order of wall and element)
    counts = np.zeros(ncell + 1, dtype=np.int64)
    c0 = np.empty(3, dtype=np.int64)
    c1 = np.empty(3, dtype=np.int64)
    listed = np.empty((0, 2), dtype=np.int64)
    fill = counts[:0]
    for sweep in range(2):
        if sweep == 1:
            for k in range(ncell):
                counts[k + 1] += counts[k]
            listed = np.empty((counts[ncell], 2), dtype=np.int64)
            fill = counts[:ncell].copy()
        for w in range(nw):
            if not bounded[w]:
                continue
            for e in range(W.elements(walls, w)):
                b = W.bounds(walls, w, e)
                empty = False
                for d in range(3):
                    # (clamped as floats first: a box far from the spheres has no cell)
                    f0 = min(max((b[d] - reach - lo[d]) / cell, -1.0), dims[d] + 1.0)
                    f1 = min(max((b[d + 3] + reach - lo[d]) / cell, -1.0), dims[d] + 1.0)
                    c0[d] = max(int(math.floor(f0)), 0)
                    c1[d] = min(int(math.floor(f1)), dims[d] - 1)
                    if c0[d] > c1[d]:
                        empty = True
                if empty:
                    continue
                for ax in range(c0[0], c1[0] + 1):
                    for ay in range(c0[1], c1[1] + 1):
                        for az in range(c0[2], c1[2] + 1):
                            k = (ax * d1 + ay) * d2 + az
                            if sweep == 0:
                                counts[k + 1] += 1
                            else:
                                listed[fill[k], 0] = w
                                listed[fill[k], 1] = e
                                fill[k] += 1
    cap = n * nw + 16
    while True:
        hits = np.empty((cap, 3), dtype=np.int64)
        kw = 0
        for i in range(n):
            k = which[i]
            if k < 0:
                continue
            q = counts[k]
            for w in range(nw):
                if bounded[w]:
                    while q < counts[k + 1] and listed[q, 0] < w:
                        q += 1
                    first = q
                    last = q
                    while last < counts[k + 1] and listed[last, 0] == w:
                        last += 1
                    q = last
                else:
                    first = 0
                    last = W.elements(walls, w)
                for p in range(first, last):
                    e = listed[p, 1] if bounded[w] else p
                    if W.distance(walls, w, e, x[i, 0], x[i, 1], x[i, 2]) < radius[i] + skin:
                        if kw < cap:
                            hits[kw, 0] = i
                            hits[kw, 1] = w
                            hits[kw, 2] = e
                        kw += 1
        if kw <= cap:
            break
        cap = kw
    return hits[:kw]
