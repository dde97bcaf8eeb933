"""The rating lives as the commands print them (racetrace.metrics): finite, infinite and
unavailable lives, in text and JSON."""

from __future__ import annotations

import json
import math

import pytest

import solver
from racetrace.metrics import life_json, life_text


@pytest.fixture(scope="module")
def radial():
    return solver.solve_quasistatic("209-radial")


def test_finite_lives_in_million_revolutions_and_hours(radial):
    out = life_json(radial)
    # 209-radial turns at the speed in its coordinates: hours = revolutions / (60 n)
    rpm = float(radial.inner_ring_speed) * 30.0 / math.pi
    assert out["L10_hours"] == pytest.approx(out["L10_million_revolutions"] * 1e6 / (60 * rpm))
    assert out["equivalent_load_N"] == pytest.approx(4450.0)  # pure radial: P_r = F_r
    text = life_text(radial)
    assert f"{out['L10_million_revolutions']:.0f} million revolutions" in text
    assert f"{out['L10r_hours']:.0f} h" in text


def test_unavailable_and_infinite_lives(radial):
    # an axial load at the deep-groove bearing's 9.9 deg contact angle: outside the X, Y table
    ds = radial.assign_coords(axial_load=100.0, inner_ring_speed=0.0)
    out = json.loads(json.dumps(life_json(ds), allow_nan=False))
    assert out["L10_million_revolutions"] is None
    assert any("not available" in note and "15 to 45 deg" in note for note in out["notes"])
    assert out["L10r_hours"] is None  # rings not turning relative to each other
    assert any("null" in note for note in out["notes"])
    text = life_text(ds)
    assert "L10  (ISO 281, applied loads):       n/a" in text
    assert "(rings not turning: no hours)" in text
    unloaded = ds.assign(contact_load=ds.contact_load * 0.0)
    assert "infinite (no loaded contact)" in life_text(unloaded)
