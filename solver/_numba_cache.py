"""Where numba keeps racetrace's compiled kernels: always a folder keyed by the solver's sources.

numba's on-disk cache (``@njit(cache=True)``) checks only the file that defines a kernel, not the
kernels it calls from other modules. After an update that changes a callee (say
``solver/physics/traction.py``) but not its caller (``solver/models/dynamic/kernels.py``), a stale
compiled caller would be loaded and silently compute with the old physics. To rule that out, numba's
cache folder is always ``racetrace-numba-<hash of every solver source file>``, so any source change
gives a fresh folder. It is made inside the first writable of:

1. the user's ``NUMBA_CACHE_DIR`` (as a subfolder: numba then caches every kernel of the process
   there, the user's own kernels included);
2. the user cache folder (``~/.cache/racetrace`` on Linux);
3. the install folder (``solver/__pycache__``);
4. a private folder under the temp dir, with one warning on stderr (it may not outlive a reboot).

Nothing is deleted here: ``racetrace cache`` lists the folders of other versions and
``racetrace cache clean`` removes them.

:func:`configure_numba_cache` sets ``NUMBA_CACHE_DIR`` and, if numba is already imported,
``numba.core.config.CACHE_DIR`` (numba fixes a kernel's cache folder when the kernel is decorated,
from that setting). It must run before any solver kernel is defined. Processes started from this one
inherit the variable and keep the same folder.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

SOLVER_DIR = Path(__file__).parent
FOLDER_PREFIX = "racetrace-numba-"
_FINGERPRINT_CHARS = 16
_VERSION_FOLDER = re.compile(rf"{FOLDER_PREFIX}[0-9a-f]{{{_FINGERPRINT_CHARS}}}")
# In racetrace's own cache folder, folders named ``numba-<hash>`` are compiled kernels too (the name
# older installs used there).
_OWN_VERSION_FOLDER = re.compile(rf"(racetrace-)?numba-[0-9a-f]{{{_FINGERPRINT_CHARS}}}")


def source_fingerprint(package_dir: Path) -> str:
    """Short hash of the paths and contents of every ``.py`` file under ``package_dir``."""
    digest = hashlib.sha256()
    for path in sorted(package_dir.rglob("*.py")):
        digest.update(path.relative_to(package_dir).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:_FINGERPRINT_CHARS]


def version_folder_name(package_dir: Path) -> str:
    """Name of the cache folder of the sources under ``package_dir``."""
    return FOLDER_PREFIX + source_fingerprint(package_dir)


def user_cache_root() -> Path:
    """racetrace's folder in the user cache directory (``~/.cache/racetrace`` on Linux)."""
    from platformdirs import user_cache_dir

    return Path(user_cache_dir("racetrace", appauthor=False))


def install_root(package_dir: Path) -> Path:
    """The fallback inside the installed package."""
    return package_dir / "__pycache__"


def temp_root() -> Path:
    """The last resort: a folder of this user's under the temp dir."""
    user = os.getuid() if hasattr(os, "getuid") else "user"
    return Path(tempfile.gettempdir()) / f"racetrace-numba-cache-{user}"


