"""The report's 3-D scene: the bearing scene of the drawing package (viz.scene, shared with the
app) at the last sample of a result, with the contact trajectories of the whole run painted on both
raceways.

Returns the pyvista Plotter; the page shows its render window through Panel's VTK pane (vtk.js,
turn and zoom in the browser) and a PNG of it for printing. Traces hold at most
``viz.marks.MAX_TRACE_SAMPLES`` samples per ball and race (longer runs are decimated).
"""

from __future__ import annotations

import numpy as np


def bearing_plotter(ds, size=(900, 600)):
    """(plotter, note) for result ``ds``: rings, balls, cage, contact ellipses at the last
    sample and the trajectories; ``note`` says what was decimated ("" when nothing was)."""
    from viz.offscreen import configure_environment

    configure_environment()  # before VTK opens a render window: EGL when there is no display
    import pyvista as pv

    from solver import geometry_from_result
    from viz.frames import FrameSource
    from viz.marks import MAX_TRACE_SAMPLES
    from viz.scene import BearingScene

    pv.OFF_SCREEN = True
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    geometry = geometry_from_result(ds)
    scene = BearingScene(plotter, geometry)
    if "time" in ds.dims:
        source = FrameSource.from_dynamic(ds)
    else:
        source = FrameSource.from_quasistatic(ds)
    scene.show_source(source, source.n_frames - 1)
    scene.set_camera("isometric")
    note = ""
    if source.n_frames > MAX_TRACE_SAMPLES:
        note = (
            f"3-D trajectories: {source.n_frames} samples per ball and race decimated to at most "
            f"{MAX_TRACE_SAMPLES}"
        )
    return plotter, note


def screenshot_png(plotter) -> bytes:
    """The plotter's current image as PNG bytes (for the printed page)."""
    import io

    from PIL import Image

    image = plotter.screenshot(return_img=True)
    buffer = io.BytesIO()
    Image.fromarray(np.asarray(image)).save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()
