"""Exact Hertz point contact between a ball and a raceway (physics.md §2.2-2.3), SI units.

Reference implementation: complete elliptic integrals from SciPy and the ellipticity found by root
finding. It is vectorised over numpy arrays where that is natural and is the reference against which
:mod:`solver.physics.hertz_fast` (the numba version used inside kernels) is tabulated and tested.

Notation (physics.md §2.3): ``curvature_sum`` is Σρ [1/m], ``curvature_difference`` is F(ρ) [-],
``effective_modulus`` is E' = 2/η [Pa] with η = (1-ν1²)/E1 + (1-ν2²)/E2, R = 1/Σρ [m]. The contact
ellipse has semi-major axis ``a`` across the groove (transverse direction) and semi-minor axis
``b`` in the rolling direction; κ = a/b ≥ 1. Elliptic integrals use the *parameter* m = 1 - 1/κ²
(SciPy convention: K(m) = ∫(1 - m sin²t)^(-1/2) dt).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.special import ellipe, ellipk, ellipkm1

__all__ = [
    "HertzContact",
    "curvature_sum_and_difference",
    "equivalent_radii",
    "ellipticity_exact",
    "ellipticity_residual",
    "hertz_contact",
    "load_deflection_constant",
    "series_stiffness",
    "race_contact",
    "shoulder_angle",
    "shoulder_diameter_limits",
    "truncation_margin",
]

_RACES = ("inner", "outer")

# Upper end of the bisection bracket in t = ln(kappa). kappa = e^40 ≈ 2e17 is far beyond the
# largest kappa reachable with F < 1 in double precision (F = 1 - 1.1e-16 gives kappa ≈ 1e10).
_T_MAX = 40.0
_BISECTION_STEPS = 200  # stops earlier once the bracket no longer shrinks (machine precision)

# Below this parameter m the ellipticity function is evaluated from its power series (the closed
# form loses digits to cancellation near the circle, where its numerator is O(m²)).
_SERIES_M_MAX = 0.5
_SERIES_TERMS = 72  # 0.5**72 ≈ 2e-22: series truncation far below double precision


def _series_coefficients(n_terms: int) -> np.ndarray:
    """Coefficients c_n with (2-m)E(m) - 2(1-m)K(m) = (π/2) m² Σ c_n m^n.

    From K = (π/2) Σ a_n m^n, E = (π/2) Σ a_n m^n / (1 - 2n), a_n = [(2n-1)!!/(2n)!!]².
    """
    n_all = n_terms + 2
    a = np.empty(n_all)
    a[0] = 1.0
    for n in range(1, n_all):
        a[n] = a[n - 1] * ((2.0 * n - 1.0) / (2.0 * n)) ** 2
    k = a
    e = a / (1.0 - 2.0 * np.arange(n_all))
    prev_e = np.concatenate(([0.0], e[:-1]))
    prev_k = np.concatenate(([0.0], k[:-1]))
    numerator = 2.0 * e - prev_e - 2.0 * k + 2.0 * prev_k
    return numerator[2:].copy()


_SERIES_C = _series_coefficients(_SERIES_TERMS)


def _coefficients_from_log_kappa(t: np.ndarray):
    """(F, kappa, K(m), E(m)) for t = ln(kappa) ≥ 0 (arrays), accurate at both ends.

    F(ρ) = [(κ²+1)E - 2K] / [(κ²-1)E] = [(2-m)E - 2(1-m)K] / (m E) with m = 1 - 1/κ².
    p = 1 - m = e^(-2t) is carried separately so that K stays accurate for very large κ.
    """
    t = np.asarray(t, dtype=float)
    p = np.exp(-2.0 * t)
    m = -np.expm1(-2.0 * t)
    kappa = np.exp(t)
    big_k = ellipkm1(p)
    big_e = ellipe(m)
    f = np.empty_like(m)
    small = m <= _SERIES_M_MAX
    if np.any(small):
        ms = m[small]
        series = np.zeros_like(ms)
        for c in _SERIES_C[::-1]:  # Horner
            series = series * ms + c
        f[small] = 0.5 * math.pi * ms * series / big_e[small]
    large = ~small
    if np.any(large):
        ml, el, kl, pl = m[large], big_e[large], big_k[large], p[large]
        f[large] = ((2.0 - ml) * el - 2.0 * pl * kl) / (ml * el)
    return f, kappa, big_k, big_e


def ellipticity_residual(kappa, curvature_difference):
    """Residual of the ellipticity equation, evaluated directly with scipy's ellipk/ellipe.

    Returns ``[(κ²+1)E(m) - 2K(m)] / [(κ²-1)E(m)] - F`` with m = 1 - 1/κ² (κ > 1). Independent
    of the series used inside :func:`ellipticity_exact`; loses accuracy (cancellation) as κ → 1.
    """
    kappa = np.asarray(kappa, dtype=float)
    m = 1.0 - 1.0 / kappa**2
    big_k, big_e = ellipk(m), ellipe(m)
    return ((kappa**2 + 1.0) * big_e - 2.0 * big_k) / (
        (kappa**2 - 1.0) * big_e
    ) - curvature_difference


def ellipticity_exact(curvature_difference):
    """Ellipticity κ = a/b and complete elliptic integrals for a curvature difference F(ρ).

    Solves F(ρ) = [(κ²+1)E(m) - 2K(m)] / [(κ²-1)E(m)], m = 1 - 1/κ², by bisection on t = ln κ
    (vectorised; F is strictly increasing in κ, so the bracket [κ = 1, κ = e^40] always holds the
    root; the bisection runs to machine precision). F = 0 returns the circle κ = 1, K = E = π/2.

    Parameters
    ----------
    curvature_difference : float or array, 0 ≤ F < 1.

    Returns
    -------
    (kappa, elliptic_k, elliptic_e) : floats (or arrays shaped like the input); K and E are the
    complete elliptic integrals of the first and second kind at parameter m = 1 - 1/κ².

    Raises
    ------
    ValueError if any F is NaN, negative or ≥ 1.
    """
    f_in = np.asarray(curvature_difference, dtype=float)
    scalar = f_in.ndim == 0
    f = np.atleast_1d(f_in).ravel()
    bad = ~((f >= 0.0) & (f < 1.0))
    if np.any(bad):
        raise ValueError(
            f"curvature_difference = {f[bad][0]!r}: the curvature difference F(rho) must satisfy "
            "0 <= F < 1"
        )
    lo = np.zeros_like(f)
    hi = np.full_like(f, _T_MAX)
    for _ in range(_BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        f_mid = _coefficients_from_log_kappa(mid)[0]
        below = f_mid < f
        new_lo = np.where(below, mid, lo)
        new_hi = np.where(below, hi, mid)
        if np.array_equal(new_lo, lo) and np.array_equal(new_hi, hi):
            break
        lo, hi = new_lo, new_hi
    # pick the end of the final bracket with the smaller residual
    f_lo, _, _, _ = _coefficients_from_log_kappa(lo)
    f_hi, _, _, _ = _coefficients_from_log_kappa(hi)
    t = np.where(np.abs(f_lo - f) <= np.abs(f_hi - f), lo, hi)
    t = np.where(f == 0.0, 0.0, t)
    _, kappa, big_k, big_e = _coefficients_from_log_kappa(t)
    shape = f_in.shape
    if scalar:
        return float(kappa[0]), float(big_k[0]), float(big_e[0])
    return kappa.reshape(shape), big_k.reshape(shape), big_e.reshape(shape)


# ---- curvature ----------------------------------------------------------------------------------
def _check_race(race: str) -> None:
    if race not in _RACES:
        raise ValueError(f"race = {race!r}: must be one of {_RACES}")


def _check_ball_race(ball_diameter, conformity, gamma) -> None:
    if not np.all(np.asarray(ball_diameter) > 0.0):
        raise ValueError(f"ball_diameter = {ball_diameter!r}: must be > 0 (m)")
    if not np.all(np.asarray(conformity) > 0.5):
        raise ValueError(
            f"conformity = {conformity!r}: groove radius / ball diameter must be > 0.5"
        )
    g = np.asarray(gamma)
    if not np.all((g >= 0.0) & (g < 1.0)):
        raise ValueError(
            f"gamma = {gamma!r}: gamma = D cos(alpha) / d_m must satisfy 0 <= gamma < 1"
        )


def curvature_sum_and_difference(ball_diameter, conformity, gamma, race: str):
    """Curvature sum Σρ [1/m] and curvature difference F(ρ) [-] of a ball-raceway contact.

    Closed forms of physics.md §2.3, with D = ``ball_diameter`` [m], f = ``conformity``
    (groove radius / D), γ = D cos α / d_m:

    * inner: Σρ = (4 - 1/f + 2γ/(1-γ)) / D,   F = (1/f + 2γ/(1-γ)) / (D Σρ)
    * outer: Σρ = (4 - 1/f - 2γ/(1+γ)) / D,   F = (1/f - 2γ/(1+γ)) / (D Σρ)

    ``race`` is "inner" or "outer". Array inputs broadcast.
    """
    _check_race(race)
    _check_ball_race(ball_diameter, conformity, gamma)
    d = np.asarray(ball_diameter, dtype=float)
    f = np.asarray(conformity, dtype=float)
    g = np.asarray(gamma, dtype=float)
    if race == "inner":
        race_term = 2.0 * g / (1.0 - g)
    else:
        race_term = -2.0 * g / (1.0 + g)
    d_sum = 4.0 - 1.0 / f + race_term
    curvature_sum = d_sum / d
    curvature_difference = (1.0 / f + race_term) / d_sum
    if curvature_sum.ndim == 0:
        return float(curvature_sum), float(curvature_difference)
    return curvature_sum, curvature_difference


def equivalent_radii(ball_diameter, conformity, gamma, race: str):
    """Equivalent radii (R_x, R_y) [m] in the rolling and transverse planes.

    R_x = (D/2)(1 - γ) (inner) or (D/2)(1 + γ) (outer); R_y = f D / (2f - 1). They satisfy
    1/R_x + 1/R_y = Σρ and (1/R_x - 1/R_y)/Σρ = F(ρ).
    """
    _check_race(race)
    _check_ball_race(ball_diameter, conformity, gamma)
    d = np.asarray(ball_diameter, dtype=float)
    f = np.asarray(conformity, dtype=float)
    g = np.asarray(gamma, dtype=float)
    r_x = 0.5 * d * (1.0 - g) if race == "inner" else 0.5 * d * (1.0 + g)
    r_y = f * d / (2.0 * f - 1.0)
    if np.ndim(r_x) == 0 and np.ndim(r_y) == 0:
        return float(r_x), float(r_y)
    return r_x, r_y


# ---- contact ------------------------------------------------------------------------------------
class HertzContact(NamedTuple):
    """Result of a Hertz point-contact calculation (floats, or arrays for array input).

    semi_major a [m] (transverse, across the groove), semi_minor b [m] (rolling direction),
    approach delta [m] (mutual approach of distant points of the two bodies), max_pressure [Pa],
    stiffness K [N/m^1.5] with Q = K delta^1.5, kappa = a/b [-], elliptic_k and elliptic_e [-]
    (complete elliptic integrals at m = 1 - 1/kappa²).
    """

    semi_major: float
    semi_minor: float
    approach: float
    max_pressure: float
    stiffness: float
    kappa: float
    elliptic_k: float
    elliptic_e: float


def _check_contact_inputs(curvature_sum, effective_modulus) -> None:
    s = np.asarray(curvature_sum, dtype=float)
    e = np.asarray(effective_modulus, dtype=float)
    if not np.all((s > 0.0) & np.isfinite(s)):
        raise ValueError(f"curvature_sum = {curvature_sum!r}: must be finite and > 0 (1/m)")
    if not np.all((e > 0.0) & np.isfinite(e)):
        raise ValueError(f"effective_modulus = {effective_modulus!r}: must be finite and > 0 (Pa)")


def _stiffness(kappa, big_k, big_e, curvature_sum, effective_modulus):
    r = 1.0 / np.asarray(curvature_sum, dtype=float)
    return math.pi * kappa * effective_modulus * np.sqrt(2.0 * big_e * r / (9.0 * big_k**3))


def load_deflection_constant(curvature_sum, curvature_difference, effective_modulus):
    """Hertz load-deflection constant K [N/m^1.5] with Q = K δ^1.5.

    K = π κ E' sqrt(2 E R / (9 K(m)³)), R = 1/Σρ (physics.md §2.3 step 3); independent of the load.
    """
    _check_contact_inputs(curvature_sum, effective_modulus)
    kappa, big_k, big_e = ellipticity_exact(curvature_difference)
    k = _stiffness(kappa, big_k, big_e, curvature_sum, effective_modulus)
    return float(k) if np.ndim(k) == 0 else k


def series_stiffness(k_inner, k_outer):
    """Stiffness of two Hertz contacts in series (a ball between two races) [N/m^1.5].

    K_n = [K_i^(-2/3) + K_o^(-2/3)]^(-3/2): the approaches add at equal load.
    """
    ki = np.asarray(k_inner, dtype=float)
    ko = np.asarray(k_outer, dtype=float)
    if not (np.all(ki > 0.0) and np.all(ko > 0.0)):
        raise ValueError(f"k_inner = {k_inner!r}, k_outer = {k_outer!r}: stiffnesses must be > 0")
    k = (ki ** (-2.0 / 3.0) + ko ** (-2.0 / 3.0)) ** -1.5
    return float(k) if k.ndim == 0 else k


def hertz_contact(load, curvature_sum, curvature_difference, effective_modulus) -> HertzContact:
    """Exact Hertz solution for a normal ``load`` Q [N] ≥ 0.

    a = (6κ²E Q R/(πE'))^(1/3), b = (6E Q R/(πκE'))^(1/3),
    δ = K(m) [9/(2E R) (Q/(πκE'))²]^(1/3), p_max = 3Q/(2πab), R = 1/Σρ.
    Zero load gives zero sizes, approach and pressure (κ, K, E and the stiffness stay defined).
    Raises ValueError for a negative or non-finite load, Σρ ≤ 0, E' ≤ 0 or F outside [0, 1).
    """
    q = np.asarray(load, dtype=float)
    if not np.all((q >= 0.0) & np.isfinite(q)):
        raise ValueError(f"load = {load!r}: the normal contact load must be finite and >= 0 (N)")
    _check_contact_inputs(curvature_sum, effective_modulus)
    kappa, big_k, big_e = ellipticity_exact(curvature_difference)
    r = 1.0 / np.asarray(curvature_sum, dtype=float)
    e_mod = np.asarray(effective_modulus, dtype=float)
    qr = q * r
    a = np.cbrt(6.0 * kappa**2 * big_e * qr / (math.pi * e_mod))
    b = np.cbrt(6.0 * big_e * qr / (math.pi * kappa * e_mod))
    delta = big_k * np.cbrt(4.5 / (big_e * r) * (q / (math.pi * kappa * e_mod)) ** 2)
    ab = a * b
    with np.errstate(invalid="ignore", divide="ignore"):
        p_max = np.where(ab > 0.0, 1.5 * q / (math.pi * np.where(ab > 0.0, ab, 1.0)), 0.0)
    stiffness = _stiffness(kappa, big_k, big_e, curvature_sum, e_mod)
    parts = np.broadcast_arrays(a, b, delta, p_max, stiffness, kappa, big_k, big_e)
    if parts[0].ndim == 0:
        return HertzContact(*(float(x) for x in parts))
    return HertzContact(*(np.array(x) for x in parts))


# ---- bearing convenience ------------------------------------------------------------------------
def _race_conformity(geometry, race: str) -> float:
    _check_race(race)
    return geometry.inner_conformity if race == "inner" else geometry.outer_conformity


def race_contact(geometry, contact_angle, load, race: str) -> HertzContact:
    """Hertz contact of a ball with the ``race`` ("inner"/"outer") of a :class:`BearingGeometry`.

    ``contact_angle`` α [rad] sets γ = D cos α / d_m; ``load`` Q [N] ≥ 0; E' from the ball and ring
    materials.
    """
    conformity = _race_conformity(geometry, race)
    gamma = (
        geometry.ball_diameter
        * np.cos(np.asarray(contact_angle, dtype=float))
        / (geometry.pitch_diameter)
    )
    s, f = curvature_sum_and_difference(geometry.ball_diameter, conformity, gamma, race)
    return hertz_contact(load, s, f, geometry.effective_modulus)


def shoulder_diameter_limits(geometry, race: str) -> tuple[float, float]:
    """Range [m] of shoulder (land) diameters that lie on the ``race`` groove arc, (low, high).

    The groove arc runs from the groove bottom (θ = 0) to the height of its curvature centre
    (θ = 90°): inner [d_i, 2ρ_i^c], outer [2ρ_o^c, d_o]. A shoulder outside this range is not on the
    groove (an inner land below the groove bottom, an outer land above it, or a land past the
    groove's quarter circle) and :func:`shoulder_angle` rejects it.
    """
    _check_race(race)
    if race == "inner":
        return geometry.inner_groove_bottom_diameter, 2.0 * geometry.inner_curvature_center_radius
    return 2.0 * geometry.outer_curvature_center_radius, geometry.outer_groove_bottom_diameter


def shoulder_angle(geometry, race: str) -> float:
    """Groove angle θ_sh [rad] of the ``race`` shoulder from the groove bottom; NaN if absent.

    The groove (radius r, curvature centre at radius ρ^c in the ring frame) reaches radius
    ρ^c - r cos θ (inner) or ρ^c + r cos θ (outer) at groove angle θ. The shoulder diameter
    d_sh gives inner: cos θ_sh = (ρ_i^c - d_sh/2)/r_i; outer: cos θ_sh = (d_sh/2 - ρ_o^c)/r_o.
    A shoulder diameter outside :func:`shoulder_diameter_limits` is clamped to the groove (θ_sh = 0
    below the groove bottom, π beyond the far side); callers warn the user about such data.
    """
    _check_race(race)
    if race == "inner":
        d_sh = geometry.inner_shoulder_diameter
        cos_sh = (
            geometry.inner_curvature_center_radius - 0.5 * d_sh
        ) / geometry.inner_groove_radius
    else:
        d_sh = geometry.outer_shoulder_diameter
        cos_sh = (
            0.5 * d_sh - geometry.outer_curvature_center_radius
        ) / geometry.outer_groove_radius
    if d_sh is None or math.isnan(d_sh):
        return math.nan
    # A land that does not rise above the groove bottom (cos > 1) offers no shoulder: θ_sh = 0,
    # so every contact reports a negative (truncated) margin. Case checks warn about it.
    return math.acos(min(1.0, max(-1.0, cos_sh)))


def truncation_margin(geometry, contact_angle, semi_major, race: str):
    """Angular margin [degrees] between the contact ellipse's edge and the loaded-side shoulder.

    The ellipse spans the groove angles α ± a/r (r = groove radius, a = ``semi_major`` [m],
    α = ``contact_angle`` [rad], measured from the groove bottom towards the loaded shoulder);
    margin = θ_sh - (α + a/r) in degrees (see :func:`shoulder_angle`). Negative means the ellipse is
    truncated by the shoulder (Hertz no longer valid). NaN when the shoulder diameter is not
    given; a shoulder that does not rise above the groove gives θ_sh = 0 (see
    :func:`shoulder_angle`). Only
    the shoulder on the loaded side (the one the case gives) is checked: for α < 0 the contact has
    crossed the groove bottom towards the other land, which this margin does not cover.
    """
    theta_sh = shoulder_angle(geometry, race)
    r = geometry.inner_groove_radius if race == "inner" else geometry.outer_groove_radius
    alpha = np.asarray(contact_angle, dtype=float)
    a = np.asarray(semi_major, dtype=float)
    margin = np.degrees(theta_sh - (alpha + a / r))
    return float(margin) if np.ndim(margin) == 0 else margin
