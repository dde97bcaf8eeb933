"""The metrics table: every number the views quote about a result, each declared once.

:data:`METRICS` holds one :class:`Metric` per metric — name, dimensions, units (UDUNITS), long name,
a one-line meaning and the function that computes it from a result. The accessor serves them:
``ds.racetrace.metrics()`` (a Dataset of every metric, with units) and ``ds.racetrace.metric(name)``
(one DataArray); it computes each one once per Dataset. The CLI, the app's charts and comparison
table, the lessons, the study runner and the report ask for metrics by name and only convert units
for display. docs/results-schema.md ("Metrics") lists the table; a test keeps the two in step.

**Loaded contact.** One definition, :func:`solver.results.loaded.loaded` (re-exported here): a
ball-race contact whose ``contact_load`` is > 0 N and whose ``contact_angle`` is finite. Every
statistic over contacts reads it.

**Analysed window.** A quasi-static result is one solution: every ball once (its trajectory
metrics those of steady running, :mod:`solver.results.steady_track`); or, for a
misalignment turning with the inner ring (:func:`solver.quasistatic_answer`), its solutions over
one revolution: every ball at every ``ring_angle``. A dynamic result is read from its
``analysis_start_time`` to the end (the settled part of the run, :mod:`solver.results.summary`).
:class:`Window` holds the result, the window's time mask and what several metrics share (the
summary metrics), each computed once.

**Dimensions.** A metric's ``dims`` are those it keeps of one bearing's result (``race`` for a
per-race metric, ``()`` for the bearing as a whole). The functions reduce over the contact
dimensions ``ball``, ``time`` and ``ring_angle`` (the samples of one result: a quasi-static
solution over one revolution is one answer, its metrics span the revolution) and keep every other
dimension of the result: a stack of results (``xr.concat`` along a sweep), a set of
bearings (``bearing``) or a window per phase of time-varying operation (a ``phase`` dimension of
the time mask) each give one value per element. Statistics take the contacts in the Dataset's own
order (ball by ball, in time within a ball), so a mean is the sum numpy forms over the flattened
selection.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import xarray as xr

from . import energy, skidding
from . import phases as phases_module
from . import summary as summary_module
from .loaded import loaded, loaded_mask
from .variables import variable

#: Dimensions a statistic over contacts reduces (every other dimension is kept): the balls, the
#: time of a dynamic run and the ring angles of a quasi-static solution over one revolution.
CONTACT_DIMS = ("ball", "time", "ring_angle")
RACES = ("inner", "outer")
#: The ring frame in which each race's trajectory metrics are quoted: its own ring's.
OWN_FRAME = {"inner": "inner_ring", "outer": "outer_ring"}
#: Dimensions of one bearing's result; any other dimension stacks results (sweep, bearing, phase).
RESULT_DIMS = frozenset(
    {"ball", "race", "time", "ring_angle", "axis", "tilt_axis", "quaternion", "body", "frame"}
)


@dataclass(frozen=True)
class Metric:
    """One row of the metrics table. ``compute`` takes a :class:`Window` and returns a DataArray
    with the metric's ``dims`` plus any stacking dimension of the result (bearing, sweep, phase)."""

    name: str
    dims: tuple[str, ...]
    units: str
    long_name: str
    meaning: str
    compute: Callable[[Window], xr.DataArray]

    def attrs(self) -> dict[str, str]:
        """NetCDF attributes: units, long_name, description (the meaning)."""
        return {"units": self.units, "long_name": self.long_name, "description": self.meaning}


