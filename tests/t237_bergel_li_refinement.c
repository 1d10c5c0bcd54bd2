/* V-BL example II (Bergel & Li 2016, section 4.2), the causes of the difference: tests/t132 solves
 * the paper's bar (5 x 5 x 50 particles, spacing h = 0.02) and finds TL -1.09% and UL -1.37% below
 * the analytical top displacement, where the paper reports TL +2.4% and UL -1.8% (ledger row L6).
 * Two listed causes are tested here.
 * labels: physics slow
 *
 * 1. Surface error of the cross-section. Every particle of a 5-particle cross-section lies within
 *    the horizon (2.015 h) of a free surface, where the correspondence model's families are
 *    one-sided. If pdk's deficit is that surface error, it falls with h at fixed horizon factor
 *    (the share of particles near a surface is ~ 4 * 2 h / W): the TL bar is solved again, by ADR
 *    to rtol 1e-7 as in t132, with 3, 5, 7 and 9 particles across (h = W/3 ... W/9; odd counts so
 *    a column of particles lies on each symmetry plane). Measured: -1.59%, -1.09%, -0.90%, -0.74%:
 *    a line in h, error = c + a h, with c = -0.33% (what is left at h -> 0 at a fixed horizon
 *    factor: the one-sided families at the loaded and the fixed end, and the non-local model's own
 *    consistency error) and a first-order surface term of -1.26% at h = W/3 (largest residual of
 *    the line 0.021%). Asserted: |error| falls at each refinement; the least-squares line
 *    through the four errors misses none by more than a tenth of the range they span (so the
 *    deficit is a first-order term in h, the surface share ~ h / W, not noise); |c| <= 0.5% (the
 *    paper's +2.4% for TL lies on the other side).
 * 2. Dynamic-relaxation damping. ADR stops at a residual ratio of 1e-7 whatever its damping;
 *    t132 already shows Newton's equilibrium equals ADR's to 5.6e-7 of the largest displacement,
 *    so the damping cannot move the result: here the 5-across bar is solved with rtol 1e-7 (t132's)
 *    and 1e-10, and the top displacements must agree to 1e-4 relative (the displacement error ADR
 *    leaves is of the order of its residual ratio times the spread of the spectrum, 1000: t132's
 *    argument). Measured at rtol 1e-5: 5.1e-5 from the converged value already.
 * Not tested: the paper's own particle layout (1075 = 5 x 5 x 43 particles would mean a
 * non-cubic spacing along the bar) and its traction (the printed one is inconsistent, t132).
 * Measured (PDK_TEST_VERBOSE=1 prints them): see docs/validation/README.md row L6.
 */
#include "bar_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double W = 0.1, tau = 0.58;
  const int across[4] = {3, 5, 7, 9};
  double err[4];
  for (int k = 0; k < 4; ++k) {
    const double h = W / across[k];
    bar_result tl = solve_bar(ctx, PDK_CONNECTIVITY_TL, 0, tau, h, PDK_STATIC_ADR, 1e-7);
    err[k] = tl.u_top / bar_analytical(h) - 1.0;
    if (getenv("PDK_TEST_VERBOSE"))
      printf("TL, %d across (%ld particles): top displacement %.6e, %+.3f%% of %.6e (%ld "
             "iterations)\n",
             across[k], (long)tl.n, tl.u_top, 100 * err[k], bar_analytical(h), tl.iterations);
    free(tl.u);
  }
  /* Least-squares line err = c + a h through the four bars. */
  double sh = 0, se = 0, shh = 0, she = 0;
  for (int k = 0; k < 4; ++k) {
    const double h = W / across[k];
    sh += h;
    se += err[k];
    shh += h * h;
    she += h * err[k];
  }
  const double a = (4 * she - sh * se) / (4 * shh - sh * sh), c = (se - a * sh) / 4;
  double res = 0;
  for (int k = 0; k < 4; ++k)
    res = fmax(res, fabs(err[k] - (c + a * W / across[k])));
  if (getenv("PDK_TEST_VERBOSE"))
    printf("fit: error = %+.3f%% %+.3f%% x h / (0.1 / 3); largest residual %.3f%%\n", 100 * c,
           100 * a * W / 3, 100 * res);
  for (int k = 1; k < 4; ++k)
    T_ASSERT(fabs(err[k]) < fabs(err[k - 1]),
             "the error does not fall with h: %+.3f%% with %d across, %+.3f%% with %d",
             100 * err[k], across[k], 100 * err[k - 1], across[k - 1]);
  T_ASSERT(a < 0 && res <= 0.1 * fabs(err[0] - err[3]),
           "the errors are not a line in h (slope %.3g, residual %.3f%% against a span of %.3f%%)",
           a, 100 * res, 100 * fabs(err[0] - err[3]));
  T_ASSERT(fabs(c) <= 0.005, "the error extrapolated to h = 0 is %+.3f%% (bound 0.5%%)", 100 * c);

  const double h = 0.02;
  bar_result loose = solve_bar(ctx, PDK_CONNECTIVITY_TL, 0, tau, h, PDK_STATIC_ADR, 1e-7);
  bar_result tight = solve_bar(ctx, PDK_CONNECTIVITY_TL, 0, tau, h, PDK_STATIC_ADR, 1e-10);
  const double d = tight.u_top / loose.u_top - 1.0;
  if (getenv("PDK_TEST_VERBOSE"))
    printf("ADR rtol 1e-7: %.9e (%ld iterations); 1e-10: %.9e (%ld iterations); ratio - 1 = %.2e\n",
           loose.u_top, loose.iterations, tight.u_top, tight.iterations, d);
  T_ASSERT(fabs(d) <= 1e-4, "ADR's tolerance moves the top displacement by %.2e (bound 1e-4)", d);
  free(loose.u);
  free(tight.u);
  pdk_ctx_destroy(&ctx);
  return 0;
}
