"""The case form: the shipped-case list, uploads, the field values and messages, and the debounced
quasi-static preview of the edited case.

State keys: ``case_items``/``case_name`` (shipped cases), ``form`` (field descriptors),
``fv_<name>`` (field text), ``fe_<name>`` (field message, "" when valid), ``fh_<name>`` (the
key's time history in words, "" for a steady key: the field then shows it read-only),
``placeholders``, ``case_message``, ``case_notice`` (a note on the case picked or uploaded, ""
when none), ``case_is_set`` (the case is a bearing set: its set fields show), ``case_valid``,
``case_toml_href``/``case_file_name`` (download of the edited case), ``run_reason`` (why the
dynamic model cannot run a valid case, "" when it can), ``run_size`` (what Run will compute:
the run length and result size), ``run_blocked`` (why Run is off while the form is invalid),
``result_stale`` (the result on show is not of the form's case), ``uploaded_case``.

A bearing set (a ``[set]`` case) opens like a single bearing: its form adds the set's fields (the
arrangement and the preload, :func:`app.case_fields.set_form_fields`) and its preview is the set's
quasi-static solution (``solver.solve``), which the result view shows bearing by bearing; Run
runs the set's dynamic model (``solver.simulate``), and says why it is off for what that model
cannot run (``run_reason``: e.g. a run too long to keep, equal ring speeds).
"""

from __future__ import annotations

import asyncio
import logging
import urllib.parse

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from ..case_fields import (
    HISTORY_HINT,
    apply_form,
    case_form_values,
    form_fields,
    form_text,
    history_texts,
    set_form_fields,
)
from ..run_length import run_size_text
from ..run_store import describe_case
from .base import Component, running_loop
from .widgets import icon_button, select

log = logging.getLogger("racetrace.app")

PREVIEW_DEBOUNCE_S = 0.1
MAX_UPLOAD_BYTES = 1024 * 1024  # an uploaded case file is at most 1 MB
_SELECT_KINDS = ("choice", "bool", "material")  # form fields shown as selects (empty = None)
SECTION_TITLES = {
    "bearing": "Bearing",
    "operating": "Speed and loads",
    "lubricant": "Lubricant",
    "cage": "Cage",
    "simulation": "Run length",
    "set": "Bearing set",
    "": "Case",
}


