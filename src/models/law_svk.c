/* Correspondence law svk (St Venant-Kirchhoff): S = lambda tr(E) I + 2 mu E, P = F S.
 * Stress and energy: kernels/ref/corr_law.h. */
#include "kernels.h"
#include "law.h"
#include "pdk/model.h"

_Static_assert(PDK_KERNEL_LAW_SVK == (int)PDK_LAW_SVK, "law values");

/* sigma = P F^T / J; plane strain sigma_zz = lambda tr(E) / J. */
static int svk_cauchy(int d, double lambda, const double F[3][3], const double P[3][3],
                      double S[3][3]) {
  const double J = pdk_law_det3(F);
  if (!pdk_law_cauchy_of_P(d, F, P, J, S)) return 0;
  if (d == 2) {
    double trE = 0.0;
    for (int a = 0; a < 2; ++a)
      trE += 0.5 * (F[0][a] * F[0][a] + F[1][a] * F[1][a] - 1.0);
    S[2][2] = lambda * trE / J;
  }
  return 1;
}

const pdk_law_info pdk_law_svk = {
    .law = PDK_LAW_SVK, .name = "svk", .flags = PDK_LAWF_HYPERELASTIC, .cauchy = svk_cauchy};
