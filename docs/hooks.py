"""MkDocs hooks of the documentation site (``hooks:`` in mkdocs.yml).

- ``<!-- law-table FAMILY -->`` in a page becomes the Markdown table of the laws of that family (``normal``,
  ``tangential``, ...), from ``dem_contact.laws.table.law_rows()``; ``<!-- law-table others -->`` becomes a
  section with the tables of the families that no marker of the page names (nothing when there are none).
- ``<!-- api-modules PACKAGE ... -->`` becomes a ``::: module`` directive (mkdocstrings) for each named package
  that exists and for every module in it, so a new law file appears in the API reference without an edit
  of the page (``api_directives`` is what ``tests/test_docs.py`` reads too).
- ``<!-- layout-rules -->`` becomes the table of what each room of the package may import, read from
  ``ALLOWED`` in ``tests/test_layout.py``.
- A docstring's bracketed unit after a shape or an index (``float64[n, 3] [m]``, ``vt[i] [m/s]``) reads as a
  Markdown reference link; the cross-reference plugin's warning about a target that a docstring wrote is
  dropped (the docstrings are plain text and link nothing). An unresolved cross-reference of a page stays a
  warning (an error under ``--strict``).
"""
from __future__ import annotations

import ast
import importlib
import logging
import pathlib
import pkgutil
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
LAW_MARKER = re.compile(r"<!--\s*law-table\s+([\w-]+)\s*-->")
LAYOUT_MARKER = "<!-- layout-rules -->"
API_MARKER = re.compile(r"<!--\s*api-modules\s+([\w. ]+?)\s*-->")
#: columns of the law tables, in this order, each shown when a row has it (options: the Scene settings the law takes)
COLUMNS = ("name", "id", "family", "source", "parameters", "state", "options")
#: families in the order their tables appear in the "others" section
FAMILY_ORDER = ("normal", "tangential", "twist", "rolling")

log = logging.getLogger("mkdocs.hooks.dem_contact")


def law_rows() -> list[dict]:
    """The rows of the table of laws: ``dem_contact.laws.table.law_rows()``, or, where the package has no
    such table, rows built from the law names, ids and sources of ``dem_contact.laws.model``."""
    try:
        table = importlib.import_module("dem_contact.laws.table")
    except ModuleNotFoundError as e:         # no table of laws in this version of the package
        if e.name != "dem_contact.laws.table":
            raise
        table = None
    package_rows = getattr(table, "law_rows", None)
    if package_rows is not None:
        return [dict(r) for r in package_rows()]
    from dem_contact.laws import model
    rows = []
    for family, ids, sources in (("normal", model.NORMAL_LAWS, model.NORMAL_LAW_SOURCES),
                                 ("tangential", model.TANGENTIAL_LAWS, model.TANGENTIAL_LAW_SOURCES)):
        for name, law_id in sorted(ids.items(), key=lambda kv: kv[1]):
            rows.append({"family": family, "id": law_id, "name": name, "source": sources.get(name, "")})
    return rows


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, dict):
        value = ", ".join(f"{k}: {v}" for k, v in value.items())
    elif isinstance(value, (list, tuple, set, frozenset)):
        value = ", ".join(str(v) for v in value)
    text = " ".join(str(value).split())
    return text.replace("|", r"\|")


def law_table(rows: list[dict]) -> str:
    """A Markdown table of rows (dicts), the columns of COLUMNS that any row has, names as code."""
    columns = [c for c in COLUMNS if any(c in r for r in rows)]
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        cells = []
        for c in columns:
            cell = _cell(r.get(c))
            cells.append(f"`{cell}`" if c == "name" and cell else cell)
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _families(rows):
    seen = []
    for r in rows:
        if r.get("family") not in seen:
            seen.append(r.get("family"))
    order = {f: i for i, f in enumerate(FAMILY_ORDER)}
    return sorted(seen, key=lambda f: (order.get(f, len(order)), str(f)))


def fill_law_tables(markdown: str, page: str) -> str:
    named = set(LAW_MARKER.findall(markdown)) - {"others"}
    if not named and "others" not in LAW_MARKER.findall(markdown):
        return markdown
    rows = law_rows()
    families = _families(rows)

    def replace(match):
        family = match.group(1)
        if family == "others":
            rest = [f for f in families if f not in named]
            parts = []
            for f in rest:
                parts += [f"## {str(f).capitalize()} laws", "", law_table([r for r in rows if r.get("family") == f]), ""]
            return "\n".join(parts)
        chosen = [r for r in rows if r.get("family") == family]
        if not chosen:
            log.warning("%s: the table of laws has no law of the family %r (families: %s)", page, family,
                        ", ".join(map(str, families)))
            return ""
        return law_table(chosen)

    return LAW_MARKER.sub(replace, markdown)


def package_modules(package: str) -> list[str]:
    """The package and every module below it, sorted; [] when the package does not exist."""
    try:
        pkg = importlib.import_module(package)
    except ModuleNotFoundError as e:
        if e.name is not None and package.startswith(e.name):
            return []
        raise
    names = [package]
    if hasattr(pkg, "__path__"):
        names += sorted(m.name for m in pkgutil.walk_packages(pkg.__path__, prefix=package + "."))
    return names


def expand_api_markers(markdown: str) -> str:
    """``<!-- api-modules PACKAGE ... -->`` replaced by ``::: module`` directives (see the module docstring)."""
    def replace(match):
        lines = []
        for package in match.group(1).split():
            for name in package_modules(package):
                lines += [f"::: {name}", ""]
        return "\n".join(lines)

    return API_MARKER.sub(replace, markdown)


def layout_rules() -> str:
    """The ALLOWED table of tests/test_layout.py as Markdown: room, may import."""
    tree = ast.parse((ROOT / "tests" / "test_layout.py").read_text())
    for node in tree.body:
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and t.id == "ALLOWED" for t in targets):
                allowed = ast.literal_eval(node.value)
                break
    else:
        raise LookupError("tests/test_layout.py has no ALLOWED table")
    lines = ["| room | may import (besides itself) |", "|---|---|"]
    for room, deps in allowed.items():
        lines.append(f"| `{room}` | {', '.join(f'`{d}`' for d in sorted(deps)) or 'nothing of the package'} |")
    return "\n".join(lines)


class _DocstringBracketsAreNotReferences(logging.Filter):
    """Drops the cross-reference plugin's warning about a target that a docstring wrote: the docstrings
    of the package are plain text, where ``float64[n, 3] [m]`` (a shape, then a unit) reads as a Markdown
    reference link. An unresolved reference of a page of this site stays a warning."""

    PATTERN = re.compile(r"from \S+\.py:\d+: .*Could not find cross-reference target '")

    def filter(self, record: logging.LogRecord) -> bool:
        return not self.PATTERN.search(record.getMessage())


def on_config(config):
    f = _DocstringBracketsAreNotReferences()
    for handler in logging.getLogger("mkdocs").handlers:
        if f not in handler.filters:
            handler.addFilter(f)
    return config


def on_page_markdown(markdown, page, config, files):
    markdown = expand_api_markers(markdown)
    markdown = fill_law_tables(markdown, page.file.src_path)
    if LAYOUT_MARKER in markdown:
        markdown = markdown.replace(LAYOUT_MARKER, layout_rules())
    return markdown
