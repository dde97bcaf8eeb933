"""Quasi-static model of a bearing set on a rigid shaft (docs/case-format.md, "Bearing sets").

Unknowns: the shaft's 5 DOF u = (x, y, z, theta_y, theta_z) [m, rad] at the load point
``set.load.position_mm`` (shaft frame: x along the shaft axis, the frame of the case's loads), and,
for a spring preload, the axial shift w [m] of the spring side's outer rings. Bearing b, whose
ball-centre plane lies at the arm L_b = position_b - load position along x, sees its inner ring
displaced rigidly with the shaft:

    d_b = (u_x, u_y + L_b theta_z, u_z - L_b theta_y),  theta_b = (theta_y, theta_z)

(delta_b = delta + theta x r_b, written as d_b = G_b u). A bearing with direction "-x" is the
mirror image (reflection x -> -x) of one with "+x": its own frame has x_b = -x, so its 5-vector of
displacements and of generalised forces is T_b = diag(s, 1, 1, s, s) times the shaft one, with
s = -1 (rotation vectors and moments are axial vectors: their y, z components change sign under
the reflection); the ring speeds about x are unchanged by the reflection. In its own frame the
inner ring is displaced by

    q_b = T_b G_b u + (c_b, 0, 0, 0, 0)

with c_b = e/2 for a fixed-position preload (e: the axial offset, the total approach of the
opposed bearings at assembly; a force preload is turned into e once, at rest), c_b = w for a
bearing on the spring side, else 0. The balls of each bearing are solved for q_b exactly as in the
single-bearing model (:func:`.kernels.ring_residual_and_jacobian`, the same ball-speed rule), which
returns R_b, the force and moment of its balls on its inner ring, and dR_b/dq_b. Equilibrium of the
shaft and of the floating outer rings:

    F_ext + sum_b G_b^T T_b R_b(q_b) = 0,      F_spring + sum_(spring side) R_b,x = 0

solved by Newton (Levenberg-Marquardt when ill-conditioned) with the Jacobian
sum_b G_b^T T_b J_b T_b G_b assembled from the bearings' own (implicit-function) Jacobians.

A misalignment (``set.misalignment_deg``) imposes the shaft's tilt (theta_y, theta_z) relative to
the housing bores, which hold every outer ring: the two moment equations are replaced by the
imposed tilt, and the moment they leave unbalanced is the one the rest of the machine exerts to
hold the tilt (``misalignment_moment``).
"""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np

from solver.errors import NoSolutionError
from solver.inputs import OperatingPoint, to_inputs
from solver.units import MM

from . import kernels
from .solver import (
    MAX_RACE_CONTROL_ITERATIONS,
    MAX_TRACTION_ITERATIONS,
    TRACTION_SPEED_TOLERANCE,
    _fixed_point_settled,
    _pack,
    _Problem,
    _race_control,
    _State,
)
from .traction_balance import JACOBIAN_SIZE, BalanceFailed, traction_balance, traction_setup

DOF = ("x", "y", "z", "tilt_y", "tilt_z")
SET_TOLERANCE = 1e-11  # scaled residual norm at which the set equilibrium is accepted
MAX_SET_ITERATIONS = 80
#: A bearing counts as unloaded when its largest inner contact load is below this fraction of the
#: set's force scale.
UNLOADED_FRACTION = 1e-9


def mirror(sign: float) -> np.ndarray:
    """T_b: the diagonal map of a 5-vector (x, y, z, tilt_y, tilt_z) between the shaft frame and
    the frame of a bearing with direction sign ``sign`` (its own inverse)."""
    return np.array([sign, 1.0, 1.0, sign, sign])


def lever(arm: float) -> np.ndarray:
    """G_b (5, 5): the inner ring's displacement at the arm ``arm`` [m] from the shaft's reference
    point, for a shaft displacement u (rigid shaft, small rotations)."""
    g = np.eye(5)
    g[1, 4] = arm
    g[2, 3] = -arm
    return g


