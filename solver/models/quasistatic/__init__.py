"""Jones–Harris quasi-static model of an angular contact ball bearing (5 DOF inner ring).

Public API:

- ``solve_quasistatic(case) -> xarray.Dataset`` (results-schema.md, quasi-static variables); every
  ``case`` argument is a :class:`solver.case.Case` or its :class:`solver.inputs.Inputs` (the
  public ``solver.solve_quasistatic`` etc. also take a case-file path or a catalogue name)
- ``solve_quasistatic_state(case, initial=None) -> QuasiStaticSolution`` (SI arrays; the dynamic
  model starts from it)
- ``quasistatic_speed_sweep(case, speeds_rpm) -> xarray.Dataset`` stacked along the
  ``inner_ring_speed`` dimension, each speed started from the previous solution (continuation)
- ``solve_over_revolution(case, angles=REVOLUTION_RING_ANGLES) -> xarray.Dataset`` stacked along
  the ``ring_angle`` dimension: the steady state at a set of inner-ring angles over one shaft
  revolution, so that a misalignment turning with the inner ring is seen over a whole revolution,
  not at t = 0 only
- ``quasistatic_answer(case) -> xarray.Dataset``: the quasi-static answer every view, study and
  command quotes: ``solve_over_revolution`` at :data:`REVOLUTION_RING_ANGLES` angles when the case's
  misalignment turns with the inner ring (:func:`turns_with_ring`), ``solve_quasistatic`` otherwise
- ``solve_operating_point(geometry, operating, initial=None)`` for callers that build a
  :class:`solver.geometry.BearingGeometry` and an :class:`solver.inputs.OperatingPoint` directly

Model summary (details in :mod:`.kernels` and :mod:`solver.physics.kinematics`): unknowns are the
ball centre positions (2 per ball, solved ball by ball) and the inner ring's 5 DOF (dx, dy, dz,
theta_y, theta_z); an imposed misalignment fixes the tilt (the moment is an output), a given tilting
moment frees it. Ball loads Q = K(alpha) delta^1.5 with the tabulated exact Hertz constant at the
current contact angle; centrifugal force at the actual orbit radius; gyroscopic moment taken by race
friction; race control decided per ball by the Jones criterion and iterated to a fixed point. With
``[simulation] quasistatic_ball_speeds = "traction"`` the ball speeds come instead from the traction
balance of every ball with one cage speed (:mod:`.traction_balance`, docs/quasistatic-traction.md),
iterated with the ring solve to a fixed point. At zero speed the model is the classic static load
distribution.

Ball-fixed frame at t = 0 (ball latitude/longitude; the dynamic model uses the same one for its
initial quaternion): z_b = cos(beta) e_x - sin(beta) e_r, y_b = e_theta,
x_b = sin(beta) e_x + cos(beta) e_r.
"""

from __future__ import annotations

import dataclasses
import os

import numpy as np

from solver.errors import CaseError, NoSolutionError, Problem
from solver.history import event_times
from solver.inputs import Inputs, OperatingPoint, operating_at, rpm_to_rad_s, to_inputs

from .solution import QuasiStaticSolution
from .solver import solve_operating_point

__all__ = [
    "REVOLUTION_RING_ANGLES",
    "OperatingPoint",
    "QuasiStaticSolution",
    "ALONG_HISTORY_TIMES",
    "inputs_at_time",
    "quasistatic_along_history",
    "quasistatic_answer",
    "quasistatic_speed_sweep",
    "solve_operating_point",
    "solve_over_revolution",
    "solve_quasistatic",
    "solve_quasistatic_state",
    "turns_with_ring",
]

#: Inner-ring angles over one revolution at which a case whose misalignment turns with the inner
#: ring is solved (:func:`quasistatic_answer`): 10 degree apart, the azimuth bins of the trajectory
#: metrics (solver.results.summary), so that every bin of the ring frame in which the track is a
#: line holds one sample per ball.
REVOLUTION_RING_ANGLES = 36


#: Times at which :func:`quasistatic_along_history` solves a history by default: this many equally
#: spaced over [0, duration], 40 intervals, plus every knot time of the history inside.
ALONG_HISTORY_TIMES = 41

#: Attributes of one sweep element that a stacked sweep drops (they describe one solve).
_ELEMENT_ATTRS = (
    "solver_iterations",
    "solver_residual",
    "solver_force_scale_N",
    "race_control_note",
    "kinematics_note",
)


