/* Explicit solver: boundary conditions, body force, initial velocity, reactions, external work,
 * and a whole run bitwise identical on 1 and 2 threads.
 * labels: physics threads */
#include "test_util.h"

/* A 2-D PMB bar [0, 40 dx] x [0, 6 dx], dx = 1 mm, with sets "left" and "right" (first and last
 * three columns). */
static void build(pdk_ctx *ctx, pdk_particles **p, pdk_families **fam, pdk_model **m, double K) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.hi[0] = 40e-3;
  lo.hi[1] = 6e-3;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, p));
  T_OK(ctx, pdk_particles_reorder_morton(*p, 3.015e-3, NULL));
  double a[3] = {-1, -1, -1}, b[3] = {3e-3, 1, 1}, c[3] = {37e-3, -1, -1}, d[3] = {1, 1, 1};
  pdk_region left = pdk_region_box(a, b), right = pdk_region_box(c, d);
  T_OK(ctx, pdk_particles_set_define(*p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(*p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(*p, &fo, fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_PMB;
  mo.bulk_modulus = K;
  mo.density = 8000;
  T_OK(ctx, pdk_model_create(*p, *fam, &mo, m));
}

static void destroy(pdk_particles **p, pdk_families **fam, pdk_model **m) {
  pdk_model_destroy(m);
  pdk_families_destroy(fam);
  pdk_particles_destroy(p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;

  /* 1. Free flight: uniform initial velocity plus a body force on every particle. Internal forces
   * vanish for rigid motion, so x = X + v0 t + b t^2 / (2 rho): velocity Verlet is exact for
   * constant acceleration, up to round-off. */
  build(ctx, &p, &fam, &m, 1e9);
  pdk_bc g = {0};
  g.kind = PDK_BC_BODY_FORCE;
  g.components = 2;
  g.value[1] = pdk_tfun_constant(-9.81 * 8000);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = &g;
  eo.num_bcs = 1;
  eo.v0_const[0] = 2.0;
  pdk_explicit *e;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  T_OK(ctx, pdk_explicit_run(e, 100, NULL));
  double t = pdk_explicit_time(e);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
    T_NEAR(x[i], pdk_particles_X(p, 0)[i] + 2.0 * t, 1e-12, 1e-15, "free flight x at %d", (int)i);
    T_NEAR(y[i], pdk_particles_X(p, 1)[i] - 0.5 * 9.81 * t * t, 1e-12, 1e-12, "free fall y at %d", (int)i);
  }
  pdk_explicit_destroy(&e);
  destroy(&p, &fam, &m);

  /* 2. Bar pulled slowly: left fixed, right displaced by a smooth ramp. Prescribed particles
   * follow the ramp exactly; at the end (quasi-static, held) the two reactions balance and the
   * external work equals the stored energy plus kinetic energy (energy balance, 2%: the run is
   * dynamic and the held state still vibrates). */
  build(ctx, &p, &fam, &m, 1e9);
  pdk_bc bcs[2] = {{0}, {0}};
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  const char *rsets[2] = {"set:left", "set:right"};
  eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 2;
  eo.reaction_sets = rsets;
  eo.num_reaction_sets = 2;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  double dt = pdk_explicit_dt(e);
  double T_ramp = 4000 * dt, u_end = 2e-5;
  pdk_explicit_destroy(&e);
  bcs[1].value[0] = (pdk_tfun){PDK_TFUN_SMOOTH, u_end, T_ramp};
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(e, 6000, &h));
  {
    uint8_t *right = pdk_particles_field_data(p, "set:right", 0), *left = pdk_particles_field_data(p, "set:left", 0);
    double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
      if (right[i]) T_NEAR(x[i], pdk_particles_X(p, 0)[i] + u_end, 1e-14, 0, "right end displaced");
      if (left[i]) {
        T_ASSERT(x[i] == pdk_particles_X(p, 0)[i] && y[i] == pdk_particles_X(p, 1)[i], "left end fixed");
      }
    }
  }
  T_ASSERT(h.reaction[1][0] > 0 && h.reaction[0][0] < 0, "pulled right end, held left: %g %g", h.reaction[1][0], h.reaction[0][0]);
  if (getenv("PDK_TEST_VERBOSE")) printf("R %g %g W %g S %g K %g\n", h.reaction[0][0], h.reaction[1][0], h.external_work, h.strain, h.kinetic);
  T_NEAR(-h.reaction[0][0], h.reaction[1][0], 0.05, 0, "reactions balance near equilibrium");
  T_NEAR(h.external_work, h.strain + h.kinetic, 0.02, 0, "energy balance");
  pdk_explicit_destroy(&e);

  /* 3. The same run on 2 threads is bitwise identical. */
  double *x1 = malloc(2 * sizeof(double) * (size_t)pdk_particles_count(p));
  destroy(&p, &fam, &m);
  for (int threads = 1; threads <= 2; ++threads) {
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, threads));
    build(ctx, &p, &fam, &m, 1e9);
    T_OK(ctx, pdk_explicit_create(m, &eo, &e));
    pdk_history h2;
    T_OK(ctx, pdk_explicit_run(e, 500, &h2));
    pdk_index n = pdk_particles_count(p);
    for (int c = 0; c < 2; ++c) {
      double *x = pdk_particles_field_data(p, "x", c);
      if (threads == 1) memcpy(x1 + c * n, x, (size_t)n * sizeof(double));
      else T_ASSERT(!memcmp(x1 + c * n, x, (size_t)n * sizeof(double)), "x differs between 1 and 2 threads");
    }
    static pdk_history h1;
    if (threads == 1) h1 = h2;
    else T_ASSERT(!memcmp(&h1, &h2, sizeof h1), "history differs between 1 and 2 threads");
    pdk_explicit_destroy(&e);
    destroy(&p, &fam, &m);
  }
  free(x1);

  /* 4. Bad input: a set that does not exist, overlapping conditions, a bad time function. */
  build(ctx, &p, &fam, &m, 1e9);
  bcs[1].set = "set:nowhere";
  T_FAILS(ctx, pdk_explicit_create(m, &eo, &e), PDK_ERR_NOT_FOUND, "set:nowhere");
  bcs[1].set = "set:left";
  T_FAILS(ctx, pdk_explicit_create(m, &eo, &e), PDK_ERR_ARG, "prescribed by both");
  bcs[1].set = "set:right";
  bcs[1].value[0] = (pdk_tfun){PDK_TFUN_RAMP, 1e-5, 0.0};
  T_FAILS(ctx, pdk_explicit_create(m, &eo, &e), PDK_ERR_ARG, "positive duration");
  destroy(&p, &fam, &m);
  pdk_ctx_destroy(&ctx);
  return 0;
}