class _Member:
    """One bearing of the set during the solve: its single-bearing problem (scales, ball model),
    state (q in its own frame, ball positions, kinematics records) and map from the shaft."""

    def __init__(self, entry, inputs, operating, arm, load_scale):
        self.entry = entry
        self.inputs = inputs
        self.name = entry.name
        self.sign = entry.sign
        self.arm = arm
        self.map = mirror(self.sign)[:, None] * lever(arm)  # q_b = map @ u + offset
        self.map_t = np.ascontiguousarray(self.map.T)
        # the problem's loads set its force and length scales only (the balls' reactions are
        # computed with zero applied load)
        scale_op = dataclasses.replace(
            operating, axial_load=load_scale, radial_load=0.0, tilting_moment=0.0
        )
        self.problem = _Problem(inputs.geometry, scale_op)
        z = inputs.geometry.ball_count
        self.state = _State(
            np.zeros(5),
            np.zeros((z, 2)),
            kernels.race_control_rows(np.zeros(z, dtype=np.bool_)),
        )
        self.offset = 0.0
        self.spring = False
        self._no_load = np.zeros(5)  # the ring kernel's applied load: the balls' reaction alone
        self._force_scales = {}  # the problem's force scale per speed fraction, see reaction()

    def q(self, u, w):
        q = self.map @ u
        q[0] += w if self.spring else self.offset
        return q

    def reaction(self, q, speed_fraction, position, want_jacobian=True):
        """(ok, R_b, J_b) of the balls on the inner ring at q (own frame); ``position`` (Z, 2)
        is updated in place."""
        model = self.problem.model(speed_fraction)
        force_scale = self._force_scales.get(speed_fraction)
        if force_scale is None:
            force_scale = self.problem.scales(speed_fraction).force
            self._force_scales[speed_fraction] = force_scale
        ring = kernels.RingLoad(
            self._no_load, self.problem.azimuth, self.state.control, model, force_scale
        )
        residual = np.empty(5)
        jacobian = np.empty((5, 5))
        ok = kernels.ring_residual_and_jacobian(
            q, position, ring, np.bool_(want_jacobian), residual, jacobian
        )
        return bool(ok), residual, jacobian


class _SetProblem:
    """The set's equations at a speed fraction: residual and Jacobian of the unknowns
    v = (u, [w])."""

    def __init__(self, members, applied, spring_force, tilt=None, tilt_weight=1.0):
        self.members = members
        self.applied = applied
        self.spring_force = spring_force
        self.n = 6 if spring_force is not None else 5
        #: an imposed shaft tilt (y, z) [rad] relative to the housing (set.misalignment_deg):
        #: the two moment equations are replaced by tilt_weight * (u_tilt - tilt) = 0 [N m]
        self.tilt = tilt
        self.tilt_weight = tilt_weight

    def split(self, v):
        return v[:5], (v[5] if self.n == 6 else 0.0)

    def evaluate(self, v, speed, positions, want_jacobian=True):
        u, w = self.split(v)
        residual = np.zeros(self.n)
        residual[:5] = self.applied
        jacobian = np.zeros((self.n, self.n))
        ok_all = True
        for m, position in zip(self.members, positions, strict=True):
            q = m.q(u, w)
            ok, r_b, j_b = m.reaction(q, speed, position, want_jacobian)
            ok_all &= ok
            residual[:5] += m.map_t @ r_b
            if want_jacobian:
                jacobian[:5, :5] += m.map_t @ j_b @ m.map
            if m.spring:
                residual[5] += r_b[0]
                if want_jacobian:
                    jacobian[5, :5] += j_b[0] @ m.map
                    jacobian[:5, 5] += m.map.T @ j_b[:, 0]
                    jacobian[5, 5] += j_b[0, 0]
        if self.n == 6:
            residual[5] += self.spring_force
        if self.tilt is not None:
            residual[3:5] = self.tilt_weight * (u[3:5] - self.tilt)
            jacobian[3:5, :] = 0.0
            jacobian[3, 3] = jacobian[4, 4] = self.tilt_weight
        return ok_all, residual, jacobian


def _scales(members, force_scale):
    """(residual scale, unknown scale) vectors of the set's 6 possible unknowns."""
    half = max(0.5 * m.inputs.geometry.pitch_diameter for m in members)
    arm = max([half] + [abs(m.arm) for m in members])
    length = min(m.problem.length_scale for m in members)
    rscale = np.array([force_scale] * 3 + [force_scale * arm] * 2 + [force_scale])
    vscale = np.array([length] * 3 + [length / arm] * 2 + [length])
    return rscale, vscale


def _norm(x) -> float:
    """The 2-norm of the vector ``x`` (as numpy.linalg.norm computes it, without its checks)."""
    return math.sqrt(float(x.dot(x)))


def _condition(a) -> float:
    """The 2-norm condition number of the square matrix ``a`` (as numpy.linalg.cond computes it:
    largest over smallest singular value; inf when singular)."""
    singular = np.linalg.svd(a, compute_uv=False)
    smallest = float(singular[-1])
    return float(singular[0]) / smallest if smallest > 0.0 else math.inf


