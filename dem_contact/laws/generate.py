"""Write ``laws/slots.py``, ``laws/dispatch.py`` and ``laws/dispatch3d.py`` from the law table:
``python -m dem_contact.laws.generate``.

numba inlines and caches a switch on a law id only when the cases are literal integers, so the switch is
written out as code, from ``laws.table``; the slots of the parameter row are numbered from the laws'
``PARAMETERS`` (``declare.Param``) for the same reason (kernels read them as constants).
``tests/laws/test_law_contract.py`` fails while a file is out of date. A law that declares a new slot can be
imported before the slot is numbered only in the process of this generator (``laws.slots`` then reads it as
-1).
"""
import pathlib

#: the generator's module, as its command line names it (``laws.slots`` looks for it)
GENERATOR = "dem_contact.laws.generate"
HERE = pathlib.Path(__file__).parent
TARGET = HERE / "dispatch.py"
TARGET_3D = HERE / "dispatch3d.py"
TARGET_SLOTS = HERE / "slots.py"


def slots_source() -> str:
    """``laws/slots.py``: the slots of the parameter row, numbered in the order of ``table.parameters()``, with
    the history slots of ``laws.history_slots``."""
    from . import table

    import textwrap

    rows = []
    out = ['"""Named slots of the parameter row (one per pair type, float64[N_PARAMS], read by every kernel) and of',
           "the history row (``laws.history_slots``), generated from the laws' ``PARAMETERS`` by",
           "``python -m dem_contact.laws.generate``: do not edit (a test fails when it is out of date).", "",
           "Parameter row:", ""]
    k = 0
    for p in table.parameters():
        readers = table.parameter_readers(p.slot)
        unit = f" [{p.unit}]" if p.unit else ""
        size = f" ({p.size} slots)" if p.size > 1 else ""
        rows.append((p.slot, f"{p.doc}{unit}{size}" + (f" ({', '.join(dict.fromkeys(readers))})" if readers else "")))
        k += p.size
    width = max(len(s) for s, _ in rows) + 2
    out += ["=" * width + "  " + "=" * 70, f"{'slot':<{width}}  meaning [unit] (the laws that read it)",
            "=" * width + "  " + "=" * 70]
    for s, d in rows:
        lines = textwrap.wrap(d, 116 - width)
        out += [f"{s:<{width}}  {lines[0]}"] + [" " * (width + 2) + line for line in lines[1:]]
    out += ["=" * width + "  " + "=" * 70, '"""', "import sys as _sys", "",
            "from .history_slots import *  # noqa: F401,F403  (the history row)", ""]
    k = 0
    for p in table.parameters():
        out.append(f"{p.slot} = {k}")
        if p.size > 1:
            out.append(f"{p.slot}_SIZE = {p.size}")
        k += p.size
    out += [f"N_PARAMS = {k}", "", "",
            "def __getattr__(name):",
            "    if name.startswith(\"P_\") and \"%s\" in getattr(_sys, \"orig_argv\", ()):" % GENERATOR,
            "        return -1      # a slot a law declares, being numbered now (laws.generate)",
            "    raise AttributeError(f\"module {__name__!r} has no attribute {name!r}\" + (",
            "        \": a slot a law's PARAMETERS declare is numbered by `python -m dem_contact.laws.generate`\"",
            "        if name.startswith(\"P_\") else \"\"))", ""]
    return "\n".join(out)
ALIASES = {"normal": "n", "tangential": "t", "twist": "q", "rolling": "r"}


def _switch(family, head, call):
    """A function ``head`` that returns ``call`` (with {m}: the law's module alias) for the law of the id (its
    first argument), as one conditional expression; the fall-through is the last law, and for the twist and
    rolling families the law of id 0, none (a row that records no law: id -1)."""
    from . import table

    laws = table.FAMILIES[family]
    arg = head.split("(")[1].split(",")[0]
    order = list(range(1, len(laws))) + [0] if family in ("twist", "rolling") else list(range(len(laws)))
    cases = [f"{call.format(m=f'{ALIASES[family]}{i}')} if {arg} == {i} else " for i in order[:-1]]
    return ["", "", "@njit(inline=\"always\", cache=True)", f"def {head}:",
            f"    return {''.join(cases)}{call.format(m=f'{ALIASES[family]}{order[-1]}')}"]


