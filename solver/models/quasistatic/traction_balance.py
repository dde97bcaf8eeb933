"""Ball speeds from the traction balance (friction-based quasi-dynamic kinematics) instead of race
control.

For contacts fixed in place (positions, loads, contact angles and ellipses of the current
quasi-static iterate) the ball speeds are found from the friction forces themselves, the way the
dynamic model finds them at steady state:

- all balls orbit at one cage speed omega_c (the cage holds them in its pockets); each ball gets a
  circumferential pocket force P_j from the cage, and the cage is in equilibrium: sum P_j = 0 (no
  cage drag or land friction in this model);
- every ball spins steadily relative to the cage with the angular velocity w (3 components in the
  azimuth frame (e_x, e_r, e_theta)): the traction moments of its two contacts about the ball
  centre equal the rate of change of its angular momentum, omega_c e_x x J w (physics.md §2.5.4);
- P_j = -(F_theta,inner + F_theta,outer): the pocket force takes the circumferential traction.

The tractions are integrated over each Hertz ellipse with the dynamic model's kernel
(:func:`solver.physics.traction.ellipse_traction_law`, spin and Heathcote slip on the deformed
surface) and the dynamic model's local law (``lubricant.traction_model``): the case's traction
curve, or the rheology of the oil with each contact's central film (Hamrock-Dowson with the inlet
thermal reduction, at the entrainment speed of rolling at the iterate's cage speed) and transit
time, evaluated in the cage frame (ball centre at rest, rings turning at
omega_ring - omega_c about the bearing axis, the inner ring about its displaced centre).

Every ball's w and omega_c are solved together by Newton's method on the bordered system
(:func:`solve_balance`, in numba): 3 moment equations per ball in its own w and omega_c, and
sum P_j = 0. Its Jacobian is block diagonal with one bordering row and column: per ball a
finite-difference 3x3 block dR/dw, a column dR/d omega_c, a row dF_theta/dw and a corner
dF_theta/d omega_c, solved by eliminating each ball's block (Schur complement on the cage speed).
The blocks are kept from one iteration, and one balance of the quasi-static fixed point, to the next
while the residual falls fast, and recomputed otherwise. Where this does not converge, the previous
method is the fall-back: the cage speed bracketed and found by Brent's method as the root of
sum P_j, every ball's w solved on its own by Newton's method at each trial cage speed
(SciPy's hybrid method where that stalls).

The result per ball is written into the quasi-static model's kinematics record
(:data:`kernels.TRACTION_BALANCE`): omega_c, spin speed and attitude (the meridian-plane part of w;
its small e_theta part is reported in the ball's angular velocity), the gyroscopic moment along
e_theta, and the transverse tractions of both contacts, which then enter the ball and ring force
balances in place of the race-control friction split. The quasi-static solver iterates positions
and tractions to a fixed point (:mod:`.solver`). Balls without any loaded contact keep their
race-control kinematics and carry no pocket force.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np
from numba import njit
from scipy import optimize

from solver.physics.hertz_fast import contact_ellipse_fast, curvature_sum_and_difference_fast
from solver.physics.rheology import RHEOLOGY_SIZE, film_and_rolling_force
from solver.physics.traction import (
    CONTACT_SIZE,
    CT_CURVATURE,
    CT_LOAD,
    CT_NORMAL,
    CT_POINT,
    CT_ROLLING,
    CT_SEMI_MAJOR,
    CT_SEMI_MINOR,
    CURVE_SIZE,
    KIN_BALL_CENTRE,
    KIN_BALL_OMEGA,
    KIN_RING_OMEGA,
    KIN_RING_POINT,
    KIN_RING_VELOCITY,
    KIN_SIZE,
    LAW_RHEOLOGY,
    LAW_SLIP_CURVE,
    NODE_BATCH,
    NODE_BATCH_ROWS,
    TR_FORCE,
    TR_MOMENT_BALL,
    TRACTION_OUT_SIZE,
    deformed_surface_curvature,
    ellipse_quadrature,
    ellipse_traction_into,
    split_ellipse_rule,
    traction_curve_parameters,
)

from . import kernels

#: Ellipse rules and slip regularisation [m/s]: the dynamic model's rheology-law rule (the split
#: rule of solver.physics.traction.split_ellipse_rule with (points along the rolling direction,
#: strips per piece) ``SPLIT_RULE_COUNTS``) and its slip regularisation
#: (solver.models.dynamic.options.DEFAULT_ELLIPSE_RULE, DEFAULT_SPLIT_COUNTS,
#: SimulationOptions.friction_regularisation; not imported: the dynamic model imports this package
#: for its start). With the slip-curve law the product rule with ``QUADRATURE`` (points along the
#: rolling direction, strips across the groove); the dynamic model uses two points along the
#: rolling direction instead of four, which changes the traction by far less than the start
#: transient.
QUADRATURE = (4, 8)
SPLIT_RULE_COUNTS = (3, 3)
SLIP_REGULARISATION = 1.0e-3
BALL_TOLERANCE = 1e-11  # ball moment residual, relative to its larger load times D / 2
MAX_BALL_ITERATIONS = 50
CAGE_SPEED_TOLERANCE = 1e-10  # relative


#: Traction-law array of the traction balance (float64, ``TRACTION_SIZE``): the local law
#: (solver.physics.traction.LAW_*), the slip curve (``CURVE_SIZE`` slots) and the rheology
#: (``RHEOLOGY_SIZE`` slots, solver.physics.rheology).
TL_LAW = 0
TL_CURVE = 1
TL_RHEOLOGY = TL_CURVE + CURVE_SIZE
TRACTION_SIZE = TL_RHEOLOGY + RHEOLOGY_SIZE

#: Contact records carry, after the ``CONTACT_SIZE`` slots of solver.physics.traction, the central
#: film [m] and transit time b / u_e [s] of the contact (used by the rheology only).
CT_FILM = CONTACT_SIZE
CT_TRANSIT = CONTACT_SIZE + 1
RECORD_SIZE = CONTACT_SIZE + 2


def traction_setup(lubricant):
    """(traction-law array (``TRACTION_SIZE``), quadrature nodes) for a
    :class:`solver.inputs.LubricantInputs`: its ``traction_model``, traction curve and rheology."""
    traction = np.zeros(TRACTION_SIZE)
    rheological = lubricant.traction_model == "rheology"
    traction[TL_LAW] = LAW_RHEOLOGY if rheological else LAW_SLIP_CURVE
    traction[TL_CURVE : TL_CURVE + CURVE_SIZE] = _curve_parameters(lubricant.traction.values())
    traction[TL_RHEOLOGY:] = lubricant.rheology_array()
    return traction, _nodes(rheological).copy()


def _floats(values) -> tuple:
    """Parameters as a tuple of floats, as the dynamic model passes them to
    ellipse_traction_into (numba then compiles one variant of it for both models)."""
    return tuple(float(v) for v in values)


@functools.lru_cache(maxsize=16)
def _curve_parameters(properties: tuple[float, float, float, float]) -> np.ndarray:
    """traction_curve_parameters of the curve properties, solved once per curve (read-only)."""
    parameters = traction_curve_parameters(*properties)
    parameters.setflags(write=False)
    return parameters


@functools.cache
def _nodes(rheological: bool) -> np.ndarray:
    """The ellipse rule of the law (module constants: made once, read-only)."""
    nodes = np.ascontiguousarray(
        split_ellipse_rule(*SPLIT_RULE_COUNTS) if rheological else ellipse_quadrature(*QUADRATURE)
    )
    nodes.setflags(write=False)
    return nodes


@njit(cache=True)
def _contact_films(contacts, states, model, rheology):
    """Central film and transit time of each loaded contact into ``contacts`` (CT_FILM,
    CT_TRANSIT): entrainment u_e = r |omega_ring - omega_c| of rolling at the contact radius r
    about the bearing axis (omega_c: the iterate's orbital speed), Hamrock-Dowson film with the
    inlet thermal reduction (solver.physics.rheology.film_and_rolling_force), R_x = D (1 -+ gamma)
    / 2, ellipticity a / b, transit b / u_e. ``model``: kernels.BallModel at full speed."""
    D = model.ball_diameter
    for j in range(contacts.shape[0]):
        omega_c = states.orbital_speed[j]
        for k in range(2):
            omega_ring = model.inner_ring_speed if k == 0 else model.outer_ring_speed
            rec = contacts[j, k]
            load, a, b = rec[CT_LOAD], rec[CT_SEMI_MAJOR], rec[CT_SEMI_MINOR]
            entrainment = abs(rec[CT_POINT + 1]) * abs(omega_ring - omega_c)
            if not (load > 0.0 and a > 0.0 and b > 0.0 and entrainment > 0.0):
                continue
            gamma = D * math.cos(states.contact_angle[j, k]) / model.pitch_diameter
            r_x = 0.5 * D * (1.0 - gamma if k == 0 else 1.0 + gamma)
            p_max = 1.5 * load / (math.pi * a * b)
            film, _, _ = film_and_rolling_force(
                entrainment, 0.0, load, r_x, a / b, p_max, model.effective_modulus, rheology
            )
            rec[CT_FILM] = film
            rec[CT_TRANSIT] = b / entrainment


@njit(cache=True)
def _fill_contact_records(
    states, position, q, azimuth, model, inner_curvature, outer_curvature, contacts, ring_centre
):
    """Contact records [inner, outer] into ``contacts`` (Z, 2, RECORD_SIZE; zeros in, films left 0)
    and inner-ring centres into ``ring_centre`` (Z, 3), in each ball's azimuth frame: components
    (x, r, theta) of the inertial frame (origin at the outer ring centre) along (e_x, e_r, e_theta)
    at the ball's azimuth. For the iterate ``states`` (kernels.evaluate_balls), ball ``position``
    (Z, 2) relative to the outer groove curvature centre and ring displacement ``q`` (dx, dy, dz,
    theta_y, theta_z); ``model``: kernels.BallModel; curvatures of the deformed contact surfaces
    [1/m]. The contact points lie on the ball surface at D/2 - delta/2 from its centre, the
    ellipses come from hertz_fast."""
    D = model.ball_diameter
    e_mod = model.effective_modulus
    for j in range(azimuth.shape[0]):
        centre_x = model.outer_center_axial + position[j, 0]
        centre_r = model.outer_center_radius + position[j, 1]
        psi = azimuth[j]
        ring_centre[j, 0] = q[0]
        ring_centre[j, 1] = q[1] * math.cos(psi) + q[2] * math.sin(psi)
        ring_centre[j, 2] = -q[1] * math.sin(psi) + q[2] * math.cos(psi)
        for k in range(2):
            is_inner = k == 0
            load = states.contact_load[j, k]
            alpha = states.contact_angle[j, k]
            deflection = max(states.contact_deflection[j, k], 0.0)
            sign = -1.0 if is_inner else 1.0  # inner contact on the -u(alpha) side
            n0 = sign * math.sin(alpha)
            n1 = sign * math.cos(alpha)
            reach = 0.5 * D - 0.5 * deflection
            rec = contacts[j, k]
            rec[CT_POINT] = centre_x + reach * n0
            rec[CT_POINT + 1] = centre_r + reach * n1
            rec[CT_POINT + 2] = 0.0
            rec[CT_NORMAL] = n0
            rec[CT_NORMAL + 1] = n1
            rec[CT_NORMAL + 2] = 0.0
            rec[CT_ROLLING] = 0.0
            rec[CT_ROLLING + 1] = 0.0
            rec[CT_ROLLING + 2] = 1.0
            rec[CT_LOAD] = load
            rec[CT_CURVATURE] = inner_curvature if is_inner else outer_curvature
            if load > 0.0:
                conformity = model.inner_conformity if is_inner else model.outer_conformity
                gamma = D * math.cos(alpha) / model.pitch_diameter
                s, f = curvature_sum_and_difference_fast(D, conformity, gamma, is_inner)
                a, b, _, _ = contact_ellipse_fast(load, s, f, e_mod)
                rec[CT_SEMI_MAJOR] = a
                rec[CT_SEMI_MINOR] = b


class Balance(NamedTuple):
    """Fixed data of one traction balance (:func:`traction_balance`), read by the compiled
    kernels; Z balls, each in its own azimuth frame (module docstring)."""

    contacts: np.ndarray  # (Z, 2, RECORD_SIZE) contact records [inner, outer]
    ring_centres: np.ndarray  # (Z, 3) inner-ring centre [m]
    centres: np.ndarray  # (Z, 3) ball centre [m]
    law: int  # local traction law (solver.physics.traction.LAW_*)
    curve: tuple  # (CURVE_SIZE) slip-curve parameters, floats
    rheology: tuple  # (RHEOLOGY_SIZE) rheology parameters (solver.physics.rheology), floats
    nodes: np.ndarray  # ellipse quadrature nodes (traction_setup)
    active: np.ndarray  # (Z) bool: the ball has a loaded contact
    moment_scales: np.ndarray  # (Z) larger contact load times D / 2 [N m]
    omega_inner: float  # inner-ring speed [rad/s] about +x
    omega_outer: float  # outer-ring speed [rad/s] about +x
    inertia: float  # ball moment of inertia [kg m^2]
    u_reg: float  # slip regularisation [m/s]
    force_scale: float  # scale of the sum of circumferential tractions [N]


class BalanceWork(NamedTuple):
    """Workspace of the balance kernels for Z balls (:func:`_balance_work`): the cage-frame
    kinematics records, the scratch of ellipse_traction_into and the residuals written by
    :func:`_balance_residuals`."""

    kin: np.ndarray  # (Z, 2, KIN_SIZE) kinematics records [inner, outer] in the cage frame
    batch: np.ndarray  # (NODE_BATCH_ROWS, NODE_BATCH) scratch of ellipse_traction_into
    out: np.ndarray  # (TRACTION_OUT_SIZE) scratch of ellipse_traction_into
    res: np.ndarray  # (Z, 3) moment residuals [N m]
    f_theta: np.ndarray  # (Z) circumferential tractions [N]
    forces: np.ndarray  # (Z, 2, 3) traction forces [N]


@njit(cache=True)
def _balance_work(z):
    """BalanceWork for ``z`` balls (kinematics records and residuals zero)."""
    return BalanceWork(
        np.zeros((z, 2, KIN_SIZE)),
        np.empty((NODE_BATCH_ROWS, NODE_BATCH)),
        np.empty(TRACTION_OUT_SIZE),
        np.zeros((z, 3)),
        np.zeros(z),
        np.zeros((z, 2, 3)),
    )


@njit(cache=True)
def _ball_moments(w, omega_c, j, balance, kin, work, res, forces):
    """Moment residual [N m] into ``res`` (3) of ball j spinning at w relative to the cage, both
    traction forces [N] into ``forces`` (2, 3); returns its circumferential traction force [N]
    (sum of both contacts). ``kin`` (2, KIN_SIZE): the ball's kinematics records [inner, outer]
    in the cage frame at omega_c; ``work``: its ``batch`` and ``out`` are the scratch of
    ellipse_traction_into."""
    res[0] = 0.0
    res[1] = 0.0
    res[2] = 0.0
    for k in range(2):
        record = kin[k]
        contact = balance.contacts[j, k]
        record[KIN_BALL_OMEGA] = w[0]
        record[KIN_BALL_OMEGA + 1] = w[1]
        record[KIN_BALL_OMEGA + 2] = w[2]
        ellipse_traction_into(
            contact,
            record,
            balance.law,
            balance.curve,
            balance.rheology,
            contact[CT_FILM],
            contact[CT_TRANSIT],
            balance.u_reg,
            balance.nodes,
            work.out,
            work.batch,
        )
        for m in range(3):
            res[m] += work.out[TR_MOMENT_BALL + m]
            forces[k, m] = work.out[TR_FORCE + m]
    # minus d(J w_abs)/dt = omega_c e_x x J w, components (x, r, theta) = J omega_c (0, -w_t, w_r)
    res[1] += balance.inertia * omega_c * w[2]
    res[2] -= balance.inertia * omega_c * w[1]
    return forces[0, 2] + forces[1, 2]


@njit(cache=True)
def _ball_residual(w, omega_c, j, balance, work):
    """Moment residual [N m] (3) of ball j spinning at w relative to the cage, and its
    circumferential traction force [N] (sum of both contacts), plus both traction forces (2, 3),
    as new arrays. ``work``: a one-ball BalanceWork whose ``kin[0]`` holds ball j's cage frame at
    omega_c (:func:`_cage_frame`)."""
    res = np.zeros(3)
    forces = np.zeros((2, 3))
    f_theta = _ball_moments(w, omega_c, j, balance, work.kin[0], work, res, forces)
    return res, f_theta, forces


@njit(cache=True)
def _solve3(a, r):
    """Solution x of a x = -r for a 3x3 matrix (Cramer's rule); (x, False) when singular."""
    c00 = a[1, 1] * a[2, 2] - a[1, 2] * a[2, 1]
    c01 = a[1, 2] * a[2, 0] - a[1, 0] * a[2, 2]
    c02 = a[1, 0] * a[2, 1] - a[1, 1] * a[2, 0]
    det = a[0, 0] * c00 + a[0, 1] * c01 + a[0, 2] * c02
    x = np.zeros(3)
    scale = np.max(np.abs(a)) ** 3
    if scale == 0.0 or abs(det) <= 1e-14 * scale:
        return x, False
    inv = np.empty((3, 3))
    inv[0, 0] = c00
    inv[1, 0] = c01
    inv[2, 0] = c02
    inv[0, 1] = a[0, 2] * a[2, 1] - a[0, 1] * a[2, 2]
    inv[1, 1] = a[0, 0] * a[2, 2] - a[0, 2] * a[2, 0]
    inv[2, 1] = a[0, 1] * a[2, 0] - a[0, 0] * a[2, 1]
    inv[0, 2] = a[0, 1] * a[1, 2] - a[0, 2] * a[1, 1]
    inv[1, 2] = a[0, 2] * a[1, 0] - a[0, 0] * a[1, 2]
    inv[2, 2] = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    for i in range(3):
        x[i] = -(inv[i, 0] * r[0] + inv[i, 1] * r[1] + inv[i, 2] * r[2]) / det
    return x, True


@njit(cache=True)
def solve_ball_spin(w0, omega_c, j, balance):
    """Angular velocity w (3) of ball j of ``balance`` relative to the cage at cage speed omega_c
    [rad/s] from its moment balance, starting from w0. Returns (w, circumferential traction [N],
    traction forces (2, 3) [N], ok)."""
    work = _balance_work(1)
    _cage_frame(work.kin[0], omega_c, j, balance)
    w = w0.copy()
    res, f_theta, forces = _ball_residual(w, omega_c, j, balance, work)
    norm = math.sqrt(res[0] ** 2 + res[1] ** 2 + res[2] ** 2)
    tol = BALL_TOLERANCE * balance.moment_scales[j]
    jac = np.empty((3, 3))
    for _ in range(MAX_BALL_ITERATIONS):
        if norm <= tol:
            return w, f_theta, forces, True
        speed = math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
        h = 1e-7 * max(speed, abs(omega_c), 1.0)
        for m in range(3):
            wp = w.copy()
            wp[m] += h
            rp, _, _ = _ball_residual(wp, omega_c, j, balance, work)
            for r in range(3):
                jac[r, m] = (rp[r] - res[r]) / h
        step, solvable = _solve3(jac, res)
        if not solvable:
            return w, f_theta, forces, False
        # keep a step within 5 % of the ball's speed
        limit = 0.05 * max(speed, 1.0)
        size = math.sqrt(step[0] ** 2 + step[1] ** 2 + step[2] ** 2)
        if size > limit:
            step *= limit / size
        t = 1.0
        accepted = False
        for _ls in range(30):
            wn = w + t * step
            rn, fn, forces_n = _ball_residual(wn, omega_c, j, balance, work)
            nn = math.sqrt(rn[0] ** 2 + rn[1] ** 2 + rn[2] ** 2)
            if nn < (1.0 - 1e-4 * t) * norm or nn <= tol:
                accepted = True
                break
            t *= 0.5
        if not accepted:
            return w, f_theta, forces, norm <= 1e3 * tol
        w, res, f_theta, forces, norm = wn, rn, fn, forces_n, nn
    return w, f_theta, forces, norm <= 1e3 * tol


#: Columns of the bordered Jacobian kept per ball by :func:`solve_balance` (``JACOBIAN_SIZE``):
#: A^-1 (3 x 3, row-major) with A = dR/dw the ball's moment Jacobian, A^-1 c with c = dR/d omega_c,
#: r = dF/dw and s = dF/d omega_c, F the ball's circumferential traction.
JB_INVERSE = 0
JB_CAGE = 9
JB_ROW = 12
JB_CORNER = 15
JACOBIAN_SIZE = 16
MAX_BALANCE_ITERATIONS = 40
SLOW_CONTRACTION = 0.25  # a reused Jacobian is refreshed when the merit falls by less
#: A solve whose merit (sum of squared scaled residuals) is still above STALL_MERIT and fell by
#: less than a factor 1 / STALL_FACTOR over its last STALL_WINDOW accepted steps is given up: it
#: crawls along step-limited, line-searched steps and does not reach the tolerance. The slowest
#: converging start seen, the 218 heavy case with an isothermal film (from race control), fell by a
#: factor 17 in its first 6 steps (0.287 -> 0.0167), and the converging solves of the six shipped
#: cases at 2 000-30 000 rpm (8 speeds each, with continuation) by more than 100 in any 5 steps
#: while above 1e-8; the crawling ones (the shipped 218 heavy case: 0.156 -> 0.135 in 6 steps) ran
#: to MAX_BALANCE_ITERATIONS before failing. Only the time to fail changes: the fall-back starts
#: afresh from the same warm start.
STALL_WINDOW = 6
STALL_FACTOR = 0.25
STALL_MERIT = 1e-8
BALL_STEP_LIMIT = 0.05  # largest change of a ball's spin in one step, relative to its speed
CAGE_STEP_LIMIT = 0.05  # largest change of the cage speed in one step, relative to the ring's


@njit(cache=True)
def _cage_frame(kin, omega_c, j, balance):
    """Kinematics records ``kin`` (2, KIN_SIZE) [inner, outer] of ball j in the cage frame at cage
    speed omega_c (the module docstring; the ball's angular velocity is set per evaluation).
    Slots not written here stay as given (zeros)."""
    ring_centre = balance.ring_centres[j]
    centre = balance.centres[j]
    kin_i = kin[0]
    kin_o = kin[1]
    for m in range(3):
        kin_i[KIN_BALL_CENTRE + m] = centre[m]
        kin_o[KIN_BALL_CENTRE + m] = centre[m]
        kin_i[KIN_RING_POINT + m] = ring_centre[m]
    kin_i[KIN_RING_VELOCITY + 1] = omega_c * ring_centre[2]
    kin_i[KIN_RING_VELOCITY + 2] = -omega_c * ring_centre[1]
    kin_i[KIN_RING_OMEGA] = balance.omega_inner - omega_c
    kin_o[KIN_RING_OMEGA] = balance.omega_outer - omega_c


@njit(cache=True)
def _balance_residuals(w, omega_c, balance, work):
    """Moment residuals ``work.res`` (Z, 3), circumferential tractions ``work.f_theta`` (Z) and
    traction forces ``work.forces`` (Z, 2, 3) of every active ball at spins ``w`` (Z, 3) and
    cage speed omega_c; ``work.kin`` is left in the cage frame at omega_c."""
    for j in range(w.shape[0]):
        if not balance.active[j]:
            continue
        _cage_frame(work.kin[j], omega_c, j, balance)
        work.f_theta[j] = _ball_moments(
            w[j], omega_c, j, balance, work.kin[j], work, work.res[j], work.forces[j]
        )


@njit(cache=True)
def _balance_merit(work, balance):
    """Sum of squares of the scaled residuals of ``work``: ball moments over their moment scales,
    the sum of the circumferential tractions over ``balance.force_scale``."""
    total = 0.0
    excess = 0.0
    for j in range(work.res.shape[0]):
        if balance.active[j]:
            for m in range(3):
                total += (work.res[j, m] / balance.moment_scales[j]) ** 2
            excess += work.f_theta[j]
    return total + (excess / balance.force_scale) ** 2


@njit(cache=True)
def _balls_settled(work, balance):
    """True when every active ball's moment residual in ``work`` is within BALL_TOLERANCE of its
    scale."""
    for j in range(work.res.shape[0]):
        if balance.active[j]:
            res = work.res[j]
            norm = math.sqrt(res[0] ** 2 + res[1] ** 2 + res[2] ** 2)
            if not norm <= BALL_TOLERANCE * balance.moment_scales[j]:
                return False
    return True


@njit(cache=True)
def _balance_jacobian(w, omega_c, balance, work, jacobian):
    """Finite-difference blocks of the bordered Jacobian at (w, omega_c) into ``jacobian``
    (Z, JACOBIAN_SIZE), from the residuals ``work.res`` and ``work.f_theta`` there (steps as in
    :func:`solve_ball_spin`). ``work.kin`` must hold the cage frame at omega_c and is left so.
    Returns False when a ball's moment Jacobian is singular."""
    a = np.empty((3, 3))
    c = np.empty(3)
    rp = np.empty(3)
    fp = np.empty((2, 3))
    wp = np.empty(3)
    shifted = np.zeros((2, KIN_SIZE))
    res = work.res
    f_theta = work.f_theta
    for j in range(w.shape[0]):
        if not balance.active[j]:
            continue
        wj = w[j]
        speed = math.sqrt(wj[0] ** 2 + wj[1] ** 2 + wj[2] ** 2)
        h = 1e-7 * max(speed, abs(omega_c), 1.0)
        for m in range(3):
            wp[:] = wj
            wp[m] += h
            f_p = _ball_moments(wp, omega_c, j, balance, work.kin[j], work, rp, fp)
            for r in range(3):
                a[r, m] = (rp[r] - res[j, r]) / h
            jacobian[j, JB_ROW + m] = (f_p - f_theta[j]) / h
        h_c = 1e-7 * max(abs(omega_c), 1.0)
        shifted[:] = work.kin[j]
        _cage_frame(shifted, omega_c + h_c, j, balance)
        f_p = _ball_moments(wj, omega_c + h_c, j, balance, shifted, work, rp, fp)
        for r in range(3):
            c[r] = (rp[r] - res[j, r]) / h_c
        jacobian[j, JB_CORNER] = (f_p - f_theta[j]) / h_c
        # A^-1 by cofactors; _solve3 gives -A^-1 r, so solve for the unit vectors
        for m in range(3):
            unit = np.zeros(3)
            unit[m] = -1.0
            col, solvable = _solve3(a, unit)
            if not solvable:
                return False
            for r in range(3):
                jacobian[j, JB_INVERSE + 3 * r + m] = col[r]
        for r in range(3):
            jacobian[j, JB_CAGE + r] = (
                jacobian[j, JB_INVERSE + 3 * r] * c[0]
                + jacobian[j, JB_INVERSE + 3 * r + 1] * c[1]
                + jacobian[j, JB_INVERSE + 3 * r + 2] * c[2]
            )
    return True


@njit(cache=True)
def _balance_step(work, balance, jacobian, step):
    """Newton step of the bordered system at the residuals of ``work``: the balls' spin changes
    into ``step`` (Z, 3); returns the cage-speed change (NaN when the system is singular)."""
    res = work.res
    f_theta = work.f_theta
    active = balance.active
    numerator = 0.0
    denominator = 0.0
    for j in range(res.shape[0]):
        if not active[j]:
            continue
        numerator += f_theta[j]
        denominator += jacobian[j, JB_CORNER]
        for r in range(3):
            x = (
                jacobian[j, JB_INVERSE + 3 * r] * res[j, 0]
                + jacobian[j, JB_INVERSE + 3 * r + 1] * res[j, 1]
                + jacobian[j, JB_INVERSE + 3 * r + 2] * res[j, 2]
            )
            step[j, r] = x
            numerator -= jacobian[j, JB_ROW + r] * x
            denominator -= jacobian[j, JB_ROW + r] * jacobian[j, JB_CAGE + r]
    if not (denominator != 0.0 and math.isfinite(numerator) and math.isfinite(denominator)):
        return math.nan
    d_cage = -numerator / denominator
    for j in range(res.shape[0]):
        if active[j]:
            for r in range(3):
                step[j, r] = -(step[j, r] + jacobian[j, JB_CAGE + r] * d_cage)
    return d_cage


@njit(cache=True)
def solve_balance(w, omega_c, balance, jacobian, refresh, forces):
    """Every active ball's spin w (Z, 3) relative to the cage and the cage speed omega_c [rad/s]
    of ``balance`` solved together by Newton's method on the bordered system: each ball's moment
    balance (3 equations in its own w and omega_c) and the cage's, sum of the circumferential
    tractions = 0. The Jacobian's blocks (:func:`_balance_jacobian`) are kept in ``jacobian``
    between iterations and calls while the merit falls by at least a factor SLOW_CONTRACTION per
    step, and refreshed otherwise (``refresh`` True: start with a fresh one). Steps are limited to
    BALL_STEP_LIMIT of a ball's speed and CAGE_STEP_LIMIT of the ring speed for the cage, then
    halved until the merit falls.

    Converged when every ball's moment residual is within BALL_TOLERANCE of its scale and the
    cage-speed step is within CAGE_SPEED_TOLERANCE of omega_c; given up when the merit stalls
    (STALL_WINDOW). ``w`` in: the start, out: the solution; ``forces`` (Z, 2, 3) out: the
    traction forces there. Returns (omega_c, converged); not converged leaves ``w`` at the last
    iterate."""
    z = w.shape[0]
    work = BalanceWork(
        np.zeros((z, 2, KIN_SIZE)),
        np.empty((NODE_BATCH_ROWS, NODE_BATCH)),
        np.empty(TRACTION_OUT_SIZE),
        np.zeros((z, 3)),
        np.zeros(z),
        forces,
    )
    # the trial point shares the kinematics records and the traction scratch
    trial = BalanceWork(
        work.kin, work.batch, work.out, np.zeros((z, 3)), np.zeros(z), np.zeros((z, 2, 3))
    )
    trial_w = w.copy()
    step = np.zeros((z, 3))
    active = balance.active
    ring = abs(balance.omega_inner - balance.omega_outer)
    _balance_residuals(w, omega_c, balance, work)
    merit = _balance_merit(work, balance)
    if not math.isfinite(merit):
        return omega_c, False
    merits = np.empty(MAX_BALANCE_ITERATIONS + 1)  # the merit at the start and after each step
    merits[0] = merit
    steps = 0
    fresh = False
    for _ in range(MAX_BALANCE_ITERATIONS):
        if refresh:
            if not _balance_jacobian(w, omega_c, balance, work, jacobian):
                return omega_c, False
            refresh = False
            fresh = True
        d_cage = _balance_step(work, balance, jacobian, step)
        if not math.isfinite(d_cage):
            if fresh:
                return omega_c, False
            refresh = True
            continue
        settled = _balls_settled(work, balance)
        if settled and abs(d_cage) <= CAGE_SPEED_TOLERANCE * abs(omega_c) + 1e-12:
            return omega_c, True
        scale = 1.0
        if abs(d_cage) > CAGE_STEP_LIMIT * ring:
            scale = CAGE_STEP_LIMIT * ring / abs(d_cage)
        for j in range(z):
            if active[j]:
                speed = math.sqrt(w[j, 0] ** 2 + w[j, 1] ** 2 + w[j, 2] ** 2)
                size = math.sqrt(step[j, 0] ** 2 + step[j, 1] ** 2 + step[j, 2] ** 2)
                limit = BALL_STEP_LIMIT * max(speed, 1.0)
                if size * scale > limit:
                    scale = limit / size
        t = scale
        accepted = False
        trial_merit = merit
        for _ls in range(30):
            for j in range(z):
                for r in range(3):
                    trial_w[j, r] = w[j, r] + t * step[j, r]
            _balance_residuals(trial_w, omega_c + t * d_cage, balance, trial)
            trial_merit = _balance_merit(trial, balance)
            if trial_merit < (1.0 - 1e-4 * t) * merit or (
                _balls_settled(trial, balance)
                and abs(t * d_cage) <= CAGE_SPEED_TOLERANCE * abs(omega_c) + 1e-12
            ):
                accepted = True
                break
            t *= 0.5
        if not accepted:
            # the kinematics records in kin are those of the last trial: back to omega_c
            _balance_residuals(w, omega_c, balance, work)
            if fresh:
                return omega_c, False
            refresh = True
            continue
        omega_c += t * d_cage
        w[:] = trial_w
        work.res[:] = trial.res
        work.f_theta[:] = trial.f_theta
        work.forces[:] = trial.forces
        if trial_merit > SLOW_CONTRACTION * merit:
            refresh = True
        merit = trial_merit
        fresh = False
        steps += 1
        merits[steps] = merit
        if (
            steps >= STALL_WINDOW
            and merit > STALL_MERIT
            and merit > STALL_FACTOR * merits[steps - STALL_WINDOW]
        ):
            return omega_c, False
    return omega_c, False


def _ball_spin(j, omega_c, w, balance):
    """(w, circumferential traction, forces) of ball j of ``balance``: the jitted Newton solve,
    and where it stalls (near a fold of the traction curve's falling branch) SciPy's hybrid
    method from its last iterate. BalanceFailed when neither converges."""
    wj, f_theta, forces, ok = solve_ball_spin(w[j], omega_c, j, balance)
    if ok:
        return wj, f_theta, forces
    work = _balance_work(1)
    _cage_frame(work.kin[0], omega_c, j, balance)

    def residual(x):
        return _ball_residual(np.asarray(x, dtype=float), omega_c, j, balance, work)[0]

    for start in (wj, w[j]):
        sol = optimize.root(residual, start, method="hybr", options={"xtol": 1e-13})
        if np.max(np.abs(residual(sol.x))) <= 1e3 * BALL_TOLERANCE * balance.moment_scales[j]:
            _, f_theta, forces = _ball_residual(sol.x, omega_c, j, balance, work)
            return sol.x, f_theta, forces
    raise BalanceFailed(
        f"at cage speed {omega_c:.6g} rad/s the spin of ball {j} has no steady balance: its "
        "tractions reach the falling branch of the traction law, where the ball slides"
    )


def pocket_force_sum(omega_c, w, balance, forces_out):
    """Sum over the balls of ``balance`` of the pocket forces P_j = -(circumferential traction)
    [N] at cage speed omega_c; ``w`` (Z, 3) warm start in, solution out; ``forces_out``
    (Z, 2, 3) the traction forces."""
    total = 0.0
    for j in range(w.shape[0]):
        if not balance.active[j]:
            continue
        w[j], f_theta, forces_out[j] = _ball_spin(j, omega_c, w, balance)
        total -= f_theta
    return total


class BalanceFailed(RuntimeError):
    """The traction balance found no cage speed or ball spin (message: why)."""


def traction_balance(
    geometry, model, states, position, q, azimuth, control, traction, nodes, jacobian=None
):
    """New kinematics records (Z, CONTROL_SIZE) from the traction balance of the iterate
    (``states`` from kernels.evaluate_balls with the records ``control`` it was solved with;
    ``model``: kernels.BallModel at full speed). Also returns the pocket forces P_j [N] (Z).
    Raises BalanceFailed when no balance is found.

    The balls' spins and the cage speed are solved together (:func:`solve_balance`); where that
    does not converge, the cage speed is bracketed and found by Brent's method, each trial cage
    speed solving every ball on its own (:func:`pocket_force_sum`). ``jacobian`` (Z,
    JACOBIAN_SIZE), optional: the bordered Jacobian of a previous call for the same bearing
    (a nearby iterate), reused and updated in place; None or all NaN: computed afresh."""
    z = azimuth.size
    contacts = np.zeros((z, 2, RECORD_SIZE))
    ring_centres = np.zeros((z, 3))
    D = geometry.ball_diameter
    _fill_contact_records(
        states,
        position,
        np.asarray(q, dtype=float),
        azimuth,
        model,
        deformed_surface_curvature(geometry.inner_groove_radius, D),
        deformed_surface_curvature(geometry.outer_groove_radius, D),
        contacts,
        ring_centres,
    )
    if int(traction[TL_LAW]) == LAW_RHEOLOGY:
        _contact_films(contacts, states, model, traction[TL_RHEOLOGY:])
    centres = np.zeros((z, 3))
    centres[:, 0] = geometry.outer_curvature_center_axial + position[:, 0]
    centres[:, 1] = geometry.outer_curvature_center_radius + position[:, 1]
    loads = states.contact_load
    active = (loads > 0.0).any(axis=1)
    if not active.any():
        return control.copy(), np.zeros(z)
    inertia = geometry.ball_inertia
    moment_scales = np.maximum(loads.max(axis=1), 1e-12) * 0.5 * geometry.ball_diameter
    # warm start: the kinematics the iterate was solved with (relative to the cage)
    omega_c0 = float(np.mean(states.orbital_speed[active]))
    w = np.zeros((z, 3))
    if control[0, kernels.CONTROL_MODE] == kernels.TRACTION_BALANCE:
        omega_r = control[:, kernels.CONTROL_SPIN]
        beta = control[:, kernels.CONTROL_ATTITUDE]
        w[:, 2] = control[:, kernels.CONTROL_YAW]
    else:
        beta, omega_r = states.attitude_angle, states.spin_speed
    w[:, 0] = omega_r * np.cos(beta)
    w[:, 1] = -omega_r * np.sin(beta)
    forces = np.zeros((z, 2, 3))
    omega_i, omega_o = model.inner_ring_speed, model.outer_ring_speed
    if jacobian is None:
        jacobian = np.full((z, JACOBIAN_SIZE), np.nan)
    balance = Balance(
        contacts,
        ring_centres,
        centres,
        int(traction[TL_LAW]),
        _floats(traction[TL_CURVE : TL_CURVE + CURVE_SIZE]),
        _floats(traction[TL_RHEOLOGY:]),
        nodes,
        active,
        moment_scales,
        omega_i,
        omega_o,
        inertia,
        SLIP_REGULARISATION,
        float(loads.max()),
    )
    newton_w = w.copy()
    omega_c, converged = solve_balance(
        newton_w, omega_c0, balance, jacobian, bool(np.isnan(jacobian[active]).any()), forces
    )
    if converged:
        return _balance_records(
            control, states, active, newton_w, forces, omega_c, omega_i, omega_o, inertia
        )
    jacobian[:] = np.nan

    def excess(omega_c):
        return pocket_force_sum(omega_c, w, balance, forces)

    span = 0.002 * max(abs(omega_i - omega_o), 1e-9)
    lo, hi = omega_c0 - span, omega_c0 + span
    f_lo, f_hi = excess(lo), excess(hi)
    for _ in range(12):
        if f_lo * f_hi <= 0.0:
            break
        span *= 2.0
        # step towards the side where the pocket forces change sign
        if (f_lo > 0.0) == (f_hi > f_lo):
            lo, f_lo = omega_c0 - span, excess(omega_c0 - span)
        else:
            hi, f_hi = omega_c0 + span, excess(omega_c0 + span)
    else:
        raise BalanceFailed(
            f"no cage speed within {span / abs(omega_c0):.0%} of the race-control one balances "
            "the balls' circumferential tractions"
        )
    if not (math.isfinite(f_lo) and math.isfinite(f_hi)):
        raise BalanceFailed(
            "the balls' circumferential tractions are not finite near the cage speed"
        )
    try:
        omega_c = optimize.brentq(
            excess, lo, hi, xtol=CAGE_SPEED_TOLERANCE * abs(omega_c0) + 1e-12, rtol=1e-14
        )
    except (ValueError, RuntimeError) as error:
        # each evaluation starts its inner solve from the previous one, so a bracket found above
        # can lose its sign change when brentq evaluates its ends again
        raise BalanceFailed(f"the cage speed could not be bracketed ({error})") from None
    excess(omega_c)  # leaves w and forces at the root
    return _balance_records(control, states, active, w, forces, omega_c, omega_i, omega_o, inertia)


@njit(cache=True)
def _balance_records(control, states, active, w, forces, omega_c, omega_i, omega_o, inertia):
    """(kinematics records (Z, CONTROL_SIZE), pocket forces (Z)) of a solved balance: spins ``w``
    (Z, 3) relative to the cage, traction forces ``forces`` (Z, 2, 3), cage speed omega_c. Balls
    without a loaded contact orbit with the cage and keep their race-control spin."""
    out = control.copy()
    pocket = np.zeros(control.shape[0])
    sign = -1.0 if omega_i - omega_o >= 0.0 else 1.0  # omega_R < 0 for a faster inner ring
    for j in range(control.shape[0]):
        row = out[j]
        row[kernels.CONTROL_MODE] = kernels.TRACTION_BALANCE
        row[kernels.CONTROL_ORBITAL] = omega_c
        if not active[j]:
            free_spin, free_beta = states.spin_speed[j], states.attitude_angle[j]
            row[kernels.CONTROL_SPIN] = free_spin
            row[kernels.CONTROL_ATTITUDE] = free_beta
            row[kernels.CONTROL_YAW] = 0.0
            row[kernels.CONTROL_GYRO] = -inertia * omega_c * free_spin * math.sin(free_beta)
            row[kernels.CONTROL_TAU_INNER] = 0.0
            row[kernels.CONTROL_TAU_OUTER] = 0.0
            continue
        fi, fo = forces[j, 0], forces[j, 1]
        pocket[j] = -(fi[2] + fo[2])
        wx, wr = w[j, 0], w[j, 1]
        omega_r = sign * math.hypot(wx, wr)
        beta = math.atan2(-wr / omega_r, wx / omega_r) if omega_r != 0.0 else 0.0
        alpha_i, alpha_o = states.contact_angle[j, 0], states.contact_angle[j, 1]
        row[kernels.CONTROL_SPIN] = omega_r
        row[kernels.CONTROL_ATTITUDE] = beta
        row[kernels.CONTROL_YAW] = w[j, 2]
        row[kernels.CONTROL_GYRO] = inertia * omega_c * wr
        row[kernels.CONTROL_TAU_INNER] = fi[0] * math.cos(alpha_i) - fi[1] * math.sin(alpha_i)
        row[kernels.CONTROL_TAU_OUTER] = -fo[0] * math.cos(alpha_o) + fo[1] * math.sin(alpha_o)
    return out, pocket


__all__ = ["BalanceFailed", "traction_balance", "traction_setup"]
