"""The points of a study: one validated case per combination of the varied values.

:func:`study_points` expands every sweep of a :class:`~solver.study.spec.StudySpec` (``grid``:
every combination, the last key changing fastest; ``zip``: the lists taken together) into
:class:`StudyPoint` objects, each holding its case (the base case with the sweep's ``set`` values,
the point's varied values and the ``[run]`` length applied, titled by :func:`point_title`) and
validated as a case file would be.
An invalid point raises CaseError naming the point, its values and the study key.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from solver.case import Case, load_case
from solver.catalogue import resolve_case
from solver.errors import CaseError, Problem

from .spec import StudySpec

#: The models a point's ``model`` value runs.
MODEL_RUNS = {
    "quasistatic": ("quasistatic",),
    "dynamic": ("dynamic",),
    "both": ("quasistatic", "dynamic"),
}


@dataclass(frozen=True)
class StudyPoint:
    """One point: ``index`` from 0 in study order, ``name`` (``p0001``...), the sweep it belongs
    to, the values it changes (dotted case key -> value, as written in the study), the validated
    case and the models it runs."""

    index: int
    name: str
    sweep: str
    values: dict
    case: Case
    models: tuple[str, ...]

    def label(self) -> str:
        """``radial_load_N=300, misalignment_frame='ring'`` (short key names)."""
        return ", ".join(f"{k.rsplit('.', 1)[-1]}={v!r}" for k, v in self.values.items())


def point_name(index: int) -> str:
    return f"p{index + 1:04d}"


def point_title(case: Case, name: str) -> str:
    """The title of a point's case: its bearing and its own operating point, and the point's name
    (``7008C-class hybrid, 10 000 rpm, 400 N axial + 0 N radial (study point p0003)``), so that
    a point's result and report never carry the base case's operating point."""
    from solver.inputs import describe_operating_point, operating_point

    operating = describe_operating_point(operating_point(case.operating))
    return f"{case.bearing.designation}, {operating} (study point {name})"


def base_case(spec: StudySpec) -> Case:
    """The study's base case; CaseError with key ``base`` when it cannot be read."""
    try:
        if spec.base_path is not None:
            return load_case(spec.base_path)
        return resolve_case(spec.base)
    except CaseError as error:
        raise CaseError(
            [Problem("base", f"base = {spec.base!r}: {p.message}") for p in error.problems]
        ) from None


def _combinations(sweep) -> list[dict]:
    keys = list(sweep.vary)
    if sweep.combine == "zip":
        rows = zip(*(sweep.vary[k] for k in keys), strict=True)
    else:
        rows = itertools.product(*(sweep.vary[k] for k in keys))
    return [dict(zip(keys, row, strict=True)) for row in rows]


def _study_dynamic_problems(case) -> list[Problem]:
    """Why a study cannot run the dynamic model on the point ``case``: the model's own rules
    (:func:`solver.case.dynamic_problems`); a study keeps the quasi-static values of a bearing
    set only (:mod:`.metrics`), so a set's point runs the quasi-static model."""
    from solver.case import dynamic_problems

    if getattr(case, "bearing_set", None) is not None:
        return [
            Problem(
                "model",
                "a study of a bearing set runs the quasi-static model only (model = "
                "'quasistatic'); run one set case's dynamic model with racetrace simulate",
            )
        ]
    return dynamic_problems(case)


def study_points(spec: StudySpec, base: Case | None = None) -> list[StudyPoint]:
    """Every point of the study, validated (CaseError listing each invalid point)."""
    base = base if base is not None else base_case(spec)
    run = {f"simulation.{k}": v for k, v in spec.run.items()}
    points: list[StudyPoint] = []
    problems: list[Problem] = []
    multi = len(spec.sweeps) > 1
    for s, sweep in enumerate(spec.sweeps):
        where = f"sweep[{s + 1}]." if multi else ""
        for values in _combinations(sweep):
            index = len(points)
            changes = {**run, **sweep.set, **values}
            try:
                case = base.with_values(changes)
                case = case.with_values({"title": point_title(case, point_name(index))})
            except CaseError as error:
                shown = ", ".join(f"{k} = {v!r}" for k, v in values.items())
                for p in error.problems:
                    key = p.key if p.key in changes else None
                    origin = (
                        f"{where}vary.{key}"
                        if key in values
                        else f"{where}set.{key}"
                        if key in sweep.set
                        else f"run.{key.split('.', 1)[1]}"
                        if key in run
                        else f"{where}vary"
                    )
                    problems.append(
                        Problem(origin, f"point {point_name(index)} ({shown}): {p.message}")
                    )
                case = None
            models = MODEL_RUNS[sweep.model]
            if case is not None and "dynamic" in models:
                for p in _study_dynamic_problems(case):
                    shown = ", ".join(f"{k} = {v!r}" for k, v in values.items())
                    problems.append(
                        Problem(
                            f"{where}model",
                            f"point {point_name(index)} ({shown}): the dynamic model cannot run "
                            f"it: {p.message}",
                        )
                    )
            points.append(StudyPoint(index, point_name(index), sweep.name, values, case, models))
    if problems:
        raise CaseError(problems)
    return points