def _newton(problem, v, speed, force_scale):
    """Newton / Levenberg-Marquardt solve of the set at a speed fraction from ``v``; the members'
    ball positions are updated in place. Returns (converged, v, iterations, merit)."""
    rscale, vscale = _scales(problem.members, force_scale)
    rscale, vscale = rscale[: problem.n], vscale[: problem.n]
    positions = [m.state.position for m in problem.members]
    ok, residual, jacobian = problem.evaluate(v, speed, positions)
    merit = _norm(residual / rscale)
    mu = 0.0
    for iteration in range(MAX_SET_ITERATIONS):
        if ok and merit <= SET_TOLERANCE:
            return True, v, iteration, merit
        jac = jacobian * vscale[None, :] / rscale[:, None]
        rhs = -residual / rscale
        accepted = False
        for _attempt in range(10):
            if mu == 0.0 and _condition(jac) < 1e12:
                step = np.linalg.solve(jac, rhs)
            else:
                mu = max(mu, 1e-6)
                jtj = jac.T @ jac
                diag = np.diag(jtj).copy()
                big = max(float(diag.max()), 1e-300)
                step = np.linalg.solve(
                    jtj + np.diag(mu * diag + 1e-15 * big + (diag == 0.0) * mu * big),
                    jac.T @ rhs,
                )
            norm = _norm(step)
            if norm > 20.0:
                step *= 20.0 / norm
            t = 1.0
            for _ls in range(12):
                trial = v + t * step * vscale
                trial_positions = [p.copy() for p in positions]
                # the full step usually succeeds: its Jacobian is that of the next iteration
                tok, tres, tjac = problem.evaluate(trial, speed, trial_positions, t == 1.0)
                tmerit = _norm(tres / rscale)
                if tok and math.isfinite(tmerit) and tmerit < (1.0 - 1e-4 * t) * merit:
                    accepted = True
                    break
                t *= 0.5
            if accepted:
                break
            mu = 1e-3 if mu == 0.0 else mu * 10.0
        if not accepted:
            return ok and merit <= 100.0 * SET_TOLERANCE, v, iteration, merit
        v = trial
        for p, tp in zip(positions, trial_positions, strict=True):
            p[:] = tp
        mu = 0.0 if t == 1.0 else mu * 0.1
        if mu < 1e-9:
            mu = 0.0
        if t == 1.0:
            ok, residual, jacobian, merit = tok, tres, tjac, tmerit
        else:
            ok, residual, jacobian = problem.evaluate(v, speed, positions)
            merit = _norm(residual / rscale)
    return ok and merit <= SET_TOLERANCE, v, MAX_SET_ITERATIONS, merit


def _with_race_control(problem, v, speed, force_scale):
    """Set solve iterated with every bearing's race-control decision until none changes. Returns
    (converged, v, iterations, merit, note)."""
    total = 0
    history = []
    note = ""
    for _ in range(MAX_RACE_CONTROL_ITERATIONS):
        ok, v, its, merit = _newton(problem, v, speed, force_scale)
        total += its
        if not ok:
            return False, v, total, merit, note
        u, w = problem.split(v)
        changed = False
        decisions = []
        for m in problem.members:
            model = m.problem.model(speed)
            states = kernels.evaluate_balls(
                m.q(u, w), m.problem.azimuth, m.state.position, m.state.control, model
            )
            decision = _race_control(states, model)
            decisions.append(decision)
            changed |= not np.array_equal(decision, m.state.inner_control)
        if not changed:
            return True, v, total, merit, note
        key = b"".join(d.tobytes() for d in decisions)
        if key in history:
            note = (
                "race control cycles between two decisions for some balls; the last solution is "
                "kept with the decision it was solved with"
            )
            return True, v, total, merit, note
        history.append(key)
        for m, decision in zip(problem.members, decisions, strict=True):
            m.state.control = kernels.race_control_rows(decision)
    note = (
        f"race control did not settle in {MAX_RACE_CONTROL_ITERATIONS} iterations; the last "
        "solution is kept with the decision it was solved with"
    )
    return True, v, total, merit, note


