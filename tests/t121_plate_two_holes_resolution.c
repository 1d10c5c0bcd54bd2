/* Resolution study of the plate with two holes (V-PH,
 * docs/validation/targets.md): the shipped scene
 * scenes/plate_two_holes.yaml at spacings 1, 0.5 (the shipped default) and 0.25 mm (the spacing
 * of plate_two_holes_fine.yaml), TL, each run to 300 us after the plate separates.
 * Recorded per spacing (plate_two_holes_util.h): peak bottom force, the time and top
 * displacement at the peak, the time and top displacement at separation (the displacement at
 * failure), when the inner and the outer ligaments first fail, the dissipated energies.
 * Checked: the plate separates into two pieces at every spacing, with no force across the crack
 * (1e-9 of the peak) and the force falling below 10% of its peak after separation (as t120);
 * the peak force of successive spacings differs by less than 20% (no regularisation: the
 * localisation, so the force after the peak and the failure displacement, depends on the
 * spacing; the peak is set by the plastic net section and should not move much).
 * Against the finite-element reference (docs/validation/plate_two_holes_fe, CalculiX, the same
 * continuum problem): the bottom force at 1.2 mm of grip travel, before anything fails, is
 * 40.4 kN there on every mesh (40.36 to 40.38 kN with 1, 0.5 and 0.25 mm elements, static, and
 * with 1 mm elements pulled at 2 m/s). pdk's force there comes down toward it with the spacing
 * (47.7, 43.9, 42.0 kN measured on 2026-11-26; observed order 0.92, extrapolated 40.0 kN): the
 * stabilized families are too stiff where the plastic strain localizes, by an amount that
 * shrinks with the horizon. Checked: the force
 * decreases from spacing to spacing and stays above the reference, and the first-order
 * extrapolation 2 F(0.25 mm) - F(0.5 mm) lies within 3% of the reference and closer to it than
 * the finest run (4% above it): the error behaves as a discretization error converging to the
 * continuum's force, not as a modelling offset. 3% is the finest run's error minus a margin; the
 * reference's own spread over its meshes is 0.05%.
 * The table is printed with PDK_TEST_VERBOSE=1 and always written to
 * t121_plate_two_holes_resolution.txt in the test's working folder; the numbers are recorded in
 * docs/validation/plate_two_holes.md. Run time: about 20 minutes on 2 cores (most of it at
 * 0.25 mm).
 *   PDK_TEST_VERBOSE=1 ctest --test-dir build -R t121 -V
 * labels: physics slow */
#include "plate_two_holes_util.h"

#define AFTER 300e-6 /* s run after separation */
#define MAX_TIME 4e-3

