"""Measure the browser app against the targets of issue 4 (run by hand, not in CI).

    python benchmarks/app_frames.py [--runs-dir DIR]

Starts ``racetrace serve`` on a free port and drives headless Chromium (/usr/bin/chromium):
- first 3-D frame: seconds from navigation start to the first image in #view-3d;
- frames shown while playing: distinct images received by #view-3d per second over 8 s;
- quasi-static preview refresh: seconds from a field edit (axial load) until the browser has the
  new result (state ``result_serial`` advanced; includes the 0.1 s debounce);
- server memory: resident set size of the server process after loading a run of 100 shaft
  revolutions at 180 samples per revolution (a synthetic dynamic result of that size, written to the
  runs folder before start; a real 100-revolution dynamic run takes far longer to compute).
"""

from __future__ import annotations

import argparse
import math
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import numpy as np
import xarray as xr

ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def synthetic_run(runs_dir: Path, revolutions=100, samples=180):
    """A dynamic-schema result of the size of a 100-revolution run of the default case."""
    from app.runs import RunStore
    from solver.catalogue import catalogue

    case = catalogue().get("spindle-combined-load").load()
    z = case.bearing.ball_count
    omega = case.operating.inner_ring_speed_rpm * 2 * math.pi / 60
    n = revolutions * samples + 1
    t = np.linspace(0, revolutions * 2 * math.pi / omega, n)
    psi = 2 * math.pi * np.arange(z)[:, None] / z + 0.44 * omega * t[None, :]
    shape = (z, 2, n)
    alpha = 17 + np.cos(psi)[:, None, :] * np.ones(shape)
    pm = case.bearing.pitch_diameter_mm / 2e3
    centre = np.stack([np.zeros_like(psi), pm * np.cos(psi), pm * np.sin(psi)], axis=1)
    half = -500 * t[None, :] * np.ones((z, 1))
    quat = np.stack([np.cos(half), np.sin(half), 0 * half, 0 * half], axis=1)
    race = np.stack([np.mod(psi - omega * t, 2 * np.pi), np.mod(psi, 2 * np.pi)], axis=1)
    ones = np.ones(shape)
    ds = xr.Dataset(
        {
            "contact_angle": (("ball", "race", "time"), alpha),
            "contact_load": (("ball", "race", "time"), 200 * ones),
            "ellipse_semi_major": (("ball", "race", "time"), 5e-4 * ones),
            "ellipse_semi_minor": (("ball", "race", "time"), 9e-5 * ones),
            "max_pressure": (("ball", "race", "time"), 1.8e9 * ones),
            "raceway_azimuth": (("ball", "race", "time"), np.degrees(race)),
            "ball_azimuth": (("ball", "time"), np.degrees(np.mod(psi, 2 * np.pi))),
            "ball_center": (("ball", "axis", "time"), centre),
            "ball_orientation": (("ball", "quaternion", "time"), quat),
            "cage_speed": (("time",), np.full(n, 0.44 * omega)),
        },
        coords={
            "time": t,
            "ball": np.arange(z),
            "race": ["inner", "outer"],
            "axis": ["x", "y", "z"],
            "quaternion": ["w", "x", "y", "z"],
        },
        attrs={"model": "dynamic", "case": case.to_toml(), "complete": 1, "software": "benchmark"},
    )
    return RunStore(runs_dir).save(ds, case.to_toml(), "synthetic 100-revolution run")


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def main() -> int:
    from playwright.sync_api import sync_playwright

    parser = argparse.ArgumentParser()
    parser.add_argument("--runs-dir", default=None)
    args = parser.parse_args()
    runs = Path(args.runs_dir or tempfile.mkdtemp(prefix="racetrace-bench-"))
    info = synthetic_run(runs)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t_start = time.monotonic()
    proc = subprocess.Popen(
        [sys.executable, "-m", "racetrace", "serve", "--port", str(port), "--runs-dir", str(runs)],
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
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1500, "height": 1000})
            t0 = time.monotonic()
            page.goto(url)
            page.wait_for_selector("#view-3d img[src]", timeout=60_000)
            print(f"first 3-D frame after navigation: {time.monotonic() - t0:.2f} s")
            page.evaluate("""() => { window.__frames = 0;
                const img = document.querySelector('#view-3d img');
                new MutationObserver(() => window.__frames++).observe(img, {attributes: true,
                attributeFilter: ['src']}); }""")
            time.sleep(8)
            frames = page.evaluate("window.__frames")
            print(f"frames shown while playing: {frames / 8:.1f} /s")
            page.locator("#play-button").click()  # pause
            times = []
            for load in ("650", "800", "950"):
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
                + ", ".join(f"{x:.2f}" for x in times)
                + " s"
            )
            before = rss_mb(proc.pid)
            page.locator("#runs-select .v-field").click()
            page.locator(".v-overlay--active .v-list-item").first.click()
            page.wait_for_function(
                f"document.body.innerText.includes('{info.title}')", timeout=120_000
            )
            time.sleep(2)
            print(
                f"server memory: {before:.0f} MB before, {rss_mb(proc.pid):.0f} MB with the "
                f"100-revolution run loaded ({info.run_id})"
            )
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    return 0


if __name__ == "__main__":
    sys.exit(main())
