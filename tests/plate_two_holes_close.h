/* Shared by t127 (0.5 mm, default suite) and t128 (0.25 mm, slow):
 * scenes/plate_two_holes_close.yaml (the two-hole plate with the holes 12.5 mm apart in x and y,
 * the formulation of docs/validation/plate_two_holes.md items 8-10 in the scene), TL, run until
 * just past the first failures in the band between the holes and in the outer ligaments, and
 * compared with the finite-element reference of the same geometry
 * (docs/validation/plate_two_holes_fe, CENTRES="18.75 43.75 31.25 56.25"; item 11): first D_c on
 * the lower hole's edge facing the band (inner ligament) at a grip displacement of 1.200 mm on 1
 * and 0.5 mm elements, in the outer ligaments at 1.360 and 1.350 mm; bottom force at 1.2 mm 40.06
 * kN on both meshes. The grip moves at 2 m/s from t = 0, so its displacement is 2 m/s x t. */
#ifndef PDK_PLATE_TWO_HOLES_CLOSE_H
#define PDK_PLATE_TWO_HOLES_CLOSE_H

#include "plate_two_holes_util.h"

#define PHC_SPEED 2.0         /* m/s, the scene's grip velocity */
#define PHC_FE_INNER 1.200e-3 /* m, first D_c in the band (both meshes) */
#define PHC_FE_OUTER 1.350e-3 /* m, first D_c in the outer ligaments (0.5 mm elements) */
#define PHC_FE_FORCE 40.06e3  /* N per 1 mm thickness at 1.2 mm of grip travel (both meshes) */

typedef struct phc_result {
  ph_result r;
  double u_inner, u_outer; /* grip displacement at the first failure in the band, outside it */
} phc_result;

/* Runs the scene at `spacing` to max_time (past both first failures) and checks what holds at
 * every spacing from 0.5 mm down: the first particles to fail are all in the band between the
 * holes, and the outer ligaments fail at least 3% later in time (the reference: 12.5% later in
 * grip displacement; 3% is above the check's time resolution, 10 steps, under 0.3%, with room
 * for the discretization's share of the margin). */
static inline void phc_run(pdk_ctx *ctx, const char *spacing, double max_time, phc_result *out) {
  char scene[2048], sp[128];
  ph_scene_path("plate_two_holes_close.yaml", scene, sizeof scene);
  snprintf(sp, sizeof sp, "geometry.spacing=%s", spacing);
  const char *ov[] = {sp, "output.fields=[u]"};
  ph_result *r = &out->r;
  ph_run(ctx, scene, ov, 2, spacing, 0.0, max_time, 10, r);
  out->u_inner = PHC_SPEED * r->t_first_inner;
  out->u_outer = PHC_SPEED * r->t_first_outer;
  if (getenv("PDK_TEST_VERBOSE")) {
    ph_print(spacing, r);
    printf("%s: first failure in the band at grip u %.4g mm (reference %.4g), outer %.4g mm "
           "(%.4g); force at 1.2 mm %.4g kN (%.4g)\n",
           spacing, out->u_inner * 1e3, PHC_FE_INNER * 1e3, out->u_outer * 1e3, PHC_FE_OUTER * 1e3,
           r->force_at_ref / 1e3, PHC_FE_FORCE / 1e3);
  }
  T_ASSERT(r->t_first_inner > 0 && r->first_all_inner,
           "%s: the first failing particles are not all in the band between the holes (first "
           "failure in the band at %g s, outside it at %g s; %d particles in the first chunk)",
           spacing, r->t_first_inner, r->t_first_outer, r->num_first);
  T_ASSERT(r->t_first_outer > 1.03 * r->t_first_inner,
           "%s: the outer ligaments fail at %g s, not 3%% after the band (%g s; -1: not by %g s)",
           spacing, r->t_first_outer, r->t_first_inner, max_time);
}

#endif
