#!/usr/bin/python3
"""The decomposition closes: `measured` (single scattering with the surface's facet NDF D_s and its
measured joint G2) against simulated L1 on Beckmann 0.75 and GGX 0.5 mirrors at theta_i 0, 60 and 85
degrees (256^2 surfaces, 2^22 rays, 2^22 facet points, 1152 cells): albedo within 3 sigma, per-cell
rms z within [0.7, 1.4] over the bright cells (at least 1 % of the peak), where Model L1 is at least
10 sigma away at every incidence.

One surface per case, on purpose: `measured` and the simulation see the same surfaces, so the
comparison is paired. An ensemble's error bars include the surfaces' spread, which both sides
share and which cancels in their difference: on ensembles of four 256^2 surfaces the per-cell rms z
falls to 0.3-0.5 (measured). One surface's errors are its rays' and points' alone, the right
yardstick.

Usage: check_masking_closure.py GONIO WORKDIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

CONFIG = """seed = 5
[material]
type = "mirror"
[beam]
theta_i = [0, 60, 85]
phi_i = 0
[sensor]
cells = 1152
[surface]
size = 256
[trace]
rays = 4194304
[model]
models = ["l1", "measured"]
[[case]]
name = "ggx_0.5"
ndf = { type = "ggx", alpha = 0.5 }
[[case]]
name = "beckmann_0.75"
ndf = { type = "beckmann", alpha = 0.75 }
"""


def main():
    gonio, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    cfg, out = os.path.join(work, "closure.toml"), os.path.join(work, "closure.h5")
    with open(cfg, "w") as f:
        f.write(CONFIG)
    subprocess.run([gonio, "run", cfg, "-o", out, "--overwrite", "--quiet", "--no-cache"], check=True)
    problems = []
    with h5py.File(out) as f:
        for name in f.attrs["cases"]:
            g = f[name]
            for t, theta in enumerate(g["theta_i"][:]):
                sim, sim_e = g["l1_albedo"][t, 0, 0], g["l1_albedo_stderr"][t, 0, 0]
                m, m_e = g["model_measured_albedo"][t, 0, 0], g["model_measured_albedo_stderr"][t, 0, 0]
                z_albedo = (sim - m) / np.hypot(sim_e, m_e)
                z_l1 = (sim - g["model_l1_albedo"][t, 0, 0]) / sim_e
                f_sim, e_sim = g["brdf_l1"][t, 0, :, 0], g["brdf_l1_stderr"][t, 0, :, 0]
                f_mod, e_mod = g["model_measured"][t, 0, :, 0], g["model_measured_stderr"][t, 0, :, 0]
                bright = f_sim > 0.01 * f_sim.max()
                z = (f_sim - f_mod)[bright] / np.sqrt(e_sim[bright] ** 2 + e_mod[bright] ** 2)
                rms = float(np.sqrt(np.mean(z ** 2)))
                print(f"{name:14s} theta_i {theta:4g}: measured albedo {z_albedo:+5.2f} sigma, per-cell "
                      f"rms z {rms:.2f} over {bright.sum()} bright cells; Model L1 {z_l1:+7.1f} sigma")
                if abs(z_albedo) > 3:
                    problems.append(f"{name} {theta}: measured albedo {z_albedo:+.2f} sigma")
                if not 0.7 <= rms <= 1.4:
                    problems.append(f"{name} {theta}: per-cell rms z {rms:.2f}")
                if abs(z_l1) < 10:
                    problems.append(f"{name} {theta}: Model L1 only {z_l1:+.1f} sigma away")
    if problems:
        print("check_masking_closure: FAILED: " + "; ".join(problems))
        sys.exit(1)
    print("check_masking_closure: ok")


if __name__ == "__main__":
    main()
