"""Who may use the server (app.access): Host, Origin and the access token."""

from __future__ import annotations

import pytest

from app.access import Access, is_loopback, new_token


@pytest.mark.parametrize(
    ("host", "expected"),
    [("127.0.0.1", True), ("localhost", True), ("::1", True), ("0.0.0.0", False)],
)
def test_loopback_addresses(host, expected):
    assert is_loopback(host) is expected


def test_loopback_server_accepts_its_own_pages():
    access = Access("127.0.0.1")
    assert access.check("127.0.0.1:8080", None) == ""
    assert access.check("localhost:8080", "http://localhost:8080") == ""
    assert access.check("[::1]:8080", "http://[::1]:8080") == ""


def test_foreign_origin_is_refused():
    access = Access("127.0.0.1")
    problem = access.check("127.0.0.1:8080", "http://evil.example")
    assert "foreign origin" in problem and "evil.example" in problem
    # same host, other port: another site too
    assert "foreign origin" in access.check("127.0.0.1:8080", "http://127.0.0.1:9999")
    assert "opaque origin" in access.check("127.0.0.1:8080", "null")


def test_foreign_host_name_is_refused_on_loopback():
    """A name of the attacker's that resolves to 127.0.0.1 (DNS rebinding) is not this page."""
    problem = Access("127.0.0.1").check("rebind.example:8080", "http://rebind.example:8080")
    assert "not this machine's loopback address" in problem


def test_network_server_requires_the_token():
    token = new_token()
    assert len(token) >= 24
    access = Access("0.0.0.0", token)
    assert "access token required" in access.check("192.168.1.5:8080", None)
    assert "access token required" in access.check("192.168.1.5:8080", None, "wrong")
    assert access.check("192.168.1.5:8080", None, token) == ""
    assert access.check("192.168.1.5:8080", "http://192.168.1.5:8080", "", token) == ""
    # the token does not excuse a foreign page
    assert "foreign origin" in access.check("192.168.1.5:8080", "http://evil.example", token)
