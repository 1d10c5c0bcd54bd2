/* Peridynamic Galerkin on Bode et al.'s manufactured field (2022 section 7.3, eqs. 86-87):
 * u = (sin(pi X/2) cos(pi Y/2), cos(pi X/2) sin(pi Y/2)) on [-1, 1]^2, its body force
 * (pi^2/2)(lambda + 2 mu) u, the exact values on the edge particles, the irregular cloud of the
 * patch test (n1 = 9, 17, 33 nodes a side, jitter 0.3 h), horizon 2.51 h, Newton; relative L2
 * error of u (the same runs as bench/bench_pg_tradeoff.c).
 * labels: galerkin physics
 *
 * What must hold, and why these bounds. Bode et al. report order 2 in L2 for the PG method
 * (their Fig. 6). Measured orders 9 -> 17 -> 33: taylor vc1 2.23, 2.08; with the bond correction
 * 2.19, 1.84 (2.00 and 1.96 further on, docs/tradeoff.md); asserted >= 1.7 on each step, a first-
 * order method fails it. The bond correction's error is lower (measured 2.7x at n1 = 33;
 * asserted lower). Correspondence with Silling's stabilization on the same particles and
 * families converges at first order at best here (measured 0.85, 1.01); asserted: its error at
 * n1 = 33 above 3 times galerkin's (measured 7.6x).
 */
#include "galerkin_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const int n1s[3] = {9, 17, 33};
  double e[4][3];
  for (int model = 0; model < 4; ++model) {
    if (model == 1) continue;
    for (int r = 0; r < 3; ++r) {
      e[model][r] = pg_mms_run(ctx, 1, model, n1s[r], NULL, NULL, NULL);
      T_INFO("model %d n1 %d: L2 %.4e%s", model, n1s[r], e[model][r], r ? "" : "\n");
      if (r) T_INFO(" order %.3f\n", log(e[model][r - 1] / e[model][r]) / log(2.0));
    }
  }
  for (int model = 2; model < 4; ++model)
    for (int r = 1; r < 3; ++r) {
      const double order = log(e[model][r - 1] / e[model][r]) / log(2.0);
      T_ASSERT(order >= 1.7, "galerkin (model %d): order %.3f from n1 %d to %d", model, order,
               n1s[r - 1], n1s[r]);
    }
  T_ASSERT(e[3][2] < e[2][2], "bond correction: %.3e, without %.3e", e[3][2], e[2][2]);
  T_ASSERT(e[0][2] > 3 * e[2][2], "correspondence %.3e against galerkin %.3e", e[0][2], e[2][2]);
  pdk_ctx_destroy(&ctx);
  return 0;
}
