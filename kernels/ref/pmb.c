/* Reference PMB (prototype microelastic brittle) force kernel, bond-based, as LAMMPS peri/pmb.
 *
 * For every particle i in [i0, i1) and every bond b of i (bond_start[i] <= b < bond_start[i+1],
 * neighbour j = bond_j[b]), with reference bond xi = X_j - X_i and current bond eta = x_j - x_i:
 *
 *   r0 = |xi|,  r = |eta|,  s = (r - r0) / r0                       bond stretch
 *   (evaluated as d = r - r0, q = 1 / (r0 r), s / r = d q: one division per bond)
 *   beta = min(1, (vs_a - r0) * vs_b)                                partial-volume factor
 *   f_i += alive_b * c * s * beta * V_j * eta / r                    (0 when r == 0)
 *   W_i  = sum_b alive_b * c * s^2 * r0 * beta * V_j / 4             strain energy density
 *
 * c is the micromodulus (3-D: 18 K / (pi delta^4); 2-D plane strain: 72 K / (5 pi delta^3), see
 * src/models/model_pmb.c); in a multi-material body (k->c_particle != NULL) bond i-j uses
 * c_ij = 2 c_i c_j / (c_i + c_j), the same from both ends (the product and sum commute). beta is LAMMPS's vfrac_scale: with h = lattice/2, beta = (delta + h - r0)/(2h)
 * when r0 >= delta - h and 1 otherwise, written branch-free as min(1, (vs_a - r0) * vs_b) with
 * vs_a = delta + h, vs_b = 1/(2h); vs_a = +inf turns it off. Each bond is stored from both ends,
 * so f_i is a gather over i's own row: a call writes only entries i in [i0, i1).
 *
 * Bond failure (LAMMPS s0 rule), only when bond_alive != NULL:
 *   - a bond with bond_alive[b] == 0 contributes nothing;
 *   - commit (s0_next != NULL): an intact bond breaks (bond_alive[b] = 0) when s > min(s0[i],
 * s0[j]) (s0 of the previous pass; the force of this pass still includes the bond, as in LAMMPS),
 * and s0_next[i] = max over the bonds intact at entry of (s00 - alpha * s), or DBL_MAX if none; the
 * return value counts the bonds broken. Both ends of a bond compute bit-identical s (eta and xi
 * only change sign), so a bond breaks from both ends in the same pass.
 *   - trial (s0_next == NULL): bond_alive and s0 are only read; returns 0.
 * w (may be NULL): receives W_i for i in [i0, i1).
 *
 * Not included (a deliberate difference from LAMMPS): the short-range contact forces LAMMPS adds
 * between any two particles closer than min(0.9 r0, 1.35 lattice); pdk treats contact separately.
 * LAMMPS also sets |r - r0| < 2.2204e-16 (an absolute length) to 0; pdk does not, so the two differ
 * by round-off near the undeformed state only.
 *
 * Float storage (table entries, bond_r0 != NULL): r0 = (double)bond_r0[b] instead of |xi|.
 *
 * Contract: pure; no allocation, no OpenMP region; arrays are [n_pad] per component (positions,
 * volume, s0, s0_next, f, w), bond_start [n+1], bond_j and bond_alive [num_bonds]; the result for
 * particle i does not depend on i0, i1 (so it is the same for any thread partition).
 */
#include <float.h>
#include <math.h>

#include "kernels.h"

/* No FMA contraction: the stretch must round the same way in the vector body and in the scalar
 * remainder, so both ends of a bond see the same s and break it together. min/max are written as
 * comparisons: fmin/fmax are library calls and stop vectorization. sqrt vectorizes only when the
 * build has -fno-math-errno (GCC honours it from the command line only, not from a pragma); without
 * it these loops run scalar, about 3 times slower. */
PDK_KERNEL_FP_EXACT
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
/* 256-bit vectors: with 512 bits the gathers cost more than they give on this machine class
 * (measured: PMB 2.0 vs 2.8 ns per bond per core, bench/README.md). Only a preference; a build
 * without AVX uses what it has. */
#pragma GCC target("prefer-vector-width=256")
#endif

/* min(1, t); a NaN t gives 1, as fmin would. */
static inline __attribute__((always_inline)) double min1(double t) { return t < 1.0 ? t : 1.0; }

/* One particle's row; the flags are compile-time constants in every caller, so each combination
 * compiles to its own loop without branches on them. */
