/* Re-estimating the stable step during a run (pdk_explicit_opts dt_update, scene solver.dt_update).
 *
 * 1. Estimates leave the trajectory alone. The t092 bar (2-D PMB, pulled, bonds break) for 400
 *    steps at 0.8 x the stable step, with an estimate every 10 steps (periodic) against none:
 *    positions, velocities, forces and the bond state are bitwise the same (an estimate moves x
 *    and overwrites f and restores both), 41 estimates were made and none lowered dt (breaking
 *    PMB bonds only softens the bar, so no estimate falls below the step).
 * 2. breaks: the same bar with dt_update breaks, interval 20: no estimate before the first bond
 *    breaks, at least one after, never more than one per 20 steps.
 * 3. Lowering. tests/scenes/t052_bar_dt.yaml runs to t = 2e-4 at 4.3e-6 (just under the stable
 *    4.32e-6) with safety 0.5 and an estimate every 10 steps: the first one lowers dt to exactly
 *    0.5 x the estimate at step 10, time 10 x 4.3e-6 (to round-off of the sum); no later estimate
 *    lowers it again (they agree to 0.1%); pdk_sim_num_steps grows from ceil(T / 4.3e-6) = 47 to
 *    10 + ceil((T - t10) / dt); the run ends at the first step at or after T (T <= t < T + dt).
 *    It is bitwise the same on 1 and 2 threads. A checkpoint written at step 25 (after the
 *    change), restored into a fresh simulation built from the same scene, continues to the end
 *    bitwise as the uninterrupted run, with the same dt, the same counts and the same
 *    step count (the dt_update state is checkpointed).
 * 4. Estimates leave the history alone. t106's notched Johnson-Cook bar (damage, softened
 *    stabilization, family triaxiality, break_stress continuous; dt 1e-7 s, about a quarter of
 *    the stable step, safety 1) for 800 steps with an estimate every 10 steps against none: every
 *    history field, the bond state, x, v and f bitwise equal after every 10 steps (measured: 81
 *    estimates, 620 bonds broken, no change of dt). t134's updated-Lagrangian block (16 x 16,
 *    rebuilds during the run), 300 steps: the same, with the same rebuild count.
 * 5. A free PMB square blown apart (every bond breaks): the estimates after that find nothing
 *    that limits the step and keep the last one; the run goes on (21 estimates in 200 steps,
 *    dt unchanged) instead of stopping with "no stiffness".
 * labels: unit threads */
#include <stdio.h>

#include "corr_util.h"
#include "jc_corr_util.h"
#include "pdk/output.h"
#include "pdk/scene.h"

typedef struct run {
  pdk_scene *scene;
  pdk_sim *sim;
} run;

static run open_run(pdk_ctx *ctx, const char *name, const char *const *ov, int num_ov) {
  const char *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(src, "PDK_SOURCE_DIR is not set (run through ctest)");
  char path[1024];
  snprintf(path, sizeof path, "%s/tests/scenes/%s", src, name);
  run r = {NULL, NULL};
  T_OK(ctx, pdk_scene_load(ctx, path, ov, num_ov, &r.scene));
  T_OK(ctx, pdk_sim_create(ctx, r.scene, &r.sim));
  return r;
}

static void close_run(run *r) {
  pdk_sim_destroy(&r->sim);
  pdk_scene_destroy(&r->scene);
}

static pdk_explicit *ex(run *r) { return pdk_sim_explicit(r->sim); }

/* 1 when field `name` (f64, dim components) of both stores is bitwise equal */
static int same_particles(pdk_particles *a, pdk_particles *b, const char *name) {
  for (int c = 0; c < pdk_particles_dim(a); ++c)
    if (memcmp(pdk_particles_field_data(a, name, c), pdk_particles_field_data(b, name, c),
               (size_t)pdk_particles_count(a) * sizeof(double)))
      return 0;
  return 1;
}

static int same_field(run *a, run *b, const char *name) {
  return same_particles(pdk_sim_particles(a->sim), pdk_sim_particles(b->sim), name);
}

static int same_state(run *a, run *b) {
  const pdk_model *ma = pdk_sim_model(a->sim), *mb = pdk_sim_model(b->sim);
  const size_t nb = (size_t)pdk_families_num_bonds(pdk_sim_families(a->sim));
  return same_field(a, b, "x") && same_field(a, b, "v") && same_field(a, b, "f") &&
         pdk_model_num_broken(ma) == pdk_model_num_broken(mb) &&
         !memcmp(pdk_model_bond_alive(ma), pdk_model_bond_alive(mb), nb) &&
         pdk_explicit_time(ex(a)) == pdk_explicit_time(ex(b));
}

