"""Ball–race traction and damped normal force kernels of the dynamic model.

physics.md §2.6.4 and §2.6.6. Everything is SI (m, s, N, rad). Vectors are 3-component float64
arrays in one common Cartesian frame of the caller's choice (the dynamic model uses the inertial
frame); the kernels never change frames.

Traction curve (ADORE-type, 4 parameters)
    mu(u) = (A + B u) exp(-C u) + D, u = slip speed >= 0 [m/s], stored as a float64 array
    ``curve`` of length ``CURVE_SIZE`` (``CURVE_A`` ... ``CURVE_D``).
    :func:`traction_curve_parameters` builds it from (mu_zero, mu_max, slip_at_max, mu_infinity);
    :func:`constant_traction_parameters` gives a Coulomb law mu(u) = mu.

Friction regularisation
    The local shear is tau = -mu(u) p dv / sqrt(u^2 + u_reg^2) (u = |dv|). With mu(0) = 0 (the
    usual ADORE curve) this is smooth and u_reg hardly matters; with mu(0) > 0 it makes the force
    continuous through zero slip (slope mu(0) p / u_reg there). ``u_reg = 0`` is allowed (no
    regularisation; tau = 0 at u = 0).

Contact description ``contact`` (float64, length ``CONTACT_SIZE``)
    ``CT_POINT`` (3): contact centre P [m] (mid-plane of the deformed zone).
    ``CT_NORMAL`` (3): unit normal n at P, from the ball centre towards the race (the outward ball
        normal, physics.md §2.6.3 n-hat). The normal force on the ball, -Q n, is NOT part of the
        traction kernels' output.
    ``CT_ROLLING`` (3): rolling direction t1 (along the minor axis b; re-orthogonalised to n here).
        The transverse direction is t2 = n x t1 (major axis a, across the groove).
    ``CT_SEMI_MAJOR``: a [m] (along t2). ``CT_SEMI_MINOR``: b [m] (along t1).
    ``CT_LOAD``: Q [N] (>= 0; 0 gives no traction).
    ``CT_CURVATURE``: 1/R_d [1/m] (>= 0), curvature across the groove of the deformed contact
        surface, R_d = 2 r D / (2 r + D) (:func:`deformed_surface_curvature`); 0 = flat contact.
    The surface point at contact coordinates (xi, eta) is p = P + xi t1 + eta t2 + z(eta) n with
    z(eta) = sqrt(R_d^2 - eta^2) - R_d (the surface bends towards the ball centre).

Kinematics ``kinematics`` (float64, length ``KIN_SIZE``; inertial velocities)
    ``KIN_BALL_CENTRE`` (3) c_b [m]; ``KIN_BALL_VELOCITY`` (3) [m/s]; ``KIN_BALL_OMEGA`` (3)
    [rad/s];
    ``KIN_RING_POINT`` (3) any point c_r fixed to the ring, e.g. its centre [m];
    ``KIN_RING_VELOCITY`` (3) velocity of that point [m/s]; ``KIN_RING_OMEGA`` (3) [rad/s].
    Surface velocities at p: ball v_b + w_b x (p - c_b), ring v_r + w_r x (p - c_r). The slip dv
    (ball minus ring) is resolved into rolling (t1) and transverse (t2) components; its component
    along n is the approach rate of the undeformed, overlapping rigid bodies, which the elastic
    deformation takes up, and is dropped. The transverse component is laid along the local tangent
    of the curved surface, t2' = cos(phi) t2 - sin(phi) n with sin(phi) = eta / R_d, so that
    dv = v1 t1 + v2 t2' lies in the local tangent plane. (Projecting the full rigid-body difference
    on the tilted local plane instead would turn part of the approach rate, ~ xi * omega_roll, into
    a spurious transverse slip, antisymmetric in xi * eta and as large as the Heathcote slip.)

Output ``out`` (float64, length ``TRACTION_OUT_SIZE``, overwritten)
    ``TR_FORCE`` (3): traction force on the ball [N] (the ring gets minus this).
    ``TR_MOMENT_BALL`` (3): moment of the traction on the ball about the ball centre c_b [N m].
    ``TR_MOMENT_POINT`` (3): moment of the traction about the contact centre P [N m]; the moment
        on the ring about a ring point c_r is -((P - c_r) x F + M_P).
    ``TR_SLIP`` (3): slip velocity (ball minus ring) at P, tangential part [m/s].
    ``TR_SLIP_SPEED``: |slip| at P [m/s]. ``TR_SPIN``: spin speed (w_b - w_r) . n [rad/s].
    ``TR_ENTRAINMENT``: entrainment speed 0.5 |v_ball,t + v_ring,t| at P [m/s].
    ``TR_POWER``: friction power dissipated in the contact, -sum(tau . dv dA) >= 0 [W].
    ``TR_POWER_SLIDING``: -F . s_0, the work rate of the traction force on the relative velocity
    s_0 of the two bodies at the contact centre [W]; ``TR_POWER_SPIN``: -M_P . Omega from the
    relative rotation Omega (spin, and the rolling-axis part that makes the differential slip)
    [W]. Their sum is the power the traction takes out of the two rigid bodies (the node velocity
    difference is s_0 + Omega x r); it equals ``TR_POWER`` up to the normal components that the
    local tangent planes drop.

Quadrature on the contact ellipse (:func:`ellipse_quadrature`)
    Strips across the major axis (Gauss–Jacobi, weight 1 - y^2) times Gauss points along the
    rolling direction (Gauss–Chebyshev of the 2nd kind, weight sqrt(1 - t^2)), x = sqrt(1 - y^2) t.
    The Hertz pressure p = p_max sqrt(1 - x^2 - y^2) = p_max sqrt(1 - y^2) sqrt(1 - t^2) is then
    exactly the rule's weight, so the pressure integrates to Q to rounding error for any node
    count. Node table columns: ``NODE_ROLLING`` x = xi/b, ``NODE_TRANSVERSE`` y = eta/a,
    ``NODE_AREA`` area weight on the unit disc, ``NODE_LOAD`` load fraction p dA / Q (sum = 1),
    ``NODE_PRESSURE`` p / p_max = sqrt(1 - x^2 - y^2), ``NODE_UNIFORM`` a second area weight on
    the same nodes that integrates the uniform measure (the plain area) exactly: interpolatory
    weights along the strip (exact for polynomials in t of degree n_rolling - 1) and across the
    strips (weight sqrt(1 - y^2), exact to degree n_transverse - 1). Nodes of one strip are
    consecutive.

Rheology on the ellipse
    The rheological stress is written tau = tau_L(p) s with the limiting shear stress tau_L = tau_L0
    + Lambda p and the saturation s = tau / tau_L in [0, 1). So tau dA = s (tau_L0 dA + Lambda p
    dA): the first part is integrated with ``NODE_UNIFORM`` and the second with the pressure
    weight ``NODE_LOAD``. Where the film is saturated (s = 1, reached within a few mm/s of slip)
    and not yet softened by shear heating, both parts are then exact for any node count;
    pressure-weighting the tau_L0 dA part instead (tau_L0 / p times the pressure) integrates an
    edge singularity and loses up to 9 % of the area with two points along the rolling direction.
    The thermal softening of solver.physics.rheology (step 6) divides each node's isothermal
    saturation s_iso by 1 + (c h_c / (8 k)) tau_L s_iso u (tau_L s_iso u: the node's isothermal
    shear power per area), in the same vectorised loop.

Split rule (:func:`split_ellipse_rule`)
    Because the rheological stress saturates within a few mm/s of slip, its rolling component
    changes sign almost as a jump across the groove where the rolling slip v1(eta) = s01 + o2
    z(eta) - on eta does (the lines of pure rolling), and fixed strips integrate that jump only to
    O(1 / strips). The split rule finds the zeros of v1 in (-a, a) per contact (exactly: a line
    meets a circle, :func:`_rolling_slip_zeros`) and puts ``strips_per_piece``
    Gauss-Legendre strips on each of the (up to three) pieces of the major axis between them,
    with ``n_rolling`` Gauss-Chebyshev points along each strip (the weights of the fixed rule
    along the strip). The strip weights of each piece are scaled so that its plain area (weight
    sqrt(1 - y^2)) and its load (weight 1 - y^2) come out exactly. The nodes move continuously
    with the contact state (a piece shrinks to nothing before it disappears; where the two zeros
    have not appeared yet, the pieces meet at the point where they will), so the integral has no
    jumps. The kernels tell the two tables apart by their column count (``NODE_COLUMNS`` or
    ``SPLIT_COLUMNS``).

Node batches (:func:`ellipse_traction_into`)
    The nodes are integrated a batch at a time (a scratch array of ``NODE_BATCH_ROWS`` rows, the
    ``NB_*`` layout below): first the nodes' geometry and weights are put into the batch (strip
    and piece terms once per strip and piece), then the local law is evaluated at every node of
    the batch in one loop with no dependence between nodes and no call into the C maths library
    (exp and log of :mod:`solver.physics.lanes`), which LLVM vectorises (8 nodes per instruction
    with AVX-512), then the nodes' contributions are summed in node order. The rheology's Eyring
    stress tau_0 asinh(x) is taken as tau_0 ln(2 x) in that loop, its form for x = eta gamma_dot
    / tau_0 > 1e3, which holds at 60-70 % of the nodes on the catalogue's running states; the
    other nodes are redone with the full law after it. The result does not depend on the
    batch's capacity.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy import optimize, special

from .lanes import exp_lanes, log_lanes
from .rheology import (
    EYRING_LARGE_FROM,
    RH_EYRING_STRESS,
    RH_LIMITING_SLOPE,
    RH_LIMITING_STRESS,
    RH_PRESSURE_VISCOSITY,
    contact_constants,
    eyring_asinh,
    eyring_asinh_large,
    eyring_log_argument,
    saturation_from_eyring,
    softening_constant,
)

# ---- traction-curve parameter array ------------------------------------------------------------
CURVE_A = 0  # mu_zero - mu_infinity
CURVE_B = 1  # [s/m]
CURVE_C = 2  # [s/m]
CURVE_D = 3  # mu_infinity
CURVE_SIZE = 4

# ---- contact description -----------------------------------------------------------------------
CT_POINT = 0
CT_NORMAL = 3
CT_ROLLING = 6
CT_SEMI_MAJOR = 9
CT_SEMI_MINOR = 10
CT_LOAD = 11
CT_CURVATURE = 12
CONTACT_SIZE = 13

# ---- body kinematics ---------------------------------------------------------------------------
KIN_BALL_CENTRE = 0
KIN_BALL_VELOCITY = 3
KIN_BALL_OMEGA = 6
KIN_RING_POINT = 9
KIN_RING_VELOCITY = 12
KIN_RING_OMEGA = 15
KIN_SIZE = 18

# ---- traction output ---------------------------------------------------------------------------
TR_FORCE = 0
TR_MOMENT_BALL = 3
TR_MOMENT_POINT = 6
TR_SLIP = 9
TR_SLIP_SPEED = 12
TR_SPIN = 13
TR_ENTRAINMENT = 14
TR_POWER = 15
TR_POWER_SLIDING = 16
TR_POWER_SPIN = 17
TRACTION_OUT_SIZE = 18

# ---- local traction laws of ellipse_traction_law -------------------------------------------------
LAW_SLIP_CURVE = 0  # mu(|dv|) of the 4-parameter curve, times the local pressure
LAW_RHEOLOGY = 1  # shear stress of solver.physics.rheology.shear_stress

# ---- quadrature node table columns ---------------------------------------------------------------
NODE_ROLLING = 0
NODE_TRANSVERSE = 1
NODE_AREA = 2
NODE_LOAD = 3
NODE_PRESSURE = 4
NODE_UNIFORM = 5
NODE_COLUMNS = 6

# ---- split rule table columns (:func:`split_ellipse_rule`; SPLIT_COLUMNS != NODE_COLUMNS) -------
SPLIT_T = 0  # node t along the rolling direction (Gauss-Chebyshev 2nd kind)
SPLIT_T_LOAD = 1  # its weight for the pressure-weighted integral (weight sqrt(1 - t^2))
SPLIT_T_UNIFORM = 2  # its weight for the plain integral over t in [-1, 1]
SPLIT_T_PRESSURE = 3  # sqrt(1 - t^2)
SPLIT_Y = 4  # Gauss-Legendre node on [-1, 1] for each piece across the groove
SPLIT_Y_WEIGHT = 5  # its weight
SPLIT_COUNTS = 6  # row 0: points along the rolling direction; row 1: strips per piece
SPLIT_COLUMNS = 7

# ---- node batch of ellipse_traction_into: float64 (NODE_BATCH_ROWS, capacity in nodes) -------
NB_XI = 0  # rolling coordinate xi [m]
NB_ETA = 1  # transverse coordinate eta [m]
NB_Z = 2  # z(eta) of the curved surface [m]
NB_SIN = 3  # sin(phi) of the local tangent t2'
NB_COS = 4  # cos(phi)
NB_PRESSURE = 5  # p / p_max
NB_LOAD = 6  # load fraction p dA / Q
NB_UNIFORM = 7  # plain-area fraction dA / (a b)
NB_FACTOR = 8  # g [N s/m] of the local law, tau dA = g dv
NB_V1 = 9  # rolling slip v1 [m/s]
NB_V2 = 10  # transverse slip v2 [m/s]
NB_U2 = 11  # |dv|^2 [m^2/s^2]
NB_LOG_ARGUMENT = 12  # ln x of the rheology's Eyring law (solver.physics.rheology)
NODE_BATCH_ROWS = 13
NODE_BATCH = 64  # nodes in a batch of the kernels' callers (the default rules have <= 32)

DEFAULT_N_ROLLING = 4
DEFAULT_N_TRANSVERSE = 10

#: Default friction regularisation speed [m/s] (physics.md §2.6.4 suggests ~1e-3 m/s).
DEFAULT_SLIP_REGULARISATION = 1.0e-3


# ================================================================================================
# Traction curve
# ================================================================================================
def _check_number(name: str, value, problems: list[str], minimum=None, strict=False):
    """``value`` as a float, or None after recording why it is not an allowed number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        problems.append(f"{name} = {value!r}: must be a number")
        return None
    if not math.isfinite(x):
        problems.append(f"{name} = {value!r}: must be a finite number")
        return None
    if minimum is not None:
        if strict and not x > minimum:
            problems.append(f"{name} = {x:g}: must be greater than {minimum:g}")
            return None
        if not strict and not x >= minimum:
            problems.append(f"{name} = {x:g}: must be at least {minimum:g}")
            return None
    return x


