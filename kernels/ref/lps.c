/* Reference LPS (linear peridynamic solid) kernels, ordinary state-based, as LAMMPS peri/lps.
 *
 * Notation for a bond b of particle i (neighbour j = bond_j[b]): xi = X_j - X_i, eta = x_j - x_i,
 * r0 = |xi|, r = |eta|, e = r - r0 (extension), s = e / r0, beta = min(1, (vs_a - r0) * vs_b)
 * (LAMMPS's partial-volume factor, see kernels/ref/pmb.c), alive_b in {0, 1} (1 when
 * bond_alive == NULL). The influence function is LAMMPS's omega = 1 / r0, so omega r0 = 1 and
 * omega r0^2 = r0 below. d = k->theta_factor (3 in 3-D, 2 in plane strain).
 *
 *   weighted volume  m_i     = sum_b omega r0^2 beta V_j          = sum_b r0 beta V_j
 *                              (all bonds; fixed at setup, as LAMMPS's wvolume)
 *   dilation         theta_i = d / m_i * sum_b alive_b omega r0 e beta V_j
 *                            = d * inv_m_i * sum_b alive_b e beta V_j          (0 if m_i = 0)
 *   force density    f_i    += alive_b beta V_j t_b eta / r                    (0 when r == 0)
 *                    t_b     = c_dil (theta_i / m_i + theta_j / m_j) + c_dev (1/m_i + 1/m_j) s
 *   energy density   W_i     = e_bulk theta_i^2 / 2
 *                              + e_dev / m_i * sum_b alive_b omega (e - theta_i r0 / d)^2 beta V_j
 *
 * Constants (src/models/model_lps.c): 3-D c_dil = 3K - 5G, c_dev = 15G, e_bulk = K, e_dev = 15G/2 (the
 * LAMMPS force; its rk = (3K-5G) (omega theta_i/m_i + omega theta_j/m_j) r0 + 15 G (omega/m_i +
 * omega/m_j) e). Plane strain (lambda = K - 2G/3, mu = G): c_dil = 2(lambda - mu) = 2K - 10G/3,
 * c_dev = 8 mu, e_bulk = lambda + mu = K + G/3, e_dev = 4 mu. In both cases V_i f_i = -dE/dx_i for
 * E = sum_i V_i W_i. For an isotropic stretch (e = s r0 on every bond) theta = d s and the
 * deviatoric term vanishes, so W = e_bulk d^2 s^2 / 2: 9 K s^2 / 2 in 3-D, 2 (lambda + mu) s^2 in
 * plane strain, the continuum values, at every particle whatever its family.
 * (LAMMPS tallies half of the deviatoric term; pdk reports the energy whose gradient is f.)
 *
 * Bond failure: as kernels/ref/pmb.c (LAMMPS s0 rule, in the force pass only; the dilation pass
 * only reads bond_alive). m_i is not updated when bonds break (LAMMPS keeps wvolume).
 * Not included: LAMMPS's short-range contact forces (see pmb.c).
 *
 * Float storage (table entries, bond_r0 != NULL): r0 = (double)bond_r0[b] instead of |xi|.
 *
 * Contract: pure; no allocation, no OpenMP region; a call writes only entries i in [i0, i1) of its
 * outputs; particle arrays are [n_pad], bond arrays [num_bonds]; the result for particle i does not
 * depend on i0, i1. The force pass reads theta and inv_m of neighbours: the dilation pass must have
 * completed for every particle first.
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

static inline __attribute__((always_inline)) double
partial_volume(double volume_j, double r0, const double vs_a, const double vs_b) {
  return volume_j * min1((vs_a - r0) * vs_b);
}

/* ---- weighted volume ------------------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
lps_m_range(const int dim, pdk_index i0, pdk_index i1, const pdk_bond_index *restrict bond_start,
            const pdk_index *restrict bond_j, const double *restrict X, const double *restrict Y,
            const double *restrict Z, const double *restrict volume, const float *restrict bond_r0,
            const pdk_lps_consts *k, double *restrict m) {
  const double vs_a = k->vs_a, vs_b = k->vs_b;
  for (pdk_index i = i0; i < i1; ++i) {
    const double Xi = X[i], Yi = Y[i], Zi = dim == 3 ? Z[i] : 0.0;
    double mi = 0.0;
    const pdk_bond_index b0 = bond_start[i], b1 = bond_start[i + 1];
#pragma omp simd reduction(+ : mi)
    for (pdk_bond_index b = b0; b < b1; ++b) {
      const pdk_index j = bond_j[b];
      const double dX = X[j] - Xi, dY = Y[j] - Yi, dZ = dim == 3 ? Z[j] - Zi : 0.0;
      const double r0 = bond_r0 ? (double)bond_r0[b] : sqrt(dX * dX + dY * dY + dZ * dZ);
      mi += r0 * partial_volume(volume[j], r0, vs_a, vs_b);
    }
    m[i] = mi;
  }
}

void pdk_kernel_lps_weighted_volume_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1, double *restrict m) {
  lps_m_range(a->dim, i0, i1, a->bond_start, a->bond_j, a->X[0], a->X[1], a->X[2], a->volume,
              a->bond_r0, k, m);
}

/* ---- dilation -------------------------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
lps_theta_range(const int dim, const int has_state, pdk_index i0, pdk_index i1,
                const pdk_bond_index *restrict bond_start, const pdk_index *restrict bond_j,
                const double *restrict X, const double *restrict Y, const double *restrict Z,
                const double *restrict x, const double *restrict y, const double *restrict z,
                const double *restrict volume, const float *restrict bond_r0,
                const pdk_lps_consts *k, const uint8_t *restrict bond_alive,
                const double *restrict inv_m, double *restrict theta) {
  const double vs_a = k->vs_a, vs_b = k->vs_b, d = k->theta_factor;
  for (pdk_index i = i0; i < i1; ++i) {
    const double Xi = X[i], Yi = Y[i], Zi = dim == 3 ? Z[i] : 0.0;
    const double xi = x[i], yi = y[i], zi = dim == 3 ? z[i] : 0.0;
    double sum = 0.0;
    const pdk_bond_index b0 = bond_start[i], b1 = bond_start[i + 1];
#pragma omp simd reduction(+ : sum)
    for (pdk_bond_index b = b0; b < b1; ++b) {
      const pdk_index j = bond_j[b];
      const double dX = X[j] - Xi, dY = Y[j] - Yi, dZ = dim == 3 ? Z[j] - Zi : 0.0;
      const double dx = x[j] - xi, dy = y[j] - yi, dz = dim == 3 ? z[j] - zi : 0.0;
      const double r0 = bond_r0 ? (double)bond_r0[b] : sqrt(dX * dX + dY * dY + dZ * dZ);
      const double r = sqrt(dx * dx + dy * dy + dz * dz);
      const double on = has_state ? (double)bond_alive[b] : 1.0;
      sum += on * (r - r0) * partial_volume(volume[j], r0, vs_a, vs_b);
    }
    theta[i] = d * inv_m[i] * sum;
  }
}

void pdk_kernel_lps_dilation_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a, pdk_index i0,
                                 pdk_index i1) {
  const double *X = a->X[0], *Y = a->X[1], *Z = a->X[2], *x = a->x[0], *y = a->x[1], *z = a->x[2];
  if (a->dim == 3) {
    if (a->bond_alive)
      lps_theta_range(3, 1, i0, i1, a->bond_start, a->bond_j, X, Y, Z, x, y, z, a->volume,
                      a->bond_r0, k, a->bond_alive, a->inv_m, a->theta_out);
    else
      lps_theta_range(3, 0, i0, i1, a->bond_start, a->bond_j, X, Y, Z, x, y, z, a->volume,
                      a->bond_r0, k, NULL, a->inv_m, a->theta_out);
  } else {
    if (a->bond_alive)
      lps_theta_range(2, 1, i0, i1, a->bond_start, a->bond_j, X, Y, NULL, x, y, NULL, a->volume,
                      a->bond_r0, k, a->bond_alive, a->inv_m, a->theta_out);
    else
      lps_theta_range(2, 0, i0, i1, a->bond_start, a->bond_j, X, Y, NULL, x, y, NULL, a->volume,
                      a->bond_r0, k, NULL, a->inv_m, a->theta_out);
  }
}

/* ---- force ----------------------------------------------------------------------------------- */

