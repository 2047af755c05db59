"""The law table: the laws of each family, in id order. Everything else about the laws (ids, names, sources,
history sizes, the parameter row, the dispatch of ``laws.dispatch`` and the batch loops of ``dem.contact3d``)
is derived from it.

A law is one file in the folder of its family (``normal/``, ``tangential/``, ``twist/``, ``rolling/``)
plus one row here. The file declares:

- ``NAME``, ``FAMILY``, ``SOURCE`` (the paper and equation it implements), ``PARAMETERS`` (the slots of
  the parameter row it reads, ``declare.Param``: ``laws.generate`` numbers the row from them, in table
  order, after ``declare.COMMON``), ``STATE`` (its history slots, by name); optional ``OPTIONS`` (the
  ``Scene`` settings it takes beyond the common ones, ``declare.Option``: name, unit, default, valid
  values; ``Scene``, the presets and the command line take them from here, and a setting given to laws
  that do not take it is refused; default none; ``TAKES_E_N`` is set here: whether ``declare.E_N`` is among
  them);
- optional ``configure(scene, p)``: sets its slots of the parameter row ``p`` from the scene (materials,
  e_n, v_ref, its options), raising ``InputError`` for what it cannot act on; optional
  ``describe(scene, p)``: the derived parameters for reports (defaults: nothing to set, nothing to report);
- its kernels, ``@njit`` functions with the signature of its family: a planar form ``planar`` (normal and
  tangential laws) and a 3D form ``vector``; where both are kept for speed they stand side by side in the
  file and ``tests/laws/test_law_contract.py`` holds them equal;
- twist and rolling laws: a 3D form ``vector(params, row, H, c, b, N, a, n, w, dt)`` that returns the
  torque on body 1 from the relative spin w = w1 - w2 of the bodies, its state in the slots b ... b +
  VECTOR_SLOTS - 1 of the history row (their ids are recorded in the parameter row, from which the 3D
  step reads them); ``VECTOR_SLOTS`` (the number of its 3D slots), optional ``SWAP_NEGATE`` (the slots,
  relative to its base, that change sign when the bodies are swapped; default none) and ``VECTORS`` (the
  first slots, relative to its base, of the 3-vectors in global axes that ``rotate_history`` turns;
  default none), ``max_torque(p, N, a)`` (the largest torque [N m] the law gives on the parameter row p
  at normal force N and contact radius a: its slider's or Coulomb limit) and ``EXAMPLE`` (the Scene
  settings of a typical contact, which the contract tests use);
- optional hooks that the integrators and checks ask instead of naming laws (defaults: none):
  ``EXAMPLE``
  (the Scene settings of a typical contact of the law, e.g. its target e_n, which the contract tests use);
  ``calibration_target(scene)``: ``(e_n, speed, what)``, the restitution the scene's law was calibrated for,
  the normal speed at which it holds (None: every speed) and a description, or None;
  ``hint(scene, situation)``: the law's own reason, appended to the message of a failed or suspicious
  impact, for ``situation`` in ``HINT_SITUATIONS`` ("" for none); ``max_radius(scene)``: the largest
  contact radius [m] that the law's state covers (None: any); LAMMPS's equivalent model, where it has
  one (``lammps.native``): ``LAMMPS`` (normal and tangential laws: its name in ``pair granular``) and
  ``lammps_keywords(p)`` (twist and rolling laws: its keywords on the parameter row p; "" for none);
  ``CONVERGED_STEPS`` (tangential laws: the steps per contact at which an oblique impact's f/mu is
  converged to the chart's accuracy, 1e-4; default 20000, as first-order laws need);
  ``lammps_k_t(p)`` (tangential laws: the coefficient k_t of LAMMPS's equivalent tangential model, from
  which its ``twisting marshall`` is scaled; default Mindlin's 8 G*);
- family flags: normal laws ``USES_RATE`` (the force depends on the overlap rate: integrators kick with a
  predicted velocity), ``PLASTIC`` (a Thornton-like state whose largest force F* and limiting pressure
  p_y, the slot ``P_PY``, the tangential laws may read), ``contact_time(scene, vn)``, ``gap``, and where ``STATE`` is not empty ``store`` (writes the 3D
  state after the tangential law, which it may read); tangential laws ``VECTOR_SLOTS`` (fixed 3D slots, the
  work and the vector of ``laws.vector`` included), ``SWAP_NEGATE`` (the slots, relative to the
  tangential base, that change sign when the bodies are swapped), optional ``CELLS`` (default False: a
  state part sized by the cell count, the parameter n) with ``CELL_HEADER`` (planar slots before the
  cells) and ``SWAP_NEGATE_CELL`` (the component of each cell that changes sign).

Layout of a 3D history row (``laws.vector``)::

    [V_N, V_A | normal law's STATE | twist law's slots | rolling law's slots | tangential law's slots (cells last)]
     0    1     2 ...                twist_base(nid)      rolling_base(nid, q)  tangential_base(nid, q, r)

The twist and rolling laws of a contact are those of its parameter row (``P_TWIST_LAW``,
``P_ROLLING_LAW``), so the bases after the normal state depend on the row; with no twist or rolling law
(``none``, 0 slots) the row is the one of the normal and tangential laws alone. A table whose rows name
twist or rolling laws of different slot counts needs rows as long as its longest
(``vector_history_size`` of each row's laws).

After a change here or in a law's declarations, ``python -m dem_contact.laws.generate`` writes
``laws/dispatch.py`` again (a test fails while it is out of date).
"""
from types import MappingProxyType

