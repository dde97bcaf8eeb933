"""Is a Dataset read from disk a racetrace result, with what its readers need?

A file given to ``racetrace report`` or ``export``, or opened by the app, may be anything: another
program's NetCDF, a result of an older version, a cut file, or one edited by hand or by an
attacker. :func:`result_problems` says, in words, what a Dataset lacks to be read as a racetrace
result (results-schema.md) or a study Dataset (``attrs["racetrace_kind"] == "study"``);
:func:`check_result` raises :class:`solver.errors.CaseError` naming the file and each problem.

Only names, dimensions, data types, attributes and the small describing coordinates are read, so a
lazily opened file is checked without reading its data. The check covers what the readers (the
views, the summary metrics, the report, the CSV export) take for granted: the variables and
coordinates they read, in the registry's dimensions and of numbers where numbers are read; each
labelled dimension with its labels; the attributes they read as text being text; a case text that
reads as TOML; every dimension one of a result's own, within the sizes a run can have.
"""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from solver.history import CHANNEL_NAMES

from .variables import COORDINATES, DIMENSION_VALUES, VARIABLES

#: Data variables the readers cannot do without (the views, the summary metrics, the report's
#: tables and charts); the others a model writes are optional to them, and checked when present.
REQUIRED_VARIABLES = (
    "contact_load",
    "contact_angle",
    "ellipse_semi_major",
    "ellipse_semi_minor",
    "max_pressure",
    "raceway_azimuth",
    "ball_azimuth",
    "ball_center",
    "cage_speed",
)
#: What the 3-D view needs besides, per model: a quasi-static result's balls turn at their
#: angular velocity (a dynamic one carries its orientations, or the view estimates them).
REQUIRED_BY_MODEL = {"quasistatic": ("ball_angular_velocity",), "dynamic": ()}
#: Variables that place the bodies (the 3-D view draws them, the report's scene too): a model
#: writes them finite, and a view cannot draw a ball at NaN.
FINITE_VARIABLES = (
    "ball_center",
    "ball_orientation",
    "ball_angular_velocity",
    "ball_azimuth",
    "orbital_speed",
    "cage_speed",
    "inner_ring_offset",
    "inner_ring_tilt",
    "cage_center",
    "contact_angle",
    "raceway_azimuth",
    "raceway_contact_point",
    "ellipse_semi_major",
    "ellipse_semi_minor",
)
#: Registered variables and coordinates that hold text rather than numbers.
TEXT_VALUES = ("race_control", "material", "misalignment_frame")
#: Attributes the readers use as text, when present (``model`` and ``case`` must be present).
TEXT_ATTRIBUTES = (
    "model",
    "case",
    "software",
    "created",
    "title",
    "bearing_provenance",
    "description",
    "stop_reason",
    "analysed_window",
    "kinematics",
    "kinematics_note",
    "race_control_note",
    "misalignment_note",
)
#: Attributes of a study Dataset used as text, when present.
STUDY_TEXT_ATTRIBUTES = ("title", "description", "base_case", "software_version", "varied_keys")
#: Dimensions a result has besides the labelled ones: balls and samples.
_OPEN_DIMENSIONS = ("ball", "time")
#: The ring angles of a quasi-static solution over one revolution (solver.quasistatic_answer): a
#: leading dimension of its per-element variables and of the coordinates that turn with the ring.
_REVOLUTION_DIM = "ring_angle"
#: Most ring angles a solution over one revolution may have (one per degree).
_MAX_RING_ANGLES = 360
_MAX_PROBLEMS_SHOWN = 6
#: Errors xarray and netCDF4 raise when a value of a lazily opened file is decoded (a scale factor
#: that is text, a fill value of the wrong type, a time unit that is not one).
_DECODE_ERRORS = (
    TypeError,
    ValueError,
    OverflowError,
    KeyError,
    IndexError,
    AttributeError,
    RuntimeError,
    OSError,
)
_MODELS = ("quasistatic", "dynamic")


def _schema_maximum(key: str) -> int:
    from solver.case.schema import field

    return int(field(key).maximum)


