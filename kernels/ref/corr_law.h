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
#include "ref/tensor_d.h"

static inline void pdk_corr_mul_d(const int d, const double S[3][3], const double T[3][3],
                                  double R[3][3]) {
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += S[a][e] * T[e][c];
      R[a][c] = s;
    }
}

/* Elastic laws (linear, SVK, Neo-Hooke) in dimension d = k->dim: P(F) and W(F); return 0 if the law
 * is undefined at F (or for another law). */
static inline int pdk_corr_law_eval_d(const int d, const pdk_corr_consts *k, const double F[3][3],
                                      double P[3][3], double *W) {
  const double lambda = k->lambda, mu = k->mu;
  switch (k->law) {
  case PDK_KERNEL_LAW_LINEAR_ELASTIC: {
    double eps[3][3], tr = 0.0, ee = 0.0;
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) {
        eps[a][c] = 0.5 * (F[a][c] + F[c][a]) - (a == c ? 1.0 : 0.0);
        ee += eps[a][c] * eps[a][c];
      }
    for (int a = 0; a < d; ++a)
      tr += eps[a][a];
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        P[a][c] = 2.0 * mu * eps[a][c] + (a == c ? lambda * tr : 0.0);
    *W = 0.5 * lambda * tr * tr + mu * ee;
    return 1;
  }
  case PDK_KERNEL_LAW_SVK: {
    double E[3][3], S[3][3], tr = 0.0, ee = 0.0;
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) {
        double C = 0.0;
        for (int e = 0; e < d; ++e)
          C += F[e][a] * F[e][c];
        E[a][c] = 0.5 * (C - (a == c ? 1.0 : 0.0));
        ee += E[a][c] * E[a][c];
      }
    for (int a = 0; a < d; ++a)
      tr += E[a][a];
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        S[a][c] = 2.0 * mu * E[a][c] + (a == c ? lambda * tr : 0.0);
    pdk_corr_mul_d(d, F, S, P);
    *W = 0.5 * lambda * tr * tr + mu * ee;
    return 1;
  }
  case PDK_KERNEL_LAW_NEO_HOOKE: {
    const double J = pdk_det_d(d, F);
    if (!(J > 0.0) || !isfinite(J)) return 0;
    double Finv[3][3], ff = 0.0;
    pdk_inv_d(d, F, J, Finv);
    const double lnJ = log(J);
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c) {
        const double FinvT = Finv[c][a];
        P[a][c] = mu * (F[a][c] - FinvT) + lambda * lnJ * FinvT;
        ff += F[a][c] * F[a][c];
      }
    *W = 0.5 * mu * (ff - d) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
    return 1;
  }
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
