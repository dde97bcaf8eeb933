"""The contact tracks each ring sees in steady running, built from one quasi-static solution.

A quasi-static solution gives every ball's contacts at one instant. When the load field is
stationary in one frame F, that instant is the whole story: a ball's contact angles and loads
depend only on its position psi relative to F, so the solution's balls sample one periodic field
alpha(psi), Q(psi), and the contact point's azimuth is s(psi) (``raceway_azimuth``: its own ring's
frame at t = 0, when every frame coincides). The frame F is

- space (speed 0) when everything imposed is fixed in space: axial and radial loads, a
  misalignment with ``misalignment_frame = "space"``, a tilting moment;
- the inner ring (speed omega_i) for a misalignment turning with the inner ring and nothing fixed
  in space besides the axial load (no radial load, no tilting moment);
- none otherwise (a tilt turning with the ring and a radial load fixed in space: the field changes
  with the ring angle; :func:`solver.quasistatic_answer` solves those over one revolution), and
  none when nothing turns.

**Kinematics.** The balls move through the field at omega_c - omega_F (``cage_speed``); ring f
turns relative to the field at omega_f - omega_F. A contact of a ball at field position psi lies,
at time t, at azimuth s(psi) + (omega_F - omega_f) t in ring f's frame, which is how
:mod:`solver.results.summary` places a dynamic run's samples (own-ring azimuth plus the angle its
ring has turned relative to ring f). So:

- a ring that holds the field still (omega_f = omega_F) meets every ball at field position psi at
  the same azimuth s(psi): its track is the **line** alpha(psi) at s(psi);
- any other ring: a point of it at azimuth phi meets the balls one after another, at times
  2 pi / (Z |omega_c - omega_f|) apart, and between two meetings the field position of the
  meeting advances by (2 pi / Z) rho with rho = (omega_f - omega_F) / (omega_c - omega_f). Unless
  rho / Z is a ratio of small whole numbers (no bearing runs at such a speed ratio exactly), the
  meetings fill the circle of field positions uniformly over a long run: in steady running every
  azimuth of that ring meets the whole field, each position equally often — a **band** whose
  spread at one azimuth is the distribution of alpha(psi) over a uniform psi. (When the balls do
  not move through the field, omega_c = omega_F, the ring meets only the balls' own positions.)

The steady-state samples :func:`steady_samples` returns are these tracks on a regular lattice. A
line: the field at :data:`LINE_FIELD_POSITIONS` equally spaced positions. A band: the field at
:data:`BAND_FIELD_POSITIONS` positions (or at the balls' own positions), each placed at the middle
of every one of the summary's :data:`BAND_AZIMUTH_STEPS` azimuth bins, so that every bin holds the
same samples, as the uniform meetings give over an unending run (where a sample sits in its bin
does not matter to a band, whose spread is the same at every azimuth). Its excursion is then 0: a
dynamic run's band shows a small excursion, the scatter of its bin medians, which shrinks as its
analysed window grows.

The field between two balls is interpolated in psi (contact angle and the small offset
s(psi) - psi): by a periodic cubic spline through the balls when every ball is loaded, else
linearly, a position then being loaded when its nearer ball is, so that a load zone ends half-way
between its last loaded ball and the first open one, where the loaded ball's contact angle holds.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .dataset import ring_speeds
from .loaded import loaded_mask

#: Field positions (equally spaced over 360 degree) at which a line is sampled: 10 per azimuth bin
#: of the trajectory metrics (solver.results.summary, 36 bins of 10 degree, at least 5 needed).
LINE_FIELD_POSITIONS = 360
#: Field positions at which a band is sampled (each at one azimuth in every azimuth bin).
BAND_FIELD_POSITIONS = 72
#: Azimuths of a band: the middles of the trajectory metrics' azimuth bins.
BAND_AZIMUTH_STEPS = 36


def _coordinate(ds: xr.Dataset, name: str):
    """A scalar describing coordinate's value (None when the result lacks it)."""
    if name not in ds.coords:
        return None
    return ds.coords[name].values.item()


def _same_speed(a: float, b: float, scale: float) -> bool:
    return abs(a - b) <= 1e-12 * max(scale, 1.0)


def field_frame_speed(ds: xr.Dataset) -> float | None:
    """Speed [rad/s] of the frame in which the load field of the quasi-static snapshot ``ds`` is
    stationary (module docstring): 0 for space, the inner ring's speed for a misalignment turning
    with the inner ring alone; None when no frame holds it still, when nothing turns (both ring
    speeds and the cage speed zero) or when ``ds`` is not one quasi-static snapshot (it has a
    ``time`` or ``ring_angle`` dimension, or no ``cage_speed``)."""
    if "time" in ds.dims or "ring_angle" in ds.dims or "cage_speed" not in ds:
        return None
    inner, outer = ring_speeds(ds)
    cage = float(ds["cage_speed"])
    if not all(math.isfinite(v) for v in (inner, outer, cage)):
        return None
    if inner == 0.0 and outer == 0.0 and cage == 0.0:
        return None
    frame = _coordinate(ds, "misalignment_frame")
    misalignment = _coordinate(ds, "misalignment")
    moment = _coordinate(ds, "tilting_moment")
    moment_given = moment is not None and math.isfinite(float(moment))
    turning = frame == "ring" and misalignment is not None and float(misalignment) != 0.0
    if not turning or moment_given:
        return 0.0
    radial = _coordinate(ds, "radial_load")
    if radial is not None and float(radial) != 0.0:
        return None
    return inner


