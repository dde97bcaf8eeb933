"""Painted contact tracks: footprints against hand-computed cells, incremental = all at once,
exaggeration clipped at the shoulders, a line and a band told apart."""

from __future__ import annotations

import math

import numpy as np
import pytest

from viz.frames import FrameSource
from viz.raceway import INNER, OUTER, Groove
from viz.tracks import TrackGrid, TrackPainter, groove_surface_arrays, track_colours

GROOVE = Groove(rho_c=0.025, x_c=0.0, r=0.004, sign=1.0)  # inner-like groove, m
GRID = TrackGrid(-0.6, 0.6, n_phi=360, n_alpha=120)  # 0.01 rad per alpha cell


def _source(alpha, phi, a=4e-4, b=1e-4, p0=1.5e9, dt=1e-4):
    """A FrameSource with the given contact angles and raceway azimuths (N, Z), both races equal."""
    alpha = np.asarray(alpha, float)
    phi = np.asarray(phi, float)
    n, z = alpha.shape
    both = np.stack([alpha, alpha], axis=-1)
    contact = {
        "contact_angle": both,
        "contact_load": np.full((n, z, 2), 100.0),
        "ellipse_semi_major": np.full((n, z, 2), a),
        "ellipse_semi_minor": np.full((n, z, 2), b),
        "max_pressure": np.full((n, z, 2), p0),
    }
    eye = np.broadcast_to(np.eye(3), (n, z, 3, 3))
    return FrameSource(
        "dynamic",
        np.arange(n) * dt,
        np.zeros((n, z, 3)),
        eye,
        np.zeros((n, z)),
        np.zeros((n, 2)),
        np.zeros(n),
        contact,
        np.stack([phi, phi], axis=-1),
    )


def _painter(source, **kw):
    return TrackPainter(source, (GROOVE, GROOVE), (GRID, GRID), (0.1, 0.1), **kw)


def test_one_ellipse_paints_its_width_across_the_groove_and_its_path_around():
    n = 40
    phi = np.linspace(0.0, 0.5, n)[:, None]  # 0.0128 rad per step: ~0.73 cells of 1 deg
    src = _source(np.full((n, 1), 0.1), phi)
    painter = _painter(src)
    painter.accumulate(n)
    painted = painter.painted(INNER)
    cols = np.flatnonzero(painted.any(axis=0))
    # across: a / r = 0.1 rad each side of 0.1 rad -> alpha cells with centres in [0.0, 0.2]
    centres = GRID.alpha_lo + (cols + 0.5) * GRID.d_alpha
    assert centres.min() == pytest.approx(0.0, abs=GRID.d_alpha)
    assert centres.max() == pytest.approx(0.2, abs=GRID.d_alpha)
    # around: from 0 to 0.5 rad (+ one step at the end, and b beyond each end), nothing more
    rows = set(np.flatnonzero(painted.any(axis=1)).tolist())
    assert set(range(0, 29)) <= rows <= set(range(0, 31)) | {359}
    # peak pressure: p0 on the centre line, falling off towards the edges (Hertz profile)
    peak = painter.field(INNER, "peak_pressure")[10]
    centre_cell = int((0.1 - GRID.alpha_lo) / GRID.d_alpha)
    assert peak[centre_cell] == pytest.approx(1.5e9, rel=2e-3)
    edge = cols.max()
    assert 0.0 < peak[edge] < 0.5e9


def test_dwell_is_the_time_a_point_spends_inside_an_ellipse():
    # the ellipse moves 0.02 rad * 0.0214 m ~ 0.43 mm per 0.1 ms step: 2b / v per pass
    n = 200
    phi = (np.arange(n) * 0.02)[:, None]
    src = _source(np.full((n, 1), 0.1), phi)
    painter = _painter(src)
    painter.accumulate(n)
    dwell = painter.field(INNER, "dwell")
    centre_cell = int((0.1 - GRID.alpha_lo) / GRID.d_alpha)
    speed = 0.02 * GROOVE.contact_radius(0.1) / 1e-4  # m/s
    expected = 2 * 1e-4 / speed
    row = dwell[30:200, centre_cell]  # away from the start of the path
    assert np.median(row) == pytest.approx(expected, rel=0.15)


def test_growing_frame_by_frame_equals_painting_at_once_and_going_back_restarts():
    rng = np.random.default_rng(1)
    n, z = 60, 3
    alpha = 0.1 + 0.05 * rng.standard_normal((n, z))
    phi = np.cumsum(np.full((n, z), 0.05), axis=0) + np.arange(z) * 2.0
    src = _source(alpha, phi)
    once, steps = _painter(src), _painter(src)
    once.accumulate(n)
    for stop in range(0, n + 1, 7):
        steps.accumulate(stop)
    steps.accumulate(n)
    for q in ("dwell", "peak_pressure"):
        np.testing.assert_allclose(steps.field(OUTER, q), once.field(OUTER, q))
    steps.accumulate(10)
    ten = _painter(src)
    ten.accumulate(10)
    np.testing.assert_allclose(steps.field(INNER, "dwell"), ten.field(INNER, "dwell"))
    assert steps.field(INNER, "dwell").sum() < once.field(INNER, "dwell").sum()


