"""Empirical friction-torque estimates of a case (:mod:`solver.physics.friction_estimates`), stored
in its results beside the model's own friction torque.

Both estimates take the applied loads, the speed of one ring relative to the other and the oil's
kinematic viscosity at the inlet temperature (dynamic viscosity / density) of an open bearing;
the SKF model's replenishment constant K_rs follows the case's lubrication method
(``lubricant.method``, docs/lubrication.md), and Palmgren's f0 is that of oil mist whatever the
method (the only f0 values transcribed, docs/sources.md). What bearing it is comes from
``bearing.designation``:

- a deep groove ball bearing: a designation ``60xx``, ``62xx``, ``63xx``, ``64xx``, or a basic
  number ``2xx`` / ``3xx`` with the words "deep groove" (series 62 / 63);
- a single-row angular contact ball bearing: ``72xx``, ``73xx``, ``70xx`` ..., or ``2xx`` / ``3xx``
  with the words "angular contact". The SKF constants exist for the 72 B series (40 deg) only.

The last two digits are the bore code (00 = 10 mm, 01 = 12, 02 = 15, 03 = 17, from 04 on five
times the code); the outside diameter follows from the pitch diameter as the catalogue defines it,
``d_m = (d + D) / 2``. The static load rating C0 (Palmgren's f1, and the SKF deep groove formula
with an axial load) is computed from the ISO 76 reference stress of 4.2 GPa for an all-steel
bearing of the case's geometry (:func:`solver.physics.friction_estimates.static_load_rating`).

An estimate that cannot be made (a designation the rules above do not read, a series without
published constants, a hybrid bearing for the SKF model, rings that do not turn) is left out of
the result; the attribute ``<name>_note`` of the Dataset says why. An estimate made carries a
``note`` attribute with what it assumed.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
from dataclasses import dataclass

import xarray as xr

from solver.physics import friction_estimates as fe
from solver.physics.hertz import race_contact

from .variables import variable

#: Names of the estimate variables (results-schema.md).
ESTIMATES = ("friction_torque_palmgren", "friction_torque_skf")
#: Named oils of solver/data/oils.toml that are synthetic (the SKF model's mu_EHL = 0.04).
SYNTHETIC_OILS = frozenset({"ester-vg22", "jet-oil-mil-prf-23699"})
STEEL = "bearing_steel"
_NUMBER = re.compile(r"(?<![\d.])(\d{3,4})\s*([A-Z]*)(?![\d.])", re.IGNORECASE)
_B_SERIES_ANGLE_DEG = 40.0


@dataclass(frozen=True)
class BearingIdentity:
    """What the estimates need to know about the bearing: its kind, SKF series label (or "" when
    none applies), bore d and outside diameter D [m]."""

    kind: str
    series: str
    bore: float
    outside_diameter: float


def _bore_mm(code: int) -> float:
    return {0: 10.0, 1: 12.0, 2: 15.0, 3: 17.0}.get(code, 5.0 * code)


def identify(designation: str, pitch_diameter: float, free_contact_angle: float):
    """(:class:`BearingIdentity`, "") or (None, reason in words) for ``designation`` (module
    docstring). ``pitch_diameter`` [m], ``free_contact_angle`` [rad]."""
    text = designation.strip()
    match = _NUMBER.search(text)
    if not match:
        return None, (
            f"the designation {text!r} holds no bearing number (e.g. 6209, 7218 B, or a basic "
            "number 209 with the words 'deep groove' or 'angular contact')"
        )
    number, suffix = match.group(1), match.group(2).upper()
    words = text.lower()
    if len(number) == 4 and number[0] in "67":
        kind = fe.DEEP_GROOVE if number[0] == "6" else fe.ANGULAR_CONTACT
        series = number[:2]
    elif len(number) == 3 and number[0] in "23" and ("deep groove" in words or "angular" in words):
        kind = fe.DEEP_GROOVE if "deep groove" in words else fe.ANGULAR_CONTACT
        series = ("6" if kind == fe.DEEP_GROOVE else "7") + number[0]
    else:
        return None, (
            f"the designation {text!r} names no deep groove (6xxx, or 2xx/3xx 'deep groove') or "
            "single-row angular contact (7xxx, or 2xx/3xx 'angular contact') ball bearing"
        )
    bore = _bore_mm(int(number[-2:])) / fe.MM_PER_M
    outside = 2.0 * pitch_diameter - bore
    if not outside > bore:
        return None, (
            f"the bore {bore * fe.MM_PER_M:g} mm of {number} does not fit the pitch diameter "
            f"{pitch_diameter * fe.MM_PER_M:g} mm (d_m = (d + D) / 2 gives D <= d)"
        )
    if kind == fe.ANGULAR_CONTACT:
        forty = abs(math.degrees(free_contact_angle) - _B_SERIES_ANGLE_DEG) < 0.5
        series = f"{series} B" if (forty or "B" in suffix) else f"{series} {suffix}".strip()
    return BearingIdentity(kind, series, bore, outside), ""


@functools.lru_cache(maxsize=32)
def _static_rating(geometry, kind: str) -> float:
    """C0 [N] of an all-steel bearing of this geometry at the nominal angle (0 for deep groove).
    Kept per geometry (a frozen dataclass, compared by value): the exact Hertz solution it takes
    costs more than the rest of a quasi-static result."""
    from solver.materials import BUILTIN_MATERIALS

    steel = BUILTIN_MATERIALS[STEEL]
    alpha = 0.0 if kind == fe.DEEP_GROOVE else geometry.free_contact_angle
    steel_geometry = dataclasses.replace(geometry, ball_material=steel, ring_material=steel)
    pressure = race_contact(steel_geometry, alpha, 1.0, "inner").max_pressure
    return fe.static_load_rating(geometry.ball_count, alpha, pressure)


def estimate(inputs, operating=None) -> tuple[dict[str, float], dict[str, str]]:
    """({name: torque N m} of the estimates that can be made, {name: note}) for a case's
    :class:`solver.inputs.Inputs` (``operating`` replaces its operating point)."""
    op = operating if operating is not None else inputs.operating
    geometry, lubricant = inputs.geometry, inputs.lubricant
    values: dict[str, float] = {}
    notes: dict[str, str] = {}
    speed = abs(op.inner_ring_speed - op.outer_ring_speed)
    identity, reason = identify(
        inputs.designation, geometry.pitch_diameter, geometry.free_contact_angle
    )
    if speed == 0.0:
        reason = "the rings do not turn relative to each other"
    if identity is None or speed == 0.0:
        for name in ESTIMATES:
            notes[name] = f"not available: {reason}"
        return values, notes
    nu = lubricant.viscosity / lubricant.density
    fr, fa = abs(op.radial_load), abs(op.axial_load)
    c0 = _static_rating(geometry, identity.kind)
    hybrid = geometry.ball_material.name != STEEL or geometry.ring_material.name != STEEL
    viscosity_text = (
        f"nu = {nu * fe.MM2_S_PER_M2_S:.3g} mm^2/s at the inlet temperature "
        f"{lubricant.inlet_temperature:g} degC, n = {fe.rpm(speed):.0f} r/min, "
        f"F_r = {fr:g} N, F_a = {fa:g} N"
    )

    # Palmgren
    f0 = fe.PALMGREN_F0_OIL_MIST[identity.kind]
    p0 = fe.static_equivalent_load(identity.kind, fr, fa, geometry.free_contact_angle)
    f1 = fe.palmgren_load_factor(identity.kind, p0, c0)
    p1 = fe.palmgren_load(identity.kind, fr, fa)
    m0 = fe.palmgren_viscous_torque(f0, geometry.pitch_diameter, nu, speed)
    m1 = fe.palmgren_load_torque(f1, p1, geometry.pitch_diameter)
    values["friction_torque_palmgren"] = m0 + m1
    kind_text = {fe.DEEP_GROOVE: "a deep groove", fe.ANGULAR_CONTACT: "an angular contact"}
    notes["friction_torque_palmgren"] = (
        f"Palmgren M0 + M1 for {kind_text[identity.kind]} ball bearing, f0 = {f0:g} of oil "
        f"mist / oil-air{_f0_method_text(lubricant.method)}: "
        f"M0 = {m0 * 1e3:.4g} N mm, M1 = {m1 * 1e3:.4g} N mm (f1 = {f1:.3g}, P1 = {p1:.4g} N, "
        f"P0/C0 = {p0:.4g}/{c0:.4g} N with C0 from the ISO 76 4.2 GPa stress); {viscosity_text}"
        + (
            "; coefficients of all-steel bearings: the estimate is that of a steel bearing of "
            "the same geometry"
            if hybrid
            else ""
        )
    )

    # SKF
    series = fe.SKF_SERIES.get(identity.series)
    if hybrid:
        notes["friction_torque_skf"] = (
            "not available: the SKF model's constants are for all-steel bearings; none for hybrid "
            "bearings (ceramic balls) were found"
        )
    elif series is None or series.kind != identity.kind:
        notes["friction_torque_skf"] = (
            f"not available: no published SKF geometry constants were found for the "
            f"{identity.series} series (known: {', '.join(fe.SKF_SERIES)})"
        )
    else:
        oil = "synthetic" if lubricant.oil in SYNTHETIC_OILS else "mineral"
        mu_ehl = fe.SKF_MU_EHL[oil]
        k_rs = fe.SKF_K_RS[lubricant.method]
        skf = fe.skf_torque(
            series, identity.bore, identity.outside_diameter, nu, speed, fr, fa, c0, mu_ehl, k_rs
        )
        values["friction_torque_skf"] = skf.total
        oil_text = (
            f"{oil} oil, mu_EHL = {mu_ehl:g}"
            if lubricant.oil
            else f"mu_EHL = {mu_ehl:g} of a mineral oil (the case names no oil)"
        )
        notes["friction_torque_skf"] = (
            f"SKF model, series {identity.series} ({series.source}), d = "
            f"{identity.bore * 1e3:g} mm, D = {identity.outside_diameter * 1e3:.4g} mm: M_rr = "
            f"{skf.rolling * 1e3:.4g} N mm (phi_ish = {skf.inlet_shear_factor:.3g}, phi_rs = "
            f"{skf.replenishment_factor:.3g}, K_rs = {k_rs:g} for {lubricant.method}"
            f"{' (assumed)' if lubricant.method_assumed else ''}), M_sl = "
            f"{skf.sliding * 1e3:.4g} N mm (mu_sl = {skf.sliding_friction:.3g}, phi_bl = "
            f"{skf.boundary_weighting:.3g}, {oil_text}), {_skf_drag_text(lubricant.method)}, "
            f"open bearing; {viscosity_text}"
        )
    return values, notes


@dataclass(frozen=True)
class EstimateFields:
    """What the estimates add to a result: ``values`` {name: torque N m} of the estimates made,
    ``notes`` {name: {"note": what it assumed}} their variable attributes, and ``attrs``
    {"<name>_note": why} a Dataset attribute for each one left out."""

    values: dict[str, float]
    notes: dict[str, dict[str, str]]
    attrs: dict[str, str]


def estimate_fields(inputs, operating=None) -> EstimateFields:
    """The estimates of :func:`estimate` as the fields of a result (:class:`EstimateFields`),
    for a Dataset builder that adds them with its other variables."""
    values, notes = estimate(inputs, operating)
    return EstimateFields(
        values,
        {name: {"note": notes[name]} for name in values},
        {f"{name}_note": notes[name] for name in ESTIMATES if name not in values},
    )


def _f0_method_text(method: str) -> str:
    """What Palmgren's f0 assumes, for a method other than oil-air / oil mist."""
    if method in ("oil_air", "oil_mist"):
        return ""
    return f" (the case's method is {method}: its f0 was not transcribed, docs/sources.md)"


