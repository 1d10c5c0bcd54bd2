/* Correspondence shape, pass 1 and pass 2, vectorized: one source for every ISA.
 * kernels/opt/corr_avx2.c and corr_avx512.c each set a target (#pragma GCC target) and CORR_SFX,
 * then include this file, so the same loops are compiled once per ISA and src/core/kernels.c installs
 * the one the CPU runs.
 *
 * Two forms of pass 1 and pass 2:
 *   - packed rows (the driver provides pdk_corr_arrays own, ref4, cur4, row or rowf: no or
 *     Silling stabilization): each bond is a step of 4-lane vectors over whole particle rows, no
 *     gathers; described at "Packed-row passes" below;
 *   - gathers (hourglass stabilization, or no rows): every bond loop an `omp simd` reduction
 *     across a family's bonds, as described next.
 *
 * Formulas and contract: kernels/ref/corr.c (pdk_kernel_corr_*_ref). What differs is the order
 * of the sums, not the terms:
 *   - every bond loop is an `omp simd` reduction over the bonds of row i (gathers of the neighbour
 *     data, FMA contraction allowed), so sums are regrouped by lane; a broken bond enters with
 *     weight 0 instead of being skipped (its terms are finite: no NaN is ever stored);
 *   - shape: m = tr K (the reference sums w V |xi|^2 separately);
 *   - pass 1 accumulates N in the vector loop; the per-particle end (law, A, flags, the pass-2
 *     data) is the reference's pdk_kernel_corr_point_ref, and a row whose intact count changed
 *     is reshaped by the reference (as src/models/model_corr.c reshapes after breaking);
 *   - pass 2 (fused stabilization): particle j enters only through the B_j (9 entries; 4 in 2-D)
 *     and k_j pass 1 stored, instead of A_j, F_j, flag_j and m_j (U = Y - xi):
 *       Silling    f_i = sum w V [(B_i + B_j) xi + (k_i + k_j) U],   B = A - k (F - I)
 *                      = B_i (sum w V xi) + k_i (sum w V U) + sum w V (B_j xi + k_j U)
 *                  (A_i xi + k_i z_i + A_j xi + k_j z_j' with z = Y - F xi, regrouped), and the
 *                  energy k_i/2 sum w V |Y - F_i xi|^2 from i's own F in the same sweep;
 *       none       f_i = A_i (sum w V xi) + sum w V A_j xi;
 *       hourglass  f_i = A_i (sum w V xi) + sum w V [A_j xi + g Y],
 *                  g = (delta / |xi|) ((k_i + k_j) U.Y - ((G_i + G_j) xi) . Y) / |Y|^2,
 *                  G = k (F - I) (0 when Y = 0), the reference's
 *                  (delta/|xi|)(k_i z_i.e + k_j z_j'.e) / |Y|.
 *     The own-particle terms are factored out of the bond loop. With float storage (Bf set) B_j,
 *     G_j are read as floats and widened; i's own B_i, G_i come from its double A_i, F_i.
 * Agreement with the reference: round-off of the regrouped sums (tests/t044_kernels_corr.c states
 * the bound).
 */
#ifndef CORR_SFX
#error "define CORR_SFX before including corr_simd.h"
#endif

#include <immintrin.h>
#include <math.h>

#include "kernels.h"
#include "ref/corr_law.h"

#define CORR_CAT2(a, b) a##b
#define CORR_CAT(a, b) CORR_CAT2(a, b)
#define CORR_FN(name) CORR_CAT(name, CORR_SFX)

#define CORR_INLINE static inline __attribute__((always_inline))

/* Row i's K = sum w V xi (x) xi, m, intact count; then the reference's per-particle end. */
CORR_INLINE int shape_row(const int d, const int has_alive, const pdk_corr_consts *k,
                          const pdk_corr_arrays *a, pdk_index i) {
  const pdk_bond_index *restrict bs = a->bond_start;
  const pdk_index *restrict bj = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict V = a->volume;
  const double *restrict X0 = a->X[0], *restrict X1 = a->X[1];
  const double *restrict X2 = d == 3 ? a->X[2] : a->X[1];
  const double c0 = X0[i], c1 = X1[i], c2 = d == 3 ? X2[i] : 0.0;
  double K00 = 0.0, K01 = 0.0, K02 = 0.0, K11 = 0.0, K12 = 0.0, K22 = 0.0;
  int32_t count = 0;
  const pdk_bond_index b0 = bs[i], b1 = bs[i + 1];
#pragma omp simd reduction(+ : K00, K01, K02, K11, K12, K22, count)
  for (pdk_bond_index b = b0; b < b1; ++b) {
    const pdk_index j = bj[b];
    const int on = has_alive ? alive[b] != 0 : 1;
    count += on;
    const double wv = (on ? omega[b] : 0.0) * V[j];
    const double e0 = X0[j] - c0, e1 = X1[j] - c1;
    K00 += wv * e0 * e0;
    K01 += wv * e0 * e1;
    K11 += wv * e1 * e1;
    if (d == 3) {
      const double e2 = X2[j] - c2;
      K02 += wv * e0 * e2;
      K12 += wv * e1 * e2;
      K22 += wv * e2 * e2;
    }
  }
  const double K[3][3] = {{K00, K01, K02}, {K01, K11, K12}, {K02, K12, K22}};
  return pdk_kernel_corr_shape_point_ref(k, a, i, K, K00 + K11 + K22, count);
}

