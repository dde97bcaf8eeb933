"""The metrics a study keeps per point and model: read from a results Dataset.

The trajectory metrics come from ``ds.racetrace.summary()`` (solver.results.summary), each race
in its own ring's frame (the headline values). Beside them, over the same analysed window (the
whole snapshot for a quasi-static result; from ``analysis_start_time`` on for a dynamic one):

- ``peak_pressure`` [Pa], per race: the largest Hertz peak pressure of any loaded contact;
- ``largest_load`` [N], per race: the largest ball-race contact load;
- ``cage_slip`` [1]: 1 - (mean cage speed) / (epicyclic cage speed), the epicyclic (no-slip)
  speed being ((1 - g) w_i + (1 + g) w_o) / 2 with g = D cos(alpha_0) / d_m (free contact angle);
  positive when the cage lags. A quasi-static cage speed is the mean orbital speed of the balls.

:data:`POINT_METRICS` is the one table of their names, dimensions, units and descriptions.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from solver.results.dataset import ring_speeds
from solver.results.summary import RACES, headline

#: name -> (dims beyond point/model, units, long name, description)
POINT_METRICS: dict[str, tuple[tuple[str, ...], str, str, str]] = {
    "excursion": (
        ("race",),
        "degree",
        "trajectory excursion",
        "trajectory_excursion of the race in its own ring's frame (results-schema.md)",
    ),
    "excursion_arc": (
        ("race",),
        "m",
        "trajectory excursion (arc)",
        "trajectory_excursion_arc of the race in its own ring's frame",
    ),
    "band_thickness": (
        ("race",),
        "degree",
        "trajectory band thickness",
        "trajectory_band_thickness of the race in its own ring's frame (NaN: quasi-static)",
    ),
    "band_thickness_arc": (
        ("race",),
        "m",
        "trajectory band thickness (arc)",
        "trajectory_band_thickness_arc of the race in its own ring's frame",
    ),
    "band_width": (
        ("race",),
        "degree",
        "trajectory band width",
        "trajectory_band_width: max - min contact angle over the analysed window",
    ),
    "mean_contact_angle": (
        ("race",),
        "degree",
        "mean contact angle",
        "mean contact angle of the loaded contacts in the analysed window",
    ),
    "peak_pressure": (
        ("race",),
        "Pa",
        "peak contact pressure",
        "largest Hertz peak pressure of a loaded contact in the analysed window",
    ),
    "largest_load": (
        ("race",),
        "N",
        "largest contact load",
        "largest ball-race contact load in the analysed window",
    ),
    "cage_slip": (
        (),
        "1",
        "cage slip",
        "1 - mean cage speed / epicyclic cage speed (free contact angle); > 0: the cage lags",
    ),
    "settling_time": (
        (),
        "s",
        "settling time",
        "settling_time of the dynamic run (NaN: not settled, or quasi-static)",
    ),
    "settled": ((), "1", "run settled", "1 settled, 0 not settled, NaN quasi-static"),
}


def _window(ds: xr.Dataset, start: float) -> xr.Dataset:
    if "time" not in ds.dims:
        return ds
    return ds.sel(time=slice(start, None))


def point_metrics(ds: xr.Dataset) -> dict[str, object]:
    """The :data:`POINT_METRICS` of one result: ``{name: float or {race: float}}``."""
    summary = ds.racetrace.summary()
    head = headline(summary)
    start = head.get("analysis_start_time_s", 0.0)
    win = _window(ds, start)
    out: dict[str, object] = {}
    for name, key in (
        ("excursion", "excursion_deg"),
        ("excursion_arc", "excursion_m"),
        ("band_thickness", "band_thickness_deg"),
        ("band_thickness_arc", "band_thickness_m"),
        ("band_width", "band_width_deg"),
    ):
        out[name] = {race: head[race][key] for race in RACES}
    out["mean_contact_angle"], out["peak_pressure"], out["largest_load"] = {}, {}, {}
    for race in RACES:
        load = np.asarray(win["contact_load"].sel(race=race).values, dtype=float)
        loaded = load > 0.0
        angle = np.asarray(win["contact_angle"].sel(race=race).values, dtype=float)
        pressure = np.asarray(win["max_pressure"].sel(race=race).values, dtype=float)
        any_loaded = bool(loaded.any())
        out["mean_contact_angle"][race] = float(angle[loaded].mean()) if any_loaded else math.nan
        out["peak_pressure"][race] = float(np.nanmax(pressure[loaded])) if any_loaded else 0.0
        out["largest_load"][race] = float(np.nanmax(load)) if load.size else math.nan
    inner, outer = ring_speeds(ds)
    diameter = float(ds.coords["ball_diameter"])
    pitch = float(ds.coords["pitch_diameter"])
    alpha = math.radians(float(ds.coords["free_contact_angle"]))
    gamma = diameter * math.cos(alpha) / pitch
    epicyclic = 0.5 * ((1.0 - gamma) * inner + (1.0 + gamma) * outer)
    cage = float(np.nanmean(np.asarray(win["cage_speed"].values, dtype=float)))
    out["cage_slip"] = 1.0 - cage / epicyclic if epicyclic != 0.0 else math.nan
    out["settling_time"] = head.get("settling_time_s", math.nan)
    out["settled"] = float(head["settled"]) if "settled" in head else math.nan
    return out
