"""The contract every wall kind keeps (``walls/<kind>.py``), and the layout of the packed wall rows.

A wall is a rigid body of infinite mass that spheres touch, moving by a prescribed rigid motion: a
translation at velocity V [m/s] of its centre C and a rotation at angular velocity Omega [rad/s] about C
(both constant; C(t) = C0 + V t). The pose given by the user is the wall's at time 0; its surface at time t
is x(t) = C(t) + Rot(Omega t) (x(0) - C0) (Rodrigues' rotation), and its velocity at a point c of its
surface is V + Omega x (c - C(t)) (``velocity`` below, the same for every kind). A motion that leaves the
surface where it is (a plane sliding or turning in its own plane, a cylinder turning about its axis) is
marked so: its surface is never re-placed, but its centre is carried to C(t) all the same (``table.place_walls``), so
that its velocity at a point and the torques of its loads are those about where the centre is now.

Each kind of wall is one module of this package that provides:

- a user class, named by ``CLASS`` (a frozen dataclass) with attributes ``wall`` (the index of its material
  in the ``PairTable``'s walls), ``velocity``, ``angular_velocity`` and ``centre`` (the rigid motion), and a
  method ``packed(k) -> (data, payload, n_elements, n_keys, moves)`` that checks the wall (raising
  ``InputError`` naming ``walls[k]`` and the parameter's valid range) and returns its ``N_DATA`` numbers
  (stored from column ``DATA`` of its row), its payload rows (float64[p, PAYLOAD_WIDTH] or None: rows
  stored after the walls' own from column 1, as a mesh's triangles; column 0 of each is ``PAYLOAD``),
  its number of elements (the parts a sphere can touch at once, each searched on its own: 1 for a plane,
  one per triangle for a mesh), of history keys (``patch``), and whether its motion moves its surface;
- ``N_DATA`` (numbers of its row) and ``PAYLOAD_WIDTH`` (columns of its payload rows, 0 if none);
- the kernels below, ``@njit(inline="always", cache=True)``, with exactly these parameter names (the table
  checks them), which read only the wall's row and its payload rows and never raise:

  ``contact(walls, w, e, x, y, z, r) -> (s, nx, ny, nz)``
      for a sphere of centre (x, y, z) and radius r [m] and element e of wall w: s the distance from the
      centre to the element's surface [m] (signed: > 0 on the side of the spheres; ``math.inf`` when the
      element reports no contact for that sphere, as a mesh edge shadowed by a face), and the unit normal
      at the contact point, from the sphere's centre toward the wall (body 1 = the sphere, body 2 = the
      wall). The overlap is delta = r - s (contact when delta > 0), the contact point c = x + s n;
  ``distance(walls, w, e, x, y, z) -> d``
      the distance from (x, y, z) to element e's surface [m] whichever element reports the contact (a
      lower bound of the s of ``contact`` where it is finite): the wall search (``search``) keeps the
      elements within r + skin by it, so that an element that takes over a contact (a mesh's neighbour) is in the list;
  ``curvature(walls, w, e, cx, cy, cz) -> k``
      1 / R2 [1/m] of the surface at c that enters R* = 1 / (1 / R1 + k): 0 for a plane, > 0 convex, < 0
      concave. The parameter rows of the contacts (``pairs.pair_table``) carry it through the wall's
      material: ``materials.Wall(..., curvature=k)`` (checked where walls meet a table);
  ``patch(walls, w, e, x, y, z) -> int``
      the history key index (0 ... n_keys - 1) of a contact of the sphere centred at (x, y, z) with
      element e: contacts that move from one element to another of the same patch keep their history (a
      mesh: the triangles connected across flat or convex edges on the sphere's side);
  ``bounds(walls, w, e) -> (xlo, ylo, zlo, xhi, yhi, zhi)``
      the axis-aligned box of element e's surface now [m] (the wall search, ``search``, bins the bounded
      elements into its cells); +-inf where it is unbounded. A wall's elements (at least one) are all bounded
      or all unbounded. An unbounded element (a plane, a cylinder) is one-sided (the LAMMPS plugin's wall fix
      refuses a sphere's centre behind it); a bounded one (a triangle) is two-sided;
  ``place(walls, w, t)``
      write the pose of wall w at time t [s] into its row and payload rows (from its pose at time 0, kept
      there too); called only for walls whose motion moves their surface.

Users of the contract: the LAMMPS plugin's wall step (``lammps.wall_kernel``: the contacts of the atoms with
the wall of one ``fix dem/contact/wall``), ``Census`` (``lammps.census``: the wall contacts it counts) and the 3D
batch face (``dem.walls.wall_contacts``).

The history of a wall contact is keyed per wall and patch: ``table.history_key(walls, w, e, x, y, z)`` =
-(first key of wall w + patch(e, x, y, z) + 1), a negative number (sphere partners are keyed by their positive atom
ids); ``table.pack`` numbers the keys of the walls one after the other, so for walls with one key each,
the key of wall w is -(w + 1).

Packed row of wall w (``table.pack``; rows 0 ... n_walls - 1, then the payload rows): column ``KIND`` its
kind id (``PAYLOAD`` for a payload row), ``KEY_BASE`` the first key number of its patches, ``NELEM`` its
number of elements, ``MOVES`` 1 if its motion moves its surface, ``VEL``, ``OMEGA``, ``CENTRE`` (at the
time of the last ``place``) and ``CENTRE0`` (at time 0) the rigid motion, ``FIRST`` its first payload row (-1: none), and from ``DATA``
its kind's numbers. A payload row has ``PAYLOAD`` in column 0 and its kind's numbers from column 1.
"""
import math

