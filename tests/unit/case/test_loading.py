"""load_case: paths, text, and the file-level errors (missing, empty, not TOML, not text)."""

from __future__ import annotations

from pathlib import Path

import pytest
import tomli_w

from solver.case import Case, CaseError, load_case


def test_path_str_path_and_text_give_the_same_case(tmp_path, valid):
    text = tomli_w.dumps(valid)
    file = tmp_path / "case.toml"
    file.write_text(text, encoding="utf-8")
    from_path = load_case(file)
    assert isinstance(from_path, Case)
    assert from_path == load_case(str(file)) == load_case(text)
    assert from_path.bearing.ball_diameter_mm == valid["bearing"]["ball_diameter_mm"]


def test_missing_file_is_reported_as_such(tmp_path):
    for arg in (tmp_path / "nope.toml", str(tmp_path / "nope.toml")):
        with pytest.raises(CaseError) as info:
            load_case(arg)
        assert info.value.problems[0].key == "file"
        assert "not found" in str(info.value) and "nope.toml" in str(info.value)


@pytest.mark.parametrize("content", ["", "\n  \n", "# only a comment\n\n# another\n"])
def test_empty_file(tmp_path, content):
    file = tmp_path / "empty.toml"
    file.write_text(content)
    with pytest.raises(CaseError) as info:
        load_case(file)
    assert "is empty" in str(info.value) and "empty.toml" in str(info.value)


def test_not_toml_names_the_line(tmp_path):
    file = tmp_path / "bad.toml"
    file.write_text('title = "x"\n[bearing]\nball_count = = 18\n')
    with pytest.raises(CaseError) as info:
        load_case(file)
    message = str(info.value)
    assert "not valid TOML" in message and "line 3" in message and "ball_count = = 18" in message


def test_not_text(tmp_path):
    file = tmp_path / "binary.toml"
    file.write_bytes(b"\xff\xfe\x00\x01garbage")
    with pytest.raises(CaseError) as info:
        load_case(file)
    assert "not a text file" in str(info.value)


def test_folder_is_not_a_case(tmp_path):
    with pytest.raises(CaseError) as info:
        load_case(tmp_path)
    assert "folder" in str(info.value)


def test_wrong_argument_type():
    with pytest.raises(CaseError):
        load_case(42)


def test_contract_example_loads_once_its_shoulders_lie_on_the_grooves():
    """The example of case-format.md, with thrust-side shoulders (see docs/case-format.md)."""
    doc = Path(__file__).parents[3] / "docs" / "case-format.md"
    text = doc.read_text().split("```toml", 1)[1].split("```", 1)[0]
    case = load_case(text)
    assert case.bearing.ball_count == 18
    assert case.lubricant.traction.mu_infinity == 0.036
    assert case.operating.misalignment_frame == "space"
    assert case.materials["my_steel"]["youngs_modulus_GPa"] == 208.0


@pytest.mark.parametrize(
    "key, value, words",
    [
        (
            "inner_shoulder_diameter_mm",
            45.9,
            ["= 45.9", "above the inner groove-bottom diameter (46.84 mm)"],
        ),
        (
            "outer_shoulder_diameter_mm",
            62.2,
            ["= 62.2", "below the outer groove-bottom diameter (61.16 mm)"],
        ),
    ],
)
def test_lands_off_their_groove_load_with_a_warning(key, value, words):
    """The contract example's lands (45.9 / 62.2 mm) do not rise above the 7008C grooves: the case
    still loads (external tools use that example) and the doubt is reported by Case.warnings()."""
    doc = Path(__file__).parents[3] / "docs" / "case-format.md"
    text = doc.read_text().split("```toml", 1)[1].split("```", 1)[0]
    good = load_case(text)
    assert good.warnings() == []
    case = good.with_values({f"bearing.{key}": value})
    (warning,) = case.warnings()
    assert warning.key == f"bearing.{key}"
    for word in words:
        assert word in warning.message
