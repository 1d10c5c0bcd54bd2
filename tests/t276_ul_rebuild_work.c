/* UL family rebuilds: the energy each removes is booked (pdk_history.rebuild_work), so the
 * account closes across them.
 *
 * tests/scenes/t261_taylor_proxy.yaml (a Johnson-Cook copper rod, 720 particles, correspondence
 * with Silling 0.1, at 227 m/s onto a rigid plane) with model.connectivity ul, solver.safety 0.3,
 * to 10 us. A rebuild restarts the Silling term's non-affine motion at 0 and re-weighs the bonds,
 * so the strain energy jumps down at each; the model books the jump (the committing pass's energy
 * less a trial pass's over the new families at the same positions).
 * Measured (to 20 us): 12 rebuilds removed 1.68 J, 17% of the energy put in, and the account
 * with them is 1.2% off (without them 18%; with ul_skin 0, no rebuild, 2.3%: UL's force is not
 * the gradient of an energy, so some drift remains at any step).
 * Asserts, to 10 us: at least one rebuild; the booked energy is more than 3% of the energy put in
 * (the booking carries the loss); the account with it within 2% (measured below), and without it
 * further off than with it.
 * The files go to $PDK_BUILD_DIR/tests/t276_ul_rebuild_work.work.
 * labels: physics */
#include <unistd.h>

#include "test_util.h"

int main(void) {
  const char *build_dir = getenv("PDK_BUILD_DIR");
  T_ASSERT(build_dir && getenv("PDK_SOURCE_DIR"), "PDK_BUILD_DIR and PDK_SOURCE_DIR are not set");
  char work[4096], cmd[2 * 4096 + 64], path[4096];
  snprintf(work, sizeof work, "%s/tests/t276_ul_rebuild_work.work", build_dir);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "%s", cmd);
  T_ASSERT(chdir(work) == 0, "cd %s", work);
  snprintf(path, sizeof path, "%s/tests/scenes/t261_taylor_proxy.yaml", getenv("PDK_SOURCE_DIR"));
  pdk_ctx *ctx = t_ctx(2);
  const char *ov[3] = {"model.connectivity=ul", "solver.safety=0.3", "solver.end_time=10.0e-6"};
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 3, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  pdk_run_opts ro = pdk_run_opts_default();
  ro.dir = "out";
  ro.plot = 0;
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(sim, scene, &ro, &rep));
  const long rebuilds = pdk_model_num_rebuilds(pdk_sim_model(sim));
  const pdk_history *a = &rep.first, *b = &rep.last;
  const double d0 = a->plastic_work + a->damage_work + a->breaking_work;
  const double d1 = b->plastic_work + b->damage_work + b->breaking_work;
  const double e0 = a->kinetic + a->strain + d0, e1 = b->kinetic + b->strain + d1;
  const double ext = b->external_work - a->external_work, in = ext + fabs(e0);
  const double booked = b->rebuild_work - a->rebuild_work;
  const double off_with = fabs(ext - (e1 + b->rebuild_work - e0 - a->rebuild_work)) / in;
  const double off_without = fabs(ext - (e1 - e0)) / in;
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%ld rebuilds, booked %g (%.3g%%), off %.3g%% with, %.3g%% without\n", rebuilds,
           booked, 100.0 * booked / in, 100.0 * off_with, 100.0 * off_without);
  T_ASSERT(rebuilds >= 1, "no rebuild");
  T_ASSERT(booked > 0.03 * in, "the rebuilds booked %g, %.3g%% of the energy put in", booked,
           100.0 * booked / in);
  T_ASSERT(off_with < 0.02 && off_with < off_without,
           "the account with the rebuilds is %.3g%% off (without them %.3g%%)", 100.0 * off_with,
           100.0 * off_without);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  pdk_ctx_destroy(&ctx);
  return 0;
}
