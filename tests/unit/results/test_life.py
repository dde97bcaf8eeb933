"""Rating life read from result Datasets (solver.results.life): which mean each ring gets, the
dynamic window, the quasi-static Dataset and the summary. Expected values are recomputed here from
the standards' formulas written out inline (ISO/TS 16281 raceway rating, cubic / 10/3 means,
e = 10/9), not through solver.physics.life."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from racetrace.metrics import life_headline
from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.results import summary
from solver.results.dataset import build_result
from solver.results.life import LIFE_METRICS, rating_life, snapshot_life_metrics
from tests.helpers.cases import operating_point

OMEGA = 2 * math.pi * 100.0  # inner ring, rad/s
PERIOD = 2 * math.pi / OMEGA
CAGE = 0.4 * OMEGA
Z = 18
PER_REV = 90
ALPHA = 18.0  # degree
GEOMETRY = resolve_case("spindle-combined-load").geometry()


def _q_c(conformity: float, inner: bool) -> float:
    """ISO/TS 16281 rating of one ball-raceway contact of the spindle bearing at ALPHA, N."""
    d_mm = GEOMETRY.ball_diameter * 1e3
    gamma = GEOMETRY.ball_diameter * math.cos(math.radians(ALPHA)) / GEOMETRY.pitch_diameter
    if inner:
        curvature = (1 - gamma) ** 1.39 / (1 + gamma) ** (1 / 3)
    else:
        curvature = (1 + gamma) ** 1.39 / (1 - gamma) ** (1 / 3)
    return (
        1.3
        * 98.1
        * (2 * conformity / (2 * conformity - 1)) ** 0.41
        * curvature
        * (GEOMETRY.ball_diameter / GEOMETRY.pitch_diameter) ** 0.3
        * d_mm**1.8
        * Z ** (-1 / 3)
    )


def _result(revolutions=4.0, early_load=None, **operating):
    """Dynamic-shaped result: load 100 (1 + 0.5 cos psi) N on both races at the ball's inertial
    azimuth psi (a load zone fixed in space, or, with a ring-fixed misalignment, turning with the
    inner ring), contact angle ALPHA. ``early_load``: load [N] in the first two revolutions, whose
    contact angle is then offset so that the run settles only after them."""
    times = np.arange(int(round(revolutions * PER_REV)) + 1) * (PERIOD / PER_REV)
    psi = 2 * np.pi * np.arange(Z)[None, :] / Z + CAGE * times[:, None]
    ring_fixed = operating.get("misalignment_frame") == "ring"
    zone = psi - OMEGA * times[:, None] if ring_fixed else psi
    load = 100.0 * (1.0 + 0.5 * np.cos(zone))
    alpha = np.full(load.shape, ALPHA)
    if early_load is not None:
        early = times < 2 * PERIOD - 1e-12
        load[early] = early_load
        alpha[early] += 0.5
    both = lambda a: np.stack([a, a], axis=-1)  # noqa: E731
    dims = ("time", "ball", "race")
    data = {
        "contact_angle": (dims, both(alpha)),
        "contact_load": (dims, both(load)),
        "raceway_azimuth": (dims, both(np.degrees(psi) % 360.0)),
        "ellipse_semi_major": (dims, np.full(both(load).shape, 4e-4)),
        "spin_to_roll": (dims, np.full(both(load).shape, 0.07)),
    }
    op = operating_point(OMEGA, axial_load=500.0, **operating)
    return build_result("dynamic", data, GEOMETRY, op, times=times), load


def _expected_l10r(loads, inner_exponent, outer_exponent):
    q_ci = _q_c(GEOMETRY.inner_conformity, True)
    q_co = _q_c(GEOMETRY.outer_conformity, False)
    q_ei = np.mean(loads**inner_exponent) ** (1 / inner_exponent)
    q_eo = np.mean(loads**outer_exponent) ** (1 / outer_exponent)
    l_i, l_o = (q_ci / q_ei) ** 3, (q_co / q_eo) ** 3
    return (l_i ** (-10 / 9) + l_o ** (-10 / 9)) ** (-0.9) * 1e6, (q_ei, q_eo)


def test_load_fixed_in_space_cubic_mean_on_the_rotating_inner_ring():
    ds, load = _result()
    life = rating_life(ds)
    expected, (q_ei, q_eo) = _expected_l10r(load, 3.0, 10.0 / 3.0)
    np.testing.assert_allclose(life.raceway_equivalent_load.values, [q_ei, q_eo], rtol=1e-9)
    assert float(life.reference_rating_life) == pytest.approx(expected, rel=1e-9)
    assert (
        "inner race: cubic mean, outer race: 10/3 mean"
        in (life.raceway_equivalent_load.attrs["note"])
    )
    np.testing.assert_allclose(
        life.raceway_load_rating.values,
        [_q_c(GEOMETRY.inner_conformity, True), _q_c(GEOMETRY.outer_conformity, False)],
        rtol=1e-9,
    )
    # revolutions -> time at 100 rev/s
    assert float(life.reference_rating_life_time) == pytest.approx(expected / 100.0, rel=1e-9)


def test_ring_fixed_misalignment_load_turns_with_the_inner_ring():
    ds, load = _result(misalignment=math.radians(0.05), misalignment_frame="ring")
    life = rating_life(ds)
    expected, _ = _expected_l10r(load, 10.0 / 3.0, 3.0)
    assert float(life.reference_rating_life) == pytest.approx(expected, rel=1e-9)
    assert "inner race: 10/3 mean" in life.raceway_equivalent_load.attrs["note"]


def test_dynamic_summary_uses_the_settled_window_only():
    ds, load = _result(revolutions=6.0, early_load=1000.0)
    metrics = summary.trajectory_summary(ds)
    assert float(metrics.settling_time) == pytest.approx(2 * PERIOD)
    # the life counts whole revolutions ending at the last sample: 4 revolutions after settling
    times = ds.time.values
    kept = times >= times[-1] - 4 * PERIOD - 1e-9 * PERIOD
    expected, _ = _expected_l10r(load[kept], 3.0, 10.0 / 3.0)
    assert float(metrics.reference_rating_life) == pytest.approx(expected, rel=1e-9)
    # with the heavy early revolutions the life would be far shorter
    assert float(rating_life(ds, 0).reference_rating_life) < 0.01 * expected


def test_stored_summary_without_life_metrics_computes_them():
    ds, _ = _result()
    metrics = summary.trajectory_summary(ds)
    track = [n for n in metrics.data_vars if n not in LIFE_METRICS]
    stored = ds.assign(metrics[track].data_vars)
    out = summary.stored_summary(stored)
    assert set(LIFE_METRICS) <= set(out.data_vars)
    assert float(out.reference_rating_life) == pytest.approx(float(metrics.reference_rating_life))
    full = ds.assign(metrics.data_vars)
    assert float(summary.stored_summary(full).basic_rating_life) == pytest.approx(
        float(metrics.basic_rating_life)
    )


def test_quasistatic_dataset_carries_the_lives():
    ds = solver.solve_quasistatic("spindle-combined-load")
    for name in LIFE_METRICS:
        assert name in ds, name
    assert ds.basic_rating_life.attrs["units"] == "1"
    assert ds.reference_rating_life_time.attrs["units"] == "s"
    # ISO 281 (hand-worked in tests/unit/physics/test_life.py): C_r = 14 049.2 N (f_c reduced
    # for f_i = 0.54), P_r = 803.083 N, L10 = (14 049.2 / 803.083)^3 = 5 353.9 million rev,
    # at 20 000 rpm 5 353.9e6 / 1.2e6 = 4 461.6 h
    assert float(ds.basic_load_rating) == pytest.approx(14049.2, rel=2e-5)
    assert float(ds.basic_rating_life) == pytest.approx(5353.88e6, rel=1e-4)
    assert float(ds.basic_rating_life_time) / 3600 == pytest.approx(4461.57, rel=1e-4)
    # ISO/TS 16281 from the Dataset's own loads and angles, per contact
    d, dm = GEOMETRY.ball_diameter, GEOMETRY.pitch_diameter
    lives = []
    for race, f, sign, w in (("inner", 0.54, -1, 3.0), ("outer", 0.53, 1, 10 / 3)):
        q = ds.contact_load.sel(race=race).values
        gamma = d * np.cos(np.radians(ds.contact_angle.sel(race=race).values)) / dm
        curvature = (1 + sign * gamma) ** 1.39 / (1 - sign * gamma) ** (1 / 3)
        qc = 1.3 * 98.1 * (2 * f / (2 * f - 1)) ** 0.41 * curvature * (d / dm) ** 0.3
        qc = qc * (d * 1e3) ** 1.8 * Z ** (-1 / 3)
        lives.append(np.mean((q / qc) ** w) ** (-3 / w))
    expected = (lives[0] ** (-10 / 9) + lives[1] ** (-10 / 9)) ** (-0.9) * 1e6
    assert float(ds.reference_rating_life) == pytest.approx(expected, rel=1e-9)
    # ceramic balls: the steel note is attached
    assert "bearing steel" in ds.reference_rating_life.attrs["note"]
    head = life_headline(ds)
    assert head["L10r_million_revolutions"] == pytest.approx(expected / 1e6)
    assert head["L10_hours"] == pytest.approx(4461.57, rel=1e-4)


@pytest.mark.parametrize("name", ["spindle-misalignment-ring", "218-heavy-combined"])
def test_snapshot_lives_from_arrays_equal_the_dataset_reading(name):
    """The quasi-static builder computes the lives from its arrays (snapshot_life_metrics) instead
    of reading them back from the Dataset: the same values and attributes as rating_life of the
    Dataset, for a ring-fixed misalignment without radial load (its load zone turns with the inner
    ring: cubic / 10/3 means swap) on a hybrid (the steel note) and for the 218 under a combined
    load."""
    case = resolve_case(name)
    inputs = to_inputs(case)
    ds = solver.solve_quasistatic(case)
    load = ds.contact_load.transpose("ball", "race").values
    angle = np.radians(ds.contact_angle.transpose("ball", "race").values)
    arrays = snapshot_life_metrics(inputs.geometry, inputs.operating, load, angle)
    read = rating_life(ds)
    assert list(arrays) == list(LIFE_METRICS)
    for metric, (dims, values, attrs) in arrays.items():
        assert dims == read[metric].dims
        np.testing.assert_allclose(values, read[metric].values, rtol=1e-13, err_msg=metric)
        assert attrs == read[metric].attrs, metric
    note = arrays["raceway_equivalent_load"][2]["note"]
    if name == "spindle-misalignment-ring":
        assert note.startswith("inner race: 10/3 mean, outer race: cubic mean")
        assert arrays["reference_rating_life"][2]["note"].startswith("ISO 281 and ISO/TS 16281")
    else:
        assert note.startswith("inner race: cubic mean, outer race: 10/3 mean")


def test_radial_deep_groove_bearing_is_rated_at_its_nominal_contact_angle():
    """ISO 281 rates a radial deep-groove ball bearing at its nominal contact angle 0, not at the
    free contact angle its clearance gives (the 209: 9.86 deg). Hand-worked, ISO 281 eq. 2:
    gamma = D_w / D_pw = 12.7 / 65 = 0.195385, f_c = 59.9 (Table 1, rows 0.18 and 0.20 both 59.9;
    f_i = f_o = 0.52: no groove-radius reduction), (i cos 0)^0.7 = 1, Z^(2/3) = 9^(2/3) =
    4.326749, D_w^1.8 = 12.7^1.8 = 97.01674: C_r = 1.3 * 59.9 * 4.326749 * 97.01674 = 32 687.3 N;
    pure radial load P_r = F_r = 4 450 N: L10 = (32 687.3 / 4 450)^3 = 396.33 million rev."""
    ds = solver.solve_quasistatic("209-radial")
    assert float(ds.coords["nominal_contact_angle"]) == 0.0
    assert float(ds.coords["free_contact_angle"]) == pytest.approx(9.86, abs=0.01)
    assert float(ds.basic_load_rating) == pytest.approx(32687.3, rel=1e-5)
    assert float(ds.equivalent_load) == pytest.approx(4450.0)
    assert float(ds.basic_rating_life) == pytest.approx(396.33e6, rel=1e-4)
    # an angular contact bearing is rated at its free contact angle
    spindle = solver.solve_quasistatic("spindle-axial-preload")
    assert float(spindle.coords["nominal_contact_angle"]) == pytest.approx(15.0)
