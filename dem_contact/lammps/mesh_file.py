"""The packed mesh file of ``fix dem/contact/wall ... mesh FILE``: a mesh wall as the walls room packs it
(``walls.mesh.MeshWall.packed``: its conforming triangles with their neighbours, flat patches, orientation and
history keys), so that the plugin compiled ahead of time, which runs no Python, reads a mesh without the STL
reader and the mesh's topology (``plugin/aot_wall.cpp``). Written once from an STL file (``from_stl``, or
``dem-contact lammps-mesh``); the plugin that reaches the package through Python reads it too (``read``), so
an input script naming it runs in either.

The file: the line ``MAGIC``, the line ``version V abi A width W triangles NT keys K`` (the package's version,
``wall_kernel.ABI``, the payload's columns ``walls.mesh.PAYLOAD_WIDTH``, the triangles and the history keys),
then little-endian float64: the mesh's default centre of rotation (3, the mean of its triangles' corners, as
``walls.table.pack`` takes it) and the payload rows (NT x W, ``walls.mesh``'s columns 1 ... W of a payload row).
A file of another version, or one that is not such a file, is refused (``InputError``, naming what to do).
"""
from __future__ import annotations

import os

import numpy as np

from ..errors import InputError
from ..version import __version__

#: the file's first line
MAGIC = b"dem_contact packed mesh\n"

_WRITE_AGAIN = "write it again from its STL file with `dem-contact lammps-mesh`"


def is_packed(path) -> bool:
    """Whether the file at ``path`` begins as a packed mesh file (False where it cannot be read)."""
    try:
        with open(path, "rb") as f:
            return f.read(len(MAGIC)) == MAGIC
    except OSError:
        return False


def _packed(wall):
    """(payload float64[nt, W], n_keys, default centre (3)) of a MeshWall: its ``packed``, with the centre
    ``walls.table.pack`` takes when none is given."""
    from ..walls import mesh
    from ..walls.table import _default_centre

    data, payload, _, n_keys, _ = wall.packed(0)
    return np.ascontiguousarray(payload), n_keys, np.array(_default_centre(mesh, data, payload))


def write(wall, path) -> str:
    """Write the MeshWall ``wall`` (its pose at time 0; its material, motion and centre are the fix's words,
    not the file's) to ``path``; returns the path. InputError where the mesh is refused (``walls.mesh``)."""
    from ..walls import MeshWall
    from ..walls.mesh import PAYLOAD_WIDTH
    from .wall_kernel import ABI

    if not isinstance(wall, MeshWall):
        raise InputError(f"the wall of a packed mesh file must be a MeshWall, got {type(wall).__name__}")
    try:
        # (the conforming mesh without vertices no triangle uses, numbered in their order: what read rebuilds)
        v, t = MeshWall(wall.vertices, wall.triangles).topology(0)[:2]
        used = np.unique(t)
        payload, n_keys, centre = _packed(MeshWall(v[used], np.searchsorted(used, t)))
    except InputError as e:
        raise InputError(str(e).replace("walls[0].", "the mesh's ").replace("walls[0]", "the mesh")) from None
    head = f"version {__version__} abi {ABI} width {PAYLOAD_WIDTH} triangles {len(payload)} keys {n_keys}\n"
    with open(path, "wb") as f:
        f.write(MAGIC + head.encode())
        f.write(np.concatenate([centre, payload.reshape(-1)]).astype("<f8").tobytes())
    return os.fspath(path)


def from_stl(stl, path, scale: float = 1.0):
    """Write the mesh of the STL file ``stl`` (ASCII or binary; its coordinates times ``scale`` [m]) to the
    packed mesh file ``path``; returns the MeshWall read back from it (``read``)."""
    from ..walls import MeshWall

    return read(write(MeshWall.from_stl(stl, scale=scale), path))


def read(path, **kw):
    """The MeshWall of the packed mesh file ``path`` (other arguments as the class: wall, velocity,
    angular_velocity, centre), checked: its version, its size, and that the walls room packs the mesh as the
    file holds it (InputError naming what to do)."""
    from ..walls import MeshWall
    from ..walls.mesh import PAYLOAD_WIDTH, _ID, _V0
    from .wall_kernel import ABI

    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"the packed mesh file {path} cannot be read ({e})") from None
    if not data.startswith(MAGIC):
        raise InputError(f"{path} is not a packed mesh file (`dem-contact lammps-mesh` writes them from STL files)")
    end = data.find(b"\n", len(MAGIC))
    words = data[len(MAGIC):end].decode(errors="replace").split(" ") if end >= 0 else []
    if (words[::2] != ["version", "abi", "width", "triangles", "keys"] or len(words) != 10
            or not all(w.isascii() and w.isdigit() and len(w) <= 18 for w in words[3::2])):
        raise InputError(f"the packed mesh file {path} is corrupt (its second line): {_WRITE_AGAIN}")
    version, (abi, width, nt, n_keys) = words[1], (int(w) for w in words[3::2])
    if version != __version__ or abi != ABI or width != PAYLOAD_WIDTH:
        raise InputError(f"the packed mesh file {path} was written by dem_contact {version} (wall interface {abi}), "
                         f"this is {__version__} (wall interface {ABI}): {_WRITE_AGAIN}")
    body = data[end + 1:]
    if nt < 1 or len(body) != 8 * (3 + nt * width):
        raise InputError(f"the packed mesh file {path} is corrupt (its size): {_WRITE_AGAIN}")
    numbers = np.frombuffer(body, dtype="<f8").astype(np.float64)
    centre, payload = numbers[:3], numbers[3:].reshape(nt, width)
    ids = payload[:, _ID - 1:_ID + 2]
    # (every vertex of a packed mesh is a corner of a triangle: at most 3 nt of them)
    if not (np.isfinite(payload).all() and ((ids >= 0) & (ids < 3 * nt) & (ids == np.round(ids))).all()):
        raise InputError(f"the packed mesh file {path} is corrupt (its triangles): {_WRITE_AGAIN}")
    triangles = ids.astype(np.int64)
    vertices = np.zeros((int(triangles.max()) + 1, 3))
    for q in range(3):
        vertices[triangles[:, q]] = payload[:, _V0 - 1 + 3 * q:_V0 + 2 + 3 * q]
    wall = MeshWall(vertices, triangles, **kw)
    try:
        again, keys_again, centre_again = _packed(MeshWall(vertices, triangles))
    except InputError:      # (a mesh the walls room refuses)
        again = None
    if again is None or keys_again != n_keys or not (np.array_equal(again, payload)
                                                     and np.array_equal(centre_again, centre)):
        raise InputError(f"the packed mesh file {path} does not hold the mesh as this version packs it: "
                         f"{_WRITE_AGAIN}")
    return wall
