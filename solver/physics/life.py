"""Rating life of an angular contact ball bearing: ISO 281 basic rating life and ISO/TS 16281
reference rating life from computed contact loads. Pure functions, SI units (m, N, rad).

**ISO 281:2007 basic rating life** (clauses 5 and 6, single-row angular contact ball bearing):

- basic dynamic radial load rating (clause 6.1.1, eq. 2 and 3, in N with D_w in mm)
  ``C_r = b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.8`` for D_w <= 25.4 mm, and
  ``C_r = 3.647 b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.4`` above; ``b_m = 1.3`` (Table 2, radial
  ball bearings), ``f_c`` from Table 1 (column "single-row radial contact groove ball bearings and
  angular contact groove ball bearings") at ``D_w cos alpha / D_pw``, linear in between. Table 1
  holds for groove radii up to 0.52 D_w on the inner ring and 0.53 D_w on the outer ring (the
  conformities its f_c values were computed with, ISO/TR 1281-1); a larger groove radius lowers
  the rating and the standard asks for a correspondingly reduced f_c, a smaller one does not raise
  it (the condition that goes with clause 6.1.1; the standard's text was not available here to
  quote it). The reduction here is the one of the Lundberg–Palmgren theory behind Table 1
  (ISO/TR 1281-1): f_c scales as the bearing's rating from its two raceway ratings (below),
  ``Q_c = (Q_ci^(-10/3) + Q_ce^(-10/3))^(-3/10)``, so it is multiplied by ``Q_c(max(f_i, 0.52),
  max(f_o, 0.53)) / Q_c(0.52, 0.53)`` at the same gamma (:func:`groove_radius_factor`; 0.807 for
  the 7008C-class spindle bearing with f_i = 0.54, f_o = 0.53, whose life is then 0.525 of the
  table's);
- dynamic equivalent radial load (clause 6.2, Table 3) ``P_r = X F_r + Y F_a`` when
  ``F_a / F_r > e``, else ``P_r = F_r`` (single row). For alpha = 15 deg, e and Y depend on
  ``f_0 F_a / C_0r = F_a / (i Z D_w^2 cos alpha)`` (N/mm^2, ISO 76: ``C_0r = f_0 i Z D_w^2 cos
  alpha``); intermediate contact angles (15 to 45 deg) and loads are interpolated linearly, loads
  outside the table take its end rows;
- ``L_10 = (C_r / P_r)^3`` million revolutions (clause 6.2, eq. 5).

**ISO/TS 16281:2008 reference rating life** (ball bearings; its clause on the basic reference
rating life of ball bearings: raceway load ratings, dynamic equivalent rolling-element loads and
the combination of the raceway lives; the text of the technical specification was not available
to check clause and equation numbers against, so the formulas are named rather than numbered):
from the normal load Q of every ball–race contact, and the contact angle at which it acts,

- basic dynamic load rating of a ball–raceway contact (Lundberg–Palmgren, ISO/TR 1281-1), N with
  D_w in mm, gamma = D_w cos alpha / D_pw:
  ``Q_ci = b_m 98.1 (2 f_i / (2 f_i - 1))^0.41 (1 - gamma)^1.39 / (1 + gamma)^(1/3)
  (gamma / cos alpha)^0.3 D_w^1.8 Z^(-1/3)``, and for the outer raceway ``f_o`` with
  ``(1 + gamma)^1.39 / (1 - gamma)^(1/3)``; above D_w = 25.4 mm ``D_w^1.8`` becomes
  ``3.647 D_w^1.4`` as in ISO 281;
- dynamic equivalent load of each raceway: for a ring that rotates relative to the load the cubic
  mean ``Q_e = ((1/N) sum Q^3)^(1/3)``, for a ring that stands still relative to the load the
  ``10/3`` mean ``Q_e = ((1/N) sum Q^(10/3))^(3/10)``. Here the contact angle (so Q_c) may differ
  from ball to ball; the ratio form ``L = ((1/N) sum (Q / Q_c)^w)^(-3/w)`` keeps each contact's
  own Q_c and equals ``(Q_c / Q_e)^3`` when the angles agree. N counts every sample (balls, and
  time samples of a dynamic run);
- raceway lives ``L_k = (Q_ck / Q_ek)^3`` and the bearing ``L_10r = (L_i^(-e) + L_o^(-e))^(-1/e)``
  with ``e = 10/9`` for ball bearings, in million revolutions of one ring relative to the other.

The raceway ratings carry the bearing's own conformities f_i, f_o, while the ISO 281 C_r above
carries them only through the groove-radius reduction of f_c; with that reduction the two methods
agree for a load both describe alike (the spindle bearing under a pure axial load: L_10r =
1.05 L_10, where Table 1's f_c alone, that of f_i = 0.52, puts L_10r 45 % below L_10).

Clearance, misalignment and the load distribution enter only through the loads Q and angles
alpha (that is the point of the reference rating life). Both methods assume rings and balls of
through-hardened bearing steel of ordinary quality (b_m = 1.3); no life modification factor
(a_ISO, reliability) is applied.
"""

