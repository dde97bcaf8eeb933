"""Frame source: steady kinematics from a quasi-static result, and dynamic results by time index."""

from __future__ import annotations

import math

import numpy as np
import pytest

from viz.frames import (
    INNER,
    OUTER,
    FrameSource,
    axis_angle_matrix,
    frame_source,
    quaternion_to_matrix,
    rot_x,
)


def _omega(fm):
    return fm.SHAFT_RPM * 2 * math.pi / 60


def test_quasistatic_ball_positions_follow_cage_speed(qs_dataset, fixture_model):
    fm = fixture_model
    src = frame_source(qs_dataset, revolutions=2.0)
    assert src.model == "quasistatic"
    z = qs_dataset.sizes["ball"]
    psi0 = 2 * np.pi * np.arange(z) / z
    w_cage = fm.CAGE_RATIO * _omega(fm)
    # 2 revolutions at 72 frames per revolution
    assert src.n_frames == 2 * 72 + 1
    assert src.times[-1] == pytest.approx(2 * 2 * math.pi / _omega(fm))
    for i in (0, 7, 50, src.n_frames - 1):
        f = src.frame(i)
        psi = psi0 + w_cage * f.time
        expected = np.stack([np.full(z, 1e-5), 27e-3 * np.cos(psi), 27e-3 * np.sin(psi)], axis=1)
        np.testing.assert_allclose(f.ball_center, expected, atol=1e-9)
        np.testing.assert_allclose(f.ring_angle, [_omega(fm) * f.time, 0.0])
        assert f.cage_angle == pytest.approx(w_cage * f.time)
    np.testing.assert_allclose(
        src.frame(0).ball_center, qs_dataset["ball_center"].values, atol=1e-12
    )


def test_quasistatic_contact_is_fixed_in_the_load_zone(qs_dataset, fixture_model):
    fm = fixture_model
    src = frame_source(qs_dataset)
    z = qs_dataset.sizes["ball"]
    f = src.frame(31)
    psi = np.mod(f.ball_azimuth, 2 * np.pi)
    # Linear interpolation between balls 30 deg apart: error <= A h^2 / 8 of the cosine amplitude.
    h = 2 * np.pi / z
    for race, name in ((INNER, "inner"), (OUTER, "outer")):
        expected = fm.alpha_of_psi(psi, name)
        ok = f.loaded[:, race]
        assert ok.sum() >= z // 2
        tol = fm.ALPHA_AMPL[name] * h * h / 8 + 1e-9
        np.testing.assert_allclose(np.degrees(f.contact_angle[ok, race]), expected[ok], atol=tol)
    # unloaded contacts (load zone edge) report no load
    assert not f.loaded[np.cos(psi) < -0.9, INNER].any()


def test_quasistatic_raceway_azimuth_in_ring_frames(qs_dataset, fixture_model):
    fm = fixture_model
    src = frame_source(qs_dataset)
    f = src.frame(40)
    # inner ring turns with the shaft, outer ring is still
    np.testing.assert_allclose(f.raceway_azimuth[:, INNER], f.ball_azimuth - _omega(fm) * f.time)
    np.testing.assert_allclose(f.raceway_azimuth[:, OUTER], f.ball_azimuth)
    phi, alpha, loaded = src.trace(INNER, 41)
    assert phi.shape == alpha.shape == loaded.shape == (qs_dataset.sizes["ball"], 41)
    # over one pass the inner contact moves backwards on the inner raceway at (w_cage - w)
    slope = np.diff(phi[0]) / np.diff(src.times[:41])
    np.testing.assert_allclose(slope, (fm.CAGE_RATIO - 1) * _omega(fm), rtol=1e-9)


