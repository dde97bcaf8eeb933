"""Study files (TOML): what a study varies around which base case (docs/study-format.md).

A study names a base case (a shipped case or bearing name, or a case file relative to the study
file) and one or more sweeps. Each sweep varies dotted case keys, as a ``grid`` (every combination)
or ``zip`` (lists of equal length, taken together), may fix other keys (``set``) and says which
model runs at each point (``quasistatic``, ``dynamic`` or ``both``). ``[run]`` sets the run length
of the dynamic points. :func:`load_study` reads a file, :func:`parse_study` text; both raise
:class:`solver.errors.CaseError` whose problems name the study key (``vary.operating.axial_load_N``,
``sweep[2].combine``) and say what is allowed.
"""

from __future__ import annotations

import difflib
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from solver.case.io import read_case_bytes
from solver.case.schema import FIELDS
from solver.errors import CaseError, Problem

MODELS = ("quasistatic", "dynamic", "both")
COMBINES = ("grid", "zip")
#: Keys of a study file's top level, of a ``[[sweep]]`` and of ``[run]``.
TOP_KEYS = ("title", "description", "base", "model", "combine", "vary", "set", "run", "sweep")
SWEEP_KEYS = ("name", "model", "combine", "vary", "set")
RUN_KEYS = ("shaft_revolutions", "samples_per_revolution")
#: Most points a study may have (a typing error in a grid should not launch a million runs).
MAX_POINTS = 5000
#: Deepest nesting of tables and lists a study file may have: a study needs about eight levels
#: (``[[sweep]]``, ``vary``, a dotted key's parts, a list of inline tables); deeper is refused
#: before anything walks the values (which would otherwise exhaust Python's recursion limit).
MAX_DEPTH = 32
_CASE_KEYS = tuple(f.key for f in FIELDS)


@dataclass(frozen=True)
class Sweep:
    """One sweep: ``vary`` maps dotted case keys to their value lists (in file order)."""

    name: str
    model: str
    combine: str
    vary: dict
    set: dict = field(default_factory=dict)

    @property
    def size(self) -> int:
        lengths = [len(v) for v in self.vary.values()]
        if not lengths:
            return 1
        if self.combine == "zip":
            return lengths[0]
        size = 1
        for n in lengths:
            size *= n
        return size


@dataclass(frozen=True)
class StudySpec:
    """A parsed study file. ``base`` is the base case as written (name or path); ``base_path`` the
    resolved file when it is a file, else None. ``run`` holds the ``[run]`` values given."""

    title: str
    description: str
    base: str
    base_path: Path | None
    sweeps: tuple[Sweep, ...]
    run: dict
    text: str
    source: str

    @property
    def varied_keys(self) -> tuple[str, ...]:
        """Every key varied or set by a sweep, in order of first appearance."""
        keys: dict[str, None] = {}
        for sweep in self.sweeps:
            keys.update(dict.fromkeys(sweep.vary))
            keys.update(dict.fromkeys(sweep.set))
        return tuple(keys)


