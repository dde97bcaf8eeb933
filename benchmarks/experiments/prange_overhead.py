"""Would ``numba.prange`` over the balls pay? Times a loop over 18 balls serially and with
``prange`` (numba's threading layer, all cores) for several amounts of work per ball.

    python benchmarks/prange_overhead.py

One right-hand-side evaluation of the dynamic model does about 0.7 us of contact work per ball
(spindle, slip curve; docs/numerics.md "Cost of one evaluation"). The figures printed are the
best of 15 batches of 2000 calls, in microseconds per call: prange pays only where the serial time
exceeds the parallel one by more than the noise, and only when the other cores are free (a study
runs one single-threaded worker per core, so there they are not).
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np
from numba import njit, prange

BALLS = 18


@njit(inline="always")
def _ball_work(x, n):
    """Stand-in for one ball's contact work: n square roots and exponentials."""
    s = 0.0
    for i in range(n):
        s += math.sqrt(x + i) * math.exp(-x * 1e-3 * i)
    return s


@njit(parallel=True)
def parallel_loop(out, n):
    for j in prange(out.shape[0]):
        out[j] = _ball_work(j * 0.1 + 1.0, n)


@njit
def serial_loop(out, n):
    for j in range(out.shape[0]):
        out[j] = _ball_work(j * 0.1 + 1.0, n)


def best_time(function, out, n, batches=15, calls=2000) -> float:
    """Best time of one call [s] over ``batches`` batches of ``calls`` calls."""
    function(out, n)
    best = math.inf
    for _ in range(batches):
        start = time.perf_counter()
        for _ in range(calls):
            function(out, n)
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def main() -> int:
    out = np.zeros(BALLS)
    serial_loop(out, 1)
    parallel_loop(out, 1)
    print(
        f"{BALLS} balls, {numba.get_num_threads()} threads, threading layer "
        f"{numba.threading_layer()}"
    )
    for n in (1, 20, 80, 200):
        serial = best_time(serial_loop, out, n) * 1e6
        parallel = best_time(parallel_loop, out, n) * 1e6
        print(
            f"  work per ball {serial / BALLS:5.2f} us: serial {serial:6.2f} us, "
            f"prange {parallel:6.2f} us, ratio {parallel / serial:4.2f}"
        )
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
