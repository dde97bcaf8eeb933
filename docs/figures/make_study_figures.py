"""Draw the figures of docs/studies.md from the study Datasets of the shipped studies.

Run from the repository root: ``python docs/figures/make_study_figures.py [SEED.nc 218.nc]``
(needs matplotlib). By default it reads the study Datasets kept in ``assets/studies/results/``
(the app opens them too), written by ``racetrace study seed-spindle --output seed`` and
``racetrace study 218-radial-load --output s218`` (each folder's ``study.nc``). Writes
``study-track-width.png`` (across-groove width of the track on each race, dynamic runs) and
``study-line-or-band.png`` (excursion and band thickness of each race in its own ring's frame
under misalignment fixed in space and turning with the ring).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

HERE = Path(__file__).parent
DATA = HERE.parents[1] / "assets" / "studies" / "results"
COLOURS = {"inner": "#1f77b4", "outer": "#d62728"}


def sweep(ds, name: str, key: str):
    """(x, dataset of the points of sweep ``name`` sorted by ``key``)."""
    part = ds.isel(point=np.flatnonzero(ds["sweep"].values == name))
    part = part.sortby(key)
    return np.asarray(part[key].values, float), part


def track_width(seed, s218, out: Path) -> None:
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), constrained_layout=True)
    panels = [
        (axes[0, 0], seed, "radial load", "operating.radial_load_N", "radial load [N]",
         "7008C-class hybrid, 500 N axial, 20 000 rpm"),
        (axes[0, 1], s218, "sweep 1", "operating.radial_load_N", "radial load [N]",
         "218 (40 deg), 17.8 kN axial, 10 000 rpm"),
        (axes[1, 0], seed, "speed, 300 N radial", "operating.inner_ring_speed_rpm",
         "inner-ring speed [rpm]", "7008C-class hybrid, 500 N axial + 300 N radial"),
        (axes[1, 1], seed, "misalignment fixed in space", "operating.misalignment_deg",
         "misalignment [deg]", "7008C-class hybrid, 500 N axial, tilt fixed in space"),
    ]  # fmt: skip
    for ax, ds, name, key, label, title in panels:
        x, part = sweep(ds, name, key)
        for race in ("inner", "outer"):
            y = part["band_width"].sel(model="dynamic", race=race).values
            ax.plot(x, y, "o-", color=COLOURS[race], label=f"{race} race")
        ax.set_xlabel(label)
        ax.set_ylabel("track width across the groove [deg]")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend()
    fig.suptitle(
        "Where the outer track is wider than the inner one (dynamic runs, 6 shaft revolutions)",
        fontsize=11,
    )
    fig.savefig(out, dpi=110)
    plt.close(fig)


def line_or_band(seed, out: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True, sharey=True)
    for ax, name in zip(
        axes, ("misalignment fixed in space", "misalignment turning with the ring"), strict=True
    ):
        x, part = sweep(seed, name, "operating.misalignment_deg")
        for race in ("inner", "outer"):
            sel = {"model": "dynamic", "race": race}
            ax.plot(x, part["excursion_arc"].sel(sel) * 1e6, "o-", color=COLOURS[race],
                    label=f"{race}: excursion")  # fmt: skip
            ax.plot(x, part["band_thickness_arc"].sel(sel) * 1e6, "s--", color=COLOURS[race],
                    label=f"{race}: band thickness")  # fmt: skip
        ax.set_title(name, fontsize=10)
        ax.set_xlabel("misalignment [deg]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("across the groove, own ring's frame [um]")
    axes[1].legend(fontsize=8)
    fig.suptitle(
        "7008C-class hybrid, 500 N axial, 20 000 rpm: a line on one race, a band on the other",
        fontsize=11,
    )
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv: list[str]) -> None:
    seed_path = Path(argv[0]) if argv else DATA / "seed-spindle.study.nc"
    s218_path = Path(argv[1]) if len(argv) > 1 else DATA / "218-radial-load.study.nc"
    with xr.open_dataset(seed_path) as seed, xr.open_dataset(s218_path) as s218:
        seed, s218 = seed.load(), s218.load()
    track_width(seed, s218, HERE / "study-track-width.png")
    line_or_band(seed, HERE / "study-line-or-band.png")
    print(f"wrote {HERE / 'study-track-width.png'} and {HERE / 'study-line-or-band.png'}")


if __name__ == "__main__":
    main(sys.argv[1:])
