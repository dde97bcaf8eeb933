"""Mutated case files and result files for the fuzz tests and ``tests/explore_fuzz.py``.

:func:`mutated_case_bytes` starts from a valid case and changes it the ways a careless user or an
attacker would: values of the wrong type, non-finite, huge, tiny or just past a bound; missing and
unknown keys (with control characters); sections replaced by values; values nested hundreds of
levels deep; other encodings, stray bytes and cut files. :func:`outcome` runs the bytes through
everything a case meets (decoding, parsing, validation, the dynamic model's rules, the TOML writer,
the quasi-static solver and its JSON summary) and says how it ended; anything but a clean
:class:`~solver.errors.CaseError`, :class:`~solver.errors.NoSolutionError` or a finite solution
propagates as the exception it is.

:func:`mutated_result_bytes` does the same to result files (a shipped quasi-static, dynamic or study
result with variables, coordinates or attributes dropped, retyped, transposed, stacked or given odd
values; a case attribute nested thousands deep; another program's NetCDF; cut or non-NetCDF bytes),
and :func:`result_outcome` gives one to ``racetrace report`` or ``export`` in this process: it ends
written or refused as invalid input (exit 2), or the exception propagates.
"""

from __future__ import annotations

import datetime
import functools
import json
import math
import random
import tomllib
from pathlib import Path

import numpy as np
import tomli_w

from solver.case.schema import FIELDS

from .cases import CONTRACT_EXAMPLE, DEEP_GROOVE_RADIAL, LUBRICANT, SPINDLE

#: The project's root folder (shipped results are read from it).
ROOT = Path(__file__).resolve().parents[2]
BASES = (SPINDLE, SPINDLE + LUBRICANT, DEEP_GROOVE_RADIAL, CONTRACT_EXAMPLE)
OUTCOMES = ("solution", "case error", "no solution")
#: Result variables that may be NaN or inf by definition (docs/results-schema.md): no shoulder
#: given; ISO 281 figures outside the tabulated contact angles, or an infinite life.
MAY_BE_NAN = {
    "truncation_margin",
    "basic_load_rating",
    "equivalent_load",
    "basic_rating_life",
    "basic_rating_life_time",
}
#: Lives that are inf when no contact is loaded or the rings do not turn, never NaN.
MAY_BE_INF = {"raceway_rating_life", "reference_rating_life", "reference_rating_life_time"}

ODD_VALUES = (
    "",
    "text",
    "\x1b[2J\x1b]0;title\x07",
    "/proc/self/environ",
    True,
    False,
    0,
    -1,
    1,
    2**63,
    -(2**63),
    10**400,
    1e308,
    -1e308,
    5e-324,
    1e-300,
    math.nan,
    math.inf,
    -math.inf,
    [],
    [1.0, 2.0],
    {"a": 1},
    {"x": {"y": {"z": 1}}},
    datetime.date(2026, 1, 1),
    datetime.time(12, 0),
)
NUMERIC = [f for f in FIELDS if f.type in ("float", "int")]


def _bound_values(field, rng: random.Random) -> list:
    """Values on, just inside and just past the bounds of a numeric key (and far past them)."""
    values = []
    for bound in (field.minimum, field.maximum):
        if bound is None:
            continue
        step = max(abs(bound), 1.0) * 1e-9
        values += [bound, bound - step, bound + step, bound * 10 + 1, -bound]
    values += [rng.uniform(-1e6, 1e6), 0.0]
    if field.type == "int":
        values = [int(v) if math.isfinite(v) and abs(v) < 1e18 else v for v in values]
    return values


def _within(field, rng: random.Random):
    """A value inside the bounds of a numeric key: log-uniform over a positive range, uniform
    otherwise (bounds that are absent are taken as 1e6 away)."""
    low = field.minimum if field.minimum is not None else -1e6
    high = field.maximum if field.maximum is not None else 1e6
    if low >= 0 and high > 0:
        low_log = math.log10(max(low, high * 1e-9))
        value = 10 ** rng.uniform(low_log, math.log10(high))
    else:
        value = rng.uniform(low, high)
    value = min(max(value, low), high)
    return int(round(value)) if field.type == "int" else value


