"""The terms of one contact, shared by the LAMMPS plugin's steps (``pair_kernel``, ``wall_kernel``) and its
table file (``table_file``): the law's inputs of a sphere on a wall (kinematics as LAMMPS's granular models: the
slip velocity with the full radius, v = v1 - v_wall + (R1 w1) x n, and the spin of the contact frame), the
moment of a tangential force; the parameter row of a contact of atoms not of their type's size (its R* and m*:
the per-row information of a table, ``RI_...``); and the load a contact puts on a wall."""

from numba import njit

from ..laws.slots import P_DELTA_Y, P_F_Y, P_MSTAR, P_RSTAR
from ..walls import table as W

# columns of the per-row information (float64[n_rows, N_ROWINFO]) of the sizes of the atoms: the parameter row of
# a type pair is that of its Spheres' radii; an atom of another radius gets the row with its contact's R* and m*
RI_RSTAR = 0     # R* of the row [m]
RI_Q = 1         # m*^2 / R* of the row: a Hertzian contact time and largest overlap scale as (m*^2 / R*)^(1/5)
RI_TC = 2        # contact time of the row at v_max [s]
RI_ALPHA = 3     # exponent of the speed in the contact time: t_c(v) = t_c(v_max) (v_max / v)^alpha
RI_DEEPEST = 4   # overlap of a head-on impact of the row at v_max [m]
RI_CURV = 5      # a wall row: the curvature of the wall's material, 1/R2 in R* (0: flat; a sphere row: 0)
RI_DEEP_ALPHA = 6   # exponent of the speed in that overlap near v_max: delta(v) ~ delta(v_max) (v / v_max)^this
N_ROWINFO = 7
#: slots of the parameter row that scale with R*^power (the rest but R* and m* do not depend on the sizes;
#: the table file checks this for each law: ``table_file.size_free``)
SIZE_SLOTS = ((P_DELTA_Y, 1.0), (P_F_Y, 2.0))


@njit(inline="always", cache=True)
def put_contact(normals, overlaps, velocities, n, nx, ny, nz, delta, vx, vy, vz):
    """The law's inputs of contact n: its unit normal, overlap and slip velocity."""
    normals[n, 0] = nx
    normals[n, 1] = ny
    normals[n, 2] = nz
    overlaps[n] = delta
    velocities[n, 0] = vx
    velocities[n, 1] = vy
    velocities[n, 2] = vz


@njit(inline="always", cache=True)
def wall_slip(x, v, omega, radius, walls, i, w, gap, nx, ny, nz, frame_spin):
    """(vx, vy, vz, wn) of the contact of sphere i with wall w (body 1 the sphere, n from the sphere to the
    wall, the contact point c = x + gap n on the wall's surface): the slip velocity, the sphere's surface
    velocity v + R omega x n minus the wall's at c (``walls.contract.velocity``), and where ``frame_spin``
    the spin of the contact frame about n, the mean of the sphere's and the wall's (else 0)."""
    uwx, uwy, uwz = W.velocity(walls, w, x[i, 0] + gap * nx, x[i, 1] + gap * ny, x[i, 2] + gap * nz)
    ra = radius[i]
    wx = ra * omega[i, 0]
    wy = ra * omega[i, 1]
    wz = ra * omega[i, 2]
    vx = v[i, 0] - uwx + (wy * nz - wz * ny)
    vy = v[i, 1] - uwy + (wz * nx - wx * nz)
    vz = v[i, 2] - uwz + (wx * ny - wy * nx)
    wn = 0.0
    if frame_spin:
        wn = 0.5 * ((omega[i, 0] + walls[w, W.OMEGA]) * nx + (omega[i, 1] + walls[w, W.OMEGA + 1]) * ny
                    + (omega[i, 2] + walls[w, W.OMEGA + 2]) * nz)
    return vx, vy, vz, wn