# ---- the analysed window -------------------------------------------------------------------------
class Window:
    """A result and its analysed window; what several metrics share is computed once.

    ``by_phase``: the windows are the phases of the result (:mod:`solver.results.phases`: one
    per part of its history between events; a steady result's one phase is its analysed window),
    so that every metric gains a ``phase`` dimension with the phases' coordinates. A quasi-static
    result has no phases: ``by_phase`` changes nothing there."""

    def __init__(self, ds: xr.Dataset, by_phase: bool = False):
        self.ds = ds
        self.by_phase = by_phase and "time" in ds.dims

    @property
    def dynamic(self) -> bool:
        return "time" in self.ds.dims

    @cached_property
    def summary(self) -> xr.Dataset:
        """The summary metrics (:func:`solver.results.summary.summary`: stored or computed), per
        phase when the window is by phase (:func:`solver.results.summary.phase_summary`)."""
        if self.by_phase:
            return summary_module.phase_summary(self.ds)
        return summary_module.summary(self.ds)

    @cached_property
    def in_window(self) -> xr.DataArray | None:
        """Time samples in the analysed window (``time`` >= ``analysis_start_time``, with any
        stacking dimension of the start time), or in each phase (dims ``phase``, ``time``); None
        for a quasi-static result (every sample)."""
        if not self.dynamic:
            return None
        if self.by_phase:
            return phases_module.phase_mask(self.ds)
        return self.ds["time"] >= self.summary["analysis_start_time"]

    @cached_property
    def loaded(self) -> xr.DataArray:
        """Loaded contacts (:func:`loaded`) in the analysed window."""
        return self.within(loaded(self.ds))

    def within(self, mask: xr.DataArray) -> xr.DataArray:
        """``mask`` restricted to the analysed window."""
        return mask if self.in_window is None else mask & self.in_window

    def samples(self, name: str) -> xr.DataArray:
        """Every sample of variable ``name`` in the analysed window (a mask, True for all of a
        quasi-static result)."""
        return self.within(xr.ones_like(self.ds[name], dtype=bool))


# ---- reductions over contacts --------------------------------------------------------------------
def reduce(values: xr.DataArray, mask: xr.DataArray, how: str, empty: float = math.nan):
    """``how`` ("mean", "min", "max", "median") of the finite ``values`` where ``mask`` holds, over
    the :data:`CONTACT_DIMS` they have; every other dimension is kept. ``empty`` where nothing is
    selected. Elements are taken in the order of ``values``' dimensions."""
    over = [d for d in values.dims if d in CONTACT_DIMS]
    values, mask = xr.broadcast(values, mask)
    keep = [d for d in values.dims if d not in over]
    # the coordinates of the mask's own dimensions (a phase's start, end and label) go along
    values = values.assign_coords(
        {
            n: c
            for n, c in mask.coords.items()
            if n not in values.coords and set(c.dims) <= set(keep)
        }
    )
    values = values.transpose(*keep, *over)
    mask = mask.transpose(*keep, *over)
    size = int(np.prod([values.sizes[d] for d in over], dtype=int))
    flat = np.asarray(values.values, dtype=float).reshape(-1, size)
    chosen = np.asarray(mask.values, dtype=bool).reshape(-1, size) & np.isfinite(flat)
    out = np.full(flat.shape[0], empty, dtype=float)
    function = getattr(np, how)
    for row in range(flat.shape[0]):
        picked = flat[row][chosen[row]]
        if picked.size:
            out[row] = function(picked)
    return _kept(out.reshape([values.sizes[d] for d in keep]), values, keep)


def _kept(data: np.ndarray, like: xr.DataArray, dims) -> xr.DataArray:
    """``data`` with the kept ``dims`` and the coordinates of ``like`` along them."""
    coords = {name: c for name, c in like.coords.items() if set(c.dims) <= set(dims)}
    return _plain(xr.DataArray(data, dims=tuple(dims), coords=coords))


def _plain(value: xr.DataArray) -> xr.DataArray:
    """``value`` with its dimension coordinates (race, a stacking dimension) and the coordinates
    along stacking dimensions only (e.g. the speed of each element of a sweep): the describing
    coordinates of one result (speeds, loads, groove radii) stay with the result."""
    drop = [
        name
        for name, coord in value.coords.items()
        if name not in value.dims and (not coord.dims or set(coord.dims) & RESULT_DIMS)
    ]
    return value.drop_vars(drop)


def _contact(w: Window, name: str, how: str, empty: float = math.nan) -> xr.DataArray:
    """A statistic of per-contact variable ``name`` over the loaded contacts in the window (NaN
    throughout when the result lacks the variable)."""
    if name not in w.ds:  # the shape of the statistic, all NaN
        return xr.full_like(reduce(w.ds["contact_load"], w.loaded, "max"), math.nan)
    return reduce(w.ds[name], w.loaded, how, empty)


def _every_contact(w: Window, name: str, how: str) -> xr.DataArray:
    """A statistic of ``name`` over every contact in the window, loaded or not."""
    return reduce(w.ds[name], w.samples(name), how)


