/* Correspondence law neo_hooke: P(F) and W(F) in dimension d (d x d in the top-left of 3 x 3),
 * compressible Neo-Hooke: P = mu (F - F^-T) + lambda ln(J) F^-T. Called by pdk_corr_law_eval_d
 * (kernels/ref/corr_law.h); the law's pdk-side entry is src/models/law_neo_hooke.c. Returns 0 if the law
 * is undefined at F. */
#ifndef PDK_KERNELS_LAW_NEO_HOOKE_H
#define PDK_KERNELS_LAW_NEO_HOOKE_H

#include <math.h>

#include "ref/tensor_d.h"

static inline int pdk_law_neo_hooke_eval_d(const int d, const double lambda, const double mu,
                                           const double F[3][3], double P[3][3], double *W) {
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

#endif