def traction_curve_parameters(
    mu_zero: float,
    mu_max: float,
    slip_at_max: float,
    mu_infinity: float,
) -> np.ndarray:
    """Parameters (A, B, C, D) of mu(u) = (A + B u) exp(-C u) + D from four curve properties.

    ``mu_zero`` = mu(0), ``mu_max`` = the maximum, reached at slip speed ``slip_at_max`` [m/s],
    ``mu_infinity`` = limit for large slip. A = mu_zero - mu_infinity, D = mu_infinity, C = B / (A +
    B u_m) puts the stationary point at u_m, and B > 0 is the unique root of mu(u_m) = mu_max
    (physics.md §2.6.4). Requires 0 <= mu_zero <= mu_max <= 1, 0 <= mu_infinity <= mu_max and
    slip_at_max > 0 (the case validation keeps case values within these rules). When mu_max is not
    above both other values (within 1e-9 relative) the curve has no interior peak; then the
    monotone limit mu(u) = mu_infinity + (mu_zero - mu_infinity) exp(-u / slip_at_max) is returned
    (B = 0): it falls from mu_max (mu_zero = mu_max) or rises to mu_max (mu_infinity = mu_max),
    reaching 1 - 1/e of the change at slip_at_max. Arguments outside these rules raise ValueError
    naming them. Returns a float64 array of length ``CURVE_SIZE``.
    """
    problems: list[str] = []
    m0 = _check_number("mu_zero", mu_zero, problems, minimum=0.0)
    mm = _check_number("mu_max", mu_max, problems, minimum=0.0, strict=True)
    um = _check_number("slip_at_max", slip_at_max, problems, minimum=0.0, strict=True)
    mi = _check_number("mu_infinity", mu_infinity, problems, minimum=0.0)
    if mm is not None:
        if mm > 1.0:
            problems.append(
                f"mu_max = {mm:g}: must be at most 1 (a lubricated traction coefficient)"
            )
        if m0 is not None and not m0 <= mm:
            problems.append(
                f"mu_zero = {m0:g}: must be at most mu_max = {mm:g} "
                "(the curve rises from mu_zero to its maximum)"
            )
        if mi is not None and not mi <= mm:
            problems.append(
                f"mu_infinity = {mi:g}: must be at most mu_max = {mm:g} "
                "(the curve falls from its maximum towards mu_infinity)"
            )
    if problems:
        raise ValueError("traction_curve_parameters: " + "; ".join(problems))
    a = m0 - mi
    target = mm - mi
    if mm - max(m0, mi) <= 1e-9 * mm:  # no interior peak: monotone limit of the family
        return np.array([a, 0.0, 1.0 / um, mi], dtype=np.float64)
    # With s = A + B u_m > max(A, 0): mu(u_m) - D = s exp(A/s - 1), increasing in s on that range.
    lo = max(a, 0.0)

    def g(s: float) -> float:
        return s * math.exp(a / s - 1.0) - target

    hi = max(2.0 * lo, target) + 1e-12
    while g(hi) <= 0.0:
        hi *= 2.0
    lo_eval = lo if lo > 0.0 else hi * 1e-12
    if g(lo_eval) >= 0.0:  # cannot happen: the peak excess is > 1e-9 mu_max here
        raise ValueError(f"mu_max = {mm:g}: too close to the other coefficients to fit a curve")
    s = optimize.brentq(g, lo_eval, hi, xtol=1e-15, rtol=1e-14, maxiter=200)
    b = (s - a) / um
    c = b / s
    return np.array([a, b, c, mi], dtype=np.float64)


