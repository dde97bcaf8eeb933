"""Measure how fast a browser draws the in-browser 3-D view while playing (run by hand, not in CI).

    python benchmarks/browser_fps.py [--size 1280x800] [--seconds 8] [--variants]

Starts ``racetrace serve --render browser`` on a free loopback port, opens it in headless Chromium
(/usr/bin/chromium, software WebGL on SwiftShader) at ``--size`` and, while the default case plays,
counts for ``--seconds`` in the page: the animation frames the browser managed
(``requestAnimationFrame`` callbacks per second: its drawing capacity, 60 at most) and the
distinct frames of the bearing it received and drew (at most the app's ``PLAY_FPS``). Also prints
the server's process CPU time over the same span (front and session processes) and the size of
the frame state the page received (``rt3d_frame`` as JSON, a measure of what it decodes per frame).

``--variants``: then, in the same page, the same counts with the balls and the cage hidden (the 18
translucent balls drawn or not), with the painted tracks hidden, and in a window of a quarter of
the pixels, and paused: which of them the drawing rate follows says what limits it (the pixels:
software WebGL's fill rate; the parts: the draw calls; paused, nothing is drawn or updated: the
rate the page's main thread gets at all on the machine as loaded); then paused with the 3-D view
not displayed, and a blank page in the same browser.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

COUNT_FRAMES = """(seconds) => new Promise((done) => {
  let ticks = 0;
  const seen = new Set();
  const t0 = performance.now();
  function tick() {
    ticks += 1;
    seen.add(window.trame.state.get('rt3d_frame').index);
    if (performance.now() - t0 < seconds * 1000) requestAnimationFrame(tick);
    else done([ticks / seconds, seen.size / seconds]);
  }
  requestAnimationFrame(tick);
})"""


COUNT_BLANK = """(seconds) => new Promise((done) => {
  let ticks = 0;
  const t0 = performance.now();
  function tick() {
    ticks += 1;
    if (performance.now() - t0 < seconds * 1000) requestAnimationFrame(tick);
    else done(ticks / seconds);
  }
  requestAnimationFrame(tick);
})"""


def _cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of ``pid`` and its children (from /proc)."""
    import os

    total = 0.0
    tick = os.sysconf("SC_CLK_TCK")
    for task in Path("/proc").iterdir():
        if not task.name.isdigit():
            continue
        try:
            fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid or int(task.name) == pid:  # the server and its sessions
            total += (int(fields[11]) + int(fields[12])) / tick
    return total


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", default="1280x800", help="browser window, WIDTHxHEIGHT")
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--variants", action="store_true", help="also measure the variants")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))

    import playwright.sync_api as playwright_api

    from tests.helpers.serve import start_server, stop_server
    from tools.chromium import CHROMIUM, LAUNCH_ARGS

    folder = Path(tempfile.mkdtemp(prefix="racetrace-fps-"))
    served = start_server(folder / "runs", folder / "serve.log", "--render", "browser")
    try:
        with playwright_api.sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            page = browser.new_page(viewport={"width": width, "height": height})
            page.goto(served["url"])
            page.wait_for_selector("#view-3d-browser canvas", timeout=120_000)
            page.evaluate("window.trame.state.set('playing', true)")
            time.sleep(3.0)  # meshes in, playing
            pid = served["proc"].pid
            print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
            variants = [("as served", {}, None)]
            if args.variants:
                variants += [
                    (f"window {width // 2}x{height // 2}", {}, (width // 2, height // 2)),
                    ("balls and cage hidden", {"show_balls": False, "show_cage": False}, None),
                    ("painted tracks hidden", {"show_tracks": False}, None),
                    ("paused (no frame updates)", {"playing": False}, None),
                ]
            for name, hidden, size in variants:
                for key, value in hidden.items():
                    page.evaluate(f"window.trame.state.set('{key}', {json.dumps(value)})")
                if size is not None:
                    page.set_viewport_size({"width": size[0], "height": size[1]})
                time.sleep(1.0)
                cpu0, wall0 = _cpu_seconds(pid), time.monotonic()
                drawn, frames = page.evaluate(COUNT_FRAMES, args.seconds)
                cpu = (_cpu_seconds(pid) - cpu0) / (time.monotonic() - wall0)
                state = len(page.evaluate("JSON.stringify(window.trame.state.get('rt3d_frame'))"))
                print(
                    f"{name}: {drawn:.1f} animation frames/s, {frames:.1f} bearing frames/s "
                    f"drawn; server (front + sessions) {100 * cpu:.0f} % of a core; frame state "
                    f"{state / 1e3:.1f} kB (JSON)"
                )
                for key, value in hidden.items():
                    page.evaluate(f"window.trame.state.set('{key}', {json.dumps(not value)})")
                if size is not None:
                    page.set_viewport_size({"width": width, "height": height})
            if args.variants:  # what the page gets without the 3-D view, and a blank page
                page.evaluate("window.trame.state.set('playing', false)")
                page.evaluate("document.querySelector('#view-3d-browser').style.display = 'none'")
                time.sleep(1.0)
                drawn, _ = page.evaluate(COUNT_FRAMES, args.seconds)
                print(f"paused, the 3-D view not displayed: {drawn:.1f} animation frames/s")
                blank = browser.new_page(viewport={"width": width, "height": height})
                blank.set_content("<html><body>blank</body></html>")
                drawn = blank.evaluate(COUNT_BLANK, args.seconds)
                print(f"a blank page: {drawn:.1f} animation frames/s")
            browser.close()
    finally:
        stop_server(served)
    return 0


if __name__ == "__main__":
    sys.exit(main())
