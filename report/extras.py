"""Which optional extras (``pip install -e ".[app]"``, ``".[report]"``) are installed."""

from __future__ import annotations

import importlib.util


def missing_modules(names) -> list[str]:
    """The modules of ``names`` that cannot be found here (their extra is not installed)."""
    missing = []
    for name in names:
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            missing.append(name)
    return missing