def _scalar_coordinate(ds: xr.Dataset, name: str) -> xr.DataArray:
    """A describing coordinate as a DataArray without the other coordinates (scalar, or with the
    stacking dimensions of a stacked result). An operating input that varies in time (a data
    variable over ``time``: a result along a history) is taken as its mean over the analysed
    window (from ``analysis_start_time`` on; the whole run for a result without it)."""
    if name not in ds.coords and name in ds.data_vars and "time" in ds[name].dims:
        da = ds[name]
        if "analysis_start_time" in ds:
            da = da.where(ds["time"] >= ds["analysis_start_time"])
        da = da.mean("time")
        return da.drop_vars([c for c in da.coords if c not in da.dims])
    da = ds.coords[name]
    return da.drop_vars([c for c in da.coords if c not in da.dims])


def _elementwise(function, da: xr.DataArray) -> xr.DataArray:
    """``function`` (a ``math`` function of one float) on every element: the same rounding as the
    scalar code it replaces."""
    return xr.apply_ufunc(np.vectorize(function, otypes=[float]), da)


# ---- the metrics' functions ----------------------------------------------------------------------
def _own_frame(name: str) -> Callable[[Window], xr.DataArray]:
    """Summary metric ``name`` (race, frame) of each race in its own ring's frame (with its
    ``note`` attribute, if any)."""

    def compute(w: Window) -> xr.DataArray:
        frames = xr.DataArray(
            [OWN_FRAME[r] for r in RACES], dims="race", coords={"race": list(RACES)}
        )
        da = w.summary[name]
        return _with_note(da.sel(frame=frames), da)

    return compute


def _with_note(value: xr.DataArray, source: xr.DataArray) -> xr.DataArray:
    """``value`` without the result's coordinates, keeping the ``note`` attribute of ``source``."""
    out = value.drop_vars([c for c in value.coords if c not in value.dims])
    note = source.attrs.get("note")
    out.attrs = {"note": note} if note else {}
    return out


def _summary_value(name: str) -> Callable[[Window], xr.DataArray]:
    """Summary metric ``name`` as stored or computed (NaN for a result without it: the settling
    of a quasi-static snapshot)."""

    def compute(w: Window) -> xr.DataArray:
        if name not in w.summary:
            return xr.DataArray(math.nan)
        return _with_note(w.summary[name], w.summary[name])

    return compute


def epicyclic_cage_speed(ds: xr.Dataset) -> xr.DataArray:
    """Cage speed of pure rolling at the free contact angle alpha_0 (rad/s):
    ((1 - gamma) omega_i + (1 + gamma) omega_o) / 2 with gamma = D cos(alpha_0) / d_m."""
    alpha = _elementwise(math.radians, _scalar_coordinate(ds, "free_contact_angle"))
    gamma = (
        _scalar_coordinate(ds, "ball_diameter")
        * _elementwise(math.cos, alpha)
        / _scalar_coordinate(ds, "pitch_diameter")
    )
    inner = _scalar_coordinate(ds, "inner_ring_speed")
    outer = _scalar_coordinate(ds, "outer_ring_speed")
    return 0.5 * ((1.0 - gamma) * inner + (1.0 + gamma) * outer)


def _mean_variable(w: Window, name: str) -> xr.DataArray:
    """Mean of the finite samples of a per-ball or bearing variable in the window (NaN when the
    result lacks it)."""
    if name not in w.ds:
        return xr.DataArray(math.nan)
    return reduce(w.ds[name], w.samples(name), "mean")


def _mean_cage_speed(w: Window) -> xr.DataArray:
    return _mean_variable(w, "cage_speed")


def _cage_slip(w: Window) -> xr.DataArray:
    cage = _mean_cage_speed(w)
    epicyclic = epicyclic_cage_speed(w.ds)
    with np.errstate(divide="ignore", invalid="ignore"):
        slip = 1.0 - cage / epicyclic
    return slip.where(epicyclic != 0.0)


def _instantaneous_cage_slip(w: Window) -> xr.DataArray:
    """The instantaneous cage slip (solver.results.skidding) over the window, weighted by the
    rolling cage speed: 1 - mean cage speed / mean rolling cage speed over the samples that have a
    rolling speed, so that samples near rest (a ratio of two small numbers) weigh little (NaN:
    quasi-static, or no such sample)."""
    if not w.dynamic or "cage_speed" not in w.ds:
        return xr.DataArray(math.nan)
    rolling = skidding.rolling_cage_speed(w.ds)
    cage = w.ds["cage_speed"].drop_vars([c for c in w.ds["cage_speed"].coords if c != "time"])
    has = np.isfinite(rolling) & (rolling != 0.0) & np.isfinite(cage)
    mask = w.within(has)
    mean_rolling = reduce(rolling, mask, "mean")
    with np.errstate(divide="ignore", invalid="ignore"):
        slip = 1.0 - reduce(cage, mask, "mean") / mean_rolling
    return slip.where(mean_rolling != 0.0)


