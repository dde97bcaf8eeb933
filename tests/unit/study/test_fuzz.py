"""Fuzz tests of study files and study folders through the CLI, in-process, with fixed seeds:
truncated, foreign, hostile and deeply nested input ends in exit 2 with a message (or, for input
that stays valid, in a normal run or table), never in an exception. tests/helpers/fuzz.py says how
the inputs are mutated."""

from __future__ import annotations

import json
import random
import shutil

import pytest

from racetrace import cli
from tests.helpers.fuzz import STUDY_BASES, mutated_json_bytes, mutated_study_bytes
from tests.helpers.studies import two_run_study_folder

#: Inputs per test: the same every run (seeds 0 ... N-1).
SEEDS = 200


@pytest.fixture
def no_cluster(monkeypatch):
    """``racetrace study`` stops where it would start the cluster: the valid studies are counted."""
    from racetrace.commands import study

    reached = []
    monkeypatch.setattr(study, "_run_study", lambda args, study, *rest: reached.append(study) or 0)
    return reached


def _ends_cleanly(code: int, err: str, valid_code: int) -> bool:
    if code == valid_code:
        return True
    assert code == 2, err
    assert "racetrace: invalid input:" in err and "Traceback" not in err, err
    assert len(err.strip().splitlines()) >= 2, f"no message: {err!r}"
    return False


def test_every_mutated_study_file_ends_cleanly(tmp_path, capsys, no_cluster):
    path = tmp_path / "fuzz.toml"
    invalid = 0
    for seed in range(SEEDS):
        path.write_bytes(mutated_study_bytes(random.Random(seed)))
        code = cli.main(["study", str(path), "--output", str(tmp_path / "out")])
        invalid += not _ends_cleanly(code, capsys.readouterr().err, 0)
        assert not (tmp_path / "out").exists()
    assert invalid > SEEDS // 2  # most mutations break the study ...
    assert no_cluster  # ... and some leave it valid


@pytest.fixture(scope="module")
def study_folder(tmp_path_factory):
    """A study folder with one finished and one failed run (written without Dask)."""
    return two_run_study_folder(
        tmp_path_factory.mktemp("fuzz") / "study", STUDY_BASES[0], "dynamic", "diverged"
    )


def test_every_mutated_study_folder_ends_cleanly(tmp_path, capsys, study_folder):
    folder = tmp_path / "study"
    names = ["study.json", "points/p0001.quasistatic.json", "points/p0002.dynamic.json"]
    originals = {name: json.loads((study_folder.path / name).read_text()) for name in names}
    invalid = 0
    for seed in range(SEEDS):
        rng = random.Random(seed)
        shutil.rmtree(folder, ignore_errors=True)
        shutil.copytree(study_folder.path, folder)
        name = rng.choice(names[:1] * 3 + names[1:])
        (folder / name).write_bytes(mutated_json_bytes(originals[name], rng))
        code = cli.main(["study", "show", str(folder)])
        captured = capsys.readouterr()
        if not _ends_cleanly(code, captured.err, 0):
            invalid += 1
            assert "not a study folder" in captured.err
    assert SEEDS // 2 < invalid < SEEDS
