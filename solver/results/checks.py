"""Warnings about a result that lies outside the model's validity (quasi-static or dynamic).

:func:`result_warnings` reads only the results Dataset (results-schema.md): the per-contact
variables, the ``ball_diameter`` and ``groove_radius`` coordinates and, for a dynamic run, the
``time`` dimension, the ``complete`` attribute and the settling window
(:mod:`solver.results.summary`). Each message names the quantity, the race,
where it happens (how many contacts and which balls, or which balls and what share of the run), the
worst value with its unit, the limit, why it matters and what to try. An empty list means no check
fired; it does not prove the result right.

The checks, per race:

- **shoulder truncation**: ``truncation_margin`` < 0 deg at a loaded contact. The ellipse runs over
  the land's edge, so the pressure is no longer elliptic (Hertz theory no longer holds) and the edge
  loads the ball. NaN margins (no shoulder given) are skipped.
- **static pressure limit**: ``max_pressure`` > 4.2 GPa, the ISO 76 reference contact stress for
  ball bearings (self-aligning ones excepted): the stress at which the permanent deformation of
  ball and raceway together is about 1e-4 of the ball diameter, the basis of the static load
  rating. It is a static limit; exceeding it dents (brinells) the raceways.
- **contact too large for Hertz theory** (see :func:`_hertz_size_check`): the ellipse wraps past the
  top of the groove (contact angle + semi-major / groove radius > 90 deg), or its semi-major axis
  exceeds the ball radius D/2.

the quasi-static **ball speeds fell back to race control** (attribute ``kinematics_note``: the
traction balance asked for by the case found no steady ball speeds), and, for a dynamic result,
**stopped early**: ``complete`` == 0, and **run too short to settle**:
``settled`` == 0 (the stored flag; computed by :func:`solver.results.summary.settling` for a result
that does not store it but has the spin-to-roll ratios), and **friction torque far from the
estimates**: the mean ``friction_torque`` over the analysed window lies outside a factor 3 of every
empirical estimate the result stores (``friction_torque_palmgren``, ``friction_torque_skf``),
and **the cage skids**: the mean instantaneous cage slip (solver.results.skidding) over the
analysed window, or over a phase of the result's history (solver.results.phases), exceeds
:data:`solver.results.skidding.CAGE_SKID_THRESHOLD` (1 %), and **the energy balance does not
close**: the residual of
:func:`solver.results.energy.energy_balance` over the analysed window exceeds
:data:`solver.results.energy.RESIDUAL_LIMIT` (1 % of the losses) in magnitude.
"""

from __future__ import annotations

import math

import numpy as np

from . import energy, summary
from .loaded import loaded_mask

#: ISO 76 reference contact stress for ball bearings (except self-aligning), Pa: the static limit.
STATIC_PRESSURE_LIMIT = 4.2e9
#: Largest contact angle plus ellipse angular half-width across the groove, degree.
GROOVE_WRAP_LIMIT = 90.0
#: Largest ellipse semi-major axis as a fraction of the ball diameter D (the ball radius).
SEMI_MAJOR_LIMIT_OF_D = 0.5


def result_warnings(ds) -> list[str]:
    """Messages (plain text, one per finding) about where ``ds`` leaves the model's validity.

    ``ds`` is a quasi-static or dynamic results Dataset (results-schema.md); dims ``(ball, race)``
    or ``(ball, race, time)``. Angles in the Dataset are in degree, lengths in m, pressures in Pa.
    """
    found: list[str] = []
    if ds.attrs.get("kinematics_note"):
        found.append(
            f"quasi-static ball speeds: {ds.attrs['kinematics_note']}. Race control puts the "
            "gyroscopic moment on one race and differs from the dynamic model's steady contact "
            "angles by a few tenths of a degree (docs/quasistatic-traction.md)."
        )
    if "time" in ds.dims and int(ds.attrs.get("complete", 1)) == 0:
        found.append(_incomplete_message(ds))
    if "time" in ds.dims:
        found += _settling_check(ds)
        found += _torque_estimate_check(ds)
        found += _energy_check(ds)
        found += _skidding_check(ds)
    grooves = _groove_radii(ds)
    for race in [str(r) for r in ds["race"].values]:
        too_large = _hertz_size_check(ds, race, *grooves) if grooves is not None else ""
        # a contact too large for Hertz theory makes its truncation margin meaningless: say one
        truncated = "" if too_large else _truncation_check(ds, race)
        found += [m for m in (too_large, truncated, _pressure_check(ds, race)) if m]
    return found


