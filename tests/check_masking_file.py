#!/usr/bin/python3
"""gonio masking end to end: an isotropic case on an ensemble of two surfaces and an anisotropic
one, written to HDF5 and opened as it is in xarray (named dimensions, units), the weak white furnace
within 4 sigma at every direction, G1 and G2 in [0, 1], the ensemble's errors its surfaces' spread.

Usage: check_masking_file.py GONIO WORKDIR
"""
import os
import subprocess
import sys

import numpy as np
import xarray as xr

CONFIG = """seed = 2
[beam]
theta_i = [0, 70]
phi_i = 0
[surface]
size = 64
iterations = 60
[[case]]
name = "ggx_iso"
ndf = { type = "ggx", alpha = 0.4 }
surface = { realisations = 2 }
[[case]]
name = "beckmann_aniso"
ndf = { type = "beckmann", alpha_x = 0.2, alpha_y = 0.6 }
"""


def main():
    gonio, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    cfg, out = os.path.join(work, "masking.toml"), os.path.join(work, "masking.h5")
    with open(cfg, "w") as f:
        f.write(CONFIG)
    r = subprocess.run([gonio, "masking", cfg, "-o", out, "--overwrite", "--no-cache",
                        "--points", "16384", "--g2-points", "4096"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("check_masking_file: FAILED: gonio masking: " + r.stderr)
    if "furnace" not in r.stdout or "G2 against Smith" not in r.stdout:
        sys.exit("check_masking_file: FAILED: no table printed:\n" + r.stdout)
    for case, phis, surfaces in [("ggx_iso", 1, 2), ("beckmann_aniso", 8, 1)]:
        ds = xr.open_dataset(out, group=case, engine="h5netcdf")
        assert ds["g1"].dims == ("theta_o", "phi_o", "normal_bin"), ds["g1"].dims
        assert ds["g2"].dims == ("theta_i", "phi_i", "g2_theta_o", "g2_dphi"), ds["g2"].dims
        assert ds.sizes["phi_o"] == phis, ds.sizes
        assert ds["g1"].attrs["units"] == "1"
        assert int(ds.attrs["surfaces"]) == surfaces
        z = np.abs(ds["furnace_z"].values)
        assert z.max() <= 4, f"{case}: weak furnace |z| {z.max():.2f}"
        for name in ["g1", "g1_height", "g2", "g2_bin", "g1_projected"]:
            v = ds[name].values
            v = v[np.isfinite(v)]
            assert v.size and v.min() >= 0 and v.max() <= 1, name
        # The retro direction (wo = wi) is on the G2 grid.
        assert 70 in ds["g2_theta_o"].values and 0 in ds["g2_dphi"].values
        print(f"check_masking_file: {case}: furnace |z| <= {z.max():.2f}, "
              f"G2 retro at 70 deg {float(ds['g2'].sel(theta_i=70, g2_theta_o=70, g2_dphi=0)[0]):.4f}")
    print("check_masking_file: ok")


if __name__ == "__main__":
    main()
