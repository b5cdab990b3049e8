#!/usr/bin/python3
"""Whole runs through two trace backends (or two builds) told apart, or not, by their Monte Carlo
error (issue 52, contract (b)).

    bench/backend_agreement.py run [--quick] [--gonio build/gonio] [--config C] [--size N]
                                   [--rays R] [--theta 0,60,85,89.9] [--keep DIR]
    bench/backend_agreement.py files A.h5 B.h5

`run` traces every case of the config (R19's ten NDFs by default) twice on the same surfaces
(`surface.seed` fixed) at independent ray seeds, once with `trace.backend = "embree"` and once with
"heightfield", and compares the files; `files` compares two result files already written (e.g. the
same config through two builds). Per case and incidence: the rms over cells of
z = (f_a - f_b) / sqrt(se_a^2 + se_b^2) for simulated L1 and L2+ (cells where either has light),
which is ~1 when the two differ only by their noise (bar: [0.8, 1.25]), and z of the L1, L2+ and
L-infinity albedos (bar: |z| <= 3). Prints a Markdown table; exits 1 when a bar is missed.
--quick (CTest): two cases, 128^2, 2^16 rays, two incidences.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

BARS = ((0.8, 1.25), 3.0)


def compare(path_a, path_b):
    """Rows (case, theta_i, L1 rms z, L2+ rms z, cells, albedo z L1, L2+, Linf) and the verdict."""
    rows, ok, identical = [], True, True
    with h5py.File(path_a, "r") as fa, h5py.File(path_b, "r") as fb:
        for case in fa:
            if not isinstance(fa[case], h5py.Group) or "brdf_l1" not in fa[case]:
                continue
            a, b = fa[case], fb[case]
            thetas = a["theta_i"][()]  # degrees
            for i, theta in enumerate(thetas):
                rms = []
                cells = 0
                for name in ("brdf_l1", "brdf_l2plus"):
                    fa_, fb_ = a[name][i], b[name][i]
                    sa, sb = a[name + "_stderr"][i], b[name + "_stderr"][i]
                    var = sa**2 + sb**2
                    lit = var > 0
                    z = (fa_[lit] - fb_[lit]) / np.sqrt(var[lit])
                    identical &= not np.any(z)
                    rms.append(float(np.sqrt(np.mean(z**2))) if z.size else float("nan"))
                    cells = max(cells, int(lit.sum()))
                albedo = []
                for name in ("l1_albedo", "l2plus_albedo", "linf_albedo"):
                    va, vb = a[name][i].ravel(), b[name][i].ravel()
                    se = np.sqrt(a[name + "_stderr"][i].ravel() ** 2 + b[name + "_stderr"][i].ravel() ** 2)
                    # A mirror's L-infinity albedo is 1 less what was capped or lost: a difference
                    # of rounding against an error of rounding is no measurement.
                    real = (se > 0) & (np.abs(va - vb) > 1e-12)
                    zs = np.where(real, (va - vb) / np.where(se > 0, se, 1), 0.0)
                    albedo.append(float(zs[np.argmax(np.abs(zs))]))
                # Too few lit cells make the rms a handful of numbers: reported, not judged.
                judged = [r for r in rms if cells >= 50 and not math.isnan(r) and r > 0]
                ok &= all(BARS[0][0] <= r <= BARS[0][1] for r in judged)
                ok &= all(abs(z) <= BARS[1] for z in albedo)
                rows.append((case, float(theta), rms[0], rms[1], cells, *albedo))
    # The same rays (e.g. two builds that trace a mirror the same way): nothing to judge.
    return rows, ok or identical, identical


def table(rows):
    out = ["| case | θi | L1 rms z | L2+ rms z | lit cells | albedo z L1 | L2+ | L∞ |",
           "|---|---|---|---|---|---|---|---|"]
    for case, theta, r1, r2, cells, z1, z2, z3 in rows:
        out.append(f"| {case} | {theta:g}° | {r1:.3f} | {r2:.3f} | {cells} | {z1:+.2f} | {z2:+.2f} | {z3:+.2f} |")
    return "\n".join(out)


def run(args):
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    gonio = args.gonio or os.path.join(root, "build", "gonio")
    config = args.config or os.path.join(root, "configs", "r19_fig11_ten_cases.toml")
    size, rays, thetas = args.size, args.rays, args.theta
    workdir = args.keep or tempfile.mkdtemp(prefix="gonio_agreement_")
    os.makedirs(workdir, exist_ok=True)
    if args.quick:  # two of R19's cases, small
        size, rays, thetas = 128, 1 << 16, "0,60"
        config = os.path.join(workdir, "quick.toml")
        with open(config, "w") as f:
            f.write('seed = 1\n[material]\ntype = "mirror"\n[sensor]\ncells = 3240\n'
                    '[trace]\norders = 10\n'
                    '[[case]]\nname = "ggx"\nndf = { type = "ggx", alpha = 0.5 }\n'
                    '[[case]]\nname = "beckmann"\nndf = { type = "beckmann", alpha = 0.5 }\n')
    outputs = []
    for backend, seed in (("embree", 101), ("heightfield", 202)):
        out = os.path.join(workdir, f"{backend}.h5")
        cmd = [gonio, "run", config, "-o", out, "--overwrite",
               "--set", f"seed={seed}", "--set", "surface.seed=1",
               "--set", f'trace.backend="{backend}"', "--set", f"surface.size={size}",
               "--set", f"trace.rays={rays}", "--set", f"beam.theta_i=[{thetas}]",
               "--quiet"]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        outputs.append(out)
    return outputs


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mode", choices=["run", "files"])
    p.add_argument("paths", nargs="*")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--gonio")
    p.add_argument("--config")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--rays", type=int, default=1 << 20)
    p.add_argument("--theta", default="0,60,85,89.9")
    p.add_argument("--keep")
    args = p.parse_args()
    paths = run(args) if args.mode == "run" else args.paths
    if len(paths) != 2:
        p.error("files needs two result files")
    rows, ok, identical = compare(*paths)
    print(f"{paths[0]} against {paths[1]}: rms z in [{BARS[0][0]}, {BARS[0][1]}], |albedo z| <= {BARS[1]}")
    print(table(rows))
    print("identical" if identical else "agree" if ok else "DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
