"""Trajectory metrics and the settling window: the one definition, used by the dynamic model's
output (stored in its Dataset), the accessor (``ds.racetrace.summary()``), the CLI and the app.

Everything here reads a results Dataset (results-schema.md) only: contact angles, loads and raceway
azimuths per (ball, race[, time]), and the ``inner_ring_speed`` / ``outer_ring_speed`` and
``groove_radius`` coordinates. Angles in degree, lengths in m, times in s.

**Mean track, excursion, band thickness** (per race, per ring frame; loaded contacts in the
analysed window). The contact samples are binned by their raceway azimuth in the ring frame
(:data:`AZIMUTH_BINS` bins of 10 degree); a bin with fewer than :data:`MIN_BIN_SAMPLES` samples is
ignored (too few to give a median: the edges of a load zone). The *mean track* is the median
contact angle of each bin, placed at the median azimuth of the bin's samples and interpolated
linearly to the neighbouring bin's point (when that bin is used; otherwise the bin median holds).

- **excursion** = max - min of the bin medians: how far the track wanders across the groove going
  round the raceway. For a sinusoidal track alpha0 + A cos(phi) it is 2 A cos(5 deg), 0.4 % below
  2 A (the bin medians sit at the bin centres). A band with no mean variation still has a small
  excursion: the scatter of the bin medians, which shrinks as 1/sqrt(samples per bin).
- **band thickness** = 97.5th - 2.5th percentile of the residuals (contact angle minus the mean
  track at its azimuth): the width of the central 95 % of the spread at one raceway azimuth across
  passes and balls. 0 for a thin line; 0.95 w for a band of uniform width w.

Both are given in degree of groove arc and, times the groove radius, in m; beside them
``ellipse_semi_major_mean`` gives the contact ellipse's half-width across the groove for scale.

**Ring frames.** A contact's azimuth in ring f's frame is its azimuth in its own ring's frame
(``raceway_azimuth``) plus the angle its own ring has turned relative to ring f: (omega_r -
omega_f) t, with the ring speeds from the coordinates (each ring's angle is its speed times time,
zero at t = 0). A disturbance fixed to one ring (a radial load fixed in space, so fixed to a
stationary outer ring; a misalignment turning with the inner ring) makes the tracks thin lines in
that ring's frame and bands in the other's: each race's headline value is the one in its own
ring's frame.

**Over one revolution** (a quasi-static solution with a ``ring_angle`` dimension,
:func:`solver.quasistatic_answer` for a misalignment turning with the inner ring): every loaded
contact at every ring angle is one sample. Ring angle theta (inner ring relative to outer) is the
time t = theta / (omega_i - omega_o); a contact's azimuth in ring f's frame is its
``raceway_azimuth`` plus the angle its own ring has turned relative to ring f by then, as for a
dynamic run, and the mean track, excursion and band thickness follow from those samples with the
same bins. The band width is max - min over every ring angle and ball. So a tilt turning with the
inner ring draws a line on the inner raceway (excursion about the snapshot's band width, thickness
near 0) and a band on the outer one, as the dynamic model does.

**One quasi-static solution** (no ``ring_angle``) whose load field is stationary in space, or in
the inner ring for a tilt turning with it alone: each ring's track in steady running, from the
balls' kinematics (:mod:`solver.results.steady_track`): a line in the ring that holds the field
still, a band (excursion 0) in a ring turning through it. A snapshot that no frame holds still (a
tilt turning with the ring beside a radial load) or in which nothing turns has both frames
coincide: its excursion is its band width and its band thickness NaN.

**Settling** (dynamic results, :func:`settling`): per shaft revolution (period 2 pi / |omega_i -
omega_o|, counted from t = 0), the mean over balls and samples of the contact angle and of the
spin-to-roll ratio of each race (loaded contacts). The run has settled at the first revolution
after which every per-revolution mean stays within the tolerances of the last revolution's:
:data:`SETTLING_ANGLE_TOLERANCE` (0.01 degree) for the contact angle, and for the spin-to-roll
ratio :data:`SETTLING_SPIN_TO_ROLL_RELATIVE` (1 %) of its last value or
:data:`SETTLING_SPIN_TO_ROLL_ABSOLUTE` (0.0005), whichever is larger; and the per-revolution
mean cage speed within :data:`SETTLING_CAGE_SPEED_RELATIVE` (0.1 %, the accuracy contract's
allowance for the cage speed) of the last revolution's, so that a cage still skidding down (a
light, fast bearing) is not called settled. At least
:data:`MIN_SETTLED_REVOLUTIONS` (2) full revolutions must follow the settling time. The analysed
window then starts at the settling time; a run that does not settle is analysed after its first
``analysis_skip_fraction`` (:data:`UNSETTLED_SKIP_FRACTION` = 30 % by default) and
:func:`solver.results.checks.result_warnings` says "run too short to settle".

Measured on the shipped spindle cases (7008C-class hybrid, 20 000 rpm, 12 shaft revolutions): the
per-revolution mean contact angles drift by less than 0.015 degree from the first revolution on and
scatter by about +-0.002 degree once settled, while the mean spin-to-roll ratios (0.07 inner,
-0.047 outer) approach their final values by a factor of about 0.43 per revolution; the 1 %
tolerance is reached after 6 revolutions (combined load: settled at t = 6 shaft periods).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from .dataset import ring_speeds
from .energy import ring_down_end
from .life import LIFE_METRICS, rating_life
from .loaded import loaded_mask
from .steady_track import field_frame_speed, steady_samples, steady_window_text
from .variables import dimension_coordinate, variable

AZIMUTH_BINS = 36
MIN_BIN_SAMPLES = 5
SETTLING_ANGLE_TOLERANCE = 0.01  # degree
SETTLING_SPIN_TO_ROLL_RELATIVE = 0.01
SETTLING_SPIN_TO_ROLL_ABSOLUTE = 0.0005
SETTLING_CAGE_SPEED_RELATIVE = 0.001  # of the last revolution's mean cage speed
MIN_SETTLED_REVOLUTIONS = 2
UNSETTLED_SKIP_FRACTION = 0.3

RACES = ("inner", "outer")
FRAMES = ("inner_ring", "outer_ring")
#: Names of the metrics :func:`trajectory_summary` returns for every result.
TRACK_METRICS = (
    "trajectory_excursion",
    "trajectory_excursion_arc",
    "trajectory_band_thickness",
    "trajectory_band_thickness_arc",
    "ellipse_semi_major_mean",
    "trajectory_band_width",
    "trajectory_band_width_arc",
)
#: Names it adds for a dynamic result.
WINDOW_METRICS = ("settling_time", "analysis_start_time", "settled")
QUASISTATIC_THICKNESS_NOTE = (
    "this quasi-static result is one snapshot (one pass of each ball): nothing turns, or no frame "
    "holds its load field still (a tilt turning with the inner ring beside a load fixed in space); "
    "the band thickness needs the solutions over one revolution (solver.quasistatic_answer) or the "
    "passes of a dynamic run (racetrace simulate)"
)
#: The dimension of a quasi-static solution over one revolution (solver.solve_over_revolution):
#: one result whose samples are its ring angles, not a stack of results.
REVOLUTION_DIM = "ring_angle"
#: Dimensions of one result; any other dimension stacks several results (xr.concat, a sweep).
_RESULT_DIMS = ("ball", "race", "time", "axis", "tilt_axis", "quaternion", "body")


# ---- the track metrics on plain arrays -----------------------------------------------------------


def _track_values(excursion, thickness, width, semi_major, groove) -> dict[str, np.ndarray]:
    """The trajectory metrics by name from per (race, frame) ``excursion`` and ``thickness`` and
    per race ``width`` [degree] and ``semi_major`` [m]; the ``_arc`` forms [m] along the groove of
    radius ``groove`` (per race) [m]."""
    arc = np.radians(1.0) * groove
    return {
        "trajectory_excursion": excursion,
        "trajectory_excursion_arc": excursion * arc[:, None],
        "trajectory_band_thickness": thickness,
        "trajectory_band_thickness_arc": thickness * arc[:, None],
        "ellipse_semi_major_mean": semi_major,
        "trajectory_band_width": width,
        "trajectory_band_width_arc": width * arc,
    }


def track_metrics(
    azimuth, angle, bins: int = AZIMUTH_BINS, min_samples: int = MIN_BIN_SAMPLES
) -> tuple[float, float]:
    """(excursion, band thickness) of contact samples, in the unit of ``angle``.

    ``azimuth`` [degree, any real value; taken modulo 360] and ``angle`` are 1-D arrays of the same
    length: one entry per loaded contact sample. See the module docstring for the definitions.
    (nan, nan) when no bin holds ``min_samples`` samples.
    """
    azimuth = np.mod(np.asarray(azimuth, dtype=float).ravel(), 360.0)
    angle = np.asarray(angle, dtype=float).ravel()
    if azimuth.shape != angle.shape:
        raise ValueError("azimuth and angle must have the same number of samples")
    ok = np.isfinite(azimuth) & np.isfinite(angle)
    azimuth, angle = azimuth[ok], angle[ok]
    width = 360.0 / bins
    index = np.minimum((azimuth // width).astype(int), bins - 1)
    counts = np.bincount(index, minlength=bins)
    medians = np.full(bins, np.nan)
    centres = np.full(bins, np.nan)  # median azimuth of each used bin
    order = np.argsort(index, kind="stable")
    splits = np.cumsum(counts)[:-1]
    for b, (chunk, where) in enumerate(
        zip(np.split(angle[order], splits), np.split(azimuth[order], splits), strict=True)
    ):
        if chunk.size >= max(min_samples, 1):
            medians[b] = np.median(chunk)
            centres[b] = np.median(where)
    used = np.isfinite(medians)
    if not used.any():
        return math.nan, math.nan
    excursion = float(medians[used].max() - medians[used].min())
    # mean track at each sample: from its bin's point towards the neighbouring bin's on its side
    own_x = centres[index]
    step = np.where(azimuth >= own_x, 1, -1)
    neighbour = (index + step) % bins
    other_x = centres[neighbour] + 360.0 * ((index + step) // bins)  # unwrapped across 0/360
    own, other = medians[index], medians[neighbour]
    span = other_x - own_x
    weight = np.clip((azimuth - own_x) / np.where(span != 0.0, span, np.inf), 0.0, 1.0)
    track = np.where(np.isfinite(other), own + (other - own) * weight, own)
    keep = np.isfinite(own)
    residual = angle[keep] - track[keep]
    high, low = np.percentile(residual, [97.5, 2.5])
    return excursion, float(high - low)


# ---- settling -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Settling:
    """Where a dynamic run settles (see the module docstring); times in s.

    ``settled``: settling found with at least MIN_SETTLED_REVOLUTIONS full shaft revolutions after
    it. ``settling_time``: start of the first settled revolution (nan when not settled).
    ``candidate_time``: the same for the last revolution found within tolerance even when too
    few revolutions follow it (nan when the run has fewer than 2 full revolutions).
    ``revolutions``: full shaft revolutions in the run; ``period``: one shaft revolution.
    ``drift``: the largest departure from the final value in the revolution just before
    ``candidate_time``, as text (quantity, race, value, tolerance), "" when there is none.
    """

    settled: bool
    settling_time: float
    candidate_time: float
    revolutions: int
    period: float
    drift: str


def _revolution_means(ds, name: str, race: str, revolution: np.ndarray, count: int) -> np.ndarray:
    def array(variable: str) -> np.ndarray:
        da = ds[variable].sel(race=race).transpose("time", "ball")
        return np.asarray(da.values, dtype=float)

    values = array(name)
    loaded = loaded_mask(array("contact_load"), array("contact_angle")) & np.isfinite(values)
    means = np.full(count, np.nan)
    for k in range(count):
        mask = loaded & (revolution == k)[:, None]
        if mask.any():
            means[k] = values[mask].mean()
    return means


def _compare_with_last(means, tolerance, within, worst, describe) -> None:
    """Mark in ``within`` (bool per revolution) the revolutions whose mean in ``means`` departs
    from the last revolution's by more than ``tolerance``, and keep in ``worst`` {revolution:
    (departure / tolerance, text)} the largest such departure, in words from
    ``describe(revolution, departure)``."""
    departure = np.abs(means - means[-1])
    ok = np.isfinite(departure) & (departure <= tolerance)
    within &= ok
    for k in np.flatnonzero(~ok):
        ratio = departure[k] / tolerance if np.isfinite(departure[k]) else math.inf
        if k not in worst or ratio > worst[k][0]:
            worst[k] = (ratio, describe(k, departure[k]))


def settling(ds: xr.Dataset) -> Settling:
    """Settling of a dynamic result (``time`` dimension; reads ``contact_angle`` and
    ``contact_load``, and ``spin_to_roll`` and ``cage_speed`` when the result has them)."""
    inner, outer = ring_speeds(ds)
    relative = abs(inner - outer)
    times = np.asarray(ds["time"].values, dtype=float)
    if relative <= 0.0 or times.size < 2:
        return Settling(False, math.nan, math.nan, 0, math.inf, "")
    period = 2.0 * math.pi / relative
    count = int(math.floor(times[-1] / period + 1e-9))
    if count < 2:
        return Settling(False, math.nan, math.nan, count, period, "")
    revolution = np.floor(times / period + 1e-9).astype(int)
    within = np.ones(count, dtype=bool)  # within tolerance of the last revolution
    worst: dict[int, tuple[float, str]] = {}
    quantities = [
        (n, u) for n, u in (("contact_angle", " degree"), ("spin_to_roll", "")) if n in ds
    ]
    for race in RACES:
        for name, unit in quantities:
            means = _revolution_means(ds, name, race, revolution, count)
            final = means[-1]
            if not np.isfinite(final):
                continue  # no loaded contact on this race at the end: nothing to settle
            if name == "contact_angle":
                tolerance = SETTLING_ANGLE_TOLERANCE
            else:
                tolerance = max(
                    SETTLING_SPIN_TO_ROLL_RELATIVE * abs(final), SETTLING_SPIN_TO_ROLL_ABSOLUTE
                )
            label = name.replace("_", "-") if name == "spin_to_roll" else "contact angle"
            _compare_with_last(
                means,
                tolerance,
                within,
                worst,
                lambda k, d, label=label, race=race, unit=unit, tol=tolerance: (
                    f"the mean {label} of the {race} race in revolution {k + 1} differs "
                    f"from the last revolution's by {d:.3g}{unit} (tolerance {tol:.2g}{unit})"
                ),
            )
    if "cage_speed" in ds and ds["cage_speed"].dims == ("time",):
        speed = np.asarray(ds["cage_speed"].values, dtype=float)
        means = np.array(
            [
                speed[revolution == k].mean() if np.any(revolution == k) else np.nan
                for k in range(count)
            ]
        )
        final = means[-1]
        if np.isfinite(final) and final != 0.0:
            _compare_with_last(
                means,
                SETTLING_CAGE_SPEED_RELATIVE * abs(final),
                within,
                worst,
                lambda k, d: (
                    f"the mean cage speed in revolution {k + 1} differs from the last "
                    f"revolution's by {100.0 * d / abs(final):.3g} % (tolerance "
                    f"{100.0 * SETTLING_CAGE_SPEED_RELATIVE:.2g} %)"
                ),
            )
    # first revolution after which every later one is within tolerance
    first = count - 1
    while first > 0 and within[first - 1]:
        first -= 1
    drift = worst[first - 1][1] if first > 0 else ""
    candidate = first * period
    settled = count - first >= MIN_SETTLED_REVOLUTIONS
    return Settling(settled, candidate if settled else math.nan, candidate, count, period, drift)


def analysis_start(ds: xr.Dataset, skip_fraction: float = UNSETTLED_SKIP_FRACTION):
    """(index of the first analysed time sample, Settling) of a dynamic result: the settling time
    when the run settled, else the sample at ``skip_fraction`` of the run; never before
    :func:`ring_down_end`."""
    times = np.asarray(ds["time"].values, dtype=float)
    state = settling(ds)
    if state.settled:
        first = int(np.searchsorted(times, state.settling_time - 1e-9 * state.period))
    else:
        first = int(math.floor(skip_fraction * (times.size - 1)))
    ring_down = ring_down_end(times, state.period)
    if ring_down > 0.0:
        first = max(first, int(np.searchsorted(times, ring_down - 1e-9 * state.period)))
    return min(first, times.size - 1), state


def window_text(ds: xr.Dataset, first: int, state: Settling, skip_fraction: float) -> str:
    """The analysed window in words (for the ``analysed_window`` attribute)."""
    times = np.asarray(ds["time"].values, dtype=float)
    start, end = float(times[first]), float(times[-1])
    period = state.period
    span = (
        f"t from {start:.6g} s to {end:.6g} s (shaft revolutions {start / period:.3f} to "
        f"{end / period:.3f})"
        if math.isfinite(period)
        else f"t from {start:.6g} s to {end:.6g} s"
    )
    if state.settled and start > state.settling_time + 1e-9 * period:
        why = "from the end of the first shaft revolution on (the ring-down from the start)"
    elif state.settled:
        why = "from the settling time on"
    else:
        why = f"the run did not settle: the first {skip_fraction:.0%} of the run is skipped"
    return f"{span}, {why}; loaded contacts only"


def unsettled_message(ds: xr.Dataset, state: Settling, start_time: float) -> str:
    """The 'run too short to settle' warning (plain text) for an unsettled dynamic result."""
    run = float(ds["time"].values[-1])
    period = state.period
    suggested = max(2 * math.ceil(run / period - 1e-9), MIN_SETTLED_REVOLUTIONS + 1)
    if state.revolutions < 2:
        why = (
            f"it covers {run / period:.3g} shaft revolutions, fewer than the 2 full revolutions "
            "needed to compare one with the next"
        )
    else:
        after = round(state.candidate_time / period)
        why = (
            f"the per-revolution means come within tolerance of the last revolution's only after "
            f"revolution {after} of {state.revolutions}, leaving {state.revolutions - after} full "
            f"revolution(s) where {MIN_SETTLED_REVOLUTIONS} are needed ({state.drift})"
        )
    return (
        f"run too short to settle: {why}. The ball spin state (spin-to-roll ratio) and the contact "
        f"angles may still be changing, so the trajectory metrics (taken from t = {start_time:.4g} "
        f"s on) may not describe the steady running. Run longer: about {suggested} shaft "
        "revolutions suggested ([simulation] shaft_revolutions or racetrace simulate "
        "--revolutions)."
    )


# ---- the summary Dataset ------------------------------------------------------------------------
def _race_array(ds, name: str, race: str, first: int, last: int | None = None) -> np.ndarray:
    da = ds[name].sel(race=race)
    if "time" in da.dims:
        return np.asarray(da.transpose("time", "ball").values, dtype=float)[first:last]
    return np.asarray(da.values, dtype=float)[None, :]


def _tracks(ds: xr.Dataset, first: int, last: int | None, field_speed) -> dict[str, np.ndarray]:
    """The :data:`TRACK_METRICS` of the time samples ``first`` to ``last`` (exclusive; None: to
    the end) of a dynamic result, or of a quasi-static one (``field_speed``: the speed of the
    frame that holds its load field still, None when none does)."""
    dynamic = "time" in ds.dims
    times = np.asarray(ds["time"].values, dtype=float)[first:last] if dynamic else np.zeros(1)
    speeds = dict(zip(FRAMES, ring_speeds(ds), strict=True))
    groove = np.asarray(ds.coords["groove_radius"].sel(race=list(RACES)).values, dtype=float)
    shape = (len(RACES), len(FRAMES))
    excursion, thickness = np.full(shape, np.nan), np.full(shape, np.nan)
    width, semi_major = np.full(len(RACES), np.nan), np.full(len(RACES), np.nan)
    for k, race in enumerate(RACES):
        angle = _race_array(ds, "contact_angle", race, first, last)
        loaded = loaded_mask(_race_array(ds, "contact_load", race, first, last), angle)
        if not loaded.any():
            continue
        width[k] = angle[loaded].max() - angle[loaded].min()
        semi_major[k] = _race_array(ds, "ellipse_semi_major", race, first, last)[loaded].mean()
        own = _race_array(ds, "raceway_azimuth", race, first, last)
        for f, frame in enumerate(FRAMES):
            if not dynamic and field_speed is not None:
                samples = steady_samples(ds, race, speeds[frame], field_speed)
                excursion[k, f], thickness[k, f] = track_metrics(*samples)
                continue
            if not dynamic:  # no frame holds the field still: the snapshot alone
                excursion[k, f] = width[k]
                continue
            turned = np.degrees((speeds[f"{race}_ring"] - speeds[frame]) * times)[:, None]
            excursion[k, f], thickness[k, f] = track_metrics((own + turned)[loaded], angle[loaded])
    return _track_values(excursion, thickness, width, semi_major, groove)


def _track_dataset(values: dict[str, np.ndarray]) -> xr.Dataset:
    """Metrics by name (from :func:`_tracks`, and any others :func:`variable` defines) as a
    Dataset over ``race`` and ``frame``, each with its attributes."""
    return xr.Dataset(
        {n: (variable(n).dims, v, variable(n).attrs()) for n, v in values.items()},
        coords={"race": dimension_coordinate("race"), "frame": dimension_coordinate("frame")},
    )


#: What :func:`stretch_track_summary` reads of a result besides ``time`` (the ring speeds are
#: coordinates where they are constant, variables over ``time`` where they vary).
STRETCH_VARIABLES = (
    "contact_angle",
    "contact_load",
    "ellipse_semi_major",
    "raceway_azimuth",
    "inner_ring_speed",
    "outer_ring_speed",
    "groove_radius",
)


def stretch_track_summary(ds: xr.Dataset) -> xr.Dataset:
    """The :data:`TRACK_METRICS` over every time sample of a dynamic result, analysed whole: no
    settling test, no analysed window, no rating life (a live session's last revolutions, whose
    inputs may still be changing). Reads only ``time`` and :data:`STRETCH_VARIABLES`.
    ValueError for a result without ``time``."""
    if "time" not in ds.dims:
        raise ValueError("a stretch's track summary needs a dynamic result (a time dimension)")
    return _track_dataset(_tracks(ds, 0, None, None))


def phase_summary(ds: xr.Dataset) -> xr.Dataset:
    """The trajectory metrics of each phase of a dynamic result (:mod:`solver.results.phases`):
    the :data:`TRACK_METRICS` over every sample of the phase, with a ``phase`` dimension and its
    coordinates; ``analysis_start_time`` is the phase's start, ``settling_time`` and ``settled``
    are NaN (a phase is analysed whole, its transient included). A steady result has one phase,
    its analysed window, whose track metrics are the result's own."""
    from .phases import phase_mask

    mask = phase_mask(ds)
    parts = []
    for k in range(mask.sizes["phase"]):
        index = np.flatnonzero(mask.values[k])
        if index.size:
            values = _tracks(ds, int(index[0]), int(index[-1]) + 1, None)
        else:  # a phase shorter than the sample period: no sample
            values = {n: np.full_like(v, np.nan) for n, v in _tracks(ds, 0, 1, None).items()}
        values["settling_time"] = np.float64(math.nan)
        values["analysis_start_time"] = np.float64(mask["phase_start_time"].values[k])
        values["settled"] = np.float64(math.nan)
        parts.append(_track_dataset(values))
    phase_coordinates = {name: c for name, c in mask.coords.items() if c.dims == ("phase",)}
    return xr.concat(parts, dim="phase").assign_coords(phase_coordinates)


