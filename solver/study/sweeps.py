"""The sweeps of a study Dataset (:func:`solver.study.store.study_dataset`): which varied keys
each sweep changes, and the key its metrics are charted against.

A study Dataset has one coordinate per varied key over ``point``; a point that does not set a key
holds NaN there (or "" for a text key). Values are compared by their text, so that an unset key
(NaN at every point of a sweep) counts as one value and is not taken for a key the sweep varies.
"""

from __future__ import annotations

import json

import numpy as np


def _varied_keys(ds) -> list[str]:
    """The study's varied keys (every key a sweep varies or sets), in the study file's order."""
    return list(json.loads(ds.attrs.get("varied_keys", "[]")))


def sweep_varied_keys(ds) -> dict[str, list[str]]:
    """{sweep: the varied keys whose value changes between the sweep's points}, sweeps in table
    order; every varied key for a sweep of one point (nothing changes, so each names the point)."""
    keys = _varied_keys(ds)
    sweeps = np.asarray(ds["sweep"].values).astype(str)
    out = {}
    for sweep in dict.fromkeys(sweeps.tolist()):
        rows = sweeps == sweep
        changed = [k for k in keys if len({str(v) for v in np.asarray(ds[k].values)[rows]}) > 1]
        out[sweep] = changed or keys
    return out


def sweep_axis_key(ds, sweep: str) -> str | None:
    """The key the metrics of ``sweep`` are charted against: the first varied key that is a number
    and takes at least two finite values over the sweep's points; None when no key does (a sweep
    of one point, or one that varies only text keys)."""
    rows = np.asarray(ds["sweep"].values).astype(str) == sweep
    for key in sweep_varied_keys(ds).get(sweep, []):
        values = np.asarray(ds[key].values)[rows]
        if values.dtype.kind not in "fi":
            continue
        finite = values[np.isfinite(values)]
        if np.unique(finite).size >= 2:
            return key
    return None
