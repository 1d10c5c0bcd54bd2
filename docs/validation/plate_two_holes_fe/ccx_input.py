#!/usr/bin/python3
"""CalculiX input of the two-hole plate (scenes/plate_two_holes.yaml) from a gmsh mesh.

Plane strain, 1 mm thick, units mm, N, MPa, tonne, s. Quadratic quadrilaterals with reduced
integration (gmsh's CPS8 become CPE8R). Finite-strain J2 plasticity (NLGEOM) with the V-JC
steel's Johnson-Cook hardening curve sigma_y = 792 + 510 eps_p^0.26 MPa as a table; no damage
(damage.py integrates the Johnson-Cook damage from the printed stresses afterwards). Bottom edge
(y = 3) clamped, top edge (y = 97) held in x and pulled in y.

  static:   ccx_input.py mesh.inp job.inp --static U_MAX --increment DU
            (grip displacement U_MAX mm reached in fixed increments of DU mm)
  dynamic:  ccx_input.py mesh.inp job.inp --dynamic T_END --increment DT
            (grip pulled at 2000 mm/s from rest, implicit dynamics with automatic steps <= DT)

Printed to the .dat file: the bottom reaction (N per mm of thickness) and, for the elements within
12 mm of a hole centre, the Cauchy stress and the equivalent plastic strain at every integration
point of every increment (every second one in dynamics).
"""
import argparse
import numpy as np

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument('mesh')
ap.add_argument('out')
g = ap.add_mutually_exclusive_group(required=True)
g.add_argument('--static', type=float, metavar='U_MAX')
g.add_argument('--dynamic', type=float, metavar='T_END')
ap.add_argument('--increment', type=float, required=True)
ap.add_argument('--centres', type=float, nargs=4, default=[17.5, 42.5, 32.5, 57.5],
                metavar=('X1', 'Y1', 'X2', 'Y2'), help='hole centres [mm] (plate.geo x1 ... y2)')
a = ap.parse_args()

nodes, elems, mode = {}, [], None
for line in open(a.mesh):
    if line.startswith('*'):
        up = line.upper()
        mode = 'n' if up.startswith('*NODE') else ('e' if 'TYPE=CPS8' in up else None)
        continue
    if mode == 'n':
        p = line.split(',')
        nodes[int(p[0])] = (float(p[1]), float(p[2]))
    elif mode == 'e':
        elems.append([int(x) for x in line.replace(' ', '').rstrip(',\n').split(',')])
if not elems:
    raise SystemExit('%s: no CPS8 elements (mesh with plate.geo, second order, recombined)' % a.mesh)
used = sorted({n for e in elems for n in e[1:]})
centres = (np.array(a.centres[:2]), np.array(a.centres[2:]))


def write_set(f, kind, name, ids):
    f.write('*%s, %s=%s\n' % (kind, kind, name))
    for i in range(0, len(ids), 10):
        f.write(', '.join(map(str, ids[i:i + 10])) + ',\n')


with open(a.out, 'w') as f:
    f.write('*NODE, NSET=NALL\n')
    for n in used:
        f.write('%d, %.10g, %.10g\n' % (n, nodes[n][0], nodes[n][1]))
    f.write('*ELEMENT, TYPE=CPE8R, ELSET=EALL\n')
    for e in elems:
        f.write(', '.join(map(str, e)) + '\n')
    write_set(f, 'NSET', 'NBOT', [n for n in used if abs(nodes[n][1] - 3.0) < 1e-6])
    write_set(f, 'NSET', 'NTOP', [n for n in used if abs(nodes[n][1] - 97.0) < 1e-6])
    near = []
    for e in elems:
        c = np.mean([nodes[n] for n in e[1:5]], axis=0)
        if min(np.linalg.norm(c - z) for z in centres) < 12.0:
            near.append(e[0])
    write_set(f, 'ELSET', 'EOUT', near)
    f.write('*MATERIAL, NAME=STEEL\n*ELASTIC\n200000., 0.29\n*DENSITY\n7.83E-9\n*PLASTIC\n')
    for ep in [0.0] + list(np.geomspace(1e-4, 3.0, 60)):
        f.write('%.8g, %.8g\n' % (792.0 + 510.0 * ep ** 0.26, ep))
    f.write('*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n1.\n')
    every = ''
    if a.dynamic is not None:
        every = ', FREQUENCY=2'
        f.write('*AMPLITUDE, NAME=PULL\n0., 0., 1., 2000.\n')  # u = 2000 mm/s x t
        f.write('*STEP, NLGEOM, INC=100000\n*DYNAMIC\n%g, %g, 1e-10, %g\n' %
                (a.increment, a.dynamic, a.increment))
        f.write('*BOUNDARY\nNBOT, 1, 2\nNTOP, 1, 1\n*BOUNDARY, AMPLITUDE=PULL\nNTOP, 2, 2, 1.\n')
    else:
        frac = a.increment / a.static
        f.write('*STEP, NLGEOM, INC=10000\n*STATIC\n%.10g, 1.0, 1e-7, %.10g\n' % (frac, frac))
        f.write('*BOUNDARY\nNBOT, 1, 2\nNTOP, 1, 1\nNTOP, 2, 2, %g\n' % a.static)
    f.write('*NODE PRINT, NSET=NBOT, TOTALS=ONLY%s\nRF\n' % every)
    f.write('*EL PRINT, ELSET=EOUT%s\nS, PEEQ\n' % every)
    f.write('*END STEP\n')
print('%s: %d nodes, %d elements, %d printed' % (a.out, len(used), len(elems), len(near)))
