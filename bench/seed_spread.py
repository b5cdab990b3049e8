#!/usr/bin/python3
"""Reported standard errors against the spread of independent seeds (issue 7).

Runs one small case N times with seeds 1..N on one surface (surface.seed fixed), with an accuracy
target on the L1 albedo, and prints per run the rays used, how it stopped and the reported error;
then, per quantity, the spread of the N values (sample standard deviation) against the root mean
square of the reported errors, their ratio, and the chi-square p-value of (N-1) s^2 / sigma^2.

Usage: bench/seed_spread.py [--gonio build/gonio] [--seeds 12] [--target 1e-3]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

CONFIG = """seed = {seed}
[beam]
theta_i = 60
[sensor]
cells = 400
[surface]
size = 128
seed = 1
[trace]
rays = 16384
target_error = {target}
target = "l1_albedo"
[[case]]
name = "c"
ndf = {{ type = "beckmann", alpha = 0.75 }}
material = {{ type = "conductor", ior = "Au" }}
"""


def chi2_sf(x, k):
    """P(X >= x) for chi-square with k degrees of freedom (series of the regularised gamma)."""
    from math import exp, lgamma, log
    a, z = k / 2.0, x / 2.0
    if z <= 0:
        return 1.0
    term = total = 1.0 / a
    n = 1
    while term > total * 1e-15 and n < 10000:
        term *= z / (a + n)
        total += term
        n += 1
    lower = exp(-z + a * log(z) - lgamma(a)) * total
    return max(0.0, 1.0 - lower)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--gonio", default="build/gonio")
    ap.add_argument("--seeds", type=int, default=12)
    ap.add_argument("--target", type=float, default=1e-3)
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="gonio_spread_")
    quantities = ["l1_albedo", "l2plus_albedo", "l1_distance"]
    values = {q: [] for q in quantities}
    errors = {q: [] for q in quantities}
    print(f"{'seed':>4} {'rays':>9} {'stop':>8} {'achieved':>9} {'L1 albedo':>22}")
    for seed in range(1, a.seeds + 1):
        cfg = os.path.join(work, "c.toml")
        out = os.path.join(work, f"s{seed}.h5")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(seed=seed, target=a.target))
        r = subprocess.run([a.gonio, "run", cfg, "-o", out, "--overwrite", "-q",
                            "--cache-dir", os.path.join(work, "cache")], capture_output=True)
        if r.returncode:
            sys.exit(r.stderr.decode())
        with h5py.File(out, "r") as f:
            g = f["c"]
            stop = g.attrs["stop"]  # a string array (format 2) or comma-joined (format 1)
            stop = stop.decode() if isinstance(stop, bytes) else stop
            stop = stop if isinstance(stop, str) else str(stop[0])
            for q in quantities:  # channel 0 (650 nm)
                values[q].append(g[q][0, 0, 0])
                errors[q].append(g[q + "_stderr"][0, 0, 0])
            print(f"{seed:4d} {g['rays'][0, 0]:9.0f} {stop:>8} {g['achieved_error'][0, 0]:9.2e} "
                  f"{values['l1_albedo'][-1]:.6f}±{errors['l1_albedo'][-1]:.1e}")
    n = a.seeds
    print(f"\n{'quantity':>14} {'spread':>10} {'reported':>10} {'ratio':>6} {'p':>6}")
    for q in quantities:
        v, e = np.array(values[q]), np.array(errors[q])
        s, sigma = v.std(ddof=1), np.sqrt(np.mean(e ** 2))
        stat = (n - 1) * s ** 2 / sigma ** 2
        p = chi2_sf(stat, n - 1)
        print(f"{q:>14} {s:10.3e} {sigma:10.3e} {s / sigma:6.2f} {2 * min(p, 1 - p):6.2f}")


if __name__ == "__main__":
    main()