from numba import njit

KIND = 0        # column of the kind id (PAYLOAD: a payload row)
KEY_BASE = 1    # column of the first key number of the wall's patches
NELEM = 2       # column of the number of elements
MOVES = 3       # 1.0 if the wall's motion moves its surface
VEL = 4         # velocity of the centre (3)
OMEGA = 7       # angular velocity (3)
CENTRE = 10     # centre of rotation now (3)
CENTRE0 = 13    # centre of rotation at time 0 (3)
FIRST = 16      # the first payload row of the wall (-1: none)
DATA = 17       # first column of the kind's own numbers

PAYLOAD = -1.0  # kind id of a payload row


@njit(cache=True)
def count(walls):
    """The number of walls of a packed table (the rows before the first payload row)."""
    for w in range(walls.shape[0]):
        if walls[w, KIND] == PAYLOAD:
            return w
    return walls.shape[0]


@njit(inline="always", cache=True)
def elements(walls, w):
    """The number of elements of wall w."""
    return int(walls[w, NELEM])


@njit(inline="always", cache=True)
def velocity(walls, w, cx, cy, cz):
    """The velocity of wall w at the point c of its surface [m/s]: V + Omega x (c - C) (rigid motion)."""
    rx = cx - walls[w, CENTRE]
    ry = cy - walls[w, CENTRE + 1]
    rz = cz - walls[w, CENTRE + 2]
    ox = walls[w, OMEGA]
    oy = walls[w, OMEGA + 1]
    oz = walls[w, OMEGA + 2]
    return (walls[w, VEL] + (oy * rz - oz * ry), walls[w, VEL + 1] + (oz * rx - ox * rz),
            walls[w, VEL + 2] + (ox * ry - oy * rx))


@njit(inline="always", cache=True)
def unbounded(walls, w, e):
    """``bounds`` of an unbounded element (a plane, a cylinder)."""
    return -math.inf, -math.inf, -math.inf, math.inf, math.inf, math.inf


@njit(inline="always", cache=True)
def one_patch(walls, w, e, x, y, z):
    """``patch`` of a wall that is one patch (one history key)."""
    return 0


@njit(inline="always", cache=True)
def rigid(walls, w, t):
    """Set the centre of wall w at time t, C0 + V t, and return the rotation by Omega t (Rodrigues'
    formula) as its 9 entries, row by row."""
    for d in range(3):
        walls[w, CENTRE + d] = walls[w, CENTRE0 + d] + walls[w, VEL + d] * t
    ox = walls[w, OMEGA]
    oy = walls[w, OMEGA + 1]
    oz = walls[w, OMEGA + 2]
    om = math.sqrt(ox * ox + oy * oy + oz * oz)
    if om == 0.0:
        return 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
    kx = ox / om
    ky = oy / om
    kz = oz / om
    c = math.cos(om * t)
    s = math.sin(om * t)
    u = 1.0 - c
    return (c + kx * kx * u, kx * ky * u - kz * s, kx * kz * u + ky * s,
            ky * kx * u + kz * s, c + ky * ky * u, ky * kz * u - kx * s,
            kz * kx * u - ky * s, kz * ky * u + kx * s, c + kz * kz * u)


@njit(inline="always", cache=True)
def move_point(walls, w, rot, row, col, row0, col0):
    """walls[row, col:col+3] := C + Rot (walls[row0, col0:col0+3] - C0): a point of wall w at the time of
    ``rigid`` (rot: its rotation)."""
    px = walls[row0, col0] - walls[w, CENTRE0]
    py = walls[row0, col0 + 1] - walls[w, CENTRE0 + 1]
    pz = walls[row0, col0 + 2] - walls[w, CENTRE0 + 2]
    walls[row, col] = walls[w, CENTRE] + rot[0] * px + rot[1] * py + rot[2] * pz
    walls[row, col + 1] = walls[w, CENTRE + 1] + rot[3] * px + rot[4] * py + rot[5] * pz
    walls[row, col + 2] = walls[w, CENTRE + 2] + rot[6] * px + rot[7] * py + rot[8] * pz


@njit(inline="always", cache=True)
def move_vector(walls, rot, row, col, row0, col0):
    """walls[row, col:col+3] := Rot walls[row0, col0:col0+3] (a direction, turned)."""
    px = walls[row0, col0]
    py = walls[row0, col0 + 1]
    pz = walls[row0, col0 + 2]
    walls[row, col] = rot[0] * px + rot[1] * py + rot[2] * pz
    walls[row, col + 1] = rot[3] * px + rot[4] * py + rot[5] * pz
    walls[row, col + 2] = rot[6] * px + rot[7] * py + rot[8] * pz


@njit(inline="always", cache=True)
def place_point_vector(walls, w, t):
    """``place`` of a kind whose data are a point and a unit vector now, then the same at time 0 (columns DATA
    ... DATA + 11: a plane's point and normal, a cylinder's point and axis)."""
    rot = rigid(walls, w, t)
    move_point(walls, w, rot, w, DATA, w, DATA + 6)
    move_vector(walls, rot, w, DATA + 3, w, DATA + 9)
