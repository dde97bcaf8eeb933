"""The energy balance of a dynamic result over its analysed window: the result's own check of
its integration.

Over the analysed window [t0, t1] (``analysis_start_time`` to the end, :mod:`.summary`) the work
fed in through the imposed ring rotations and by the applied loads must leave as losses or as a
change of the kinetic energy of the moving bodies and of the contacts' elastic energy:

    residual = (mean drive_power + (W(t1) - W(t0)) / (t1 - t0) - mean total_power_loss
                - (KE(t1) - KE(t0)) / (t1 - t0) - (U(t1) - U(t0)) / (t1 - t0))
               / mean total_power_loss

with the means taken as time integrals over the window (trapezoidal rule over the output samples)
divided by its length, and KE the ``kinetic_energy`` variable of the result (every moving body:
the balls' translation and rotation, the cage's six degrees of freedom, the inner ring's
translations and tilts where they are free), W the ``load_work``: the work done since t = 0 by the
applied loads (the integral of F . dx over the inner ring's displacement and of M . d(tilt): loads
that vary in time have no potential -F . x) and by gravity, and U the ``elastic_energy`` of the
ball-race contacts. A result without ``load_work`` or ``elastic_energy`` (written before they were
stored) balances without them. Powers in W, energies in J, times in s; the residual
is dimensionless. It is small when the integrator resolves the forces the losses and the drive
power come from; a residual above :data:`RESIDUAL_LIMIT` means the tolerance is too loose for
them (or the window too short to average out the ball passages).

**The first shaft revolution is left out** of a run at least two revolutions long
(:func:`ring_down_end`; shaft period: the ``shaft_period_s`` attribute), as from every mean over
the analysed window (:func:`solver.results.summary.analysis_start`): the run starts from the
quasi-static state and rings down in its first revolution, and the energy its normal-contact
damping takes and the contacts' elastic energy are not terms of the balance (the 209-radial case
at tolerance 1e-5: drive power - losses 19 W in the first revolution, within 0.3 W of zero in
each later one; losses 59 W).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

#: Largest |residual| a result may carry without a warning (1 % of the losses).
RESIDUAL_LIMIT = 0.01

#: Variables the balance reads (dims ``(time,)``).
BALANCE_VARIABLES = ("drive_power", "total_power_loss", "kinetic_energy")
#: ... and those it reads when the result has them (zero otherwise).
OPTIONAL_BALANCE_VARIABLES = ("load_work", "elastic_energy")


@dataclass(frozen=True)
class EnergyBalance:
    """Means over the analysed window: ``drive`` and ``loss`` [W], ``kinetic_rate`` = change of
    kinetic energy / window length [W], ``load`` (work of the applied loads and gravity / window
    length) and
    ``elastic_rate`` (change of the contacts' elastic energy / window length) [W], ``residual``
    (dimensionless, NaN when the window has no length or no losses) and the window ``start``
    and ``end`` [s]."""

    drive: float
    loss: float
    kinetic_rate: float
    residual: float
    start: float
    end: float
    load: float = 0.0
    elastic_rate: float = 0.0


def _series(ds: xr.Dataset, name: str) -> np.ndarray:
    return np.asarray(ds[name].transpose("time").values, dtype=float)


def _integral(values: np.ndarray, times: np.ndarray) -> float:
    """Trapezoidal integral of samples ``values`` at ``times``."""
    return float(0.5 * np.sum((values[1:] + values[:-1]) * np.diff(times)))


def ring_down_end(times: np.ndarray, period: float) -> float:
    """End [s] of the ring-down of a dynamic run: the end of its first shaft revolution
    (``period`` [s]) when the run is at least two revolutions long, else 0. A run starts from the
    quasi-static state and rings down into its contact damping in that revolution (the 209-radial
    case at tolerance 1e-5: drive power - losses 19 W in the first revolution, within 0.3 W of
    zero in each later one, losses 59 W), so no mean over the run includes it."""
    if math.isfinite(period) and times.size and times[-1] >= 2.0 * period:
        return period
    return 0.0


def balance_start_time(ds: xr.Dataset, start_time: float) -> float:
    """Start [s] of the balance's window of a dynamic result whose analysed window starts at
    ``start_time`` [s]: ``start_time``, or the end of the first shaft revolution when that is
    later and the run is at least two revolutions long (module docstring). Outputs compared with
    the balance (drive power, losses, friction torque) are means over the same window."""
    times = np.asarray(ds["time"].values, dtype=float)
    period = float(ds.attrs.get("shaft_period_s", math.nan))
    return max(start_time, ring_down_end(times, period))


def energy_balance(ds: xr.Dataset, start_time: float) -> EnergyBalance | None:
    """The balance of a dynamic result over the samples at or after
    :func:`balance_start_time` (``start_time`` [s], or the end of the first shaft revolution);
    None when the result lacks a variable of :data:`BALANCE_VARIABLES` (a quasi-static result, or
    one written before the kinetic energy was stored)."""
    if "time" not in ds.dims or not all(name in ds for name in BALANCE_VARIABLES):
        return None
    times = np.asarray(ds["time"].values, dtype=float)
    start_time = balance_start_time(ds, start_time)
    first = int(np.searchsorted(times, start_time - 1e-12 * max(abs(start_time), 1.0)))
    t = times[first:]
    nan = math.nan
    if t.size < 2 or not t[-1] > t[0]:
        start = float(t[0]) if t.size else nan
        return EnergyBalance(nan, nan, nan, nan, start, start)
    span = float(t[-1] - t[0])
    drive = _integral(_series(ds, "drive_power")[first:], t) / span
    loss = _integral(_series(ds, "total_power_loss")[first:], t) / span
    kinetic = _series(ds, "kinetic_energy")[first:]
    rate = float(kinetic[-1] - kinetic[0]) / span
    load = elastic_rate = 0.0
    if "load_work" in ds:
        work = _series(ds, "load_work")[first:]
        load = float(work[-1] - work[0]) / span
    if "elastic_energy" in ds:
        elastic = _series(ds, "elastic_energy")[first:]
        elastic_rate = float(elastic[-1] - elastic[0]) / span
    net = drive + load - loss - rate - elastic_rate
    residual = net / loss if loss > 0.0 else nan
    return EnergyBalance(drive, loss, rate, residual, float(t[0]), float(t[-1]), load, elastic_rate)


def balance_words(balance: EnergyBalance) -> str:
    """The balance in words: means and residual, for the warning and the summaries."""
    return (
        f"drive power {balance.drive:.4g} W, work of the loads {balance.load:.3g} W, losses "
        f"{balance.loss:.4g} W, change of kinetic energy {balance.kinetic_rate:.3g} W and of "
        f"elastic energy {balance.elastic_rate:.3g} W: residual {100.0 * balance.residual:+.2f} % "
        "of the losses"
    )


def residual_message(balance: EnergyBalance, tolerance_note: str = "") -> str:
    """The warning for a residual beyond :data:`RESIDUAL_LIMIT` (plain text)."""
    where = f" (integrator: {tolerance_note})" if tolerance_note else ""
    return (
        f"the energy balance does not close over the analysed window: {balance_words(balance)}, "
        f"more than {100.0 * RESIDUAL_LIMIT:g} %{where}. The integration does not resolve the "
        "forces the drive power and the losses come from, so the friction torque, the drive power "
        "and the losses may be wrong. Tighten [simulation] tolerance (racetrace simulate "
        "--tolerance, e.g. a tenth of it) and, if the residual stays, run longer "
        "([simulation] shaft_revolutions)."
    )


__all__ = [
    "BALANCE_VARIABLES",
    "RESIDUAL_LIMIT",
    "EnergyBalance",
    "balance_start_time",
    "balance_words",
    "energy_balance",
    "residual_message",
]
