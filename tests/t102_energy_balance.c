/* Energy balance of a ductile bar pulled by a prescribed velocity (Johnson-Cook correspondence):
 *   external work = kinetic + strain (elastic, with the Silling term) + plastic + damage + breaking
 * where breaking is what bond breaking released (pdk_model_plastic_work, "w_broken").
 *
 * Bar [0, 40] x [0, 10] mm, dx = 1 mm, horizon 3.015 dx, plane strain, left three columns fixed,
 * right three columns pulled along x at a constant velocity v from t = 0 (prescribed as the
 * displacement u = v t, so their positions are exact at every step); the V-JC steel, Silling
 * stabilization (C_s = 0.1, an exact potential, part of the strain energy).
 * The kinetic energy is that of the free components: the solver's external work counts the
 * change of the prescribed particles' kinetic energy after t = 0, and here that is zero (they move
 * at v from t = 0, a jump that is part of the initial state).
 * Cases:
 *   1. plasticity, no damage, v = 20 m/s, 100 us (the bar ends with about 5% strain, 90% of the
 *      work dissipated plastically), at dt = 1e-7 s and 5e-8 s;
 *   2. plasticity, damage and breaking (short failure strain as in t101, a notch), v = 10 m/s,
 *      run until the bar is in two pieces and 20 us beyond: TL at dt = 1e-7 s and 5e-8 s,
 *      semi-TL at 1e-7 s.
 * The worst imbalance over the run (checked every 2 us), relative to the final external work:
 *   case 1: <= 1e-4, and at least 3 times smaller at dt/2. Velocity Verlet conserves the energy
 *     of the discrete system to O(dt^2), the external work is a trapezoid rule in time, and the
 *     material update satisfies P:dF = dW + dW_plastic to second order per step (t080). Measured
 *     1.8e-5, 4.4e-6 (dt/2), 1.1e-6 (dt/4): second order. (With the end pulled by a velocity
 *     condition that ramps, the imbalance is first order, 2e-4 at dt: the solver drifts prescribed
 *     particles by dt v(t_n), so the pulled end lags the integrated velocity by dt v / 2.)
 *   case 2: <= 5e-3 at dt = 1e-7 s, and at least 1.4 times smaller at dt/2. A particle that fails
 *     drops its stress within one step; its stored energy (and its Silling term) is booked as
 *     damage at the end of the step, while the internal work of that step, a trapezoid in time,
 *     sees only half of the drop: an error of order V P:dF per failure, first order in dt for a
 *     fixed number of failures. Breaking is booked at fixed positions with a trial update, and the
 *     next committed update reaches the new F in one return instead of two. Measured 2.1e-3 at
 *     1e-7 s, 7.4e-4 at 5e-8 s: discretization, not a leak (before the Silling energy of failing
 *     particles was booked the imbalance was 17%, the same at every dt).
 * labels: physics */
#include "jc_corr_util.h"


typedef jcu_sim sim;


