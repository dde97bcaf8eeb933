"""result_warnings: each validity check fires just past its limit and not at it, on small hand-built
Datasets (results-schema.md layout), then on real quasi-static results.

The limits are the published or geometric ones, written out here independently of the module:
4.2 GPa (ISO 76 reference contact stress for ball bearings), truncation margin 0 deg, contact angle
plus a / (f D) = 90 deg, semi-major a = D / 2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from solver.results.checks import result_warnings

D_MM = 10.0  # ball diameter of the hand-built cases, mm
F = 0.55  # groove radius ratio of both races: groove radius f D = 5.5 mm
GROOVE_RADIUS = F * D_MM * 1e-3  # m
#: The describing coordinates the size check reads (registered names, SI units).
GEOMETRY = {
    "ball_diameter": ((), D_MM * 1e-3),
    "groove_radius": (("race",), [GROOVE_RADIUS, GROOVE_RADIUS]),
}
ISO_76_LIMIT = 4.2e9  # Pa


def dataset(
    load=(100.0, 100.0, 100.0),
    angle=(10.0, 10.0, 10.0),
    semi_major=(0.5e-3, 0.5e-3, 0.5e-3),
    pressure=(1.0e9, 1.0e9, 1.0e9),
    margin=(math.nan, math.nan, math.nan),
    race="inner",
    geometry=True,
) -> xr.Dataset:
    """A quasi-static-shaped Dataset of 3 balls: the given values on ``race``, a benign contact
    (100 N, 10 deg, a = 0.5 mm, 1 GPa, no shoulder) on the other race."""
    values = {
        "contact_load": load,
        "contact_angle": angle,
        "ellipse_semi_major": semi_major,
        "max_pressure": pressure,
        "truncation_margin": margin,
    }
    benign = {
        "contact_load": 100.0,
        "contact_angle": 10.0,
        "ellipse_semi_major": 0.5e-3,
        "max_pressure": 1.0e9,
        "truncation_margin": math.nan,
    }
    k = 0 if race == "inner" else 1
    data = {}
    for name, given in values.items():
        array = np.full((3, 2), benign[name], dtype=float)
        array[:, k] = given
        data[name] = (("ball", "race"), array)
    attrs = {"model": "quasistatic", "complete": 1}
    coords = {"ball": [0, 1, 2], "race": ["inner", "outer"], **(GEOMETRY if geometry else {})}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def dynamic(ds: xr.Dataset, per_time: list[xr.Dataset], complete: int = 1) -> xr.Dataset:
    """A dynamic-shaped Dataset: the quasi-static snapshots ``per_time`` stacked along ``time``."""
    out = xr.concat(per_time, dim="time").transpose("ball", "race", "time")
    out = out.assign_coords(time=0.001 * np.arange(len(per_time)))
    out.attrs = {**ds.attrs, "model": "dynamic", "complete": complete, "shaft_period_s": 0.004}
    return out


def test_benign_result_gives_no_warning():
    assert result_warnings(dataset()) == []


# ---- shoulder truncation -----------------------------------------------------------------------
def test_truncation_fires_below_zero_margin_only():
    at_limit = dataset(margin=(0.0, 3.0, math.nan))
    assert result_warnings(at_limit) == []
    (message,) = result_warnings(dataset(margin=(-0.25, 3.0, math.nan), race="outer"))
    assert message.startswith("outer race:")
    assert "truncation_margin -0.25 deg" in message and "limit 0 deg" in message
    assert "at 1 of 3 contacts (ball 0)" in message
    assert "Hertz" in message and "edge loading" in message
    assert "bearing.outer_shoulder_diameter_mm" in message


def test_truncation_ignores_open_contacts():
    ds = dataset(load=(0.0, 100.0, 100.0), margin=(-5.0, 3.0, 3.0))
    assert result_warnings(ds) == []


# ---- static pressure limit ---------------------------------------------------------------------
def test_pressure_fires_above_the_iso_76_limit_only():
    at_limit = dataset(pressure=(ISO_76_LIMIT, 1e9, 1e9))
    assert result_warnings(at_limit) == []
    (message,) = result_warnings(dataset(pressure=(1e9, ISO_76_LIMIT * (1 + 1e-9), 5.0e9)))
    assert message.startswith("inner race: peak contact pressure")
    assert "5 GPa" in message  # the worst value, with its unit
    assert "4.2 GPa" in message and "ISO 76" in message and "static" in message
    assert "2 of 3 contacts (balls 1-2)" in message


# ---- contact too large for Hertz theory --------------------------------------------------------
def _semi_major_for_span(span_deg: float, angle_deg: float) -> float:
    """a [m] with angle + degrees(a / (f D)) = span (hand-built inverse of the criterion)."""
    return math.radians(span_deg - angle_deg) * GROOVE_RADIUS


def test_groove_wrap_fires_beyond_90_degrees_only():
    inside = _semi_major_for_span(90.0 - 1e-6, 80.0)
    assert result_warnings(dataset(angle=(80.0, 10, 10), semi_major=(inside, 5e-4, 5e-4))) == []
    beyond = _semi_major_for_span(95.0, 80.0)
    (message,) = result_warnings(
        dataset(angle=(-80.0, 10, 10), semi_major=(beyond, 5e-4, 5e-4))  # sign of alpha: either
    )
    assert "too large for Hertz theory" in message
    assert "95 deg" in message and "90 deg" in message and "5.5 mm" in message
    assert "not physical" in message


def test_semi_major_fires_beyond_half_the_ball_diameter_only():
    half_d = 0.5 * D_MM * 1e-3
    # at a = D/2 and alpha = 0 the span is degrees(0.5 / 0.55) = 52 deg: only the size criterion
    assert result_warnings(dataset(angle=(0.0, 0, 0), semi_major=(half_d, 5e-4, 5e-4))) == []
    (message,) = result_warnings(dataset(angle=(0.0, 0, 0), semi_major=(1.01 * half_d, 5e-4, 5e-4)))
    assert "5.05 mm" in message and "D/2 = 5 mm" in message


def test_size_check_reads_the_geometry_coordinates_not_the_case_text():
    big = dataset(semi_major=(0.02, 5e-4, 5e-4), geometry=False)
    # a case text in the attributes is provenance only: it is not read
    big.attrs["case"] = "[bearing]\nball_diameter_mm = 10.0\ninner_groove_radius_ratio = 0.55\n"
    assert result_warnings(big) == []
    assert result_warnings(dataset(semi_major=(0.02, 5e-4, 5e-4))) != []


# ---- dynamic results ---------------------------------------------------------------------------
def test_dynamic_result_gives_the_share_of_the_run():
    calm = dataset()
    hot = dataset(pressure=(1e9, 6e9, 1e9))
    ds = dynamic(calm, [calm, hot, calm, calm])
    (message,) = result_warnings(ds)
    assert "6 GPa" in message
    assert "ball 1 (of 3)" in message and "25% of the run" in message
    assert "1 of 4 time samples" in message


def test_dynamic_run_stopped_early_says_so():
    calm = dataset()
    assert result_warnings(dynamic(calm, [calm, calm], complete=1)) == []
    stopped = dynamic(calm, [calm, calm], complete=0)
    stopped.attrs["stop_reason"] = "cancelled"
    (message,) = result_warnings(stopped)
    assert "stopped early" in message and "t = 0.001 s" in message
    assert "0.25 shaft revolutions" in message and "cancelled" in message


# ---- real quasi-static results -----------------------------------------------------------------
def test_absurd_axial_load_is_flagged_by_solve_quasistatic():
    """An absurd load on a real case: the 209 deep-groove case at 1e9 N axial load."""
    from solver import solve_quasistatic
    from solver.catalogue import resolve_case

    case = resolve_case("209-radial").with_values({"operating.axial_load_N": 1e9})
    found = result_warnings(solve_quasistatic(case))
    for race in ("inner", "outer"):
        mine = [m for m in found if m.startswith(f"{race} race:")]
        assert any("peak contact pressure" in m and "4.2 GPa" in m for m in mine), found
        assert any("too large for Hertz theory" in m for m in mine), found
        # the shoulder message would quote a meaningless margin there: it is left out
        assert not any("runs over the shoulder" in m for m in mine), found
        # and a span past 180 deg is not quoted as a number
        assert not any("reaches 5" in m or "reaches 6" in m for m in mine), found


def test_a_contact_too_large_for_hertz_is_not_also_reported_as_truncated():
    beyond = _semi_major_for_span(95.0, 80.0)
    found = result_warnings(
        dataset(angle=(80.0, 10, 10), semi_major=(beyond, 5e-4, 5e-4), margin=(-20.0, 3, 3))
    )
    assert len(found) == 1 and "too large for Hertz theory" in found[0]


def _catalogue_names():
    from solver import catalogue

    return [entry.name for entry in catalogue()]


#: The one warning a shipped case is expected to give: the 218 heavy case's most loaded ball spins
#: on the falling branch of the thermally softened traction, so its quasi-static ball speeds come
#: from race control (docs/quasistatic-traction.md, docs/traction.md).
EXPECTED_WARNINGS = {"218-heavy-combined": "quasi-static ball speeds: the traction balance"}


@pytest.mark.parametrize("name", _catalogue_names())
def test_shipped_catalogue_cases_give_no_warning(name):
    """No shipped case gives a result warning, but for the one expected above."""
    from solver import set_result_warnings, solve, solve_quasistatic
    from solver.catalogue import resolve_case

    case = resolve_case(name)
    if case.bearing_set is not None:  # a bearing set: its Dataset has a bearing dimension
        found = set_result_warnings(solve(case))
    else:
        found = result_warnings(solve_quasistatic(case))
    if name in EXPECTED_WARNINGS:
        assert len(found) == 1 and found[0].startswith(EXPECTED_WARNINGS[name]), found
    else:
        assert found == []


# ---- friction torque against the empirical estimates --------------------------------------------
def _with_torque(model_torque: float, **estimates: float) -> xr.Dataset:
    """A dynamic-shaped benign result whose friction torque is ``model_torque`` [N m] after the
    first of 4 samples (the analysed window starts at the second) with the given estimates."""
    calm = dataset()
    ds = dynamic(calm, [calm, calm, calm, calm])
    torque = np.array([100.0, model_torque, model_torque, model_torque])  # first: start-up
    ds = ds.assign(friction_torque=("time", torque), analysis_start_time=0.001)
    return ds.assign({name: value for name, value in estimates.items()})


def test_torque_check_fires_outside_a_factor_3_of_every_estimate_only():
    # estimates 0.1 and 0.3 N m: inside a factor 3 of one of them up to 0.9 N m and down to 1/30
    for inside in (0.9, 0.1 / 3.0, 0.2):
        ds = _with_torque(inside, friction_torque_palmgren=0.1, friction_torque_skf=0.3)
        assert result_warnings(ds) == [], inside
    (message,) = result_warnings(
        _with_torque(0.91, friction_torque_palmgren=0.1, friction_torque_skf=0.3)
    )
    assert message.startswith("friction torque:") and "910 N mm" in message
    assert "Palmgren 100 N mm" in message and "SKF model 300 N mm" in message
    assert "factor 3" in message and "simulation.tolerance" in message
    (low,) = result_warnings(_with_torque(0.03, friction_torque_palmgren=0.1))
    assert "30 N mm" in low and "0.3 x Palmgren" in low
    assert result_warnings(_with_torque(100.0)) == []  # no estimate: nothing to compare with
