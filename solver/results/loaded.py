"""The one definition of a loaded contact, read by every statistic over contacts.

A ball-race contact is *loaded* when its ``contact_load`` is > 0 N and its ``contact_angle`` is
finite: an open contact (load 0, or NaN where a view has no value) carries nothing, and a contact
without a position on the groove cannot enter an average. The metrics table
(:mod:`solver.results.metrics`), the summary metrics and settling (:mod:`solver.results.summary`),
the rating lives (:mod:`solver.results.life`), the validity checks and the views' drawings all use
it.
"""

from __future__ import annotations

import numpy as np
import xarray as xr


def loaded_mask(load, angle):
    """True where a contact is loaded: ``load`` [N] > 0 and ``angle`` finite. Works on numpy arrays
    and DataArrays of any (matching or broadcastable) shape; a NaN load is not loaded."""
    return (load > 0.0) & np.isfinite(angle)


def loaded(ds: xr.Dataset) -> xr.DataArray:
    """The loaded contacts of a result (:func:`loaded_mask` of ``contact_load`` and
    ``contact_angle``), with the dimensions of ``contact_load``."""
    return loaded_mask(ds["contact_load"], ds["contact_angle"])


__all__ = ["loaded", "loaded_mask"]