def _cage_skids(w: Window) -> xr.DataArray:
    """1 where the mean instantaneous cage slip exceeds the skidding threshold, 0 where it does
    not, NaN where it is not known (quasi-static, no rolling speed)."""
    slip = _instantaneous_cage_slip(w)
    return xr.where(slip > skidding.CAGE_SKID_THRESHOLD, 1.0, 0.0).where(np.isfinite(slip))


def _centrifugal_force(w: Window) -> xr.DataArray:
    """The quasi-static result's own mean centrifugal force, else m (d_m / 2) omega^2 with the
    ball's mass from its density and diameter and the mean orbital speed in the window."""
    if "centrifugal_force" in w.ds:
        return _mean_variable(w, "centrifugal_force")
    if "orbital_speed" not in w.ds:
        return xr.DataArray(math.nan)
    density = _scalar_coordinate(w.ds, "density").sel(body="ball", drop=True)
    diameter = _scalar_coordinate(w.ds, "ball_diameter")
    mass = density * math.pi * diameter**3 / 6.0
    orbital = _mean_variable(w, "orbital_speed")
    return mass * 0.5 * _scalar_coordinate(w.ds, "pitch_diameter") * orbital**2


def _energy_balance_residual(w: Window) -> xr.DataArray:
    """The stored ``energy_balance_residual``, else computed over the analysed window when the
    result has the variables of the balance; NaN otherwise (a quasi-static result)."""
    if "energy_balance_residual" in w.ds:
        value = w.ds["energy_balance_residual"]
        return value.drop_vars([c for c in value.coords if c not in value.dims])
    if not w.dynamic:
        return xr.DataArray(math.nan)
    source = w.ds if "analysis_start_time" in w.ds else summary_module.summary(w.ds)
    balance = energy.energy_balance(w.ds, float(source["analysis_start_time"]))
    return xr.DataArray(math.nan if balance is None else balance.residual)


def _race_heat(w: Window) -> xr.DataArray:
    """Heat generated in the contacts of each race (summed over the balls), mean over the window
    (NaN per race when the result lacks ``contact_heat``: quasi-static)."""
    if "contact_heat" not in w.ds:
        return _contact(w, "contact_heat", "mean")
    heat = w.ds["contact_heat"].where(np.isfinite(w.ds["contact_heat"]), 0.0).sum("ball")
    return reduce(heat, w.within(xr.ones_like(heat, dtype=bool)), "mean")


def composite_roughness(ds: xr.Dataset) -> xr.DataArray:
    """sqrt(Rq_ball^2 + Rq_raceway^2) (m) of the bearing a result was solved for, from the
    roughness keys of its case (``attrs["case"]``, given or the schema defaults); NaN with a
    ``note`` saying why when the result holds no case that parses."""
    case = ds.racetrace.case()
    if case is None:
        return xr.DataArray(
            math.nan,
            attrs={
                "note": "no film parameter: the result holds no readable case, so the surface "
                "roughness of its balls and raceways is unknown"
            },
        )
    ball = case.bearing.ball_roughness_um * 1e-6
    raceway = case.bearing.raceway_roughness_um * 1e-6
    return xr.DataArray(math.hypot(ball, raceway))


def _film_parameter(w: Window) -> xr.DataArray:
    """Smallest film thickness over the composite roughness, per race."""
    roughness = composite_roughness(w.ds)
    return _with_note(_contact(w, "film_thickness", "min") / roughness, roughness)


def _ring_displacement(w: Window, axes: tuple[str, ...]) -> xr.DataArray:
    """Mean inner-ring displacement over the window along ``axes`` (its length when several)."""
    if "inner_ring_offset" not in w.ds:
        return xr.DataArray(math.nan)
    offset = w.ds["inner_ring_offset"].sel(axis=list(axes))
    mean = reduce(offset, w.samples("inner_ring_offset").sel(axis=list(axes)), "mean")
    return np.sqrt((mean**2).sum("axis")) if len(axes) > 1 else mean.sel(axis=axes[0], drop=True)


