"""An uploaded case is bytes (or text) from a client: decoded with ``decode_case_bytes`` and parsed
with ``parse_case``, as the app's upload handler does. Never read as a path, at most 1 MB, UTF-8
with or without a byte-order mark."""

from __future__ import annotations

import os
import time

import pytest

from solver.case import CaseError, parse_case
from solver.case import io as case_io
from solver.case.io import MAX_CASE_BYTES, decode_case_bytes
from tests.helpers.cases import SPINDLE


def _upload(content, name="evil.toml"):
    """What the app's upload handler does with a file's content."""
    text = decode_case_bytes(content, name) if isinstance(content, bytes) else str(content)
    return parse_case(text, source=f"uploaded file {name}")


@pytest.fixture
def no_file_reading(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("an uploaded text was read as a path")

    monkeypatch.setattr(case_io, "read_case_bytes", refuse)
    monkeypatch.setattr(case_io, "load_case", refuse)
    monkeypatch.setenv("RACETRACE_UPLOAD_SECRET", "do-not-show-this-value")


@pytest.mark.parametrize("text", ["/proc/self/environ", "/dev/zero", "/dev/stdin"])
@pytest.mark.parametrize("as_bytes", [True, False])
def test_one_line_path_is_invalid_toml_not_a_file(no_file_reading, text, as_bytes):
    start = time.perf_counter()
    with pytest.raises(CaseError) as caught:
        _upload(text.encode() if as_bytes else text)
    assert time.perf_counter() - start < 5.0
    message = str(caught.value)
    assert message.startswith("uploaded file evil.toml is not valid TOML"), message
    assert "do-not-show-this-value" not in message and os.environ["PATH"] not in message


def test_upload_over_one_megabyte_is_refused_before_decoding():
    content = SPINDLE.encode() + b"#" * MAX_CASE_BYTES
    with pytest.raises(CaseError, match="evil.toml is larger than 1 MB"):
        _upload(content)
    with pytest.raises(CaseError, match="larger than 1 MB"):
        _upload(content.decode())


def test_upload_with_a_byte_order_mark_is_accepted():
    case = _upload(b"\xef\xbb\xbf" + SPINDLE.encode())
    assert case.bearing.ball_count == 18


@pytest.mark.parametrize(
    "content", [b"\xff\xfe" + SPINDLE.encode("utf-16-le"), b"\x00\x01\x02\xff", b"\xc3"]
)
def test_upload_that_is_not_utf8_is_a_case_error(content):
    with pytest.raises(CaseError, match="not a text file"):
        _upload(content)
