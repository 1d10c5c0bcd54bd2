/* Johnson-Cook damage and the optional rate and thermal terms (V-JC, third and fourth items).
 *
 * Constant triaxiality: F = diag(exp(la), exp(lr), exp(lr)) (3-D, axisymmetric) or
 * diag(exp(la), exp(lr)) (plane strain), la increased in equal steps, lr found at every step by a
 * bracketed secant iteration so that tau_m = eta q (|tau_m - eta q| <= 1e-3 Pa, i.e. eta to
 * ~1e-12); eta in {-1/3, 0, 1/3, 2/3, 1} (3-D) and 1/sqrt(3) (plane strain). Checked:
 *  - the triaxiality the law used (result) equals the target to 1e-9;
 *  - D equals sum d_eps_p / eps_f with eps_f = [D1 + D2 exp(D3 eta)][1 + D4 ln rate*][1 + D5 T*]
 *    evaluated here from the formula (rate* from the step's plastic rate, T* from the temperature
 *    at the step start), to 1e-12 (a sum of ~500 positive terms);
 *  - the point fails on the first step with D >= D_c, i.e. (constant eta, no rate or temperature
 *    change) when eps_p first reaches D_c eps_f(eta): eps_p before < D_c eps_f <= eps_p after;
 *    then P = 0, W = 0, dW_damage = the stored energy released, and the history stays frozen;
 *  - rate term on (C = 0.014, ~1e3/s): tau_vm / (A + B eps_p^n) = 1 + C ln(rate*) to 1e-13 at every
 *    plastic step; below the reference rate the factor is exactly absent;
 *  - thermal: isothermal T* = 0.4: tau_vm = (A + B eps_p^n)(1 - T*^m) and eps_f scaled by
 *    (1 + D5 T*); with adiabatic heating temp_rise = beta sum dW_plastic / (rho c_p) (1e-12) and
 *    the flow stress uses T* of the step start;
 *  - absent terms are absent: with C = D4 = 0 the results are bitwise the same for dt = 1e-3 and
 *    dt = 7 s; thermal = 0 and thermal = 1 at T* = 0 without heating (1 - 0^m = 1 and
 *    1 + D5 * 0 = 1 exactly) give bitwise the same results;
 *  - effective-stress coupling: tau_vm = (1 - D) sigma_y; FAILED_COMPRESSION: a failed point
 *    carries K ln J in compression and nothing in tension.
 * labels: unit physics
 *
 * Tolerances: the flow stress and consistency are exact to a few ulps (t081); 1e-13 leaves margin.
 * The D sums are formed from the same increments in the same order; only exp/log/pow rounding
 * and eta's iteration tolerance (1e-12 relative, times |D3| ~ 2) differ: 1e-12.
 */
#include "jc_util.h"

typedef struct axi {
  const pdk_jc_params *p;
  const pdk_jc_state *in;
  int dim;
  double la, eta, dt;
} axi;

static void axi_F(int dim, double la, double lr, double F[3][3]) {
  ju_identity(F);
  F[0][0] = exp(la);
  F[1][1] = exp(lr);
  if (dim == 3) F[2][2] = exp(lr);
}

static double triax_residual(double lr, void *data) {
  const axi *a = data;
  double F[3][3], P[3][3];
  pdk_jc_state tmp;
  pdk_jc_result r;
  axi_F(a->dim, a->la, lr, F);
  ju_update(a->p, a->dim, F, a->dt, a->in, &tmp, P, &r);
  const double tau_m = r.J * (r.sigma[0] + r.sigma[1] + r.sigma[2]) / 3.0;
  return tau_m - a->eta * r.tau_vm;
}

static double hom_T(const pdk_jc_params *p, double temp_rise) {
  if (!p->thermal) return 0.0;
  double ts = (p->T_initial + temp_rise - p->T_room) / (p->T_melt - p->T_room);
  return ts < 0 ? 0 : (ts > 1 ? 1 : ts);
}

static double eps_f_formula(const pdk_jc_params *p, double eta, double rate_star, double Ts) {
  double ef = p->D1 + p->D2 * exp(p->D3 * eta);
  ef *= 1.0 + p->D4 * log(rate_star > 1.0 ? rate_star : 1.0);
  ef *= 1.0 + p->D5 * Ts;
  return ef;
}

static double yield_formula(const pdk_jc_params *p, double eps_p, double rate_star, double Ts) {
  double sy = p->A + p->B * pow(eps_p, p->n);
  if (p->C != 0.0 && rate_star > 1.0) sy *= 1.0 + p->C * log(rate_star);
  if (p->thermal) sy *= 1.0 - pow(Ts, p->m);
  return sy;
}

