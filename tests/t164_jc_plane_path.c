/* The Johnson-Cook update's plane-strain path and its kernel entry against the 3-D update.
 *  A. pdk_jc_update with dim 2 works on the xy block of b_tr with the closed-form 2 x 2
 *     eigen-decomposition (kernels/ref/jc.c, trial_plane); dim 3 on the same F (F33 = 1, no
 *     out-of-plane shear) takes the general 3 x 3 path (congruence, cyclic Jacobi). Along a
 *     non-proportional plane path (stretch on rotating axes, shear, unloading and reloading, so
 *     elastic and plastic steps) run to failure and ten steps beyond, both give the same history,
 *     P (xy block), Cauchy stress, W, energies, von Mises and yield stress, triaxiality, failure
 *     strain to round-off, and the same plastic and failure flags at every step. Settings: rate
 *     independent without damage; rate terms on with damage (own pressure and a given family
 *     pressure); thermal with coupled damage; failed points with the compressive pressure kept.
 *  B. pdk_jc_update_kernel (what the correspondence kernels call) gives the same bits as
 *     pdk_jc_update / pdk_jc_update_avg in everything but res->sigma, which it leaves 0.
 * labels: unit physics
 *
 * Tolerances (A): the two paths round differently (eigenvalues to a few ulps of their mean, then
 * logarithms), so each step's elastic log strain and the C_p^-1 it leaves differ by ~1e-16
 * absolute, stresses by ~E 1e-16 = 2e-5 Pa (~1e-14 of the yield stress A); the history carries
 * these on as a random walk over the plastic steps. Measured: at most 3.4e-12 (P over A, after
 * 578 plastic steps to a log strain of 1.1), 1.1e-12 in the runs with damage. Asserted, per step:
 * stresses within 1e-10 A (P, sigma, von Mises, yield stress, mean stress), energy densities
 * within 1e-10 (A^2 / E + |value|), C_p^-1 entries, eps_p, D within 1e-10 (absolute; all O(1) or
 * below), the rest within 1e-10 relative. A wrong axis, eigenvalue order or missing term errs by
 * O(1). B has no tolerance: the same arithmetic.
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
  double dev_max = 0.0;
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
    /* A: the plane path against the 3 x 3 path, to round-off */
    const double S = p->A, Es = p->A * p->A / p->young_modulus;
    double dev = 0.0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        dev = fmax(dev, fabs(P2[i][j] - P3[i][j]) / S);
    for (int c = 0; c < 6; ++c)
      dev = fmax(dev, fabs(r2.sigma[c] - r3.sigma[c]) / S);
    dev = fmax(dev, fabs(r2.tau_vm - r3.tau_vm) / S);
    dev = fmax(dev, fabs(r2.sigma_vm - r3.sigma_vm) / S);
    dev = fmax(dev, fabs(r2.yield_stress - r3.yield_stress) / S);
    dev = fmax(dev, fabs(r2.sigma_m_eff - r3.sigma_m_eff) / S);
    const double en2[3] = {r2.W, r2.dW_plastic, r2.dW_damage};
    const double en3[3] = {r3.W, r3.dW_plastic, r3.dW_damage};
    for (int c = 0; c < 3; ++c)
      dev = fmax(dev, fabs(en2[c] - en3[c]) / (Es + fabs(en3[c])));
    for (int c = 0; c < 6; ++c)
      dev = fmax(dev, fabs(o2.cp_inv[c] - o3.cp_inv[c]));
    dev = fmax(dev, fabs(o2.eps_p - o3.eps_p));
    dev = fmax(dev, fabs(o2.damage - o3.damage));
    const double rel2[5] = {o2.temp_rise, r2.d_eps_p, r2.eps_p_rate, r2.triaxiality,
                            r2.failure_strain};
    const double rel3[5] = {o3.temp_rise, r3.d_eps_p, r3.eps_p_rate, r3.triaxiality,
                            r3.failure_strain};
    for (int c = 0; c < 5; ++c)
      dev = fmax(dev, fabs(rel2[c] - rel3[c]) / fmax(fabs(rel3[c]), 1e-300));
    T_ASSERT(dev <= 1e-10, "%s, step %d: plane and 3-D paths differ by %.3g (eps_p %.17g vs %.17g)",
             what, k, dev, o2.eps_p, o3.eps_p);
    T_ASSERT(r2.plastic == r3.plastic && r2.failed_now == r3.failed_now && o2.failed == o3.failed &&
                 r2.J == r3.J,
             "%s, step %d: flags differ (plastic %d/%d, failed %d/%d)", what, k, r2.plastic,
             r3.plastic, o2.failed, o3.failed);
    dev_max = fmax(dev_max, dev);
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
  T_INFO("%s: %d plastic steps, %d elastic after flow, failed at step %d; plane vs 3-D %.2g\n",
         what, plastic, elastic_after_flow, failed_at, dev_max);
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
