"""The report's 3-D scene: the bearing scene of the drawing package (viz.scene, shared with the
app) at the last sample of a result, with the contact trajectories of the whole run painted on both
raceways.

The raceways are painted by the peak pressure of the contacts that ran over them
(:mod:`viz.tracks`). Returns the pyvista Plotter and the :class:`PressureScale` of the painting;
the page shows the render window through Panel's VTK pane (vtk.js, turn and zoom in the browser)
with the scale drawn beside it in HTML (:func:`pressure_scale_html`), and a PNG of it for printing.
Traces hold at most ``viz.marks.MAX_TRACE_SAMPLES`` samples per ball and race (longer runs are
decimated).
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import numpy as np

#: Colour stops of the HTML scale taken from the scene's lookup table.
SCALE_STOPS = 11
#: Labels along the HTML scale (both ends included).
SCALE_LABELS = 5


@dataclass(frozen=True)
class PressureScale:
    """The colour scale of the painted raceways: ``lo`` to ``hi`` in GPa, the colour map as
    ``colours`` (CSS hex strings, ``lo`` first)."""

    lo: float
    hi: float
    colours: tuple[str, ...]


def bearing_plotter(ds, size=(900, 600)):
    """(plotter, note, scale) for result ``ds``: rings, balls, cage, contact ellipses at the last
    sample, the trajectories and the raceways painted by peak pressure; ``note`` says what was
    decimated ("" when nothing was), ``scale`` is the painting's :class:`PressureScale`."""
    from viz.offscreen import configure_environment

    configure_environment()  # before VTK opens a render window: EGL when there is no display
    import pyvista as pv

    from solver import geometry_from_result
    from viz.frames import FrameSource
    from viz.marks import MAX_TRACE_SAMPLES
    from viz.options import SceneOptions
    from viz.scene import BearingScene

    pv.OFF_SCREEN = True
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    geometry = geometry_from_result(ds)
    scene = BearingScene(plotter, geometry, SceneOptions(track_quantity="peak_pressure"))
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
    return plotter, note, _pressure_scale(scene)


def _pressure_scale(scene) -> PressureScale:
    """The scene's painted-track range (GPa) and colour map, sampled at :data:`SCALE_STOPS`."""
    lo, hi = scene.track_range
    table = np.asarray(scene.tracks.actors[0].mapper.lookup_table.values, np.uint8)
    picks = np.linspace(0, table.shape[0] - 1, SCALE_STOPS).round().astype(int)
    colours = tuple("#{:02x}{:02x}{:02x}".format(*table[k, :3]) for k in picks)
    return PressureScale(float(lo), float(hi), colours)


def pressure_scale_html(scale: PressureScale) -> str:
    """A horizontal colour bar of ``scale`` with its title and :data:`SCALE_LABELS` labels in GPa;
    the ends are in ``data-lo-gpa`` and ``data-hi-gpa`` of the element of class
    ``rt-colour-scale``."""
    gradient = ", ".join(scale.colours)
    labels = "".join(
        f'<span style="position:absolute;left:{100 * k / (SCALE_LABELS - 1):g}%;'
        f'transform:translateX(-50%)">{value:.3g}</span>'
        for k, value in enumerate(np.linspace(scale.lo, scale.hi, SCALE_LABELS))
    )
    return (
        f'<div class="rt-colour-scale" data-lo-gpa="{scale.lo!r}" data-hi-gpa="{scale.hi!r}" '
        'style="width:360px;margin:6px 0 14px 12px;font-size:12px">'
        f"<div>{html.escape('raceways painted by peak contact pressure [GPa]')}</div>"
        f'<div style="height:14px;border:1px solid #888;background:linear-gradient(to right, '
        f'{gradient})"></div>'
        f'<div style="position:relative;height:16px">{labels}</div></div>'
    )


def screenshot_png(plotter) -> bytes:
    """The plotter's current image as PNG bytes (for the printed page)."""
    import io

    from PIL import Image

    image = plotter.screenshot(return_img=True)
    buffer = io.BytesIO()
    Image.fromarray(np.asarray(image)).save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()
