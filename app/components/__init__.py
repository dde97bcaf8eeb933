"""The parts of one browser session, each with its state keys and handlers.

Each component keeps its own state keys (``init_state``), attaches its change handlers and
controller actions (``bind``) and builds its own section of the page (``build_ui`` and, for the
result view, one method per section; :mod:`app.ui` arranges them). Components reach each other
only through the state and the controller: what one offers the others it registers with
:meth:`Component.provide` (e.g. the result view's ``show_saved_run``, the case form's
``edited_case``), and the others call ``self.ctrl.<name>(...)``. The export component alone reads
the result view itself, whose renderer it draws the images with.
"""

from .case_form import CaseForm
from .compare import Compare
from .export import Export
from .live import Live
from .result_view import ResultView
from .runs import Runs
from .set_panel import SetPanel
from .studies import Studies

__all__ = [
    "CaseForm",
    "Compare",
    "Export",
    "Live",
    "ResultView",
    "Runs",
    "SetPanel",
    "Studies",
]
