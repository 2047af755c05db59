"""The package's rooms and the direction of their imports: laws <- impacts <- studies <- commands, with
rebound/ (pure functions of numbers) and dem/ (what DEM codes call) beside them; walls/ (the kinds of wall,
under dem/ and lammps/); kernel_cache (numba's cache locators) below everything, set up first by the
package's __init__."""
import ast
import importlib
import pathlib
import pkgutil

import dem_contact

PKG = pathlib.Path(dem_contact.__file__).parent

#: What each room may import from the package (besides itself). Lazy imports inside functions count too.
ALLOWED = {
    "errors": set(),
    "version": set(),
    "kernel_cache": set(),
    "materials": {"errors"},
    "laws": {"errors", "materials"},
    "rebound": {"errors"},
    "reference": {"errors", "materials", "laws"},
    "walls": {"errors", "materials", "laws"},
    "dem": {"errors", "materials", "laws", "walls"},
    "impacts": {"errors", "materials", "laws", "dem"},
    "plots": {"errors", "rebound"},
    "studies": {"errors", "materials", "laws", "reference", "impacts", "rebound", "plots", "dem"},
    "lammps": {"errors", "version", "materials", "laws", "dem", "walls"},
    "commands": {"errors", "materials", "laws", "reference", "impacts", "rebound", "plots", "studies", "dem",
                 "lammps"},
    "cli": {"errors", "commands"},
    "__init__": {"kernel_cache", "version", "errors", "materials", "laws", "impacts"},
    "__main__": {"cli"},
}


def _room(module: str) -> str:
    """Room of a dotted module name below dem_contact (dem_contact.laws.mdr -> laws)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _package_imports(path: pathlib.Path, module: str):
    """Modules of dem_contact that the file imports (absolute names), with line numbers."""
    tree = ast.parse(path.read_text())
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("dem_contact"):
                if node.module is None:
                    for alias in node.names:
                        yield f"{target}.{alias.name}", node.lineno
                else:
                    yield target, node.lineno
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("dem_contact"):
                    yield alias.name, node.lineno


def _modules():
    """Every module of the package but __main__ (importing it runs the command line)."""
    for info in pkgutil.walk_packages([str(PKG)], prefix="dem_contact."):
        if not info.name.endswith("__main__"):
            yield info.name


def test_every_module_imports():
    """Importing each module on its own succeeds (an import cycle fails here)."""
    for name in _modules():
        importlib.import_module(name)


def test_imports_point_down():
    bad = []
    for name in [*_modules(), "dem_contact.__main__"]:
        path = PKG / "__main__.py" if name.endswith("__main__") else pathlib.Path(
            importlib.import_module(name).__file__)
        room = _room(name)
        assert room in ALLOWED, f"{name}: room {room!r} has no place in the layering"
        for target, line in _package_imports(path, name):
            other = _room(target)
            if other != room and other not in ALLOWED[room]:
                bad.append(f"{name}:{line} imports {target} ({room} -> {other})")
    assert not bad, "imports against the layering:\n" + "\n".join(bad)


#: The rooms inside laws/, lowest first: a module may import from its own room and the rooms below it,
#: function-level imports included. "parts": the law files and what they share (slots, the 3D layout, closed
#: forms); "table": the table of laws and what is generated or composed from it (the dispatch, the planar
#: contact step); "integration": what integrates a contact in time to calibrate a law (the head-on impact)
#: and the Scene that calls the calibrations.
LAW_ROOMS = (
    ("parts", {"normal", "tangential", "twist", "rolling", "declare", "slots", "history_slots", "vector", "closed_forms", "traction_yield",
               "twist_shear"}),
    ("table", {"table", "generate", "dispatch", "dispatch3d", "compose", "contact"}),
    ("integration", {"normal_impact", "model", "__init__"}),
)


def _law_room(module: str) -> int:
    """Index in LAW_ROOMS of a module of dem_contact.laws (dem_contact.laws.normal.hertz -> parts)."""
    parts = module.split(".")
    part = parts[2] if len(parts) > 2 else "__init__"
    for k, (_, members) in enumerate(LAW_ROOMS):
        if part in members:
            return k
    raise AssertionError(f"{module} has no room in LAW_ROOMS")


def test_laws_rooms_point_down():
    """Inside laws/, imports point down the rooms of LAW_ROOMS (function-level ones too): a law file imports
    nothing that integrates an impact or reads the table, so no import circle is broken by a late import."""
    bad = []
    for name in _modules():
        if _room(name) != "laws":
            continue
        here = _law_room(name)
        path = pathlib.Path(importlib.import_module(name).__file__)
        for target, line in _package_imports(path, name):
            if _room(target) == "laws" and target != "dem_contact.laws" and _law_room(target) > here:
                bad.append(f"{name}:{line} imports {target} ({LAW_ROOMS[here][0]} -> "
                           f"{LAW_ROOMS[_law_room(target)][0]})")
    assert not bad, "imports up the rooms of laws/:\n" + "\n".join(bad)


def test_rebound_never_integrates():
    for path in (PKG / "rebound").glob("*.py"):
        text = path.read_text()
        assert "integrate_impact" not in text and "numba" not in text, path


def test_no_import_cycle():
    """No cycle among the module-level imports of the package's modules."""
    names = set(_modules())
    graph = {}
    for name in names:
        path = pathlib.Path(importlib.import_module(name).__file__)
        top = ast.parse(path.read_text()).body
        module_level = set()
        for target, line in _package_imports(path, name):
            if any(getattr(node, "lineno", -1) == line for node in top):
                module_level.add(target if target in names else target.rsplit(".", 1)[0])
        graph[name] = {t for t in module_level if t in names and t != name}
    state = {}

    def visit(n, stack):
        state[n] = 1
        for m in graph[n]:
            if state.get(m) == 1:
                raise AssertionError("import cycle: " + " -> ".join(stack + [n, m]))
            if m not in state:
                visit(m, stack + [n])
        state[n] = 2

    for n in sorted(graph):
        if n not in state:
            visit(n, [])