def test_quasistatic_ball_spin(qs_dataset, fixture_model):
    fm = fixture_model
    src = frame_source(qs_dataset, revolutions=0.01, samples_per_revolution=2000)
    f0, f1 = src.frame(0), src.frame(1)
    for r in (f0.ball_rotation, f1.ball_rotation):
        np.testing.assert_allclose(
            np.einsum("zji,zjk->zik", r, r), np.broadcast_to(np.eye(3), r.shape), atol=1e-12
        )
        np.testing.assert_allclose(np.linalg.det(r), 1.0)
    # rotation relative to the azimuth frame between the two frames: angle = |spin| dt, axis tilted
    dt = f1.time - f0.time
    rel = np.einsum(
        "ij,jk->ik",
        rot_x(-f1.ball_azimuth[3]) @ f1.ball_rotation[3],
        (rot_x(-f0.ball_azimuth[3]) @ f0.ball_rotation[3]).T,
    )
    angle = math.acos((np.trace(rel) - 1) / 2)
    assert angle == pytest.approx(abs(fm.SPIN_RATE) * dt, rel=1e-6)
    axis = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]])
    axis /= np.linalg.norm(axis) * np.sign(fm.SPIN_RATE)
    beta = math.radians(fm.SPIN_TILT_DEG)
    np.testing.assert_allclose(axis, [math.cos(beta), -math.sin(beta), 0.0], atol=1e-6)


def test_dynamic_frames_by_time_index(dynamic_dataset):
    src = frame_source(dynamic_dataset)
    assert src.model == "dynamic"
    assert src.n_frames == dynamic_dataset.sizes["time"]
    i = 17
    f = src.frame(i)
    np.testing.assert_allclose(f.ball_center, dynamic_dataset["ball_center"].isel(time=i).values)
    np.testing.assert_allclose(
        np.degrees(f.contact_angle), dynamic_dataset["contact_angle"].isel(time=i).values
    )
    # quaternion spin about +x by SPIN_RATE * t
    t = float(dynamic_dataset.time[i])
    np.testing.assert_allclose(f.ball_rotation[0], rot_x(-1200.0 * t), atol=1e-12)
    # cage angle integrates the cage speed
    w = float(dynamic_dataset["cage_speed"][0])
    assert f.cage_angle == pytest.approx(w * t)
    # unwrapped raceway azimuth is continuous
    phi, _, _ = src.trace(INNER)
    assert np.abs(np.diff(phi, axis=1)).max() < math.pi
    assert src.frame(10_000).index == src.n_frames - 1  # clipped


def test_rotation_helpers_agree():
    rng = np.random.default_rng(1)
    axis = rng.normal(size=(5, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    angle = rng.uniform(-3, 3, size=5)
    q = np.concatenate([np.cos(angle / 2)[:, None], np.sin(angle / 2)[:, None] * axis], axis=1)
    np.testing.assert_allclose(quaternion_to_matrix(q), axis_angle_matrix(axis, angle), atol=1e-12)
    np.testing.assert_allclose(axis_angle_matrix(np.array([1.0, 0, 0]), np.array(0.3)), rot_x(0.3))


def test_missing_variable_is_named(qs_dataset):
    with pytest.raises(ValueError, match="ball_angular_velocity"):
        FrameSource.from_quasistatic(qs_dataset.drop_vars("ball_angular_velocity"))


def test_quasistatic_animation_length_is_capped(qs_dataset):
    from viz.frames import QS_MAX_REVOLUTIONS, QS_SAMPLES_PER_REVOLUTION

    src = frame_source(qs_dataset, revolutions=500.0)
    assert src.n_frames == int(QS_MAX_REVOLUTIONS * QS_SAMPLES_PER_REVOLUTION) + 1
    src = frame_source(qs_dataset, revolutions=2.0)
    assert src.n_frames == int(2 * QS_SAMPLES_PER_REVOLUTION) + 1


def test_ring_speeds_come_from_the_coordinates_not_the_case_text(qs_dataset, fixture_model):
    """A result whose provenance case text says another speed is animated at its own speed."""
    from viz.frames import ring_speeds

    other = qs_dataset.assign_attrs(
        case=qs_dataset.attrs["case"].replace(f"{fixture_model.SHAFT_RPM}", "1.0")
    )
    omega = fixture_model.SHAFT_RPM * 2 * math.pi / 60
    assert ring_speeds(other) == pytest.approx((omega, 0.0))
    src = frame_source(other, revolutions=1.0)
    assert src.ring_angle[-1, 0] == pytest.approx(2 * math.pi)
    with pytest.raises(ValueError, match="inner_ring_speed"):
        ring_speeds(qs_dataset.drop_vars("inner_ring_speed"))
