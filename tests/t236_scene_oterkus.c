/* The Oterkus dilatation law through a scene: model.kind oterkus (2-D plane strain), its option
 * model.oterkus_a and the influence function quadratic resolve to the C options; a Newton solve of
 * a 2 x 1 block (particles at 0.05 .. 1.95) whose first column is held in x and whose last is
 * pulled 0.002 in x (strain 0.002 / 1.9) balances, has a modulus between the continuum's bounds,
 * and depends on oterkus_a (the key reaches the model); the keys are refused where they do not
 * apply.
 * Checked: the resolved options; reactions held = -pulled to 1e-9 (Newton to 1e-12); the strip's
 * modulus (reaction / height / strain) between 0.9 E / (1 - nu^2) (a free strip) and 1.1 E (1 -
 * nu) / ((1 + nu)(1 - 2 nu)) (sides held: the stiffest a homogeneous strip can be), the 10% for
 * a strip only 10 spacings wide with horizon 3. Measured: oterkus calibrated 1.25 E / (1 - nu^2),
 * 1.02 of the held-sides bound (the same scene gives 1.14 with lps and 0.98 with correspondence);
 * published and calibrated differ by more than 1e-3 relative; the messages of the refusals.
 * labels: unit */
#define _DEFAULT_SOURCE /* strdup */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pdk/scene.h"
#include "scene/scene_impl.h"
#include "test_util.h"

static const char *scene =
    "name: obar\n"
    "dimension: 2\n"
    "geometry:\n"
    "  lattice: square\n"
    "  spacing: 0.1\n"
    "  horizon_factor: 3.015\n"
    "  box: {lo: [0, 0], hi: [2, 1]}\n"
    "material: {density: 1, youngs_modulus: 1.0e5, poisson_ratio: 0.3}\n"
    "model:\n"
    "  kind: oterkus\n"
    "  influence: quadratic\n"
    "  oterkus_a: calibrated\n"
    "sets:\n"
    "  - {name: held, box: {lo: [-1, -1], hi: [0.05, 2]}}\n"
    "  - {name: bottom, box: {lo: [-1, -1], hi: [0.05, 0.05]}}\n"
    "  - {name: pulled, box: {lo: [1.95, -1], hi: [3, 2]}}\n"
    "boundary_conditions:\n"
    "  - {set: held, type: displacement, x: 0}\n"
    "  - {set: bottom, type: displacement, y: 0}\n"
    "  - {set: pulled, type: displacement, x: 0.002}\n"
    "solver: {type: newton, load_steps: 1, tolerance: 1.0e-12}\n"
    "output: {reactions: [pulled, held]}\n";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  T_ASSERT(f, "cannot write %s", path);
  fputs(text, f);
  fclose(f);
}

/* Loads t236.yaml with the overrides, solves, returns the pulled set's reaction along x. */
static double solve(pdk_ctx *ctx, const char *const *ov, int nov, pdk_oterkus_a want) {
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t236.yaml", ov, nov, &s));
  T_ASSERT(s->model.kind == PDK_MODEL_OTERKUS, "model.kind oterkus resolved");
  T_ASSERT(s->model.influence == PDK_INFLUENCE_QUADRATIC, "model.influence quadratic resolved");
  T_ASSERT(s->model.oterkus_a == want, "model.oterkus_a resolved to %d", (int)want);
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_history h;
  T_OK(ctx, pdk_sim_static_step(sim, &h));
  T_INFO("oterkus_a %d: reactions pulled %.9g held %.9g\n", (int)want, h.reaction[0][0],
         h.reaction[1][0]);
  T_ASSERT(h.reaction[0][0] > 0, "the support pulls the end outward (%g)", h.reaction[0][0]);
  T_NEAR(h.reaction[1][0], -h.reaction[0][0], 1e-9, 0, "held balances pulled");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  return h.reaction[0][0];
}

static void refused(pdk_ctx *ctx, const char *const *ov, int nov, const char *needle) {
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  int err = pdk_scene_load(ctx, "t236.yaml", ov, nov, &s);
  if (!err) {
    err = pdk_sim_create(ctx, s, &sim);
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&s);
  }
  T_ASSERT(err != 0, "refused: %s", needle);
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), needle), "message '%s' lacks '%s'",
           pdk_ctx_error_message(ctx), needle);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  write_file("t236.yaml", scene);
  const double calibrated = solve(ctx, NULL, 0, PDK_OTERKUS_A_CALIBRATED);
  const char *pub[] = {"model.oterkus_a=published"};
  const double published = solve(ctx, pub, 1, PDK_OTERKUS_A_PUBLISHED);
  /* reaction per unit thickness over the strip's height 1, strain 0.002 / 1.9 */
  const double E = 1.0e5, nu = 0.3, modulus = calibrated / 1.0 / (0.002 / 1.9);
  const double lo = E / (1 - nu * nu), hi = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  T_INFO("strip modulus %.6g: %.4f of E/(1-nu^2), %.4f of the held-sides modulus; "
         "published/calibrated %.4f\n",
         modulus, modulus / lo, modulus / hi, published / calibrated);
  T_ASSERT(modulus > 0.9 * lo && modulus < 1.1 * hi, "strip modulus %g outside [%g, %g]", modulus,
           0.9 * lo, 1.1 * hi);
  T_ASSERT(fabs(published / calibrated - 1) > 1e-3,
           "oterkus_a must reach the model: reactions %g and %g", published, calibrated);
  {
    const char *ov[] = {"model.kind=lps"};
    refused(ctx, ov, 1, "model.influence: only the correspondence and oterkus models use it");
  }
  {
    const char *ov[] = {"model.oterkus_a=exact"};
    refused(ctx, ov, 1, "model.oterkus_a");
  }
  {
    /* the same scene without the influence line, as pmb: oterkus_a is refused */
    char *text = strdup(scene);
    char *line = strstr(text, "  influence: quadratic\n");
    memmove(line, line + strlen("  influence: quadratic\n"),
            strlen(line + strlen("  influence: quadratic\n")) + 1);
    write_file("t236.yaml", text);
    free(text);
    const char *ov[] = {"model.kind=pmb"};
    refused(ctx, ov, 1, "model.oterkus_a: only the oterkus model uses it");
  }
  remove("t236.yaml");
  pdk_ctx_destroy(&ctx);
  return 0;
}