@njit(inline="always", cache=True)
def normal_cross(normals, tforces, k):
    """n x Ft of contact k: times the arm, the moment of its tangential force about a body's centre."""
    nx = normals[k, 0]
    ny = normals[k, 1]
    nz = normals[k, 2]
    tx = tforces[k, 0]
    ty = tforces[k, 1]
    tz = tforces[k, 2]
    return ny * tz - nz * ty, nz * tx - nx * tz, nx * ty - ny * tx


@njit(inline="always", cache=True)
def size_factor(rowinfo, row, rstar, mstar):
    """(m*^2 / R*)^(1/5) of a contact over that of its row: a Hertzian contact time and largest overlap
    scale so (Johnson 1985, Contact Mechanics, eqs. 11.23-11.24)."""
    return (mstar * mstar / (rstar * rowinfo[row, RI_Q])) ** 0.2


@njit(inline="always", cache=True)
def contact_row(params, row, pc, n, rowinfo, rstar, mstar):
    """pc[n] := the parameter row ``row`` with the contact's R* and m* (and the slots of SIZE_SLOTS scaled)."""
    for q in range(params.shape[1]):
        pc[n, q] = params[row, q]
    s = rstar / rowinfo[row, RI_RSTAR]
    pc[n, P_RSTAR] = rstar
    pc[n, P_MSTAR] = mstar
    pc[n, P_DELTA_Y] = params[row, P_DELTA_Y] * s
    pc[n, P_F_Y] = params[row, P_F_Y] * (s * s)


@njit(inline="always", cache=True)
def resized(radius, rmass, typ, type_size, i):
    """Whether atom i's radius or mass is not its type's (type_size[type - 1] = (radius, mass), to 1e-12)."""
    t = typ[i] - 1
    return abs(radius[i] - type_size[t, 0]) > 1e-12 * type_size[t, 0] or \
        abs(rmass[i] - type_size[t, 1]) > 1e-12 * type_size[t, 1]


@njit(inline="always", cache=True)
def effective(radius, rmass, a, b, rowinfo, row):
    """(R*, m*) of atoms a and b of parameter row ``row``, as LAMMPS's granular models (b < 0: a wall, 1/R2 its
    material's curvature RI_CURV, 0 if flat, and 1/m2 = 0)."""
    if b < 0:
        k = rowinfo[row, RI_CURV]
        return (radius[a] if k == 0.0 else 1.0 / (1.0 / radius[a] + k)), rmass[a]
    return radius[a] * radius[b] / (radius[a] + radius[b]), rmass[a] * rmass[b] / (rmass[a] + rmass[b])


@njit(inline="always", cache=True)
def add_wall_load(x, radius, walls, w, a, delta, normals, forces, torques, n, load):
    """Add to load float64[7] the load on wall w of contact n of sphere a (forces[n], torques[n]: on the
    sphere; normals[n] from the sphere to the wall, overlap delta): -F, (c - C) x (-F) - M and F . v_wall(c),
    with c = x + (R - delta) n the contact point on the wall's surface and C the wall's centre now."""
    s = radius[a] - delta
    cx = x[a, 0] + s * normals[n, 0]
    cy = x[a, 1] + s * normals[n, 1]
    cz = x[a, 2] + s * normals[n, 2]
    fx = forces[n, 0]
    fy = forces[n, 1]
    fz = forces[n, 2]
    rx = cx - walls[w, W.CENTRE]
    ry = cy - walls[w, W.CENTRE + 1]
    rz = cz - walls[w, W.CENTRE + 2]
    load[0] -= fx
    load[1] -= fy
    load[2] -= fz
    load[3] -= ry * fz - rz * fy + torques[n, 0]
    load[4] -= rz * fx - rx * fz + torques[n, 1]
    load[5] -= rx * fy - ry * fx + torques[n, 2]
    vx, vy, vz = W.velocity(walls, w, cx, cy, cz)
    load[6] += fx * vx + fy * vy + fz * vz
