"""What the browser tests share: Debian's chromium and its launch flags (tools/chromium.py), where
screenshots go, the first drawn 3-D image and the marks that skip a module without chromium."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.chromium import CHROMIUM

FIRST_IMAGE = "#view-3d img[src]:not([src=''])"  # the first drawn image, not an empty img
#: How long a test waits for a playing page to show the answer to what it did (ms): an edited
#: field's message, a run's first status. The page applies each message, then draws the 3-D view
#: in software; on a loaded machine the answer comes a few of those later (a field edit's answer
#: while playing, at load 9 on 2 cores: median 3.0 s, max 6.6 s with the server-rendered view and
#: median 6.8 s, max 10.3 s with the browser-drawn one), and CI runs two browser tests at once.
RESPONSE_MS = 30_000
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts" / "browser"
#: ``pytestmark`` of a browser test module
BROWSER_MARKS = [
    pytest.mark.browser,
    pytest.mark.skipif(
        not Path(CHROMIUM).exists(),
        reason=f"{CHROMIUM} is missing (apt-get install --no-install-recommends chromium)",
    ),
]
