/* Correspondence law linear_elastic (small strain): sigma = lambda tr(eps) I + 2 mu eps, P = sigma.
 * Stress and energy: kernels/ref/corr_law.h. Not objective: rotations beyond a few degrees create
 * strain energy. */
#include "kernels.h"
#include "law.h"
#include "pdk/model.h"

_Static_assert(PDK_KERNEL_LAW_LINEAR_ELASTIC == (int)PDK_LAW_LINEAR_ELASTIC, "law values");

/* sigma = sym(P) (small strain: P is sigma); plane strain sigma_zz = lambda tr(eps). */
static int linear_cauchy(int d, double lambda, const double F[3][3], const double P[3][3],
                         double S[3][3]) {
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      S[a][c] = 0.5 * (P[a][c] + P[c][a]);
  if (d == 2) S[2][2] = lambda * (F[0][0] - 1.0 + F[1][1] - 1.0);
  return 1;
}

const pdk_law_info pdk_law_linear_elastic = {.law = PDK_LAW_LINEAR_ELASTIC,
                                             .name = "linear_elastic",
                                             .flags = PDK_LAWF_HYPERELASTIC,
                                             .cauchy = linear_cauchy};
