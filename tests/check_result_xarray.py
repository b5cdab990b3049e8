#!/usr/bin/python3
"""Opens a `gonio run` result with xarray (Debian's python3-xarray and python3-h5netcdf), as is.

Usage: check_result_xarray.py GONIO_BINARY
Runs a small two-case config (a mirror with two models, a spectral conductor) into a temporary
directory and checks that each case opens with `xr.open_dataset(f, group=case,
engine="h5netcdf")`: `brdf` has the dimensions (theta_i, phi_i, order, cell, channel), the cell
geometry is a coordinate along `cell` (and `wavelength` along `channel`), `.sel(theta_i=60,
order=1)` selects, the units and long names come through, and the string lists (`cases`,
`models`, `stop`, `phases`) come back as lists. Exits non-zero on the first failure.
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import xarray as xr

CONFIG = """seed = 2
[ndf]
type = "beckmann"
alpha = 0.5
[beam]
theta_i = [0, 60]
phi_i = [0, 90]
[sensor]
cells = 145
[surface]
size = 64
iterations = 20
[trace]
rays = 4096
orders = 3                  # orders 1, 2, 3 and "4 or more"
[[case]]
name = "mirror"
model = { models = ["l1", "ashikhmin"] }
[[case]]
name = "gold"
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 550, 450] }
"""
CELL = ("theta_center", "phi_center", "theta_min", "theta_max", "phi_min", "phi_max",
        "solid_angle", "projected_solid_angle")


def main():
    gonio = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "c.toml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([gonio, "run", "c.toml", "-q", "--cache-dir", "cache", "-o", "r.h5"],
                       cwd=tmp, check=True)
        path = os.path.join(tmp, "r.h5")
        with h5py.File(path, "r") as f:
            cases = f.attrs["cases"]
            assert list(cases) == ["mirror", "gold"], cases
            assert list(f["mirror"].attrs["models"]) == ["l1", "ashikhmin"]
            phases = list(f.attrs["phases"])
            assert phases[-1] == "wall" and "trace" in phases, phases
            assert all(f"phase_{p}_seconds" in f.attrs for p in phases), phases
        for case, channels in (("mirror", 1), ("gold", 3)):
            with xr.open_dataset(path, group=case, engine="h5netcdf") as ds:
                brdf = ds["brdf"]
                assert brdf.dims == ("theta_i", "phi_i", "order", "cell", "channel"), brdf.dims
                assert brdf.shape == (2, 2, 4, 145, channels), brdf.shape
                for coord in CELL:
                    assert coord in brdf.coords, f"{case}: {coord} is not a coordinate of brdf"
                    assert ds[coord].dims == ("cell",), (coord, ds[coord].dims)
                assert set(ds.dims) == {"theta_i", "phi_i", "order", "cell", "channel"}, ds.dims
                assert brdf.attrs["units"] == "1/sr" and brdf.attrs["long_name"]
                assert ds["theta_center"].attrs["units"] == "degree"
                for name, v in ds.variables.items():
                    assert "units" in v.attrs and "long_name" in v.attrs, f"{case}/{name}"
                one = brdf.sel(theta_i=60, order=1)
                assert one.dims == ("phi_i", "cell", "channel"), one.dims
                assert np.allclose(one.values, ds["brdf_l1"].sel(theta_i=60).values, rtol=0,
                                   atol=0)
                assert float(one.sel(phi_i=0, channel=0).max()) > 0
                # The same numbers as h5py reads, and theta_center as the sensor lays it out.
                with h5py.File(path, "r") as f:
                    assert np.array_equal(f[case]["brdf"][...], brdf.values)
                theta = ds["theta_center"].values
                assert 0 <= theta.min() and theta.max() < 90
                if channels == 3:
                    assert "wavelength" in brdf.coords and ds["wavelength"].dims == ("channel",)
                    assert list(ds["wavelength"].values) == [650, 550, 450]
                    assert list(ds["l1_albedo"].sel(theta_i=0, phi_i=0).coords["wavelength"].values) \
                        == [650, 550, 450]
                else:
                    models = ds.attrs["models"]
                    assert isinstance(models, list) and models == ["l1", "ashikhmin"], models
                stop = ds.attrs["stop"]
                assert isinstance(stop, list) and stop == ["rays"] * 4, stop
                phases = ds.attrs["phases"]
                assert isinstance(phases, list) and "surface" in phases and "trace" in phases, phases
                for phase in phases:
                    assert ds.attrs[f"phase_{phase}_seconds"] >= 0
                print(f"{case}: brdf {brdf.dims} {brdf.shape}, "
                      f"L1 albedo at 60 deg {float(ds['l1_albedo'].sel(theta_i=60)[0, 0]):.4f}")
    print("xarray: ok")


if __name__ == "__main__":
    main()
