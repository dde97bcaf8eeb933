"""Lesson files: one TOML file per lesson (docs/lessons.md), read into :class:`Lesson` records.

A lesson names one or more results (a shipped case with optional changes, solved by the
quasi-static or the dynamic model), the camera preset and the chart to open, its explanation (a
list of sentences, each with the claims that bind what it says to a condition over the results:
:mod:`app.lessons.claims`) and a "try this" prompt; the placeholders of the texts are filled from
the results (:mod:`app.lessons.values`). Nothing here solves or draws anything:
:func:`parse_lesson` checks a file completely (keys, types, case names and changes, model rules,
placeholders, claims and their binding to their sentences) and raises
:class:`LessonError` naming every problem; :func:`load_lessons` reads a folder, keeps every lesson
that is right and reports the others in words.
"""

from __future__ import annotations

import re
import string
import tomllib
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

import solver
from solver import Case, CaseError, dynamic_problems

from .claims import Claim, Sentence, binding_problems, parse_condition
from .values import VALUE_NAMES

#: Camera presets a lesson may ask for (the 3-D view's presets).
CAMERAS = ("isometric", "axial", "radial", "inner track", "outer track", "close-up")
#: Charts a lesson may open and highlight (the keys of the app's chart panels).
CHARTS = ("contact_angle", "raceway_map", "load_azimuth", "ellipse", "cage_speed", "comparison")
MODELS = ("quasistatic", "dynamic")
MAX_RESULTS = 4
DEFAULT_REVOLUTIONS = 4.0
DEFAULT_SAMPLES_PER_REVOLUTION = 60
MAX_REVOLUTIONS = 20.0  # a lesson result is shipped with the app: keep it small
MAX_SAMPLES_PER_REVOLUTION = 180
#: Most samples of a dynamic result along a time history (its run is a duration, not revolutions).
MAX_HISTORY_SAMPLES = 1000
MAX_FILE_BYTES = 64 * 1024

_NAME = re.compile(r"^[a-z][a-z0-9_]{0,31}$")
_TOP_KEYS = {"title", "summary", "results", "view", "text"}
_RESULT_KEYS = {
    "name",
    "label",
    "case",
    "overrides",
    "model",
    "shaft_revolutions",
    "samples_per_revolution",
}
_VIEW_KEYS = {"camera", "chart"}
_TEXT_KEYS = {"explain", "try_this"}
_SENTENCE_KEYS = {"say", "claim", "descriptive"}
MAX_SENTENCES = 30


class LessonError(ValueError):
    """A lesson file that cannot be used; ``problems`` lists what is wrong, one sentence each."""

    def __init__(self, source: str, problems: list[str]):
        self.source = source
        self.problems = list(problems)
        super().__init__(f"lesson {source}: " + "; ".join(self.problems))


@dataclass(frozen=True)
class ResultSpec:
    """One result a lesson shows: ``case`` (a catalogue name) with ``overrides`` (dotted case keys,
    case units) solved by ``model``; a dynamic run covers ``shaft_revolutions`` revolutions sampled
    ``samples_per_revolution`` times each, or, when the case has a time history, its own
    ``simulation.duration_s``. ``title`` is the solved case's title ("<lesson title>: <label>"):
    the catalogue case's own title would not name what the lesson changed. ``given_run_keys``: the
    run-length keys the lesson file gave (a history case refuses them)."""

    name: str
    label: str
    case_name: str
    overrides: tuple[tuple[str, object], ...]
    model: str
    shaft_revolutions: float
    samples_per_revolution: int
    title: str = ""
    given_run_keys: tuple[str, ...] = ()

    def case(self) -> Case:
        """The validated case this result solves, under :attr:`title` (CaseError when the changes
        are invalid)."""
        case = solver.catalogue().get(self.case_name).load()
        values = {"title": self.title} if self.title else {}
        values.update(self.overrides)  # a title among the changes is the lesson's own choice
        return case.with_values(values) if values else case


@dataclass(frozen=True)
class Lesson:
    """A checked lesson. ``id`` is the file name without ``.toml``; lessons are ordered by it.
    ``results[0]`` is the result shown when the lesson opens."""

    id: str
    title: str
    summary: str
    results: tuple[ResultSpec, ...]
    camera: str
    chart: str
    sentences: tuple[Sentence, ...]
    try_this: str

    @property
    def explain(self) -> str:
        """The explanation's template: its sentences in order, as one paragraph."""
        return " ".join(sentence.template for sentence in self.sentences)

    def result(self, name: str) -> ResultSpec:
        for spec in self.results:
            if spec.name == name:
                return spec
        raise KeyError(f"lesson {self.id} has no result {name!r}")


