"""The 3-D scene: actors follow the frame source, traces lie on the raceways, frames differ."""

from __future__ import annotations

import numpy as np
import pytest
import pyvista as pv

from viz.frames import frame_source, rot_x
from viz.raceway import INNER, OUTER, grooves
from viz.scene import BearingScene


@pytest.fixture
def scene(qs_dataset, geometry):
    pv.global_theme.multi_samples = 0
    plotter = pv.Plotter(off_screen=True, window_size=(320, 240))
    s = BearingScene(plotter, geometry)
    s.show_source(frame_source(qs_dataset))
    s.set_layer("traces", True)  # off by default: the painted tracks show the paths
    yield s
    plotter.close()


def test_actors_follow_the_frame(scene):
    scene.set_frame(23)
    f = scene.source.frame(23)
    for j in (0, 5):
        m = np.asarray(scene.actors["balls"][j].user_matrix)
        np.testing.assert_allclose(m[:3, 3], f.ball_center[j])
        np.testing.assert_allclose(m[:3, :3], f.ball_rotation[j])
    ring = np.asarray(scene.actors["inner_ring"][0].user_matrix)
    np.testing.assert_allclose(ring[:3, :3], rot_x(f.ring_angle[INNER]), atol=1e-12)


def test_traces_lie_on_their_raceways(scene, geometry):
    scene.set_frame(60)
    for race in (INNER, OUTER):
        groove = grooves(geometry)[race]
        pts = scene.marks.traces[race].points  # ring frame (the actor carries the ring rotation)
        assert len(pts) > 10
        radius = np.hypot(pts[:, 1], pts[:, 2])
        dist = np.hypot(pts[:, 0] - groove.x_c, radius - groove.rho_c)
        np.testing.assert_allclose(dist, groove.r, rtol=0.02)
    # the inner trace grows with time; one chosen ball draws only its own trace
    n60 = scene.trace_point_count(INNER)
    scene.set_frame(120)
    assert scene.trace_point_count(INNER) > n60
    scene.set_trace_ball(3)
    assert set(np.unique(scene.marks.traces[INNER].point_data["ball"])) == {3.0}


def test_exaggeration_moves_traces_across_the_groove(scene):
    scene.set_frame(100)
    x1 = scene.marks.traces[INNER].points[:, 0].copy()
    scene.set_exaggeration(10.0)
    x10 = scene.marks.traces[INNER].points[:, 0]
    assert np.ptp(x10) > 5 * np.ptp(x1)


def test_rendered_frames_change(scene):
    p = scene.plotter
    scene.set_frame(0)
    p.render()
    a = p.screenshot(return_img=True).astype(int)
    scene.set_frame(9)
    p.render()
    b = p.screenshot(return_img=True).astype(int)
    assert a.shape == (240, 320, 3)
    assert np.abs(a - b).mean() > 0.5


def test_bad_options_are_named(scene):
    with pytest.raises(ValueError, match="layers are"):
        scene.set_layer("bogus", True)
    with pytest.raises(ValueError, match="isometric"):
        scene.set_camera("top")
    scene.set_layer("cage", False)
    assert not scene.actors["cage"][0].visibility


def test_no_outer_marks_in_the_cut_away_sector(scene):
    scene.set_frame(100)
    lo, hi = scene.options.outer_cutaway
    pts = scene.marks.traces[OUTER].points
    phi = np.arctan2(pts[:, 2], pts[:, 1])
    assert len(pts) > 10
    assert not np.any(np.mod(phi - lo, 2 * np.pi) < (hi - lo) - 1e-9)
    # the inner ring has no cut: its trace goes all the way round
    inner = scene.marks.traces[INNER].points
    assert np.ptp(np.mod(np.arctan2(inner[:, 2], inner[:, 1]) - lo, 2 * np.pi)) > 6.0


# ---- camera presets, colour bar, see-through balls ----------------------------------------------
def _display_xy(plotter, points):
    """Display coordinates (pixels, origin bottom left) of world ``points`` (m)."""
    renderer = plotter.renderer
    out = []
    for p in points:
        renderer.SetWorldPoint(*p, 1.0)
        renderer.WorldToDisplay()
        out.append(renderer.GetDisplayPoint()[:2])
    return np.array(out)