def _skf_drag_text(method: str) -> str:
    """Why the SKF estimate has no drag term, for the case's lubrication method."""
    if method in ("oil_bath", "oil_jet"):
        return (
            f"no drag term (the catalogue's drag loss for {method} reads a diagram whose values "
            "were not among the sources found, docs/lubrication.md)"
        )
    return f"no drag term (the catalogue's drag loss is for an oil bath or jet, not {method})"


def friction_estimates(inputs, operating=None) -> xr.Dataset:
    """The estimates as a Dataset: a scalar variable per estimate made (with its ``note``) and,
    for each one left out, the attribute ``<name>_note`` saying why."""
    fields = estimate_fields(inputs, operating)
    data = {}
    for name, value in fields.values.items():
        spec = variable(name)
        data[name] = (spec.dims, value, {**spec.attrs(), **fields.notes[name]})
    return xr.Dataset(data, attrs=fields.attrs)


def with_estimates(ds: xr.Dataset, inputs, operating=None) -> xr.Dataset:
    """``ds`` with the friction-torque estimates of its case (variables and notes)."""
    extra = friction_estimates(inputs, operating)
    out = ds.assign(extra.data_vars)
    out.attrs.update(extra.attrs)
    return out


__all__ = ["ESTIMATES", "BearingIdentity", "EstimateFields", "estimate", "estimate_fields"]
__all__ += ["friction_estimates", "identify", "with_estimates"]
