/* Test helper: a square plate with an edge pre-crack, pulled apart by its top and bottom rows
 * (t245, t246, t247). Include after test_util.h.
 *
 * 40 x 40 mm, spacing 1 mm (1600 particles), horizon 3.015 mm, plane strain; a pre-crack from
 * the left edge to x = 16 mm along y = 20 mm; the three bottom and top rows are moved apart along
 * y at 0.5 m/s each from t = 0 (displacement conditions linear in time: their positions are exact
 * at every step, so the run's energy account carries no error of the grips). E = 1 GPa,
 * nu = 0.25 (PMB's Poisson ratio), rho = 8000 kg/m^3, critical stretch 0.004: the crack starts
 * from the tip after about 50 us and crosses the plate by 200 us. */
#ifndef PDK_TEST_CRACK_PLATE_UTIL_H
#define PDK_TEST_CRACK_PLATE_UTIL_H

#include <stdio.h>

#include "pdk/explicit.h"
#include "pdk/model.h"
#include "pdk/scene.h"

#define CP_DELTA 3.015e-3
#define CP_CRACK_Y 0.02
#define CP_TIP_X 0.016

static const char *cp_scene = "name: crackplate\n"
                              "dimension: 2\n"
                              "geometry:\n"
                              "  lattice: square\n"
                              "  spacing: 1.0e-3\n"
                              "  horizon_factor: 3.015\n"
                              "  box: {lo: [0, 0], hi: [0.04, 0.04]}\n"
                              "  precracks:\n"
                              "    - segment: [[0.0, 0.02], [0.016, 0.02]]\n"
                              "material: {density: 8000, youngs_modulus: 1.0e9, poisson_ratio: 0.25}\n"
                              "model: {kind: pmb, critical_stretch: 0.004}\n"
                              "sets:\n"
                              "  - {name: bottom, box: {lo: [-1, -1], hi: [1, 0.003]}}\n"
                              "  - {name: top, box: {lo: [-1, 0.037], hi: [1, 1]}}\n"
                              "boundary_conditions:\n"
                              "  - {set: bottom, type: displacement, y: -0.5, function: linear}\n"
                              "  - {set: top, type: displacement, y: 0.5, function: linear}\n"
                              "solver: {end_time: 2.0e-4, safety: 0.5}\n"
                              "output: {field_interval: 0, fields: [u], history_interval: 20}\n";

/* Writes the scene to `path` and builds it with the overrides ("key=value"). */
static inline pdk_sim *cp_build(pdk_ctx *ctx, const char *path, const char *const *ov, int nov,
                                pdk_scene **scene_out) {
  FILE *f = fopen(path, "w");
  T_ASSERT(f, "cannot write %s", path);
  fputs(cp_scene, f);
  fclose(f);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, nov, &s));
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  if (scene_out)
    *scene_out = s;
  else
    pdk_scene_destroy(&s);
  return sim;
}

/* Bond damage by brute force from the bond state: 1 - sum_intact V_j / sum_all V_j over the
 * families' bonds (no partial volumes in these scenes), in the order of the families. */
static inline void cp_damage_brute(pdk_model *m, double *out) {
  pdk_particles *p = pdk_model_particles(m);
  pdk_families *fam = pdk_model_families(m);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const uint8_t *alive = pdk_model_bond_alive(m);
  const double *V = pdk_particles_volume(p);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    double all = 0.0, intact = 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      all += V[bj[b]];
      if (!alive || alive[b]) intact += V[bj[b]];
    }
    out[i] = all > 0.0 ? 1.0 - intact / all : 0.0;
  }
}

/* sum_i V_i w_broken_i, in index order (0 without the field). */
static inline double cp_broken_sum(pdk_particles *p) {
  const double *w = pdk_particles_field_data(p, "w_broken", 0);
  const double *V = pdk_particles_volume(p);
  double s = 0.0;
  for (pdk_index i = 0; w && i < pdk_particles_count(p); ++i) s += V[i] * w[i];
  return s;
}

#endif
