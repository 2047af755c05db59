"""numba's on-disk cache, keyed on every source file that a compiled kernel may contain.

numba keys a cached kernel on the source file of the function it compiles, but the laws are inlined from
other files (``laws/*.py``): an edit there, or a new version of the package installed over an old one, would
leave every kernel that inlines them at the old numbers. This module registers cache locators (numba's
``CacheImpl._locator_classes``, consulted in order) that serve the package's files, and files a user
registers with ``follow_kernels``, and every jitted function whose globals reach the package (a function or a
module of the package, directly or through other jitted functions: a user's loop that calls ``contact_force``),
exactly as numba's own (same folders: ``NUMBA_CACHE_DIR``, the source's
``__pycache__`` or the user-wide cache), with the source stamp widened to a hash of every kernel source of the
package (``kernel_sources_hash``). Any change to those sources invalidates every such cache entry; an unchanged
package reuses them.

It must be imported before any jitted function of the package is defined (``dem_contact/__init__`` does it
first).
"""
from __future__ import annotations

import builtins
import dis
import functools
import hashlib
import os
import types

from numba.core import caching

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))

#: Parts of the package that no kernel reads (the CLI layer and the figures): edits there keep the cache.
_NOT_KERNEL_SOURCES = ("cli.py", "__main__.py", "plots.py", "commands")

_FOLLOWED = set()


@functools.lru_cache(maxsize=None)
def kernel_sources_hash() -> str:
    """SHA-256 over the path and content of every Python source of the package that a kernel may compile
    or inline (all but the CLI layer and the figures)."""
    h = hashlib.sha256()
    for root, dirs, files in os.walk(PACKAGE_DIR):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__" and not d.startswith("."))
        rel_root = os.path.relpath(root, PACKAGE_DIR)
        if rel_root.split(os.sep)[0] in _NOT_KERNEL_SOURCES:
            continue
        for name in sorted(files):
            if not name.endswith(".py") or (rel_root == "." and name in _NOT_KERNEL_SOURCES):
                continue
            rel = os.path.normpath(os.path.join(rel_root, name))
            with open(os.path.join(root, name), "rb") as f:
                h.update(rel.encode() + b"\0" + f.read() + b"\0")
    return h.hexdigest()


def follow_kernels(path: str) -> None:
    """Key numba's cache of the jitted functions defined in the file ``path`` (a user's own module, usually
    ``__file__``) on dem_contact's kernel sources too: call it before the file's ``@njit(cache=True)``
    functions are defined. Their cache entries are then recompiled whenever the inlined laws change
    (a new version of dem_contact), instead of running the previous version's laws."""
    _FOLLOWED.add(os.path.abspath(path))


def _of_package(name) -> bool:
    return isinstance(name, str) and (name == "dem_contact" or name.startswith("dem_contact."))


def _global_names(code) -> set:
    """The global names that ``code`` (and the code nested in it) loads."""
    names = {i.argval for i in dis.get_instructions(code) if i.opname in ("LOAD_GLOBAL", "LOAD_NAME")}
    for c in code.co_consts:
        if isinstance(c, types.CodeType):
            names |= _global_names(c)
    return names


def _reaches_package(py_func, seen=None) -> bool:
    """Whether a global that ``py_func`` loads is a module or a function of the package, directly or through
    the jitted functions (numba dispatchers) it calls: then its compiled code may inline laws. A global not
    defined yet (a function further down its file) counts as reaching it."""
    seen = set() if seen is None else seen
    if id(py_func) in seen:
        return False
    seen.add(id(py_func))
    code = getattr(py_func, "__code__", None)
    if code is None:
        return False
    globs = getattr(py_func, "__globals__", {})
    for name in _global_names(code):
        if name not in globs:
            if hasattr(builtins, name):
                continue
            return True
        v = globs[name]
        if isinstance(v, types.ModuleType):
            if _of_package(v.__name__):
                return True
            continue
        inner = getattr(v, "py_func", None)
        if _of_package(getattr(inner if inner is not None else v, "__module__", None)):
            return True
        if inner is not None and _reaches_package(inner, seen):
            return True
    return False


def _served(py_file, py_func=None) -> bool:
    path = os.path.abspath(py_file)
    return (path.startswith(PACKAGE_DIR + os.sep) or path in _FOLLOWED
            or (py_func is not None and _reaches_package(py_func)))


class _KernelStamp:
    """Mixin: a numba locator for the package's files (and followed files) whose source stamp also holds
    ``kernel_sources_hash``."""

    @classmethod
    def from_function(cls, py_func, py_file):
        if not _served(py_file, py_func):
            return None
        return super().from_function(py_func, py_file)

    def get_source_stamp(self):
        return (super().get_source_stamp(), kernel_sources_hash())


class UserProvidedKernelLocator(_KernelStamp, caching.UserProvidedCacheLocator):
    """``NUMBA_CACHE_DIR``, when set."""


class InTreeKernelLocator(_KernelStamp, caching.InTreeCacheLocator):
    """The ``__pycache__`` folder beside the source."""


class UserWideKernelLocator(_KernelStamp, caching.UserWideCacheLocator):
    """The user-wide cache folder, when ``__pycache__`` is not writable (a read-only install)."""


LOCATORS = (UserProvidedKernelLocator, InTreeKernelLocator, UserWideKernelLocator)


def install() -> None:
    """Put the locators ahead of numba's own (idempotent)."""
    classes = caching.CacheImpl._locator_classes
    if LOCATORS[0] not in classes:
        classes[:0] = LOCATORS


install()
