#!/usr/bin/python3
"""Hostile inputs, one by one: every defect a tester found (issue 31) reproduced and held fixed.
Each case makes a bad input, runs gonio on it, and checks the exit code of the contract (0 done,
1 failed, 2 usage or config, 3 a format cannot hold the data, 130 interrupted), that the message is
one line `gonio: error: ...` naming what it must (the file, the dataset or key), and that nothing is
left behind (no temporary, no half-written output, no checkpoint the failure created).

Usage: check_hostile_inputs.py GONIO_BINARY [CASE ...]    (all cases when none is named)
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exr_min import write_exr  # noqa: E402

SMALL = """seed = 3
[beam]
theta_i = [0, 40, 80]
[sensor]
cells = 145
[surface]
size = 32
iterations = 5
[trace]
rays = 4096
batches = 4
[[case]]
name = "gold"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 550, 450] }
"""
# A sweep dense enough for every export format (rgl, merl need theta_i 0..80 in steps <= 10).
DENSE = SMALL.replace("theta_i = [0, 40, 80]", "theta_i = { start = 0, stop = 80, step = 10 }")


class Failure(Exception):
    pass


class Hostile:
    def __init__(self, gonio, root):
        self.gonio, self.root = gonio, root
        self.fixtures = os.path.join(root, "fixtures")
        os.makedirs(self.fixtures)
        self.write("small.toml", SMALL, self.fixtures)
        self.write("dense.toml", DENSE, self.fixtures)
        self.ok(["run", "small.toml", "-o", "small.h5", "-q", "--no-cache"], self.fixtures)
        self.ok(["run", "dense.toml", "-o", "dense.h5", "-q", "--no-cache"], self.fixtures)
        for i in range(2):
            self.ok(["run", "small.toml", "-o", f"part{i}.h5", "-q", "--no-cache", "--shard",
                     f"{i}/2"], self.fixtures)

    def write(self, name, text, where):
        with open(os.path.join(where, name), "w") as f:
            f.write(text)

    def fresh(self, name):
        """An empty directory for one case, with copies of the fixtures it names."""
        d = os.path.join(self.root, name)
        os.makedirs(d)
        return d

    def copy(self, fixture, d, as_name=None):
        dst = os.path.join(d, as_name or fixture)
        shutil.copy(os.path.join(self.fixtures, fixture), dst)
        return dst

    def run(self, args, cwd, timeout=120, env=None):
        try:
            return subprocess.run([self.gonio] + args, cwd=cwd, capture_output=True, text=True,
                                  timeout=timeout, env=env)
        except subprocess.TimeoutExpired:
            raise Failure(f"gonio {' '.join(args)}: no answer within {timeout} s (a hang)")

    def ok(self, args, cwd, **kw):
        r = self.run(args, cwd, **kw)
        if r.returncode != 0:
            raise Failure(f"gonio {' '.join(args)} failed ({r.returncode}): {r.stderr}")
        return r

    def refused(self, args, cwd, code, *fragments, **kw):
        """gonio exits with `code`, one `gonio: error:` line (or `gonio export: refused:`) that
        holds every fragment, and nothing crashed."""
        r = self.run(args, cwd, **kw)
        if r.returncode < 0 or r.returncode >= 128 and r.returncode != 130:
            raise Failure(f"gonio {' '.join(args)} crashed ({r.returncode}): {r.stderr[-2000:]}")
        if r.returncode != code:
            raise Failure(f"gonio {' '.join(args)}: exit {r.returncode}, expected {code}: "
                          f"{r.stderr[-2000:]}")
        err = r.stderr.strip()
        prefix = "gonio export: refused:" if code == 3 else "gonio: error:"
        if not err.startswith(prefix) or "\n" in err:
            raise Failure(f"gonio {' '.join(args)}: not one '{prefix}' line: {err[:2000]!r}")
        for f in fragments:
            if f not in err:
                raise Failure(f"gonio {' '.join(args)}: {f!r} not in {err[:2000]!r}")
        if len(err) > 1000:
            raise Failure(f"gonio {' '.join(args)}: a message of {len(err)} characters")
        return r

    def left(self, d, *expected):
        """The directory holds exactly `expected` (and no temporary)."""
        names = sorted(os.listdir(d))
        if names != sorted(expected):
            raise Failure(f"{d}: holds {names}, expected {sorted(expected)}")


def mutate_h5(path, edit, keep_file_checksum=False):
    """Edits a file through HDF5. gonio's files carry a checksum of all their bytes, which any
    edit breaks (and gonio then refuses the file as changed); to reach the checks of the content
    behind it, the checksum is blanked first, as if the file came from an older gonio."""
    if not keep_file_checksum:
        with open(path, "r+b") as f:
            if f.read(16) == b"gonio file crc32":
                f.seek(0)
                f.write(bytes(32))
    with h5py.File(path, "a") as f:
        edit(f)


def replace_dataset(group, name, data):
    del group[name]
    group.create_dataset(name, data=data)


# ---------------------------------------------------------------------------------------------
# Crashes

def astm_without_wavelength(h):
    d = h.fresh("astm_without_wavelength")
    h.copy("small.h5", d)
    mutate_h5(os.path.join(d, "small.h5"), lambda f: f["gold"].__delitem__("wavelength"))
    h.refused(["export", "small.h5", "--format", "astm", "-o", "x.astm"], d, 1, "small.h5",
              "wavelength")
    h.left(d, "small.h5")


def albedo_without_incidences(h):
    d = h.fresh("albedo_without_incidences")
    h.copy("small.h5", d)
    mutate_h5(os.path.join(d, "small.h5"),
              lambda f: replace_dataset(f["gold"], "theta_i", np.zeros(0)))
    for fmt in ("albedo", "astm"):
        h.refused(["export", "small.h5", "--format", fmt, "-o", "x.csv"], d, 1, "small.h5",
                  "theta_i")
    h.refused(["info", "small.h5"], d, 1, "small.h5", "theta_i")
    h.left(d, "small.h5")


def unit_of_rank_two(h):
    d = h.fresh("unit_of_rank_two")
    for i in range(2):
        h.copy(f"part{i}.h5", d)

    def reshape(f):
        name = sorted(k for k in f if k.startswith("unit_"))[0]
        data = f[name][...]
        attrs = dict(f[name].attrs)
        del f[name]
        f.create_dataset(name, data=np.tile(data, (2, 1)))
        for k, v in attrs.items():
            f[name].attrs[k] = v
    mutate_h5(os.path.join(d, "part1.h5"), reshape)
    h.refused(["merge", "part0.h5", "part1.h5", "-o", "m.h5"], d, 1, "part1.h5", "unit_")
    # The same record in a checkpoint, met by --resume.
    shutil.copy(os.path.join(d, "part1.h5"), os.path.join(d, "out.h5.checkpoint"))
    h.copy("small.toml", d)
    h.refused(["run", "small.toml", "-o", "out.h5", "--resume", "--no-cache", "-q"], d, 1,
              "out.h5.checkpoint", "unit_")
    h.left(d, "part0.h5", "part1.h5", "out.h5.checkpoint", "small.toml")


def render_light_not_finite(h):
    d = h.fresh("render_light_not_finite")
    h.copy("dense.h5", d)
    for light in ("nan,0", "30,nan", "30,inf", "inf,0", "-1,0", "90,0"):
        h.refused(["render", "dense.h5", "-o", "o.png", "--light", light, "--spp", "1",
                   "--size", "8x8"], d, 2, "--light")
    h.left(d, "dense.h5")


def deep_config(h):
    d = h.fresh("deep_config")
    h.write("deep.toml", "[" + ".".join(["a"] * 50000) + "]\nx = 1\n", d)
    h.refused(["ndf", "deep.toml"], d, 2, "deep.toml", "nest")
    h.write("long.toml", "x = \"" + "y" * (2 << 20) + "\"\n", d)
    h.refused(["ndf", "long.toml"], d, 2, "long.toml", "MB")


def full_disk(h):
    d = h.fresh("full_disk")
    disk = os.path.join(d, "disk")
    os.makedirs(disk)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", disk],
                      capture_output=True).returncode != 0:
        print("  full_disk: skipped (cannot mount a tmpfs here)")
        return
    try:
        h.copy("dense.toml", disk)
        big = ["-o", "big.h5", "-q", "--set", "sensor.cells=3240", "--set",
               "beam.phi_i=[0, 30, 60, 90]"]
        for args in (["run", "dense.toml", "--no-cache"] + big, ["model", "dense.toml"] + big):
            h.refused(args, disk, 1, "big.h5", "No space left on device")
            h.left(disk, "dense.toml")
    finally:
        subprocess.run(["umount", disk])


# ---------------------------------------------------------------------------------------------
# Silent corruption

def shapes_against_axes(h):
    d = h.fresh("shapes_against_axes")
    h.copy("small.h5", d)
    mutate_h5(os.path.join(d, "small.h5"),
              lambda f: replace_dataset(f["gold"], "phi_i", np.array([0.0, 10.0, 20.0])))
    for args in (["export", "small.h5", "--format", "astm", "-o", "x.astm"], ["info", "small.h5"],
                 ["compare", "small.h5"]):
        h.refused(args, d, 1, "small.h5", "phi_i")
    h.left(d, "small.h5")


def file_checksums(h):
    d = h.fresh("file_checksums")
    h.copy("small.h5", d)
    path = os.path.join(d, "small.h5")
    mutate_h5(path, lambda f: f["gold"].attrs.__setitem__("material", "not gold"),
              keep_file_checksum=True)
    h.refused(["info", "small.h5"], d, 1, "small.h5", "checksum")
    with open(path, "r+b") as f:
        f.seek(os.path.getsize(path) // 2)
        f.write(b"\xff" * 16)
    h.refused(["export", "small.h5", "--format", "astm", "-o", "x.astm"], d, 1, "small.h5",
              "checksum")
    h.left(d, "small.h5")


def unit_checksums(h):
    d = h.fresh("unit_checksums")
    for i in range(2):
        h.copy(f"part{i}.h5", d)
    path = os.path.join(d, "part1.h5")
    mutate_h5(path, lambda f: None)  # the file's own checksum blanked: the record's is left
    with h5py.File(path, "r") as f:  # (HDF5's addresses count from after the user block)
        name = sorted(k for k in f if k.startswith("unit_"))[0]
        offset = f.userblock_size + f[name].id.get_chunk_info(0).byte_offset
    with open(path, "r+b") as f:
        f.seek(offset + 40)
        b = f.read(1)
        f.seek(offset + 40)
        f.write(bytes([b[0] ^ 0x10]))
    h.refused(["merge", "part0.h5", "part1.h5", "-o", "m.h5"], d, 1, "part1.h5", name)
    h.left(d, "part0.h5", "part1.h5")


def impossible_values(h):
    for what, edit in (
            ("nan", lambda f: f["gold/brdf"].__setitem__((0, 0, 0, 5, 0), np.nan)),
            ("negative", lambda f: f["gold/brdf_linf"].__setitem__((1, 0, 7, 1), -1.0)),
            ("unsorted", lambda f: replace_dataset(f["gold"], "theta_i",
                                                   f["gold/theta_i"][...][::-1].copy()))):
        d = h.fresh("impossible_values_" + what)
        h.copy("dense.h5", d)
        mutate_h5(os.path.join(d, "dense.h5"), edit)
        for fmt in ("rgl", "merl", "astm", "albedo"):
            h.refused(["export", "dense.h5", "--format", fmt, "-o", "x.out"], d, 1, "dense.h5")
        h.refused(["render", "dense.h5", "-o", "o.png", "--spp", "1", "--size", "8x8"], d, 1,
                  "dense.h5")
        h.left(d, "dense.h5")


def missing_case_group(h):
    d = h.fresh("missing_case_group")
    h.copy("small.h5", d)
    mutate_h5(os.path.join(d, "small.h5"), lambda f: f.__delitem__("gold"))
    for args in (["info", "small.h5"], ["compare", "small.h5"],
                 ["export", "small.h5", "--format", "astm", "-o", "x.astm"]):
        h.refused(args, d, 1, "small.h5", "gold")


# ---------------------------------------------------------------------------------------------
# Hangs

def grazing_beam(h):
    d = h.fresh("grazing_beam")
    h.copy("small.toml", d)
    h.refused(["run", "small.toml", "-o", "g.h5", "--set", "beam.theta_i=89.99999999999"], d,
              2, "beam.theta_i", "89.99")
    h.ok(["run", "small.toml", "-o", "g.h5", "--no-cache", "-q", "--set", "beam.theta_i=89.99"],
         d, timeout=60)


def absurd_height_map(h):
    d = h.fresh("absurd_height_map")
    config = SMALL.replace("[surface]\nsize = 32\niterations = 5", "[surface]\ninput = \"m.exr\"")
    h.write("input.toml", config, d)
    # A map of 1e38 heights on a 16-sample patch: relief absurd for its size.
    heights = np.full((16, 16), 1e38, dtype=np.float32)
    heights[::2, ::3] = -1e38
    write_exr(os.path.join(d, "m.exr"), {"Y": heights}, doubles={"gonio_spacing": 1.0})
    h.refused(["run", "input.toml", "-o", "m.h5", "--no-cache", "-q"], d, 1, "m.exr", "relief",
              timeout=60)
    # A map gonio wrote, bits flipped in its pixels: its checksum refuses it.
    h.copy("small.toml", d)
    h.ok(["surface", "small.toml", "-o", "s.exr", "--no-cache", "-q"], d)
    with open(os.path.join(d, "s.exr"), "r+b") as f:
        data = bytearray(f.read())
        for k in range(len(data) * 2 // 3, len(data), 97):
            data[k] ^= 0x40
        f.seek(0)
        f.write(bytes(data))
    h.write("input.toml", config.replace("m.exr", "s.exr"), d)
    h.refused(["run", "input.toml", "-o", "m.h5", "--no-cache", "-q"], d, 1, "s.exr", timeout=60)
    assert not os.path.exists(os.path.join(d, "m.h5"))


# ---------------------------------------------------------------------------------------------
# Left behind

def render_all_or_nothing(h):
    d = h.fresh("render_all_or_nothing")
    h.copy("dense.h5", d)
    os.makedirs(os.path.join(d, "o.exr"))  # the EXR cannot be written: no PNG either
    h.refused(["render", "dense.h5", "-o", "o.png", "--spp", "1", "--size", "8x8",
               "--overwrite"], d, 2, "o.exr")
    h.left(d, "dense.h5", "o.exr")
    # (The rollback of outputs written but not all renamed: tests/test_run_api.cpp.)


def surface_all_or_nothing(h):
    d = h.fresh("surface_all_or_nothing")
    h.copy("small.toml", d)
    os.makedirs(os.path.join(d, "s_normals.exr"))
    h.refused(["surface", "small.toml", "-o", "s.exr", "--no-cache", "-q", "--overwrite"], d, 2,
              "s_normals.exr")
    h.left(d, "small.toml", "s_normals.exr")


def output_is_a_directory(h):
    d = h.fresh("output_is_a_directory")
    h.copy("small.toml", d)
    os.makedirs(os.path.join(d, "out"))
    h.refused(["run", "small.toml", "-o", "out", "--overwrite", "--no-cache", "-q"], d, 2, "out",
              "directory")
    h.left(d, "small.toml", "out")


def dot_case_names(h):
    d = h.fresh("dot_case_names")
    for name in (".", "..", "a/b"):
        h.write("c.toml", SMALL.replace('name = "gold"', f'name = "{name}"'), d)
        h.refused(["run", "c.toml", "-o", "c.h5", "--no-cache", "-q"], d, 2, "name")
        h.left(d, "c.toml")


def stale_temporaries(h):
    d = h.fresh("stale_temporaries")
    h.copy("small.toml", d)
    args = ["run", "small.toml", "-o", "out.h5", "--no-cache", "-q", "--set", "trace.rays=4000000"]
    p = subprocess.Popen([h.gonio] + args, cwd=d, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while not os.path.exists(os.path.join(d, "out.h5.checkpoint")) and time.time() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)
    p.send_signal(signal.SIGKILL)
    p.wait()
    stale = [n for n in os.listdir(d) if ".tmp-" in n]
    if not stale:
        raise Failure("stale_temporaries: the killed run left no temporary (the test is moot)")
    h.ok(args + ["--resume"], d)
    h.left(d, "small.toml", "out.h5")


# ---------------------------------------------------------------------------------------------
# Wrong or unclear

def names_with_spaces(h):
    d = h.fresh("names_with_spaces")
    sub = os.path.join(d, "dir with space é")
    os.makedirs(sub)
    lone = 'ndf = { type = "beckmann", alpha = 0.5 }\n' + SMALL.split("[[case]]")[0]
    h.write("lone.toml", lone, d)
    h.ok(["run", "lone.toml", "-o", os.path.join(sub, "rés ult.h5"), "--no-cache", "-q"], d)
    h.ok(["export", os.path.join(sub, "rés ult.h5"), "--format", "astm", "-o",
          os.path.join(sub, "x é.astm")], d)


def corrupt_inputs_are_failures(h):
    d = h.fresh("corrupt_inputs_are_failures")
    with open(os.path.join(d, "junk.h5"), "wb") as f:
        f.write(b"\x89HDF\r\n\x1a\n" + bytes(200))
    h.refused(["export", "junk.h5", "--format", "astm", "-o", "x.astm"], d, 1, "junk.h5")
    h.refused(["render", "junk.h5", "-o", "o.png"], d, 1, "junk.h5")
    h.refused(["info", "junk.h5"], d, 1, "junk.h5")
    h.left(d, "junk.h5")


def memory_asked_up_front(h):
    d = h.fresh("memory_asked_up_front")
    h.copy("small.toml", d)
    # 256 batches x 11 orders x 1e7 cells x 3 channels of doubles: 675 GB for one trace.
    h.refused(["run", "small.toml", "-o", "m.h5", "--no-cache", "-q", "--set",
               "sensor.cells=10000000", "--set", "trace.batches=256"], d, 1, "GB", "memory",
              timeout=60)
    # Model L1's maps over 1000 incidences of 1e7 cells: 720 GB.
    h.refused(["model", "small.toml", "-o", "m.h5", "-q", "--set", "sensor.cells=10000000",
               "--set", "beam.theta_i={ start = 0, stop = 89, count = 1000 }"], d, 1, "memory",
              timeout=60)
    h.left(d, "small.toml")


def missing_seed(h):
    d = h.fresh("missing_seed")
    h.copy("small.h5", d)
    mutate_h5(os.path.join(d, "small.h5"), lambda f: f.attrs.__delitem__("seed"))
    h.refused(["info", "small.h5"], d, 1, "small.h5", "seed")


def checkpoint_in_use(h):
    d = h.fresh("checkpoint_in_use")
    h.copy("small.toml", d)
    args = ["run", "small.toml", "-o", "out.h5", "--no-cache", "-q", "--set", "trace.rays=2000000"]
    p = subprocess.Popen([h.gonio] + args, cwd=d, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    try:
        deadline = time.time() + 60
        while not os.path.exists(os.path.join(d, "out.h5.checkpoint")) and time.time() < deadline:
            time.sleep(0.05)
        time.sleep(0.3)
        h.refused(args + ["--resume"], d, 1, "out.h5.checkpoint", "another process")
    finally:
        p.kill()
        p.wait()


def long_values_cut(h):
    d = h.fresh("long_values_cut")
    h.write("k.toml", SMALL + "\n" + "x" * (1 << 20) + " = 1\n", d)
    h.refused(["ndf", "k.toml"], d, 2, "k.toml")


def cli_errors_prefixed(h):
    d = h.fresh("cli_errors_prefixed")
    h.refused(["run"], d, 2)
    h.refused(["export", "x.h5", "--format", "png", "-o", "y"], d, 2, "--format")
    h.refused(["frobnicate"], d, 2)


def existing_output_is_usage(h):
    d = h.fresh("existing_output_is_usage")
    h.copy("small.toml", d)
    h.write("out.h5", "precious", d)
    h.refused(["run", "small.toml", "-o", "out.h5", "--no-cache", "-q"], d, 2, "out.h5",
              "--overwrite")


def cache_max_spaces(h):
    d = h.fresh("cache_max_spaces")
    for value in (" 2G", "2G ", "2 G"):
        env = dict(os.environ, GONIO_CACHE_MAX=value)
        h.ok(["cache", "list", "--cache-dir", "cache"], d, env=env)
    env = dict(os.environ, GONIO_CACHE_MAX="2 gallons")
    h.refused(["cache", "list", "--cache-dir", "cache"], d, 2, "GONIO_CACHE_MAX", env=env)


def output_is_the_input(h):
    d = h.fresh("output_is_the_input")
    h.copy("small.h5", d)
    before = open(os.path.join(d, "small.h5"), "rb").read()
    h.refused(["export", "small.h5", "--format", "astm", "-o", "small.h5", "--overwrite"], d, 2,
              "small.h5")
    h.refused(["export", "small.h5", "--format", "astm", "-o", "./small.h5", "--overwrite"], d,
              2, "small.h5")
    for i in range(2):
        h.copy(f"part{i}.h5", d)
    h.refused(["merge", "part0.h5", "part1.h5", "-o", "part1.h5", "--overwrite"], d, 2,
              "part1.h5")
    assert open(os.path.join(d, "small.h5"), "rb").read() == before


CASES = [astm_without_wavelength, albedo_without_incidences, unit_of_rank_two,
         render_light_not_finite, deep_config, full_disk, shapes_against_axes, file_checksums,
         unit_checksums,
         impossible_values, missing_case_group, grazing_beam, absurd_height_map,
         render_all_or_nothing, surface_all_or_nothing, output_is_a_directory, dot_case_names,
         stale_temporaries, names_with_spaces, corrupt_inputs_are_failures,
         memory_asked_up_front, missing_seed, checkpoint_in_use, long_values_cut,
         cli_errors_prefixed, existing_output_is_usage, cache_max_spaces, output_is_the_input]


def main():
    gonio = os.path.abspath(sys.argv[1])
    wanted = sys.argv[2:]
    failed = []
    with tempfile.TemporaryDirectory() as root:
        h = Hostile(gonio, root)
        for case in CASES:
            if wanted and case.__name__ not in wanted:
                continue
            try:
                case(h)
                print(f"ok    {case.__name__}")
            except (Failure, AssertionError) as e:
                failed.append(case.__name__)
                print(f"FAIL  {case.__name__}: {e}")
    print(f"hostile inputs: {len(failed)} failed" + (": " + ", ".join(failed) if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