# ---- the friction torque against the empirical estimates ----------------------------------------
#: The model's friction torque is flagged when it lies outside this factor of every estimate.
TORQUE_ESTIMATE_FACTOR = 3.0
_ESTIMATE_NAMES = {"friction_torque_palmgren": "Palmgren", "friction_torque_skf": "SKF model"}


def _torque_estimate_check(ds) -> list[str]:
    """The mean friction torque of the analysed window outside a factor 3 of every empirical
    estimate stored in the result (solver.results.estimates); nothing when none is stored."""
    estimates = {
        label: float(ds[name])
        for name, label in _ESTIMATE_NAMES.items()
        if name in ds and ds[name].ndim == 0 and math.isfinite(float(ds[name]))
    }
    if not estimates or "friction_torque" not in ds:
        return []
    times = np.asarray(ds["time"].values, dtype=float)
    start = float(ds["analysis_start_time"]) if "analysis_start_time" in ds else times[0]
    torque = np.asarray(ds["friction_torque"].values, dtype=float)[times >= start]
    torque = torque[np.isfinite(torque)]
    if torque.size == 0:
        return []
    model = float(torque.mean())
    slack = 1.0 + 1.0e-12  # the factor itself counts as inside (rounding of the product)
    inside = [
        1.0 / (TORQUE_ESTIMATE_FACTOR * slack) <= model / value <= TORQUE_ESTIMATE_FACTOR * slack
        for value in estimates.values()
        if value > 0.0
    ]
    if any(inside):
        return []
    quoted = ", ".join(f"{label} {value * 1e3:.4g} N mm" for label, value in estimates.items())
    ratio = ", ".join(f"{model / value:.3g} x {label}" for label, value in estimates.items())
    return [
        f"friction torque: the model's mean friction torque over the analysed window, "
        f"{model * 1e3:.4g} N mm, lies outside a factor {TORQUE_ESTIMATE_FACTOR:g} of every "
        f"empirical estimate ({quoted}; the model gives {ratio}). The estimates are catalogue "
        "formulas for oil-air lubrication and may not fit this bearing, but a gap this large "
        "also arises from an unconverged run (tighten simulation.tolerance), gross sliding, an "
        "oil far from the application, or drag and cage losses that the case overstates: compare "
        "power_loss by source before trusting the torque."
    ]


# ---- reading the Dataset -----------------------------------------------------------------------
def _race_values(ds, name: str, race: str) -> np.ndarray:
    """Values of a per-contact variable on one race as an array (ball, time); time of length 1
    for a quasi-static result."""
    da = ds[name].sel(race=race)
    if "time" in da.dims:
        return np.asarray(da.transpose("ball", "time").values, dtype=float)
    return np.asarray(da.values, dtype=float)[:, None]


def _loaded(ds, race: str) -> np.ndarray:
    """True at loaded contacts (:func:`~solver.results.loaded.loaded_mask`; open contacts have no
    ellipse to check)."""
    return loaded_mask(
        _race_values(ds, "contact_load", race), _race_values(ds, "contact_angle", race)
    )


def _groove_radii(ds) -> tuple[float, dict[str, float]] | None:
    """(ball diameter D [m], {race: groove radius [m]}) from the result's coordinates; None when
    the result does not carry them."""
    if "ball_diameter" not in ds.coords or "groove_radius" not in ds.coords:
        return None
    diameter = float(ds.coords["ball_diameter"])
    radii = {race: float(ds.coords["groove_radius"].sel(race=race)) for race in ("inner", "outer")}
    if not (math.isfinite(diameter) and diameter > 0.0):
        return None
    return diameter, radii


