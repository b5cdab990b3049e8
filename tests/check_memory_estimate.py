#!/usr/bin/python3
"""The memory a run estimates before it starts (printed, and kept in the result file as
memory_estimate_bytes) is within 25 % of the process's peak (memory_peak_bytes, getrusage): the
quickstart (three cases of eight surfaces), a 32-wavelength gold case on one surface, and the same
on four; and a run that would not fit in the memory the machine has is refused before it starts.

Usage: check_memory_estimate.py GONIO_BINARY SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile

import h5py

TOLERANCE = 0.25


def run(args, cwd):
    r = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def main():
    gonio, source = sys.argv[1], sys.argv[2]
    runs = {
        "quickstart": [os.path.join(source, "configs/quickstart.toml")],
        "spectral, one surface": [os.path.join(source, "bench/configs/gold_spectral.toml")],
        "spectral, four surfaces": [os.path.join(source, "bench/configs/gold_spectral.toml"),
                                    "--set", "surface.realisations=4"],
    }
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for what, args in runs.items():
            out = os.path.join(tmp, "r.h5")
            run([gonio, "run", *args, "-o", out, "--overwrite", "--quiet", "--no-cache"], tmp)
            with h5py.File(out, "r") as f:
                estimate = float(f.attrs["memory_estimate_bytes"])
                peak = float(f.attrs["memory_peak_bytes"])
            off = (estimate - peak) / peak
            worst = max(worst, abs(off))
            print(f"{what}: estimated {estimate / 1e6:.0f} MB, peak {peak / 1e6:.0f} MB "
                  f"({off:+.0%} off)")
            assert abs(off) <= TOLERANCE, f"{what}: the estimate is {off:.0%} off the peak"
        # Far more than any machine: refused before any work, with the figures, nothing written.
        out = os.path.join(tmp, "huge.h5")
        r = subprocess.run([gonio, "run", os.path.join(source, "configs/quickstart.toml"), "-o",
                            out, "--quiet", "--set", "sensor.cells=200000",
                            "--set", "trace.batches=1024", "--set", "trace.orders=1000"],
                           cwd=tmp, capture_output=True, text=True)
        assert r.returncode != 0 and "of memory" in r.stderr, (r.returncode, r.stderr)
        assert not os.listdir(tmp) or not any(n.startswith("huge") for n in os.listdir(tmp)), \
            os.listdir(tmp)
        print(f"refused: {r.stderr.strip()}")
    print(f"memory estimate: ok (worst {worst:.0%} off)")


if __name__ == "__main__":
    main()
