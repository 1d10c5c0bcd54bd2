/* V-Q3 / V-Q4 smoke test (Queiruga & Moridis 2017, seeds/notes/002 section 4.1): uniaxial
 * compression of a 10 mm square, correspondence (F-based) law, cubic influence, RF = 1.5, solved
 * by Newton at two resolutions; the top-displacement error falls with order about 1.
 * labels: physics
 *
 * Setup as the paper (Table 1, Fig. 5): H = W = 10 mm, E = 1000 GPa, nu = 0, plane strain, T = 1e-3
 * GPa (N-mm-GPa units: forces in kN); node-type grid (particles on the boundary lines); bottom row
 * clamped, side columns on vertical rollers (u_x = 0), traction on the top row as a body force
 * b = T W / (N_top V) (notes 2.6); the small-strain linear law without stabilization (the paper
 * has none). Exact top displacement u_y = -T H / E = -1e-5 mm (compression: negative). Probe: mean
 * u_y over the top particles with 0.4 W <= x <= 0.6 W.
 *
 * Expected: the paper's order for this case is 0.9999 (Table 3/4, a fit over NP > 99); V-Q3 allows
 * 0.92-1.04 over the influence functions and problems. Between NP = 40 and 80 we measure 0.985; the
 * test accepts [0.9, 1.1] (pre-asymptotic at these sizes, where the 1/NP boundary-layer error still
 * carries a few per cent of higher-order terms). Errors: 3.7% and 1.9%; the test requires them
 * below 5% and 2.5% (first order with a constant of ~1.5 h / H, as the paper's Fig. 8 shows for
 * RF 1.5).
 */
#include "test_util.h"

static double probe(pdk_ctx *ctx, int np) {
  const double W = 10.0, H = 10.0, E = 1000.0, T = 1e-3, h = W / np, rf = 1.5;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.node_type = 1;
  lo.spacing = h;
  lo.hi[0] = W;
  lo.hi[1] = H;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  T_OK(ctx, pdk_particles_reorder_morton(p, rf * h, NULL));
  const double e = 0.25 * h;
  double b0[3] = {-1, -1, -1}, b1[3] = {W + 1, e, 1};        /* bottom row */
  double l0[3] = {-1, e, -1}, l1[3] = {e, H + 1, 1};         /* left column above it */
  double r0[3] = {W - e, e, -1}, r1[3] = {W + 1, H + 1, 1};  /* right column above it */
  double t0[3] = {-1, H - e, -1}, t1[3] = {W + 1, H + 1, 1}; /* top row */
  pdk_region bottom = pdk_region_box(b0, b1), left = pdk_region_box(l0, l1);
  pdk_region right = pdk_region_box(r0, r1), top = pdk_region_box(t0, t1);
  pdk_index n_top;
  T_OK(ctx, pdk_particles_set_define(p, "bottom", &bottom, NULL));
  T_OK(ctx, pdk_particles_set_define(p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(p, "right", &right, NULL));
  T_OK(ctx, pdk_particles_set_define(p, "top", &top, &n_top));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf * h;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.bulk_modulus = E / 3.0; /* nu = 0 */
  mo.shear_modulus = E / 2.0;
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = PDK_STAB_NONE;
  mo.law = PDK_LAW_LINEAR_ELASTIC;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_bc bcs[4];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:bottom";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:left";
  bcs[1].components = 1;
  bcs[2].kind = PDK_BC_DISPLACEMENT;
  bcs[2].set = "set:right";
  bcs[2].components = 1;
  bcs[3].kind = PDK_BC_BODY_FORCE;
  bcs[3].set = "set:top";
  bcs[3].components = 2;
  bcs[3].value[1] = pdk_tfun_constant(-T * W / (n_top * pdk_particles_volume(p)[0]));
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 4;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  if (getenv("PDK_TEST_VERBOSE")) pdk_static_stats_print(pdk_static_stats_get(s), stdout);
  const double *y = pdk_particles_field_data(p, "x", 1), *Y = pdk_particles_X(p, 1);
  const double *X = pdk_particles_X(p, 0);
  const uint8_t *in_top = pdk_particles_field_data(p, "set:top", 0);
  double sum = 0.0;
  int count = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    if (in_top[i] && X[i] >= 0.4 * W - 1e-9 && X[i] <= 0.6 * W + 1e-9) {
      sum += y[i] - Y[i];
      ++count;
    }
  T_ASSERT(count == np / 5 + 1, "probe holds %d particles at NP = %d", count, np);
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return sum / count;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double exact = -1e-5;
  const int np[2] = {40, 80};
  double err[2];
  for (int k = 0; k < 2; ++k) {
    const double u = probe(ctx, np[k]);
    T_ASSERT(u < 0, "NP = %d: the top moved up (u_y = %g) under compression", np[k], u);
    err[k] = fabs(u - exact) / fabs(exact);
    if (getenv("PDK_TEST_VERBOSE"))
      printf("NP %d: u_y %.10e, relative error %.4e\n", np[k], u, err[k]);
  }
  const double order = log(err[0] / err[1]) / log(2.0);
  if (getenv("PDK_TEST_VERBOSE")) printf("order %.4f\n", order);
  T_ASSERT(err[0] < 0.05 && err[1] < 0.025, "errors %.3e (NP 40), %.3e (NP 80)", err[0], err[1]);
  T_ASSERT(order >= 0.9 && order <= 1.1, "convergence order %.4f, expected about 1 (V-Q3)", order);
  pdk_ctx_destroy(&ctx);
  return 0;
}
