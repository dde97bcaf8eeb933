"""What determines a result, as a fingerprint: the case's values, the model, its options and the
results version.

:data:`RESULTS_VERSION` is bumped by every change of the physics or the numerics that moves results
beyond the tolerances at which shipped results are checked (the slow tests
tests/integration/test_shipped_results.py and test_shipped_studies.py re-solve every shipped lesson
result and study point and fail when one drifts while the version is unchanged); shipped results
are then regenerated (``python tools/make_lesson_results.py`` and
``python tools/make_study_results.py``). A change that moves no result leaves it alone, so the
shipped results stay current across refactoring, comments and help texts.
"""

from __future__ import annotations

import hashlib
import json

from solver.case.schema import FIELDS

#: Version of the results' physics and numerics (module docstring).
RESULTS_VERSION = 3


def case_values(case) -> dict:
    """Every key's value of ``case`` as the models read it ({dotted key: value}: given, default,
    estimated or from a named oil), and the user material tables; not the title, any comment or a
    key that no model reads (``Field.solved`` False: the surface roughnesses) or that only the
    other kind of case reads (``Field.applies``). A case with time histories adds each history's
    knots, sine, rate and frame under ``histories`` (a changed ramp, or a changed history file,
    makes a result out of date); a steady case's values are those of a case file without them."""
    histories = getattr(case, "histories", {})
    kind = "history" if histories else "steady"
    values = {}
    for f in FIELDS:
        if not f.section or not f.solved or f.applies not in ("", kind):
            continue
        value = case
        for part in f.path:
            value = getattr(value, part)
        values[f.key] = value
    values["materials"] = case.materials
    if histories:
        values["histories"] = {key: h.fingerprint() for key, h in sorted(histories.items())}
    return values


def result_fingerprint(case, model: str, options: dict | None = None) -> str:
    """A 20-hex-digit hash of what a result depends on: :data:`RESULTS_VERSION`, the model
    (``"quasistatic"`` or ``"dynamic"``), its options (e.g. the run length) and the case's values
    (:func:`case_values`). Equal for two cases that differ only in title or comments."""
    text = json.dumps(
        {
            "results_version": RESULTS_VERSION,
            "model": model,
            "options": options or {},
            "case": case_values(case),
        },
        sort_keys=True,
        default=repr,
    )
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:20]


def study_fingerprint(runs) -> str:
    """A 20-hex-digit hash of what a study's results depend on: ``runs`` is an iterable of
    ``(point name, model, case)``, one per run of the study; each contributes its
    :func:`result_fingerprint`. Equal for two studies whose points solve the same cases with the
    same models under the same :data:`RESULTS_VERSION`, whatever their titles and comments."""
    prints = sorted(
        (str(name), str(model), result_fingerprint(case, model)) for name, model, case in runs
    )
    text = json.dumps({"results_version": RESULTS_VERSION, "runs": prints})
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:20]
