"""The quasi-static bearing set's Dataset (results-schema.md, "Bearing sets").

Every single-bearing quasi-static variable is stacked along a ``bearing`` dimension, each bearing's
values in its own frame (x along the thrust it carries) at its own operating point: the loads its
balls carry (its ``axial_load``, ``radial_load`` ... coordinates gain the ``bearing`` dimension) and
the tilt of its inner ring. Bearings with fewer balls than the largest ball count of the set hold
NaN beyond their ``ball_count``. The set's own variables (:data:`SET_VARIABLES`) are in the shaft
frame: x along the shaft, y and z as in the case, moments about the bearing's ball-centre plane or
the load point as stated.
"""

from __future__ import annotations

from datetime import UTC, datetime

import numpy as np
import xarray as xr

from solver.results.dataset import (
    ResultArrays,
    coordinate_variables,
    direct_dataset,
    label_index,
    raw_variable,
)
from solver.results.loaded import loaded_mask
from solver.results.variables import Variable

from .bearing_set import DOF

_STIFFNESS_UNITS = "N/m, N/rad, N, N m/rad by block (see description)"
_STIFFNESS_BLOCKS = (
    "rows: generalised forces (Fx, Fy, Fz [N], My, Mz [N m]); columns: displacements (x, y, z "
    "[m], tilt_y, tilt_z [rad]); K[i, j] = -d(force i on the shaft)/d(displacement j), so the "
    "translation block is in N/m, the force-tilt block in N/rad, the moment-translation block in "
    "N m/m = N and the tilt block in N m/rad"
)