def _with_traction_balance(problem, v, force_scale, lubricant, relative_speed):
    """From a race-control solution at full speed: every bearing's ball speeds from its traction
    balance, iterated with the set solve to a fixed point (as the single-bearing model does).
    Returns (v, iterations, merit, note); raises BalanceFailed."""
    curve, nodes = traction_setup(lubricant)
    jacobians = [np.full((m.problem.azimuth.size, JACOBIAN_SIZE), np.nan) for m in problem.members]
    changes = []
    total = 0
    merit = math.nan
    first = True
    for iteration in range(1, MAX_TRACTION_ITERATIONS + 1):
        u, w = problem.split(v)
        change = 0.0
        for m, jac in zip(problem.members, jacobians, strict=True):
            model = m.problem.model(1.0)
            q = m.q(u, w)
            states = kernels.evaluate_balls(
                q, m.problem.azimuth, m.state.position, m.state.control, model
            )
            control, _ = traction_balance(
                m.inputs.geometry,
                model,
                states,
                m.state.position,
                q,
                m.problem.azimuth,
                m.state.control,
                curve,
                nodes,
                jac,
            )
            diff = np.abs(control - m.state.control)
            change = max(
                change,
                diff[:, kernels.CONTROL_ORBITAL].max() / relative_speed,
                diff[:, kernels.CONTROL_SPIN].max() / relative_speed,
                diff[:, kernels.CONTROL_ATTITUDE].max(),
            )
            m.state.control = control
        ok, v, its, merit = _newton(problem, v, 1.0, force_scale)
        total += its
        if not ok:
            raise BalanceFailed("no set equilibrium with the ball speeds of the traction balance")
        if first:
            first = False
            continue
        changes.append(change / TRACTION_SPEED_TOLERANCE)
        if _fixed_point_settled(changes):
            return (
                v,
                total,
                merit,
                (
                    f"ball speeds from the traction balance of every bearing, fixed point after "
                    f"{iteration} iterations"
                ),
            )
    return (
        v,
        total,
        merit,
        (
            f"ball speeds from the traction balance: the fixed point did not settle within "
            f"{MAX_TRACTION_ITERATIONS} iterations; the last iterate is kept"
        ),
    )


def _axial_static_force(member, approach):
    """(axial force [N], its derivative [N/m]) a bearing carries at rest for an axial approach
    ``approach`` [m] of its inner ring towards its own +x (no other displacement)."""
    position = np.zeros((member.problem.azimuth.size, 2))
    control = member.state.control
    member.state.control = kernels.race_control_rows(np.zeros(position.shape[0], dtype=np.bool_))
    try:
        _, r_b, j_b = member.reaction(np.array([approach, 0, 0, 0, 0.0]), 0.0, position)
    finally:
        member.state.control = control
    return -r_b[0], -j_b[0, 0]


def _approach_for(members, force):
    """Axial approach [m] at which ``members`` (same direction, same shaft) carry ``force`` [N]
    together at rest: Newton on the static load-deflection curves with the kernel's derivative,
    safeguarded by bisection."""
    lo, hi = 0.0, math.inf
    d = min(m.problem.length_scale for m in members)
    limit = 0.05 * min(m.inputs.geometry.ball_diameter for m in members)
    for _ in range(100):
        excess, slope = -force, 0.0
        for m in members:
            f, k = _axial_static_force(m, d)
            excess += f
            slope += k
        if excess < 0.0:
            lo = d
        else:
            hi = d
        if abs(excess) <= 1e-12 * force or (math.isfinite(hi) and hi - lo <= 1e-15 * hi):
            return d
        step = d - excess / slope if slope > 0.0 else math.nan
        if math.isfinite(step) and lo < step < hi:
            d = step
        elif math.isfinite(hi):
            d = 0.5 * (lo + hi)
        else:
            d = 2.0 * d
        if d > limit:
            raise NoSolutionError(
                f"a preload force of {force:g} N needs an axial approach beyond 5 % of the ball "
                "diameter: lower set.preload.force_N"
            )
    return d


def preload_offset(members, force):
    """The axial offset e [m] of a fixed-position preload that gives the preload force ``force``
    [N] at rest without external load: each group of bearings facing one way carries ``force``
    (their axial approaches d_+ and d_- at that force sum to e)."""
    plus = [m for m in members if m.sign > 0]
    minus = [m for m in members if m.sign < 0]
    approach = _approach_for(plus, force)
    if _same_bearings(plus, minus):  # a symmetric set: both groups take the same approach
        return 2.0 * approach
    return approach + _approach_for(minus, force)


def _same_bearings(first, second) -> bool:
    """True when two groups hold the same number of bearings of the same geometry."""
    return len(first) == len(second) and all(
        a.inputs.geometry == b.inputs.geometry for a, b in zip(first, second, strict=True)
    )