from __future__ import annotations

import math

import numpy as np

B_M = 1.3  # ISO 281 Table 2: radial ball bearings (not filling-slot)
LIFE_EXPONENT = 3.0  # ISO 281 eq. 5, ball bearings
WEIBULL_EXPONENT = 10.0 / 9.0  # ISO/TS 16281: e for ball bearings
ROTATING_MEAN_EXPONENT = 3.0  # ring rotating relative to the load
STATIONARY_MEAN_EXPONENT = 10.0 / 3.0  # ring stationary relative to the load
LARGE_BALL_MM = 25.4  # ISO 281 eq. 2 / eq. 3 switch
#: Groove radius ratios r / D_w the f_c values of ISO 281 Table 1 hold for (ISO/TR 1281-1)
TABLE_INNER_CONFORMITY = 0.52
TABLE_OUTER_CONFORMITY = 0.53

# ISO 281:2007 Table 1, single-row radial / angular contact groove ball bearings:
# D_w cos(alpha) / D_pw -> f_c
_FC_GAMMA = np.array(
    [0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20]
    + [0.22, 0.24, 0.26, 0.28, 0.30, 0.32, 0.34, 0.36, 0.38, 0.40]
)
_FC = np.array(
    [29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 57.5, 58.8, 59.6, 59.9, 59.9]
    + [59.6, 59.0, 58.2, 57.1, 56.0, 54.6, 53.2, 51.7, 50.0, 48.4]
)

# ISO 281:2007 Table 3, single-row angular contact ball bearings, F_a / F_r > e.
# alpha = 15 deg: rows by f_0 F_a / C_0r [N/mm^2], X = 0.44
_A15_LOAD = np.array([0.178, 0.357, 0.714, 1.07, 1.43, 2.14, 3.57, 5.35, 7.14])
_A15_E = np.array([0.38, 0.40, 0.43, 0.46, 0.47, 0.50, 0.55, 0.56, 0.56])
_A15_Y = np.array([1.47, 1.40, 1.30, 1.23, 1.19, 1.12, 1.02, 1.00, 1.00])
_A15_X = 0.44
# alpha >= 20 deg: alpha [deg] -> e, X, Y
_ANGLES = np.array([20.0, 25.0, 30.0, 35.0, 40.0, 45.0])
_ANGLE_E = np.array([0.57, 0.68, 0.80, 0.95, 1.14, 1.34])
_ANGLE_X = np.array([0.43, 0.41, 0.39, 0.37, 0.35, 0.33])
_ANGLE_Y = np.array([1.00, 0.87, 0.76, 0.66, 0.57, 0.50])
MIN_CONTACT_ANGLE_DEG = 15.0
MAX_CONTACT_ANGLE_DEG = 45.0


