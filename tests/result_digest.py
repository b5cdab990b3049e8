#!/usr/bin/python3
"""A fingerprint of a gonio result file's numbers, to show that a refactor did not move them.

Usage: result_digest.py RESULT.h5 > digest.json          (write a digest)
       result_digest.py RESULT.h5 --against digest.json  (compare; exit 1 if anything moved)

Per case it keeps every per-incidence quantity whole (albedos, their errors, the ledger) and, of
every per-cell map, the sum, an index-weighted sum (so a permutation of cells shows) and the
maximum. It reads file formats 1 and 2 alike: only dataset names are used, and those are the same.
Values are compared to 1e-9 relative (round-off of a reordered sum, not Monte Carlo noise), standard
errors to 1e-6: they come from squared batch means, whose round-off (which differs between CPUs and
their libm code paths, by an ulp) is amplified by (mean / error)^2, up to 1e8 for an albedo near 1
known to 1e-4.
"""
import json
import sys

import h5py
import numpy as np

PER_INCIDENCE = ["l1_albedo", "l2_albedo", "l2plus_albedo", "linf_albedo", "model_l1_albedo",
                 "ledger_absorbed", "ledger_capped", "ledger_lost", "rays", "segments"]
PER_CELL = ["brdf", "brdf_l1", "brdf_l2plus", "brdf_linf", "model_l1", "l1_ratio"]
TOLERANCE = 1e-9
STDERR_TOLERANCE = 1e-6


def digest(path):
    out = {}
    with h5py.File(path, "r") as f:
        for name, group in f.items():
            if not isinstance(group, h5py.Group):
                continue
            case = {}
            for key in PER_INCIDENCE:
                for k in (key, key + "_stderr"):
                    if k in group:
                        case[k] = np.asarray(group[k][...], dtype=float).ravel().tolist()
            for key in PER_CELL:
                for k in (key, key + "_stderr"):
                    if k in group:
                        v = np.asarray(group[k][...], dtype=float).ravel()
                        w = np.arange(1, v.size + 1, dtype=float) / v.size
                        case[k] = [float(v.sum()), float((v * w).sum()), float(v.max())]
            out[name] = case
    return out


def compare(now, ref):
    moved = 0
    for case, quantities in ref.items():
        if case not in now:
            print(f"missing case {case}")
            moved += 1
            continue
        for key, values in quantities.items():
            got = now[case].get(key)
            if got is None or len(got) != len(values):
                print(f"{case}/{key}: missing or of another size")
                moved += 1
                continue
            a, b = np.asarray(got), np.asarray(values)
            scale = np.maximum(np.abs(b), 1e-300)
            worst = float(np.max(np.abs(a - b) / scale)) if a.size else 0.0
            if worst > (STDERR_TOLERANCE if key.endswith("_stderr") else TOLERANCE):
                print(f"{case}/{key}: moved by {worst:.3e} (relative)")
                moved += 1
    return moved


def main():
    path = sys.argv[1]
    now = digest(path)
    if len(sys.argv) == 4 and sys.argv[2] == "--against":
        with open(sys.argv[3]) as f:
            ref = json.load(f)
        moved = compare(now, ref)
        checked = sum(len(q) for q in ref.values())
        print(f"digest: {checked - moved} passed, {moved} failed")
        sys.exit(1 if moved else 0)
    json.dump(now, sys.stdout, indent=0)
    print()


if __name__ == "__main__":
    main()
