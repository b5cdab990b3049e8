#!/usr/bin/python3
"""Which multiple-scattering approximation is closest to explicit multiple scattering, where, by how much.

For R19's ten NDFs (configs/r19_fig11_ten_cases.toml) and Beckmann / GGX alpha 0.1-1.5, on mirrors,
gold (Johnson & Christy, 550 nm) and glass (eta 1.5), at theta_i 0, 45, 70 and 85 degrees, one gonio run
traces the explicit surface (every order, per order) beside the models of every order:
    heitz16      the Smith random walk (Heitz et al. 2016), any facet material
    kulla_conty  Model L1 + Kulla & Conty's compensation lobe (opaque specular facets)
    turquin      Model L1 x (1 + F0 (1 - E) / E) (opaque specular facets)
    vcavity      V-cavity multiple scattering (M18 section 3.3; opaque facets)
and Model L1 (single scattering only). Each is held against simulated L-infinity (albedo and per
cell) and its orders 2 and up against simulated L2+; glass is held on its reflected side. R19's
sinc blend has no compensated models (its E(mu) table costs minutes per material).

Writes OUT/ms_study.csv, OUT/ms_study.md (the docs' tables) and OUT/ms_study.png.
Usage: ms_study.py [--gonio build/gonio] [--out DIR] [--quick]
  --quick: three cases, 64^2 surfaces, 2^15 rays, theta_i 0 and 70 (the CTest smoke run)
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
OPAQUE = ["l1", "heitz16", "kulla_conty", "turquin", "vcavity"]
GLASS = ["l1", "heitz16"]
MS = ["heitz16", "kulla_conty", "turquin", "vcavity"]
# Cases whose E(mu) table (4 azimuths x 91 nodes of a tabulated anisotropic Model L1) costs minutes
# per material: the random walk and the V-cavities only.
NO_TABLES = {"r19_9_blend_sinc"}
MATERIALS = {
    "mirror": '{ type = "mirror" }',
    "gold": '{ type = "conductor", ior = "Au" }',
    "glass": '{ type = "dielectric", eta = 1.5 }',
}


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


def ndfs(quick):
    out = []
    for a in ([0.5] if quick else [0.1, 0.3, 0.5, 1.0, 1.5]):
        out.append((f"beckmann_{a}", {"type": "beckmann", "alpha": a}))
        out.append((f"ggx_{a}", {"type": "ggx", "alpha": a}))
    with open(os.path.join(HERE, "configs/r19_fig11_ten_cases.toml"), "rb") as f:
        r19 = tomllib.load(f)
    for c in r19["case"][: 0 if quick else None]:
        out.append(("r19_" + c["name"], c["ndf"]))
    return out


def config(quick):
    theta = [0, 70] if quick else [0, 45, 70, 85]
    rays = 32768 if quick else 262144
    lines = ["seed = 1", f"[beam]\ntheta_i = {theta}\nphi_i = 0", "[sensor]\ncells = 1152",
             f"[surface]\nsize = {64 if quick else 256}\niterations = {60 if quick else 500}",
             f"[trace]\nrays = {rays}\norders = 4"]
    for name, ndf in ndfs(quick):
        for material in (["mirror", "gold"] if quick else MATERIALS):
            models = GLASS if material == "glass" else OPAQUE
            if name in NO_TABLES:
                models = [m for m in models if m not in ("kulla_conty", "turquin")]
            lines.append(f'[[case]]\nname = "{name}_{material}"\nndf = {toml_value(ndf)}\n'
                         f"material = {MATERIALS[material]}\nmodel = {{ models = {toml_value(models)} }}" +
                         ("\nspectrum = { wavelengths = [550] }" if material == "gold" else ""))
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--gonio", default=os.path.join(HERE, "build/gonio"))
    p.add_argument("--out", default=os.path.join(HERE, "build/ms_study"))
    p.add_argument("--quick", action="store_true")
    p.add_argument("--tables-only", action="store_true", help="remake the tables from OUT/ms_study.h5")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    cfg = os.path.join(a.out, "ms_study.toml")
    with open(cfg, "w") as f:
        f.write(config(a.quick))
    result = os.path.join(a.out, "ms_study.h5")
    cmd = [a.gonio, "run", cfg, "-o", result, "--overwrite", "--quiet"]
    if not a.tables_only:
        print("ms_study: " + " ".join(cmd), flush=True)
        subprocess.run(cmd, check=True)

    rows = []
    with h5py.File(result) as f:
        for name in f.attrs["cases"]:
            g = f[name]
            material = name.rsplit("_", 1)[1]
            for t, theta in enumerate(g["theta_i"][:]):
                row = {"case": name.rsplit("_", 1)[0], "material": material, "theta_i": float(theta),
                       "sim_linf": g["linf_albedo"][t, 0, 0], "sim_linf_stderr": g["linf_albedo_stderr"][t, 0, 0],
                       "sim_l2plus": g["l2plus_albedo"][t, 0, 0],
                       "sim_l2plus_stderr": g["l2plus_albedo_stderr"][t, 0, 0],
                       "model_l1": g["model_l1_albedo"][t, 0, 0]}
                for m in MS:
                    if f"model_{m}" not in g:
                        continue
                    row[f"{m}_linf"] = g[f"model_{m}_albedo"][t, 0, 0]
                    row[f"{m}_linf_rel"] = g[f"{m}_relative_difference"][t, 0, 0]
                    row[f"{m}_linf_sigmas"] = g[f"{m}_sigmas"][t, 0, 0]
                    row[f"{m}_linf_distance"] = g[f"{m}_distance"][t, 0, 0]
                    row[f"{m}_l2plus"] = g[f"model_{m}_l2plus_albedo"][t, 0, 0]
                    row[f"{m}_l2plus_rel"] = g[f"{m}_l2plus_relative_difference"][t, 0, 0]
                    row[f"{m}_l2plus_sigmas"] = g[f"{m}_l2plus_sigmas"][t, 0, 0]
                    row[f"{m}_l2plus_distance"] = g[f"{m}_l2plus_distance"][t, 0, 0]
                rows.append(row)

    keys = sorted({k for r in rows for k in r}, key=lambda k: (k not in rows[0], list(rows[0]).index(k)
                                                               if k in rows[0] else 0, k))
    with open(os.path.join(a.out, "ms_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)

    # Summary: per material and model, over the cases and incidences, the median and the largest
    # |relative difference| of L-infinity (below 80 degrees and at 85), the median per-cell distance
    # of L2+ (below 80 and at 85), and how often the model is the closest of those evaluated by that
    # distance (on lossless facets every energy-conserving Smith model has the same L2+ albedo,
    # 1 - E1: only the cells tell them apart).
    def closest(r):
        have = [m for m in MS if f"{m}_l2plus_distance" in r]
        return min(have, key=lambda m: r[f"{m}_l2plus_distance"]) if have else None

    summary = ["| facets | model | median \\|L∞ rel. diff.\\| θi < 80° / 85° | max \\|L∞ rel. diff.\\| | "
               "median L2+ cell distance θi < 80° / 85° | closest L2+ per cell |", "|---|---|---|---|---|---|"]
    for material in MATERIALS:
        sel = [r for r in rows if r["material"] == material]
        if not sel:
            continue
        wins = [closest(r) for r in sel]
        for m in MS:
            have = [r for r in sel if f"{m}_linf_rel" in r]
            if not have:
                continue
            low = [r for r in have if r["theta_i"] < 80]
            high = [r for r in have if r["theta_i"] >= 80]
            med = lambda rs, k: np.median([abs(r[k]) for r in rs]) if rs else math.nan
            summary.append(f"| {material} | {m} | {med(low, f'{m}_linf_rel'):.4f} / {med(high, f'{m}_linf_rel'):.4f} | "
                           f"{max(abs(r[f'{m}_linf_rel']) for r in have):.3f} | "
                           f"{med(low, f'{m}_l2plus_distance'):.2f} / {med(high, f'{m}_l2plus_distance'):.2f} | "
                           f"{wins.count(m)}/{len(sel)} |")
    detail = ["| case | facets | θi | simulated L∞ | simulated L2+ | Model L1 | " +
              " | ".join(f"{m} L2+ (σ)" for m in MS) + " |", "|---|---|---|---|---|---|" + "---|" * len(MS)]
    for r in rows:
        cells = []
        for m in MS:
            cells.append(f"{r[f'{m}_l2plus']:.4f} ({r[f'{m}_l2plus_sigmas']:+.0f})" if f"{m}_l2plus" in r else "–")
        detail.append(f"| {r['case']} | {r['material']} | {r['theta_i']:g}° | {r['sim_linf']:.4f} | "
                      f"{r['sim_l2plus']:.4f}±{r['sim_l2plus_stderr']:.4f} | {r['model_l1']:.4f} | " +
                      " | ".join(cells) + " |")
    with open(os.path.join(a.out, "ms_study.md"), "w") as f:
        f.write("\n".join(summary) + "\n\n" + "\n".join(detail) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    mats = [m for m in MATERIALS if any(r["material"] == m for r in rows)]
    fig, axes = plt.subplots(1, len(mats), figsize=(4.6 * len(mats), 4.4))
    axes = np.atleast_1d(axes)
    marks = {"heitz16": "o", "kulla_conty": "s", "turquin": "^", "vcavity": "x"}
    for ax, material in zip(axes, mats):
        sel = [r for r in rows if r["material"] == material]
        top = max(r["sim_l2plus"] for r in sel) * 1.1 or 1
        for m in MS:
            have = [r for r in sel if f"{m}_l2plus" in r]
            if have:
                ax.scatter([r["sim_l2plus"] for r in have], [r[f"{m}_l2plus"] for r in have], s=14,
                           marker=marks[m], label=m)
        ax.plot([0, top], [0, top], color="#888", lw=0.7)
        ax.set_xlim(0, top)
        ax.set_ylim(0, top)
        ax.set_title(f"{material}: albedo of orders 2+")
        ax.set_xlabel("explicit surface (simulated L2+)")
        ax.set_ylabel("model L2+")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "ms_study.png"), dpi=110)
    print(f"ms_study: {len(rows)} rows; wrote {a.out}/ms_study.*")


if __name__ == "__main__":
    sys.exit(main())
