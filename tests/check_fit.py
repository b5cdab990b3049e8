#!/usr/bin/python3
"""gonio fit, end to end (CTest fit_recovers_parameters).

1. Recovery: Model L1 of GGX alpha 0.3 and of Beckmann alpha_x 0.2 / alpha_y 0.6, written as a result
   file by `gonio model`, fitted with the right family: the parameters come back to 1e-3.
2. A traced case (one 64^2 Beckmann 0.5 mirror, two incidences): alpha with an error bar from Ceres'
   covariance and from the bootstrap, which agree within the bootstrap's own uncertainty; chi2/dof
   reported; the JSON holds the residual map; the Mitsuba 3 XML parses; another loss and --with
   kulla_conty run; a bad combination of options is refused with exit code 2 and no output.
Usage: check_fit.py GONIO WORKDIR
"""
import json
import math
import os
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET

gonio, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)


def run(*args, ok=True):
    p = subprocess.run([gonio, *args], capture_output=True, text=True)
    if ok and p.returncode != 0:
        sys.exit(f"{' '.join(args)} failed ({p.returncode}): {p.stderr}")
    return p


model_cfg = os.path.join(work, "models.toml")
with open(model_cfg, "w") as f:
    f.write("""seed = 1
[beam]
theta_i = [0, 30, 60]
[sensor]
cells = 577
[model]
models = ["l1"]
[[case]]
name = "ggx"
ndf = { type = "ggx", alpha = 0.3 }
material = { type = "mirror" }
[[case]]
name = "beckmann_aniso"
ndf = { type = "beckmann", alpha_x = 0.2, alpha_y = 0.6 }
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 450] }
beam = { phi_i = [0, 45] }
""")
models = os.path.join(work, "models.h5")
run("model", model_cfg, "-o", models, "--overwrite", "--quiet")

fit_ggx = os.path.join(work, "ggx.json")
run("fit", models, "--case", "ggx", "--model", "ggx", "-o", fit_ggx, "--overwrite", "--quiet")
with open(fit_ggx) as f:
    g = json.load(f)
a = g["parameters"]["alpha"]["value"]
assert abs(a - 0.3) < 1e-3, f"GGX alpha 0.3 came back as {a}"

fit_b = os.path.join(work, "beckmann.toml")
run("fit", models, "--case", "beckmann_aniso", "--model", "beckmann", "--anisotropic", "-o", fit_b,
    "--overwrite", "--quiet")
with open(fit_b, "rb") as f:
    b = tomllib.load(f)
ax, ay = b["parameters"]["alpha_x"]["value"], b["parameters"]["alpha_y"]["value"]
assert abs(ax - 0.2) < 1e-3 and abs(ay - 0.6) < 1e-3, f"Beckmann 0.2/0.6 came back as {ax}/{ay}"
ET.fromstring(b["renderers"]["mitsuba3"])  # well-formed XML
assert 'value="Au"' in b["renderers"]["mitsuba3"]
assert "no equivalent of beckmann" in b["renderers"]["pbrt_v4"]

# A traced case: the error bars.
run_cfg = os.path.join(work, "traced.toml")
with open(run_cfg, "w") as f:
    f.write("""seed = 3
[beam]
theta_i = [20, 50]
[sensor]
cells = 577
[surface]
size = 64
iterations = 40
[trace]
rays = 262144
orders = 3
[[case]]
name = "beckmann_0.5"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "mirror" }
""")
traced = os.path.join(work, "traced.h5")
run("run", run_cfg, "-o", traced, "--overwrite", "--quiet", "--no-cache")
fit_t = os.path.join(work, "traced.json")
run("fit", traced, "--model", "beckmann", "--bootstrap", "16", "-o", fit_t, "--overwrite", "--quiet")
with open(fit_t) as f:
    t = json.load(f)
p = t["parameters"]["alpha"]
assert 0.3 < p["value"] < 0.7, p
assert p["stderr"] > 0 and p["stderr_bootstrap"] > 0, p
# The bootstrap's standard deviation from 16 replicas is itself uncertain by about 1/sqrt(2 x 15)
# (18 %); 4 of those either way.
ratio = p["stderr_bootstrap"] / p["stderr"]
assert abs(math.log(ratio)) < 4 * (1 / math.sqrt(2 * 15)), f"covariance {p['stderr']} vs bootstrap {p['stderr_bootstrap']}"
assert t["fit"]["chi2_per_dof"] > 0
r = t["residuals"]
assert len(r["normalised"]) == len(r["theta_i"]) * len(r["phi_i"]) * r["cells"] * r["channels"]
assert any(v is not None for v in r["normalised"])

# Another loss, and Model L1 with Kulla-Conty fitted to every order.
run("fit", traced, "--model", "ggx", "--loss", "bieron_log", "--bootstrap", "0", "--quiet")
run("fit", traced, "--model", "beckmann", "--with", "kulla_conty", "--bootstrap", "0", "--quiet")

# A bad combination: usage error (2), nothing written.
bad = os.path.join(work, "bad.json")
if os.path.exists(bad):
    os.remove(bad)
q = run("fit", traced, "--model", "ggx", "--with", "turquin", "--orders", "l1", "-o", bad, ok=False)
assert q.returncode == 2 and "--orders linf" in q.stderr and not os.path.exists(bad), q.stderr
q = run("fit", traced, "--model", "piecewise_linear", ok=False)
assert q.returncode == 2, q.stderr
print(f"fit: GGX 0.3 -> {a:.6f}; Beckmann 0.2/0.6 -> {ax:.6f}/{ay:.6f}; traced Beckmann 0.5 -> "
      f"{p['value']:.4f} ± {p['stderr']:.4f} (bootstrap {p['stderr_bootstrap']:.4f}), "
      f"chi2/dof {t['fit']['chi2_per_dof']:.2f}")
