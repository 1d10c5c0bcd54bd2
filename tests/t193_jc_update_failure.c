/* A Johnson-Cook update that fails (F not finite, det F <= 0, a trial elastic stretch that is not
 * positive) stops a committing force pass with PDK_ERR_NUMERIC naming the first such particle,
 * why, how many, and what to check. Before, the particle silently carried zero stress and the
 * run went on: the two-hole plate with its grip at 1e20 m/s ran to the end with every point
 * near the grip failing, and its energy summary read "off by 0 (0% of the energy put in)".
 * Cases:
 *  1. the model API (the 40 x 10 mm bar of t101, TL and UL connectivity): every particle
 *     mirrored, x = (-X, Y), so F = diag(-1, 1) and det F = -1 everywhere:
 *     - a trial pass succeeds (it commits nothing; the particles are flagged, as before);
 *     - a committing pass fails naming particle 0 (its id), why ("det F = -1"; UL: its family
 *       is turned inside out, which UL tests before F) and the count n;
 *     - particles that had failed before carry no stress whatever F is (failed_mode zero): no
 *       error; with failed_mode compression (a pressure K ln J needs J > 0) the error again.
 *  2. the scene path: scenes/plate_two_holes.yaml at 1 mm with the grip at 1e20 m/s: the first
 *     step fails, the message names the step, a particle of the body and the remedy.
 * labels: unit physics
 */
#include "jc_corr_util.h"
#include "pdk/scene.h"

static void mirror(pdk_particles *p) {
  const pdk_index n = pdk_particles_count(p);
  double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  for (pdk_index i = 0; i < n; ++i)
    x[i] = -X[i], y[i] = Y[i];
}

static void model_api(pdk_ctx *ctx, pdk_connectivity conn) {
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  jcu_bar(ctx, 0, &p, &fam);
  const pdk_index n = pdk_particles_count(p);
  for (int mode = 0; mode <= 2; ++mode) { /* 0 intact, 1 failed (zero), 2 failed (compression) */
    pdk_model_opts mo = pdk_model_opts_default();
    mo.kind = PDK_MODEL_CORRESPONDENCE;
    mo.law = PDK_LAW_JC;
    mo.bulk_modulus = mo.shear_modulus = mo.density = 0.0; /* from mo.jc */
    mo.connectivity = conn;
    mo.failed_keeps_bonds = 1;
    if (mode == 2) mo.jc.failed_mode = PDK_JC_FAILED_COMPRESSION;
    pdk_model *m = NULL;
    T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
    T_OK(ctx, pdk_model_set_dt(m, 1e-7));
    if (mode > 0) {
      uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
      for (pdk_index i = 0; i < n; ++i)
        failed[i] = 1;
    }
    mirror(p);
    T_OK(ctx, pdk_model_force_trial(m, NULL));
    T_ASSERT(pdk_model_num_flagged(m) == n, "conn %d mode %d: %d of %d flagged", (int)conn, mode,
             (int)pdk_model_num_flagged(m), (int)n);
    if (mode == 1) {
      T_OK(ctx, pdk_model_force(m, NULL));
    } else {
      char needle[128];
      snprintf(needle, sizeof needle, "failed for particle 0 (id %lld,",
               (long long)pdk_particles_id(p)[0]);
      T_FAILS(ctx, pdk_model_force(m, NULL), PDK_ERR_NUMERIC, needle);
      const char *msg = pdk_ctx_error_message(ctx);
      snprintf(needle, sizeof needle, "%d particle(s) in all", (int)n);
      const char *why = conn == PDK_CONNECTIVITY_UL ? "turned inside out" : "det F = -1";
      T_ASSERT(strstr(msg, why) && strstr(msg, needle) && strstr(msg, "take smaller steps"),
               "conn %d mode %d: %s", (int)conn, mode, msg);
    }
    pdk_model_destroy(&m);
    pdk_particles_field_remove(p, "failed");
  }
  jcu_sim s = {p, fam, NULL, NULL, {{0}}};
  jcu_sim_destroy(&s);
}

static void scene_path(pdk_ctx *ctx) {
  char path[1024];
  snprintf(path, sizeof path, "%s/scenes/plate_two_holes.yaml", getenv("PDK_SOURCE_DIR"));
  const char *ov[2] = {"geometry.spacing=1e-3", "boundary_conditions[1].y=1e20"};
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 2, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(e, 0, &h));
  T_FAILS(ctx, pdk_explicit_run(e, 10, &h), PDK_ERR_NUMERIC, "step 1 (time ");
  const char *msg = pdk_ctx_error_message(ctx);
  const char *q = strstr(msg, "the Johnson-Cook update failed for particle ");
  long long i = -1, id = -1;
  T_ASSERT(q &&
               sscanf(q, "the Johnson-Cook update failed for particle %lld (id %lld", &i, &id) == 2,
           "%s", msg);
  pdk_particles *p = pdk_sim_particles(sim);
  T_ASSERT(i >= 0 && i < pdk_particles_count(p) && pdk_particles_id(p)[i] == id,
           "not a particle of the body: %s", msg);
  T_ASSERT(strstr(msg, "check the boundary conditions"), "no remedy: %s", msg);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  model_api(ctx, PDK_CONNECTIVITY_TL);
  model_api(ctx, PDK_CONNECTIVITY_UL);
  scene_path(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