def _secant_stiffness(w: Window, load: str, axes: tuple[str, ...]) -> xr.DataArray:
    """Applied load over the mean ring displacement it causes (NaN without load or
    displacement)."""
    force = _scalar_coordinate(w.ds, load)
    displacement = _ring_displacement(w, axes)
    with np.errstate(divide="ignore", invalid="ignore"):
        stiffness = force / displacement
    return stiffness.where((force != 0.0) & (displacement > 0.0))


def _loaded_balls(w: Window) -> xr.DataArray:
    """Balls carrying load on each race: the count of a snapshot, the median count over the
    window's samples of a dynamic run (rounded to a whole ball)."""
    counts = w.loaded.sum("ball")
    samples = [d for d in ("time", "ring_angle") if d in counts.dims]
    if not samples:
        return counts.astype(float)
    window = w.in_window if w.in_window is not None else xr.ones_like(counts, dtype=bool)
    median = reduce(counts, window, "median")
    return _elementwise(lambda x: float(round(x)) if math.isfinite(x) else math.nan, median)


def _truncated_contacts(w: Window) -> xr.DataArray:
    """Ball-race contacts whose ellipse runs over the shoulder (truncation_margin < 0 at a loaded
    contact) at least once in the window."""
    if "truncation_margin" not in w.ds:
        return xr.DataArray(0.0)
    over = (w.ds["truncation_margin"] < 0.0) & w.loaded
    samples = [d for d in ("time", "ring_angle") if d in over.dims]
    if samples:
        over = over.any(samples)
    return over.sum(("ball", "race")).astype(float)


def _relative_speed(ds: xr.Dataset) -> xr.DataArray:
    """|omega_i - omega_o| (rad/s) from the coordinates."""
    inner = _scalar_coordinate(ds, "inner_ring_speed")
    return abs(inner - _scalar_coordinate(ds, "outer_ring_speed"))


def _shaft_period(w: Window) -> xr.DataArray:
    """One revolution of one ring relative to the other (s); inf when they do not turn."""
    with np.errstate(divide="ignore"):
        return 2.0 * math.pi / _relative_speed(w.ds)


def _shaft_revolutions(w: Window) -> xr.DataArray:
    """Revolutions of one ring relative to the other that a dynamic run covers (NaN: snapshot)."""
    if not w.dynamic:
        return xr.DataArray(math.nan)
    return float(w.ds["time"].values[-1]) * _relative_speed(w.ds) / (2.0 * math.pi)


def _estimate(name: str) -> Callable[[Window], xr.DataArray]:
    """A friction-torque estimate of the result (solver.results.estimates) with its ``note``;
    NaN with the reason as ``note`` when the result has none."""

    def compute(w: Window) -> xr.DataArray:
        if name in w.ds:
            return _with_note(w.ds[name], w.ds[name])
        reason = w.ds.attrs.get(f"{name}_note") or (
            "not available: this result was not given the estimates (only a single quasi-static "
            "solve and a dynamic run compute them)"
        )
        return xr.DataArray(math.nan, attrs={"note": reason})

    return compute


def _stored_row(name: str, meaning: str) -> Metric:
    """A row that is a summary variable of the results registry itself (its dims and units)."""
    spec = variable(name)
    return Metric(name, spec.dims, spec.units, spec.long_name, meaning, _summary_value(name))


