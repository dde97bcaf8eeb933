"""Driver of the dynamic model of a bearing set on one rigid shaft:
``simulate_set(case, progress=None, cancel=None, options=None)`` (:mod:`.set_kernels` for the
model, :mod:`.set_output` for the Dataset).

The run starts from the quasi-static set solution
(:func:`solver.models.quasistatic.bearing_set.solve_set_state`): the shaft at its displacement,
each bearing's balls, ring and cage as the single-bearing model starts from its own quasi-static
solution (:func:`.initial.initial_state_from_quasistatic`). The shaft is free in its five
degrees of freedom (translations, tilts) under the set's external load; its spin follows the
case's inner-ring speed; an imposed tilt (``set.misalignment_deg``) holds the shaft's two tilts
at their imposed values (:func:`_mass_inverse`). A fixed-position preload (an offset or a force
turned into an offset at rest) is the rings' axial offset, every outer ring fixed; a spring preload
floats the outer rings of the spring side axially as one body (:mod:`.set_kernels`; their mass
:func:`.params.outer_ring_mass` of each, width ``set.width_mm``), starting at the quasi-static
set's ``spring_shift`` at rest relative to it. Time histories are not modelled
(:func:`solver.case.validate.set_dynamic_problems`, CaseError). Outcomes as for
:func:`.simulate.simulate`.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from solver.case.validate import set_dynamic_problems
from solver.errors import CaseError, NoSolutionError, Problem, SimulationDiverged
from solver.history import event_times, steady_history
from solver.models.quasistatic.bearing_set import lever, mirror, set_inputs, solve_set_state

from . import layout as L
from .initial import initial_state_from_quasistatic
from .integrate import stepper
from .integrate.control import step_control
from .integrate.model import SetModel, bearing_model
from .options import SimulationOptions
from .params import build_params, build_quadrature, outer_ring_mass
from .set_kernels import SetShaft
from .set_output import set_dynamic_dataset
from .simulate import RunStatistics, _time_grid, run_chunks, state_scales

#: The integration method of a set run: the explicit Dormand-Prince method (the additive method
#: treats one bearing's cage land implicitly and is not extended to a set).
SET_METHOD = "dopri5"
#: Slots of the floating outer rings of a spring preload after the shaft block: w [m], w' [m/s].
SPRING_SIZE = 2


@dataclasses.dataclass
class SetMember:
    """One bearing of the set in the dynamic run: its inputs, parameters, history and quadrature
    (own frame), sign and arm [m], the axial offset of its rings [m], its slice of the state, the
    quasi-static solution it starts from, and whether its outer ring floats (spring side of a
    spring preload: its state is then in its outer ring's frame, :mod:`.set_kernels`)."""

    name: str
    inputs: object
    par: tuple
    history: tuple
    quad: np.ndarray
    sign: float
    arm: float
    offset: float
    start: int
    stop: int
    quasistatic: object
    floating: bool = False


def _problems(case, options: SimulationOptions) -> list[Problem]:
    """Why the set's dynamic model cannot run ``case`` under ``options`` (empty when it can): the
    case's rules (:func:`solver.case.validate.set_dynamic_problems`) and the method."""
    problems = set_dynamic_problems(case)
    if options.method not in ("auto", SET_METHOD):
        problems.append(
            Problem(
                "method",
                f"simulation option method = {options.method!r}: a bearing set runs with "
                f"{SET_METHOD!r} (or 'auto', which picks it)",
            )
        )
    return problems


def _member_operating(operating):
    """A bearing's operating point in the set: its ring speeds, no applied load or imposed tilt
    of its own (the shaft carries the set's load and moves the rings)."""
    return dataclasses.replace(
        operating,
        axial_load=0.0,
        radial_load=0.0,
        radial_load_angle=0.0,
        misalignment=0.0,
        misalignment_axis=0.0,
        misalignment_frame="space",
        tilting_moment=0.0,
        moment_axis=0.0,
    )


def _mass_matrix(members) -> np.ndarray:
    """The shaft's 5 x 5 mass matrix at the load point: the inner rings, rigidly joined."""
    m = np.zeros((5, 5))
    for b in members:
        g = lever(b.arm)
        own = np.array([b.par.ring_mass] * 3 + [b.par.ring_diametral_inertia] * 2, dtype=float)
        m += g.T @ (own[:, None] * g)
    return m


def _mass_inverse(mass: np.ndarray, tilt_imposed: bool) -> np.ndarray:
    """The inverse of the shaft's mass matrix ``mass`` (5 x 5); with the tilt imposed
    (set.misalignment_deg) the tilts are held: the translations' block inverted alone and the
    tilt rows and columns zero, so the tilts never accelerate from their imposed start (their
    rates start at zero) and the housing's moment holding them does no work."""
    if not tilt_imposed:
        return np.linalg.inv(mass)
    inverse = np.zeros((5, 5))
    inverse[:3, :3] = np.linalg.inv(mass[:3, :3])
    return inverse


def _weight(members, gravity: float) -> np.ndarray:
    w = np.zeros(5)
    for b in members:
        w += lever(b.arm).T @ np.array([0.0, 0.0, -b.par.ring_mass * gravity, 0.0, 0.0])
    return w


def shaft_ring_pose(sign: float, arm: float, offset: float, shaft_block: np.ndarray) -> dict:
    """A bearing's ring block (own frame: position, velocity, tilt, tilt rate) from the shaft
    block ``shaft_block`` (layout of an inner-ring block, shaft frame)."""
    t = mirror(sign) * np.ones(5)
    g = t[:, None] * lever(arm)
    u = np.r_[shaft_block[L.R_POS : L.R_POS + 3], shaft_block[L.R_TILT : L.R_TILT + 2]]
    v = np.r_[shaft_block[L.R_VEL : L.R_VEL + 3], shaft_block[L.R_TILT_RATE : L.R_TILT_RATE + 2]]
    q = g @ u
    q[0] += offset
    qd = g @ v
    return {"pos": q[:3], "tilt": q[3:], "vel": qd[:3], "tilt_rate": qd[3:]}


def build_set(case, options: SimulationOptions):
    """(members, shaft record, initial state, set inputs, quasi-static set solution) of a set
    case under ``options`` (validated, not yet resolved)."""
    problems = _problems(case, options)
    if problems:
        raise CaseError(problems)
    given = set_inputs(case)
    resolved = dataclasses.replace(options, method=SET_METHOD).resolved(given.inputs.simulation)
    try:
        qs = solve_set_state(given)
    except NoSolutionError as error:
        raise CaseError(
            Problem("set", f"no quasi-static set solution to start the dynamic run from: {error}")
        ) from None
    members = []
    start = 0
    bearing_set = given.bearing_set
    spring = bearing_set.preload_kind == "spring"
    for entry, solution, op in zip(qs.members, qs.solutions, qs.operatings, strict=True):
        inputs = dataclasses.replace(entry.inputs, operating=_member_operating(op))
        par = build_params(inputs, resolved)._replace(tilt_mode=L.TILT_FREE, ring_free=True)
        history = steady_history(inputs.operating)
        stop = start + L.state_size(int(par.ball_count))
        members.append(
            SetMember(
                entry.name,
                inputs,
                par,
                history,
                build_quadrature(resolved, par),
                float(entry.sign),
                float(entry.arm),
                float(entry.offset),
                start,
                stop,
                solution,
                bool(entry.spring),
            )
        )
        start = stop
    spring_slot = start + L.RING_SIZE if spring else -1
    y = np.zeros(start + L.RING_SIZE + (SPRING_SIZE if spring else 0))
    sb = start
    floating_mass = 0.0
    if spring:
        y[spring_slot] = qs.spring_shift
        width = bearing_set.width_mm * 1e-3
        floating_mass = sum(
            outer_ring_mass(m.inputs.geometry, width) for m in members if m.floating
        )
    y[sb + L.R_POS : sb + L.R_POS + 3] = qs.shaft[:3]
    y[sb + L.R_TILT : sb + L.R_TILT + 2] = qs.shaft[3:]
    for m in members:
        y_b = initial_state_from_quasistatic(m.par, m.quasistatic)
        rb = L.ring_base(int(m.par.ball_count))
        offset = m.offset + (qs.spring_shift if m.floating else 0.0)
        pose = shaft_ring_pose(m.sign, m.arm, offset, y[sb : sb + L.RING_SIZE])
        y_b[rb + L.R_POS : rb + L.R_POS + 3] = pose["pos"]
        y_b[rb + L.R_TILT : rb + L.R_TILT + 2] = pose["tilt"]
        y[m.start : m.stop] = y_b
    mass = _mass_matrix(members)
    shaft = SetShaft(
        np.array([m.start for m in members] + [sb], dtype=np.int64),
        np.array([m.sign for m in members]),
        np.array([m.arm for m in members]),
        np.ascontiguousarray(_mass_inverse(mass, given.bearing_set.misalignment_deg is not None)),
        np.ascontiguousarray(given.applied, dtype=float),
        _weight(members, float(resolved.gravity)),
        float(sum(m.par.ring_polar_inertia for m in members)),
        np.array([1.0 if m.floating else 0.0 for m in members]),
        int(spring_slot),
        float(bearing_set.preload_force_N) if spring else 0.0,
        1.0 / floating_mass if spring else 0.0,
    )
    return members, shaft, y, given, qs, resolved


def spring_mass(shaft: SetShaft) -> float:
    """Mass [kg] of the floating outer rings of a spring preload (0 without one)."""
    return 0.0 if shaft.spring_mass_inverse == 0.0 else 1.0 / shaft.spring_mass_inverse


def set_scales(members, y: np.ndarray) -> np.ndarray:
    """Error-norm scales of the set state: each bearing's (:func:`.simulate.state_scales`), the
    shaft's as the first bearing's inner ring, a spring shift and its rate (when the state has
    them) as that ring's axial position and velocity."""
    parts = [state_scales(m.history, m.par, y[m.start : m.stop]) for m in members]
    first = members[0]
    rb = L.ring_base(int(first.par.ball_count))
    ring = parts[0][rb : rb + L.RING_SIZE]
    parts.append(ring)
    if y.shape[0] > members[-1].stop + L.RING_SIZE:
        parts.append(np.array([ring[L.R_POS], ring[L.R_VEL]]))
    return np.concatenate(parts)


def simulate_set(case, progress=None, cancel=None, options: SimulationOptions | None = None):
    """Run the dynamic model of the bearing set of ``case`` (a Case with ``bearing_set``) and
    return its ``xarray.Dataset`` with a ``bearing`` dimension (results-schema.md, "Dynamic
    results of a bearing set"); arguments and outcomes as :func:`.simulate.simulate`."""
    given_options = (options or SimulationOptions()).validated()
    members, shaft, y, given, qs, resolved = build_set(case, given_options)
    inputs = given.inputs
    grid = _time_grid(inputs, resolved, given_options, members[0].history)
    times, period = grid.times, grid.period
    n_samples = times.size - 1
    states = np.empty((n_samples + 1, y.shape[0]))
    states[0] = y
    scale = set_scales(members, y)
    omega_n = scale[L.B_VEL] / scale[L.B_POS]
    h = 0.05 / omega_n
    method = stepper(SET_METHOD)
    model = SetModel(
        tuple(bearing_model(m.history, m.par, m.quad) for m in members),
        shaft,
    )
    work = method.workspace(model, y.shape[0], 0.0, h)
    control = step_control(
        resolved.tolerance,
        scale,
        1e-6 * h,
        resolved.max_steps_per_chunk,
        event_times(members[0].history, 0.0, float(times[-1])),
    )
    stats = RunStatistics(work.progress)
    stats.initial_step = h
    run = run_chunks(method, model, y, grid, states, control, work, resolved, progress, cancel)
    done, stop_reason, diverged_message = run.done, run.stop_reason, run.diverged_message
    stats.wall_time = run.wall_time
    ds = set_dynamic_dataset(
        given,
        qs,
        members,
        shaft,
        resolved,
        times[:done],
        states[:done],
        period,
        stop_reason == "finished",
        stop_reason,
        stats,
    )
    if diverged_message is not None:
        err = SimulationDiverged(diverged_message)
        err.dataset = ds
        raise err
    return ds
