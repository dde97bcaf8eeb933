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


def set_result_warnings(ds) -> list[str]:
    """Warnings of a bearing set's Dataset: a bearing whose balls all lost their inner contact
    (its preload lost), or some of them; a bearing unloaded at rest under the case's loads; and
    each bearing's own result warnings (:func:`solver.results.checks.result_warnings`), named by
    bearing. In a dynamic set's Dataset the contacts are those of the last stored sample, and a
    warning every bearing gives alike (the run stopped early, the set's energy balance) is given
    once, for the set."""
    from solver.results.checks import result_warnings

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
        count = int(ds["ball_count"][index])
        loads = inner.isel(bearing=index).values[:count]
        unloaded = int(np.sum(loads <= UNLOADED_CONTACT_FRACTION * max(scale, 1e-300)))
        if unloaded == count:
            found.append(
                f"bearing {name!s} carries no load {at}: every ball has lost its inner contact "
                "(its preload is lost under the external load); raise the preload, or use a "
                "spring preload that keeps its force"
            )
        elif unloaded:
            found.append(
                f"bearing {name!s}: {unloaded} of {count} balls have lost their inner contact "
                f"{at} (part of the preload is lost there)"
            )
        own.append((name, result_warnings(bearing_result(ds, index))))
    every = set.intersection(*(set(messages) for _, messages in own)) if dynamic else set()
    found += [message for message in own[0][1] if message in every]
    for name, messages in own:
        found += [f"bearing {name!s}: {m}" for m in messages if m not in every]
    if ds.attrs.get("unloaded_at_rest"):
        found.append(
            f"at rest under the case's loads the preload does not keep every bearing loaded: "
            f"{ds.attrs['unloaded_at_rest']} carries no load; raise the preload if that is not "
            "what was meant"
        )
    return found
