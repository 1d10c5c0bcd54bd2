/* Correspondence law svk: P(F) and W(F) in dimension d (d x d in the top-left of 3 x 3), St
 * Venant-Kirchhoff: S = lambda tr(E) I + 2 mu E, P = F S. Called by pdk_corr_law_eval_d
 * (kernels/ref/corr_law.h); the law's pdk-side entry is src/models/law_svk.c. Returns 0 if the law is
 * undefined at F. */
#ifndef PDK_KERNELS_LAW_SVK_H
#define PDK_KERNELS_LAW_SVK_H

#include <math.h>

#include "ref/tensor_d.h"

static inline int pdk_law_svk_eval_d(const int d, const double lambda, const double mu,
                                     const double F[3][3], double P[3][3], double *W) {
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

#endif
