"""Cage contact kernels of the dynamic model: ball–pocket contact and cage–land (guiding) force.

physics.md §2.6.7. SI units throughout (m, s, N, rad, Pa s). All kernels are ``@njit(cache=True)``,
take small named float64 arrays and write into a preallocated output array.

Ball–pocket contact (:func:`pocket_contact`)
--------------------------------------------
Pocket frame: origin at the pocket centre (on the cage's pocket circle, in the cage mid-plane);
axes (x, r, theta) = (bearing axis, pocket axis = cage radial direction, circumferential
direction), i.e. the azimuth frame of physics.md §2.1 at the pocket's angle (right-handed). The
pocket is a cylinder of diameter D + C_p about the r axis (infinitely long: the pocket ends are not
checked).

``kinematics`` (``POCKET_KIN_SIZE``), pocket-frame components:
    ``PK_POSITION`` (3): ball centre minus pocket centre [m].
    ``PK_VELOCITY`` (3): ball-centre velocity minus the velocity of the cage material point at the
        ball centre, v_b - v_c - w_c x (c_b - c_c) [m/s] (the rate of ``PK_POSITION`` seen from the
        cage).
    ``PK_OMEGA`` (3): ball angular velocity minus cage angular velocity [rad/s].
``params`` (``POCKET_PARAM_SIZE``), built by :func:`pocket_parameters`:
    ``PP_STIFFNESS`` K_p [N/m^n]; ``PP_EXPONENT`` n (1.5: Hertz sphere in a metal cylinder; 1:
    polymer cage, linear); ``PP_DAMPING_RATIO`` zeta; ``PP_MASS`` effective mass for the damping
    [kg] (the ball mass or the ball–cage reduced mass); ``PP_FRICTION`` mu_bc;
    ``PP_SLIP_REGULARISATION`` u_reg [m/s]; ``PP_CLEARANCE`` diametral clearance C_p [m];
    ``PP_BALL_RADIUS`` [m]; ``PP_DAMPING_DEPTH`` penetration over which the damping is ramped in at
    contact onset [m] (needed for n = 1, whose critical damping coefficient does not vanish at zero
    penetration; 0 = no ramp).
Law: gap g = C_p/2 - rho, rho = sqrt(d_x^2 + d_theta^2) (distance of the ball centre from the
pocket axis). For g < 0 the normal force is F_n = K_p (-g)^n + c (-g_dot) with
c = 2 zeta sqrt(n K_p (-g)^(n-1) m) (critical-damping ratio as for the races,
:func:`damped_power_law_force`), never negative, acting on the ball along -e_rho (back towards the
pocket axis). Friction at the contact point c_b + R_b e_rho: F_t = -mu_bc F_n s / sqrt(|s|^2 +
u_reg^2), s = sliding velocity of the ball surface over the pocket wall. Lubricant squeeze and
hydrodynamic pocket forces are not modelled.
``out`` (``POCKET_OUT_SIZE``), pocket-frame components:
    ``PO_FORCE`` (3) force on the ball [N]; ``PO_MOMENT_BALL`` (3) moment on the ball about its
    centre [N m]; ``PO_POINT`` (3) contact point minus pocket centre [m] (the cage receives
    -``PO_FORCE`` there); ``PO_NORMAL_FORCE`` F_n >= 0 [N]; ``PO_GAP`` g [m] (negative =
    penetration); ``PO_SLIP_SPEED`` |s| [m/s].

Pocket stiffness estimate (:func:`pocket_stiffness_estimate`): the Hertz constant of a sphere
(radius R_b) inside a concave cylinder (radius R_p = R_b + C_p/2): curvature sum 2/R_b - 1/R_p,
curvature difference (1/R_p)/(2/R_b - 1/R_p), exact elliptic-integral solution
(solver.physics.hertz). For a metal cage this is K_p with n = 1.5. For a polymer cage (n = 1;
physics.md §2.6.7 quotes K_p ~ 1e6–1e7 N/m [E]) the linear stiffness is the secant of the same
Hertz law, with the polymer's modulus, at a reference load F_ref (default 10 N, the order of pocket
loads in high-speed spindle bearings): K_lin = K_h^(2/3) F_ref^(1/3). For a 7.144 mm silicon
nitride ball, C_p = 0.2 mm and glass-filled polyamide (E = 8 GPa, nu = 0.4) this gives 3.8e6 N/m;
unfilled PA66 (E = 3 GPa) 2.0e6 N/m, inside the quoted range. (Steel ball in a brass pocket,
n = 1.5: K_p = 1.9e10 N/m^1.5.)

Cage–land guiding force (:func:`land_force`)
--------------------------------------------
The guiding land is a short journal bearing (Ocvirk; half-Sommerfeld: sub-ambient pressures
discarded) of radius R, width L and radial clearance C with viscosity eta, plus a metallic contact
once the film closes. Radial-plane vectors are (y, z) components of the inertial frame; speeds are
about +x.

``kinematics`` (``LAND_KIN_SIZE``):
    ``LK_OFFSET`` (2) cage centre minus guiding-ring centre, e [m]; ``LK_VELOCITY`` (2) its rate
    [m/s]; ``LK_CAGE_SPEED`` cage angular speed [rad/s]; ``LK_RING_SPEED`` guiding ring speed
    [rad/s].
``params`` (``LAND_PARAM_SIZE``), built by :func:`land_parameters`:
    ``LP_RADIUS`` R [m]; ``LP_WIDTH`` L [m]; ``LP_CLEARANCE`` radial clearance C [m];
    ``LP_VISCOSITY`` eta [Pa s]; ``LP_CONTACT_ECCENTRICITY`` eps_c (metal contact for eps > eps_c,
    i.e. film < (1 - eps_c) C); ``LP_MAX_ECCENTRICITY`` eps_max (eps_c < eps_max < 1; above eps_c
    the hydrodynamic eccentricity is capped smoothly, eps_h = eps_c + (eps_max - eps_c)
    tanh((eps - eps_c)/(eps_max - eps_c)), continuous with slope 1); ``LP_METAL_STIFFNESS`` K_m
    [N/m^n]; ``LP_METAL_EXPONENT`` n; ``LP_METAL_DAMPING_RATIO`` zeta; ``LP_MASS`` effective mass
    (the cage mass) [kg]; ``LP_METAL_FRICTION`` mu; ``LP_SLIP_REGULARISATION`` [m/s];
    ``LP_CAGE_SIDE`` +1 if the cage runs inside the land (outer-ring guided), -1 if outside it
    (inner-ring guided); ``LP_DAMPING_DEPTH`` damping ramp depth [m] (as for the pocket).
``out`` (``LAND_OUT_SIZE``):
    ``LO_FORCE`` (2) force on the cage [N]; ``LO_TORQUE`` torque on the cage about its centre, x
    component [N m]; ``LO_RING_TORQUE`` torque on the guiding ring about its centre, -T - (e x F)_x
    [N m] (the ring also receives -F); ``LO_HYDRO_FORCE`` (2) hydrodynamic part of the force [N];
    ``LO_METAL_NORMAL`` metal normal force >= 0 [N]; ``LO_ECCENTRICITY`` eps = |e|/C; ``LO_FILM``
    minimum geometric film C - |e| [m] (negative in metal contact).

Hydrodynamic force. With psi measured from the line of centres e_par = e/|e| towards
e_perp = x × e_par and the film h = C (1 - eps cos psi), the short-bearing Reynolds equation
integrated over the width gives the pressure P(psi) = -eta L^3 G / h^3 (axially integrated), with
G = A sin psi - B cos psi, A = (w_cage + w_ring)/2 e - v_perp, B = e_dot = v_par. (The whirl term
e phi_dot = v_perp is written without dividing by e, so the law stays regular at e = 0.) Only P > 0
(G < 0) counts. The force on the cage,
    F = R eta L^3 / C^3 * integral over G < 0 of G (cos psi e_par + sin psi e_perp) / w^3 dpsi,
w = 1 - eps cos psi, is evaluated in closed form with the Sommerfeld substitution
cos psi = (eps + cos g)/(1 + eps cos g), which turns every integrand into a trigonometric polynomial
in g. For a steady eccentric cage (v = 0) it reduces to the Ocvirk values of physics.md §2.6.7 with
U = R (w_cage + w_ring):
    F_rad = -eta U L^3 / C^2 * eps^2 / (1 - eps^2)^2 (towards the centre),
    F_tan = pi eta U L^3 / (4 C^2) * eps / (1 - eps^2)^1.5 (90° ahead in the sense of rotation).
U is the *sum* of the surface speeds (what drags oil into the wedge); physics.md's R |w_c - w_land|
coincides with it only for a stationary guiding ring (outer-ring guidance). The same formula holds
whether the cage is inside or outside the land (the film sees only the relative geometry).
Viscous torque on the cage about its axis, Couette shear over the full film plus the pressure term:
T = eta R^3 L (w_ring - w_cage) / C * 2 pi / sqrt(1 - eps_h^2) - e_h F_perp / 2 (both sides).
Metal contact: approach delta = |e| - eps_c C; normal force from :func:`damped_power_law_force`
along -e_par; friction -mu F_n s / sqrt(s^2 + u_reg^2) along e_perp at the contact point
(side * R e_par from the cage centre), s = sliding speed of the cage surface over the land there.
Default metal stiffness (:func:`land_contact_stiffness_estimate`): linear, k = pi E' L / 4, the
order of magnitude of a conformal cylinder-in-bore line contact (approach ~ 4 P / (pi E' L) times a
logarithmic factor of order one; Johnson, Contact Mechanics §5.6) [E].
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# ---- pocket kinematics / parameters / output -----------------------------------------------
PK_POSITION = 0
PK_VELOCITY = 3
PK_OMEGA = 6
POCKET_KIN_SIZE = 9

PP_STIFFNESS = 0
PP_EXPONENT = 1
PP_DAMPING_RATIO = 2
PP_MASS = 3
PP_FRICTION = 4
PP_SLIP_REGULARISATION = 5
PP_CLEARANCE = 6
PP_BALL_RADIUS = 7
PP_DAMPING_DEPTH = 8
POCKET_PARAM_SIZE = 9

PO_FORCE = 0
PO_MOMENT_BALL = 3
PO_POINT = 6
PO_NORMAL_FORCE = 9
PO_GAP = 10
PO_SLIP_SPEED = 11
POCKET_OUT_SIZE = 12

# ---- land kinematics / parameters / output -------------------------------------------------
LK_OFFSET = 0
LK_VELOCITY = 2
LK_CAGE_SPEED = 4
LK_RING_SPEED = 5
LAND_KIN_SIZE = 6

LP_RADIUS = 0
LP_WIDTH = 1
LP_CLEARANCE = 2
LP_VISCOSITY = 3
LP_CONTACT_ECCENTRICITY = 4
LP_MAX_ECCENTRICITY = 5
LP_METAL_STIFFNESS = 6
LP_METAL_EXPONENT = 7
LP_METAL_DAMPING_RATIO = 8
LP_MASS = 9
LP_METAL_FRICTION = 10
LP_SLIP_REGULARISATION = 11
LP_CAGE_SIDE = 12
LP_DAMPING_DEPTH = 13
LAND_PARAM_SIZE = 14

LO_FORCE = 0
LO_TORQUE = 2
LO_RING_TORQUE = 3
LO_HYDRO_FORCE = 4
LO_METAL_NORMAL = 6
LO_ECCENTRICITY = 7
LO_FILM = 8
LAND_OUT_SIZE = 9

#: Default metal-contact threshold eccentricity and hydrodynamic cap.
DEFAULT_CONTACT_ECCENTRICITY = 0.95
DEFAULT_MAX_ECCENTRICITY = 0.98
#: Default damping-ramp depth for linear (n = 1) contacts [m].
DEFAULT_DAMPING_DEPTH = 1.0e-6
#: Default reference load for the secant stiffness of a polymer pocket [N].
DEFAULT_POCKET_REFERENCE_LOAD = 10.0


# ================================================================================================
# Shared normal law
# ================================================================================================
@njit(cache=True)
def damped_power_law_force(
    approach, approach_rate, stiffness, exponent, damping_ratio, effective_mass, damping_depth
):
    """Normal force K d^n + c d_dot, c = 2 zeta sqrt(n K d^(n-1) m) s(d), clipped at 0 [N].

    ``approach`` d [m] (> 0 in contact), ``approach_rate`` [m/s] (> 0 closing), ``stiffness`` K
    [N/m^n], ``exponent`` n >= 1, ``damping_ratio`` zeta, ``effective_mass`` m [kg]. s(d) is a
    smoothstep ramp from 0 at d = 0 to 1 at d = ``damping_depth`` (1 everywhere if ``damping_depth``
    <= 0), so the force is continuous at contact onset also for n = 1. For n = 1.5 and no ramp this
    equals solver.physics.traction.damped_normal_force. Q = 0 for d <= 0; never negative.
    """
    if approach <= 0.0:
        return 0.0
    dn1 = approach ** (exponent - 1.0)
    elastic = stiffness * dn1 * approach
    c = 2.0 * damping_ratio * math.sqrt(exponent * stiffness * dn1 * effective_mass)
    if damping_depth > 0.0 and approach < damping_depth:
        s = approach / damping_depth
        c *= s * s * (3.0 - 2.0 * s)
    q = elastic + c * approach_rate
    if q < 0.0:
        return 0.0
    return q


# ================================================================================================
# Ball–pocket contact
# ================================================================================================
@njit(cache=True)
def pocket_contact(kinematics, params, out):
    """Force and moment on a ball from its cylindrical cage pocket (arrays: module docstring)."""
    dx = kinematics[PK_POSITION]
    dr = kinematics[PK_POSITION + 1]
    dt = kinematics[PK_POSITION + 2]
    rb = params[PP_BALL_RADIUS]
    rho = math.sqrt(dx * dx + dt * dt)
    if rho > 0.0:
        ex = dx / rho
        et = dt / rho
    else:
        ex = 0.0
        et = 1.0
    gap = 0.5 * params[PP_CLEARANCE] - rho
    for i in range(POCKET_OUT_SIZE):
        out[i] = 0.0
    out[PO_POINT] = dx + rb * ex
    out[PO_POINT + 1] = dr
    out[PO_POINT + 2] = dt + rb * et
    out[PO_GAP] = gap
    if gap >= 0.0:
        return
    vx = kinematics[PK_VELOCITY]
    vr = kinematics[PK_VELOCITY + 1]
    vt = kinematics[PK_VELOCITY + 2]
    rate = vx * ex + vt * et  # d rho / dt = -d gap / dt: approach rate
    fn = damped_power_law_force(
        -gap,
        rate,
        params[PP_STIFFNESS],
        params[PP_EXPONENT],
        params[PP_DAMPING_RATIO],
        params[PP_MASS],
        params[PP_DAMPING_DEPTH],
    )
    # sliding velocity of the ball surface over the pocket wall at the contact point (r = rb e_rho)
    wx = kinematics[PK_OMEGA]
    wr = kinematics[PK_OMEGA + 1]
    wt = kinematics[PK_OMEGA + 2]
    rx = rb * ex
    rt = rb * et
    sx = vx + (wr * rt - 0.0)
    sr = vr + (wt * rx - wx * rt)
    st = vt + (0.0 - wr * rx)
    d = sx * ex + st * et
    sx -= d * ex
    st -= d * et
    s = math.sqrt(sx * sx + sr * sr + st * st)
    ur = params[PP_SLIP_REGULARISATION]
    den = math.sqrt(s * s + ur * ur)
    g = 0.0
    if den > 0.0:
        g = -params[PP_FRICTION] * fn / den
    fx = -fn * ex + g * sx
    fr = g * sr
    ft = -fn * et + g * st
    out[PO_FORCE] = fx
    out[PO_FORCE + 1] = fr
    out[PO_FORCE + 2] = ft
    # moment about the ball centre: r x F with r = (rx, 0, rt)
    out[PO_MOMENT_BALL] = 0.0 * ft - rt * fr
    out[PO_MOMENT_BALL + 1] = rt * fx - rx * ft
    out[PO_MOMENT_BALL + 2] = rx * fr - 0.0 * fx
    out[PO_NORMAL_FORCE] = fn
    out[PO_SLIP_SPEED] = s


# ================================================================================================
# Cage–land (guiding) force
# ================================================================================================
@njit(cache=True)
def _sommerfeld_angle(psi, eps):
    """Continuous Sommerfeld angle g(psi), tan(g/2) = sqrt((1+eps)/(1-eps)) tan(psi/2), g(0) = 0."""
    k = math.sqrt((1.0 + eps) / (1.0 - eps))
    return psi + 2.0 * math.atan(
        (k - 1.0) * math.sin(psi) / ((1.0 + k) + (1.0 - k) * math.cos(psi))
    )


@njit(cache=True)
def _film_integrals(psi1, psi2, eps):
    """Integrals of (sin cos, sin^2, cos^2)(psi) / (1 - eps cos psi)^3 over [psi1, psi2]."""
    g1 = _sommerfeld_angle(psi1, eps)
    g2 = _sommerfeld_angle(psi2, eps)
    q = 1.0 - eps * eps
    s1, c1 = math.sin(g1), math.cos(g1)
    s2, c2 = math.sin(g2), math.cos(g2)
    sc = ((-eps * c2 + 0.5 * s2 * s2) - (-eps * c1 + 0.5 * s1 * s1)) / (q * q)
    ss = ((0.5 * g2 - 0.5 * s2 * c2) - (0.5 * g1 - 0.5 * s1 * c1)) / (q * math.sqrt(q))
    cc = (
        ((eps * eps + 0.5) * g2 + 2.0 * eps * s2 + 0.5 * s2 * c2)
        - ((eps * eps + 0.5) * g1 + 2.0 * eps * s1 + 0.5 * s1 * c1)
    ) / (q * q * math.sqrt(q))
    return sc, ss, cc


@njit(cache=True)
def short_bearing_force(eps, a_term, b_term, radius, width, clearance, viscosity):
    """Half-Sommerfeld short-bearing force components (F_par, F_perp) on the journal [N].

    ``eps`` = e/C in [0, 1); ``a_term`` A = mean surface angular speed x e - v_perp [m/s],
    ``b_term`` B = e_dot [m/s] (module docstring). F_par is along the line of centres (negative =
    towards the centre), F_perp at +90 degrees from it about +x.
    """
    gm = math.hypot(a_term, b_term)
    if gm <= 0.0:
        return 0.0, 0.0
    psi0 = math.atan2(b_term, a_term)
    psi1 = psi0 + math.pi  # G = gm sin(psi - psi0) < 0 on (psi0 + pi, psi0 + 2 pi)
    sc, ss, cc = _film_integrals(psi1, psi1 + math.pi, eps)
    k0 = radius * viscosity * width**3 / clearance**3
    return k0 * (a_term * sc - b_term * cc), k0 * (a_term * ss - b_term * sc)


@njit(cache=True)
def land_force(kinematics, params, out):
    """Guiding-land force and torque on the cage (arrays and physics: module docstring)."""
    ey = kinematics[LK_OFFSET]
    ez = kinematics[LK_OFFSET + 1]
    vy = kinematics[LK_VELOCITY]
    vz = kinematics[LK_VELOCITY + 1]
    wc = kinematics[LK_CAGE_SPEED]
    wr = kinematics[LK_RING_SPEED]
    radius = params[LP_RADIUS]
    width = params[LP_WIDTH]
    clearance = params[LP_CLEARANCE]
    eta = params[LP_VISCOSITY]
    eps_c = params[LP_CONTACT_ECCENTRICITY]
    eps_m = params[LP_MAX_ECCENTRICITY]
    side = params[LP_CAGE_SIDE]
    e = math.hypot(ey, ez)
    # line-of-centres basis; at e = 0 take the velocity direction (the force is then basis-free)
    if e > 0.0:
        py = ey / e
        pz = ez / e
    else:
        vm = math.hypot(vy, vz)
        if vm > 0.0:
            py = vy / vm
            pz = vz / vm
        else:
            py = 1.0
            pz = 0.0
    qy = -pz  # e_perp = x × e_par
    qz = py
    v_par = vy * py + vz * pz
    v_perp = vy * qy + vz * qz
    eps = e / clearance
    # smooth cap of the hydrodynamic eccentricity
    if eps > eps_c:
        span = eps_m - eps_c
        eps_h = eps_c + span * math.tanh((eps - eps_c) / span)
    else:
        eps_h = eps
    e_h = eps_h * clearance
    a_term = 0.5 * (wc + wr) * e_h - v_perp
    f_par, f_perp = short_bearing_force(eps_h, a_term, v_par, radius, width, clearance, eta)
    hy = f_par * py + f_perp * qy
    hz = f_par * pz + f_perp * qz
    torque = (
        eta
        * radius**3
        * width
        * (wr - wc)
        / clearance
        * 2.0
        * math.pi
        / math.sqrt(1.0 - eps_h * eps_h)
        - 0.5 * e_h * f_perp
    )
    fy = hy
    fz = hz
    # metal contact once the film is thinner than (1 - eps_c) C
    fn = damped_power_law_force(
        e - eps_c * clearance,
        v_par,
        params[LP_METAL_STIFFNESS],
        params[LP_METAL_EXPONENT],
        params[LP_METAL_DAMPING_RATIO],
        params[LP_MASS],
        params[LP_DAMPING_DEPTH],
    )
    if fn > 0.0:
        # sliding of the cage surface over the land at the contact point, side*R e_par from the
        # cage centre
        s = v_perp + side * radius * (wc - wr) - wr * e
        ur = params[LP_SLIP_REGULARISATION]
        den = math.sqrt(s * s + ur * ur)
        ft = 0.0
        if den > 0.0:
            ft = -params[LP_METAL_FRICTION] * fn * s / den
        fy += -fn * py + ft * qy
        fz += -fn * pz + ft * qz
        torque += side * radius * ft
    out[LO_FORCE] = fy
    out[LO_FORCE + 1] = fz
    out[LO_TORQUE] = torque
    out[LO_RING_TORQUE] = -torque - (ey * fz - ez * fy)
    out[LO_HYDRO_FORCE] = hy
    out[LO_HYDRO_FORCE + 1] = hz
    out[LO_METAL_NORMAL] = fn
    out[LO_ECCENTRICITY] = eps
    out[LO_FILM] = clearance - e


# ================================================================================================
# Parameter builders and estimates (plain Python, validated)
# ================================================================================================
def _positive(problems: list[str], name: str, value, allow_zero=False):
    """``value`` as a float, or None after recording why it is not a (non-negative) number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        problems.append(f"{name} = {value!r}: must be a number")
        return None
    if not math.isfinite(x) or (x < 0.0 if allow_zero else x <= 0.0):
        what = "a finite number >= 0" if allow_zero else "a finite number > 0"
        problems.append(f"{name} = {value!r}: must be {what}")
        return None
    return x