def _max_sizes() -> dict[str, int]:
    """Most balls a bearing can have (the case schema's bound) and most samples a run can keep
    (shaft revolutions times samples per revolution at their bounds, and the start)."""
    balls = _schema_maximum("bearing.ball_count")
    samples = _schema_maximum("simulation.shaft_revolutions") * _schema_maximum(
        "simulation.samples_per_revolution"
    )
    return {"ball": balls, "time": samples + 1}


def _is_text(value) -> bool:
    return isinstance(value, str)


def _dims_text(dims) -> str:
    return "(" + ", ".join(str(d) for d in dims) + ")"


def _numeric(values: xr.DataArray) -> bool:
    return values.dtype.kind in "fiub"


def result_problems(ds: xr.Dataset, values: bool = False) -> list[str]:
    """What ``ds`` lacks to be read as a racetrace result or study Dataset, in words ([] when
    nothing). Reads names, dimensions, data types, attributes and the describing coordinates;
    with ``values``, also the data of :data:`FINITE_VARIABLES` (a Dataset in memory)."""
    if not isinstance(ds, xr.Dataset):
        return [f"a {type(ds).__name__}, not a Dataset"]
    kind = ds.attrs.get("racetrace_kind")
    if kind is not None:
        if kind == "study":
            return _study_problems(ds)
        return [f"its 'racetrace_kind' attribute is {_short(kind)}, not \"study\""]
    if "bearing" in ds.dims and ds.attrs.get("bearing_set"):
        return _set_problems(ds, values)
    problems = _attribute_problems(ds)
    if ds.attrs.get("model") not in _MODELS:
        if not any(name in ds.variables for name in REQUIRED_VARIABLES):
            # nothing of a result: say so once rather than list every missing name
            return [
                "it has none of a racetrace result's variables (contact_load, ball_azimuth, ...) "
                "and no 'model' attribute: it is not a racetrace result file"
            ]
        return problems
    model = ds.attrs["model"]
    problems += _dimension_problems(ds, model)
    if problems:
        return problems  # the variables' dimensions cannot be judged against odd dimensions
    problems += _variable_problems(ds, model)
    problems += _coordinate_problems(ds)
    if values and not problems:
        problems += _value_problems(ds)
    return problems


def _value_problems(ds: xr.Dataset) -> list[str]:
    problems = []
    for name in FINITE_VARIABLES:
        if name in ds.variables and not np.all(np.isfinite(ds[name].values)):
            problems.append(
                f"its '{name}' variable holds NaN or infinite values (a racetrace model writes "
                "it finite)"
            )
    return problems


def _short(value, limit: int = 40) -> str:
    from solver.errors import clip, printable

    if isinstance(value, np.ndarray | np.generic):
        value = value.tolist()
    return clip(printable(repr(value)), limit)


def _attribute_problems(ds: xr.Dataset) -> list[str]:
    problems = []
    model = ds.attrs.get("model")
    if model is None:
        problems.append('it has no \'model\' attribute ("quasistatic" or "dynamic")')
    elif model not in _MODELS:
        problems.append(
            f'its \'model\' attribute is {_short(model)}, not "quasistatic" or "dynamic"'
        )
    if "case" not in ds.attrs:
        problems.append("it has no 'case' attribute (the case as run)")
    for name in TEXT_ATTRIBUTES[1:]:  # the model's name is checked above
        if name in ds.attrs and not _is_text(ds.attrs[name]):
            problems.append(f"its '{name}' attribute is {_short(ds.attrs[name])}, not text")
    complete = ds.attrs.get("complete", 1)
    if not (isinstance(complete, int | np.integer) and not isinstance(complete, bool)) or int(
        complete
    ) not in (0, 1):
        problems.append(f"its 'complete' attribute is {_short(complete)}, not 0 or 1")
    case = ds.attrs.get("case")
    if _is_text(case) and case.strip():
        problems += _case_text_problems(case)
    return problems


def _case_text_problems(text: str) -> list[str]:
    """The case text is provenance only, but the report shows values from it: it must read as
    TOML (no nesting hundreds of levels deep, no number of thousands of digits)."""
    from solver.case.io import parse_toml
    from solver.errors import CaseError

    try:
        parse_toml(text, "its 'case' attribute")
    except CaseError as error:
        return [str(error)]
    return []