# ---- describing where a check fires ------------------------------------------------------------
def _ball_list(balls) -> str:
    """Ball numbers as compact ranges: "0-3, 7, 9-10"."""
    balls = sorted(int(b) for b in balls)
    runs: list[list[int]] = []
    for b in balls:
        if runs and b == runs[-1][1] + 1:
            runs[-1][1] = b
        else:
            runs.append([b, b])
    return ", ".join(f"{lo}" if lo == hi else f"{lo}-{hi}" for lo, hi in runs)


def _where(ds, flagged: np.ndarray) -> str:
    """Where a (ball, time) mask is true, in words: contacts and balls, and the share of the run."""
    n_balls, n_times = flagged.shape
    balls = np.flatnonzero(flagged.any(axis=1))
    ball_word = "ball" if len(balls) == 1 else "balls"
    if "time" not in ds.dims:
        return f"at {len(balls)} of {n_balls} contacts ({ball_word} {_ball_list(balls)})"
    samples = flagged.any(axis=0)
    times = np.asarray(ds["time"].values, dtype=float)
    share = 100.0 * samples.sum() / n_times
    first, last = times[samples][0], times[samples][-1]
    return (
        f"on {ball_word} {_ball_list(balls)} (of {n_balls}) during {share:.3g}% of the run "
        f"({samples.sum()} of {n_times} time samples, between t = {first:.4g} s and {last:.4g} s)"
    )


# ---- the checks --------------------------------------------------------------------------------
def _truncation_check(ds, race: str) -> str:
    """Contact ellipse cut by the shoulder: truncation_margin < 0 deg at a loaded contact."""
    if "truncation_margin" not in ds:
        return ""
    margin = _race_values(ds, "truncation_margin", race)
    flagged = _loaded(ds, race) & (margin < 0.0)  # NaN (no shoulder) compares False
    if not flagged.any():
        return ""
    worst = float(margin[flagged].min())
    return (
        f"{race} race: the contact ellipse runs over the shoulder {_where(ds, flagged)}; "
        f"by up to {-worst:.3g} deg of groove arc (truncation_margin {worst:.3g} deg, "
        "limit 0 deg). Hertz theory no longer holds "
        "there: the land's edge loads the ball (edge loading, a stress concentration the computed "
        "pressures do not show). Try a lower axial load or check "
        f"bearing.{race}_shoulder_diameter_mm."
    )


def _pressure_check(ds, race: str) -> str:
    """Peak Hertz pressure above the ISO 76 static limit (4.2 GPa)."""
    pressure = _race_values(ds, "max_pressure", race)
    flagged = pressure > STATIC_PRESSURE_LIMIT
    if not flagged.any():
        return ""
    worst = float(pressure[flagged].max())
    return (
        f"{race} race: peak contact pressure {worst * 1e-9:.3g} GPa "
        f"{_where(ds, flagged)}, above the static limit of {STATIC_PRESSURE_LIMIT * 1e-9:.3g} GPa "
        "(ISO 76 reference contact stress for ball bearings: the ball and raceway deform "
        "permanently by about 1e-4 of the ball diameter). The raceways would be dented; try a "
        "lower load or a larger bearing."
    )


