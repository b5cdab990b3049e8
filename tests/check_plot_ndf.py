#!/usr/bin/python3
"""Runs `gonio ndf --csv` on a two-case config (an isotropic curve and a blend) and draws it with
scripts/plot_ndf.py.

Usage: check_plot_ndf.py GONIO_BINARY PLOT_SCRIPT
Checks the printed normalisation and albedo lines, the CSV's shape (181 angles per case, D equal
along both azimuths for the isotropic case and not for the blend) and that a non-empty PNG is
written. Exits non-zero on the first failure.
"""
import csv
import os
import subprocess
import sys
import tempfile

CONFIG = """seed = 1
[beam]
theta_i = 60
[sensor]
cells = 145
[[case]]
name = "sinc"
ndf = { type = "sinc", k = 6, floor = 0.05, points = 65 }
[[case]]
name = "blend"
[case.ndf]
type = "blend"
x = { type = "ggx", alpha = 0.5 }
y = { type = "beckmann", alpha = 0.3 }
"""


def fail(message):
    print("check_plot_ndf: " + message, file=sys.stderr)
    sys.exit(1)


def main():
    gonio, script = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as d:
        config = os.path.join(d, "c.toml")
        with open(config, "w") as f:
            f.write(CONFIG)
        curves = os.path.join(d, "curves.csv")
        out = subprocess.run([gonio, "ndf", config, "--csv", curves], capture_output=True,
                             text=True)
        if out.returncode != 0:
            fail("gonio ndf failed: " + out.stderr)
        if out.stdout.count("int D cos dw = 1.00000") != 2:
            fail("normalisation lines missing or not 1:\n" + out.stdout)
        if out.stdout.count("Model L1 albedo at theta_i=60") != 2:
            fail("albedo lines missing:\n" + out.stdout)
        with open(curves, newline="") as f:
            rows = list(csv.DictReader(f))
        for name, isotropic in (("sinc", True), ("blend", False)):
            mine = [r for r in rows if r["case"] == name]
            if len(mine) != 181:
                fail("%s: %d rows, expected 181" % (name, len(mine)))
            same = all(r["D_phi0"] == r["D_phi90"] for r in mine)
            if same != isotropic:
                fail("%s: D along phi = 0 and 90 should %sdiffer" % (name, "not " if isotropic else ""))
        png = os.path.join(d, "curves.png")
        subprocess.run(["/usr/bin/python3", script, curves, png], check=True)
        if not os.path.exists(png) or os.path.getsize(png) < 10000:
            fail("no PNG written")
    print("check_plot_ndf: ok")


if __name__ == "__main__":
    main()