def _dimension_problems(ds: xr.Dataset, model: str) -> list[str]:
    problems = []
    limits = _max_sizes()
    for dim, size in ds.sizes.items():
        if dim in DIMENSION_VALUES:
            labels = DIMENSION_VALUES[dim]
            found = ds[dim].values.tolist() if dim in ds.coords else None
            if found != labels:
                shown = "none" if found is None else _short(found, 80)
                problems.append(
                    f"its '{dim}' dimension must be labelled {', '.join(labels)} (found {shown})"
                )
        elif dim == _REVOLUTION_DIM and model == "quasistatic":
            problems += _ring_angle_problems(ds)
        elif dim in _OPEN_DIMENSIONS:
            if dim == "time" and model != "dynamic":
                problems.append("it has a 'time' dimension but its model is not \"dynamic\"")
            elif size < 1 or size > limits[dim]:
                problems.append(f"its '{dim}' dimension has {size} elements (1 to {limits[dim]})")
        else:
            problems.append(
                f"it has a '{_short(dim, 60)}' dimension: a racetrace result has only "
                f"{', '.join((*_OPEN_DIMENSIONS, *DIMENSION_VALUES))}; a file that stacks several "
                "results (a sweep) must be split into one result per file first"
            )
    for dim in ("ball", "race"):
        if dim not in ds.sizes:
            problems.append(f"it has no '{dim}' dimension")
    if model == "dynamic" and "time" not in ds.sizes:
        problems.append("it is a dynamic result without a 'time' dimension")
    if "time" in ds.sizes:
        time = ds["time"] if "time" in ds.coords else None
        if time is None or time.dtype.kind != "f" or time.dims != ("time",):
            problems.append("its 'time' coordinate is missing or not a number of seconds")
        elif not np.all(np.isfinite(time.values)) or np.any(np.diff(time.values) < 0):
            problems.append("its 'time' coordinate is not finite and increasing")
    return problems


def _ring_angle_problems(ds: xr.Dataset) -> list[str]:
    """What is wrong with the ``ring_angle`` dimension of a solution over one revolution."""
    size = ds.sizes[_REVOLUTION_DIM]
    angles = ds[_REVOLUTION_DIM] if _REVOLUTION_DIM in ds.coords else None
    if size < 2 or size > _MAX_RING_ANGLES:
        return [f"its 'ring_angle' dimension has {size} elements (2 to {_MAX_RING_ANGLES})"]
    if angles is None or angles.dims != (_REVOLUTION_DIM,) or not _numeric(angles):
        return ["its 'ring_angle' coordinate is missing or not a number of degrees"]
    values = np.asarray(angles.values, dtype=float)
    if not (np.all(np.isfinite(values)) and np.all(np.diff(values) > 0)):
        return ["its 'ring_angle' coordinate is not finite and increasing"]
    if values[0] < 0.0 or values[-1] >= 360.0:
        return ["its 'ring_angle' coordinate leaves 0 to 360 degree"]
    return []


def _variable_problems(ds: xr.Dataset, model: str) -> list[str]:
    problems = []
    for name in REQUIRED_VARIABLES + REQUIRED_BY_MODEL[model]:
        if name not in ds.variables:
            problems.append(f"it has no '{name}' variable")
    for name, spec in VARIABLES.items():
        if name not in ds.variables:
            continue
        expected = spec.dims_for(model)
        found = ds[name].dims
        if found != expected and found != (_REVOLUTION_DIM, *expected):
            problems.append(
                f"its '{name}' variable has dimensions {_dims_text(found)}, not "
                f"{_dims_text(expected)}"
            )
        elif name in TEXT_VALUES:
            if ds[name].dtype.kind not in "OUS":
                problems.append(f"its '{name}' variable holds {ds[name].dtype}, not text")
        elif not _numeric(ds[name]):
            problems.append(f"its '{name}' variable holds {ds[name].dtype}, not numbers")
        units = ds[name].attrs.get("units")
        if units is not None and not _is_text(units):
            problems.append(f"its '{name}' variable's units are {_short(units)}, not text")
    return problems


