"""The one builder of results Datasets, used by both models (results-schema.md).

:func:`build_result` takes a model's arrays, checks their dimensions against the registry
(:mod:`solver.results.variables`), attaches units and names, and writes what the result *is* as
coordinates: the operating point and the geometry (:func:`describing_coordinates`). Because these
are coordinates, ``xr.concat(results, dim="case")`` keeps every element's own operating point and
geometry. Views read them back with :func:`ring_speeds` and :func:`geometry_from_result`, never
from the case text in ``attrs["case"]``, which is kept for provenance only.

Units: the operating point and geometry arrive in SI with angles in rad (``operating`` and
``geometry`` objects); the coordinates hold angles in degree like every angle in a results
Dataset, everything else SI.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from datetime import UTC, datetime

import numpy as np
import xarray as xr
from xarray.indexes import PandasIndex

from .variables import COORDINATES, DIMENSION_VALUES, coordinates, dimension_coordinate, variable

MODELS = ("quasistatic", "dynamic")

#: Operating-point fields read from ``operating`` (all SI, angles in rad), in coordinate order.
OPERATING_FIELDS = (
    "inner_ring_speed",
    "outer_ring_speed",
    "axial_load",
    "radial_load",
    "radial_load_angle",
    "misalignment",
    "misalignment_axis",
    "misalignment_frame",
    "tilting_moment",
    "moment_axis",
)
_ANGLES = {"radial_load_angle", "misalignment", "misalignment_axis", "moment_axis"}


def software() -> str:
    """``"racetrace <version>"`` for the ``software`` attribute."""
    from solver._version import __version__

    return f"racetrace {__version__}"


def case_text(case) -> str:
    """The case as TOML text for the provenance attribute ``case`` ("" without a case)."""
    if case is None:
        return ""
    to_toml = getattr(case, "to_toml", None)
    return to_toml() if callable(to_toml) else str(case)


#: Attributes that name what a result is in words, from its case (build_result writes them).
DESCRIPTION_ATTRIBUTES = ("title", "bearing_provenance", "description")


def case_description(text: str) -> dict[str, str]:
    """The :data:`DESCRIPTION_ATTRIBUTES` of a case text: its ``title``, ``bearing.provenance``
    and ``description`` (the schema's defaults where the text leaves them out); {} for no text
    or text that is not TOML."""
    return dict(_parsed_description(text))


@functools.lru_cache(maxsize=64)
def _parsed_description(text: str) -> tuple[tuple[str, str], ...]:
    """:func:`case_description` as ``(name, value)`` pairs; kept per text, since the results of
    one case (a study's points, the app's edits of the operating point) carry the same title."""
    from solver.case.io import parse_toml
    from solver.case.schema import field
    from solver.errors import CaseError

    if not text:
        return ()
    try:
        data = parse_toml(text, "the result's case")
    except CaseError:
        return ()
    bearing = data.get("bearing")
    provenance = bearing.get("provenance") if isinstance(bearing, dict) else None
    title = data.get("title")
    description = data.get("description")
    return (
        ("title", str(field("title").default if title is None else title)),
        (
            "description",
            str(field("description").default if description is None else description),
        ),
        (
            "bearing_provenance",
            str(field("bearing.provenance").default if provenance is None else provenance),
        ),
    )


def result_description(ds: xr.Dataset) -> dict[str, str]:
    """``title``, ``bearing_provenance`` and ``description`` of a result: its attributes, or, for
    a result written before it carried them, read from its case text here (views never parse the
    case text). A name is missing when neither says it."""
    stored = {name: str(ds.attrs[name]) for name in DESCRIPTION_ATTRIBUTES if name in ds.attrs}
    if len(stored) == len(DESCRIPTION_ATTRIBUTES):
        return stored
    return {**case_description(str(ds.attrs.get("case", ""))), **stored}


def describing_coordinates(geometry, operating) -> dict:
    """Coordinates that say what a result is: ``{name: (dims, values, attrs)}``.

    ``geometry``: a :class:`solver.geometry.BearingGeometry` (SI). ``operating``: any object with
    the attributes of :data:`OPERATING_FIELDS` in SI units and rad (``tilting_moment`` None when
    the tilt is imposed; ``misalignment_frame`` "space" or "ring"). Every name is registered in
    ``solver.results.variables.COORDINATES``.
    """
    values: dict[str, object] = {}
    for name in OPERATING_FIELDS:
        value = getattr(operating, name)
        if name == "misalignment_frame":
            values[name] = str(value)
        elif name == "tilting_moment":
            values[name] = math.nan if value is None else float(value)
        elif name in _ANGLES:
            values[name] = math.degrees(float(value))
        else:
            values[name] = float(value)
    g = geometry
    values.update(
        ball_count=int(g.ball_count),
        ball_diameter=float(g.ball_diameter),
        pitch_diameter=float(g.pitch_diameter),
        free_contact_angle=math.degrees(float(g.free_contact_angle)),
        nominal_contact_angle=math.degrees(float(g.rating_contact_angle)),
        groove_radius=np.array([g.inner_groove_radius, g.outer_groove_radius], dtype=float),
        shoulder_diameter=np.array(
            [g.inner_shoulder_diameter, g.outer_shoulder_diameter], dtype=float
        ),
        groove_bottom_diameter=np.array(
            [g.inner_groove_bottom_diameter, g.outer_groove_bottom_diameter], dtype=float
        ),
        material=np.array([g.ball_material.name, g.ring_material.name], dtype=object),
        youngs_modulus=np.array(
            [g.ball_material.youngs_modulus, g.ring_material.youngs_modulus], dtype=float
        ),
        poisson_ratio=np.array(
            [g.ball_material.poisson_ratio, g.ring_material.poisson_ratio], dtype=float
        ),
        density=np.array([g.ball_material.density, g.ring_material.density], dtype=float),
    )
    coords = {}
    for name, value in values.items():
        spec = COORDINATES[name]
        coords[name] = (spec.dims, value, spec.attrs())
    coords["body"] = dimension_coordinate("body")
    return coords


def build_result(
    model: str,
    data: dict,
    geometry,
    operating,
    *,
    case="",
    times=None,
    complete: bool = True,
    attrs: dict | None = None,
    variable_attrs: dict | None = None,
) -> xr.Dataset:
    """A results Dataset of ``model`` ("quasistatic" or "dynamic"): the Dataset of
    :func:`result_arrays` (same arguments)."""
    return result_arrays(
        model,
        data,
        geometry,
        operating,
        case=case,
        times=times,
        complete=complete,
        attrs=attrs,
        variable_attrs=variable_attrs,
    ).dataset()


def result_arrays(
    model: str,
    data: dict,
    geometry,
    operating,
    *,
    case="",
    times=None,
    complete: bool = True,
    attrs: dict | None = None,
    variable_attrs: dict | None = None,
) -> ResultArrays:
    """The :class:`ResultArrays` of a results Dataset of ``model`` ("quasistatic" or "dynamic").

    ``data``: ``{name: (dims, values)}`` for registered variables; ``dims`` name the axes of
    ``values`` in any order and must be the registry's dimensions for ``model`` (else
    RuntimeError: a programming error). ``times`` (s) is the dynamic model's ``time`` coordinate.
    ``case`` (a Case or its TOML text) goes to ``attrs["case"]`` for provenance only; its title
    bearing provenance and description to ``attrs["title"]``, ``attrs["bearing_provenance"]``
    and ``attrs["description"]``
    (:func:`case_description`).
    ``attrs`` adds model-specific attributes; ``variable_attrs`` ``{name: {key: value}}`` adds or
    extends per-variable attributes (a ``description`` there is appended to the registry's).
    """
    if model not in MODELS:
        raise ValueError(f"model {model!r}: must be one of {', '.join(MODELS)}")
    extra = variable_attrs or {}
    variables = {}
    for name, (dims, values) in data.items():
        spec = variable(name)
        target = spec.dims_for(model)
        if set(target) != set(dims) or len(target) != len(dims):
            raise RuntimeError(f"{model} output {name}: dims {dims} do not match {target}")
        values = np.asarray(values)
        if values.dtype.kind == "f":
            values = values.astype(np.float64)
        values = values.transpose([tuple(dims).index(d) for d in target]).copy(order="C")
        var_attrs = spec.attrs()
        for key, value in extra.get(name, {}).items():
            var_attrs[key] = var_attrs[key] + value if key == "description" else value
        variables[name] = (target, values, var_attrs)
    coords = coordinates(
        int(geometry.ball_count),
        times,
        quaternion="ball_orientation" in data,
        losses="power_loss" in data,
    )
    coords.update(describing_coordinates(geometry, operating))
    text = case if isinstance(case, str) else case_text(case)
    base = {
        "model": model,
        "case": text,
        **case_description(text),
        "software": software(),
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "complete": int(bool(complete)),
    }
    return ResultArrays(
        variables,
        {name: (_dims(dims), values, meta) for name, (dims, values, meta) in coords.items()},
        {**base, **(attrs or {})},
    )


def _dims(dims) -> tuple:
    return (dims,) if isinstance(dims, str) else tuple(dims)


@dataclasses.dataclass
class ResultArrays:
    """A result before it is a Dataset: what :func:`build_result` checked and named, as numpy
    arrays. ``data`` and ``coords``: ``{name: (dims, values, attrs)}`` (dims a tuple, values a
    numpy array or scalar whose dtype is final, data in the registry's order); ``attrs``: the
    Dataset's attributes. ``made``: ``{name: (Variable, index)}`` of dimension coordinates
    whose index already exists (those of a Dataset read back with :meth:`of_dataset`).

    A builder that combines results (a bearing set stacks its bearings') reads these arrays
    instead of building each result's Dataset first."""

    data: dict
    coords: dict
    attrs: dict
    made: dict = dataclasses.field(default_factory=dict)

    def dataset(self) -> xr.Dataset:
        """The result Dataset (:func:`direct_dataset`)."""
        variables = {name: raw_variable(*spec) for name, spec in self.data.items()}
        coord_variables, indexes = coordinate_variables(self.coords, self.made)
        return direct_dataset(variables, coord_variables, indexes, self.attrs)

    @classmethod
    def of_dataset(cls, ds: xr.Dataset) -> ResultArrays:
        """The arrays of a finished Dataset (its dimension coordinates' Variables and indexes
        kept as they are)."""
        table = ds.variables

        def parts(name):
            var = table[name]
            return var.dims, var.values, var.attrs

        made = {
            name: (table[name], ds.xindexes[name])
            for name in ds.coords
            if table[name].dims == (name,) and name in ds.xindexes
        }
        return cls(
            {name: parts(name) for name in ds.data_vars},
            {name: parts(name) for name in ds.coords},
            dict(ds.attrs),
            made,
        )


def direct_dataset(data_variables: dict, coord_variables: dict, indexes: dict, attrs: dict):
    """The Dataset of these Variables (data first, as xr.Dataset orders them) and indexes, as
    ``xr.Dataset(data_variables, coords=xr.Coordinates(coord_variables, indexes))`` gives it but
    without xarray's merge and alignment, which one result never needs: its Variables are new and
    its own, and share one set of dimensions (their sizes are still checked, ValueError when
    they differ). xarray's own constructor of a Dataset from finished parts
    (``Dataset._construct_direct``) takes about 1/20 of the time of the public one; a test in
    tests/unit/results/test_dataset.py keeps the two identical."""
    return xr.Dataset._construct_direct(
        {**data_variables, **coord_variables}, set(coord_variables), indexes=indexes, attrs=attrs
    )


def with_data_variables(ds: xr.Dataset, added: dict, dropped=()) -> xr.Dataset:
    """``ds`` without the variables ``dropped`` and with the data variables ``added`` ({name:
    DataArray or Variable} over dimensions of ``ds``, taken as they are; a DataArray's coordinates
    are not read): what ``ds.drop_vars(dropped).assign(added)`` gives for such variables, built
    with xarray's direct constructor (:func:`direct_dataset`) without a merge over every variable of
    ``ds`` (the chunks of a live simulation are built often). ValueError when a size differs
    from ``ds``'s."""
    dropped = set(dropped)
    variables = {n: v for n, v in ds.variables.items() if n not in dropped}
    for name, value in added.items():
        variables.pop(name, None)
        variables[name] = value.variable if isinstance(value, xr.DataArray) else value
    coord_names = {n for n in ds.coords if n not in dropped and n not in added}
    indexes = {n: i for n, i in ds.xindexes.items() if n not in dropped and n not in added}
    return xr.Dataset._construct_direct(
        variables, coord_names, indexes=indexes, attrs=dict(ds.attrs), encoding=dict(ds.encoding)
    )


def raw_variable(dims, values, attrs) -> xr.Variable:
    """An xarray Variable of ``values`` as they are: a numpy array (or a Python scalar, made one)
    whose dtype is final. xarray's own conversion is skipped; for an object array of strings it
    would hand the array to pandas and back unchanged, the dearest step of building a result."""
    return xr.Variable(dims, np.asarray(values), attrs, fastpath=True)


@functools.lru_cache(maxsize=64)
def label_index(dim: str, labels: tuple, dtype: str) -> PandasIndex:
    """The index of a dimension with these labels of this dtype (a tuple of Python values);
    xarray's indexes are immutable, so every result with the same labels shares one."""
    labels_array = np.array(labels, dtype=dtype)
    return PandasIndex.from_variables({dim: xr.Variable(dim, labels_array)}, options={})


def coordinate_variables(coords: dict, made: dict | None = None) -> tuple[dict, dict]:
    """({name: Variable}, {name: index}) of ``{name: (dims, values, attrs)}`` with an index for
    each dimension coordinate, as xarray would make it (the labelled dimensions' ones shared);
    ``made`` ``{name: (Variable, index)}`` gives dimension coordinates already made."""
    variables = {}
    indexes = {}
    made = made or {}
    for name, (dims, values, attrs) in coords.items():
        if name in made:
            variables[name], indexes[name] = made[name]
            continue
        var = raw_variable(dims, values, attrs)
        if var.dims != (name,):
            variables[name] = var
            continue
        if name == "ball" or name in DIMENSION_VALUES:
            index = label_index(name, tuple(var.values.tolist()), var.dtype.str)
        else:
            index = PandasIndex.from_variables({name: var}, options={})
        indexes[name] = index
        variables.update(index.create_variables({name: var}))
    return variables, indexes


# ---- reading what a result is --------------------------------------------------------------------
def _scalar(ds: xr.Dataset, name: str):
    _present(ds, name)
    value = ds.coords[name]
    if value.ndim:
        raise ValueError(
            f"the result holds several cases ('{name}' varies along {', '.join(value.dims)}); "
            "select one element first"
        )
    return value.values.item()


def ring_speeds(ds: xr.Dataset) -> tuple[float, float]:
    """(inner, outer) ring speeds of a result, rad/s, from its coordinates. Along a history where a
    ring's speed varies (a data variable over ``time``), its speed at the end of the run: that of
    the final phase, which the trajectory summary and the settling test read (results-schema.md,
    "Results along a history")."""
    return _speed(ds, "inner_ring_speed"), _speed(ds, "outer_ring_speed")


def _speed(ds: xr.Dataset, name: str) -> float:
    if name in ds.data_vars and "time" in ds[name].dims:
        return float(ds[name].isel(time=-1))
    return float(_scalar(ds, name))


def geometry_from_result(ds: xr.Dataset):
    """The :class:`solver.geometry.BearingGeometry` a result was computed for, from its
    coordinates (no case text is read). ValueError when the result lacks them."""
    from solver.geometry import BearingGeometry
    from solver.materials import BUILTIN_MATERIALS, Material

    for name in ("groove_radius", "shoulder_diameter", "material"):
        _present(ds, name)
    diameter = float(_scalar(ds, "ball_diameter"))
    radius = ds.coords["groove_radius"]
    shoulder = ds.coords["shoulder_diameter"]
    if radius.ndim != 1 or shoulder.ndim != 1:
        raise ValueError("the result holds several cases: select one element first")

    def material(body: str) -> Material:
        name = str(ds.coords["material"].sel(body=body).values.item())
        elastic = (
            float(ds.coords["youngs_modulus"].sel(body=body)),
            float(ds.coords["poisson_ratio"].sel(body=body)),
            float(ds.coords["density"].sel(body=body)),
        )
        builtin = BUILTIN_MATERIALS.get(name)
        if (
            builtin is not None
            and (builtin.youngs_modulus, builtin.poisson_ratio, builtin.density) == elastic
        ):
            return builtin  # its hysteresis loss too (not a coordinate of the result)
        return Material(name, *elastic)

    return BearingGeometry(
        ball_count=int(_scalar(ds, "ball_count")),
        ball_diameter=diameter,
        pitch_diameter=float(_scalar(ds, "pitch_diameter")),
        inner_conformity=float(radius.sel(race="inner")) / diameter,
        outer_conformity=float(radius.sel(race="outer")) / diameter,
        free_contact_angle=math.radians(float(_scalar(ds, "free_contact_angle"))),
        ball_material=material("ball"),
        ring_material=material("ring"),
        inner_shoulder_diameter=float(shoulder.sel(race="inner")),
        outer_shoulder_diameter=float(shoulder.sel(race="outer")),
        nominal_contact_angle=(
            math.radians(float(_scalar(ds, "nominal_contact_angle")))
            if "nominal_contact_angle" in ds.coords
            else math.nan
        ),
    )


def operating_from_result(ds: xr.Dataset):
    """The :class:`solver.inputs.OperatingPoint` (SI, rad) a result was computed for, from its
    coordinates (no case text is read). ValueError when the result lacks them."""
    from solver.inputs import OperatingPoint

    values = {name: _scalar(ds, name) for name in OPERATING_FIELDS}
    for name in _ANGLES:
        values[name] = math.radians(float(values[name]))
    moment = float(values["tilting_moment"])
    values["tilting_moment"] = None if math.isnan(moment) else moment
    values["misalignment_frame"] = str(values["misalignment_frame"])
    for name in ("inner_ring_speed", "outer_ring_speed", "axial_load", "radial_load"):
        values[name] = float(values[name])
    return OperatingPoint(**values)


def _present(ds: xr.Dataset, name: str) -> None:
    if name in ds.data_vars and "time" in ds[name].dims:
        raise ValueError(
            f"the result's '{name}' varies in time (a case with time histories): read "
            f"ds['{name}'] over time (results-schema.md)"
        )
    if name not in ds.coords:
        raise ValueError(
            f"the result has no '{name}' coordinate (results-schema.md); it was written by an "
            "older racetrace: run the case again"
        )


__all__ = [
    "MODELS",
    "OPERATING_FIELDS",
    "ResultArrays",
    "build_result",
    "coordinate_variables",
    "direct_dataset",
    "label_index",
    "raw_variable",
    "result_arrays",
    "case_text",
    "describing_coordinates",
    "case_description",
    "geometry_from_result",
    "operating_from_result",
    "result_description",
    "ring_speeds",
    "software",
    "with_data_variables",
]
