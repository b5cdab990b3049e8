#!/usr/bin/python3
"""gonio from Python, a worked example (docs/python.md): sweep the roughness of a GGX mirror,
trace each surface, and hold the simulated single scattering against Model L1.

    /usr/bin/python3 docs/python/sweep_alpha.py [--quick] [--out docs/python/sweep_alpha.png]

--quick: three roughnesses and few rays (CTest runs it so); the figure in docs/ is the full run.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import gonio  # noqa: E402

CONFIG = """
seed = 7
[beam]
theta_i = [0, 40, 60, 75]
[sensor]
cells = 3240
[surface]
size = 256
[ndf]
type = "ggx"
alpha = 0.3
[[case]]
name = "ggx"
material = { type = "mirror" }
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default="docs/python/sweep_alpha.png")
    a = ap.parse_args()
    alphas = [0.1, 0.5, 1.0] if a.quick else [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5]
    rays = 2**14 if a.quick else 2**20

    rows = []
    for alpha in alphas:
        cfg = gonio.Config.from_toml(CONFIG, overrides={"ndf.alpha": alpha, "trace.rays": rays})
        ds = gonio.run(cfg, cache=False).to_xarray("ggx")
        sim = ds["l1_albedo"].isel(phi_i=0, channel=0)
        err = ds["l1_albedo_stderr"].isel(phi_i=0, channel=0)
        model = ds["model_l1_albedo"].isel(phi_i=0, channel=0)
        multiple = ds["l2plus_albedo"].isel(phi_i=0, channel=0)
        rows.append((alpha, sim.values, err.values, model.values, multiple.values))
        print(f"alpha {alpha:4}: " + ", ".join(
            f"{t:g} deg L1 {s:.4f} +- {e:.4f} (model {m:.4f})"
            for t, s, e, m in zip(ds.theta_i.values, sim.values, err.values, model.values)))
    theta = ds.theta_i.values

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    x = np.array([r[0] for r in rows])
    for k, t in enumerate(theta):
        sim = np.array([r[1][k] for r in rows])
        err = np.array([r[2][k] for r in rows])
        model = np.array([r[3][k] for r in rows])
        line = ax[0].errorbar(x, sim, yerr=2 * err, fmt="o", ms=4, label=f"θi {t:g}°: simulated")
        ax[0].plot(x, model, "-", color=line[0].get_color(), lw=1)
        ax[1].errorbar(x, sim / model - 1, yerr=2 * err / model, fmt="o-", ms=4,
                       color=line[0].get_color(), label=f"θi {t:g}°")
        ax[0].plot(x, [r[4][k] for r in rows], ":", color=line[0].get_color(), lw=1)
    ax[0].set(xscale="log", xlabel="GGX α", ylabel="albedo",
              title="L1 simulated (dots, ±2σ) and Model L1 (lines); L2+ dotted")
    ax[1].axhline(0, color="k", lw=0.5)
    ax[1].set(xscale="log", xlabel="GGX α", ylabel="simulated / Model L1 − 1",
              title="single scattering: the explicit surface against Smith")
    ax[0].legend(fontsize=7)
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
