"""A small study folder written without Dask, for the tests that read one."""

from __future__ import annotations

from pathlib import Path

#: The record of the finished run of :func:`two_run_study_folder`.
DONE_RECORD = {
    "status": "done",
    "message": "",
    "metrics": {"excursion": {"inner": 1.25, "outer": 2.5}, "cage_slip": 0.01},
    "wall_time_s": 0.1,
}


def two_run_study_folder(path: Path, study_text: str, failed_model: str, failed_message: str):
    """The :class:`solver.study.StudyFolder` at ``path`` of the study ``study_text`` (two points or
    more) with p0001 done (quasi-static, :data:`DONE_RECORD`) and p0002 failed (``failed_model``,
    ``failed_message``)."""
    from solver.study import Study, StudyFolder

    study = Study.from_text(study_text)
    folder = StudyFolder(path)
    folder.start(study.spec, study.points(), "test", resume=False)
    folder.save_run("p0001", "quasistatic", DONE_RECORD, None)
    folder.save_run("p0002", failed_model, {"status": "failed", "message": failed_message}, None)
    return folder
