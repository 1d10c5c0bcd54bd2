/* The St Venant-Kirchhoff bar of Bergel & Li 2016, section 4.2 (V-BL example II), shared by
 * t132 (TL against UL, ADR against Newton) and t237 (refinement, damping): a 0.1 x 0.1 x 1.0 bar
 * (lambda = 200, mu = 20, rho0 = 1.4) of a simple cubic lattice of spacing h, horizon 2.015 h,
 * constant influence, correspondence with or without Silling's 0.1; bottom layer u_z = 0, the
 * symmetry planes x = 0.05 (u_x = 0) and y = 0.05 (u_y = 0), top layer the body force tau / h
 * (the nominal traction tau on the end face); solved statically (ADR in 4 load levels, Newton in
 * one) to `rtol`. bar_analytical(h): the uniaxial SVK top displacement for tau = 0.58 over the
 * length 1 - h between the centres of the bottom and top layers. */
#ifndef PDK_TEST_BAR_UTIL_H
#define PDK_TEST_BAR_UTIL_H

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

static double bar_analytical(double h) {
  const double tau = 0.58, lambda = 200.0, mu = 20.0;
  const double E = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
  double s = 1.0; /* lambda3 (lambda3^2 - 1) / 2 = tau / E, by Newton from 1 */
  for (int it = 0; it < 50; ++it)
    s -= (0.5 * s * (s * s - 1.0) - tau / E) / (1.5 * s * s - 0.5);
  return (s - 1.0) * (1.0 - h);
}

#endif
