"""Where a bearing set's quasi-static result needs a second look (:func:`set_result_warnings`)."""

from __future__ import annotations

import numpy as np

from .set_result import SET_VARIABLES

#: A contact counts as unloaded below this fraction of the largest contact load of the set.
UNLOADED_CONTACT_FRACTION = 1e-9


def bearing_result(ds, index: int):
    """The single-bearing Dataset of bearing ``index`` of a set's Dataset (its own frame, its own
    operating point, its ``ball_count``; the set's variables and the balls beyond its ball count
    left out): a single-bearing result (results-schema.md) that the single-bearing views read."""
    one = ds.isel(bearing=index)
    count = int(one["ball_count"])
    one = one.drop_vars([name for name in SET_VARIABLES if name in one.variables])
    one = one.drop_vars(
        [
            name
            for name in (
                "bearing",
                "bearing_position",
                "bearing_direction",
                "dof",
                "dof_",
                "load_position",
            )
            if name in one.variables
        ]
    )
    return one.isel(ball=slice(0, count))


def set_spring_preload(ds) -> dict | None:
    """The spring preload of a bearing set's result (results-schema.md), None without one.

    A dynamic run (``spring_shift`` over ``time``): ``spring_force_N`` (the constant spring
    force), ``spring_shift_m`` (the floating outer rings' shift w, mean over the set's analysed
    window, the latest of the bearings' ``analysis_start_time``) and ``spring_shift_span_m`` (its
    peak to peak there). A quasi-static result: ``spring_shift_m`` (its solved w, which is 0
    without a spring preload: None then); its spring force is the case's
    ``set.preload.force_N``, named in ``attrs["bearing_set"]``, not a variable."""
    if "spring_shift" not in ds:
        return None
    shift = ds["spring_shift"]
    if "time" not in shift.dims:
        value = float(shift)
        return {"spring_shift_m": value} if value != 0.0 else None
    start = float(ds["analysis_start_time"].max())
    window = shift.sel(time=slice(start, None)).values
    return {
        "spring_force_N": float(ds["spring_force"]),
        "spring_shift_m": float(window.mean()),
        "spring_shift_span_m": float(window.max() - window.min()),
    }


def _set_energy_check(ds) -> list[str]:
    """The warning of a dynamic set whose energy-balance residual (the whole set's, over the
    analysed window) exceeds :data:`solver.results.energy.RESIDUAL_LIMIT`."""
    from solver.results.energy import RESIDUAL_LIMIT

    residual = float(ds["energy_balance_residual"]) if "energy_balance_residual" in ds else 0.0
    if not abs(residual) > RESIDUAL_LIMIT:
        return []
    return [
        f"the set's energy balance does not close over the analysed window: residual "
        f"{100.0 * residual:+.2f} % of the losses, more than {100.0 * RESIDUAL_LIMIT:g} %. The "
        "integration does not resolve the forces the drive power and the losses come from, so "
        "the friction torques, the drive power and the losses may be wrong. Tighten "
        "[simulation] tolerance (racetrace simulate --tolerance, e.g. a tenth of it) and, if the "
        "residual stays, run longer ([simulation] shaft_revolutions)."
    ]


def _called(name) -> str:
    """How a warning names a bearing of the set: its name, with "bearing" before it unless the
    name says so already (the default names are "bearing 1", "bearing 2", ...)."""
    name = str(name)
    return name if name.lower().startswith("bearing") else f"bearing {name}"


def set_result_warnings(ds) -> list[str]:
    """Warnings of a bearing set's Dataset: a bearing whose balls all lost their inner contact
    (its preload lost), or some of them; a bearing unloaded at rest under the case's loads; and
    each bearing's own result warnings (:func:`solver.results.checks.result_warnings`), named by
    bearing. In a dynamic set's Dataset the contacts are those of the last stored sample, a
    warning every bearing gives alike (the run stopped early) is given once, the energy balance
    checked is the whole set's (``energy_balance_residual``), not each bearing's, and a
    bearing's friction torque is not compared with the empirical estimates (they read applied
    loads, and the shaft loads a bearing of a set)."""
    from solver.results.checks import _energy_check, _torque_estimate_check, result_warnings

    found = []
    dynamic = "time" in ds.dims
    inner = ds["contact_load"].sel(race="inner")
    if dynamic:
        inner = inner.isel(time=-1)
    scale = float(np.nanmax(ds["contact_load"].values)) if ds["contact_load"].size else 0.0
    speed = float(ds["inner_ring_speed"].max()) if "inner_ring_speed" in ds.coords else 0.0
    at = "at the end of the run" if dynamic else "at speed" if speed else "at rest"
    own = []
    for index, name in enumerate(ds["bearing"].values):
        count = int(ds["ball_count"].isel(bearing=index, missing_dims="ignore"))
        loads = inner.isel(bearing=index).values[:count]
        unloaded = int(np.sum(loads <= UNLOADED_CONTACT_FRACTION * max(scale, 1e-300)))
        if unloaded == count:
            found.append(
                f"{_called(name)} carries no load {at}: every ball has lost its inner contact "
                "(its preload is lost under the external load); raise the preload, or use a "
                "spring preload that keeps its force"
            )
        elif unloaded:
            found.append(
                f"{_called(name)}: {unloaded} of {count} balls have lost their inner contact "
                f"{at} (part of the preload is lost there)"
            )
        one = bearing_result(ds, index)
        messages = result_warnings(one)
        if dynamic:
            # a bearing's own balance lacks the shaft's work on its ring (the set's is checked);
            # the empirical torque estimates need the bearing's applied loads, and a bearing of
            # a set has none of its own (the shaft loads it)
            left_out = _energy_check(one) + _torque_estimate_check(one)
            messages = [m for m in messages if m not in left_out]
        own.append((name, messages))
    every = set.intersection(*(set(messages) for _, messages in own)) if dynamic else set()
    found += [message for message in own[0][1] if message in every]
    if dynamic:
        found += _set_energy_check(ds)
    for name, messages in own:
        found += [f"{_called(name)}: {m}" for m in messages if m not in every]
    if ds.attrs.get("unloaded_at_rest"):
        found.append(
            f"at rest under the case's loads the preload does not keep every bearing loaded: "
            f"{ds.attrs['unloaded_at_rest']} carries no load; raise the preload if that is not "
            "what was meant"
        )
    return found
