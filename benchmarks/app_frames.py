"""Measure the browser app's responsiveness and memory (run by hand, not in CI).

    python benchmarks/app_frames.py [--runs-dir DIR] [--run FILE.nc] [--loads N]

Starts ``racetrace serve`` on a free port and drives headless Chromium (/usr/bin/chromium):
- first 3-D frame: seconds from navigation start to the first image in #view-3d, timed in the page
  (the first, cold load and the median of ``--loads`` loads);
- frames shown while playing: distinct images received by #view-3d per second over 8 s;
- quasi-static preview refresh: seconds from a field edit (axial load) until the browser has the
  new result (state ``result_serial`` advanced; includes the 0.1 s debounce);
- server memory: proportional set size of the server's processes (front, sessions) after loading a
  real dynamic run of 100 shaft revolutions of the default case (computed first unless
  ``--run FILE`` gives one); with two sessions holding it, each process's share and role (front,
  fork server, sessions).
"""

from __future__ import annotations

import argparse
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

# run as a script, sys.path[0] is benchmarks/: put the repository first for ``tools``
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tools.chromium import CHROMIUM, LAUNCH_ARGS  # noqa: E402


def real_run(runs_dir: Path, run_file: Path | None, revolutions: int = 100):
    """Save a dynamic run of ``revolutions`` shaft revolutions of the default case in ``runs_dir``.

    ``run_file``: an existing NetCDF result (from ``racetrace simulate``); otherwise one is computed
    now with ``racetrace simulate spindle-combined-load --revolutions 100`` (about a minute).
    """
    from app.run_store import RunStore
    from solver import load_dataset

    if run_file is None:
        run_file = runs_dir / "spindle-100-revolutions.nc.src"
        t0 = time.monotonic()
        subprocess.run(
            [
                sys.executable,
                "-m",
                "racetrace",
                "simulate",
                "spindle-combined-load",
                "--revolutions",
                str(revolutions),
                "--quiet",
                "--output",
                str(run_file),
            ],
            check=True,
        )
        print(f"computed the {revolutions}-revolution run in {time.monotonic() - t0:.0f} s")
    ds = load_dataset(run_file)
    size = run_file.stat().st_size / 1e6
    print(f"run: {ds.sizes['time']} samples, {size:.0f} MB NetCDF")
    info = RunStore(runs_dir).save(ds, ds.attrs["case"], f"{revolutions}-revolution spindle run")
    ds.close()
    return info


CHARTS_READY = "window.racetrace_charts && window.racetrace_charts.ready"

# Set before the page's own scripts run: the page time (ms from navigation start) at which
# #view-3d first received an image.
FIRST_FRAME_PROBE = """
new MutationObserver((_, observer) => {
  const img = document.querySelector('#view-3d img[src]');
  if (img && img.getAttribute('src')) {
    window.__firstFrameMs = performance.now();
    observer.disconnect();
  }
}).observe(document, {subtree: true, childList: true, attributes: true,
                      attributeFilter: ['src']});
"""


def _tree(pid: int) -> list[int]:
    """``pid`` and every process below it (the front, its session processes, their solvers)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except OSError:
                continue
            children.setdefault(ppid, []).append(int(entry.name))
    found, todo = [pid], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def rss_mb(pid: int) -> float:
    """Memory of the server: proportional set size (shared pages split between the processes that
    share them; resident size where the kernel gives no PSS) summed over the process tree."""
    total = 0.0
    for p in _tree(pid):
        try:
            rollup = Path(f"/proc/{p}/smaps_rollup").read_text().splitlines()
            key = "Pss:"
        except OSError:
            try:
                rollup = Path(f"/proc/{p}/status").read_text().splitlines()
                key = "VmRSS:"
            except OSError:
                continue
        for line in rollup:
            if line.startswith(key):
                total += int(line.split()[1]) / 1024
                break
    return total


def _role(pid: int, front: int) -> str:
    """What process ``pid`` of the server's tree is, from its command line."""
    try:
        cmd = Path(f"/proc/{pid}/cmdline").read_text().replace("\0", " ")
        ppid = int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
    except OSError:
        return "gone"
    if pid == front:
        return "front"
    if "resource_tracker" in cmd:
        return "resource tracker"
    if "forkserver" in cmd:
        return "fork server" if ppid == front else "session (forked)"
    if "app.serve.session_process" in cmd:
        return "session"
    return "solver or other"


def memory_by_process(pid: int) -> str:
    """Proportional set size of each process of the server's tree, with its role, one a line."""
    rows = []
    for p in _tree(pid):
        try:
            rollup = Path(f"/proc/{p}/smaps_rollup").read_text().splitlines()
        except OSError:
            continue
        pss = next((int(x.split()[1]) / 1024 for x in rollup if x.startswith("Pss:")), 0.0)
        rows.append(f"   {p:>8} {_role(p, pid):18s} {pss:7.0f} MB")
    return "\n".join(rows)


def open_first_run(page, title: str) -> None:
    """Open the first saved run of the runs list in ``page``, wait until the app shows the run
    titled ``title``, then 2 s more for its first frames."""
    page.locator("#runs-select .v-field").click()
    page.locator(".v-overlay--active .v-list-item").first.click()
    page.wait_for_function(
        f"(window.trame.state.get('result_label') || '').includes('{title}')", timeout=120_000
    )
    time.sleep(2)


