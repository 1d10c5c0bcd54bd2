/* The Johnson-Cook update's plane-strain path and its kernel entry against the 3-D update.
 *  A. pdk_jc_update with dim 2 works on the xy block of b_tr (kernels/ref/jc.c, trial_plane);
 *     dim 3 on the same F (F33 = 1, no out-of-plane shear) takes the general 3 x 3 path
 * (congruence, cyclic Jacobi). Along a non-proportional plane path (stretch on rotating axes,
 * shear, unloading and reloading, so elastic and plastic steps) run to failure, every step gives
 * the same bits from both: history, P (xy block), W, the energies, von Mises stress, yield stress,
 *     triaxiality, failure strain, flags; the Cauchy stress equal as numbers (the zero
 *     out-of-plane shear may differ in sign). Settings: rate independent without damage; rate
 *     terms on with damage (own pressure and a given family pressure); thermal with coupled
 *     damage; failed points with the compressive pressure kept.
 *  B. pdk_jc_update_kernel (what the correspondence kernels call) gives the same bits as
 *     pdk_jc_update / pdk_jc_update_avg in everything but res->sigma, which it leaves 0.
 * labels: unit physics
 *
 * Tolerance: none; the plane path is meant to be the 3 x 3 path's arithmetic without the terms
 * that are exactly zero, so any difference is a defect (a wrong eigenvector sign or order, a
 * missing term, a changed sum order).
 */
#include "jc_util.h"
#include "kernels.h" /* pdk_jc_update_kernel */

/* Result fields equal bit for bit, sigma excepted (compared by the caller). */
static int result_equal(const pdk_jc_result *a, const pdk_jc_result *b) {
  const double x[] = {a->W,          a->dW_plastic,  a->dW_damage,    a->tau_vm,
                      a->sigma_vm,   a->J,           a->yield_stress, a->d_eps_p,
                      a->eps_p_rate, a->triaxiality, a->sigma_m_eff,  a->failure_strain};
  const double y[] = {b->W,          b->dW_plastic,  b->dW_damage,    b->tau_vm,
                      b->sigma_vm,   b->J,           b->yield_stress, b->d_eps_p,
                      b->eps_p_rate, b->triaxiality, b->sigma_m_eff,  b->failure_strain};
  return memcmp(x, y, sizeof x) == 0 && a->plastic == b->plastic && a->failed_now == b->failed_now;
}

/* Step k of the plane path: stretch exp(h) on axes at angle a, shear 0.3 h; h rises 2e-3 per step
 * and a 0.02 rad, except over steps 20..40, where a holds and h falls by 2e-4 per step (elastic
 * unloading, 4e-3 in all, inside the elastic range of 2 sigma_y / E in reverse). */
static void plane_F(int k, double F[3][3]) {
  const double h = 2e-3 * (k < 20 ? k : (k < 40 ? 20 - 0.1 * (k - 20) : 18 + (k - 40)));
  const double a = 0.02 * (k < 20 ? k : (k < 40 ? 20 : k - 20)), c = cos(a), s = sin(a);
  const double l1 = exp(h), l2 = exp(-0.8 * h);
  ju_identity(F);
  F[0][0] = c * c * l1 + s * s * l2;
  F[1][1] = s * s * l1 + c * c * l2;
  F[0][1] = c * s * (l1 - l2) + 0.3 * h;
  F[1][0] = c * s * (l1 - l2);
}

