#!/usr/bin/python3
"""Reaction against grip displacement: finite-element runs (CalculiX .dat of ccx_input.py jobs)
and pdk runs (force traces of tests/t120, PDK_PLATE_TRACE=PREFIX writes PREFIX_tl_force.csv with
time, bottom force). The reference has no failure, so it is one only up to its first D = D_c
(u = 1.34 mm); pdk's curves go on through the failure. Writes a PNG.

  plot_force.py OUT.png --fe LABEL JOB.dat U_PER_TIME [--fe ...] --pdk LABEL TRACE.csv [--pdk ...]
                [--speed 2000] [--umax 1.6]

U_PER_TIME: grip displacement [mm] per unit of step time (static: U_MAX; dynamic: 2000).
--speed: pdk's grip speed [mm/s] (the scene's 2 m/s); --umax: the axis limit [mm].
"""
import argparse
import numpy as np
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument('out')
ap.add_argument('--fe', nargs=3, action='append', default=[], metavar=('LABEL', 'DAT', 'U_PER_TIME'))
ap.add_argument('--pdk', nargs=2, action='append', default=[], metavar=('LABEL', 'CSV'))
ap.add_argument('--speed', type=float, default=2000.0)
ap.add_argument('--umax', type=float, default=1.6)
a = ap.parse_args()


def fe_curve(dat, per):
    lines = open(dat).read().splitlines()
    u, f = [0.0], [0.0]
    for i, line in enumerate(lines):
        if 'total force' in line:
            u.append(float(line.split()[-1]) * per)
            f.append(abs(float(lines[i + 2].split()[1])) / 1e3)
    return np.array(u), np.array(f)


fig, ax = plt.subplots(figsize=(7, 4.5))
for label, dat, per in a.fe:
    u, f = fe_curve(dat, float(per))
    ax.plot(u, f, '-', lw=2.2, label='finite elements, ' + label)
for label, csv in a.pdk:
    t, f = np.loadtxt(csv, delimiter=',', unpack=True)
    u = t * a.speed
    keep = u <= a.umax
    ax.plot(u[keep], f[keep] / 1e3, '--', lw=1.2, label='pdk, ' + label)
ax.set_xlim(0, a.umax)
ax.set_xlabel('grip displacement [mm]')
ax.set_ylabel('bottom reaction [kN per mm of thickness]')
ax.set_title('Two-hole plate: pdk against the finite-element reference\n(the reference has no failure: it stops being one at D = D_c, u = 1.34 mm)', fontsize=10)
ax.grid(alpha=0.3)
ax.legend(fontsize=8, loc='lower right')
fig.tight_layout()
fig.savefig(a.out, dpi=110)
print('plot_force.py: wrote', a.out)