def _exponent(problems: list[str], name: str, value):
    """A contact law's exponent, validated (in [1, 3]); None when it is not (the problem noted)."""
    n = _positive(problems, name, value)
    if n is not None and not 1.0 <= n <= 3.0:
        problems.append(f"{name} = {n:g}: must be in [1, 3]")
    return n


def _damping_depth(problems: list[str], damping_depth, exponent):
    """The validated damping depth [m]; None: DEFAULT_DAMPING_DEPTH for a law of exponent below
    1.5, else 0 (no damping ramp)."""
    if damping_depth is None:
        damping_depth = DEFAULT_DAMPING_DEPTH if (exponent is not None and exponent < 1.5) else 0.0
    return _positive(problems, "damping_depth", damping_depth, allow_zero=True)


def _raise(function: str, problems: list[str]) -> None:
    """ValueError listing every problem of the arguments of ``function`` (a programming error: the
    case validation keeps case values within these limits)."""
    if problems:
        raise ValueError(f"{function}: " + "; ".join(problems))


def pocket_stiffness_estimate(
    ball_diameter: float,
    pocket_clearance: float,
    ball_material,
    cage_material,
    exponent: float = 1.5,
    reference_load: float = DEFAULT_POCKET_REFERENCE_LOAD,
) -> float:
    """Pocket contact stiffness K_p for the law F = K_p (-g)^n (module docstring for the reasoning).

    ``ball_diameter`` D and diametral ``pocket_clearance`` C_p in m; materials are
    :class:`solver.materials.Material`. ``exponent`` 1.5 returns the Hertz constant [N/m^1.5] of a
    sphere in a concave cylinder of radius (D + C_p)/2; ``exponent`` 1 returns its secant stiffness
    at
    ``reference_load`` [N/m].
    """
    from solver.materials import effective_modulus
    from solver.physics.hertz import load_deflection_constant

    problems: list[str] = []
    d = _positive(problems, "ball_diameter", ball_diameter)
    cp = _positive(problems, "pocket_clearance", pocket_clearance)
    fr = _positive(problems, "reference_load", reference_load)
    if exponent not in (1, 1.0, 1.5):
        problems.append(f"exponent = {exponent!r}: must be 1 (polymer) or 1.5 (Hertz)")
    _raise("pocket_stiffness_estimate", problems)
    rb = 0.5 * d
    rp = rb + 0.5 * cp
    curvature_sum = 2.0 / rb - 1.0 / rp
    curvature_difference = (1.0 / rp) / curvature_sum
    k_h = load_deflection_constant(
        curvature_sum, curvature_difference, effective_modulus(ball_material, cage_material)
    )
    if exponent == 1.5:
        return float(k_h)
    return float(k_h ** (2.0 / 3.0) * fr ** (1.0 / 3.0))


