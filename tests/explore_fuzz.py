"""Explore new fuzz inputs by hand (not in CI): how racetrace copes with mutated input files.

    python -m tests.explore_fuzz --surface case --seeds 1000-2000
    python -m tests.explore_fuzz --surface report --seeds 1-200 --surface export --seeds 1-2000

Each seed makes one input with the generators the fuzz tests use (tests/helpers/fuzz.py), so an
input found here is reproduced by its seed: ``random.Random(seed)``. Surfaces:

- ``case``: a mutated case file through decoding, parsing, validation, the TOML writer, the
  quasi-static solver and its JSON summary (:func:`tests.helpers.fuzz.outcome`);
- ``report`` and ``export``: a mutated result file given to ``racetrace report`` or ``racetrace
  export --csv`` (:func:`tests.helpers.fuzz.result_outcome`).

Each input ends in one of the surface's clean outcomes, a traceback (any other exception or a
failed check of the outcome) or a hang (longer than the surface's limit). Prints, per surface, the
inputs tried, the outcomes, the tracebacks (grouped by where they were raised, with a seed of
each) and the hangs; exits 1 when there was a traceback or a hang.
"""

from __future__ import annotations

import argparse
import collections
import random
import signal
import sys
import tempfile
import time
import traceback

#: Seconds after which an input counts as a hang, per surface (a report builds a page with a 3-D
#: scene: it takes seconds on a busy machine).
HANG_S = {"case": 20, "report": 180, "export": 30}
SURFACES = tuple(HANG_S)


class Hang(Exception):
    """An input ran past its surface's time limit."""


def _alarm(signum, frame):  # noqa: ARG001 - signal handler signature
    raise Hang


def seed_range(text: str) -> range:
    """``"1000-2000"`` -> range(1000, 2000); ``"7"`` -> range(7, 8)."""
    first, _, last = text.partition("-")
    start = int(first)
    stop = int(last) if last else start + 1
    if stop <= start:
        raise argparse.ArgumentTypeError(f"{text}: give FIRST-LAST with LAST > FIRST")
    return range(start, stop)


def _one(surface: str, seed: int, folder: str) -> str:
    from tests.helpers import fuzz

    rng = random.Random(seed)
    if surface == "case":
        return fuzz.outcome(fuzz.mutated_case_bytes(rng))
    return fuzz.result_outcome(fuzz.mutated_result_bytes(rng), surface, folder)


def warm_up(surface: str, folder: str) -> None:
    """One valid input, untimed: the first one pays for compiling the kernels (or importing the
    report's libraries), which is no hang."""
    from tests.helpers import fuzz

    if surface == "case":
        fuzz.outcome(fuzz.BASES[0].encode())
    else:
        content = (fuzz.ROOT / fuzz.RESULT_BASES[0]).read_bytes()
        fuzz.result_outcome(content, surface, folder)


def explore(surface: str, seeds: range) -> dict:
    """Counts of the outcomes of ``surface`` over ``seeds``, with the tracebacks by place."""
    counts = collections.Counter()
    places: dict[str, list[int]] = collections.defaultdict(list)
    slowest = 0.0
    previous = signal.signal(signal.SIGALRM, _alarm)
    try:
        with tempfile.TemporaryDirectory() as folder:
            warm_up(surface, folder)
            for seed in seeds:
                start = time.perf_counter()
                signal.alarm(HANG_S[surface])
                try:
                    counts[_one(surface, seed, folder)] += 1
                except Hang:
                    counts["hang"] += 1
                    places["hang"].append(seed)
                except Exception as error:  # noqa: BLE001 - counting every kind of failure
                    counts["traceback"] += 1
                    where = traceback.extract_tb(error.__traceback__)[-1]
                    places[f"{type(error).__name__} at {where.filename}:{where.lineno}"].append(
                        seed
                    )
                finally:
                    signal.alarm(0)
                slowest = max(slowest, time.perf_counter() - start)
    finally:
        signal.signal(signal.SIGALRM, previous)
    return {"counts": counts, "places": places, "slowest": slowest}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--surface", action="append", choices=SURFACES, help="what to fuzz (repeat for several)"
    )
    parser.add_argument(
        "--seeds",
        action="append",
        type=seed_range,
        help="seeds FIRST-LAST of each --surface (one --seeds for all, or one per --surface)",
    )
    args = parser.parse_args(argv)
    surfaces = args.surface or list(SURFACES)
    seeds = args.seeds or [range(1000, 1100)]
    if len(seeds) == 1:
        seeds = seeds * len(surfaces)
    if len(seeds) != len(surfaces):
        parser.error("give one --seeds, or one per --surface")
    failed = False
    print(f"{'surface':8s} {'inputs':>7s} {'tracebacks':>10s} {'hangs':>6s}  outcomes")
    for surface, chosen in zip(surfaces, seeds, strict=True):
        started = time.perf_counter()
        found = explore(surface, chosen)
        counts = found["counts"]
        clean = ", ".join(
            f"{n} {name}" for name, n in sorted(counts.items()) if name not in ("traceback", "hang")
        )
        print(
            f"{surface:8s} {len(chosen):7d} {counts['traceback']:10d} {counts['hang']:6d}  {clean}"
            f" (seeds {chosen.start}-{chosen.stop}, slowest {found['slowest']:.1f} s, all "
            f"{time.perf_counter() - started:.0f} s)",
            flush=True,
        )
        for place, which in found["places"].items():
            print(f"    {len(which)} x {place} (seeds {', '.join(map(str, which[:5]))})")
        failed = failed or bool(counts["traceback"] or counts["hang"])
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