def _element_summary(ds: xr.Dataset, skip_fraction: float) -> xr.Dataset:
    dynamic = "time" in ds.dims
    if dynamic:
        first, state = analysis_start(ds, skip_fraction)
        times = np.asarray(ds["time"].values, dtype=float)[first:]
    else:
        first, state, times = 0, None, np.zeros(1)
    # a snapshot whose load field is stationary in one frame: the steady-state tracks
    field_speed = None if dynamic else field_frame_speed(ds)
    values = _tracks(ds, first, None, field_speed)
    attrs = {}
    if dynamic:
        text = window_text(ds, first, state, skip_fraction)
        values["settling_time"] = np.float64(state.settling_time)
        values["analysis_start_time"] = np.float64(times[0])
        values["settled"] = np.int8(1 if state.settled else 0)
        attrs["analysed_window"] = text
    elif field_speed is not None:
        text = steady_window_text(field_speed != 0.0)
        attrs["analysed_window"] = text
    else:
        text = "the quasi-static snapshot: every loaded ball once"
    out = {}
    for name, value in values.items():
        spec = variable(name)
        var_attrs = spec.attrs()
        if name.startswith("trajectory_") or name == "ellipse_semi_major_mean":
            var_attrs["analysed_window"] = text
        if field_speed is None and not dynamic and name.startswith("trajectory_band_thickness"):
            var_attrs["note"] = QUASISTATIC_THICKNESS_NOTE
        out[name] = (spec.dims, value, var_attrs)
    coords = {"race": dimension_coordinate("race"), "frame": dimension_coordinate("frame")}
    metrics = xr.Dataset(out, coords=coords, attrs=attrs)
    return metrics.assign(rating_life(ds, first).data_vars)


