"""Raceway surface mapping (physics.md §2.8.1, §2.8.3) against the reference ball position."""

from __future__ import annotations

import math

import numpy as np
import pytest

from viz.raceway import INNER, OUTER, ellipse_outline, exaggerate, grooves


def test_contacts_at_free_angle_touch_the_reference_ball(geometry):
    inner, outer = grooves(geometry)
    a0 = geometry.free_contact_angle
    centre = np.array([0.0, geometry.pitch_diameter / 2, 0.0])  # ball at psi = 0, just touching
    pi = inner.point(0.0, a0)
    po = outer.point(0.0, a0)
    assert np.linalg.norm(pi - centre) == pytest.approx(geometry.ball_diameter / 2, rel=1e-12)
    assert np.linalg.norm(po - centre) == pytest.approx(geometry.ball_diameter / 2, rel=1e-12)
    # hand of the bearing: outer contact on +x, inner contact on -x, along u(alpha0)
    u = (po - pi) / np.linalg.norm(po - pi)
    np.testing.assert_allclose(u, [math.sin(a0), math.cos(a0), 0.0], atol=1e-12)


def test_points_lie_on_the_torus_and_turn_with_phi(geometry):
    for groove in grooves(geometry):
        phi = np.linspace(0, 2 * np.pi, 7)
        alpha = np.linspace(-0.5, 0.6, 7)
        p = groove.point(phi, alpha, lift=1e-5)
        radius = np.hypot(p[:, 1], p[:, 2])
        dist = np.hypot(p[:, 0] - groove.x_c, radius - groove.rho_c)
        np.testing.assert_allclose(dist, groove.r - 1e-5, rtol=1e-12)
        np.testing.assert_allclose(
            np.arctan2(p[:, 2], p[:, 1]), np.angle(np.exp(1j * phi)), atol=1e-12
        )


def test_ellipse_outline_to_scale(geometry):
    groove = grooves(geometry)[OUTER]
    a, b = 0.9e-3, 0.1e-3
    pts = ellipse_outline(groove, 0.4, 0.3, a, b, n=4)  # tau = 0, 90, 180, 270 deg
    across = np.linalg.norm(pts[0] - pts[2])  # chord of the arc 2a/r on radius r
    assert across == pytest.approx(2 * groove.r * math.sin(a / groove.r), rel=1e-12)
    along = np.linalg.norm(pts[1] - pts[3])
    rho = groove.contact_radius(0.3)
    assert along == pytest.approx(2 * rho * math.sin(b / rho), rel=1e-12)
    assert INNER == 0


def test_exaggerate():
    assert exaggerate(0.3, 0.25, 1.0) == pytest.approx(0.3)
    assert exaggerate(0.3, 0.25, 10.0) == pytest.approx(0.75)
