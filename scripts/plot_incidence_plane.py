#!/usr/bin/python3
"""The BRDF in the plane of incidence, as in R19 Fig. 11: simulated L1, L2+ and L-infinity with
their error bars and every model of the case, against the signed outgoing angle.

Usage: scripts/plot_incidence_plane.py RESULT.h5 [OUT_DIR] [--case NAME] [--phi INDEX]
                                       [--channel K] [--linear]

theta_o runs from -90 to 90 degrees through the plane of incidence: positive towards phi_i + 180
(the specular side), negative towards phi_i (the side of the light). Each point is one Beckers cell
crossed by that plane (its phi range holds the azimuth), at its centre's polar angle; simulated
curves carry +-1 standard error bars. One PNG per case, one panel per theta_i (at the azimuth
index --phi, default 0), logarithmic unless --linear. Needs Debian's python3-h5py and
python3-matplotlib (under /usr/bin/python3).
"""
import argparse
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plane_cells(group, phi_deg):
    """Indices and signed polar angles of the cells the plane of incidence at phi_deg crosses."""
    p0, p1 = group["phi_min"][...], group["phi_max"][...]
    theta = group["theta_center"][...]
    index, signed = [], []
    for azimuth, sign in ((phi_deg + 180.0) % 360.0, 1.0), (phi_deg % 360.0, -1.0):
        for c in np.nonzero((p0 <= azimuth) & (azimuth < p1))[0]:
            if c not in index:  # the polar cell spans every azimuth: once, at 0
                index.append(int(c))
                signed.append(float(sign * theta[c]))
    order = np.argsort(signed)
    return np.asarray(index)[order], np.asarray(signed)[order]


def plot_case(group, name, out_dir, phi_index, channel, linear):
    theta_i = group["theta_i"][...]
    phi_i = group["phi_i"][...]
    if "brdf_l1" not in group:
        raise SystemExit(f"{name}: not a gonio run result (no simulated orders)")
    models = [m.decode() if isinstance(m, bytes) else str(m)
              for m in group.attrs.get("models", [])]
    n = len(theta_i)
    cols = min(n, 4)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 3.2 * rows), squeeze=False)
    index, signed = plane_cells(group, float(phi_i[phi_index]))
    for k in range(n):
        ax = axes[k // cols][k % cols]
        for key, label, colour in (("brdf_l1", "simulated L1", "C0"),
                                   ("brdf_l2plus", "simulated L2+", "C1"),
                                   ("brdf_linf", "simulated L∞", "k")):
            v = group[key][k, phi_index, :, channel][index]
            e = group[key + "_stderr"][k, phi_index, :, channel][index]
            ax.errorbar(signed, v, yerr=e, fmt="-", color=colour, lw=1, elinewidth=0.6,
                        capsize=0, label=label)
        for j, m in enumerate(models):
            v = group["model_" + m][k, phi_index, :, channel][index]
            ax.plot(signed, v, "--", color=f"C{j + 2}", lw=1, label="Model " + m.upper()
                    if m == "l1" else "model " + m)
        ax.set_xlim(-90, 90)
        ax.set_xticks([-90, -60, -30, 0, 30, 60, 90])
        if not linear:
            ax.set_yscale("log")
        ax.set_title(f"θi = {theta_i[k]:g}°, φi = {phi_i[phi_index]:g}°", fontsize=9)
        ax.set_xlabel("θo (° , + towards φi + 180°)", fontsize=8)
        ax.set_ylabel("BRDF (1/sr)", fontsize=8)
        ax.tick_params(labelsize=7)
        if k == 0:
            ax.legend(fontsize=7)
    for k in range(n, rows * cols):
        axes[k // cols][k % cols].axis("off")
    fig.suptitle(f"{name}: {group.attrs.get('ndf', '')}", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out_dir, f"{name}_incidence_plane.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("out_dir", nargs="?", default=".")
    ap.add_argument("--case")
    ap.add_argument("--phi", type=int, default=0, help="azimuth index of the sweep")
    ap.add_argument("--channel", type=int, default=0)
    ap.add_argument("--linear", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    with h5py.File(args.result, "r") as f:
        names = [n for n in f if isinstance(f[n], h5py.Group)]
        if args.case:
            if args.case not in names:
                raise SystemExit(f"{args.result}: no case {args.case} (it holds {', '.join(names)})")
            names = [args.case]
        for n in names:
            print(plot_case(f[n], n, args.out_dir, args.phi, args.channel, args.linear))


if __name__ == "__main__":
    sys.exit(main())
