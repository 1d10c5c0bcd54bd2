#!/usr/bin/python3
"""Johnson-Cook damage of the finite-element reference, and a comparison with a pdk particle dump.

Reads the CalculiX .dat written by a ccx_input.py job (Cauchy stress and equivalent plastic strain
at every integration point, per printed increment) and integrates, at each integration point,

    D = sum over increments of  d eps_p / eps_f(eta),  eps_f = D1 + D2 exp(D3 eta),

with eta = sigma_m / sigma_vm at the end of the increment, as pdk does per step (kernels/ref/jc.c;
D1 0.05, D2 3.44, D3 -2.12, D_c 0.3; rate and temperature terms off). The damage does not act
on the stress here, as pdk's default coupling: none, so up to the first failure the two models
are the same continuum problem.

Prints: the first elements to reach D_c (grip displacement, region, centroid, eta, eps_p); per
printed increment the largest D in the ligament between the holes ("inner": between the two
centres along their line and within one radius of it, as tests/plate_two_holes_util.h) and
elsewhere ("outer"), with eps_p and eta there and the largest eps_p of the region; the reaction.
With --pdk CSV --at U: the element means next to pdk's particle values along the lower hole's
horizontal diameter, along the line between the hole centres and around the lower hole's edge, at
grip displacement U mm (CSV from
PDK_PLATE_DUMP/PDK_PLATE_DUMP_AT of tests/t120, columns X,Y,x,y,eps_p,damage,...,eta,...).

  damage.py job.dat job.inp --u-per-time U_MAX     (static job: step time 1 = U_MAX mm)
  damage.py job.dat job.inp --u-per-time 2000      (dynamic job: 2000 mm/s)
"""
import argparse
import numpy as np

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument('dat')
ap.add_argument('inp')
ap.add_argument('--u-per-time', type=float, required=True)
ap.add_argument('--pdk', help='pdk particle dump (csv) to compare with')
ap.add_argument('--at', type=float, help='grip displacement [mm] of the comparison')
ap.add_argument('--centres', type=float, nargs=4, default=[17.5, 42.5, 32.5, 57.5],
                metavar=('X1', 'Y1', 'X2', 'Y2'), help='hole centres [mm] (plate.geo x1 ... y2)')
a = ap.parse_args()
D1, D2, D3, DC = 0.05, 3.44, -2.12, 0.3
C1, C2, R = np.array(a.centres[:2]), np.array(a.centres[2:]), 5.0

nodes, cent, mode = {}, {}, None
for line in open(a.inp):
    if line.startswith('*'):
        up = line.upper()
        mode = 'n' if up.startswith('*NODE,') else ('e' if up.startswith('*ELEMENT,') else None)
        continue
    p = line.split(',')
    if mode == 'n':
        nodes[int(p[0])] = (float(p[1]), float(p[2]))
    elif mode == 'e':
        q = [int(x) for x in p if x.strip()]
        cent[q[0]] = np.mean([nodes[n] for n in q[1:5]], axis=0)


def inner(c):
    u = C2 - C1
    t = np.dot(c - C1, u) / np.dot(u, u)
    dist = abs(u[0] * (c[1] - C1[1]) - u[1] * (c[0] - C1[0])) / np.linalg.norm(u)
    return 0.0 < t < 1.0 and dist <= R


def blocks(f):
    kind, t, rows = None, None, []
    for line in f:
        if 'for set' in line:
            if kind:
                yield kind, t, rows
            kind = 'S' if 'stresses' in line else ('PE' if 'plastic' in line else 'F')
            t, rows = float(line.split()[-1]), []
        elif line.strip():
            rows.append(line)
    if kind:
        yield kind, t, rows


