"""Follow mode under a class (issue 26): followers watching a presenter play a 100-revolution run.

    python benchmarks/follow.py [--run FILE.nc] [--followers 30] [--seconds 30] [--render browser]
                                [--settle 15] [--alone]

The run: a dynamic run of ``--revolutions`` (100) shaft revolutions of the default case
(``spindle-combined-load``). ``--run FILE`` gives one; otherwise the one stored in
``~/.cache/racetrace/benchmarks/`` is reused when it is complete and that long, or computed once
there (``racetrace simulate``: about a minute on a free core) and kept for the next time.

Starts ``racetrace serve`` (``--render``: browser, the app's default, or server) on a free loopback
port with a runs folder holding that run. A presenter (a websocket client that speaks to its
session as the page does, :class:`tests.helpers.wslink_client.WslinkClient`) says that it draws
WebGL, as the page does once trame is up (``--presenter-webgl no``: a page without it, for which
the session draws every frame itself and pushes the image to every page), opens the run and
plays it; then ``--followers`` websocket followers (the same protocol, through
``/follow/CODE/ws``: hello, the whole state, then every state change and image the session
publishes; ``--follower-deflate yes``: asking for compressed messages, permessage-deflate, as
browsers do) and one headless Chromium follower at 1280 x 800 (``/?follow=CODE``,
/usr/bin/chromium) join. Printed, for ``--seconds`` of playing alone and then with the followers:

- server CPU in cores (CPU time of the processes over wall time, from /proc/PID/stat, sampled every
  second): the front, the presenter's session (the busiest), the other processes (the spare
  session and the fork server: idle) and their sum, median and largest of the 1-s samples;
- server CPU time per played frame (front, presenter's session, all): CPU time, so it holds on a
  loaded machine too, where the cores measure the load as much as the server;
- the images the presenter was pushed (none while the browser draws);
- frame lag: for each frame index the presenter got (its first arrival), how long after it each
  follower showed that index or a later one (the window begins once the Chromium follower has
  started: its first 3-D drawing and its charts drawn, seconds of work for its main thread in
  software WebGL; how long that took is printed); median and largest per follower kind, the
  followers ever over 0.5 s, and the frames a follower never reached (the window must not wrap
  around the end of the run: 720 of the 100-revolution run's 18 000 frames in 30 s). The Chromium
  follower shows a frame index when its page has applied it (the time counter and slider, the
  index the target is checked on) and, later, in its 3-D view once drawn (the index of
  ``rt3d_frame`` at an animation frame, noted once the browser has painted that frame): both are
  printed;
- memory: proportional set size of the server's processes before and with the followers;
- what a follower is sent: the bytes the first websocket follower read in the window, per second
  and per played frame, and the state keys that made most of them (msgpack, uncompressed).

``--settle`` (15 s): how long the presenter plays before the first window (the spare session,
started beside the presenter's, must be idle by then); ``--alone``: only the window of the
presenter alone.

``--profile DIR``: py-spy (``pip install py-spy``) records the front and the presenter's session
during the window with the followers, as collapsed stacks (``DIR/front.txt``, ``DIR/session.txt``).

``--page-profile FILE.cpuprofile``: V8's sampling profiler (Chrome DevTools Protocol) records the
Chromium follower's page during that window (the file opens in DevTools' Performance panel); the
share of its samples is printed by what they were in: under a plotly function (the charts), under
the 3-D view's or trame's scripts, native work outside JavaScript (``(program)``: drawing, style,
layout, paint, waiting on SwiftShader), the garbage collector, idle.
"""

from __future__ import annotations

import argparse
import asyncio
import bisect
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# run as a script, sys.path[0] is benchmarks/: put the repository first
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from app_frames import _tree, real_run, rss_mb  # noqa: E402

from tools.chromium import CHROMIUM, LAUNCH_ARGS  # noqa: E402

