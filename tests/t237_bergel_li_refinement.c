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
#include "test_util.h"

typedef struct bar_result {
  double u_top;
  long rebuilds;
  long iterations;
  double *u; /* displacement of every particle, 3 per particle (the caller frees it) */
  pdk_index n;
} bar_result;

static bar_result solve_bar(pdk_ctx *ctx, pdk_connectivity mode, int stab, double tau, double h,
                            pdk_static_method method, double rtol) {
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
  const pdk_index na = (pdk_index)lround(W / h), nl = (pdk_index)lround(L / h);
  T_ASSERT(n_top == na * na && n_bottom == na * na && n_x == na * nl && n_y == na * nl,
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
  so.rtol = rtol;
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
    for (pdk_index i = 0; i < r.n; ++i)
      r.u[3 * i + d] = xd[i] - Xd[i];
  }
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return r;
}

static double analytical(double h) {
  const double tau = 0.58, lambda = 200.0, mu = 20.0;
  const double E = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
  double s = 1.0; /* lambda3 (lambda3^2 - 1) / 2 = tau / E, by Newton from 1 */
  for (int it = 0; it < 50; ++it)
    s -= (0.5 * s * (s * s - 1.0) - tau / E) / (1.5 * s * s - 0.5);
  return (s - 1.0) * (1.0 - h);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double W = 0.1, tau = 0.58;
  const int across[4] = {3, 5, 7, 9};
  double err[4];
  for (int k = 0; k < 4; ++k) {
    const double h = W / across[k];
    bar_result tl = solve_bar(ctx, PDK_CONNECTIVITY_TL, 0, tau, h, PDK_STATIC_ADR, 1e-7);
    err[k] = tl.u_top / analytical(h) - 1.0;
    if (getenv("PDK_TEST_VERBOSE"))
      printf("TL, %d across (%ld particles): top displacement %.6e, %+.3f%% of %.6e (%ld "
             "iterations)\n",
             across[k], (long)tl.n, tl.u_top, 100 * err[k], analytical(h), tl.iterations);
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
