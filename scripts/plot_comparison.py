#!/usr/bin/python3
"""Each model against the simulation on the sensor, as in R19 Fig. 9 and 11.

Usage: scripts/plot_comparison.py RESULT.h5 [OUT_DIR] [--channel K]

For every case of a `gonio run` result, every model of the case and every incidence, one PNG with
four polar maps of the upper hemisphere (radius theta_o in degrees, angle phi_o, one wedge per
Beckers cell): the simulated BRDF the model is held against (L1, or every order), the model (the
same colour scale, logarithmic), their ratio (1 is white; blue where the simulation is lower), and
the simulated multiple scattering L2+. The title gives the albedos, their relative difference and the
per-cell relative L1 distance. Needs Debian's python3-h5py and
python3-matplotlib (under /usr/bin/python3).
"""
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import colors  # noqa: E402


def polar_map(ax, group, values, norm, cmap, title):
    """Draws one value per Beckers cell as a wedge (theta as radius, phi as angle)."""
    t0, t1 = group["theta_min"][...], group["theta_max"][...]
    p0, p1 = np.radians(group["phi_min"][...]), np.radians(group["phi_max"][...])
    shown = np.where(values > 0, values, np.nan) if isinstance(norm, colors.LogNorm) else values
    rgba = plt.get_cmap(cmap)(norm(np.ma.masked_invalid(shown)))
    rgba[~np.isfinite(shown)] = (0.85, 0.85, 0.85, 1.0)  # no value: grey
    ax.bar(x=0.5 * (p0 + p1), height=t1 - t0, width=p1 - p0, bottom=t0, color=rgba,
           edgecolor="none", linewidth=0, align="center")
    ax.set_ylim(0, 90)
    ax.set_yticks([30, 60, 90])
    ax.set_yticklabels(["30°", "60°", "90°"], fontsize=7)
    ax.tick_params(axis="x", labelsize=7)
    ax.set_title(title, fontsize=9)
    mappable = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    plt.colorbar(mappable, ax=ax, shrink=0.7, pad=0.1)


def draw(group, name, m, sim_name, sim_label, t, p, theta, phi, channel, out_dir):
    """One figure: simulated BRDF, model, ratio and L2+ for one incidence; returns 1."""
    sim = group[sim_name][t, p, :, channel]
    model = group[f"model_{m}"][t, p, :, channel]
    ratio = group[f"{m}_ratio"][t, p, :, channel]
    l2plus = group["brdf_l2plus"][t, p, :, channel]
    top = max(sim.max(), model.max())
    log = colors.LogNorm(vmin=top * 1e-4, vmax=top)
    fig, axes = plt.subplots(1, 4, figsize=(17, 4.6), subplot_kw={"projection": "polar"})
    polar_map(axes[0], group, sim, log, "viridis", f"simulated {sim_label} (1/sr)")
    polar_map(axes[1], group, model, log, "viridis", f"model {m} (1/sr)")
    # The ratio only where the model expects >= 100 rays in the cell (a relative Monte Carlo error
    # <= 10 %); grey elsewhere.
    expected = group[f"model_{m}_energy"][t, p, :, channel] * group["rays"][t, p]
    ratio = np.where(expected >= 100, ratio, np.nan)
    polar_map(axes[2], group, ratio, colors.TwoSlopeNorm(1.0, 0.5, 1.5), "RdBu_r",
              f"simulated / model {m} (cells with >= 100 rays expected)")
    l2_top = max(l2plus.max(), 1e-12)
    polar_map(axes[3], group, l2plus, colors.LogNorm(vmin=l2_top * 1e-3, vmax=l2_top), "magma",
              "simulated L2+ (1/sr)")
    a = lambda key: group[key][t, p, channel]  # noqa: E731
    sim_albedo = a("linf_albedo") if sim_name == "brdf_linf" else a("l1_albedo")
    fig.suptitle(
        f"{name}  θi = {theta:.2f}° ({np.radians(theta):.3f} rad), φi = {phi:.1f}°"
        f"  channel {channel}:  {sim_label} sim {sim_albedo:.4f}, model {m} "
        f"{a(f'model_{m}_albedo'):.4f} ({a(f'{m}_relative_difference'):+.2%}), "
        f"distance {a(f'{m}_distance'):.3f}, L2+ {a('l2plus_albedo'):.4f}",
        fontsize=10)
    suffix = "" if m == "l1" else f"_{m}"
    out = os.path.join(out_dir, f"{name}_theta{theta:.2f}_phi{phi:.1f}{suffix}.png")
    fig.savefig(out, dpi=80, bbox_inches="tight")
    plt.close(fig)
    print(out)
    return 1


def string_list(value):
    """A list attribute: a string array (file format 2) or a comma-joined string (format 1)."""
    if isinstance(value, (bytes, str)):
        value = value.decode() if isinstance(value, bytes) else value
        return value.split(",") if value else []
    return [v.decode() if isinstance(v, bytes) else str(v) for v in value]


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    channel = 0
    if "--channel" in sys.argv:
        channel = int(sys.argv[sys.argv.index("--channel") + 1])
        args.remove(str(channel))
    if not args:
        sys.exit(__doc__)
    path = args[0]
    out_dir = args[1] if len(args) > 1 else os.path.splitext(path)[0] + "_comparison"
    os.makedirs(out_dir, exist_ok=True)
    written = 0
    with h5py.File(path, "r") as f:
        for name, group in f.items():
            models = string_list(group.attrs.get("models", ""))
            if "brdf_l1" not in group or not models:
                continue  # a model-only case, or a run without models
            nc = group["channel"].shape[0]
            if channel >= nc:
                sys.exit(f"{name}: channel {channel} out of range [0, {nc - 1}]")
            theta_i, phi_i = group["theta_i"][...], group["phi_i"][...]
            for m in models:
                vs = group.attrs[f"model_{m}_compared_with"]
                vs = vs.decode() if isinstance(vs, bytes) else str(vs)
                sim_name, sim_label = ("brdf_linf", "every order") if vs == "linf" else ("brdf_l1", "L1")
                for t, theta in enumerate(theta_i):
                    for p, phi in enumerate(phi_i):
                        written += draw(group, name, m, sim_name, sim_label, t, p, theta, phi,
                                        channel, out_dir)
    if written == 0:
        sys.exit(f"{path}: no case with both a simulation and a model (run `gonio run` with a model)")


if __name__ == "__main__":
    main()