CASE = "spindle-combined-load"
STORE = Path.home() / ".cache" / "racetrace" / "benchmarks"
LAG_TARGET_S = 0.5
CPU_TARGET_CORES = 1.0
MEMORY_TARGET_MB = 300.0
TICKS = os.sysconf("SC_CLK_TCK")
PY_SPY = str(Path(sys.executable).with_name("py-spy"))  # pip install py-spy, for --profile
# in the browser follower: each frame index as it arrives, with the wall-clock time (ms): from the
# state's watcher, and read every 20 ms as well (whichever sees an index first counts); and each
# frame index the 3-D view shows, once drawn: the index of rt3d_frame at an animation frame (the
# view draws a change at the second animation frame after it, app.components.browser_view),
# noted at the first task after the next animation frame, once the browser has painted it
FRAME_PROBE = """() => { window.__frames = []; window.__drawn = [];
  const note = (f) => window.__frames.push([f, Date.now()]);
  window.trame.state.watch(['frame'], note);
  let last = null;
  setInterval(() => { const f = window.trame.state.get('frame');
                      if (f !== last) { last = f; note(f); } }, 20);
  let drawn = null;
  const frame = () => {
    const f = (window.trame.state.get('rt3d_frame') || {}).index;
    if (f !== drawn) {
      drawn = f;
      requestAnimationFrame(() => setTimeout(() => window.__drawn.push([f, Date.now()]), 0));
    }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame); }"""


# the Chromium follower has started: its 3-D view has drawn (app.components.browser_view) and the
# two charts that follow the time have drawn (app.lazy_charts)
STARTED = """() => !!(window.trame.utils.rt3d && window.trame.utils.rt3d.shown
  && document.querySelector('#chart-contact-angle .main-svg')
  && document.querySelector('#chart-raceway-map .main-svg'))"""


def cpu_ticks(pid: int) -> dict[int, int]:
    """CPU time (user + system, clock ticks) of ``pid`` and of every process below it, by pid."""
    ticks = {}
    for p in _tree(pid):
        try:
            fields = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        ticks[p] = int(fields[11]) + int(fields[12])  # utime, stime
    return ticks


class CpuSampler:
    """Cores used by the server's front (``pid``), by its busiest session (the presenter's) and by
    the other processes below the front (the spare session, the fork server: idle), sampled every
    ``every_s`` seconds while running (:meth:`run` as a task); and the CPU seconds of each process
    over the whole run (:attr:`used`, by pid)."""

    def __init__(self, pid: int, every_s: float = 1.0):
        self.pid, self.every_s = pid, every_s
        self.samples: list[dict[int, float]] = []  # cores per process per interval
        self.used: dict[int, float] = {}  # CPU seconds per process

    async def run(self) -> None:
        before, t0 = cpu_ticks(self.pid), time.monotonic()
        while True:
            await asyncio.sleep(self.every_s)
            now, t = cpu_ticks(self.pid), time.monotonic()
            # a process that ended since counts its last interval as nothing
            used = {p: now[p] - before.get(p, 0) for p in now}
            seconds = (t - t0) * TICKS
            self.samples.append({p: n / seconds for p, n in used.items()})
            for p, n in used.items():
                self.used[p] = self.used.get(p, 0.0) + n / TICKS
            before, t0 = now, t

    def presenter_session(self) -> int:
        """The session that used the most CPU: the presenter's (the others are idle)."""
        sessions = {p: x for p, x in self.used.items() if p != self.pid}
        return max(sessions, key=sessions.get) if sessions else -1

    def split(self) -> list[tuple[float, float, float]]:
        """(front, the presenter's session, other processes) cores per sample."""
        session = self.presenter_session()
        out = []
        for sample in self.samples:
            front, busy = sample.get(self.pid, 0.0), sample.get(session, 0.0)
            out.append((front, busy, sum(sample.values()) - front - busy))
        return out


def cores_line(sampler: CpuSampler) -> tuple[str, float]:
    """The front's, the presenter's session's, the other processes' and the total cores (median
    / largest) in words; the largest total."""
    samples = sampler.split()
    if not samples:
        return "no samples", float("nan")
    parts, largest = [], 0.0
    for name, values in (
        ("front", [f for f, _, _ in samples]),
        ("presenter's session", [x for _, x, _ in samples]),
        ("others", [o for _, _, o in samples]),
        ("total", [sum(x) for x in samples]),
    ):
        parts.append(f"{name} {statistics.median(values):.2f} / {max(values):.2f}")
        largest = max(values)
    return ", ".join(parts) + f" (median / largest of {len(samples)} 1-s samples)", largest