class CaseForm(Component):
    """The case being edited: ``base_case`` (picked, uploaded or opened) and ``case`` (the valid
    edited case, or None while the form is invalid)."""

    PROVIDES = (
        "drop_pending_preview",
        "update_staleness",
        "take_case",
        "edited_case",
        "validate_case",
    )

    def __init__(self, session):
        super().__init__(session)
        self.fields = form_fields() + set_form_fields()
        self._field_by_name = {f.name: f for f in self.fields}
        self.base_case = None
        self.case = None
        self.case_text = None  # case TOML of the valid edited case
        self._catalogue = {}
        self._filling = False
        self._preview_generation = 0
        self._case_name = None  # the shipped case last opened (None: uploaded or from a run)

    # ---- set-up ---------------------------------------------------------------------------------
    def init_state(self) -> None:
        s = self.state
        import solver

        entries = list(solver.catalogue())
        s.case_items = [{"title": _entry_title(e), "value": e.name} for e in entries]
        self._catalogue = {e.name: e for e in entries}
        s.case_name = None
        s.form = [
            {
                "name": f.name,
                "key": f.key,
                "label": f.label,
                "kind": f.kind,
                "unit": f.unit,
                "help": f.help,
                "choices": list(f.choices),
                "section": f.section,
            }
            for f in self.fields
        ]
        for f in self.fields:
            s[f"fv_{f.name}"] = ""
            s[f"fe_{f.name}"] = ""
            s[f"fh_{f.name}"] = ""
        # what an empty field means: the default the solver uses (estimated ones per case)
        s.placeholders = {f.name: f.default_text for f in self.fields}
        s.case_message = ""
        s.case_notice = ""
        s.case_is_set = False
        s.run_size = ""
        s.case_valid = False
        s.case_toml_href = ""
        s.case_file_name = "case.toml"
        s.run_reason = ""
        s.run_blocked = ""  # why Run is off because of the form ("" when valid)
        s.result_stale = False  # the result on show is not of the case in the form
        s.uploaded_case = None

    def bind(self) -> None:
        self.on_change("case_name")(self._on_case_name)
        self.on_change(*[f"fv_{f.name}" for f in self.fields])(self._on_field)
        self.on_change("uploaded_case")(self._on_upload)
        self.action("reset_case", self.reset_case)

    def first_case_name(self, case_name: str) -> str:
        """``case_name`` if it is a shipped case or catalogue bearing, else the first of those."""
        if case_name in self._catalogue:
            return case_name
        return next(iter(self._catalogue))

    def open_first(self, case_name: str) -> None:
        """Open ``case_name`` (solved now) before the first page is served; an unknown name opens
        the first shipped case."""
        opened = self.first_case_name(case_name)
        self.state.case_name = opened
        self._on_case_name(opened, synchronous=True)

    # ---- case and form --------------------------------------------------------------------------
    def _on_case_name(self, case_name=None, synchronous=False, **_):
        entry = self._catalogue.get(case_name)
        if entry is None:
            return
        self._case_name = case_name
        self.set_base_case(entry.load(), synchronous=synchronous)

    def set_base_case(self, case, synchronous: bool = False) -> None:
        """Put ``case`` in the form and preview it."""
        self.take_case(case)
        if synchronous:
            self.preview_now()
        else:
            self.schedule_preview()

    def take_case(self, case) -> None:
        """Make ``case`` the one the form edits: its values, placeholders and messages."""
        self.base_case = case
        self.state.case_notice = set_notice(case)
        self.state.case_is_set = case.bearing_set is not None
        self._fill_form(case)
        self._update_placeholders(case)
        self.validate()

    def _fill_form(self, case) -> None:
        """Put the values of ``case`` in the form without triggering a preview per field."""
        values = case_form_values(case, self.fields)
        histories = history_texts(case)
        self._filling = True
        try:
            with self.state:
                for name, value in values.items():
                    field = self._field_by_name[name]
                    empty = None if field.kind in _SELECT_KINDS else ""
                    self.state[f"fv_{name}"] = empty if value is None else form_text(value)
                    self.state[f"fe_{name}"] = ""
                    self.state[f"fh_{name}"] = histories.get(field.key, "")
        finally:
            self._filling = False

    def _update_placeholders(self, case) -> None:
        from ..case_fields import estimated_default_texts

        placeholders = {f.name: f.default_text for f in self.fields}
        try:
            placeholders.update(estimated_default_texts(case, self.fields))
        except (ValueError, ArithmeticError) as error:  # a doubtful case keeps the rules
            log.warning("no estimated defaults for this case: %s", error)
        self.state.placeholders = placeholders

    def _on_upload(self, uploaded_case=None, **_):
        if not uploaded_case:
            return
        from solver import CaseError, decode_case_bytes, parse_case

        item = uploaded_case[0] if isinstance(uploaded_case, list) else uploaded_case
        self.state.uploaded_case = None  # empty the file box, so the same file can be sent again
        if not isinstance(item, dict):
            self.state.status = "error: the upload was not a file"
            return
        name = str(item.get("name", "file"))[:200]
        content = item.get("content", b"")
        if len(content) > MAX_UPLOAD_BYTES:
            self.state.case_message = (
                f"{name}: {len(content)} bytes; a case file is at most {MAX_UPLOAD_BYTES} bytes"
            )
            self.state.status = f"error: upload refused: {name} is too large"
            return
        try:
            # the upload is case text, never a path on the server
            text = decode_case_bytes(content, name) if isinstance(content, bytes) else str(content)
            case = parse_case(text, source=f"uploaded file {name}")
        except CaseError as error:
            self.state.case_message = f"{name}: {error}"
            self.state.status = f"error: upload {name} is not a valid case (see above the form)"
            return
        self._case_name = None
        self.state.case_name = None  # picking a shipped case afterwards (even the same) reloads it
        self.set_base_case(case)

    def reset_case(self) -> None:
        """Undo the edits: the form gets the values of the case last picked, uploaded or opened."""
        entry = self._catalogue.get(self.state.case_name)
        case = entry.load() if entry is not None else self.base_case
        if case is not None:
            self.set_base_case(case)

    def form_values(self) -> dict:
        return {f.name: self.state[f"fv_{f.name}"] for f in self.fields}

    def validate(self):
        """Check the form; set field messages, ``case_valid``, ``run_disabled``; return result."""
        if self.base_case is None:
            return None
        result = apply_form(self.base_case, self.fields, self.form_values())
        with self.state:
            for f in self.fields:
                self.state[f"fe_{f.name}"] = result.errors.get(f.name, "")
            self.state.case_message = "\n".join(result.general)
            self.state.case_valid = result.valid
            self.state.run_reason = self._run_reason(result.case) if result.valid else ""
            self.state.run_size = (
                run_size_text(result.case) if result.valid and not self.state.run_reason else ""
            )
            self.state.run_disabled = (
                not result.valid or bool(self.state.run_reason) or self.state.busy
            )
        self.case = result.case if result.valid else None
        self.case_text = self.case.to_toml() if self.case is not None else None
        self.state.run_blocked = self._blocked_reason(result)
        self.update_staleness()
        if self.case is not None:
            download = self._download_case(self.case)
            self.state.case_toml_href = "data:application/toml;charset=utf-8," + urllib.parse.quote(
                download.to_toml()
            )
            self.state.case_file_name = _file_name(describe_case(self.case)) + ".toml"
        return result

    def _download_case(self, case):
        """The edited case as offered for download: a title left as the picked case had it, but
        with other values edited, no longer describes it; it is then rewritten from the values."""
        import dataclasses

        base = self.base_case
        if base is None or case.title != base.title:
            return case  # the user's own title
        if dataclasses.replace(case, title=None) == dataclasses.replace(base, title=None):
            return case  # not edited
        return dataclasses.replace(case, title=describe_case(case))

    def _blocked_reason(self, result) -> str:
        """Why Run is off because of the form ("" when the form is valid)."""
        if result.valid:
            return ""
        labels = [f.label for f in self.fields if result.errors.get(f.name)]
        if labels:
            shown = ", ".join(labels[:4]) + (
                f" and {len(labels) - 4} more" if len(labels) > 4 else ""
            )
            return f"Run is off until the form is fixed: {shown}"
        return "Run is off until the case is fixed (see the message above the form)"

    def edited_case(self):
        """The valid edited case, or None while the form is invalid."""
        return self.case

    def validate_case(self):
        """:meth:`validate` (for the other components)."""
        return self.validate()

    def update_staleness(self) -> None:
        """``result_stale``: the result on show is not of the case in the form (edited, or the
        form is invalid)."""
        shown = self.ctrl.shown_result().case_text
        self.state.result_stale = shown is not None and self.case_text != shown

    @staticmethod
    def _run_reason(case) -> str:
        """Why the dynamic model cannot run the valid ``case`` ("" when it can)."""
        from solver import dynamic_problems

        return "\n".join(f"dynamic model: {p.message}" for p in dynamic_problems(case))

    def _on_field(self, **_):
        if self._filling:
            return
        if self.validate() is not None and self.case is not None:
            if self.case_text == self.ctrl.shown_result().case_text:
                return  # the result on show is already this case (e.g. a reopened run)
            self.schedule_preview()

    # ---- quasi-static preview -------------------------------------------------------------------
    def drop_pending_preview(self) -> None:
        """A preview still on its way must not replace what is about to be shown."""
        self._preview_generation += 1

    def schedule_preview(self) -> None:
        """Recompute the quasi-static preview soon (debounced) without blocking the page."""
        self._preview_generation += 1
        generation = self._preview_generation
        loop = running_loop()
        if loop is None:
            self.preview_now()
            return
        if not self.state.busy:
            self.state.status = "updating preview"
        loop.create_task(self._preview_async(generation))

    async def _preview_async(self, generation: int) -> None:
        await asyncio.sleep(PREVIEW_DEBOUNCE_S)
        if generation != self._preview_generation or self.case is None:
            return
        case = self.case
        try:
            ds = await asyncio.to_thread(solve_preview, case)
        except Exception as error:  # shown in words in the status line
            if not self.state.busy:
                with self.state:
                    self.state.status = f"error: {error}"
            return
        if generation == self._preview_generation:
            with self.state:
                self.ctrl.show_preview(ds)
                if not self.state.busy:  # a run's status stays until it ends
                    self.state.status = "preview done"

    def preview_now(self) -> None:
        """Solve the quasi-static model for the current case now and show it."""
        if self.case is None:
            return
        try:
            ds = solve_preview(self.case)
        except Exception as error:
            self.state.status = f"error: {error}"
            return
        self.ctrl.show_preview(ds)
        self.state.status = "preview done"

    # ---- page -----------------------------------------------------------------------------------
    def build_toolbar(self) -> None:
        """Toolbar chip ``#result-stale``: the result on show is not of the case in the form."""
        v3.VChip(
            "out of date: the form has changed",
            id="result-stale",
            v_show="result_stale",
            color="warning",
            size="small",
            classes="mr-2",
            title="The result on show is not of the case in the form",
        )

    def build_ui(self) -> None:
        """The drawer: the case picker, upload and download, then one field per case input under
        its section's title."""
        with html.Div(classes="pa-3"):
            _case_choice(self.ctrl)
            _case_files()
            html.Div("{{ case_message }}", classes="text-error text-caption", id="case-message")
            html.Div(
                "{{ case_notice }}",
                v_if="case_notice",
                classes="text-warning text-caption",
                id="case-notice",
            )
            section = None
            for f in self.fields:
                shown = "case_is_set" if f.section == "set" else None  # set fields: sets only
                if f.section != section:
                    section = f.section
                    html.Div(
                        SECTION_TITLES.get(section, section.title()),
                        classes="text-subtitle-2 mt-3 mb-1",
                        v_if=shown,
                    )
                _field(f, shown)


