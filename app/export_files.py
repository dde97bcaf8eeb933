"""Exports of a result and of the 3-D view: NetCDF, CSV, PNG and an MP4 or GIF animation.

NetCDF and CSV go through the solver's ``ds.racetrace`` accessor (the one export door); PNG and the
animations need this app's renderer. Every file is written to a temporary name next to its target
and renamed into place (atomic).
"""

from __future__ import annotations

import os
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import xarray as xr

import solver  # noqa: F401  (registers the ds.racetrace accessor)

ANIMATION_FORMATS = ("gif", "mp4")


@contextmanager
def _atomic_target(path: Path):
    """Yields a temporary name next to ``path``; renamed onto ``path`` only if the block ends
    normally, removed otherwise."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.tmp{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def _atomic(path: Path, write) -> Path:
    path = Path(path)
    with _atomic_target(path) as tmp:
        write(tmp)
    return path


def export_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """The result as NetCDF (the results-schema.md contract), through ``ds.racetrace.save``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return ds.racetrace.save(path)


def export_csv(ds: xr.Dataset, path: str | Path) -> Path:
    """The per-contact table as CSV, through ``ds.racetrace.to_csv`` (columns defined by
    :func:`solver.results.io.contact_table`)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return ds.racetrace.to_csv(path)


def captioned(image: np.ndarray, caption: str | None) -> np.ndarray:
    """``image`` (height x width x RGB[A], uint8) with ``caption`` written in a dark band along
    its bottom (the image keeps its size); unchanged when ``caption`` is empty."""
    if not caption:
        return image
    from PIL import Image, ImageDraw, ImageFont

    picture = Image.fromarray(np.ascontiguousarray(image[..., :3]))
    height = picture.height
    draw = ImageDraw.Draw(picture)
    size = max(8, min(16, height // 28))
    while True:  # the largest size (down to 8 px) at which the caption fits the width
        try:
            font = ImageFont.load_default(size=size)
        except TypeError:  # Pillow < 10.1: one bitmap size
            font = ImageFont.load_default()
            break
        if size <= 8 or draw.textlength(caption, font=font) <= picture.width - 8:
            break
        size -= 1
    band = size + 6
    draw.rectangle([0, height - band, picture.width, height], fill=(20, 20, 20))
    draw.text((4, height - band + 3), caption, fill=(240, 240, 240), font=font)
    return np.asarray(picture)


def even_sized(image: np.ndarray) -> np.ndarray:
    """``image`` padded by one edge row/column where its height/width is odd (H.264 in MP4
    needs even sizes)."""
    pad_h, pad_w = image.shape[0] % 2, image.shape[1] % 2
    if not (pad_h or pad_w):
        return image
    return np.pad(image, ((0, pad_h), (0, pad_w), (0, 0)), mode="edge")


def export_png(plotter, path: str | Path, caption: str | None = None) -> Path:
    """The 3-D view as PNG, with ``caption`` along its bottom (renders first: ``screenshot``
    alone can return a stale image)."""
    import imageio.v2 as imageio

    plotter.render()
    plotter.render_window.Render()
    image = captioned(np.asarray(plotter.screenshot(return_img=True)), caption)
    return _atomic(Path(path), lambda tmp: imageio.imwrite(str(tmp), image, format="PNG"))


def export_animation(scene, path: str | Path, **options) -> Path:
    """Frames ``start:stop:step`` of the scene's current source as GIF or MP4 (by suffix), in one
    call: the options (``start``, ``stop``, ``step``, ``fps``, ``caption``) and what is written
    are those of :func:`iter_export_animation`. The scene is left at its previous frame."""
    for _ in iter_export_animation(scene, path, **options):
        pass
    return Path(path)


def iter_export_animation(
    scene,
    path: str | Path,
    start: int = 0,
    stop: int | None = None,
    step: int = 1,
    fps: float = 12.0,
    caption=None,
):
    """Write the animation frame by frame, yielding the fraction done (0-1] after each frame.

    ``caption``: a function of the frame index giving the text written along the bottom of that
    frame (None: no caption). MP4 frames of odd width or height are padded to even sizes.

    Lets the caller keep its event loop going between frames (rendering must stay in the thread
    that owns the VTK window). ``fps`` is the playback rate stored in the file (GIF frame delay
    ``1000 / fps`` ms). The file appears, complete, only at the end (written to a temporary name
    and renamed); the scene is put back at its previous frame even if the export is abandoned.
    """
    import imageio.v2 as imageio

    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ANIMATION_FORMATS:
        raise ValueError(f"animation file {path.name!r}: use a .gif or .mp4 name")
    if scene.source is None:
        raise ValueError("no result is shown, so there is nothing to animate")
    if not fps > 0:
        raise ValueError(f"fps = {fps}: must be positive")
    stop = scene.source.n_frames if stop is None else min(stop, scene.source.n_frames)
    indices = range(max(0, start), stop, max(1, int(step)))
    if len(indices) < 2:
        raise ValueError("an animation needs at least two frames")
    previous = scene.frame_index
    plotter = scene.plotter
    if fmt == "mp4":
        options = {"format": "FFMPEG", "fps": fps, "macro_block_size": 1}
    else:  # imageio's GIF writer (Pillow) takes the frame delay in milliseconds
        options = {"format": "GIF", "duration": 1000.0 / fps, "loop": 0}
    try:
        with _atomic_target(path) as tmp, imageio.get_writer(str(tmp), **options) as writer:
            for done, i in enumerate(indices, start=1):
                scene.set_frame(i)
                plotter.render_window.Render()
                image = np.asarray(plotter.screenshot(return_img=True))
                image = captioned(image, caption(i) if caption is not None else None)
                writer.append_data(even_sized(image) if fmt == "mp4" else image)
                yield done / len(indices)
    finally:
        scene.set_frame(previous)