CORR_INLINE pdk_index shape_rows(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                 pdk_index i0, pdk_index i1) {
  pdk_index flagged = 0;
  if (a->bond_alive)
    for (pdk_index i = i0; i < i1; ++i)
      flagged += shape_row(d, 1, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      flagged += shape_row(d, 0, k, a, i);
  return flagged;
}

pdk_index CORR_FN(pdk_kernel_corr_shape_)(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                          pdk_index i0, pdk_index i1) {
  return k->dim == 2 ? shape_rows(2, k, a, i0, i1) : shape_rows(3, k, a, i0, i1);
}

/* ---- Packed-row passes (pdk_corr_arrays own set: no or Silling stabilization) ---------------
 * The neighbour data of a bond are whole rows: in pass 1 ref4 (X, V) and cur4 (u = x - X, 1); in
 * pass 2 pass 1's pdk_corr_row (double storage: one 128-byte record per particle with V_j B_j,
 * V_j k_j, X_j and -u_j, so a bond is one index and loads at fixed offsets from one address) or
 * pdk_corr_rowf (float storage: B_j, k_j, with ref4 and cur4). A bond is one step of 4-lane
 * vectors whose lanes are a row's components (within the bond, not across bonds): the
 * neighbour's X_c and the scalars come as broadcast loads (pass 1: X_i - X_j as one subtraction,
 * spread by permutes) and its vectors as aligned loads, so there is no gather and no transpose.
 * Two accumulator sets (intact bonds alternately) halve the dependency chains.
 *
 * Pass 1 of i, per intact bond (broken bonds are skipped; w = omega V_j, e = xi, v = u_j - u_i = Y - xi, and the 4th lane
 * of v equal to 1 from cur4):
 *   D_c += w v e_c (c < d)   lanes 0..d-1: D = sum w v (x) xi,  lane 3: s_c = sum w e_c
 *   U   += w v               lanes 0..d-1: u = sum w v
 *   Q   += w v v             lanes 0..d-1 summed: vv = sum w |v|^2
 * then the reference's per-particle end from D (pdk_kernel_corr_point_disp_ref: F = I + D K^-1,
 * the law, A, W, flags; inline for the elastic laws, rows_end) and i's rows: B_i, k_i for the
 * neighbours, and for itself
 *   own = (B_i s + k_i u, zz),  zz = sum w |v - H e|^2 = vv - H : D,  H = D K^-1
 * (the identity holds because H K = D, K = sum w e (x) e with the same weights; zz is clamped at
 * 0 against round-off). B = A - k (F - I) (Silling) or A, k = stab_modulus_i / m_i (0 when
 * flagged), as the reference's store_pair.
 * Pass 2 of i: f_i = own_i + sum_b w (B_j e + k_j v) (double storage: omega (V_j B_j e +
 * V_j k_j v), the volume taken from the record), and the Silling energy
 * W_i += k_i/2 zz_i (or, in the commit pass where i fails, w_damage_i += (stab_modulus/m_i)/2 zz_i)
 * as the reference's pass 2. The reference's pair term sum w [(B_i + B_j) e + (k_i + k_j) v] is
 * the same sum with i's part factored out. */

typedef double corr_v4 __attribute__((vector_size(32)));

CORR_INLINE corr_v4 cv_set1(double s) { return (corr_v4){s, s, s, s}; }
CORR_INLINE corr_v4 cv_load(const double *p) { return (corr_v4)_mm256_load_pd(p); }
CORR_INLINE corr_v4 cv_loadf(const float *p) { return (corr_v4)_mm256_cvtps_pd(_mm_load_ps(p)); }
/* *p in every lane, as a broadcast load: the empty asm keeps GCC from folding a difference of two
 * broadcasts into a scalar difference and a register broadcast (one more shuffle uop). */
CORR_INLINE corr_v4 cv_bcast(const double *p) {
  __m256d v = _mm256_broadcast_sd(p);
  __asm__("" : "+x"(v));
  return (corr_v4)v;
}

/* The intact bonds of row i in order, alternately into the accumulators p and q (BOND(b, acc)):
 * broken bonds are skipped, so a row with broken bonds gives bit for bit what the same row
 * without them gives (semi-TL's compacted list against the full one). */
#define ROWS_WALK(has_alive, a, i, BOND, p, q)                                                     \
  do {                                                                                             \
    const pdk_bond_index b1_ = (a)->bond_start[(i) + 1];                                           \
    pdk_bond_index b_ = (a)->bond_start[i];                                                        \
    if (has_alive) {                                                                               \
      const uint8_t *restrict al_ = (a)->bond_alive;                                               \
      for (;;) {                                                                                   \
        while (b_ < b1_ && !al_[b_])                                                               \
          ++b_;                                                                                    \
        if (b_ >= b1_) break;                                                                      \
        BOND(b_, p);                                                                               \
        ++b_;                                                                                      \
        while (b_ < b1_ && !al_[b_])                                                               \
          ++b_;                                                                                    \
        if (b_ >= b1_) break;                                                                      \
        BOND(b_, q);                                                                               \
        ++b_;                                                                                      \
      }                                                                                            \
    } else {                                                                                       \
      for (; b_ + 2 <= b1_; b_ += 2) {                                                             \
        BOND(b_, p);                                                                               \
        BOND(b_ + 1, q);                                                                           \
      }                                                                                            \
      if (b_ < b1_) BOND(b_, p);                                                                   \
    }                                                                                              \
  } while (0)

/* One intact bond of pass 1 into acc[0..4] = D_0, D_1, D_2, U, Q. */
CORR_INLINE void rp1_bond(const int d, const pdk_corr_arrays *a, pdk_bond_index b, corr_v4 Xi4,
                          corr_v4 ui, corr_v4 *acc, int32_t *count) {
  const pdk_index j = a->bond_j[b];
  const double *restrict rj = a->ref4 + 4 * (size_t)j;
  ++*count;
  const corr_v4 v = cv_load(a->cur4 + 4 * (size_t)j) - ui;
  const corr_v4 wv = (cv_bcast(a->bond_omega + b) * cv_bcast(rj + 3)) * v;
  /* ne = X_i - X_j in lanes 0..2 (one subtraction from memory), spread by permutes; acc -= wv ne
   * is the same rounding as acc += wv xi (negation is exact) */
  const __m256d ne = _mm256_sub_pd((__m256d)Xi4, _mm256_load_pd(rj));
  acc[0] -= wv * (corr_v4)_mm256_permute4x64_pd(ne, 0x00);
  acc[1] -= wv * (corr_v4)_mm256_permute4x64_pd(ne, 0x55);
  if (d == 3) acc[2] -= wv * (corr_v4)_mm256_permute4x64_pd(ne, 0xAA);
  acc[3] += wv;
  acc[4] += wv * v;
}

/* i's rows after the per-particle end: row / rowf for the neighbours, own for itself. The float
 * row holds (float) B, the reference's Bf. */
CORR_INLINE void rows_store(const int d, const int fl, const pdk_corr_consts *k,
                            const pdk_corr_arrays *a, pdk_index i, const double D[3][3],
                            const corr_v4 *acc, const double A[3][3], const double F[3][3]) {
  const int silling = k->stab == PDK_KERNEL_STAB_SILLING;
  const double ki = pdk_corr_kst(k, a, i);
  double B[3][3] = {{0}};
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      B[r][c] = silling ? A[r][c] - ki * (F[r][c] - (r == c ? 1.0 : 0.0)) : A[r][c];
  double *restrict own = a->own + 4 * (size_t)i;
  for (int r = 0; r < 3; ++r) {
    double f = 0.0;
    if (r < d) {
      f = ki * acc[3][r];
      for (int c = 0; c < d; ++c)
        f += B[r][c] * acc[c][3];
    }
    own[r] = f;
  }
  const double zz =
      silling ? pdk_corr_silling_zz(d, D, a, i, acc[4][0] + acc[4][1] + acc[4][2]) : 0.0;
  own[3] = zz;
  if (fl) {
    pdk_corr_rowf *restrict R = a->rowf + i;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 4; ++r)
        R->c[4 * c + r] = r < 3 ? (float)B[r][c] : 0.0f;
    R->k = ki;
    R->pad = 0.0;
  } else {
    /* the record of pdk_corr_row: V B, V k, X, -u */
    pdk_corr_row *restrict R = a->row + i;
    const double *restrict ri = a->ref4 + 4 * (size_t)i, *restrict ci = a->cur4 + 4 * (size_t)i;
    const double Vi = ri[3];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        R->c[4 * c + r] = Vi * B[r][c];
    R->c[3] = Vi * ki;
    R->c[7] = ri[0];
    R->c[11] = ri[1];
    R->c[15] = ri[2];
    for (int r = 0; r < 3; ++r)
      R->c[12 + r] = -ci[r];
  }
}

