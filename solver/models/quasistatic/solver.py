"""Solve driver of the quasi-static model: starting guess, continuation, race-control fixed point.

The numerical work (ball equilibria, ring Newton/Levenberg–Marquardt) is in :mod:`.kernels`; this
module chooses where to start, ramps load and then speed when a direct solve fails, iterates the
per-ball race control decision to a fixed point, and packs a :class:`QuasiStaticSolution`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from solver.errors import NoSolutionError
from solver.inputs import OperatingPoint, rad_s_to_rpm
from solver.physics.hertz_fast import (
    contact_ellipse_fast,
    curvature_sum_and_difference_fast,
    hertz_coefficients_fast,
)
from solver.physics.kinematics import race_control_is_inner

from . import kernels
from .solution import QuasiStaticSolution
from .traction_balance import JACOBIAN_SIZE, BalanceFailed, traction_balance, traction_setup

RING_TOLERANCE = 1e-11  # scaled residual norm at which the ring equilibrium is accepted
MAX_RING_ITERATIONS = 60
MAX_RACE_CONTROL_ITERATIONS = 12
MAX_TRACTION_ITERATIONS = 30
TRACTION_SPEED_TOLERANCE = 1e-9  # fixed point: ball speeds relative to the ring speed, angles rad
SETTLE_CHANGE_LIMIT = 100.0  # largest last change (in tolerances) a contraction estimate may accept


@njit(cache=True)
def _race_control(states, model):
    """Jones criterion for every ball from its current state (kernels.BallStates): True = inner
    control."""
    z = states.contact_load.shape[0]
    out = np.zeros(z, dtype=np.bool_)
    e_mod = model.effective_modulus
    for j in range(z):
        q_i = states.contact_load[j, 0]
        q_o = states.contact_load[j, 1]
        a_i = states.contact_angle[j, 0]
        a_o = states.contact_angle[j, 1]
        semi = np.zeros(2)
        ell = np.zeros(2)
        for k in range(2):
            is_inner = k == 0
            alpha = a_i if is_inner else a_o
            load = q_i if is_inner else q_o
            conformity = model.inner_conformity if is_inner else model.outer_conformity
            gamma = model.ball_diameter * math.cos(alpha) / model.pitch_diameter
            s, f = curvature_sum_and_difference_fast(
                model.ball_diameter, conformity, gamma, is_inner
            )
            semi[k] = contact_ellipse_fast(load, s, f, e_mod)[0]
            ell[k] = hertz_coefficients_fast(f)[2]
        out[j] = race_control_is_inner(q_i, q_o, semi[0], semi[1], ell[0], ell[1], a_i, a_o)
    return out


class Scales(NamedTuple):
    """Scales of the ring solve: its residuals are relative to ``force`` [N], its unknowns to
    ``length`` [m]."""

    force: float
    length: float


class _Problem:
    """Everything fixed for one bearing and load case; speeds vary during continuation."""

    def __init__(self, geometry, operating: OperatingPoint):
        self.geometry = geometry
        self.operating = operating
        z = geometry.ball_count
        self.azimuth = 2.0 * np.pi * np.arange(z) / z
        self.applied = operating.applied_loads()
        self.free = np.array([True, True, True, operating.tilt_is_free, operating.tilt_is_free])
        static = kernels.ball_model(geometry, 0.0, 0.0)
        self.static_model = static
        # force scale: the largest of the applied loads and the centrifugal force at the speed
        # solved for (see scales())
        omega_max = max(abs(operating.inner_ring_speed), abs(operating.outer_ring_speed))
        half_pitch = 0.5 * geometry.pitch_diameter
        self.centrifugal = geometry.ball_mass * half_pitch * omega_max**2
        moment = abs(operating.tilting_moment or 0.0) / half_pitch
        self.loads = max(abs(operating.axial_load), abs(operating.radial_load), moment, 1e-6)
        alpha0 = geometry.free_contact_angle
        k_i = kernels.contact_stiffness(static, alpha0, True)
        k_o = kernels.contact_stiffness(static, alpha0, False)
        self.ball_stiffness = (k_i ** (-2.0 / 3.0) + k_o ** (-2.0 / 3.0)) ** -1.5
        self.force_scale, self.length_scale = self.scales(1.0)
        self._models = {}  # BallModel (immutable) per speed fraction, see model()

    def scales(self, speed_fraction: float) -> Scales:
        """The scales at a fraction of the full speed: the force, the larger of the applied loads
        and the centrifugal force, and the length, the deflection of a ball carrying a share."""
        force = max(self.loads, self.centrifugal * speed_fraction**2)
        share = force / max(1.0, 0.25 * self.azimuth.size)
        length = max((share / self.ball_stiffness) ** (2.0 / 3.0), 1e-12)
        return Scales(force, length)

    def model(self, speed_fraction: float):
        """The kernels' BallModel at ``speed_fraction`` of the ring speeds (made once per
        fraction: the solve asks for it at every ring solve and ball evaluation)."""
        model = self._models.get(speed_fraction)
        if model is None:
            op = self.operating
            model = kernels.ball_model(
                self.geometry,
                speed_fraction * op.inner_ring_speed,
                speed_fraction * op.outer_ring_speed,
            )
            self._models[speed_fraction] = model
        return model

    def initial_positions(self, q, model) -> np.ndarray:
        pos = np.empty((self.azimuth.size, 2))
        for j, psi in enumerate(self.azimuth):
            a1, a2 = kernels.inner_center(q, psi, model)
            pos[j] = kernels._static_ball(a1, a2, model)
        return pos


def _static_start(problem: _Problem, load_fraction: float):
    """Static starting point: the axial and radial ring shifts found by bisection so that the axial
    and radial forces balance (tilt as imposed, or 0), and the closed-form ball positions."""
    model = problem.static_model
    q = np.zeros(5)
    q[3:] = problem.operating.imposed_tilt()
    kernels.static_start(
        q,
        problem.applied * load_fraction,
        problem.operating.tilt_is_free,
        problem.azimuth,
        model,
        problem.scales(0.0).length,
        3,
    )
    return q, problem.initial_positions(q, model)


class _State:
    """Mutable iterate of the continuation: ring displacement, ball positions, and each ball's
    kinematics record ``control`` (Z, kernels.CONTROL_SIZE): race control or the traction
    balance."""

    def __init__(self, q, position, control):
        self.q = q
        self.position = position
        self.control = control

    @property
    def inner_control(self) -> np.ndarray:
        """Race-control decision per ball (True = inner control)."""
        return self.control[:, kernels.CONTROL_MODE] == kernels.INNER_CONTROL

    def copy(self):
        return _State(self.q.copy(), self.position.copy(), self.control.copy())


def _ring_solve(problem: _Problem, state: _State, speed_fraction: float, load_fraction: float):
    model = problem.model(speed_fraction)
    force_scale, length_scale = problem.scales(speed_fraction)
    ring = kernels.RingLoad(
        problem.applied * load_fraction, problem.azimuth, state.control, model, force_scale
    )
    converged, iterations, merit = kernels.solve_ring(
        state.q,
        state.position,
        ring,
        problem.free,
        length_scale,
        RING_TOLERANCE,
        MAX_RING_ITERATIONS,
    )
    return bool(converged), int(iterations), float(merit)


def _solve_with_race_control(problem, state, speed_fraction, load_fraction):
    """Ring solve iterated with the race-control decision until it no longer changes.

    Returns (converged, iterations, merit, note)."""
    model = problem.model(speed_fraction)
    history = [state.inner_control.tobytes()]
    total = 0
    note = ""
    for _ in range(MAX_RACE_CONTROL_ITERATIONS):
        converged, iterations, merit = _ring_solve(problem, state, speed_fraction, load_fraction)
        total += iterations
        if not converged:
            return False, total, merit, note
        states = kernels.evaluate_balls(
            state.q, problem.azimuth, state.position, state.control, model
        )
        decision = _race_control(states, model)
        if np.array_equal(decision, state.inner_control):
            return True, total, merit, note
        key = decision.tobytes()
        if key in history:
            # the decision cycles: keep the last consistent solution and say so
            note = (
                "race control cycles between two decisions for some balls; the last solution is "
                "kept with the decision it was solved with"
            )
            return True, total, merit, note
        history.append(key)
        state.control = kernels.race_control_rows(decision)
    note = (
        f"race control did not settle in {MAX_RACE_CONTROL_ITERATIONS} iterations; the last "
        "solution is kept with the decision it was solved with"
    )
    return True, total, merit, note


def _continuation(solve, start: float, target: float, min_step: float):
    """Advance a parameter from ``start`` to ``target`` with adaptive steps. ``solve(value)``
    returns True on success (and keeps its state) or False (the caller restores the state). Returns
    the last value reached."""
    current = start
    step = target - start
    while current != target:
        trial = target if abs(target - current) <= abs(step) else current + step
        if solve(trial):
            current = trial
            step *= 2.0
        else:
            step *= 0.5
            if abs(step) < min_step:
                return current
    return current


def _fixed_point_settled(changes) -> bool:
    """True when the traction fixed point is within TRACTION_SPEED_TOLERANCE of its limit, from
    ``changes``, the largest change of the ball speeds (relative to the ring speed) and attitudes
    [rad] in each iteration so far, in units of the tolerance: the last change is within the
    tolerance, or the iteration contracts by a ratio r < 1/2 (the larger of the last two ratios of
    successive changes) so that the distance still to go, about r / (1 - r) times the last change,
    is within it (for a last change of at most SETTLE_CHANGE_LIMIT tolerances)."""
    last = changes[-1]
    if last <= 1.0:
        return True
    if len(changes) < 3 or last > SETTLE_CHANGE_LIMIT:
        return False
    ratio = max(changes[-1] / changes[-2], changes[-2] / changes[-3])
    return ratio < 0.5 and last * ratio / (1.0 - ratio) <= 1.0


def _solve_with_traction_balance(problem: _Problem, state: _State, lubricant):
    """From a race-control solution at full speed: ball speeds and transverse tractions from the
    traction balance (:mod:`.traction_balance`), iterated with the ring solve to a fixed point.
    Returns (iterations, merit, note); raises BalanceFailed (message: why) when no balance is
    found."""
    curve, nodes = traction_setup(lubricant)
    model = problem.model(1.0)
    relative = abs(problem.operating.inner_ring_speed - problem.operating.outer_ring_speed)
    total = 0
    merit = math.nan
    jacobian = np.full((problem.azimuth.size, JACOBIAN_SIZE), np.nan)  # kept between balances
    changes = []  # change of the ball speeds in each iteration, in tolerances
    for iteration in range(1, MAX_TRACTION_ITERATIONS + 1):
        states = kernels.evaluate_balls(
            state.q, problem.azimuth, state.position, state.control, model
        )
        control, _ = traction_balance(
            problem.geometry,
            model,
            states,
            state.position,
            state.q,
            problem.azimuth,
            state.control,
            curve,
            nodes,
            jacobian,
        )
        previous = state.control
        state.control = control
        converged, iterations, merit = _ring_solve(problem, state, 1.0, 1.0)
        total += iterations
        if not converged:
            raise BalanceFailed("no ring equilibrium with the ball speeds of the traction balance")
        if previous[0, kernels.CONTROL_MODE] != kernels.TRACTION_BALANCE:
            continue  # the first balance: from race control
        change = np.abs(control - previous)
        changes.append(
            max(
                change[:, kernels.CONTROL_ORBITAL].max() / relative,
                change[:, kernels.CONTROL_SPIN].max() / relative,
                change[:, kernels.CONTROL_ATTITUDE].max(),
            )
            / TRACTION_SPEED_TOLERANCE
        )
        if _fixed_point_settled(changes):
            cage = control[0, kernels.CONTROL_ORBITAL] / (2 * math.pi) * 60.0
            return (
                total,
                merit,
                (
                    f"ball speeds from the traction balance (cage speed {cage:.6g} rpm), "
                    f"fixed point after {iteration} iterations"
                ),
            )
    return (
        total,
        merit,
        (
            f"ball speeds from the traction balance: the fixed point did not settle within "
            f"{MAX_TRACTION_ITERATIONS} iterations; the last iterate is kept"
        ),
    )


def solve_operating_point(
    geometry,
    operating: OperatingPoint,
    initial: QuasiStaticSolution | None = None,
    traction_lubricant=None,
) -> QuasiStaticSolution:
    """Quasi-static equilibrium of ``geometry`` at ``operating``; see
    :func:`solve_quasistatic_state`. ``traction_lubricant`` (a
    :class:`solver.inputs.LubricantInputs`) switches the ball speeds from race control to the
    traction balance with that lubricant's traction curve (:mod:`.traction_balance`)."""
    problem = _Problem(geometry, operating)
    z = geometry.ball_count
    totals = {"iterations": 0}
    best = {}

    def attempt(state, speed, load):
        trial = state.copy()
        ok, its, merit, note = _solve_with_race_control(problem, trial, speed, load)
        totals["iterations"] += its
        if ok:
            state.q, state.position, state.control = (trial.q, trial.position, trial.control)
            best["merit"], best["note"] = merit, note
        return ok

    def start_at_speed(state):
        """The static solution, then the full speed from outer race control for every ball;
        True and the state solved on success, False and the state as given otherwise. (Without
        speed the Jones criterion has no rolling to compare: its decision at rest is no guide to
        the one at speed, and starting from it can take a whole extra solve at full speed.)"""
        trial = state.copy()
        ok, its, _ = _ring_solve(problem, trial, 0.0, 1.0)
        totals["iterations"] += its
        if not ok:
            return False
        if not attempt(trial, 1.0, 1.0):
            return False
        state.q, state.position, state.control = trial.q, trial.position, trial.control
        return True

    state = None
    if (
        initial is not None
        and initial.ball_position is not None
        and len(initial.ball_position) == z
    ):
        state = _State(
            np.concatenate([initial.inner_ring_offset, initial.inner_ring_tilt]).astype(float),
            np.array(initial.ball_position, dtype=float),
            kernels.race_control_rows(np.asarray(initial.race_control) == "inner"),
        )
        state.q[3:] = np.where(problem.free[3:], state.q[3:], operating.imposed_tilt())
        if not attempt(state, 1.0, 1.0):
            state = None
    has_speed = operating.inner_ring_speed != 0.0 or operating.outer_ring_speed != 0.0
    if state is None:
        q0, pos0 = _static_start(problem, 1.0)
        state = _State(q0, pos0, kernels.race_control_rows(np.zeros(z, dtype=np.bool_)))
        if not (has_speed and start_at_speed(state)):
            # the static solution first (its race control decided at rest, which a result
            # without speed reports), with load continuation if the direct solve fails, then the
            # speed, with speed continuation if the direct solve fails
            if not attempt(state, 0.0, 1.0):
                q0, pos0 = _static_start(problem, 0.05)
                state = _State(q0, pos0, kernels.race_control_rows(np.zeros(z, dtype=np.bool_)))
                if not attempt(state, 0.0, 0.05):
                    raise NoSolutionError(_no_static_message(problem))
                reached = _continuation(lambda s: attempt(state, 0.0, s), 0.05, 1.0, 1e-4)
                if reached != 1.0:
                    raise NoSolutionError(_no_static_message(problem))
            if has_speed and not attempt(state, 1.0, 1.0):
                reached = _continuation(lambda s: attempt(state, s, 1.0), 0.0, 1.0, 1e-4)
                if reached != 1.0:
                    raise NoSolutionError(_no_speed_message(problem, state, reached))
    note = best.get("note", "")
    merit = best.get("merit", math.nan)
    has_speed = operating.inner_ring_speed != operating.outer_ring_speed
    ball_speeds, fallback = "race_control", ""
    if traction_lubricant is not None and has_speed:
        race_control = state.copy()
        try:
            its, merit, note = _solve_with_traction_balance(problem, state, traction_lubricant)
            totals["iterations"] += its
            ball_speeds = "traction"
        except BalanceFailed as error:
            state = race_control
            fallback = (
                f"the traction balance found no steady ball speeds ({error}); the ball speeds "
                "come from race control instead"
            )
    solution = _pack(problem, state, totals["iterations"], merit, note)
    solution.ball_speeds = ball_speeds
    solution.ball_speeds_note = fallback
    _check_finite(solution)
    return solution


