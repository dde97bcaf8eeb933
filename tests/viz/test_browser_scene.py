"""The browser's per-frame state (viz.browser_scene.BrowserScene.frame_state): its matrices and
ellipse points are exactly those that the parts' placements and the ellipses' definition give
(the frame's numbers are built in a few array operations; these are the slow, plain formulas)."""

from __future__ import annotations

import base64
import dataclasses

import numpy as np
import pytest
import pyvista as pv

from viz.browser_scene import BrowserScene, ball_group
from viz.frames import frame_source, rot_x
from viz.layout import ELLIPSE_POINTS, MARK_LIFT
from viz.marks import ellipse_points
from viz.meshes import placement
from viz.raceway import INNER, OUTER, ellipse_outline
from viz.scene import BearingScene


@pytest.fixture
def browser(dynamic_dataset, geometry):
    pv.global_theme.multi_samples = 0
    plotter = pv.Plotter(off_screen=True, window_size=(200, 150))
    scene = BearingScene(plotter, geometry)
    scene.show_source(frame_source(dynamic_dataset))
    yield BrowserScene(scene)
    plotter.close()


def _plain_matrices(browser, f) -> dict:
    """Each group's user matrix from its placement, column-major, rounded to 9 decimals."""
    layout = browser.layout
    placed = {
        "inner": placement(rot_x(f.ring_angle[INNER])),
        "outer": placement(rot_x(f.ring_angle[OUTER]), (layout.outer_shift, 0.0, 0.0)),
        "cage": placement(rot_x(f.cage_angle)),
    }
    for j in range(f.ball_center.shape[0]):
        placed[ball_group(j)] = placement(f.ball_rotation[j], f.ball_center[j])
    return {k: [round(float(v), 9) for v in m.T.ravel()] for k, m in placed.items()}


def _plain_ellipses(layout, race, f, scale) -> np.ndarray:
    """Each ellipse's centre then its outline (ellipse_outline), one contact at a time."""
    groove = layout.grooves[race]
    lift = 2 * MARK_LIFT * groove.r
    out = []
    for j in range(f.ball_center.shape[0]):
        phi = f.raceway_azimuth[j, race]
        drawn = f.loaded[j, race] and not layout.in_cutaway(race, np.array([phi]))[0]
        alpha = layout.display_alpha(
            race, np.array([f.contact_angle[j, race] if drawn else layout.reference[race]])
        )[0]
        a = float(np.nan_to_num(f.semi_major[j, race])) * scale if drawn else 0.0
        b = float(np.nan_to_num(f.semi_minor[j, race])) * scale if drawn else 0.0
        out.append(groove.point(phi, alpha, lift=lift)[None, :])
        out.append(ellipse_outline(groove, phi, alpha, a, b, n=ELLIPSE_POINTS, lift=lift))
    return np.concatenate(out)


def test_a_frames_matrices_are_the_parts_placements(browser):
    for index in (0, 7, 23):
        sent = browser.frame_state(index, 5.0)
        assert sent["index"] == index
        assert sent["m"] == _plain_matrices(browser, browser.scene.source.frame(index))
        assert list(sent["m"])[:3] == ["inner", "outer", "cage"]


def test_a_frames_ellipses_are_their_centres_and_outlines_on_the_groove(browser):
    source = browser.scene.source
    for index in (3, 17):
        f = source.frame(index)
        sent = browser.frame_state(index, 5.0)["e"]
        for race in (INNER, OUTER):
            expected = _plain_ellipses(browser.layout, race, f, 5.0)
            assert sent[race]["dtype"] == "float32"
            got = np.frombuffer(base64.b64decode(sent[race]["bvals"]), np.float32).reshape(-1, 3)
            np.testing.assert_array_equal(got, expected.astype(np.float32))


def test_a_contact_without_a_size_collapses_to_its_centre(browser):
    f = browser.scene.source.frame(9)
    semi_major = f.semi_major.copy()
    semi_major[2, INNER] = np.nan  # a contact with no size
    f = dataclasses.replace(f, semi_major=semi_major)
    points, pressure = ellipse_points(browser.layout, INNER, f, 5.0)
    np.testing.assert_array_equal(points, _plain_ellipses(browser.layout, INNER, f, 5.0))
    assert np.isfinite(points).all() and np.isfinite(pressure).all()
    ring = points[2 * (ELLIPSE_POINTS + 1) : 3 * (ELLIPSE_POINTS + 1)]
    assert np.ptp(ring[:, 0]) == 0.0  # no extent across the groove
