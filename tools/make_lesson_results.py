"""Regenerate the shipped lesson results: assets/lessons/results/<lesson>--<result>.nc.

Solves every result of every shipped lesson (assets/lessons/*.toml) whose shipped file is missing
or out of date (its fingerprint or its case title differs), writes it as compressed NetCDF and
removes files no lesson uses. Prints each file's size and the time its solve took.

    python tools/make_lesson_results.py            # only what is missing or out of date
    python tools/make_lesson_results.py --all      # solve everything again
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.lessons.format import load_lessons  # noqa: E402
from app.lessons.results import (  # noqa: E402
    FINGERPRINT_ATTR,
    compute,
    fingerprint,
    save_compressed,
    shipped_name,
)

LESSONS = ROOT / "assets" / "lessons"
RESULTS = LESSONS / "results"


def _current(path: Path, wanted: str, title: str) -> bool:
    """The file holds the result of this fingerprint, solved under the result's title (the title
    the app's form shows with it)."""
    if not path.is_file():
        return False
    from solver.results.io import load_dataset

    ds = load_dataset(path)
    return ds.attrs.get(FINGERPRINT_ATTR) == wanted and ds.attrs.get("title") == title


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="solve every result again")
    args = parser.parse_args(argv)
    lessons = load_lessons(LESSONS)
    for problem in lessons.problems:
        print(f"skipped: {problem}")
    RESULTS.mkdir(exist_ok=True)
    used = set()
    for lesson in lessons.lessons:
        for spec in lesson.results:
            path = RESULTS / shipped_name(lesson, spec)
            used.add(path.name)
            if not args.all and _current(path, fingerprint(spec), spec.title):
                print(f"{path.name}: up to date ({path.stat().st_size / 1e6:.2f} MB)")
                continue
            start = time.perf_counter()
            ds = compute(spec)
            seconds = time.perf_counter() - start
            save_compressed(ds, path)
            print(f"{path.name}: {spec.model}, {seconds:.1f} s, {path.stat().st_size / 1e6:.2f} MB")
    for stale in sorted(RESULTS.glob("*.nc")):
        if stale.name in used:
            continue
        if lessons.problems:  # it may be a skipped lesson's: keep it until the lessons load
            print(f"{stale.name}: kept (unused, but a lesson above was skipped)")
            continue
        stale.unlink()
        print(f"{stale.name}: removed (no lesson uses it)")
    return 1 if lessons.problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