def _set(data: dict, key: str, value) -> None:
    *path, last = key.split(".")
    table = data
    for part in path:
        if not isinstance(table.get(part), dict):
            table[part] = {}
        table = table[part]
    table[last] = value


def _delete(data: dict, key: str) -> None:
    *path, last = key.split(".")
    table = data
    for part in path:
        table = table.get(part)
        if not isinstance(table, dict):
            return
    table.pop(last, None)


def _mutate(data: dict, rng: random.Random) -> str:
    """Change ``data`` in place, or return TOML text to append (deep nesting)."""
    kind = rng.choice(
        ["within"] * 4 + ["bound"] * 3 + ["odd", "odd", "delete", "unknown", "section", "deep"]
    )
    field = rng.choice(FIELDS)
    if kind == "within":  # valid values in odd combinations: these reach the solvers
        for numeric in rng.sample(NUMERIC, rng.randint(1, 6)):
            _set(data, numeric.key, _within(numeric, rng))
    elif kind == "bound":
        numeric = rng.choice(NUMERIC)
        _set(data, numeric.key, rng.choice(_bound_values(numeric, rng)))
    elif kind == "odd":
        _set(data, field.key, rng.choice(ODD_VALUES))
    elif kind == "delete":
        _delete(data, field.key)
    elif kind == "unknown":
        name = rng.choice(["x", "bal_count", "ball_count_", "\x1b[31mred", "a" * 300, "ünï"])
        section = rng.choice(["", "bearing", "operating", "nowhere", "materials"])
        _set(data, f"{section}.{name}" if section else name, rng.choice(ODD_VALUES))
    elif kind == "section":
        section = rng.choice(["bearing", "operating", "simulation", "lubricant", "cage"])
        data[section] = rng.choice(ODD_VALUES)
    else:
        depth = rng.choice([10, 200, 400, 1000, 5000])
        table = rng.choice(["deep", "bearing_x"])
        return f"\n[{table}]\nv = " + "[" * depth + "1" + "]" * depth + "\n"
    return ""


def _encode(text: str, rng: random.Random) -> bytes:
    kind = rng.choice(["utf8"] * 6 + ["bom", "utf16", "latin1", "nul", "cut", "flip", "control"])
    data = text.encode("utf-8")
    if kind == "bom":
        return b"\xef\xbb\xbf" + data
    if kind == "utf16":
        return text.encode("utf-16")
    if kind == "latin1":
        return (text + "\n# r\xe9sum\xe9 \xb0C\n").encode("latin-1", "replace")
    if kind == "nul":
        at = rng.randrange(len(data) + 1)
        return data[:at] + b"\x00" + data[at:]
    if kind == "cut":
        return data[: rng.randrange(len(data) + 1)]
    if kind == "flip":
        at = rng.randrange(max(len(data), 1))
        return data[:at] + bytes([rng.randrange(256)]) + data[at + 1 :]
    at = rng.randrange(len(data) + 1)
    return data[:at] + rng.choice([b"\x1b[2J", b"\r", b"\x7f", b"\x0c"]) + data[at:]


#: Keys whose valid values stress the solvers most: loads, speeds, misalignment, lubricant.
SOLVER_KEYS = [f for f in NUMERIC if f.section in ("operating", "lubricant")]


def _valid_extremes(data: dict, rng: random.Random) -> None:
    """Valid operating values in odd combinations, often on their bounds: these reach the
    quasi-static solver."""
    for field in rng.sample(SOLVER_KEYS, rng.randint(1, 6)):
        bounds = [b for b in (field.minimum, field.maximum) if b is not None]
        if bounds and rng.random() < 0.4:
            value = rng.choice(bounds)
            if field.type == "float":
                value = float(value)
        else:
            value = _within(field, rng)
        _set(data, field.key, value)
    if rng.random() < 0.3:  # and sometimes a bearing value too
        _set(data, (f := rng.choice(NUMERIC)).key, _within(f, rng))


