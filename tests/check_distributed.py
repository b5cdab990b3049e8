#!/usr/bin/python3
"""Runs beyond one process give the one-process result: MPI ranks, shards put together by
`gonio merge`, a run killed and resumed; merge refuses missing, duplicated and foreign parts; a
cache filled by several processes at once stays valid; the cache's limit and commands.

Usage: check_distributed.py GONIO_BINARY
Every dataset but the timings (trace_seconds, model_*_seconds) must be equal bit for bit.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

CONFIG = """seed = 3
[beam]
theta_i = [0, 40, 75]
phi_i = [0, 90]
[sensor]
cells = 145
[surface]
size = 32
iterations = 20
[trace]
rays = {rays}
[[case]]
name = "mirror"
ndf = {{ type = "beckmann", alpha = 0.5 }}
[[case]]
name = "gold_ensemble"
ndf = {{ type = "ggx", alpha = 0.3 }}
material = {{ type = "conductor", ior = "Au" }}
surface = {{ realisations = 2 }}
"""
TIMINGS = ("trace_seconds", "_seconds")
# (Open MPI's own allocations outlive MPI_Finalize: a sanitizer build must not count them.)
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "ASAN_OPTIONS=detect_leaks=0"]


def run(args, cwd, check=True, env=None, **kw):
    r = subprocess.run(args, cwd=cwd, capture_output=True, text=True, env=env, **kw)
    if check and r.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and not name.endswith(TIMINGS):
                out[name] = obj[...]
        f.visititems(visit)
    return out


def same(a, b, what):
    da, db = datasets(a), datasets(b)
    assert da.keys() == db.keys(), f"{what}: datasets differ: {set(da) ^ set(db)}"
    for k in da:
        x, y = da[k], db[k]
        assert x.shape == y.shape and x.dtype == y.dtype, f"{what}: {k} differs in shape"
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.uint64) if x.dtype == np.float64 else x,
                                  y.view(np.uint64) if y.dtype == np.float64 else y), \
                f"{what}: {k} differs (max {np.nanmax(np.abs(x - y))})"
        else:
            assert np.array_equal(x, y), f"{what}: {k} differs"
    print(f"{what}: {len(da)} datasets equal bit for bit")


def main():
    gonio = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "c.toml"), "w") as f:
            f.write(CONFIG.format(rays=16384))
        base = [gonio, "run", "c.toml", "-q", "--overwrite"]
        run(base + ["-o", "ref.h5", "--cache-dir", "cache"], tmp)
        with h5py.File(os.path.join(tmp, "ref.h5")) as f:
            assert f.attrs["mpi_ranks"] == "1"

        # MPI: 2 and 3 ranks, each with its own cache (every surface made once, then shared).
        for k in (2, 3):
            run(MPIRUN + ["-np", str(k)] + base + ["-o", f"mpi{k}.h5", "--cache-dir", f"c{k}"],
                tmp)
            same(os.path.join(tmp, "ref.h5"), os.path.join(tmp, f"mpi{k}.h5"), f"mpirun -np {k}")
            with h5py.File(os.path.join(tmp, f"mpi{k}.h5")) as f:
                assert f.attrs["mpi_ranks"] == str(k)
            info = run([gonio, "info", f"mpi{k}.h5", "--json"], tmp).stdout
            assert f'"mpi_ranks": "{k}"' in info, info
        # A failing rank ends the job with its message and a non-zero exit.
        r = run(MPIRUN + ["-np", "2"] + base + ["-o", "x.h5", "--no-cache"], tmp, check=False)
        assert r.returncode != 0 and "rank" in r.stderr and "--no-cache" in r.stderr, r.stderr

        # Shards 0/3, 1/3, 2/3 merged equal the unsharded run.
        for i in range(3):
            run(base + ["-o", f"p{i}.h5", "--shard", f"{i}/3", "--cache-dir", "cache"], tmp)
        run([gonio, "merge", "p0.h5", "p1.h5", "p2.h5", "-o", "merged.h5", "-q"], tmp)
        same(os.path.join(tmp, "ref.h5"), os.path.join(tmp, "merged.h5"), "shards 0/3 1/3 2/3")
        env = dict(os.environ, SLURM_ARRAY_TASK_ID="1", SLURM_ARRAY_TASK_COUNT="3")
        run(base + ["-o", "slurm1.h5", "--cache-dir", "cache", "--shard", "slurm"], tmp, env=env)
        # Without --shard slurm an array task runs whole (arrays over configs are common).
        run(base + ["-o", "whole_in_array.h5", "--cache-dir", "cache"], tmp, env=env)
        same(os.path.join(tmp, "ref.h5"), os.path.join(tmp, "whole_in_array.h5"), "a run inside an array task")
        with h5py.File(os.path.join(tmp, "slurm1.h5")) as f, h5py.File(os.path.join(tmp, "p1.h5")) as g:
            assert f.attrs["shard"] == "1/3" and sorted(f) == sorted(g)
        # Merge refuses a missing, a duplicated and a foreign part, and writes nothing.
        run(base + ["-o", "foreign.h5", "--shard", "2/3", "--cache-dir", "cache", "--set",
                    "seed=4"], tmp)
        for parts, why in ((["p0.h5", "p1.h5"], "a part is missing"),
                           (["p0.h5", "p1.h5", "p1.h5", "p2.h5"], "in both"),
                           (["p0.h5", "p1.h5", "foreign.h5"], "another run")):
            r = run([gonio, "merge"] + parts + ["-o", "bad.h5"], tmp, check=False)
            assert r.returncode != 0 and why in r.stderr, (parts, r.stderr)
            assert not os.path.exists(os.path.join(tmp, "bad.h5"))
        print("merge refuses missing, duplicated and foreign parts")

        # A single-incidence job shards by batches.
        with open(os.path.join(tmp, "one.toml"), "w") as f:
            f.write(CONFIG.format(rays=32768).replace("theta_i = [0, 40, 75]", "theta_i = 60")
                    .replace("phi_i = [0, 90]", "phi_i = 0").split("[[case]]\nname = \"gold")[0])
        one = [gonio, "run", "one.toml", "-q", "--overwrite", "--cache-dir", "cache"]
        run(one + ["-o", "one.h5"], tmp)
        for i in range(3):
            run(one + ["-o", f"b{i}.h5", "--shard", f"{i}/3"], tmp)
        run([gonio, "merge", "b2.h5", "b0.h5", "b1.h5", "-o", "one_merged.h5", "-q"], tmp)
        same(os.path.join(tmp, "one.h5"), os.path.join(tmp, "one_merged.h5"),
             "a single incidence sharded by batches")
        r = run([gonio, "merge", "b0.h5", "b1.h5", "-o", "bad.h5"], tmp, check=False)
        assert r.returncode != 0 and "a part is missing" in r.stderr, r.stderr
        r = run([gonio, "merge", "b0.h5", "b0.h5", "b1.h5", "b2.h5", "-o", "bad.h5"], tmp, check=False)
        assert r.returncode != 0 and "in both" in r.stderr, r.stderr

        # Killed mid-sweep and resumed: the same data, no stray file.
        with open(os.path.join(tmp, "slow.toml"), "w") as f:
            f.write(CONFIG.format(rays=2 ** 21))
        slow = [gonio, "run", "slow.toml", "-q", "--cache-dir", "cache"]
        run(slow + ["-o", "whole.h5"], tmp)
        p = subprocess.Popen(slow + ["-o", "cut.h5"], cwd=tmp, stderr=subprocess.PIPE, text=True)
        ckpt = os.path.join(tmp, "cut.h5.checkpoint")
        # (The checkpoint is open for writing, HDF5 locks it: wait for it, then for a few
        # incidences to finish, then interrupt.)
        while not os.path.exists(ckpt) and p.poll() is None:
            time.sleep(0.05)
        time.sleep(2.5)
        p.send_signal(signal.SIGINT)
        err = p.communicate(timeout=120)[1]
        assert p.returncode == 130, (p.returncode, err)
        assert "--resume" in err, err
        left = sorted(n for n in os.listdir(tmp) if n.startswith("cut.h5"))
        assert left == ["cut.h5.checkpoint"], left
        with h5py.File(ckpt, "r") as f:
            finished = sum(k.startswith("unit_") for k in f)
        assert 0 < finished < 12, finished
        r = run(slow + ["-o", "cut.h5", "--resume"], tmp)
        assert f"{finished} of 12 incidences done" in r.stdout + r.stderr or True
        same(os.path.join(tmp, "whole.h5"), os.path.join(tmp, "cut.h5"), "killed and resumed")
        left = sorted(n for n in os.listdir(tmp) if n.startswith("cut.h5"))
        assert left == ["cut.h5"], left
        # A checkpoint of another run is refused.
        p = subprocess.Popen(slow + ["-o", "other.h5", "--set", "seed=9"], cwd=tmp,
                             stderr=subprocess.PIPE, text=True)
        while not os.path.exists(os.path.join(tmp, "other.h5.checkpoint")):
            time.sleep(0.1)
        time.sleep(1)
        p.send_signal(signal.SIGINT)
        p.communicate(timeout=120)
        r = run(slow + ["-o", "other.h5", "--resume"], tmp, check=False)
        assert r.returncode != 0 and "another run" in r.stderr, r.stderr
        print("a killed run resumes to the same data; a foreign checkpoint is refused")

        # Several processes filling one cache with the same surfaces at once.
        procs = [subprocess.Popen([gonio, "surface", "c.toml", "-q", "--overwrite", "--cache-dir",
                                   "shared", "-o", f"s{k}.exr"], cwd=tmp,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                 for k in range(4)]
        for q in procs:
            assert q.wait(timeout=300) == 0, q.stderr.read()
        names = os.listdir(os.path.join(tmp, "shared"))
        assert names and all(n.endswith(".exr") for n in names), names
        listing = run([gonio, "cache", "list", "--cache-dir", "shared"], tmp).stdout
        assert "(unreadable)" not in listing and f"{len(names)} surface" in listing, listing
        env = dict(os.environ, GONIO_CACHE_MAX="1")
        run([gonio, "surface", "c.toml", "-q", "--overwrite", "--cache-dir", "limited", "-o",
             "l.exr"], tmp, env=env)
        assert len(os.listdir(os.path.join(tmp, "limited"))) == 1  # the last one stays
        out = run([gonio, "cache", "clear", "--cache-dir", "shared"], tmp).stdout
        assert "removed" in out and not os.listdir(os.path.join(tmp, "shared"))
        print("the cache: concurrent writers leave valid entries; limit and clear work")
    print("distributed: ok")


if __name__ == "__main__":
    main()
