#!/usr/bin/python3
"""gonio's speed-against-accuracy study (issue 7).

For four reference cases it sweeps one knob at a time around a baseline -- rays, surface size,
generation iterations, sensor cells, bounce cap, quadrature points of the model -- and measures
each point's wall time, peak memory (the gonio process's maximum resident set) and its error
against a converged reference: relative error of the L1 and L2+ albedos and the per-cell relative
L1 distance sum |f - f_ref| Omega_perp / sum f_ref Omega_perp of the L1 BRDF (of the model for the
quadrature knob). It then times what a scene can leave out: an L1-only run against an L-infinity
run, a mirror against a three-channel conductor, a run without model evaluation, and a theta_i
sweep on one surface against one surface per incidence.

Writes <out>/study.csv, <out>/study.png (error against time, one curve per knob, log-log),
<out>/table.md (what to set for ~1 %, ~0.1 % and ~0.01 %) and <out>/ratios.md, and prints them.

Usage: bench/study.py [--gonio build/gonio] [--out docs/study] [--quick] [--cases A,...]
--quick runs tiny sizes (a smoke test: minutes become seconds; the numbers mean nothing).
--cases runs some cases only: their rows replace theirs in an existing <out>/study.csv and
<out>/ratios.csv, and the table and plot are redrawn from the whole file.
"""
import argparse
import csv
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

CASES = {
    "A_beckmann0.75_mirror_60": dict(
        ndf='{ type = "beckmann", alpha = 0.75 }', material='{ type = "mirror" }', theta=60),
    "B_ggx0.3_gold_80": dict(
        ndf='{ type = "ggx", alpha = 0.3 }', material='{ type = "conductor", ior = "Au" }',
        theta=80),
    "C_beckmann0.3_glass_45": dict(
        ndf='{ type = "beckmann", alpha = 0.3 }', material='{ type = "dielectric", eta = 1.5 }',
        theta=45),
    "D_beckmann0.5_il_60": dict(
        ndf='{ type = "beckmann", alpha = 0.5 }',
        material='{ type = "interfaced_lambertian", eta = 1.5, albedo = 0.6 }', theta=60),
}

FULL = dict(
    size=512, iterations=100, iterations_ref=500, cells=3240, rays=10**6, ref_rays=10**8,
    ref_cells_rays=2 * 10**7,
    ref_size=4096, rays_sweep=[10**4, 10**5, 10**6, 10**7, 3 * 10**7],
    size_sweep=[64, 128, 256, 512, 1024, 2048], size_rays=10**7,
    iterations_sweep=[0, 10, 30, 100, 300], iterations_rays=10**7,
    cells_sweep=[145, 580, 1000, 3240, 10000], bounce_sweep=[1, 2, 3, 5, 10],
    bounce_rays=10**7, quadrature_sweep=[1, 2, 3, 4, 6, 8], sweep_thetas=9)
QUICK = dict(
    size=64, iterations=20, iterations_ref=30, cells=145, rays=10**4, ref_rays=10**5,
    ref_cells_rays=10**5,
    ref_size=128, rays_sweep=[10**3, 10**4], size_sweep=[32, 64], size_rays=10**4,
    iterations_sweep=[0, 10], iterations_rays=10**4, cells_sweep=[145, 580],
    bounce_sweep=[1, 2], bounce_rays=10**4, quadrature_sweep=[1, 4], sweep_thetas=3)


