/* Reference PMB force pass and LPS dilation / force passes over the sliced layout (SELL-C-sigma;
 * arrays in kernels/kernels.h, pdk_sell_arrays; layout built by src/space/sell.c).
 *
 * Formula, partial volumes, bond failure (LAMMPS s0 rule) and energy: kernels/ref/pmb.c, term for
 * term. For each slice s in [s0, s1) and each column col < (slice_start[s+1] - slice_start[s]) / C,
 * lane l holds entry e = slice_start[s] + col C + l: particle i = row_i[s C + l], neighbour
 * j = sj[e]. The lanes run side by side, each with its own sums; at the end of the slice the lanes
 * of real rows (s C + l < n) store f_i, W_i, s0_next_i. Padding entries point at i itself (r0 = r
 * = 0: q = 0, g = 0 exactly) and are flagged broken when there is bond state.
 *
 * Bond state: s->alive is read (and, in a committing pass, a bond that breaks is cleared there and
 * in the CSR state a->bond_alive[bond_start[i] + col], so both stay the same). Float storage: r0 =
 * (double)s->r0[e].
 *
 * LPS: formulas of kernels/ref/lps.c term for term, walked the same way; theta_j, inv_m_j of the
 * neighbours are read from a->theta, a->inv_m. A padding entry (r0 = r = e = 0) adds exact zeros
 * to the dilation and the force; its deviatoric energy term (e - theta r0/d)^2 / r0 would be 0/0,
 * so that term is taken only where r0 > 0 (every real bond: families hold distinct points).
 *
 * Contract: pure; no allocation, no OpenMP region; writes f, w, s0_next (theta_out) only at the
 * rows of slices [s0, s1), so any partition of the slices gives the same bits.
 */
#include <float.h>
#include <math.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#define SELL_MAX_WIDTH 16

static inline __attribute__((always_inline)) double min1(double t) { return t < 1.0 ? t : 1.0; }

/* The failure rule of kernels/ref/pmb.c on sliced entry e (lane l of slice rows, column (e - e0) / C):
 * a bond intact at entry breaks when its extension ext exceeds min(s0_i, s0_j) r0, and is cleared
 * in the sliced and in the CSR bond state; an intact bond offers s00 - alpha s to s0_next (s the
 * stretch ext r q = ext / r0, -1 for r = 0). Returns 1 when the bond broke. */
static inline __attribute__((always_inline)) int
sell_break(const pdk_bond_arrays *a, uint8_t *al, const pdk_index *rows, int l, int64_t e,
           int64_t e0, int C, pdk_index i, pdk_index j, double ext, double r, double q, double r0,
           double s00, double alpha, double *s0_max) {
  const double sv = r > 0.0 ? ext * (r * q) : -1.0;
  const int alive = al[e + l] != 0;
  const double s0_i = a->s0[i];
  const double s0_min = a->s0[j] < s0_i ? a->s0[j] : s0_i;
  const int brk = alive && ext > s0_min * r0;
  if (brk) {
    al[e + l] = 0;
    a->bond_alive[a->bond_start[rows[l]] + (e - e0) / C] = 0;
  }
  const double cand = alive ? s00 - alpha * sv : -DBL_MAX;
  s0_max[l] = cand > s0_max[l] ? cand : s0_max[l];
  return brk;
}