/* The per-particle end of pass 1 from D: the reference's (pdk_kernel_corr_point_disp_ref), here
 * inline for the elastic laws with F, A, K^-1 kept in registers for the rows (the same
 * operations: ref/corr_law.h; the target may contract them into FMAs), the reference's own call
 * otherwise (Johnson-Cook, a family that does not span, the reference's pass-2 arrays). */
CORR_INLINE void rows_end(const int d, const int fl, const pdk_corr_consts *k,
                          const pdk_corr_arrays *a, pdk_index i, const double D[3][3],
                          const corr_v4 *acc) {
  double A[3][3] = {{0}}, F[3][3] = {{0}};
  if (k->law == PDK_KERNEL_LAW_JC || (a->flag[i] & PDK_CORR_FLAG_SPAN) || a->kst || a->Bf[0]) {
    pdk_kernel_corr_point_disp_ref(k, a, i, D);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) {
        A[r][c] = a->A[r * d + c][i];
        F[r][c] = a->F[r * d + c][i];
      }
  } else {
    pdk_corr_end_elastic(d, k, a, i, D, F, A);
  }
  rows_store(d, fl, k, a, i, D, acc, A, F);
}

CORR_INLINE void rp1_row(const int d, const int has_alive, const int fl, const pdk_corr_consts *k,
                         const pdk_corr_arrays *a, pdk_index i) {
  const double *restrict ri = a->ref4 + 4 * (size_t)i, *restrict ci = a->cur4 + 4 * (size_t)i;
  const corr_v4 Xi4 = {ri[0], ri[1], ri[2], 0.0};
  const corr_v4 ui = {ci[0], ci[1], ci[2], 0.0};
  const corr_v4 z = cv_set1(0.0);
  corr_v4 p[5] = {z, z, z, z, z}, q[5] = {z, z, z, z, z};
  int32_t count = 0;
#define RP1_BOND(b, acc) rp1_bond(d, a, b, Xi4, ui, acc, &count)
  ROWS_WALK(has_alive, a, i, RP1_BOND, p, q);
#undef RP1_BOND
  for (int t = 0; t < 5; ++t)
    p[t] += q[t];
  /* The reference's shape where bonds broke since K^-1 (see pass1_row below). */
  if (has_alive && a->num_alive && count != a->num_alive[i])
    pdk_kernel_corr_shape_ref(k, a, i, i + 1);
  double D[3][3] = {{0}};
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      D[r][c] = p[c][r];
  rows_end(d, fl, k, a, i, D, p);
}

