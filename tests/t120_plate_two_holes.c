/* Ductile fracture of the plate with two holes (V-PH,
 * docs/validation/targets.md), coarse: the shipped scene
 * scenes/plate_two_holes.yaml (0.5 mm) at 1 mm spacing, run in TL with bond breaking and in
 * semi-TL, to 300 us after separation. Checked, in both modes (regions and definitions in
 * plate_two_holes_util.h):
 *   - the plate separates: the bottom and top sets end in different connected components of the
 *     intact bond graph, and exactly two pieces hold more than 1% of the particles, one with
 *     each set (the rest are failed particles, which lose all their bonds, and small debris);
 *   - failure starts at the holes: the particles failed in the first chunk (10 steps) that has a
 *     failure lie within one horizon of a hole's edge;
 *   - failure starts between the holes: those particles lie in the inner ligament, and the outer
 *     ligaments fail later. CAUTION: this holds at this spacing (1 mm: inner 0.870 ms, outer
 *     0.910 ms) but is a near tie that flips with the resolution and the influence function: at
 *     0.625, 0.5 and 0.25 mm, and with the cubic influence at 1 and 1.25 mm, the hole edges
 *     facing the outer ligaments fail first (t121 records the order per spacing;
 *     docs/validation/plate_two_holes.md says why: the triaxiality of hole-edge particles, and
 *     for this geometry the finite-element continuum itself ties the two). Where the holes are
 *     closer and the continuum decides, t127 and t128 check the order against it;
 *   - the bottom force rises, peaks and falls: the peak comes before separation, and the mean
 *     force over the last half of the time run after separation is below 10% of the peak in
 *     magnitude (the separated bottom piece rings about zero; its mean |force| is reported);
 *   - no force crosses the crack: the internal force summed over the bottom piece, sum V f, is 0
 *     to 1e-9 of the peak (pair forces cancel to round-off within a piece; a bond joining the
 *     pieces would carry the whole load);
 *   - energy: plastic work, damage and breaking work are positive and below the external work;
 *   - semi-TL compacted its bond list at least once.
 * Exploring (not for the suite): PDK_TEST_VERBOSE=1 prints the numbers; PDK_PLATE_SPACING=<m>
 * replaces the spacing; PDK_PLATE_SET=<key=value>[;<key=value>...] adds overrides;
 * PDK_PLATE_MODE=tl|semi_tl runs one mode; PDK_PLATE_MAXTIME=<s> changes the time limit;
 * PDK_PLATE_DUMP, PDK_PLATE_TRACE, PDK_PLATE_DUMP_AT, PDK_PLATE_PATH write particle and force
 * files (plate_two_holes_util.h).
 * Run time: about 20 s on 2 cores.
 * labels: physics */
#include "plate_two_holes_util.h"

#define SPACING "1e-3" /* m: 50 x 100 lattice points, 4 849 particles */
#define AFTER 300e-6   /* s run after separation */
#define MAX_TIME 4e-3  /* s: give up */

static void check(const char *what, const ph_result *r) {
  T_ASSERT(r->t_sep > 0,
           "%s: the plate did not separate by t = %g s (%lld bonds broken, %d failed)", what,
           MAX_TIME, (long long)r->broken, (int)r->failed);
  T_ASSERT(r->pieces_ok,
           "%s: %d pieces with more than 1%% of the particles (want 2, holding the bottom and the "
           "top sets)",
           what, r->num_pieces);
  T_ASSERT(r->num_first > 0 && r->first_edge_dist <= r->horizon,
           "%s: the first failures lie up to %g m from a hole's edge, more than the horizon %g m",
           what, r->first_edge_dist, r->horizon);
  T_ASSERT(r->t_first_inner > 0 && r->first_all_inner,
           "%s: failure did not start in the inner ligament (first inner t %g s, first outer t %g "
           "s, all of the first %d failures inner: %d)",
           what, r->t_first_inner, r->t_first_outer, r->num_first, r->first_all_inner);
  T_ASSERT(r->t_first_outer > r->t_first_inner,
           "%s: the outer ligaments failed at t %g s, not after the inner one (t %g s)", what,
           r->t_first_outer, r->t_first_inner);
  T_ASSERT(r->t_peak < r->t_sep, "%s: the force peaks at t %g s, after separation at t %g s", what,
           r->t_peak, r->t_sep);
  T_ASSERT(r->final_force < 0.1 * r->peak,
           "%s: the force after separation, |mean F| %g N over the last %g s, is not below 10%% "
           "of the peak %g N",
           what, r->final_force, r->final_window, r->peak);
  T_NEAR(r->crack_force, 0.0, 0.0, 1e-9 * r->peak,
         "%s: force across the crack on the bottom piece (peak %g N)", what, r->peak);
  T_ASSERT(r->plastic_work > 0 && r->damage_work > 0 && r->breaking_work > 0 &&
               r->plastic_work + r->damage_work + r->breaking_work < r->external_work,
           "%s: dissipation plastic %g, damage %g, breaking %g J vs external work %g J", what,
           r->plastic_work, r->damage_work, r->breaking_work, r->external_work);
}

int main(void) {
  char scene[2048], spacing[128];
  ph_scene_path("plate_two_holes.yaml", scene, sizeof scene);
  const char *sp = getenv("PDK_PLATE_SPACING");
  snprintf(spacing, sizeof spacing, "geometry.spacing=%s", sp ? sp : SPACING);
  pdk_ctx *ctx = t_ctx(0);
  const char *modes[2] = {"tl", "semi_tl"};
  for (int k = 0; k < 2; ++k) {
    char conn[64];
    snprintf(conn, sizeof conn, "model.connectivity=%s", modes[k]);
    const char *ov[8] = {spacing, conn, "output.fields=[u]"};
    int num_ov = 3;
    char set[1024] = "";
    if (getenv("PDK_PLATE_SET")) { /* overrides separated by ';' */
      snprintf(set, sizeof set, "%s", getenv("PDK_PLATE_SET"));
      for (char *t = strtok(set, ";"); t && num_ov < 8; t = strtok(NULL, ";"))
        ov[num_ov++] = t;
    }
    ph_result r;
    if (getenv("PDK_PLATE_MODE") && strcmp(getenv("PDK_PLATE_MODE"), modes[k])) continue;
    const double max_time =
        getenv("PDK_PLATE_MAXTIME") ? atof(getenv("PDK_PLATE_MAXTIME")) : MAX_TIME;
    ph_run(ctx, scene, ov, num_ov, modes[k], AFTER, max_time, 50, &r);
    if (getenv("PDK_TEST_VERBOSE")) ph_print(modes[k], &r);
    check(modes[k], &r);
    T_ASSERT(k == 0 || r.compactions > 0, "semi_tl: the bond list was never compacted");
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
