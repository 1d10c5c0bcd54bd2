/* A run whose energy account runs away stops within a few steps, naming the step, the time, the
 * particle whose acceleration grew most (index, id, position) and the keys to change; the output
 * is not completed (pdk_sim_run: PDK_RUN_FAILED at PDK_RUN_STAGE_STEP, no <name>.h5 left).
 *
 * Body: scenes/block_3d.yaml at 4 mm spacing (10^3 particles, PMB, elastic, a breathing initial
 * velocity: energy in play from the start).
 * 1. The default step (0.8 of the estimate) runs its 400 steps: PDK_RUN_DONE.
 * 2. solver.dt = 3 x the estimated stable step (force_dt): the top mode grows by ~34 per step
 *    (velocity Verlet, omega dt = 6), so the energy created passes the energy put in before the
 *    first check (step 8; measured: step 8): the run must stop by step 16 (one check of margin).
 * 3. solver.dt = 1.1 x the estimate (force_dt): the breathing start excites the top modes, which
 *    grow by about 2 per step; measured stop at step 8 (over twice the energy put in), asserted
 *    by step 200 of the 400.
 * Both stops here take the check's "over twice the energy put in" path; its slower path (30% of
 * the energy in play, growing over 4 checks) is not reached by these runs. The check only reads
 * the state, so a stable run's bits are unchanged (scenes/plate_two_holes.yaml at 1 mm: history,
 * fields CSV and XDMF byte-identical to the build before the check).
 * The files go to $PDK_BUILD_DIR/tests/t260_explicit_runaway.work.
 * labels: unit */
#include <unistd.h>

#include "test_util.h"

static double run_case(pdk_ctx *ctx, const char *dt_over, pdk_run_report *rep, int *err) {
  char path[4096];
  snprintf(path, sizeof path, "%s/scenes/block_3d.yaml", getenv("PDK_SOURCE_DIR"));
  const char *ov[6] = {"geometry.spacing=4e-3", "geometry.box.hi=[0.04,0.04,0.04]",
                       "solver.steps=400", "output.field_interval=100", NULL, NULL};
  int nov = 4;
  if (dt_over) {
    ov[nov++] = dt_over;
    ov[nov++] = "solver.force_dt=true";
  }
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, nov, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  const double dts = pdk_explicit_stable_dt(pdk_sim_explicit(sim));
  pdk_run_opts ro = pdk_run_opts_default();
  ro.dir = "out";
  ro.plot = 0;
  *err = pdk_sim_run(sim, scene, &ro, rep);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  return dts;
}

static void check_stopped(pdk_ctx *ctx, const char *what, int err, const pdk_run_report *rep,
                          long max_step) {
  const char *msg = pdk_ctx_error_message(ctx);
  if (getenv("PDK_TEST_VERBOSE")) printf("%s: err %d, step %ld: %s\n", what, err, rep->step, msg);
  T_ASSERT(err == PDK_ERR_NUMERIC && rep->status == PDK_RUN_FAILED &&
               rep->stage == PDK_RUN_STAGE_STEP,
           "%s: err %d, status %d, stage %d (%s)", what, err, (int)rep->status, (int)rep->stage,
           msg);
  T_ASSERT(rep->step <= max_step, "%s: stopped at step %ld, later than %ld", what, rep->step,
           max_step);
  char at[64];
  snprintf(at, sizeof at, "at step %ld (time ", rep->step);
  T_ASSERT(strstr(msg, "energy account runs away") && strstr(msg, at) &&
               strstr(msg, "particle ") && strstr(msg, "(id ") && strstr(msg, ") at (") &&
               strstr(msg, "solver.safety") && strstr(msg, "smaller solver.dt") &&
               strstr(msg, "solver.dt_update"),
           "%s: the message does not name the step, the particle, its position and the keys: %s",
           what, msg);
  T_ASSERT(access("out/block_3d.h5", F_OK) != 0 && access("out/block_3d_history.csv", F_OK) != 0,
           "%s: a failed run left output files that look complete", what);
}

int main(void) {
  const char *build_dir = getenv("PDK_BUILD_DIR");
  T_ASSERT(build_dir && getenv("PDK_SOURCE_DIR"), "PDK_BUILD_DIR and PDK_SOURCE_DIR are not set");
  char work[4096], cmd[2 * 4096 + 64];
  snprintf(work, sizeof work, "%s/tests/t260_explicit_runaway.work", build_dir);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "%s", cmd);
  T_ASSERT(chdir(work) == 0, "cd %s", work);
  pdk_ctx *ctx = t_ctx(2);
  pdk_run_report rep;
  int err = 0;

  const double dts = run_case(ctx, NULL, &rep, &err);
  T_ASSERT(!err && rep.status == PDK_RUN_DONE && rep.step == 400,
           "stable run: err %d, status %d, step %ld (%s)", err, (int)rep.status, rep.step,
           pdk_ctx_error_message(ctx));
  T_ASSERT(system("rm -rf out") == 0, "rm out");

  char over[128];
  snprintf(over, sizeof over, "solver.dt=%.17g", 3.0 * dts);
  run_case(ctx, over, &rep, &err);
  check_stopped(ctx, "dt 3x", err, &rep, 16);

  snprintf(over, sizeof over, "solver.dt=%.17g", 1.1 * dts);
  run_case(ctx, over, &rep, &err);
  check_stopped(ctx, "dt 1.1x", err, &rep, 200);

  pdk_ctx_destroy(&ctx);
  return 0;
}