static inline __attribute__((always_inline)) pdk_bond_index
pmb_row(const int dim, const int has_state, const int commit, const int want_energy,
        const int multi, pdk_index i,
        const pdk_bond_index *restrict bond_start, const pdk_index *restrict bond_j,
        const double *restrict X, const double *restrict Y, const double *restrict Z,
        const double *restrict x, const double *restrict y, const double *restrict z,
        const double *restrict volume, const float *restrict bond_r0, const pdk_pmb_consts *k,
        uint8_t *restrict bond_alive, const double *restrict s0, double *restrict s0_next,
        double *restrict fx, double *restrict fy, double *restrict fz, double *restrict w) {
  const double Xi = X[i], Yi = Y[i], Zi = dim == 3 ? Z[i] : 0.0;
  const double xi = x[i], yi = y[i], zi = dim == 3 ? z[i] : 0.0;
  const double c = k->c, vs_a = k->vs_a, vs_b = k->vs_b, s00 = k->s00, alpha = k->alpha;
  const double *restrict cp = k->c_particle;
  const double c_i = multi ? cp[i] : 0.0;
  const double s0_i = has_state && commit ? s0[i] : 0.0;
  double f0 = 0.0, f1 = 0.0, f2 = 0.0, wi = 0.0, s0_max = -DBL_MAX;
  pdk_bond_index broken = 0;
  const pdk_bond_index b0 = bond_start[i], b1 = bond_start[i + 1];
#pragma omp simd reduction(+ : f0, f1, f2, wi, broken) reduction(max : s0_max)
  for (pdk_bond_index b = b0; b < b1; ++b) {
    const pdk_index j = bond_j[b];
    const double dX = X[j] - Xi, dY = Y[j] - Yi, dZ = dim == 3 ? Z[j] - Zi : 0.0;
    const double dx = x[j] - xi, dy = y[j] - yi, dz = dim == 3 ? z[j] - zi : 0.0;
    /* bond_r0 is loop-invariant: the compiler unswitches the loop */
    const double r0 = bond_r0 ? (double)bond_r0[b] : sqrt(dX * dX + dY * dY + dZ * dZ);
    const double r = sqrt(dx * dx + dy * dy + dz * dz);
    const double d = r - r0;                         /* extension */
    const double q = r > 0.0 ? 1.0 / (r0 * r) : 0.0; /* the one division: s / r = d q */
    const double vol = volume[j] * min1((vs_a - r0) * vs_b);
    const double on = has_state ? (double)bond_alive[b] : 1.0;
    const double c_b = multi ? 2.0 * (c_i * cp[j]) / (c_i + cp[j]) : c;
    const double g = on * c_b * vol * d * q; /* c s beta V_j / r */
    f0 += g * dx;
    f1 += g * dy;
    if (dim == 3) f2 += g * dz;
    if (want_energy)
      wi += 0.25 * g * d * r; /* c s^2 r0 beta V_j / 4 = (c s beta V_j / r) d r / 4 */
    if (has_state && commit) {
      const double s = r > 0.0 ? d * (r * q) : -1.0; /* stretch (r = 0: fully compressed) */
      const int alive = bond_alive[b] != 0;
      const double s0_min = s0[j] < s0_i ? s0[j] : s0_i;
      const int brk = alive && d > s0_min * r0; /* s > s0_min, without a division */
      broken += brk;
      bond_alive[b] = (uint8_t)(alive && !brk);
      const double cand = alive ? s00 - alpha * s : -DBL_MAX;
      s0_max = cand > s0_max ? cand : s0_max;
    }
  }
  fx[i] = f0;
  fy[i] = f1;
  if (dim == 3) fz[i] = f2;
  if (want_energy) w[i] = wi;
  if (has_state && commit) s0_next[i] = s0_max == -DBL_MAX ? DBL_MAX : s0_max;
  return broken;
}

#define PMB_RANGE(dim, st, cm, en)                                                                 \
  do {                                                                                             \
    if (k->c_particle)                                                                             \
      for (pdk_index i = i0; i < i1; ++i)                                                          \
        broken += pmb_row(dim, st, cm, en, 1, i, bond_start, bond_j, X, Y, Z, x, y, z, volume, bond_r0, k, \
                          bond_alive, s0, s0_next, fx, fy, fz, w);                                 \
    else                                                                                           \
      for (pdk_index i = i0; i < i1; ++i)                                                          \
        broken += pmb_row(dim, st, cm, en, 0, i, bond_start, bond_j, X, Y, Z, x, y, z, volume, bond_r0, k, \
                          bond_alive, s0, s0_next, fx, fy, fz, w);                                 \
  } while (0)

static pdk_bond_index
pmb_range(const int dim, pdk_index i0, pdk_index i1, const pdk_bond_index *restrict bond_start,
          const pdk_index *restrict bond_j, const double *restrict X, const double *restrict Y,
          const double *restrict Z, const double *restrict x, const double *restrict y,
          const double *restrict z, const double *restrict volume, const float *restrict bond_r0,
          const pdk_pmb_consts *k, uint8_t *restrict bond_alive, const double *restrict s0,
          double *restrict s0_next, double *restrict fx, double *restrict fy, double *restrict fz,
          double *restrict w) {
  pdk_bond_index broken = 0;
  const int has_state = bond_alive != NULL, commit = has_state && s0_next != NULL;
  const int want_energy = w != NULL;
  /* Dispatch once per call to the loop specialised for (state, commit, energy). */
  PDK_BOND_RANGE_DISPATCH(PMB_RANGE, dim, has_state, commit, want_energy);
  return broken;
}

/* Table entry: the SoA arrays of a, and bond_r0 (float storage) when set. */
pdk_bond_index pdk_kernel_pmb_force_ref(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1) {
  return pmb_range(a->dim, i0, i1, a->bond_start, a->bond_j, a->X[0], a->X[1], a->X[2], a->x[0],
                   a->x[1], a->x[2], a->volume, a->bond_r0, k, a->bond_alive, a->s0, a->s0_next,
                   a->f[0], a->f[1], a->f[2], a->w);
}

void pdk_kernel_bond_lengths_ref(const pdk_bond_arrays *a, pdk_index i0, pdk_index i1,
                                 double *restrict r0) {
  const double *restrict X = a->X[0], *restrict Y = a->X[1], *restrict Z = a->X[2];
  const pdk_bond_index *restrict bs = a->bond_start;
  const pdk_index *restrict bj = a->bond_j;
  const int dim = a->dim;
  for (pdk_index i = i0; i < i1; ++i) {
    const double Xi = X[i], Yi = Y[i], Zi = dim == 3 ? Z[i] : 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      const double dX = X[j] - Xi, dY = Y[j] - Yi, dZ = dim == 3 ? Z[j] - Zi : 0.0;
      r0[b] = sqrt(dX * dX + dY * dY + dZ * dZ); /* as pmb_row; 2-D adds +0.0, an identity */
    }
  }
}
