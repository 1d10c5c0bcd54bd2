/* Scenes with several materials (docs/scenes.md, "materials"): the keys map onto
 * pdk_model_opts.materials (material 0 from `material`, E and nu converted), the built body's
 * "material" field holds each particle's material by region (a later entry wins where regions
 * overlap: counted here independently of pdk), the explicit solver's stable step follows the
 * stiffest material, and bad keys are errors naming the key.
 * labels: unit */
#include "pdk/scene.h"
#include "scene/scene_impl.h"
#include "test_util.h"

static char path[2048];

static pdk_scene *load(pdk_ctx *ctx, const char *const *ov, int n) {
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, n, &s));
  return s;
}

static void load_fails(pdk_ctx *ctx, const char *ov, const char *key, const char *needle) {
  pdk_scene *s = NULL;
  const char *o[1] = {ov};
  pdk_ctx_error_clear(ctx);
  const int err = pdk_scene_load(ctx, path, o, 1, &s);
  T_ASSERT(err == PDK_ERR_ARG, "--set %s: returned %d (%s)", ov, err, pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), key) && strstr(pdk_ctx_error_message(ctx), needle),
           "--set %s: message '%s' lacks '%s' or '%s'", ov, pdk_ctx_error_message(ctx), key,
           needle);
}

int main(void) {
  const char *src = getenv("PDK_SOURCE_DIR");
  snprintf(path, sizeof path, "%s/tests/scenes/t065_bimaterial.yaml", src ? src : "..");
  pdk_ctx *ctx = t_ctx(2);
  pdk_scene *s = load(ctx, NULL, 0);
  const pdk_model_opts *mo = &s->model;
  T_ASSERT(mo->num_materials == 3 && mo->materials, "num_materials %d", mo->num_materials);
  const double E0 = 200e9, E1 = 2e9, nu = 0.3;
  T_NEAR(mo->materials[0].bulk_modulus, E0 / (3 * (1 - 2 * nu)), 1e-15, 0, "material 0 K");
  T_NEAR(mo->materials[1].shear_modulus, E1 / (2 * (1 + nu)), 1e-15, 0, "material 1 G");
  T_NEAR(mo->materials[1].density, 1100, 0, 0, "material 1 density");
  T_NEAR(mo->materials[2].bulk_modulus, 5e9, 0, 0, "material 2 K");
  T_NEAR(mo->materials[2].shear_modulus, 2e9, 0, 0, "material 2 G");

  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const int32_t *mat = pdk_particles_field_data(p, "material", 0);
  T_ASSERT(mat, "no material field");
  int count[3] = {0, 0, 0}, wrong = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    const double x = pdk_particles_X(p, 0)[i], y = pdk_particles_X(p, 1)[i];
    int want = x >= 0.01 ? 1 : 0;
    if ((x - 0.015) * (x - 0.015) + (y - 0.002) * (y - 0.002) <= 0.0012 * 0.0012) want = 2;
    wrong += mat[i] != want;
    count[mat[i]]++;
  }
  T_ASSERT(!wrong && count[0] == 40 && count[1] > 0 && count[2] > 0,
           "materials by region: %d wrong, counts %d %d %d", wrong, count[0], count[1], count[2]);
  /* The stable step follows the stiffest material: below the soft-only bound, equal to the steel
   * one's within the Lanczos estimate's spread (5%). */
  const double dt = pdk_explicit_stable_dt(pdk_sim_explicit(sim));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  const char *steel[2] = {"materials=[]", "output.fields=[u]"};
  s = load(ctx, steel, 2);
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  const double dt_steel = pdk_explicit_stable_dt(pdk_sim_explicit(sim));
  T_ASSERT(!pdk_particles_field_exists(pdk_sim_particles(sim), "material"),
           "one material: no material field expected");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  T_NEAR(dt, dt_steel, 0.05, 0, "stable step of the three-material bar vs steel alone");

  load_fails(ctx, "model={kind: lps}", "materials", "lps");
  load_fails(ctx, "materials[1].name=soft", "materials[1].name", "already defined");
  load_fails(ctx, "materials[0].bulk_modulus=1e9", "materials[0]", "not a mix");
  load_fails(ctx, "materials[0].density=-1", "materials[0].density", "must be > 0");
  load_fails(ctx, "materials[1].poisson_ratio=0.3", "materials[1]", "not a mix");
  /* A region outside the body: an error when building, naming the entry. */
  const char *away[1] = {"materials[1].disk.center=[5, 5]"};
  s = load(ctx, away, 1);
  pdk_ctx_error_clear(ctx);
  T_ASSERT(pdk_sim_create(ctx, s, &sim) == PDK_ERR_ARG &&
               strstr(pdk_ctx_error_message(ctx), "materials[1]") &&
               strstr(pdk_ctx_error_message(ctx), "core"),
           "empty material region: '%s'", pdk_ctx_error_message(ctx));
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
  return 0;
}