D = pe_prev = S = snap = masks = None
first, hist, force = {}, [], []
with open(a.dat) as f:
    for kind, t, rows in blocks(f):
        u = t * a.u_per_time
        if kind == 'F':
            force.append((u, abs(float(rows[0].split()[1]))))
            continue
        arr = np.array([[float(x) for x in r.split()] for r in rows])
        if kind == 'S':
            S = arr
            continue
        el, pe = arr[:, 0].astype(int), arr[:, 2]
        if S is None or len(S) != len(pe):
            raise SystemExit('%s: stress and plastic strain blocks do not match at t = %g' % (a.dat, t))
        sm = (S[:, 2] + S[:, 3] + S[:, 4]) / 3.0
        dev = S[:, 2:5] - sm[:, None]
        svm = np.sqrt(1.5 * (np.sum(dev ** 2, axis=1) + 2.0 * S[:, 5] ** 2 + 2.0 * S[:, 6] ** 2 +
                             2.0 * S[:, 7] ** 2))
        eta = np.where(svm > 0.0, sm / np.maximum(svm, 1e-300), 0.0)
        if D is None:
            D, pe_prev = np.zeros_like(pe), np.zeros_like(pe)
            masks = {r: np.array([inner(cent[e]) == (r == 'inner') for e in el]) for r in ('inner', 'outer')}
        D += (pe - pe_prev) / (D1 + D2 * np.exp(D3 * eta))
        pe_prev = pe.copy()
        for k in np.nonzero(D >= DC)[0]:
            if el[k] not in first:
                first[el[k]] = (u, eta[k], pe[k], len(first))
        row = [u]
        for r in ('inner', 'outer'):
            m = masks[r]
            k = np.argmax(np.where(m, D, -1.0))
            row += [D[k], pe[k], eta[k], pe[m].max()]
        hist.append(row)
        if a.at is not None and snap is None and u >= a.at - 1e-9:
            snap = (u, el.copy(), D.copy(), pe.copy(), eta.copy())

print('# first elements to reach D_c = %g: grip u [mm], region, centroid x y [mm], eta, eps_p' % DC)
for e, (u, et, p, _) in sorted(first.items(), key=lambda kv: kv[1][3])[:16]:
    c = cent[e]
    print('%.3f %-5s %6.2f %6.2f %5.2f %.3f' % (u, 'inner' if inner(c) else 'outer', c[0], c[1], et, p))
for r in ('inner', 'outer'):
    us = [v[0] for e, v in first.items() if inner(cent[e]) == (r == 'inner')]
    print('# first D_c %s: %s' % (r, ('u = %.3f mm' % min(us)) if us else 'not reached'))
print('# grip u | inner: max D, eps_p and eta there, max eps_p | outer: the same')
for row in hist[::max(1, len(hist) // 30)] + ([hist[-1]] if len(hist) > 30 else []):
    print('%.3f | %.3f %.3f %5.2f %.3f | %.3f %.3f %5.2f %.3f' % tuple(row))
print('# reaction [kN per mm of thickness] at grip u [mm]:',
      ' '.join('%.2f:%.2f' % (u, fy / 1e3) for u, fy in force[::max(1, len(force) // 12)]))

if a.pdk and snap is not None:
    u, el, Ds, pes, etas = snap
    ue, inv = np.unique(el, return_inverse=True)
    cnt = np.bincount(inv)
    Dm, pm, em = (np.bincount(inv, v) / cnt for v in (Ds, pes, etas))
    C = np.array([cent[e] for e in ue])
    P = np.loadtxt(a.pdk, delimiter=',', skiprows=1)
    X, Y = P[:, 0] * 1e3, P[:, 1] * 1e3

    def show(title, sel, coord):
        print('# %s, grip u %.3f mm: position | pdk eps_p eta D | FE (nearest element) eps_p eta D'
              % (title, u))
        for k in sorted(np.nonzero(sel)[0], key=lambda k: (coord(X[k], Y[k]), X[k], Y[k])):
            j = np.argmin(np.hypot(C[:, 0] - X[k], C[:, 1] - Y[k]))
            if np.hypot(C[j, 0] - X[k], C[j, 1] - Y[k]) > 1.0:
                continue
            print('%6.2f | %.3f %5.2f %.3f | %.3f %5.2f %.3f' %
                  (coord(X[k], Y[k]), P[k, 4], P[k, 9], P[k, 5], pm[j], em[j], Dm[j]))

    row = np.min(np.abs(Y - C1[1]))
    show('y = %g mm (lower hole, horizontal diameter), x [mm]' % C1[1],
         np.abs(Y - C1[1]) <= row + 1e-9, lambda x, y: x)
    d = (C2 - C1) / np.linalg.norm(C2 - C1)
    along = (X - C1[0]) * d[0] + (Y - C1[1]) * d[1]
    perp = np.abs((X - C1[0]) * d[1] - (Y - C1[1]) * d[0])
    h = np.min(np.diff(np.unique(np.round(X, 9))))
    rad = np.hypot(X - C1[0], Y - C1[1])
    show('lower hole, the particles within one spacing of its edge, angle from +x [degrees]',
         rad < R + h + 1e-9, lambda x, y: np.degrees(np.arctan2(y - C1[1], x - C1[0])))
    show('line between the centres, distance from the lower centre [mm]',
         (perp < 0.5 * h + 1e-9) & (along > R) & (along < np.linalg.norm(C2 - C1) - R),
         lambda x, y: (x - C1[0]) * d[0] + (y - C1[1]) * d[1])
