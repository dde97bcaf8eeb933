"""Imported once by the session fork server (:mod:`app.services.forkserver`) before it forks.

Imports what every session process imports, so that the forked sessions share it. Importing only:
no render window, no OpenGL context and no thread is created here (VTK's context is made in each
session, after the fork). The objects imported so far are moved out of the garbage collector's
reach (``gc.freeze``), so that its passes in the sessions do not write to, and so copy, the pages
they share.
"""

from __future__ import annotations

import gc

from app.offscreen import configure_environment

configure_environment()  # before VTK is imported: the off-screen window type

import plotly.graph_objects  # noqa: E402, F401
import pyvista  # noqa: E402, F401
import trame_pyvista.rca_view  # noqa: E402, F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402, F401
import xarray  # noqa: E402, F401
from trame.app import get_server  # noqa: E402, F401

import app.access  # noqa: E402, F401
import app.scene  # noqa: E402, F401
import app.session_process  # noqa: E402, F401
import app.state  # noqa: E402, F401
import app.tracks  # noqa: E402, F401
import app.ui  # noqa: E402, F401
import solver  # noqa: E402, F401
import solver.case  # noqa: E402, F401
import solver.models.quasistatic  # noqa: E402, F401
import solver.results.checks  # noqa: E402, F401
import solver.results.dataset  # noqa: E402, F401
import solver.results.io  # noqa: E402, F401
import solver.results.summary  # noqa: E402, F401

gc.freeze()