static inline __attribute__((always_inline)) pdk_bond_index
sell_slices(const int dim, const int has_state, const int commit, const int want_energy,
            const int stored, const pdk_pmb_consts *k, const pdk_bond_arrays *a,
            const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  const int C = s->width;
  const double *restrict X = a->X[0], *restrict Y = a->X[1], *restrict Z = a->X[2];
  const double *restrict x = a->x[0], *restrict y = a->x[1], *restrict z = a->x[2];
  const double *restrict volume = a->volume;
  const pdk_index *restrict sj = s->sj;
  const float *restrict r0s = s->r0;
  uint8_t *restrict al = s->alive;
  const double c = k->c, vs_a = k->vs_a, vs_b = k->vs_b, s00 = k->s00, alpha = k->alpha;
  pdk_bond_index broken = 0;
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * C;
    double f0[SELL_MAX_WIDTH], f1[SELL_MAX_WIDTH], f2[SELL_MAX_WIDTH], wi[SELL_MAX_WIDTH];
    double s0_max[SELL_MAX_WIDTH];
    for (int l = 0; l < C; ++l)
      f0[l] = f1[l] = f2[l] = wi[l] = 0.0, s0_max[l] = -DBL_MAX;
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += C)
      for (int l = 0; l < C; ++l) {
        const pdk_index i = rows[l], j = sj[e + l];
        const double dX = X[j] - X[i], dY = Y[j] - Y[i], dZ = dim == 3 ? Z[j] - Z[i] : 0.0;
        const double dx = x[j] - x[i], dy = y[j] - y[i], dz = dim == 3 ? z[j] - z[i] : 0.0;
        const double r0 = stored ? (double)r0s[e + l] : sqrt(dX * dX + dY * dY + dZ * dZ);
        const double r = sqrt(dx * dx + dy * dy + dz * dz);
        const double d = r - r0;
        const double q = r > 0.0 ? 1.0 / (r0 * r) : 0.0;
        const double vol = volume[j] * min1((vs_a - r0) * vs_b);
        const double on = has_state ? (double)al[e + l] : 1.0;
        const double g = on * c * vol * d * q;
        f0[l] += g * dx;
        f1[l] += g * dy;
        if (dim == 3) f2[l] += g * dz;
        if (want_energy) wi[l] += 0.25 * g * d * r;
        if (has_state && commit)
          broken += sell_break(a, al, rows, l, e, e0, C, i, j, d, r, q, r0, s00, alpha, s0_max);
      }
    for (int l = 0; l < C; ++l) {
      if (sl * C + l >= s->n) break;
      const pdk_index i = rows[l];
      a->f[0][i] = f0[l];
      a->f[1][i] = f1[l];
      if (dim == 3) a->f[2][i] = f2[l];
      if (want_energy) a->w[i] = wi[l];
      if (has_state && commit) a->s0_next[i] = s0_max[l] == -DBL_MAX ? DBL_MAX : s0_max[l];
    }
  }
  return broken;
}

#define SELL_S(dim, st, cm, en)                                                                    \
  (s->r0 ? sell_slices(dim, st, cm, en, 1, k, a, s, s0, s1)                                        \
         : sell_slices(dim, st, cm, en, 0, k, a, s, s0, s1))
#define SELL_E(dim, st, cm) (a->w ? SELL_S(dim, st, cm, 1) : SELL_S(dim, st, cm, 0))
#define SELL_D(dim)                                                                                \
  (!s->alive ? SELL_E(dim, 0, 0) : !a->s0_next ? SELL_E(dim, 1, 0) : SELL_E(dim, 1, 1))

pdk_bond_index pdk_kernel_pmb_force_sell_ref(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                             const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  return a->dim == 3 ? SELL_D(3) : SELL_D(2);
}

/* ---- LPS ------------------------------------------------------------------------------------ */

static inline __attribute__((always_inline)) void
sell_lps_theta(const int dim, const int has_state, const int stored, const pdk_lps_consts *k,
               const pdk_bond_arrays *a, const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  const int C = s->width;
  const double *restrict X = a->X[0], *restrict Y = a->X[1], *restrict Z = a->X[2];
  const double *restrict x = a->x[0], *restrict y = a->x[1], *restrict z = a->x[2];
  const double *restrict volume = a->volume;
  const pdk_index *restrict sj = s->sj;
  const float *restrict r0s = s->r0;
  const uint8_t *restrict al = s->alive;
  const double vs_a = k->vs_a, vs_b = k->vs_b, d = k->theta_factor;
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * C;
    double sum[SELL_MAX_WIDTH];
    for (int l = 0; l < C; ++l)
      sum[l] = 0.0;
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += C)
      for (int l = 0; l < C; ++l) {
        const pdk_index i = rows[l], j = sj[e + l];
        const double dX = X[j] - X[i], dY = Y[j] - Y[i], dZ = dim == 3 ? Z[j] - Z[i] : 0.0;
        const double dx = x[j] - x[i], dy = y[j] - y[i], dz = dim == 3 ? z[j] - z[i] : 0.0;
        const double r0 = stored ? (double)r0s[e + l] : sqrt(dX * dX + dY * dY + dZ * dZ);
        const double r = sqrt(dx * dx + dy * dy + dz * dz);
        const double on = has_state ? (double)al[e + l] : 1.0;
        sum[l] += on * (r - r0) * (volume[j] * min1((vs_a - r0) * vs_b));
      }
    for (int l = 0; l < C; ++l) {
      if (sl * C + l >= s->n) break;
      const pdk_index i = rows[l];
      a->theta_out[i] = d * a->inv_m[i] * sum[l];
    }
  }
}

void pdk_kernel_lps_dilation_sell_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                      const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  if (a->dim == 3) {
    if (s->alive)
      s->r0 ? sell_lps_theta(3, 1, 1, k, a, s, s0, s1) : sell_lps_theta(3, 1, 0, k, a, s, s0, s1);
    else
      s->r0 ? sell_lps_theta(3, 0, 1, k, a, s, s0, s1) : sell_lps_theta(3, 0, 0, k, a, s, s0, s1);
  } else {
    if (s->alive)
      s->r0 ? sell_lps_theta(2, 1, 1, k, a, s, s0, s1) : sell_lps_theta(2, 1, 0, k, a, s, s0, s1);
    else
      s->r0 ? sell_lps_theta(2, 0, 1, k, a, s, s0, s1) : sell_lps_theta(2, 0, 0, k, a, s, s0, s1);
  }
}

