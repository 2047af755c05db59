"""MkDocs hooks of the documentation site (``hooks:`` in mkdocs.yml).

- ``<!-- law-table FAMILY -->`` in a page becomes the Markdown table of the laws of that family (``normal``,
  ``tangential``, ...), from ``dem_contact.laws.table.law_rows()``; ``<!-- law-table others -->`` becomes a
  section with the tables of the families that no marker of the page names (nothing when there are none).
- ``<!-- api-modules PACKAGE ... -->`` becomes a ``::: module`` directive (mkdocstrings) for each named package
  that exists and for every module in it (``PACKAGE.*``: the modules in it only), so a new law file or wall
  kind appears in the API reference without an edit of the page (``api_directives`` is what
  ``tests/test_docs.py`` reads too).
- ``<!-- layout-rules -->`` becomes the table of what each room of the package may import, read from
  ``ALLOWED`` in ``tests/test_layout.py``.
- ``<!-- value FILE KEY [COLUMN=VALUE ...] [fmt=SPEC] -->`` becomes a number of a stored result: FILE (a path
  from the repository root) is a JSON file (KEY: a dotted path, list indices as numbers, a key of the file
  that holds dots taken whole; with filters, of the one record of a top-level list that they select) or a
  CSV file (KEY: a
  column, of the one row that the COLUMN=VALUE filters select), formatted with SPEC (default ``.2g``) after
  multiplying by ``scale=`` (default 1: ``scale=1e3`` writes seconds as ms); a KEY or VALUE with spaces is
  written in double quotes (``path="circle 0.3"``). A file,
  key or row that is not there fails the build (``ResultMissing``): every figure that a page states this way
  comes from a result that a named command writes (the page names it next to the marker).
- ``<!-- figure PATH caption text -->`` becomes the figure PATH (a PNG under the repository, where the command
  that makes it writes it) with its caption; the PNG is copied into the site at build time (``figures/...``),
  not into docs/. A missing PNG fails the build.
- A docstring's bracketed unit after a shape or an index (``float64[n, 3] [m]``, ``vt[i] [m/s]``) reads as a
  Markdown reference link; the cross-reference plugin's warning about a target that a docstring wrote is
  dropped (the docstrings are plain text and link nothing). An unresolved cross-reference of a page stays a
  warning (an error under ``--strict``).
"""
from __future__ import annotations

import ast
import csv
import importlib
import json
import logging
import pathlib
import pkgutil
import re
import shlex

ROOT = pathlib.Path(__file__).resolve().parents[1]
LAW_MARKER = re.compile(r"<!--\s*law-table\s+([\w-]+)\s*-->")
LAYOUT_MARKER = "<!-- layout-rules -->"
VALUE_MARKER = re.compile(r'<!--\s*value\s+(\S+)\s+("[^"]*"|\S+)((?:\s+[\w.]+=(?:"[^"]*"|\S+))*)\s*-->')
FIGURE_MARKER = re.compile(r"<!--\s*figure\s+(\S+\.png)\s+(.*?)\s*-->", re.S)
#: where the figures are copied to in the site
FIGURE_DIR = "figures"
API_MARKER = re.compile(r"<!--\s*api-modules\s+([\w.* ]+?)\s*-->")
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
            below = package.endswith(".*")
            for name in package_modules(package[:-2] if below else package)[1 if below else 0:]:
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


class ResultMissing(LookupError):
    """A figure or number that a page states is not in the stored result it names."""


def _filters(text: str) -> tuple[dict, str, float]:
    filters, fmt, scale = {}, ".2g", 1.0
    for item in shlex.split(text):
        k, v = item.split("=", 1)
        if k == "fmt":
            fmt = v
        elif k == "scale":
            scale = float(v)
        else:
            filters[k] = v
    return filters, fmt, scale


def _same(cell: str, want: str) -> bool:
    if cell == want:
        return True
    try:
        return float(cell) == float(want)
    except ValueError:
        return False


def stored_value(path: str, key: str, filters: dict | None = None):
    """The value of KEY in the stored result PATH (JSON: dotted path; CSV: the column of the one row that the
    filters select; a filter's value matches the cell as text or as a number)."""
    filters = filters or {}
    file = ROOT / path
    if not file.is_file():
        raise ResultMissing(f"{path}: no such stored result")
    if file.suffix == ".json":
        value = json.loads(file.read_text())
        if filters:                          # a list of records: the one that the filters select
            rows = [r for r in value if isinstance(r, dict)
                    and all(k in r and _same(str(r[k]), v) for k, v in filters.items())] \
                if isinstance(value, list) else []
            if len(rows) != 1:
                raise ResultMissing(f"{path}: {len(rows)} records match {filters} (one wanted)")
            value = rows[0]
        parts = key.split(".")
        while parts:                         # a dict's key may hold dots: the shortest key present is taken
            for n in range(1, len(parts) + 1):
                part = ".".join(parts[:n])
                try:
                    value = value[int(part)] if isinstance(value, list) else value[part]
                except (KeyError, IndexError, ValueError, TypeError):
                    continue
                parts = parts[n:]
                break
            else:
                raise ResultMissing(f"{path}: no {key!r}")
        return value
    if file.suffix == ".csv":
        with open(file, newline="") as f:
            rows = [r for r in csv.DictReader(f) if all(_same(r.get(k, ""), v) for k, v in filters.items())]
        if len(rows) != 1 or key not in rows[0]:
            raise ResultMissing(f"{path}: {len(rows)} rows match {filters} (one wanted) with a column {key!r}")
        return float(rows[0][key])
    raise ResultMissing(f"{path}: only .json and .csv results are read")


def fill_values(markdown: str) -> str:
    def replace(match):
        filters, fmt, scale = _filters(match.group(3))
        value = stored_value(match.group(1), match.group(2).strip('"'), filters)
        return format(value * scale, fmt) if isinstance(value, (int, float)) else str(value)
    return VALUE_MARKER.sub(replace, markdown)


def figure_paths(markdown: str) -> list[str]:
    """The PNGs that the figure markers of a page name (paths from the repository root)."""
    return [m.group(1) for m in FIGURE_MARKER.finditer(markdown)]


def _site_name(path: str) -> str:
    return FIGURE_DIR + "/" + path.replace("/", "_")


def fill_figures(markdown: str, page_src: str) -> str:
    depth = page_src.count("/")

    def replace(match):
        path, caption = match.group(1), " ".join(match.group(2).split())
        if not (ROOT / path).is_file():
            raise ResultMissing(f"{page_src}: figure {path} is not there (its command makes it)")
        src = "../" * depth + _site_name(path)
        return (f'<figure markdown="span">\n  ![{caption}]({src})\n  <figcaption markdown="span">{caption}'
                f"</figcaption>\n</figure>")
    return FIGURE_MARKER.sub(replace, markdown)


def on_files(files, config):
    """Every PNG that a figure marker of a page names, copied into the site under figures/."""
    from mkdocs.structure.files import File
    seen = set()
    for f in list(files.documentation_pages()):
        for path in figure_paths(pathlib.Path(f.abs_src_path).read_text()):
            if path in seen:
                continue
            seen.add(path)
            if not (ROOT / path).is_file():
                raise ResultMissing(f"{f.src_uri}: figure {path} is not there (its command makes it)")
            files.append(File.generated(config, _site_name(path), abs_src_path=str(ROOT / path)))
    return files


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
    markdown = fill_values(markdown)
    markdown = fill_figures(markdown, page.file.src_uri)
    if LAYOUT_MARKER in markdown:
        markdown = markdown.replace(LAYOUT_MARKER, layout_rules())
    return markdown