def _hertz_size_check(ds, race: str, ball_diameter: float, groove_radius: dict) -> str:
    """Contact so large that Hertz theory cannot hold, even with no shoulder in the way.

    Hertz theory replaces both surfaces near the contact by paraboloids on elastic half-spaces, so
    the contact must be small against the radii of curvature. Two limits are used, both geometric
    impossibilities rather than accuracy thresholds, so that a heavily loaded but real bearing is
    left to the pressure check:

    - contact angle alpha + semi-major a / groove radius (f D), in degrees, above 90: the ellipse
      spans the groove angles alpha +- a/(f D); at 90 deg the groove profile is parallel to the
      radial plane and beyond it the profile would turn back over the ball, which no ring has (the
      ring could not be assembled). The contact would wrap past the top of the groove.
    - a > D/2: the contact would be wider than the ball. In a conforming contact the gap between
      ball and groove at distance x across the groove is x^2 (1/R - 1/r) / 2 (the paraboloid Hertz
      keeps) plus x^4 (1/R^3 - 1/r^3) / 8; for r close to R = D/2 the second term reaches about
      3/4 of the first at x = R, so at a = D/2 the geometry Hertz theory assumes is gone.

    For scale, the shipped catalogue cases reach alpha + a/(f D) <= 71 deg and a <= 0.16 D; with
    a fixed geometry a and p_max both grow as Q^(1/3), so a = D/2 lies at 2-3 times the 4.2 GPa
    static limit for these bearings.
    """
    loaded = _loaded(ds, race)
    semi_major = _race_values(ds, "ellipse_semi_major", race)
    angle = np.abs(_race_values(ds, "contact_angle", race))
    radius = groove_radius[race]
    span = angle + np.degrees(semi_major / radius)
    wraps = loaded & (span > GROOVE_WRAP_LIMIT)
    size_limit = SEMI_MAJOR_LIMIT_OF_D * ball_diameter
    too_wide = loaded & (semi_major > size_limit)
    if not (wraps.any() or too_wide.any()):
        return ""
    reasons = []
    if wraps.any():
        worst_span = float(span[wraps].max())
        reach = (  # past 180 deg the number has no geometric meaning left: do not show it
            f"reaches {worst_span:.3g} deg" if worst_span <= 180.0 else "goes far"
        )
        reasons.append(
            f"contact angle plus the ellipse's angular half-width across the groove "
            f"(semi-major axis / groove radius {radius * 1e3:.4g} mm) {reach} beyond the "
            f"{GROOVE_WRAP_LIMIT:g} deg top of the groove"
        )
    if too_wide.any():
        reasons.append(
            f"ellipse semi-major axis reaches {float(semi_major[too_wide].max()) * 1e3:.3g} mm, "
            f"more than the ball radius D/2 = {size_limit * 1e3:.4g} mm"
        )
    return (
        f"{race} race: contact too large for Hertz theory {_where(ds, wraps | too_wide)}: "
        + "; ".join(reasons)
        + ". The contact would wrap past the groove or be wider than the ball, so this result is "
        "not physical; reduce the load (or choose a larger bearing)."
    )


def _settling_check(ds) -> list[str]:
    """'run too short to settle' for a dynamic result whose analysed window does not start at a
    settling time (see solver.results.summary)."""
    if "settled" in ds:
        if int(ds["settled"]) == 1:
            return []
    elif not (
        {"spin_to_roll", "contact_angle", "contact_load"} <= set(ds.data_vars)
        and {"inner_ring_speed", "outer_ring_speed"} <= set(ds.coords)
    ):
        return []  # neither stored nor computable: nothing to say
    state = summary.settling(ds)
    if state.settled:
        return []
    if "analysis_start_time" in ds:
        start = float(ds["analysis_start_time"])
    else:
        first, _ = summary.analysis_start(ds)
        start = float(ds["time"].values[first])
    return [summary.unsettled_message(ds, state, start)]