def test_the_cells_painted_up_to_a_frame_are_those_first_painted_before_it():
    rng = np.random.default_rng(2)
    n, z = 50, 3
    alpha = 0.1 + 0.05 * rng.standard_normal((n, z))
    phi = np.cumsum(np.full((n, z), 0.04), axis=0) + np.arange(z) * 2.0
    src = _source(alpha, phi)
    painter = _painter(src)
    first = [painter.first_painted(race) for race in (INNER, OUTER)]
    for stop in (0, 1, 7, 23, n):
        painter.accumulate(stop)
        for race in (INNER, OUTER):
            np.testing.assert_array_equal(painter.painted(race), first[race] < stop)
    assert (first[INNER] == n).any() and (first[INNER] < n).any()  # some cells never painted


def test_exaggeration_widens_the_track_but_stays_between_the_shoulders():
    n = 400
    phi = np.linspace(0.0, 4 * math.pi, n)[:, None]
    alpha = 0.1 + 0.02 * np.sin(phi)
    plain, big = _painter(_source(alpha, phi)), _painter(_source(alpha, phi), exaggeration=40.0)
    for p in (plain, big):
        p.accumulate(n)
    spread = [np.flatnonzero(p.painted(INNER).any(axis=0)).size for p in (plain, big)]
    assert spread[1] > 3 * spread[0]
    # exaggerated 40x the centres would reach 0.1 +- 0.8 rad: clipped to the +-0.6 rad shoulders
    fp = big._footprints[INNER]
    assert fp.centre.min() >= GRID.alpha_lo and fp.centre.max() <= GRID.alpha_hi
    assert fp.i0.min() >= 0 and (fp.i0 + fp.ni).max() <= GRID.n_alpha


def test_a_line_and_a_band_are_told_apart():
    """A line: every pass at the same place across the groove. A band: passes scattered."""
    n, z = 600, 4
    phi = np.cumsum(np.full((n, z), 0.03), axis=0) + np.arange(z) * 1.5
    line = 0.1 + 0.03 * np.cos(phi)  # wanders round the raceway, same on every pass
    rng = np.random.default_rng(0)
    band = 0.1 + 0.06 * (rng.random((n, z)) - 0.5)
    widths = []
    for alpha in (line, band):
        p = _painter(_source(alpha, phi))
        p.accumulate(n)
        widths.append(np.median(p.painted(INNER).sum(axis=1)))  # cells across, per phi cell
    assert widths[1] > 1.2 * widths[0]


def test_groove_surface_lies_on_the_groove_and_addresses_the_cells_by_texture():
    grid = TrackGrid(-0.5, 0.5, n_phi=36, n_alpha=8)
    phis = np.linspace(4.0, 4.0 + np.pi, 7)  # a half shell running past phi = 2 pi
    pts, faces, tcoords = groove_surface_arrays(GROOVE, grid, phis, 5)
    quads = faces.reshape(-1, 5)
    assert quads.shape == (6 * 4, 5) and set(quads[:, 0]) == {4}
    assert quads[:, 1:].max() == len(pts) - 1
    radius = np.hypot(pts[:, 1], pts[:, 2])
    np.testing.assert_allclose(np.hypot(pts[:, 0] - GROOVE.x_c, radius - GROOVE.rho_c), GROOVE.r)
    # u: turns of phi (the texture repeats past 1); v: 0 at one shoulder, 1 at the other
    np.testing.assert_allclose(tcoords[:, 0], np.repeat(phis / (2 * np.pi), 5))
    np.testing.assert_allclose(tcoords[:, 1], np.tile(np.linspace(0, 1, 5), 7))
    # the point at phi, alpha: alpha from v over the grid's shoulders, phi from the azimuth
    alpha = grid.alpha_lo + tcoords[:, 1] * (grid.alpha_hi - grid.alpha_lo)
    np.testing.assert_allclose(pts, GROOVE.point(2 * np.pi * tcoords[:, 0], alpha), atol=1e-12)


def test_track_colours_spread_the_colour_map_over_the_range_and_mark_unpainted_cells():
    table = np.array([[0, 0, 0, 255], [100, 0, 0, 255], [200, 0, 0, 255], [255, 0, 0, 255]])
    field = np.array([[0.0, 0.3, 0.6], [0.9, 1.0, 5.0]])  # (n_phi=2, n_alpha=3)
    painted = np.array([[True, True, True], [True, True, False]])
    rgba = track_colours(field, painted, 0.0, 1.0, table, (7, 8, 9, 255))
    assert rgba.shape == (6, 4) and rgba.dtype == np.uint8
    texel = rgba.reshape(3, 2, 4)  # [alpha cell, phi cell]: phi runs fastest
    assert texel[0, 0, 0] == 0 and texel[1, 0, 0] == 100 and texel[2, 0, 0] == 200
    assert texel[0, 1, 0] == 255 and texel[1, 1, 0] == 255  # 0.9 and the top of the range
    assert texel[2, 1].tolist() == [7, 8, 9, 255]  # not run over: the ring colour


def test_unknown_quantity_is_named():
    p = _painter(_source(np.full((3, 1), 0.1), np.zeros((3, 1))))
    with pytest.raises(ValueError, match="dwell"):
        p.field(INNER, "colour")
