#!/usr/bin/python3
"""Two gonio result files hold the same numbers, bit for bit: every numeric dataset but the
timings (*_seconds), optionally only those whose name starts with a prefix.

Usage: compare_results.py A.h5 B.h5 [--prefix model_]     (exit 1 if anything differs)
"""
import sys

import h5py
import numpy as np


def datasets(path, prefix=""):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            leaf = name.split("/")[-1]
            if isinstance(obj, h5py.Dataset) and not name.endswith("_seconds") and \
                    leaf.startswith(prefix):
                out[name] = obj[...]
        f.visititems(visit)
    return out


def same(a, b, what, prefix=""):
    """Asserts that a and b hold the same datasets, bit for bit; prints how many."""
    da, db = datasets(a, prefix), datasets(b, prefix)
    assert da and da.keys() == db.keys(), f"{what}: datasets differ: {set(da) ^ set(db)}"
    for k in da:
        x, y = da[k], db[k]
        assert x.shape == y.shape and x.dtype == y.dtype, f"{what}: {k} differs in shape"
        assert x.tobytes() == y.tobytes(), \
            f"{what}: {k} differs in {np.count_nonzero(x != y)} values"
    print(f"{what}: {len(da)} datasets equal bit for bit")


if __name__ == "__main__":
    args = sys.argv[1:]
    prefix = ""
    if "--prefix" in args:
        i = args.index("--prefix")
        prefix = args[i + 1]
        del args[i:i + 2]
    try:
        same(args[0], args[1], f"{args[0]} against {args[1]}", prefix)
    except AssertionError as e:
        print(e)
        sys.exit(1)