def _skidding_check(ds) -> list[str]:
    """'the cage skids' for a dynamic result whose mean instantaneous cage slip over the analysed
    window, or over a phase of its history, exceeds the threshold (solver.results.skidding)."""
    from . import metrics, phases, skidding

    if not {"cage_speed", "contact_angle", "contact_load"} <= set(ds.data_vars):
        return []
    threshold = skidding.CAGE_SKID_THRESHOLD
    by_phase = phases.PHASE_BOUNDARIES_ATTRIBUTE in ds.attrs
    slip = metrics.compute_metric(metrics.Window(ds, by_phase), "mean_instantaneous_cage_slip")
    if not by_phase:
        slip = slip.expand_dims(phase=[0]).assign_coords(phase_label=("phase", [_window_words(ds)]))
    masks = phases.phase_mask(ds).values
    found = []
    for k in range(slip.sizes["phase"]):
        value = float(slip.values[k])
        if value > threshold:
            label = str(slip["phase_label"].values[k])
            where = f"the phase {label}" if by_phase else label
            extent = skidding.skid_extent(ds, masks[k] if k < len(masks) else None)
            found.append(
                f"the cage skids: over {where} it turns on average {100.0 * value:.3g} % slower "
                f"than its rolling speed (mean instantaneous_cage_slip, threshold "
                f"{100.0 * threshold:.3g} %){_skid_extent_words(extent)}: the balls slide over "
                "the raceways instead of "
                "rolling, which smears and wears them and heats the contacts. A light load at "
                "high speed or a fast start-up causes it; more preload (operating.axial_load_N) "
                "or a slower ramp holds the balls to rolling."
            )
    return found


def _skid_extent_words(extent) -> str:
    """When and how much the cage lagged (solver.results.skidding.skid_extent), in words: "; it
    lags most, 6.1 % (skidding_ratio 0.939), at t = 0.045 s, and by more than 1 % from t = 0.012 s
    to 0.051 s (80 % of the samples at more than a tenth of the run's top rolling speed)"; ""
    when nothing is known."""
    from .skidding import CAGE_SKID_THRESHOLD

    if extent is None:
        return ""
    words = (
        f"; it lags most, {100.0 * extent.peak:.3g} % (skidding_ratio "
        f"{1.0 - extent.peak:.3g}), at t = {extent.peak_time:.4g} s"
    )
    if extent.start is not None:
        words += (
            f", and by more than {100.0 * CAGE_SKID_THRESHOLD:.3g} % from t = "
            f"{extent.start:.4g} s to {extent.end:.4g} s ({100.0 * extent.share:.3g} % of the "
            "samples at more than a tenth of the run's top rolling speed)"
        )
    return words


def _window_words(ds) -> str:
    """The analysed window of a dynamic result in words (time span)."""
    start = float(ds["analysis_start_time"]) if "analysis_start_time" in ds else None
    if start is None:
        first, _ = summary.analysis_start(ds)
        start = float(ds["time"].values[first])
    end = float(ds["time"].values[-1])
    return f"the analysed window (t from {start:.4g} s to {end:.4g} s)"


def _energy_check(ds) -> list[str]:
    """'the energy balance does not close' for a dynamic result whose residual over the analysed
    window exceeds :data:`~solver.results.energy.RESIDUAL_LIMIT` (see solver.results.energy)."""
    if not all(name in ds for name in energy.BALANCE_VARIABLES):
        return []  # a result without the balance's variables: nothing to check
    if "analysis_start_time" in ds:
        start = float(ds["analysis_start_time"])
    elif {"contact_angle", "contact_load"} <= set(ds.data_vars):
        first, _ = summary.analysis_start(ds)
        start = float(ds["time"].values[first])
    else:
        return []
    balance = energy.energy_balance(ds, start)
    if balance is None or not abs(balance.residual) > energy.RESIDUAL_LIMIT:
        return []
    note = str(ds.attrs.get("integrator", ""))
    return [energy.residual_message(balance, note)]


def _incomplete_message(ds) -> str:
    """A dynamic run that stopped before its planned end."""
    times = np.asarray(ds["time"].values, dtype=float)
    end = float(times[-1]) if times.size else 0.0
    period = ds.attrs.get("shaft_period_s")
    revolutions = f" ({end / float(period):.3g} shaft revolutions)" if period else ""
    reason = str(ds.attrs.get("stop_reason", "") or "").strip()
    why = f"; reason: {reason}" if reason and reason != "finished" else ""
    return (
        f"the dynamic run stopped early (complete = 0) at t = {end:.4g} s{revolutions}{why}. "
        "The data up to the stop are kept, but the trajectory band widths and any time average "
        "cover only that part; run it again to the end for the full result."
    )


__all__ = ["result_warnings", "STATIC_PRESSURE_LIMIT"]
