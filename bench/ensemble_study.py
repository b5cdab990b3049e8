#!/usr/bin/python3
"""Surface ensembles against one large surface, at equal cost (issue 15).

1. How far apart single surfaces are, in their own (rays-only) error bars: case A (Beckmann 0.75,
   mirror, theta_i 60) on a 512^2 surface, 4 M rays; two ray seeds on one surface, two surface
   seeds; then two independent ensembles of 8 x 512^2 with the same rays. The figure is the rms
   over the bright cells (L-infinity BRDF >= 10 % of the peak) of the difference over its
   reported standard error.
2. At equal cost -- the same total surface samples (2^24: 256 x 256^2 ... 1 x 4096^2) and the same
   total rays -- many small surfaces against few large ones, for case A and case B (GGX 0.3, gold,
   theta_i 80), against an independent reference ensemble (other seeds, more surfaces than any
   point). Per point: the per-cell relative L1 distance of the L-infinity BRDF to the reference,
   the error of the L1 and L-infinity albedos, the reported errors beside the measured ones, the
   wall time and the peak memory.

Writes <out>/ensembles.csv and <out>/ensembles.md and prints them.
Usage: bench/ensemble_study.py [--gonio build/gonio] [--out docs/study] [--quick]
--quick: toy sizes (a smoke test; the numbers mean nothing).
"""
import argparse
import csv
import os
import platform
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

CASES = {
    "A_beckmann0.75_mirror_60": ('{ type = "beckmann", alpha = 0.75 }', '{ type = "mirror" }', 60),
    "B_ggx0.3_gold_80": ('{ type = "ggx", alpha = 0.3 }', '{ type = "conductor", ior = "Au" }',
                         80),
}
FULL = dict(samples=2**24, sizes=[256, 512, 1024, 2048, 4096], rays=2**24, ref_size=256,
            ref_realisations=512, ref_rays=2**26, iterations=100, cells=3240,
            spread_size=512, spread_rays=4 * 2**20, spread_realisations=8)
QUICK = dict(samples=2**12, sizes=[16, 32, 64], rays=2**14, ref_size=16, ref_realisations=32,
             ref_rays=2**16, iterations=10, cells=145, spread_size=32, spread_rays=2**14,
             spread_realisations=4)


class Runner:
    def __init__(self, gonio, work):
        self.gonio, self.work, self.count = gonio, work, 0
        self.cache = os.path.join(work, "cache")

    def run(self, case, size, realisations, rays, surface_seed, seed, p, keep_cache=False):
        """One gonio run; returns (result dict, wall seconds, peak MiB)."""
        ndf, material, theta = CASES[case]
        self.count += 1
        cfg = os.path.join(self.work, f"e{self.count}.toml")
        out = os.path.join(self.work, f"e{self.count}.h5")
        with open(cfg, "w") as f:
            f.write(f"""seed = {seed}
name = "c"
ndf = {ndf}
material = {material}
[beam]
theta_i = {theta}
[sensor]
cells = {p['cells']}
[model]
evaluate = false
[surface]
size = {size}
iterations = {p['iterations']}
seed = {surface_seed}
realisations = {realisations}
[trace]
rays = {rays}
""")
        cache = self.cache if keep_cache else os.path.join(self.work, f"cache{self.count}")
        args = [self.gonio, "run", cfg, "-o", out, "--overwrite", "-q", "--cache-dir", cache]
        start = time.perf_counter()
        proc = subprocess.Popen(args, stderr=subprocess.PIPE)
        _, status, usage = os.wait4(proc.pid, 0)
        seconds = time.perf_counter() - start
        err = proc.stderr.read().decode()
        proc.stderr.close()
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"ensemble_study: gonio failed on {case} {size} x {realisations}: {err}")
        if not keep_cache:
            subprocess.run(["rm", "-rf", cache], check=True)
        with h5py.File(out, "r") as f:
            g = f["c"]
            r = dict(omega=g["projected_solid_angle"][()], cells=g["brdf_linf"][0, 0, :, :],
                     cells_err=g["brdf_linf_stderr"][0, 0, :, :],
                     l1=g["l1_albedo"][0, 0, :], l1_err=g["l1_albedo_stderr"][0, 0, :],
                     linf=g["linf_albedo"][0, 0, :], linf_err=g["linf_albedo_stderr"][0, 0, :])
        os.remove(out)
        return r, seconds, usage.ru_maxrss / 1024.0


def bright(ref):
    peak = ref["cells"].max(axis=0)
    return ref["cells"] >= 0.1 * peak


def sigmas(a, b, mask):
    """rms over the bright cells of the difference in standard errors of the difference."""
    e = np.sqrt(a["cells_err"] ** 2 + b["cells_err"] ** 2)
    keep = mask & (e > 0)
    return float(np.sqrt(np.mean(((a["cells"] - b["cells"])[keep] / e[keep]) ** 2)))


