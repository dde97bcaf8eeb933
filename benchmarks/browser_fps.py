"""Measure how fast a browser draws the in-browser 3-D view while playing (run by hand, not in CI).

    python benchmarks/browser_fps.py [--size 1280x800] [--seconds 8] [--variants]

Starts ``racetrace serve --render browser`` on a free loopback port, opens it in headless Chromium
(/usr/bin/chromium, software WebGL on SwiftShader) at ``--size`` and, while the default case plays,
counts for ``--seconds`` in the page: the animation frames the browser managed
(``requestAnimationFrame`` callbacks per second: its drawing capacity, 60 at most), the drawings
of the 3-D view (vtk.js render events: the picture's own frame rate), the
distinct frames of the bearing the page held at an animation frame (at most the app's
``PLAY_FPS``) and the state messages the page took (and keys per message). Also prints the CPU
time over the same span of the server (front and session processes) and of Chromium's renderer
(the page's main thread: trame, Vue, vtk.js) and GPU process (SwiftShader drawing the WebGL), per
second and per drawing of the 3-D view, and the size of the frame state (``rt3d_frame`` as JSON).
CPU times count the work whatever else the machine runs; the rates depend on the load (printed).

``--variants``: then, in the same page, the same counts with the balls and the cage hidden (the 18
translucent balls drawn or not), with the painted tracks hidden, and in a window of a quarter of
the pixels, and paused: which of them the drawing rate follows says what limits it (the pixels:
software WebGL's fill rate; the parts: the draw calls; paused, nothing is drawn or updated: the
rate the page's main thread gets at all on the machine as loaded); then a blank page in the same
browser.
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
  const counts = window.racetraceCounts;
  const [draws0, messages0, keys0] = [counts.draws, counts.messages, counts.keys];
  const t0 = performance.now();
  function tick() {
    ticks += 1;
    seen.add(window.trame.state.get('rt3d_frame').index);
    if (performance.now() - t0 < seconds * 1000) requestAnimationFrame(tick);
    else {
      const messages = counts.messages - messages0;
      done([ticks / seconds, seen.size / seconds, (counts.draws - draws0) / seconds,
            messages / seconds, (counts.keys - keys0) / Math.max(messages, 1)]);
    }
  }
  requestAnimationFrame(tick);
})"""

# counts the drawings of the 3-D view (its interactor's render events) and the state messages
# the page takes
INSTALL_COUNTS = """() => {
  const counts = { draws: 0, messages: 0, keys: 0 };
  window.racetraceCounts = counts;
  const view = window.trame.refs.rt3d_view.$.provides.view;
  view.interactor.onRenderEvent(() => { counts.draws += 1; });
  window.trame.state.addListener(({ type, keys }) => {
    if (type === 'dirty-state') { counts.messages += 1; counts.keys += keys.length; }
  });
}"""


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


def _chromium_cpu_seconds() -> dict[str, float]:
    """CPU seconds of the Chromium processes this process started, by kind (``renderer``,
    ``gpu-process``, ``browser``, ...), from /proc."""
    tick = os.sysconf("SC_CLK_TCK")
    parents, processes = {}, {}
    for task in Path("/proc").iterdir():
        if not task.name.isdigit():
            continue
        try:
            fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
            # Chromium's child processes rewrite their command line as one string
            command = (task / "cmdline").read_bytes().decode(errors="replace")
        except OSError:
            continue
        pid = int(task.name)
        parents[pid] = int(fields[1])
        processes[pid] = ((int(fields[11]) + int(fields[12])) / tick, command)
    mine, cpu = os.getpid(), {}
    for pid, (seconds, command) in processes.items():
        ancestor = parents.get(pid, 0)
        while ancestor not in (0, 1, mine):
            ancestor = parents.get(ancestor, 0)
        if ancestor != mine or "chrom" not in command.split("\0")[0].split(" ")[0]:
            continue
        kind = command.split("--type=", 1)[1].split()[0] if "--type=" in command else "browser"
        cpu[kind] = cpu.get(kind, 0.0) + seconds
    return cpu


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
            page.wait_for_function("window.trame.refs.rt3d_view", timeout=60_000, polling=200)
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
            page.evaluate(INSTALL_COUNTS)
            for name, hidden, size in variants:
                for key, value in hidden.items():
                    page.evaluate(f"window.trame.state.set('{key}', {json.dumps(value)})")
                if size is not None:
                    page.set_viewport_size({"width": size[0], "height": size[1]})
                time.sleep(2.0)
                cpu0, browser0, wall0 = _cpu_seconds(pid), _chromium_cpu_seconds(), time.monotonic()
                counted = page.evaluate(COUNT_FRAMES, args.seconds)
                wall = time.monotonic() - wall0
                cpu = (_cpu_seconds(pid) - cpu0) / wall
                browser_cpu = {
                    k: (v - browser0.get(k, 0.0)) / wall for k, v in _chromium_cpu_seconds().items()
                }
                drawn, frames, draws, messages, keys = counted
                state = len(page.evaluate("JSON.stringify(window.trame.state.get('rt3d_frame'))"))
                renderer = browser_cpu.get("renderer", 0.0)
                gpu = browser_cpu.get("gpu-process", 0.0)
                per_draw = (
                    f"{1e3 * renderer / draws:.0f} + {1e3 * gpu / draws:.0f} ms per drawing"
                    if draws
                    else "no drawing"
                )
                print(
                    f"{name}: {drawn:.1f} animation frames/s, {draws:.1f} drawings of the 3-D "
                    f"view/s, {frames:.1f} bearing frames/s shown; {messages:.1f} state "
                    f"messages/s ({keys:.1f} keys each); CPU: server (front + sessions) "
                    f"{100 * cpu:.0f} %, Chromium renderer {100 * renderer:.0f} % + GPU process "
                    f"{100 * gpu:.0f} % of a core ({per_draw}); frame state {state / 1e3:.1f} kB "
                    f"(JSON)"
                )
                for key, value in hidden.items():
                    page.evaluate(f"window.trame.state.set('{key}', {json.dumps(not value)})")
                if size is not None:
                    page.set_viewport_size({"width": width, "height": height})
            if args.variants:  # a blank page in the same browser
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