int main(void) {
  char scene[2048];
  ph_scene_path("plate_two_holes.yaml", scene, sizeof scene);
  pdk_ctx *ctx = t_ctx(0);
  const char *spacings[] = {"1e-3", "0.5e-3", "0.25e-3"};
  const int num = 3;
  ph_result r[3];
  FILE *table = fopen("t121_plate_two_holes_resolution.txt", "w");
  T_ASSERT(table, "cannot write t121_plate_two_holes_resolution.txt");
  fprintf(table,
          "# plate with two holes, TL, %d threads; times in ms, displacements in mm, forces "
          "in kN (per 1 mm thickness), energies in J\n",
          pdk_ctx_num_threads(ctx));
  fprintf(table, "# spacing particles steps wall_s peak_kN t_peak u_peak t_first_inner "
                 "t_first_outer first t_sep u_sep final_mean_kN plastic damage breaking "
                 "force_at_1.2mm_kN\n");
  for (int k = 0; k < num; ++k) {
    char sp[128];
    snprintf(sp, sizeof sp, "geometry.spacing=%s", spacings[k]);
    const char *ov[] = {sp, "output.fields=[u]"};
    ph_run(ctx, scene, ov, 2, spacings[k], AFTER, MAX_TIME, 50, &r[k]);
    const ph_result *q = &r[k];
    fprintf(table,
            "%s %d %ld %.1f %.2f %.4f %.4f %.4f %.4f %s %.4f %.4f %.2f %.2f %.2f %.2f %.3f\n",
            spacings[k], (int)q->num_particles, q->steps, q->wall, q->peak / 1e3, q->t_peak * 1e3,
            q->u_peak * 1e3, q->t_first_inner * 1e3, q->t_first_outer * 1e3,
            q->t_first_inner >= 0 && q->first_all_inner ? "inner" : "outer", q->t_sep * 1e3,
            q->u_sep * 1e3, q->final_force / 1e3, q->plastic_work, q->damage_work, q->breaking_work,
            q->force_at_ref / 1e3);
    fflush(table);
    if (getenv("PDK_TEST_VERBOSE")) ph_print(spacings[k], q);
  }
  fclose(table);
  if (getenv("PDK_TEST_VERBOSE")) {
    FILE *f = fopen("t121_plate_two_holes_resolution.txt", "r");
    if (f) {
      char line[512];
      while (fgets(line, sizeof line, f))
        fputs(line, stdout);
      fclose(f);
    }
  }
  for (int k = 0; k < num; ++k) {
    const ph_result *q = &r[k];
    T_ASSERT(q->t_sep > 0 && q->pieces_ok, "%s: the plate did not separate into two pieces by %g s",
             spacings[k], MAX_TIME);
    T_NEAR(q->crack_force, 0.0, 0.0, 1e-9 * q->peak, "%s: force across the crack", spacings[k]);
    T_ASSERT(q->final_force < 0.1 * q->peak && q->t_peak < q->t_sep,
             "%s: the force after separation %g N is not below 10%% of the peak %g N", spacings[k],
             q->final_force, q->peak);
    if (k > 0)
      T_NEAR(q->peak, r[k - 1].peak, 0.2, 0.0, "peak force at %s vs %s", spacings[k],
             spacings[k - 1]);
  }
  /* the finite-element reference's force at PH_U_REF (1.2 mm), N per 1 mm of thickness */
  const double f_ref = 40.4e3;
  for (int k = 0; k < num; ++k) {
    T_ASSERT(r[k].force_at_ref > f_ref, "%s: force at 1.2 mm %g N is not above the reference %g N",
             spacings[k], r[k].force_at_ref, f_ref);
    if (k > 0)
      T_ASSERT(r[k].force_at_ref < r[k - 1].force_at_ref,
               "force at 1.2 mm does not decrease with the spacing: %g N at %s, %g N at %s",
               r[k].force_at_ref, spacings[k], r[k - 1].force_at_ref, spacings[k - 1]);
  }
  const double f_ext = 2.0 * r[2].force_at_ref - r[1].force_at_ref;
  const double order =
      log((r[0].force_at_ref - r[1].force_at_ref) / (r[1].force_at_ref - r[2].force_at_ref)) /
      log(2.0);
  if (getenv("PDK_TEST_VERBOSE"))
    printf("force at 1.2 mm: %.1f, %.1f, %.1f kN; observed order %.2f; extrapolated %.1f kN; "
           "finite elements %.1f kN\n",
           r[0].force_at_ref / 1e3, r[1].force_at_ref / 1e3, r[2].force_at_ref / 1e3, order,
           f_ext / 1e3, f_ref / 1e3);
  T_NEAR(f_ext, f_ref, 0.03, 0.0, "extrapolated force at 1.2 mm against the finite elements");
  T_ASSERT(fabs(f_ext - f_ref) < fabs(r[2].force_at_ref - f_ref),
           "the extrapolated force %g N is not closer to the reference %g N than the finest run's "
           "%g N",
           f_ext, f_ref, r[2].force_at_ref);
  pdk_ctx_destroy(&ctx);
  return 0;
}