class Study:
    def __init__(self, gonio, work, p):
        self.gonio, self.work, self.p = gonio, work, p
        self.cache = os.path.join(work, "cache")
        self.count = 0

    def config(self, case, theta=None, **keys):
        """A one-case TOML config: the case with the baseline, overridden by keys."""
        c = CASES[case]
        k = dict(size=self.p["size"], iterations=self.p["iterations"], cells=self.p["cells"],
                 rays=self.p["rays"], max_bounces=1000, seed=1, quadrature=4, tolerance=1e-6,
                 evaluate="true", material=c["material"])
        k.update(keys)
        thetas = theta if theta is not None else [c["theta"]]
        models = '["il"]' if "interfaced" in k["material"] else '["l1"]'
        return f"""seed = {k['seed']}
[beam]
theta_i = [{', '.join(str(t) for t in thetas)}]
[sensor]
cells = {k['cells']}
[surface]
size = {k['size']}
iterations = {k['iterations']}
seed = 1
[trace]
rays = {k['rays']}
max_bounces = {k['max_bounces']}
[model]
models = {models}
evaluate = {k['evaluate']}
quadrature = {k['quadrature']}
tolerance = {k['tolerance']}
[[case]]
name = "c"
ndf = {c['ndf']}
material = {k['material']}
"""

    def run(self, case, command="run", cache=True, theta=None, **keys):
        """Runs gonio on the case; returns (h5 path, wall seconds, peak MiB)."""
        self.count += 1
        cfg = os.path.join(self.work, f"p{self.count}.toml")
        out = os.path.join(self.work, f"p{self.count}.h5")
        with open(cfg, "w") as f:
            f.write(self.config(case, theta=theta, **keys))
        args = [self.gonio, command, cfg, "-o", out, "--overwrite", "-q"]
        if command == "run":
            args += ["--cache-dir", self.cache] if cache else ["--no-cache"]
        start = time.perf_counter()
        proc = subprocess.Popen(args, stderr=subprocess.PIPE)
        _, status, usage = os.wait4(proc.pid, 0)
        seconds = time.perf_counter() - start
        err = proc.stderr.read().decode()
        proc.stderr.close()
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"study: gonio failed on {case} {keys}: {err}")
        return out, seconds, usage.ru_maxrss / 1024.0

    def warm(self, case, **keys):
        """Generates (and caches) a surface, so that the timed run that follows only loads it."""
        self.run(case, rays=1, evaluate="false", **keys)


def read(path, model=False):
    with h5py.File(path, "r") as f:
        g = f["c"]
        omega = g["projected_solid_angle"][()]
        if model:
            name = [k for k in g.keys() if k.startswith("model_") and k.endswith("_energy")][0]
            e = g[name][0, 0, :, 0]
            return dict(l1=e.sum(), l2plus=np.nan, cells=e / omega, omega=omega, err=np.nan)
        return dict(l1=g["l1_albedo"][0, 0, 0], l2plus=g["l2plus_albedo"][0, 0, 0],
                    cells=g["brdf_l1"][0, 0, :, 0], omega=omega,
                    err=g["l1_albedo_stderr"][0, 0, 0] / g["l1_albedo"][0, 0, 0],
                    trace=g["trace_seconds"][()].sum())


