"""The trajectory metrics and rating lives of a result as text and as JSON, for the commands that
print them.

The numbers are metrics of the metrics table, asked for by name (``ds.racetrace.metric``,
solver.results.metrics); each race is reported in its own ring's frame, the headline value. Here
they are only converted to the units printed.
"""

from __future__ import annotations

import math

import solver  # noqa: F401  (registers the ds.racetrace accessor)

HOUR = 3600.0  # s
#: (key printed per race, metric): each race's trajectory numbers, SI units and degree.
RACE_METRICS = (
    ("excursion_deg", "excursion"),
    ("excursion_m", "excursion_arc"),
    ("band_thickness_deg", "band_thickness"),
    ("band_thickness_m", "band_thickness_arc"),
    ("ellipse_semi_major_mean_m", "mean_semi_major"),
    ("band_width_deg", "band_width"),
)
#: (key printed, metric, divisor): the rating lives (million revolutions, hours) and C_r, P_r.
LIFE_VALUES = (
    ("L10_million_revolutions", "basic_rating_life", 1e6),
    ("L10_hours", "basic_rating_life_time", HOUR),
    ("L10r_million_revolutions", "reference_rating_life", 1e6),
    ("L10r_hours", "reference_rating_life_time", HOUR),
    ("basic_load_rating_N", "basic_load_rating", 1.0),
    ("equivalent_load_N", "equivalent_load", 1.0),
)


