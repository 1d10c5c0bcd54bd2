/* Johnson-Cook damage stays in [0, 1]: one step can carry D_n + d_eps_p / eps_f far past the
 * critical damage, and D was stored as that sum (the shipped two-hole plate ended with D = 1.57);
 * with coupling: effective the step's plastic dissipation (1 - (D_n + D)/2) int sigma_y d eps_p
 * then turned negative (-2.5e6 J/m^3 at D = 1.81), against the documented dW_plastic >= 0. The
 * update caps D at 1 (Johnson-Cook's fracture) on the step the point fails.
 * One material point (pdk_jc_update, and pdk_jc_update_avg), plane strain and 3-D, both
 * couplings:
 *  1. from the virgin state, one step of axial logarithmic strain 8 (lateral -4, isochoric:
 *     d_eps_p ~ 8, eps_f <= 3.49, so d_eps_p / eps_f > 2): the point fails with D = 1
 *     exactly;
 *  2. D_c = 1, D_n = 0.9, a step of axial strain 4 (D would be above 1.5): D = 1, and
 *     dW_plastic >= 0 (coupling effective: (1 - (0.9 + 1)/2) = 0.05 of the hardening integral);
 *  3. below the cap nothing changes: a small step from D_n = 0.1 gives D = D_n + d_eps_p / eps_f
 *     (the law's own failure strain) to 1e-15.
 * labels: unit physics
 */
#include "jc_util.h"

static void set_F(int dim, double la, double lr, double F[3][3]) {
  ju_identity(F);
  F[0][0] = exp(la);
  F[1][1] = exp(lr);
  if (dim == 3) F[2][2] = exp(lr);
}

/* One step to axial log strain la from `in`, the lateral strain -la/2 (isochoric: plastic flow
 * dominates at these strains). */
static void step(const pdk_jc_params *p, int dim, int avg, double la, const pdk_jc_state *in,
                 pdk_jc_state *out, pdk_jc_result *r) {
  double F[3][3], P[3][3];
  set_F(dim, la, -0.5 * la, F);
  const int err = avg ? pdk_jc_update_avg(p, dim, F, 1e-3, 1e9, in, out, P, r)
                      : pdk_jc_update(p, dim, F, 1e-3, in, out, P, r);
  T_ASSERT(!err, "pdk_jc_update returned %d", err);
}

int main(void) {
  for (int dim = 2; dim <= 3; ++dim)
    for (int coupling = 0; coupling <= 1; ++coupling)
      for (int avg = 0; avg <= 1; ++avg) {
        pdk_jc_params p = pdk_jc_params_default();
        p.coupling = (pdk_jc_coupling)coupling;
        const char *what = coupling ? "effective" : "none";
        pdk_jc_state in = pdk_jc_state_initial(), out;
        pdk_jc_result r;

        /* 1. the virgin state, one big step */
        step(&p, dim, avg, 8.0, &in, &out, &r);
        T_ASSERT(r.failed_now && out.failed, "dim %d %s: the point fails", dim, what);
        T_ASSERT(r.d_eps_p / r.failure_strain > 1.0,
                 "dim %d %s: the step's increment %g must exceed 1 for the case to test the cap",
                 dim, what, r.d_eps_p / r.failure_strain);
        T_ASSERT(out.damage == 1.0, "dim %d %s avg %d: D = %.17g after one step past failure", dim,
                 what, avg, out.damage);
        T_ASSERT(r.dW_plastic >= 0.0, "dim %d %s: dW_plastic = %g", dim, what, r.dW_plastic);

        /* 2. D_c = 1, D_n = 0.9, D_n + increment ~ 1.8 */
        p.D_c = 1.0;
        in = pdk_jc_state_initial();
        in.damage = 0.9;
        step(&p, dim, avg, 4.0, &in, &out, &r);
        T_ASSERT(in.damage + r.d_eps_p / r.failure_strain > 1.5,
                 "dim %d %s: the increment %g is too small for the case", dim, what,
                 r.d_eps_p / r.failure_strain);
        T_ASSERT(out.failed && out.damage == 1.0, "dim %d %s avg %d: failed %d, D = %.17g", dim,
                 what, avg, out.failed, out.damage);
        T_ASSERT(r.dW_plastic > 0.0,
                 "dim %d %s avg %d: dW_plastic = %g at D %g (plastic strain %g)", dim, what, avg,
                 r.dW_plastic, out.damage, r.d_eps_p);

        /* 3. below the cap: D_n + d_eps_p / eps_f */
        in = pdk_jc_state_initial();
        in.damage = 0.1;
        step(&p, dim, avg, 0.02, &in, &out, &r);
        T_ASSERT(r.plastic && !out.failed, "dim %d %s: a plastic step below failure", dim, what);
        T_NEAR(out.damage, 0.1 + r.d_eps_p / r.failure_strain, 1e-15, 0.0, "dim %d %s: D", dim,
               what);
      }
  return 0;
}