@dataclass(frozen=True)
class LessonSet:
    """The lessons of a folder that could be read, and the problems of those that could not (one
    message per broken file, naming the file)."""

    lessons: tuple[Lesson, ...]
    problems: tuple[str, ...]

    def get(self, lesson_id: str) -> Lesson:
        for lesson in self.lessons:
            if lesson.id == lesson_id:
                return lesson
        known = ", ".join(lesson.id for lesson in self.lessons) or "none"
        raise KeyError(f"no lesson {lesson_id!r}; lessons: {known}")


def shipped_lessons_dir():
    """The folder of the lessons shipped with racetrace (``assets/lessons``)."""
    return files("assets") / "lessons"


# ---- templates -----------------------------------------------------------------------------------
def placeholders(template: str) -> list[tuple[str, str]]:
    """The (field, format spec) pairs of a template; ValueError for a malformed template (an
    unmatched brace, a conversion such as ``!r``, a nested field)."""
    out = []
    for _literal, field, spec, conversion in string.Formatter().parse(template):
        if field is None:
            continue
        if conversion:
            raise ValueError(f"{{{field}!{conversion}}}: conversions (!r, !s) are not allowed")
        if "{" in (spec or ""):
            raise ValueError(f"{{{field}:{spec}}}: nested placeholders are not allowed")
        out.append((field, spec or ""))
    return out


def _template_problems(where: str, template: str, result_names: list[str]) -> list[str]:
    try:
        fields = placeholders(template)
    except ValueError as error:
        return [f"{where}: {error} (write {{{{ and }}}} for literal braces)"]
    problems = []
    for field, spec in fields:
        result, _, value = field.rpartition(".")
        if not field:
            problems.append(f"{where}: an empty placeholder {{}}; name a value, e.g. {{speed_rpm}}")
            continue
        if result and result not in result_names:
            problems.append(
                f"{where}: placeholder {{{field}}} names the result {result!r}, but this lesson's "
                f"results are {', '.join(result_names)}"
            )
        if value not in VALUE_NAMES:
            problems.append(
                f"{where}: placeholder {{{field}}}: unknown value {value!r}; the values are listed "
                "in docs/lessons.md"
            )
        elif spec:
            try:
                format(1.5, spec)
            except ValueError:
                problems.append(
                    f"{where}: placeholder {{{field}:{spec}}}: {spec!r} is not a number format "
                    "(use e.g. .1f or .3g)"
                )
    return problems


# ---- reading one file ----------------------------------------------------------------------------
def _table(data: dict, name: str, allowed, problems: list[str]) -> dict:
    """Table ``[name]`` of a lesson file, its unknown keys added to ``problems`` ({} when it is
    absent, or when it is not a table, which is said too)."""
    table = data.get(name, {})
    if not isinstance(table, dict):
        problems.append(f"[{name}] must be a table")
        return {}
    problems.extend(_unknown_keys(f"[{name}]", table, allowed))
    return table


def _unknown_keys(where: str, table: dict, allowed: set[str]) -> list[str]:
    extra = sorted(set(table) - allowed)
    if not extra:
        return []
    return [
        f"{where}: unknown key{'s' if len(extra) > 1 else ''} {', '.join(extra)}; allowed: "
        f"{', '.join(sorted(allowed))}"
    ]


def _text(where: str, table: dict, key: str, problems: list[str], required=True) -> str:
    value = table.get(key)
    if value is None:
        if required:
            problems.append(f"{where}: {key} is missing")
        return ""
    if not isinstance(value, str) or not value.strip():
        problems.append(f"{where}: {key} must be a non-empty text")
        return ""
    return value.strip()


def _number(where, table, key, default, low, high, problems, integer=False):
    value = table.get(key, default)
    kinds = (int,) if integer else (int, float)
    if isinstance(value, bool) or not isinstance(value, kinds):
        kind = "a whole number" if integer else "a number"
        problems.append(f"{where}: {key} must be {kind}, not {value!r}")
        return default
    if not low <= value <= high:
        problems.append(f"{where}: {key} = {value} is outside {low} … {high}")
        return default
    return value