class LifeRangeError(ValueError):
    """The bearing lies outside the tables of the standard (message: which value, which range)."""


def _mm(length_m: float) -> float:
    return 1000.0 * length_m


def _diameter_term(ball_diameter_mm: float) -> float:
    """D_w^1.8 (D_w <= 25.4 mm) or 3.647 D_w^1.4 (ISO 281 eq. 2 and 3), D_w in mm."""
    if ball_diameter_mm <= LARGE_BALL_MM:
        return ball_diameter_mm**1.8
    return 3.647 * ball_diameter_mm**1.4


def rating_factor_fc(gamma: float) -> float:
    """ISO 281 Table 1 factor f_c at gamma = D_w cos(alpha) / D_pw, linear between the rows.
    LifeRangeError outside 0.01 to 0.40."""
    if not (_FC_GAMMA[0] <= gamma <= _FC_GAMMA[-1]):
        raise LifeRangeError(
            f"D_w cos(alpha) / D_pw = {gamma:.4g} lies outside ISO 281 Table 1 "
            f"({_FC_GAMMA[0]:g} to {_FC_GAMMA[-1]:g})"
        )
    return float(np.interp(gamma, _FC_GAMMA, _FC))


def groove_radius_factor(
    ball_diameter: float,
    pitch_diameter: float,
    inner_conformity: float,
    outer_conformity: float,
    contact_angle: float,
    ball_count: int,
) -> float:
    """Reduction (<= 1) of the ISO 281 Table 1 f_c for groove radii larger than the table's
    (module docstring): ``Q_c(max(f_i, 0.52), max(f_o, 0.53)) / Q_c(0.52, 0.53)`` with the
    bearing's rating ``Q_c = (Q_ci^(-10/3) + Q_ce^(-10/3))^(-3/10)`` from the raceway ratings
    (:func:`raceway_load_rating`) at the nominal ``contact_angle`` [rad]. Lengths in m."""

    def bearing_rating(f_i: float, f_o: float) -> float:
        q_i = raceway_load_rating(
            ball_diameter, pitch_diameter, f_i, contact_angle, ball_count, True
        )
        q_o = raceway_load_rating(
            ball_diameter, pitch_diameter, f_o, contact_angle, ball_count, False
        )
        return (q_i ** (-10.0 / 3.0) + q_o ** (-10.0 / 3.0)) ** -0.3

    own = bearing_rating(
        max(inner_conformity, TABLE_INNER_CONFORMITY), max(outer_conformity, TABLE_OUTER_CONFORMITY)
    )
    return own / bearing_rating(TABLE_INNER_CONFORMITY, TABLE_OUTER_CONFORMITY)


def basic_dynamic_load_rating(
    ball_diameter: float,
    pitch_diameter: float,
    contact_angle: float,
    ball_count: int,
    rows: int = 1,
    inner_conformity: float = TABLE_INNER_CONFORMITY,
    outer_conformity: float = TABLE_OUTER_CONFORMITY,
) -> float:
    """ISO 281 basic dynamic radial load rating C_r [N] of a radial or angular contact ball
    bearing.

    ``ball_diameter`` D_w and ``pitch_diameter`` D_pw in m, nominal ``contact_angle`` alpha in
    rad, ``ball_count`` Z per row, ``rows`` i, groove radius ratios ``inner_conformity`` f_i and
    ``outer_conformity`` f_o (larger than the table's 0.52 / 0.53: f_c reduced by
    :func:`groove_radius_factor`)."""
    gamma = ball_diameter * math.cos(contact_angle) / pitch_diameter
    fc = rating_factor_fc(gamma) * groove_radius_factor(
        ball_diameter, pitch_diameter, inner_conformity, outer_conformity, contact_angle, ball_count
    )
    d_mm = _mm(ball_diameter)
    return (
        B_M
        * fc
        * (rows * math.cos(contact_angle)) ** 0.7
        * ball_count ** (2.0 / 3.0)
        * _diameter_term(d_mm)
    )


