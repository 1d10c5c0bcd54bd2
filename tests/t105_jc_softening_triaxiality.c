/* Softened stabilization and family-averaged damage triaxiality (pdk_model_opts stab_softening,
 * damage_triaxiality; kernels/ref/corr.c, src/models/model_corr.c).
 *
 * 1. Material point, pdk_jc_update_avg: given the point's own effective mean stress it returns
 *    what pdk_jc_update returns (stress, history; to 1e-12, the round-off of sigma_m J / q against
 *    tau_m / q); given another mean stress it uses eta = sigma_m_avg J / q for the damage (the
 *    increment d_eps_p / eps_f(eta) to 1e-12), including negative triaxiality, and the stress does
 *    not change (uncoupled). A non-finite mean stress is refused.
 * 2. Elastic run: with no plastic flow the factor stays 1 and the run is bitwise the same as with
 *    softening off (the option costs nothing where nothing flows).
 * 3. Plastic bar (t102's: 40 x 10 mm, dx 1 mm, V-JC steel, pulled at 20 m/s, 100 us) with
 *    softening: factors never rise and each particle's w_stab stays >= 0 (checked every 5 us;
 *    the term is passive); factors lie in [floor, 1], exactly 1 where eps_p = 0 and at most the
 *    secant bound sigma_y(eps_p) / (J E eps_p) where it flowed, over a quarter of the particles
 *    below 1; and the balance external = kinetic + strain + plastic (with w_stab) holds to 1e-4
 *    of the external work, at least 3 times better at dt/2 (second order, as t102 without
 *    softening). Without booking w_stab the imbalance would be w_stab itself: the test also
 *    asserts w_stab exceeds 10 times the tolerance, so it would fail. Measured: w_stab 100 J of
 *    21 800 J; imbalance 1.76e-5 at dt, 4.38e-6 at dt/2 (booking the change of the factor at the
 *    step's end only, instead of at its mean, was first order: 3.4e-5, 1.3e-5).
 * 4. Notched bar with damage and breaking, softening and family triaxiality on: "sigma_m_avg"
 *    equals an average evaluated here from "sigma_m", the families, the bond state and "failed"
 *    (to 1e-13 relative: the same sum in the same order, written independently); one committed
 *    step of a plastic particle reproduces the model's damage exactly from pdk_jc_update_avg with
 *    the average before the step (and differs from the local update's, so the option acts); the
 *    state after the run is bitwise the same on 1 and 2 threads (histories, factors, averages,
 *    bond state), and in semi-TL with a compaction in every breaking pass (no particle is
 *    detached, so its sums over the compacted list are TL's, term for term).
 * 5. Kernel variants: the same run with the reference kernels, the optimized general path and the
 *    stencil path: positions agree to 1e-9 of the largest displacement and eps_p to 1e-9 absolute
 *    after 300 committed steps (the variants sum in different orders; round-off grows through
 *    the return map and the steps; measured 6e-17 m of 3e-4 m and 8e-15).
 * labels: physics */
#include <math.h>

#include "jc_corr_util.h"
#include "pdk/explicit.h"


typedef jcu_sim sim;