def _depth(data) -> int:
    """How many tables and lists deep ``data`` nests (without recursion)."""
    deepest = 0
    stack = [(data, 1)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            children = value.values()
        elif isinstance(value, list):
            children = value
        else:
            continue
        deepest = max(deepest, depth)
        if deepest > MAX_DEPTH:
            break
        stack.extend((child, depth + 1) for child in children)
    return deepest


def _flatten(table: dict, prefix: str = "") -> dict:
    """``{"operating": {"axial_load_N": [..]}}`` -> ``{"operating.axial_load_N": [..]}``.

    Inline tables that are case values (``lubricant.traction``) stay whole when their key is a
    case key; every other table is flattened (so quoted and bare dotted keys both work).
    """
    out = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and name not in _CASE_KEYS:
            out.update(_flatten(value, name + "."))
        else:
            out[name] = value
    return out


def _unknown(where: str, key: str, allowed) -> Problem:
    close = difflib.get_close_matches(key, list(allowed), n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return Problem(
        f"{where}{key}",
        f"{where}{key}: unknown study key{hint}; allowed here: {', '.join(allowed)}",
    )


def _check_case_key(where: str, key: str, problems: list[Problem]) -> bool:
    # a bearing set's keys (set.preload.force_N ...) are checked by the case of each point
    if key in _CASE_KEYS or key.startswith(("materials.", "set.")):
        return True
    close = difflib.get_close_matches(key, list(_CASE_KEYS), n=1, cutoff=0.6)
    hint = f"did you mean {close[0]!r}? " if close else ""
    problems.append(
        Problem(
            f"{where}.{key}",
            f"{where}.{key}: {key!r} is not a case key: {hint}give a dotted key of the case "
            "format such as operating.radial_load_N (docs/case-format.md lists them)",
        )
    )
    return False


def _choice(data: dict, key: str, where: str, allowed, default, problems) -> str:
    value = data.get(key, default)
    if value not in allowed:
        problems.append(
            Problem(
                f"{where}{key}",
                f"{where}{key} = {value!r}: must be one of {', '.join(map(repr, allowed))}",
            )
        )
        return default
    return value


def _sweep(data: dict, where: str, defaults: dict, problems: list[Problem], index: int) -> Sweep:
    allowed = SWEEP_KEYS if where else TOP_KEYS
    for key in data:
        if key not in allowed:
            problems.append(_unknown(where, key, allowed))
    name = data.get("name", f"sweep {index + 1}")
    if not isinstance(name, str):
        problems.append(Problem(f"{where}name", f"{where}name must be text, not {name!r}"))
        name = f"sweep {index + 1}"
    model = _choice(data, "model", where, MODELS, defaults["model"], problems)
    combine = _choice(data, "combine", where, COMBINES, defaults["combine"], problems)
    vary_raw = data.get("vary", {})
    set_raw = data.get("set", {})
    vary: dict = {}
    fixed: dict = {}
    if not isinstance(vary_raw, dict):
        problems.append(Problem(f"{where}vary", f"{where}vary must be a table of key = [values]"))
        vary_raw = {}
    if not isinstance(set_raw, dict):
        problems.append(Problem(f"{where}set", f"{where}set must be a table of key = value"))
        set_raw = {}
    for key, values in _flatten(vary_raw).items():
        if not _check_case_key(f"{where}vary", key, problems):
            continue
        if not isinstance(values, list) or not values:
            problems.append(
                Problem(
                    f"{where}vary.{key}",
                    f"{where}vary.{key} = {values!r}: give a non-empty list of values, "
                    "e.g. [0.0, 500.0, 1000.0]",
                )
            )
            continue
        vary[key] = list(values)
    for key, value in _flatten(set_raw).items():
        if not _check_case_key(f"{where}set", key, problems):
            continue
        if key in vary:
            problems.append(
                Problem(f"{where}set.{key}", f"{where}set.{key}: this key is also in vary")
            )
            continue
        fixed[key] = value
    if combine == "zip" and len({len(v) for v in vary.values()}) > 1:
        lengths = ", ".join(f"{k} has {len(v)}" for k, v in vary.items())
        problems.append(
            Problem(
                f"{where}combine",
                f"{where}combine = 'zip' takes the lists together, so they must have the same "
                f"length: {lengths}. Use combine = 'grid' for every combination",
            )
        )
    return Sweep(name, model, combine, vary, fixed)


def parse_study(text: str, source: str = "study", folder: Path | None = None) -> StudySpec:
    """A :class:`StudySpec` from study-file text; CaseError naming every wrong key.

    ``folder``: where a relative base case file is looked for (the study file's folder)."""
    too_deep = CaseError(
        Problem(
            "file",
            f"{source} nests tables, lists or dotted keys more than {MAX_DEPTH} levels deep: a "
            "study file has a few tables of key = [values] lines (docs/study-format.md)",
        )
    )
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise CaseError(Problem("file", f"{source} is not valid TOML: {error}")) from None
    except RecursionError:
        raise too_deep from None
    except (ValueError, OverflowError) as error:  # e.g. an integer with thousands of digits
        raise CaseError(
            Problem("file", f"{source} holds a value that cannot be read ({error})")
        ) from None
    if _depth(data) > MAX_DEPTH:
        raise too_deep
    problems: list[Problem] = []
    for key in data:
        if key not in TOP_KEYS:
            problems.append(_unknown("", key, TOP_KEYS))
    title = data.get("title", "")
    description = data.get("description", "")
    for key, value in (("title", title), ("description", description)):
        if not isinstance(value, str):
            problems.append(Problem(key, f"{key} must be text, not {value!r}"))
    base = data.get("base")
    base_path = None
    if not isinstance(base, str) or not base:
        problems.append(
            Problem(
                "base",
                "base: name the base case, a shipped case or bearing (racetrace cases) or a case "
                'file relative to the study file, e.g. base = "spindle-combined-load"',
            )
        )
        base = ""
    elif base.endswith(".toml") or "/" in base:
        candidate = Path(base)
        if not candidate.is_absolute() and folder is not None:
            candidate = folder / candidate
        base_path = candidate
    run = data.get("run", {})
    if not isinstance(run, dict):
        problems.append(Problem("run", "run must be a table ([run])"))
        run = {}
    for key in run:
        if key not in RUN_KEYS:
            problems.append(_unknown("run.", key, RUN_KEYS))
    defaults = {
        "model": _choice(data, "model", "", MODELS, "quasistatic", problems),
        "combine": _choice(data, "combine", "", COMBINES, "grid", problems),
    }
    sweeps_raw = data.get("sweep")
    sweeps: list[Sweep] = []
    if sweeps_raw is None:
        top = {k: data[k] for k in ("vary", "set") if k in data}
        sweeps.append(_sweep(top, "", defaults, problems, 0))
        if not sweeps[0].vary and not problems:
            problems.append(
                Problem(
                    "vary",
                    "vary: the study varies nothing: add a [vary] table such as "
                    "vary.'operating.radial_load_N' = [0.0, 500.0], or [[sweep]] tables",
                )
            )
    else:
        if "vary" in data or "set" in data:
            problems.append(
                Problem(
                    "vary",
                    "vary/set at the top level and [[sweep]] tables together: put every "
                    "variation in a [[sweep]]",
                )
            )
        if not isinstance(sweeps_raw, list) or not all(isinstance(s, dict) for s in sweeps_raw):
            problems.append(Problem("sweep", "sweep must be [[sweep]] tables"))
            sweeps_raw = []
        for i, raw in enumerate(sweeps_raw):
            sweep = _sweep(raw, f"sweep[{i + 1}].", defaults, problems, i)
            if not sweep.vary:
                problems.append(
                    Problem(
                        f"sweep[{i + 1}].vary", f"sweep[{i + 1}].vary: the sweep varies nothing"
                    )
                )
            sweeps.append(sweep)
    total = sum(s.size for s in sweeps)
    if total > MAX_POINTS:
        problems.append(
            Problem(
                "vary",
                f"the study has {total} points, more than {MAX_POINTS}: use fewer values, or "
                "combine = 'zip' for keys that change together",
            )
        )
    if problems:
        raise CaseError(problems)
    return StudySpec(
        title=title or (Path(source).stem if source else "study"),
        description=description,
        base=base,
        base_path=base_path,
        sweeps=tuple(sweeps),
        run=dict(run),
        text=text,
        source=source,
    )


def load_study(path) -> StudySpec:
    """Read and parse the study file ``path`` (a regular file up to 1 MB); CaseError."""
    path = Path(path)
    raw = read_case_bytes(path)
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise CaseError(Problem("file", f"{path} is not UTF-8 text: is it a study file?")) from None
    return parse_study(text, str(path), path.parent)


def shipped_studies() -> dict[str, object]:
    """``{name: resource}`` of the studies shipped in ``assets/studies`` (names without .toml)."""
    from solver.catalogue import _assets_root

    folder = _assets_root().joinpath("studies")
    try:
        resources = list(folder.iterdir())
    except (FileNotFoundError, NotADirectoryError):
        return {}
    return {
        r.name.removesuffix(".toml"): r
        for r in sorted(resources, key=lambda r: r.name)
        if r.name.endswith(".toml")
    }


def resolve_study(path_or_name) -> StudySpec:
    """A study from a study file path or a shipped study name; CaseError otherwise.

    An existing file wins over a shipped name of the same spelling."""
    path = Path(path_or_name)
    if path.is_file():
        return load_study(path)
    shipped = shipped_studies()
    name = str(path_or_name)
    if name in shipped:
        return parse_study(shipped[name].read_text(encoding="utf-8"), f"shipped study {name}")
    if path.suffix == ".toml" or "/" in name or path.exists():
        return load_study(path)
    close = difflib.get_close_matches(name, list(shipped), n=2, cutoff=0.5)
    hint = f"did you mean {', '.join(close)}? " if close else ""
    raise CaseError(
        Problem(
            "study",
            f"{name!r} is neither a study file nor a shipped study: {hint}shipped studies: "
            f"{', '.join(shipped) or 'none'}",
        )
    )
