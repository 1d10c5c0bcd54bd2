#!/usr/bin/env python3
"""Crack paths of two-hole plate runs, side by side: failed particles in the reference
configuration, from the particle files that t120's harness writes with PDK_PLATE_DUMP
(columns X, Y, ..., eps_p, damage, failed; tests/plate_two_holes_util.h).

    crack_paths.py OUT.png "TITLE=FILE.csv" ... [--field eps_p:0.4 "TITLE=FILE.csv"]

A panel given after --field NAME:VMAX shows that field (0 to VMAX) with the failed particles on
top; the window is the plate (0-50 x 0-100 mm) unless --window X0,X1,Y0,Y1 (mm) comes first.
Used for docs/validation/plate_two_holes.md items 11 and 12."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    out, window, field, panels = argv[0], (0, 50, 0, 100), None, []
    args = iter(argv[1:])
    for a in args:
        if a == "--window":
            window = tuple(float(v) for v in next(args).split(","))
        elif a == "--field":
            name, vmax = next(args).split(":")
            field = (name, float(vmax))
        else:
            title, path = a.rsplit("=", 1)
            panels.append((title, path, field, window))
    fig, axs = plt.subplots(1, len(panels), figsize=(2.4 * len(panels), 4.6), squeeze=False)
    for ax, (title, path, fld, win) in zip(axs[0], panels):
        d = np.genfromtxt(path, delimiter=",", names=True)
        x, y, failed = d["X"] * 1e3, d["Y"] * 1e3, d["failed"] > 0.5
        zoom = (win[1] - win[0]) < 40
        if fld:
            sc = ax.scatter(x, y, s=6 if zoom else 0.4, c=d[fld[0]], lw=0, vmin=0, vmax=fld[1])
            fig.colorbar(sc, ax=ax, shrink=0.6, label=fld[0])
        else:
            ax.scatter(x, y, s=3000.0 / len(x), c="0.85", lw=0)
        ax.scatter(x[failed], y[failed], s=6 if zoom else 0.8, c="r", lw=0)
        ax.set_xlim(win[0], win[1])
        ax.set_ylim(win[2], win[3])
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=7)
        ax.tick_params(labelsize=6)
        ax.set_xlabel("X [mm]", fontsize=6)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1:])