#: Solution fields that must be finite numbers in every solution returned.
_FINITE_FIELDS = (
    "ball_center",
    "contact_angle",
    "contact_load",
    "contact_deflection",
    "orbital_speed",
    "spin_speed",
    "attitude_angle",
    "ball_angular_velocity",
    "inner_ring_offset",
    "inner_ring_tilt",
    "cage_speed",
    "centrifugal_force",
    "gyroscopic_moment",
    "applied_moment",
)


def _check_finite(solution) -> None:
    """NoSolutionError when a value of the solution is not finite (the iteration overflowed or
    divided by zero somewhere): a result with NaN or inf is never returned as a solution."""
    bad = [
        name
        for name in _FINITE_FIELDS
        if not np.all(np.isfinite(np.asarray(getattr(solution, name), dtype=float)))
    ]
    if bad:
        raise NoSolutionError(
            "the quasi-static iteration ended with values that are not finite numbers "
            f"({', '.join(bad)}): the case lies outside what the model can compute. Try loads, "
            "speeds and misalignment closer to the bearing's rating."
        )


def _no_static_message(problem: _Problem) -> str:
    op = problem.operating
    return (
        f"no static equilibrium found for axial load {op.axial_load:g} N, radial load "
        f"{op.radial_load:g} N"
        + (f", tilting moment {op.tilting_moment:g} N m" if op.tilt_is_free else "")
        + ": the balls cannot hold the inner ring in every loaded direction (for example a free "
        "tilt or a radial load with too few balls in contact). Try adding axial preload, imposing "
        "the tilt (misalignment_deg) instead of a moment, or reducing the load."
    )