def _bearing_points(geometry):
    """Corners of the bearing drawn whole: circles at the outer ring's outside radius (a closed
    form from the geometry: pitch radius + ball radius + 0.45 D of material, :func:`ring_profile`)
    at both faces (x = +-0.95 D)."""
    D = geometry.ball_diameter
    radius = 0.5 * geometry.pitch_diameter + 0.5 * D
    phi = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    return np.concatenate(
        [
            np.column_stack([np.full(90, x), radius * np.cos(phi), radius * np.sin(phi)])
            for x in (-0.95 * D, 0.95 * D)
        ]
    )


@pytest.mark.parametrize("preset", ["isometric", "axial", "radial"])
def test_presets_frame_the_whole_bearing_left_of_the_colour_bar(geometry, preset):
    pv.global_theme.multi_samples = 0
    plotter = pv.Plotter(off_screen=True, window_size=(650, 480))
    try:
        from viz.scene import SceneOptions

        scene = BearingScene(plotter, geometry, SceneOptions(explode=0.0))  # drawn assembled
        scene.set_camera(preset)
        plotter.render()
        xy = _display_xy(plotter, _bearing_points(geometry))
        bar_left = plotter.scalar_bar.GetPositionCoordinate().GetValue()[0] * 650
        assert xy[:, 0].min() > 5 and xy[:, 1].min() > 5 and xy[:, 1].max() < 475
        assert xy[:, 0].max() < bar_left  # the colour bar stands beside the bearing
        # and the bearing fills the view: not a small picture in the middle
        assert max(np.ptp(xy[:, 0]) / bar_left, np.ptp(xy[:, 1]) / 480) > 0.8
    finally:
        plotter.close()


def test_set_camera_reapplies_the_current_preset(scene):
    scene.set_camera("radial")
    expected = np.array(scene.plotter.camera_position.position)
    scene.plotter.camera.azimuth = 40.0
    scene.plotter.camera.zoom(2.0)
    scene.set_camera("radial")
    np.testing.assert_allclose(scene.plotter.camera_position.position, expected)


def test_colour_bar_is_vertical_and_its_title_clear_of_the_labels(scene):
    bar = scene.plotter.scalar_bar
    assert bar.GetOrientation() == 1  # vertical
    assert bar.GetVerticalTitleSeparation() >= 5


def test_balls_are_see_through_by_default_with_an_opaque_option(qs_dataset, geometry):
    from viz.scene import SceneOptions

    pv.global_theme.multi_samples = 0
    for translucent in (True, False):
        plotter = pv.Plotter(off_screen=True, window_size=(160, 120))
        scene = BearingScene(plotter, geometry, SceneOptions(translucent_balls=translucent))
        alpha = np.array(scene.actors["balls"][0].mapper.lookup_table.values)[:, 3]
        if translucent:  # plain octants nearly clear, marked ones darker and denser
            assert alpha[0] < 80 and 80 < alpha[1] < 255
        else:
            assert np.all(alpha == 255)
        plotter.close()


def test_ellipses_are_outlined_to_scale(scene, geometry):
    scene.set_frame(5)
    mesh = scene.marks.ellipses[INNER]
    assert mesh.n_lines == geometry.ball_count  # one closed outline per ball
    f = scene.source.frame(5)
    j = int(np.argmax(f.semi_major[:, INNER]))
    outline = mesh.points[j * 25 + 1 : (j + 1) * 25]  # the fan's centre comes first
    across = np.ptp(outline[:, 0]) / np.cos(f.contact_angle[j, INNER])
    assert across == pytest.approx(2 * f.semi_major[j, INNER], rel=0.05)


def test_close_up_shows_one_balls_pressure_domes_and_recent_paths(scene, geometry):
    f = scene.source.frame(40)
    j = int(np.argmax(np.nan_to_num(f.contact_load[:, INNER])))  # a loaded ball
    scene.set_closeup_ball(j)
    scene.set_frame(40)
    scene.set_camera("close-up")
    assert scene.closeup.on and all(a.visibility for a in scene.closeup.actors[:2])
    assert [a.visibility for a in scene.actors["balls"]] == [
        k == j for k in range(geometry.ball_count)
    ]
    for race in (INNER, OUTER):
        dome = scene.closeup.domes[race]
        p = dome.point_data["pressure_GPa"]
        assert p.max() == pytest.approx(f.max_pressure[j, race] * 1e-9, rel=1e-6)
        # the dome stands on the groove (ring frame): its rim on the raceway, its top lifted
        groove = grooves(geometry)[race]
        pts = dome.points
        radius = np.hypot(pts[:, 1], pts[:, 2])
        off = groove.r - np.hypot(pts[:, 0] - groove.x_c, radius - groove.rho_c)
        rim, top = off[p < 1e-6 * p.max() + 1e-12], off[p == p.max()]
        assert rim.max() < 0.02 * groove.r
        assert top.min() == pytest.approx(
            0.6 * f.semi_major[j, race] + 2 * 0.004 * groove.r, rel=0.05
        )
        assert scene.closeup.paths[race].n_points > 10  # the recent path of its centre
    # the camera looks at that ball
    focal = np.array(scene.plotter.camera_position.focal_point)
    assert np.linalg.norm(focal - f.ball_center[j]) < geometry.ball_diameter
    scene.set_camera("isometric")
    assert not any(a.visibility for a in scene.closeup.actors)
    assert all(a.visibility for a in scene.actors["balls"])


