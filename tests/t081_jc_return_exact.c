/* Johnson-Cook plasticity: the radial return is exact for proportional loading (V-JC, second
 * item). Proportional loading: F(t) = Q diag(exp(t h)) Q^T, fixed principal axes Q, log strains
 * t h growing linearly to t = 1, reached in 1, 10 and 100 equal steps; 3-D and plane strain.
 * Checked:
 *  - after every plastic step the stress recomputed from P (tau = P F^T) lies on the yield
 *    surface: |q(tau) - sigma_y(eps_p)| <= 1e-13 sigma_y, with sigma_y evaluated here from the
 *    formula, for rate-independent, rate-dependent (sigma_y with the step's plastic rate) and
 *    temperature-dependent (T* of the step start) laws;
 *  - the largest consistency error of the 1-step run is no larger than 4x that of the 100-step
 *    run plus 1e-15 (it does not grow with the step size, though the 1-step trial overshoots the
 *    yield surface about 100-fold);
 *  - rate-independent, isothermal: the final eps_p and stress do not depend on the number of
 *    steps (the log-strain return depends on the end strain only): agreement to 1e-12;
 *  - plastic incompressibility: det C_p^-1 = 1 to 1e-13 after every step.
 * labels: unit physics
 *
 * Tolerances: the stress goes through an eigen-decomposition (Jacobi, orthogonality to ~1e-16),
 * the spectral sum, P = tau F^-T here and back tau = P F^T; each costs a few ulps of the largest
 * stress component, which is at most ~3 sigma_y here (pressure included), and q involves a
 * difference of such components: 1e-13 sigma_y leaves a margin of ~20 over the measured worst
 * (~5e-15). The 1 / 10 / 100-step finals differ only by such round-off summed over the steps.
 */
#include "jc_util.h"

typedef struct path {
  int dim;
  double h[3];    /* principal log strains at t = 1 (h[2] = 0 in plane strain) */
  double Q[3][3]; /* fixed principal axes */
} path;

static void path_F(const path *pa, double t, double F[3][3]) {
  double D[3][3] = {{0}}, T[3][3];
  for (int a = 0; a < 3; ++a)
    D[a][a] = exp(t * pa->h[a]);
  ju_mul(pa->Q, D, T);
  ju_mul_bt(T, pa->Q, F);
}

typedef struct run_out {
  double max_err; /* max |q - sigma_y| / sigma_y over plastic steps */
  double eps_p;
  double tau[3][3];
  int nplastic;
} run_out;

/* sigma_y from the formula, independent of the library's helpers */
static double yield_formula(const pdk_jc_params *p, double eps_p, double d_eps_p, double dt,
                            double temp_rise_start) {
  double sy = p->A + p->B * pow(eps_p, p->n);
  if (p->C != 0.0) {
    const double rs = d_eps_p / dt / p->ref_rate;
    if (rs > 1.0) sy *= 1.0 + p->C * log(rs);
  }
  if (p->thermal) {
    double ts = (p->T_initial + temp_rise_start - p->T_room) / (p->T_melt - p->T_room);
    ts = ts < 0 ? 0 : (ts > 1 ? 1 : ts);
    sy *= 1.0 - pow(ts, p->m);
  }
  return sy;
}

static run_out run(const pdk_jc_params *p, const path *pa, int nsteps, const char *what) {
  run_out o;
  memset(&o, 0, sizeof o);
  pdk_jc_state st = pdk_jc_state_initial();
  const double total_time = 1e-3; /* plastic rates ~ 1e3 / s for the rate-dependent case */
  const double dt = total_time / nsteps;
  double F[3][3], P[3][3], tau[3][3];
  pdk_jc_result r;
  for (int k = 1; k <= nsteps; ++k) {
    const double T_rise_start = st.temp_rise;
    path_F(pa, (double)k / nsteps, F);
    ju_update(p, pa->dim, F, dt, &st, &st, P, &r);
    ju_kirchhoff(pa->dim, P, F, &r, tau);
    double Cp[3][3] = {{st.cp_inv[0], st.cp_inv[5], st.cp_inv[4]},
                       {st.cp_inv[5], st.cp_inv[1], st.cp_inv[3]},
                       {st.cp_inv[4], st.cp_inv[3], st.cp_inv[2]}};
    T_NEAR(ju_det(Cp), 1.0, 0.0, 1e-13, "%s, %d steps, step %d: det C_p^-1", what, nsteps, k);
    if (!r.plastic) continue;
    ++o.nplastic;
    const double sy = yield_formula(p, st.eps_p, r.d_eps_p, dt, T_rise_start);
    const double q = ju_von_mises(tau);
    const double err = fabs(q - sy) / sy;
    if (err > 1e-13)
      T_FAIL("%s, %d steps, step %d (eps_p %.6g): q(tau) = %.17g, sigma_y = %.17g, rel. error "
             "%.3g > 1e-13",
             what, nsteps, k, st.eps_p, q, sy, err);
    o.max_err = fmax(o.max_err, err);
  }
  o.eps_p = st.eps_p;
  memcpy(o.tau, tau, sizeof tau);
  return o;
}

