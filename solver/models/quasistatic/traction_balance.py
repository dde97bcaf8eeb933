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
omega_ring - omega_c about the bearing axis, the inner ring about its displaced centre). For each
trial cage speed every ball's w is found by Newton's method (finite-difference 3x3 Jacobian); the
cage speed is the root of sum P_j.

The result per ball is written into the quasi-static model's kinematics record
(:data:`kernels.TRACTION_BALANCE`): omega_c, spin speed and attitude (the meridian-plane part of w;
its small e_theta part is reported in the ball's angular velocity), the gyroscopic moment along
e_theta, and the transverse tractions of both contacts, which then enter the ball and ring force
balances in place of the race-control friction split. The quasi-static solver iterates positions
and tractions to a fixed point (:mod:`.solver`). Balls without any loaded contact keep their
race-control kinematics and carry no pocket force.
"""

from __future__ import annotations

import math

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
    TR_FORCE,
    TR_MOMENT_BALL,
    TRACTION_OUT_SIZE,
    deformed_surface_curvature,
    ellipse_quadrature,
    ellipse_traction_law,
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
    traction[TL_CURVE : TL_CURVE + CURVE_SIZE] = traction_curve_parameters(
        *lubricant.traction.values()
    )
    traction[TL_RHEOLOGY:] = lubricant.rheology_array()
    nodes = np.ascontiguousarray(
        split_ellipse_rule(*SPLIT_RULE_COUNTS) if rheological else ellipse_quadrature(*QUADRATURE)
    )
    return traction, nodes


def _contact_films(geometry, contacts, states, omega_inner, omega_outer, rheology):
    """Central film and transit time of each loaded contact into ``contacts`` (CT_FILM,
    CT_TRANSIT): entrainment u_e = r |omega_ring - omega_c| of rolling at the contact radius r
    about the bearing axis (omega_c: the iterate's orbital speed), Hamrock-Dowson film with the
    inlet thermal reduction (solver.physics.rheology.film_and_rolling_force), R_x = D (1 -+ gamma)
    / 2, ellipticity a / b, transit b / u_e."""
    D = geometry.ball_diameter
    for j in range(contacts.shape[0]):
        omega_c = states.orbital_speed[j]
        for k, omega_ring in ((0, omega_inner), (1, omega_outer)):
            rec = contacts[j, k]
            load, a, b = rec[CT_LOAD], rec[CT_SEMI_MAJOR], rec[CT_SEMI_MINOR]
            entrainment = abs(rec[CT_POINT + 1]) * abs(omega_ring - omega_c)
            if not (load > 0.0 and a > 0.0 and b > 0.0 and entrainment > 0.0):
                continue
            gamma = D * math.cos(states.contact_angle[j, k]) / geometry.pitch_diameter
            r_x = 0.5 * D * (1.0 - gamma if k == 0 else 1.0 + gamma)
            p_max = 1.5 * load / (math.pi * a * b)
            film, _, _ = film_and_rolling_force(
                entrainment, 0.0, load, r_x, a / b, p_max, geometry.effective_modulus, rheology
            )
            rec[CT_FILM] = film
            rec[CT_TRANSIT] = b / entrainment


def contact_records(geometry, states, position, q, azimuth):
    """Contact records (Z, 2, RECORD_SIZE; films left 0) [inner, outer] and inner-ring centres
    (Z, 3) in each ball's azimuth frame: components (x, r, theta) of the inertial frame (origin at
    the outer ring centre) along (e_x, e_r, e_theta) at the ball's azimuth. For the iterate
    ``states`` (kernels.BallStates), ball ``position`` (Z, 2) relative to the outer groove
    curvature centre and ring displacement ``q`` (dx, dy, dz, theta_y, theta_z); the contact points
    lie on the ball surface at D/2 - delta/2 from its centre, the ellipses come from hertz_fast."""
    z = azimuth.size
    D = geometry.ball_diameter
    contacts = np.zeros((z, 2, RECORD_SIZE))
    ring_centre = np.zeros((z, 3))
    e_mod = geometry.effective_modulus
    curvature = (
        deformed_surface_curvature(geometry.inner_groove_radius, D),
        deformed_surface_curvature(geometry.outer_groove_radius, D),
    )
    for j in range(z):
        centre_x = geometry.outer_curvature_center_axial + position[j, 0]
        centre_r = geometry.outer_curvature_center_radius + position[j, 1]
        psi = azimuth[j]
        ring_centre[j] = (q[0], q[1] * math.cos(psi) + q[2] * math.sin(psi), 0.0)
        ring_centre[j, 2] = -q[1] * math.sin(psi) + q[2] * math.cos(psi)
        for k, is_inner in ((0, True), (1, False)):
            load = states.contact_load[j, k]
            alpha = states.contact_angle[j, k]
            deflection = max(states.contact_deflection[j, k], 0.0)
            sign = -1.0 if is_inner else 1.0  # inner contact on the -u(alpha) side
            n = (sign * math.sin(alpha), sign * math.cos(alpha), 0.0)
            reach = 0.5 * D - 0.5 * deflection
            rec = contacts[j, k]
            rec[CT_POINT] = centre_x + reach * n[0]
            rec[CT_POINT + 1] = centre_r + reach * n[1]
            rec[CT_POINT + 2] = 0.0
            rec[CT_NORMAL : CT_NORMAL + 3] = n
            rec[CT_ROLLING : CT_ROLLING + 3] = (0.0, 0.0, 1.0)
            rec[CT_LOAD] = load
            rec[CT_CURVATURE] = curvature[k]
            if load > 0.0:
                conformity = geometry.inner_conformity if is_inner else geometry.outer_conformity
                gamma = D * math.cos(alpha) / geometry.pitch_diameter
                s, f = curvature_sum_and_difference_fast(D, conformity, gamma, is_inner)
                a, b, _, _ = contact_ellipse_fast(load, s, f, e_mod)
                rec[CT_SEMI_MAJOR] = a
                rec[CT_SEMI_MINOR] = b
    return contacts, ring_centre


@njit(cache=True)
def _ball_residual(w, omega_c, contact_i, contact_o, kin_i, kin_o, traction, u_reg, nodes, inertia):
    """Moment residual [N m] (3) of one ball spinning at w relative to the cage, and its
    circumferential traction force [N] (sum of both contacts), plus both traction forces (2, 3)."""
    out = np.empty(TRACTION_OUT_SIZE)
    res = np.zeros(3)
    forces = np.zeros((2, 3))
    for k in range(2):
        kin = kin_i if k == 0 else kin_o
        contact = contact_i if k == 0 else contact_o
        kin[KIN_BALL_OMEGA] = w[0]
        kin[KIN_BALL_OMEGA + 1] = w[1]
        kin[KIN_BALL_OMEGA + 2] = w[2]
        ellipse_traction_law(
            contact,
            kin,
            int(traction[TL_LAW]),
            traction[TL_CURVE : TL_CURVE + CURVE_SIZE],
            traction[TL_RHEOLOGY:],
            contact[CT_FILM],
            contact[CT_TRANSIT],
            u_reg,
            nodes,
            out,
        )
        for m in range(3):
            res[m] += out[TR_MOMENT_BALL + m]
            forces[k, m] = out[TR_FORCE + m]
    # minus d(J w_abs)/dt = omega_c e_x x J w, components (x, r, theta) = J omega_c (0, -w_t, w_r)
    res[1] += inertia * omega_c * w[2]
    res[2] -= inertia * omega_c * w[1]
    return res, forces[0, 2] + forces[1, 2], forces


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
def solve_ball_spin(
    w0,
    omega_c,
    omega_inner,
    omega_outer,
    contact_i,
    contact_o,
    ring_centre,
    centre,
    traction,
    u_reg,
    nodes,
    inertia,
    moment_scale,
):
    """Angular velocity w (3) of one ball relative to the cage at cage speed omega_c [rad/s] from
    its moment balance, starting from w0. Returns (w, circumferential traction [N], traction
    forces (2, 3) [N], ok)."""
    kin_i = np.zeros(KIN_SIZE)
    kin_o = np.zeros(KIN_SIZE)
    for kin in (kin_i, kin_o):
        kin[KIN_BALL_CENTRE] = centre[0]
        kin[KIN_BALL_CENTRE + 1] = centre[1]
        kin[KIN_BALL_CENTRE + 2] = centre[2]
    # inner ring: turns at omega_i - omega_c about its own (displaced) centre c; in the cage frame
    # that centre moves at -omega_c e_x x c
    kin_i[KIN_RING_POINT] = ring_centre[0]
    kin_i[KIN_RING_POINT + 1] = ring_centre[1]
    kin_i[KIN_RING_POINT + 2] = ring_centre[2]
    kin_i[KIN_RING_VELOCITY + 1] = omega_c * ring_centre[2]
    kin_i[KIN_RING_VELOCITY + 2] = -omega_c * ring_centre[1]
    kin_i[KIN_RING_OMEGA] = omega_inner - omega_c
    kin_o[KIN_RING_OMEGA] = omega_outer - omega_c
    w = w0.copy()
    res, f_theta, forces = _ball_residual(
        w, omega_c, contact_i, contact_o, kin_i, kin_o, traction, u_reg, nodes, inertia
    )
    norm = math.sqrt(res[0] ** 2 + res[1] ** 2 + res[2] ** 2)
    tol = BALL_TOLERANCE * moment_scale
    jac = np.empty((3, 3))
    for _ in range(MAX_BALL_ITERATIONS):
        if norm <= tol:
            return w, f_theta, forces, True
        speed = math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
        h = 1e-7 * max(speed, abs(omega_c), 1.0)
        for m in range(3):
            wp = w.copy()
            wp[m] += h
            rp, _, _ = _ball_residual(
                wp, omega_c, contact_i, contact_o, kin_i, kin_o, traction, u_reg, nodes, inertia
            )
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
            rn, fn, forces_n = _ball_residual(
                wn, omega_c, contact_i, contact_o, kin_i, kin_o, traction, u_reg, nodes, inertia
            )
            nn = math.sqrt(rn[0] ** 2 + rn[1] ** 2 + rn[2] ** 2)
            if nn < (1.0 - 1e-4 * t) * norm or nn <= tol:
                accepted = True
                break
            t *= 0.5
        if not accepted:
            return w, f_theta, forces, norm <= 1e3 * tol
        w, res, f_theta, forces, norm = wn, rn, fn, forces_n, nn
    return w, f_theta, forces, norm <= 1e3 * tol


def _kinematics(omega_c, omega_inner, omega_outer, ring_centre, centre):
    """Kinematics records (inner, outer) of one ball in the cage frame (module docstring); the
    ball's angular velocity is filled in per evaluation."""
    kin_i = np.zeros(KIN_SIZE)
    kin_o = np.zeros(KIN_SIZE)
    for kin in (kin_i, kin_o):
        kin[KIN_BALL_CENTRE : KIN_BALL_CENTRE + 3] = centre
    kin_i[KIN_RING_POINT : KIN_RING_POINT + 3] = ring_centre
    kin_i[KIN_RING_VELOCITY + 1] = omega_c * ring_centre[2]
    kin_i[KIN_RING_VELOCITY + 2] = -omega_c * ring_centre[1]
    kin_i[KIN_RING_OMEGA] = omega_inner - omega_c
    kin_o[KIN_RING_OMEGA] = omega_outer - omega_c
    return kin_i, kin_o


def _ball_spin(
    j,
    omega_c,
    w,
    omega_inner,
    omega_outer,
    contacts,
    ring_centres,
    centres,
    traction,
    nodes,
    inertia,
    moment_scales,
):
    """(w, circumferential traction, forces) of ball j: the jitted Newton solve, and where it
    stalls (near a fold of the traction curve's falling branch) SciPy's hybrid method from its
    last iterate. BalanceFailed when neither converges."""
    args = (
        omega_c,
        omega_inner,
        omega_outer,
        contacts[j, 0],
        contacts[j, 1],
        ring_centres[j],
        centres[j],
        traction,
        SLIP_REGULARISATION,
        nodes,
        inertia,
        moment_scales[j],
    )
    wj, f_theta, forces, ok = solve_ball_spin(w[j], *args)
    if ok:
        return wj, f_theta, forces
    kin_i, kin_o = _kinematics(omega_c, omega_inner, omega_outer, ring_centres[j], centres[j])

    def residual(x):
        return _ball_residual(
            np.asarray(x, dtype=float),
            omega_c,
            contacts[j, 0],
            contacts[j, 1],
            kin_i,
            kin_o,
            traction,
            SLIP_REGULARISATION,
            nodes,
            inertia,
        )[0]

    for start in (wj, w[j]):
        sol = optimize.root(residual, start, method="hybr", options={"xtol": 1e-13})
        if np.max(np.abs(residual(sol.x))) <= 1e3 * BALL_TOLERANCE * moment_scales[j]:
            _, f_theta, forces = _ball_residual(
                sol.x,
                omega_c,
                contacts[j, 0],
                contacts[j, 1],
                kin_i,
                kin_o,
                traction,
                SLIP_REGULARISATION,
                nodes,
                inertia,
            )
            return sol.x, f_theta, forces
    raise BalanceFailed(
        f"at cage speed {omega_c:.6g} rad/s the spin of ball {j} has no steady balance: its "
        "tractions reach the falling branch of the traction law, where the ball slides"
    )


def pocket_force_sum(
    omega_c,
    w,
    omega_inner,
    omega_outer,
    contacts,
    ring_centres,
    centres,
    traction,
    nodes,
    inertia,
    moment_scales,
    active,
    forces_out,
):
    """Sum over the balls of the pocket forces P_j = -(circumferential traction) [N] at cage speed
    omega_c; ``w`` (Z, 3) warm start in, solution out; ``forces_out`` (Z, 2, 3) the traction
    forces."""
    total = 0.0
    for j in range(w.shape[0]):
        if not active[j]:
            continue
        w[j], f_theta, forces_out[j] = _ball_spin(
            j,
            omega_c,
            w,
            omega_inner,
            omega_outer,
            contacts,
            ring_centres,
            centres,
            traction,
            nodes,
            inertia,
            moment_scales,
        )
        total -= f_theta
    return total


class BalanceFailed(RuntimeError):
    """The traction balance found no cage speed or ball spin (message: why)."""


def traction_balance(geometry, model, states, position, q, azimuth, control, traction, nodes):
    """New kinematics records (Z, CONTROL_SIZE) from the traction balance of the iterate
    (``states`` from kernels.evaluate_balls with the records ``control`` it was solved with).
    Also returns the pocket forces P_j [N] (Z). Raises BalanceFailed when no balance is found."""
    z = azimuth.size
    contacts, ring_centres = contact_records(geometry, states, position, q, azimuth)
    if int(traction[TL_LAW]) == LAW_RHEOLOGY:
        _contact_films(
            geometry,
            contacts,
            states,
            model.inner_ring_speed,
            model.outer_ring_speed,
            traction[TL_RHEOLOGY:],
        )
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
        for j in range(z):
            w[j] = _stored_w(control[j])
    else:
        beta, omega_r = states.attitude_angle, states.spin_speed
        w[:, 0] = omega_r * np.cos(beta)
        w[:, 1] = -omega_r * np.sin(beta)
    forces = np.zeros((z, 2, 3))
    omega_i, omega_o = model.inner_ring_speed, model.outer_ring_speed

    def excess(omega_c):
        return pocket_force_sum(
            omega_c,
            w,
            omega_i,
            omega_o,
            contacts,
            ring_centres,
            centres,
            traction,
            nodes,
            inertia,
            moment_scales,
            active,
            forces,
        )

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
    pocket = np.zeros(z)
    out = control.copy()
    for j in range(z):
        if not active[j]:
            continue
        alpha_i, alpha_o = states.contact_angle[j]
        fi, fo = forces[j, 0], forces[j, 1]
        pocket[j] = -(fi[2] + fo[2])
        wx, wr, wt = w[j]
        sign = -1.0 if omega_i - omega_o >= 0.0 else 1.0  # omega_R < 0 for a faster inner ring
        omega_r = sign * math.hypot(wx, wr)
        beta = math.atan2(-wr / omega_r, wx / omega_r) if omega_r != 0.0 else 0.0
        out[j, kernels.CONTROL_MODE] = kernels.TRACTION_BALANCE
        out[j, kernels.CONTROL_ORBITAL] = omega_c
        out[j, kernels.CONTROL_SPIN] = omega_r
        out[j, kernels.CONTROL_ATTITUDE] = beta
        out[j, kernels.CONTROL_YAW] = wt
        out[j, kernels.CONTROL_GYRO] = inertia * omega_c * wr
        out[j, kernels.CONTROL_TAU_INNER] = fi[0] * math.cos(alpha_i) - fi[1] * math.sin(alpha_i)
        out[j, kernels.CONTROL_TAU_OUTER] = -fo[0] * math.cos(alpha_o) + fo[1] * math.sin(alpha_o)
    # balls without contact: orbit with the cage, keep their race-control spin
    for j in range(z):
        if not active[j]:
            out[j, kernels.CONTROL_MODE] = kernels.TRACTION_BALANCE
            out[j, kernels.CONTROL_ORBITAL] = omega_c
            out[j, kernels.CONTROL_SPIN] = states.spin_speed[j]
            out[j, kernels.CONTROL_ATTITUDE] = states.attitude_angle[j]
            out[j, kernels.CONTROL_YAW] = 0.0
            out[j, kernels.CONTROL_GYRO] = (
                -inertia * omega_c * states.spin_speed[j] * math.sin(states.attitude_angle[j])
            )
            out[j, kernels.CONTROL_TAU_INNER] = 0.0
            out[j, kernels.CONTROL_TAU_OUTER] = 0.0
    return out, pocket


def _stored_w(row) -> np.ndarray:
    """w (relative to the cage, azimuth frame) of a TRACTION_BALANCE record."""
    omega_r, beta = row[kernels.CONTROL_SPIN], row[kernels.CONTROL_ATTITUDE]
    return np.array([omega_r * math.cos(beta), -omega_r * math.sin(beta), row[kernels.CONTROL_YAW]])


__all__ = ["BalanceFailed", "traction_balance", "traction_setup"]