def constant_traction_parameters(mu: float) -> np.ndarray:
    """Curve array of a constant (Coulomb) coefficient mu(u) = mu (boundary friction, tests)."""
    if not (math.isfinite(mu) and mu >= 0.0):
        raise ValueError(f"mu = {mu!r}: must be a finite number >= 0")
    return np.array([0.0, 0.0, 0.0, float(mu)], dtype=np.float64)


@njit(cache=True)
def traction_coefficient(slip_speed, curve):
    """Traction coefficient mu(|u|) = (A + B|u|) exp(-C|u|) + D at slip speed u [m/s]."""
    u = abs(slip_speed)
    return (curve[0] + curve[1] * u) * math.exp(-curve[2] * u) + curve[3]


@njit(cache=True)
def regularised_traction_factor(slip_speed, curve, slip_regularisation):
    """mu(u) / sqrt(u^2 + u_reg^2) [s/m]: multiply by -Q * slip vector to get the friction force."""
    u = abs(slip_speed)
    den = math.sqrt(u * u + slip_regularisation * slip_regularisation)
    if den <= 0.0:
        return 0.0
    return traction_coefficient(u, curve) / den


# ================================================================================================
# Contact-ellipse quadrature
# ================================================================================================
def ellipse_quadrature(
    n_rolling: int = DEFAULT_N_ROLLING, n_transverse: int = DEFAULT_N_TRANSVERSE
) -> np.ndarray:
    """Normalised nodes and weights on the unit disc for Hertz-pressure-weighted integrals.

    ``n_rolling`` points along the rolling direction (minor axis b) on each of ``n_transverse``
    strips across the major axis a. Returns an array (n_rolling * n_transverse, ``NODE_COLUMNS``): x
    = xi/b, y = eta/a, area weight (so that sum w f(x, y) ~ integral of f over the unit disc), load
    fraction (so that sum of fraction * g(x, y) ~ integral of p g dA / Q for the Hertz pressure),
    the Hertz pressure over its maximum and the plain-area weight (module docstring); strip by
    strip. The pressure itself is integrated
    exactly (sum of load fractions = 1 to rounding error).
    """
    for name, n in (("n_rolling", n_rolling), ("n_transverse", n_transverse)):
        if int(n) != n or n < 1 or n > 200:
            raise ValueError(f"{name} = {n!r}: must be an integer between 1 and 200")
    t, wt = special.roots_chebyu(int(n_rolling))  # weight sqrt(1 - t^2)
    y, wy = special.roots_jacobi(int(n_transverse), 1.0, 1.0)  # weight (1 - y^2)
    # the plain area on the same nodes: weight 1 along the strip, sqrt(1 - y^2) across
    ut = _interpolatory_weights(t, special.eval_legendre, 2.0)
    uy = _interpolatory_weights(y, special.eval_chebyu, 0.5 * math.pi)
    nodes = np.empty((int(n_rolling) * int(n_transverse), NODE_COLUMNS))
    k = 0
    for j in range(len(y)):
        sy = math.sqrt(1.0 - y[j] ** 2)
        for i in range(len(t)):
            st = math.sqrt(1.0 - t[i] ** 2)
            nodes[k, NODE_ROLLING] = sy * t[i]
            nodes[k, NODE_TRANSVERSE] = y[j]
            nodes[k, NODE_AREA] = wy[j] * wt[i] / (sy * st)
            nodes[k, NODE_LOAD] = 1.5 / math.pi * wy[j] * wt[i]
            nodes[k, NODE_PRESSURE] = sy * st
            nodes[k, NODE_UNIFORM] = uy[j] * ut[i]
            k += 1
    return nodes