def trajectory_summary(ds: xr.Dataset, skip_fraction: float = UNSETTLED_SKIP_FRACTION):
    """The trajectory metrics of a result, computed from its data (module docstring).

    A quasi-static snapshot gives the excursion over its loaded balls (the same in both frames) and
    NaN band thicknesses (with a ``note`` attribute); a quasi-static solution over one revolution
    (a ``ring_angle`` dimension) all track metrics over its ring angles and balls, its window in
    ``attrs["analysed_window"]``; a dynamic one all metrics over its analysed
    window plus ``settling_time``, ``analysis_start_time`` and ``settled``, and the window in
    ``attrs["analysed_window"]``. ``skip_fraction``: start of the window of an unsettled run, as
    a fraction of the run. A result stacked along further dimensions (``xr.concat`` of several
    results, a speed sweep) gives the metrics of every element along those dimensions.
    """
    extra = [d for d in ds["contact_angle"].dims if d not in (*_RESULT_DIMS, REVOLUTION_DIM)]
    if extra:
        dim = extra[0]
        parts = [trajectory_summary(ds.isel({dim: i}), skip_fraction) for i in range(ds.sizes[dim])]
        stacked = xr.concat(
            parts, dim=dim, coords="different", compat="equals", combine_attrs="drop_conflicts"
        )
        return stacked.assign_coords({dim: ds[dim]}) if dim in ds.coords else stacked
    if REVOLUTION_DIM in ds["contact_angle"].dims and "time" not in ds.dims:
        return _revolution_summary(ds)
    return _element_summary(ds, skip_fraction)