def _result_spec(index: int, table, problems: list[str], lesson_title: str) -> ResultSpec | None:
    where = f"[[results]] #{index + 1}"
    if not isinstance(table, dict):
        problems.append(f"{where} must be a table")
        return None
    problems += _unknown_keys(where, table, _RESULT_KEYS)
    name = table.get("name")
    if not isinstance(name, str) or not _NAME.match(name):
        problems.append(
            f"{where}: name must be a short lower-case word (letters, digits, _), not {name!r}"
        )
        name = f"result{index + 1}"
    where = f"result {name!r}"
    label = _text(where, table, "label", problems, required=False) or name
    model = table.get("model", "quasistatic")
    if model not in MODELS:
        problems.append(f"{where}: model must be one of {', '.join(MODELS)}, not {model!r}")
        model = "quasistatic"
    revolutions = _number(
        where, table, "shaft_revolutions", DEFAULT_REVOLUTIONS, 1.0, MAX_REVOLUTIONS, problems
    )
    samples = _number(
        where,
        table,
        "samples_per_revolution",
        DEFAULT_SAMPLES_PER_REVOLUTION,
        12,
        MAX_SAMPLES_PER_REVOLUTION,
        problems,
        integer=True,
    )
    if model == "quasistatic":
        for key in ("shaft_revolutions", "samples_per_revolution"):
            if key in table:
                problems.append(f"{where}: {key} applies to a dynamic result only")
    overrides = table.get("overrides", {})
    if not isinstance(overrides, dict) or any(isinstance(v, dict) for v in overrides.values()):
        problems.append(
            f"{where}: overrides must be a table of dotted case keys, e.g. "
            f'overrides = {{ "operating.axial_load_N" = 300.0 }}'
        )
        overrides = {}
    case_name = table.get("case")
    spec = ResultSpec(
        name=name,
        label=label,
        case_name=str(case_name),
        overrides=tuple(sorted(overrides.items())),
        model=model,
        shaft_revolutions=float(revolutions),
        samples_per_revolution=int(samples),
        title=f"{lesson_title}: {label}" if lesson_title else label,
        given_run_keys=tuple(
            k for k in ("shaft_revolutions", "samples_per_revolution") if k in table
        ),
    )
    if not isinstance(case_name, str):
        problems.append(f"{where}: case is missing (a shipped case name, see racetrace cases)")
        return spec
    problems += _case_problems(where, spec)
    return spec


def _case_problems(where: str, spec: ResultSpec) -> list[str]:
    try:
        solver.catalogue().get(spec.case_name)
    except CaseError as error:
        return [f"{where}: case {spec.case_name!r}: {error}"]
    try:
        case = spec.case()
    except CaseError as error:
        return [f"{where}: overrides: {error}"]
    if spec.model == "dynamic":
        problems = [
            f"{where}: the dynamic model cannot run it: {p}" for p in dynamic_problems(case)
        ]
        if case.histories:
            problems += _history_run_problems(where, spec, case)
        return problems
    return []


def _history_run_problems(where: str, spec: ResultSpec, case: Case) -> list[str]:
    """A run along a time history lasts the case's ``simulation.duration_s`` sampled
    ``samples_per_second`` times a second (docs/case-format.md): the lesson's run-length keys do
    not apply, and the run must stay small enough to ship."""
    problems = [
        f"{where}: {key} applies to a steady case; the case {spec.case_name!r} has a time "
        f"history ({', '.join(sorted(case.histories))}), so its run lasts "
        "simulation.duration_s: change it, or simulation.samples_per_second, under overrides"
        for key in spec.given_run_keys
    ]
    samples = case.simulation.duration_s * case.simulation.samples_per_second
    if samples > MAX_HISTORY_SAMPLES:
        problems.append(
            f"{where}: the run along the history would store {samples:.0f} samples "
            f"(simulation.duration_s {case.simulation.duration_s:g} s x samples_per_second "
            f"{case.simulation.samples_per_second:g}); a lesson result is shipped with the app: "
            f"at most {MAX_HISTORY_SAMPLES}, so lower simulation.samples_per_second under overrides"
        )
    return problems


def _sentences(raw, results: list[str], problems: list[str]) -> list[Sentence]:
    """The explanation's ``[[text.explain]]`` entries read into sentences with parsed claims."""
    if raw is None:
        problems.append(
            "[[text.explain]] is missing: the explanation is a list of sentences, each with its "
            "claims or descriptive = true (docs/lessons.md)"
        )
        return []
    if not isinstance(raw, list) or not raw or not all(isinstance(e, dict) for e in raw):
        problems.append(
            "[text] explain must be a list of [[text.explain]] tables (say = the sentence, "
            'claim."its words" = "a condition", or descriptive = true), see docs/lessons.md'
        )
        return []
    if len(raw) > MAX_SENTENCES:
        problems.append(f"{len(raw)} [[text.explain]] sentences: at most {MAX_SENTENCES}")
        return []
    sentences = []
    for number, entry in enumerate(raw, start=1):
        where = f"[[text.explain]] sentence {number}"
        problems += _unknown_keys(where, entry, _SENTENCE_KEYS)
        template = _text(where, entry, "say", problems)
        descriptive = entry.get("descriptive", False)
        if not isinstance(descriptive, bool):
            problems.append(f"{where}: descriptive must be true or false, not {descriptive!r}")
            descriptive = False
        raw_claims = entry.get("claim", {})
        if not isinstance(raw_claims, dict) or not all(
            isinstance(v, str) for v in raw_claims.values()
        ):
            problems.append(
                f'{where}: claim must be a table of quoted words = "a condition", e.g. '
                'claim."the outer track is a thin line" = '
                '"outer_band_thickness < 0.2 * inner_band_thickness"'
            )
            raw_claims = {}
        claims = []
        for says, condition in raw_claims.items():
            try:
                claims.append(Claim(says, parse_condition(condition, results)))
            except ValueError as error:
                problems.append(f"{where}: claim {says!r}: condition {condition!r}: {error}")
        sentences.append(Sentence(template, tuple(claims), descriptive))
    return sentences