def test_tracks_coloured_by_peak_pressure_name_it_on_the_colour_bar(scene):
    scene.set_track_options(quantity="peak_pressure", whole_run=True)
    assert "pressure" in scene.plotter.scalar_bar.GetTitle()
    lo, hi = scene.track_range
    f = scene.source
    assert hi == pytest.approx(np.nanmax(f.contact["max_pressure"]) * 1e-9, rel=0.02)
    assert 0 < lo < hi
    with pytest.raises(ValueError, match="dwell"):
        scene.set_track_options(quantity="colour")


def _track_pixels(scene, race: int) -> int:
    """Pixels the painted track of ``race`` colours: the image with it minus the image without."""
    p = scene.plotter
    p.render()
    shown = p.screenshot(return_img=True).astype(int)
    scene.actors["tracks"][race].visibility = False
    p.render()
    hidden = p.screenshot(return_img=True).astype(int)
    scene.actors["tracks"][race].visibility = True
    return int((np.abs(shown - hidden).sum(axis=2) > 60).sum())


@pytest.mark.parametrize(
    "preset, races",
    [
        ("isometric", (INNER, OUTER)),  # the default: both tracks
        ("radial", (INNER, OUTER)),
        ("axial", (INNER,)),
        ("inner track", (INNER,)),
        ("outer track", (OUTER,)),
        ("close-up", (INNER,)),
    ],
)
def test_camera_presets_show_painted_tracks(scene, preset, races):
    scene.set_layer("traces", False)
    scene.set_track_options(whole_run=True)
    scene.set_camera(preset)
    for race in races:
        assert _track_pixels(scene, race) > 40, (preset, race)


def test_exaggerated_marks_stay_on_the_groove_between_the_shoulders(scene, geometry):
    scene.set_exaggeration(30.0)
    scene.set_frame(150)
    for race in (INNER, OUTER):
        groove, grid = grooves(geometry)[race], scene.grids[race]
        pts = scene.marks.traces[race].points
        assert len(pts) > 10
        radius = np.hypot(pts[:, 1], pts[:, 2])
        distance = np.hypot(pts[:, 0] - groove.x_c, radius - groove.rho_c)  # marks are lifted
        np.testing.assert_allclose(distance, groove.r, rtol=0.01)
        # latitude of each point on the groove: within the shoulder edges
        alpha = np.arcsin(np.clip(-(pts[:, 0] - groove.x_c) / (groove.sign * distance), -1, 1))
        assert alpha.min() >= grid.alpha_lo - 1e-3 and alpha.max() <= grid.alpha_hi + 1e-3
        if race == INNER:  # 30x the fixture's +-3 deg reaches the shoulder: clipped there
            assert np.isclose(np.abs(alpha).max(), grid.alpha_hi, atol=2e-3)


def test_scene_lighting_is_cheap_for_software_rendering(scene):
    """Few camera lights and no order-independent translucency: each costs every pixel a frame."""
    from viz.scene import LIGHTS

    renderer = scene.plotter.renderer
    assert renderer.GetLights().GetNumberOfItems() == len(LIGHTS) <= 3
    assert not renderer.GetUseOIT()
    # the painted tracks are drawn before the rings, so the groove under them is not shaded
    props = list(renderer.GetViewProps())
    tracks = [props.index(a) for a in scene.actors["tracks"]]
    rings = [props.index(a) for a in scene.actors["inner_ring"] + scene.actors["outer_ring"]]
    assert max(tracks) < min(rings)


