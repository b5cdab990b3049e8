#!/usr/bin/python3
"""A contact sheet of renders: rows of images with their file names (or --labels) as captions.

Usage: scripts/contact_sheet.py OUT.png IMAGE.png... [--columns N] [--labels A,B,...]
       [--title TEXT]
Used for docs/renders.md's R19 Fig. 11/12-style sheet (every case with and without multiple
scattering, and their Delta E00). Needs Debian's python3-matplotlib (under /usr/bin/python3).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("images", nargs="+")
    ap.add_argument("--columns", type=int, default=5)
    ap.add_argument("--labels")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    labels = args.labels.split(",") if args.labels else [
        os.path.splitext(os.path.basename(p))[0] for p in args.images]
    if len(labels) != len(args.images):
        raise SystemExit(f"{len(labels)} labels for {len(args.images)} images")
    cols = min(args.columns, len(args.images))
    rows = (len(args.images) + cols - 1) // cols
    first = mpimg.imread(args.images[0])
    aspect = first.shape[0] / first.shape[1]
    fig, axes = plt.subplots(rows, cols, figsize=(2.6 * cols, 2.6 * aspect * rows + 0.4),
                             squeeze=False)
    for k, ax in enumerate(axes.flat):
        ax.axis("off")
        if k < len(args.images):
            ax.imshow(mpimg.imread(args.images[k]))
            ax.set_title(labels[k], fontsize=8)
    if args.title:
        fig.suptitle(args.title, fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(args.out)


if __name__ == "__main__":
    sys.exit(main())
