/* The crack path is the body's, not the lattice's. scenes/plate_two_holes_close.yaml at 1 mm, TL,
 * run to 3 ms twice: as shipped (lattice rows along the plate's edges) and with the plate, its
 * holes, its grips and the pull turned by 30 degrees about the plate's centre inside the same
 * square lattice (geometry.box enlarged, geometry.notches keeping the turned rectangle, the grips
 * half-spaces, the pull 2 m/s along the turned axis; every other key the shipped scene's). A crack
 * that followed the lattice's rows or diagonals would run at -30, +15, +60 or -75 degrees in the
 * turned plate's own frame; one set by the body runs where it runs in the shipped plate.
 * In the plate's own frame (x across, y along the pull), checked for both:
 *   - the plate separates: the grips lie in different components of the intact bond graph;
 *   - each outer ligament (failed particles more than 6 mm outward of its hole's centre, within
 *     15 mm of it in y) tears along a line whose angle differs between the two lattices by at
 *     most 8 degrees (measured 2026-11-27: +1.1/+1.1 as shipped, +3.5/-4.0 turned; the turned
 *     lattice's nearest directions are 15 degrees away; the least-squares angle of a band one or
 *     two spacings wide and about 12 mm long scatters by a few degrees with the lattice's
 *     staircase), and whose mean height differs by at most 1.5 spacings (measured 0.25 mm for
 *     both; a crack along the turned rows would sit about 3 mm off);
 *   - the crack between the holes runs along the same direction to within 10 degrees (principal
 *     axis of its failed particles; measured 69.5 and 66.3 degrees from x);
 *   - the number of failed particles agrees to 20% (measured 104 and 92).
 * What this does not check: that the outer ligaments tear at the 45 degrees V-PH expects. They tear
 * across (docs/validation/plate_two_holes.md item 12), and this test shows it is the model's
 * answer for this body, not the lattice's.
 * Guarded: the turned run's body, grips and pull are the plate's, turned (counts and positions).
 * Run time: about 30 s on 2 cores. PDK_TEST_VERBOSE=1 prints the numbers.
 * labels: physics */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jc_corr_util.h"
#include "pdk/scene.h"
#include "scene/scene_impl.h"

#define SPACING 1.0e-3
#define END_TIME 3.0e-3 /* both separate by then (2.6 ms is too short as shipped) */
#define CX 0.025        /* the plate's centre: turned about it */
#define CY 0.05

typedef struct tear {
  double outer_angle[2], outer_height[2]; /* lower hole's (left), upper hole's (right) */
  double inner_angle;
  pdk_index failed, n, n_top, n_bottom;
  double outside, grip_v_err; /* checks that the body is the turned plate, pulled along it */
  int separated;
} tear;

/* plate frame -> lattice frame, turned by th about the centre */
static void turn(double th, double x, double y, double out[2]) {
  const double dx = x - CX, dy = y - CY;
  out[0] = CX + cos(th) * dx - sin(th) * dy;
  out[1] = CY + sin(th) * dx + cos(th) * dy;
}

/* angle (degrees, in (-90, 90]) of the least-squares line y(x) through the points */
static double fit_angle(const double *x, const double *y, int n) {
  double mx = 0, my = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < n; ++k) {
    mx += x[k];
    my += y[k];
  }
  mx /= n;
  my /= n;
  for (int k = 0; k < n; ++k) {
    sxx += (x[k] - mx) * (x[k] - mx);
    sxy += (x[k] - mx) * (y[k] - my);
  }
  return atan(sxy / sxx) * 180.0 / M_PI;
}