@dataclasses.dataclass
class SetSolution:
    """The solved set, SI. ``solutions``: each bearing's :class:`QuasiStaticSolution` in its own
    frame at its own operating point (the loads its balls carry); ``reactions`` (B, 5): force and
    moment each bearing exerts on the shaft at its ball-centre plane, shaft frame;
    ``displacements`` (B, 5): each inner ring's displacement relative to its outer ring at its
    plane, shaft frame; ``stiffness`` (B, 5, 5): each bearing's stiffness at its plane, shaft
    frame; ``set_stiffness`` (5, 5) at the load point; ``unloaded_at_rest``: names of the bearings
    with no loaded ball at rest under the case's loads; ``misalignment_moment`` (y, z) [N m]: with
    an imposed tilt (set.misalignment_deg), the moment on the shaft at the load point, from
    outside the set, that holds the tilt (None otherwise)."""

    members: list
    shaft: np.ndarray
    spring_shift: float
    offset: float
    solutions: list
    operatings: list
    reactions: np.ndarray
    displacements: np.ndarray
    stiffness: np.ndarray
    set_stiffness: np.ndarray
    iterations: int
    merit: float
    note: str
    ball_speeds: str
    ball_speeds_note: str
    unloaded_at_rest: list
    misalignment_moment: np.ndarray | None = None


def _bearing_operating(base: OperatingPoint, q, r_b) -> OperatingPoint:
    """A bearing's own operating point: the loads its balls carry (minus the reaction, own frame)
    and its inner ring's tilt imposed."""
    load = -r_b
    tilt = q[3:]
    return dataclasses.replace(
        base,
        axial_load=float(load[0]),
        radial_load=float(math.hypot(load[1], load[2])),
        radial_load_angle=float(math.atan2(load[2], load[1])) if load[1] or load[2] else 0.0,
        misalignment=float(math.hypot(tilt[0], tilt[1])),
        misalignment_axis=float(math.atan2(tilt[1], tilt[0])) if tilt.any() else 0.0,
        misalignment_frame="space",
        tilting_moment=None,
        moment_axis=0.0,
    )


@dataclasses.dataclass
class SetInputs:
    """What the set solve reads, SI: the bearings (:class:`_Member`), the set case's inputs and
    its external loads (Fx, Fy, Fz [N], My, Mz [N m] at the load point, shaft frame)."""

    bearing_set: object
    members: list
    inputs: object
    applied: np.ndarray


def set_inputs(case) -> SetInputs:
    """The :class:`SetInputs` of a set case."""
    members, inputs, applied = members_of(case)
    return SetInputs(case.bearing_set, members, inputs, applied)


def members_of(case):
    """The set's :class:`_Member` list, the set case's SI inputs and the external loads."""
    bearing_set = case.bearing_set
    inputs = to_inputs(case)
    base = inputs.operating
    applied = np.array([*bearing_set.load_force_N, *bearing_set.load_moment_Nm], dtype=float)
    preload = bearing_set.preload_force_N or 0.0
    load_scale = max(float(np.max(np.abs(applied[:3]))), preload, 1e-6)
    members = []
    for entry in bearing_set.bearings:
        # a bearing of the case's own [bearing] shares the case's inputs
        own = inputs if entry.source == "case" else to_inputs(entry.case)
        arm = (entry.position_mm - bearing_set.load_position_mm) * MM
        members.append(_Member(entry, own, base, arm, load_scale))
    return members, inputs, applied