def split_ellipse_rule(n_rolling: int = 2, strips_per_piece: int = 3) -> np.ndarray:
    """Table of the split rule of :func:`ellipse_traction_law` (module docstring, "Split rule"):
    ``n_rolling`` points along the rolling direction and ``strips_per_piece`` Gauss-Legendre strips
    on each piece of the major axis between the lines of zero rolling slip. Returns an array
    (max(n_rolling, strips_per_piece, 2), ``SPLIT_COLUMNS``); unused entries are NaN."""
    for name, n in (("n_rolling", n_rolling), ("strips_per_piece", strips_per_piece)):
        if int(n) != n or n < 1 or n > 200:
            raise ValueError(f"{name} = {n!r}: must be an integer between 1 and 200")
    n_rolling = int(n_rolling)
    strips_per_piece = int(strips_per_piece)
    rule = np.full((max(n_rolling, strips_per_piece, 2), SPLIT_COLUMNS), np.nan)
    t, wt = special.roots_chebyu(n_rolling)
    rule[:n_rolling, SPLIT_T] = t
    rule[:n_rolling, SPLIT_T_LOAD] = wt
    rule[:n_rolling, SPLIT_T_UNIFORM] = _interpolatory_weights(t, special.eval_legendre, 2.0)
    rule[:n_rolling, SPLIT_T_PRESSURE] = np.sqrt(1.0 - t * t)
    y, wy = special.roots_legendre(strips_per_piece)
    rule[:strips_per_piece, SPLIT_Y] = y
    rule[:strips_per_piece, SPLIT_Y_WEIGHT] = wy
    rule[0, SPLIT_COUNTS] = n_rolling
    rule[1, SPLIT_COUNTS] = strips_per_piece
    return rule


def _interpolatory_weights(points: np.ndarray, basis, moment0: float) -> np.ndarray:
    """Weights w at ``points`` with sum w basis_k(points) = integral of basis_k for k < n, given an
    orthogonal basis ``basis(k, x)`` of the integral's weight whose integral is ``moment0`` for
    k = 0 and zero for k >= 1 (exact for polynomials of degree n - 1)."""
    n = len(points)
    v = np.array([basis(k, points) for k in range(n)])
    rhs = np.zeros(n)
    rhs[0] = moment0
    return np.linalg.solve(v, rhs)


def deformed_surface_curvature(groove_radius: float, ball_diameter: float) -> float:
    """Curvature 1/R_d [1/m] of the deformed contact surface across the groove.

    R_d = 2 r D / (2 r + D), the harmonic mean of the groove radius r and the ball radius D/2.
    """
    return (2.0 * groove_radius + ball_diameter) / (2.0 * groove_radius * ball_diameter)


# ================================================================================================
# Traction kernels
# ================================================================================================
@njit(cache=True)
def _contact_basis(contact):
    """Unit normal n, rolling t1 (orthogonalised to n) and transverse t2 = n x t1."""
    nx = contact[CT_NORMAL]
    ny = contact[CT_NORMAL + 1]
    nz = contact[CT_NORMAL + 2]
    inv = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)
    nx *= inv
    ny *= inv
    nz *= inv
    ax = contact[CT_ROLLING]
    ay = contact[CT_ROLLING + 1]
    az = contact[CT_ROLLING + 2]
    d = ax * nx + ay * ny + az * nz
    ax -= d * nx
    ay -= d * ny
    az -= d * nz
    inv = 1.0 / math.sqrt(ax * ax + ay * ay + az * az)
    ax *= inv
    ay *= inv
    az *= inv
    bx = ny * az - nz * ay
    by = nz * ax - nx * az
    bz = nx * ay - ny * ax
    return nx, ny, nz, ax, ay, az, bx, by, bz


@njit(cache=True)
def _centre_kinematics(contact, kin, nx, ny, nz):
    """Lever arm P - c_b, ball and ring surface velocities at P, relative angular velocity."""
    px = contact[CT_POINT]
    py = contact[CT_POINT + 1]
    pz = contact[CT_POINT + 2]
    # ball surface velocity at P
    rbx = px - kin[KIN_BALL_CENTRE]
    rby = py - kin[KIN_BALL_CENTRE + 1]
    rbz = pz - kin[KIN_BALL_CENTRE + 2]
    wbx = kin[KIN_BALL_OMEGA]
    wby = kin[KIN_BALL_OMEGA + 1]
    wbz = kin[KIN_BALL_OMEGA + 2]
    vbx = kin[KIN_BALL_VELOCITY] + wby * rbz - wbz * rby
    vby = kin[KIN_BALL_VELOCITY + 1] + wbz * rbx - wbx * rbz
    vbz = kin[KIN_BALL_VELOCITY + 2] + wbx * rby - wby * rbx
    # ring surface velocity at P
    rrx = px - kin[KIN_RING_POINT]
    rry = py - kin[KIN_RING_POINT + 1]
    rrz = pz - kin[KIN_RING_POINT + 2]
    wrx = kin[KIN_RING_OMEGA]
    wry = kin[KIN_RING_OMEGA + 1]
    wrz = kin[KIN_RING_OMEGA + 2]
    vrx = kin[KIN_RING_VELOCITY] + wry * rrz - wrz * rry
    vry = kin[KIN_RING_VELOCITY + 1] + wrz * rrx - wrx * rrz
    vrz = kin[KIN_RING_VELOCITY + 2] + wrx * rry - wry * rrx
    return (rbx, rby, rbz, vbx, vby, vbz, vrx, vry, vrz, wbx - wrx, wby - wry, wbz - wrz)


