#!/usr/bin/python3
"""Runs a small `gonio run` and draws its comparison maps with scripts/plot_comparison.py.

Usage: check_plot_comparison.py GONIO_BINARY PLOT_SCRIPT
Checks that one non-empty PNG is written per case and incidence, and that the script refuses a
file without Model L1. Exits non-zero on the first failure.
"""
import os
import subprocess
import sys
import tempfile

CONFIG = """seed = 1
[ndf]
type = "beckmann"
alpha = 0.5
[beam]
theta_i = [30, 80]
[sensor]
cells = 145
[surface]
size = 64
iterations = 20
[trace]
rays = 20000
"""


def main():
    gonio, script = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "c.toml"), "w") as f:
            f.write(CONFIG)
        run = [gonio, "run", "c.toml", "-q", "--cache-dir", "cache"]
        subprocess.run(run + ["-o", "r.h5"], cwd=tmp, check=True)
        subprocess.run([sys.executable, script, "r.h5", "maps"], cwd=tmp, check=True,
                       stdout=subprocess.DEVNULL)
        pngs = sorted(os.listdir(os.path.join(tmp, "maps")))
        assert pngs == ["c_theta30.00_phi0.0.png", "c_theta80.00_phi0.0.png"], pngs
        for p in pngs:
            assert os.path.getsize(os.path.join(tmp, "maps", p)) > 5000, p
        subprocess.run(run + ["-o", "nomodel.h5", "--set", "model.evaluate=false"], cwd=tmp,
                       check=True)
        refused = subprocess.run([sys.executable, script, "nomodel.h5", "none"], cwd=tmp,
                                 capture_output=True, text=True)
        assert refused.returncode != 0 and "no case with both" in refused.stderr, refused.stderr
    print("plot_comparison: ok")


if __name__ == "__main__":
    main()
