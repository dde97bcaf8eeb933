"""Follow mode under a class (issue 26): followers watching a presenter play a 100-revolution run.

    python benchmarks/follow.py [--run FILE.nc] [--followers 30] [--seconds 30] [--render browser]

The run: a dynamic run of ``--revolutions`` (100) shaft revolutions of the default case
(``spindle-combined-load``). ``--run FILE`` gives one; otherwise the one stored in
``~/.cache/racetrace/benchmarks/`` is reused when it is complete and that long, or computed once
there (``racetrace simulate``: about a minute on a free core) and kept for the next time.

Starts ``racetrace serve`` (``--render``: browser, the app's default, or server) on a free loopback
port with a runs folder holding that run. A presenter (a websocket client that speaks to its
session as the page does, :class:`tests.helpers.wslink_client.WslinkClient`) opens the run and
plays it; then ``--followers`` websocket followers (the same protocol, through
``/follow/CODE/ws``: hello, the whole state, then every state change and image the session
publishes) and one headless Chromium follower at 1280 x 800 (``/?follow=CODE``, /usr/bin/chromium)
join. Printed, for ``--seconds`` of playing alone and then with the followers:

- server CPU in cores (CPU time of the processes over wall time, from /proc/PID/stat, sampled every
  second): the front, the sessions (the presenter's, the spare and the fork server: the latter two
  idle) and their sum, median and largest of the 1-s samples;
- frame lag: for each frame index the presenter got (its first arrival), how long after it each
  follower showed that index or a later one; median and largest per follower kind, the followers
  ever over 0.5 s, and the frames a follower never reached (the window must not wrap around the
  end of the run: 720 of the 100-revolution run's 18 000 frames in 30 s);
- memory: proportional set size of the server's processes before and with the followers.
"""

from __future__ import annotations

import argparse
import asyncio
import bisect
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
# in the browser follower: each frame index as it arrives, with the wall-clock time (ms): from the
# state's watcher, and read every 20 ms as well (whichever sees an index first counts)
FRAME_PROBE = """() => { window.__frames = [];
  const note = (f) => window.__frames.push([f, Date.now()]);
  window.trame.state.watch(['frame'], note);
  let last = null;
  setInterval(() => { const f = window.trame.state.get('frame');
                      if (f !== last) { last = f; note(f); } }, 20); }"""


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
    """Cores used by the server's front (``pid``) and by its sessions (every process below it),
    sampled every ``every_s`` seconds while running (:meth:`run` as a task)."""

    def __init__(self, pid: int, every_s: float = 1.0):
        self.pid, self.every_s = pid, every_s
        self.samples: list[tuple[float, float]] = []  # (front, sessions) cores per interval

    async def run(self) -> None:
        before, t0 = cpu_ticks(self.pid), time.monotonic()
        while True:
            await asyncio.sleep(self.every_s)
            now, t = cpu_ticks(self.pid), time.monotonic()
            # a process that ended since counts its last interval as nothing
            used = {p: now[p] - before.get(p, 0) for p in now}
            seconds = (t - t0) * TICKS
            front = used.pop(self.pid, 0) / seconds
            self.samples.append((front, sum(used.values()) / seconds))
            before, t0 = now, t


def cores_line(samples: list[tuple[float, float]]) -> tuple[str, float]:
    """The front's, the sessions' and the total cores (median / largest) in words; the largest
    total."""
    if not samples:
        return "no samples", float("nan")
    parts, largest = [], 0.0
    for name, values in (
        ("front", [f for f, _ in samples]),
        ("sessions", [x for _, x in samples]),
        ("total", [f + x for f, x in samples]),
    ):
        parts.append(f"{name} {statistics.median(values):.2f} / {max(values):.2f}")
        largest = max(values)
    return ", ".join(parts) + f" (median / largest of {len(samples)} 1-s samples)", largest


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


def describe(values: list[float]) -> str:
    if not values:
        return "no frames in common"
    values = sorted(values)
    p95 = values[min(len(values) - 1, int(0.95 * len(values)))]
    return (
        f"median {statistics.median(values) * 1e3:5.0f} ms, 95 % {p95 * 1e3:5.0f} ms, "
        f"largest {values[-1] * 1e3:5.0f} ms"
    )


async def window(seconds: float, pid: int, presenter) -> tuple[list, float]:
    """Play on for ``seconds`` sampling the server's CPU: the samples and the window's start."""
    presenter.frames.clear()
    sampler = CpuSampler(pid)
    t0 = time.monotonic()
    task = asyncio.get_running_loop().create_task(sampler.run())
    await asyncio.sleep(seconds)
    task.cancel()
    return sampler.samples, t0


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
        await presenter.update(playing=False)
        await presenter.update(run_id=info.run_id)
        await presenter.wait_for("result_label", lambda s: info.title in str(s), timeout=600)
        frames = presenter.state.get("frame_max")
        print(f"presenter: the {info.title!r} run open ({frames} frames), join code {code}")
        await presenter.update(playing=True)
        await asyncio.sleep(3)

        alone, t0 = await window(args.seconds, pid, presenter)
        played_alone = len(_first_of([x for x in presenter.frames if x[0] >= t0]))
        memory_alone = rss_mb(pid)
        text, _ = cores_line(alone)
        print(f"presenter alone: server CPU {text}")
        print(f"   {played_alone / args.seconds:.1f} frames/s played, memory {memory_alone:.0f} MB")

        followers = []
        joining = time.monotonic()
        for _ in range(args.followers):
            follower_http = aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True))
            async with follower_http.get(
                f"{base}/?follow={code}", headers={"Accept": "text/html"}
            ) as page:
                assert page.status == 200, page.status
            follower = WslinkClient()
            # the whole state (the scene of a 100-revolution run) for each: slow on a loaded machine
            await follower.connect(
                follower_http, f"ws://127.0.0.1:{port}/follow/{code}/ws", base, timeout=600
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
            await page.goto(f"{base}/?follow={code}")
            await page.wait_for_function(
                "window.trame && window.trame.state && window.trame.state.get('follow_code')",
                timeout=300_000,
            )
            await page.evaluate(FRAME_PROBE)
            count = await presenter.wait_for(
                "follow_count", lambda n: n == args.followers + 1, timeout=120
            )
            await asyncio.sleep(3)
            memory_with = rss_mb(pid)
            for _, follower in followers:
                follower.frames.clear()
            wall0, mono0 = time.time(), time.monotonic()
            with_followers, t0 = await window(args.seconds, pid, presenter)
            reference = [x for x in presenter.frames if x[0] >= t0]
            played = len(_first_of(reference))
            shown = await page.evaluate("window.__frames || []")
            now_showing = await page.evaluate("window.trame.state.get('frame')")
            presenter_showing = presenter.state.get("frame")
            await browser.close()

        text, largest_cores = cores_line(with_followers)
        print(f"with {count} followers: server CPU {text}")
        print(f"   {played / args.seconds:.1f} frames/s played, memory {memory_with:.0f} MB")
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
            f"   the Chromium follower: {describe(got)}; {not_seen} of {played} frames not reached "
            f"({len(shown)} frame changes noted; frame {now_showing} at the end, the presenter's "
            f"{presenter_showing})"
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
