#!/usr/bin/python3
"""The same config and seed give the same bits whatever the layout: one process with 1 or 2
threads, three shards put together by `gonio merge`, `mpirun -np 2`, a run stopped by SIGINT
and resumed, and one killed by SIGKILL and resumed; and `gonio model` gives the models of `gonio run` bit for bit.

The case is the quickstart's gold one (anisotropic Beckmann, three wavelengths), whose Model L1
reaches the underflow range in its far cells: there the floating-point mode decides the bits
(flush-to-zero in threads that had run Embree, not elsewhere), and before every thread was put in
one mode (core/float_mode.h) the merged, MPI and model-only files differed from the one-process
file in those cells (~1e-305, measured on `configs/quickstart.toml`). A 16-wavelength ensemble
takes every path of the reduced units (streamed batches, surfaces combined where traced).

Usage: check_same_bits.py GONIO_BINARY
Every numeric dataset but the timings (*_seconds) must be equal bit for bit.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_results import same  # noqa: E402

CONFIG = """seed = 5
[beam]
theta_i = [0, 30, 60, 80]
phi_i = [0, 45]
[sensor]
cells = 3240
[surface]
size = 64
iterations = 20
[trace]
rays = {rays}
batches = 8
[[case]]
name = "gold_beckmann_aniso"
ndf = {{ type = "beckmann", alpha_x = 0.2, alpha_y = 0.6 }}
material = {{ type = "conductor", ior = "Au" }}
spectrum = {{ wavelengths = [650, 550, 450] }}
[[case]]
name = "gold_ensemble"
ndf = {{ type = "ggx", alpha = 0.3 }}
material = {{ type = "conductor", ior = "Au" }}
surface = {{ realisations = 2 }}
[[case]]
name = "gold_spectral_ensemble"
ndf = {{ type = "beckmann", alpha = 0.5 }}
material = {{ type = "conductor", ior = "Au" }}
spectrum = {{ wavelengths = [400, 420, 440, 460, 480, 500, 520, 540, 560, 580, 600, 620, 640, 660, 680, 700] }}
surface = {{ realisations = 2 }}
trace = {{ rays = {spectral_rays} }}
"""
UNITS = 24  # 3 cases x 4 theta_i x 2 phi_i
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "ASAN_OPTIONS=detect_leaks=0"]


def run(args, cwd, check=True):
    r = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    if check and r.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def main():
    gonio = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        path = lambda name: os.path.join(tmp, name)
        with open(path("c.toml"), "w") as f:
            f.write(CONFIG.format(rays=16384, spectral_rays=16384))
        base = [gonio, "run", "c.toml", "-q", "--overwrite", "--cache-dir", "cache"]
        run(base + ["-o", "ref.h5", "--threads", "1"], tmp)
        with h5py.File(path("ref.h5")) as f:
            model = f["gold_beckmann_aniso/model_l1"][...]
        tail = np.count_nonzero((model > 0) & (model < 1e-250))
        assert tail > 0, "the case no longer reaches the underflow range"
        print(f"Model L1 has {tail} cells in (0, 1e-250): the floating-point mode matters here")

        run(base + ["-o", "two.h5", "--threads", "2"], tmp)
        same(path("ref.h5"), path("two.h5"), "1 and 2 threads")
        for i in range(3):
            run(base + ["-o", f"p{i}.h5", "--shard", f"{i}/3"], tmp)
        run([gonio, "merge", "p0.h5", "p1.h5", "p2.h5", "-o", "merged.h5", "-q"], tmp)
        same(path("ref.h5"), path("merged.h5"), "shards 0/3 1/3 2/3 merged")
        run(MPIRUN + ["-np", "2"] + base + ["-o", "mpi.h5"], tmp)
        same(path("ref.h5"), path("mpi.h5"), "mpirun -np 2")
        run([gonio, "model", "c.toml", "-q", "--overwrite", "-o", "model.h5"], tmp)
        same(path("ref.h5"), path("model.h5"), "gonio model against gonio run", prefix="model_")

        # Stopped by SIGINT after a few incidences, then resumed.
        with open(path("slow.toml"), "w") as f:
            f.write(CONFIG.format(rays=2 ** 20, spectral_rays=2 ** 16))
        slow = [gonio, "run", "slow.toml", "-q", "--cache-dir", "cache"]
        run(slow + ["-o", "whole.h5"], tmp)
        p = subprocess.Popen(slow + ["-o", "cut.h5"], cwd=tmp, stderr=subprocess.PIPE, text=True)
        while not os.path.exists(path("cut.h5.checkpoint")) and p.poll() is None:
            time.sleep(0.05)
        time.sleep(2.0)
        p.send_signal(signal.SIGINT)
        err = p.communicate(timeout=300)[1]
        assert p.returncode == 130, (p.returncode, err)
        with h5py.File(path("cut.h5.checkpoint"), "r") as f:
            finished = sum(k.startswith("unit_") for k in f)
        assert 0 < finished < UNITS, finished
        run(slow + ["-o", "cut.h5", "--resume"], tmp)
        same(path("whole.h5"), path("cut.h5"), f"stopped after {finished} of {UNITS} units, resumed")

        # Killed (kill -9: no handler runs, a record may be half written), then resumed.
        p = subprocess.Popen(slow + ["-o", "killed.h5"], cwd=tmp, stderr=subprocess.PIPE,
                             text=True)
        while not os.path.exists(path("killed.h5.checkpoint")) and p.poll() is None:
            time.sleep(0.05)
        time.sleep(3.0)
        p.kill()
        p.communicate(timeout=300)
        assert p.returncode == -signal.SIGKILL, p.returncode
        run(slow + ["-o", "killed.h5", "--resume"], tmp)
        same(path("whole.h5"), path("killed.h5"), "killed by SIGKILL, resumed")
    print("same bits: ok")


if __name__ == "__main__":
    main()
