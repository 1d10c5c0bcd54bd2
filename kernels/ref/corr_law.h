/* Correspondence: the small dense tensors (d x d in the top-left of 3 x 3, row-major) and the
 * elastic laws P(F), W(F), shared by the reference (kernels/ref/corr.c) and the packed-row
 * variants' per-particle end (kernels/opt/corr_simd.h): one source, so both evaluate the same
 * operations (the variants' targets may contract a product and a sum into one FMA: round-off,
 * tests/t044). Formulas: kernels/ref/corr.c. d is a parameter so that a caller with a constant d
 * gets the loops unrolled. */
#ifndef PDK_KERNELS_CORR_LAW_H
#define PDK_KERNELS_CORR_LAW_H

#include <math.h>

#include "kernels.h"
#include "ref/law_linear_elastic.h"
#include "ref/law_neo_hooke.h"
#include "ref/law_svk.h"
#include "ref/tensor_d.h"

/* Elastic laws in dimension d = k->dim: P(F) and W(F), each law in its own header
 * (kernels/ref/law_<law>.h); return 0 if the law is undefined at F (or for another law). */
static inline int pdk_corr_law_eval_d(const int d, const pdk_corr_consts *k, const double F[3][3],
                                      double P[3][3], double *W) {
  const double lambda = k->lambda, mu = k->mu;
  switch (k->law) {
  case PDK_KERNEL_LAW_LINEAR_ELASTIC: return pdk_law_linear_elastic_eval_d(d, lambda, mu, F, P, W);
  case PDK_KERNEL_LAW_SVK: return pdk_law_svk_eval_d(d, lambda, mu, F, P, W);
  case PDK_KERNEL_LAW_NEO_HOOKE: return pdk_law_neo_hooke_eval_d(d, lambda, mu, F, P, W);
  }
  return 0;
}

/* The per-particle end of pass 1 from D (F = I + D K^-1) for an elastic law and a family that
 * spans (no Johnson-Cook; the caller takes pdk_kernel_corr_point_disp_ref otherwise), inline so
 * that F and A stay in registers for what the caller builds from them: the reference's point_end
 * with the same operations. Stores F, A, W and flag bit INVERTED of i, returns F and A (A = 0 where
 * the law is undefined). Used by the packed-row and stencil passes (kernels/opt/corr_simd.h,
 * corr_stencil.h). */
static inline void pdk_corr_end_elastic(const int d, const pdk_corr_consts *k,
                                        const pdk_corr_arrays *a, pdk_index i, const double D[3][3],
                                        double F[3][3], double A[3][3]) {
  pdk_corr_consts k_i; /* multi-material: particle i's lambda, mu */
  const pdk_corr_consts *ki = pdk_corr_consts_at(k, i, &k_i);
  double Kinv[3][3] = {{0}}, P[3][3] = {{0}}, W = 0.0;
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      Kinv[r][c] = a->Kinv[r * d + c][i];
  pdk_corr_mul_d(d, D, Kinv, F);
  for (int c = 0; c < d; ++c)
    F[c][c] += 1.0;
  if (pdk_corr_law_eval_d(d, ki, F, P, &W)) {
    pdk_corr_mul_d(d, P, Kinv, A);
    a->W[i] = W;
    a->flag[i] = (uint8_t)(a->flag[i] & ~PDK_CORR_FLAG_INVERTED);
  } else {
    a->W[i] = 0.0;
    a->flag[i] = (uint8_t)(a->flag[i] | PDK_CORR_FLAG_INVERTED);
  }
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      a->F[r * d + c][i] = F[r][c];
      a->A[r * d + c][i] = A[r][c];
    }
}

#endif