def per_frame_line(sampler: CpuSampler, frames: int) -> str:
    """CPU time per played frame (ms) of the front, the presenter's session and the whole server:
    CPU time, so it holds on a loaded machine too."""
    if frames <= 0:
        return "no frames played"
    front = sampler.used.get(sampler.pid, 0.0)
    session = sampler.used.get(sampler.presenter_session(), 0.0)
    total = sum(sampler.used.values())
    return (
        f"CPU per played frame: front {front / frames * 1e3:.1f} ms, presenter's session "
        f"{session / frames * 1e3:.1f} ms, server {total / frames * 1e3:.1f} ms"
    )


def lags(reference: list[tuple[float, int]], seen: list[tuple[float, int]]):
    """For each frame index of ``reference`` (its first arrival), how many seconds later ``seen``
    first showed that index or a later one (a follower that skips a frame is as late as the next
    frame it shows), and how many of the reference's frames ``seen`` never reached. The window
    must not wrap around the end of the run (indices then only grow)."""
    reached_at, reached = [], []  # times at which seen's largest index so far grew, and the index
    for t, f in sorted(seen):
        if not reached or f > reached[-1]:
            reached_at.append(t)
            reached.append(f)
    out, missing = [], 0
    for t, f in _first_of(reference):
        i = bisect.bisect_left(reached, f)
        if i < len(reached):
            out.append(reached_at[i] - t)
        else:
            missing += 1
    return out, missing


def _first_of(frames: list[tuple[float, int]]) -> list[tuple[float, int]]:
    """Each frame index once, at its first arrival."""
    seen, out = set(), []
    for t, f in frames:
        if f not in seen:
            seen.add(f)
            out.append((t, f))
    return out


# what a sample of the page's profile was in, by the first of these its stack holds (from the
# innermost frame out; a script's address or V8's own names), and the names printed
PROFILE_KINDS = (
    ("trame-plotly", "plotly (the charts)"),
    ("racetrace-charts", "the charts' stand-in"),
    ("vtk", "vtk.js (the 3-D view)"),
    ("trame", "trame, Vue, the page's scripts"),
)
NATIVE_KINDS = {
    "(program)": "native, outside JavaScript",
    "(garbage collector)": "garbage collector",
    "(idle)": "idle",
}


def profile_shares(profile: dict) -> dict[str, float]:
    """The share of a V8 CPU profile's samples (``Profiler.stop``'s profile) by what they were
    in: the first of :data:`PROFILE_KINDS` whose words a frame's script address holds, from the
    sampled frame out to the stack's root; V8's own nodes (:data:`NATIVE_KINDS`); "other"."""
    nodes = {node["id"]: node for node in profile["nodes"]}
    parent = {}
    for node in profile["nodes"]:
        for child in node.get("children", []):
            parent[child] = node["id"]
    kind_of: dict[int, str] = {}

    def kind(node_id: int) -> str:
        if node_id in kind_of:
            return kind_of[node_id]
        frame = nodes[node_id]["callFrame"]
        name, url = frame.get("functionName", ""), frame.get("url", "")
        found = NATIVE_KINDS.get(name) if not url else None
        if found is None:
            for words, label in PROFILE_KINDS:
                if words in url:
                    found = label
                    break
        if found is None:
            up = parent.get(node_id)
            found = kind(up) if up is not None else "other"
        kind_of[node_id] = found
        return found

    counts: dict[str, int] = {}
    for sample in profile.get("samples", []):
        label = kind(sample)
        counts[label] = counts.get(label, 0) + 1
    total = max(1, sum(counts.values()))
    return {label: n / total for label, n in sorted(counts.items(), key=lambda x: -x[1])}


def describe(values: list[float]) -> str:
    if not values:
        return "no frames in common"
    values = sorted(values)
    p95 = values[min(len(values) - 1, int(0.95 * len(values)))]
    return (
        f"median {statistics.median(values) * 1e3:5.0f} ms, 95 % {p95 * 1e3:5.0f} ms, "
        f"largest {values[-1] * 1e3:5.0f} ms"
    )