def _no_speed_message(problem: _Problem, state: _State, reached: float) -> str:
    op = problem.operating
    model = problem.model(reached)
    states = kernels.evaluate_balls(state.q, problem.azimuth, state.position, state.control, model)
    alpha_o = math.degrees(float(np.min(states.contact_angle[:, 1])))
    speed = rad_s_to_rpm(reached * op.inner_ring_speed)
    target = rad_s_to_rpm(op.inner_ring_speed)
    return (
        f"the quasi-static equilibrium was followed up to {speed:.0f} rpm (of {target:.0f} rpm) "
        f"and lost beyond it; there the smallest outer contact angle was {alpha_o:.1f}°: the "
        f"centrifugal force and gyroscopic moment of the balls exceed what the axial load of "
        f"{op.axial_load:g} N can hold. Try more axial preload or a lower speed."
    )


def _pack(problem: _Problem, state: _State, iterations: int, merit: float, note: str):
    g = problem.geometry
    op = problem.operating
    model = problem.model(1.0)
    states = kernels.evaluate_balls(state.q, problem.azimuth, state.position, state.control, model)
    psi = problem.azimuth
    alpha = states.contact_angle
    load = states.contact_load
    deflection = np.where(load > 0.0, np.maximum(states.contact_deflection, 0.0), 0.0)
    # An open contact reports the angle of the line between the groove curvature centres: where the
    # ball would touch if the gap closed (a ball with no contact at all sits on that line).
    open_contact = ~(load > 0.0)
    if open_contact.any():
        line = np.array([math.atan2(*kernels.inner_center(state.q, p, model)) for p in psi])
        alpha = np.where(open_contact, line[:, None], alpha)
    beta = states.attitude_angle
    omega_c = states.orbital_speed
    omega_r = states.spin_speed
    # ball centre (inertial, meridian plane): outer groove centre + X
    center = np.column_stack(
        [
            g.outer_curvature_center_axial + state.position[:, 0],
            g.outer_curvature_center_radius + state.position[:, 1],
        ]
    )
    # angular velocity: omega_c e_x + omega_R (cos beta e_x - sin beta e_r) + w_theta e_theta
    # (w_theta: the small yaw of the traction balance; 0 under race control)
    traction = state.control[:, kernels.CONTROL_MODE] == kernels.TRACTION_BALANCE
    w_t = np.where(traction, state.control[:, kernels.CONTROL_YAW], 0.0)
    w_x = omega_c + omega_r * np.cos(beta)
    w_r = -omega_r * np.sin(beta)
    ang = np.column_stack(
        [w_x, w_r * np.cos(psi) - w_t * np.sin(psi), w_r * np.sin(psi) + w_t * np.cos(psi)]
    )
    # friction taking the gyroscopic moment (kernels.ball_state): lambda M_g / D under race
    # control, the integrated transverse tractions under the traction balance
    m_g = states.gyroscopic_moment
    inner = state.inner_control
    race_traction = (
        np.column_stack([np.where(inner, m_g, 0.0), np.where(inner, m_g, 2.0 * m_g)])
        / g.ball_diameter
    )
    race_traction[traction, 0] = state.control[traction, kernels.CONTROL_TAU_INNER]
    race_traction[traction, 1] = state.control[traction, kernels.CONTROL_TAU_OUTER]
    # moment on the inner ring: balls' moment sum (about y, z) must be balanced by the applied one
    m_theta = states.ring_moment
    ball_moment = np.array([np.sum(-m_theta * np.sin(psi)), np.sum(m_theta * np.cos(psi))])
    applied_moment = op.applied_loads()[3:] if op.tilt_is_free else -ball_moment
    return QuasiStaticSolution(
        ball_azimuth=psi.copy(),
        ball_center=center,
        contact_angle=alpha,
        contact_load=load,
        contact_deflection=deflection,
        orbital_speed=omega_c,
        spin_speed=omega_r,
        attitude_angle=beta,
        ball_angular_velocity=ang,
        race_control=np.where(
            traction, "traction", np.where(state.inner_control, "inner", "outer")
        ),
        inner_ring_offset=state.q[:3].copy(),
        inner_ring_tilt=state.q[3:].copy(),
        cage_speed=float(np.mean(omega_c)),
        centrifugal_force=states.centrifugal_force,
        gyroscopic_moment=states.gyroscopic_moment,
        applied_moment=np.asarray(applied_moment, dtype=float),
        inner_ring_speed=op.inner_ring_speed,
        outer_ring_speed=op.outer_ring_speed,
        converged=True,
        residual=merit,
        iterations=iterations,
        force_scale=problem.force_scale,
        race_control_note=note,
        ball_position=state.position.copy(),
        operating=op,
        race_traction=race_traction,
    )