/* One intact bond of pass 2 into *acc (lanes 0..d-1 of the force). */
CORR_INLINE void rp2_bond(const int d, const int fl, const int stab, const pdk_corr_arrays *a,
                          pdk_bond_index b, const corr_v4 *Xi, corr_v4 ui, corr_v4 nui,
                          corr_v4 *acc) {
  const pdk_index j = a->bond_j[b];
  const double *restrict rj = a->ref4 + 4 * (size_t)j;
  corr_v4 g;
  if (fl) {
    const pdk_corr_rowf *restrict R = a->rowf + j;
    g = cv_loadf(R->c) * (cv_bcast(rj) - Xi[0]) + cv_loadf(R->c + 4) * (cv_bcast(rj + 1) - Xi[1]);
    if (d == 3) g += cv_loadf(R->c + 8) * (cv_bcast(rj + 2) - Xi[2]);
    if (stab) g += cv_bcast(&R->k) * (cv_load(a->cur4 + 4 * (size_t)j) - ui);
  } else {
    /* One record (pdk_corr_row): V_j is in the columns and in k, so the weight is omega alone;
     * lane 3 of g carries junk (finite) that nobody reads. */
    const pdk_corr_row *restrict R = a->row + j;
    g = cv_load(R->c) * (cv_bcast(R->c + 7) - Xi[0]) +
        cv_load(R->c + 4) * (cv_bcast(R->c + 11) - Xi[1]);
    if (d == 3) g += cv_load(R->c + 8) * (cv_bcast(R->c + 15) - Xi[2]);
    if (stab) g += cv_bcast(R->c + 3) * (nui - cv_load(R->c + 12));
    *acc += cv_bcast(a->bond_omega + b) * g;
    return;
  }
  *acc += (cv_bcast(a->bond_omega + b) * cv_bcast(rj + 3)) * g;
}