static void estimates_leave_trajectory(pdk_ctx *ctx) {
  static const char *const ov[] = {"solver.dt_update=periodic", "solver.dt_update_interval=10"};
  run a = open_run(ctx, "t092_bar.yaml", NULL, 0), b = open_run(ctx, "t092_bar.yaml", ov, 2);
  T_ASSERT(pdk_explicit_dt(ex(&a)) == pdk_explicit_dt(ex(&b)), "same initial step");
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(ex(&a), 400, &h));
  T_OK(ctx, pdk_explicit_run(ex(&b), 400, &h));
  T_ASSERT(pdk_model_num_broken(pdk_sim_model(a.sim)) > 0, "precondition: bonds broke");
  T_ASSERT(same_state(&a, &b), "periodic estimates changed the trajectory");
  T_ASSERT(pdk_explicit_num_estimates(ex(&b)) == 41, "estimates: %d, expected 41",
           pdk_explicit_num_estimates(ex(&b)));
  T_ASSERT(pdk_explicit_num_dt_changes(ex(&b)) == 0 &&
               pdk_explicit_dt(ex(&b)) == pdk_explicit_dt(ex(&a)),
           "an estimate lowered dt on a bar that only softens");
  T_ASSERT(pdk_explicit_num_estimates(ex(&a)) == 1, "none: one estimate (at creation)");
  close_run(&a);
  close_run(&b);
}

static void breaks_mode(pdk_ctx *ctx) {
  static const char *const ov[] = {"solver.dt_update=breaks", "solver.dt_update_interval=20"};
  run r = open_run(ctx, "t092_bar.yaml", ov, 2);
  pdk_explicit *e = ex(&r);
  pdk_model *m = pdk_sim_model(r.sim);
  long first_break = -1;
  int last = 1;
  for (long s = 0; s < 400; s += 5) {
    T_OK(ctx, pdk_explicit_run(e, 5, NULL));
    const long step = pdk_explicit_step(e);
    const int k = pdk_explicit_num_estimates(e);
    if (first_break < 0) {
      if (pdk_model_num_broken(m) > 0)
        first_break = step;
      else
        T_ASSERT(k == 1, "step %ld: an estimate before any bond broke", step);
    }
    T_ASSERT(k - last <= 1, "step %ld: two estimates within 5 steps (interval 20)", step);
    T_ASSERT(k - 1 <= step / 20, "step %ld: %d estimates, more than one per 20 steps", step, k);
    last = k;
  }
  T_ASSERT(first_break > 0, "precondition: bonds broke");
  T_ASSERT(pdk_explicit_num_estimates(e) >= 2, "no estimate after bonds broke (first at %ld)",
           first_break);
  close_run(&r);
}

/* Runs r to its (growing) step count in chunks of 7 steps, or to stop_at when > 0. */
static void run_to_end(pdk_ctx *ctx, run *r, long stop_at) {
  for (;;) {
    const long s = pdk_explicit_step(ex(r)),
               total = stop_at > 0 ? stop_at : pdk_sim_num_steps(r->sim);
    if (s >= total) break;
    T_OK(ctx, pdk_explicit_run(ex(r), total - s < 7 ? total - s : 7, NULL));
  }
}

