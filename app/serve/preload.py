"""Imported once by the session fork server (:mod:`app.serve.forkserver`) before it forks.

Imports what every session process imports, so that the forked sessions share it, and says what
it is doing meanwhile (:mod:`app.serve.preparing`: compiling the kernels on an empty cache, or
loading them). Importing only: no render window, no OpenGL context and no thread is created
here (VTK's context is made in each session, after the fork). The objects imported so far are
moved out of the garbage collector's reach (``gc.freeze``), so that its passes in the sessions do
not write to, and so copy, the pages they share.
"""

from __future__ import annotations

import gc
import logging

from app.serve.preparing import say
from viz.offscreen import configure_environment

say("importing the solver, VTK and the chart libraries")
configure_environment()  # before VTK is imported: the off-screen window type

import plotly.graph_objects  # noqa: E402, F401
import pyvista  # noqa: E402, F401
import trame_pyvista.rca_view  # noqa: E402, F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402, F401
import xarray  # noqa: E402, F401
from trame.app import get_server  # noqa: E402, F401

import app.access  # noqa: E402, F401
import app.serve.session_process  # noqa: E402, F401
import app.state  # noqa: E402, F401
import app.ui  # noqa: E402, F401
import solver  # noqa: E402
import viz.scene  # noqa: E402, F401
import viz.tracks  # noqa: E402, F401

solver.preload()


def _warm() -> None:
    """Load the compiled numba kernels a session uses at once (the quasi-static solve of the
    default case and the track painter), so the forked sessions share them too."""
    import numpy as np

    from app.compile_watch import LOADING, compiling_words, watching_compiles
    from app.state import DEFAULT_CASE
    from viz.tracks import _paint

    say(LOADING)
    with watching_compiles(lambda count: say(compiling_words(count))):
        entries = {entry.name: entry for entry in solver.catalogue()}
        if DEFAULT_CASE in entries:
            solver.solve_quasistatic(entries[DEFAULT_CASE].load())
        i, f = np.zeros(1, np.int64), np.zeros(1)
        _paint(np.zeros((1, 1)), np.zeros((1, 1)), i, i, i, i, f, f + 1.0, f, f, 0.0, 1.0, 1)
    say("starting the first session")


try:
    _warm()
except Exception as error:  # a session then loads them itself; never stop the fork server
    logging.getLogger("racetrace.front").warning("fork server warm-up skipped: %s", error)
gc.freeze()
