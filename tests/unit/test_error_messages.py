"""Error messages are safe to print: control characters become visible escapes, length is capped."""

from __future__ import annotations

import re

import pytest

from racetrace.cli import main
from solver import CaseError, parse_case
from solver.errors import MAX_MESSAGE_CHARS, Problem, clean_message, printable
from tests.helpers.cases import SPINDLE

# any character a terminal acts on instead of showing (a line feed between lines is allowed)
_CONTROL = re.compile("[\x00-\x09\x0b-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]")


def _case_with_bad_key_and_value() -> str:
    # an unknown key whose name clears the screen and a text value that sets the window title
    return (
        SPINDLE.replace(
            'designation = "7008C-class hybrid"',
            'designation = "x\\u001b]0;pwned\\u0007"\n"\\u001b[2J\\r\\u202e" = 1',
        )
        + "\n"
    )


def test_control_characters_of_a_case_are_escaped_in_the_message():
    with pytest.raises(CaseError) as caught:
        parse_case(_case_with_bad_key_and_value())
    message = str(caught.value)
    assert not _CONTROL.search(message), repr(message)
    assert "\\x1b[2J\\x0d\\u202e" in message  # the key, visibly escaped
    for problem in caught.value.problems:
        assert not _CONTROL.search(problem.message + problem.key)


def test_cli_prints_escaped_messages(tmp_path, capsys):
    case = tmp_path / "bad.toml"
    case.write_text(_case_with_bad_key_and_value(), encoding="utf-8")
    assert main(["check", str(case)]) == 2
    err = capsys.readouterr().err
    assert "\\x1b[2J" in err
    assert not _CONTROL.search(err.replace("\n", "")), repr(err)


def test_a_path_with_control_characters_is_escaped(capsys):
    assert main(["check", "no-such-\x1b[2J-case.toml"]) == 2
    err = capsys.readouterr().err
    assert "\x1b" not in err and "\\x1b[2J" in err


def test_fifty_thousand_unknown_keys_give_a_short_message():
    text = SPINDLE + "\n[lubricant]\n" + "".join(f"k{i} = 1\n" for i in range(50_000))
    with pytest.raises(CaseError) as caught:
        parse_case(text)
    message = str(caught.value)
    assert len(caught.value.problems) == 50_000  # every problem is still there for a form
    assert len(message) < MAX_MESSAGE_CHARS + 200
    assert re.search(r"\.\.\. and \d+ more problems", message)
    assert message.startswith("unknown key lubricant.k0 = 1")


def test_one_huge_key_is_cut():
    problem = Problem("k" * 100_000, "unknown key " + "k" * 100_000)
    assert len(problem.message) < 1_100 and "more characters" in problem.message


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("a\x1bb", "a\\x1bb"),
        ("bell\x07", "bell\\x07"),
        ("c1\x9b", "c1\\x9b"),
        ("rtl\u202eltr", "rtl\\u202eltr"),
        ("line\u2028sep", "line\\u2028sep"),
        ("lone\ud800", "lone\\ud800"),
        ("tab\tand\nnewline", "tab\\x09and\\x0anewline"),
        ("plain ä °C μm", "plain ä °C μm"),
    ],
)
def test_printable(text, expected):
    assert printable(text) == expected


def test_clean_message_keeps_lines_and_caps_length():
    assert clean_message("one\ntwo\x1b") == "one\ntwo\\x1b"
    assert len(clean_message("x" * 100_000, limit=100)) < 140


@pytest.mark.parametrize("command", ["check", "quasistatic"])
def test_a_title_with_control_characters_is_printed_escaped(tmp_path, capsys, command):
    case = tmp_path / "title.toml"
    text = SPINDLE.replace(
        'title = "7008C-class hybrid spindle bearing, combined load"',
        'title = "clear\\u001b[2J\\u001b]0;pwned\\u0007"',
    )
    case.write_text(text, encoding="utf-8")
    assert main([command, str(case)]) == 0
    out = capsys.readouterr().out
    assert "clear\\x1b[2J\\x1b]0;pwned\\x07" in out
    assert not _CONTROL.search(out.replace("\n", "")), repr(out)