def _inputs(case) -> Inputs:
    """SI inputs of a Case (CaseError if invalid); Inputs as given. A path or a catalogue name is
    a TypeError: the public door (solver.facade) resolves those."""
    if isinstance(case, Inputs):
        return case
    if isinstance(case, str | os.PathLike):
        raise TypeError(
            f"the model takes a Case or Inputs, not {case!r}: solver.solve_quasistatic resolves "
            "a case-file path or a catalogue name"
        )
    if getattr(case, "bearing_set", None) is not None:
        from solver.errors import CaseError, Problem

        raise CaseError(
            Problem(
                "set",
                "this case describes a bearing set ([set]): the single-bearing quasi-static "
                "functions solve one bearing; solve the set with solver.solve(case) (racetrace "
                "solve CASE)",
            )
        )
    return to_inputs(case)


def _film_lubricant(inputs: Inputs):
    """The lubricant for the film thickness: the case's own, None when the case gives none (the
    quasi-static result then has no film thickness)."""
    return inputs.lubricant if inputs.lubricant.given else None


def _traction_lubricant(inputs: Inputs):
    """The lubricant whose traction curve sets the ball speeds when the case asks for the traction
    balance (``[simulation] quasistatic_ball_speeds = "traction"``), else None (race control)."""
    if inputs.simulation.quasistatic_ball_speeds == "traction":
        return inputs.lubricant
    return None


def _continued(geometry, points, traction_lubricant=None):
    """The solutions at each ``(operating point, where)`` of ``points`` in turn, each started from
    the one before: yields ``(operating point, QuasiStaticSolution)``. NoSolutionError for the
    first point without a solution, its message starting with that point's ``where``."""
    previous = None
    for operating, where in points:
        try:
            previous = solve_operating_point(geometry, operating, previous, traction_lubricant)
        except NoSolutionError as error:
            raise NoSolutionError(f"{where}: {error}") from None
        yield operating, previous


def _stacked(datasets, dim: str):
    """The element Datasets stacked along ``dim``: a coordinate that differs between them gains
    ``dim``, an attribute that differs is dropped; ``created`` is now."""
    from datetime import UTC, datetime

    import xarray as xr

    stacked = xr.concat(
        datasets,
        dim=dim,
        data_vars="all",
        coords="different",
        compat="equals",
        join="outer",
        combine_attrs="drop_conflicts",
    )
    stacked.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
    return stacked


def solve_quasistatic_state(
    case, initial: QuasiStaticSolution | None = None
) -> QuasiStaticSolution:
    """Quasi-static equilibrium of ``case`` as SI arrays. ``initial`` (a previous solution of the
    same bearing) is used as the starting point when given. Raises NoSolutionError (message: why,
    what to try) when no equilibrium is found."""
    inputs = _inputs(case)
    return solve_operating_point(
        inputs.geometry, inputs.operating, initial, _traction_lubricant(inputs)
    )


def _history_inputs(inputs: Inputs, what: str) -> Inputs:
    """``inputs`` of a case with a time history; CaseError naming ``what`` for a steady case."""
    if inputs.history is None:
        raise CaseError(
            Problem(
                "at_time",
                f"{what} needs a case with a time history, and every operating key of this case "
                "is a number (give one as a history, docs/case-format.md; a steady case is "
                "solved as it is)",
            )
        )
    return inputs


def inputs_at_time(case, t: float) -> Inputs:
    """The inputs of ``case`` (a Case or Inputs with a time history) at time ``t`` [s]: its
    operating point :func:`solver.inputs.operating_at` ``t``. CaseError for a steady case or a
    time that is not a finite number >= 0."""
    inputs = _history_inputs(_inputs(case), "a solution at a time")
    try:
        operating = operating_at(inputs, t)
    except ValueError as error:
        raise CaseError(Problem("at_time", f"at_time = {t!r}: {error}")) from None
    return dataclasses.replace(inputs, operating=operating)


def solve_quasistatic(case, at_time: float | None = None):
    """Quasi-static equilibrium of ``case`` as an xarray Dataset (results-schema.md).

    ``at_time`` [s]: for a case with a time history, the equilibrium under its operating point at
    that time (attribute ``history_time``); None: at t = 0 (a steady case: its operating point).
    """
    from solver.results.estimates import estimate_fields

    from .result import solution_to_dataset

    inputs = _inputs(case)
    if at_time is not None:
        inputs = inputs_at_time(inputs, at_time)
    solution = solve_operating_point(
        inputs.geometry, inputs.operating, traction_lubricant=_traction_lubricant(inputs)
    )
    ds = solution_to_dataset(
        solution,
        inputs.geometry,
        inputs.case_text,
        _film_lubricant(inputs),
        estimates=estimate_fields(inputs),
    )
    if at_time is not None:
        ds.attrs["history_time"] = float(at_time)
    return ds


