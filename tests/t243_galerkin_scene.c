/* Peridynamic Galerkin through a scene: model.kind galerkin with its options under
 * model.galerkin resolves to the C options, runs a Newton solve (a jittered 2-D block held at
 * x = 0 on rollers, pulled 1% at x = 2), and the keys are refused where they do not apply.
 * Checked: the options (basis, correction, surface); after the solve the held and pulled reactions
 * balance (Newton to 1e-12 of the load: 1e-9 relative) and the interior area vectors of the VC1
 * correction are round-off (<= 1e-12 of the surface's); the messages of the refusals.
 * labels: unit galerkin */
#include "pdk/scene.h"
#include "scene/scene_impl.h"
#include "test_util.h"

static const char *scene =
    "name: gbar\n"
    "dimension: 2\n"
    "geometry:\n"
    "  lattice: square\n"
    "  spacing: 0.1\n"
    "  horizon_factor: 2.51\n"
    "  jitter: 0.2\n"
    "  box: {lo: [0, 0], hi: [2, 1]}\n"
    "material: {density: 1, youngs_modulus: 1.0e5, poisson_ratio: 0.3}\n"
    "model:\n"
    "  kind: galerkin\n"
    "  law: linear_elastic\n"
    "  galerkin: {basis: taylor, form: bubnov, correction: vc1, surface: surface}\n"
    "sets:\n"
    "  - {name: surface, box: {lo: [0.1, 0.1], hi: [1.9, 0.9]}, invert: true}\n"
    "  - {name: held, box: {lo: [-1, -1], hi: [0.1, 2]}}\n"
    "  - {name: bottom, box: {lo: [-1, -1], hi: [3, 0.1]}}\n"
    "  - {name: pulled, box: {lo: [1.9, -1], hi: [3, 2]}}\n"
    "boundary_conditions:\n"
    "  - {set: held, type: displacement, x: 0}\n"
    "  - {set: bottom, type: displacement, y: 0}\n"
    "  - {set: pulled, type: displacement, x: 0.02}\n"
    "solver: {type: newton, load_steps: 1, tolerance: 1.0e-12}\n"
    "output: {reactions: [pulled, held]}\n";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  T_ASSERT(f, "cannot write %s", path);
  fputs(text, f);
  fclose(f);
}

static void refused(pdk_ctx *ctx, const char *const *ov, int nov, const char *needle) {
  pdk_scene *s = NULL;
  T_FAILS(ctx, pdk_scene_load(ctx, "t243.yaml", ov, nov, &s), PDK_ERR_ARG, needle);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  write_file("t243.yaml", scene);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t243.yaml", NULL, 0, &s));
  T_ASSERT(s->model.kind == PDK_MODEL_GALERKIN, "kind");
  T_ASSERT(s->model.galerkin.basis == PDK_GALERKIN_TAYLOR &&
               s->model.galerkin.correction == PDK_GALERKIN_VC1 &&
               !strcmp(s->model.galerkin.surface, "surface"),
           "model.galerkin resolved");
  T_ASSERT(s->model.stabilization == PDK_STAB_NONE, "galerkin scenes default to no stabilization");
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_history h;
  T_OK(ctx, pdk_sim_static_step(sim, &h));
  pdk_particles *p = pdk_sim_particles(sim);
  const uint8_t *surf = pdk_particles_field_data(p, "set:surface", 0);
  const double *A[2] = {pdk_particles_field_data(p, "area", 0),
                        pdk_particles_field_data(p, "area", 1)};
  double ai = 0.0, as = 0.0;
  for (pdk_index k = 0; k < pdk_particles_count(p); ++k) {
    const double a = hypot(A[0][k], A[1][k]);
    if (surf[k])
      as = fmax(as, a);
    else
      ai = fmax(ai, a);
  }
  T_INFO("reactions pulled %.9g held %.9g; interior |A| %.3e of %.3e\n", h.reaction[0][0],
         h.reaction[1][0], ai, as);
  T_ASSERT(ai <= 1e-12 * as, "interior area vectors %.3e of %.3e", ai, as);
  T_ASSERT(h.reaction[0][0] > 0, "the support pulls the end outward (%g)", h.reaction[0][0]);
  T_NEAR(h.reaction[1][0], -h.reaction[0][0], 1e-9, 0, "held balances pulled");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  {
    const char *ov[] = {"model.kind=correspondence"};
    refused(ctx, ov, 1, "model.galerkin: only the galerkin model uses it");
  }
  {
    const char *ov[] = {"model.galerkin.correction=none"};
    refused(ctx, ov, 1, "only the vc1 correction uses it");
  }
  {
    const char *ov[] = {"model.galerkin.basis=cubic"};
    refused(ctx, ov, 1, "model.galerkin.basis");
  }
  write_file("t243.yaml", "dimension: 2\n"
                          "geometry: {spacing: 0.1, box: {lo: [0, 0], hi: [1, 1]}}\n"
                          "material: {density: 1, youngs_modulus: 1.0e5, poisson_ratio: 0.3}\n"
                          "model: {kind: galerkin, galerkin: {correction: vc1}}\n"
                          "solver: {steps: 1}\n");
  refused(ctx, NULL, 0, "vc1 needs model.galerkin.surface");
  remove("t243.yaml");
  pdk_ctx_destroy(&ctx);
  return 0;
}