def source() -> str:
    from . import table

    out = ['"""Law dispatch by id, generated from ``laws.table`` by ``python -m dem_contact.laws.generate``: do not',
           'edit (a test fails when it is out of date). The ids are the places of the laws in ``table.FAMILIES``."""',
           "from numba import njit", ""]
    for family, laws in table.FAMILIES.items():
        out += [f"from .{family} import {m.__name__.rsplit('.', 1)[1]} as {ALIASES[family]}{i}"
                for i, m in enumerate(laws)]
    out.append("")
    for family, laws in table.FAMILIES.items():
        out.append(f"{family.upper()}_NAMES = ({', '.join(repr(m.NAME) for m in laws)},)")
        out.append(f"{family.upper()}_IDS = tuple(range({len(laws)}))")
    normal = table.FAMILIES["normal"]
    out += _switch("normal", "normal_force(nid, p, h, delta, vel)", "{m}.planar(p, h, delta, vel)")
    out += _switch("normal", "normal_gap(nid, p, h, delta, vel)", "{m}.gap(p, h, delta, vel)")
    out += _switch("tangential", "tangential_force(tid, p, h, N, dN, a, a_old, dd)",
                   "{m}.planar(p, h, N, dN, a, a_old, dd)")
    out += _switch("normal", "normal_vector(nid, params, row, H, c, delta, vel)",
                   "{m}.vector(params, row, H, c, delta, vel)")
    for family in ("twist", "rolling"):
        out += _switch(family, f"{family}_torque(lid, params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt)",
                       "{m}.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt)")
    rate = [i for i, m in enumerate(normal) if m.USES_RATE]
    out += ["", "", "@njit(inline=\"always\", cache=True)", "def uses_rate(nid):",
            "    \"\"\"Whether the normal law's force depends on the overlap rate (``USES_RATE``).\"\"\"",
            f"    return {' or '.join(f'nid == {i}' for i in rate) or 'False'}"]
    out += ["", "", "@njit(inline=\"always\", cache=True)", "def twist_base(nid):",
            "    \"\"\"First slot of the twist law's state in a 3D history row: after the normal law's state.\"\"\""]
    for i, m in enumerate(normal):
        if m.STATE:
            out += [f"    if nid == {i}:", f"        return {table.twist_base(i)}"]
    out.append("    return 2")
    for family, head, base in (("twist", "rolling_base(nid, qid)", "twist_base(nid)"),
                               ("rolling", "tangential_base(nid, qid, rid)", "rolling_base(nid, qid)")):
        arg = "qid" if family == "twist" else "rid"
        sized = [(i, m.VECTOR_SLOTS) for i, m in enumerate(table.FAMILIES[family]) if m.VECTOR_SLOTS]
        slots = "".join(f"{k} if {arg} == {i} else " for i, k in sized) + "0"
        out += ["", "", "@njit(inline=\"always\", cache=True)", f"def {head}:",
                f"    \"\"\"First slot after the {family} law's state (``laws.table``: the layout of a 3D row).\"\"\"",
                f"    return {base} + ({slots})"]
    out += ["", "", "@njit(inline=\"always\", cache=True)",
            "def store_normal(nid, H, c, s0, s1, s2, s3, s4, N, tx, ty, tz):",
            "    \"\"\"The normal law's ``store`` (laws with a 3D state).\"\"\""]
    for i, m in enumerate(normal):
        if m.STATE:
            out += [f"    if nid == {i}:", f"        n{i}.store(H, c, s0, s1, s2, s3, s4, N, tx, ty, tz)"]
    out.append("")
    return "\n".join(out)


def source_3d() -> str:
    """The switch of the single-contact 3D entry on the tangential law id, over ``compose.LEAVES``."""
    from . import table

    laws = table.FAMILIES["tangential"]
    out = ['"""The 3D contact step by tangential law id, generated from ``laws.table`` by',
           '``python -m dem_contact.laws.generate``: do not edit."""',
           "from numba import njit", "", "from .compose import LEAVES", "from .vector import JIT", "",
           f"({', '.join(f'_{i}' for i in range(len(laws)))},) = LEAVES", "", "",
           "@njit(inline=\"always\", **JIT)",
           "def contact_leaf(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt):",
           "    \"\"\"``compose.LEAVES[tid]`` (tid assumed valid).\"\"\""]
    call = "_{i}(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt)"
    cases = "".join(f"{call.format(i=i)} if tid == {i} else " for i in range(len(laws) - 1))
    out += [f"    return {cases}{call.format(i=len(laws) - 1)}", ""]
    return "\n".join(out)


def main():
    TARGET_SLOTS.write_text(slots_source())
    TARGET.write_text(source())
    TARGET_3D.write_text(source_3d())
    print(f"wrote {TARGET_SLOTS}, {TARGET} and {TARGET_3D}")


if __name__ == "__main__":
    main()