def along_history_times(inputs: Inputs, times=None) -> np.ndarray:
    """The sorted distinct times [s] of :func:`quasistatic_along_history`: ``times`` None gives
    :data:`ALONG_HISTORY_TIMES` equally spaced over [0, duration] and every knot time inside; an
    int n >= 2, n equally spaced; a sequence, those times. ValueError for times < 0, not finite,
    or fewer than 2."""
    duration = float(inputs.simulation.duration)
    if times is None or (isinstance(times, int | np.integer) and not isinstance(times, bool)):
        count = ALONG_HISTORY_TIMES if times is None else int(times)
        if count < 2:
            raise ValueError(f"the sweep along the history needs at least 2 times, not {count}")
        grid = np.linspace(0.0, duration, count)
        if times is None:
            grid = np.concatenate([grid, event_times(inputs.history, 0.0, duration)])
    else:
        grid = np.asarray(list(times), dtype=float)
        if grid.ndim != 1 or grid.size < 2:
            raise ValueError("the sweep along the history needs a sequence of at least 2 times")
    if not np.all(np.isfinite(grid)) or np.any(grid < 0.0):
        raise ValueError("times along the history must be finite and >= 0 s")
    return np.unique(grid)


def quasistatic_along_history(case, times=None):
    """The quasi-static reference along the time history of ``case``: the solution under the
    operating point at each time (:func:`along_history_times`), stacked along a ``time``
    dimension [s], each started from the previous solution.

    An operating input that varies along the history is a data variable over ``time`` (the other
    inputs stay scalar coordinates, as in every result); every per-ball variable and metric gains
    ``time``. ``attrs["case"]`` is the case text; ``attrs["along_history"]`` says what was solved.
    CaseError for a steady case; NoSolutionError naming the first time without a solution.
    """
    from solver.results.dataset import OPERATING_FIELDS
    from solver.results.variables import coordinates

    from .result import solution_to_dataset

    inputs = _history_inputs(_inputs(case), "a sweep along the history")
    try:
        grid = along_history_times(inputs, times)
    except ValueError as error:
        raise CaseError(Problem("times", str(error))) from None
    geometry = inputs.geometry
    lubricant = _film_lubricant(inputs)
    points = [
        (operating_at(inputs, t), f"sweep along the history stopped at t = {t:g} s") for t in grid
    ]
    solutions = _continued(geometry, points, _traction_lubricant(inputs))
    ds = _stacked(
        [
            solution_to_dataset(sol, geometry, inputs.case_text, lubricant, op)
            for op, sol in solutions
        ],
        "time",
    )
    for key in _ELEMENT_ATTRS:  # one element's statistics and notes, even where they agree
        ds.attrs.pop(key, None)
    ds = ds.assign_coords(time=coordinates(geometry.ball_count, grid)["time"])
    varying = [n for n in OPERATING_FIELDS if n in ds.coords and "time" in ds[n].dims]
    ds = ds.reset_coords(varying)
    ds.attrs["along_history"] = (
        f"quasi-static solutions at {grid.size} times from {grid[0]:g} s to {grid[-1]:g} s along "
        "the case's time history (time); varying inputs: " + (", ".join(varying) or "none")
    )
    return ds


def quasistatic_speed_sweep(case, speeds_rpm):
    """Solutions of ``case`` at each inner-ring speed in ``speeds_rpm`` (other conditions as in the
    case), stacked along the ``inner_ring_speed`` dimension [rad/s]: every element carries its own
    operating point in its coordinates. Each speed starts from the previous solution. Raises
    NoSolutionError naming the first speed without a solution.

    The elements' solver statistics and notes, and any other attribute that differs between them,
    are dropped;
    ``attrs["case"]`` is the case text as given, with a first comment line saying that
    ``operating.inner_ring_speed_rpm`` varies along the sweep (provenance only: the speed of an
    element is its ``inner_ring_speed`` coordinate).
    """
    from .result import solution_to_dataset

    inputs = _inputs(case)
    geometry = inputs.geometry
    lubricant = _film_lubricant(inputs)
    speeds = np.asarray(list(speeds_rpm), dtype=float)
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds)):
        raise ValueError("speeds_rpm must be a non-empty sequence of finite speeds in rpm")
    if np.unique(speeds).size != speeds.size:
        raise ValueError("speeds_rpm must not repeat a speed")
    text = (
        "# speed sweep: operating.inner_ring_speed_rpm varies along the sweep "
        f"({', '.join(f'{rpm:g}' for rpm in speeds)} rpm); each element's speed is its "
        "inner_ring_speed coordinate\n" + inputs.case_text
    )
    points = [
        (
            dataclasses.replace(inputs.operating, inner_ring_speed=rpm_to_rad_s(rpm)),
            f"speed sweep stopped at {rpm:g} rpm",
        )
        for rpm in speeds
    ]
    solutions = _continued(geometry, points, _traction_lubricant(inputs))
    ds = _stacked(
        [solution_to_dataset(sol, geometry, text, lubricant, op) for op, sol in solutions],
        "inner_ring_speed",
    )
    for key in _ELEMENT_ATTRS:  # one element's statistics and notes, even where they agree
        ds.attrs.pop(key, None)
    return ds


