"""Skidding of the cage against time: the one definition of the rolling cage speed at each
sample, the skidding ratio and the cage slip of a dynamic result (results-schema.md).

At each time sample the **rolling cage speed** is the cage speed at which the two raceways pass
the cage at the same surface speed at their contact circles, so that a ball between them rolls
without the two rolling speeds differing::

    omega_roll = (omega_i r_i + omega_o r_o) / (r_i + r_o),
    r_i = (d_m - D cos alpha_i) / 2,  r_o = (d_m + D cos alpha_o) / 2,

with the ring speeds omega_i, omega_o [rad/s] of that sample (the result's ``inner_ring_speed``
and ``outer_ring_speed``: coordinates of a steady result, data variables over ``time`` when they
vary) and alpha_i, alpha_o the mean ``contact_angle`` of the loaded contacts of each race at that
sample (:func:`solver.results.loaded.loaded`). With alpha_i = alpha_o = alpha it is the epicyclic
speed ((1 - g) omega_i + (1 + g) omega_o) / 2, g = D cos(alpha) / d_m, of the ``cage_slip``
metric, which takes the free contact angle instead.

- ``skidding_ratio`` = ``cage_speed`` / omega_roll: 1 for pure rolling, below 1 when the cage lags
  (the balls skid), above 1 when it runs ahead. NaN at a sample where omega_roll is 0 (the rings
  at rest, or turning so that pure rolling holds the cage still) or where a race has no loaded
  contact (the rolling speed is undefined: nothing holds the balls).
- ``instantaneous_cage_slip`` = 1 - ``skidding_ratio`` (a fraction; views show it in %).

**The cage skids** (a warning of :func:`solver.results.checks.result_warnings`) when the
instantaneous cage slip over the analysed window, or over a phase of a history
(:mod:`solver.results.phases`), weighted by the rolling speed (the metric
``mean_instantaneous_cage_slip`` = 1 - mean cage speed / mean rolling speed: samples near rest
weigh little) exceeds :data:`CAGE_SKID_THRESHOLD`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr

from .loaded import loaded_mask
from .variables import variable

#: Mean instantaneous cage slip (a fraction of the rolling cage speed) above which a result warns
#: that the cage skids. Means over the analysed window of the shipped lesson runs: the spindle at
#: 500 N preload and 30 000 rpm -0.21 % (lesson 5 "preload"), at 500 N and 20 000 rpm -0.02 %
#: (lesson 1), the 209 under 4.45 kN radial load -0.64 % (the cage ahead of rolling); the
#: spindle at 5 N and 30 000 rpm, whose balls skid and whose cage is still slowing at the end of
#: the run, +1.34 % (lesson 5 "light", peak 5.2 %). 1 % lies between.
CAGE_SKID_THRESHOLD = 0.01

#: Samples whose rolling cage speed is below this fraction of the run's largest are left out of
#: the peak and the span of skidding a warning names (:func:`skid_extent`): near rest the ratio
#: of two small speeds says nothing about skidding (a start from rest passes through them).
SKID_EXTENT_MIN_ROLLING_FRACTION = 0.1

#: The variables :func:`skidding_variables` adds to a dynamic result.
SKIDDING_VARIABLES = ("skidding_ratio", "instantaneous_cage_slip")


#: What :func:`skidding_ratio` reads of a result.
_SKIDDING_INPUTS = (
    "contact_angle",
    "contact_load",
    "cage_speed",
    "inner_ring_speed",
    "outer_ring_speed",
    "ball_diameter",
    "pitch_diameter",
)


def _skidding_inputs(ds: xr.Dataset) -> xr.Dataset:
    """The part of ``ds`` that :func:`skidding_ratio` reads, without the other coordinates: the
    same numbers, computed without aligning the result's many scalar coordinates at every
    operation (the chunks of a live simulation are built often)."""
    part = ds[list(_SKIDDING_INPUTS)]
    keep = set(part.dims) | set(_SKIDDING_INPUTS)
    return part.drop_vars([c for c in part.coords if c not in keep])


def _rolling_speed_values(angle_i, load_i, angle_o, load_o, speed_i, speed_o, diameter, pitch):
    """numpy core of :func:`rolling_cage_speed`: contact angles [degree] and loads [N] of each
    race with the balls along the last axis, ring speeds [rad/s] broadcastable against them
    without that axis."""

    def mean_angle(angle, load):  # of the loaded contacts, NaN where none is
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "Mean of empty slice", RuntimeWarning)
            return np.radians(np.nanmean(np.where(loaded_mask(load, angle), angle, np.nan), -1))

    inner_radius = 0.5 * (pitch - diameter * np.cos(mean_angle(angle_i, load_i)))
    outer_radius = 0.5 * (pitch + diameter * np.cos(mean_angle(angle_o, load_o)))
    return (speed_i * inner_radius + speed_o * outer_radius) / (inner_radius + outer_radius)


def rolling_cage_speed(ds: xr.Dataset) -> xr.DataArray:
    """The rolling cage speed omega_roll [rad/s] at each sample of a dynamic result (module
    docstring), dims ``(time,)`` and any stacking dimension of the result."""
    part = _skidding_inputs(ds)
    angle, load = part["contact_angle"], part["contact_load"]
    races = [a.sel(race=race, drop=True) for race in ("inner", "outer") for a in (angle, load)]
    speed = xr.apply_ufunc(
        _rolling_speed_values,
        *races,
        part["inner_ring_speed"],
        part["outer_ring_speed"],
        input_core_dims=[["ball"]] * 4 + [[], []],
        kwargs={
            "diameter": float(part.coords["ball_diameter"]),
            "pitch": float(part.coords["pitch_diameter"]),
        },
    )
    return speed.drop_vars([c for c in speed.coords if c not in speed.dims])


def skidding_ratio(ds: xr.Dataset) -> xr.DataArray:
    """``cage_speed`` / :func:`rolling_cage_speed` at each sample (NaN where the rolling speed
    is 0 or undefined)."""
    part = _skidding_inputs(ds)
    rolling = rolling_cage_speed(part)
    cage = part["cage_speed"].drop_vars([c for c in part["cage_speed"].coords if c != "time"])
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = cage / rolling
    return ratio.where(rolling != 0.0)


def skidding_variables(ds: xr.Dataset) -> dict[str, xr.DataArray]:
    """The :data:`SKIDDING_VARIABLES` of a dynamic result, with the registry's attributes."""
    ratio = skidding_ratio(ds).transpose("time", ...)
    values = {"skidding_ratio": ratio, "instantaneous_cage_slip": 1.0 - ratio}
    return {name: value.assign_attrs(variable(name).attrs()) for name, value in values.items()}


