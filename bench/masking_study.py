#!/usr/bin/python3
"""Why the explicit surface is not Smith: the decomposition of simulated L1 - Model L1, measured.

For R19's ten NDFs (configs/r19_fig11_ten_cases.toml) and Beckmann / GGX alpha 0.1-1.5, on mirrors,
at theta_i 0, 30, 60 and 85 degrees, one gonio run with the models of the chain
    l1 -> smith_measured_ndf -> measured_g1 -> measured
splits the gap into (a) the surface's NDF fidelity (Smith with D_s instead of D), (b) the facet
dependence of masking (the measured G1(i, m) G1(o, m) instead of Smith's), (c) the correlation of
masking with shadowing (the measured joint G2 instead of the product), and (d) what is left
(simulated L1 - measured: zero within its error when the decomposition closes). Albedo shares, each
with its standard error (the two sides' errors combined; the models share their facet points, so
this is conservative).

Writes OUT/masking_study.csv, OUT/masking_study.md (the docs' table) and OUT/masking_study.png.
Usage: masking_study.py [--gonio build/gonio] [--out DIR] [--quick]
  --quick: three cases, 64^2 surfaces, 2^16 rays, theta_i 0 and 60 (the CTest smoke run)
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tomllib

import h5py
import numpy as np

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CHAIN = ["l1", "smith_measured_ndf", "measured_g1", "measured"]


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + " }"
    return repr(v)


def cases(quick):
    out = []
    for a in ([0.5] if quick else [0.1, 0.3, 0.5, 0.75, 1.0, 1.5]):
        out.append((f"beckmann_{a}", {"type": "beckmann", "alpha": a}))
        out.append((f"ggx_{a}", {"type": "ggx", "alpha": a}))
    with open(os.path.join(HERE, "configs/r19_fig11_ten_cases.toml"), "rb") as f:
        r19 = tomllib.load(f)
    for c in r19["case"][: 1 if quick else None]:
        out.append(("r19_" + c["name"], c["ndf"]))
    return out


def config(quick):
    theta = [0, 60] if quick else [0, 30, 60, 85]
    lines = ["seed = 1", '[material]\ntype = "mirror"',
             f"[beam]\ntheta_i = {theta}\nphi_i = 0", "[sensor]\ncells = 1152",
             f"[surface]\nsize = {64 if quick else 256}\niterations = {60 if quick else 500}",
             f"[trace]\nrays = {65536 if quick else 1048576}",
             f"[model]\nmodels = {toml_value(CHAIN)}"]
    for name, ndf in cases(quick):
        lines.append(f'[[case]]\nname = "{name}"\nndf = {toml_value(ndf)}')
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--gonio", default=os.path.join(HERE, "build/gonio"))
    p.add_argument("--out", default=os.path.join(HERE, "build/masking_study"))
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    cfg = os.path.join(a.out, "masking_study.toml")
    with open(cfg, "w") as f:
        f.write(config(a.quick))
    result = os.path.join(a.out, "masking_study.h5")
    cmd = [a.gonio, "run", cfg, "-o", result, "--overwrite", "--quiet"]
    print("masking_study: " + " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)

    rows = []
    with h5py.File(result) as f:
        for name in f.attrs["cases"]:
            g = f[name]
            for t, theta in enumerate(g["theta_i"][:]):
                sim = g["l1_albedo"][t, 0, 0]
                sim_e = g["l1_albedo_stderr"][t, 0, 0]
                alb = {m: g[f"model_{m}_albedo"][t, 0, 0] for m in CHAIN}
                err = {m: (g[f"model_{m}_albedo_stderr"][t, 0, 0]
                           if f"model_{m}_albedo_stderr" in g else 0.0) for m in CHAIN}
                steps = [("ndf", "l1", "smith_measured_ndf"), ("g1_of_m", "smith_measured_ndf", "measured_g1"),
                         ("correlation", "measured_g1", "measured")]
                row = {"case": name, "theta_i": float(theta), "sim_l1": sim, "sim_l1_stderr": sim_e,
                       "model_l1": alb["l1"], "gap": sim - alb["l1"],
                       "gap_sigmas": (sim - alb["l1"]) / sim_e if sim_e > 0 else math.nan}
                for key, lo, hi in steps:
                    row[key] = alb[hi] - alb[lo]
                    row[key + "_stderr"] = math.hypot(err[hi], err[lo])
                row["residual"] = sim - alb["measured"]
                row["residual_stderr"] = math.hypot(sim_e, err["measured"])
                row["residual_sigmas"] = row["residual"] / row["residual_stderr"]
                # Per-cell closure of `measured` over bright cells (at least 1 % of the peak).
                f_sim = g["brdf_l1"][t, 0, :, 0]
                e_sim = g["brdf_l1_stderr"][t, 0, :, 0]
                f_mod = g["model_measured"][t, 0, :, 0]
                e_mod = g["model_measured_stderr"][t, 0, :, 0]
                bright = f_sim > 0.01 * f_sim.max()
                z = (f_sim - f_mod)[bright] / np.sqrt(e_sim[bright] ** 2 + e_mod[bright] ** 2)
                row["measured_cell_rms_z"] = float(np.sqrt(np.mean(z ** 2)))
                rows.append(row)

    with open(os.path.join(a.out, "masking_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    def pm(v, e):
        return f"{v:+.4f}±{e:.4f}"

    md = ["| case | θi | simulated L1 | Model L1 | gap (σ) | NDF fidelity | G1 depends on m | "
          "masking–shadowing correlation | left (σ) | rms z per cell |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        md.append(f"| {r['case']} | {r['theta_i']:g}° | {r['sim_l1']:.4f}±{r['sim_l1_stderr']:.4f} | "
                  f"{r['model_l1']:.4f} | {r['gap']:+.4f} ({r['gap_sigmas']:+.0f}) | "
                  f"{pm(r['ndf'], r['ndf_stderr'])} | {pm(r['g1_of_m'], r['g1_of_m_stderr'])} | "
                  f"{pm(r['correlation'], r['correlation_stderr'])} | "
                  f"{r['residual']:+.4f} ({r['residual_sigmas']:+.1f}) | {r['measured_cell_rms_z']:.2f} |")
    with open(os.path.join(a.out, "masking_study.md"), "w") as f:
        f.write("\n".join(md) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    thetas = sorted({r["theta_i"] for r in rows})
    fig, axes = plt.subplots(1, len(thetas), figsize=(4.2 * len(thetas), 0.32 * len(rows) / len(thetas) + 1.8),
                             sharey=True)
    axes = np.atleast_1d(axes)
    for ax, theta in zip(axes, thetas):
        sel = [r for r in rows if r["theta_i"] == theta]
        y = np.arange(len(sel))
        left = np.zeros(len(sel))
        for key, colour, label in [("ndf", "#8da0cb", "NDF fidelity"), ("g1_of_m", "#fc8d62", "G1 depends on m"),
                                   ("correlation", "#66c2a5", "masking–shadowing correlation")]:
            v = np.array([r[key] for r in sel])
            ax.barh(y, v, left=left, color=colour, label=label)  # the steps, end to end
            left = left + v
        ax.errorbar([r["gap"] for r in sel], y, xerr=[2 * r["sim_l1_stderr"] for r in sel], fmt="k|",
                    label="simulated L1 − Model L1")
        ax.axvline(0, color="#888", lw=0.6)
        ax.set_title(f"θi = {theta:g}°")
        ax.set_yticks(y)
        ax.set_yticklabels([r["case"] for r in sel], fontsize=7)
        ax.set_xlabel("albedo difference")
    axes[0].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "masking_study.png"), dpi=110)
    worst = max(abs(r["residual_sigmas"]) for r in rows)
    rms = [r["measured_cell_rms_z"] for r in rows]
    print(f"masking_study: {len(rows)} rows; closure |residual| at most {worst:.1f} sigma; "
          f"rms z per cell of `measured` {min(rms):.2f}-{max(rms):.2f}; wrote {a.out}/masking_study.*")


if __name__ == "__main__":
    sys.exit(main())