def solve_over_revolution(case, angles: int = REVOLUTION_RING_ANGLES):
    """Quasi-static solutions of ``case`` at ``angles`` equally spaced inner-ring angles over one
    shaft revolution, stacked along the ``ring_angle`` dimension (degree, 0 <= angle < 360).

    The inner ring is turned by ``ring_angle`` relative to the outer ring; what is fixed in space
    (loads, a misalignment with ``misalignment_frame = "space"``) stays, and a misalignment turning
    with the inner ring (``"ring"``) has its axis at ``misalignment_axis + ring_angle``. Each
    element carries its own operating point in its coordinates (``misalignment_axis`` gains the
    ``ring_angle`` dimension when it turns). ``raceway_azimuth`` is each contact's azimuth in its
    own ring's frame at that angle: the inner ring's is turned back by the ring angle, the outer
    ring's by the outer ring's angle at the same time (ring speeds from the case; a stationary
    outer ring keeps its azimuths). Each angle starts from the previous solution. Raises
    ValueError for fewer than 2 angles and NoSolutionError naming the first angle without a
    solution.
    """
    import math

    import xarray as xr

    from solver.results.variables import DIMENSION_COORDINATES

    from .result import solution_to_dataset

    count = int(angles)
    if count < 2:
        raise ValueError(f"angles must be at least 2 (got {angles!r}): angles over one revolution")
    inputs = _inputs(case)
    geometry, base = inputs.geometry, inputs.operating
    lubricant = _film_lubricant(inputs)
    turning = base.misalignment_frame == "ring"
    w_in, w_out = base.inner_ring_speed, base.outer_ring_speed
    w_rel = w_in - w_out
    ring_angles = np.arange(count) * 2.0 * math.pi / count
    points = [
        (
            dataclasses.replace(base, misalignment_axis=base.misalignment_axis + theta)
            if turning
            else base,
            f"solution over a revolution stopped at ring angle {math.degrees(theta):g} degree",
        )
        for theta in ring_angles
    ]
    datasets = []
    points_solved = _continued(geometry, points, _traction_lubricant(inputs))
    for theta, (op, solution) in zip(ring_angles, points_solved, strict=True):
        ds = solution_to_dataset(solution, geometry, inputs.case_text, lubricant, op)
        # each ring's own frame at this angle: the inner ring turned by theta relative to the
        # outer ring, the outer ring by w_out * t with t = theta / (w_in - w_out)
        outer_turn = w_out * theta / w_rel if w_rel != 0.0 else 0.0
        turn = np.degrees(np.array([theta + outer_turn, outer_turn]))
        azimuth = (ds["raceway_azimuth"] - xr.DataArray(turn, dims="race")) % 360.0
        ds["raceway_azimuth"] = azimuth.assign_attrs(ds["raceway_azimuth"].attrs)
        datasets.append(ds)
    result = _stacked(datasets, "ring_angle")
    spec = DIMENSION_COORDINATES["ring_angle"]
    result = result.assign_coords(ring_angle=("ring_angle", np.degrees(ring_angles), spec.attrs()))
    if "misalignment_note" in result.attrs:  # the elements' note speaks of one snapshot
        result.attrs["misalignment_note"] = (
            f"misalignment_frame = ring: solved at {count} inner-ring angles over one revolution "
            "(ring_angle); the metrics are taken over every ring angle and ball"
        )
    return result


def turns_with_ring(case) -> bool:
    """True when ``case`` (a Case or Inputs) imposes a misalignment that turns with the inner ring
    (``misalignment_frame = "ring"``, a non-zero ``misalignment`` and no ``tilting_moment``): its
    load pattern turns with the inner ring, so a snapshot at t = 0 does not show what either ring
    sees over a revolution."""
    operating = _inputs(case).operating
    return (
        operating.misalignment_frame == "ring"
        and operating.misalignment != 0.0
        and operating.tilting_moment is None
    )


def quasistatic_answer(case):
    """The quasi-static answer for ``case`` that the CLI, the studies, the app and the report
    quote: for a misalignment turning with the inner ring (:func:`turns_with_ring`) the solutions
    over one revolution (:func:`solve_over_revolution` at :data:`REVOLUTION_RING_ANGLES` angles,
    dimension ``ring_angle``), whose metrics are taken over the ring angles and balls
    (solver.results.metrics); otherwise the snapshot of :func:`solve_quasistatic`."""
    inputs = _inputs(case)
    if turns_with_ring(inputs):
        return solve_over_revolution(inputs, angles=REVOLUTION_RING_ANGLES)
    return solve_quasistatic(inputs)
