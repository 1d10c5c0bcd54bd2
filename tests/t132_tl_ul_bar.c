/* V-BL example II (Bergel & Li 2016, section 4.2): a 0.1 x 0.1 x 1.0 St Venant-Kirchhoff bar
 * (lambda = 200, mu = 20, rho0 = 1.4) pulled by an end traction, solved to equilibrium with
 * adaptive dynamic relaxation in TL and in UL connectivity; both top displacements lie close to
 * the analytical value, and their difference is reported.
 * labels: physics
 *
 * Setup. Simple cubic lattice of spacing h = 0.02 (5 x 5 x 50 = 1250 particles at cell centres;
 * the paper has 1075, spacing and horizon unstated), horizon 2.015 h, constant influence, no
 * stabilization (as the paper), then again with Silling's C_s = 0.1. Bottom layer: u_z = 0; the
 * particles on the
 * planes x = 0.05 and y = 0.05 (symmetry planes of the uniaxial solution) hold u_x = 0 and u_y = 0
 * so the bar cannot drift or spin; top layer: body force b_z = tau / h, i.e. the nominal traction
 * tau on the end face. UL rebuilds its families at every committing pass where particles moved
 * more than ul_skin delta / 2 since the last one (ul_skin = 0.1); the load is applied in 4 levels,
 * so the families are rebuilt in the stretched configuration along the way (the test asserts at
 * least one rebuild).
 * The printed parameters of the paper are inconsistent (notes 004, 4.2: tau_z = 14 would stretch
 * the bar by ~20%, not give 0.01), so the traction here is chosen to give the paper's analytical
 * top displacement of about 0.01: tau = 0.58, and the analytical value is the uniaxial SVK
 * solution for a nominal traction, lambda3 E (lambda3^2 - 1)/2 = tau with Young's modulus
 * E = mu (3 lambda + 2 mu)/(lambda + mu), over the length 1 - h between the centres of the bottom
 * and top layers: u = (lambda3 - 1)(1 - h) = 9.627e-3.
 * The paper's TL +2.4% / UL -1.8% is a comparison, not a target. Measured here (probe: mean u_z of
 * the top layer; ADR to rtol 1e-7, 2 UL rebuilds):
 *   no stabilization   TL 9.522e-3 (-1.09%), UL 9.495e-3 (-1.37%), UL/TL - 1 = -0.28%
 *   Silling 0.1        TL 9.468e-3 (-1.65%), UL 9.471e-3 (-1.62%), UL/TL - 1 = +0.04%
 * Asserted: both within 3% of the analytical value (the error of a 5-particle cross-section whose
 * every particle lies within the horizon of a free surface), and TL - UL within 0.5%. The paper's
 * pattern (TL above, UL below the analytical value, 4% apart) is not reproduced: here UL's
 * spatial gradient and rebuilt families change the answer by much less than the surface error
 * both share, and both lie below.
 * V-BL asks the TL bar by ADR to be compared with the Newton solution: with Silling 0.1 the TL bar
 * is solved again by Newton (rtol 1e-10) and every particle's displacement must agree with ADR's to
 * 1e-4 of the largest one. Why that bound: ADR stops at ||r|| <= 1e-7 ||F_ext||; the displacement
 * error it leaves is K^-1 r, and since what is left of r lies mostly in the soft modes that carry
 * the solution, |e| / |u| is of the order of the residual ratio, with a factor 1000 for the spread
 * over the spectrum (the argument of t110). Measured: 5.7e-7 (Newton: 1 level, 4 iterations).
 * PDK_TEST_VERBOSE=1 prints the solves.
 */
#include "bar_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double h = 0.02, tau = 0.58;
  const double exact = bar_analytical(h);
  for (int stab = 0; stab < 2; ++stab) {
    bar_result tl = solve_bar(ctx, PDK_CONNECTIVITY_TL, stab, tau, h, PDK_STATIC_ADR, 1e-7);
    bar_result ul = solve_bar(ctx, PDK_CONNECTIVITY_UL, stab, tau, h, PDK_STATIC_ADR, 1e-7);
    const double e_tl = tl.u_top / exact - 1.0, e_ul = ul.u_top / exact - 1.0;
    const double diff = ul.u_top / tl.u_top - 1.0;
    const char *what = stab ? "Silling 0.1" : "no stabilization";
    if (getenv("PDK_TEST_VERBOSE"))
      printf("%s: analytical %.6e\nTL %.6e (%+.3f%%, %ld iterations)\nUL %.6e (%+.3f%%, %ld "
             "iterations, %ld rebuilds)\nUL / TL - 1 = %+.3f%%\n",
             what, exact, tl.u_top, 100 * e_tl, tl.iterations, ul.u_top, 100 * e_ul, ul.iterations,
             ul.rebuilds, 100 * diff);
    T_ASSERT(ul.rebuilds >= 1, "%s: UL never rebuilt its families (ul_skin 0.1)", what);
    T_ASSERT(fabs(e_tl) <= 0.03, "%s: TL top displacement %.6e is %.2f%% off %.6e", what, tl.u_top,
             100 * e_tl, exact);
    T_ASSERT(fabs(e_ul) <= 0.03, "%s: UL top displacement %.6e is %.2f%% off %.6e", what, ul.u_top,
             100 * e_ul, exact);
    T_ASSERT(fabs(diff) <= 0.005, "%s: UL differs from TL by %.3f%%", what, 100 * diff);
    if (stab) {
      /* The same TL bar by Newton (the stabilized tangent is regular; without stabilization the
       * constant-influence families have zero-energy modes and Newton refuses the singular
       * tangent, t111). */
      bar_result nt = solve_bar(ctx, PDK_CONNECTIVITY_TL, stab, tau, h, PDK_STATIC_NEWTON, 1e-10);
      T_ASSERT(nt.n == tl.n, "particle counts differ");
      double dmax = 0.0, umax = 0.0;
      for (pdk_index k = 0; k < 3 * nt.n; ++k) {
        dmax = fmax(dmax, fabs(nt.u[k] - tl.u[k]));
        umax = fmax(umax, fabs(nt.u[k]));
      }
      if (getenv("PDK_TEST_VERBOSE"))
        printf("%s: TL by Newton %.6e (%ld iterations); max |u_adr - u_newton| / max |u| = %.2e\n",
               what, nt.u_top, nt.iterations, dmax / umax);
      T_ASSERT(dmax <= 1e-4 * umax,
               "%s: ADR and Newton differ by %.2e of max |u| (bound 1e-4 = 1000 x ADR's rtol)",
               what, dmax / umax);
      free(nt.u);
    }
    free(tl.u);
    free(ul.u);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