static void lowering(pdk_ctx *ctx1, pdk_ctx *ctx2) {
  const double T = 2e-4, dt0 = 4.3e-6;
  run a = open_run(ctx1, "t052_bar_dt.yaml", NULL, 0);
  pdk_explicit *e = ex(&a);
  T_ASSERT(pdk_explicit_dt(e) == dt0 && pdk_sim_num_steps(a.sim) == 47, "planned: dt %g, %ld steps",
           pdk_explicit_dt(e), pdk_sim_num_steps(a.sim));
  T_ASSERT(dt0 < pdk_explicit_stable_dt(e) && dt0 > 0.9 * pdk_explicit_stable_dt(e),
           "precondition: dt just under the stable %g", pdk_explicit_stable_dt(e));
  run_to_end(ctx1, &a, 0);
  long s0;
  double t0;
  pdk_explicit_dt_start(e, &s0, &t0);
  const double dt = pdk_explicit_dt(e), est = pdk_explicit_stable_dt(e);
  T_ASSERT(pdk_explicit_num_dt_changes(e) == 1 && s0 == 10, "changes %d, at step %ld",
           pdk_explicit_num_dt_changes(e), s0);
  T_NEAR(t0, 10 * dt0, 1e-14, 0.0, "time of the change");
  T_NEAR(dt, 0.5 * est, 1e-3, 0.0, "dt after the change, against 0.5 x the latest estimate");
  T_ASSERT(dt < 0.5001 * dt0 / 0.99 && dt > 0.45 * dt0, "dt %g after the change", dt);
  const long total = pdk_sim_num_steps(a.sim);
  T_ASSERT(total == 10 + (long)ceil((T - t0) / dt * (1 - 1e-12)) && total > 47,
           "step count %ld after the change", total);
  const double t_end = pdk_explicit_time(e);
  T_ASSERT(pdk_explicit_step(e) == total && t_end >= T * (1 - 1e-12) && t_end < T + dt,
           "ended at step %ld, t %.17g (T %g, dt %g)", pdk_explicit_step(e), t_end, T, dt);
  T_ASSERT(pdk_explicit_num_estimates(e) == 1 + (int)(total / 10), "estimates %d for %ld steps",
           pdk_explicit_num_estimates(e), total);

  /* 2 threads */
  run b = open_run(ctx2, "t052_bar_dt.yaml", NULL, 0);
  run_to_end(ctx2, &b, 0);
  T_ASSERT(same_state(&a, &b) && pdk_explicit_dt(ex(&b)) == dt, "1 and 2 threads differ");
  close_run(&b);

  /* checkpoint after the change, restore into a fresh simulation, continue */
  const char *ckpt = "t052_dt_update_checkpoint.h5";
  run c = open_run(ctx1, "t052_bar_dt.yaml", NULL, 0);
  run_to_end(ctx1, &c, 25);
  T_ASSERT(pdk_explicit_num_dt_changes(ex(&c)) == 1, "precondition: dt changed before step 25");
  T_OK(ctx1, pdk_checkpoint_write(ctx1, ckpt, ex(&c), NULL));
  close_run(&c);
  run d = open_run(ctx1, "t052_bar_dt.yaml", NULL, 0);
  T_ASSERT(pdk_sim_num_steps(d.sim) == 47, "fresh simulation plans 47 steps");
  T_OK(ctx1, pdk_checkpoint_read(ctx1, ckpt, ex(&d)));
  T_ASSERT(pdk_sim_num_steps(d.sim) == total, "restored step count %ld, expected %ld",
           pdk_sim_num_steps(d.sim), total);
  run_to_end(ctx1, &d, 0);
  long s0d;
  double t0d;
  pdk_explicit_dt_start(ex(&d), &s0d, &t0d);
  T_ASSERT(same_state(&a, &d), "the restored run differs from the uninterrupted one");
  T_ASSERT(pdk_explicit_dt(ex(&d)) == dt && s0d == s0 && t0d == t0 &&
               pdk_explicit_num_estimates(ex(&d)) == pdk_explicit_num_estimates(e) &&
               pdk_explicit_num_dt_changes(ex(&d)) == 1 && pdk_explicit_stable_dt(ex(&d)) == est,
           "restored dt_update state differs");
  remove(ckpt);
  close_run(&d);
  close_run(&a);
}

/* ---- 4. estimates and the history of correspondence models ---------------------------------- */

/* The notched Johnson-Cook bar of t106 (damage, softened stabilization, family triaxiality,
 * break_stress continuous), pulled by u = v t, dt 1e-7 s; `update` adds periodic estimates every
 * 10 steps at safety 1 (dt is about half the stable step, so they do not lower it). */