typedef struct triax_out {
  double eps_before, eps_fail; /* eps_p before the failing step and after it */
  double ef_fail;              /* eps_f of the failing step */
  int steps, failed;
  double sum_dWp;
} triax_out;

/* Drives a point at constant triaxiality until it fails (or max_steps); checks every step. */
static triax_out run_triax(const pdk_jc_params *p, int dim, double eta, double dla, double dt,
                           int max_steps, const char *what) {
  triax_out o;
  memset(&o, 0, sizeof o);
  pdk_jc_params pnd = *p; /* the same stress without failure, for the lateral iteration */
  pnd.damage = 0;
  pnd.coupling = PDK_JC_COUPLING_NONE;
  pdk_jc_state st = pdk_jc_state_initial();
  double D_test = 0.0, W_prev = 0.0;
  for (int k = 1; k <= max_steps; ++k) {
    const double la = dla * k;
    axi a = {&pnd, &st, dim, la, eta, dt};
    const double lr = ju_root(triax_residual, &a, -la - 1.0, la, 1e-3);
    double F[3][3], P[3][3];
    pdk_jc_result r;
    axi_F(dim, la, lr, F);
    const pdk_jc_state before = st;
    const double Ts = hom_T(p, st.temp_rise);
    ju_update(p, dim, F, dt, &st, &st, P, &r);
    o.steps = k;
    o.sum_dWp += r.dW_plastic;
    if (!r.plastic) {
      W_prev = r.W;
      continue;
    }
    T_NEAR(r.triaxiality, eta, 0.0, 1e-9, "%s, step %d: triaxiality used", what, k);
    const double rate_star = r.d_eps_p / dt / p->ref_rate;
    const double ef = eps_f_formula(p, r.triaxiality, rate_star, Ts);
    T_NEAR(r.failure_strain, ef, 1e-13, 0.0, "%s, step %d: failure strain", what, k);
    D_test += r.d_eps_p / ef;
    T_NEAR(st.damage, D_test, 1e-12, 0.0, "%s, step %d: D vs sum d_eps_p / eps_f", what, k);
    /* flow stress (effective), every plastic step */
    const double keep = p->coupling == PDK_JC_COUPLING_EFFECTIVE ? 1.0 - st.damage : 1.0;
    if (!r.failed_now)
      T_NEAR(r.tau_vm, keep * yield_formula(p, st.eps_p, rate_star, Ts), 1e-13, 0.0,
             "%s, step %d (eps_p %.6g): tau_vm vs %sflow stress", what, k, st.eps_p,
             keep != 1.0 ? "(1 - D) " : "");
    T_ASSERT(r.failed_now == (D_test >= p->D_c) && st.failed == r.failed_now,
             "%s, step %d: failed_now %d, state %d, but D = %.17g vs D_c %g", what, k, r.failed_now,
             st.failed, D_test, p->D_c);
    if (r.failed_now) {
      o.failed = 1;
      o.eps_before = before.eps_p;
      o.eps_fail = st.eps_p;
      o.ef_fail = ef;
      if (p->failed_mode == PDK_JC_FAILED_ZERO) {
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            T_ASSERT(P[i][j] == 0.0, "%s: failed point has P[%d][%d] = %g", what, i, j, P[i][j]);
        T_ASSERT(r.W == 0.0, "%s: failed point stores W = %g", what, r.W);
        /* released: the stored energy just before failure (W changes little in one step) */
        T_NEAR(r.dW_damage, W_prev, 0.05, 0.0, "%s: energy released on failure", what);
      }
      /* later steps: history frozen, P = 0 */
      pdk_jc_state after = st;
      axi_F(dim, la + 0.1, lr - 0.05, F);
      ju_update(p, dim, F, dt, &st, &st, P, &r);
      T_ASSERT(ju_state_equal(&after, &st), "%s: failed history changed", what);
      if (p->failed_mode == PDK_JC_FAILED_ZERO)
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            T_ASSERT(P[i][j] == 0.0, "%s: failed point has P[%d][%d] = %g later", what, i, j,
                     P[i][j]);
      return o;
    }
    W_prev = r.W;
  }
  return o;
}

