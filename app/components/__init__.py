"""The parts of one browser session, each with its state keys and handlers.

Every component gets the session (:class:`app.state.RacetraceApp`) and reaches the others through
it: ``session.form`` (:class:`CaseForm`), ``session.result`` (:class:`ResultView`),
``session.runs`` (:class:`Runs`), ``session.compare`` (:class:`Compare`), ``session.exports``
(:class:`Export`) and ``session.studies`` (:class:`Studies`). ``init_state`` sets the component's
state keys; ``bind`` attaches its change handlers and controller actions.
"""

from .case_form import CaseForm
from .compare import Compare
from .export import Export
from .result_view import ResultView
from .runs import Runs
from .studies import Studies

__all__ = ["CaseForm", "Compare", "Export", "ResultView", "Runs", "Studies"]
