/* Correspondence law linear_elastic: P(F) and W(F) in dimension d (d x d in the top-left of 3 x
 * 3), small strain: sigma = lambda tr(eps) I + 2 mu eps, P = sigma. Called by pdk_corr_law_eval_d
 * (kernels/ref/corr_law.h); the law's pdk-side entry is src/models/law_linear_elastic.c. Returns 0 if the
 * law is undefined at F. */
#ifndef PDK_KERNELS_LAW_LINEAR_ELASTIC_H
#define PDK_KERNELS_LAW_LINEAR_ELASTIC_H

#include <math.h>

#include "ref/tensor_d.h"

static inline int pdk_law_linear_elastic_eval_d(const int d, const double lambda, const double mu,
                                                const double F[3][3], double P[3][3], double *W) {
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

#endif