def errors(x, ref):
    rel = lambda a, b: abs(a - b) / abs(b) if b else np.nan
    dist = (np.abs(x["cells"] - ref["cells"]) * x["omega"]).sum() / (ref["cells"] * x["omega"]).sum()
    return rel(x["l1"], ref["l1"]), rel(x["l2plus"], ref["l2plus"]), dist


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--gonio", default="build/gonio")
    ap.add_argument("--out", default="docs/study")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--cases", default=",".join(CASES), help="comma-separated case names")
    a = ap.parse_args()
    p = QUICK if a.quick else FULL
    os.makedirs(a.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="gonio_study_")
    s = Study(os.path.abspath(a.gonio), work, p)
    rows, ratios = [], []
    machine = f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores"
    try:
        with open("/proc/cpuinfo") as f:
            model = [l.split(":", 1)[1].strip() for l in f if l.startswith("model name")]
            if model:
                machine = f"{model[0]}, {os.cpu_count()} cores"
        with open("/proc/meminfo") as f:
            kib = int(f.readline().split()[1])
            machine += f", {kib / 2**20:.0f} GiB"
    except (OSError, ValueError, IndexError):
        pass

    def point(case, knob, value, path, seconds, mib, ref, model=False):
        x = read(path, model)
        e1, e2, d = errors(x, ref)
        rows.append(dict(case=case, knob=knob, value=value, seconds=round(seconds, 3),
                         peak_mib=round(mib, 1), l1_albedo=x["l1"], l2plus_albedo=x["l2plus"],
                         err_l1_albedo=e1, err_l2plus_albedo=e2, err_cells_l1=d,
                         reported_err_l1=x["err"]))
        print(f"{case:26s} {knob:10s} {value!s:>9} {seconds:8.2f} s {mib:7.0f} MiB  "
              f"L1 {e1:.2e}  L2+ {e2:.2e}  cells {d:.2e}", flush=True)

    for case in a.cases.split(","):
        print(f"== {case}: references", flush=True)
        s.warm(case)
        ref_path, _, _ = s.run(case, rays=p["ref_rays"], seed=99)
        ref = read(ref_path)
        # Rays: Monte Carlo error alone (one surface, the reference with its own seed).
        for n in p["rays_sweep"]:
            point(case, "rays", n, *s.run(case, rays=n), ref)
        # Bounce cap: the higher orders it cuts (time saved, L2+ lost).
        for cap in p["bounce_sweep"]:
            point(case, "bounces", cap, *s.run(case, rays=p["bounce_rays"], max_bounces=cap), ref)
        # Generation iterations and surface size: the surface's own error (generation included
        # in the time: no cache), against the reference surface and rays (for the iterations,
        # a reference surface iterated further than the baseline's).
        it_path, _, _ = s.run(case, iterations=p["iterations_ref"], rays=p["ref_rays"], seed=99)
        it_ref = read(it_path)
        for it in p["iterations_sweep"]:
            point(case, "iterations", it,
                  *s.run(case, cache=False, iterations=it, rays=p["iterations_rays"]), it_ref)
        big_path, _, _ = s.run(case, size=p["ref_size"], rays=p["ref_rays"], seed=99)
        big = read(big_path)
        for n in p["size_sweep"]:
            point(case, "size", n, *s.run(case, cache=False, size=n, rays=p["size_rays"]), big)
        # Sensor cells: each against a reference on the same sensor.
        for cells in p["cells_sweep"]:
            rp, _, _ = s.run(case, cells=cells, rays=p["ref_cells_rays"], seed=99)
            point(case, "cells", cells, *s.run(case, cells=cells), read(rp))
        # Quadrature points per cell of the model (adaptivity off: tolerance 0.1), against the
        # model at 8 points and tolerance 1e-10.
        mp, _, _ = s.run(case, command="model", quadrature=8, tolerance=1e-10)
        mref = read(mp, model=True)
        for q in p["quadrature_sweep"]:
            point(case, "quadrature", q,
                  *s.run(case, command="model", quadrature=q, tolerance=0.1), mref, model=True)

        # What a scene can leave out: ratios of wall time, taken in this run.
        def timed(**keys):
            return s.run(case, **keys)[1]
        n = p["bounce_rays"]
        l1_only, linf = timed(rays=n, max_bounces=1), timed(rays=n)
        ratios.append((case, "L-infinity / L1-only (bounce cap 1)", linf / l1_only))
        no_model, with_model = timed(evaluate="false"), timed()
        ratios.append((case, "with / without model evaluation", with_model / no_model))
        if case.startswith("A_"):
            gold = timed(rays=n, material='{ type = "conductor", ior = "Au" }')
            ratios.append((case, "3-channel gold / mirror", gold / linf))
            thetas = [10 * k for k in range(p["sweep_thetas"])]
            one = s.run(case, cache=False, theta=thetas)[1]
            each = sum(s.run(case, cache=False, theta=[t])[1] for t in thetas)
            ratios.append((case, f"{len(thetas)} runs of one incidence / one sweep of "
                           f"{len(thetas)} (surface generated each time)", each / one))

    rows = merge(os.path.join(a.out, "study.csv"), rows, list(rows[0].keys()))
    ratios = merge(os.path.join(a.out, "ratios.csv"),
                   [dict(case=c, ratio=w, value=v) for c, w, v in ratios], ["case", "ratio", "value"])
    ratios = [(r["case"], r["ratio"], float(r["value"])) for r in ratios]
    write_ratios(a.out, ratios, machine)
    write_table(a.out, rows, p, machine)
    plot(a.out, rows, machine)
    shutil.rmtree(work, ignore_errors=True)
    print(f"study: wrote {a.out}/study.csv, study.png, table.md, ratios.md")


