"""STL files (ASCII and binary) to and from indexed triangle meshes (vertices float64[nv, 3], triangles
int64[nt, 3]); vertices with identical coordinates are merged. The facet normals of a file are ignored
(recomputed from the vertices)."""
from __future__ import annotations

import os
import struct

import numpy as np

from ..errors import InputError


def _index(corners, path):
    """(vertices, triangles) of corners float64[nt, 3, 3], identical points merged."""
    if len(corners) == 0:
        raise InputError(f"STL file {path}: no facets")
    if not np.isfinite(corners).all():
        raise InputError(f"STL file {path}: a vertex coordinate is not finite")
    flat = corners.reshape(-1, 3)
    vertices, inverse = np.unique(flat, axis=0, return_inverse=True)
    return vertices, inverse.reshape(-1, 3).astype(np.int64)


def read_stl(path):
    """(vertices float64[nv, 3], triangles int64[nt, 3]) of an STL file, ASCII or binary (a file whose size
    is 84 + 50 n with n its facet count is binary, whatever its first bytes). InputError if unreadable."""
    path = os.fspath(path)
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"STL file {path} cannot be read: {e.strerror}") from None
    if len(data) >= 84:
        n = struct.unpack_from("<I", data, 80)[0]
        if len(data) == 84 + 50 * n:
            rec = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                                count=n, offset=84)
            return _index(rec["v"].astype(np.float64), path)
    try:
        text = data.decode("ascii")
    except UnicodeDecodeError:
        raise InputError(f"STL file {path} is neither binary STL (size 84 + 50 n) nor ASCII STL") from None
    words = text.split()
    if not words or words[0].lower() != "solid":
        raise InputError(f"STL file {path} is neither binary STL (size 84 + 50 n) nor ASCII STL (starting 'solid')")
    corners = []
    try:
        for k, word in enumerate(words):
            if word.lower() == "vertex":
                corners.append([float(c) for c in words[k + 1:k + 4]])
    except ValueError:
        raise InputError(f"STL file {path}: a vertex line does not hold 3 numbers") from None
    if len(corners) % 3:
        raise InputError(f"STL file {path}: {len(corners)} vertices, not 3 per facet")
    return _index(np.array(corners, dtype=np.float64).reshape(-1, 3, 3), path)


def write_stl(path, vertices, triangles, ascii: bool = True, name: str = "mesh"):
    """Write an STL file (ASCII, or binary with float32 coordinates) of an indexed triangle mesh."""
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles, dtype=np.int64)
    corners = v[t]
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    if ascii:
        lines = [f"solid {name}"]
        for c, nn in zip(corners, n):
            lines.append("  facet normal " + " ".join(repr(float(q)) for q in nn))
            lines.append("    outer loop")
            lines += ["      vertex " + " ".join(repr(float(q)) for q in p) for p in c]
            lines += ["    endloop", "  endfacet"]
        lines.append(f"endsolid {name}")
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        return
    rec = np.zeros(len(t), dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["n"] = n
    rec["v"] = corners
    with open(path, "wb") as f:
        f.write(name.encode("ascii")[:80].ljust(80, b" "))
        f.write(struct.pack("<I", len(t)))
        f.write(rec.tobytes())