#: Where a law's name stands in code outside laws/ because a user or a published case names the law
#: (the laws a study compares, a command's choices), as (module, name): the behaviour of the package never
#: turns on a law's name there.
NAMED_BY_USER = {
    ("dem_contact.reference.impact", "hertz"),      # the BEM reference solves Hertz's contact
    ("dem_contact.commands.path", "hertz"),         # --reference: the BEM reference solves Hertz's contact
    ("dem_contact.studies.paths", "hertz"),         # the coupled twist-shear path law is written for Hertz
}


def _law_names():
    from dem_contact.laws import table
    return {m.NAME for laws in table.FAMILIES.values() for m in laws} - {"none"}


def _law_comparisons(path: pathlib.Path, names):
    """(line, name) of each comparison of a law attribute (``.normal``, ``.tangential``, ``.twist``,
    ``.rolling``, ``args.normal``, ...) with a law's name: behaviour chosen by a law's name."""
    tree = ast.parse(path.read_text())
    attrs = {"normal", "tangential", "twist", "rolling"}
    for node in ast.walk(tree):
        if not isinstance(node, ast.Compare):
            continue
        sides = [node.left, *node.comparators]
        if not any((isinstance(s, ast.Attribute) and s.attr in attrs) or (isinstance(s, ast.Name) and s.id in attrs)
                   for s in sides):
            continue
        for s in sides:
            for c in ast.walk(s):
                if isinstance(c, ast.Constant) and isinstance(c.value, str) and c.value in names:
                    yield node.lineno, c.value


def test_no_law_chosen_by_name_outside_laws():
    """Outside laws/, no code compares a scene's (or an option's) law with a law's name: a law's properties
    (contact time, calibration target, hints, the grid it covers, whether e_n acts) are its declarations
    and hooks (``laws.table``), so a new law gets the behaviour of its declarations."""
    names = _law_names()
    bad = []
    for name in _modules():
        if _room(name) == "laws":
            continue
        path = pathlib.Path(importlib.import_module(name).__file__)
        for line, law in _law_comparisons(path, names):
            if (name, law) not in NAMED_BY_USER:
                bad.append(f"{name}:{line} compares with {law!r}")
    assert not bad, "\n".join(bad)


def test_the_tests_mirror_the_rooms():
    """Every folder of tests/ (but the benchmarks) is a room of the package, and every test file sits in the
    folder of its room, but the tests of the whole package (its layout, its documentation, its examples)."""
    tests = pathlib.Path(__file__).parent
    folders = {p.name for p in tests.iterdir() if p.is_dir() and not p.name.startswith((".", "__"))} - {"benchmarks"}
    assert folders and folders <= set(ALLOWED), folders - set(ALLOWED)
    assert {p.name for p in tests.glob("test_*.py")} == {"test_layout.py", "test_docs.py", "test_examples.py"}