static void build(pdk_ctx *ctx, int damage, pdk_connectivity mode, double v, double dt, sim *s) {
  jcu_bar(ctx, damage, &s->p, &s->fam);
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_JC;
  mo.jc.damage = damage;
  mo.jc.D1 = 0.02;
  mo.jc.D2 = 0.0;
  mo.stabilization = PDK_STAB_SILLING;
  mo.connectivity = mode;
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  jcu_bar_pull(s->bcs, 1, v); /* u = v t: velocity v, positions exact at every step */
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = s->bcs;
  eo.num_bcs = 2;
  eo.dt = dt; /* 1e-7 s: half the stable step (about 2e-7 s) */
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

/* Kinetic energy of the prescribed components (x of the pulled end): constant (v from t = 0), and
 * present from the initial state on, so the balance uses the kinetic energy of the free
 * components. */
static double prescribed_kinetic(sim *s) {
  const uint8_t *r = pdk_particles_field_data(s->p, "set:right", 0);
  const double *vx = pdk_particles_field_data(s->p, "v", 0);
  const double *vol = pdk_particles_volume(s->p);
  const double rho = pdk_model_opts_get(s->m)->density;
  double k = 0.0;
  for (pdk_index i = 0; i < pdk_particles_count(s->p); ++i)
    if (r[i]) k += 0.5 * rho * vol[i] * vx[i] * vx[i];
  return k;
}

static double imbalance(sim *s, const pdk_history *h) {
  return h->external_work - (h->kinetic - prescribed_kinetic(s) + h->strain + h->plastic_work +
                             h->damage_work + h->breaking_work);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const int verbose = getenv("PDK_TEST_VERBOSE") != NULL;

  /* 1. plasticity only, at dt and dt/2 */
  double worst1[2];
  for (int k = 0; k < 2; ++k) {
    sim s;
    const double dt = k ? 5e-8 : 1e-7;
    build(ctx, 0, PDK_CONNECTIVITY_TL, 20.0, dt, &s);
    pdk_history h;
    double worst = 0.0;
    for (int chunk = 0; chunk < 20; ++chunk) {
      T_OK(ctx, pdk_explicit_run(s.e, k ? 100 : 50, &h));
      worst = fmax(worst, fabs(imbalance(&s, &h)));
    }
    worst1[k] = worst / h.external_work;
    if (verbose)
      printf("plastic, dt %g: W_ext %g = K %g + S %g + P %g + D %g + B %g; imbalance %.3e "
             "(worst %.3e) of W_ext\n",
             dt, h.external_work, h.kinetic, h.strain, h.plastic_work, h.damage_work,
             h.breaking_work, imbalance(&s, &h) / h.external_work, worst1[k]);
    T_ASSERT(h.plastic_work > 0.5 * h.external_work, "the bar hardly yielded: plastic %g of %g",
             h.plastic_work, h.external_work);
    T_ASSERT(h.damage_work == 0.0 && h.breaking_work == 0.0 && h.broken == 0,
             "damage off, yet damage %g, breaking %g", h.damage_work, h.breaking_work);
    T_NEAR(worst, 0.0, 0.0, 1e-4 * h.external_work, "energy balance, plasticity only, dt %g", dt);
    jcu_sim_destroy(&s);
  }
  T_ASSERT(worst1[1] * 3.0 <= worst1[0], "plasticity only: not second order in dt (%.3e, %.3e)",
           worst1[0], worst1[1]);

  /* 2. plasticity, damage and breaking, until the bar is in two pieces */
  const pdk_connectivity modes[3] = {PDK_CONNECTIVITY_TL, PDK_CONNECTIVITY_TL,
                                     PDK_CONNECTIVITY_SEMI_TL};
  const double dts[3] = {1e-7, 5e-8, 1e-7};
  double worst_rel[3];
  for (int k = 0; k < 3; ++k) {
    sim s;
    build(ctx, 1, modes[k], 10.0, dts[k], &s);
    pdk_index *comp = malloc((size_t)pdk_particles_count(s.p) * sizeof *comp);
    T_ASSERT(comp, "out of memory");
    const long chunk = (long)(20 * (1e-7 / dts[k]) + 0.5); /* the same times for every dt */
    pdk_history h;
    double worst = 0.0;
    long steps = 0, sep = -1;
    while (steps < 8000 * chunk / 20 && (sep < 0 || steps < sep + 10 * chunk)) {
      T_OK(ctx, pdk_explicit_run(s.e, chunk, &h));
      steps += chunk;
      worst = fmax(worst, fabs(imbalance(&s, &h)));
      if (sep < 0 && jcu_components(s.m, comp) > 1) {
        const uint8_t *l = pdk_particles_field_data(s.p, "set:left", 0);
        const uint8_t *r = pdk_particles_field_data(s.p, "set:right", 0);
        pdk_index il = 0, ir = 0;
        while (!l[il])
          ++il;
        while (!r[ir])
          ++ir;
        if (comp[il] != comp[ir]) sep = steps;
      }
    }
    worst_rel[k] = worst / h.external_work;
    if (verbose)
      printf("%s, dt %g: steps %ld (separated %ld) W_ext %g = K %g + S %g + P %g + D %g + B %g; "
             "imbalance %.3e (worst %.3e) of W_ext\n",
             modes[k] == PDK_CONNECTIVITY_TL ? "TL" : "semi-TL", dts[k], steps, sep,
             h.external_work, h.kinetic, h.strain, h.plastic_work, h.damage_work, h.breaking_work,
             imbalance(&s, &h) / h.external_work, worst_rel[k]);
    T_ASSERT(sep > 0, "case %d: the bar did not separate", k);
    T_ASSERT(h.damage_work > 0.0 && h.breaking_work != 0.0, "damage %g, breaking %g", h.damage_work,
             h.breaking_work);
    T_NEAR(worst, 0.0, 0.0, 5e-3 * h.external_work,
           "energy balance with damage and breaking (case %d, dt %g)", k, dts[k]);
    free(comp);
    jcu_sim_destroy(&s);
  }
  T_ASSERT(worst_rel[1] * 1.4 <= worst_rel[0],
           "halving dt did not shrink the imbalance: %.3e at dt, %.3e at dt/2", worst_rel[0],
           worst_rel[1]);
  pdk_ctx_destroy(&ctx);
  return 0;
}
