#!/usr/bin/python3
"""Wall time of one sweep run as 1 process and as MPI ranks, and threads against ranks at equal
cores (issue 18). Case: Beckmann 0.75 mirror on a 512^2 surface (cached beforehand, so that the
table is the tracing), theta_i 0..77 in 7-degree steps, 2^21 rays per incidence, 3240 cells.
Prints a Markdown table; every layout's result is checked equal to the first (bit for bit, timings
aside) by tests/check_distributed.py's comparison.

Usage: bench/distributed_bench.py [--gonio build/gonio] [--quick]
"""
import argparse
import importlib.util
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIG = """seed = 1
ndf = {{ type = "beckmann", alpha = 0.75 }}
[beam]
theta_i = [{theta}]
[sensor]
cells = 3240
[surface]
size = {size}
[trace]
rays = {rays}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gonio", default="build/gonio")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    spec = importlib.util.spec_from_file_location(
        "check", os.path.join(HERE, "..", "tests", "check_distributed.py"))
    check = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(check)
    rays, size, n = (2 ** 14, 32, 4) if args.quick else (2 ** 21, 512, 12)
    theta = ", ".join(str(7 * k) for k in range(n))
    layouts = [("1 process x 1 thread", 1, 1), ("1 process x 2 threads", 1, 2),
               ("2 ranks x 1 thread", 2, 1), ("2 ranks x 2 threads (oversubscribed)", 2, 2)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "b.toml"), "w") as f:
            f.write(CONFIG.format(theta=theta, size=size, rays=rays))
        subprocess.run([args.gonio, "surface", "b.toml", "-q", "--cache-dir", "cache", "-o",
                        "s.exr"], cwd=tmp, check=True)
        first = None
        for label, ranks, threads in layouts:
            cmd = [args.gonio, "run", "b.toml", "-q", "--overwrite", "--cache-dir", "cache",
                   "--threads", str(threads), "-o", f"r{ranks}_{threads}.h5"]
            if ranks > 1:
                cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
            start = time.time()
            subprocess.run(cmd, cwd=tmp, check=True)
            wall = time.time() - start
            out = os.path.join(tmp, f"r{ranks}_{threads}.h5")
            if first is None:
                first = out
            else:
                check.same(first, out, label)
            rows.append((label, wall, n * rays / wall))
    base = rows[0][1]
    print("| layout | wall time | rays/s | speed-up over 1 x 1 |")
    print("|---|---|---|---|")
    for label, wall, rate in rows:
        print(f"| {label} | {wall:.1f} s | {rate / 1e6:.2f} M | {base / wall:.2f} |")


if __name__ == "__main__":
    sys.exit(main())
