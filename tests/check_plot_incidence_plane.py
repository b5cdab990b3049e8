#!/usr/bin/python3
"""Runs a small `gonio run` and draws it with scripts/plot_incidence_plane.py.

Usage: check_plot_incidence_plane.py GONIO_BINARY PLOT_SCRIPT
Checks the cells the plane crosses (both half-planes, signed angles through 0, each cell once), that
one non-empty PNG is written per case, and that a model-only file is refused.
"""
import importlib.util
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

CONFIG = """seed = 1
[ndf]
type = "beckmann"
alpha = 0.4
[beam]
theta_i = [20, 50, 75]
[sensor]
cells = 400
[surface]
size = 64
iterations = 20
[trace]
rays = 40000
"""


def main():
    gonio, script = sys.argv[1], sys.argv[2]
    spec = importlib.util.spec_from_file_location("plot", script)
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "c.toml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([gonio, "run", "c.toml", "-q", "--cache-dir", "cache", "-o", "r.h5"],
                       cwd=tmp, check=True)
        with h5py.File(os.path.join(tmp, "r.h5")) as f:
            g = f["c"]
            index, signed = plot.plane_cells(g, 0.0)
            assert len(set(index.tolist())) == len(index), "a cell appears twice"
            assert signed.min() < -80 and signed.max() > 80, (signed.min(), signed.max())
            assert np.all(np.diff(signed) >= 0)
            # The reflected lobe (f cos) at theta_i = 50 peaks on the positive side near +50.
            v = g["brdf_l1"][1, 0, :, 0][index] * np.cos(np.radians(signed))
            assert 35 < signed[np.argmax(v)] < 70, signed[np.argmax(v)]
        subprocess.run([sys.executable, script, "r.h5", "plots"], cwd=tmp, check=True,
                       stdout=subprocess.DEVNULL)
        png = os.path.join(tmp, "plots", "c_incidence_plane.png")
        assert os.path.getsize(png) > 10000, os.path.getsize(png)
        subprocess.run([gonio, "model", "c.toml", "-q", "-o", "m.h5"], cwd=tmp, check=True)
        r = subprocess.run([sys.executable, script, "m.h5", "plots"], cwd=tmp,
                           capture_output=True, text=True)
        assert r.returncode != 0 and "no simulated orders" in r.stderr, r.stderr
    print("plot_incidence_plane: ok")


if __name__ == "__main__":
    main()