def distance(x, ref):
    """sum |f - f_ref| Omega_perp / sum f_ref Omega_perp, worst channel."""
    w = ref["omega"][:, None]
    return float(np.max(np.abs(x["cells"] - ref["cells"]).__mul__(w).sum(axis=0) /
                        (ref["cells"] * w).sum(axis=0)))


def expected_distance(x, ref):
    """The distance the reported errors predict: E|N(0, s^2)| = s sqrt(2 / pi) per cell, with
    the reference's own error added in quadrature."""
    w = ref["omega"][:, None]
    s = np.sqrt(x["cells_err"] ** 2 + ref["cells_err"] ** 2) * np.sqrt(2 / np.pi)
    return float(np.max((s * w).sum(axis=0) / (ref["cells"] * w).sum(axis=0)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--gonio", default="build/gonio")
    ap.add_argument("--out", default="docs/study")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    p = QUICK if a.quick else FULL
    os.makedirs(a.out, exist_ok=True)
    machine = f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores"
    rows, lines = [], []
    with tempfile.TemporaryDirectory() as work:
        g = Runner(os.path.abspath(a.gonio), work)
        # 1. Single surfaces in their own error bars, and ensembles in theirs.
        case = "A_beckmann0.75_mirror_60"
        n, rays, R = p["spread_size"], p["spread_rays"], p["spread_realisations"]
        one, _, _ = g.run(case, n, 1, rays, 11, 1, p, keep_cache=True)
        rays_only, _, _ = g.run(case, n, 1, rays, 11, 2, p, keep_cache=True)
        other, _, _ = g.run(case, n, 1, rays, 12, 3, p)
        e1, _, _ = g.run(case, n, R, rays, 21, 4, p)
        e2, _, _ = g.run(case, n, R, rays, 22, 5, p)
        mask = bright(one)
        spread = dict(same_surface=sigmas(one, rays_only, mask),
                      other_surface=sigmas(one, other, mask), ensembles=sigmas(e1, e2, mask))
        lines.append(f"Case A, {n}^2 surfaces, {rays} rays, bright cells of the L-infinity BRDF: "
                     f"two ray seeds on one surface differ by {spread['same_surface']:.2f} "
                     f"reported standard errors (rms), two surfaces by "
                     f"{spread['other_surface']:.2f}, two ensembles of {R} x {n}^2 by "
                     f"{spread['ensembles']:.2f}.")
        # 2. Equal cost: the same surface samples and rays, split over R surfaces.
        for case in CASES:
            ref, ref_s, ref_mib = g.run(case, p["ref_size"], p["ref_realisations"], p["ref_rays"],
                                        900, 9, p)
            for size in p["sizes"]:
                R = max(1, p["samples"] // (size * size))
                x, seconds, mib = g.run(case, size, R, p["rays"], 100 + size, 7, p)
                rel = lambda v, r: float(np.max(np.abs(v - r) / r))
                rows.append(dict(
                    case=case, surfaces=R, size=size, rays=p["rays"],
                    cell_distance=distance(x, ref), cell_expected=expected_distance(x, ref),
                    l1_error=rel(x["l1"], ref["l1"]),
                    l1_reported=float(np.max(np.hypot(x["l1_err"], ref["l1_err"]) / ref["l1"])),
                    linf_error=rel(x["linf"], ref["linf"]),
                    linf_reported=float(np.max(np.hypot(x["linf_err"], ref["linf_err"]) /
                                               ref["linf"])),
                    seconds=seconds, peak_mib=mib))
                print(rows[-1], flush=True)
            lines.append(f"{case}: reference {p['ref_realisations']} x {p['ref_size']}^2, "
                         f"{p['ref_rays']} rays, {ref_s:.0f} s, {ref_mib:.0f} MiB.")
    fields = list(rows[0].keys())
    with open(os.path.join(a.out, "ensembles.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    md = [f"On {machine} (bench/ensemble_study.py; {p['iterations']} generator iterations, "
          f"{p['cells']} cells; every point {p['samples']} surface samples and {p['rays']} rays; "
          "errors against the reference ensemble, reported = the errors the file gives, the "
          "reference's added in quadrature; per-cell: the relative L1 distance of the "
          "L-infinity BRDF, and what the reported errors predict for it):", "",
          "| case | surfaces | size | per-cell distance | predicted | L1 albedo error | reported "
          "| L∞ albedo error | reported | time | peak memory |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        md.append(f"| {r['case']} | {r['surfaces']} | {r['size']}² | {r['cell_distance']:.4f} | "
                  f"{r['cell_expected']:.4f} | {r['l1_error']:.1e} | {r['l1_reported']:.1e} | "
                  f"{r['linf_error']:.1e} | {r['linf_reported']:.1e} | {r['seconds']:.1f} s | "
                  f"{r['peak_mib']:.0f} MiB |")
    md += [""] + lines
    with open(os.path.join(a.out, "ensembles.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