#: Describing coordinates a result may lack: a result without ``nominal_contact_angle`` is rated
#: at its free contact angle (solver.results.dataset.geometry_from_result).
_OPTIONAL = ("nominal_contact_angle",)
#: Describing coordinates that may be NaN (results-schema.md); every other number is finite.
_MAY_BE_NAN = ("tilting_moment", "shoulder_diameter")
#: Describing coordinates that are lengths or material constants: positive.
_POSITIVE = ("ball_diameter", "pitch_diameter", "groove_radius", "youngs_modulus", "density")


def _coordinate_problems(ds: xr.Dataset) -> list[str]:
    problems = []
    for name, spec in COORDINATES.items():
        if name not in ds.coords:
            if name in CHANNEL_NAMES and name in ds.data_vars:  # an input varying along a history
                values = ds[name]
                if values.dims != ("time",) or not _numeric(values):
                    problems.append(
                        f"its '{name}' varies in time but is not a number over 'time' "
                        f"(dimensions {_dims_text(values.dims)}, {values.dtype})"
                    )
                elif not np.all(np.isfinite(np.asarray(values.values, dtype=float))):
                    problems.append(f"its '{name}' over time is not finite")
                continue
            if name not in _OPTIONAL:
                problems.append(f"it has no '{name}' coordinate")
            continue
        values = ds.coords[name]
        if values.dims != spec.dims and values.dims != (_REVOLUTION_DIM, *spec.dims):
            problems.append(
                f"its '{name}' coordinate has dimensions {_dims_text(values.dims)}, not "
                f"{_dims_text(spec.dims)}"
            )
            continue
        if name in TEXT_VALUES:
            if values.dtype.kind not in "OUS":
                problems.append(f"its '{name}' coordinate holds {values.dtype}, not text")
            continue
        if not _numeric(values):
            problems.append(f"its '{name}' coordinate holds {values.dtype}, not numbers")
            continue
        numbers = np.asarray(values.values, dtype=float)
        if name not in _MAY_BE_NAN and not np.all(np.isfinite(numbers)):
            problems.append(f"its '{name}' coordinate is not finite ({_short(numbers.tolist())})")
        elif name in _POSITIVE and not np.all(numbers > 0):
            problems.append(f"its '{name}' coordinate is not positive ({_short(numbers.tolist())})")
    if problems:
        return problems
    balls = ds.coords["ball_count"].values.item()
    if float(balls) != ds.sizes["ball"]:
        problems.append(
            f"its 'ball_count' coordinate ({_short(balls)}) differs from its {ds.sizes['ball']} "
            "balls"
        )
    diameter = float(ds.coords["ball_diameter"])
    if float(ds.coords["pitch_diameter"]) <= diameter:
        problems.append("its 'pitch_diameter' is not larger than its 'ball_diameter'")
    if not np.all(np.asarray(ds.coords["groove_radius"].values, float) > 0.5 * diameter):
        problems.append("its 'groove_radius' is not larger than the ball's radius")
    return problems


def _study_problems(ds: xr.Dataset) -> list[str]:
    """What a study Dataset (solver.study.store.study_dataset) lacks for the study report."""
    from solver.study.metrics import POINT_METRICS, set_point_metric_table

    problems = []
    for name in STUDY_TEXT_ATTRIBUTES:
        if name in ds.attrs and not _is_text(ds.attrs[name]):
            problems.append(f"its '{name}' attribute is {_short(ds.attrs[name])}, not text")
    for dim in ("point", "model", "race"):
        if dim not in ds.sizes:
            problems.append(f"it has no '{dim}' dimension")
        elif dim not in ds.coords or ds[dim].dims != (dim,):
            problems.append(f"its '{dim}' dimension has no labels")
    # a study of bearing sets has the set's bearings too (SET_STUDY_METRIC_NAMES)
    for dim in ds.sizes:
        if dim not in ("point", "model", "race", "bearing"):
            problems.append(f"it has a '{_short(dim, 60)}' dimension a study Dataset does not have")
    if "bearing" in ds.sizes and ("bearing" not in ds.coords or ds["bearing"].dims != ("bearing",)):
        problems.append("its 'bearing' dimension has no labels")
    if problems:
        return problems
    if ds["race"].values.tolist() != DIMENSION_VALUES["race"]:
        problems.append("its 'race' dimension is not labelled inner, outer")
    expected = {name: ("point", "model", *dims) for name, (dims, *_rest) in POINT_METRICS.items()}
    expected |= {"status": ("point", "model"), "message": ("point", "model")}
    if "bearing" in ds.sizes:
        expected |= {
            name: ("point", "model", *dims)
            for name, (dims, *_rest) in set_point_metric_table().items()
        }
    for name, dims in expected.items():
        if name not in ds.variables:
            problems.append(f"it has no '{name}' variable")
        elif ds[name].dims != dims:
            problems.append(
                f"its '{name}' variable has dimensions {_dims_text(ds[name].dims)}, not "
                f"{_dims_text(dims)}"
            )
        elif (name in ("status", "message")) != (ds[name].dtype.kind in "OUS"):
            problems.append(f"its '{name}' variable holds {ds[name].dtype}")
    if "sweep" not in ds.coords or ds["sweep"].dims != ("point",):
        problems.append("it has no 'sweep' coordinate along 'point'")
    problems += _varied_key_problems(ds)
    return problems


