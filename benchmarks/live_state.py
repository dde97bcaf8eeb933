"""Measure live mode at the page's state level, without a browser (run by hand, not in CI).

    python benchmarks/live_state.py [--changes N]

Starts a session of the app without rendering on the default case, starts live mode and calls the
live loop's tick 12 times a second, as the page's loop does; then changes the radial load
``--changes`` times (default 6), alternately up and down by 200 N, 1 s apart, and prints for each
the wall time from the change to the first frame on show (``live_frame``) whose radial load has
left the old value, and the playback the solver keeps. Timings are wall times on the machine as
loaded when run: state the load (``uptime``) with them.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main() -> int:
    from app.services import Services
    from app.state import DEFAULT_CASE, RacetraceApp
    from tests.helpers.app_session import trame_server

    parser = argparse.ArgumentParser()
    parser.add_argument("--changes", type=int, default=6)
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="racetrace-live-state-"))
    services = Services(folder / "runs", folder / "slots", max_runs=1)
    app = RacetraceApp(trame_server(), services=services, render=False)
    app.start(DEFAULT_CASE, play=False)
    s = app.state

    def run_for(seconds, condition=None) -> bool:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            begin = time.monotonic()
            app.live.tick()
            if condition is not None and condition():
                return True
            time.sleep(max(0.005, 1.0 / 12.0 - (time.monotonic() - begin)))
        return False

    try:
        t0 = time.monotonic()
        app.live.start()
        run_for(900, lambda: (s.live_frame or {}).get("serial", 0) > 5)
        print(f"Live started to the 6th live frame: {time.monotonic() - t0:.1f} s")
        load, latencies = 300.0, []
        for k in range(args.changes):
            load += 200.0 if k % 2 == 0 else -200.0
            old = s.live_frame["radial_load_N"]
            s.live_radial_load_N = load
            begin = time.monotonic()
            s.flush()
            seen = run_for(60, lambda: abs(s.live_frame["radial_load_N"] - old) > 0.5)  # noqa: B023
            latencies.append(time.monotonic() - begin if seen else None)
            run_for(1.0)
        text = ", ".join("none" if x is None else f"{x:.2f}" for x in latencies)
        print(f"control change to the first frame showing it (s): {text}")
        print(f"playback: {s.live_rate}")
        print(f"solver keeping up: {'no: ' + s.live_behind if s.live_behind else 'yes'}")
    finally:
        app.shutdown()
        services.shutdown()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