def mutated_case_bytes(rng: random.Random) -> bytes:
    """A case file's bytes: a valid case with valid values in odd combinations (two in five), or
    one to four mutations of any kind in some encoding."""
    data = tomllib.loads(rng.choice(BASES))
    if rng.random() < 0.4:
        _valid_extremes(data, rng)
        return tomli_w.dumps(data).encode()
    extra = ""
    for _ in range(rng.randint(1, 4)):
        extra += _mutate(data, rng)
    try:
        text = tomli_w.dumps(data) + extra
    except (TypeError, ValueError):  # a value TOML cannot hold: write it as text instead
        text = tomli_w.dumps({"title": repr(data)[:200]}) + extra
    return _encode(text, rng)


# ---- result files given to `racetrace report` and `export` --------------------------------------
#: Saved results the result-file mutations start from: a quasi-static and a dynamic run (cut to a
#: few samples) and a study Dataset, all shipped with racetrace.
RESULT_BASES = (
    "assets/lessons/results/02-speed--rest.nc",
    "assets/lessons/results/01-axial-load--axial.nc",
    "assets/studies/results/218-radial-load.study.nc",
)
#: Samples of the dynamic base kept: enough for every view, few enough for a quick report.
_BASE_SAMPLES = 12
RESULT_SURFACES = ("report", "export")
RESULT_OUTCOMES = ("written", "invalid input")
#: Attribute values a hostile or careless file may hold.
ODD_ATTRIBUTES = (
    "",
    "<img src=x onerror=alert(1)>",
    "\x1b[2J\x1b]0;title\x07",
    "\u202e" + "x" * 50,
    "x" * 100_000,
    0,
    -1,
    2**62,
    1.5,
    math.nan,
    math.inf,
    [1, 2, 3],
    [1.0, math.nan],
)
#: Case texts for the ``case`` attribute: nested deep, not TOML, numbers too long to read.
ODD_CASE_TEXTS = (
    "v = " + "[" * 5000 + "1" + "]" * 5000,
    "[bearing]\nprovenance = " + "{a = " * 3000 + "1" + "}" * 3000,
    "a = " + "9" * 10_000,
    "title = 'unterminated",
    "[[[",
    "title = 5\n[bearing]\nprovenance = []\n",
    "\x00\x01binary",
)


@functools.cache
def _read_base(name: str):
    from solver.results.io import load_dataset

    ds = load_dataset(ROOT / name)
    return ds.isel(time=slice(-_BASE_SAMPLES, None)) if "time" in ds.dims else ds


def _base_dataset(rng: random.Random):
    """A fresh copy of one of :data:`RESULT_BASES` (each is read once per process)."""
    return _read_base(rng.choice(RESULT_BASES)).copy(deep=True)