#: The set's variables (quasi-static model, shaft frame), by name: dims, units, meaning.
SET_VARIABLES: dict[str, Variable] = {
    "shaft_offset": Variable(
        ("axis",),
        "m",
        "shaft displacement",
        "displacement of the shaft at the load point (set.load.position_mm), shaft frame",
        ("quasistatic",),
    ),
    "shaft_tilt": Variable(
        ("tilt_axis",),
        "degree",
        "shaft tilt",
        "rotation vector (y, z) of the shaft, shaft frame",
        ("quasistatic",),
    ),
    "bearing_force": Variable(
        ("bearing", "axis"),
        "N",
        "bearing force on the shaft",
        "force each bearing's balls exert on the shaft through its inner ring, shaft frame; "
        "together with the external load they sum to zero",
        ("quasistatic",),
    ),
    "bearing_moment": Variable(
        ("bearing", "tilt_axis"),
        "N m",
        "bearing moment on the shaft",
        "moment each bearing exerts on the shaft about the centre of its ball-centre plane, "
        "shaft frame",
        ("quasistatic",),
    ),
    "bearing_axial_load": Variable(
        ("bearing",),
        "N",
        "axial load carried",
        "axial load each bearing carries in its own direction (> 0 when loaded the way it "
        "carries thrust); the preload included",
        ("quasistatic",),
    ),
    "bearing_radial_load": Variable(
        ("bearing",),
        "N",
        "radial load carried",
        "magnitude of the radial force each bearing carries",
        ("quasistatic",),
    ),
    "axial_load_share": Variable(
        ("bearing",),
        "1",
        "share of the external axial load",
        "each bearing's axial force on the shaft over the external axial load, with the sign that "
        "makes the shares sum to 1 (with preload, the bearings facing the load take more than 1 "
        "and the opposed ones a negative share); present when the external axial load is not "
        "zero",
        ("quasistatic",),
    ),
    "radial_load_share": Variable(
        ("bearing",),
        "1",
        "share of the external radial load",
        "each bearing's radial force on the shaft along the external radial load, over that load "
        "(the shares sum to 1; negative: the bearing pulls the other way, as with an overhung "
        "load); present when the external radial load is not zero",
        ("quasistatic",),
    ),
    "bearing_offset": Variable(
        ("bearing", "axis"),
        "m",
        "inner ring displacement",
        "displacement of each bearing's inner ring relative to its outer ring at its ball-centre "
        "plane, shaft frame, preload offset included",
        ("quasistatic",),
    ),
    "bearing_tilt": Variable(
        ("bearing", "tilt_axis"),
        "degree",
        "inner ring tilt",
        "rotation vector (y, z) of each inner ring relative to its outer ring, shaft frame",
        ("quasistatic",),
    ),
    "bearing_stiffness": Variable(
        ("bearing", "dof", "dof_"),
        _STIFFNESS_UNITS,
        "bearing stiffness",
        "5x5 stiffness of each bearing at the operating point, about the centre of its ball-centre "
        "plane, shaft frame, with the ball speeds held at their solved values; "
        + _STIFFNESS_BLOCKS,
        ("quasistatic",),
    ),
    "set_stiffness": Variable(
        ("dof", "dof_"),
        _STIFFNESS_UNITS,
        "set stiffness",
        "5x5 stiffness of the shaft on its bearings at the load point (floating outer rings of a "
        "spring preload condensed out), ball speeds held; " + _STIFFNESS_BLOCKS,
        ("quasistatic",),
    ),
    "bearing_axial_stiffness": Variable(
        ("bearing",),
        "N/m",
        "axial stiffness of the bearing",
        "bearing_stiffness[x, x] of each bearing: axial force per axial displacement of its inner "
        "ring, other displacements held",
        ("quasistatic",),
    ),
    "bearing_radial_stiffness": Variable(
        ("bearing",),
        "N/m",
        "radial stiffness of the bearing",
        "mean of bearing_stiffness[y, y] and [z, z] of each bearing, about its ball-centre plane",
        ("quasistatic",),
    ),
    "bearing_tilt_stiffness": Variable(
        ("bearing",),
        "N m/rad",
        "tilting stiffness of the bearing",
        "mean of bearing_stiffness[tilt_y, tilt_y] and [tilt_z, tilt_z] of each bearing, about "
        "its ball-centre plane",
        ("quasistatic",),
    ),
    "bearing_inner_contact_angle": Variable(
        ("bearing",),
        "degree",
        "mean inner contact angle",
        "mean contact angle of each bearing's loaded inner contacts (contact_load > 0); NaN when "
        "no ball of the bearing touches its inner race (the bearing carries no load)",
        ("quasistatic",),
    ),
    "bearing_outer_contact_angle": Variable(
        ("bearing",),
        "degree",
        "mean outer contact angle",
        "mean contact angle of each bearing's loaded outer contacts (contact_load > 0); NaN when "
        "no ball of the bearing touches its outer race",
        ("quasistatic",),
    ),
    "axial_stiffness": Variable(
        (),
        "N/m",
        "axial stiffness of the set",
        "set_stiffness[x, x]: axial force per axial displacement of the shaft, other "
        "displacements held",
        ("quasistatic",),
    ),
    "radial_stiffness": Variable(
        (),
        "N/m",
        "radial stiffness of the set",
        "mean of set_stiffness[y, y] and [z, z] at the load point, other displacements held",
        ("quasistatic",),
    ),
    "tilt_stiffness": Variable(
        (),
        "N m/rad",
        "tilting stiffness of the set",
        "mean of set_stiffness[tilt_y, tilt_y] and [tilt_z, tilt_z] at the load point, other "
        "displacements held",
        ("quasistatic",),
    ),
    "preload_offset": Variable(
        (),
        "m",
        "preload offset",
        "axial offset of a fixed-position preload: the total axial approach of the opposed "
        "bearings at assembly (given, or solved at rest from the preload force); 0 otherwise",
        ("quasistatic",),
    ),
    "misalignment_moment": Variable(
        ("tilt_axis",),
        "N m",
        "moment holding the misalignment",
        "moment (y, z) on the shaft at the load point, from outside the set, that holds the "
        "shaft's tilt imposed by set.misalignment_deg (the bearings' moments balance it); "
        "present when set.misalignment_deg is given",
        ("quasistatic",),
    ),
    "spring_shift": Variable(
        (),
        "m",
        "spring side outer ring shift",
        "axial shift w of the spring side's floating outer rings, along those bearings' own "
        "direction (their inner rings' approach is w plus their shaft displacement in their own "
        "frame; spring preload); 0 otherwise",
        ("quasistatic",),
    ),
}


def _stacked_values(values):
    """The arrays ``values`` (one per bearing) stacked on a new first axis; arrays shorter along
    their first axis (fewer balls) padded with NaN (numbers) or "" (text)."""
    if len({v.shape for v in values}) == 1:
        return np.stack(values)
    longest = max(v.shape[0] for v in values)
    text = values[0].dtype.kind in "OUS"
    out = np.full(
        (len(values), longest, *values[0].shape[1:]),
        "" if text else np.nan,
        dtype=object if text else float,
    )
    for index, v in enumerate(values):
        out[index, : v.shape[0]] = v
    return out.astype(str) if text else out


def _arrays(result) -> ResultArrays:
    return result if isinstance(result, ResultArrays) else ResultArrays.of_dataset(result)