def parse_lesson(text: str, lesson_id: str) -> Lesson:
    """Check a lesson file's text completely; :class:`LessonError` lists every problem."""
    source = f"{lesson_id}.toml"
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise LessonError(source, [f"not valid TOML: {error}"]) from None
    return parse_lesson_data(data, lesson_id)


def parse_lesson_data(data: dict, lesson_id: str) -> Lesson:
    """Check a lesson file's contents (its TOML read into a dict) completely; :class:`LessonError`
    lists every problem."""
    source = f"{lesson_id}.toml"
    problems = _unknown_keys("top level", data, _TOP_KEYS)
    title = _text("top level", data, "title", problems)
    summary = _text("top level", data, "summary", problems, required=False)
    raw_results = data.get("results")
    results: list[ResultSpec] = []
    if not isinstance(raw_results, list) or not raw_results:
        problems.append(
            "no [[results]]: a lesson shows at least one result (a case and a model), "
            "see docs/lessons.md"
        )
    elif len(raw_results) > MAX_RESULTS:
        problems.append(f"{len(raw_results)} [[results]]: at most {MAX_RESULTS}")
    else:
        for i, table in enumerate(raw_results):
            spec = _result_spec(i, table, problems, title)
            if spec is not None:
                results.append(spec)
    names = [r.name for r in results]
    if len(set(names)) != len(names):
        problems.append(f"result names must differ: {', '.join(names)}")
    view = _table(data, "view", _VIEW_KEYS, problems)
    camera = view.get("camera", "isometric")
    if camera not in CAMERAS:
        problems.append(f"[view] camera must be one of {', '.join(CAMERAS)}, not {camera!r}")
    chart = view.get("chart", "contact_angle")
    if chart not in CHARTS:
        problems.append(f"[view] chart must be one of {', '.join(CHARTS)}, not {chart!r}")
    text = _table(data, "text", _TEXT_KEYS, problems)
    sentences = _sentences(text.get("explain"), names, problems)
    for number, sentence in enumerate(sentences, start=1):
        problems += _template_problems(
            f"[[text.explain]] sentence {number}", sentence.template, names
        )
    problems += binding_problems(sentences)
    try_this = _text("[text]", text, "try_this", problems)
    problems += _template_problems("[text] try_this", try_this, names)
    if problems:
        raise LessonError(source, problems)
    return Lesson(
        id=lesson_id,
        title=title,
        summary=summary,
        results=tuple(results),
        camera=camera,
        chart=chart,
        sentences=tuple(sentences),
        try_this=try_this,
    )


def read_lesson(path) -> Lesson:
    """Read and check one lesson file (a Path or importlib.resources Traversable)."""
    name = path.name
    lesson_id = name[: -len(".toml")] if name.endswith(".toml") else name
    try:
        data = path.read_bytes()
    except OSError as error:
        raise LessonError(name, [f"cannot be read: {error.strerror or error}"]) from None
    if len(data) > MAX_FILE_BYTES:
        raise LessonError(name, [f"the file is larger than {MAX_FILE_BYTES // 1024} kB"])
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise LessonError(name, ["the file is not UTF-8 text"]) from None
    return parse_lesson(text, lesson_id)


def load_lessons(directory=None) -> LessonSet:
    """Every ``*.toml`` lesson in ``directory`` (default: the shipped lessons), ordered by file
    name. A broken file is reported in :attr:`LessonSet.problems`; the others still load."""
    folder = shipped_lessons_dir() if directory is None else Path(directory)
    if not folder.is_dir():
        return LessonSet((), (f"the lessons folder {folder} does not exist",))
    paths = sorted(
        (p for p in folder.iterdir() if p.name.endswith(".toml") and p.is_file()),
        key=lambda p: p.name,
    )
    lessons, problems = [], []
    for path in paths:
        try:
            lessons.append(read_lesson(path))
        except LessonError as error:
            problems.append(str(error))
    return LessonSet(tuple(lessons), tuple(problems))


__all__ = [
    "CAMERAS",
    "CHARTS",
    "Lesson",
    "LessonError",
    "LessonSet",
    "ResultSpec",
    "load_lessons",
    "parse_lesson",
    "parse_lesson_data",
    "placeholders",
    "read_lesson",
    "shipped_lessons_dir",
]
