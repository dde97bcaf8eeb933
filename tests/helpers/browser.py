"""What the browser tests share: Debian's chromium and its launch flags (tools/chromium.py), where
screenshots go, the first drawn 3-D image and the marks that skip a module without chromium."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.chromium import CHROMIUM

FIRST_IMAGE = "#view-3d img[src]:not([src=''])"  # the first drawn image, not an empty img
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts" / "browser"
#: ``pytestmark`` of a browser test module
BROWSER_MARKS = [
    pytest.mark.browser,
    pytest.mark.skipif(
        not Path(CHROMIUM).exists(),
        reason=f"{CHROMIUM} is missing (apt-get install --no-install-recommends chromium)",
    ),
]
