"""load_case (a case file) and parse_case (TOML text): the file-level errors (missing, empty, not
TOML, not text, not a regular file, too large) and text that is never read as a path."""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

import pytest
import tomli_w

from solver.case import Case, CaseError, load_case, parse_case
from solver.case.io import MAX_CASE_BYTES


def _message(call) -> str:
    with pytest.raises(CaseError) as info:
        call()
    assert info.value.problems[0].key == "file"
    return str(info.value)


def test_path_and_str_path_give_the_case_of_the_text(tmp_path, valid):
    text = tomli_w.dumps(valid)
    file = tmp_path / "case.toml"
    file.write_text(text, encoding="utf-8")
    from_path = load_case(file)
    assert isinstance(from_path, Case)
    assert from_path == load_case(str(file)) == parse_case(text)
    assert from_path.bearing.ball_diameter_mm == valid["bearing"]["ball_diameter_mm"]


def test_a_str_is_always_a_path(tmp_path, valid, monkeypatch):
    """TOML text given to load_case is a (missing) file name, never parsed."""
    monkeypatch.chdir(tmp_path)
    message = _message(lambda: load_case('title = "x"'))
    assert "not found" in message


def test_text_is_never_read_as_a_path(tmp_path, valid):
    """A one-line text naming an existing file is invalid TOML, not that file."""
    file = tmp_path / "case.toml"
    file.write_text(tomli_w.dumps(valid), encoding="utf-8")
    for text in (str(file), f"  {file}  \n"):
        message = _message(lambda text=text: parse_case(text))
        assert "not valid TOML" in message and "case text" in message


def test_missing_file_is_reported_as_such(tmp_path):
    for arg in (tmp_path / "nope.toml", str(tmp_path / "nope.toml")):
        message = _message(lambda arg=arg: load_case(arg))
        assert "not found" in message and "nope.toml" in message


@pytest.mark.parametrize("content", ["", "\n  \n", "# only a comment\n\n# another\n"])
def test_empty_file(tmp_path, content):
    file = tmp_path / "empty.toml"
    file.write_text(content)
    message = _message(lambda: load_case(file))
    assert "is empty" in message and "empty.toml" in message


def test_not_toml_names_the_line(tmp_path):
    file = tmp_path / "bad.toml"
    file.write_text('title = "x"\n[bearing]\nball_count = = 18\n')
    message = _message(lambda: load_case(file))
    assert "not valid TOML" in message and "line 3" in message and "ball_count = = 18" in message


def test_not_text(tmp_path):
    file = tmp_path / "binary.toml"
    file.write_bytes(b"\xff\xfe\x00\x01garbage")
    assert "not a text file" in _message(lambda: load_case(file))


def test_utf8_byte_order_mark_is_accepted(tmp_path, valid):
    file = tmp_path / "bom.toml"
    file.write_bytes(b"\xef\xbb\xbf" + tomli_w.dumps(valid).encode("utf-8"))
    assert load_case(file) == parse_case(tomli_w.dumps(valid))


def test_folder_is_not_a_case(tmp_path):
    message = _message(lambda: load_case(tmp_path))
    assert "folder" in message and str(tmp_path) in message


def test_file_over_one_megabyte_is_refused(tmp_path, valid):
    file = tmp_path / "big.toml"
    padding = "# padding line\n" * (MAX_CASE_BYTES // 15 + 1)
    file.write_text(tomli_w.dumps(valid) + padding, encoding="utf-8")
    assert file.stat().st_size > MAX_CASE_BYTES
    message = _message(lambda: load_case(file))
    assert "larger than 1 MB" in message and "big.toml" in message
    assert "larger than 1 MB" in _message(lambda: parse_case(tomli_w.dumps(valid) + padding))


def _returns_within(seconds, call):
    """Result of ``call()`` run in a thread; fails if it does not return within ``seconds``."""
    out = {}

    def target():
        try:
            out["value"] = call()
        except BaseException as error:  # noqa: BLE001 - handed to the test
            out["error"] = error

    thread = threading.Thread(target=target, daemon=True)
    start = time.perf_counter()
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), f"did not return within {seconds} s"
    return out, time.perf_counter() - start


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes need a POSIX system")
def test_fifo_is_refused_without_opening_it(tmp_path):
    """Opening a FIFO for reading waits for a writer: the type is checked before opening."""
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    out, _ = _returns_within(5.0, lambda: load_case(fifo))
    error = out.get("error")
    assert isinstance(error, CaseError), out
    assert "named pipe" in str(error) and "pipe.toml" in str(error)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
def test_device_is_refused_promptly():
    out, _ = _returns_within(5.0, lambda: load_case("/dev/zero"))
    error = out.get("error")
    assert isinstance(error, CaseError), out
    assert "/dev/zero is a device, not a case file" in str(error)


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc")
def test_proc_file_reporting_size_zero_is_read_only_up_to_the_limit():
    """/proc files report size 0; at most 1 MB + 1 bytes are read, so they give a TOML error."""
    assert os.stat("/proc/self/status").st_size == 0
    message = _message(lambda: load_case("/proc/self/status"))
    assert "/proc/self/status is not valid TOML" in message


def test_deep_nesting_is_a_case_error():
    text = "title = " + "[" * 2000 + "]" * 2000 + "\n"
    message = _message(lambda: parse_case(text))
    assert "nests" in message and "deep" in message


def test_huge_integers_are_case_errors(valid):
    text = tomli_w.dumps(valid)
    digits = "9" * 5000
    huge = text + f"\n[simulation]\nsamples_per_revolution = {digits}\n"
    message = _message(lambda: parse_case(huge))
    assert "cannot be read" in message
    # an integer that parses but does not fit a float: a message naming the key
    with pytest.raises(CaseError) as info:
        parse_case(text.replace("axial_load_N = 500.0", "axial_load_N = " + "9" * 400))
    assert info.value.for_key("operating.axial_load_N")
    assert "far too large" in info.value.for_key("operating.axial_load_N")[0]


def test_wrong_argument_type():
    with pytest.raises(TypeError):
        load_case(42)
    with pytest.raises(TypeError):
        parse_case(b'title = "x"')


def test_contract_example_loads_once_its_shoulders_lie_on_the_grooves():
    """The example of case-format.md, with thrust-side shoulders (see docs/case-format.md)."""
    doc = Path(__file__).parents[3] / "docs" / "case-format.md"
    text = doc.read_text().split("```toml", 1)[1].split("```", 1)[0]
    case = parse_case(text)
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
    good = parse_case(text)
    assert good.warnings() == []
    case = good.with_values({f"bearing.{key}": value})
    (warning,) = case.warnings()
    assert warning.key == f"bearing.{key}"
    for word in words:
        assert word in warning.message
