/* A wall from a scene (boundary_conditions type: wall) run by pdk_sim_run: the history's columns
 * wall_<name>_force, wall_<name>_impulse and contact_work; the force column summed against the
 * rows' time steps equals the impulse (to round-off), and the impulse equals the body's momentum
 * change; no particle ends behind the wall; the contact work is the whole external work here (the
 * wall is the only condition). History rows every 7 steps, so records and run chunks do not align.
 * labels: scene */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pdk/run.h"
#include "pdk/scene.h"
#include "test_util.h"

static const char *scene_text =
    "name: t257_wall\n"
    "dimension: 3\n"
    "geometry:\n"
    "  spacing: 1.0e-3\n"
    "  box: {lo: [0, 0, 0.3e-3], hi: [4.0e-3, 4.0e-3, 10.3e-3]}\n"
    "material: {density: 7800, bulk_modulus: 160e9}\n"
    "model: {kind: pmb}\n"
    "boundary_conditions:\n"
    "  - {set: all, type: wall, point: [0, 0, 0], normal: [0, 0, 1], name: anvil}\n"
    "initial_conditions: {velocity: [3.0, 0, -30.0]}\n"
    "solver: {end_time: 30.0e-6, safety: 0.4}\n"
    "output: {history_interval: 7, field_interval: 0, fields: [u, v]}\n";

#define MAX_ROWS 4096

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const char *path = "t257_wall.yaml";
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "open %s", path);
  fputs(scene_text, f);
  fclose(f);
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  const double *V = pdk_particles_volume(p);
  double mass = 0;
  for (pdk_index i = 0; i < n; ++i)
    mass += 7800 * V[i];
  const double p0z = mass * -30.0, p0x = mass * 3.0;
  pdk_run_opts ro = pdk_run_opts_default();
  ro.dir = "t257_out";
  ro.plot = 0;
  T_OK(ctx, pdk_sim_run(sim, s, &ro, NULL));
  double pz = 0, px = 0, zmin = INFINITY;
  const double *vz = pdk_particles_field_data(p, "v", 2), *vx = pdk_particles_field_data(p, "v", 0);
  const double *xz = pdk_particles_field_data(p, "x", 2);
  for (pdk_index i = 0; i < n; ++i) {
    pz += 7800 * V[i] * vz[i];
    px += 7800 * V[i] * vx[i];
    zmin = fmin(zmin, xz[i]);
  }

  /* the history CSV */
  f = fopen("t257_out/t257_wall_history.csv", "r");
  T_ASSERT(f != NULL, "history CSV");
  static char line[1 << 16];
  T_ASSERT(fgets(line, sizeof line, f), "header");
  int c_time = -1, c_force = -1, c_imp = -1, c_cw = -1, c_ext = -1, col = 0;
  for (char *tok = strtok(line, ",\n"); tok; tok = strtok(NULL, ",\n"), ++col) {
    if (!strncmp(tok, "time ", 5)) c_time = col;
    if (!strncmp(tok, "wall_anvil_force ", 17)) c_force = col;
    if (!strncmp(tok, "wall_anvil_impulse ", 19)) c_imp = col;
    if (!strncmp(tok, "contact_work ", 13)) c_cw = col;
    if (!strncmp(tok, "external_work ", 14)) c_ext = col;
  }
  T_ASSERT(c_time >= 0 && c_force >= 0 && c_imp >= 0 && c_cw >= 0 && c_ext >= 0,
           "history columns: time %d force %d impulse %d contact_work %d external_work %d", c_time,
           c_force, c_imp, c_cw, c_ext);
  double integral = 0, t_prev = 0, imp = 0, cw = 0, ext = 0, fmax_ = 0;
  int rows = 0;
  while (fgets(line, sizeof line, f)) {
    double v[64] = {0};
    col = 0;
    for (char *tok = strtok(line, ",\n"); tok && col < 64; tok = strtok(NULL, ",\n"))
      v[col++] = strtod(tok, NULL);
    if (rows == 0)
      T_ASSERT(v[c_force] == 0, "first row's force %g, expected 0", v[c_force]);
    else
      integral += v[c_force] * (v[c_time] - t_prev);
    t_prev = v[c_time];
    imp = v[c_imp];
    cw = v[c_cw];
    ext = v[c_ext];
    fmax_ = fmax(fmax_, fabs(v[c_force]));
    ++rows;
  }
  fclose(f);
  T_INFO("rows %d, impulse %g, integral %g, dp %g (p0 %g), peak force %g N, contact work %g, "
         "zmin %g\n",
         rows, imp, integral, pz - p0z, p0z, fmax_, cw, zmin);
  T_ASSERT(rows > 10, "only %d history rows", rows);
  /* the mean forces times the rows' intervals telescope to the last impulse: round-off of the
   * CSV's 17 digits and of the sums */
  T_NEAR(integral, imp, 1e-12, 0, "force column integrated vs the impulse");
  /* the impulse is the momentum change (PMB's internal forces sum to zero): the rod rebounds */
  T_NEAR(imp, pz - p0z, 1e-12, 0, "impulse vs momentum change");
  T_ASSERT(pz > 0, "the block rebounds: p_z %g", pz);
  T_NEAR(px, p0x, 1e-12, 0, "frictionless: tangential momentum");
  T_ASSERT(zmin >= -1e-18, "a particle ends %g m behind the wall", zmin);
  /* the wall is the only condition: all the external work is contact work */
  T_ASSERT(cw < 0 && cw == ext, "contact work %g, external work %g", cw, ext);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove(path);
  pdk_ctx_destroy(&ctx);
  return 0;
}