static void check_path(const pdk_jc_params *p, const path *pa, int path_independent,
                       const char *what) {
  run_out r1 = run(p, pa, 1, what), r10 = run(p, pa, 10, what), r100 = run(p, pa, 100, what);
  T_ASSERT(r1.nplastic == 1 && r100.nplastic > 90, "%s: plastic steps %d, %d", what, r1.nplastic,
           r100.nplastic);
  T_ASSERT(r1.max_err <= 4.0 * r100.max_err + 1e-15,
           "%s: consistency error grows with the step: 1 step %.3g, 10 steps %.3g, 100 steps %.3g",
           what, r1.max_err, r10.max_err, r100.max_err);
  if (!path_independent) return;
  T_NEAR(r1.eps_p, r100.eps_p, 1e-12, 0.0, "%s: final eps_p, 1 vs 100 steps", what);
  T_NEAR(r10.eps_p, r100.eps_p, 1e-12, 0.0, "%s: final eps_p, 10 vs 100 steps", what);
  const double scale = ju_von_mises(r100.tau);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      T_NEAR(r1.tau[i][j], r100.tau[i][j], 0.0, 1e-12 * scale,
             "%s: final tau[%d][%d], 1 vs 100 steps", what, i, j);
      T_NEAR(r10.tau[i][j], r100.tau[i][j], 0.0, 1e-12 * scale,
             "%s: final tau[%d][%d], 10 vs 100 steps", what, i, j);
    }
}

int main(void) {
  /* 3-D: principal axes rotated about (1,2,3)/|.| by 0.7 rad; mostly deviatoric log strain with
   * 1% volume change; plane strain: axes rotated by 0.4 rad in the plane, 0.1% volume change
   * (so that eta stays ~0.1 and the damaged run does not fail). */
  path p3 = {3, {0.45, -0.12, -0.32}, {{0}}};
  const double k3[3] = {1.0 / sqrt(14.0), 2.0 / sqrt(14.0), 3.0 / sqrt(14.0)};
  ju_rotation(k3, 0.7, p3.Q);
  path p2 = {2, {0.35, -0.349, 0.0}, {{0}}};
  const double kz[3] = {0.0, 0.0, 1.0};
  ju_rotation(kz, 0.4, p2.Q);

  pdk_jc_params p = pdk_jc_params_default();
  p.damage = 0;
  check_path(&p, &p3, 1, "3-D rate-independent");
  check_path(&p, &p2, 1, "plane strain rate-independent");

  /* with damage (uncoupled): the same stresses until failure, which must not happen here */
  pdk_jc_params pd = pdk_jc_params_default();
  check_path(&pd, &p2, 1, "plane strain, damage on");

  pdk_jc_params pr = p;
  pr.C = 0.014;
  pr.ref_rate = 1.0;
  check_path(&pr, &p3, 0, "3-D rate-dependent");
  check_path(&pr, &p2, 0, "plane strain rate-dependent");

  pdk_jc_params pt = p;
  pt.thermal = 1;
  pt.T_initial = 600.0; /* T* ~ 0.2 at start, rising by adiabatic heating */
  check_path(&pt, &p3, 0, "3-D thermal softening with heating");
  pt.beta = 0.0; /* isothermal at T* = 0.2: path independent again */
  check_path(&pt, &p3, 1, "3-D isothermal at T* = 0.2");
  return 0;
}
