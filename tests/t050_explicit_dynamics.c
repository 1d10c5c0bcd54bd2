/* Explicit solver: velocity Verlet kinematics, energy conservation ~ dt^2, time-step estimate and
 * refusal, non-finite detection, bitwise thread independence.
 * labels: physics threads */
#include "test_util.h"

/* A PMB cube of n^3 particles, spacing 1e-3 m, delta = 3.015 dx, steel-like. */
static void build(pdk_ctx *ctx, int n, pdk_particles **p, pdk_families **fam, pdk_model **m) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_CUBIC;
  lo.spacing = 1e-3;
  for (int d = 0; d < 3; ++d) lo.hi[d] = n * lo.spacing;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, p));
  T_OK(ctx, pdk_particles_reorder_morton(*p, 3.015e-3, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(*p, &fo, fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_PMB;
  mo.bulk_modulus = 160e9;
  mo.density = 7800;
  T_OK(ctx, pdk_model_create(*p, *fam, &mo, m));
}

static double total_energy(pdk_explicit *e, pdk_history *h) {
  T_OK(NULL, pdk_explicit_run(e, 0, h));
  return h->kinetic + h->strain;
}

/* Runs to time T with time step dt from an initial velocity field; returns max |E - E0| / E0. */
static double energy_drift(pdk_ctx *ctx, double dt_factor, double *dt_used) {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  build(ctx, 8, &p, &fam, &m);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  /* a smooth breathing-and-shearing velocity field, 1 m/s scale */
  eo.v0_grad[0][0] = 100.0;
  eo.v0_grad[1][0] = 60.0;
  eo.v0_grad[2][2] = -80.0;
  pdk_explicit *e;
  double dts = 0;
  {
    pdk_explicit *probe;
    T_OK(ctx, pdk_explicit_create(m, &eo, &probe));
    dts = pdk_explicit_stable_dt(probe);
    pdk_explicit_destroy(&probe);
  }
  eo.dt = dt_factor * dts;
  *dt_used = eo.dt;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  pdk_history h;
  double e0 = total_energy(e, &h), worst = 0;
  double T = 40 * 0.4 * dts;
  long steps = (long)llround(T / eo.dt);
  for (long s = 0; s < steps; ++s) {
    T_OK(ctx, pdk_explicit_run(e, 1, &h));
    worst = fmax(worst, fabs(h.kinetic + h.strain - e0));
  }
  pdk_explicit_destroy(&e);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return worst / e0;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  /* Energy drift of velocity Verlet is O(dt^2): halving dt divides it by about 4. The ratio is
   * asymptotic, so accept 3..5 (nonlinear PMB terms and the finite run perturb it). */
  double dt1, dt2;
  double d1 = energy_drift(ctx, 0.4, &dt1);
  double d2 = energy_drift(ctx, 0.2, &dt2);
  if (getenv("PDK_TEST_VERBOSE")) printf("drift %g %g ratio %g dt %g %g\n", d1, d2, d1 / d2, dt1, dt2);
  T_ASSERT(d1 < 1e-2, "energy drift %g at 0.4 dt_stable should be small", d1);
  T_ASSERT(d2 > 0 && d1 / d2 > 3.0 && d1 / d2 < 5.0, "drift ratio %g (%g / %g), expected ~4", d1 / d2, d1, d2);

  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  build(ctx, 6, &p, &fam, &m);
  /* Stable-step estimate: the Silling-Askari bound dt_SA = sqrt(2 rho / sum_j c V_j / |xi|) is a
   * Gershgorin (guaranteed) bound, so the true limit, and the Lanczos estimate of it, lie above. */
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  pdk_explicit *e;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  double dts = pdk_explicit_stable_dt(e);
  T_NEAR(pdk_explicit_dt(e), 0.8 * dts, 1e-15, 0, "default dt is 0.8 of the estimate");
  {
    const pdk_bond_index *bs = pdk_families_bond_start(fam);
    const pdk_index *bj = pdk_families_bond_j(fam);
    const double c = 18.0 * 160e9 / (M_PI * pow(3.015e-3, 4));
    double worst = 1e300;
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
      double s = 0;
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        double r2 = 0;
        for (int d = 0; d < 3; ++d) {
          double dx = pdk_particles_X(p, d)[bj[b]] - pdk_particles_X(p, d)[i];
          r2 += dx * dx;
        }
        s += c * pdk_particles_volume(p)[bj[b]] / sqrt(r2);
      }
      worst = fmin(worst, sqrt(2 * 7800 / s));
    }
    T_ASSERT(dts >= worst * 0.999 && dts < 4 * worst, "estimate %g vs Silling-Askari bound %g", dts, worst);
  }
  pdk_explicit_destroy(&e);
  /* A dt above the estimate is refused, with the limit in the message; forced, a far too large dt
   * blows up and the run stops naming step and particle. */
  eo.dt = 1.05 * dts;
  pdk_ctx_error_clear(ctx);
  T_ASSERT(pdk_explicit_create(m, &eo, &e) == PDK_ERR_ARG, "dt above the limit refused");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "exceeds the estimated stable limit"), "%s", pdk_ctx_error_message(ctx));
  eo.dt = 0.99 * dts;
  eo.v0_grad[0][0] = 10.0;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(e, 0, &h));
  double e0 = h.kinetic + h.strain;
  T_OK(ctx, pdk_explicit_run(e, 300, &h));
  T_ASSERT(h.kinetic + h.strain < 1.5 * e0, "0.99 of the limit stays bounded: %g vs %g", h.kinetic + h.strain, e0);
  pdk_explicit_destroy(&e);
  eo.dt = 3.0 * dts;
  eo.force_dt = 1;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  int err = PDK_SUCCESS;
  for (int k = 0; k < 2000 && !err; ++k) err = pdk_explicit_run(e, 10, NULL);
  T_ASSERT(err == PDK_ERR_NUMERIC, "forced unstable dt detected (err %d)", err);
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), " at step ") && strstr(pdk_ctx_error_message(ctx), "particle") && strstr(pdk_ctx_error_message(ctx), "stable"),
           "%s", pdk_ctx_error_message(ctx));
  pdk_explicit_destroy(&e);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
