"""Measure what one played frame of the 3-D view costs on the server (run by hand, not in CI).

    python benchmarks/app_render.py [--run FILE.nc] [--size 820x670] [--frames 60]

Both ways of drawing the view are timed in the same run, frame after frame on the same frames:

* server rendering (``racetrace serve --render server``): as below;
* in-browser rendering (the default): what the server does for a played frame when the browser
  draws (:class:`viz.browser_scene.BrowserScene`): the moving parts' matrices, the frame's
  ellipses and how many painted-track quads are shown, and the encoding of that state for the
  websocket (msgpack, as wslink sends it). What is sent once per result (the painted tracks'
  quads in painting order and their whole-run colours) and for a frame chosen by hand (the
  colours painted up to it) is timed and sized apart.

Builds the scene of the app (:class:`viz.scene.BearingScene`, the default isometric camera, the
painted tracks growing) for a dynamic result off screen, and times each step of a played frame as
the app's view does it: the scene update (``set_frame``: actors, ellipses, painted tracks), the
render, the capture of the image and its JPEG encoding (trame-rca's, at the quality it uses while
playing). Prints medians of process CPU time and of wall time per step. CPU time counts the work
done whatever else the machine runs (the renderer's threads included), so it compares versions on
a shared machine; wall time is what a user waits on an idle one.

``--run``: a dynamic result (``racetrace simulate ... --output FILE.nc``); without it, a run of
the default case with ``--revolutions`` shaft revolutions is computed first.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

INTERACTIVE_QUALITY = 60  # trame-rca's JPEG quality for frames in motion


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--run", type=Path, default=None, help="a dynamic result (.nc)")
    parser.add_argument("--revolutions", type=int, default=100)
    parser.add_argument("--size", default="820x670", help="render size, WIDTHxHEIGHT pixels")
    parser.add_argument("--frames", type=int, default=60)
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    run = args.run
    if run is None:
        run = Path(tempfile.mkdtemp(prefix="racetrace-render-")) / "run.nc"
        subprocess.run(
            [sys.executable, "-m", "racetrace", "simulate", "spindle-combined-load",
             "--revolutions", str(args.revolutions), "--quiet", "--output", str(run)],
            check=True,
        )  # fmt: skip

    from viz.offscreen import configure_environment

    configure_environment()
    import pyvista as pv
    from trame_rca.encoders import RcaImageEncoder
    from trame_rca.rca.vtk_rca import VtkRemoteControlledArea

    from solver import load_dataset
    from solver.results.dataset import geometry_from_result
    from viz.frames import frame_source
    from viz.scene import BearingScene, SceneOptions

    ds = load_dataset(run)
    t0 = time.perf_counter()
    source = frame_source(ds)
    side = math.radians(float(ds.coords["radial_load_angle"]))
    options = SceneOptions(
        exaggeration=5.0,
        view_azimuth=side,
        outer_cutaway=(side - math.pi / 2, side + math.pi / 2),
    )
    pv.global_theme.multi_samples = 0
    plotter = pv.Plotter(off_screen=True, window_size=(width, height))
    scene = BearingScene(plotter, geometry_from_result(ds), options)
    scene.show_source(source, 0)
    print(
        f"run: {source.n_frames} frames, {source.ball_count} balls; scene and tracks ready in "
        f"{time.perf_counter() - t0:.1f} s; render {width}x{height}; load average "
        + " ".join(f"{x:.1f}" for x in os.getloadavg())
    )
    area = VtkRemoteControlledArea(plotter.render_window)
    encoder = RcaImageEncoder("jpeg")
    steps = ("scene update", "render", "capture", "encode")
    cpu = {k: [] for k in steps}
    wall = {k: [] for k in steps}
    size = []
    frame = source.n_frames // 3  # well into the run: the painted tracks hold many passes
    for _ in range(args.frames):
        frame += 1
        marks = [(time.process_time(), time.perf_counter())]
        scene.set_frame(frame)
        marks.append((time.process_time(), time.perf_counter()))
        area._render()
        marks.append((time.process_time(), time.perf_counter()))
        area._window_to_image.Modified()
        area._window_to_image.Update()
        image = area._window_to_image.GetOutput()
        from vtkmodules.util.numpy_support import vtk_to_numpy

        cols, rows, _ = image.GetDimensions()
        pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(rows, cols, -1)
        pixels = pixels[::-1, :, :3].copy()
        marks.append((time.process_time(), time.perf_counter()))
        jpeg, _, _ = encoder.encode(pixels, cols, rows, INTERACTIVE_QUALITY)
        marks.append((time.process_time(), time.perf_counter()))
        size.append(len(jpeg))
        for k, step in enumerate(steps):
            cpu[step].append(marks[k + 1][0] - marks[k][0])
            wall[step].append(marks[k + 1][1] - marks[k][1])
    browser = _browser_frames(scene, source.n_frames // 3, args.frames)
    print(f"per played frame, median of {args.frames} (ms): step, CPU time, wall time")
    for step in steps:
        print(
            f"  {step:13s} {1e3 * statistics.median(cpu[step]):6.1f} "
            f"{1e3 * statistics.median(wall[step]):6.1f}"
        )
    total_cpu = sum(statistics.median(cpu[s]) for s in steps)
    total_wall = sum(statistics.median(wall[s]) for s in steps)
    print(
        f"  {'total':13s} {1e3 * total_cpu:6.1f} {1e3 * total_wall:6.1f}   "
        f"(at most {1 / total_cpu:.0f} frames/s of CPU time); JPEG "
        f"{statistics.median(size) / 1e3:.0f} kB"
    )
    print(
        "in-browser rendering, server CPU per played frame (ms, median): matrices + ellipses + "
        f"painted quads shown + encoding {1e3 * browser['frame_cpu']:.2f} "
        f"({total_cpu / browser['frame_cpu']:.0f}x less than server rendering); sent per frame "
        f"{browser['frame_bytes'] / 1e3:.1f} kB. Once per result: the tracks' quads in painting "
        f"order and their whole-run colours {1e3 * browser['result_cpu']:.0f} ms, "
        f"{browser['result_bytes'] / 1e3:.0f} kB. A frame chosen by hand: its colours "
        f"{1e3 * browser['chosen_cpu']:.1f} ms, {browser['chosen_bytes'] / 1e3:.0f} kB"
    )
    plotter.close()
    return 0


def _browser_frames(scene, first: int, count: int) -> dict:
    """Median CPU seconds and bytes of a played frame's state with in-browser rendering (frames
    ``first + 1 ...``, ``count`` of them; ``frame_cpu``, ``frame_bytes``), of what is sent once
    per result (``result_cpu``, ``result_bytes``) and of a frame chosen by hand (``chosen_cpu``,
    ``chosen_bytes``: the colours painted up to it, a second of play apart)."""
    import msgpack

    from viz.browser_scene import BrowserScene

    browser = BrowserScene(scene)
    options = scene.options
    n = scene.source.n_frames
    t0 = time.process_time()
    packed = msgpack.packb(
        {
            "rt3d_track_cells": browser.track_cells(),
            "rt3d_track_run": browser.track_state(n, options.track_quantity),
        }
    )
    result_cpu, result_bytes = time.process_time() - t0, len(packed)
    cpu, size, chosen_cpu, chosen_size = [], [], [], []
    frame = first
    for _ in range(count):
        frame += 1
        t0 = time.process_time()
        state = browser.frame_state(frame, options.ellipse_scale, frame + 1)
        state["run"] = True
        packed = msgpack.packb({"rt3d_frame": state})
        cpu.append(time.process_time() - t0)
        size.append(len(packed))
    frame = first
    for _ in range(min(count, 20)):
        frame += 24
        t0 = time.process_time()
        packed = msgpack.packb(
            {"rt3d_tracks": browser.track_state(frame + 1, options.track_quantity)}
        )
        chosen_cpu.append(time.process_time() - t0)
        chosen_size.append(len(packed))
    median = statistics.median
    return {
        "frame_cpu": median(cpu),
        "frame_bytes": median(size),
        "result_cpu": result_cpu,
        "result_bytes": result_bytes,
        "chosen_cpu": median(chosen_cpu),
        "chosen_bytes": median(chosen_size),
    }


if __name__ == "__main__":
    sys.exit(main())