async def window(
    seconds: float, pid: int, presenter, profile: Path | None = None, session: int = -1
) -> tuple[CpuSampler, float]:
    """Play on for ``seconds`` sampling the server's CPU: the sampler and the window's start.
    ``profile``: a folder where py-spy records the front and the presenter's ``session``
    meanwhile (``front.txt``, ``session.txt``: collapsed stacks, idle frames left out)."""
    presenter.frames.clear()
    presenter.images = 0
    sampler = CpuSampler(pid)
    spies = []
    if profile is not None:
        profile.mkdir(parents=True, exist_ok=True)
        for who, p in (("front", pid), ("session", session)):
            command = [PY_SPY, "record", "--pid", str(p), "--duration", str(int(seconds))]
            command += ["--rate", "100", "--nonblocking", "--format", "raw"]
            command += ["--output", str(profile / f"{who}.txt")]
            spies.append(
                subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            )
    t0 = time.monotonic()
    task = asyncio.get_running_loop().create_task(sampler.run())
    await asyncio.sleep(seconds)
    task.cancel()
    for spy in spies:
        await asyncio.to_thread(spy.wait)
    return sampler, t0


async def measure(args, server: dict, info) -> int:
    import aiohttp
    from playwright.async_api import async_playwright

    from tests.helpers.wslink_client import WslinkClient

    port, pid = server["port"], server["proc"].pid
    base = f"http://127.0.0.1:{port}"
    jar = aiohttp.CookieJar(unsafe=True)
    async with aiohttp.ClientSession(cookie_jar=jar) as http:
        async with http.get(base + "/", headers={"Accept": "text/html"}) as page:
            assert page.status == 200, page.status
        presenter = WslinkClient()
        await presenter.connect(http, f"ws://127.0.0.1:{port}/ws", origin=base)
        code = presenter.state["follow_code"]
        # as the page does once trame is up (app.components.browser_view.DETECT_WEBGL): without
        # it the session draws every frame itself and pushes the images to every page
        await presenter.update(browser_webgl=args.presenter_webgl == "yes")
        await presenter.update(playing=False)
        await presenter.update(run_id=info.run_id)
        await presenter.wait_for("result_label", lambda s: info.title in str(s), timeout=600)
        frames = presenter.state.get("frame_max")
        drawn = "by the browser" if presenter.state.get("view_in_browser") else "on the server"
        print(
            f"presenter: the {info.title!r} run open ({frames} frames), join code {code}, "
            f"the 3-D view drawn {drawn}"
        )
        await presenter.update(playing=True)
        # the spare session the front starts beside the presenter's must be idle in the window
        await asyncio.sleep(args.settle)

        alone, t0 = await window(args.seconds, pid, presenter)
        played_alone = len(_first_of([x for x in presenter.frames if x[0] >= t0]))
        memory_alone = rss_mb(pid)
        text, _ = cores_line(alone)
        print(f"presenter alone: server CPU {text}")
        print(
            f"   {played_alone / args.seconds:.1f} frames/s played, {presenter.images} images "
            f"pushed, memory {memory_alone:.0f} MB; {per_frame_line(alone, played_alone)}"
        )

        if args.alone:
            await presenter.update(playing=False)
            await presenter.close()
            return 0
        followers = []
        joining = time.monotonic()
        for _ in range(args.followers):
            follower_http = aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True))
            async with follower_http.get(
                f"{base}/?follow={code}", headers={"Accept": "text/html"}
            ) as page:
                assert page.status == 200, page.status
            follower = WslinkClient(count_keys=not followers)  # the first one counts its keys
            # the whole state (the scene of a 100-revolution run) for each: slow on a loaded machine
            await follower.connect(
                follower_http,
                f"ws://127.0.0.1:{port}/follow/{code}/ws",
                base,
                timeout=600,
                deflate=args.follower_deflate == "yes",
            )
            followers.append((follower_http, follower))
        import msgpack

        size = len(msgpack.packb(followers[0][1].state, default=str)) / 1e6 if followers else 0
        print(
            f"{args.followers} websocket followers joined in {time.monotonic() - joining:.0f} s "
            f"(one after the other; the whole state each reads on joining: {size:.1f} MB)"
        )

        async with async_playwright() as p:
            browser = await p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            page = await browser.new_page(viewport={"width": 1280, "height": 800})
            opening = time.monotonic()
            await page.goto(f"{base}/?follow={code}")
            await page.wait_for_function(
                "window.trame && window.trame.state && window.trame.state.get('follow_code')",
                timeout=300_000,
            )
            await page.evaluate(FRAME_PROBE)
            count = await presenter.wait_for(
                "follow_count", lambda n: n == args.followers + 1, timeout=120
            )
            # the page's start-up (its first 3-D drawing, the chart bundle's run and each chart's
            # first drawing: seconds of main-thread work in software WebGL, frames waiting
            # meanwhile) is over before the window: the window measures following, not joining
            await page.wait_for_function(STARTED, timeout=300_000, polling=100)
            started_s = time.monotonic() - opening
            await asyncio.sleep(3)
            memory_with = rss_mb(pid)
            for _, follower in followers:
                follower.frames.clear()
                follower.received = 0
                follower.key_bytes.clear()
            cdp = None
            if args.page_profile is not None:
                cdp = await page.context.new_cdp_session(page)
                await cdp.send("Profiler.enable")
                await cdp.send("Profiler.setSamplingInterval", {"interval": 1000})  # µs
                await cdp.send("Profiler.start")
            wall0, mono0 = time.time(), time.monotonic()
            with_followers, t0 = await window(
                args.seconds, pid, presenter, args.profile, alone.presenter_session()
            )
            page_profile = None
            if cdp is not None:
                page_profile = (await cdp.send("Profiler.stop"))["profile"]
                args.page_profile.write_text(json.dumps(page_profile))
            reference = [x for x in presenter.frames if x[0] >= t0]
            played = len(_first_of(reference))
            shown = await page.evaluate("window.__frames || []")
            drawn = await page.evaluate("window.__drawn || []")
            now_showing = await page.evaluate("window.trame.state.get('frame')")
            presenter_showing = presenter.state.get("frame")
            await browser.close()

        text, largest_cores = cores_line(with_followers)
        print(f"with {count} followers: server CPU {text}")
        print(
            f"   {played / args.seconds:.1f} frames/s played, {presenter.images} images pushed, "
            f"memory {memory_with:.0f} MB; {per_frame_line(with_followers, played)}"
        )
        pooled, worst, missing = [], [], 0
        for _, follower in followers:
            got, not_seen = lags(reference, follower.frames)
            pooled += got
            worst.append(max(got) if got else float("inf"))
            missing += not_seen
        late = sum(w > LAG_TARGET_S for w in worst)
        print(
            f"frame lag behind the presenter over {played} frame indices in {args.seconds:g} s:\n"
            f"   {len(followers)} websocket followers: {describe(pooled)}; "
            f"{late} followers ever over {LAG_TARGET_S} s; "
            f"{missing} of {played * len(followers)} frames not reached"
        )
        browser_frames = [(mono0 + (ms / 1e3 - wall0), f) for f, ms in shown]
        got, not_seen = lags(reference, browser_frames)
        worst.append(max(got) if got else float("inf"))
        print(
            f"   the Chromium follower started {started_s:.1f} s after opening the page (its first "
            "3-D drawing and both charts drawn); the window began 3 s later"
        )
        print(
            f"   the Chromium follower: {describe(got)}; {not_seen} of {played} frames not reached "
            f"({len(shown)} frame changes noted; frame {now_showing} at the end, the presenter's "
            f"{presenter_showing})"
        )
        got, not_seen = lags(reference, [(mono0 + (ms / 1e3 - wall0), f) for f, ms in drawn])
        print(
            f"   the Chromium follower's 3-D view, once drawn: {describe(got)}; {not_seen} of "
            f"{played} frames not reached ({len(drawn)} frames drawn)"
        )
        if page_profile is not None:
            shares = ", ".join(
                f"{label} {100 * share:.0f} %"
                for label, share in profile_shares(page_profile).items()
            )
            print(f"   the Chromium follower's page, its profile's samples: {shares}")
        if followers:
            first = followers[0][1]
            keys = sorted(first.key_bytes.items(), key=lambda item: -item[1])
            total = sum(first.key_bytes.values())
            top = ", ".join(
                f"{key} {size / args.seconds / 1e3:.1f} kB/s ({100 * size / total:.0f} %)"
                for key, size in keys[:6]
            )
            print(
                f"what a follower is sent: {first.received / args.seconds / 1e6:.3f} MB/s, "
                f"{first.received / max(1, played) / 1e3:.1f} kB per played frame; by key: {top}"
            )
        added = memory_with - memory_alone
        print(
            f"memory: {memory_alone:.0f} MB alone, {memory_with:.0f} MB with the followers "
            f"(+{added:.0f} MB for {count})"
        )
        print(
            "targets: server CPU under "
            f"{CPU_TARGET_CORES:g} core {'met' if largest_cores < CPU_TARGET_CORES else 'MISSED'} "
            f"(largest total {largest_cores:.2f}); every follower within {LAG_TARGET_S} s "
            f"{'met' if max(worst) <= LAG_TARGET_S else 'MISSED'} (worst {max(worst) * 1e3:.0f} ms)"
            f"; memory added under {MEMORY_TARGET_MB:.0f} MB "
            f"{'met' if added < MEMORY_TARGET_MB else 'MISSED'}"
        )
        for follower_http, follower in followers:
            await follower.close()
            await follower_http.close()
        await presenter.update(playing=False)
        await presenter.close()
    return 0


