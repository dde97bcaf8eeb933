"""Empirical friction torque of a ball bearing: Palmgren's M0 + M1 and the SKF friction model.

These are catalogue estimates, independent of racetrace's contact mechanics, to set beside the
dynamic model's friction torque. Pure functions. Arguments and results are SI (m, N, rad/s, m^2/s,
N m); the catalogue formulas are written in N mm, mm, mm^2/s and r/min, and each function converts
at its edges. Every formula and coefficient is listed with its source in docs/sources.md
("Friction torque estimates"); certainty marks there say which values could be checked.

**Palmgren** (Harris & Kotzalas, *Rolling Bearing Analysis*, friction chapter; Palmgren, *Ball and
Roller Bearing Engineering*):

- viscous term ``M0 = 1e-7 f0 (nu n)^(2/3) d_m^3`` N mm for ``nu n >= 2000`` (mm^2/s x r/min),
  and ``M0 = 160e-7 f0 d_m^3`` below: at low speed the viscous torque does not vanish but stays at
  its value at ``nu n = 2000`` (2000^(2/3) = 158.7, rounded to 160 by Palmgren);
- load term ``M1 = f1 P1 d_m`` with ``f1 = z (P0 / C0)^y`` (P0 static equivalent load, C0 static
  load rating) and ``P1`` per bearing type: deep groove ``max(F_r, 3 F_a - 0.1 F_r)``, single-row
  angular contact ``max(F_r, F_a - 0.1 F_r)``.

**SKF friction model** (SKF *Rolling bearings* catalogue, section "Friction"):
``M = M_rr + M_sl + M_seal + M_drag`` with

- rolling ``M_rr = phi_ish phi_rs G_rr (nu n)^0.6``;
  inlet shear heating ``phi_ish = 1 / (1 + 1.84e-9 (n d_m)^1.28 nu^0.64)``;
  kinematic replenishment ``phi_rs = exp(-K_rs nu n (d + D) sqrt(K_Z / (2 (D - d))))``;
- sliding ``M_sl = G_sl mu_sl``, ``mu_sl = phi_bl mu_bl + (1 - phi_bl) mu_EHL``,
  ``phi_bl = exp(-2.6e-8 (n nu)^1.4 d_m)``;
- ``G_rr``, ``G_sl`` of deep groove and angular contact ball bearings from the series constants
  R1..R3, S1..S3 (:data:`SKF_SERIES`);
- ``K_rs`` by lubrication method: 3e-8 for a low oil bath or oil jet, 6e-8 for grease or
  oil-air (:data:`SKF_K_RS`);
- open bearings (``M_seal = 0``); the drag term is the catalogue's for an oil bath (or jets):
  the values of its diagram were not among the sources found, and none is defined for oil-air or
  grease, so no drag term is added (the result's note says so).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

# ---- units at the edges -------------------------------------------------------------------------
MM_PER_M = 1.0e3
MM2_S_PER_M2_S = 1.0e6  # kinematic viscosity: mm^2/s per m^2/s
N_M_PER_N_MM = 1.0e-3


def rpm(speed: float) -> float:
    """Speed in r/min from rad/s (absolute value: the formulas take a speed magnitude)."""
    return abs(speed) * 60.0 / (2.0 * math.pi)


DEEP_GROOVE = "deep_groove"
ANGULAR_CONTACT = "angular_contact"
BEARING_KINDS = (DEEP_GROOVE, ANGULAR_CONTACT)

# ---- Palmgren ------------------------------------------------------------------------------------
#: nu n [mm^2/s r/min] below which Palmgren's viscous torque keeps its constant low-speed value.
PALMGREN_LOW_SPEED_LIMIT = 2000.0
#: Palmgren's constant of the low-speed branch (2000^(2/3) = 158.7, rounded by Palmgren).
PALMGREN_LOW_SPEED_CONSTANT = 160.0
#: f0 for oil mist (oil-air) lubrication, per bearing kind (Harris & Kotzalas, table of f0).
PALMGREN_F0_OIL_MIST = {DEEP_GROOVE: 1.0, ANGULAR_CONTACT: 1.7}
#: (z, y) of f1 = z (P0/C0)^y (Harris & Kotzalas); deep groove z is the middle of 0.0004-0.0006.
PALMGREN_F1 = {DEEP_GROOVE: (0.0005, 0.55), ANGULAR_CONTACT: (0.001, 0.33)}


def palmgren_viscous_torque(
    f0: float, pitch_diameter: float, kinematic_viscosity: float, speed: float
) -> float:
    """Palmgren's viscous friction torque M0 [N m].

    ``pitch_diameter`` d_m [m], ``kinematic_viscosity`` nu [m^2/s] at the operating temperature,
    ``speed`` [rad/s] of one ring relative to the other. Below ``nu n = 2000`` mm^2/s r/min the
    low-speed branch ``160e-7 f0 d_m^3`` N mm holds (it does not tend to 0 with the speed).
    """
    if f0 < 0.0 or pitch_diameter <= 0.0 or kinematic_viscosity < 0.0:
        raise ValueError("f0 >= 0, pitch diameter > 0 and viscosity >= 0 are required")
    dm = pitch_diameter * MM_PER_M
    nu_n = kinematic_viscosity * MM2_S_PER_M2_S * rpm(speed)
    if nu_n >= PALMGREN_LOW_SPEED_LIMIT:
        torque_nmm = 1.0e-7 * f0 * nu_n ** (2.0 / 3.0) * dm**3
    else:
        torque_nmm = PALMGREN_LOW_SPEED_CONSTANT * 1.0e-7 * f0 * dm**3
    return torque_nmm * N_M_PER_N_MM


def palmgren_load(kind: str, radial_load: float, axial_load: float) -> float:
    """Palmgren's load P1 [N] of the load torque: deep groove ``max(F_r, 3 F_a - 0.1 F_r)``,
    single-row angular contact ``max(F_r, F_a - 0.1 F_r)`` (loads in N, magnitudes)."""
    fr, fa = abs(radial_load), abs(axial_load)
    if kind == DEEP_GROOVE:
        return max(fr, 3.0 * fa - 0.1 * fr)
    if kind == ANGULAR_CONTACT:
        return max(fr, fa - 0.1 * fr)
    raise ValueError(f"bearing kind {kind!r}: one of {', '.join(BEARING_KINDS)}")


def palmgren_load_factor(kind: str, static_equivalent_load: float, static_rating: float) -> float:
    """f1 = z (P0 / C0)^y of Palmgren's load torque (:data:`PALMGREN_F1`); loads in N."""
    if static_rating <= 0.0:
        raise ValueError("the static load rating C0 must be > 0 N")
    z, y = PALMGREN_F1[kind]
    return z * (max(static_equivalent_load, 0.0) / static_rating) ** y


