#!/usr/bin/python3
"""Plots the measured facet NDF of a generated surface against its target.

Usage: scripts/plot_surface_ndf.py SURFACE_ndf.csv [OUT.png]
The CSV is written by `gonio surface` beside each height map: D(m) cos(theta_m) averaged over rings
of equal-area cells. The plot shows both over theta_m (log scale) and their ratio.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else path.rsplit(".", 1)[0] + ".png"
    title = ""
    theta, measured, target = [], [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                title = line[1:].strip()
                continue
            if line.startswith("theta_min"):
                continue
            a, b, m, t = (float(x) for x in line.split(","))
            theta.append(0.5 * (a + b))
            measured.append(m)
            target.append(t)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    top.semilogy(theta, target, "-", color="tab:green", label="target D cos")
    top.semilogy(theta, measured, ".", color="tab:red", label="surface triangles")
    top.set_ylabel("D(m) cos(theta_m)  [1/sr]")
    top.set_ylim(max(target) * 1e-6, max(target) * 3)
    top.legend()
    top.set_title(title, fontsize=8)
    ratio = [m / t if t > 0 else float("nan") for m, t in zip(measured, target)]
    bottom.plot(theta, ratio, ".", color="tab:red")
    bottom.axhline(1.0, color="tab:green")
    bottom.set_ylim(0.8, 1.2)
    bottom.set_xlabel("theta_m [degree]")
    bottom.set_ylabel("measured / target")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
