/* The stencil path refuses a horizon of billions of spacings with the reach it measured, and
 * computes that reach without overflowing. The reach (horizon / spacing, rounded up) was converted
 * to int before the range check: a horizon_factor of 2.15e9 or more made the conversion and the
 * side 2 R + 1 of the offset table overflow (undefined behaviour; UBSan stops there, a release
 * build reported a bond spanning "0 spacings" and went on). A horizon is allowed any size (docs:
 * horizon_factor > 1), so only the stencil path refuses, naming the reach and its limit of 64;
 * auto takes the general path.
 * Cases: the C API (a 4 x 3 square lattice, families of every pair) with model.stencil on for PMB
 * and LPS, horizons of 3e9, 2.15e9 and 1e300 spacings, and 65.5 (just beyond the limit); auto
 * with 3e9 falls back with the same reason; a scene with --set geometry.horizon_factor=3e9 and
 * model.stencil=on fails at pdk_sim_create naming the reach. Run under the sanitizer build too
 * (no UB on the way).
 * labels: unit
 */
#include "bond_models_test.h"
#include "pdk/scene.h"

static void refused(pdk_ctx *ctx, int kind, double factor, const char *needle) {
  pdk_particles *p = bm_body(ctx, 2, 4, 3, 1, 1.0, 0.0, 0.0, 1);
  pdk_families *fam = bm_families(ctx, p, factor);
  T_ASSERT(pdk_families_num_bonds(fam) == 12 * 11, "every pair is a bond: %lld",
           (long long)pdk_families_num_bonds(fam));
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = (pdk_model_kind)kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.stencil = PDK_STENCIL_ON;
  pdk_model *m = NULL;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, needle);
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "more than 64"), "the limit is named: %s",
           pdk_ctx_error_message(ctx));
  T_ASSERT(!m, "no model on failure");
  o.stencil = PDK_STENCIL_AUTO;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(!pdk_model_stencil_active(m) && strstr(pdk_model_stencil_reason(m), needle),
           "auto falls back naming the reach: '%s'", pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
    refused(ctx, kind, 3e9, "the horizon spans 3e+09 spacings");
    refused(ctx, kind, 2.15e9, "the horizon spans 2.15e+09 spacings");
    refused(ctx, kind, 1e300, "the horizon spans 1e+300 spacings");
    refused(ctx, kind, 65.5, "the horizon spans 66 spacings");
  }
  /* the scene path */
  char path[1024];
  snprintf(path, sizeof path, "%s/tests/scenes/t060_minimal.yaml", getenv("PDK_SOURCE_DIR"));
  const char *ov[2] = {"geometry.horizon_factor=3e9", "model.stencil=on"};
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 2, &s));
  T_FAILS(ctx, pdk_sim_create(ctx, s, &sim), PDK_ERR_UNSUPPORTED,
          "the horizon spans 3e+09 spacings");
  T_ASSERT(!sim, "no simulation on failure");
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
  return 0;
}
