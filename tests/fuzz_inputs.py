#!/usr/bin/python3
"""A fuzzer of everything gonio reads: the shipped configs, a result file, part files, a
checkpoint, a height map and third-party measured maps (X3P, SDF, GSF), each mutated with a fixed seed (bytes flipped, truncated,
overwritten; values made NaN, negative or out of range; datasets and attributes removed or
reshaped; keys, tables and numbers of a config garbled) and handed to the command that reads it.

A case fails on
  - a crash: a signal, a sanitizer report, `terminate called`, a failed GONIO_CHECK;
  - a hang: no answer within the timeout;
  - exit 0 on a corrupted input with an output other than the pristine input's (a mutation that
    changes nothing gonio reads is not a corruption: the output must then be the same);
  - an exit code outside the contract (0, 1, 2, 3), or a failure message that is not one
    `gonio: error:` (or `gonio export: refused:`) line;
  - a stray file: a temporary, a half-written output, a checkpoint a failure left.

Usage: fuzz_inputs.py GONIO [--cases N] [--seed S] [--timeout SECONDS] [--keep DIR]
(CTest runs the quick mode: a few hundred cases, under about three minutes.)
"""
import argparse
import os
import random
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from compare_results import datasets  # noqa: E402

SMALL = """seed = 3
[beam]
theta_i = { start = 0, stop = 80, step = 10 }
[sensor]
cells = 145
[surface]
size = 32
iterations = 5
[trace]
rays = 2048
batches = 4
[[case]]
name = "gold"
ndf = { type = "beckmann", alpha = 0.5 }
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 550, 450] }
"""
# Keys that keep a mutated config's run small (each only where the config may set it).
CAPS = ["sensor.cells=145", "trace.rays=256", "trace.batches=2"]
SURFACE_CAPS = ["surface.size=16", "surface.iterations=2", "surface.realisations=1"]
CRASH_MARKS = ("AddressSanitizer", "LeakSanitizer", "runtime error:", "terminate called",
               "internal error", "Segmentation fault")
STYLE = ("gonio: error:", "gonio export: refused:")


