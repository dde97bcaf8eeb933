"""The trajectory metrics of a result as text and as JSON, for the commands that print them.

The numbers come from ``ds.racetrace.summary()`` (defined in :mod:`solver.results.summary`); each
race is reported in its own ring's frame, the headline value.
"""

from __future__ import annotations

import math

import solver  # noqa: F401  (registers the ds.racetrace accessor)
from solver.results.dataset import ring_speeds
from solver.results.summary import QUASISTATIC_THICKNESS_NOTE, headline


def _finite_or_none(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def metrics_json(ds) -> dict:
    """JSON-ready metrics (SI units, angles in degree; NaN written as null)."""
    metrics = ds.racetrace.summary()
    values = headline(metrics)
    out = {
        "frame": "each race in its own ring's frame",
        "units": {"angle": "degree", "length": "m", "time": "s"},
    }
    for race in ("inner", "outer"):
        out[race] = {key: _finite_or_none(v) for key, v in values[race].items()}
    if "settled" in values:
        out["settled"] = values["settled"]
        out["settling_time_s"] = _finite_or_none(values["settling_time_s"])
        out["analysis_start_time_s"] = values["analysis_start_time_s"]
        out["analysed_window"] = metrics.attrs.get("analysed_window", "")
    else:
        out["band_thickness_note"] = QUASISTATIC_THICKNESS_NOTE
    return out


def metrics_text(ds) -> str:
    """Readable lines: excursion and band thickness per race (degree and um), the mean ellipse
    semi-major axis for scale, and where the analysed window starts (dynamic results)."""
    metrics = ds.racetrace.summary()
    values = headline(metrics)
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
    if "settled" in values:
        inner, outer = ring_speeds(ds)
        period = 2.0 * math.pi / abs(inner - outer)
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
    return "\n".join(lines)


__all__ = ["metrics_json", "metrics_text"]