def _case_choice(ctrl) -> None:
    """``#case-select`` (shipped cases and catalogue bearings) and ``#case-reset``."""
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(), html.Div(id="case-select"):
            select("Shipped case or catalogue bearing", "case_name", "case_items")
        with v3.VCol(cols="auto"):
            icon_button(
                "mdi-restore",
                ctrl.reset_case,
                "case-reset",
                title="Undo the edits: back to the values of the chosen case",
            )


def _case_files() -> None:
    """``#case-upload`` (a case file from the computer) and ``#case-download`` (the edited case)."""
    with v3.VRow(classes="my-1", dense=True):
        with v3.VCol():
            v3.VFileInput(
                label="Upload a case (.toml)",
                v_model=("uploaded_case",),
                accept=".toml",
                density="compact",
                hide_details=True,
                id="case-upload",
            )
        with v3.VCol(cols="auto"):
            # a plain link: Vuetify's button drops the download attribute
            with html.A(
                href=("case_valid ? case_toml_href : undefined",),
                download=("case_file_name",),
                id="case-download",
                title="Download the case as a TOML case file",
                classes=(
                    "case_valid ? 'v-btn v-btn--size-small v-btn--variant-tonal pa-2'"
                    " : 'v-btn v-btn--size-small v-btn--disabled pa-2'",
                ),
                style="text-decoration: none;",
            ):
                v3.VIcon("mdi-download", size="small")
                html.Span("TOML")


