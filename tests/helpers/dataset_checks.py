"""Checks on how a result Dataset was assembled."""

from __future__ import annotations

import xarray as xr


def assert_public_constructor_makes(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` is the Dataset the public ``xr.Dataset(data_vars, coords)`` makes of its own
    variables: attributes, order, sizes and index names included. Returns that Dataset."""
    public = xr.Dataset(
        {name: ds[name].variable for name in ds.data_vars},
        coords=ds.coords,
        attrs=ds.attrs,
    )
    xr.testing.assert_identical(ds, public)
    assert list(ds.data_vars) == list(public.data_vars)
    assert list(ds.coords) == list(public.coords)
    assert dict(ds.sizes) == dict(public.sizes)
    assert set(ds.xindexes) == set(public.xindexes)
    return public
