"""The contact network of a LAMMPS run as a VTK file for ParaView (legacy VTK, ASCII ``POLYDATA``; no
dependency): points at the sphere centres (and at the contact point on the wall for a wall contact), one
line per contact, carrying its forces.

A contact is one row of ``COLUMNS`` (``rows``, from the dict of ``LammpsContacts.contacts``). The file
(``write_vtk``) has

- ``POINTS``: each sphere in a contact once (atom id and position; a periodic image of an atom is a point of
  its own), then one point per wall contact (its contact point on the wall);
- ``LINES``: one per contact, between the centres of its two spheres, or from the sphere's centre to its
  contact point on the wall;
- ``CELL_DATA`` (per contact): ``normal_force`` N [N], ``tangential_force`` |Ft| [N], ``overlap`` [m],
  ``sliding`` (0/1), ``wall`` (the wall's index, -1 for a sphere pair), and the vector ``force`` on the
  first body [N];
- ``POINT_DATA``: ``id`` (the atom id; 0 for a point on a wall) and ``radius`` [m] (0 on a wall).

In ParaView: open the file (one per output step: ParaView groups ``name_00001000.vtk, ...`` as a time
series), then a Tube filter with "Vary Radius: By Scalar" on ``normal_force``; the spheres from LAMMPS's own
``dump custom`` files (Glyph filter on ``radius``). ``read_vtk`` reads such a file back (tests).
"""
from __future__ import annotations

import numpy as np

#: the columns of a contact row (``rows``): ids, wall, the two centres and radii (a wall: the contact point and
#: 0), the contact point, the unit normal from body 1 to body 2, overlap, N, the tangential force vector on
#: body 1, sliding (0/1) and the force on body 1
COLUMNS = ("id1", "id2", "wall", "x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2", "px", "py", "pz", "nx", "ny",
           "nz", "overlap", "normal_force", "ftx", "fty", "ftz", "sliding", "fx", "fy", "fz")
N_COLUMNS = len(COLUMNS)
_C = {name: k for k, name in enumerate(COLUMNS)}


def rows(contacts: dict) -> np.ndarray:
    """float64[k, N_COLUMNS]: the contacts of ``LammpsContacts.contacts`` as rows of ``COLUMNS``."""
    c = contacts
    k = len(c["id1"])
    out = np.zeros((k, N_COLUMNS))
    out[:, _C["id1"]] = c["id1"]
    out[:, _C["id2"]] = c["id2"]
    out[:, _C["wall"]] = c["wall"]
    out[:, 3:6] = c["x1"]
    out[:, 6] = c["r1"]
    out[:, 7:10] = c["x2"]
    out[:, 10] = c["r2"]
    out[:, 11:14] = c["point"]
    out[:, 14:17] = c["normal"]
    out[:, _C["overlap"]] = c["overlap"]
    out[:, _C["normal_force"]] = c["normal_force"]
    out[:, 19:22] = c["tangential_force"]
    out[:, _C["sliding"]] = c["sliding"]
    out[:, 23:26] = c["force"]
    return out


def _numbers(values, fmt="%.17g", per_line=9):
    v = np.asarray(values).ravel()
    return "\n".join(" ".join(fmt % q for q in v[i:i + per_line]) for i in range(0, len(v), per_line))