@njit(cache=True)
def _write_centre_outputs(out, nx, ny, nz, vbx, vby, vbz, vrx, vry, vrz, ox, oy, oz):
    """Slip, slip speed, spin and entrainment at P (tangential parts) into ``out``."""
    sx = vbx - vrx
    sy = vby - vry
    sz = vbz - vrz
    d = sx * nx + sy * ny + sz * nz
    sx -= d * nx
    sy -= d * ny
    sz -= d * nz
    out[TR_SLIP] = sx
    out[TR_SLIP + 1] = sy
    out[TR_SLIP + 2] = sz
    out[TR_SLIP_SPEED] = math.sqrt(sx * sx + sy * sy + sz * sz)
    out[TR_SPIN] = ox * nx + oy * ny + oz * nz
    ex = vbx + vrx
    ey = vby + vry
    ez = vbz + vrz
    d = ex * nx + ey * ny + ez * nz
    ex -= d * nx
    ey -= d * ny
    ez -= d * nz
    out[TR_ENTRAINMENT] = 0.5 * math.sqrt(ex * ex + ey * ey + ez * ez)
    return sx, sy, sz


@njit(cache=True, inline="always")
def _strip_terms(a, kappa, y):
    """Curvature terms of the strip at y = eta / a [-] across the groove: (eta [m], sin(phi),
    cos(phi), z [m]) of the curved surface (module docstring, "Contact description")."""
    eta = a * y
    sphi = kappa * eta
    cphi = math.sqrt(max(1.0 - sphi * sphi, 0.0))
    return eta, sphi, cphi, -kappa * eta * eta / (1.0 + cphi)


@njit(cache=True, inline="always")
def _add_node(sums, g, v1, v2, u2, xi, eta, z, sphi, cphi):
    """``sums`` (f1, f2, fn, m1, m2, mn, power) plus the node's traction tau dA = g dv (dv = v1 t1 +
    v2 t2'), its moment about the contact centre and its friction power -g |dv|^2."""
    f1, f2, fn, m1, m2, mn, power = sums
    tau1 = g * v1
    tau2 = g * v2 * cphi
    taun = -g * v2 * sphi
    return (
        f1 + tau1,
        f2 + tau2,
        fn + taun,
        m1 + (eta * taun - z * tau2),
        m2 + (z * tau1 - xi * taun),
        mn + (xi * tau2 - eta * tau1),
        power - g * u2,
    )


@njit(cache=True, inline="always")
def _put_node(batch, k, xi, eta, z, sphi, cphi, ps, w_load, w_uniform):
    """Geometry and weights of node ``k`` into the node batch ``batch`` (``NB_*`` rows; units
    there)."""
    batch[NB_XI, k] = xi
    batch[NB_ETA, k] = eta
    batch[NB_Z, k] = z
    batch[NB_SIN, k] = sphi
    batch[NB_COS, k] = cphi
    batch[NB_PRESSURE, k] = ps
    batch[NB_LOAD, k] = w_load
    batch[NB_UNIFORM, k] = w_uniform


@njit(cache=True, inline="always")
def _node_slip(batch, k, s01, s02, o1, o2, on):
    """(v1, v2, |dv|^2) [m/s, m/s, m^2/s^2] at node ``k`` of the batch, from the slip (s01, s02)
    at the contact centre and the relative angular velocity (o1, o2, on) in the contact basis.

    Rigid-body slip at the node p = P + (xi, eta, z): dv = s0 + Omega x (xi, eta, z). Its n
    component is the approach rate of the undeformed bodies (taken up by the elastic deformation,
    not slip) and is dropped; the rolling component v1 stays along t1 and the transverse one v2 is
    laid along the local tangent t2' = cos(phi) t2 - sin(phi) n."""
    eta = batch[NB_ETA, k]
    z = batch[NB_Z, k]
    v1 = s01 + o2 * z - on * eta
    v2 = s02 + on * batch[NB_XI, k] - o1 * z
    return v1, v2, v1 * v1 + v2 * v2


