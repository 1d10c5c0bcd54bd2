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
#include "test_util.h"

typedef struct bar_result {
  double u_top;
  long rebuilds;
  long iterations;
  double *u; /* displacement of every particle, 3 per particle (the caller frees it) */
  pdk_index n;
} bar_result;

static bar_result solve_bar(pdk_ctx *ctx, pdk_connectivity mode, int stab, double tau, double h,
                            pdk_static_method method) {
  const double W = 0.1, L = 1.0, lambda = 200.0, mu = 20.0;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_CUBIC;
  lo.spacing = h;
  lo.hi[0] = W;
  lo.hi[1] = W;
  lo.hi[2] = L;
  pdk_particles *p;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  const double delta = 2.015 * h;
  T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, delta), NULL));
  const double e = 0.25 * h, big = 10.0;
  const double b0[3] = {-big, -big, -big}, b1[3] = {big, big, h - e};
  const double t0[3] = {-big, -big, L - h + e}, t1[3] = {big, big, big};
  const double x0[3] = {0.5 * W - e, -big, -big}, x1[3] = {0.5 * W + e, big, big};
  const double y0[3] = {-big, 0.5 * W - e, -big}, y1[3] = {big, 0.5 * W + e, big};
  pdk_region bottom = pdk_region_box(b0, b1), top = pdk_region_box(t0, t1);
  pdk_region xmid = pdk_region_box(x0, x1), ymid = pdk_region_box(y0, y1);
  pdk_index n_top = 0, n_bottom = 0, n_x = 0, n_y = 0;
  T_OK(ctx, pdk_particles_set_define(p, "bottom", &bottom, &n_bottom));
  T_OK(ctx, pdk_particles_set_define(p, "top", &top, &n_top));
  T_OK(ctx, pdk_particles_set_define(p, "xmid", &xmid, &n_x));
  T_OK(ctx, pdk_particles_set_define(p, "ymid", &ymid, &n_y));
  T_ASSERT(n_top == 25 && n_bottom == 25 && n_x == 250 && n_y == 250,
           "sets: top %d bottom %d xmid %d ymid %d", (int)n_top, (int)n_bottom, (int)n_x, (int)n_y);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = delta;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_SVK;
  mo.shear_modulus = mu;
  mo.bulk_modulus = lambda + 2.0 * mu / 3.0;
  mo.density = 1.4;
  mo.influence = PDK_INFLUENCE_CONSTANT;
  mo.stabilization = stab ? PDK_STAB_SILLING : PDK_STAB_NONE;
  mo.stab_coefficient = 0.1;
  mo.connectivity = mode;
  mo.ul_skin = 0.1;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));

  pdk_bc bcs[4];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:bottom";
  bcs[0].components = 4;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:xmid";
  bcs[1].components = 1;
  bcs[2].kind = PDK_BC_DISPLACEMENT;
  bcs[2].set = "set:ymid";
  bcs[2].components = 2;
  bcs[3].kind = PDK_BC_BODY_FORCE;
  bcs[3].set = "set:top";
  bcs[3].components = 4;
  bcs[3].value[2] = pdk_tfun_constant(tau / h);
  pdk_static_opts so = pdk_static_opts_default(method);
  so.bcs = bcs;
  so.num_bcs = 4;
  so.num_levels = method == PDK_STATIC_ADR ? 4 : 1; /* Newton: one level suffices at 1% strain */
  so.rtol = method == PDK_STATIC_ADR ? 1e-7 : 1e-10;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  if (getenv("PDK_TEST_VERBOSE")) pdk_static_stats_print(pdk_static_stats_get(s), stdout);
  const double *z = pdk_particles_field_data(p, "x", 2), *Z = pdk_particles_X(p, 2);
  const uint8_t *in_top = pdk_particles_field_data(p, "set:top", 0);
  double sum = 0.0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    if (in_top[i]) sum += z[i] - Z[i];
  bar_result r;
  r.u_top = sum / (double)n_top;
  r.rebuilds = pdk_model_num_rebuilds(m);
  r.iterations = pdk_static_stats_get(s)->iterations;
  r.n = pdk_particles_count(p);
  r.u = malloc(3 * (size_t)r.n * sizeof *r.u);
  T_ASSERT(r.u, "out of memory");
  for (int d = 0; d < 3; ++d) {
    const double *xd = pdk_particles_field_data(p, "x", d), *Xd = pdk_particles_X(p, d);
    for (pdk_index i = 0; i < r.n; ++i) r.u[3 * i + d] = xd[i] - Xd[i];
  }
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return r;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double h = 0.02, tau = 0.58, lambda = 200.0, mu = 20.0;
  const double E = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
  /* lambda3 (lambda3^2 - 1) / 2 = tau / E, by Newton from 1. */
  double s = 1.0;
  for (int it = 0; it < 50; ++it)
    s -= (0.5 * s * (s * s - 1.0) - tau / E) / (1.5 * s * s - 0.5);
  const double exact = (s - 1.0) * (1.0 - h);
  for (int stab = 0; stab < 2; ++stab) {
    bar_result tl = solve_bar(ctx, PDK_CONNECTIVITY_TL, stab, tau, h, PDK_STATIC_ADR);
    bar_result ul = solve_bar(ctx, PDK_CONNECTIVITY_UL, stab, tau, h, PDK_STATIC_ADR);
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
      bar_result nt = solve_bar(ctx, PDK_CONNECTIVITY_TL, stab, tau, h, PDK_STATIC_NEWTON);
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
               "%s: ADR and Newton differ by %.2e of max |u| (bound 1e-4 = 1000 x ADR's rtol)", what,
               dmax / umax);
      free(nt.u);
    }
    free(tl.u);
    free(ul.u);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
