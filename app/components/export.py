"""Export of the result on show (NetCDF, CSV) or of the 3-D view (PNG, GIF, MP4).

State keys: ``export_href``/``export_name`` (the file offered for download), ``export_message``
(progress or why it failed), ``exporting``.
"""

from __future__ import annotations

import asyncio
import os
import tempfile
import time
import urllib.parse
from pathlib import Path

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from ..paths import child_path
from .base import Component, running_loop

EXPORT_URL = "racetrace-exports"  # the exports folder is served under /racetrace-exports/
MAX_ANIMATION_FRAMES = 120
EXPORT_EXTENSIONS = {"netcdf": "nc", "csv": "csv", "png": "png", "gif": "gif", "mp4": "mp4"}
EXPORT_LABELS = {"netcdf": "NetCDF", "csv": "CSV", "png": "PNG", "gif": "GIF", "mp4": "MP4"}


class Export(Component):
    PROVIDES = ("forget_download",)

    def __init__(self, session):
        super().__init__(session)
        self.task = None  # the export running in the background, if any
        self._dir = None  # see exports_dir

    def init_state(self) -> None:
        s = self.state
        s.export_href = ""
        s.export_name = ""
        s.export_message = ""
        s.exporting = False

    def bind(self) -> None:
        self.action("export", self.request_export)

    @property
    def exports_dir(self) -> Path:
        """Where exported files are written (served under ``/racetrace-exports/``): ``.exports``
        in the runs folder, or a temporary folder when the runs folder cannot take files."""
        if self._dir is None:
            wanted = self.session.store.root / ".exports"
            try:
                wanted.mkdir(parents=True, exist_ok=True)
                writable = os.access(wanted, os.W_OK)
            except OSError:
                writable = False
            if not writable:
                wanted = Path(tempfile.mkdtemp(prefix="racetrace-exports-"))
            self._dir = wanted
        return self._dir

    def forget_download(self) -> None:
        """A new result is on show: the file offered is no longer of it."""
        s = self.state
        s.export_href, s.export_name, s.export_message = "", "", ""

    def _export_path(self, kind: str) -> Path:
        """Target file of an export of ``kind``, named after the result on show."""
        ext = EXPORT_EXTENSIONS.get(kind)
        if ext is None:
            raise ValueError(f"unknown export {kind!r}; use netcdf, csv, png, gif or mp4")
        label = str(self.state.result_label)
        stem = "".join(c if c.isalnum() else "-" for c in label)[:60].strip("-") or "racetrace"
        return child_path(self.exports_dir, f"{stem}.{ext}", "export")

    def _export_problem(self, kind: str) -> str:
        """Why ``kind`` cannot be exported now ("" if it can)."""
        result = self.session.result
        if result.dataset is None:
            return "nothing to export yet"
        if kind in ("png", "gif", "mp4") and result.scene is None:
            return "export failed: the 3-D view is not available"
        return ""

    def caption(self, index: int) -> str:
        """What an exported image says about itself: the case, its loads, the time shown."""
        result = self.session.result
        t_ms = float(result.source.times[index]) * 1e3
        return f"t = {t_ms:.3f} ms   {result.shown_title}   (racetrace)"

    def _animation_step(self) -> int:
        return max(1, -(-self.session.result.source.n_frames // MAX_ANIMATION_FRAMES))

    def _offer_download(self, path: Path) -> None:
        self.state.export_name = path.name
        self.state.export_href = f"{EXPORT_URL}/{urllib.parse.quote(path.name)}?t={time.time():.0f}"
        self.state.export_message = ""

    def export(self, kind: str) -> Path | None:
        """Write the shown result or view as ``kind`` (netcdf, csv, png, gif, mp4) now.

        Returns the file (offered for download in ``export_href``), or None with the reason in
        ``export_message``. For callers without a running event loop (scripts, tests); the page
        uses :meth:`request_export`, which keeps it responsive.
        """
        return asyncio.run(self._export_async(kind))

    def request_export(self, kind: str) -> None:
        """Export from the page: in the background, with progress in ``export_message``.

        NetCDF and CSV are written in a worker thread; an animation is rendered frame by frame
        on the event loop (VTK renders in the thread that owns its window), pausing the animation
        while it runs. Returns nothing (the page cannot receive a path).
        """
        if self.state.exporting:
            return
        loop = running_loop()
        if loop is None:
            self.export(kind)
            return
        self.task = loop.create_task(self._export_async(kind))

    async def _export_async(self, kind: str) -> Path | None:
        """The export itself (see :meth:`request_export`); returns the file or None."""
        from .. import export_files as ex

        result = self.session.result
        path = self._export_path(kind)
        problem = self._export_problem(kind)
        if problem:
            self.state.export_message = problem
            self.state.flush()
            return None
        with self.state:
            self.state.exporting = True
            self.state.export_href = ""
            self.state.export_message = f"writing {path.name} ..."
        await asyncio.sleep(0)
        dataset, label = result.dataset, self.state.result_label
        try:
            if kind == "netcdf":
                await asyncio.to_thread(ex.export_netcdf, dataset, path)
            elif kind == "csv":
                await asyncio.to_thread(ex.export_csv, dataset, path)
            elif kind == "png":
                result.sync_scene()
                ex.export_png(result.plotter, path, self.caption(result.scene.frame_index))
            else:
                await self._export_animation(ex, path)
        except (OSError, ValueError) as error:
            with self.state:
                self.state.export_message = f"export failed: {error}"
            return None
        finally:
            result.animating_export = False
            with self.state:
                self.state.exporting = False
        with self.state:
            if self.state.result_label == label:  # still the same result on show
                self._offer_download(path)
            else:
                self.state.export_message = ""
        result.push_view()
        return path

    async def _export_animation(self, ex, path: Path) -> None:
        result = self.session.result
        with self.state:
            self.state.playing = False
        result.animating_export = True  # frame changes from the page wait until it is written
        frames = ex.iter_export_animation(
            result.scene, path, step=self._animation_step(), caption=self.caption
        )
        for fraction in frames:
            with self.state:
                self.state.export_message = f"writing {path.name}: {100 * fraction:.0f} %"
            await asyncio.sleep(0)

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """``#export``: a button per kind (``#export-<kind>``), then the link to the file written
        (``#export-link``) or why it failed."""
        with v3.VRow(dense=True, align="center", id="export"):
            with v3.VCol(cols="auto"):
                html.Span("Export:", classes="text-body-2 mr-1")
                for kind, label in EXPORT_LABELS.items():
                    v3.VBtn(
                        label,
                        click=(self.ctrl.export, f"['{kind}']"),
                        size="small",
                        variant="tonal",
                        disabled=("exporting",),
                        classes="mr-1",
                        id=f"export-{kind}",
                    )
            with v3.VCol():
                html.A(
                    "download {{ export_name }}",
                    href=("export_href",),
                    download=("export_name",),
                    v_show="export_href",
                    id="export-link",
                    target="_blank",
                )
                html.Span("{{ export_message }}", classes="text-error text-caption")
