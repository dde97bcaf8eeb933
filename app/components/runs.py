"""Saved runs and the background dynamic run of this session.

State keys: ``runs`` (the runs folder's list, shared by every session), ``run_id`` (the saved run
on show), ``busy``, ``run_disabled``, ``progress`` (0-100), ``eta``, ``run_note`` (feedback near
Run), ``run_confirm`` (Run asks for confirmation: the result on show leaves the model's
validity). The run's status goes to the session's ``status`` (ends in ``done``, ``cancelled`` or
``error: ...``; queued runs say their place).
"""

from __future__ import annotations

import asyncio
import math
import os
import secrets
import tempfile
import time
from pathlib import Path

import numpy as np
from trame.widgets import html
from trame.widgets import vuetify3 as v3

from .. import runner as runner_module
from ..run_length import has_history
from ..run_store import describe_case, load_netcdf
from .base import Component, running_loop
from .widgets import alert, alert_list, select

POLL_S = 0.2  # runner polling period
STOP_TIMEOUT_S = 30.0  # a stopping server waits this long for the run's partial result
WATCH_S = 2.0  # runs folder check period (runs saved by other sessions)


def _title(ds, run_info: dict) -> str:
    """The run's title with the length reached (a cancelled run stops short): the revolutions of
    a steady case, the seconds of a case with a time history (``run_info["duration_s"]``)."""
    title = run_info["title"]
    if "time" not in ds.dims:
        return title
    duration = run_info.get("duration_s")
    if duration:
        reached = float(ds["time"][-1])
        if reached >= duration * 0.999:
            return title
        return title.replace(f"{duration:g} s", f"{reached:.3g} of {duration:g} s")
    planned = run_info.get("revolutions")
    if not planned:
        return title
    from solver import ring_speeds

    inner, outer = ring_speeds(ds)
    reached = float(ds["time"][-1]) * abs(inner - outer) / (2 * math.pi)
    if reached >= planned * 0.999:
        return title
    return title.replace(f"{planned:g} rev", f"{reached:.3g} of {planned:g} rev")


NOTHING_COMPUTED = "nothing computed yet, so nothing saved: cancelled"  # a run cancelled early


def _job() -> str:
    """The solver job of a run (looked up at each run, so that tests can swap it)."""
    return runner_module.DYNAMIC_JOB