def land_contact_stiffness_estimate(land_width: float, effective_modulus: float) -> float:
    """Linear metal-contact stiffness of the cage on its land, k = pi E' L / 4 [N/m] (estimate)."""
    problems: list[str] = []
    w = _positive(problems, "land_width", land_width)
    e = _positive(problems, "effective_modulus", effective_modulus)
    _raise("land_contact_stiffness_estimate", problems)
    return math.pi * e * w / 4.0


def pocket_parameters(
    stiffness: float,
    exponent: float,
    damping_ratio: float,
    effective_mass: float,
    friction: float,
    clearance: float,
    ball_diameter: float,
    slip_regularisation: float = 1.0e-3,
    damping_depth: float | None = None,
) -> np.ndarray:
    """Pocket parameter array (``POCKET_PARAM_SIZE``), validated; SI units (module docstring).

    ``damping_depth`` defaults to ``DEFAULT_DAMPING_DEPTH`` for n < 1.5 and 0 (no ramp) otherwise.
    """
    problems: list[str] = []
    k = _positive(problems, "stiffness", stiffness)
    n = _exponent(problems, "exponent", exponent)
    z = _positive(problems, "damping_ratio", damping_ratio, allow_zero=True)
    m = _positive(problems, "effective_mass", effective_mass)
    mu = _positive(problems, "friction", friction, allow_zero=True)
    cp = _positive(problems, "clearance", clearance)
    d = _positive(problems, "ball_diameter", ball_diameter)
    ur = _positive(problems, "slip_regularisation", slip_regularisation, allow_zero=True)
    dd = _damping_depth(problems, damping_depth, n)
    _raise("pocket_parameters", problems)
    p = np.zeros(POCKET_PARAM_SIZE)
    p[PP_STIFFNESS] = k
    p[PP_EXPONENT] = n
    p[PP_DAMPING_RATIO] = z
    p[PP_MASS] = m
    p[PP_FRICTION] = mu
    p[PP_SLIP_REGULARISATION] = ur
    p[PP_CLEARANCE] = cp
    p[PP_BALL_RADIUS] = 0.5 * d
    p[PP_DAMPING_DEPTH] = dd
    return p