def palmgren_load_torque(f1: float, load: float, pitch_diameter: float) -> float:
    """Palmgren's load friction torque M1 = f1 P1 d_m [N m] (P1 in N, d_m in m)."""
    return f1 * load * pitch_diameter


# ---- ISO 76 static load rating and equivalent load ---------------------------------------------
#: ISO 76 reference contact stress of ball bearings (except self-aligning), Pa.
ISO76_CONTACT_STRESS = 4.2e9
#: Stribeck's ratio of the largest ball load to the mean: Q_max = 5 F_r / (Z cos alpha).
STRIBECK_CONSTANT = 5.0
#: ISO 76 static radial factors X0, Y0 of single-row radial ball bearings; angular contact Y0
#: against the nominal contact angle [deg] (linear in between; deep groove: Y0 = 0.5).
ISO76_X0 = 0.5
ISO76_DEEP_GROOVE = (0.6, 0.5)
ISO76_ANGLES_DEG = (15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0)
ISO76_Y0 = (0.46, 0.42, 0.38, 0.33, 0.29, 0.26, 0.22)


def static_equivalent_load(
    kind: str, radial_load: float, axial_load: float, contact_angle: float
) -> float:
    """ISO 76 static equivalent radial load P0 = max(F_r, X0 F_r + Y0 F_a) [N]; ``contact_angle``
    [rad] is the nominal angle of an angular contact bearing (ignored for deep groove)."""
    fr, fa = abs(radial_load), abs(axial_load)
    if kind == DEEP_GROOVE:
        x0, y0 = ISO76_DEEP_GROOVE
    else:
        angle = min(max(math.degrees(contact_angle), ISO76_ANGLES_DEG[0]), ISO76_ANGLES_DEG[-1])
        x0, y0 = ISO76_X0, _interpolate(angle, ISO76_ANGLES_DEG, ISO76_Y0)
    return max(fr, x0 * fr + y0 * fa)


