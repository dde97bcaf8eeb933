"""How reproducible a case's accuracy-contract metrics are: one case run at several tolerances,
each compared with the tightest over the same fixed window (docs/numerics.md, "Accuracy
contract"). Run from the repository root:

    python -m tests.helpers.reference_spread [--case heavy_218] [--revolutions 30]
                                             [--tolerances 1e-6 3e-6 1e-4 1e-3]
                                             [--window-starts 5 10 15 20]

The cases and the contract are those of ``tests/helpers/accuracy.py``, beside which this lives.
For each window (from the given shaft revolution to the end of the run) the metrics are computed
on the same samples for every run: per (ball, race) mean contact angle and load, mean cage speed,
and each race's excursion and band thickness in its own ring's frame
(``solver.results.summary.track_metrics``).
Printed: each run's deviation as a fraction of the contract's allowance (<= 1 meets it). When two
runs at reference-quality tolerances (1e-6, 3e-6) already differ by more than the allowance, the
case's metrics are not reproducible to the contract's precision and no method can be checked on
it. Also prints the per-revolution mean contact angle of each race of the tightest run (the
settling criterion of solver.results.summary compares these).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from solver.models.dynamic import SimulationOptions, simulate
from tests.helpers import accuracy as A


def revolution_means(ds, period: float) -> np.ndarray:
    """(revolutions, 2) mean contact angle [deg] of the loaded contacts of each race."""
    times = ds["time"].values
    rev = np.floor(times / period + 1e-9).astype(int)
    count = int(math.floor(times[-1] / period + 1e-9))
    angle = ds["contact_angle"].values
    load = ds["contact_load"].values
    out = np.full((count, 2), np.nan)
    for k in range(count):
        m = rev == k
        for race in range(2):
            a = angle[:, race, m]
            loaded = load[:, race, m] > 0.0
            if loaded.any():
                out[k, race] = a[loaded].mean()
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="heavy_218", choices=list(A.CASES))
    parser.add_argument("--revolutions", type=float, default=30.0)
    parser.add_argument("--tolerances", type=float, nargs="+", default=[1e-6, 3e-6, 1e-4, 1e-3])
    parser.add_argument("--window-starts", type=float, nargs="+", default=[5.0, 10.0, 15.0, 20.0])
    args = parser.parse_args(argv)
    inputs = A.case_inputs(args.case)
    op = inputs.operating
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    runs = {}
    for tol in sorted(args.tolerances):
        start = time.perf_counter()
        options = SimulationOptions(
            shaft_revolutions=args.revolutions, samples_per_revolution=180, tolerance=tol
        )
        runs[tol] = simulate(inputs, options=options)
        print(
            f"tolerance {tol:g}: {runs[tol].attrs['steps']} steps, "
            f"{time.perf_counter() - start:.1f} s wall",
            flush=True,
        )
    tight = min(runs)
    means = revolution_means(runs[tight], period)
    print(f"\nper-revolution mean contact angle [deg] at tolerance {tight:g} (inner, outer):")
    for k, (inner, outer) in enumerate(means):
        change = ""
        if k > 0:
            change = f"   change {inner - means[k - 1, 0]:+.4f} {outer - means[k - 1, 1]:+.4f}"
        print(f"  revolution {k + 1:3d}: {inner:.4f} {outer:.4f}{change}")
    for first in args.window_starts:
        ref = A.window_metrics(runs[tight], first * period)
        print(
            f"\nwindow from revolution {first:g}: reference excursion "
            f"{np.round(ref['excursion_deg'], 3).tolist()} deg, band thickness "
            f"{np.round(ref['band_thickness_deg'], 3).tolist()} deg; deviation / allowance:"
        )
        for tol, ds in runs.items():
            if tol == tight:
                continue
            dev = A.deviations(A.window_metrics(ds, first * period), ref)
            print(f"  tolerance {tol:g}: " + ", ".join(f"{k} {v:.2f}" for k, v in dev.items()))
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