static void run(pdk_ctx *ctx, double deg, tear *t) {
  const double th = deg * M_PI / 180.0;
  char path[4096];
  const char *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(src, "PDK_SOURCE_DIR is not set (ctest sets it)");
  snprintf(path, sizeof path, "%s/scenes/plate_two_holes_close.yaml", src);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  T_ASSERT(s->num_holes == 2, "the scene must have two holes");
  double hole[2][2];
  for (int h = 0; h < 2; ++h)
    for (int a = 0; a < 2; ++a)
      hole[h][a] = s->holes[h].region.center[a];
  const double radius = s->holes[0].region.radius;
  pdk_scene_destroy(&s);

  /* the overrides: the turned plate in a box that holds it */
  double c[4][2], h1[2], h2[2], lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  const double corner[4][2] = {{0, 0}, {0.05, 0}, {0.05, 0.1}, {0, 0.1}};
  for (int k = 0; k < 4; ++k) {
    turn(th, corner[k][0], corner[k][1], c[k]);
    for (int a = 0; a < 2; ++a) {
      lo[a] = fmin(lo[a], c[k][a] - SPACING);
      hi[a] = fmax(hi[a], c[k][a] + SPACING);
    }
  }
  turn(th, hole[0][0], hole[0][1], h1);
  turn(th, hole[1][0], hole[1][1], h2);
  const double ey[2] = {-sin(th), cos(th)}; /* the pull's direction */
  double pb[2], pt[2];
  turn(th, CX, 0.003, pb); /* the grips: 3 mm deep, as the shipped scene's boxes */
  turn(th, CX, 0.097, pt);
  char o[6][512];
  snprintf(o[0], sizeof o[0], "geometry.spacing=%.17g", SPACING);
  snprintf(o[1], sizeof o[1], "geometry.box={lo: [%.17g, %.17g], hi: [%.17g, %.17g]}", lo[0], lo[1],
           hi[0], hi[1]);
  snprintf(o[2], sizeof o[2],
           "geometry.notches=[{polygon: {vertices: [[%.17g, %.17g], [%.17g, %.17g], [%.17g, "
           "%.17g], [%.17g, %.17g]]}, invert: true}]",
           c[0][0], c[0][1], c[1][0], c[1][1], c[2][0], c[2][1], c[3][0], c[3][1]);
  snprintf(o[3], sizeof o[3],
           "geometry.holes=[{disk: {center: [%.17g, %.17g], radius: %.17g}}, {disk: {center: "
           "[%.17g, %.17g], radius: %.17g}}]",
           h1[0], h1[1], radius, h2[0], h2[1], radius);
  snprintf(o[4], sizeof o[4],
           "sets=[{name: bottom, halfspace: {point: [%.17g, %.17g], normal: [%.17g, %.17g]}}, "
           "{name: top, halfspace: {point: [%.17g, %.17g], normal: [%.17g, %.17g]}}]",
           pb[0], pb[1], ey[0], ey[1], pt[0], pt[1], -ey[0], -ey[1]);
  snprintf(o[5], sizeof o[5],
           "boundary_conditions=[{set: bottom, type: displacement, x: 0, y: 0}, {set: top, type: "
           "velocity, x: %.17g, y: %.17g}]",
           2.0 * ey[0], 2.0 * ey[1]);
  const char *ov[6] = {o[0], o[1], o[2], o[3], o[4], o[5]};
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 6, &s));
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  pdk_model *m = pdk_sim_model(sim);
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_history hist;
  while (pdk_explicit_time(e) < END_TIME - 0.5 * pdk_explicit_dt(e))
    T_OK(ctx, pdk_explicit_run(e, 50, &hist));

  const pdk_index n = pdk_particles_count(p);
  pdk_index *comp = malloc((size_t)n * sizeof *comp);
  double *bx = malloc((size_t)n * 2 * sizeof *bx), *by = bx + n;
  T_ASSERT(comp && bx, "out of memory");
  jcu_components(m, comp);
  const uint8_t *in_top = pdk_particles_field_data(p, "set:top", 0);
  const uint8_t *in_bottom = pdk_particles_field_data(p, "set:bottom", 0);
  const uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  pdk_index i_top = -1, i_bottom = -1;
  t->failed = 0;
  for (pdk_index i = 0; i < n; ++i) {
    if (in_top[i] && i_top < 0) i_top = i;
    if (in_bottom[i] && i_bottom < 0) i_bottom = i;
    t->failed += failed[i] != 0;
  }
  T_ASSERT(i_top >= 0 && i_bottom >= 0, "turned %g deg: a grip holds no particle", deg);
  t->separated = comp[i_top] != comp[i_bottom];

  /* the body is the plate turned by deg: every particle, turned back, lies in the 50 x 100 mm
   * rectangle and outside both holes (the distance by which it does not, at most); the grips'
   * particles, counted, move at 2 m/s along the turned axis */
  const double *vx = pdk_particles_field_data(p, "v", 0), *vy = pdk_particles_field_data(p, "v", 1);
  t->n = n;
  t->n_top = t->n_bottom = 0;
  t->outside = t->grip_v_err = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    double q[2];
    turn(-th, X[i], Y[i], q);
    double out = fmax(fmax(-q[0], q[0] - 0.05), fmax(-q[1], q[1] - 0.1));
    for (int h = 0; h < 2; ++h)
      out = fmax(out, radius - hypot(q[0] - hole[h][0], q[1] - hole[h][1]));
    t->outside = fmax(t->outside, out);
    t->n_top += in_top[i] != 0;
    t->n_bottom += in_bottom[i] != 0;
    if (in_top[i])
      t->grip_v_err = fmax(t->grip_v_err, hypot(vx[i] - 2.0 * ey[0], vy[i] - 2.0 * ey[1]));
  }

  /* the failed particles in the plate's frame (turned back) */
  for (int h = 0; h < 2; ++h) {
    const double side = h == 0 ? -1.0 : 1.0;
    int k = 0;
    double sum_y = 0.0;
    for (pdk_index i = 0; i < n; ++i) {
      if (!failed[i]) continue;
      double q[2];
      turn(-th, X[i], Y[i], q);
      if (side * (q[0] - hole[h][0]) > 6e-3 && fabs(q[1] - hole[h][1]) < 15e-3) {
        bx[k] = q[0];
        by[k++] = q[1];
        sum_y += q[1];
      }
    }
    T_ASSERT(k >= 5, "turned %g deg: %d failed particles in the outer ligament of hole %d", deg, k,
             h + 1);
    t->outer_angle[h] = fit_angle(bx, by, k);
    t->outer_height[h] = sum_y / k;
  }
  /* the crack between the holes: principal axis of the failed particles in the corridor */
  {
    const double ux = hole[1][0] - hole[0][0], uy = hole[1][1] - hole[0][1];
    const double len = hypot(ux, uy);
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
    int k = 0;
    for (pdk_index i = 0; i < n; ++i) {
      if (!failed[i]) continue;
      double q[2];
      turn(-th, X[i], Y[i], q);
      const double a = ((q[0] - hole[0][0]) * ux + (q[1] - hole[0][1]) * uy) / (len * len);
      const double dist = fabs((q[0] - hole[0][0]) * uy - (q[1] - hole[0][1]) * ux) / len;
      if (a > 0 && a < 1 && dist <= radius) {
        bx[k] = q[0];
        by[k++] = q[1];
      }
    }
    T_ASSERT(k >= 5, "turned %g deg: %d failed particles between the holes", deg, k);
    for (int j = 0; j < k; ++j) {
      mx += bx[j] / k;
      my += by[j] / k;
    }
    for (int j = 0; j < k; ++j) {
      sxx += (bx[j] - mx) * (bx[j] - mx);
      syy += (by[j] - my) * (by[j] - my);
      sxy += (bx[j] - mx) * (by[j] - my);
    }
    t->inner_angle = 0.5 * atan2(2.0 * sxy, sxx - syy) * 180.0 / M_PI;
  }
  if (getenv("PDK_TEST_VERBOSE"))
    printf(
        "turned %4.1f deg: %zu particles (grips %zu / %zu), %zu failed, separated %d; outer tears "
        "%+.1f / %+.1f deg at y %.2f / %.2f mm; inner crack %.1f deg\n",
        deg, (size_t)n, (size_t)t->n_top, (size_t)t->n_bottom, (size_t)t->failed, t->separated,
        t->outer_angle[0], t->outer_angle[1], 1e3 * t->outer_height[0], 1e3 * t->outer_height[1],
        t->inner_angle);
  free(comp);
  free(bx);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(0);
  tear a, b;
  run(ctx, 0.0, &a);
  run(ctx, 30.0, &b);
  /* the turned body is the plate: its particles inside the turned rectangle and outside the
   * holes, as many as the shipped plate's to 2% (the lattice's sites along the turned edges;
   * measured 4 842 and 4 843), its grips as deep (3 mm: counts within 10%, measured 150 / 150 and
   * 150 / 149) and the top pulled along the turned axis (prescribed: to round-off). Overrides that
   * did not take (the whole box kept, the grips or the pull along the lattice) fail here. */
  for (int k = 0; k < 2; ++k) {
    const tear *t = k ? &b : &a;
    T_ASSERT(t->outside <= 0.0, "turned %d deg: a particle lies %.3g m outside the plate",
             k ? 30 : 0, t->outside);
    T_ASSERT(t->grip_v_err <= 1e-12, "turned %d deg: the top grip moves %.3g m/s off its pull",
             k ? 30 : 0, t->grip_v_err);
  }
  T_ASSERT(fabs((double)b.n - (double)a.n) <= 0.02 * (double)a.n,
           "the turned plate has %zu particles, the shipped one %zu", (size_t)b.n, (size_t)a.n);
  T_ASSERT(fabs((double)b.n_top - (double)a.n_top) <= 0.1 * (double)a.n_top &&
               fabs((double)b.n_bottom - (double)a.n_bottom) <= 0.1 * (double)a.n_bottom,
           "grips: top %zu / %zu, bottom %zu / %zu particles (shipped / turned)", (size_t)a.n_top,
           (size_t)b.n_top, (size_t)a.n_bottom, (size_t)b.n_bottom);
  T_ASSERT(a.separated && b.separated,
           "the plate did not separate by %g s (as shipped %d, turned %d)", END_TIME, a.separated,
           b.separated);
  for (int h = 0; h < 2; ++h) {
    T_ASSERT(fabs(a.outer_angle[h] - b.outer_angle[h]) <= 8.0,
             "outer ligament %d tears at %+.1f deg as shipped, %+.1f deg turned", h + 1,
             a.outer_angle[h], b.outer_angle[h]);
    T_ASSERT(fabs(a.outer_height[h] - b.outer_height[h]) <= 1.5 * SPACING,
             "outer ligament %d tears at y %.3g m as shipped, %.3g m turned", h + 1,
             a.outer_height[h], b.outer_height[h]);
  }
  T_ASSERT(fabs(a.inner_angle - b.inner_angle) <= 10.0,
           "the crack between the holes runs at %.1f deg as shipped, %.1f deg turned",
           a.inner_angle, b.inner_angle);
  T_ASSERT(fabs((double)a.failed - (double)b.failed) <= 0.2 * (double)a.failed,
           "%zu particles failed as shipped, %zu turned", (size_t)a.failed, (size_t)b.failed);
  pdk_ctx_destroy(&ctx);
  return 0;
}