def _interpolate(x: float, xs: tuple, ys: tuple) -> float:
    for k in range(len(xs) - 1):
        if xs[k] <= x <= xs[k + 1]:
            t = (x - xs[k]) / (xs[k + 1] - xs[k])
            return ys[k] + t * (ys[k + 1] - ys[k])
    return ys[0] if x < xs[0] else ys[-1]


def static_load_rating(
    ball_count: int, contact_angle: float, peak_pressure_per_unit_load: float
) -> float:
    """Static radial load rating C0 [N] from the ISO 76 reference stress: the radial load at which
    the most loaded ball (Q_max = 5 F_r / (Z cos alpha), Stribeck) reaches 4.2 GPa at its more
    stressed contact. ``peak_pressure_per_unit_load`` is that contact's Hertz peak pressure at
    Q = 1 N [Pa]; the peak pressure grows as Q^(1/3)."""
    if peak_pressure_per_unit_load <= 0.0:
        raise ValueError("the peak pressure at 1 N must be > 0 Pa")
    ball_load = (ISO76_CONTACT_STRESS / peak_pressure_per_unit_load) ** 3
    return ball_count * math.cos(contact_angle) * ball_load / STRIBECK_CONSTANT


# ---- SKF friction model --------------------------------------------------------------------------
@dataclass(frozen=True)
class SkfSeries:
    """Geometry constants of one SKF bearing series (catalogue Table 3, "geometry constants for
    rolling and sliding frictional moments"): R1..R3, S1..S3 (R3 = S3 = 0 for deep groove), the
    replenishment constant K_Z of the bearing type and where the row comes from."""

    kind: str
    r1: float
    r2: float
    s1: float
    s2: float
    r3: float = 0.0
    s3: float = 0.0
    k_z: float = 3.1
    source: str = ""


_DGBB_SOURCE = "SKF Table 3 deep groove row, as transcribed in public code (docs/sources.md)"
_ACBB_SOURCE = (
    "SKF Table 3 row 72 B(E); two transcriptions agree, a third labels other values 72 B(E): "
    "MEDIUM confidence (docs/sources.md)"
)
#: Series label -> constants. Deep groove K_Z = 3.1, single-row angular contact K_Z = 4.4.
SKF_SERIES: dict[str, SkfSeries] = {
    "60": SkfSeries(DEEP_GROOVE, 4.1e-7, 1.7, 3.73e-3, 14.6, source=_DGBB_SOURCE),
    "62": SkfSeries(DEEP_GROOVE, 3.9e-7, 1.7, 3.23e-3, 36.5, source=_DGBB_SOURCE),
    "63": SkfSeries(DEEP_GROOVE, 3.7e-7, 1.7, 2.84e-3, 92.8, source=_DGBB_SOURCE),
    "64": SkfSeries(DEEP_GROOVE, 3.6e-7, 1.7, 2.43e-3, 198.0, source=_DGBB_SOURCE),
    "72 B": SkfSeries(
        ANGULAR_CONTACT, 5.03e-7, 1.97, 1.30e-2, 0.68, 1.90e-12, 1.91e-12, 4.4, _ACBB_SOURCE
    ),
}
#: K_rs of the replenishment factor for oil-air (and grease) lubrication.
SKF_K_RS_OIL_AIR = 6.0e-8
#: K_rs of the replenishment factor for a low oil bath or oil jet.
SKF_K_RS_OIL_BATH_JET = 3.0e-8
#: K_rs by lubrication method (lubricant.method; oil mist is oil-air lubrication).
SKF_K_RS = {
    "oil_air": SKF_K_RS_OIL_AIR,
    "oil_mist": SKF_K_RS_OIL_AIR,
    "grease": SKF_K_RS_OIL_AIR,
    "oil_jet": SKF_K_RS_OIL_BATH_JET,
    "oil_bath": SKF_K_RS_OIL_BATH_JET,
}
#: Boundary-film friction coefficient (catalogue: about 0.15, depends on the additive package).
SKF_MU_BL = 0.15
#: Full-film friction coefficient of ball bearings with mineral and with synthetic oils.
SKF_MU_EHL = {"mineral": 0.05, "synthetic": 0.04}


