"""Each shipped lesson's claims hold in its own shipped data (and, marked slow, in freshly solved
results), every sentence is bound to its claims, a lesson whose qualitative words are swapped is
refused, no quoted number comes from an unsettled run, the shipped results are current and small,
and every text fills with numbers from the results (none missing, no NaN)."""

from __future__ import annotations

import copy
import dataclasses
import re
import tomllib

import numpy as np
import pytest

import solver  # noqa: F401  (registers ds.racetrace)
from app.lessons import results as lesson_results
from app.lessons.claims import Sentence, binding_problems, check_claims
from app.lessons.format import LessonError, load_lessons, parse_lesson_data, placeholders
from app.lessons.text import lesson_text
from app.lessons.values import lesson_values

MAX_SHIPPED_BYTES = 1_500_000
LESSONS = load_lessons()


@pytest.fixture(scope="module")
def shipped():
    """lesson id -> {result name: Dataset}, read from the shipped files only."""
    out = {}
    for lesson in LESSONS.lessons:
        out[lesson.id] = {}
        for spec in lesson.results:
            path = lesson_results.shipped_results_dir() / lesson_results.shipped_name(lesson, spec)
            ds = lesson_results._read_matching(path, lesson_results.fingerprint(spec))
            assert ds is not None, (
                f"{path.name} is missing or out of date: run tools/make_lesson_results.py"
            )
            out[lesson.id][spec.name] = ds
    return out


def _thickness(ds, race):
    """Band thickness of a race in its own ring's frame (solver metric), degree."""
    frame = {"inner": "inner_ring", "outer": "outer_ring"}[race]
    return float(ds.racetrace.summary()["trajectory_band_thickness"].sel(race=race, frame=frame))


def _loaded(ds, name, race):
    values = ds[name].sel(race=race).values
    return values[ds["contact_load"].sel(race=race).values > 0]


def test_shipped_files_are_small():
    for lesson in LESSONS.lessons:
        for spec in lesson.results:
            path = lesson_results.shipped_results_dir() / lesson_results.shipped_name(lesson, spec)
            assert path.stat().st_size < MAX_SHIPPED_BYTES, path.name


def test_lesson_1_axial_every_ball_alike_and_a_line_on_both_raceways(shipped):
    ds = shipped["01-axial-load"]["axial"]
    assert float(ds.coords["radial_load"]) == 0.0
    start = float(ds.racetrace.summary()["analysis_start_time"])
    loads = ds["contact_load"].sel(race="inner", time=ds["time"] >= start).transpose("time", "ball")
    spread = np.ptp(loads.values, axis=1) / loads.values.mean(axis=1)
    assert spread.max() < 0.01  # at every instant of the analysed window all balls share alike
    half_width = {  # ellipse half-width across the groove, as groove arc in degree
        race: np.degrees(
            np.mean(_loaded(ds, "ellipse_semi_major", race))
            / float(ds.coords["groove_radius"].sel(race=race))
        )
        for race in ("inner", "outer")
    }
    for race in ("inner", "outer"):
        assert _thickness(ds, race) < 0.02 * half_width[race]
    assert not ds.racetrace.warnings()


def test_lesson_2_speed_outer_angle_falls_below_inner_and_free(shipped):
    speed, rest = shipped["02-speed"]["speed"], shipped["02-speed"]["rest"]
    free = float(speed.coords["free_contact_angle"])
    inner = float(_loaded(speed, "contact_angle", "inner").mean())
    outer = float(_loaded(speed, "contact_angle", "outer").mean())
    assert outer < inner and outer < free
    at_rest = rest["contact_angle"].values
    assert np.ptp(at_rest) < 0.01  # at rest inner and outer coincide, every ball alike
    assert outer < at_rest.mean() < inner
    assert float(speed["centrifugal_force"].mean()) > 0.0
    assert float(rest["centrifugal_force"].max()) == 0.0
    assert set(speed["race_control"].values) == {"outer"}
    # the controlling (outer) raceway: the ball nearly rolls; at the inner contact it spins
    outer_spin = abs(float(speed["spin_to_roll"].sel(race="outer").mean()))
    inner_spin = abs(float(speed["spin_to_roll"].sel(race="inner").mean()))
    assert outer_spin < inner_spin / 3 and inner_spin > 0.05