def solve_set_state(case) -> SetSolution:
    """The quasi-static equilibrium of the bearing set of ``case`` (a Case with ``bearing_set``,
    or its :class:`SetInputs`). Raises NoSolutionError when none is found."""
    given = case if isinstance(case, SetInputs) else set_inputs(case)
    bearing_set, members, inputs, applied = (
        given.bearing_set,
        given.members,
        given.inputs,
        given.applied,
    )
    for m in members:  # a fresh start (SetInputs may be solved again)
        z = m.inputs.geometry.ball_count
        m.state = _State(
            np.zeros(5), np.zeros((z, 2)), kernels.race_control_rows(np.zeros(z, dtype=np.bool_))
        )
    operating = inputs.operating
    spring_force = None
    offset = 0.0
    if bearing_set.preload_kind == "offset":
        offset = bearing_set.preload_offset_um * 1e-6
    elif bearing_set.preload_kind == "force":
        offset = preload_offset(members, bearing_set.preload_force_N)
    elif bearing_set.preload_kind == "spring":
        spring_force = bearing_set.preload_force_N
    for m in members:
        m.offset = 0.5 * offset
        m.spring = spring_force is not None and m.entry.direction == bearing_set.spring_side
    force_scale = max(max(m.problem.force_scale for m in members), 1e-6)
    tilt = None
    if bearing_set.misalignment_deg is not None:
        tilt = np.radians(np.asarray(bearing_set.misalignment_deg, dtype=float))
    rscale, vscale = _scales(members, force_scale)
    # the tilt rows' weight makes their scaled residual the tilt error over the tilt scale
    problem = _SetProblem(members, applied, spring_force, tilt, rscale[3] / vscale[3])
    v = _initial_guess(problem, members, force_scale)
    for m in members:
        model = m.problem.model(0.0)
        m.state.position = m.problem.initial_positions(m.q(*problem.split(v)), model)
    # at rest first, then the speed (in steps when the direct solve fails)
    ok, v, total, merit, note = _with_race_control(problem, v, 0.0, force_scale)
    if not ok:
        raise NoSolutionError(_no_rest_message(bearing_set))
    unloaded_at_rest = _unloaded(problem, v, 0.0, force_scale)
    has_speed = operating.inner_ring_speed != 0.0 or operating.outer_ring_speed != 0.0
    if has_speed:
        v, total, merit, note = _speed_up(problem, v, force_scale, total, merit, note, operating)
    ball_speeds, fallback = "race_control", ""
    relative = abs(operating.inner_ring_speed - operating.outer_ring_speed)
    if inputs.simulation.quasistatic_ball_speeds == "traction" and relative > 0.0:
        saved = (v.copy(), [m.state.copy() for m in members])
        try:
            v, its, merit, note = _with_traction_balance(
                problem, v, force_scale, inputs.lubricant, relative
            )
            total += its
            ball_speeds = "traction"
        except BalanceFailed as error:
            v = saved[0]
            for m, state in zip(members, saved[1], strict=True):
                m.state = state
            fallback = (
                f"the traction balance found no steady ball speeds ({error}); the ball speeds "
                "come from race control instead"
            )
    return _packed(problem, v, offset, total, merit, note, ball_speeds, fallback, unloaded_at_rest)


def _speed_up(problem, v, force_scale, total, merit, note, operating):
    """The solution at full speed from the one at rest (directly, else by continuation)."""
    saved = (v.copy(), [m.state.copy() for m in problem.members])

    def attempt(speed):
        nonlocal v, total, merit, note, saved
        ok, trial, its, m_merit, m_note = _with_race_control(problem, v, speed, force_scale)
        total += its
        if ok:
            v, merit, note = trial, m_merit, m_note
            saved = (v.copy(), [m.state.copy() for m in problem.members])
            return True
        v = saved[0].copy()
        for m, state in zip(problem.members, saved[1], strict=True):
            m.state = state.copy()
        return False

    if attempt(1.0):
        return v, total, merit, note
    reached, step = 0.0, 0.5
    while reached < 1.0:
        trial = min(1.0, reached + step)
        if attempt(trial):
            reached, step = trial, step * 2.0
        else:
            step *= 0.5
            if step < 1e-4:
                raise NoSolutionError(
                    "the quasi-static equilibrium of the bearing set was followed up to "
                    f"{reached * operating.inner_ring_speed * 30 / math.pi:.0f} rpm and lost "
                    "beyond it: the balls' centrifugal forces and gyroscopic moments exceed what "
                    "the preload and loads can hold. Try more preload or a lower speed."
                )
    return v, total, merit, note


def _initial_guess(problem, members, force_scale):
    """A start for the set solve: the linear solution with every ball in contact at its free
    contact angle with the stiffness of a ball carrying a share of the force scale."""
    stiffness = np.zeros((problem.n, problem.n))
    preload_load = np.zeros(problem.n)
    for m in members:
        g = m.inputs.geometry
        share = force_scale / max(1.0, 0.25 * g.ball_count)
        k_n = 1.5 * m.problem.ball_stiffness ** (2.0 / 3.0) * share ** (1.0 / 3.0)
        a0 = g.free_contact_angle
        rc = g.inner_curvature_center_radius
        psi = m.problem.azimuth
        normals = np.column_stack(
            [
                np.full(psi.size, math.sin(a0)),
                math.cos(a0) * np.cos(psi),
                math.cos(a0) * np.sin(psi),
                rc * math.sin(a0) * np.sin(psi),
                -rc * math.sin(a0) * np.cos(psi),
            ]
        )
        k_b = k_n * normals.T @ normals
        stiffness[:5, :5] += m.map.T @ k_b @ m.map
        if not m.spring:  # a fixed-position offset acts like the load -k_b c_b
            preload_load[:5] -= m.map.T @ k_b[:, 0] * m.offset
        if m.spring:
            stiffness[5, :5] += k_b[0] @ m.map
            stiffness[:5, 5] += m.map.T @ k_b[:, 0]
            stiffness[5, 5] += k_b[0, 0]
    load = np.zeros(problem.n)
    load[:5] = problem.applied
    if problem.n == 6:
        load[5] = problem.spring_force
    load += preload_load
    if problem.tilt is not None:  # the imposed tilt replaces the moment balance
        stiffness[3:5, :] = 0.0
        stiffness[3, 3] = stiffness[4, 4] = 1.0
        load[3:5] = problem.tilt
    guess = np.linalg.lstsq(stiffness, load, rcond=1e-12)[0]
    return guess