def _field(ds: xr.Dataset, race: str):
    """The field one race's contacts sample, ordered by the balls' field position: (psi [degree,
    increasing from the first ball], contact angle [degree], loaded, azimuth offset s - psi
    [degree, in (-180, 180]])."""
    psi = np.asarray(ds["ball_azimuth"].values, dtype=float) % 360.0
    order = np.argsort(psi, kind="stable")
    psi = psi[order]
    angle = np.asarray(ds["contact_angle"].sel(race=race).values, dtype=float)[order]
    load = np.asarray(ds["contact_load"].sel(race=race).values, dtype=float)[order]
    azimuth = np.asarray(ds["raceway_azimuth"].sel(race=race).values, dtype=float)[order]
    offset = (azimuth - psi + 180.0) % 360.0 - 180.0
    return psi, angle, loaded_mask(load, angle), offset


def _interpolated(field, positions: np.ndarray):
    """(azimuth s [degree], contact angle [degree], loaded) of the field at ``positions`` [degree]
    (module docstring: a periodic cubic spline through the balls when every ball is loaded, else
    linear between balls, loaded as the nearer ball)."""
    psi, angle, loaded, offset = field
    count = psi.size
    ends = np.append(psi, psi[0] + 360.0)
    # positions relative to the first ball, in [psi_0, psi_0 + 360)
    query = psi[0] + (positions - psi[0]) % 360.0
    if count >= 3 and loaded.all():
        from scipy.interpolate import CubicSpline

        values = np.column_stack([angle, offset])
        spline = CubicSpline(ends, np.vstack([values, values[:1]]), bc_type="periodic")
        smooth = spline(query)
        return query + smooth[:, 1], smooth[:, 0], np.ones(query.size, dtype=bool)
    left = np.clip(np.searchsorted(ends, query, side="right") - 1, 0, count - 1)
    right = (left + 1) % count
    weight = (query - ends[left]) / (ends[left + 1] - ends[left])
    nearer = np.where(weight < 0.5, left, right)
    both = loaded[left] & loaded[right]
    value = np.where(both, angle[left] + (angle[right] - angle[left]) * weight, angle[nearer])
    shift = offset[left] + (offset[right] - offset[left]) * weight
    return query + shift, value, loaded[nearer]


def steady_samples(ds: xr.Dataset, race: str, frame_speed: float, field_speed: float):
    """(azimuth [degree], contact angle [degree]) of the loaded steady-state samples of ``race``'s
    track in the frame of a ring turning at ``frame_speed`` [rad/s], for the snapshot ``ds`` whose
    field is stationary in a frame turning at ``field_speed`` (:func:`field_frame_speed`): a line
    when the ring holds the field still, else a band (module docstring)."""
    field = _field(ds, race)
    inner, outer = ring_speeds(ds)
    cage = float(ds["cage_speed"])
    scale = max(abs(inner), abs(outer), abs(cage))
    if _same_speed(frame_speed, field_speed, scale):
        positions = np.arange(LINE_FIELD_POSITIONS) * (360.0 / LINE_FIELD_POSITIONS)
        azimuth, angle, loaded = _interpolated(field, field[0][0] + positions)
        return azimuth[loaded], angle[loaded]
    if _same_speed(cage, field_speed, scale):  # the balls stay where they are in the field
        azimuth = field[0] + field[3]
        angle, loaded = field[1], field[2]
    else:
        positions = np.arange(BAND_FIELD_POSITIONS) * (360.0 / BAND_FIELD_POSITIONS)
        azimuth, angle, loaded = _interpolated(field, field[0][0] + positions)
    # every field position at the middle of every azimuth bin: each bin holds the same samples
    count = int(loaded.sum())
    middles = (np.arange(BAND_AZIMUTH_STEPS) + 0.5) * (360.0 / BAND_AZIMUTH_STEPS)
    azimuth = np.repeat(middles, count)
    angle = np.tile(angle[loaded], BAND_AZIMUTH_STEPS)
    return azimuth, angle


def steady_window_text(turning_with_inner_ring: bool) -> str:
    """The analysed window of the steady-state tracks in words (``analysed_window``)."""
    where = "turning with the inner ring" if turning_with_inner_ring else "fixed in space"
    return (
        f"steady running from the quasi-static solution (its load field {where}): each ring's "
        "track over an unending run, the balls moving through the field at the cage speed; "
        "loaded contacts only"
    )


__all__ = [
    "BAND_AZIMUTH_STEPS",
    "BAND_FIELD_POSITIONS",
    "LINE_FIELD_POSITIONS",
    "field_frame_speed",
    "steady_samples",
    "steady_window_text",
]