class Runs(Component):
    PROVIDES = ("is_listed",)

    def __init__(self, session):
        super().__init__(session)
        self.pool = session.services.pool
        self.runner = self.pool.runner()
        self.ticket = None  # the run's place in the solver queue, or its slot while it runs
        self.run_info = {}
        self._cancel_requested = False
        self._poll_task = None
        self._watch_task = None
        self._folder_key = ()
        self._preparing = False  # before the run's first step: kernels loaded or compiled

    @property
    def store(self):
        return self.session.store

    def init_state(self) -> None:
        s = self.state
        s.busy = False
        s.run_disabled = True
        s.progress = 0
        s.eta = ""
        s.run_note = ""  # feedback near Run (e.g. to an extra press while a run is going)
        s.run_confirm = False  # Run asks: the result of this case leaves the model's validity
        s.runs = []
        s.run_id = None
        self.refresh()

    def bind(self) -> None:
        self.on_change("run_id")(self._on_run_id)
        self.action("run", self.run)
        self.action("run_anyway", self.run_anyway)
        self.action("cancel", self.cancel)
        self.action("refresh_runs", self.refresh)

    # ---- saved runs -----------------------------------------------------------------------------
    def refresh(self) -> None:
        """List the runs folder in ``runs``."""
        self._folder_key = self._folder_signature()
        self.state.runs = [{"title": r.label, "value": r.run_id} for r in self.store.list()]

    def is_listed(self, run_id) -> bool:
        """Whether ``run_id`` (as a client sent it) names a run of the folder, as the server
        lists it now (never as the page's ``runs`` says); only those are ever opened (a
        client's text never becomes a path)."""
        if not isinstance(run_id, str):
            return False
        if not any(r.run_id == run_id for r in self.store.list()):
            return False
        if all(r.get("value") != run_id for r in self.state.runs or () if isinstance(r, dict)):
            self.refresh()  # another session has just saved it: the page lists it too
        return True

    def _folder_signature(self):
        """What changes when a run is saved or removed: the folder's visible entries."""
        try:
            return tuple(sorted(e.name for e in os.scandir(self.store.root) if e.name[0] != "."))
        except OSError:
            return ()

    def watch(self) -> None:
        """Follow the runs folder (other sessions save runs there), while the loop runs."""
        if self._watch_task is None or self._watch_task.done():
            self._watch_task = asyncio.get_running_loop().create_task(self._watch_loop())

    async def _watch_loop(self) -> None:
        while True:
            await asyncio.sleep(WATCH_S)
            if self._folder_signature() != self._folder_key:
                with self.state:
                    self.refresh()

    def _on_run_id(self, run_id=None, **_):
        if not run_id or run_id == self.ctrl.shown_result().run_id:
            return
        if not self.is_listed(run_id):
            self.state.status = f"error: no run {str(run_id)[:80]!r} in the runs folder"
            return
        try:
            ds, case_text = self.store.load(run_id)
        except (OSError, ValueError) as error:
            self.state.status = f"error: {error}"
            return
        from solver import parse_case

        self.ctrl.take_case(parse_case(case_text, "the saved run's case"))
        label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
        with self.state:
            self.ctrl.show_saved_run(ds, run_id, label)
            if not self.state.busy:
                self.state.progress = 0  # the bar belongs to a run going, not to this one
                self.state.eta = ""
                self.state.status = "saved run opened: done"  # at rest the status ends in done

    # ---- the background run ---------------------------------------------------------------------
    def run(self, confirmed: bool = False) -> None:
        """Start the dynamic model on the current case in the background (or queue it for a
        solver slot, with its place shown in ``status``). When the result on show, of this very
        case, leaves the model's validity, ask first (``run_confirm``) unless ``confirmed``."""
        self.state.run_confirm = False
        if self.ticket is not None:
            self.state.run_note = "a run is already going: wait for it to end, or press Cancel"
            return
        if self.ctrl.validate_case() is None or self.ctrl.edited_case() is None:
            self.state.run_note = self.state.run_blocked
            return
        if self.state.run_reason:  # the form says why
            return
        warnings = self.state.result_warnings
        if not confirmed and warnings and not self.state.result_stale:
            self.state.run_confirm = True  # the page shows the warnings and asks
            return
        # the solver's result goes next to the runs (a stopped server's is recovered from there),
        # or to the temporary folder when the runs folder cannot take files
        folder = Path(tempfile.gettempdir()) if self.store.folder_problem() else self.store.root
        out = folder / f".job-{secrets.token_hex(4)}.nc"
        case = self.ctrl.edited_case()
        case_text = case.to_toml()
        title = describe_case(case)
        sim = getattr(case, "simulation", None)
        history = has_history(case)
        self.run_info = {
            "case_text": case_text,
            "title": title,
            "out": out,
            "revolutions": None if history else getattr(sim, "shaft_revolutions", None),
            "duration_s": getattr(sim, "duration_s", None) if history else None,
        }
        self._cancel_requested = False
        self.ctrl.drop_pending_preview()  # the run's result, not a preview on its way, is next
        self.ticket = self.pool.enqueue()
        with self.state:
            # the animation would take processor time from the solver (2 cores here): pause it
            self.state.playing = False
            self.state.busy = True
            self.state.run_disabled = True
            self.state.progress = 0
            self.state.eta = ""
            self._start_when_free()
        loop = running_loop()
        if loop is not None:  # without one, tests drive poll_runner() themselves
            self._poll_task = loop.create_task(self.poll_until_done(self.poll_runner, POLL_S))

    def run_anyway(self) -> None:
        """Run although the result on show leaves the model's validity (the user confirmed)."""
        self.run(confirmed=True)

    def _start_when_free(self) -> bool:
        """Start the queued run if a solver slot is free (True), else show its place."""
        if not self.pool.try_acquire(self.ticket):
            cap = self.pool.max_runs
            self.state.status = (
                f"queued: place {self.ticket.place + 1} in the queue for a solver "
                f"(at most {cap} run{'s' * (cap != 1)} at once)"
            )
            return False
        self.runner.start(self.run_info["case_text"], self.run_info["out"], target=_job())
        self._preparing = True  # until the first step: the solver process says what it does
        self.state.status = "running dynamic: starting the solver process"
        return True

    def cancel(self) -> None:
        """Stop the run; the part computed so far is kept and saved. A queued run is dropped."""
        if self.ticket is None:
            return
        self._cancel_requested = True
        if not self.ticket.held:
            self._end_run("cancelled")
            return
        if self._preparing:  # no step computed, and a compiling process checks no cancel event
            self.runner.stop_now()
            self._end_run(NOTHING_COMPUTED)
            return
        self.state.status = "cancelling"
        self.runner.cancel()

    def poll_runner(self) -> bool:
        """Apply runner events to the state; True once the run has finished."""
        if self.ticket is None:
            return True
        if not self.ticket.held and not self._start_when_free():
            return False
        events = self.runner.poll()
        if not events and not self.runner.busy and self.state.busy:
            # the runner was shut down before its last event (SolverRunner.shutdown)
            self._end_run("cancelled" if self._cancel_requested else "error: the run stopped")
            return True
        for event in events:
            if event.kind == "progress":
                if event.text.startswith(
                    runner_module.PREPARING
                ):  # loading or compiling the kernels
                    if self._preparing:
                        self.state.status = (
                            "running dynamic: " + event.text[len(runner_module.PREPARING) :]
                        )
                    continue
                if self._preparing and event.fraction > 0:
                    self._preparing = False  # the first step is done
                    self.state.status = "running dynamic"
                self.state.progress = round(100 * event.fraction, 1)
                if np.isfinite(event.eta_s):
                    self.state.eta = f"about {event.eta_s:.0f} s left"
            elif event.kind == "done":
                self._finish_run(event)
                return True
            elif event.kind == "error":
                status = "cancelled" if self._cancel_requested else f"error: {event.text}"
                self._end_run(status)
                return True
        return False

    def _finish_run(self, event, stopping: bool = False) -> None:
        """Save the run's result and show it. ``stopping``: the server is stopping; the partial
        run is saved (``cancelled``, its result marked incomplete, "server stopped" in its title)
        and not shown."""
        out = Path(event.path)
        try:
            ds = load_netcdf(out)
            samples = int(ds.sizes.get("time", 1))
            if samples < 2 and int(ds.attrs.get("complete", 1)) != 1:
                # stopped before a step was computed: nothing worth a run in the list
                self._end_run(NOTHING_COMPUTED)
                return
            title = _title(ds, self.run_info) + (" (server stopped)" if stopping else "")
            info = self.store.save(ds, self.run_info["case_text"], title)
        except Exception as error:
            self._end_run(f"error: the result could not be saved ({error})")
            return
        finally:
            out.unlink(missing_ok=True)
        if stopping:
            self._end_run(f"stopped with the server: saved as {info.run_id} (incomplete)")
            return
        self.refresh()
        self.ctrl.show_saved_run(ds, info.run_id, info.label)
        self._end_run("cancelled" if info.status == "cancelled" else "done")
        if not info.saved:  # kept in memory: the page says so, and offers the download
            self.state.run_note = info.problem

    def stop_and_keep(self, timeout_s: float = STOP_TIMEOUT_S) -> None:
        """The server is stopping: stop the run, save what it computed (marked incomplete) and
        end its solver process."""
        if self.ticket is None:
            return
        if not self.ticket.held:
            self._end_run("cancelled")
            return
        self._cancel_requested = True
        self.runner.cancel()
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            for event in self.runner.poll():
                if event.kind == "done":
                    self._finish_run(event, stopping=True)
                    return
                if event.kind == "error":
                    self._end_run(f"error: {event.text}")
                    return
            if not self.runner.busy:
                break
            time.sleep(0.1)
        self._end_run("error: the run did not stop in time; nothing saved")

    def _end_run(self, status: str) -> None:
        s = self.state
        s.busy = False
        s.run_disabled = not s.case_valid or bool(s.run_reason)
        s.eta = ""
        if status == "done":
            s.progress = 100
        s.status = status
        s.run_note = ""
        self.pool.drop(self.ticket)
        self.ticket = None
        out = self.run_info.get("out")
        if out is not None:
            Path(out).unlink(missing_ok=True)

    def shutdown(self) -> None:
        self.stop_and_keep()
        if self._watch_task is not None:
            self._watch_task.cancel()
        self.pool.release(self.runner)
        self.pool.drop(self.ticket)
        self.ticket = None

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """The run card: Run and Cancel with the status, what stops or questions a run, the
        warnings of the result on show, the progress bar and the saved runs."""
        ctrl = self.ctrl
        with v3.VCard(variant="outlined", classes="mb-2 pa-2"):
            _run_buttons(ctrl)
            html.Div(
                "{{ run_blocked }}",
                id="run-blocked",
                v_show="run_blocked",
                classes="text-caption text-error",
            )
            html.Div(
                "{{ run_note }}",
                id="run-note",
                v_show="run_note",
                classes="text-caption text-warning",
            )
            _run_confirm(ctrl)
            html.Div(
                "{{ run_reason }}",
                id="run-reason",
                v_show="run_reason",
                classes="text-caption text-error",
                style="white-space: pre-line",
            )
            alert_list("result_warnings", "warning", "result-warnings")
            v3.VProgressLinear(
                id="progress", model_value=("progress",), height=8, color="primary", classes="my-1"
            )
            with html.Div(id="runs-select"):
                select("Saved runs", "run_id", "runs", no_data_text="no saved runs yet")


