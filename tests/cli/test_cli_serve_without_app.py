"""`racetrace serve` without the app extra: a clear message and exit 2, never a traceback.

The subprocess blocks the import of some of the app's modules, as if the extra were not installed.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from racetrace.commands.serve import APP_EXTRA_MESSAGE, APP_MODULES

BLOCKED_RUN = """import sys

BLOCKED = set(sys.argv[1].split(","))


class NotInstalled:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in BLOCKED:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


sys.meta_path.insert(0, NotInstalled())
from racetrace.cli import main

sys.exit(main(["serve", "--port", "9"]))
"""


@pytest.mark.parametrize("blocked", [("trame",), ("pyvista", "vtkmodules"), APP_MODULES])
def test_serve_without_the_app_extra_says_how_to_install_it(blocked):
    result = subprocess.run(
        [sys.executable, "-c", BLOCKED_RUN, ",".join(blocked)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    assert APP_EXTRA_MESSAGE in result.stderr
    assert "pip install 'racetrace[app]'" in result.stderr
    assert f"(missing: {', '.join(blocked)})" in result.stderr
    assert result.stdout == ""