def _unloaded(problem, v, speed, force_scale):
    """Names of the bearings with no ball loaded at the solution ``v``."""
    u, w = problem.split(v)
    names = []
    for m in problem.members:
        model = m.problem.model(speed)
        states = kernels.evaluate_balls(
            m.q(u, w), m.problem.azimuth, m.state.position, m.state.control, model
        )
        if float(states.contact_load[:, 0].max()) <= UNLOADED_FRACTION * force_scale:
            names.append(m.name)
    return names


def _packed(problem, v, offset, iterations, merit, note, ball_speeds, fallback, unloaded_at_rest):
    u, w = problem.split(v)
    set_jacobian = np.zeros((problem.n, problem.n))
    solutions, operatings = [], []
    reactions, displacements, stiffness = [], [], []
    shaft_load = np.array(problem.applied, dtype=float)
    for m in problem.members:
        q = m.q(u, w)
        m.state.q = q.copy()
        ok, r_b, j_b = m.reaction(q, 1.0, m.state.position)
        shaft_load += m.map.T @ r_b
        set_jacobian[:5, :5] += m.map.T @ j_b @ m.map
        if m.spring:
            set_jacobian[5, :5] += j_b[0] @ m.map
            set_jacobian[:5, 5] += m.map.T @ j_b[:, 0]
            set_jacobian[5, 5] += j_b[0, 0]
        op = _bearing_operating(m.inputs.operating, q, r_b)
        # the member's problem at the bearing's own operating point: the same geometry, ring
        # speeds (its ball models are reused), azimuths and force scale
        pack_problem = copy.copy(m.problem)
        pack_problem.operating = op
        solution = _pack(pack_problem, m.state, iterations, merit, note)
        solution.ball_speeds = ball_speeds
        solution.ball_speeds_note = fallback
        solutions.append(solution)
        operatings.append(op)
        t = mirror(m.sign)
        reactions.append(t * r_b)  # the bearing's force on the shaft, shaft frame
        displacements.append(t * q)
        stiffness.append(-(t[:, None] * j_b * t[None, :]))
    # the shaft's stiffness about the load point with any floating outer rings condensed out
    k = -set_jacobian
    if problem.n == 6:
        k = k[:5, :5] - np.outer(k[:5, 5], k[5, :5]) / k[5, 5]
    return SetSolution(
        members=problem.members,
        shaft=np.asarray(u, dtype=float).copy(),
        spring_shift=float(w),
        offset=float(offset),
        solutions=solutions,
        operatings=operatings,
        reactions=np.array(reactions),
        displacements=np.array(displacements),
        stiffness=np.array(stiffness),
        set_stiffness=k,
        iterations=iterations,
        merit=merit,
        note=note,
        ball_speeds=ball_speeds,
        ball_speeds_note=fallback,
        unloaded_at_rest=unloaded_at_rest,
        misalignment_moment=(-shaft_load[3:5] if problem.tilt is not None else None),
    )


def _no_rest_message(bearing_set) -> str:
    force = ", ".join(f"{value:g}" for value in bearing_set.load_force_N)
    return (
        f"no static equilibrium found for the bearing set ({bearing_set.describe()}) under "
        f"the force [{force}] N: the "
        "bearings cannot hold the shaft in every loaded direction. Add preload, turn a bearing "
        "round so that thrust is carried both ways, or reduce the load."
    )


def solve_set(case):
    """The quasi-static equilibrium of the bearing set of ``case`` as a Dataset with a ``bearing``
    dimension (results-schema.md, "Bearing sets"). Raises NoSolutionError."""
    from .set_result import set_dataset

    given = set_inputs(case)
    state = solve_set_state(given)
    text = given.inputs.case_text
    results = bearing_results(state, text)
    return set_dataset(case.bearing_set, state, results, given.applied, text)


