"""Triangle-mesh walls (``MeshWall``, from vertices and triangles or an STL file), two-sided, moving by a
prescribed rigid motion (``contract``). Each triangle is an element; the history keys are the sides of the
sets of triangles joined across edges flat or convex on that side (see History below).

Contact rule (one contact per sphere and contact region, none counted twice where triangles meet). For a
sphere's centre x and each triangle T, the closest point of T to x is a point of its face (x projects
inside T), of an edge or a vertex (Ericson 2005, Real-Time Collision Detection, sec. 5.1.5). Then:

- a face contact of T counts, unless a neighbour of T across an edge, in T's patch and of lower index,
  has a face contact too (two nearly coplanar triangles: one contact);
- an edge contact counts once, for the triangle of lowest index sharing the edge, and only if every
  triangle sharing the edge has its closest point on that edge (else a face, or another feature, of the
  neighbour is nearer: the edge is shadowed);
- a vertex contact counts once, for the triangle of lowest index around the vertex, and only if every
  triangle around it has that vertex as its closest point (every edge at the vertex points away from x).

So a sphere on a flat patch (triangulated plane) has one contact wherever it is, at a seam or a vertex
too, with the plane's distance and normal; over a convex edge or vertex one contact whose normal turns
continuously from one face to the next; in a concave corner one contact per face it touches. This is the
rule of LIGGGHTS (``tri_mesh_I.h``, ``resolveTriSphereContactBary``: barycentric regions, a shared edge and
a corner owned by one triangle) with the shadowing decided from the geometry of the neighbours at each
step (no state). The mesh is two-sided: the normal points from the sphere's centre to the closest point,
whichever side the sphere is on; a sphere whose centre crosses the surface is pushed out on the other
side. An edge shared by more than two triangles is refused. The rule sees the mesh's triangles after
``conforming``: corners given as separate copies are one vertex, and a triangle with another's vertex inside
one of its edges (a T-junction) is split there, so a seam cut either way is an edge of the triangles on both
sides (the wall's elements are those triangles).

History. A contact keeps its history while it moves from triangle to triangle over a surface that is
convex or flat on the sphere's side: the history key is the sphere's side of the contact's triangle (the
triangles oriented alike across every edge; at an edge or a vertex, the side of the triangles that meet
there; at a free edge of the mesh, its front) and the set of triangles connected across the edges that
are flat or convex on that side. So a contact that crosses a seam of a flat patch (as LIGGGHTS, which copies
the history onto a coplanar neighbour) or rolls over a convex edge or vertex, where it is one contact
throughout, keeps its tangential history (the law turns it with the normal); in a concave corner, where
the sphere has a contact per face, the faces are keyed apart. A non-orientable mesh is refused.

Payload rows (one per triangle, from column 1): the vertices now (9) and at time 0 (9), the vertex ids
(3), the neighbour across each edge k = (V_k, V_k+1) (3; -1: none), the flat patch, the orientation
(+1 / -1: the sign that makes the triangles' normals agree across the edges) and the history keys of its
two sides (front: along the oriented normal). Row data: the number of triangles.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import InputError
from . import checks
from .contract import DATA, FIRST, move_point, rigid

CLASS = "MeshWall"
N_DATA = 1
PAYLOAD_WIDTH = 28
_V = 1          # payload: vertices now (9)
_V0 = 10        # vertices at time 0 (9)
_ID = 19        # vertex ids (3)
_NB = 22        # neighbour triangle across edge k (3)
_PATCH = 25     # flat patch
_ORIENT = 26    # orientation (+1 / -1)
_KEY = 27       # history keys of the front and back sides (2)
DATA_NT = DATA  # row data: the number of triangles

#: triangles whose unit normals differ by less than this angle [rad] across an edge are one patch
COPLANAR = 1e-5
#: the largest coordinate of a vertex [m] (squares of coordinates stay far from overflow)
MAX_COORDINATE = 1e100
#: longest walk around a vertex (triangles)
MAX_FAN = 256


#: vertices closer than this fraction of the mesh's size are one vertex, and a vertex this close to another
#: triangle's edge lies on it (``conforming``)
JOIN_TOL = 1e-9


def conforming(v, t):
    """(vertices, triangles) of the same surface in which triangles that touch share their vertices and
    edges: vertices closer than JOIN_TOL times the mesh's size merged (triangles given with their own copies
    of the corners), and each triangle with a vertex of another lying inside one of its edges (a
    T-junction) split there, so that every seam is an edge of the triangles on both sides and the contact
    rule and the history keys (module docstring) see one surface. A mesh that conforms already is returned
    as it is (same vertices, triangles and order)."""
    size = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0))) or 1.0
    tol = JOIN_TOL * size
    _, first, inverse = np.unique(np.round((v - v.min(axis=0)) / tol), axis=0, return_index=True,
                                  return_inverse=True)
    inverse = inverse.reshape(-1)
    if len(first) < len(v):                    # keep the first of each group, in the order given
        keep = np.sort(first)
        new_id = np.empty(len(v), dtype=np.int64)
        new_id[keep] = np.arange(len(keep))
        v, t = v[keep], new_id[first[inverse]][t]
    t = [list(tri) for tri in t.tolist()]
    for _ in range(64):                          # each pass splits every triangle at most once
        owners = {}
        for j, tri in enumerate(t):
            for q in range(3):
                a, b = tri[q], tri[(q + 1) % 3]
                owners.setdefault((min(a, b), max(a, b)), []).append((j, q))
        free = [(e, js[0]) for e, js in owners.items() if len(js) == 1]
        if not free:
            break
        ends = np.unique([i for e, _ in free for i in e])
        pts = v[ends]
        split = {}
        for _, (j, q) in free:
            if j in split:
                continue
            a, b = t[j][q], t[j][(q + 1) % 3]
            e = v[b] - v[a]
            ee = float(e @ e)
            if ee == 0.0:       # (an edge of no length: its triangle is refused as degenerate)
                continue
            s = (pts - v[a]) @ e / ee
            off = np.linalg.norm(pts - v[a] - s[:, None] * e, axis=1)
            on = (s * math.sqrt(ee) > tol) & ((1.0 - s) * math.sqrt(ee) > tol) & (off <= tol)
            if on.any():
                inner = ends[on][np.argsort(s[on])]
                split[j] = (q, inner.tolist())
        if not split:
            break
        out = []
        for j, tri in enumerate(t):
            if j not in split:
                out.append(tri)
                continue
            q, inner = split[j]
            a, b, c = tri[q], tri[(q + 1) % 3], tri[(q + 2) % 3]
            chain = [a, *inner, b]
            out += [[chain[i], chain[i + 1], c] for i in range(len(chain) - 1)]   # (the orientation of tri)
        t = out
    return v, np.array(t, dtype=np.int64)


@dataclass(frozen=True, eq=False)
class MeshWall:
    """A triangle mesh: ``vertices`` float[nv, 3] [m] (its pose at time 0) and ``triangles`` int[nt, 3]
    (vertex indices); ``wall``: index of its material in the PairTable's walls. Rigid motion as
    ``PlaneWall``: ``velocity``, ``angular_velocity`` about ``centre`` (default: the mean of its triangles' corners).
    Contact rule and history: see the module's docstring."""

    vertices: np.ndarray
    triangles: np.ndarray
    wall: int = 0
    velocity: tuple = (0.0, 0.0, 0.0)
    angular_velocity: tuple = (0.0, 0.0, 0.0)
    centre: tuple | None = None

    @classmethod
    def from_stl(cls, path, scale: float = 1.0, offset=(0.0, 0.0, 0.0), **kw) -> "MeshWall":
        """The mesh of an STL file (ASCII or binary, ``stl.read_stl``), its coordinates times ``scale``
        plus ``offset`` [m]; other arguments as the class."""
        from .stl import read_stl

        v, t = read_stl(path)
        return cls(v * float(scale) + np.asarray(offset, dtype=np.float64), t, **kw)

    def topology(self, k: int = 0):
        """(vertices float64[nv, 3], triangles int64[nt, 3], neighbours int64[nt, 3] across each edge
        (V_k, V_k+1), -1 none, patches int64[nt]) of the conforming mesh (``conforming``: the elements of the
        wall), checked (InputError naming walls[k])."""
        try:
            v = np.array(self.vertices, dtype=np.float64)
            t = np.array(self.triangles)
        except (TypeError, ValueError):
            raise InputError(f"walls[{k}].vertices and .triangles must be arrays of numbers") from None
        if v.ndim != 2 or v.shape[1] != 3 or not np.isfinite(v).all():
            raise InputError(f"walls[{k}].vertices must be finite numbers of shape (nv, 3), got shape {v.shape}")
        if len(v) and np.abs(v).max() > MAX_COORDINATE:
            # (the areas and normals of the triangles are products of coordinates)
            raise InputError(f"walls[{k}].vertices must lie within {MAX_COORDINATE:g} m of the origin, got a "
                             f"coordinate {float(np.abs(v).max()):g} m")
        if t.ndim != 2 or t.shape[1] != 3 or len(t) == 0 or not np.issubdtype(t.dtype, np.integer):
            raise InputError(f"walls[{k}].triangles must be integers of shape (nt >= 1, 3), got shape {t.shape}")
        t = t.astype(np.int64)
        if t.min() < 0 or t.max() >= len(v):
            raise InputError(f"walls[{k}].triangles must index the vertices (0 ... {len(v) - 1})")
        v, t = conforming(v, t)
        c = v[t]
        n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        area = np.linalg.norm(n, axis=1)
        scale = np.linalg.norm(c - c.mean(axis=1, keepdims=True), axis=2).max(axis=1)
        bad = ~(area > 1e-12 * scale ** 2)
        if bad.any():
            j = int(np.argmax(bad))
            raise InputError(f"walls[{k}].triangles[{j}] is degenerate (zero area, or repeated vertices)")
        unit = n / area[:, None]
        edges = {}
        for j, tri in enumerate(t.tolist()):
            for q in range(3):
                a, b = tri[q], tri[(q + 1) % 3]
                edges.setdefault((min(a, b), max(a, b)), []).append((j, q))
        nb = np.full((len(t), 3), -1, dtype=np.int64)
        parent = list(range(len(t)))

        def root(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for (a, b), owners in edges.items():
            if len(owners) > 2:
                raise InputError(f"walls[{k}]: the edge between vertices {a} and {b} is shared by {len(owners)} "
                                 f"triangles (at most 2)")
            if len(owners) == 2:
                (j1, q1), (j2, q2) = owners
                nb[j1, q1] = j2
                nb[j2, q2] = j1
                if np.linalg.norm(np.cross(unit[j1], unit[j2])) <= COPLANAR:
                    parent[root(j1)] = root(j2)
        roots = [root(j) for j in range(len(t))]
        _, patches = np.unique(roots, return_inverse=True)
        return v, t, nb, patches.astype(np.int64)

    def packed(self, k: int):
        """(data, payload, n_elements, n_keys, moves): see ``contract`` (k: the wall's index, for messages)."""
        v, t, nb, patches = self.topology(k)
        orient, keys = self.history_keys(v, t, nb, patches, k)
        vel, om, _ = checks.motion(k, self, tuple(v.mean(axis=0).tolist()))
        payload = np.zeros((len(t), PAYLOAD_WIDTH + 1))
        payload[:, _V:_V + 9] = v[t].reshape(-1, 9)
        payload[:, _V0:_V0 + 9] = payload[:, _V:_V + 9]
        payload[:, _ID:_ID + 3] = t
        payload[:, _NB:_NB + 3] = nb
        payload[:, _PATCH] = patches
        payload[:, _ORIENT] = orient
        payload[:, _KEY:_KEY + 2] = keys
        moves = checks.norm(vel) > 0.0 or checks.norm(om) > 0.0
        return (float(len(t)),), payload[:, 1:], len(t), int(keys.max()) + 1, moves

    @staticmethod
    def history_keys(v, t, nb, patches, k: int = 0):
        """(orient float64[nt] (+1 / -1), keys int64[nt, 2]): the orientation that makes the triangles'
        normals agree across every edge (each connected part oriented from its lowest triangle), and the
        history key of each side of each triangle (front: along the oriented normal): the connected sets
        of triangles across the edges that are flat (one patch) or convex on that side, numbered front sets
        first. InputError (naming walls[k]) for a non-orientable mesh."""
        nt = len(t)
        orient = np.zeros(nt)
        for start in range(nt):
            if orient[start] != 0.0:
                continue
            orient[start] = 1.0
            stack = [start]
            while stack:
                j = stack.pop()
                for q in range(3):
                    o = int(nb[j, q])
                    if o < 0:
                        continue
                    a, b = t[j, q], t[j, (q + 1) % 3]
                    # the same orientation traverses the shared edge in opposite directions
                    same_dir = any(t[o, r] == a and t[o, (r + 1) % 3] == b for r in range(3))
                    want = -orient[j] if same_dir else orient[j]
                    if orient[o] == 0.0:
                        orient[o] = want
                        stack.append(o)
                    elif orient[o] != want:
                        raise InputError(f"walls[{k}]: the mesh is not orientable (its triangles cannot all be "
                                         f"given normals that agree across their edges): a mesh wall needs "
                                         f"two sides")
        c = v[t]
        normal = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]) * orient[:, None]
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        size = np.linalg.norm(v.max(axis=0) - v.min(axis=0))
        parents = [list(range(nt)), list(range(nt))]

        def root(parent, i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for j in range(nt):
            for q in range(3):
                o = int(nb[j, q])
                if o <= j:
                    continue
                if patches[o] == patches[j]:
                    sides = (0, 1)                    # flat: one surface on both sides
                else:
                    # the vertex of o off the shared edge lies behind j's front: convex seen from the front
                    p = next(r for r in range(3) if t[o, r] not in (t[j, q], t[j, (q + 1) % 3]))
                    h = float(np.dot(v[t[o, p]] - v[t[j, q]], normal[j]))
                    sides = (0,) if h < -1e-12 * size else (1,) if h > 1e-12 * size else (0, 1)
                for side in sides:
                    parents[side][root(parents[side], j)] = root(parents[side], o)
        keys = np.empty((nt, 2), dtype=np.int64)
        front = np.unique([root(parents[0], j) for j in range(nt)], return_inverse=True)[1]
        back = np.unique([root(parents[1], j) for j in range(nt)], return_inverse=True)[1]
        keys[:, 0] = front
        keys[:, 1] = back + front.max() + 1
        return orient, keys


@njit(inline="always", cache=True)
def _edge(walls, q, lo, hi, x, y, z):
    """The edge of triangle row q from its local vertex lo to hi: (t, the point of lo, the edge vector), t
    the parameter of the point of the edge's line nearest (x, y, z) (0 at lo, 1 at hi)."""
    px = walls[q, _V + 3 * lo]
    py = walls[q, _V + 3 * lo + 1]
    pz = walls[q, _V + 3 * lo + 2]
    ex = walls[q, _V + 3 * hi] - px
    ey = walls[q, _V + 3 * hi + 1] - py
    ez = walls[q, _V + 3 * hi + 2] - pz
    t = ((x - px) * ex + (y - py) * ey + (z - pz) * ez) / (ex * ex + ey * ey + ez * ez)
    return t, px, py, pz, ex, ey, ez


@njit(inline="always", cache=True)
def _closest(walls, q, x, y, z):
    """The closest point of triangle row q to (x, y, z): (feature: 0 face, 1 edge, 2 vertex; its local
    index (edge k = (V_k, V_k+1), vertex k); the point; the squared distance; the unit normal (face); the
    signed distance along it). Edges are parametrised from their lower vertex id, so that the two
    triangles of an edge find the same point."""
    ax = walls[q, _V]
    ay = walls[q, _V + 1]
    az = walls[q, _V + 2]
    e1x = walls[q, _V + 3] - ax
    e1y = walls[q, _V + 4] - ay
    e1z = walls[q, _V + 5] - az
    e2x = walls[q, _V + 6] - ax
    e2y = walls[q, _V + 7] - ay
    e2z = walls[q, _V + 8] - az
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    nx /= nn
    ny /= nn
    nz /= nn
    inside = True
    for k in range(3):
        c0 = _V + 3 * k
        c1 = _V + 3 * ((k + 1) % 3)
        px = walls[q, c0]
        py = walls[q, c0 + 1]
        pz = walls[q, c0 + 2]
        ex = walls[q, c1] - px
        ey = walls[q, c1 + 1] - py
        ez = walls[q, c1 + 2] - pz
        rx = x - px
        ry = y - py
        rz = z - pz
        if (ey * rz - ez * ry) * nx + (ez * rx - ex * rz) * ny + (ex * ry - ey * rx) * nz <= 0.0:
            inside = False
    d = (x - ax) * nx + (y - ay) * ny + (z - az) * nz
    if inside:
        return 0, 0, x - d * nx, y - d * ny, z - d * nz, d * d, nx, ny, nz, d
    best = math.inf
    feat = 1
    idx = 0
    bx = by = bz = 0.0
    for k in range(3):
        k1 = (k + 1) % 3
        lo, hi = (k, k1) if walls[q, _ID + k] < walls[q, _ID + k1] else (k1, k)
        t, px, py, pz, ex, ey, ez = _edge(walls, q, lo, hi, x, y, z)
        f = 1
        i = k
        if t <= 0.0:
            cx, cy, cz = px, py, pz
            f = 2
            i = lo
        elif t >= 1.0:
            cx = walls[q, _V + 3 * hi]
            cy = walls[q, _V + 3 * hi + 1]
            cz = walls[q, _V + 3 * hi + 2]
            f = 2
            i = hi
        else:
            cx = px + t * ex
            cy = py + t * ey
            cz = pz + t * ez
        d2 = (x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2
        if d2 < best:
            best = d2
            feat = f
            idx = i
            bx, by, bz = cx, cy, cz
    return feat, idx, bx, by, bz, best, nx, ny, nz, d


@njit(inline="always", cache=True)
def _local(walls, q, vid):
    """The local index of vertex id vid in triangle row q (-1: not there)."""
    for k in range(3):
        if walls[q, _ID + k] == vid:
            return k
    return -1


@njit(inline="always", cache=True)
def _clear(walls, q, k, x, y, z):
    """Whether both edges of triangle row q at its vertex k have their closest point to x at that vertex
    (the parametrisation of ``_closest``)."""
    vid = walls[q, _ID + k]
    for kk in (k, (k + 2) % 3):
        other = (kk + 1) % 3 if kk == k else kk
        lo, hi = (k, other) if vid < walls[q, _ID + other] else (other, k)
        t = _edge(walls, q, lo, hi, x, y, z)[0]
        if (lo == k and t > 0.0) or (hi == k and t < 1.0):
            return False
    return True


@njit(inline="always", cache=True)
def _vertex_counts(walls, first, e, k, x, y, z):
    """Whether the vertex contact of triangle e at its vertex k counts: e is the lowest triangle around
    the vertex and the vertex is the closest point of each (walk around it across the edges)."""
    vid = walls[first + e, _ID + k]
    closed = False
    for direction in range(2):
        if closed:
            break
        prev = e
        nxt = int(walls[first + e, _NB + (k if direction == 0 else (k + 2) % 3)])
        for _ in range(MAX_FAN):
            if nxt < 0:
                break
            if nxt == e:
                closed = True
                break
            if nxt < e:
                return False
            q = first + nxt
            kk = _local(walls, q, vid)
            if kk < 0 or not _clear(walls, q, kk, x, y, z):
                return False
            a = int(walls[q, _NB + kk])
            b = int(walls[q, _NB + (kk + 2) % 3])
            prev, nxt = nxt, (b if a == prev else a)
    return True


@njit(inline="always", cache=True)
def contact(walls, w, e, x, y, z, r):
    """(s, nx, ny, nz) of triangle e (the rule of the module's docstring; s = inf: no contact counted)."""
    first = int(walls[w, FIRST])
    q = first + e
    feat, idx, px, py, pz, d2, fx, fy, fz, d = _closest(walls, q, x, y, z)
    if feat == 0:
        for k in range(3):
            nb = int(walls[q, _NB + k])
            if 0 <= nb < e and walls[first + nb, _PATCH] == walls[q, _PATCH]:
                if _closest(walls, first + nb, x, y, z)[0] == 0:
                    return math.inf, 0.0, 0.0, 0.0
        if d >= 0.0:
            return d, -fx, -fy, -fz
        return -d, fx, fy, fz
    if feat == 1:
        nb = int(walls[q, _NB + idx])
        if nb >= 0:
            if nb < e:
                return math.inf, 0.0, 0.0, 0.0
            qn = first + nb
            a = _local(walls, qn, walls[q, _ID + idx])
            b = _local(walls, qn, walls[q, _ID + (idx + 1) % 3])
            kn = a if (a + 1) % 3 == b else b
            f2, i2, _, _, _, _, _, _, _, _ = _closest(walls, qn, x, y, z)
            if f2 != 1 or i2 != kn:
                return math.inf, 0.0, 0.0, 0.0
    elif not _vertex_counts(walls, first, e, idx, x, y, z):
        return math.inf, 0.0, 0.0, 0.0
    s = math.sqrt(d2)
    if s == 0.0:
        return 0.0, -fx, -fy, -fz
    return s, (px - x) / s, (py - y) / s, (pz - z) / s


@njit(inline="always", cache=True)
def distance(walls, w, e, x, y, z):
    """The distance from (x, y, z) to triangle e, whatever the rule of ``contact``."""
    return math.sqrt(_closest(walls, int(walls[w, FIRST]) + e, x, y, z)[5])


@njit(inline="always", cache=True)
def curvature(walls, w, e, cx, cy, cz):
    """Triangles are flat: 0 (an edge or a vertex is taken as flat too)."""
    return 0.0


@njit(inline="always", cache=True)
def patch(walls, w, e, x, y, z):
    """The history key of a contact of triangle e with the sphere centred at (x, y, z): that of the
    triangle's side where the centre lies (the module's docstring)."""
    first = int(walls[w, FIRST])
    q = first + e
    feat, idx, _, _, _, _, _, _, _, d = _closest(walls, q, x, y, z)
    side = d * walls[q, _ORIENT]
    if feat > 0:
        # an edge or a vertex: the side of the triangles that meet there (the sum of the distances along
        # their oriented normals, >= 0 in the region in front of an edge convex seen from the front, however
        # sharp); at a free edge, the front
        for j in range(feat):
            k = idx if j == 0 else (idx + 2) % 3
            nb = int(walls[q, _NB + k])
            if nb < 0:
                return int(walls[q, _KEY])
            side += _closest(walls, first + nb, x, y, z)[9] * walls[first + nb, _ORIENT]
    return int(walls[q, _KEY] if side >= 0.0 else walls[q, _KEY + 1])


@njit(inline="always", cache=True)
def bounds(walls, w, e):
    """The box of triangle e's vertices now."""
    q = int(walls[w, FIRST]) + e
    xlo = min(walls[q, _V], walls[q, _V + 3], walls[q, _V + 6])
    ylo = min(walls[q, _V + 1], walls[q, _V + 4], walls[q, _V + 7])
    zlo = min(walls[q, _V + 2], walls[q, _V + 5], walls[q, _V + 8])
    xhi = max(walls[q, _V], walls[q, _V + 3], walls[q, _V + 6])
    yhi = max(walls[q, _V + 1], walls[q, _V + 4], walls[q, _V + 7])
    zhi = max(walls[q, _V + 2], walls[q, _V + 5], walls[q, _V + 8])
    return xlo, ylo, zlo, xhi, yhi, zhi


@njit(inline="always", cache=True)
def place(walls, w, t):
    """The vertices at time t."""
    rot = rigid(walls, w, t)
    first = int(walls[w, FIRST])
    for e in range(int(walls[w, DATA_NT])):
        q = first + e
        for k in range(3):
            move_point(walls, w, rot, q, _V + 3 * k, q, _V0 + 3 * k)


def example(**motion) -> MeshWall:
    """A typical wall of this kind, with the rigid motion ``motion`` (the contract tests use it): a regular
    octahedron, 1 m from its centre to its corners, turned off the axes."""
    c, s = math.cos(0.4), math.sin(0.4)
    rot = np.array([[c, -s, 0.0], [s * c, c * c, -s], [s * s, s * c, c]])
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float) @ rot.T
    t = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return MeshWall(v + np.array([0.1, -0.2, 0.3]), t, **motion)


def sample(wall: MeshWall, n: int, rng):
    """(surface points float[m, 3], sphere centres float[n, 3]) of ``wall`` at time 0: points covering every
    triangle densely, and centres 0.1 to 0.5 m outside the example's octahedron (the contract tests' brute
    force)."""
    v, t = np.asarray(wall.vertices, float), np.asarray(wall.triangles)
    per = 100_000
    a, b = rng.uniform(0.0, 1.0, (2, len(t) * per, 1))
    flip = a + b > 1.0
    a, b = np.where(flip, 1.0 - a, a), np.where(flip, 1.0 - b, b)
    tri = np.repeat(t, per, axis=0)
    surface = v[tri[:, 0]] + a * (v[tri[:, 1]] - v[tri[:, 0]]) + b * (v[tri[:, 2]] - v[tri[:, 0]])
    centre = v.mean(axis=0)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    # the octahedron |x|_1 <= 1 (in its own axes) lies within 1 of its centre and contains the ball of radius
    # 1/sqrt(3): a centre at 1 + [0.1, 0.5] from it is 0.1 to 1.5 from the surface
    centres = centre + d * rng.uniform(1.1, 1.5, (n, 1))
    return surface, centres