def land_parameters(
    radius: float,
    width: float,
    radial_clearance: float,
    viscosity: float,
    metal_stiffness: float,
    cage_mass: float,
    cage_inside_land: bool,
    metal_exponent: float = 1.0,
    metal_damping_ratio: float = 0.05,
    metal_friction: float = 0.08,
    contact_eccentricity: float = DEFAULT_CONTACT_ECCENTRICITY,
    max_eccentricity: float = DEFAULT_MAX_ECCENTRICITY,
    slip_regularisation: float = 1.0e-3,
    damping_depth: float | None = None,
) -> np.ndarray:
    """Land parameter array (``LAND_PARAM_SIZE``), validated; SI units (module docstring).

    ``cage_inside_land`` is True for outer-ring guidance (the cage's outside diameter runs in the
    outer ring's land bore) and False for inner-ring guidance. ``viscosity`` may be 0 (dry: metal
    contact only).
    """
    problems: list[str] = []
    r = _positive(problems, "radius", radius)
    w = _positive(problems, "width", width)
    c = _positive(problems, "radial_clearance", radial_clearance)
    eta = _positive(problems, "viscosity", viscosity, allow_zero=True)
    k = _positive(problems, "metal_stiffness", metal_stiffness)
    m = _positive(problems, "cage_mass", cage_mass)
    n = _exponent(problems, "metal_exponent", metal_exponent)
    z = _positive(problems, "metal_damping_ratio", metal_damping_ratio, allow_zero=True)
    mu = _positive(problems, "metal_friction", metal_friction, allow_zero=True)
    ur = _positive(problems, "slip_regularisation", slip_regularisation, allow_zero=True)
    ec = _positive(problems, "contact_eccentricity", contact_eccentricity)
    em = _positive(problems, "max_eccentricity", max_eccentricity)
    if ec is not None and em is not None and not (0.0 < ec < em < 1.0):
        problems.append(
            f"contact_eccentricity = {ec:g} and max_eccentricity = {em:g}: "
            "need 0 < contact < max < 1"
        )
    dd = _damping_depth(problems, damping_depth, n)
    _raise("land_parameters", problems)
    p = np.zeros(LAND_PARAM_SIZE)
    p[LP_RADIUS] = r
    p[LP_WIDTH] = w
    p[LP_CLEARANCE] = c
    p[LP_VISCOSITY] = eta
    p[LP_CONTACT_ECCENTRICITY] = ec
    p[LP_MAX_ECCENTRICITY] = em
    p[LP_METAL_STIFFNESS] = k
    p[LP_METAL_EXPONENT] = n
    p[LP_METAL_DAMPING_RATIO] = z
    p[LP_MASS] = m
    p[LP_METAL_FRICTION] = mu
    p[LP_SLIP_REGULARISATION] = ur
    p[LP_CAGE_SIDE] = 1.0 if cage_inside_land else -1.0
    p[LP_DAMPING_DEPTH] = dd
    return p
