"""Saved runs and the background dynamic run of this session.

State keys: ``runs`` (the runs folder's list, shared by every session), ``run_id`` (the saved run
on show), ``busy``, ``run_disabled``, ``progress`` (0-100), ``eta``. The run's status goes to the
session's ``status`` (ends in ``done``, ``cancelled`` or ``error: ...``).
"""

from __future__ import annotations

import asyncio
import secrets
from pathlib import Path

import numpy as np

from .. import runner as runner_module
from ..runs import describe_case, load_netcdf
from .base import Component

POLL_S = 0.2  # runner polling period


class Runs(Component):
    def __init__(self, session):
        super().__init__(session)
        self.runner = session.services.pool.runner()
        self.run_info = {}
        self._cancel_requested = False
        self._poll_task = None

    @property
    def store(self):
        return self.session.store

    def init_state(self) -> None:
        s = self.state
        s.busy = False
        s.run_disabled = True
        s.progress = 0
        s.eta = ""
        s.runs = []
        s.run_id = None
        self.refresh()

    def bind(self) -> None:
        self.state.change("run_id")(self._on_run_id)
        self.ctrl.run = self.run
        self.ctrl.cancel = self.cancel
        self.ctrl.refresh_runs = self.refresh

    # ---- saved runs -----------------------------------------------------------------------------
    def refresh(self) -> None:
        """List the runs folder in ``runs``."""
        self.state.runs = [{"title": r.label, "value": r.run_id} for r in self.store.list()]

    def _on_run_id(self, run_id=None, **_):
        if not run_id or run_id == self.session.result.shown_run_id:
            return
        try:
            ds, case_text = self.store.load(run_id)
        except (OSError, ValueError) as error:
            self.state.status = f"error: {error}"
            return
        from solver import parse_case

        self.session.form.take_case(parse_case(case_text, "the saved run's case"))
        label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
        with self.state:
            self.session.result.show_saved_run(ds, run_id, label)
            if not self.state.busy:
                self.state.status = "saved run opened: done"  # at rest the status ends in done

    # ---- the background run ---------------------------------------------------------------------
    def run(self) -> None:
        """Start the dynamic model on the current case in the background."""
        form = self.session.form
        if self.runner.busy or form.validate() is None or form.case is None:
            return
        if self.state.run_reason:  # the form says why
            return
        self.store.root.mkdir(parents=True, exist_ok=True)
        out = self.store.root / f".job-{secrets.token_hex(4)}.nc"
        case_text = form.case.to_toml()
        title = describe_case(form.case)
        self.run_info = {"case_text": case_text, "title": title, "out": out}
        self._cancel_requested = False
        self.runner.start(case_text, out, target=runner_module.DYNAMIC_JOB)
        with self.state:
            # the animation would take processor time from the solver (2 cores here): pause it
            self.state.playing = False
            self.state.busy = True
            self.state.run_disabled = True
            self.state.progress = 0
            self.state.eta = ""
            self.state.status = "running dynamic"
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            return  # tests drive poll_runner() themselves
        self._poll_task = loop.create_task(self._poll_loop())

    def cancel(self) -> None:
        """Stop the run; the part computed so far is kept and saved."""
        if not self.runner.busy:
            return
        self._cancel_requested = True
        self.state.status = "cancelling"
        self.runner.cancel()

    async def _poll_loop(self) -> None:
        while self.runner.busy or self.state.busy:
            with self.state:
                finished = self.poll_runner()
            if finished:
                return
            await asyncio.sleep(POLL_S)

    def poll_runner(self) -> bool:
        """Apply runner events to the state; True once the run has finished."""
        events = self.runner.poll()
        if not events and not self.runner.busy and self.state.busy:
            # the runner was shut down before its last event (SolverRunner.shutdown)
            self._end_run("cancelled" if self._cancel_requested else "error: the run stopped")
            return True
        for event in events:
            if event.kind == "progress":
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

    def _finish_run(self, event) -> None:
        out = Path(event.path)
        try:
            ds = load_netcdf(out)
            info = self.store.save(ds, self.run_info["case_text"], self.run_info["title"])
        except Exception as error:
            self._end_run(f"error: the result could not be saved ({error})")
            return
        finally:
            out.unlink(missing_ok=True)
        self.refresh()
        self.session.result.show_saved_run(ds, info.run_id, info.label)
        self._end_run("cancelled" if info.status == "cancelled" else "done")

    def _end_run(self, status: str) -> None:
        s = self.state
        s.busy = False
        s.run_disabled = not s.case_valid or bool(s.run_reason)
        s.eta = ""
        if status == "done":
            s.progress = 100
        s.status = status
        out = self.run_info.get("out")
        if out is not None:
            Path(out).unlink(missing_ok=True)

    def shutdown(self) -> None:
        self.session.services.pool.release(self.runner)