def merge(path, new, fields):
    """Writes `new` to the CSV at path, keeping the rows of the cases `new` does not have."""
    ran = {r["case"] for r in new}
    old = []
    if os.path.exists(path):
        with open(path, newline="") as f:
            old = [r for r in csv.DictReader(f) if r["case"] not in ran]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(old + new)
    with open(path, newline="") as f:  # numbers back as numbers
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            try:
                r[k] = float(v) if k not in ("case", "knob", "ratio") else v
            except ValueError:
                pass
        if "value" in r and "knob" in r:
            r["value"] = int(r["value"])
    order = list(CASES)
    rows.sort(key=lambda r: order.index(r["case"]) if r["case"] in order else len(order))
    return rows


def write_ratios(out, ratios, machine):
    lines = [f"Wall-time ratios on {machine} (bench/study.py, one run):", "",
             "| case | ratio | value |", "|---|---|---|"]
    lines += [f"| {c} | {what} | {v:.2f} |" for c, what, v in ratios]
    text = "\n".join(lines) + "\n"
    open(os.path.join(out, "ratios.md"), "w").write(text)
    print(text)


def write_table(out, rows, p, machine):
    """Rays for a target L1-albedo error and per-cell distance (the measured errors fitted to
    c / sqrt(N)), with the time that costs, and the surface size whose own error is below it."""
    lines = [f"On {machine} (bench/study.py; rays fitted to error = c / sqrt(rays) over the "
             "rays sweep; size: smallest surface whose measured L1-albedo error is below the "
             "target, '>' when none is):", "",
             "| case | target | rays for L1 albedo | time | rays for per-cell L1 | time | surface |",
             "|---|---|---|---|---|---|---|"]
    for case in dict.fromkeys(r["case"] for r in rows):
        rr = [r for r in rows if r["case"] == case and r["knob"] == "rays"]
        n = np.array([r["value"] for r in rr], float)
        t = np.array([r["seconds"] for r in rr], float)
        sec_per_ray = np.polyfit(n, t, 1)[0]  # slope: the fixed cost does not scale
        fixed = max(0.0, float(np.polyfit(n, t, 1)[1]))
        sizes = [r for r in rows if r["case"] == case and r["knob"] == "size"]
        for target in (1e-2, 1e-3, 1e-4):
            cells = []
            for key in ("err_l1_albedo", "err_cells_l1"):
                e = np.array([r[key] for r in rr], float)
                c = np.exp(np.mean(np.log(e * np.sqrt(n))))  # geometric mean of e sqrt(N)
                need = (c / target) ** 2
                cells += [f"{need:.1e}", f"{fixed + sec_per_ray * need:.3g} s"]
            ok = [r["value"] for r in sizes if r["err_l1_albedo"] <= target]
            surface = f"{min(ok)}²" if ok else f"> {max(r['value'] for r in sizes)}²"
            lines.append(f"| {case} | {target:g} | " + " | ".join(cells) + f" | {surface} |")
    text = "\n".join(lines) + "\n"
    open(os.path.join(out, "table.md"), "w").write(text)
    print(text)


def plot(out, rows, machine):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig, axes = plt.subplots(2, len(cases), figsize=(4.2 * len(cases), 7.5), squeeze=False)
    for j, case in enumerate(cases):
        for i, (key, label) in enumerate((("err_l1_albedo", "relative error, L1 albedo"),
                                          ("err_cells_l1", "per-cell relative L1 distance"))):
            ax = axes[i][j]
            for knob in dict.fromkeys(r["knob"] for r in rows):
                rr = [r for r in rows if r["case"] == case and r["knob"] == knob]
                pts = [(r["seconds"], r[key], r["value"]) for r in rr
                       if np.isfinite(r[key]) and r[key] > 0]
                if not pts:
                    continue
                x, y, v = zip(*pts)
                ax.loglog(x, y, "o-", label=knob, ms=3)
                ax.annotate(str(v[-1]), (x[-1], y[-1]), fontsize=6)
            ax.set_ylim(bottom=1e-8)  # the quadrature's errors go on down to round-off
            ax.set_xlabel("wall time (s)")
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
            if i == 0:
                ax.set_title(case, fontsize=9)
    axes[0][0].legend(fontsize=7)
    fig.suptitle(f"gonio: error against cost, one knob at a time ({machine})", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "study.png"), dpi=110)


if __name__ == "__main__":
    main()
