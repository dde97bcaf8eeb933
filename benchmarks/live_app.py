"""Measure live mode in the browser (run by hand, not in CI).

    python benchmarks/live_app.py [--seconds S] [--changes N] [--render browser|server]

Starts ``racetrace serve`` on a free loopback port, opens the default case in headless Chromium
(/usr/bin/chromium), presses Live and waits for the live view to draw; then prints:
- frames per second while live: distinct frames the page received per wall second over
  ``--seconds`` (default 10): images of #view-3d with server rendering, ``rt3d_frame`` updates
  seen at the page's animation frames with the browser-drawn view (``--render``, default the
  app's default, browser); and the live frames the server drew in that time (state
  ``live_frame.serial``);
- latency from a control change to the first frame that shows it (wall, timed in the page): the
  radial load is set through the page's state (as the slider does) and the page notes the time
  at which ``#live-data``'s ``data-radial-load`` (the input of the frame on show) first leaves the
  old value (the page has taken that frame), the time at which the server drew that frame (its
  ``live_frame.sent_at_s``, the server's wall clock: the state-level share, the page to the
  server included), and the time at which the 3-D view's first drawing
  after that is on screen (the view's ``utils.rt3d.shown``; with a page that does not say it, the
  first animation frame after it; none with server rendering);
  ``--changes`` changes (default 12, so that the tail is measured), alternately up and down by
  200 N, each set once the frame on show carries the load set before (so that a ramp still
  playing is not taken for the change: at a slowed playback a ramp takes seconds of wall time);
  median, max, how many within the 0.5-s target (issue 24) and all;
- the playback the solver keeps (``#live-rate``) and whether it says it cannot keep up
  (``#live-behind``).
Timings are wall times on the machine as loaded when run: state the load (``uptime``) with them.
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tools.chromium import CHROMIUM, LAUNCH_ARGS  # noqa: E402

#: a control change is to be visible in the picture within this (s; issue 24)
TARGET_S = 0.5

# frames the page received: with server rendering the distinct images of #view-3d, with the
# browser-drawn view the distinct frames (rt3d_frame) present at each animation frame of the page
FRAME_COUNTER = """() => { window.__srcs = new Set(); window.__counting = true;
    const img = document.querySelector('#view-3d img');
    if (img && !window.trame.state.get('view_in_browser')) {
      const observer = new MutationObserver(() => window.__srcs.add(img.src));
      observer.observe(img, {attributes: true, attributeFilter: ['src']});
      window.__stop = () => observer.disconnect();
    } else {
      let last = null;
      const tick = () => {
        if (!window.__counting) return;
        const f = window.trame.state.get('rt3d_frame');
        if (f !== last) { window.__srcs.add(window.__srcs.size); last = f; }
        requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
      window.__stop = () => { window.__counting = false; };
    } }"""

# set the radial load and note when the frame on show first carries a different load (the page
# has applied it), then when the 3-D view's first drawing after that is on screen: as the view
# says (utils.rt3d.shown, a drawing begun after it), else the first animation frame after it
CHANGE_AND_WATCH = """(load) => new Promise((resolve) => {
    const el = document.querySelector('#live-data');
    const old = Number(el.dataset.radialLoad);
    const t0 = performance.now();
    const wall0 = Date.now() / 1e3;  // the server's clock (one machine)
    const since = (t) => (t - t0) / 1e3;
    const observer = new MutationObserver(() => {
      if (Math.abs(Number(el.dataset.radialLoad) - old) <= 0.5) return;
      observer.disconnect();
      const applied = performance.now();
      const sent = window.trame.state.get('live_frame').sent_at_s;
      const server = sent ? sent - wall0 : null;
      const rt3d = window.trame.utils.rt3d;
      if (!window.trame.state.get('view_in_browser')) {
        resolve([since(applied), null, server]);
        return;
      }
      if (rt3d && 'shown' in rt3d) {
        const wait = () => {
          const shown = rt3d.shown;
          if (shown && shown.start >= applied) resolve([since(applied), since(shown.end), server]);
          else setTimeout(wait, 2);
        };
        wait();
      } else {
        const done = () => resolve([since(applied), since(performance.now()), server]);
        requestAnimationFrame(() => setTimeout(done, 0));
      }
    });
    observer.observe(el, {attributes: true});
    window.trame.state.set('live_radial_load_N', load);
    setTimeout(() => { observer.disconnect(); resolve([null, null, null]); }, 60000);
})"""


def main() -> int:
    from playwright.sync_api import sync_playwright

    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--changes", type=int, default=12)
    parser.add_argument("--render", choices=("browser", "server"), default="browser")
    args = parser.parse_args()
    runs = Path(tempfile.mkdtemp(prefix="racetrace-live-bench-"))
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    proc = subprocess.Popen(
        [
            *(sys.executable, "-m", "racetrace", "serve", "--port", str(port)),
            *("--runs-dir", str(runs), "--render", args.render),
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
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            page = browser.new_page(viewport={"width": 1500, "height": 1000})
            page.goto(url, timeout=300_000)
            page.wait_for_selector("#chart-contact-angle .main-svg", timeout=300_000)
            t0 = time.monotonic()
            page.locator("#live-button").click()
            page.wait_for_function(
                "(window.trame.state.get('live_frame') || {}).serial > 5",
                timeout=900_000,
                polling=200,
            )
            print(f"Live pressed to the 6th live frame: {time.monotonic() - t0:.1f} s")
            page.evaluate(FRAME_COUNTER)
            serial0 = page.evaluate("window.trame.state.get('live_frame').serial")
            time.sleep(args.seconds)
            shown = page.evaluate("(() => { __stop(); return __srcs.size; })()")
            serial1 = page.evaluate("window.trame.state.get('live_frame').serial")
            in_browser = page.evaluate("window.trame.state.get('view_in_browser')")
            print(
                f"frames per second while live ({args.render} rendering; drawn by the browser: "
                f"{in_browser}): "
                f"{shown / args.seconds:.1f} frames received /s "
                f"({(serial1 - serial0) / args.seconds:.1f} live frames drawn /s by the server)"
            )
            latencies = []
            load = 300.0
            for k in range(args.changes):
                page.wait_for_function(
                    f"Math.abs(Number(document.querySelector('#live-data').dataset.radialLoad)"
                    f" - {load}) < 0.5",
                    timeout=120_000,
                    polling=50,
                )
                load += 200.0 if k % 2 == 0 else -200.0
                latency = page.evaluate(CHANGE_AND_WATCH, load)
                latencies.append(latency)
                time.sleep(1.0)
            for what, k in (
                ("the server draws the first frame showing it", 2),
                ("the page takes that frame", 0),
                ("that frame drawn on screen", 1),
            ):
                values = [x[k] for x in latencies]
                seen = [x for x in values if x is not None]
                text = ", ".join("none" if x is None else f"{x:.2f}" for x in values)
                if seen:
                    within = sum(x <= TARGET_S for x in seen)
                    print(
                        f"control change to {what}: median {statistics.median(seen):.2f} s, "
                        f"max {max(seen):.2f} s, {within} of {len(values)} within "
                        f"{TARGET_S:g} s (all: {text})"
                    )
                else:
                    print(f"control change to {what}: not seen ({text})")
            print(f"playback: {page.locator('#live-rate').inner_text().strip()}")
            behind = page.locator("#live-behind").inner_text().strip()
            print(f"solver keeping up: {'no: ' + behind if behind else 'yes'}")
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