def instantaneous_cage_slip(ds: xr.Dataset) -> xr.DataArray:
    """The result's ``instantaneous_cage_slip`` (stored, or computed from its variables)."""
    if "instantaneous_cage_slip" in ds:
        return ds["instantaneous_cage_slip"]
    return 1.0 - skidding_ratio(ds)


@dataclass(frozen=True)
class SkidExtent:
    """When and how much the cage lags within a set of samples: the largest instantaneous cage
    slip ``peak`` (a fraction) at ``peak_time`` [s], and the first and last times [s] at which
    the slip exceeds :data:`CAGE_SKID_THRESHOLD` (``start``, ``end``; None when no sample does),
    with the fraction ``share`` of the samples counted that exceed it."""

    peak: float
    peak_time: float
    start: float | None
    end: float | None
    share: float


def skid_extent(ds: xr.Dataset, within=None) -> SkidExtent | None:
    """:class:`SkidExtent` of a dynamic result over the samples ``within`` (a boolean array over
    ``time``; None: every sample), counting only samples with a finite slip whose rolling cage
    speed is at least :data:`SKID_EXTENT_MIN_ROLLING_FRACTION` of the run's largest. None when
    no sample counts (rings at rest, a quasi-static result)."""
    if "time" not in ds.dims or "cage_speed" not in ds:
        return None
    rolling = np.abs(np.asarray(rolling_cage_speed(ds).values, dtype=float)).ravel()
    slip = np.asarray(instantaneous_cage_slip(ds).values, dtype=float).ravel()
    times = np.asarray(ds["time"].values, dtype=float)
    if rolling.shape != times.shape or slip.shape != times.shape:
        return None  # a stacked result (a study): one extent per run is not defined here
    finite = np.isfinite(rolling) & np.isfinite(slip)
    if not finite.any():
        return None
    fast = rolling >= SKID_EXTENT_MIN_ROLLING_FRACTION * rolling[finite].max()
    counted = finite & fast
    if within is not None:
        counted &= np.asarray(within, dtype=bool)
    if not counted.any():
        return None
    k = int(np.argmax(np.where(counted, slip, -np.inf)))
    over = counted & (slip > CAGE_SKID_THRESHOLD)
    over_times = times[over]
    return SkidExtent(
        peak=float(slip[k]),
        peak_time=float(times[k]),
        start=float(over_times[0]) if over_times.size else None,
        end=float(over_times[-1]) if over_times.size else None,
        share=float(over.sum() / counted.sum()),
    )


__all__ = [
    "SKID_EXTENT_MIN_ROLLING_FRACTION",
    "SkidExtent",
    "skid_extent",
    "CAGE_SKID_THRESHOLD",
    "SKIDDING_VARIABLES",
    "instantaneous_cage_slip",
    "rolling_cage_speed",
    "skidding_ratio",
    "skidding_variables",
]
