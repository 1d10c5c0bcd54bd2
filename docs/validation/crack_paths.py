#!/usr/bin/env python3
"""Crack paths of two-hole plate runs, side by side: failed particles in the reference
configuration, from the particle files that t120's harness writes with PDK_PLATE_DUMP
(columns X, Y, ..., eps_p, damage, failed; tests/plate_two_holes_util.h).

    crack_paths.py OUT.png "TITLE=FILE.csv" ... [--field eps_p:0.4 "TITLE=FILE.csv"]

A panel given after --field NAME:VMAX shows that field (0 to VMAX) with the failed particles on
top; the window is the plate (0-50 x 0-100 mm) unless --window X0,X1,Y0,Y1 (mm) comes first.
Panels given after --turn DEG come from a plate turned by DEG degrees in the lattice (about its
centre, 25, 50 mm) and are drawn turned back, in the plate's own frame (--turn 0 ends that).
The files may also be `pdk run`'s <name>_fields.csv (columns "X [<unit>]", ...).
Used for docs/validation/plate_two_holes.md items 11 and 12."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    out, window, field, turn, panels = argv[0], (0, 50, 0, 100), None, 0.0, []
    args = iter(argv[1:])
    for a in args:
        if a == "--window":
            window = tuple(float(v) for v in next(args).split(","))
        elif a == "--turn":
            turn = float(next(args))
        elif a == "--field":
            name, vmax = next(args).split(":")
            field = (name, float(vmax))
        else:
            title, path = a.rsplit("=", 1)
            panels.append((title, path, field, window, turn))
    fig, axs = plt.subplots(1, len(panels), figsize=(2.4 * len(panels), 4.6), squeeze=False)
    for ax, (title, path, fld, win, deg) in zip(axs[0], panels):
        d = np.genfromtxt(path, delimiter=",", names=True)
        names = d.dtype.names  # genfromtxt turns "X [m]" into "X_m"
        cx = next(c for c in names if c == "X" or c.startswith("X_"))
        cy = next(c for c in names if c == "Y" or c.startswith("Y_"))
        th = np.radians(deg)
        dx, dy = d[cx] * 1e3 - 25.0, d[cy] * 1e3 - 50.0
        x = 25.0 + np.cos(th) * dx + np.sin(th) * dy
        y = 50.0 - np.sin(th) * dx + np.cos(th) * dy
        failed = d["failed"] > 0.5
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