def _writable(folder: Path) -> bool:
    """Create ``folder`` if needed and check that a file can be written in it (as numba does)."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError:
        return False
    return True


def _private(folder: Path) -> bool:
    """True if ``folder`` is a real directory owned by this user that nobody else can write.

    numba's cache index is a pickle: a folder others can write would let them run code here.
    """
    try:
        info = folder.lstat()
    except OSError:
        return False
    if not folder.is_dir() or folder.is_symlink():
        return False
    if hasattr(os, "getuid"):
        return info.st_uid == os.getuid() and not info.st_mode & 0o022
    return True


def _temp_folder(name: str) -> Path | None:
    """The cache folder ``name`` in a private, writable folder under the temp dir (None if none)."""
    root = temp_root()
    try:
        root.mkdir(mode=0o700, exist_ok=True)
    except OSError:
        pass
    if not _private(root):  # taken by someone else: a fresh private folder instead
        try:
            root = Path(tempfile.mkdtemp(prefix="racetrace-numba-cache-"))
        except OSError:
            return None
    folder = root / name
    return folder if _writable(folder) else None


def _requested_folder(given: str, name: str) -> Path:
    """The cache folder inside a ``NUMBA_CACHE_DIR`` that the user (or a parent process) set."""
    path = Path(given)
    if path.name == name:  # inherited from a racetrace process of this version
        return path
    if _VERSION_FOLDER.fullmatch(path.name):  # inherited from another version
        return path.parent / name
    return path / name


def _point_numba_at(folder: Path) -> None:
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    config = sys.modules.get("numba.core.config")
    if config is not None:  # numba read the variable when it was imported
        config.CACHE_DIR = str(folder)


def configure_numba_cache(package_dir: Path) -> Path | None:
    """Point numba's cache at the folder keyed by the sources under ``package_dir``; return it.

    Returns None (after a warning on stderr) only if no folder at all can be written, not even
    under the temp dir; numba then refuses to define the kernels.
    """
    name = version_folder_name(package_dir)
    given = os.environ.get("NUMBA_CACHE_DIR", "")
    candidates = [user_cache_root() / name, install_root(package_dir) / name]
    if given:
        candidates.insert(0, _requested_folder(given, name))
    for folder in candidates:
        if _writable(folder):
            if given and folder != candidates[0]:
                _warn(f"NUMBA_CACHE_DIR={given} cannot be written; compiled kernels go to {folder}")
            _point_numba_at(folder)
            return folder
    tried = ", ".join(str(c.parent) for c in candidates)
    folder = _temp_folder(name)
    if folder is None:
        _warn(f"no folder can be written for compiled kernels (tried {tried} and the temp dir)")
        return None
    _warn(
        f"cannot write compiled kernels to {tried}; using {folder} for now, which may not outlive "
        "a reboot (set NUMBA_CACHE_DIR to a writable folder to keep them)"
    )
    _point_numba_at(folder)
    return folder


def _warn(message: str) -> None:
    print(f"racetrace: warning: {message}", file=sys.stderr)


@dataclass(frozen=True)
class CacheFolder:
    """One folder of compiled kernels: its path, size in bytes, and whether this version uses it."""

    path: Path
    size_bytes: int
    current: bool


def active_folder(package_dir: Path = SOLVER_DIR) -> Path | None:
    """The cache folder this process uses (set by :func:`configure_numba_cache`), if any."""
    given = os.environ.get("NUMBA_CACHE_DIR", "")
    if given and Path(given).name == version_folder_name(package_dir):
        return Path(given)
    return None


def _roots(package_dir: Path, active: Path | None) -> list[tuple[Path, re.Pattern]]:
    """The folders that may hold cache folders of any version, each with its folder-name pattern."""
    roots = [(user_cache_root(), _OWN_VERSION_FOLDER), (install_root(package_dir), _VERSION_FOLDER)]
    if _private(temp_root()):
        roots.append((temp_root(), _VERSION_FOLDER))
    if active is not None:
        roots.append((active.parent, _VERSION_FOLDER))
    unique: dict[str, tuple[Path, re.Pattern]] = {}
    for root, pattern in roots:
        key = os.path.realpath(root)
        if key not in unique or pattern is _OWN_VERSION_FOLDER:
            unique[key] = (root, pattern)
    return list(unique.values())


def _size(folder: Path) -> int:
    total = 0
    for dirpath, _, filenames in os.walk(folder):
        for filename in filenames:
            try:
                total += os.lstat(os.path.join(dirpath, filename)).st_size
            except OSError:
                pass
    return total


def cache_folders(package_dir: Path = SOLVER_DIR) -> list[CacheFolder]:
    """Every cache folder of compiled kernels found, of this version and of others."""
    active = active_folder(package_dir)
    found: dict[str, CacheFolder] = {}
    for root, pattern in _roots(package_dir, active):
        try:
            entries = sorted(root.iterdir())
        except OSError:
            continue
        for entry in entries:
            if not pattern.fullmatch(entry.name) or entry.is_symlink() or not entry.is_dir():
                continue
            current = active is not None and os.path.realpath(entry) == os.path.realpath(active)
            found[os.path.realpath(entry)] = CacheFolder(entry, _size(entry), current)
    return list(found.values())


def remove_folders(folders: list[CacheFolder]) -> list[tuple[Path, str]]:
    """Delete the given cache folders; return ``(path, reason)`` for each that could not be."""
    failed = []
    for folder in folders:
        try:
            shutil.rmtree(folder.path)
        except OSError as error:
            failed.append((folder.path, error.strerror or str(error)))
    return failed