@njit(cache=True, inline="always")
def _batch_sums(sums, batch, count, slip, law_data):
    """``sums`` (f1, f2, fn, m1, m2, mn, power; :func:`_add_node`) plus the contributions of the
    first ``count`` nodes of the node batch ``batch`` (geometry filled by :func:`_put_node`).
    ``slip`` = (s01, s02, o1, o2, on) [m/s, rad/s] in the contact basis; ``law_data`` = (law,
    filmed, Q [N], the curve's A, B [s/m], C [s/m], D, u_reg^2 [m^2/s^2], alpha p_max, tau_L0
    [Pa], Lambda p_max [Pa], tau_0 [Pa], tau_L0 a b [N], Lambda Q [N], ln(eta_0 / (tau_0 h_c)),
    G t / h_c [Pa s/m], c h_c / (8 k) [m^2/W] of the thermal softening).

    First the local law at every node, g [N s/m] with tau dA = g dv, in a loop with no dependence
    between nodes and no library call (exp and log of solver.physics.lanes), which LLVM
    vectorises; then the sums in node order. Inlined into kernels compiled with numpy's error
    model: no test and branch before each division (a division by zero is never selected)."""
    s01, s02, o1, o2, on = slip
    (law, filmed, q, c0, c1, c2, c3, ur2) = law_data[:8]
    (alpha_pmax, tl0, lam_pmax, tau_0, tl0_area, lam_q, ln_c, elastic, heating) = law_data[8:]
    if law == LAW_RHEOLOGY and filmed:
        # Eyring stress as tau_0 ln(2 x) (x = eta gamma_dot / tau_0), as it is at nearly every
        # node: no library call, the loop vectorises; the few nodes with a smaller x are redone
        # with the full law (solver.physics.rheology.eyring_asinh) below
        for k in range(count):
            v1, v2, u2 = _node_slip(batch, k, s01, s02, o1, o2, on)
            ps = batch[NB_PRESSURE, k]
            # tau dA = s (tau_L0 dA + Lambda p dA): plain-area and load weights (module docstring)
            weight = tl0_area * batch[NB_UNIFORM, k] + lam_q * batch[NB_LOAD, k]
            ln_x = eyring_log_argument(0.5 * log_lanes(u2), alpha_pmax * ps, ln_c)
            tau_l = tl0 + lam_pmax * ps
            s_u = saturation_from_eyring(
                math.sqrt(u2), tau_0 * eyring_asinh_large(ln_x), tau_l, elastic
            )
            # thermal softening 1 / (1 + c h_c tau_iso u / (8 k)), tau_iso u = tau_L (s / u) u^2
            g = -weight * s_u / (1.0 + heating * tau_l * s_u * u2)
            batch[NB_FACTOR, k] = g if u2 > 0.0 else 0.0
            batch[NB_LOG_ARGUMENT, k] = ln_x
            batch[NB_V1, k] = v1
            batch[NB_V2, k] = v2
            batch[NB_U2, k] = u2
        for k in range(count):
            ln_x = batch[NB_LOG_ARGUMENT, k]
            if ln_x <= EYRING_LARGE_FROM and batch[NB_U2, k] > 0.0:
                ps = batch[NB_PRESSURE, k]
                weight = tl0_area * batch[NB_UNIFORM, k] + lam_q * batch[NB_LOAD, k]
                u2 = batch[NB_U2, k]
                tau_l = tl0 + lam_pmax * ps
                s_u = saturation_from_eyring(
                    math.sqrt(u2), tau_0 * eyring_asinh(ln_x), tau_l, elastic
                )
                batch[NB_FACTOR, k] = -weight * s_u / (1.0 + heating * tau_l * s_u * u2)
    elif law == LAW_RHEOLOGY:
        # no film (no entrainment): the limiting shear stress tau_L0 + Lambda p for any slip above
        # 1e-9 m/s (solver.physics.rheology.shear_stress without a film), integrated as above
        for k in range(count):
            v1, v2, u2 = _node_slip(batch, k, s01, s02, o1, o2, on)
            u = math.sqrt(u2)
            weight = tl0_area * batch[NB_UNIFORM, k] + lam_q * batch[NB_LOAD, k]
            g = -weight / u
            batch[NB_FACTOR, k] = g if u > 1e-9 else 0.0
            batch[NB_V1, k] = v1
            batch[NB_V2, k] = v2
            batch[NB_U2, k] = u2
    else:
        # slip curve: tau = -mu(|dv|) p dv / sqrt(|dv|^2 + u_reg^2)
        for k in range(count):
            v1, v2, u2 = _node_slip(batch, k, s01, s02, o1, o2, on)
            den = math.sqrt(u2 + ur2)
            u = math.sqrt(u2)
            mu = (c0 + c1 * u) * exp_lanes(-c2 * u) + c3
            g = -q * batch[NB_LOAD, k] * mu / den
            batch[NB_FACTOR, k] = g if den > 0.0 else 0.0
            batch[NB_V1, k] = v1
            batch[NB_V2, k] = v2
            batch[NB_U2, k] = u2
    for k in range(count):
        sums = _add_node(
            sums,
            batch[NB_FACTOR, k],
            batch[NB_V1, k],
            batch[NB_V2, k],
            batch[NB_U2, k],
            batch[NB_XI, k],
            batch[NB_ETA, k],
            batch[NB_Z, k],
            batch[NB_SIN, k],
            batch[NB_COS, k],
        )
    return sums


@njit(cache=True, inline="always")
def _rolling_slip_zeros(a, kappa, s01, o2, on):
    """Break points y = eta / a in (-1, 1) of the split rule, ascending, -2 for a missing one: the
    zeros of the rolling slip v1(eta) = s01 + o2 z(eta) - on eta across the major axis (lines of
    pure rolling). With z = sqrt(R^2 - eta^2) - R (R = 1 / kappa) they are where a line meets a
    circle: (on^2 + o2^2) eta^2 + 2 on c eta - s01 (2 o2 R - s01) = 0, c = o2 R - s01, solved in a
    form free of cancellation. Where the line misses the circle, both break points are its point
    of closest approach, where the two zeros appear together, so the pieces change continuously
    with the state. (Squaring also admits crossings of the circle's far half, z < -R; they are kept
    as break points, which keeps the pieces continuous and costs no accuracy.) Flat contact: the
    one zero s01 / on."""
    r1 = -2.0
    r2 = -2.0
    if kappa > 0.0:
        r = 1.0 / kappa
        qa = on * on + o2 * o2
        if qa > 0.0:
            half_b = on * (o2 * r - s01)
            qc = -s01 * (2.0 * o2 * r - s01)
            disc = on * on * r * r + 2.0 * o2 * r * s01 - s01 * s01  # (half_b^2 - qa qc) / o2^2
            q = 0.0
            if disc > 0.0:
                q = -(half_b + math.copysign(abs(o2) * math.sqrt(disc), half_b))
            if q != 0.0:
                r1 = q / qa / a
                r2 = qc / q / a
            else:  # no crossing (or a double one): the point of closest approach
                r1 = -half_b / qa / a
                r2 = r1
    elif on != 0.0:
        r1 = s01 / on / a
    r1 = r1 if -1.0 < r1 < 1.0 else -2.0
    r2 = r2 if -1.0 < r2 < 1.0 else -2.0
    return min(r1, r2), max(r1, r2)


@njit(cache=True, error_model="numpy")
def _full_batch_sums(sums, batch, slip, law_data):
    """:func:`_batch_sums` of a full batch, as a call: rules with more nodes than a batch holds
    are rare, so the node loops keep one inlined copy of the batch's loops (at their end)."""
    return _batch_sums(sums, batch, batch.shape[1], slip, law_data)


