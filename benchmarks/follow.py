"""Follow mode under a class (issue 26): followers watching a presenter play a 100-revolution run.

    python benchmarks/follow.py [--run FILE.nc] [--followers 30] [--seconds 20]

Starts ``racetrace serve`` on a free loopback port with a runs folder holding a real dynamic run
of 100 shaft revolutions of the default case (computed first unless ``--run FILE`` gives one,
:func:`app_frames.real_run`). A presenter (a websocket client that speaks to its session as the
page does, :class:`tests.helpers.wslink_client.WslinkClient`) opens the run and plays it; then
``--followers`` websocket followers (the same protocol, through ``/follow/CODE/ws``: hello, the
whole state, then every state change and image the session publishes) and one headless Chromium
follower (``/?follow=CODE``, /usr/bin/chromium) join. Printed, for ``--seconds`` of playing
alone and then with the followers:

- server CPU: CPU time of the server's processes (front, sessions, fork server; from
  /proc/PID/stat) over wall time, in cores;
- frame lag: for each follower, how long after the presenter each frame index arrived (median,
  95th percentile and largest, over the frames both saw), and the frames it never saw;
- memory: proportional set size of the server's processes before and with the followers.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

# run as a script, sys.path[0] is benchmarks/: put the repository first
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from app_frames import _tree, real_run, rss_mb  # noqa: E402

from tools.chromium import CHROMIUM, LAUNCH_ARGS  # noqa: E402

TICKS = os.sysconf("SC_CLK_TCK")
# in the browser follower: each frame index as it arrives, with the wall-clock time (ms)
FRAME_PROBE = """() => { window.__frames = [];
  window.trame.state.watch(['frame'], (f) => window.__frames.push([f, Date.now()])); }"""


def cpu_s(pid: int) -> float:
    """CPU time (user + system, s) of ``pid`` and every process below it."""
    total = 0
    for p in _tree(pid):
        try:
            fields = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += int(fields[11]) + int(fields[12])  # utime, stime
    return total / TICKS


def lags(reference: list[tuple[float, int]], seen: list[tuple[float, int]]):
    """Seconds after ``reference`` that ``seen`` got each frame index both got (first arrival of
    each index), and how many of the reference's frames ``seen`` never got."""
    first: dict[int, float] = {}
    for t, f in seen:
        first.setdefault(f, t)
    out, missing = [], 0
    for t, f in _first_of(reference):
        if f in first:
            out.append(first[f] - t)
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


async def measure(args, server: dict, info) -> int:
    import aiohttp

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
        await presenter.wait_for("result_label", lambda s: info.title in str(s), timeout=300)
        frames = presenter.state.get("frame_max")
        print(f"presenter: the {info.title!r} run open ({frames} frames), join code {code}")
        await presenter.update(playing=True)
        await asyncio.sleep(3)

        async def window(label: str) -> tuple[float, float]:
            await asyncio.sleep(0)
            c0, t0 = cpu_s(pid), time.monotonic()
            images0 = presenter.images
            await asyncio.sleep(args.seconds)
            cores = (cpu_s(pid) - c0) / (time.monotonic() - t0)
            fps = (presenter.images - images0) / args.seconds
            print(
                f"{label}: server CPU {cores:.2f} cores, {fps:.1f} images/s to the presenter, "
                f"memory {rss_mb(pid):.0f} MB"
            )
            return cores, t0

        alone, _ = await window("presenter alone")
        memory_alone = rss_mb(pid)

        followers = []
        for _ in range(args.followers):
            follower_http = aiohttp.ClientSession(cookie_jar=aiohttp.CookieJar(unsafe=True))
            async with follower_http.get(
                f"{base}/?follow={code}", headers={"Accept": "text/html"}
            ) as page:
                assert page.status == 200, page.status
            follower = WslinkClient()
            await follower.connect(follower_http, f"ws://127.0.0.1:{port}/follow/{code}/ws", base)
            followers.append((follower_http, follower))

        from playwright.async_api import async_playwright

        async with async_playwright() as p:
            browser = await p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            page = await browser.new_page(viewport={"width": 1280, "height": 800})
            await page.goto(f"{base}/?follow={code}")
            await page.wait_for_function(
                "window.trame && window.trame.state && window.trame.state.get('follow_code')",
                timeout=120_000,
            )
            await page.evaluate(FRAME_PROBE)
            await asyncio.sleep(3)
            count = presenter.state.get("follow_count")
            memory_with = rss_mb(pid)
            wall0, mono0 = time.time(), time.monotonic()
            for _, follower in followers:
                follower.frames.clear()
            presenter.frames.clear()
            with_followers, t0 = await window(f"with {count} followers")
            reference = [x for x in presenter.frames if x[0] >= t0]
            worst = []
            for i, (_, follower) in enumerate(followers):
                got, missing = lags(reference, follower.frames)
                worst.append(max(got) if got else float("inf"))
                if i < 3 or i == len(followers) - 1:
                    print(f"   follower {i + 1:2d}: {describe(got)}, {missing} frames not seen")
            shown = await page.evaluate("window.__frames")
            browser_frames = [(mono0 + (ms / 1e3 - wall0), f) for f, ms in shown]
            got, missing = lags(reference, browser_frames)
            worst.append(max(got) if got else float("inf"))
            print(f"   browser follower: {describe(got)}, {missing} frames not seen")
            print(
                f"largest frame lag over every follower: {max(worst) * 1e3:.0f} ms; "
                f"the presenter got {len(_first_of(reference))} frame indices in {args.seconds} s"
            )
            print(
                f"server: {alone:.2f} cores alone, {with_followers:.2f} cores with the followers; "
                f"memory {memory_alone:.0f} MB alone, {memory_with:.0f} MB with them "
                f"(+{memory_with - memory_alone:.0f} MB)"
            )
            await browser.close()
        for follower_http, follower in followers:
            await follower.close()
            await follower_http.close()
        await presenter.update(playing=False)
        await presenter.close()
    return 0


def main() -> int:
    from tests.helpers.serve import start_server, stop_server

    parser = argparse.ArgumentParser()
    parser.add_argument("--run", type=Path, default=None, help="existing 100-revolution .nc")
    parser.add_argument(
        "--revolutions", type=int, default=100, help="the run's length (its title, with --run)"
    )
    parser.add_argument("--followers", type=int, default=30, help="websocket followers")
    parser.add_argument("--seconds", type=float, default=20.0, help="each measuring window")
    args = parser.parse_args()
    root = Path(tempfile.mkdtemp(prefix="racetrace-follow-"))
    (root / "runs").mkdir()
    info = real_run(root / "runs", args.run, args.revolutions)
    print(f"runs folder {root / 'runs'} (pass its .nc.src file as --run next time)")
    server = start_server(root / "runs", root / "serve.log")
    try:
        return asyncio.run(measure(args, server, info))
    finally:
        stop_server(server, timeout_s=60)


if __name__ == "__main__":
    sys.exit(main())
