/* The registry of model kinds and correspondence laws (src/models/model_registry.h) is the one place
 * that knows them: every registered kind has a name, operations for its options and the
 * capabilities it claims (a kind that claims an analytic tangent has one); every law has a
 * name and what its flags promise (an elastic law its Cauchy stress, a law with history its von
 * Mises); the names scenes accept for model.kind and model.law are the registry's, in its order;
 * and the scene messages built from the registry's capabilities read as they read when scene.c
 * spelled the kinds out, as do model creation's refusals decided by the kinds' entries (the texts
 * below are those of before the registry). pdk_model_opts_uses answers from the same entries.
 * labels: unit */
#include "models/model_impl.h"
#include "scene/scene_impl.h"
#include "test_util.h"

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  T_ASSERT(f, "cannot write %s", path);
  fputs(text, f);
  fclose(f);
}

static const char *minimal = "dimension: 2\n"
                             "geometry:\n"
                             "  spacing: 0.001\n"
                             "  box: {lo: [0, 0], hi: [0.006, 0.004]}\n"
                             "material: {density: 1000, bulk_modulus: 1.0e9}\n"
                             "solver: {steps: 3}\n";
static const char *elastic =
    "dimension: 2\n"
    "geometry:\n"
    "  spacing: 0.001\n"
    "  box: {lo: [0, 0], hi: [0.006, 0.004]}\n"
    "material: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}\n"
    "solver: {steps: 3}\n";
static const char *two_materials =
    "dimension: 2\n"
    "geometry:\n"
    "  spacing: 0.001\n"
    "  box: {lo: [0, 0], hi: [0.006, 0.004]}\n"
    "material: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}\n"
    "materials:\n"
    "  - {name: soft, box: {lo: [0.003, -1], hi: [1, 1]}, density: 900, bulk_modulus: 1.0e8}\n"
    "solver: {steps: 3}\n";

static void check_kinds(pdk_ctx *ctx) {
  int count = 0;
  for (int i = 0; pdk_model_kind_at(i); ++i, ++count) {
    const pdk_model_kind_info *k = pdk_model_kind_at(i);
    T_ASSERT(k->name && k->name[0], "kind %d has a name", i);
    T_ASSERT(pdk_model_kind_info_of(k->kind) == k, "%s: looked up by its value", k->name);
    T_ASSERT(!strcmp(pdk_model_kind_name(k->kind), k->name), "%s: pdk_model_kind_name", k->name);
    for (int j = 0; j < i; ++j)
      T_ASSERT(strcmp(pdk_model_kind_at(j)->name, k->name) && pdk_model_kind_at(j)->kind != k->kind,
               "%s: registered once", k->name);
    T_ASSERT(k->hops == 1 || k->hops == 2, "%s: coupling hops %d", k->name, k->hops);
    pdk_model_opts o = pdk_model_opts_default();
    o.kind = k->kind;
    const pdk_model_ops *ops = k->ops_for(&o);
    T_ASSERT(ops && ops->setup && ops->force, "%s: operations for its default options", k->name);
    T_ASSERT(!(k->caps & PDK_KIND_TANGENT) == !ops->tangent_column,
             "%s: claims an analytic tangent exactly when its operations have one", k->name);
    T_ASSERT(!k->derived || ops->derived, "%s: lists derived fields and computes them", k->name);
  }
  T_ASSERT(count >= 4, "pmb, lps, correspondence and oterkus are registered (%d kinds)", count);
  T_ASSERT(!strcmp(pdk_model_kind_name((pdk_model_kind)99), "?"), "an unknown kind's name");
  (void)ctx;
}

static void check_laws(void) {
  int count = 0;
  for (int i = 0; pdk_law_at(i); ++i, ++count) {
    const pdk_law_info *l = pdk_law_at(i);
    T_ASSERT(l->name && l->name[0], "law %d has a name", i);
    T_ASSERT(pdk_law_info_of(l->law) == l && !strcmp(pdk_law_name(l->law), l->name),
             "%s: looked up by its value", l->name);
    for (int j = 0; j < i; ++j)
      T_ASSERT(strcmp(pdk_law_at(j)->name, l->name) && pdk_law_at(j)->law != l->law,
               "%s: registered once", l->name);
    T_ASSERT(!l->von_mises != !l->cauchy, "%s: one way to its von Mises stress", l->name);
    T_ASSERT(!(l->flags & PDK_LAWF_HISTORY) == !l->von_mises,
             "%s: a law with history evaluates its own stress from it", l->name);
    T_ASSERT(!(l->flags & PDK_LAWF_ONE_MATERIAL) || l->one_material_why,
             "%s: says why it takes one material", l->name);
    T_ASSERT(!l->history_fields || l->history_hint, "%s: a hint for its history fields", l->name);
  }
  T_ASSERT(count >= 4, "four laws are registered (%d)", count);
}

/* A scene from `text` with overrides must load, or fail naming `needle`. */
static void load(pdk_ctx *ctx, const char *text, const char *const *ov, int nov, const char *needle,
                 pdk_scene **out) {
  write_file("t211.yaml", text);
  pdk_scene *s = NULL;
  if (needle) {
    T_FAILS(ctx, pdk_scene_load(ctx, "t211.yaml", ov, nov, &s), PDK_ERR_ARG, needle);
  } else {
    T_OK(ctx, pdk_scene_load(ctx, "t211.yaml", ov, nov, &s));
  }
  if (out)
    *out = s;
  else
    pdk_scene_destroy(&s);
}