def stack_bearings(results, extra_coords=None, extra_data=None) -> xr.Dataset:
    """The bearings' results (Datasets or their :class:`ResultArrays`) stacked along a new
    ``bearing`` dimension: every data variable gains it, a coordinate only where the bearings
    differ; attributes that differ are dropped. ``extra_coords`` and ``extra_data`` (name:
    xarray.Variable) are added in the same build.

    The Dataset is assembled from the bearings' arrays as the public ``xr.Dataset(data, coords)``
    would make it, without its merge and alignment
    (:func:`solver.results.dataset.direct_dataset`): a dimension coordinate is the one of the
    bearing with the most labels (its index kept when it has one), the set's own get theirs."""
    tables = [_arrays(result) for result in results]
    first = tables[0]
    data = {}
    for name, (dims, _, attrs) in first.data.items():
        values = _stacked_values([np.asarray(table.data[name][1]) for table in tables])
        data[name] = raw_variable(("bearing", *dims), values, attrs)
    coords = {}
    made = {}
    for name, (dims, values, attrs) in first.coords.items():
        if dims == (name,):
            longest = max(tables, key=lambda table, n=name: np.size(table.coords[n][1]))
            coords[name] = longest.coords[name]
            if name in longest.made:
                made[name] = longest.made[name]
            continue
        all_values = [np.asarray(table.coords[name][1]) for table in tables]
        if all(np.array_equal(v, all_values[0]) for v in all_values[1:]):
            coords[name] = (dims, values, attrs)
        else:
            coords[name] = (("bearing", *dims), _stacked_values(all_values), attrs)
    coord_variables, indexes = coordinate_variables(coords, made)
    for name, var in (extra_coords or {}).items():
        if var.dims != (name,):
            coord_variables[name] = var
            continue
        index = label_index(name, tuple(var.values.tolist()), var.dtype.str)
        indexes[name] = index
        coord_variables.update(index.create_variables({name: var}))
    data.update(extra_data or {})
    attrs = {
        key: value
        for key, value in first.attrs.items()
        if all(key in table.attrs and _same(table.attrs[key], value) for table in tables[1:])
    }
    return direct_dataset(data, coord_variables, indexes, attrs)


def _same(a, b) -> bool:
    try:
        return bool(np.all(a == b))
    except (TypeError, ValueError):
        return False


def _var(name, values):
    spec = SET_VARIABLES[name]
    return raw_variable(spec.dims, np.asarray(values, dtype=float), spec.attrs())


def mean_loaded_contact_angle(bearing_results, race: str) -> np.ndarray:
    """The mean contact angle [degree] of the loaded ``race`` contacts (:func:`loaded_mask`) of
    each bearing's single-bearing result (a Dataset or its :class:`ResultArrays`); NaN for a
    bearing without a loaded contact there."""
    out = np.full(len(bearing_results), np.nan)
    for index, result in enumerate(bearing_results):
        table = _arrays(result)
        column = list(np.asarray(table.coords["race"][1])).index(race)
        angle = _race_values(table.data["contact_angle"], column)
        loaded = loaded_mask(_race_values(table.data["contact_load"], column), angle)
        if loaded.any():
            out[index] = float(np.mean(angle[loaded]))
    return out


def _race_values(parts, column) -> np.ndarray:
    """The values of the data variable ``parts`` ((dims, values, attrs), with a ``race``
    dimension) at the race index ``column``, as floats."""
    dims, values, _ = parts
    return np.take(np.asarray(values, float), column, axis=dims.index("race"))