def _table() -> dict[str, Metric]:
    per_race = ("race",)
    rows = [
        # ---- contacts, per race: loaded contacts in the analysed window ------------------------
        Metric(
            "mean_contact_angle",
            per_race,
            "degree",
            "mean contact angle",
            "mean contact angle of the loaded contacts",
            lambda w: _contact(w, "contact_angle", "mean"),
        ),
        Metric(
            "min_contact_angle",
            per_race,
            "degree",
            "smallest contact angle",
            "smallest contact angle of a loaded contact",
            lambda w: _contact(w, "contact_angle", "min"),
        ),
        Metric(
            "max_contact_angle",
            per_race,
            "degree",
            "largest contact angle",
            "largest contact angle of a loaded contact",
            lambda w: _contact(w, "contact_angle", "max"),
        ),
        Metric(
            "mean_load",
            per_race,
            "N",
            "mean contact load",
            "mean contact load of the loaded contacts",
            lambda w: _contact(w, "contact_load", "mean"),
        ),
        Metric(
            "largest_load",
            per_race,
            "N",
            "largest contact load",
            "largest ball-race contact load (0 when no contact is loaded)",
            lambda w: _every_contact(w, "contact_load", "max"),
        ),
        Metric(
            "smallest_load",
            per_race,
            "N",
            "smallest contact load",
            "smallest ball-race contact load (0 when a ball is unloaded)",
            lambda w: _every_contact(w, "contact_load", "min"),
        ),
        Metric(
            "peak_pressure",
            per_race,
            "Pa",
            "peak contact pressure",
            "largest Hertz peak pressure of a loaded contact (0 when none is loaded)",
            lambda w: _contact(w, "max_pressure", "max", empty=0.0),
        ),
        Metric(
            "mean_semi_major",
            per_race,
            "m",
            "mean contact ellipse semi-major axis",
            "mean ellipse semi-axis across the groove of the loaded contacts "
            "(ellipse_semi_major_mean)",
            _summary_value("ellipse_semi_major_mean"),
        ),
        Metric(
            "mean_semi_minor",
            per_race,
            "m",
            "mean contact ellipse semi-minor axis",
            "mean ellipse semi-axis along the rolling direction of the loaded contacts",
            lambda w: _contact(w, "ellipse_semi_minor", "mean"),
        ),
        Metric(
            "mean_spin_to_roll",
            per_race,
            "1",
            "mean spin-to-roll ratio",
            "mean spin-to-roll ratio of the loaded contacts (NaN when the result has none)",
            lambda w: _contact(w, "spin_to_roll", "mean"),
        ),
        Metric(
            "min_truncation_margin",
            per_race,
            "degree",
            "smallest truncation margin",
            "smallest margin between a loaded ellipse and the shoulder (< 0: over it)",
            lambda w: _contact(w, "truncation_margin", "min"),
        ),
        Metric(
            "loaded_balls",
            per_race,
            "1",
            "loaded balls",
            "balls carrying load on the race (a dynamic run or a solution over one revolution: "
            "median over the samples)",
            _loaded_balls,
        ),
        # ---- trajectory metrics, per race in its own ring's frame (solver.results.summary) -----
        Metric(
            "excursion",
            per_race,
            "degree",
            "trajectory excursion",
            "trajectory_excursion of the race in its own ring's frame",
            _own_frame("trajectory_excursion"),
        ),
        Metric(
            "excursion_arc",
            per_race,
            "m",
            "trajectory excursion (arc)",
            "trajectory_excursion_arc of the race in its own ring's frame",
            _own_frame("trajectory_excursion_arc"),
        ),
        Metric(
            "band_thickness",
            per_race,
            "degree",
            "trajectory band thickness",
            "trajectory_band_thickness of the race in its own ring's frame (NaN: a quasi-static "
            "snapshot that no frame holds still)",
            _own_frame("trajectory_band_thickness"),
        ),
        Metric(
            "band_thickness_arc",
            per_race,
            "m",
            "trajectory band thickness (arc)",
            "trajectory_band_thickness_arc of the race in its own ring's frame",
            _own_frame("trajectory_band_thickness_arc"),
        ),
        Metric(
            "band_width",
            per_race,
            "degree",
            "trajectory band width",
            "trajectory_band_width: max - min contact angle of the loaded contacts",
            _summary_value("trajectory_band_width"),
        ),
        Metric(
            "band_width_arc",
            per_race,
            "m",
            "trajectory band width (arc)",
            "trajectory_band_width_arc: groove radius times the band width",
            _summary_value("trajectory_band_width_arc"),
        ),
        # ---- the bearing as a whole ------------------------------------------------------------
        Metric(
            "mean_cage_speed",
            (),
            "rad/s",
            "mean cage speed",
            "mean cage speed (a quasi-static result: its cage speed)",
            _mean_cage_speed,
        ),
        Metric(
            "epicyclic_cage_speed",
            (),
            "rad/s",
            "epicyclic cage speed",
            "cage speed of pure rolling at the free contact angle",
            lambda w: epicyclic_cage_speed(w.ds),
        ),
        Metric(
            "cage_slip",
            (),
            "1",
            "cage slip",
            "1 - mean cage speed / epicyclic cage speed (free contact angle); > 0: the cage lags",
            _cage_slip,
        ),
        Metric(
            "mean_instantaneous_cage_slip",
            (),
            "1",
            "mean instantaneous cage slip",
            "instantaneous_cage_slip over the analysed window weighted by the rolling cage "
            "speed (1 - mean cage speed / mean rolling cage speed): how far the cage lags its "
            "rolling speed at the actual ring speeds and contact angles (NaN: quasi-static)",
            _instantaneous_cage_slip,
        ),
        Metric(
            "cage_skids",
            (),
            "1",
            "the cage skids",
            "1 when mean_instantaneous_cage_slip exceeds "
            f"{skidding.CAGE_SKID_THRESHOLD:g} (the result warns), 0 when not, NaN: quasi-static",
            _cage_skids,
        ),
        Metric(
            "mean_centrifugal_force",
            (),
            "N",
            "mean ball centrifugal force",
            "mean centrifugal force on one ball",
            _centrifugal_force,
        ),
        Metric(
            "mean_gyroscopic_moment",
            (),
            "N m",
            "mean ball gyroscopic moment",
            "mean gyroscopic moment on one ball (NaN when the result has none: dynamic)",
            lambda w: _mean_variable(w, "gyroscopic_moment"),
        ),
        Metric(
            "truncated_contacts",
            (),
            "1",
            "truncated contacts",
            "ball-race contacts whose ellipse runs over the shoulder at least once",
            _truncated_contacts,
        ),
        Metric(
            "shaft_period",
            (),
            "s",
            "shaft period",
            "one revolution of one ring relative to the other (inf: the rings do not turn)",
            _shaft_period,
        ),
        Metric(
            "shaft_revolutions",
            (),
            "1",
            "shaft revolutions",
            "revolutions of one ring relative to the other that a dynamic run covers "
            "(NaN: quasi-static)",
            _shaft_revolutions,
        ),
        # ---- friction torque: the model's and the empirical estimates -------------------------
        Metric(
            "mean_friction_torque",
            (),
            "N m",
            "mean friction torque",
            "mean friction_torque on the inner ring over the analysed window (NaN: quasi-static)",
            lambda w: _mean_variable(w, "friction_torque"),
        ),
        Metric(
            "friction_torque_palmgren",
            (),
            "N m",
            "Palmgren friction torque estimate",
            "Palmgren's M0 + M1 of the case (NaN when it cannot be made: the note says why)",
            _estimate("friction_torque_palmgren"),
        ),
        Metric(
            "friction_torque_skf",
            (),
            "N m",
            "SKF-model friction torque estimate",
            "the SKF friction model's torque of the case (NaN when it cannot be made: the note "
            "says why)",
            _estimate("friction_torque_skf"),
        ),
        # ---- losses, film and ring displacement --------------------------------------------------
        Metric(
            "mean_total_power_loss",
            (),
            "W",
            "mean total power loss",
            "mean total_power_loss over the analysed window (NaN: quasi-static)",
            lambda w: _mean_variable(w, "total_power_loss"),
        ),
        Metric(
            "mean_contact_heat",
            per_race,
            "W",
            "mean contact heat",
            "heat generated in the race's ball contacts (summed over the balls), mean over the "
            "analysed window (NaN: quasi-static)",
            _race_heat,
        ),
        Metric(
            "min_film_thickness",
            per_race,
            "m",
            "smallest film thickness",
            "smallest central EHL film thickness of a loaded contact (NaN without a lubricant)",
            lambda w: _contact(w, "film_thickness", "min"),
        ),
        Metric(
            "min_film_parameter",
            per_race,
            "1",
            "smallest film parameter λ",
            "min_film_thickness over the composite roughness sqrt(Rq_ball^2 + Rq_raceway^2) of "
            "the case's bearing.ball_roughness_um and bearing.raceway_roughness_um: below 1 "
            "boundary, 1 to 3 mixed, above 3 full-film lubrication (NaN without a lubricant or a "
            "readable case)",
            _film_parameter,
        ),
        Metric(
            "axial_displacement",
            (),
            "m",
            "axial ring displacement",
            "mean inner_ring_offset along the bearing axis (x) from the just-touching position",
            lambda w: _ring_displacement(w, ("x",)),
        ),
        Metric(
            "radial_displacement",
            (),
            "m",
            "radial ring displacement",
            "length of the mean radial (y, z) inner_ring_offset",
            lambda w: _ring_displacement(w, ("y", "z")),
        ),
        Metric(
            "axial_stiffness",
            (),
            "N/m",
            "axial secant stiffness",
            "axial_load over axial_displacement (secant, from the just-touching position; NaN "
            "without an axial load)",
            lambda w: _secant_stiffness(w, "axial_load", ("x",)),
        ),
        Metric(
            "radial_stiffness",
            (),
            "N/m",
            "radial secant stiffness",
            "radial_load over radial_displacement (secant; NaN without a radial load)",
            lambda w: _secant_stiffness(w, "radial_load", ("y", "z")),
        ),
        # ---- the analysed window (dynamic) -----------------------------------------------------
        Metric(
            "settling_time",
            (),
            "s",
            "settling time",
            "settling_time of the dynamic run (NaN: not settled, or quasi-static)",
            _summary_value("settling_time"),
        ),
        Metric(
            "settled",
            (),
            "1",
            "run settled",
            "1 settled, 0 not settled, NaN quasi-static",
            _summary_value("settled"),
        ),
        Metric(
            "analysis_start_time",
            (),
            "s",
            "start of the analysed window",
            "analysis_start_time of the dynamic run (NaN: quasi-static)",
            _summary_value("analysis_start_time"),
        ),
        Metric(
            "energy_balance_residual",
            (),
            "1",
            "energy balance residual",
            "(drive power - losses + work of the loads - change of kinetic and elastic energy) / "
            "losses over the analysed window "
            f"(NaN: quasi-static); beyond {energy.RESIDUAL_LIMIT:g} the result warns",
            _energy_balance_residual,
        ),
        # ---- rating life (solver.results.life) -------------------------------------------------
        _stored_row("basic_load_rating", "ISO 281 basic dynamic radial load rating C_r"),
        _stored_row("equivalent_load", "ISO 281 dynamic equivalent radial load P_r"),
        _stored_row("basic_rating_life", "ISO 281 basic rating life L10, in revolutions"),
        _stored_row("basic_rating_life_time", "ISO 281 basic rating life L10 as time"),
        _stored_row(
            "reference_rating_life",
            "ISO/TS 16281 reference rating life L10r from the contact loads, in revolutions",
        ),
        _stored_row(
            "reference_rating_life_time", "ISO/TS 16281 reference rating life L10r as time"
        ),
    ]
    return {row.name: row for row in rows}