CORR_INLINE void rp2_row(const int d, const int has_alive, const int fl, const int stab,
                         const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i) {
  const double *restrict ri = a->ref4 + 4 * (size_t)i, *restrict ci = a->cur4 + 4 * (size_t)i;
  const corr_v4 Xi[3] = {cv_set1(ri[0]), cv_set1(ri[1]), cv_set1(ri[2])};
  const corr_v4 ui = {ci[0], ci[1], ci[2], 0.0}, nui = -ui;
  corr_v4 p = cv_set1(0.0), q = p;
#define RP2_BOND(b, acc) rp2_bond(d, fl, stab, a, b, Xi, ui, nui, &acc)
  ROWS_WALK(has_alive, a, i, RP2_BOND, p, q);
#undef RP2_BOND
  p += q;
  const double *restrict own = a->own + 4 * (size_t)i;
  for (int r = 0; r < d; ++r)
    a->f[r][i] = own[r] + p[r];
  if (stab) {
    const double zz = own[3];
    a->W[i] += 0.5 * pdk_corr_kst(k, a, i) * zz;
    if ((a->flag[i] & PDK_CORR_FLAG_FAILED_NOW) && a->m[i] > 0.0)
      a->w_damage[i] += 0.5 * pdk_corr_kst_unflagged(k, a, i) * zz;
  }
}

