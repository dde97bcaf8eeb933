"""Quasi-static solutions over one revolution: a misalignment turning with the inner ring draws a
line on the inner raceway (in the inner ring's frame) and a band on the outer one; fixed in space,
the roles swap."""

from __future__ import annotations

import numpy as np
import pytest

import solver

ANGLES = 8


def _spread(ds, race: str) -> float:
    """Largest difference (degree) between the contact-angle curves of the ring angles, each as a
    periodic function of the azimuth in the race's own ring frame: 0 for a line."""
    grid = np.linspace(0.0, 360.0, 73)
    curves = []
    for k in range(ds.sizes["ring_angle"]):
        e = ds.isel(ring_angle=k).sel(race=race)
        az, alpha = e["raceway_azimuth"].values, e["contact_angle"].values
        curves.append(np.interp(grid, az, alpha, period=360.0))
    curves = np.array(curves)
    return float(np.max(curves.max(axis=0) - curves.min(axis=0)))


@pytest.fixture(scope="module")
def turning():
    return solver.solve_over_revolution("spindle-misalignment-ring", angles=ANGLES)


@pytest.fixture(scope="module")
def fixed():
    return solver.solve_over_revolution("spindle-misalignment-space", angles=ANGLES)


def test_angles_and_turning_axis(turning):
    np.testing.assert_allclose(turning["ring_angle"].values, np.arange(ANGLES) * 360.0 / ANGLES)
    assert turning["ring_angle"].attrs["units"] == "degree"
    axis = turning["misalignment_axis"].values
    np.testing.assert_allclose(np.diff(axis), 360.0 / ANGLES)
    assert turning["raceway_azimuth"].dims == ("ring_angle", "ball", "race")


def test_turning_misalignment_is_a_line_inside_and_a_band_outside(turning):
    inner, outer = _spread(turning, "inner"), _spread(turning, "outer")
    assert inner < 0.1 * outer, (inner, outer)


def test_fixed_misalignment_is_a_line_outside_and_a_band_inside(fixed):
    inner, outer = _spread(fixed, "inner"), _spread(fixed, "outer")
    assert outer < 0.1 * inner, (inner, outer)


def test_too_few_angles_is_named():
    with pytest.raises(ValueError, match="at least 2"):
        solver.solve_over_revolution("spindle-misalignment-ring", angles=1)