/* eps_p at failure brackets D_c eps_f (constant eta, rate and temperature) */
static void check_failure_strain(const pdk_jc_params *p, int dim, double eta, int nsteps,
                                 const char *what) {
  const double target = p->D_c * eps_f_formula(p, eta, 1.0, hom_T(p, 0.0));
  const triax_out o = run_triax(p, dim, eta, 1.2 * target / nsteps, 1e-3, 2 * nsteps, what);
  T_ASSERT(o.failed, "%s: no failure after %d steps (target eps_p %g)", what, o.steps, target);
  if (!(o.eps_before < target * (1 + 1e-9) && o.eps_fail >= target * (1 - 1e-9)))
    T_FAIL("%s: failed between eps_p %.10g and %.10g, expected D_c eps_f = %.10g", what,
           o.eps_before, o.eps_fail, target);
  T_ASSERT(o.eps_fail - o.eps_before < 0.01 * target, "%s: step too coarse", what);
}

/* Runs the same path for two parameter sets (and dt values) and compares every bit. */
static void check_bitwise(const pdk_jc_params *p1, double dt1, const pdk_jc_params *p2, double dt2,
                          int dim, const char *what) {
  pdk_jc_state s1 = pdk_jc_state_initial(), s2 = pdk_jc_state_initial();
  for (int k = 1; k <= 150; ++k) {
    double F[3][3], P1[3][3] = {{0}}, P2[3][3] = {{0}};
    pdk_jc_result r1, r2;
    /* a non-proportional path: stretch, shear, rotation of the stretch axes */
    const double t = 0.003 * k;
    ju_identity(F);
    F[0][0] = exp(t);
    F[1][1] = exp((dim == 3 ? -0.5 : -1.0) * t);
    F[0][1] = 0.5 * t * t;
    F[1][0] = 0.2 * sin(3.0 * t);
    if (dim == 3) {
      F[2][2] = exp(-0.49 * t);
      F[0][2] = 0.1 * t;
    }
    ju_update(p1, dim, F, dt1, &s1, &s1, P1, &r1);
    ju_update(p2, dim, F, dt2, &s2, &s2, P2, &r2);
    if (!ju_state_equal(&s1, &s2) || memcmp(P1, P2, sizeof P1) ||
        memcmp(r1.sigma, r2.sigma, sizeof r1.sigma) || r1.W != r2.W ||
        r1.dW_plastic != r2.dW_plastic)
      T_FAIL("%s: step %d differs: eps_p %.17g vs %.17g, P00 %.17g vs %.17g", what, k, s1.eps_p,
             s2.eps_p, P1[0][0], P2[0][0]);
  }
  T_ASSERT(s1.eps_p > 0.2, "%s: path too mild (eps_p %g)", what, s1.eps_p);
}