def test_each_ball_is_marked_in_its_legend_colour(scene, geometry):
    from viz.palette import ball_colours

    colours = ball_colours(geometry.ball_count)
    for actor, colour in zip(scene.actors["balls"], colours, strict=True):
        marked = np.array(actor.mapper.lookup_table.values)[-1, :3]
        expected = [int(colour[k : k + 2], 16) for k in (1, 3, 5)]
        assert np.allclose(marked, expected, atol=2), (marked, colour)


def _facts(outer_ring_speed: float = 0.0):
    """The operating point the teaching overlay reads (as the app's ``Facts``)."""
    from types import SimpleNamespace

    return SimpleNamespace(
        inner_ring_speed=2000.0,
        outer_ring_speed=outer_ring_speed,
        radial_load=300.0,
        radial_load_angle=0.0,
        misalignment=0.0,
        misalignment_axis=0.0,
        misalignment_turns=False,
    )


def test_legend_names_the_ellipse_scale_and_follows_it(qs_dataset, geometry):
    from viz.scene import SceneOptions

    plotter = pv.Plotter(off_screen=True, window_size=(320, 240))
    try:
        scene = BearingScene(plotter, geometry, SceneOptions(ellipse_scale=5.0))
        scene.show_source(frame_source(qs_dataset))
        scene.show_facts(_facts())
        assert scene.overlay.legend_words()[0] == "contact ellipses now ×5"
        scene.set_ellipse_scale(3.0)
        assert scene.overlay.legend_words()[0] == "contact ellipses now ×3"
        scene.set_ellipse_scale(1.0)
        assert scene.overlay.legend_words()[0] == "contact ellipses now (to scale)"
    finally:
        plotter.close()


def test_painted_tracks_stay_at_true_size_when_the_ellipses_are_enlarged(scene):
    scene.set_track_options(whole_run=True)
    true_size = [scene.tracks.painter.painted(race).sum() for race in (INNER, OUTER)]
    scene.set_ellipse_scale(5.0)
    assert scene.options.ellipse_scale == 5.0
    assert [scene.tracks.painter.painted(race).sum() for race in (INNER, OUTER)] == true_size


def test_raceway_labels_say_which_ring_is_fixed():
    from viz.overlay import ring_words

    inner, outer = ring_words(_facts(outer_ring_speed=0.0))
    assert "turning" in inner and "shaft" in inner
    assert "fixed" in outer and "housing" in outer
    assert "turning" in ring_words(_facts(outer_ring_speed=100.0))[1]


def test_inner_track_preset_shows_the_track_without_balls_and_cage(scene):
    scene.set_camera("inner track")
    scene.set_frame(3)
    assert not any(a.visibility for a in scene.actors["balls"] + scene.actors["cage"])
    scene.set_camera("isometric")
    scene.set_frame(4)
    assert all(a.visibility for a in scene.actors["balls"] + scene.actors["cage"])


def test_outer_track_preset_shows_the_opened_outer_ring_whole(geometry):
    """The far half of the outer ring, both faces at its largest radius, is in the view (left of
    the colour bar), its raceway in the middle."""
    import math

    from viz.camera import track_points
    from viz.raceway import OUTER

    pv.global_theme.multi_samples = 0
    plotter = pv.Plotter(off_screen=True, window_size=(650, 480))
    try:
        scene = BearingScene(plotter, geometry)
        scene.set_camera("outer track")
        plotter.render()
        layout = scene.layout
        x, radius = layout.profiles[OUTER]
        phi = math.pi + np.linspace(-0.5 * math.pi, 0.5 * math.pi, 19)
        r = float(np.max(radius))
        ring = np.concatenate(
            [
                np.column_stack([np.full(19, face + layout.outer_shift), r * np.cos(phi),
                                 r * np.sin(phi)])
                for face in (float(np.min(x)), float(np.max(x)))
            ]
        )  # fmt: skip
        xy = _display_xy(plotter, ring)
        bar_left = plotter.scalar_bar.GetPositionCoordinate().GetValue()[0] * 650
        assert xy[:, 0].min() > 0 and xy[:, 0].max() < bar_left
        assert xy[:, 1].min() > 0 and xy[:, 1].max() < 480
        track = _display_xy(plotter, track_points(layout, OUTER, 0.0)[:74])  # the shoulder edges
        middle = 0.5 * (track[:, 1].min() + track[:, 1].max())
        assert 0.25 * 480 < middle < 0.75 * 480
    finally:
        plotter.close()