/* The bar of t102: damage (with a notch and a short failure strain) or not, pulled at v. */
static void build(pdk_ctx *ctx, int damage, int soft, int family, pdk_stencil_mode stencil,
                  pdk_connectivity conn, double v, double dt, sim *s) {
  jcu_bar(ctx, damage, &s->p, &s->fam);
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_JC;
  mo.bulk_modulus = mo.shear_modulus = mo.density = 0.0; /* from mo.jc */
  mo.jc.damage = damage;
  mo.jc.D1 = 0.02;
  mo.jc.D2 = 0.3;
  mo.jc.D3 = -2.12;
  mo.stabilization = PDK_STAB_SILLING;
  mo.stab_softening = soft;
  mo.damage_triaxiality = family ? PDK_TRIAX_FAMILY : PDK_TRIAX_LOCAL;
  mo.stencil = stencil;
  mo.connectivity = conn;
  mo.compact_fraction = 0.0; /* semi-TL: compact in every pass that broke bonds */
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  jcu_bar_pull(s->bcs, 1, v); /* u = v t: positions exact at every step */
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = s->bcs;
  eo.num_bcs = 2;
  eo.dt = dt;
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static double field(sim *s, const char *name, pdk_index i) {
  return ((const double *)pdk_particles_field_data(s->p, name, 0))[i];
}

/* ---- 1. material point ----------------------------------------------------------------------- */

static void point(void) {
  pdk_jc_params p = pdk_jc_params_default();
  p.D1 = 0.05;
  p.D2 = 3.44;
  p.D3 = -2.12;
  const pdk_jc_state s0 = pdk_jc_state_initial();
  /* a plastic state: plane strain stretch with shear, then one more step */
  const double F0[3][3] = {{1.02, 0.004, 0}, {0.001, 0.995, 0}, {0, 0, 1}};
  const double F1[3][3] = {{1.024, 0.005, 0}, {0.001, 0.994, 0}, {0, 0, 1}};
  pdk_jc_state s1, a, b;
  pdk_jc_result r0, ra, rb;
  double P[3][3], Pa[3][3], Pb[3][3];
  T_ASSERT(pdk_jc_update(&p, 2, F0, 1e-7, &s0, &s1, P, &r0) == 0, "update");
  T_ASSERT(r0.plastic && s1.damage > 0.0, "the first step must flow (eps_p %g)", s1.eps_p);
  T_ASSERT(pdk_jc_update(&p, 2, F1, 1e-7, &s1, &a, Pa, &ra) == 0, "update");
  T_ASSERT(ra.plastic, "the second step must flow");
  /* own mean stress: the same step */
  const double own = ra.sigma_m_eff;
  T_NEAR(own, (ra.sigma[0] + ra.sigma[1] + ra.sigma[2]) / 3.0, 0.0, 1e-12 * fabs(own),
         "uncoupled: sigma_m_eff is the Cauchy mean stress");
  T_ASSERT(pdk_jc_update_avg(&p, 2, F1, 1e-7, own, &s1, &b, Pb, &rb) == 0, "update_avg");
  T_NEAR(b.damage, a.damage, 0.0, 1e-12 * a.damage, "damage with the own mean stress");
  T_NEAR(rb.triaxiality, ra.triaxiality, 0.0, 1e-12 * fabs(ra.triaxiality), "eta");
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      T_NEAR(Pb[i][j], Pa[i][j], 0.0, 1e-12 * fabs(Pa[0][0]), "P[%d][%d]", i, j);
  /* another mean stress: eta from it, the damage increment at that eta, the stress unchanged */
  const double avgs[3] = {2.5 * own, -1.5 * fabs(own), 0.0};
  for (int k = 0; k < 3; ++k) {
    T_ASSERT(pdk_jc_update_avg(&p, 2, F1, 1e-7, avgs[k], &s1, &b, Pb, &rb) == 0, "update_avg");
    const double eta = avgs[k] / ra.sigma_vm; /* sigma_m_avg J / q = sigma_m_avg / sigma_vm */
    T_NEAR(rb.triaxiality, eta, 0.0, 1e-12 * fmax(fabs(eta), 1.0), "eta from sigma_m_avg %g",
           avgs[k]);
    const double ef = pdk_jc_failure_strain(&p, eta, 1.0, 0.0);
    T_NEAR(b.damage, s1.damage + ra.d_eps_p / ef, 0.0, 1e-12 * b.damage,
           "damage at eta %g (failure strain %g)", eta, ef);
    T_NEAR(b.eps_p, a.eps_p, 0.0, 0.0, "eps_p does not depend on the damage's pressure");
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        T_NEAR(Pb[i][j], Pa[i][j], 0.0, 0.0, "uncoupled: P[%d][%d] unchanged", i, j);
  }
  T_ASSERT(pdk_jc_update_avg(&p, 2, F1, 1e-7, NAN, &s1, &b, Pb, &rb) == PDK_ERR_ARG,
           "a non-finite mean stress is refused");
}

/* ---- 2. elastic: bitwise unchanged ------------------------------------------------------------
 */

static void elastic(pdk_ctx *ctx) {
  sim s[2];
  for (int k = 0; k < 2; ++k) {
    build(ctx, 0, k, 0, PDK_STENCIL_OFF, PDK_CONNECTIVITY_TL, 0.5, 1e-7, &s[k]); /* 0.5 m/s x 20 us: strain 2.5e-4 */
    pdk_history h;
    T_OK(ctx, pdk_explicit_run(s[k].e, 200, &h));
  }
  const pdk_index n = pdk_particles_count(s[0].p);
  const double *f = pdk_particles_field_data(s[1].p, "stab_factor", 0);
  for (pdk_index i = 0; i < n; ++i) {
    T_ASSERT(field(&s[1], "eps_p", i) == 0.0, "the elastic run yielded at particle %d", (int)i);
    T_ASSERT(f[i] == 1.0, "particle %d: factor %g without flow", (int)i, f[i]);
    for (int d = 0; d < 2; ++d)
      T_ASSERT(((const double *)pdk_particles_field_data(s[0].p, "x", d))[i] ==
                   ((const double *)pdk_particles_field_data(s[1].p, "x", d))[i],
               "elastic run: x[%d] of particle %d differs with softening on", d, (int)i);
  }
  jcu_sim_destroy(&s[0]);
  jcu_sim_destroy(&s[1]);
}

/* ---- 3. plastic bar: factors and energy -------------------------------------------------------
 */

static void plastic(pdk_ctx *ctx, int verbose) {
  double worst_rel[2];
  for (int k = 0; k < 2; ++k) {
    const double dt = k ? 5e-8 : 1e-7;
    sim s;
    build(ctx, 0, 1, 0, PDK_STENCIL_OFF, PDK_CONNECTIVITY_TL, 20.0, dt, &s);
    const pdk_index n = pdk_particles_count(s.p);
    const uint8_t *r = pdk_particles_field_data(s.p, "set:right", 0);
    const double rho = pdk_model_opts_get(s.m)->density;
    pdk_history h;
    double worst = 0.0;
    double *f_prev = malloc((size_t)n * sizeof *f_prev);
    T_ASSERT(f_prev, "out of memory");
    for (pdk_index i = 0; i < n; ++i)
      f_prev[i] = 1.0;
    for (int chunk = 0; chunk < 20; ++chunk) {
      T_OK(ctx, pdk_explicit_run(s.e, k ? 100 : 50, &h));
      /* passive: the factor never rises, so the account never gives energy back */
      for (pdk_index i = 0; i < n; ++i) {
        const double f = field(&s, "stab_factor", i);
        T_ASSERT(f <= f_prev[i], "particle %d: factor rose from %g to %g", (int)i, f_prev[i], f);
        T_ASSERT(field(&s, "w_stab", i) >= 0.0, "particle %d: w_stab %g < 0", (int)i,
                 field(&s, "w_stab", i));
        f_prev[i] = f;
      }
      /* the pulled end moves at v from t = 0, part of the initial state (t102) */
      double kin = 0.0;
      const double *vx = pdk_particles_field_data(s.p, "v", 0);
      const double *vol = pdk_particles_volume(s.p);
      for (pdk_index i = 0; i < n; ++i)
        if (r[i]) kin += 0.5 * rho * vol[i] * vx[i] * vx[i];
      const double imb = h.external_work - (h.kinetic - kin + h.strain + h.plastic_work +
                                            h.damage_work + h.breaking_work);
      worst = fmax(worst, fabs(imb));
    }
    double w_stab = 0.0, f_min = 1.0;
    int softened = 0;
    const double *vol = pdk_particles_volume(s.p);
    const double floor = pdk_model_opts_get(s.m)->stab_softening_floor;
    for (pdk_index i = 0; i < n; ++i) {
      const double f = field(&s, "stab_factor", i), ep = field(&s, "eps_p", i);
      T_ASSERT(f >= floor && f <= 1.0, "particle %d: factor %g outside [%g, 1]", (int)i, f, floor);
      /* f = sigma_vm / (E eps_p) clamped, sigma_vm <= sigma_y(eps_p) / J (J > 0.9 here) */
      const pdk_jc_params *jc = &pdk_model_opts_get(s.m)->jc;
      const double bound =
          ep > 0.0 ? pdk_jc_flow_stress(jc, ep, 1.0, 0.0) / (0.9 * jc->young_modulus * ep) : 1.0;
      T_ASSERT(ep > 0.0 ? f <= fmax(fmin(bound, 1.0), floor) : f == 1.0,
               "particle %d: factor %g at eps_p %g (at most %g)", (int)i, f, ep, bound);
      softened += f < 1.0;
      f_min = f_min < f ? f_min : f;
      w_stab += vol[i] * field(&s, "w_stab", i);
    }
    free(f_prev);
    worst_rel[k] = worst / h.external_work;
    if (verbose)
      printf("softened, dt %g: W_ext %g = K %g + S %g + P %g (of which w_stab %g); imbalance "
             "(worst) %.3e of W_ext; %d softened particles, smallest factor %g\n",
             dt, h.external_work, h.kinetic, h.strain, h.plastic_work, w_stab, worst_rel[k],
             softened, f_min);
    T_ASSERT(softened > n / 4, "only %d of %d particles softened", softened, (int)n);
    T_ASSERT(w_stab > 10.0 * 1e-4 * h.external_work,
             "w_stab %g is too small for the balance to notice it (external work %g)", w_stab,
             h.external_work);
    T_NEAR(worst, 0.0, 0.0, 1e-4 * h.external_work, "energy balance with softening, dt %g", dt);
    jcu_sim_destroy(&s);
  }
  T_ASSERT(worst_rel[1] * 3.0 <= worst_rel[0], "softening: not second order in dt (%.3e, %.3e)",
           worst_rel[0], worst_rel[1]);
}

/* ---- 4. family average, its use, and threads --------------------------------------------------
 */

/* The damage run to step `steps`, then one more step for particle check. */
static void family(pdk_ctx *ctx1, pdk_ctx *ctx2, int verbose) {
  sim s[3]; /* TL on 1 thread, TL on 2, semi-TL on 2 */
  const long steps = 600; /* 60 us at 10 m/s: damage grows at the notch, particles fail */
  for (int k = 0; k < 3; ++k) {
    pdk_ctx *ctx = k ? ctx2 : ctx1;
    build(ctx, 1, 1, 1, PDK_STENCIL_OFF, k == 2 ? PDK_CONNECTIVITY_SEMI_TL : PDK_CONNECTIVITY_TL,
          10.0, 1e-7, &s[k]);
    pdk_history h;
    T_OK(ctx, pdk_explicit_run(s[k].e, steps, &h));
    if (verbose)
      printf("family, run %d: after %ld steps %d failed, %lld bonds broken, %ld compactions\n", k,
             steps, (int)pdk_model_num_failed(s[k].m), (long long)pdk_model_num_broken(s[k].m),
             pdk_model_num_compactions(s[k].m));
    T_ASSERT(pdk_model_num_failed(s[k].m) > 0, "no particle failed in %ld steps", steps);
  }
  T_ASSERT(pdk_model_num_compactions(s[2].m) > 0, "semi-TL never compacted its bond list");
  jcu_snapshot snap = jcu_snapshot_take(s[0].m);
  T_ASSERT(jcu_snapshot_equal(s[1].m, &snap), "1 and 2 threads differ (histories, factors, "
                                              "averages or bond state)");
  /* no particle is detached here, so semi-TL walks the same sums in the same order (over its
   * compacted list) and must give TL's bits, the averages included */
  T_ASSERT(jcu_snapshot_equal(s[2].m, &snap), "semi-TL differs from TL");
  free(snap.data);
  jcu_sim_destroy(&s[2]);

  /* the average, evaluated here */
  sim *t = &s[0];
  const pdk_index n = pdk_particles_count(t->p);
  const pdk_bond_index *start = pdk_families_bond_start(t->fam);
  const pdk_index *bj = pdk_families_bond_j(t->fam);
  const uint8_t *alive = pdk_model_bond_alive(t->m);
  const uint8_t *failed = pdk_particles_field_data(t->p, "failed", 0);
  const double *sm = pdk_particles_field_data(t->p, "sigma_m", 0);
  const double *avg = pdk_particles_field_data(t->p, "sigma_m_avg", 0);
  const double *vol = pdk_particles_volume(t->p);
  double smax = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    smax = fmax(smax, fabs(sm[i]));
  T_ASSERT(smax > 1e8, "mean stresses up to %g Pa only; the bar should be loaded", smax);
  for (pdk_index i = 0; i < n; ++i) {
    double sw = vol[i], sp = vol[i] * sm[i]; /* omega = 1 (constant influence) */
    for (pdk_bond_index b = start[i]; b < start[i + 1]; ++b)
      if (alive[b] && !failed[bj[b]]) {
        sw += vol[bj[b]];
        sp += vol[bj[b]] * sm[bj[b]];
      }
    T_NEAR(avg[i], sp / sw, 0.0, 1e-13 * smax, "sigma_m_avg of particle %d", (int)i);
  }

  /* one more step: the plastic particle with the largest damage below D_c */
  pdk_index q = -1;
  const double *D = pdk_particles_field_data(t->p, "damage", 0);
  const double D_c = pdk_model_opts_get(t->m)->jc.D_c;
  for (pdk_index i = 0; i < n; ++i)
    if (!failed[i] && D[i] < 0.8 * D_c && field(t, "eps_p_rate", i) > 0.0 && (q < 0 || D[i] > D[q]))
      q = i;
  int flowing = 0;
  for (pdk_index i = 0; i < n; ++i)
    flowing += field(t, "eps_p_rate", i) > 0.0;
  T_ASSERT(q >= 0, "no flowing particle to follow (%d flowing)", flowing);
  pdk_jc_state in;
  for (int c = 0; c < 6; ++c)
    in.cp_inv[c] = ((const double *)pdk_particles_field_data(t->p, "cp_inv", c))[q];
  in.eps_p = field(t, "eps_p", q);
  in.damage = D[q];
  in.temp_rise = 0.0;
  in.failed = 0;
  const double avg_q = avg[q];
  pdk_history h;
  T_OK(ctx1, pdk_explicit_run(t->e, 1, &h));
  double F[3][3] = {{0}};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      F[r][c] = ((const double *)pdk_particles_field_data(t->p, "F", r * 2 + c))[q];
  const pdk_jc_params *jc = &pdk_model_opts_get(t->m)->jc;
  pdk_jc_state out, out_local;
  double P[3][3];
  pdk_jc_result res;
  T_ASSERT(pdk_jc_update_avg(jc, 2, F, pdk_model_get_dt(t->m), avg_q, &in, &out, P, &res) == 0,
           "update_avg");
  T_ASSERT(pdk_jc_update(jc, 2, F, pdk_model_get_dt(t->m), &in, &out_local, P, NULL) == 0,
           "update");
  if (verbose)
    printf("particle %d: D %.6g -> %.6g (model %.6g, local pressure %.6g), sigma_m %g, average "
           "%g\n",
           (int)q, in.damage, out.damage, D[q], out_local.damage, res.sigma_m_eff, avg_q);
  T_ASSERT(out.damage > in.damage, "particle %d did not flow in the step", (int)q);
  T_ASSERT(D[q] == out.damage,
           "particle %d: the model's damage %.17g is not the averaged "
           "update's %.17g",
           (int)q, D[q], out.damage);
  T_ASSERT(out_local.damage != out.damage, "particle %d: the local update gives the same damage",
           (int)q);
  jcu_sim_destroy(&s[0]);
  jcu_sim_destroy(&s[1]);
}

/* ---- 5. kernel variants -----------------------------------------------------------------------
 */

static void build_variant(pdk_ctx *ctx, pdk_stencil_mode stencil, sim *s) {
  build(ctx, 1, 1, 1, stencil, PDK_CONNECTIVITY_TL, 10.0, 1e-7, s);
}

static void variants(int verbose) {
  double ep_max;
  pdk_bond_index broken;
  jcu_kernel_variants(build_variant, 300, verbose, &ep_max, &broken);
  T_ASSERT(ep_max > 0.01, "the run hardly flowed (eps_p up to %g)", ep_max);
}

int main(void) {
  const int verbose = getenv("PDK_TEST_VERBOSE") != NULL;
  point();
  pdk_ctx *ctx1 = t_ctx(1), *ctx2 = t_ctx(2);
  elastic(ctx2);
  plastic(ctx2, verbose);
  family(ctx1, ctx2, verbose);
  variants(verbose);
  pdk_ctx_destroy(&ctx1);
  pdk_ctx_destroy(&ctx2);
  return 0;
}
