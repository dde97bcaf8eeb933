"""Regenerate the shipped study results: assets/studies/results/<study>.study.nc.

Runs every shipped study (assets/studies/*.toml) whose shipped study Dataset is missing or out of
date (its ``results_fingerprint`` differs from the study's: a study file, its base case or
``solver.RESULTS_VERSION`` changed), on a local Dask cluster, and writes its study Dataset.
Prints each file's size and how long the study took.

    python tools/make_study_results.py            # only what is missing or out of date
    python tools/make_study_results.py --all      # run every study again
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import solver  # noqa: E402

STUDIES = ROOT / "assets" / "studies"
RESULTS = STUDIES / "results"


def shipped_path(study_file: Path) -> Path:
    return RESULTS / f"{study_file.stem}.study.nc"


def _current(path: Path, wanted: str) -> bool:
    return path.is_file() and solver.load_dataset(path).attrs.get("results_fingerprint") == wanted


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="run every study again")
    parser.add_argument("--workers", type=int, default=2, help="local Dask workers (default 2)")
    args = parser.parse_args(argv)
    RESULTS.mkdir(exist_ok=True)
    for study_file in sorted(STUDIES.glob("*.toml")):
        study = solver.Study.from_file(study_file)
        path = shipped_path(study_file)
        if not args.all and _current(path, study.fingerprint()):
            print(f"{path.name}: up to date ({path.stat().st_size / 1e6:.2f} MB)")
            continue
        start = time.perf_counter()
        with tempfile.TemporaryDirectory() as tmp:
            ds = study.run(Path(tmp) / study_file.stem, workers=args.workers)
        failed = int((ds["status"] == "failed").sum())
        solver.save_dataset(ds, path)
        print(
            f"{path.name}: {ds.sizes['point']} points, {failed} failed, "
            f"{time.perf_counter() - start:.0f} s, {path.stat().st_size / 1e6:.2f} MB"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