from . import declare
from .slots import P_GSTAR

from .normal import hertz, hertz_damped, thornton
from .normal import linear as linear_normal
from .rolling import none as rolling_none
from .rolling import sds as rolling_sds
from .tangential import ddm, md, md_rescale, mdr, mdr_adaptive, mindlin_incremental, mindlin_rescale, mindlin_total
from .tangential import linear as linear_tangential
from .twist import deresiewicz
from .twist import marshall as twist_marshall
from .twist import none as twist_none
from .twist import sds as twist_sds

#: the laws of each family, in id order (the id of a law is its place here)
FAMILIES = MappingProxyType({
    "normal": (hertz, thornton, hertz_damped, linear_normal),
    "tangential": (md, md_rescale, mindlin_total, mindlin_incremental, mindlin_rescale, linear_tangential, ddm, mdr,
                   mdr_adaptive),
    "twist": (twist_none, twist_marshall, twist_sds, deresiewicz),
    "rolling": (rolling_none, rolling_sds),
})

#: the law of each family that a Scene uses when none is named
DEFAULTS = MappingProxyType({"normal": "hertz", "tangential": "mdr_adaptive", "twist": "none", "rolling": "none"})

#: the largest normal state (3D slots V_STATE ... V_STATE + 4: the five values s0 ... s4 of the 3D form)
MAX_NORMAL_STATE = 5


def ids(family: str) -> MappingProxyType:
    """{name: id} of the laws of ``family``."""
    return MappingProxyType({law.NAME: i for i, law in enumerate(FAMILIES[family])})


def law_id(family: str, name: str) -> int:
    return ids(family)[name]


def law(family: str, key):
    """The law module of ``family`` with the name or id ``key``."""
    laws = FAMILIES[family]
    if isinstance(key, str):
        return laws[ids(family)[key]]
    return laws[key]


def options() -> tuple:
    """Every Scene option that some law takes (``declare.Option``), in table order."""
    seen = []
    for laws in FAMILIES.values():
        for m in laws:
            seen += [o for o in m.OPTIONS if o not in seen]
    return tuple(seen)


def option(name: str):
    """The ``declare.Option`` of the Scene option ``name``."""
    return {o.name: o for o in options()}[name]


def takers(name: str) -> list:
    """The laws that take the Scene option ``name``, as "law (family)"."""
    return [f"{m.NAME} ({m.FAMILY})" for laws in FAMILIES.values() for m in laws if name in m.OPTIONS]


def parameters() -> tuple:
    """The slots of the parameter row, in row order (``declare.Param``): ``declare.COMMON``, then those the laws
    declare, in table order, each slot once (where several laws read it, the first one's declaration)."""
    seen = {}
    for p in declare.COMMON + tuple(p for laws in FAMILIES.values() for m in laws for p in m.PARAMETERS):
        seen.setdefault(p.slot, p)
    return tuple(seen.values())


def parameter_readers(slot: str) -> list:
    """The laws that declare the slot ``slot`` ("family name")."""
    return [f"{m.FAMILY} {m.NAME}" for laws in FAMILIES.values() for m in laws
            if any(p.slot == slot for p in m.PARAMETERS)]


def twist_base(nid: int) -> int:
    """First slot of the twist law's state in a 3D history row (``laws.vector``): after the normal state."""
    return 2 + len(FAMILIES["normal"][nid].STATE)


def rolling_base(nid: int, qid: int = 0) -> int:
    """First slot of the rolling law's state: after the state of the twist law ``qid``."""
    return twist_base(nid) + FAMILIES["twist"][qid].VECTOR_SLOTS


def tangential_base(nid: int, qid: int = 0, rid: int = 0) -> int:
    """First tangential slot of a 3D history row (``laws.vector``): after the states of the normal law
    ``nid``, the twist law ``qid`` and the rolling law ``rid``."""
    return rolling_base(nid, qid) + FAMILIES["rolling"][rid].VECTOR_SLOTS


