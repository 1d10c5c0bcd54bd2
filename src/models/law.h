/* Private: helpers the correspondence laws' files share (src/law_*.c, src/models/model_corr_derived.c). */
#ifndef PDK_LAW_H
#define PDK_LAW_H

#include "model_impl.h"

/* det F of a 3 x 3 matrix (F[2][2] = 1 in 2-D). */
static inline double pdk_law_det3(const double F[3][3]) {
  return F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
         F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
         F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
}

/* The d x d block of the Cauchy stress P F^T / J; 0 when J <= 0 (S is then not set). */
static inline int pdk_law_cauchy_of_P(int d, const double F[3][3], const double P[3][3], double J,
                                      double S[3][3]) {
  if (!(J > 0)) return 0;
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c) {
      double v = 0.0;
      for (int e = 0; e < d; ++e)
        v += P[a][e] * F[c][e];
      S[a][c] = v / J;
    }
  return 1;
}

#endif