def _field(f, shown: str | None = None) -> None:
    """One case input wrapped in ``div#field-<name>`` with its message inside; ``shown``: the
    condition (a state expression) under which it is on the page (None: always)."""
    tooltip = f.help.replace('"', "'")  # the help text is shown as a tooltip
    with html.Div(id=f"field-{f.name}", classes="mb-1", title=tooltip, v_if=shown):
        common = dict(
            label=f.label,
            v_model=(f"fv_{f.name}",),
            density="compact",
            placeholder=(f"placeholders.{f.name}",),  # the default used when left empty
            persistent_placeholder=bool(f.default_text),
        )
        if f.kind in _SELECT_KINDS:
            # Vuetify's select fails on error-messages here: the message goes in a div below.
            items = ["true", "false"] if f.kind == "bool" else list(f.choices)
            widget = v3.VCombobox if f.kind == "material" else v3.VSelect
            # a plain list would be read by trame as (state name, default): pass a JS literal
            literal = "[" + ", ".join("'" + str(c).replace("'", "\\'") + "'" for c in items) + "]"
            widget(items=(literal,), hide_details=True, error=(f"!!fe_{f.name}",), **common)
            html.Div(
                f"{{{{ fe_{f.name} }}}}",
                v_if=f"fe_{f.name}",
                classes="text-error text-caption px-3",
            )
        else:
            # a key given as a time history shows the history in words, read-only
            v3.VTextField(
                error_messages=(f"fe_{f.name} ? [fe_{f.name}] : []",),
                hide_details="auto",
                readonly=(f"!!fh_{f.name}",),
                hint=(f"fh_{f.name} ? '{HISTORY_HINT}' : ''",),
                persistent_hint=(f"!!fh_{f.name}",),
                **common,
            )


def set_notice(case) -> str:
    """The note above the form for a bearing set ``case`` ("" for a single bearing): what the
    set is and what the app shows of it."""
    if case.bearing_set is None:
        return ""
    return (
        f"bearing set: {case.bearing_set.describe()}. The preview is the set's quasi-static "
        "solution; Run runs the set's dynamic model (every bearing on one rigid shaft); choose "
        "the bearing the 3-D view and charts show under 'Bearing set'."
    )


def _entry_title(entry) -> str:
    """The case picker's title of a catalogue entry; a bearing set says so."""
    if entry.kind == "case" and entry.load().bearing_set is not None:
        return f"{entry.title} (bearing set)"
    return f"{entry.title} ({entry.kind})"


def _file_name(text: str) -> str:
    """``text`` as a file name stem: letters and digits, runs of anything else as one dash."""
    stem = "".join(c if c.isalnum() else "-" for c in text)
    while "--" in stem:
        stem = stem.replace("--", "-")
    return stem.strip("-")[:80] or "case"


def solve_preview(case):
    """The preview of ``case``: the quasi-static answer (``solver.solve``): for a bearing set the
    set's solution (a ``bearing`` dimension); for one bearing the snapshot, or, for a
    misalignment turning with the inner ring, the solutions over one revolution, since a t = 0
    snapshot would show a band where the run draws a line and the reverse."""
    import solver

    return solver.solve(case)
