"""Draw docs/figures/trajectory-metrics.png: what the trajectory excursion and band thickness
measure.

Run from the repository root: ``python docs/figures/make_metrics_figure.py`` (needs matplotlib).
Synthetic contact samples, measured with the solver's own definition
(:func:`solver.results.summary.track_metrics`): a thin line that wanders across the groove (large
excursion, no thickness) and a band (thickness, no excursion).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from solver.results.summary import AZIMUTH_BINS, track_metrics  # noqa: E402

OUT = Path(__file__).with_name("trajectory-metrics.png")
MEAN_ANGLE = 18.0  # degree
SAMPLES = 20000


def mean_track(azimuth, angle):
    """Bin centres and bin medians (degree), as summary.track_metrics bins them."""
    width = 360.0 / AZIMUTH_BINS
    index = np.minimum((azimuth // width).astype(int), AZIMUTH_BINS - 1)
    centres = (np.arange(AZIMUTH_BINS) + 0.5) * width
    medians = np.array([np.median(angle[index == b]) for b in range(AZIMUTH_BINS)])
    return centres, medians, medians[index]


def panel(ax, azimuth, angle, title):
    excursion, thickness = track_metrics(azimuth, angle)
    centres, medians, track = mean_track(azimuth, angle)
    low, high = np.percentile(angle - track, [2.5, 97.5])
    ax.plot(azimuth, angle, ".", ms=1.0, color="#7f9fbf", alpha=0.35, label="contact samples")
    ax.fill_between(
        centres,
        medians + low,
        medians + high,
        color="#f2b134",
        alpha=0.35,
        label="central 95 % of the residuals",
    )
    ax.plot(centres, medians, "-", color="#1f3b73", lw=2, label="mean track (bin medians)")
    top, bottom = medians.max(), medians.min()
    x = 370.0
    ax.annotate("", (x, top), (x, bottom), arrowprops={"arrowstyle": "<->", "color": "#1f3b73"})
    ax.text(x + 6, 0.5 * (top + bottom), f"excursion\n{excursion:.2f}°", va="center", fontsize=8)
    ax.annotate(
        "",
        (90.0, medians[9] + high),
        (90.0, medians[9] + low),
        arrowprops={"arrowstyle": "<->", "color": "#b35900"},
    )
    ax.text(
        96.0, medians[9] + high + 0.05, f"thickness {thickness:.2f}°", fontsize=8, color="#b35900"
    )
    ax.set_title(title, fontsize=10)
    ax.set_xlim(0, 420)
    ax.set_ylim(MEAN_ANGLE - 0.65, MEAN_ANGLE + 0.75)
    ax.set_xticks(range(0, 361, 90))
    ax.set_xlabel("raceway azimuth in the ring frame, degree")


def main() -> None:
    rng = np.random.default_rng(3)
    azimuth = rng.uniform(0.0, 360.0, SAMPLES)
    line = MEAN_ANGLE + 0.5 * np.cos(np.radians(azimuth)) + rng.normal(0.0, 0.005, SAMPLES)
    band = MEAN_ANGLE + rng.uniform(-0.5, 0.5, SAMPLES)
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.4), sharey=True, dpi=110)
    panel(axes[0], azimuth, line, "a thin line: the same track on every pass")
    panel(axes[1], azimuth, band, "a band: passes scatter at one azimuth")
    axes[0].set_ylabel("contact angle, degree")
    axes[0].legend(loc="lower left", fontsize=7, markerscale=4)
    fig.tight_layout()
    fig.savefig(OUT)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
