#!/usr/bin/python3
"""Opens a gonio result file with h5py, as a user would, and checks its layout.

Usage: check_result_h5py.py GONIO_BINARY CONFIG
Runs `gonio model CONFIG` into a temporary directory, then checks the layout of file format 2:
one dimension scale per axis, every cell coordinate a variable along `cell` with units and named
in the data variable's `coordinates` attribute, lists as string arrays, and that the albedo is
consistent with the per-cell energies. Exits non-zero on the first failure.
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
            assert (fmt.decode() if isinstance(fmt, bytes) else fmt) == "gonio-result 2"
            for key in ("gonio_version", "git_hash", "command_line", "config_toml", "conventions", "seed"):
                assert key in f.attrs, f"missing root attribute {key}"
            cases = f.attrs["cases"]
            assert not isinstance(cases, (str, bytes)) and list(cases) == list(f.keys()), cases
            assert f.attrs.get_id("cases").dtype.kind == "O"  # variable-length strings
            assert h5py.check_string_dtype(f.attrs.get_id("conventions").dtype).encoding == "utf-8"
            for name, group in f.items():
                brdf = group["model_l1"]
                for axis, dim in enumerate(("theta_i", "phi_i", "cell", "channel")):
                    assert list(brdf.dims[axis].keys()) == [dim], (name, axis, brdf.dims[axis].keys())
                coordinates = brdf.attrs["coordinates"].split()
                for coord in ("theta_center", "phi_center", "theta_min", "theta_max", "phi_min",
                              "phi_max", "solid_angle", "projected_solid_angle"):
                    assert coord in coordinates, f"{name}: {coord} is not a coordinate of model_l1"
                    assert not h5py.h5ds.is_scale(group[coord].id), f"{name}: {coord} is a scale"
                    assert list(group[coord].dims[0].keys()) == ["cell"], f"{name}/{coord}"
                    units = group[coord].attrs["units"]
                    assert units in ("degree", "sr"), f"{name}/{coord}: units {units!r}"
                for key, value in group.items():
                    assert "units" in value.attrs and "long_name" in value.attrs, f"{name}/{key}"
                models = group.attrs["models"]
                assert not isinstance(models, (str, bytes)) and list(models) == ["l1"], models
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