def skf_inlet_shear_factor(pitch_diameter: float, kinematic_viscosity: float, speed: float):
    """phi_ish = 1 / (1 + 1.84e-9 (n d_m)^1.28 nu^0.64) (n r/min, d_m mm, nu mm^2/s)."""
    n, dm = rpm(speed), pitch_diameter * MM_PER_M
    nu = kinematic_viscosity * MM2_S_PER_M2_S
    return 1.0 / (1.0 + 1.84e-9 * (n * dm) ** 1.28 * nu**0.64)


def skf_replenishment_factor(
    bore: float,
    outside_diameter: float,
    kinematic_viscosity: float,
    speed: float,
    k_z: float,
    k_rs: float = SKF_K_RS_OIL_AIR,
) -> float:
    """phi_rs = exp(-K_rs nu n (d + D) sqrt(K_Z / (2 (D - d)))) (d, D mm; nu mm^2/s; n r/min)."""
    d, big_d = bore * MM_PER_M, outside_diameter * MM_PER_M
    if not big_d > d > 0.0:
        raise ValueError("0 < bore < outside diameter is required")
    nu, n = kinematic_viscosity * MM2_S_PER_M2_S, rpm(speed)
    return math.exp(-k_rs * nu * n * (d + big_d) * math.sqrt(k_z / (2.0 * (big_d - d))))


def skf_boundary_weighting(pitch_diameter: float, kinematic_viscosity: float, speed: float):
    """phi_bl = exp(-2.6e-8 (n nu)^1.4 d_m) (n r/min, nu mm^2/s, d_m mm)."""
    n, dm = rpm(speed), pitch_diameter * MM_PER_M
    nu = kinematic_viscosity * MM2_S_PER_M2_S
    return math.exp(-2.6e-8 * (n * nu) ** 1.4 * dm)


def skf_load_variables(
    series: SkfSeries,
    pitch_diameter: float,
    speed: float,
    radial_load: float,
    axial_load: float,
    static_rating: float,
) -> tuple[float, float]:
    """(G_rr, G_sl) of the catalogue's Table 2a, in its units (d_m mm, loads N, n r/min).

    Deep groove: with F_a = 0, ``G_rr = R1 d_m^1.96 F_r^0.54``, ``G_sl = S1 d_m^-0.26 F_r^(5/3)``;
    with F_a > 0, ``G_rr = R1 d_m^1.96 (F_r + R2 F_a / sin alpha_F)^0.54`` and ``G_sl = S1
    d_m^-0.145 (F_r^5 + S2 d_m^1.5 F_a^4 / sin alpha_F)^(1/3)``, ``alpha_F = 24.6 (F_a /
    C0)^0.24`` deg. Angular contact: ``G_rr = R1 d_m^1.97 (F_r + F_g + R2 F_a)^0.54`` with ``F_g
    = R3 d_m^4 n^2``, ``G_sl = S1 d_m^0.26 ((F_r + F_g)^(4/3) + S2 F_a^(4/3))`` with ``F_g = S3
    d_m^4 n^2``.
    """
    dm, n = pitch_diameter * MM_PER_M, rpm(speed)
    fr, fa = abs(radial_load), abs(axial_load)
    if series.kind == DEEP_GROOVE:
        if fa == 0.0:
            return series.r1 * dm**1.96 * fr**0.54, series.s1 * dm**-0.26 * fr ** (5.0 / 3.0)
        sin_alpha = math.sin(math.radians(24.6 * (fa / static_rating) ** 0.24))
        g_rr = series.r1 * dm**1.96 * (fr + series.r2 / sin_alpha * fa) ** 0.54
        g_sl = series.s1 * dm**-0.145 * (fr**5 + series.s2 * dm**1.5 / sin_alpha * fa**4) ** (1 / 3)
        return g_rr, g_sl
    f_g_rolling = series.r3 * dm**4 * n**2
    f_g_sliding = series.s3 * dm**4 * n**2
    g_rr = series.r1 * dm**1.97 * (fr + f_g_rolling + series.r2 * fa) ** 0.54
    g_sl = series.s1 * dm**0.26 * ((fr + f_g_sliding) ** (4 / 3) + series.s2 * fa ** (4 / 3))
    return g_rr, g_sl


