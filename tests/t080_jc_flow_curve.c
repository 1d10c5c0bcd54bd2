/* Johnson-Cook plasticity, uniaxial stress, monotonic loading (V-JC, first item): along the whole
 * flow curve the axial Kirchhoff stress equals A + B eps_p^n, and the plastic strain equals the
 * axial log strain minus the elastic one, eps_p = ln(lambda) - tau_11 / E (Hencky + isochoric
 * flow give exactly this in uniaxial stress). Material: the V-JC steel (defaults), damage off so
 * the curve can run to eps_p = 1. Also: with the effective-stress coupling the axial stress is
 * (1 - D)(A + B eps_p^n) with D = eps_p / eps_f(1/3); and the work balance
 * int tau_11 d ln(lambda) = W + sum dW_plastic.
 * labels: unit physics
 *
 * Loading: F = diag(lambda, lambda_t, lambda_t), ln(lambda) in 400 equal steps to 1.0; at every
 * step lambda_t is found by a bracketed secant iteration on the lateral Kirchhoff stress tau_22
 * (= tau_33 by symmetry) to |tau_22| <= 1e-4 Pa (1.3e-13 of A), using trial updates from the
 * committed history.
 * Tolerances:
 *  - elastic steps: tau_11 = E ln(lambda) + 2 nu tau_22; the log strain of a stretch near 1 has
 *    an absolute round-off of a few 1e-16 (ln of a number near 1), hence atol |tau_22| + 1e-15 E.
 *  - flow stress: tau_11 - tau_22 = q = sigma_y(eps_p) holds to a few ulps by construction of
 *    the return (the deviator is scaled to sigma_y), so |tau_11 - (A + B eps_p^n)| <=
 *    |tau_22| + 1e-13 tau_11 (round-off of the eigen-decomposition and of P -> tau).
 *  - eps_p = ln(lambda) - tau_11/E: both sides are sums of ~400 increments of C_p^-1 updates;
 *    measured agreement ~1e-15, allowed 1e-12 absolute.
 *  - energies: sum dW_plastic = A eps_p + B eps_p^(n+1)/(n+1) (the exact integral, 1e-12) and
 *    W = tau_11^2/(2E) (uniaxial Hencky, 1e-12): exact up to round-off.
 *  - work balance: trapezoidal work int tau_11 d ln(lambda) versus W + dissipation. The trapezoid
 *    rule errs by sum h^3/12 |tau''| ~ h^2/12 tau'(eps_p at the start of the coarse steps)
 *    = (0.00248)^2/12 * 5.9e9 Pa ~ 3e3 Pa = 2.5e-6 of the work (the fine steps make the kink at
 *    first yield negligible); allowed 5e-6. With damage coupling the same trapezoid error plus
 *    that of dW_damage = W~_(n+1) dD (W~ varies little once plastic): measured 5.9e-6, allowed
 *    2e-5.
 */
#include "jc_util.h"

typedef struct axi {
  const pdk_jc_params *p;
  const pdk_jc_state *in;
  double la; /* axial log stretch */
} axi;

static void axi_F(double la, double lr, double F[3][3]) {
  ju_identity(F);
  F[0][0] = exp(la);
  F[1][1] = F[2][2] = exp(lr);
}

/* lateral Kirchhoff stress of a trial step to (la, lr) */
static double lateral_stress(double lr, void *data) {
  const axi *a = data;
  double F[3][3], P[3][3];
  pdk_jc_state tmp;
  pdk_jc_result r;
  axi_F(a->la, lr, F);
  ju_update(a->p, 3, F, 1e-3, a->in, &tmp, P, &r);
  return r.sigma[1] * r.J;
}