static inline __attribute__((always_inline)) pdk_bond_index
lps_row(const int dim, const int has_state, const int commit, const int want_energy, pdk_index i,
        const pdk_bond_index *restrict bond_start, const pdk_index *restrict bond_j,
        const double *restrict X, const double *restrict Y, const double *restrict Z,
        const double *restrict x, const double *restrict y, const double *restrict z,
        const double *restrict volume, const float *restrict bond_r0, const pdk_lps_consts *k,
        const double *restrict theta, const double *restrict inv_m,
        uint8_t *restrict bond_alive, const double *restrict s0,
        double *restrict s0_next, double *restrict fx, double *restrict fy, double *restrict fz,
        double *restrict w) {
  const double Xi = X[i], Yi = Y[i], Zi = dim == 3 ? Z[i] : 0.0;
  const double xi = x[i], yi = y[i], zi = dim == 3 ? z[i] : 0.0;
  const double vs_a = k->vs_a, vs_b = k->vs_b, c_dil = k->c_dil, c_dev = k->c_dev;
  const double s00 = k->s00, alpha = k->alpha, d = k->theta_factor;
  const double theta_i = theta[i], inv_m_i = inv_m[i], q_i = theta_i * inv_m_i;
  const double sd_i = theta_i / d; /* deviatoric extension: e - theta r0/d = e - sd_i r0 */
  const double s0_i = has_state && commit ? s0[i] : 0.0;
  double f0 = 0.0, f1 = 0.0, f2 = 0.0, wdev = 0.0, s0_max = -DBL_MAX;
  pdk_bond_index broken = 0;
  const pdk_bond_index b0 = bond_start[i], b1 = bond_start[i + 1];
#pragma omp simd reduction(+ : f0, f1, f2, wdev, broken) reduction(max : s0_max)
  for (pdk_bond_index b = b0; b < b1; ++b) {
    const pdk_index j = bond_j[b];
    const double dX = X[j] - Xi, dY = Y[j] - Yi, dZ = dim == 3 ? Z[j] - Zi : 0.0;
    const double dx = x[j] - xi, dy = y[j] - yi, dz = dim == 3 ? z[j] - zi : 0.0;
    const double r0 = bond_r0 ? (double)bond_r0[b] : sqrt(dX * dX + dY * dY + dZ * dZ);
    const double r = sqrt(dx * dx + dy * dy + dz * dz);
    const double e = r - r0;                         /* extension */
    const double q = r > 0.0 ? 1.0 / (r0 * r) : 0.0; /* the one division */
    const double on = has_state ? (double)bond_alive[b] : 1.0;
    const double vol = on * partial_volume(volume[j], r0, vs_a, vs_b);
    /* vol t / r with t = A + B s, s = e / r0:  vol (A r0 + B e) q */
    const double g =
        vol * (c_dil * (q_i + theta[j] * inv_m[j]) * r0 + c_dev * (inv_m_i + inv_m[j]) * e) * q;
    f0 += g * dx;
    f1 += g * dy;
    if (dim == 3) f2 += g * dz;
    if (want_energy) {
      const double ed = e - sd_i * r0; /* deviatoric extension e - theta r0 / d */
      wdev += ed * ed / r0 * vol;      /* omega e_d^2 beta V_j */
    }
    if (has_state && commit) {
      const double s = r > 0.0 ? e * (r * q) : -1.0; /* stretch (r = 0: fully compressed) */
      const int alive = bond_alive[b] != 0;
      const double s0_min = s0[j] < s0_i ? s0[j] : s0_i;
      const int brk = alive && e > s0_min * r0; /* s > s0_min, without a division */
      broken += brk;
      bond_alive[b] = (uint8_t)(alive && !brk);
      const double cand = alive ? s00 - alpha * s : -DBL_MAX;
      s0_max = cand > s0_max ? cand : s0_max;
    }
  }
  fx[i] = f0;
  fy[i] = f1;
  if (dim == 3) fz[i] = f2;
  if (want_energy) w[i] = 0.5 * k->e_bulk * theta_i * theta_i + k->e_dev * inv_m_i * wdev;
  if (has_state && commit) s0_next[i] = s0_max == -DBL_MAX ? DBL_MAX : s0_max;
  return broken;
}

