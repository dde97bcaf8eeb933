"""Compare the quasi-static model's two sources of ball speeds with the dynamic model at steady
state, print the figures and draw docs/figures/quasistatic-traction.png.

Run from the repository root (needs matplotlib):
``python docs/figures/make_quasistatic_traction_figure.py [--case spindle-combined-load]
[--dynamic RUN.nc]``. Without ``--dynamic`` the dynamic model is run first (12 shaft revolutions:
about a minute on an idle machine). Per race it prints the mean contact angle, the contact-angle
range over the balls (dynamic: peak-to-peak of the steady track against the ball's azimuth in
space, 36 bins of 10 degree), the largest jump between neighbouring balls (dynamic: its mean over
the analysed samples), the RMS distance of the quasi-static balls from the dynamic track at their
azimuths, and the cage speed.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import solver  # noqa: E402
from solver.results.summary import AZIMUTH_BINS, analysis_start  # noqa: E402

OUT = Path(__file__).with_name("quasistatic-traction.png")
RACES = ("inner", "outer")


def dynamic_track(ds, race):
    """(bin centres, bin medians) of the steady contact angle [degree] against the ball azimuth in
    space, over the analysed window (loaded contacts)."""
    first, _ = analysis_start(ds)
    window = ds.isel(time=slice(first, None))
    azimuth = np.mod(window.ball_azimuth.values, 360.0).ravel()
    sub = window.sel(race=race)
    angle = sub.contact_angle.transpose("ball", "time").values.ravel()
    loaded = sub.contact_load.transpose("ball", "time").values.ravel() > 0.0
    width = 360.0 / AZIMUTH_BINS
    index = np.minimum((azimuth[loaded] // width).astype(int), AZIMUTH_BINS - 1)
    medians = np.array(
        [np.median(angle[loaded][index == b]) for b in range(AZIMUTH_BINS)], dtype=float
    )
    return (np.arange(AZIMUTH_BINS) + 0.5) * width, medians


def neighbour_jump_dynamic(ds, race):
    """Mean over the analysed samples of the largest contact-angle difference [degree] between
    neighbouring balls."""
    first, _ = analysis_start(ds)
    angle = ds.contact_angle.sel(race=race).transpose("time", "ball").values[first:]
    jumps = np.abs(np.diff(np.concatenate([angle, angle[:, :1]], axis=1), axis=1))
    return float(jumps.max(axis=1).mean())


def compare(qs, ds):
    """Per race: {"mean", "range", "jump", "rms_from_dynamic"} of a quasi-static result ``qs``
    (degree), and of the dynamic result ``ds`` itself (no rms)."""
    out = {"quasistatic": {}, "dynamic": {}}
    azimuth = qs.ball_azimuth.values
    for race in RACES:
        centres, medians = dynamic_track(ds, race)
        angle = qs.contact_angle.sel(race=race).values
        track = np.interp(azimuth, centres, medians, period=360.0)
        out["quasistatic"][race] = {
            "mean": float(angle.mean()),
            "range": float(np.ptp(angle)),
            "jump": float(np.max(np.abs(np.diff(np.r_[angle, angle[:1]])))),
            "rms_from_dynamic": float(np.sqrt(np.mean((angle - track) ** 2))),
        }
        first, _ = analysis_start(ds)
        steady = ds.contact_angle.sel(race=race).isel(time=slice(first, None))
        out["dynamic"][race] = {
            "mean": float(steady.mean()),
            "range": float(np.nanmax(medians) - np.nanmin(medians)),
            "jump": neighbour_jump_dynamic(ds, race),
        }
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="spindle-combined-load")
    parser.add_argument("--dynamic", help="a saved dynamic run of the same case (NetCDF)")
    args = parser.parse_args(argv)
    case = solver.catalogue().get(args.case).load()
    if args.dynamic:
        ds = solver.load_dataset(args.dynamic)
    else:
        ds = solver.simulate(case.with_values({"simulation.shaft_revolutions": 12.0}))
    results = {}
    for mode in ("race_control", "traction"):
        variant = case.with_values({"simulation.quasistatic_ball_speeds": mode})
        results[mode] = solver.solve_quasistatic(variant)
    settled = analysis_start(ds)[1]
    print(f"case {args.case}; dynamic run settled: {settled.settled}")
    header = f"{'':14s} {'race':6s} {'mean':>8s} {'range':>8s} {'jump':>8s} {'rms':>8s}"
    print(header + "   (degree; rms: distance from the dynamic steady track)")
    rows = {mode: compare(qs, ds) for mode, qs in results.items()}
    for race in RACES:
        d = rows["race_control"]["dynamic"][race]
        print(f"{'dynamic':14s} {race:6s} {d['mean']:8.3f} {d['range']:8.3f} {d['jump']:8.3f}")
        for mode in results:
            q = rows[mode]["quasistatic"][race]
            print(
                f"{mode:14s} {race:6s} {q['mean']:8.3f} {q['range']:8.3f} {q['jump']:8.3f} "
                f"{q['rms_from_dynamic']:8.3f}"
            )
    cage = float(ds.cage_speed.isel(time=slice(analysis_start(ds)[0], None)).mean())
    print(
        "cage speed [rad/s]: dynamic "
        + f"{cage:.3f}, "
        + ", ".join(f"{m} {float(qs.cage_speed):.3f}" for m, qs in results.items())
    )

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharex=True)
    styles = {"race_control": ("s", "#d62728"), "traction": ("o", "#2ca02c")}
    for ax, race in zip(axes, RACES, strict=True):
        centres, medians = dynamic_track(ds, race)
        ax.plot(centres, medians, "-", color="#1f77b4", lw=2, label="dynamic, steady track")
        for mode, qs in results.items():
            marker, colour = styles[mode]
            ax.plot(
                qs.ball_azimuth.values,
                qs.contact_angle.sel(race=race).values,
                marker,
                ms=5,
                mfc="none",
                color=colour,
                label=f"quasi-static, {mode.replace('_', ' ')}",
            )
        ax.set_title(f"{race} race")
        ax.set_xlabel("ball azimuth in space (degree)")
        ax.set_xlim(0, 360)
    axes[0].set_ylabel("contact angle (degree)")
    axes[1].legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT, dpi=110)
    print(f"figure written to {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
