#!/usr/bin/python3
"""How well the tabulated BSDF interpolates between swept incidences (issue 16).

For two cases -- the shipped table (Beckmann 0.5 gold, configs/table_beckmann_0.5_gold.toml) and a
glossier one (GGX 0.2 mirror) -- sweeps of theta_i in steps of 2.5, 5 and 10 degrees are traced,
and held-out incidences (midpoints of the 2.5-degree grid: 13.75, 36.25, 61.25, 78.75 degrees)
are traced directly with 4 times the rays, on the same surface. bench/table_interpolation compares
each table at the held-out incidences with the traced cells: the median and 90th percentile of the
per-cell relative error over the bright cells (L-infinity BRDF >= 10 % of the peak), beside the
traced cells' own relative noise, and the albedo error (worst channel) beside its noise.

Writes <out>/table_interpolation.csv and .md and prints the table.
Usage: bench/table_study.py [--gonio build/gonio] [--tool build/table_interpolation]
                            [--out docs/study] [--quick]
--quick: toy sizes (a smoke test; the numbers mean nothing).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
GLOSSY = """seed = 1
[ndf]
type = "ggx"
alpha = 0.2
[material]
type = "mirror"
[beam]
theta_i = 0
phi_i = 0
[sensor]
cells = 3240
[surface]
size = 512
[trace]
rays = 1048576
[[case]]
name = "mirror_ggx_0.2"
"""
FULL = dict(steps=[2.5, 5, 10], held=[13.75, 36.25, 61.25, 78.75], rays=2**20, held_rays=2**22,
            size=512, cells=3240, last=87.5)
QUICK = dict(steps=[5, 10], held=[36.25], rays=2**13, held_rays=2**14, size=32, cells=145,
             last=80)


def sweep(step, last):
    out, t = [], 0.0
    while t <= last + 1e-9:
        out.append(t)
        t += step
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gonio", default="build/gonio")
    ap.add_argument("--tool", default="build/table_interpolation")
    ap.add_argument("--out", default="docs/study")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    p = QUICK if args.quick else FULL
    os.makedirs(args.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="gonio_table_study_")
    glossy = os.path.join(work, "glossy.toml")
    with open(glossy, "w") as f:
        f.write(GLOSSY)
    cases = {"gold_beckmann_0.5": os.path.join(HERE, "..", "configs", "table_beckmann_0.5_gold.toml"),
             "mirror_ggx_0.2": glossy}
    rows = []
    for name, config in cases.items():
        def run(theta, rays, tag):
            out = os.path.join(work, f"{name}_{tag}.h5")
            theta_list = "[" + ",".join(f"{t:g}" for t in theta) + "]"
            cmd = [args.gonio, "run", config, "-o", out, "--overwrite", "--quiet",
                   "--cache-dir", os.path.join(work, "cache"),
                   "--set", f"beam.theta_i={theta_list}", "--set", f"trace.rays={rays}",
                   "--set", f"surface.size={p['size']}", "--set", f"sensor.cells={p['cells']}"]
            start = time.time()
            subprocess.run(cmd, check=True)
            return out, time.time() - start
        held, held_s = run(p["held"], p["held_rays"], "held")
        for step in p["steps"]:
            table, seconds = run(sweep(step, p["last"]), p["rays"], f"step{step:g}")
            got = subprocess.run([args.tool, table, held], check=True, capture_output=True,
                                 text=True).stdout
            for line in got.splitlines():
                r = json.loads(line)
                rows.append(dict(case=name, step_deg=step, theta_i=r["theta_i"],
                                 bright_cells=r["cells"],
                                 median_cell_error=r["median_cell_error"],
                                 p90_cell_error=r["p90_cell_error"],
                                 median_cell_noise=r["median_cell_noise"],
                                 albedo_error=r["albedo_error"], albedo_noise=r["albedo_noise"],
                                 sweep_seconds=seconds))
    with open(os.path.join(args.out, "table_interpolation.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = ["| case | sweep step | held-out θi | median cell error | 90th pct | traced cells' noise "
             "(median) | albedo error | albedo noise |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['step_deg']:g}° | {r['theta_i']:g}° | "
                     f"{100 * r['median_cell_error']:.1f} % | {100 * r['p90_cell_error']:.1f} % | "
                     f"{100 * r['median_cell_noise']:.1f} % | {100 * r['albedo_error']:+.2f} % | "
                     f"{100 * r['albedo_noise']:.2f} % |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "table_interpolation.md"), "w") as f:
        f.write("# Interpolation error of the tabulated BSDF (bench/table_study.py)\n\n")
        f.write(f"Sweeps at {p['rays']} rays per incidence; held-out incidences at "
                f"{p['held_rays']} rays on the same {p['size']}² surface; {p['cells']} cells.\n\n")
        f.write(text)
    print(text)


if __name__ == "__main__":
    sys.exit(main())
