"""Rating life of a result (ISO 281 and ISO/TS 16281, :mod:`solver.physics.life`), read from its
Dataset: the geometry and operating point from the coordinates, the contact loads and angles from
``contact_load`` / ``contact_angle`` (:func:`rating_life`); or, while a quasi-static Dataset is
built, from the same arrays before they are stored (:func:`snapshot_life_metrics`).

- **ISO 281** ``basic_rating_life`` from the applied axial and radial loads and the nominal
  contact angle (``nominal_contact_angle``: 0 for a radial deep-groove bearing, whose case gives
  its diametral clearance; the free contact angle of an angular contact bearing), with f_c reduced
  for groove radii above 0.52 D_w (inner) / 0.53 D_w (outer). Moments and misalignment do not
  enter it.
- **ISO/TS 16281** ``reference_rating_life`` from the computed normal load of every ball–race
  contact at its own contact angle: clearance, misalignment, speed effects (centrifugal force,
  gyroscopic moments) and the load distribution enter through those loads. A quasi-static result
  gives one snapshot (each ball once); a dynamic result uses every sample of the whole shaft
  revolutions at the end of the analysed window (at least one: else the whole window), so the
  equivalent loads are means over balls and over time.

Which ring "rotates relative to the load" (cubic mean) and which stands still (10/3 mean): the load
direction is fixed in space, except for a ring-fixed misalignment without radial load, whose load
zone turns with the inner ring. A ring whose speed equals the load direction's stands still
relative to it.

Lives are stored in revolutions of one ring relative to the other (unit "1") and as times in s at
the result's relative ring speed (inf when the rings do not turn relative to each other, or when no
contact is loaded); the CLI prints million revolutions and hours. Where the standard's tables do not
cover the bearing (ISO 281 X, Y factors outside 15-45 deg), the ISO 281 figures are NaN with a
``note`` attribute saying why.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from solver.physics import life

from .dataset import geometry_from_result, ring_speeds
from .loaded import loaded_mask
from .variables import variable

#: Names of the life metrics (results-schema.md, summary metrics).
LIFE_METRICS = (
    "basic_load_rating",
    "equivalent_load",
    "basic_rating_life",
    "basic_rating_life_time",
    "raceway_load_rating",
    "raceway_equivalent_load",
    "raceway_rating_life",
    "reference_rating_life",
    "reference_rating_life_time",
)
STEEL_NOTE = (
    "ISO 281 and ISO/TS 16281 rate rings and balls of bearing steel: for other materials (ceramic "
    "balls of a hybrid bearing) the figures are those of steel balls carrying the computed loads"
)


def _coord(ds: xr.Dataset, name: str) -> float:
    return float(np.asarray(ds.coords[name].values, dtype=float))


def load_direction_speed(operating) -> float:
    """Angular speed [rad/s] of the load direction of an operating point (SI, rad; the attributes
    of :data:`solver.results.dataset.OPERATING_FIELDS`): 0 (fixed in space), or the inner ring's
    for a ring-fixed misalignment without radial load."""
    frame = str(operating.misalignment_frame)
    misaligned = abs(float(operating.misalignment)) > 0.0
    radial = abs(float(operating.radial_load)) > 0.0
    if frame == "ring" and misaligned and not radial:
        return float(operating.inner_ring_speed)
    return 0.0


def _load_direction_speed(ds: xr.Dataset) -> float:
    """:func:`load_direction_speed` of a result, from its coordinates."""
    frame = str(np.asarray(ds.coords["misalignment_frame"].values).item())
    misaligned = abs(_coord(ds, "misalignment")) > 0.0
    radial = abs(_coord(ds, "radial_load")) > 0.0
    if frame == "ring" and misaligned and not radial:
        return ring_speeds(ds)[0]
    return 0.0


def _window(ds: xr.Dataset, start: int) -> slice:
    """Time samples used for a dynamic result: the whole shaft revolutions ending at the last
    sample within the window starting at ``start`` (the whole window when it is shorter)."""
    times = np.asarray(ds["time"].values, dtype=float)
    inner, outer = ring_speeds(ds)
    relative = abs(inner - outer)
    if relative == 0.0:
        return slice(start, None)
    period = 2.0 * math.pi / relative
    span = times[-1] - times[start]
    whole = math.floor(span / period + 1e-9)
    if whole < 1:
        return slice(start, None)
    first = int(np.searchsorted(times, times[-1] - whole * period - 1e-9 * period))
    return slice(max(first, start), None)


def _contacts(ds: xr.Dataset, name: str, race: str, samples: slice | None) -> np.ndarray:
    da = ds[name].sel(race=race)
    if "time" in da.dims:
        return np.asarray(da.transpose("time", "ball").values, dtype=float)[samples]
    return np.asarray(da.values, dtype=float)[None, :]


def rating_life(ds: xr.Dataset, start: int = 0) -> xr.Dataset:
    """Life metrics (:data:`LIFE_METRICS`) of one result element (no stacking dimensions).
    ``start``: first time sample of the analysed window of a dynamic result."""
    samples = _window(ds, start) if "time" in ds.dims else None
    loads = [_contacts(ds, "contact_load", race, samples) for race in ("inner", "outer")]
    angles = [
        np.radians(_contacts(ds, "contact_angle", race, samples)) for race in ("inner", "outer")
    ]
    inner_speed, outer_speed = ring_speeds(ds)
    return xr.Dataset(
        life_metrics(
            geometry_from_result(ds),
            inner_speed,
            outer_speed,
            _coord(ds, "axial_load"),
            _coord(ds, "radial_load"),
            _load_direction_speed(ds),
            loads,
            angles,
        )
    )


def snapshot_life_metrics(geometry, operating, contact_load, contact_angle) -> dict[str, tuple]:
    """:func:`life_metrics` of one quasi-static snapshot: ``operating`` (SI, rad; the attributes of
    :data:`solver.results.dataset.OPERATING_FIELDS`), ``contact_load`` [N] and ``contact_angle``
    [rad] (Z, 2) [inner, outer]. The same figures as :func:`rating_life` of its Dataset, without
    reading them back from it."""
    load = np.asarray(contact_load, dtype=float)
    angle = np.asarray(contact_angle, dtype=float)
    return life_metrics(
        geometry,
        float(operating.inner_ring_speed),
        float(operating.outer_ring_speed),
        float(operating.axial_load),
        float(operating.radial_load),
        load_direction_speed(operating),
        [load[None, :, 0], load[None, :, 1]],
        [angle[None, :, 0], angle[None, :, 1]],
    )


def life_metrics(
    geometry,
    inner_speed: float,
    outer_speed: float,
    axial_load: float,
    radial_load: float,
    load_speed: float,
    loads,
    angles,
) -> dict[str, tuple]:
    """Life metrics (:data:`LIFE_METRICS`) as ``{name: (dims, values, attrs)}`` from arrays:
    the :class:`solver.geometry.BearingGeometry`, the ring speeds [rad/s], the applied axial and
    radial loads [N], the load direction's speed [rad/s] (:func:`load_direction_speed`), and per
    race (inner, outer) the contact loads [N] and contact angles [rad] of every sample and ball
    (samples, Z): one sample for a quasi-static result, the analysed window of a dynamic one."""
    z = geometry.ball_count
    d, dm = geometry.ball_diameter, geometry.pitch_diameter
    relative = inner_speed - outer_speed
    attrs: dict[str, dict] = {name: {} for name in LIFE_METRICS}

    # ISO 281
    alpha0 = geometry.rating_contact_angle
    try:
        c = life.basic_dynamic_load_rating(
            d, dm, alpha0, z, 1, geometry.inner_conformity, geometry.outer_conformity
        )
        p = life.equivalent_dynamic_load(axial_load, radial_load, alpha0, d, z)
        l10 = life.basic_rating_life(c, p) * 1e6
    except life.LifeRangeError as error:
        c = p = l10 = math.nan
        for name in ("basic_load_rating", "equivalent_load", "basic_rating_life"):
            attrs[name]["note"] = f"not available: {error}"
        attrs["basic_rating_life_time"]["note"] = attrs["basic_rating_life"]["note"]

    # ISO/TS 16281
    q_c = np.full(2, math.nan)
    q_e = np.full(2, math.nan)
    raceway = np.full(2, math.inf)
    means = {}
    for k, (race, speed) in enumerate((("inner", inner_speed), ("outer", outer_speed))):
        conformity = geometry.inner_conformity if k == 0 else geometry.outer_conformity
        load = np.asarray(loads[k], dtype=float)
        angle = np.asarray(angles[k], dtype=float)
        rotating = speed != load_speed
        ratings = life.raceway_load_rating(d, dm, conformity, angle, z, k == 0)
        loaded = loaded_mask(load, angle)
        raceway[k] = life.raceway_life(np.where(loaded, load, 0.0), ratings, rotating) * 1e6
        q_e[k] = life.equivalent_contact_load(load, rotating)
        if loaded.any():
            q_c[k] = life.raceway_load_rating(
                d, dm, conformity, float(angle[loaded].mean()), z, k == 0
            )
        means[race] = "cubic" if rotating else "10/3"
    l10r = life.combined_life(raceway[0] / 1e6, raceway[1] / 1e6) * 1e6
    attrs["raceway_equivalent_load"]["note"] = (
        f"inner race: {means['inner']} mean, outer race: {means['outer']} mean (ring rotating / "
        "stationary relative to the load)"
    )
    if geometry.ball_material.name != "bearing_steel" or (
        geometry.ring_material.name != "bearing_steel"
    ):
        for name in LIFE_METRICS:
            attrs[name].setdefault("note", STEEL_NOTE)

    def seconds(revolutions: float) -> float:
        if not math.isfinite(revolutions):
            return revolutions
        return life.life_hours(revolutions / 1e6, relative) * 3600.0

    values = {
        "basic_load_rating": np.float64(c),
        "equivalent_load": np.float64(p),
        "basic_rating_life": np.float64(l10),
        "basic_rating_life_time": np.float64(seconds(l10)),
        "raceway_load_rating": q_c,
        "raceway_equivalent_load": q_e,
        "raceway_rating_life": raceway,
        "reference_rating_life": np.float64(l10r),
        "reference_rating_life_time": np.float64(seconds(l10r)),
    }
    out = {}
    for name, value in values.items():
        spec = variable(name)
        out[name] = (spec.dims, value, {**spec.attrs(), **attrs[name]})
    return out


__all__ = [
    "LIFE_METRICS",
    "STEEL_NOTE",
    "life_metrics",
    "load_direction_speed",
    "rating_life",
    "snapshot_life_metrics",
]