static void run(const pdk_jc_params *p, int coupled) {
  pdk_jc_state st = pdk_jc_state_initial();
  /* 100 steps to ln(lambda) = 0.01 (through first yield at 0.004), then 400 to 1.0 */
  const int nfine = 100, nsteps = 500;
  const double la_fine = 0.01, la_end = 1.0;
  const double E = p->young_modulus;
  double work = 0.0, dissipated = 0.0, tau11_prev = 0.0, W = 0.0;
  int nplastic = 0;
  pdk_jc_params pnd = *p; /* same stress, no failure: for the lateral iteration */
  pnd.damage = 0;
  for (int k = 1; k <= nsteps; ++k) {
    const double la = k <= nfine ? la_fine * k / nfine
                                 : la_fine + (la_end - la_fine) * (k - nfine) / (nsteps - nfine);
    const double dla = k <= nfine ? la_fine / nfine : (la_end - la_fine) / (nsteps - nfine);
    axi a = {&pnd, &st, la};
    const double lr = ju_root(lateral_stress, &a, -la, 0.0, 1e-4);
    double F[3][3], P[3][3], tau[3][3];
    pdk_jc_result r;
    axi_F(la, lr, F);
    ju_update(p, 3, F, 1e-3, &st, &st, P, &r);
    T_ASSERT(!st.failed, "coupled run failed at step %d (eps_p %g)", k, st.eps_p);
    ju_kirchhoff(3, P, F, &r, tau);
    const double t11 = tau[0][0], t22 = tau[1][1], t33 = tau[2][2];
    T_ASSERT(fabs(t22) <= 1e-4 + 1e-14 * fabs(t11) && fabs(t33 - t22) <= 1e-13 * fabs(t11),
             "step %d: lateral stresses %g, %g not zero", k, t22, t33);
    work += 0.5 * (tau11_prev + t11) * dla;
    tau11_prev = t11;
    dissipated += r.dW_plastic + r.dW_damage;
    W = r.W;
    if (!r.plastic) {
      T_ASSERT(st.eps_p == 0.0, "elastic step %d after yielding (eps_p %g)", k, st.eps_p);
      T_NEAR(t11, E * la, 1e-13, fabs(t22) + 1e-15 * E,
             "step %d: elastic uniaxial Kirchhoff stress E ln(lambda)", k);
      continue;
    }
    ++nplastic;
    const double hard = p->A + p->B * pow(st.eps_p, p->n);
    double expect = hard;
    if (coupled) {
      const double ef = p->D1 + p->D2 * exp(p->D3 / 3.0);
      T_NEAR(st.damage, st.eps_p / ef, 1e-9, 0.0, "step %d: D = eps_p / eps_f(1/3)", k);
      expect = (1.0 - st.damage) * hard;
    }
    T_NEAR(t11, expect, 1e-13, fabs(t22),
           "step %d (eps_p = %.6f): axial stress vs %s(A + B eps_p^n)", k, st.eps_p,
           coupled ? "(1 - D) " : "");
    T_NEAR(st.eps_p, la - t11 / (coupled ? (1.0 - st.damage) * E : E), 0.0, 1e-12,
           "step %d: eps_p vs ln(lambda) - tau_11/E", k);
    T_NEAR(r.tau_vm, t11 - t22, 1e-13, 1e-6, "step %d: result tau_vm", k);
  }
  T_ASSERT(nplastic > 450, "only %d plastic steps", nplastic);
  if (!coupled) {
    T_ASSERT(st.eps_p > 0.99, "final eps_p %g", st.eps_p);
    const double e = st.eps_p;
    T_NEAR(dissipated, p->A * e + p->B * pow(e, p->n + 1.0) / (p->n + 1.0), 1e-12, 0.0,
           "sum of dW_plastic vs int (A + B e^n) de");
    T_NEAR(W, tau11_prev * tau11_prev / (2.0 * E), 1e-12, 0.0, "W vs tau_11^2 / (2E)");
    T_NEAR(W + dissipated, work, 5e-6, 0.0,
           "work balance: W + dissipation vs int tau d ln(lambda)");
  } else {
    T_NEAR(W + dissipated, work, 2e-5, 0.0, "work balance with damage coupling");
  }
}

int main(void) {
  pdk_jc_params p = pdk_jc_params_default();
  p.damage = 0;
  run(&p, 0);
  /* coupled: D_c = 1 so the curve can run past D_c eps_f; (1 - D) tau~ all along */
  p = pdk_jc_params_default();
  p.coupling = PDK_JC_COUPLING_EFFECTIVE;
  p.D_c = 1.0;
  run(&p, 1);
  return 0;
}