def frames_per_s(page, seconds: float = 8.0) -> float:
    """Distinct images received by #view-3d per second over ``seconds``."""
    page.evaluate("""() => { window.__srcs = new Set(); window.__ticks = 0;
        const img = document.querySelector('#view-3d img');
        window.__observer = new MutationObserver(() => window.__srcs.add(img.src));
        window.__observer.observe(img, {attributes: true, attributeFilter: ['src']}); }""")
    frame0 = page.evaluate("window.trame.state.get('frame')")
    time.sleep(seconds)
    shown = page.evaluate("(() => { window.__observer.disconnect(); return __srcs.size; })()")
    frame1 = page.evaluate("window.trame.state.get('frame')")
    print(f"   (animation frames advanced {frame1 - frame0} in {seconds:g} s)")
    return shown / seconds


def main() -> int:
    from playwright.sync_api import sync_playwright

    parser = argparse.ArgumentParser()
    parser.add_argument("--runs-dir", default=None)
    parser.add_argument("--run", type=Path, default=None, help="existing 100-revolution .nc")
    parser.add_argument("--loads", type=int, default=5, help="page loads for the first frame")
    args = parser.parse_args()
    runs = Path(args.runs_dir or tempfile.mkdtemp(prefix="racetrace-bench-"))
    info = real_run(runs, args.run)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t_start = time.monotonic()
    proc = subprocess.Popen(
        # the server-rendered view: its images are what this script counts (browser_fps.py
        # measures the in-browser view)
        [
            sys.executable,
            "-m",
            "racetrace",
            "serve",
            "--port",
            str(port),
            "--runs-dir",
            str(runs),
            "--render",
            "server",
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    url = f"http://127.0.0.1:{port}/"
    while True:
        try:
            urllib.request.urlopen(url, timeout=1)
            break
        except OSError:
            time.sleep(0.2)
    print(f"server start to first HTTP answer: {time.monotonic() - t_start:.1f} s")
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            firsts = []
            # the first load is a new browser (it gets the spare session, started ahead); the
            # others load the page again in the same browser (its own session)
            context = browser.new_context(viewport={"width": 1500, "height": 1000})
            for _ in range(args.loads):
                page = context.new_page()
                page.add_init_script(FIRST_FRAME_PROBE)
                page.goto(url)
                page.wait_for_function("window.__firstFrameMs !== undefined", timeout=60_000)
                firsts.append(page.evaluate("window.__firstFrameMs") / 1e3)
                page.wait_for_function(CHARTS_READY, timeout=60_000)
                page.close()
            context.close()
            print(
                f"first 3-D frame after navigation start: new browser {firsts[0]:.2f} s, median "
                f"of {len(firsts)} loads {statistics.median(firsts):.2f} s "
                f"(all: {', '.join(f'{x:.2f}' for x in firsts)})"
            )
            page = browser.new_page(viewport={"width": 1500, "height": 1000})
            page.goto(url, timeout=300_000)  # a second new browser: its session may be starting
            page.wait_for_function(CHARTS_READY, timeout=300_000)
            time.sleep(1)
            print(f"frames shown while playing the default case: {frames_per_s(page):.1f} /s")
            page.locator("#play-button").click()  # pause
            time.sleep(1)  # let the charts of the paused frame settle before timing edits
            times = []
            for load in ("650", "800", "950", "700", "850", "1000", "750"):
                serial = page.evaluate("window.trame.state.get('result_serial')")
                box = page.locator("#field-axial_load_N input")
                box.fill(load)
                t1 = time.monotonic()
                box.press("Tab")
                page.wait_for_function(
                    f"window.trame.state.get('result_serial') > {serial}", polling=10
                )
                times.append(time.monotonic() - t1)
            print(
                "quasi-static preview refresh after an edit: "
                f"median {statistics.median(times):.2f} s, "
                f"max {max(times):.2f} s (all: " + ", ".join(f"{x:.2f}" for x in times) + ")"
            )
            before = rss_mb(proc.pid)
            open_first_run(page, info.title)
            loaded = rss_mb(proc.pid)
            page.locator("#play-button").click()  # play the run
            fps_run = frames_per_s(page)
            for title in page.locator(".v-expansion-panel-title").all():
                title.click()  # open every chart panel (their charts are computed only when open)
            time.sleep(1)
            fps_panels = frames_per_s(page)
            print(
                f"frames shown while playing the 100-revolution run: {fps_run:.1f} /s, "
                f"{fps_panels:.1f} /s with every chart panel open"
            )
            print(
                f"server memory: {before:.0f} MB before, {loaded:.0f} MB with the 100-revolution "
                f"run loaded ({info.run_id}), {rss_mb(proc.pid):.0f} MB after playing it with "
                "every chart panel open"
            )
            other = browser.new_page(viewport={"width": 1200, "height": 900})  # a second session
            other.goto(url, timeout=300_000)
            other.wait_for_function(CHARTS_READY, timeout=300_000)
            open_first_run(other, info.title)
            print(
                f"server memory with two sessions, each with the 100-revolution run loaded: "
                f"{rss_mb(proc.pid):.0f} MB (front, {len(_tree(proc.pid)) - 1} processes below it)"
            )
            print(memory_by_process(proc.pid))
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=60)  # the sessions stop first
    return 0


if __name__ == "__main__":
    sys.exit(main())