def bearing_datasets(state: SetSolution, case_text: str) -> list:
    """Each bearing's single-bearing quasi-static Dataset of the solved set ``state``, at its own
    operating point (the loads its balls carry), with its friction estimates there."""
    return [result.dataset() for result in bearing_results(state, case_text)]


def bearing_results(state: SetSolution, case_text: str) -> list:
    """The :class:`solver.results.dataset.ResultArrays` of :func:`bearing_datasets`: what the set's
    Dataset stacks, without building each bearing's Dataset first."""
    from solver.results.estimates import estimate_fields

    from .result import solution_arrays

    results = []
    for member, solution, op in zip(state.members, state.solutions, state.operatings, strict=True):
        inputs = dataclasses.replace(member.inputs, operating=op)
        lubricant = inputs.lubricant if inputs.lubricant.given else None
        results.append(
            solution_arrays(
                solution,
                inputs.geometry,
                case_text,
                lubricant,
                op,
                estimates=estimate_fields(inputs, op),
            )
        )
    return results


#: The set's scalar and per-bearing variables a stiffness study keeps at each point.
STUDY_VARIABLES = (
    "axial_stiffness",
    "radial_stiffness",
    "tilt_stiffness",
    "bearing_axial_load",
    "bearing_radial_load",
    "preload_offset",
)


def set_stiffness_study(case, preload_forces_N, speeds_rpm):
    """The set's stiffness (axial, radial, tilt at the load point) and each bearing's axial and
    radial load over a grid of preload forces [N] (``set.preload.force_N``; the case's preload
    kind must be "force" or "spring") and inner-ring speeds [rpm], as a Dataset with dimensions
    ``preload_force`` [N] and ``inner_ring_speed`` [rpm] (and ``bearing``). Each point is the
    set solved as :func:`solve_set_state` solves it. Raises CaseError for a preload kind without a
    force, NoSolutionError naming the first point without a solution."""
    import xarray as xr

    from solver.errors import CaseError, Problem

    from .set_result import SET_VARIABLES

    if case.bearing_set.preload_kind not in ("force", "spring"):
        raise CaseError(
            Problem(
                "set.preload.kind",
                'a stiffness study over the preload force needs set.preload.kind = "force" or '
                f'"spring" (the case has {case.bearing_set.preload_kind!r})',
            )
        )
    forces = [float(f) for f in preload_forces_N]
    speeds = [float(s) for s in speeds_rpm]
    if not forces or not speeds or min(forces) <= 0.0 or min(speeds) < 0.0:
        raise ValueError("give at least one preload force > 0 N and one speed >= 0 rpm")
    values = {name: [] for name in STUDY_VARIABLES}
    for force in forces:
        rows = {name: [] for name in STUDY_VARIABLES}
        for speed in speeds:
            point = case.with_values(
                {"set.preload.force_N": force, "operating.inner_ring_speed_rpm": speed}
            )
            try:
                state = solve_set_state(point)
            except NoSolutionError as error:
                raise NoSolutionError(
                    f"stiffness study stopped at preload {force:g} N, {speed:g} rpm: {error}"
                ) from None
            k = state.set_stiffness
            sign = np.array([m.sign for m in state.members])
            point_values = {
                "axial_stiffness": k[0, 0],
                "radial_stiffness": 0.5 * (k[1, 1] + k[2, 2]),
                "tilt_stiffness": 0.5 * (k[3, 3] + k[4, 4]),
                "bearing_axial_load": -sign * state.reactions[:, 0],
                "bearing_radial_load": np.hypot(state.reactions[:, 1], state.reactions[:, 2]),
                "preload_offset": state.offset,
            }
            for name in STUDY_VARIABLES:
                rows[name].append(point_values[name])
        for name in STUDY_VARIABLES:
            values[name].append(rows[name])
    names = [b.name for b in case.bearing_set.bearings]
    data = {}
    for name in STUDY_VARIABLES:
        spec = SET_VARIABLES[name]
        data[name] = xr.Variable(
            ("preload_force", "inner_ring_speed", *spec.dims),
            np.asarray(values[name], dtype=float),
            spec.attrs(),
        )
    return xr.Dataset(
        data,
        coords={
            "preload_force": ("preload_force", forces, {"units": "N"}),
            "inner_ring_speed": ("inner_ring_speed", speeds, {"units": "rpm"}),
            "bearing": ("bearing", names),
        },
        attrs={"bearing_set": case.bearing_set.describe(), "case": case.to_toml()},
    )