@njit(cache=True, error_model="numpy")
def ellipse_traction_into(
    contact,
    kinematics,
    law,
    curve,
    rheology,
    film,
    transit_time,
    slip_regularisation,
    nodes,
    out,
    batch,
):
    """:func:`ellipse_traction_law` with the caller's node batch ``batch``: a C-contiguous float64
    scratch array (``NODE_BATCH_ROWS``, capacity), any capacity >= 1 (``NODE_BATCH`` is the usual
    one). Allocates nothing.

    The nodes are taken a batch at a time: their geometry and weights (per strip, and per piece
    of the split rule) are put into the batch, then :func:`_batch_sums` evaluates the local law
    at all of them in one vectorised loop and adds their contributions to the force, moment and
    power sums in node order."""
    nx, ny, nz, t1x, t1y, t1z, t2x, t2y, t2z = _contact_basis(contact)
    (rbx, rby, rbz, vbx, vby, vbz, vrx, vry, vrz, ox, oy, oz) = _centre_kinematics(
        contact, kinematics, nx, ny, nz
    )
    _write_centre_outputs(out, nx, ny, nz, vbx, vby, vbz, vrx, vry, vrz, ox, oy, oz)
    a = contact[CT_SEMI_MAJOR]
    b = contact[CT_SEMI_MINOR]
    q = contact[CT_LOAD]
    kappa = contact[CT_CURVATURE]
    if not q > 0.0:  # unloaded (or not finite): no traction; the centre kinematics are reported
        for i in range(9):
            out[TR_FORCE + i] = 0.0
        out[TR_POWER] = 0.0
        out[TR_POWER_SLIDING] = 0.0
        out[TR_POWER_SPIN] = 0.0
        return
    # Work in the contact basis (t1, t2, n). Slip at P and the relative angular velocity Omega:
    s01 = (vbx - vrx) * t1x + (vby - vry) * t1y + (vbz - vrz) * t1z
    s02 = (vbx - vrx) * t2x + (vby - vry) * t2y + (vbz - vrz) * t2z
    o1 = ox * t1x + oy * t1y + oz * t1z
    o2 = ox * t2x + oy * t2y + oz * t2z
    on = ox * nx + oy * ny + oz * nz
    ur2 = slip_regularisation * slip_regularisation
    rheological = law == LAW_RHEOLOGY
    filmed = film > 0.0
    ln_c = 0.0
    elastic = 0.0
    heating = 0.0
    ab = a * b
    # rheology: Hertz p_max = 1.5 Q / (pi a b); per node p = p_max (p / p_max), so the Barus
    # exponent and the limiting shear stress are p_max-scaled node constants
    p_max = 1.5 * q / (math.pi * ab) if rheological and ab > 0.0 else 0.0
    alpha_pmax = rheology[RH_PRESSURE_VISCOSITY] * p_max if rheological else 0.0
    tl0 = rheology[RH_LIMITING_STRESS] if rheological else 0.0
    lam_pmax = rheology[RH_LIMITING_SLOPE] * p_max if rheological else 0.0
    tau_0 = rheology[RH_EYRING_STRESS] if rheological else 0.0
    tl0_area = tl0 * ab
    lam_q = rheology[RH_LIMITING_SLOPE] * q if rheological else 0.0
    if rheological:
        ur2 = 0.0
        if filmed:
            ln_c, elastic = contact_constants(film, transit_time, rheology)
            heating = softening_constant(film, rheology)
    slip = (s01, s02, o1, o2, on)
    law_data = (
        law,
        filmed,
        q,
        curve[0],
        curve[1],
        curve[2],
        curve[3],
        ur2,
        alpha_pmax,
        tl0,
        lam_pmax,
        tau_0,
        tl0_area,
        lam_q,
        ln_c,
        elastic,
        heating,
    )
    cap = batch.shape[1]
    count = 0
    sums = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # f1, f2, fn, m1, m2, mn, power (_add_node)
    if nodes.shape[1] == SPLIT_COLUMNS:
        # split rule: Gauss-Legendre strips on each piece of the major axis between the zeros of
        # the rolling slip, the rolling-direction points of the rule on each
        n_t = int(nodes[0, SPLIT_COUNTS])
        n_y = int(nodes[1, SPLIT_COUNTS])
        ra, rb = _rolling_slip_zeros(a, kappa, s01, o2, on)
        lo = -1.0
        area_lo = -0.25 * math.pi  # plain-area primitive 0.5 (y sqrt(1 - y^2) + asin y) at lo
        for piece in range(3):
            hi = ra if piece == 0 else (rb if piece == 1 else 1.0)
            if hi - lo <= 1e-9:
                continue
            mid = 0.5 * (lo + hi)
            half = 0.5 * (hi - lo)
            # scale the strips' weights so that the piece's plain area and load (weights sqrt(1 -
            # y^2) and 1 - y^2 across) come out exactly: a saturated piece is then exact
            sum_area = 0.0
            sum_load = 0.0
            for j in range(n_y):
                y = mid + half * nodes[j, SPLIT_Y]
                sy2 = max(1.0 - y * y, 0.0)
                sum_area += nodes[j, SPLIT_Y_WEIGHT] * math.sqrt(sy2)
                sum_load += nodes[j, SPLIT_Y_WEIGHT] * sy2
            area_hi = 0.5 * (hi * math.sqrt(max(1.0 - hi * hi, 0.0)) + math.asin(min(hi, 1.0)))
            load_piece = (hi - hi * hi * hi / 3.0) - (lo - lo * lo * lo / 3.0)
            area_scale = (area_hi - area_lo) / sum_area if sum_area > 0.0 else 0.0
            load_scale = 1.5 / math.pi * load_piece / sum_load if sum_load > 0.0 else 0.0
            lo = hi
            area_lo = area_hi
            for j in range(n_y):
                y = mid + half * nodes[j, SPLIT_Y]
                wy = nodes[j, SPLIT_Y_WEIGHT]
                sy = math.sqrt(max(1.0 - y * y, 0.0))
                eta, sphi, cphi, z = _strip_terms(a, kappa, y)
                w_load = load_scale * sy * sy * wy
                w_uniform = area_scale * sy * wy
                for i in range(n_t):
                    _put_node(
                        batch,
                        count,
                        b * sy * nodes[i, SPLIT_T],
                        eta,
                        z,
                        sphi,
                        cphi,
                        sy * nodes[i, SPLIT_T_PRESSURE],
                        w_load * nodes[i, SPLIT_T_LOAD],
                        w_uniform * nodes[i, SPLIT_T_UNIFORM],
                    )
                    count += 1
                    if count == cap:
                        sums = _full_batch_sums(sums, batch, slip, law_data)
                        count = 0
    else:
        y_strip = 2.0  # outside [-1, 1]: the first node starts a strip
        eta = sphi = cphi = z = 0.0
        for k in range(nodes.shape[0]):
            if nodes[k, NODE_TRANSVERSE] != y_strip:  # a new strip: its curvature terms
                y_strip = nodes[k, NODE_TRANSVERSE]
                eta, sphi, cphi, z = _strip_terms(a, kappa, y_strip)
            _put_node(
                batch,
                count,
                b * nodes[k, NODE_ROLLING],
                eta,
                z,
                sphi,
                cphi,
                nodes[k, NODE_PRESSURE],
                nodes[k, NODE_LOAD],
                nodes[k, NODE_UNIFORM],
            )
            count += 1
            if count == cap:
                sums = _full_batch_sums(sums, batch, slip, law_data)
                count = 0
    if count > 0:
        sums = _batch_sums(sums, batch, count, slip, law_data)
    f1, f2, fn, m1, m2, mn, power = sums
    fx = f1 * t1x + f2 * t2x + fn * nx
    fy = f1 * t1y + f2 * t2y + fn * ny
    fz = f1 * t1z + f2 * t2z + fn * nz
    mx = m1 * t1x + m2 * t2x + mn * nx
    my = m1 * t1y + m2 * t2y + mn * ny
    mz = m1 * t1z + m2 * t2z + mn * nz
    out[TR_FORCE] = fx
    out[TR_FORCE + 1] = fy
    out[TR_FORCE + 2] = fz
    out[TR_MOMENT_POINT] = mx
    out[TR_MOMENT_POINT + 1] = my
    out[TR_MOMENT_POINT + 2] = mz
    out[TR_MOMENT_BALL] = rby * fz - rbz * fy + mx
    out[TR_MOMENT_BALL + 1] = rbz * fx - rbx * fz + my
    out[TR_MOMENT_BALL + 2] = rbx * fy - rby * fx + mz
    out[TR_POWER] = power
    s0n = (vbx - vrx) * nx + (vby - vry) * ny + (vbz - vrz) * nz
    out[TR_POWER_SLIDING] = -(f1 * s01 + f2 * s02 + fn * s0n)
    out[TR_POWER_SPIN] = -(m1 * o1 + m2 * o2 + mn * on)


