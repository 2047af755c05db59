"""The 3D layout of a contact's history row, and the arithmetic of vectors in the tangent plane that the 3D
forms of the laws share.

The 3D forms of the laws (``vector`` in each law file) are functions of scalars and of the contact's row of
the history table ``H[c, j]``: they read their state from it and write it back, so that no array is passed
between functions on the hot path.

Layout of a 3D history row (float64):

=========================  =============================================================================
slot                       meaning
=========================  =============================================================================
V_N, V_A                   normal force [N] and contact radius [m] after the last step
2 ...                      the normal law's state (its ``STATE``; none for most laws)
q ...                      the twist law's state (its ``VECTOR_SLOTS``; none for ``none``)
r ...                      the rolling law's state (its ``VECTOR_SLOTS``; none for ``none``)
b + W_WORK                 running work absorbed by the tangential force, sum of 0.5 (T_old + T) . dd [J]
b + W_X, W_Y, W_Z          the tangential law's vector (global axes): a spring displacement, a force, a
                           force axis or the first axis of a frame
b + 4 ...                  the rest of the tangential law's state (its file), cells last
=========================  =============================================================================

with q = ``twist_base(nid)`` = 2 + the number of state slots of the normal law, r = ``rolling_base(nid, qid)``
= q + the twist law's slots and b = ``tangential_base(nid, qid, rid)`` = r + the rolling law's slots
(``laws.dispatch``; the twist and rolling laws are those of the contact's parameter row, ``laws.table``).
T is the tangential force in the direction of the displacement (the force on body 1 is -T). Each step
every stored vector is first carried into the current tangent plane and turned about the normal with the
contact (``carry``), then the slip increment dd (a vector in the tangent plane) acts on it.
"""
import math
import types

from numba import njit
from numba import types as nbtypes
from numba.core import cgutils, config
from numba.core.targetconfig import ConfigStack
from numba.extending import intrinsic, overload

#: numba options of every flat kernel: numpy's error model (no zero-division checks), and of fastmath only
#: 'contract' (fused multiply-add, as gcc does by default) and 'afn' (library functions such as cbrt may be
#: approximated): results stay within rounding of the strict build. Not 'nnan' / 'ninf' (a NaN force
#: signals an outgrown mdr grid, and the checks rely on NaN and inf), not 'reassoc' (cell sums keep order).
FASTMATH = {"contract", "afn"}
JIT = dict(cache=True, error_model="numpy", fastmath=FASTMATH)

# header of a 3D history row (the same slots as the planar row)
V_N = 0
V_A = 1
V_STATE = 2     # the normal law's state (its STATE; thornton: delta*, F*, R_p, delta_p, |T| / N)
# the slots every tangential law has, relative to its base b
W_WORK = 0
W_X = 1
W_Y = 2
W_Z = 3


def _row_pointer(context, builder, signature, args, checked):
    aryty = signature.args[0]
    ary = context.make_array(aryty)(context, builder, args[0])
    idx = [context.cast(builder, v, t, nbtypes.intp) for v, t in zip(args[1:3], signature.args[1:3])]
    return cgutils.get_item_pointer(context, builder, aryty, ary, idx, wraparound=False, boundscheck=checked)


def _is_row_access(H, c, j):
    return (isinstance(H, nbtypes.Array) and H.ndim == 2 and isinstance(c, nbtypes.Integer)
            and isinstance(j, nbtypes.Integer))


def _row_intrinsics(checked):
    """The load and the store of ``at``/``put``; ``checked``: bounds checked (an IndexError)."""

    @intrinsic
    def load(typingctx, H, c, j):
        if not _is_row_access(H, c, j):
            return None

        def codegen(context, builder, signature, args):
            return builder.load(_row_pointer(context, builder, signature, args, checked))

        return H.dtype(H, c, j), codegen

    @intrinsic
    def store(typingctx, H, c, j, value):
        if not _is_row_access(H, c, j):
            return None

        def codegen(context, builder, signature, args):
            v = context.cast(builder, args[3], signature.args[3], signature.args[0].dtype)
            builder.store(v, _row_pointer(context, builder, signature, args, checked))
            return context.get_dummy_value()

        return nbtypes.void(H, c, j, value), codegen

    return load, store


_LOAD, _STORE = _row_intrinsics(False)
_LOAD_CHECKED, _STORE_CHECKED = _row_intrinsics(True)


def _caller_checks_bounds() -> bool:
    """Whether the function being compiled checks bounds: NUMBA_BOUNDSCHECK where it is set (it overrides every
    function's flag, as in numba's own indexing), else the function's ``boundscheck`` (the overloads below are
    compiled with their own flags, so they ask the caller's)."""
    if config.BOUNDSCHECK is not None:
        return bool(config.BOUNDSCHECK)
    flags = ConfigStack.top_or_none()
    return bool(flags is not None and flags.boundscheck)