def finite_or_none(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def headline(ds) -> dict:
    """Each race's trajectory numbers in its own ring's frame (:data:`RACE_METRICS`, plain floats)
    plus ``settled`` / ``settling_time_s`` / ``analysis_start_time_s`` /
    ``energy_balance_residual`` for a dynamic result."""
    metric = ds.racetrace.metric
    out = {
        race: {key: float(metric(name).sel(race=race)) for key, name in RACE_METRICS}
        for race in ("inner", "outer")
    }
    if "time" in ds.dims:
        out["settled"] = bool(int(metric("settled")))
        out["settling_time_s"] = float(metric("settling_time"))
        out["analysis_start_time_s"] = float(metric("analysis_start_time"))
        out["energy_balance_residual"] = float(metric("energy_balance_residual"))
    return out


def life_headline(ds) -> dict:
    """The rating lives as plain floats (:data:`LIFE_VALUES`: NaN where not available, inf for an
    unloaded or non-rotating bearing) and ``notes`` (the metrics' notes, without repeats)."""
    out, notes = {}, []
    for key, name, divisor in LIFE_VALUES:
        value = ds.racetrace.metric(name)
        out[key] = float(value) / divisor
        note = value.attrs.get("note")
        if note and note not in notes:
            notes.append(note)
    out["notes"] = notes
    return out


def metrics_json(ds) -> dict:
    """JSON-ready metrics (SI units, angles in degree; NaN written as null)."""
    values = headline(ds)
    out = {
        "frame": "each race in its own ring's frame",
        "units": {"angle": "degree", "length": "m", "time": "s"},
    }
    for race in ("inner", "outer"):
        out[race] = {key: finite_or_none(v) for key, v in values[race].items()}
    if "settled" in values:
        out["settled"] = values["settled"]
        out["settling_time_s"] = finite_or_none(values["settling_time_s"])
        out["analysis_start_time_s"] = values["analysis_start_time_s"]
        out["analysed_window"] = ds.racetrace.summary().attrs.get("analysed_window", "")
        out["energy_balance_residual"] = finite_or_none(values["energy_balance_residual"])
    else:
        note = ds.racetrace.metric("band_thickness").attrs.get("note")
        if note:  # a snapshot; a solution over one revolution has band thicknesses
            out["band_thickness_note"] = note
        else:
            out["analysed_window"] = ds.racetrace.summary().attrs.get("analysed_window", "")
    return out


def metrics_text(ds) -> str:
    """Readable lines: excursion and band thickness per race (degree and um), the mean ellipse
    semi-major axis for scale, and where the analysed window starts and the energy-balance
    residual over it (dynamic results)."""
    values = headline(ds)
    lines = ["trajectory metrics (each race in its own ring's frame):"]
    for race in ("inner", "outer"):
        v = values[race]
        if math.isfinite(v["band_thickness_deg"]):
            thickness = (
                f"band thickness {v['band_thickness_deg']:.4f} deg "
                f"({v['band_thickness_m'] * 1e6:.2f} um)"
            )
        elif "settled" in values:
            thickness = (
                "band thickness n/a (fewer than 5 samples in every 10-degree azimuth bin: run "
                "longer or with more samples per revolution)"
            )
        else:
            thickness = "band thickness n/a (one snapshot: needs a dynamic run)"
        lines.append(
            f"  {race} race: excursion {v['excursion_deg']:.4f} deg "
            f"({v['excursion_m'] * 1e6:.2f} um), {thickness}; contact ellipse semi-major axis "
            f"{v['ellipse_semi_major_mean_m'] * 1e6:.1f} um (mean)"
        )
    if "time" not in ds.dims:  # over one revolution, or steady running from one solution
        window = ds.racetrace.summary()["trajectory_excursion"].attrs.get("analysed_window", "")
        if window and "snapshot" not in window:
            lines.append(f"analysed: {window}")
    if "settled" in values:
        period = float(ds.racetrace.metric("shaft_period"))
        start = values["analysis_start_time_s"]
        if values["settled"]:
            settled = values["settling_time_s"]
            lines.append(
                f"settling: settled at t = {settled:.4g} s ({settled / period:.3g} shaft "
                f"revolutions); metrics from t = {start:.4g} s to the end"
            )
        else:
            lines.append(
                f"settling: NOT settled (see the warning); metrics from t = {start:.4g} s "
                f"({start / period:.3g} shaft revolutions) to the end"
            )
        lines.append(energy_text(values["energy_balance_residual"]))
    return "\n".join(lines)


def energy_text(residual: float) -> str:
    """The energy-balance line of a dynamic result (``residual``: the metric, a fraction)."""
    if not math.isfinite(residual):
        return "energy balance: n/a (no losses in the analysed window)"
    return (
        f"energy balance: residual {100.0 * residual:+.2f} % of the losses over the analysed "
        "window (drive power - losses + work of the loads - change of kinetic and elastic energy)"
    )


def life_json(ds) -> dict:
    """JSON-ready rating lives: L10 (ISO 281) and L10r (ISO/TS 16281) in million revolutions and
    hours, C_r and P_r in N; a life that is not finite is null, with the reason in ``notes``."""
    values = life_headline(ds)
    notes = list(values.pop("notes"))
    if any(math.isinf(v) for v in values.values()):
        notes.append(
            "an infinite life (no loaded contact, or rings not turning relative to each other) "
            "is written as null"
        )
    out = {key: finite_or_none(v) for key, v in values.items()}
    out["reliability_percent"] = 90
    out["notes"] = notes
    return out


def _life_value(million_revolutions: float, hours: float) -> str:
    if math.isnan(million_revolutions):
        return "n/a"
    if math.isinf(million_revolutions):
        return "infinite (no loaded contact)"
    revolutions = _number(million_revolutions)
    if math.isinf(hours):
        return f"{revolutions} million revolutions (rings not turning: no hours)"
    return f"{revolutions} million revolutions = {_number(hours)} h"


def _number(value: float) -> str:
    """Whole numbers from 100 up, three significant digits below."""
    return f"{value:.0f}" if abs(value) >= 100.0 else f"{value:.3g}"


def life_text(ds) -> str:
    """Readable lines: L10 (ISO 281, applied loads) and L10r (ISO/TS 16281, computed contact
    loads) in million revolutions and hours, with C_r, P_r and the notes."""
    values = life_headline(ds)
    window = " over the analysed window" if "time" in ds.dims else ""
    rating = (
        f" (C_r {values['basic_load_rating_N']:.0f} N, P_r {values['equivalent_load_N']:.0f} N)"
        if math.isfinite(values["basic_load_rating_N"])
        else ""
    )
    lines = [
        "rating life (90 % reliability, no life modification factor):",
        "  L10  (ISO 281, applied loads):       "
        + _life_value(values["L10_million_revolutions"], values["L10_hours"])
        + rating,
        "  L10r (ISO/TS 16281, contact loads): "
        + _life_value(values["L10r_million_revolutions"], values["L10r_hours"])
        + window,
    ]
    lines += [f"  note: {note}" for note in values["notes"]]
    return "\n".join(lines)


#: (key printed, metric, label): the model's friction torque and the empirical estimates.
TORQUE_VALUES = (
    ("model_N_m", "mean_friction_torque", "model (mean over the analysed window)"),
    ("palmgren_N_m", "friction_torque_palmgren", "Palmgren M0 + M1"),
    ("skf_N_m", "friction_torque_skf", "SKF friction model"),
)


def torque_json(ds) -> dict:
    """JSON-ready friction torques (N m): the model's mean (dynamic results) and the empirical
    estimates; one not available is null, with the reason in ``notes``."""
    out: dict = {}
    notes = {}
    for key, name, _label in TORQUE_VALUES:
        value = ds.racetrace.metric(name)
        out[key] = finite_or_none(float(value))
        if out[key] is None and value.attrs.get("note"):
            notes[key] = value.attrs["note"]
    out["notes"] = notes
    return out


def torque_text(ds) -> str:
    """Readable lines: the model's mean friction torque (dynamic results) beside the Palmgren and
    SKF estimates, in N mm; an estimate not available says why."""
    lines = ["friction torque:"]
    for key, name, label in TORQUE_VALUES:
        value = ds.racetrace.metric(name)
        number = float(value)
        if key == "model_N_m" and "time" not in ds.dims:
            continue  # a quasi-static result has no friction torque of its own
        if math.isfinite(number):
            text = f"{number * 1e3:.4g} N mm"
            if key != "model_N_m" and value.attrs.get("note"):
                text += f" ({value.attrs['note']})"
        else:
            text = value.attrs.get("note") or "not available"
        lines.append(f"  {label}: {text}")
    return "\n".join(lines)


__all__ = ["life_json", "life_text", "metrics_json", "metrics_text", "torque_json", "torque_text"]