int main(void) {
  const pdk_jc_params def = pdk_jc_params_default();

  /* ---- failure at D_c eps_f(eta), several triaxialities (D1, D2, D3) ---- */
  const double etas[] = {-1.0 / 3.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
  for (int e = 0; e < 5; ++e) {
    char what[64];
    snprintf(what, sizeof what, "3-D eta = %.4f", etas[e]);
    check_failure_strain(&def, 3, etas[e], 400, what);
  }
  check_failure_strain(&def, 2, 1.0 / sqrt(3.0), 400, "plane strain eta = 1/sqrt(3)");
  /* sanity of the failure strains themselves (thesis notes: eps_f(0) = 3.490, eps_f(1/3) = 1.747,
   * eps_f(2/3) = 0.887) */
  T_NEAR(pdk_jc_failure_strain(&def, 0.0, 1.0, 0.0), 3.49, 0, 1e-12, "eps_f(0)");
  T_NEAR(pdk_jc_failure_strain(&def, 1.0 / 3.0, 1.0, 0.0), 1.747, 0, 5e-4, "eps_f(1/3)");
  T_NEAR(pdk_jc_failure_strain(&def, 2.0 / 3.0, 1.0, 0.0), 0.887, 0, 5e-4, "eps_f(2/3)");

  /* ---- rate term (C) and rate-dependent failure strain (D4) ---- */
  pdk_jc_params pr = def;
  pr.C = 0.014;
  pr.D4 = 0.05;
  pr.ref_rate = 1.0;
  {
    /* ~1e3 /s: la step 2e-3 in 2e-6 s; run_triax checks tau_vm = (A + B e^n)(1 + C ln rate*)
     * and D with the (1 + D4 ln rate*) factor at every step */
    triax_out o = run_triax(&pr, 3, 1.0 / 3.0, 2e-3, 2e-6, 2000, "rate on, eta = 1/3");
    T_ASSERT(o.failed, "rate on: no failure");
    /* eps_f grew by ~(1 + 0.05 ln 1e3) = 1.35 */
    const double plain = def.D_c * eps_f_formula(&def, 1.0 / 3.0, 1.0, 0.0);
    T_ASSERT(o.eps_fail > 1.3 * plain && o.eps_fail < 1.4 * plain + 2e-3,
             "rate on: failure at eps_p %g, rate-free %g", o.eps_fail, plain);
    /* below the reference rate: exactly the rate-free stresses (factor absent, rate* clamped) */
    pdk_jc_params slow = pr;
    slow.ref_rate = 1e9;
    run_triax(&slow, 3, 0.0, 2e-3, 1.0, 50, "rate on, below the reference rate");
  }

  /* ---- thermal: isothermal T* = 0.4 (m, D5), then adiabatic heating (beta, c_p) ---- */
  pdk_jc_params pt = def;
  pt.thermal = 1;
  pt.beta = 0.0;
  pt.D5 = 0.61;
  pt.T_initial = pt.T_room + 0.4 * (pt.T_melt - pt.T_room);
  check_failure_strain(&pt, 3, 1.0 / 3.0, 400, "isothermal T* = 0.4, eta = 1/3");
  pt.beta = 0.9;
  {
    triax_out o = run_triax(&pt, 3, 0.5, 2e-3, 1e-6, 2000, "adiabatic heating, eta = 0.5");
    T_ASSERT(o.failed, "heating: no failure");
  }
  {
    /* temperature rise = beta sum dW_plastic / (rho c_p) */
    pdk_jc_params ph = pt;
    ph.damage = 0;
    pdk_jc_state st = pdk_jc_state_initial();
    double sum = 0.0;
    for (int k = 1; k <= 200; ++k) {
      double F[3][3], P[3][3];
      pdk_jc_result r;
      axi_F(3, 0.005 * k, -0.0025 * k, F);
      ju_update(&ph, 3, F, 1e-6, &st, &st, P, &r);
      sum += r.dW_plastic;
    }
    T_NEAR(st.temp_rise, ph.beta * sum / (ph.density * ph.heat_capacity), 1e-12, 0.0,
           "temperature rise vs beta W_p / (rho c_p)");
    T_ASSERT(st.temp_rise > 50.0, "temperature rise %g K too small to test", st.temp_rise);
  }

  /* ---- absent terms are absent (bitwise) ---- */
  check_bitwise(&def, 1e-3, &def, 7.0, 3, "C = D4 = 0: dt 1e-3 vs 7 (3-D)");
  check_bitwise(&def, 1e-3, &def, 7.0, 2, "C = D4 = 0: dt 1e-3 vs 7 (plane strain)");
  {
    pdk_jc_params p0 = def;
    p0.thermal = 1;
    p0.beta = 0.0;
    p0.D5 = 0.61;
    p0.T_initial = p0.T_room;
    check_bitwise(&def, 1e-3, &p0, 1e-3, 3, "thermal off vs on at T* = 0");
  }

  /* ---- effective-stress coupling (run_triax checks tau_vm = (1 - D) sigma_y) ---- */
  pdk_jc_params pc = def;
  pc.coupling = PDK_JC_COUPLING_EFFECTIVE;
  check_failure_strain(&pc, 3, 2.0 / 3.0, 400, "coupled, eta = 2/3");

  /* ---- FAILED_COMPRESSION ---- */
  {
    pdk_jc_params pf = def;
    pf.failed_mode = PDK_JC_FAILED_COMPRESSION;
    pdk_jc_state st = pdk_jc_state_initial();
    st.failed = 1;
    double F[3][3], P[3][3];
    pdk_jc_result r;
    const double K = pf.young_modulus / (3.0 * (1.0 - 2.0 * pf.poisson_ratio));
    ju_identity(F);
    F[0][0] = 0.95;
    F[1][1] = 0.97;
    F[0][1] = 0.1;
    ju_update(&pf, 3, F, 1e-3, &st, &st, P, &r);
    const double J = ju_det(F), lnJ = log(J);
    /* P = K ln J F^-T: check P F^T = K ln J 1 */
    double tau[3][3];
    ju_mul_bt(P, F, tau);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        T_NEAR(tau[i][j], i == j ? K * lnJ : 0.0, 1e-14, 1e-14 * K * fabs(lnJ),
               "failed, compression: tau[%d][%d]", i, j);
    T_NEAR(r.W, 0.5 * K * lnJ * lnJ, 1e-14, 0.0, "failed, compression: W");
    F[0][0] = 1.05;
    ju_update(&pf, 3, F, 1e-3, &st, &st, P, &r);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        T_ASSERT(P[i][j] == 0.0, "failed, tension: P[%d][%d] = %g", i, j, P[i][j]);
  }
  return 0;
}