def _mutate_result(ds, rng: random.Random):
    """One change to a result Dataset, the ways a foreign tool, an old version, a careless edit or
    an attacker would: variables, coordinates and attributes dropped, renamed, retyped,
    transposed, stacked or given odd values and labels. Returns the changed Dataset."""
    import numpy as np
    import xarray as xr

    names = list(ds.data_vars)
    coords = [c for c in ds.coords if c not in ds.dims]
    kind = rng.choice(
        [
            "drop variable",
            "drop coordinate",
            "drop attribute",
            "odd attribute",
            "odd attribute",
            "case text",
            "variable attribute",
            "retype",
            "transpose",
            "stack",
            "labels",
            "values",
            "values",
            "resize",
            "rename dimension",
        ]
    )
    if kind == "drop variable" and names:
        return ds.drop_vars(rng.sample(names, rng.randint(1, min(3, len(names)))))
    if kind == "drop coordinate" and coords:
        return ds.drop_vars(rng.choice(coords))
    if kind == "drop attribute" and ds.attrs:
        ds = ds.copy()
        del ds.attrs[rng.choice(list(ds.attrs))]
        return ds
    if kind == "odd attribute":
        ds = ds.copy()
        name = rng.choice([*ds.attrs, "model", "case", "created", "racetrace_kind", "title"])
        ds.attrs[name] = rng.choice(ODD_ATTRIBUTES)
        return ds
    if kind == "case text":
        ds = ds.copy()
        ds.attrs["case"] = rng.choice(ODD_CASE_TEXTS)
        return ds
    if kind == "variable attribute" and names:
        ds = ds.copy()
        name = rng.choice([*names, *ds.coords])
        attribute, value = rng.choice(
            [
                ("units", rng.choice(ODD_ATTRIBUTES)),
                ("units", "seconds since 2000-01-01"),
                ("units", "days since garbage"),
                ("calendar", "no_such_calendar"),
                ("scale_factor", "x"),
                ("add_offset", [1.0, 2.0]),
                ("long_name", rng.choice(ODD_ATTRIBUTES)),
            ]
        )
        ds[name].attrs[attribute] = value
        return ds
    if kind == "retype" and names:
        name = rng.choice(names + coords)
        values = ds[name].values
        new = rng.choice(
            [
                lambda: values.astype(str),
                lambda: np.zeros(values.shape, dtype=bool),
                lambda: np.full(values.shape, 7, dtype=np.int8),
            ]
        )()
        return (
            ds.assign({name: (ds[name].dims, new)})
            if name in names
            else ds.assign_coords({name: (ds[name].dims, new)})
        )
    if kind == "transpose" and names:
        name = rng.choice(names)
        return ds.assign({name: ds[name].transpose(*reversed(ds[name].dims))})
    if kind == "stack":
        return xr.concat(
            [ds, ds], dim=rng.choice(["case", "inner_ring_speed", "time"]), data_vars="all"
        )
    if kind == "labels":
        dim = rng.choice([d for d in ("race", "axis", "body", "frame", "model") if d in ds.dims])
        labels = list(ds[dim].values)
        labels = rng.choice([labels[::-1], [f"x{i}" for i in range(len(labels))]])
        return ds.assign_coords({dim: labels})
    if kind == "values" and names:
        ds = ds.copy()
        name = rng.choice(names + [c for c in coords if ds[c].dtype.kind == "f"])
        values = np.array(ds[name].values, copy=True)
        if values.dtype.kind == "f" and values.size:
            values = values.astype(np.float64)  # float32 variables hold the odd values too
            flat = values.reshape(-1)
            for _ in range(rng.randint(1, 5)):
                flat[rng.randrange(flat.size)] = rng.choice(
                    [math.nan, math.inf, -math.inf, 1e308, -1e308, 0.0, -1.0, 5e-324]
                )
            if rng.random() < 0.3:
                flat[:] = rng.choice([math.nan, 0.0, -1.0, 1e300])
            values = flat.reshape(values.shape)
        elif values.dtype.kind in "iu":
            values = values * 0 + rng.choice([0, -1, 1000, 2**31 - 1])
        if name in names:
            return ds.assign({name: (ds[name].dims, values, ds[name].attrs)})
        return ds.assign_coords({name: (ds[name].dims, values, ds[name].attrs)})
    if kind == "resize":
        dim = rng.choice([d for d in ("ball", "time", "point", "race") if d in ds.dims])
        return ds.isel({dim: slice(0, rng.choice([0, 1, 2]))})
    if kind == "rename dimension":
        dim = rng.choice(list(ds.dims))
        return ds.rename_dims({dim: rng.choice(["x", f"{dim}_", "sample"])})
    return ds


