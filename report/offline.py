"""Make a saved Panel page open with no network.

``panel.save(..., resources=INLINE)`` inlines the JavaScript but leaves stylesheet links to the
Panel CDN in the document (``ImportedStyleSheet`` models and ``<link>`` tags). Each such link is
replaced here by a ``data:`` URL holding the same file from the installed Panel package, so the
page needs nothing from outside. What cannot be found locally is dropped (with its URL returned).
"""

from __future__ import annotations

import base64
import re
from pathlib import Path

_CDN = re.compile(
    r"https://cdn\.holoviz\.org/panel/[^/\"'\\]+/dist/([^\"'\\?#)\s]+)(\?[^\"'\\)\s]*)?"
)


def _panel_dist() -> Path:
    import panel

    return Path(panel.__file__).parent / "dist"


def inline_cdn_links(html: str) -> tuple[str, list[str]]:
    """(html with every Panel CDN URL replaced by a data: URL, URLs that had no local file)."""
    dist = _panel_dist()
    missing: list[str] = []
    cache: dict[str, str] = {}

    def replace(match: re.Match) -> str:
        relative = match.group(1)
        if relative not in cache:
            path = dist / relative
            if path.is_file():
                kind = "text/css" if relative.endswith(".css") else "application/javascript"
                data = base64.b64encode(path.read_bytes()).decode("ascii")
                cache[relative] = f"data:{kind};base64,{data}"
            else:
                missing.append(match.group(0))
                cache[relative] = "data:text/css;base64,"
        return cache[relative]

    return _CDN.sub(replace, html), missing


def external_urls(html: str) -> list[str]:
    """URLs the page would load from outside: ``src``/``href`` attributes and stylesheet URLs in
    the document JSON that start with http(s) (links a reader clicks, such as <a href>, count
    too; the report has none)."""
    found = re.findall(
        r"""<(?:script|link|img|iframe)\b[^>]*?(?:src|href)\s*=\s*["'](https?://[^"']+)""", html
    )
    found += re.findall(r'\\?"url\\?"\s*:\s*\\?"(https?://[^"\\]+)', html)
    return sorted(set(found))