#define LPS_RANGE(dim, st, cm, en)                                                                 \
  for (pdk_index i = i0; i < i1; ++i)                                                              \
  broken += lps_row(dim, st, cm, en, i, bond_start, bond_j, X, Y, Z, x, y, z, volume, bond_r0, k,  \
                    theta, inv_m, bond_alive, s0, s0_next, fx, fy, fz, w)

static pdk_bond_index
lps_force_range(const int dim, pdk_index i0, pdk_index i1,
                const pdk_bond_index *restrict bond_start, const pdk_index *restrict bond_j,
                const double *restrict X, const double *restrict Y, const double *restrict Z,
                const double *restrict x, const double *restrict y, const double *restrict z,
                const double *restrict volume, const float *restrict bond_r0,
                const pdk_lps_consts *k, const double *restrict theta,
                const double *restrict inv_m, uint8_t *restrict bond_alive,
                const double *restrict s0, double *restrict s0_next, double *restrict fx,
                double *restrict fy, double *restrict fz, double *restrict w) {
  pdk_bond_index broken = 0;
  const int has_state = bond_alive != NULL, commit = has_state && s0_next != NULL;
  const int want_energy = w != NULL;
  PDK_BOND_RANGE_DISPATCH(LPS_RANGE, dim, has_state, commit, want_energy);
  return broken;
}

pdk_bond_index pdk_kernel_lps_force_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1) {
  return lps_force_range(a->dim, i0, i1, a->bond_start, a->bond_j, a->X[0], a->X[1], a->X[2],
                         a->x[0], a->x[1], a->x[2], a->volume, a->bond_r0, k, a->theta, a->inv_m,
                         a->bond_alive, a->s0, a->s0_next, a->f[0], a->f[1], a->f[2], a->w);
}