def write_vtk(path, contact_rows: np.ndarray, title: str = "dem_contact contact network") -> None:
    """Write the contacts ``contact_rows`` (float64[k, N_COLUMNS], ``rows``) to ``path`` as legacy VTK
    PolyData (module docstring)."""
    r = np.asarray(contact_rows, dtype=float).reshape(-1, N_COLUMNS)
    k = len(r)
    # the spheres: each (id, position) once
    ends = np.concatenate([r[:, [0, 3, 4, 5, 6]], r[:, [1, 7, 8, 9, 10]]])     # (id, x, y, z, radius)
    pair = r[:, _C["wall"]] < 0
    sphere_end = np.concatenate([np.ones(k, dtype=bool), pair])
    spheres, inverse = np.unique(ends[sphere_end][:, :4], axis=0, return_inverse=True)
    radius = np.zeros(len(spheres))
    radius[inverse.ravel()] = ends[sphere_end][:, 4]
    index = np.full(2 * k, -1, dtype=np.int64)
    index[sphere_end] = inverse.ravel()
    walls = np.flatnonzero(~pair)
    index[k + walls] = len(spheres) + np.arange(len(walls))
    points = np.concatenate([spheres[:, 1:4], r[walls][:, 11:14]])
    ids = np.concatenate([spheres[:, 0], np.zeros(len(walls))]).astype(np.int64)
    radii = np.concatenate([radius, np.zeros(len(walls))])
    lines = np.stack([np.full(k, 2), index[:k], index[k:]], axis=1)
    ft = np.linalg.norm(r[:, 19:22], axis=1)
    with open(path, "w") as f:
        f.write(f"# vtk DataFile Version 3.0\n{title.replace(chr(10), ' ')[:250]}\nASCII\nDATASET POLYDATA\n")
        f.write(f"POINTS {len(points)} double\n{_numbers(points)}\n")
        f.write(f"LINES {k} {3 * k}\n{_numbers(lines, '%d', 3)}\n")
        f.write(f"CELL_DATA {k}\n")
        for name, values, fmt in (("normal_force", r[:, _C["normal_force"]], "%.17g"), ("tangential_force", ft, "%.17g"),
                                  ("overlap", r[:, _C["overlap"]], "%.17g"), ("sliding", r[:, _C["sliding"]], "%d"),
                                  ("wall", r[:, _C["wall"]], "%d")):
            kind = "int" if fmt == "%d" else "double"
            f.write(f"SCALARS {name} {kind} 1\nLOOKUP_TABLE default\n{_numbers(values, fmt)}\n")
        f.write(f"VECTORS force double\n{_numbers(r[:, 23:26])}\n")
        f.write(f"POINT_DATA {len(points)}\n")
        f.write(f"SCALARS id int 1\nLOOKUP_TABLE default\n{_numbers(ids, '%d')}\n")
        f.write(f"SCALARS radius double 1\nLOOKUP_TABLE default\n{_numbers(radii)}\n")


def read_vtk(path) -> dict:
    """A legacy VTK PolyData file of ``write_vtk`` read back: {"points": float64[n, 3], "lines": int64[k, 2],
    "cell": {name: array}, "point": {name: array}} (the ``VECTORS`` as [k, 3] arrays)."""
    with open(path) as f:
        head = [f.readline() for _ in range(4)]
        words = f.read().split()
    if not head[0].startswith("# vtk DataFile") or head[2].strip() != "ASCII" or head[3].split() != [
            "DATASET", "POLYDATA"]:
        raise ValueError(f"{path}: not an ASCII legacy VTK PolyData file")
    out = {"points": None, "lines": None, "cell": {}, "point": {}}
    i = 0
    where = None
    while i < len(words):
        w = words[i]
        if w == "POINTS":
            n = int(words[i + 1])
            out["points"] = np.array(words[i + 3:i + 3 + 3 * n], dtype=float).reshape(n, 3)
            i += 3 + 3 * n
        elif w == "LINES":
            k, size = int(words[i + 1]), int(words[i + 2])
            cells = np.array(words[i + 3:i + 3 + size], dtype=np.int64).reshape(k, 3)
            if (cells[:, 0] != 2).any():
                raise ValueError(f"{path}: a line that is not a segment")
            out["lines"] = cells[:, 1:]
            i += 3 + size
        elif w in ("CELL_DATA", "POINT_DATA"):
            where = ("cell", int(words[i + 1])) if w == "CELL_DATA" else ("point", int(words[i + 1]))
            i += 2
        elif w == "SCALARS":
            name, kind = words[i + 1], words[i + 2]
            n = where[1]
            start = i + 4 + (2 if words[i + 4] == "LOOKUP_TABLE" else 0)
            out[where[0]][name] = np.array(words[start:start + n], dtype=np.int64 if kind == "int" else float)
            i = start + n
        elif w == "VECTORS":
            name, n = words[i + 1], where[1]
            out[where[0]][name] = np.array(words[i + 3:i + 3 + 3 * n], dtype=float).reshape(n, 3)
            i += 3 + 3 * n
        else:
            raise ValueError(f"{path}: unexpected {w!r}")
    return out
