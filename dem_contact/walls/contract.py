"""The contract every wall kind keeps (``walls/<kind>.py``), and the layout of the packed wall rows.

A wall is a rigid body of infinite mass that spheres touch. Each kind of wall (plane today; moving planes,
cylinders and meshes later) is one module of this package that provides:

- a user class, named by ``CLASS`` (a frozen dataclass; for the plane ``PlaneWall``) with an attribute ``wall``:
  the index of its material in the ``PairTable``'s walls, and a method ``row_data(k) -> tuple`` that checks
  the wall (raising ``InputError`` naming ``walls[k]`` and the parameter's valid range) and returns its
  ``N_DATA`` numbers, stored from column ``DATA`` of its packed row;
- ``N_DATA``: how many numbers its row holds;
- ``ELEMENTS``: how many elements each wall of the kind has (the parts whose contacts keep histories of
  their own: a plane has one; a mesh would have one per triangle);
- the kernels below, ``@njit(inline="always", cache=True)``, with exactly these parameter names (the table
  checks them), which read only the wall's row (``walls[w]`` of the float64[n_walls, ROW_SIZE] table that
  ``table.pack`` builds) and never raise:

  ``contact(walls, w, x, y, z, r) -> (s, nx, ny, nz)``
      for a sphere of centre (x, y, z) and radius r [m]: s the signed distance from the centre to the
      wall's surface [m] (> 0 on the side of the spheres), and the unit normal at the contact point, from
      the sphere's centre toward the wall (body 1 = the sphere, body 2 = the wall). The overlap is
      delta = r - s (contact when delta > 0), the contact point on the surface c = x + s n;
  ``velocity(walls, w, cx, cy, cz) -> (vx, vy, vz)``
      the wall's velocity at the point c of its surface [m/s]; the relative velocity of a contact is the
      sphere's at c minus this one (zero for a wall at rest);
  ``curvature(walls, w, cx, cy, cz) -> k``
      1 / R2 [1/m] of the wall's surface at c, for R* = 1 / (1 / R1 + k): 0 for a plane, > 0 convex,
      < 0 concave (the inside of a cylinder). ``pairs.pair_table`` builds its sphere-wall rows with
      R* = R1, that is k = 0: a curved kind must come with sphere-wall rows built with its R*;
  ``element(walls, w, x, y, z) -> e``
      the element (0 ... ELEMENTS - 1) of the wall that a sphere centred at (x, y, z) touches (one contact
      per sphere and wall: a kind whose walls a sphere can touch at several elements at once, as a mesh,
      will need the contact searches to list each (sphere, wall, element)).

Users of the contract: the LAMMPS bridge (``lammps.kernels``: its Verlet lists hold (sphere, wall,
element)) and the 3D batch face (``dem.walls.wall_contacts``).

The history of a wall contact is keyed per wall and element: ``history_key(walls, w, e)`` (here, the same
for every kind) = -(first key of wall w + e + 1), a negative number (sphere partners are keyed by their
positive atom ids); ``table.pack`` numbers the keys of the walls one after the other, so for walls with one
element each, the key of wall w is -(w + 1).

Packed row of wall w (``table.pack``): column ``KIND`` its kind id (the row of ``table.KINDS``), column
``KEY_BASE`` the first key number of its elements, columns ``DATA`` ... its kind's numbers.
"""
from numba import njit

KIND = 0        # column of the kind id
KEY_BASE = 1    # column of the first key number of the wall's elements
DATA = 2        # first column of the kind's own numbers


@njit(inline="always", cache=True)
def history_key(walls, w, e):
    """Key of the history of a contact with element e of wall w (negative; see the module docstring)."""
    return -(walls[w, KEY_BASE] + e + 1.0)