def test_lesson_3_radial_load_zone_band_inner_line_outer(shipped):
    ds = shipped["03-radial-load"]["radial"]
    loads = _loaded(ds, "contact_load", "inner")
    assert loads.max() > 5.0 * loads.min()  # a load zone: the loads differ round the ring
    assert _thickness(ds, "inner") > 5.0 * _thickness(ds, "outer")
    angles = _loaded(ds, "contact_angle", "inner")
    assert np.ptp(angles) > 5.0  # the contact angle changes around the ring


def test_lesson_4_line_and_band_swap_between_frames(shipped):
    space, ring = shipped["04-misalignment"]["space"], shipped["04-misalignment"]["ring"]
    assert str(space.coords["misalignment_frame"].values) == "space"
    assert str(ring.coords["misalignment_frame"].values) == "ring"
    assert _thickness(space, "inner") > 10.0 * _thickness(space, "outer")  # band in, line out
    assert _thickness(ring, "outer") > 10.0 * _thickness(ring, "inner")  # line in, band out


def _mean_cage(ds):
    return lesson_values(ds)["cage_speed_rpm"]


def test_lesson_5_cage_follows_rolling_under_preload_and_skids_at_light_load(shipped):
    runs = shipped["05-cage"]
    preload = _mean_cage(runs["preload"]) / _mean_cage(runs["preload_rolling"]) - 1.0
    light = _mean_cage(runs["light"]) / _mean_cage(runs["light_rolling"]) - 1.0
    assert abs(preload) < 0.005  # within 0.5 % of pure rolling
    assert light < -0.02  # more than 2 % slower: skidding
    assert abs(light) > 5.0 * abs(preload)
    shaft = lesson_values(runs["light"])["speed_rpm"]
    epicyclic = lesson_values(runs["light"])["epicyclic_cage_speed_rpm"]
    assert 0.4 * shaft < epicyclic < 0.5 * shaft


def test_lesson_6_overload_warns_heavy_does_not(shipped):
    overload, heavy = shipped["06-overload"]["overload"], shipped["06-overload"]["heavy"]
    warnings = overload.racetrace.warnings()
    assert any("runs over the shoulder" in w for w in warnings)
    assert any("peak contact pressure" in w for w in warnings)
    assert float(overload["max_pressure"].max()) > 4.2e9
    assert float(overload["truncation_margin"].min()) < 0.0
    assert heavy.racetrace.warnings() == []
    assert float(heavy["truncation_margin"].min()) > 0.0


@pytest.mark.parametrize("lesson", LESSONS.lessons, ids=lambda lesson: lesson.id)
def test_every_text_fills_from_the_results(lesson, shipped):
    values = {name: lesson_values(ds) for name, ds in shipped[lesson.id].items()}
    explain, try_this = lesson_text(lesson, values)
    for text in (explain, try_this):
        assert "{" not in text and "(no " not in text and "nan" not in text.lower()
    # a number that the template formats appears in the text as the result gives it
    first = lesson.results[0].name
    for field, spec in re.findall(r"\{([a-z_.]+):([^}]+)\}", lesson.explain):
        result, _, name = field.rpartition(".")
        assert format(values[result or first][name], spec) in explain


# ---- claims bound to their sentences ------------------------------------------------------------
def _false_claims(lesson, datasets) -> list[str]:
    values = {name: lesson_values(ds) for name, ds in datasets.items()}
    return [o.describe(lesson.id) for o in check_claims(lesson, values) if not o.holds]


@pytest.mark.parametrize("lesson", LESSONS.lessons, ids=lambda lesson: lesson.id)
def test_every_claim_holds_in_the_shipped_results(lesson, shipped):
    assert _false_claims(lesson, shipped[lesson.id]) == []


@pytest.mark.slow
@pytest.mark.parametrize("lesson", LESSONS.lessons, ids=lambda lesson: lesson.id)
def test_every_claim_holds_in_freshly_solved_results(lesson):
    """The shipped results count as current by a fingerprint of what they were solved from; the
    solver of today may say otherwise: solve every result again and check the claims."""
    fresh = {spec.name: lesson_results.compute(spec) for spec in lesson.results}
    assert _false_claims(lesson, fresh) == []
    assert _unsettled_quotes(lesson, fresh) == []


@pytest.mark.parametrize("lesson", LESSONS.lessons, ids=lambda lesson: lesson.id)
def test_every_sentence_carries_a_claim_or_is_descriptive(lesson):
    assert binding_problems(lesson.sentences) == []
    claimed = [s for s in lesson.sentences if s.claims]
    assert len(claimed) >= len(lesson.sentences) / 2  # a lesson's sentences mostly find something