/* model.kind and model.law take the registry's names; the messages built from its entries. */
static void check_scenes(pdk_ctx *ctx) {
  for (int i = 0; pdk_model_kind_at(i); ++i) {
    const pdk_model_kind_info *k = pdk_model_kind_at(i);
    if (!(k->caps & PDK_KIND_SCENE)) continue;
    char ov[64];
    snprintf(ov, sizeof ov, "model.kind=%s", k->name);
    const char *o[] = {ov};
    pdk_scene *s = NULL;
    load(ctx, elastic, o, 1, NULL, &s);
    T_ASSERT(s->model.kind == k->kind, "model.kind: %s", k->name);
    T_ASSERT(s->model.stabilization == k->scene_stabilization, "%s: default stabilization",
             k->name);
    pdk_scene_destroy(&s);
  }
  for (int i = 0; pdk_law_at(i); ++i) {
    const pdk_law_info *l = pdk_law_at(i);
    if (l->flags & PDK_LAWF_PLASTICITY) continue; /* needs material.johnson_cook */
    char ov[64];
    snprintf(ov, sizeof ov, "model.law=%s", l->name);
    const char *o[] = {"model.kind=correspondence", ov};
    pdk_scene *s = NULL;
    load(ctx, elastic, o, 2, NULL, &s);
    T_ASSERT(s->model.law == l->law, "model.law: %s", l->name);
    pdk_scene_destroy(&s);
  }
  {
    const char *o[] = {"model.kind=nonesuch"};
    load(ctx, elastic, o, 1, "pmb, lps, correspondence", NULL);
  }
  {
    const char *o[] = {"model.kind=pmb", "model.law=svk"};
    load(ctx, elastic, o, 2,
         "only the correspondence and galerkin models use it (model.kind is pmb); remove it "
         "or set model.kind: correspondence or galerkin",
         NULL);
  }
  {
    const char *o[] = {"model.kind=lps"};
    load(ctx, minimal, o, 1,
         "is missing; the lps model needs bulk_modulus and shear_modulus "
         "(only pmb needs the bulk modulus alone)",
         NULL);
  }
  {
    const char *o[] = {"model.kind=correspondence", "model.law=svk"};
    load(ctx, two_materials, o, 2, "shear_modulus (pmb: bulk_modulus alone), not a mix", NULL);
  }
  {
    const char *o[] = {"model.kind=lps"};
    load(ctx, two_materials, o, 1,
         "several materials are implemented for pmb, correspondence and oterkus, "
         "not lps; use one material or model.kind pmb, correspondence or oterkus",
         NULL);
  }
}

/* Model creation's refusals that the kinds' entries and operations now decide, with the texts
 * model.c spelled out before. */
static void check_refusals(pdk_ctx *ctx) {
  const char *ul[] = {"model.kind=correspondence", "model.connectivity=ul", "model.stencil=on"};
  const char *hg[] = {"model.kind=correspondence", "model.stabilization=hourglass",
                      "model.stencil=on"};
  const char *sell[] = {"model.kind=correspondence", "model.layout=sell"};
  const char *const *ov[] = {ul, hg, sell};
  const char *want[] = {
      "correspondence model with ul connectivity: the stencil path implements tl only (ul "
      "rebuilds its families in the current configuration); use stencil off or auto, or "
      "connectivity tl",
      "correspondence model with hourglass stabilization: the stencil path implements "
      "stabilization none and silling only (the hourglass force needs |Y| per bond); use "
      "stencil off or auto, or stabilization silling",
      "correspondence model: layout sell is implemented for pmb and lps (LAMMPS's omega) only; "
      "use layout csr"};
  for (int k = 0; k < 3; ++k) {
    pdk_scene *s = NULL;
    pdk_sim *sim = NULL;
    load(ctx, elastic, ov[k], k == 2 ? 2 : 3, NULL, &s);
    T_FAILS(ctx, pdk_sim_create(ctx, s, &sim), PDK_ERR_UNSUPPORTED, want[k]);
    pdk_scene_destroy(&s);
  }
}

static void check_uses(void) {
  pdk_model_opts o = pdk_model_opts_default();
  T_ASSERT(!pdk_model_opts_uses(&o, "law") && !pdk_model_opts_uses(&o, "influence"),
           "pmb takes no law and no influence function");
  T_ASSERT(pdk_model_opts_uses(&o, "critical_stretch"), "an option every kind takes");
  o.kind = PDK_MODEL_CORRESPONDENCE;
  T_ASSERT(pdk_model_opts_uses(&o, "law") && pdk_model_opts_uses(&o, "connectivity"),
           "correspondence takes a law and a connectivity");
  T_ASSERT(!pdk_model_opts_uses(&o, "break_stress"), "an elastic law has no history to remap");
  o.law = PDK_LAW_JC;
  T_ASSERT(pdk_model_opts_uses(&o, "break_stress") && pdk_model_opts_uses(&o, "stab_softening"),
           "jc: its history options");
  o.connectivity = PDK_CONNECTIVITY_UL;
  T_ASSERT(!pdk_model_opts_uses(&o, "break_stress"), "ul breaks no bonds");
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  check_kinds(ctx);
  check_laws();
  check_scenes(ctx);
  check_refusals(ctx);
  check_uses();
  remove("t211.yaml");
  pdk_ctx_destroy(&ctx);
  return 0;
}