def at(H, c, j):
    """H[c, j] of a 2D array, both indices >= 0. Compiled, without numba's handling of negative indices: a
    compare and a select per access wherever numba cannot tell the index is >= 0, as for the slots b + k of the
    tangential laws and the cells of the MDR laws (on every cell of their loops: about 3% of the default law's
    contact update in a pour). Bounds are checked (an IndexError) where the function that calls it is compiled
    with bounds checks (``boundscheck=True``, or NUMBA_BOUNDSCHECK=1), as numba's own indexing is."""
    return H[c, j]


def put(H, c, j, value):
    """H[c, j] = value (``at``)."""
    H[c, j] = value


@overload(at)
def _at_jit(H, c, j):
    if _is_row_access(H, c, j):
        load = _LOAD_CHECKED if _caller_checks_bounds() else _LOAD
        return lambda H, c, j: load(H, c, j)


@overload(put)
def _put_jit(H, c, j, value):
    if _is_row_access(H, c, j) and H.mutable:
        store = _STORE_CHECKED if _caller_checks_bounds() else _STORE
        return lambda H, c, j, value: store(H, c, j, value)


def renamed(func, name, **bindings):
    """A copy of the Python function ``func`` under the name ``name`` (numba names compiled code by the
    qualified name: a kernel compiled twice with other options, or made per law, needs a name of its own),
    with the global names ``bindings`` bound (e.g. the law's kernel a template calls: globals, not closure
    cells, so that numba's disk cache, which keys on the closure's contents, serves it in every process)."""
    globs = {**func.__globals__, **bindings} if bindings else func.__globals__
    copy = types.FunctionType(func.__code__, globs, name, func.__defaults__, func.__closure__)
    copy.__qualname__ = name
    return copy


@njit(inline="always", **JIT)
def turn(x, y, z, nx, ny, nz, cs, sn):
    """Vector (x, y, z) in the plane normal to n turned by the angle (cos, sin) = (cs, sn) about n
    (Rodrigues' formula for a vector perpendicular to the axis)."""
    return (x * cs + (ny * z - nz * y) * sn,
            y * cs + (nz * x - nx * z) * sn,
            z * cs + (nx * y - ny * x) * sn)


@njit(inline="always", **JIT)
def in_plane(x, y, z, nx, ny, nz, un):
    """(x, y, z) less its part un = (x, y, z).n along n, and the squared length of what is left."""
    x -= un * nx
    y -= un * ny
    z -= un * nz
    return x, y, z, x * x + y * y + z * z


@njit(inline="always", **JIT)
def carry(x, y, z, nx, ny, nz, cs, sn):
    """A history vector carried into the tangent plane of n keeping its magnitude (projection and
    rescaling, as LAMMPS granular's tangential models do), then turned with the contact about n."""
    un = x * nx + y * ny + z * nz
    if un != 0.0:
        m2 = x * x + y * y + z * z
        x, y, z, p2 = in_plane(x, y, z, nx, ny, nz, un)
        x, y, z = _scaled(x, y, z, math.sqrt(m2 / p2) if p2 > 0.0 else 0.0)
    return _turned(x, y, z, nx, ny, nz, cs, sn)


@njit(inline="always", **JIT)
def _scaled(x, y, z, s):
    return x * s, y * s, z * s


@njit(inline="always", **JIT)
def _turned(x, y, z, nx, ny, nz, cs, sn):
    """(x, y, z) turned by the angle (cs, sn) about n, unless it is 0."""
    if sn != 0.0:
        x, y, z = turn(x, y, z, nx, ny, nz, cs, sn)
    return x, y, z


@njit(inline="always", **JIT)
def carry_unit(x, y, z, nx, ny, nz, cs, sn):
    """A unit axis carried into the tangent plane of n and turned with the contact about n; returns
    (0, 0, 0) when the axis is unset or parallel to n."""
    x, y, z, p2 = in_plane(x, y, z, nx, ny, nz, x * nx + y * ny + z * nz)
    if p2 <= 0.0:
        return 0.0, 0.0, 0.0
    x, y, z = _scaled(x, y, z, 1.0 / math.sqrt(p2))
    return _turned(x, y, z, nx, ny, nz, cs, sn)


@njit(inline="always", **JIT)
def cap_vector(x, y, z, muN):
    """Coulomb: scale the vector back to |T| = mu N if it is longer (direction kept)."""
    m2 = x * x + y * y + z * z
    if m2 > muN * muN:
        s = muN / math.sqrt(m2)
        return x * s, y * s, z * s, True
    return x, y, z, False