class Fuzzer:
    def __init__(self, gonio, work, rng, timeout):
        self.gonio, self.work, self.rng, self.timeout = gonio, work, rng, timeout
        self.fixtures = os.path.join(work, "fixtures")
        os.makedirs(self.fixtures)
        os.symlink(os.path.join(ROOT, "data"), os.path.join(work, "data"))
        with open(os.path.join(self.fixtures, "small.toml"), "w") as f:
            f.write(SMALL)
        run = lambda args: self.must(args, self.fixtures)
        run(["run", "small.toml", "-o", "small.h5", "-q", "--no-cache"])
        for i in range(2):
            run(["run", "small.toml", "-o", f"part{i}.h5", "-q", "--no-cache", "--shard", f"{i}/2"])
        run(["merge", "part0.h5", "part1.h5", "-o", "merged.h5", "-q"])
        run(["surface", "small.toml", "-o", "map.exr", "-q", "--no-cache"])
        for name in os.listdir(self.fixtures):  # the surface's companions are not inputs
            if name.startswith("map_"):
                os.remove(os.path.join(self.fixtures, name))
        with open(os.path.join(self.fixtures, "input.toml"), "w") as f:
            f.write(SMALL.replace("[surface]\nsize = 32\niterations = 5",
                                  "[surface]\ninput = \"map.exr\""))
        run(["run", "input.toml", "-o", "input.h5", "-q", "--no-cache"])
        self.configs = sorted(os.path.join(ROOT, "configs", n)
                              for n in os.listdir(os.path.join(ROOT, "configs")))
        self.configs.append(os.path.join(self.fixtures, "small.toml"))
        self.reference = {}  # (command, input) -> the pristine input's output
        self.counts = {}
        self.failures = []

    def must(self, args, cwd):
        r = subprocess.run([self.gonio] + args, cwd=cwd, capture_output=True, text=True)
        if r.returncode != 0:
            raise SystemExit(f"fixture: gonio {' '.join(args)} failed: {r.stderr}")

    def call(self, args, cwd):
        try:
            r = subprocess.run([self.gonio] + args, cwd=cwd, capture_output=True, text=True,
                               timeout=self.timeout)
            return r.returncode, r.stdout, r.stderr
        except subprocess.TimeoutExpired:
            return None, "", ""

    # --- mutations -------------------------------------------------------------------------

    def mutate_bytes(self, path):
        data = bytearray(open(path, "rb").read())
        how = self.rng.choice(["flip", "flip", "flip", "truncate", "block", "zero"])
        size = len(data)
        if how == "flip":
            spots = [self.rng.randrange(size) for _ in range(self.rng.choice([1, 1, 2, 8, 64]))]
            for at in spots:
                data[at] ^= 1 << self.rng.randrange(8)
            where = ",".join(str(at) for at in spots[:4]) + (",..." if len(spots) > 4 else "")
        elif how == "truncate":
            data = data[:self.rng.randrange(size)]
            where = str(len(data))
        else:
            at, n = self.rng.randrange(size), self.rng.choice([4, 64, 512])
            for k in range(at, min(size, at + n)):
                data[k] = 0 if how == "zero" else self.rng.randrange(256)
            where = f"{at}+{n}"
        open(path, "wb").write(bytes(data))
        return f"bytes {how} at {where} of {size}"

    def mutate_h5(self, path):
        """A change of meaning through HDF5 itself: values, shapes, datasets, attributes. (Half
        the time the file's own checksum is blanked first, as in an older file, so that the
        checks of the content behind it are reached too.)"""
        if self.rng.random() < 0.5:
            with open(path, "r+b") as f:
                if f.read(16) == b"gonio file crc32":
                    f.seek(0)
                    f.write(bytes(32))
        with h5py.File(path, "a") as f:
            names = []
            f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
            attrs = [(None, k) for k in f.attrs]
            for n in f:
                if isinstance(f[n], h5py.Group):
                    attrs += [(n, k) for k in f[n].attrs]
            how = self.rng.choice(["nan", "negative", "huge", "delete", "reshape", "axis",
                                   "attribute", "attribute_type"])
            if how in ("attribute", "attribute_type") and attrs:
                group, key = self.rng.choice(attrs)
                owner = f if group is None else f[group]
                if how == "attribute":
                    del owner.attrs[key]
                else:
                    owner.attrs[key] = np.array([[1.5, -2.0]])
                return f"h5 {how} {group}/{key}"
            name = self.rng.choice(names)
            d = f[name]
            if how in ("nan", "negative", "huge") and d.dtype.kind == "f" and d.size:
                v = d[...]
                flat = v.reshape(-1)
                flat[self.rng.randrange(flat.size)] = {"nan": np.nan, "negative": -1.0,
                                                      "huge": 1e300}[how]
                d[...] = v
                return f"h5 {how} {name}"
            parent = f[os.path.dirname(name)] if "/" in name else f
            leaf = os.path.basename(name)
            if how == "axis" and d.ndim == 1 and d.dtype.kind == "f":
                v = d[...]
                del parent[leaf]
                parent.create_dataset(leaf, data=v[::-1].copy() if v.size > 1 else v * 2 + 100)
                return f"h5 axis {name}"
            if how == "reshape":
                v = d[...]
                del parent[leaf]
                parent.create_dataset(leaf, data=v.reshape(-1)[: max(1, v.size // 2)])
                return f"h5 reshape {name}"
            del parent[leaf]
            return f"h5 delete {name}"

    def mutate_config(self, text):
        lines = text.split("\n")
        how = self.rng.choice(["number", "number", "string", "line", "bytes", "deep", "key",
                               "table"])
        if how == "number":
            spots = [i for i, l in enumerate(lines) if "=" in l and any(c.isdigit() for c in l)]
            if spots:
                i = self.rng.choice(spots)
                key, _, value = lines[i].partition("=")
                lines[i] = key + "= " + self.rng.choice(
                    ["nan", "inf", "-inf", "-1", "0", "1e308", "-1e308", "9223372036854775807",
                     "1e-320", "[]", "[1e9, -5]", "{ start = 0, stop = 1e9, step = 1e-9 }",
                     "\"x\"", "true", "89.99999999999", "1e7"])
        elif how == "string":
            spots = [i for i, l in enumerate(lines) if '"' in l]
            if spots:
                i = self.rng.choice(spots)
                a, b = lines[i].find('"'), lines[i].rfind('"')
                lines[i] = lines[i][:a + 1] + self.rng.choice(
                    ["", ".", "..", "/etc/passwd", "a/b", "x" * 5000, "é\u0000x", "../" * 40,
                     "nonexistent.exr"]) + lines[i][b:]
        elif how == "line":
            if len(lines) > 1:
                i = self.rng.randrange(len(lines))
                if self.rng.random() < 0.5:
                    del lines[i]
                else:
                    lines.insert(i, lines[self.rng.randrange(len(lines))])
        elif how == "deep":
            lines.append("[" + ".".join(["t"] * self.rng.choice([65, 5000])) + "]")
        elif how == "key":
            lines.insert(self.rng.randrange(len(lines) + 1),
                         self.rng.choice(["x = 1", "ndf.alpha = 2", "[case]", "[[case]]",
                                          "k" * 100000 + " = 1", "[sensor]\ncells = -3"]))
        elif how == "table":
            lines.insert(self.rng.randrange(len(lines) + 1),
                         "[" + self.rng.choice(["beam", "trace", "surface", "model", "ndf",
                                                "material", "spectrum"]) + "]")
        text = "\n".join(lines)
        if how == "bytes":
            b = bytearray(text.encode())
            for _ in range(self.rng.choice([1, 3, 20])):
                b[self.rng.randrange(len(b))] = self.rng.randrange(256)
            text = b.decode("utf-8", "replace")
        return text, "config " + how

    # --- cases -------------------------------------------------------------------------------

    def case_dir(self, k):
        d = os.path.join(self.work, "cases", str(k))
        os.makedirs(d)
        return d

    def check(self, kind, what, args, d, inputs, outputs, compare):
        """Runs the command and judges it (see the module's description)."""
        before = set(os.listdir(d))
        code, out, err = self.call(args, d)
        problems = []
        if code is None:
            problems.append(f"hang (no answer in {self.timeout} s)")
        elif code < 0 or any(m in err for m in CRASH_MARKS):
            problems.append(f"crash (exit {code}): {err[-1500:]}")
        elif code not in (0, 1, 2, 3):
            problems.append(f"exit {code} is outside the contract: {err[-500:]}")
        elif code != 0:
            errors = [l for l in err.strip().split("\n") if not l.startswith("gonio: warning:")]
            if len(errors) != 1 or not errors[0].startswith(STYLE):
                problems.append(f"not one gonio error line: {err[-500:]!r}")
        now = set(os.listdir(d))
        expected = before | (set(outputs) if code == 0 else set())
        stray = sorted((now - expected) | {n for n in now if ".tmp-" in n})
        if stray:
            problems.append(f"left behind: {stray}")
        if code == 0 and not problems:
            differs = compare(out)
            if differs:
                problems.append(f"exit 0 on a corrupted input, and {differs}")
        outcome = "failed" if problems else ("accepted" if code == 0 else f"exit {code}")
        self.counts[(kind, outcome)] = self.counts.get((kind, outcome), 0) + 1
        if problems:
            self.failures.append((kind, what, " ".join(args), problems, d))

    def same_output(self, key, produce):
        """An oracle: the command's output equals the pristine input's."""
        def compare(out):
            value = produce(out)
            if key not in self.reference:
                return ""  # (the pristine reference is taken first, below)
            return "" if value == self.reference[key] else "its output differs from the " \
                                                           "pristine input's"
        return compare

    def reference_of(self, key, args, cwd, produce):
        if key in self.reference:
            return
        code, out, err = self.call(args, cwd)
        if code != 0:
            raise SystemExit(f"reference: gonio {' '.join(args)} failed: {err}")
        self.reference[key] = produce(out)

    def config_case(self, k):
        d = self.case_dir(k)
        source = self.rng.choice(self.configs)
        text, what = self.mutate_config(open(source).read())
        os.symlink(os.path.join(self.work, "data"), os.path.join(d, "data"))
        os.makedirs(os.path.join(d, "configs"))
        cfg = os.path.join("configs", "x.toml")
        with open(os.path.join(d, cfg), "w", encoding="utf-8", errors="replace") as f:
            f.write(text)
        caps = []
        for c in CAPS:
            caps += ["--set", c]
        if "input" not in text:
            for c in SURFACE_CAPS:
                caps += ["--set", c]
        if self.rng.random() < 0.6:
            args = ["ndf", cfg, "--set", "sensor.cells=145"]
            outputs = []
        else:
            args = ["run", cfg, "-o", "out.h5", "-q", "--no-cache"] + caps
            outputs = ["out.h5"]
        # A mutated config may be another valid config: exit 0 is then right, whatever it says.
        self.check("config", f"{os.path.basename(source)}: {what}", args, d, [cfg], outputs,
                   lambda out: "")

    RESULT_COMMANDS = {
        "info": (["info", "r.h5"], []),
        "compare": (["compare", "r.h5"], []),
        "render": (["render", "r.h5", "-o", "o.png", "--spp", "1", "--size", "8x8", "-q"],
                   ["o.png", "o.exr"]),
    }

    @staticmethod
    def output_of(d, outputs, out):
        """What a command produced: its last output file's bytes, or its standard output."""
        return open(os.path.join(d, outputs[-1]), "rb").read() if outputs else out

    def result_case(self, k):
        d = self.case_dir(k)
        shutil.copy(os.path.join(self.fixtures, "small.h5"), os.path.join(d, "r.h5"))
        command = self.rng.choice(["info", "compare", "astm", "albedo", "rgl", "merl", "render"])
        args, outputs = self.RESULT_COMMANDS.get(
            command, (["export", "r.h5", "--format", command, "-o", "x.out", "-q"], ["x.out"]))
        key = ("result", command)
        if key not in self.reference:
            ref = os.path.join(self.work, "ref_" + command)
            os.makedirs(ref)
            shutil.copy(os.path.join(self.fixtures, "small.h5"), os.path.join(ref, "r.h5"))
            self.reference_of(key, args, ref, lambda out: self.output_of(ref, outputs, out))
        what = self.mutate(os.path.join(d, "r.h5"))
        self.check("result", what, args, d, ["r.h5"], outputs,
                   self.same_output(key, lambda out: self.output_of(d, outputs, out)))

    def mutate(self, path):
        return self.mutate_h5(path) if self.rng.random() < 0.4 else self.mutate_bytes(path)

    def part_case(self, k):
        d = self.case_dir(k)
        for i in range(2):
            shutil.copy(os.path.join(self.fixtures, f"part{i}.h5"), os.path.join(d, f"p{i}.h5"))
        what = self.mutate(os.path.join(d, f"p{self.rng.randrange(2)}.h5"))
        pristine = datasets(os.path.join(self.fixtures, "merged.h5"))
        self.check("part", what, ["merge", "p0.h5", "p1.h5", "-o", "m.h5", "-q"], d,
                   ["p0.h5", "p1.h5"], ["m.h5"],
                   lambda out, d=d: self.same_data(pristine, os.path.join(d, "m.h5")))

    def checkpoint_case(self, k):
        d = self.case_dir(k)
        shutil.copy(os.path.join(self.fixtures, "small.toml"), d)
        shutil.copy(os.path.join(self.fixtures, "part0.h5"), os.path.join(d, "o.h5.checkpoint"))
        what = self.mutate(os.path.join(d, "o.h5.checkpoint"))
        pristine = datasets(os.path.join(self.fixtures, "small.h5"))
        self.check("checkpoint", what,
                   ["run", "small.toml", "-o", "o.h5", "--resume", "-q", "--no-cache"], d,
                   ["small.toml", "o.h5.checkpoint"], ["o.h5"],
                   lambda out, d=d: self.same_data(pristine, os.path.join(d, "o.h5")))

    def map_case(self, k):
        d = self.case_dir(k)
        shutil.copy(os.path.join(self.fixtures, "input.toml"), d)
        shutil.copy(os.path.join(self.fixtures, "map.exr"), d)
        what = self.mutate_bytes(os.path.join(d, "map.exr"))
        pristine = datasets(os.path.join(self.fixtures, "input.h5"))
        self.check("height map", what, ["run", "input.toml", "-o", "o.h5", "-q", "--no-cache"],
                   d, ["input.toml", "map.exr"], ["o.h5"],
                   lambda out, d=d: self.same_data(pristine, os.path.join(d, "o.h5")))

    def measured_case(self, k):
        # A third-party map: X3P carries MD5 checksums, so a corruption it accepts must change
        # nothing gonio reads (the same report); SDF has none, so any outcome but a crash, a
        # hang, a stray file or a malformed error is fine; nor has GSF.
        d = self.case_dir(k)
        name = self.rng.choice(["testing.x3p", "pyramid.x3p", "iso_25178_71_example.sdf",
                               "spm-tools-test.gsf"])
        shutil.copy(os.path.join(ROOT, "tests", "data", "measured", name), d)
        with open(os.path.join(d, "measured.toml"), "w") as f:
            f.write(f'[surface]\ninput = "{name}"\nmax_missing = 0.9\n[ndf]\ntype = "ggx"\n'
                    f'alpha = 0.3\n[[case]]\nname = "m"\n')
        args = ["surface", "measured.toml", "-o", "o.exr", "--no-cache"]
        report = lambda out: [l for l in out.split("\n") if "loaded" not in l and "wrote" not in l]
        outputs = ["o.exr", "o_ndf.exr", "o_ndf.csv", "o_normals.exr"]
        if name.endswith(".x3p"):
            ref = os.path.join(self.work, "measured_" + name)
            if not os.path.exists(ref):
                os.makedirs(ref)
                shutil.copy(os.path.join(ROOT, "tests", "data", "measured", name), ref)
                shutil.copy(os.path.join(d, "measured.toml"), ref)
            self.reference_of(("measured", name), args, ref, report)
            compare = self.same_output(("measured", name), report)
        else:
            compare = lambda out: ""  # noqa: E731
        what = name + " " + self.mutate_bytes(os.path.join(d, name))
        self.check("measured", what, args, d, [name, "measured.toml"], outputs, compare)

    @staticmethod
    def same_data(pristine, path):
        got = datasets(path)
        if got.keys() != pristine.keys():
            return "its datasets differ from the pristine input's"
        for k, v in pristine.items():
            if v.tobytes() != got[k].tobytes():
                return f"its {k} differs from the pristine input's"
        return ""


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("gonio")
    p.add_argument("--cases", type=int, default=240)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--timeout", type=float, default=180)
    p.add_argument("--keep", help="copy the failing cases' directories here")
    a = p.parse_args()
    rng = random.Random(a.seed)
    kinds = ["config"] * 4 + ["result"] * 3 + ["part", "checkpoint", "map", "measured"]
    with tempfile.TemporaryDirectory() as work:
        f = Fuzzer(os.path.abspath(a.gonio), work, rng, a.timeout)
        for k in range(a.cases):
            getattr(f, rng.choice(kinds).replace(" ", "_") + "_case")(k)
            if (k + 1) % 100 == 0:
                print(f"{k + 1} cases, {len(f.failures)} failed", flush=True)
        for kind, what, args, problems, d in f.failures:
            print(f"FAIL {kind} [{what}] gonio {args}:")
            for problem in problems:
                print(f"     {problem[:3000]}")
            if a.keep:
                shutil.copytree(d, os.path.join(a.keep, os.path.basename(d)), symlinks=True)
    print(f"fuzz: {a.cases} cases (seed {a.seed}), {len(f.failures)} failed")
    for (kind, outcome), n in sorted(f.counts.items()):
        print(f"  {kind:11s} {outcome:9s} {n}")
    return 1 if f.failures else 0


if __name__ == "__main__":
    sys.exit(main())
