#!/usr/bin/python3
"""The quick look of `gonio ndf --csv`: each case's D(theta) and Smith Lambda(theta).

Usage: scripts/plot_ndf.py CURVES.csv [OUT.png]

One column per case: on top D(theta_m) along phi = 0 and phi = 90 deg (logarithmic), below
Lambda(theta) along both azimuths (logarithmic). Needs Debian's python3-matplotlib and
python3-numpy (under /usr/bin/python3).
"""
import csv
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_curves(path):
    """{case: {column: array}} in the file's case order."""
    cases = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            columns = cases.setdefault(row["case"], {})
            for key, value in row.items():
                if key != "case":
                    columns.setdefault(key, []).append(float(value))
    return {name: {k: np.array(v) for k, v in cols.items()} for name, cols in cases.items()}


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    out = argv[2] if len(argv) > 2 else argv[1].rsplit(".", 1)[0] + ".png"
    cases = read_curves(argv[1])
    if not cases:
        print("plot_ndf: no curves in " + argv[1], file=sys.stderr)
        return 1
    per_row = min(5, len(cases))
    rows = (len(cases) + per_row - 1) // per_row
    fig, axes = plt.subplots(2 * rows, per_row, figsize=(3.0 * per_row, 4.6 * rows),
                             squeeze=False)
    for ax in axes.flat:
        ax.set_visible(False)
    for k, (name, c) in enumerate(cases.items()):
        t = c["theta_deg"]
        top, bottom = axes[2 * (k // per_row)][k % per_row], axes[2 * (k // per_row) + 1][k % per_row]
        top.set_visible(True)
        bottom.set_visible(True)
        for column, label, style in (("D_phi0", "phi = 0", "-"), ("D_phi90", "phi = 90", "--")):
            top.semilogy(t, np.where(c[column] > 0, c[column], np.nan), style, label=label)
        for column, label, style in (("lambda_phi0", "phi = 0", "-"),
                                     ("lambda_phi90", "phi = 90", "--")):
            bottom.semilogy(t, np.where(c[column] > 0, c[column], np.nan), style, label=label)
        top.set_title(name, fontsize=9)
        peak = max(c["D_phi0"].max(), c["D_phi90"].max())
        top.set_ylim(1e-4 * peak, 2 * peak)
        bottom.set_ylim(1e-4, 1e4)
        bottom.set_xlabel("theta (deg)")
        top.set_xlim(0, 90)
        bottom.set_xlim(0, 90)
        if k % per_row == 0:
            top.set_ylabel("D(theta)")
            bottom.set_ylabel("Lambda(theta)")
        if k == 0:
            top.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote " + out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