def load_factors(
    axial_load: float,
    radial_load: float,
    contact_angle: float,
    ball_diameter: float,
    ball_count: int,
    rows: int = 1,
) -> tuple[float, float, float]:
    """(X, Y, e) of ISO 281 Table 3 for a single-row angular contact ball bearing.

    Loads in N (magnitudes), ``contact_angle`` in rad (15 to 45 deg, else LifeRangeError),
    ``ball_diameter`` in m. (1, 0, e) when F_a / F_r <= e; a pure radial load gives (1, 0, nan)
    at any contact angle (the rule F_a / F_r <= e holds in every row of the table)."""
    alpha_deg = math.degrees(contact_angle)
    if axial_load == 0.0:
        return 1.0, 0.0, math.nan
    if not (MIN_CONTACT_ANGLE_DEG - 1e-9 <= alpha_deg <= MAX_CONTACT_ANGLE_DEG + 1e-9):
        raise LifeRangeError(
            f"nominal contact angle {alpha_deg:.3g} deg: the X, Y factors of ISO 281 Table 3 are "
            f"used here for {MIN_CONTACT_ANGLE_DEG:g} to {MAX_CONTACT_ANGLE_DEG:g} deg"
        )
    fa, fr = abs(axial_load), abs(radial_load)
    # f_0 F_a / C_0r with C_0r = f_0 i Z D_w^2 cos(alpha) (ISO 76), N and mm
    relative = fa / (rows * ball_count * _mm(ball_diameter) ** 2 * math.cos(contact_angle))
    e15 = float(np.interp(relative, _A15_LOAD, _A15_E))
    y15 = float(np.interp(relative, _A15_LOAD, _A15_Y))
    if alpha_deg <= _ANGLES[0]:
        t = (alpha_deg - MIN_CONTACT_ANGLE_DEG) / (_ANGLES[0] - MIN_CONTACT_ANGLE_DEG)
        t = min(max(t, 0.0), 1.0)
        e = e15 + t * (_ANGLE_E[0] - e15)
        x = _A15_X + t * (_ANGLE_X[0] - _A15_X)
        y = y15 + t * (_ANGLE_Y[0] - y15)
    else:
        e = float(np.interp(alpha_deg, _ANGLES, _ANGLE_E))
        x = float(np.interp(alpha_deg, _ANGLES, _ANGLE_X))
        y = float(np.interp(alpha_deg, _ANGLES, _ANGLE_Y))
    if fr > 0.0 and fa / fr <= e:
        return 1.0, 0.0, e
    return x, y, e


def equivalent_dynamic_load(
    axial_load: float,
    radial_load: float,
    contact_angle: float,
    ball_diameter: float,
    ball_count: int,
    rows: int = 1,
) -> float:
    """ISO 281 dynamic equivalent radial load P_r = X F_r + Y F_a [N] (arguments as
    :func:`load_factors`)."""
    x, y, _ = load_factors(axial_load, radial_load, contact_angle, ball_diameter, ball_count, rows)
    return x * abs(radial_load) + y * abs(axial_load)


def basic_rating_life(load_rating: float, equivalent_load: float) -> float:
    """ISO 281 L_10 = (C / P)^3 in million revolutions; inf when P = 0."""
    if equivalent_load <= 0.0:
        return math.inf
    return (load_rating / equivalent_load) ** LIFE_EXPONENT