static void check_path(const pdk_jc_params *p, int with_avg, const char *what) {
  pdk_jc_state s2 = pdk_jc_state_initial(), s3 = s2, sk = s2;
  int plastic = 0, elastic_after_flow = 0, failed_at = -1;
  for (int k = 1; k <= 600 && (failed_at < 0 || k <= failed_at + 10); ++k) {
    double F[3][3], P2[3][3], P3[3][3], Pk[3][3];
    plane_F(k, F);
    const double sm = 0.4 * p->A * sin(0.05 * k); /* a family pressure for the _avg calls */
    pdk_jc_result r2, r3, rk;
    pdk_jc_state o2, o3, ok;
    int e2, e3, ek;
    if (with_avg) {
      e2 = pdk_jc_update_avg(p, 2, F, 1e-6, sm, &s2, &o2, P2, &r2);
      e3 = pdk_jc_update_avg(p, 3, F, 1e-6, sm, &s3, &o3, P3, &r3);
      ek = pdk_jc_update_kernel(p, 2, F, 1e-6, &sm, &sk, &ok, Pk, &rk);
    } else {
      e2 = pdk_jc_update(p, 2, F, 1e-6, &s2, &o2, P2, &r2);
      e3 = pdk_jc_update(p, 3, F, 1e-6, &s3, &o3, P3, &r3);
      ek = pdk_jc_update_kernel(p, 2, F, 1e-6, NULL, &sk, &ok, Pk, &rk);
    }
    T_ASSERT(e2 == 0 && e3 == 0 && ek == 0, "%s, step %d: returned %d, %d, %d", what, k, e2, e3,
             ek);
    /* A: the plane path against the 3 x 3 path */
    T_ASSERT(ju_state_equal(&o2, &o3), "%s, step %d: history differs (eps_p %.17g vs %.17g)", what,
             k, o2.eps_p, o3.eps_p);
    T_ASSERT(result_equal(&r2, &r3), "%s, step %d: result differs (W %.17g vs %.17g)", what, k,
             r2.W, r3.W);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        T_ASSERT(memcmp(&P2[i][j], &P3[i][j], sizeof(double)) == 0,
                 "%s, step %d: P[%d][%d] %.17g (plane) vs %.17g (3-D)", what, k, i, j, P2[i][j],
                 P3[i][j]);
    for (int c = 0; c < 6; ++c)
      T_ASSERT(r2.sigma[c] == r3.sigma[c], "%s, step %d: sigma[%d] %.17g vs %.17g", what, k, c,
               r2.sigma[c], r3.sigma[c]);
    /* B: the kernel entry against the public one */
    T_ASSERT(ju_state_equal(&ok, &o2) && result_equal(&rk, &r2),
             "%s, step %d: pdk_jc_update_kernel differs from the public update", what, k);
    for (int i = 0; i < 2; ++i)
      T_ASSERT(memcmp(Pk[i], P2[i], 2 * sizeof(double)) == 0, "%s, step %d: kernel P differs", what,
               k);
    for (int c = 0; c < 6; ++c)
      T_ASSERT(rk.sigma[c] == 0.0, "%s, step %d: kernel sigma[%d] = %g, expected 0", what, k, c,
               rk.sigma[c]);
    plastic += r2.plastic;
    elastic_after_flow += !r2.plastic && s2.eps_p > 0.0 && !s2.failed;
    if (r2.failed_now) failed_at = k;
    s2 = o2;
    s3 = o3;
    sk = ok;
  }
  /* the path must have exercised what it is meant to: plastic and elastic steps after flow, and
   * failure (then ten steps of the failed point) when damage is on */
  T_ASSERT(plastic > 20 && elastic_after_flow > 5, "%s: %d plastic, %d elastic steps after flow",
           what, plastic, elastic_after_flow);
  if (p->damage) T_ASSERT(failed_at > 0, "%s: the point did not fail", what);
  printf("%s: %d plastic steps, %d elastic after flow, failed at step %d: same bits\n", what,
         plastic, elastic_after_flow, failed_at);
}

int main(void) {
  const pdk_jc_params def = pdk_jc_params_default();
  pdk_jc_params p = def;
  p.damage = 0;
  check_path(&p, 0, "rate independent, no damage");
  p = def;
  p.C = 0.014;
  p.D4 = 0.002;
  check_path(&p, 0, "rate terms, damage");
  check_path(&p, 1, "rate terms, damage, family pressure");
  p = def;
  p.thermal = 1;
  p.D5 = 0.61;
  p.coupling = PDK_JC_COUPLING_EFFECTIVE;
  p.failed_mode = PDK_JC_FAILED_COMPRESSION;
  check_path(&p, 0, "thermal, coupled damage, failed keeps compression");
  return 0;
}