@njit(cache=True)
def ellipse_traction_law(
    contact, kinematics, law, curve, rheology, film, transit_time, slip_regularisation, nodes, out
):
    """Traction force and moments on the ball integrated over the Hertz contact ellipse, with the
    local law ``law``: ``LAW_SLIP_CURVE`` (tau = mu(|dv|) p, ``curve``) or ``LAW_RHEOLOGY`` (tau of
    :func:`solver.physics.rheology.shear_stress` with ``rheology``, central film ``film`` [m] and
    transit time ``transit_time`` [s]; no regularisation needed: tau vanishes linearly with slip).

    ``contact`` (``CONTACT_SIZE``), ``kinematics`` (``KIN_SIZE``), ``curve`` (``CURVE_SIZE``) and
    the output ``out`` (``TRACTION_OUT_SIZE``) are laid out as in the module docstring; ``nodes``
    comes from :func:`ellipse_quadrature` or :func:`split_ellipse_rule`; ``slip_regularisation``
    u_reg [m/s] >= 0.

    At each node the surface point p = P + xi t1 + eta t2 + z(eta) n lies on the deformed surface of
    curvature ``contact[CT_CURVATURE]`` across the groove; the slip of the ball surface over the
    ring surface there (rigid-body velocities of both bodies, rolling and transverse components laid
    on the local tangent plane, see the module docstring) gives the local shear tau = -mu(|dv|) p dv
    / sqrt(|dv|^2 + u_reg^2). Spin moment and the differential (Heathcote) slip thus come out of one
    formula. Returns nothing; fills ``out``. Allocates its node batch
    (:func:`ellipse_traction_into` takes the caller's).
    """
    ellipse_traction_into(
        contact,
        kinematics,
        law,
        curve,
        rheology,
        film,
        transit_time,
        slip_regularisation,
        nodes,
        out,
        np.empty((NODE_BATCH_ROWS, NODE_BATCH)),
    )


@njit(cache=True)
def ellipse_traction(contact, kinematics, curve, slip_regularisation, nodes, out):
    """:func:`ellipse_traction_law` with the slip curve ``curve`` (``LAW_SLIP_CURVE``)."""
    ellipse_traction_law(
        contact, kinematics, LAW_SLIP_CURVE, curve, curve, 0.0, 0.0, slip_regularisation, nodes, out
    )


@njit(cache=True)
def centre_traction(contact, kinematics, curve, slip_regularisation, out):
    """Single-point traction: the centre slip only, F = -Q mu(u) dv / sqrt(u^2 + u_reg^2).

    Same arrays as :func:`ellipse_traction` (``contact[CT_SEMI_MAJOR/MINOR/CURVATURE]`` unused). It
    has no spin moment (``TR_MOMENT_POINT`` = 0); 10–50x cheaper, for comparison and tests.
    """
    nx, ny, nz, t1x, t1y, t1z, t2x, t2y, t2z = _contact_basis(contact)
    (rbx, rby, rbz, vbx, vby, vbz, vrx, vry, vrz, ox, oy, oz) = _centre_kinematics(
        contact, kinematics, nx, ny, nz
    )
    sx, sy, sz = _write_centre_outputs(out, nx, ny, nz, vbx, vby, vbz, vrx, vry, vrz, ox, oy, oz)
    u = out[TR_SLIP_SPEED]
    g = -contact[CT_LOAD] * regularised_traction_factor(u, curve, slip_regularisation)
    fx = g * sx
    fy = g * sy
    fz = g * sz
    out[TR_FORCE] = fx
    out[TR_FORCE + 1] = fy
    out[TR_FORCE + 2] = fz
    out[TR_MOMENT_POINT] = 0.0
    out[TR_MOMENT_POINT + 1] = 0.0
    out[TR_MOMENT_POINT + 2] = 0.0
    out[TR_MOMENT_BALL] = rby * fz - rbz * fy
    out[TR_MOMENT_BALL + 1] = rbz * fx - rbx * fz
    out[TR_MOMENT_BALL + 2] = rbx * fy - rby * fx
    out[TR_POWER] = -(fx * sx + fy * sy + fz * sz)
    out[TR_POWER_SLIDING] = out[TR_POWER]
    out[TR_POWER_SPIN] = 0.0


# ================================================================================================
# Damped Hertz normal force
# ================================================================================================
@njit(cache=True)
def damped_normal_force(approach, approach_rate, stiffness_K, damping_ratio, effective_mass):
    """Hertz normal force with ADORE-style damping, Q = K d^1.5 + c d_dot, clipped at 0 [N].

    ``approach`` d [m] (> 0 in contact), ``approach_rate`` d_dot [m/s] (> 0 closing),
    ``stiffness_K`` [N/m^1.5], ``damping_ratio`` zeta (critical-damping fraction, >= 0),
    ``effective_mass`` m [kg] (the ball mass for a ball–race contact, physics.md §2.6.6; the
    ADORE-port data use zeta = 0.05). c = 2 zeta sqrt(1.5 K d^0.5 m) uses the linearised stiffness
    1.5 K d^0.5, so the damping force vanishes smoothly (like d^(1/4)) as d -> 0: no jump at contact
    onset. Q = 0 for d <= 0 and never negative (no tension: a separating contact whose damping would
    pull is released). The law is scale-free: the coefficient of restitution of an impact depends
    on zeta only, not on the impact speed.
    """
    if approach <= 0.0:
        return 0.0
    sq = math.sqrt(approach)
    elastic = stiffness_K * approach * sq
    c = 2.0 * damping_ratio * math.sqrt(1.5 * stiffness_K * sq * effective_mass)
    q = elastic + c * approach_rate
    if q < 0.0:
        return 0.0
    return q