@dataclass(frozen=True)
class SkfTorque:
    """The SKF model's terms [N m] and factors (dimensionless)."""

    rolling: float
    sliding: float
    drag: float
    inlet_shear_factor: float
    replenishment_factor: float
    boundary_weighting: float
    sliding_friction: float

    @property
    def total(self) -> float:
        return self.rolling + self.sliding + self.drag


def skf_torque(
    series: SkfSeries,
    bore: float,
    outside_diameter: float,
    kinematic_viscosity: float,
    speed: float,
    radial_load: float,
    axial_load: float,
    static_rating: float,
    mu_ehl: float,
    k_rs: float = SKF_K_RS_OIL_AIR,
    mu_bl: float = SKF_MU_BL,
) -> SkfTorque:
    """The SKF model's friction torque of an open bearing, without the drag term; ``k_rs`` of the
    lubrication method (:data:`SKF_K_RS`).

    Lengths [m] (d_m = (d + D) / 2 as the catalogue defines it), ``kinematic_viscosity`` [m^2/s]
    at the operating temperature, ``speed`` [rad/s] of one ring relative to the other, loads [N],
    ``static_rating`` C0 [N] (deep groove with axial load). Result in N m.
    """
    pitch = 0.5 * (bore + outside_diameter)
    phi_ish = skf_inlet_shear_factor(pitch, kinematic_viscosity, speed)
    phi_rs = skf_replenishment_factor(
        bore, outside_diameter, kinematic_viscosity, speed, series.k_z, k_rs
    )
    g_rr, g_sl = skf_load_variables(series, pitch, speed, radial_load, axial_load, static_rating)
    nu_n = kinematic_viscosity * MM2_S_PER_M2_S * rpm(speed)
    rolling_nmm = phi_ish * phi_rs * g_rr * nu_n**0.6
    phi_bl = skf_boundary_weighting(pitch, kinematic_viscosity, speed)
    mu_sl = phi_bl * mu_bl + (1.0 - phi_bl) * mu_ehl
    return SkfTorque(
        rolling=rolling_nmm * N_M_PER_N_MM,
        sliding=g_sl * mu_sl * N_M_PER_N_MM,
        drag=0.0,
        inlet_shear_factor=phi_ish,
        replenishment_factor=phi_rs,
        boundary_weighting=phi_bl,
        sliding_friction=mu_sl,
    )


__all__ = [
    "ANGULAR_CONTACT",
    "BEARING_KINDS",
    "DEEP_GROOVE",
    "PALMGREN_F0_OIL_MIST",
    "PALMGREN_F1",
    "SKF_K_RS",
    "SKF_K_RS_OIL_AIR",
    "SKF_K_RS_OIL_BATH_JET",
    "SKF_MU_BL",
    "SKF_MU_EHL",
    "SKF_SERIES",
    "SkfSeries",
    "SkfTorque",
    "palmgren_load",
    "palmgren_load_factor",
    "palmgren_load_torque",
    "palmgren_viscous_torque",
    "rpm",
    "skf_boundary_weighting",
    "skf_inlet_shear_factor",
    "skf_load_variables",
    "skf_replenishment_factor",
    "skf_torque",
    "static_equivalent_load",
    "static_load_rating",
]