def _revolution_summary(ds: xr.Dataset) -> xr.Dataset:
    """The trajectory metrics of a quasi-static solution over one revolution (a ``ring_angle``
    dimension): every loaded contact at every ring angle is one sample, placed in each ring frame
    by the angle its own ring has turned relative to that ring's at that ring angle (module
    docstring, "Over one revolution"). Life metrics: those of ring angle 0."""
    ring_angles = np.radians(np.asarray(ds[REVOLUTION_DIM].values, dtype=float))
    inner_speed, outer_speed = ring_speeds(ds)
    relative = inner_speed - outer_speed
    outer_turn = outer_speed * ring_angles / relative if relative != 0.0 else 0.0 * ring_angles
    turned = {
        "inner_ring": np.degrees(ring_angles + outer_turn),
        "outer_ring": np.degrees(outer_turn),
    }
    groove = np.asarray(ds.coords["groove_radius"].sel(race=list(RACES)).values, dtype=float)
    shape = (len(RACES), len(FRAMES))
    excursion, thickness = np.full(shape, np.nan), np.full(shape, np.nan)
    width, semi_major = np.full(len(RACES), np.nan), np.full(len(RACES), np.nan)

    def array(name: str, race: str) -> np.ndarray:
        values = ds[name].sel(race=race).transpose(REVOLUTION_DIM, "ball").values
        return np.asarray(values, dtype=float)

    for k, race in enumerate(RACES):
        angle = array("contact_angle", race)
        loaded = loaded_mask(array("contact_load", race), angle)
        if not loaded.any():
            continue
        width[k] = angle[loaded].max() - angle[loaded].min()
        semi_major[k] = array("ellipse_semi_major", race)[loaded].mean()
        own = array("raceway_azimuth", race)
        for f, frame in enumerate(FRAMES):
            shift = (turned[f"{race}_ring"] - turned[frame])[:, None]
            excursion[k, f], thickness[k, f] = track_metrics((own + shift)[loaded], angle[loaded])
    values = _track_values(excursion, thickness, width, semi_major, groove)
    text = (
        f"the quasi-static solutions at {ring_angles.size} inner-ring angles over one revolution: "
        "every loaded ball at every angle"
    )
    out = {}
    for name, value in values.items():
        spec = variable(name)
        out[name] = (spec.dims, value, {**spec.attrs(), "analysed_window": text})
    coords = {"race": dimension_coordinate("race"), "frame": dimension_coordinate("frame")}
    metrics = xr.Dataset(out, coords=coords, attrs={"analysed_window": text})
    return metrics.assign(rating_life(ds.isel({REVOLUTION_DIM: 0}, drop=True)).data_vars)


