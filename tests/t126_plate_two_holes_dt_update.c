/* The plate with two holes at 1 mm (scenes/plate_two_holes.yaml, TL, the shipped formulation) with
 * model.break_stress continuous and model.critical_stretch 1, where the stable time step falls
 * during the tearing: a particle whose family has lost most of its bonds keeps its stress (the
 * remap) and its stabilization stiffness grows as its family shrinks, so the step chosen at the
 * start exceeds the stable one from about 2.1 ms on. Without solver.dt_update the run ends with
 * its energy account 11.2 J off of 112 J (a burst of kinetic energy at 2.6-2.9 ms; measured,
 * docs/validation/plate_two_holes.md item 10), and its dissipation then exceeds the work put in.
 *
 * With solver.dt_update breaks (the default interval, 100 steps), run to 300 us after separation:
 *   - dt was lowered at least once (the estimate falls to about 0.65 of the initial one);
 *   - the account external = kinetic + strain + plastic + damage + breaking holds to 2% of the
 *     external work at every chunk (measured 0.63 J of 112.6 J; without the update 11.2 J, so the
 *     check fails without it), and the breaking work is never negative;
 *   - the plate separates into two pieces holding the bottom and the top sets, with no force
 *     across the crack (below 1e-9 of the peak) and a final mean force below 10% of the peak;
 *   - plastic + damage + breaking work stay below the external work.
 * Run time: about 20 s on 2 cores.
 * labels: physics */
#include "plate_two_holes_util.h"

#define AFTER 300e-6 /* s run after separation */
#define MAX_TIME 4e-3

int main(void) {
  char scene[2048];
  ph_scene_path("plate_two_holes.yaml", scene, sizeof scene);
  pdk_ctx *ctx = t_ctx(0);
  const char *ov[] = {"geometry.spacing=1e-3",      "model.connectivity=tl",
                      "output.fields=[u]",          "model.break_stress=continuous",
                      "model.critical_stretch=1.0", "solver.dt_update=breaks"};
  ph_result r;
  ph_run(ctx, scene, ov, (int)(sizeof ov / sizeof ov[0]), "dt_update", AFTER, MAX_TIME, 50, &r);
  if (getenv("PDK_TEST_VERBOSE")) ph_print("dt_update", &r);
  const double W = r.external_work;
  T_ASSERT(r.num_dt_changes >= 1 && r.dt_final < r.dt,
           "the step was never lowered (%d estimates, dt %g, final %g)", r.num_estimates, r.dt,
           r.dt_final);
  T_NEAR(r.worst_imbalance, 0.0, 0.0, 0.02 * W, "energy account (external work %g J)", W);
  T_ASSERT(r.min_breaking >= 0.0, "breaking work %g J < 0", r.min_breaking);
  T_ASSERT(r.t_sep > 0, "the plate did not separate by t = %g s (%d failed)", MAX_TIME,
           (int)r.failed);
  T_ASSERT(r.pieces_ok,
           "%d pieces with more than 1%% of the particles (want 2, holding the "
           "bottom and the top sets)",
           r.num_pieces);
  T_NEAR(r.crack_force, 0.0, 0.0, 1e-9 * r.peak, "force across the crack");
  T_ASSERT(r.t_peak < r.t_sep && r.final_force < 0.1 * r.peak,
           "peak at %g s, separation at %g s, final |mean force| %g N of %g N", r.t_peak, r.t_sep,
           r.final_force, r.peak);
  T_ASSERT(r.plastic_work + r.damage_work + r.breaking_work < W,
           "dissipation plastic %g + damage %g + breaking %g J exceeds the external work %g J",
           r.plastic_work, r.damage_work, r.breaking_work, W);
  pdk_ctx_destroy(&ctx);
  return 0;
}