def stored_run(revolutions: int) -> Path:
    """The dynamic run of ``revolutions`` revolutions of :data:`CASE` kept in :data:`STORE`:
    reused when it is complete and that long, else computed now (and kept)."""
    from solver import load_dataset

    path = STORE / f"{CASE}-{revolutions}-revolutions.nc"
    if path.exists():
        ds = load_dataset(path)
        try:
            done = float(ds.time[-1]) / float(ds.attrs["shaft_period_s"])
            if int(ds.attrs.get("complete", 0)) == 1 and abs(done - revolutions) < 0.5:
                print(f"reusing the stored run {path}")
                return path
        finally:
            ds.close()
        print(
            f"the stored run {path} is not a complete {revolutions}-revolution run: computed again"
        )
    STORE.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(".partial.nc")
    t0 = time.monotonic()
    subprocess.run(
        [
            sys.executable,
            "-m",
            "racetrace",
            "simulate",
            CASE,
            "--revolutions",
            str(revolutions),
            "--quiet",
            "--output",
            str(partial),
        ],
        check=True,
    )
    os.replace(partial, path)  # kept only once whole
    print(f"computed the {revolutions}-revolution run in {time.monotonic() - t0:.0f} s: {path}")
    return path


def main() -> int:
    from tests.helpers.serve import start_server, stop_server

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--run", type=Path, default=None, help="an existing run's .nc file")
    parser.add_argument("--revolutions", type=int, default=100, help="the run's length")
    parser.add_argument("--followers", type=int, default=30, help="websocket followers")
    parser.add_argument("--seconds", type=float, default=30.0, help="each measuring window")
    parser.add_argument(
        "--settle",
        type=float,
        default=15.0,
        help="seconds of playing before the first window (on a loaded machine the spare session "
        "takes seconds to start)",
    )
    parser.add_argument(
        "--alone", action="store_true", help="measure the presenter alone only (no followers)"
    )
    parser.add_argument(
        "--profile",
        type=Path,
        default=None,
        help="a folder for py-spy records of the front and the presenter's session with followers",
    )
    parser.add_argument(
        "--page-profile",
        type=Path,
        default=None,
        help="a .cpuprofile file for a V8 profile of the Chromium follower's page in that window",
    )
    parser.add_argument(
        "--follower-deflate",
        choices=("yes", "no"),
        default="no",
        help="yes: the websocket followers ask for compressed messages, as browsers do (their "
        "decompression then loads the benchmark's own process)",
    )
    parser.add_argument(
        "--presenter-webgl",
        choices=("yes", "no"),
        default="yes",
        help="what the presenter's page says of WebGL (no: the session draws every frame)",
    )
    parser.add_argument(
        "--render",
        choices=("browser", "server"),
        default="browser",
        help="where the 3-D view is drawn (browser: the app's default)",
    )
    args = parser.parse_args()
    run = args.run or stored_run(args.revolutions)
    root = Path(tempfile.mkdtemp(prefix="racetrace-follow-"))
    (root / "runs").mkdir()
    info = real_run(root / "runs", run, args.revolutions)
    server = start_server(root / "runs", root / "serve.log", "--render", args.render)
    try:
        return asyncio.run(measure(args, server, info))
    finally:
        stop_server(server, timeout_s=60)


if __name__ == "__main__":
    sys.exit(main())