def _foreign_dataset(rng: random.Random):
    """Another program's NetCDF: random names, sometimes one of a result's names."""
    import numpy as np
    import xarray as xr

    data = {}
    for _ in range(rng.randint(0, 4)):
        name = rng.choice(["x", "temperature", "contact_load", "ball_azimuth", "time", "ü"])
        dims = tuple(rng.sample(["a", "b", "ball", "race", "time"], rng.randint(0, 2)))
        data[name] = (dims, np.random.default_rng(rng.randrange(2**32)).random((3,) * len(dims)))
    attrs = {}
    if rng.random() < 0.5:
        attrs["model"] = rng.choice(["dynamic", "quasistatic", "other"])
    if rng.random() < 0.3:
        attrs["racetrace_kind"] = rng.choice(["study", "run"])
    try:
        return xr.Dataset(data, attrs=attrs)
    except ValueError:  # conflicting sizes of one dimension
        return xr.Dataset(attrs=attrs)


def _netcdf_bytes(ds) -> bytes:
    import os
    import tempfile

    fd, path = tempfile.mkstemp(suffix=".nc")
    os.close(fd)
    try:
        ds.to_netcdf(path, engine="netcdf4")
        with open(path, "rb") as handle:
            return handle.read()
    finally:
        os.remove(path)


def mutated_result_bytes(rng: random.Random) -> bytes:
    """A result file's bytes: a shipped result (quasi-static, dynamic or a study) with one to three
    changes (:func:`_mutate_result`), another program's NetCDF, or bytes that are not NetCDF at all
    or cut short. Changes that xarray itself refuses to write are skipped."""
    choice = rng.random()
    if choice < 0.1:
        return _netcdf_bytes(_foreign_dataset(rng))
    ds = _base_dataset(rng)
    for _ in range(rng.randint(1, 3)):
        try:
            ds = _mutate_result(ds, rng)
        except (ValueError, TypeError, KeyError, IndexError, OverflowError):
            continue  # a change xarray or numpy cannot make to this Dataset
    try:
        data = _netcdf_bytes(ds)
    except (ValueError, TypeError, RuntimeError, OverflowError, AttributeError):
        data = _netcdf_bytes(_base_dataset(rng))  # a change NetCDF cannot hold
    if choice < 0.25:
        kind = rng.choice(["cut", "flip", "empty", "text", "header"])
        if kind == "cut":
            return data[: rng.randrange(len(data))]
        if kind == "flip":
            at = rng.randrange(len(data))
            return data[:at] + bytes([rng.randrange(256)]) + data[at + 1 :]
        if kind == "empty":
            return b""
        if kind == "text":
            return b"title = 'a case file, not a result'\n"
        return data[:8]
    return data


def result_outcome(content: bytes, surface: str, folder) -> str:
    """How ``racetrace SURFACE`` (``report`` or ``export``) ends on a result file of ``content``
    (written in ``folder``): one of :data:`RESULT_OUTCOMES`. The command runs in this process, so
    any exception propagates; an exit code other than 0 or 2, or a message that is empty, fails an
    assertion."""
    import contextlib
    import io
    from pathlib import Path

    from racetrace.cli import main

    folder = Path(folder)
    source = folder / "fuzz.nc"
    source.write_bytes(content)
    target = folder / ("review.html" if surface == "report" else "table.csv")
    target.unlink(missing_ok=True)
    args = (
        ["report", str(source), "--output", str(target)]
        if surface == "report"
        else ["export", str(source), "--csv", str(target)]
    )
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        code = main(args)
    text = stderr.getvalue()
    assert "Traceback" not in text, text[-2000:]
    if code == 0:
        assert target.is_file() and target.stat().st_size > 0, "exit 0 without the output"
        return "written"
    assert code == 2, f"exit {code}: {text[-500:]}"
    assert "invalid input" in text and len(text.strip()) > 30, text
    assert not target.exists(), "a failed command left its output"
    return "invalid input"