def raceway_load_rating(
    ball_diameter: float,
    pitch_diameter: float,
    conformity: float,
    contact_angle,
    ball_count: int,
    inner: bool,
):
    """ISO/TS 16281 basic dynamic load rating Q_c [N] of one ball–raceway contact (module
    docstring). Lengths in m, ``conformity`` f = groove radius / D_w, ``contact_angle`` [rad]
    (scalar or array: one Q_c per contact angle); ``inner`` selects the raceway."""
    alpha = np.asarray(contact_angle, dtype=float)
    gamma = ball_diameter * np.cos(alpha) / pitch_diameter
    osculation = (2.0 * conformity / (2.0 * conformity - 1.0)) ** 0.41
    if inner:
        curvature = (1.0 - gamma) ** 1.39 / (1.0 + gamma) ** (1.0 / 3.0)
    else:
        curvature = (1.0 + gamma) ** 1.39 / (1.0 - gamma) ** (1.0 / 3.0)
    value = (
        B_M
        * 98.1
        * osculation
        * curvature
        * (ball_diameter / pitch_diameter) ** 0.3  # (gamma / cos alpha)^0.3
        * _diameter_term(_mm(ball_diameter))
        * ball_count ** (-1.0 / 3.0)
    )
    return value if value.ndim else float(value)


def raceway_life(loads, load_ratings, rotating: bool) -> float:
    """Life of one raceway [million revolutions] from the normal loads Q [N] of its contacts
    (every ball, every sample) and each contact's rating Q_c [N] (same shape, or a scalar):
    ``((1/N) sum (Q / Q_c)^w)^(-3/w)`` with w = 3 for a ring rotating relative to the load,
    10/3 for one stationary relative to it. Open contacts (Q = 0) count as samples without load.
    inf when no contact carries load."""
    q = np.asarray(loads, dtype=float).ravel()
    qc = np.broadcast_to(np.asarray(load_ratings, dtype=float), np.shape(loads)).ravel()
    if q.size == 0:
        raise ValueError("raceway_life needs at least one contact load")
    w = ROTATING_MEAN_EXPONENT if rotating else STATIONARY_MEAN_EXPONENT
    mean = float(np.mean((np.clip(q, 0.0, None) / qc) ** w))
    if mean <= 0.0:
        return math.inf
    return mean ** (-LIFE_EXPONENT / w)


def equivalent_contact_load(loads, rotating: bool) -> float:
    """Dynamic equivalent rolling-element load Q_e [N] of one raceway: the cubic mean (ring
    rotating relative to the load) or the 10/3 mean (ring stationary relative to the load) of
    the contact loads Q [N] over every ball (and sample)."""
    q = np.clip(np.asarray(loads, dtype=float).ravel(), 0.0, None)
    w = ROTATING_MEAN_EXPONENT if rotating else STATIONARY_MEAN_EXPONENT
    return float(np.mean(q**w) ** (1.0 / w))


def combined_life(inner_life: float, outer_life: float) -> float:
    """ISO/TS 16281 bearing life from the raceway lives [million revolutions]:
    (L_i^(-e) + L_o^(-e))^(-1/e), e = 10/9."""
    e = WEIBULL_EXPONENT
    total = 0.0
    for life in (inner_life, outer_life):
        if math.isfinite(life):
            total += life ** (-e)
    return math.inf if total == 0.0 else total ** (-1.0 / e)


def life_hours(million_revolutions: float, relative_speed: float) -> float:
    """Life in hours at ``relative_speed`` [rad/s] of one ring relative to the other; inf when
    the rings do not turn relative to each other or the hours exceed a float (Python float
    arithmetic: inf, not a numpy overflow warning)."""
    revolutions_per_hour = abs(float(relative_speed)) / (2.0 * math.pi) * 3600.0
    if revolutions_per_hour == 0.0:
        return math.inf
    return float(million_revolutions) * 1e6 / revolutions_per_hour


__all__ = [
    "B_M",
    "TABLE_INNER_CONFORMITY",
    "TABLE_OUTER_CONFORMITY",
    "LifeRangeError",
    "basic_dynamic_load_rating",
    "basic_rating_life",
    "combined_life",
    "equivalent_contact_load",
    "equivalent_dynamic_load",
    "groove_radius_factor",
    "life_hours",
    "load_factors",
    "raceway_life",
    "raceway_load_rating",
    "rating_factor_fc",
]