def vector_history_size(nid: int, tid: int, n_cells: int = 0, qid: int = 0, rid: int = 0) -> int:
    """Length of a 3D history row for the normal law ``nid``, the tangential law ``tid`` with ``n_cells``
    cells (laws with ``CELLS``), the twist law ``qid`` and the rolling law ``rid``."""
    t = FAMILIES["tangential"][tid]
    return tangential_base(nid, qid, rid) + t.VECTOR_SLOTS + (2 * int(n_cells) if t.CELLS else 0)


def planar_extra(tid: int, n_cells: int) -> int:
    """Planar history slots after ``slots.N_HIST_BASE`` of the tangential law ``tid``."""
    t = FAMILIES["tangential"][tid]
    return t.CELL_HEADER + int(n_cells) if t.CELLS else 0


def law_rows() -> list:
    """One dict per law (family, id, name, source, parameters, state, options), for reports and the
    documentation's tables."""
    return [dict(family=family, id=i, name=m.NAME, source=m.SOURCE, parameters=", ".join(m.PARAMETERS),
                 state=", ".join(m.STATE), options=", ".join(m.OPTIONS))
            for family, laws in FAMILIES.items() for i, m in enumerate(laws)]


def _nothing(scene, p):
    return {}


def _no_target(scene):
    return None


def _no_hint(scene, situation):
    return ""


def _unbounded(scene):
    return None


def _no_lammps(p):
    return None


def _mindlin_k_t(p):
    return 8.0 * p[P_GSTAR]


#: the optional declarations and their defaults (set here on the law files that leave them out)
OPTIONAL = MappingProxyType({"OPTIONS": (), "CELLS": False, "configure": _nothing, "describe": _nothing,
                             "SWAP_NEGATE": (), "VECTORS": (), "EXAMPLE": MappingProxyType({}),
                             "calibration_target": _no_target, "hint": _no_hint, "max_radius": _unbounded,
                             "LAMMPS": None, "lammps_keywords": _no_lammps, "CONVERGED_STEPS": 20000,
                             "lammps_k_t": _mindlin_k_t})

#: the situations a law's ``hint`` may explain (an impact's failure or warning, by the law's own reasons)
HINT_SITUATIONS = ("long_contact", "coarse_step", "impulse_excess")


def _check():
    for family, laws in FAMILIES.items():
        names = [m.NAME for m in laws]
        assert len(set(names)) == len(names), f"two {family} laws of one name"
        for m in laws:
            for attr, default in OPTIONAL.items():
                if not hasattr(m, attr):
                    setattr(m, attr, default)
            assert m.FAMILY == family, f"{m.__name__} declares family {m.FAMILY}, listed under {family}"
            assert all(isinstance(o, declare.Option) for o in m.OPTIONS), f"{m.__name__}: OPTIONS are declare.Option"
            assert all(isinstance(p, declare.Param) for p in m.PARAMETERS), f"{m.__name__}: PARAMETERS: declare.Param"
            # whether a target restitution e_n acts on the law (a dashpot or a calibration)
            m.TAKES_E_N = declare.E_N in m.OPTIONS
            for attr in ("SOURCE", "PARAMETERS", "STATE", "OPTIONS", "configure", "describe", "vector"):
                assert hasattr(m, attr), f"{m.__name__} lacks {attr}"
        assert DEFAULTS[family] in names
    assert max(len(m.STATE) for m in FAMILIES["normal"]) <= MAX_NORMAL_STATE
    for name in {o.name for o in options()}:
        decl = {id(o) for laws in FAMILIES.values() for m in laws for o in m.OPTIONS if o.name == name}
        assert len(decl) == 1, f"the laws that take {name} must list the same declare.Option"
    for p in parameters():
        same = {(q.unit, q.size) for laws in FAMILIES.values() for m in laws for q in m.PARAMETERS if q.slot == p.slot}
        assert len(same) <= 1, f"laws declare the slot {p.slot} with different units or sizes"
    for m in FAMILIES["normal"]:
        assert not m.PLASTIC or "P_PY" in {p.slot for p in m.PARAMETERS}, f"{m.__name__}: a PLASTIC law sets P_PY"
    for f in ("twist", "rolling"):
        for m in FAMILIES[f]:
            assert all(0 <= k < m.VECTOR_SLOTS for k in m.SWAP_NEGATE), f"{m.__name__}: SWAP_NEGATE outside its slots"
            assert all(0 <= k <= m.VECTOR_SLOTS - 3 for k in m.VECTORS), f"{m.__name__}: VECTORS outside its slots"
            assert callable(m.max_torque) and isinstance(m.EXAMPLE, dict), f"{m.__name__}: max_torque, EXAMPLE"
        assert FAMILIES[f][0].NAME == "none" and FAMILIES[f][0].VECTOR_SLOTS == 0, \
            f"the {f} law of id 0 is 'none', without slots (the default of the contact helpers)"


_check()