static inline __attribute__((always_inline)) pdk_bond_index
sell_lps_force(const int dim, const int has_state, const int commit, const int want_energy,
               const int stored, const pdk_lps_consts *k, const pdk_bond_arrays *a,
               const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  const int C = s->width;
  const double *restrict X = a->X[0], *restrict Y = a->X[1], *restrict Z = a->X[2];
  const double *restrict x = a->x[0], *restrict y = a->x[1], *restrict z = a->x[2];
  const double *restrict volume = a->volume;
  const double *restrict theta = a->theta, *restrict inv_m = a->inv_m;
  const pdk_index *restrict sj = s->sj;
  const float *restrict r0s = s->r0;
  uint8_t *restrict al = s->alive;
  const double vs_a = k->vs_a, vs_b = k->vs_b, c_dil = k->c_dil, c_dev = k->c_dev;
  const double s00 = k->s00, alpha = k->alpha, d = k->theta_factor;
  pdk_bond_index broken = 0;
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * C;
    double f0[SELL_MAX_WIDTH], f1[SELL_MAX_WIDTH], f2[SELL_MAX_WIDTH], wdev[SELL_MAX_WIDTH];
    double s0_max[SELL_MAX_WIDTH];
    for (int l = 0; l < C; ++l)
      f0[l] = f1[l] = f2[l] = wdev[l] = 0.0, s0_max[l] = -DBL_MAX;
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += C)
      for (int l = 0; l < C; ++l) {
        const pdk_index i = rows[l], j = sj[e + l];
        const double theta_i = theta[i], inv_m_i = inv_m[i], q_i = theta_i * inv_m_i;
        const double sd_i = theta_i / d;
        const double dX = X[j] - X[i], dY = Y[j] - Y[i], dZ = dim == 3 ? Z[j] - Z[i] : 0.0;
        const double dx = x[j] - x[i], dy = y[j] - y[i], dz = dim == 3 ? z[j] - z[i] : 0.0;
        const double r0 = stored ? (double)r0s[e + l] : sqrt(dX * dX + dY * dY + dZ * dZ);
        const double r = sqrt(dx * dx + dy * dy + dz * dz);
        const double ext = r - r0;
        const double q = r > 0.0 ? 1.0 / (r0 * r) : 0.0;
        const double on = has_state ? (double)al[e + l] : 1.0;
        const double vol = on * (volume[j] * min1((vs_a - r0) * vs_b));
        const double g =
            vol * (c_dil * (q_i + theta[j] * inv_m[j]) * r0 + c_dev * (inv_m_i + inv_m[j]) * ext) *
            q;
        f0[l] += g * dx;
        f1[l] += g * dy;
        if (dim == 3) f2[l] += g * dz;
        if (want_energy && r0 > 0.0) {
          const double ed = ext - sd_i * r0;
          wdev[l] += ed * ed / r0 * vol;
        }
        if (has_state && commit)
          broken += sell_break(a, al, rows, l, e, e0, C, i, j, ext, r, q, r0, s00, alpha, s0_max);
      }
    for (int l = 0; l < C; ++l) {
      if (sl * C + l >= s->n) break;
      const pdk_index i = rows[l];
      a->f[0][i] = f0[l];
      a->f[1][i] = f1[l];
      if (dim == 3) a->f[2][i] = f2[l];
      if (want_energy) {
        const double theta_i = theta[i];
        a->w[i] = 0.5 * k->e_bulk * theta_i * theta_i + k->e_dev * inv_m[i] * wdev[l];
      }
      if (has_state && commit) a->s0_next[i] = s0_max[l] == -DBL_MAX ? DBL_MAX : s0_max[l];
    }
  }
  return broken;
}

#define SELL_LS(dim, st, cm, en)                                                                   \
  (s->r0 ? sell_lps_force(dim, st, cm, en, 1, k, a, s, s0, s1)                                     \
         : sell_lps_force(dim, st, cm, en, 0, k, a, s, s0, s1))
#define SELL_LE(dim, st, cm) (a->w ? SELL_LS(dim, st, cm, 1) : SELL_LS(dim, st, cm, 0))
#define SELL_LD(dim)                                                                               \
  (!s->alive ? SELL_LE(dim, 0, 0) : !a->s0_next ? SELL_LE(dim, 1, 0) : SELL_LE(dim, 1, 1))

pdk_bond_index pdk_kernel_lps_force_sell_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                             const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  return a->dim == 3 ? SELL_LD(3) : SELL_LD(2);
}