def outcome(content: bytes) -> str:
    """How a case file's bytes end: one of :data:`OUTCOMES`. Any other exception propagates; a
    solution that is not finite, or whose JSON summary is not valid JSON, fails an assertion."""
    import solver
    from racetrace.commands.quasistatic import summary
    from solver.case.io import decode_case_bytes

    try:
        case = solver.parse_case(decode_case_bytes(content, "fuzz.toml"), "fuzz.toml")
        case.warnings()
        solver.dynamic_problems(case)
        solver.parse_case(case.to_toml())  # what the writer writes reads back
        ds = solver.solve_quasistatic(case)
    except solver.CaseError as error:
        assert str(error), "a CaseError without a message"
        return "case error"
    except solver.NoSolutionError as error:
        assert str(error), "a NoSolutionError without a message"
        return "no solution"
    for name, variable in ds.data_vars.items():
        if variable.dtype.kind != "f" or name in MAY_BE_NAN:
            continue
        values = variable.values
        if name in MAY_BE_INF:
            assert not np.isnan(values).any() and (values > 0).all(), f"{name} = {values}"
        else:
            assert np.isfinite(values).all(), f"{name} is not finite in a solution"
    json.dumps(summary(ds), allow_nan=False)  # what --json prints
    return "solution"


# ---- study files and study folders (tests/unit/study/test_fuzz.py) -----------------------------
#: Study files the study mutations start from: small, so that a mutation that stays valid has few
#: points to validate.
STUDY_BASES = (
    'title = "radial"\nbase = "spindle-axial-preload"\nmodel = "both"\n'
    "[run]\nshaft_revolutions = 2.0\nsamples_per_revolution = 40\n"
    '[vary]\n"operating.radial_load_N" = [0.0, 300.0, 600.0]\n',
    'base = "218-heavy-combined"\n[[sweep]]\nname = "tilt"\ncombine = "zip"\n'
    'vary."operating.misalignment_deg" = [0.05, 0.1]\nvary."operating.radial_load_N" = [0.0, 1.0]\n'
    'set."operating.misalignment_frame" = "ring"\n'
    '[[sweep]]\nmodel = "dynamic"\nvary.operating.inner_ring_speed_rpm = [5000.0, 10000.0]\n',
)
STUDY_KEYS = ("title", "description", "base", "model", "combine", "vary", "set", "run", "sweep")
ODD_BASES = (
    "/proc/self/environ",
    "/dev/zero",
    "../../../../etc/passwd.toml",
    "nowhere.toml",
    "spindle",
    "\x1b[2J",
    "a" * 5000,
)


def _deep_study_text(rng: random.Random) -> str:
    """TOML nested thousands deep in one of the ways a study file can nest."""
    depth = rng.choice([40, 400, 3000])
    kind = rng.choice(["list", "dotted", "inline", "sweep"])
    if kind == "list":
        return '\n[vary]\n"operating.radial_load_N" = ' + "[" * depth + "1.0" + "]" * depth + "\n"
    if kind == "dotted":
        return "\nvary." + ".".join(["a"] * depth) + " = [1.0]\n"
    if kind == "inline":
        return "\n[set]\nx = " + "{a = " * depth + "1" + "}" * depth + "\n"
    return "\n[[sweep]]\nvary = " + "{b = [" * depth + "1" + "]}" * depth + "\n"


