"""Where numba keeps its compiled kernels: a folder keyed by the solver's source code.

numba's on-disk cache (``@njit(cache=True)``) checks only the timestamp of the file that defines a
kernel, not of the kernels it calls from other modules. After an update that changes a callee (say
``solver/physics/traction.py``) but not its caller (``solver/models/dynamic/kernels.py``), the stale
compiled caller would still be loaded and silently compute with the old physics. To rule that out,
the cache lives in ``<user cache dir>/racetrace/numba-<hash of every solver source file>``: any
source change gives a fresh folder. Folders of other versions unused for a week are removed.

A ``NUMBA_CACHE_DIR`` set by the user is respected. This must run before numba is imported.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sys
import time
from pathlib import Path

_STALE_AFTER_S = 7 * 24 * 3600.0


def source_fingerprint(package_dir: Path) -> str:
    """Short hash of the paths and contents of every ``.py`` file under ``package_dir``."""
    digest = hashlib.sha256()
    for path in sorted(package_dir.rglob("*.py")):
        digest.update(path.relative_to(package_dir).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure_numba_cache(package_dir: Path) -> Path | None:
    """Point numba's cache at a folder keyed by the solver sources; return it (None if not set)."""
    if "NUMBA_CACHE_DIR" in os.environ or "numba" in sys.modules:
        return None
    try:
        from platformdirs import user_cache_dir

        root = Path(user_cache_dir("racetrace", appauthor=False))
        folder = root / f"numba-{source_fingerprint(package_dir)}"
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None  # unwritable home: numba falls back to __pycache__ next to the sources
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    now = time.time()
    for other in root.glob("numba-*"):
        try:
            if other != folder and now - other.stat().st_mtime > _STALE_AFTER_S:
                shutil.rmtree(other, ignore_errors=True)
        except OSError:
            pass
    os.utime(folder)  # mark as used
    return folder