#: name -> Metric: the metrics table, in the order docs/results-schema.md lists it.
METRICS: dict[str, Metric] = _table()


def metric_row(name: str) -> Metric:
    """The table row of ``name``; KeyError naming the known metrics otherwise."""
    try:
        return METRICS[name]
    except KeyError:
        known = ", ".join(METRICS)
        raise KeyError(f"unknown metric {name!r}; known metrics: {known}") from None


def compute_metric(window: Window, name: str) -> xr.DataArray:
    """Metric ``name`` of the result in ``window``, with its units, long name and meaning."""
    row = metric_row(name)
    value = row.compute(window)
    if not isinstance(value, xr.DataArray):
        value = xr.DataArray(value)
    value = _plain(value).astype(float)
    return value.assign_attrs({**value.attrs, **row.attrs()}).rename(name)


def metrics_table(ds: xr.Dataset, by_phase: bool = False) -> xr.Dataset:
    """Every metric of one result, computed directly (``ds.racetrace.metrics()`` caches them);
    ``by_phase``: per phase of the result (:class:`Window`), each with a ``phase`` dimension."""
    window = Window(ds, by_phase)
    return xr.Dataset({name: compute_metric(window, name) for name in METRICS})


def markdown_table() -> str:
    """The table as the Markdown rows of docs/results-schema.md ("Metrics"), which a test keeps
    equal to it."""
    lines = ["| name | dims | units | meaning |", "|---|---|---|---|"]
    for row in METRICS.values():
        dims = "(" + ", ".join(row.dims) + ")"
        lines.append(f"| `{row.name}` | {dims} | {row.units} | {row.meaning} |")
    return "\n".join(lines)


__all__ = [
    "CONTACT_DIMS",
    "METRICS",
    "Metric",
    "Window",
    "composite_roughness",
    "compute_metric",
    "epicyclic_cage_speed",
    "loaded",
    "loaded_mask",
    "markdown_table",
    "metric_row",
    "metrics_table",
    "reduce",
]