def stored_summary(ds: xr.Dataset) -> xr.Dataset | None:
    """The metrics stored in a result (a dynamic run writes them), or None when any trajectory
    metric is missing. Life metrics missing from a stored result (written before they existed)
    are computed over its stored analysed window."""
    names = TRACK_METRICS + (WINDOW_METRICS if "time" in ds.dims else ())
    if not all(name in ds for name in names):
        return None
    stored_life = all(name in ds for name in LIFE_METRICS)
    out = ds[list(names) + (list(LIFE_METRICS) if stored_life else [])]
    out = out.drop_vars([c for c in out.coords if c not in ("race", "frame", *out.dims)])
    out.attrs = {k: ds.attrs[k] for k in ("analysed_window",) if k in ds.attrs}
    if not stored_life:
        first = 0
        if "time" in ds.dims:
            start = float(ds["analysis_start_time"])
            first = int(np.searchsorted(np.asarray(ds["time"].values, float), start))
        out = out.assign(rating_life(ds, min(first, ds.sizes.get("time", 1) - 1)).data_vars)
    return out


def summary(ds: xr.Dataset) -> xr.Dataset:
    """The metrics of a result: the stored ones when it has them, otherwise computed."""
    stored = stored_summary(ds)
    return stored if stored is not None else trajectory_summary(ds)


__all__ = [
    "AZIMUTH_BINS",
    "MIN_BIN_SAMPLES",
    "MIN_SETTLED_REVOLUTIONS",
    "SETTLING_ANGLE_TOLERANCE",
    "SETTLING_SPIN_TO_ROLL_ABSOLUTE",
    "SETTLING_SPIN_TO_ROLL_RELATIVE",
    "Settling",
    "analysis_start",
    "phase_summary",
    "settling",
    "stored_summary",
    "summary",
    "track_metrics",
    "trajectory_summary",
    "unsettled_message",
]