def _mutate_study(data: dict, rng: random.Random) -> str:
    """Change the study ``data`` in place, or return TOML text to append."""
    kind = rng.choice(
        ["odd", "odd", "delete", "vary", "unknown", "base", "deep", "sweeps", "valid", "valid"]
    )
    sweeps = data.get("sweep", [])
    tables = (
        [data] + [s for s in sweeps if isinstance(s, dict)] if isinstance(sweeps, list) else [data]
    )
    table = rng.choice(tables)
    if kind == "odd":
        table[rng.choice(STUDY_KEYS)] = rng.choice(ODD_VALUES)
    elif kind == "delete" and table:
        table.pop(rng.choice(list(table)))
    elif kind == "vary":
        vary = table.setdefault("vary", {})
        if not isinstance(vary, dict):
            table["vary"] = vary = {}
        key = rng.choice([f.key for f in FIELDS] + ["nowhere.x", "operating", ""])
        vary[key] = rng.choice(
            [[rng.choice(ODD_VALUES)], [], rng.choice(ODD_VALUES), [1.0] * rng.randint(2, 4)]
        )
    elif kind == "unknown":
        name = rng.choice(["x", "swep", "\x1b[31mred", "a" * 300, "ünï", "run.x"])
        table[name] = rng.choice(ODD_VALUES)
    elif kind == "base":
        data["base"] = rng.choice(ODD_BASES)
    elif kind == "valid":  # a change that keeps the study valid
        data["description"] = rng.choice(["", "ünïcode", "a" * 2000, "line\nbreak"])
    elif kind == "deep":
        return _deep_study_text(rng)
    else:
        data["sweep"] = rng.choice([[], [{}], ["x"], {"a": 1}, [{"vary": {}}]])
    return ""


def mutated_study_bytes(rng: random.Random) -> bytes:
    """A study file's bytes: one of :data:`STUDY_BASES` with one to three mutations (wrong types,
    missing and unknown keys, odd base cases, nesting thousands deep) in some encoding, or cut."""
    data = tomllib.loads(rng.choice(STUDY_BASES))
    extra = ""
    for _ in range(rng.randint(1, 3)):
        extra += _mutate_study(data, rng)
    try:
        text = tomli_w.dumps(data) + extra
    except (TypeError, ValueError):  # a value TOML cannot hold: the text as it was instead
        text = rng.choice(STUDY_BASES) + extra
    return _encode(text, rng)


def _json_odd(rng: random.Random):
    """An odd value that JSON can hold (dates as text; NaN and infinities as Python writes them)."""
    value = rng.choice(ODD_VALUES)
    if isinstance(value, datetime.date | datetime.time):
        return value.isoformat()
    return value


def _paths(value, prefix=()) -> list:
    """The paths (keys and indices) to the values inside nested dicts and lists, down to eight
    levels (and the first three items of each list)."""
    out = [prefix]
    if len(prefix) >= 8:
        return out
    if isinstance(value, dict):
        for key, child in value.items():
            out += _paths(child, (*prefix, key))
    elif isinstance(value, list):
        for i, child in enumerate(value[:3]):
            out += _paths(child, (*prefix, i))
    return out


def mutated_json_bytes(data, rng: random.Random) -> bytes:
    """The JSON of ``data`` (a study folder's manifest or run record) with one to three values
    replaced, removed or nested thousands deep, or the whole replaced by a foreign value; in some
    encoding, or cut."""
    data = json.loads(json.dumps(data))
    for _ in range(rng.randint(1, 3)):
        path = rng.choice(_paths(data))
        kind = rng.choice(["odd", "odd", "delete", "deep", "whole"])
        if not path or kind == "whole":
            data = rng.choice([[], [data], "study", 3, None, {"points": [[]]}, _json_odd(rng)])
            continue
        parent = data
        try:
            for part in path[:-1]:
                parent = parent[part]
            if kind == "delete" and isinstance(parent, dict):
                parent.pop(path[-1], None)
            elif kind == "deep":
                depth = rng.choice([50, 900, 5000])
                parent[path[-1]] = json.loads("[" * min(depth, 900) + "]" * min(depth, 900))
            else:
                parent[path[-1]] = _json_odd(rng)
        except (TypeError, KeyError, IndexError):  # an earlier mutation changed the structure
            continue
    try:
        text = json.dumps(data)
    except (ValueError, RecursionError):
        text = "[" * 5000 + "]" * 5000
    if rng.random() < 0.2:
        text = "[" * 100_000 + "]" * 100_000  # deeper than json.loads can go
    return _encode(text, rng)