def _lesson_data(lesson_id: str) -> dict:
    path = lesson_results.shipped_results_dir().parent / f"{lesson_id}.toml"
    return tomllib.loads(path.read_text("utf-8"))


def _say(data: dict, old: str, new: str) -> dict:
    """``data`` with ``old`` replaced by ``new`` in the prose (the sentences' ``say``) only: the
    claims beside them stay as they are."""
    changed = copy.deepcopy(data)
    hits = 0
    for sentence in changed["text"]["explain"]:
        words = " ".join(sentence["say"].split())
        if old in words:
            sentence["say"] = words.replace(old, new)
            hits += 1
    assert hits == 1, f"{old!r} is in {hits} sentences"
    return changed


@pytest.mark.parametrize(
    ("lesson_id", "swaps"),
    [
        (
            "03-radial-load",
            [
                ("the outer track is a thin line", "the outer track is a wide band"),
                ("the inner track is a band", "the inner track is a thin line"),
            ],
        ),
        ("05-cage", [("The balls skid", "The balls do not skid")]),
        ("02-speed", [("The outer contact angle falls", "The outer contact angle rises")]),
        ("06-overload", [("the outer one, closer", "the inner one, closer")]),
        ("07-start-up-skid", [("the cage catches up", "the cage never catches up")]),
        (
            "08-live-radial-load",
            [("the inner track opens into a band", "the inner track stays a thin line")],
        ),
    ],
)
def test_a_lesson_with_its_qualitative_words_swapped_is_refused(lesson_id, swaps):
    data = _lesson_data(lesson_id)
    parse_lesson_data(data, lesson_id)  # as shipped: fine
    for old, new in swaps:
        data = _say(data, old, new)
    with pytest.raises(LessonError) as info:
        parse_lesson_data(data, lesson_id)
    refused = [p for p in info.value.problems if "quotes words the sentence does not say" in p]
    assert len(refused) == len(swaps), info.value.problems


def test_a_finding_marked_descriptive_is_refused():
    data = _lesson_data("05-cage")
    (sentence,) = [s for s in data["text"]["explain"] if "The balls\nskid" in s["say"]]
    del sentence["claim"]
    sentence["descriptive"] = True
    with pytest.raises(LessonError, match=r"marked descriptive, but it says .*\bskid\b"):
        parse_lesson_data(data, "05-cage")


# ---- quoted numbers come from settled runs ------------------------------------------------------
def _unsettled_quotes(lesson, datasets) -> list[str]:
    """The placeholders of ``lesson`` (the numbers it quotes) that read a dynamic result that did
    not settle (its metric ``settled`` is not 1: the result warns "run too short to settle"). A
    claim may read such a run: it says what the transient shows (lesson 5)."""
    first = lesson.results[0].name
    read = [
        (field.rpartition(".")[0] or first, field)
        for field, _ in placeholders(lesson.explain) + placeholders(lesson.try_this)
    ]
    out = []
    for result, quoted in read:
        ds = datasets[result]
        if "time" in ds.dims and float(ds.racetrace.metric("settled")) != 1.0:
            out.append(f"lesson {lesson.id}: {quoted} is read from the unsettled run {result!r}")
    return sorted(set(out))


@pytest.mark.parametrize("lesson", LESSONS.lessons, ids=lambda lesson: lesson.id)
def test_no_quoted_number_comes_from_an_unsettled_run(lesson, shipped):
    assert _unsettled_quotes(lesson, shipped[lesson.id]) == []


def test_the_unsettled_check_reads_the_settling_warning(shipped):
    """The check above reads the metric behind the warning: lesson 5's light run (a transient)
    warns and is found unsettled; its preloaded run neither."""
    light, preload = shipped["05-cage"]["light"], shipped["05-cage"]["preload"]
    assert any("too short to settle" in w for w in light.racetrace.warnings())
    assert not any("too short to settle" in w for w in preload.racetrace.warnings())
    lesson = LESSONS.get("05-cage")
    quoting = dataclasses.replace(
        lesson,
        sentences=(*lesson.sentences, Sentence("It ran at {cage_speed_rpm:.0f} rpm.", (), True)),
    )
    assert _unsettled_quotes(quoting, shipped["05-cage"]) == [
        "lesson 05-cage: cage_speed_rpm is read from the unsettled run 'light'"
    ]