def _varied_key_problems(ds: xr.Dataset) -> list[str]:
    text = ds.attrs.get("varied_keys", "[]")
    try:
        keys = json.loads(text) if _is_text(text) else None
    except (ValueError, RecursionError):
        keys = None
    if not isinstance(keys, list) or not all(isinstance(k, str) for k in keys):
        return ["its 'varied_keys' attribute is not a JSON list of case keys"]
    problems = []
    for key in keys:
        if key not in ds.coords or ds[key].dims != ("point",):
            problems.append(
                f"it varies {_short(key, 60)} but has no coordinate of it along 'point'"
            )
        elif ds[key].dtype.kind not in "fiubOUS":
            problems.append(f"its {_short(key, 60)} coordinate holds {ds[key].dtype}")
    return problems


#: The set's own names in a bearing set's Dataset (results-schema.md, "Bearing sets"), in every
#: set's, in a quasi-static set's and in a dynamic set's (a ``time`` dimension: "Dynamic results
#: of a bearing set").
_SET_NAMES = ("bearing_position", "bearing_direction", "bearing_axial_load", "bearing_force")
_QUASISTATIC_SET_NAMES = ("set_stiffness", "bearing_stiffness")
_DYNAMIC_SET_NAMES = ("shaft_offset", "energy_balance_residual")


def _set_problems(ds: xr.Dataset, values: bool) -> list[str]:
    """What a bearing set's Dataset (a ``bearing`` dimension, the ``bearing_set`` attribute)
    lacks: the set's own variables, and each bearing's single-bearing result, named by bearing."""
    from solver.models.quasistatic.set_warnings import bearing_result

    names = _SET_NAMES + (_DYNAMIC_SET_NAMES if "time" in ds.dims else _QUASISTATIC_SET_NAMES)
    problems = [f"a bearing set without '{name}'" for name in names if name not in ds]
    if "ball_count" not in ds or problems:
        return problems or ["a bearing set without 'ball_count'"]
    for index in range(ds.sizes["bearing"]):
        name = str(ds["bearing"].values[index]) if "bearing" in ds.coords else str(index)
        one = bearing_result(ds, index)
        problems += [f"{name}: {p}" for p in result_problems(one, values)]
    return problems


def check_result(ds: xr.Dataset, source: str = "the result", values: bool = False) -> xr.Dataset:
    """``ds`` when :func:`result_problems` (with ``values``) finds nothing; otherwise
    :class:`solver.errors.CaseError` naming ``source`` and the problems (the first few, and how
    many more), and saying what a racetrace result is."""
    from solver.errors import CaseError, Problem, clip, printable

    try:
        problems = result_problems(ds, values)
    except _DECODE_ERRORS as error:  # a lazily opened file decodes a value as it is read
        reason = clip(printable(f"{type(error).__name__}: {error}"), 300)
        problems = [f"its values cannot be decoded ({reason})"]
    if not problems:
        return ds
    shown = problems[:_MAX_PROBLEMS_SHOWN]
    more = len(problems) - len(shown)
    text = "; ".join(shown) + (f"; and {more} more" if more > 0 else "")
    raise CaseError(
        Problem(
            "result",
            f"{source}: not readable as a racetrace result: {text} (a result file is written by "
            "racetrace simulate or quasistatic --output, or the app; see docs/results-schema.md)",
        )
    )
