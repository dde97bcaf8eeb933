"""Jones–Harris quasi-static model of an angular contact ball bearing (5 DOF inner ring).

Public API:

- ``solve_quasistatic(case) -> xarray.Dataset`` (results-schema.md, quasi-static variables); every
  ``case`` argument may also be a case-file path or a catalogue name
- ``solve_quasistatic_state(case, initial=None) -> QuasiStaticSolution`` (SI arrays; the dynamic
  model starts from it)
- ``quasistatic_speed_sweep(case, speeds_rpm) -> xarray.Dataset`` stacked along the
  ``inner_ring_speed`` dimension, each speed started from the previous solution (continuation)
- ``operating_point_from_case(case) -> OperatingPoint`` and
  ``solve_operating_point(geometry, operating, initial=None)`` for callers that build a
  :class:`solver.geometry.BearingGeometry` directly

Model summary (details in :mod:`.kernels` and :mod:`solver.physics.kinematics`): unknowns are the
ball centre positions (2 per ball, solved ball by ball) and the inner ring's 5 DOF (dx, dy, dz,
theta_y, theta_z); an imposed misalignment fixes the tilt (the moment is an output), a given tilting
moment frees it. Ball loads Q = K(alpha) delta^1.5 with the tabulated exact Hertz constant at the
current contact angle; centrifugal force at the actual orbit radius; gyroscopic moment taken by race
friction; race control decided per ball by the Jones criterion and iterated to a fixed point. At
zero speed the model is the classic static load distribution.

Ball-fixed frame at t = 0 (ball latitude/longitude; the dynamic model uses the same one for its
initial quaternion): z_b = cos(beta) e_x - sin(beta) e_r, y_b = e_theta,
x_b = sin(beta) e_x + cos(beta) e_r.
"""

from __future__ import annotations

import math
import os

import numpy as np

from solver.errors import NoSolutionError

from .solution import OperatingPoint, QuasiStaticSolution
from .solver import solve_operating_point

__all__ = [
    "OperatingPoint",
    "QuasiStaticSolution",
    "operating_point_from_case",
    "quasistatic_speed_sweep",
    "solve_operating_point",
    "solve_quasistatic",
    "solve_quasistatic_state",
]

_RPM = math.pi / 30.0


def _get(section, name, default):
    value = getattr(section, name, None)
    return default if value is None else value


def operating_point_from_case(case) -> OperatingPoint:
    """SI operating point of ``case.operating`` (case-format.md keys; rpm, N, deg, N m → SI)."""
    op = case.operating
    moment = getattr(op, "tilting_moment_Nm", None)
    return OperatingPoint(
        inner_ring_speed=float(_get(op, "inner_ring_speed_rpm", 0.0)) * _RPM,
        outer_ring_speed=float(_get(op, "outer_ring_speed_rpm", 0.0)) * _RPM,
        axial_load=float(_get(op, "axial_load_N", 0.0)),
        radial_load=float(_get(op, "radial_load_N", 0.0)),
        radial_load_angle=math.radians(float(_get(op, "radial_load_angle_deg", 0.0))),
        misalignment=math.radians(float(_get(op, "misalignment_deg", 0.0))),
        misalignment_axis=math.radians(float(_get(op, "misalignment_axis_deg", 90.0))),
        misalignment_frame=str(_get(op, "misalignment_frame", "space")),
        tilting_moment=None if moment is None else float(moment),
        moment_axis=math.radians(float(_get(op, "moment_axis_deg", 90.0))),
    )


def _geometry(case):
    from solver.geometry import BearingGeometry

    return BearingGeometry.from_case(case)


def _as_case(case):
    """A Case as given, or resolved from a case-file path / catalogue name (CaseError if
    invalid)."""
    if isinstance(case, (str, os.PathLike)):
        from solver.catalogue import resolve_case

        return resolve_case(case)
    return case


def solve_quasistatic_state(
    case, initial: QuasiStaticSolution | None = None
) -> QuasiStaticSolution:
    """Quasi-static equilibrium of ``case`` as SI arrays. ``initial`` (a previous solution of the
    same bearing) is used as the starting point when given. Raises NoSolutionError (message: why,
    what to try) when no equilibrium is found."""
    case = _as_case(case)
    return solve_operating_point(_geometry(case), operating_point_from_case(case), initial)


def solve_quasistatic(case):
    """Quasi-static equilibrium of ``case`` as an xarray Dataset (results-schema.md)."""
    from solver.results.quasistatic import solution_to_dataset

    case = _as_case(case)
    geometry = _geometry(case)
    solution = solve_operating_point(geometry, operating_point_from_case(case))
    return solution_to_dataset(solution, geometry, case, getattr(case, "lubricant", None))


def quasistatic_speed_sweep(case, speeds_rpm):
    """Solutions of ``case`` at each inner-ring speed in ``speeds_rpm`` (other conditions as in the
    case), stacked along the ``inner_ring_speed`` dimension [rad/s]: every element carries its own
    operating point in its coordinates. Each speed starts from the previous solution. Raises
    NoSolutionError naming the first speed without a solution.

    Attributes that differ between the elements (solver statistics, notes) are dropped;
    ``attrs["case"]`` is the case text as given, with a first comment line saying that
    ``operating.inner_ring_speed_rpm`` varies along the sweep (provenance only: the speed of an
    element is its ``inner_ring_speed`` coordinate).
    """
    import dataclasses
    from datetime import UTC, datetime

    import xarray as xr

    from solver.results.dataset import case_text
    from solver.results.quasistatic import solution_to_dataset

    case = _as_case(case)
    geometry = _geometry(case)
    base = operating_point_from_case(case)
    lubricant = getattr(case, "lubricant", None)
    speeds = np.asarray(list(speeds_rpm), dtype=float)
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds)):
        raise ValueError("speeds_rpm must be a non-empty sequence of finite speeds in rpm")
    if np.unique(speeds).size != speeds.size:
        raise ValueError("speeds_rpm must not repeat a speed")
    text = (
        "# speed sweep: operating.inner_ring_speed_rpm varies along the sweep "
        f"({', '.join(f'{rpm:g}' for rpm in speeds)} rpm); each element's speed is its "
        "inner_ring_speed coordinate\n" + case_text(case)
    )
    datasets = []
    previous = None
    for rpm in speeds:
        op = dataclasses.replace(base, inner_ring_speed=float(rpm) * _RPM)
        try:
            previous = solve_operating_point(geometry, op, previous)
        except NoSolutionError as error:
            raise NoSolutionError(f"speed sweep stopped at {rpm:g} rpm: {error}") from None
        datasets.append(solution_to_dataset(previous, geometry, text, lubricant, op))
    ds = xr.concat(
        datasets,
        dim="inner_ring_speed",
        data_vars="all",
        coords="different",
        compat="equals",
        join="outer",
        combine_attrs="drop_conflicts",
    )
    ds.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
    return ds
