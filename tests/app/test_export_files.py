"""Exports: NetCDF and CSV of a result, PNG of the view, GIF/MP4 of the animation."""

from __future__ import annotations

import csv

import numpy as np
import pytest
import xarray as xr

from app.export_files import export_animation, export_csv, export_netcdf, export_png
from solver.results.io import contact_table
from viz.frames import frame_source


def test_netcdf_and_csv(tmp_path, dynamic_dataset):
    nc = export_netcdf(dynamic_dataset, tmp_path / "run.nc")
    with xr.open_dataset(nc) as back:
        np.testing.assert_allclose(
            back["contact_angle"].values, dynamic_dataset["contact_angle"].values
        )
    path = export_csv(dynamic_dataset, tmp_path / "run.csv")
    rows = list(csv.DictReader(path.open()))
    z, n = dynamic_dataset.sizes["ball"], dynamic_dataset.sizes["time"]
    assert len(rows) == z * 2 * n
    row = next(
        r
        for r in rows
        if r["ball"] == "3"
        and r["race"] == "outer"
        and float(r["time"]) == float(dynamic_dataset.time[5])
    )
    expected = float(dynamic_dataset["contact_angle"].sel(ball=3, race="outer").isel(time=5))
    assert float(row["contact_angle [degree]"]) == pytest.approx(expected)
    assert not list(tmp_path.glob(".*"))  # no temporary files left


def test_table_of_a_quasistatic_result(qs_dataset):
    table = contact_table(qs_dataset)
    assert len(table) == qs_dataset.sizes["ball"] * 2
    assert "contact_load [N]" in table.columns


def test_png_and_animation(tmp_path, qs_dataset, geometry):
    import imageio.v2 as imageio
    import pyvista as pv

    from viz.scene import BearingScene

    plotter = pv.Plotter(off_screen=True, window_size=(160, 120))
    scene = BearingScene(plotter, geometry)
    scene.show_source(frame_source(qs_dataset))
    scene.set_frame(4)
    png = export_png(plotter, tmp_path / "view.png")
    assert imageio.imread(png).shape[:2] == (120, 160)
    gif = export_animation(scene, tmp_path / "anim.gif", start=0, stop=12, step=3)
    frames = imageio.mimread(gif)
    assert len(frames) == 4
    assert np.abs(frames[0].astype(int) - frames[1].astype(int)).mean() > 0.1
    assert scene.frame_index == 4  # restored
    from PIL import Image

    with Image.open(
        gif
    ) as image:  # played at 12 frames/s: 83 ms per frame (Pillow stores 10 ms units)
        assert image.info["duration"] == pytest.approx(1000 / 12, abs=10)
    mp4 = export_animation(scene, tmp_path / "anim.mp4", stop=6)
    assert mp4.stat().st_size > 1000
    with pytest.raises(ValueError, match=".gif or .mp4"):
        export_animation(scene, tmp_path / "anim.avi")
    plotter.close()


def test_mp4_of_an_odd_sized_view_and_captions(tmp_path, qs_dataset, geometry):
    """An odd view width (a browser decides it) still gives an MP4; the caption is drawn in."""
    import imageio.v2 as imageio
    import pyvista as pv

    from app.export_files import captioned, even_sized
    from viz.scene import BearingScene

    plotter = pv.Plotter(off_screen=True, window_size=(161, 121))
    scene = BearingScene(plotter, geometry)
    scene.show_source(frame_source(qs_dataset))
    mp4 = export_animation(scene, tmp_path / "odd.mp4", stop=4, caption=lambda i: f"frame {i}")
    frames = imageio.mimread(mp4, format="FFMPEG")
    assert len(frames) == 4 and frames[0].shape[:2] == (122, 162)
    plain = tmp_path / "plain.png"
    export_png(plotter, plain)
    shown = tmp_path / "captioned.png"
    export_png(plotter, shown, caption="case X, Fa 500 N, t = 1.000 ms")
    a, b = imageio.imread(plain), imageio.imread(shown)
    assert a.shape == b.shape
    rows_changed = np.flatnonzero(np.any(a[..., :3] != b[..., :3], axis=(1, 2)))
    assert rows_changed.min() > 0.75 * a.shape[0]  # only the band along the bottom
    plotter.close()
    odd = np.zeros((5, 7, 3), np.uint8)
    assert even_sized(odd).shape == (6, 8, 3)
    assert captioned(odd, "") is odd
