/* Correspondence law neo_hooke (compressible): P = mu (F - F^-T) + lambda ln(J) F^-T.
 * Stress and energy: kernels/ref/corr_law.h. */
#include <math.h>

#include "kernels.h"
#include "law.h"
#include "pdk/model.h"

_Static_assert(PDK_KERNEL_LAW_NEO_HOOKE == (int)PDK_LAW_NEO_HOOKE, "law values");

/* sigma = P F^T / J; plane strain sigma_zz = lambda ln(J) / J. */
static int neo_hooke_cauchy(int d, double lambda, const double F[3][3], const double P[3][3],
                            double S[3][3]) {
  const double J = pdk_law_det3(F);
  if (!pdk_law_cauchy_of_P(d, F, P, J, S)) return 0;
  if (d == 2) S[2][2] = lambda * log(J) / J;
  return 1;
}

const pdk_law_info pdk_law_neo_hooke = {.law = PDK_LAW_NEO_HOOKE,
                                        .name = "neo_hooke",
                                        .flags = PDK_LAWF_HYPERELASTIC,
                                        .cauchy = neo_hooke_cauchy};