def _run_buttons(ctrl) -> None:
    """``#run-button``, ``#cancel-button`` and the status with the time left."""
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols="auto"):
            v3.VBtn(
                "Run",
                id="run-button",
                color="primary",
                click=ctrl.run,
                disabled=("run_disabled",),
                prepend_icon="mdi-play-circle",
            )
            v3.VBtn(
                "Cancel",
                id="cancel-button",
                click=ctrl.cancel,
                disabled=("!busy",),
                classes="ml-2",
                prepend_icon="mdi-stop-circle",
            )
        with v3.VCol():
            html.Div("{{ status }}", id="status", classes="text-body-2")
            html.Div("{{ eta }}", classes="text-caption")
    html.Div("{{ run_size }}", id="run-size", v_if="run_size", classes="text-caption")


def _run_confirm(ctrl) -> None:
    """``#run-confirm``: Run asks first when the result on show leaves the model's validity."""
    with alert("warning", id="run-confirm", v_if="run_confirm"):
        html.Div(
            "The result of this case leaves the model's validity (see the warnings below). "
            "Run the dynamic model anyway?"
        )
        v3.VBtn(
            "Run anyway",
            id="run-anyway",
            click=ctrl.run_anyway,
            size="small",
            color="warning",
            classes="mt-1 mr-2",
        )
        v3.VBtn(
            "Back",
            id="run-back",
            click="run_confirm = false",
            size="small",
            variant="text",
            classes="mt-1",
        )