def set_dataset(bearing_set, state, bearing_results, applied, case_text) -> xr.Dataset:
    """The set's Dataset from its :class:`.bearing_set.SetSolution` ``state``, the bearings'
    single-bearing results (each at its own operating point; Datasets or, cheaper, their
    :class:`ResultArrays`), the external loads ``applied`` (Fx, Fy, Fz, My, Mz at the load point,
    shaft frame) and the case text."""
    bearing_results = [_arrays(result) for result in bearing_results]
    names = [m.name for m in state.members]
    set_coords = {
        "bearing": xr.Variable(
            "bearing", names, {"long_name": "bearing of the set (set.bearing[].name)"}
        ),
        "bearing_position": xr.Variable(
            "bearing",
            [m.entry.position_mm * 1e-3 for m in state.members],
            {"units": "m", "long_name": "axial position of the bearing's ball-centre plane"},
        ),
        "bearing_direction": xr.Variable(
            "bearing",
            [m.entry.direction for m in state.members],
            {"long_name": "axial direction of the shaft thrust the bearing carries"},
        ),
        "ball_count": xr.Variable(
            "bearing",
            [m.inputs.geometry.ball_count for m in state.members],
            {"long_name": "number of balls of the bearing"},
        ),
        "dof": xr.Variable(
            "dof", list(DOF), {"long_name": "degree of freedom (force/displacement row)"}
        ),
        "dof_": xr.Variable(
            "dof_", list(DOF), {"long_name": "degree of freedom (displacement column)"}
        ),
        "load_position": xr.Variable(
            (),
            bearing_set.load_position_mm * 1e-3,
            {"units": "m", "long_name": "axial position of the external loads on the shaft"},
        ),
    }
    reactions = state.reactions
    k = state.set_stiffness
    sign = np.array([m.sign for m in state.members])
    data = {
        "shaft_offset": _var("shaft_offset", state.shaft[:3]),
        "shaft_tilt": _var("shaft_tilt", np.degrees(state.shaft[3:])),
        "bearing_force": _var("bearing_force", reactions[:, :3]),
        "bearing_moment": _var("bearing_moment", reactions[:, 3:]),
        "bearing_axial_load": _var("bearing_axial_load", -sign * reactions[:, 0]),
        "bearing_radial_load": _var(
            "bearing_radial_load", np.hypot(reactions[:, 1], reactions[:, 2])
        ),
        "bearing_offset": _var("bearing_offset", state.displacements[:, :3]),
        "bearing_tilt": _var("bearing_tilt", np.degrees(state.displacements[:, 3:])),
        "bearing_stiffness": _var("bearing_stiffness", state.stiffness),
        "set_stiffness": _var("set_stiffness", k),
        "bearing_axial_stiffness": _var("bearing_axial_stiffness", state.stiffness[:, 0, 0]),
        "bearing_radial_stiffness": _var(
            "bearing_radial_stiffness", 0.5 * (state.stiffness[:, 1, 1] + state.stiffness[:, 2, 2])
        ),
        "bearing_tilt_stiffness": _var(
            "bearing_tilt_stiffness", 0.5 * (state.stiffness[:, 3, 3] + state.stiffness[:, 4, 4])
        ),
        "bearing_inner_contact_angle": _var(
            "bearing_inner_contact_angle", mean_loaded_contact_angle(bearing_results, "inner")
        ),
        "bearing_outer_contact_angle": _var(
            "bearing_outer_contact_angle", mean_loaded_contact_angle(bearing_results, "outer")
        ),
        "axial_stiffness": _var("axial_stiffness", k[0, 0]),
        "radial_stiffness": _var("radial_stiffness", 0.5 * (k[1, 1] + k[2, 2])),
        "tilt_stiffness": _var("tilt_stiffness", 0.5 * (k[3, 3] + k[4, 4])),
        "preload_offset": _var("preload_offset", state.offset),
        "spring_shift": _var("spring_shift", state.spring_shift),
    }
    if state.misalignment_moment is not None:
        data["misalignment_moment"] = _var("misalignment_moment", state.misalignment_moment)
    if applied[0] != 0.0:
        data["axial_load_share"] = _var("axial_load_share", -reactions[:, 0] / applied[0])
    radial = np.hypot(applied[1], applied[2])
    if radial != 0.0:
        direction = applied[1:3] / radial
        data["radial_load_share"] = _var(
            "radial_load_share", -(reactions[:, 1:3] @ direction) / radial
        )
    ds = stack_bearings(bearing_results, set_coords, data)
    ds.attrs.update(
        {
            "bearing_set": bearing_set.describe(),
            "case": case_text,
            "created": datetime.now(UTC).isoformat(timespec="seconds"),
            "solver_iterations": int(state.iterations),
            "solver_residual": float(state.merit),
            "set_note": state.note,
            "stiffness_symmetry": stiffness_symmetry_note(k),
        }
    )
    if state.unloaded_at_rest:
        ds.attrs["unloaded_at_rest"] = ", ".join(state.unloaded_at_rest)
    return ds


def stiffness_asymmetry(k: np.ndarray) -> float:
    """Largest |K - K^T| over the largest |K| of the same block (translations, tilts), each
    entry scaled by the geometric mean of its diagonal terms so that the mixed units cancel."""
    d = np.sqrt(np.abs(np.diag(k)))
    d = np.where(d > 0.0, d, 1.0)
    scaled = k / np.outer(d, d)
    return float(np.max(np.abs(scaled - scaled.T)))


def stiffness_symmetry_note(k: np.ndarray) -> str:
    """How symmetric the stiffness ``k`` is, in words (results attribute
    ``stiffness_symmetry``)."""
    value = stiffness_asymmetry(k)
    return (
        f"largest asymmetry of the set stiffness, scaled by its diagonal: {value:.2g}. At rest "
        "the contacts are elastic (Hertz) and the stiffness is symmetric to the accuracy of the "
        "Jacobian; at speed the friction taking the balls' gyroscopic moments, which follows the "
        "contact angles, makes it unsymmetric by a small amount"
    )
