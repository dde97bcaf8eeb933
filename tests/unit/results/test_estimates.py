"""The friction-torque estimates of a case (solver.results.estimates): which bearing a designation
names, that an estimate which cannot be made is left out with the reason, and that a quasi-static
result stores them and the metrics table, the CLI text and JSON show them (never a bare NaN)."""

from __future__ import annotations

import math

import pytest

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.physics import friction_estimates as fe
from solver.results.estimates import estimate, identify

MM = 1e-3


@pytest.mark.parametrize(
    ("designation", "pitch_mm", "angle_deg", "kind", "series", "bore_mm", "outside_mm"),
    [
        ("209 deep groove", 65.0, 9.86, fe.DEEP_GROOVE, "62", 45.0, 85.0),
        ("6310", 80.0, 0.0, fe.DEEP_GROOVE, "63", 50.0, 110.0),
        ("218 angular contact (40 deg)", 125.0, 40.0, fe.ANGULAR_CONTACT, "72 B", 90.0, 160.0),
        ("7008C-class hybrid", 54.0, 15.0, fe.ANGULAR_CONTACT, "70 C", 40.0, 68.0),
        ("7203 BE", 28.5, 40.0, fe.ANGULAR_CONTACT, "72 B", 17.0, 40.0),
    ],
)
def test_identify_reads_kind_series_and_boundary_diameters(
    designation, pitch_mm, angle_deg, kind, series, bore_mm, outside_mm
):
    identity, reason = identify(designation, pitch_mm * MM, math.radians(angle_deg))
    assert reason == ""
    assert (identity.kind, identity.series) == (kind, series)
    assert identity.bore == pytest.approx(bore_mm * MM)
    assert identity.outside_diameter == pytest.approx(outside_mm * MM)


@pytest.mark.parametrize("designation", ["", "turbopump hybrid", "209", "NU 209", "1209"])
def test_identify_says_what_it_cannot_read(designation):
    identity, reason = identify(designation, 0.065, 0.0)
    assert identity is None
    assert "designation" in reason and "7xxx" in reason or "bearing number" in reason


def test_a_designation_that_does_not_fit_the_pitch_diameter_is_refused():
    identity, reason = identify("6220", 0.065, 0.0)  # bore 100 mm on a 65 mm pitch circle
    assert identity is None and "does not fit the pitch diameter" in reason


def test_hybrid_spindle_gets_palmgren_and_the_reason_there_is_no_skf_estimate():
    values, notes = estimate(to_inputs(resolve_case("spindle-combined-load")))
    assert set(values) == {"friction_torque_palmgren"}
    assert values["friction_torque_palmgren"] > 0.0
    assert "steel bearing of the same geometry" in notes["friction_torque_palmgren"]
    assert notes["friction_torque_skf"].startswith("not available:")
    assert "hybrid" in notes["friction_torque_skf"]


def test_an_unknown_series_is_not_guessed():
    case = resolve_case("218-heavy-combined").with_values({"bearing.designation": "7318 B"})
    values, notes = estimate(to_inputs(case))
    assert "friction_torque_skf" not in values and "friction_torque_palmgren" in values
    assert "73 B series" in notes["friction_torque_skf"]


def test_rings_not_turning_give_no_estimate():
    case = resolve_case("209-radial").with_values({"operating.inner_ring_speed_rpm": 0.0})
    values, notes = estimate(to_inputs(case))
    assert values == {}
    assert all("do not turn" in note for note in notes.values())


def test_quasistatic_result_stores_the_estimates_and_the_views_show_them():
    from racetrace.metrics import torque_json, torque_text
    from solver import solve_quasistatic

    ds = solve_quasistatic(resolve_case("209-radial"))
    values, _ = estimate(to_inputs(resolve_case("209-radial")))
    for name in ("friction_torque_palmgren", "friction_torque_skf"):
        assert float(ds[name]) == values[name]
        assert ds[name].attrs["units"] == "N m" and ds[name].attrs["note"]
        assert float(ds.racetrace.metric(name)) == values[name]
    text = torque_text(ds)
    # the 209 case is oil-bath lubricated: K_rs = 3e-8 (143.5 N mm with oil-air's 6e-8)
    assert "Palmgren M0 + M1: 103.8 N mm" in text and "SKF friction model: 147 N mm" in text
    assert "model" not in text.splitlines()[1]  # a quasi-static result has no torque of its own
    out = torque_json(ds)
    assert out["palmgren_N_m"] == pytest.approx(values["friction_torque_palmgren"])
    assert out["model_N_m"] is None


def test_an_estimate_left_out_shows_its_reason_not_nan():
    from racetrace.metrics import torque_json, torque_text
    from solver import solve_quasistatic

    ds = solve_quasistatic(resolve_case("spindle-axial-preload"))
    assert "friction_torque_skf" not in ds
    assert "hybrid" in ds.attrs["friction_torque_skf_note"]
    metric = ds.racetrace.metric("friction_torque_skf")
    assert math.isnan(float(metric)) and "hybrid" in metric.attrs["note"]
    text = torque_text(ds)
    assert "nan" not in text.lower() and "SKF friction model: not available:" in text
    assert torque_json(ds)["skf_N_m"] is None
    assert "hybrid" in torque_json(ds)["notes"]["skf_N_m"]


def test_skf_replenishment_constant_follows_the_lubrication_method():
    """K_rs = 3e-8 for an oil bath or jet, 6e-8 for oil-air or grease (SKF catalogue): the jet-fed
    218 keeps more of its rolling torque (phi_rs closer to 1) than the same bearing on oil-air,
    and each note names the constant and the method; no drag term, with the reason."""
    jet_case = resolve_case("218-heavy-combined")
    air_case = jet_case.with_values(
        {
            "lubricant.method": "oil_air",
            "lubricant.jet_flow_l_min": None,
            "lubricant.oil_flow_mm3_h": 500.0,
        }
    )
    jet_values, jet_notes = estimate(to_inputs(jet_case))
    air_values, air_notes = estimate(to_inputs(air_case))
    assert jet_values["friction_torque_skf"] > air_values["friction_torque_skf"]
    assert "K_rs = 3e-08 for oil_jet" in jet_notes["friction_torque_skf"]
    assert "K_rs = 6e-08 for oil_air" in air_notes["friction_torque_skf"]
    assert "no drag term" in jet_notes["friction_torque_skf"]
    assert "were not among the sources found" in jet_notes["friction_torque_skf"]
    assert "its f0 was not transcribed" in jet_notes["friction_torque_palmgren"]
    assert "not transcribed" not in air_notes["friction_torque_palmgren"]
