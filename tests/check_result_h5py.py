#!/usr/bin/python3
"""Opens a gonio result file with h5py, as a user would, and checks its layout.

Usage: check_result_h5py.py GONIO_BINARY CONFIG
Runs `gonio model CONFIG` into a temporary directory, then checks that every case's Model L1 has
its cell coordinates attached as dimension scales with units, and that the albedo is consistent
with the per-cell energies. Exits non-zero on the first failure.
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def main():
    gonio, config = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "result.h5")
        subprocess.run([gonio, "model", config, "-o", out, "--quiet"], check=True)
        with h5py.File(out, "r") as f:
            fmt = f.attrs["file_format"]
            assert (fmt.decode() if isinstance(fmt, bytes) else fmt) == "gonio-result 1"
            for key in ("gonio_version", "git_hash", "command_line", "config_toml", "conventions", "seed"):
                assert key in f.attrs, f"missing root attribute {key}"
            for name, group in f.items():
                brdf = group["model_l1"]
                cell_scales = list(brdf.dims[2].keys())
                for coord in ("theta_center", "phi_center", "theta_min", "theta_max", "phi_min",
                              "phi_max", "solid_angle", "projected_solid_angle"):
                    assert coord in cell_scales, f"{name}: {coord} is not attached to the cell dimension"
                    units = group[coord].attrs["units"]
                    units = units.decode() if isinstance(units, bytes) else units
                    assert units in ("degree", "sr"), f"{name}/{coord}: units {units!r}"
                assert "theta_i" in brdf.dims[0].keys() and "phi_i" in brdf.dims[1].keys()
                energy = group["model_l1_energy"][...]
                albedo = group["model_l1_albedo"][...]
                assert np.allclose(energy.sum(axis=2), albedo, rtol=1e-12, atol=0)
                assert np.all(np.isfinite(brdf[...])) and np.all(brdf[...] >= 0)
                assert np.allclose(group["solid_angle"][...], 2 * np.pi / group["cell"].shape[0], rtol=1e-12)
                print(f"{name}: model_l1 {brdf.shape}, albedo at theta_i={group['theta_i'][0]}: "
                      f"{albedo[0, 0]}")
    print("h5py: 1 passed, 0 failed")


if __name__ == "__main__":
    main()