CORR_INLINE void rp1_rows(const int d, const int fl, const pdk_corr_consts *k,
                          const pdk_corr_arrays *a, pdk_index i0, pdk_index i1) {
  if (a->bond_alive)
    for (pdk_index i = i0; i < i1; ++i)
      rp1_row(d, 1, fl, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      rp1_row(d, 0, fl, k, a, i);
}

CORR_INLINE void rp2_rows(const int d, const int fl, const int stab, const pdk_corr_consts *k,
                          const pdk_corr_arrays *a, pdk_index i0, pdk_index i1) {
  if (a->bond_alive)
    for (pdk_index i = i0; i < i1; ++i)
      rp2_row(d, 1, fl, stab, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      rp2_row(d, 0, fl, stab, k, a, i);
}

static void rows_pass1(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                       pdk_index i1) {
  const int fl = a->rowf != NULL;
  if (k->dim == 2)
    fl ? rp1_rows(2, 1, k, a, i0, i1) : rp1_rows(2, 0, k, a, i0, i1);
  else
    fl ? rp1_rows(3, 1, k, a, i0, i1) : rp1_rows(3, 0, k, a, i0, i1);
}

static void rows_pass2(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                       pdk_index i1) {
  const int fl = a->rowf != NULL, st = k->stab == PDK_KERNEL_STAB_SILLING;
  if (k->dim == 2) {
    if (fl)
      st ? rp2_rows(2, 1, 1, k, a, i0, i1) : rp2_rows(2, 1, 0, k, a, i0, i1);
    else
      st ? rp2_rows(2, 0, 1, k, a, i0, i1) : rp2_rows(2, 0, 0, k, a, i0, i1);
  } else {
    if (fl)
      st ? rp2_rows(3, 1, 1, k, a, i0, i1) : rp2_rows(3, 1, 0, k, a, i0, i1);
    else
      st ? rp2_rows(3, 0, 1, k, a, i0, i1) : rp2_rows(3, 0, 0, k, a, i0, i1);
  }
}

/* Pass 1 of row i: N = sum w V Y (x) xi and the intact count in one sweep; the shape again if the
 * count changed; then the reference's per-particle end. */
CORR_INLINE void pass1_row(const int d, const int has_alive, const pdk_corr_consts *k,
                           const pdk_corr_arrays *a, pdk_index i) {
  const pdk_bond_index *restrict bs = a->bond_start;
  const pdk_index *restrict bj = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict V = a->volume;
  const double *restrict X0 = a->X[0], *restrict X1 = a->X[1];
  const double *restrict X2 = d == 3 ? a->X[2] : a->X[1];
  const double *restrict x0 = a->x[0], *restrict x1 = a->x[1];
  const double *restrict x2 = d == 3 ? a->x[2] : a->x[1];
  const double c0 = X0[i], c1 = X1[i], c2 = d == 3 ? X2[i] : 0.0;
  const double p0 = x0[i], p1 = x1[i], p2 = d == 3 ? x2[i] : 0.0;
  double N00 = 0.0, N01 = 0.0, N02 = 0.0, N10 = 0.0, N11 = 0.0, N12 = 0.0, N20 = 0.0, N21 = 0.0,
         N22 = 0.0;
  int32_t count = 0;
  const pdk_bond_index b0 = bs[i], b1 = bs[i + 1];
#pragma omp simd reduction(+ : N00, N01, N02, N10, N11, N12, N20, N21, N22, count)
  for (pdk_bond_index b = b0; b < b1; ++b) {
    const pdk_index j = bj[b];
    const int on = has_alive ? alive[b] != 0 : 1;
    count += on;
    const double wv = (on ? omega[b] : 0.0) * V[j];
    const double e0 = X0[j] - c0, e1 = X1[j] - c1;
    const double y0 = wv * (x0[j] - p0), y1 = wv * (x1[j] - p1);
    N00 += y0 * e0;
    N01 += y0 * e1;
    N10 += y1 * e0;
    N11 += y1 * e1;
    if (d == 3) {
      const double e2 = X2[j] - c2, y2 = wv * (x2[j] - p2);
      N02 += y0 * e2;
      N12 += y1 * e2;
      N20 += y2 * e0;
      N21 += y2 * e1;
      N22 += y2 * e2;
    }
  }
  /* The reference's shape, as the driver's reshape after breaking uses, so a row's K^-1 is the
   * same whichever of the two recomputes it (a restart from a checkpoint reshapes here). */
  if (has_alive && a->num_alive && count != a->num_alive[i])
    pdk_kernel_corr_shape_ref(k, a, i, i + 1);
  const double N[3][3] = {{N00, N01, N02}, {N10, N11, N12}, {N20, N21, N22}};
  pdk_kernel_corr_point_ref(k, a, i, N);
}

CORR_INLINE void pass1_rows(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                            pdk_index i0, pdk_index i1) {
  if (a->bond_alive)
    for (pdk_index i = i0; i < i1; ++i)
      pass1_row(d, 1, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      pass1_row(d, 0, k, a, i);
}

void CORR_FN(pdk_kernel_corr_pass1_)(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                     pdk_index i0, pdk_index i1) {
  if (a->own && k->stab != PDK_KERNEL_STAB_HOURGLASS)
    rows_pass1(k, a, i0, i1);
  else if (k->dim == 2)
    pass1_rows(2, k, a, i0, i1);
  else
    pass1_rows(3, k, a, i0, i1);
}

/* Pass 2 of row i; stab: 0 none, 1 Silling, 2 hourglass; ET the storage type of B_j, G_j. The
 * d x d tensors are indexed [r * d + c]; for d = 2 the third row and column are never touched. */
#define CORR_PASS2_ROW(NAME, ET)                                                                   \
  CORR_INLINE void NAME(const int d, const int has_alive, const int stab,                          \
                        const pdk_corr_consts *k, const pdk_corr_arrays *a, const ET *const *Bn,   \
                        const ET *const *Gn, pdk_index i) {                                        \
    const pdk_bond_index *restrict bs = a->bond_start;                                             \
    const pdk_index *restrict bj = a->bond_j;                                                      \
    const double *restrict omega = a->bond_omega;                                                  \
    const uint8_t *restrict alive = a->bond_alive;                                                 \
    const double *restrict V = a->volume;                                                          \
    const double *restrict kst = a->kst;                                                           \
    const double *restrict X0 = a->X[0], *restrict X1 = a->X[1];                                   \
    const double *restrict X2 = d == 3 ? a->X[2] : a->X[1];                                        \
    const double *restrict x0 = a->x[0], *restrict x1 = a->x[1];                                   \
    const double *restrict x2 = d == 3 ? a->x[2] : a->x[1];                                        \
    const ET *restrict B0 = Bn[0], *restrict B1 = Bn[1], *restrict B2 = Bn[d == 3 ? 2 : 1];        \
    const ET *restrict B3 = Bn[d == 3 ? 3 : 2], *restrict B4 = Bn[d == 3 ? 4 : 3];                 \
    const ET *restrict B5 = Bn[d == 3 ? 5 : 3], *restrict B6 = Bn[d == 3 ? 6 : 3];                 \
    const ET *restrict B7 = Bn[d == 3 ? 7 : 3], *restrict B8 = Bn[d == 3 ? 8 : 3];                 \
    const ET *restrict G0 = Gn[0], *restrict G1 = Gn[1], *restrict G2 = Gn[d == 3 ? 2 : 1];        \
    const ET *restrict G3 = Gn[d == 3 ? 3 : 2], *restrict G4 = Gn[d == 3 ? 4 : 3];                 \
    const ET *restrict G5 = Gn[d == 3 ? 5 : 3], *restrict G6 = Gn[d == 3 ? 6 : 3];                 \
    const ET *restrict G7 = Gn[d == 3 ? 7 : 3], *restrict G8 = Gn[d == 3 ? 8 : 3];                 \
    /* own tensors, double, as 3 x 3 (zero outside d x d) */                                       \
    double Ai[3][3] = {{0}}, Fi[3][3] = {{0}};                                                     \
    for (int r = 0; r < d; ++r)                                                                    \
      for (int c = 0; c < d; ++c) {                                                                \
        Ai[r][c] = a->A[r * d + c][i];                                                             \
        Fi[r][c] = a->F[r * d + c][i];                                                             \
      }                                                                                            \
    const double ki = stab ? kst[i] : 0.0;                                                         \
    double Bi[3][3], Gi[3][3];                                                                     \
    for (int r = 0; r < 3; ++r)                                                                    \
      for (int c = 0; c < 3; ++c) {                                                                \
        Gi[r][c] = ki * (Fi[r][c] - (r == c && r < d ? 1.0 : 0.0));                                \
        Bi[r][c] = stab == 1 ? Ai[r][c] - Gi[r][c] : Ai[r][c];                                     \
      }                                                                                            \
    const double c0 = X0[i], c1 = X1[i], c2 = d == 3 ? X2[i] : 0.0;                                \
    const double p0 = x0[i], p1 = x1[i], p2 = d == 3 ? x2[i] : 0.0;                                \
    const double F00 = Fi[0][0], F01 = Fi[0][1], F02 = Fi[0][2], F10 = Fi[1][0], F11 = Fi[1][1];   \
    const double F12 = Fi[1][2], F20 = Fi[2][0], F21 = Fi[2][1], F22 = Fi[2][2];                   \
    const double H00 = Gi[0][0], H01 = Gi[0][1], H02 = Gi[0][2], H10 = Gi[1][0], H11 = Gi[1][1];   \
    const double H12 = Gi[1][2], H20 = Gi[2][0], H21 = Gi[2][1], H22 = Gi[2][2];                   \
    const double delta = k->horizon;                                                               \
    double f0 = 0.0, f1 = 0.0, f2 = 0.0, s0 = 0.0, s1 = 0.0, s2 = 0.0;                             \
    double u0 = 0.0, u1 = 0.0, u2 = 0.0, zz = 0.0;                                                 \
    const pdk_bond_index b0 = bs[i], b1 = bs[i + 1];                                               \
    _Pragma(                                                                                       \
        "omp simd reduction(+ : f0, f1, f2, s0, s1, s2, u0, u1, u2, zz)") for (pdk_bond_index b =  \
                                                                                   b0;             \
                                                                               b < b1; ++b) {      \
      const pdk_index j = bj[b];                                                                   \
      const double wv = (has_alive ? (alive[b] ? omega[b] : 0.0) : omega[b]) * V[j];               \
      const double e0 = X0[j] - c0, e1 = X1[j] - c1, e2 = d == 3 ? X2[j] - c2 : 0.0;               \
      const double y0 = x0[j] - p0, y1 = x1[j] - p1, y2 = d == 3 ? x2[j] - p2 : 0.0;               \
      double t0, t1, t2 = 0.0;                                                                     \
      if (d == 3) {                                                                                \
        t0 = (double)B0[j] * e0 + (double)B1[j] * e1 + (double)B2[j] * e2;                         \
        t1 = (double)B3[j] * e0 + (double)B4[j] * e1 + (double)B5[j] * e2;                         \
        t2 = (double)B6[j] * e0 + (double)B7[j] * e1 + (double)B8[j] * e2;                         \
      } else {                                                                                     \
        t0 = (double)B0[j] * e0 + (double)B1[j] * e1;                                              \
        t1 = (double)B3[j] * e0 + (double)B4[j] * e1;                                              \
      }                                                                                            \
      s0 += wv * e0;                                                                               \
      s1 += wv * e1;                                                                               \
      s2 += wv * e2;                                                                               \
      if (stab == 1) {                                                                             \
        const double kj = kst[j];                                                                  \
        const double v0 = y0 - e0, v1 = y1 - e1, v2 = y2 - e2;                                     \
        t0 += kj * v0;                                                                             \
        t1 += kj * v1;                                                                             \
        t2 += kj * v2;                                                                             \
        u0 += wv * v0;                                                                             \
        u1 += wv * v1;                                                                             \
        u2 += wv * v2;                                                                             \
        const double z0 = y0 - (F00 * e0 + F01 * e1 + F02 * e2);                                   \
        const double z1 = y1 - (F10 * e0 + F11 * e1 + F12 * e2);                                   \
        const double z2 = y2 - (F20 * e0 + F21 * e1 + F22 * e2);                                   \
        zz += wv * (z0 * z0 + z1 * z1 + z2 * z2);                                                  \
      }                                                                                            \
      if (stab == 2) {                                                                             \
        const double kj = kst[j];                                                                  \
        double g0, g1, g2 = 0.0;                                                                   \
        if (d == 3) {                                                                              \
          g0 = ((double)G0[j] + H00) * e0 + ((double)G1[j] + H01) * e1 +                           \
               ((double)G2[j] + H02) * e2;                                                         \
          g1 = ((double)G3[j] + H10) * e0 + ((double)G4[j] + H11) * e1 +                           \
               ((double)G5[j] + H12) * e2;                                                         \
          g2 = ((double)G6[j] + H20) * e0 + ((double)G7[j] + H21) * e1 +                           \
               ((double)G8[j] + H22) * e2;                                                         \
        } else {                                                                                   \
          g0 = ((double)G0[j] + H00) * e0 + ((double)G1[j] + H01) * e1;                            \
          g1 = ((double)G3[j] + H10) * e0 + ((double)G4[j] + H11) * e1;                            \
        }                                                                                          \
        const double yy = y0 * y0 + y1 * y1 + y2 * y2;                                             \
        const double xx = e0 * e0 + e1 * e1 + e2 * e2;                                             \
        const double q = yy > 0.0 ? 1.0 / yy : 0.0;                                                \
        const double uy = (y0 - e0) * y0 + (y1 - e1) * y1 + (y2 - e2) * y2;                        \
        const double g =                                                                           \
            yy > 0.0 ? delta / sqrt(xx) * ((ki + kj) * uy - (g0 * y0 + g1 * y1 + g2 * y2)) * q     \
                     : 0.0;                                                                        \
        t0 += g * y0;                                                                              \
        t1 += g * y1;                                                                              \
        t2 += g * y2;                                                                              \
      }                                                                                            \
      f0 += wv * t0;                                                                               \
      f1 += wv * t1;                                                                               \
      f2 += wv * t2;                                                                               \
    }                                                                                              \
    (void)B2, (void)B5, (void)B6, (void)B7, (void)B8, (void)G2, (void)G5, (void)G6, (void)G7;      \
    (void)G8, (void)F02, (void)F12, (void)F20, (void)F21, (void)F22, (void)H02, (void)H12;         \
    (void)H20, (void)H21, (void)H22, (void)u2;                                                     \
    const double s[3] = {s0, s1, s2}, u[3] = {u0, u1, u2}, ff[3] = {f0, f1, f2};                   \
    for (int r = 0; r < d; ++r) {                                                                  \
      double v = ff[r] + ki * u[r];                                                                \
      for (int c = 0; c < d; ++c)                                                                  \
        v += Bi[r][c] * s[c];                                                                      \
      a->f[r][i] = v;                                                                              \
    }                                                                                              \
    if (stab == 1) {                                                                               \
      a->W[i] += 0.5 * ki * zz;                                                                    \
      if ((a->flag[i] & PDK_CORR_FLAG_FAILED_NOW) && a->m[i] > 0.0)                                \
        a->w_damage[i] += 0.5 * pdk_corr_kst_unflagged(k, a, i) * zz;                                  \
    }                                                                                              \
  }

CORR_PASS2_ROW(pass2_row_d, double)
CORR_PASS2_ROW(pass2_row_f, float)

#define CORR_PASS2_ROWS(ROW, Bn, Gn)                                                               \
  do {                                                                                             \
    const int ha = a->bond_alive != NULL;                                                          \
    for (pdk_index i = i0; i < i1; ++i) {                                                          \
      if (d == 2) {                                                                                \
        if (ha)                                                                                    \
          ROW(2, 1, stab, k, a, Bn, Gn, i);                                                        \
        else                                                                                       \
          ROW(2, 0, stab, k, a, Bn, Gn, i);                                                        \
      } else {                                                                                     \
        if (ha)                                                                                    \
          ROW(3, 1, stab, k, a, Bn, Gn, i);                                                        \
        else                                                                                       \
          ROW(3, 0, stab, k, a, Bn, Gn, i);                                                        \
      }                                                                                            \
    }                                                                                              \
  } while (0)

/* One instantiation per (storage, stabilization): d, has_alive become constants inside. */
CORR_INLINE void pass2_rows(const int stab, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                            pdk_index i0, pdk_index i1) {
  const int d = k->dim;
  if (a->Bf[0]) {
    const float *const *Bn = (const float *const *)a->Bf;
    const float *const *Gn = (const float *const *)(stab == 2 ? a->Gf : a->Bf);
    CORR_PASS2_ROWS(pass2_row_f, Bn, Gn);
  } else {
    const double *const *Bn = (const double *const *)(stab == 1 ? a->B : a->A);
    const double *const *Gn = stab == 2 ? (const double *const *)a->G : Bn;
    CORR_PASS2_ROWS(pass2_row_d, Bn, Gn);
  }
}

void CORR_FN(pdk_kernel_corr_pass2_)(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                     pdk_index i0, pdk_index i1) {
  if (a->own && k->stab != PDK_KERNEL_STAB_HOURGLASS)
    rows_pass2(k, a, i0, i1);
  else if (k->stab == PDK_KERNEL_STAB_SILLING)
    pass2_rows(1, k, a, i0, i1);
  else if (k->stab == PDK_KERNEL_STAB_HOURGLASS)
    pass2_rows(2, k, a, i0, i1);
  else
    pass2_rows(0, k, a, i0, i1);
}
