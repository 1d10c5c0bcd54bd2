/* The state-following explicit step (solver.dt_update auto): a run whose bonds never shorten by 10% keeps
 * its first estimate and is the run of dt_update none bit for bit; a run that crushes bonds is
 * re-estimated mid-run and its step lowered.
 *
 * 1. tests/scenes/t092_bar.yaml (PMB bar pulled at one end, 400 steps: stretches of 0.2%, no
 *    bond shortens by 10%): with the default and with dt_update none, the same last history
 *    record to the bit (kinetic and strain energy, external work, time), one estimate only, no
 *    dt change: the per-step check reads the state and changes nothing.
 * It is not the default: on the shipped two-hole plate (JC failure, breaking) it re-estimated
 * after the fracture and changed the run (tests/t120's dissipation check then failed).
 * 2. tests/scenes/t261_taylor_proxy.yaml to 3 us (a copper rod at 227 m/s onto a plane; the
 *    first layers are crushed by 8% of a spacing per step): auto re-estimates (measured:
 *    at step 8, 1.745e-7 -> 1.608e-7 s, then at step 18, 1.516e-7) and lowers dt below 0.8 x the
 *    first estimate x 0.95 (safety x a 5% fall: the measured fall is 13% by 2.4 us), where dt
 *    none keeps 0.8 x the first estimate throughout.
 * The files go to $PDK_BUILD_DIR/tests/t275_explicit_dt_auto.work.
 * labels: physics */
#include <unistd.h>

#include "test_util.h"

typedef struct result {
  int err;
  pdk_run_report rep;
  double dt0, dt1; /* the first estimate and the last step */
  int num_estimates, num_changes;
} result;

static result run_case(pdk_ctx *ctx, const char *scene_file, const char *const *ov, int nov) {
  char path[4096];
  snprintf(path, sizeof path, "%s/tests/scenes/%s", getenv("PDK_SOURCE_DIR"), scene_file);
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  result r;
  memset(&r, 0, sizeof r);
  T_OK(ctx, pdk_scene_load(ctx, path, ov, nov, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  r.dt0 = pdk_explicit_stable_dt(pdk_sim_explicit(sim));
  pdk_run_opts ro = pdk_run_opts_default();
  ro.dir = "out";
  ro.plot = 0;
  r.err = pdk_sim_run(sim, scene, &ro, &r.rep);
  const pdk_explicit *e = pdk_sim_explicit(sim);
  r.dt1 = pdk_explicit_dt(e);
  r.num_estimates = pdk_explicit_num_estimates(e);
  r.num_changes = pdk_explicit_num_dt_changes(e);
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%s: err %d step %ld, %d estimates, %d changes, first estimate %g, last dt %g\n",
           scene_file, r.err, r.rep.step, r.num_estimates, r.num_changes, r.dt0, r.dt1);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  return r;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

int main(void) {
  const char *build_dir = getenv("PDK_BUILD_DIR");
  T_ASSERT(build_dir && getenv("PDK_SOURCE_DIR"), "PDK_BUILD_DIR and PDK_SOURCE_DIR are not set");
  char work[4096], cmd[2 * 4096 + 64];
  snprintf(work, sizeof work, "%s/tests/t275_explicit_dt_auto.work", build_dir);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "%s", cmd);
  T_ASSERT(chdir(work) == 0, "cd %s", work);
  pdk_ctx *ctx = t_ctx(2);

  const char *none[1] = {"solver.dt_update=none"};
  const char *autom[1] = {"solver.dt_update=auto"};
  result a = run_case(ctx, "t092_bar.yaml", autom, 1);
  result b = run_case(ctx, "t092_bar.yaml", none, 1);
  T_ASSERT(!a.err && !b.err, "bar: err %d / %d", a.err, b.err);
  T_ASSERT(a.num_estimates == 1 && a.num_changes == 0 && same_bits(a.dt1, b.dt1),
           "bar (auto): %d estimates, %d changes, dt %g vs %g", a.num_estimates, a.num_changes,
           a.dt1, b.dt1);
  const pdk_history *ha = &a.rep.last, *hb = &b.rep.last;
  T_ASSERT(ha->step == hb->step && same_bits(ha->time, hb->time) &&
               same_bits(ha->kinetic, hb->kinetic) && same_bits(ha->strain, hb->strain) &&
               same_bits(ha->external_work, hb->external_work),
           "bar: auto and none differ: step %ld/%ld, kinetic %.17g/%.17g, strain %.17g/%.17g, "
           "work %.17g/%.17g",
           ha->step, hb->step, ha->kinetic, hb->kinetic, ha->strain, hb->strain,
           ha->external_work, hb->external_work);

  const char *short_auto[2] = {"solver.end_time=3.0e-6", "solver.dt_update=auto"};
  const char *short_none[2] = {"solver.end_time=3.0e-6", "solver.dt_update=none"};
  a = run_case(ctx, "t261_taylor_proxy.yaml", short_auto, 2);
  b = run_case(ctx, "t261_taylor_proxy.yaml", short_none, 2);
  T_ASSERT(!a.err && !b.err, "proxy: err %d / %d (%s)", a.err, b.err, pdk_ctx_error_message(ctx));
  T_ASSERT(a.num_estimates >= 2 && a.num_changes >= 1 && a.dt1 < 0.95 * 0.8 * a.dt0,
           "proxy (auto): %d estimates, %d changes, dt %g against the first estimate %g",
           a.num_estimates, a.num_changes, a.dt1, a.dt0);
  T_ASSERT(b.num_estimates == 1 && same_bits(b.dt1, 0.8 * b.dt0),
           "proxy (none): %d estimates, dt %g against 0.8 x %g", b.num_estimates, b.dt1, b.dt0);

  pdk_ctx_destroy(&ctx);
  return 0;
}