static void jc_bar(pdk_ctx *ctx, int update, jcu_sim *s) {
  jcu_bar(ctx, 1, &s->p, &s->fam);
  pdk_model_opts mo = jcu_tearing_opts(PDK_BREAK_STRESS_CONTINUOUS);
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  jcu_bar_pull(s->bcs, 1, 10.0);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = s->bcs;
  eo.num_bcs = 2;
  eo.dt = 1e-7;
  eo.safety = 1.0;
  if (update) {
    eo.dt_update = PDK_DT_UPDATE_PERIODIC;
    eo.dt_update_interval = 10;
  }
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static void jc_history_untouched(pdk_ctx *ctx) {
  jcu_sim a, b;
  jc_bar(ctx, 0, &a);
  jc_bar(ctx, 1, &b);
  long compared = 0;
  for (long s = 0; s < 800; s += 10) {
    T_OK(ctx, pdk_explicit_run(a.e, 10, NULL));
    T_OK(ctx, pdk_explicit_run(b.e, 10, NULL));
    if (pdk_explicit_num_dt_changes(b.e)) break; /* from here on the runs step differently */
    jcu_snapshot h = jcu_snapshot_take(a.m);
    T_ASSERT(jcu_snapshot_equal(b.m, &h) && same_particles(a.p, b.p, "x") &&
                 same_particles(a.p, b.p, "v") && same_particles(a.p, b.p, "f"),
             "JC bar, step %ld: periodic estimates changed the run", s + 10);
    free(h.data);
    compared = s + 10;
  }
  T_ASSERT(pdk_model_num_broken(a.m) > 0 && compared >= 400,
           "precondition: bonds broke (%lld) within the %ld steps compared",
           (long long)pdk_model_num_broken(a.m), compared);
  T_ASSERT(pdk_explicit_num_estimates(b.e) >= 41, "JC bar: %d estimates",
           pdk_explicit_num_estimates(b.e));
  if (getenv("PDK_TEST_VERBOSE"))
    printf("JC bar: %ld steps compared, %lld bonds broken, %d estimates, %d changes, stable %g\n",
           compared, (long long)pdk_model_num_broken(a.m), pdk_explicit_num_estimates(b.e),
           pdk_explicit_num_dt_changes(b.e), pdk_explicit_stable_dt(b.e));
  jcu_sim_destroy(&a);
  jcu_sim_destroy(&b);
}

/* t134's updated-Lagrangian block (16 x 16, pulled biaxially, rebuilds on both halves): 300 steps
 * with periodic estimates every 10 steps against none, bitwise, with rebuilds in between. */
static void ul_block(pdk_ctx *ctx, int update, jcu_sim *s, pdk_bc bcs[4]) {
  s->m = cu_pulled_block(ctx, 16, PDK_CONNECTIVITY_UL, bcs, &s->p, &s->fam);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 4;
  eo.dt_update = update ? PDK_DT_UPDATE_PERIODIC : PDK_DT_UPDATE_NONE;
  eo.dt_update_interval = update ? 10 : 0;
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static void ul_untouched(pdk_ctx *ctx) {
  jcu_sim a, b;
  pdk_bc ba[4], bb[4];
  ul_block(ctx, 0, &a, ba);
  ul_block(ctx, 1, &b, bb);
  T_OK(ctx, pdk_explicit_run(a.e, 300, NULL));
  T_OK(ctx, pdk_explicit_run(b.e, 300, NULL));
  T_ASSERT(pdk_model_num_rebuilds(a.m) > 0, "precondition: the ul families were rebuilt");
  T_ASSERT(pdk_explicit_num_dt_changes(b.e) == 0 && pdk_explicit_num_estimates(b.e) == 31,
           "ul block: %d estimates, %d changes", pdk_explicit_num_estimates(b.e),
           pdk_explicit_num_dt_changes(b.e));
  T_ASSERT(same_particles(a.p, b.p, "x") && same_particles(a.p, b.p, "v") &&
               same_particles(a.p, b.p, "f") &&
               pdk_model_num_rebuilds(a.m) == pdk_model_num_rebuilds(b.m),
           "ul block: periodic estimates changed the run");
  jcu_sim_destroy(&a);
  jcu_sim_destroy(&b);
}

/* ---- 5. a body that loses every bond ----------------------------------------------------------
 */

/* A free 2-D PMB square blown apart by an initial expansion (velocity gradient 2000/s, critical
 * stretch 1e-4): every bond breaks within the run, and the estimates after that (nothing left
 * to limit the step) keep the last estimate instead of stopping the run. */
static void fragments(pdk_ctx *ctx) {
  static const char *text = "dimension: 2\n"
                            "geometry: {spacing: 1.0e-3, box: {lo: [0, 0], hi: [0.01, 0.01]}}\n"
                            "material: {density: 8000, bulk_modulus: 1.0e9}\n"
                            "model: {kind: pmb, critical_stretch: 1.0e-4}\n"
                            "initial_conditions: {velocity_gradient: [[2000, 0], [0, 2000]]}\n"
                            "solver: {steps: 200, dt_update: periodic, dt_update_interval: 10}\n";
  const char *path = "t052_fragments.yaml";
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing %s", path);
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  pdk_explicit *e = pdk_sim_explicit(sim);
  const double dt0 = pdk_explicit_dt(e), est0 = pdk_explicit_stable_dt(e);
  T_OK(ctx, pdk_explicit_run(e, 200, NULL));
  const pdk_bond_index nb = pdk_families_num_bonds(pdk_sim_families(sim));
  T_ASSERT(pdk_model_num_broken(pdk_sim_model(sim)) == nb,
           "precondition: all %lld bonds broke "
           "(%lld did)",
           (long long)nb, (long long)pdk_model_num_broken(pdk_sim_model(sim)));
  T_ASSERT(pdk_explicit_num_estimates(e) == 21 && pdk_explicit_dt(e) == dt0 &&
               isfinite(pdk_explicit_stable_dt(e)) && pdk_explicit_stable_dt(e) >= est0,
           "fragments: %d estimates, dt %g (from %g), latest estimate %g (from %g)",
           pdk_explicit_num_estimates(e), pdk_explicit_dt(e), dt0, pdk_explicit_stable_dt(e), est0);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  remove(path);
}

int main(void) {
  pdk_ctx *ctx1 = t_ctx(1), *ctx2 = t_ctx(2);
  estimates_leave_trajectory(ctx2);
  breaks_mode(ctx2);
  lowering(ctx1, ctx2);
  jc_history_untouched(ctx2);
  ul_untouched(ctx2);
  fragments(ctx2);
  pdk_ctx_destroy(&ctx1);
  pdk_ctx_destroy(&ctx2);
  return 0;
}
