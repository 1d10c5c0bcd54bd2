/* Scene errors of the ductile keys (material.johnson_cook, model.law: jc, model.connectivity,
 * model.compact_fraction, model.failed_keeps_bonds, model.stabilization_softening(_floor),
 * model.damage_triaxiality, model.break_stress, output field von_mises), one case per kind of
 * mistake, in the form of t061: each case edits a small valid Johnson-Cook scene, and the message
 * must read
 *   <file>:<line>: <key.path>: ...      (or <file>: --set <override>: <key.path>: ...)
 * with the line of the offending key, marked "#<" in the case's text (no mark: line 1), and say
 * what is allowed.
 * labels: unit */
#include "pdk/scene.h"
#include "test_util.h"

static const char *base_scene = "dimension: 2\n"
                                "geometry:\n"
                                "  spacing: 1.0e-3\n"
                                "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                                "material:\n"
                                "  density: 7830\n"
                                "  youngs_modulus: 200e9\n"
                                "  poisson_ratio: 0.29\n"
                                "  johnson_cook:\n"
                                "    A: 792e6\n"
                                "    B: 510e6\n"
                                "    n: 0.26\n"
                                "    D1: 0.05\n"
                                "    D2: 3.44\n"
                                "    D3: -2.12\n"
                                "    D_c: 0.3\n"
                                "model:\n"
                                "  kind: correspondence\n"
                                "  law: jc\n"
                                "solver:\n"
                                "  steps: 10\n";

enum { AT_LOAD = 0, AT_BUILD = 1 };

typedef struct error_case {
  const char *what;
  const char *find, *replace; /* edit of base_scene; both NULL: the base scene */
  const char *override;       /* NULL or one "key=value" */
  int stage;
  int code;
  const char *key;
  const char *needle;
} error_case;

static const error_case cases[] = {
    /* presence */
    {"johnson_cook with an elastic law", "  law: jc\n", "  law: neo_hooke\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.johnson_cook", "only the jc law uses it"},
    {"jc law without johnson_cook",
     "  johnson_cook:\n    A: 792e6\n    B: 510e6\n    n: 0.26\n    D1: 0.05\n    D2: 3.44\n"
     "    D3: -2.12\n    D_c: 0.3\n",
     "", NULL, AT_LOAD, PDK_ERR_ARG, "material.johnson_cook", "give the Johnson-Cook parameters"},
    {"jc law with pmb", "  kind: correspondence\n", "  kind: pmb\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "model.law", "only the correspondence and galerkin models"},
    {"missing A", "    A: 792e6\n", "", NULL, AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.A",
     "required key is missing"},
    {"unknown Johnson-Cook key", "    D_c: 0.3\n", "    D_c: 0.3\n    D6: 1 #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.johnson_cook.D6", "allows: A, B, n, C"},
    {"word for a number", "    n: 0.26", "    n: hard #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.n", "must be a number"},
    /* ranges */
    {"negative B", "    B: 510e6", "    B: -1 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.B", "must be >= 0"},
    {"n zero", "    n: 0.26", "    n: 0 #<", NULL, AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.n",
     "must be > 0"},
    {"A and B zero", "    A: 792e6\n    B: 510e6", "    A: 0\n    B: 0 #<", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.johnson_cook.B", "A + B > 0"},
    {"negative C", "    D_c: 0.3\n", "    D_c: 0.3\n    C: -0.1 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.C", "must be >= 0"},
    {"D_c above 1", "    D_c: 0.3", "    D_c: 1.5 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.D_c", "(0, 1]"},
    {"D1 + D2 not positive", "    D2: 3.44", "    D2: -0.05 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.D2", "must be > 0"},
    {"negative D4", "    D_c: 0.3\n", "    D_c: 0.3\n    D4: -1 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.D4", "must be >= 0"},
    {"beta above 1", "    D_c: 0.3\n",
     "    D_c: 0.3\n    thermal: true\n    m: 1\n    T_room: 293\n    T_melt: 1793\n"
     "    heat_capacity: 477\n    beta: 1.5 #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.beta", "[0, 1]"},
    {"T_melt below T_room", "    D_c: 0.3\n",
     "    D_c: 0.3\n    thermal: true\n    m: 1\n    T_room: 293\n    T_melt: 200 #<\n"
     "    heat_capacity: 477\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.T_melt", "must exceed T_room"},
    /* required with an option, unused without it */
    {"damage without D_c", "    D_c: 0.3\n", "", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.D_c", "is missing; damage is on"},
    {"D1 with damage off", "    D_c: 0.3\n", "    D_c: 0.3\n    damage: false\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.johnson_cook.D1", "only used with damage"},
    {"thermal without heat capacity", "    D_c: 0.3\n",
     "    D_c: 0.3\n    thermal: true\n    m: 1\n    T_room: 293\n    T_melt: 1793\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.heat_capacity", "is missing; thermal is true"},
    {"thermal key without thermal", "    D_c: 0.3\n", "    D_c: 0.3\n    T_melt: 1793 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.T_melt", "thermal is false"},
    {"reference rate without a rate term", "    D_c: 0.3\n",
     "    D_c: 0.3\n    reference_strain_rate: 1 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.reference_strain_rate", "C and D4 are 0"},
    {"D5 without thermal", "    D_c: 0.3\n", "    D_c: 0.3\n    D5: 0.61 #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.johnson_cook.D5", "thermal: true"},
    /* words */
    {"unknown coupling", "    D_c: 0.3\n", "    D_c: 0.3\n    coupling: lemaitre #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.coupling", "allowed: none, effective"},
    {"unknown failed mode", "    D_c: 0.3\n", "    D_c: 0.3\n    failed_mode: gone #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "material.johnson_cook.failed_mode", "allowed: zero, compression"},
    {"unknown connectivity", "  law: jc\n", "  law: jc\n  connectivity: eulerian #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "model.connectivity", "allowed: tl, semi_tl, ul"},
    /* model keys */
    {"connectivity with lps", "  kind: correspondence\n  law: jc\n",
     "  kind: lps\n  connectivity: tl #<\n", NULL, AT_LOAD, PDK_ERR_ARG, "model.connectivity",
     "only the correspondence model"},
    {"compact_fraction in TL", "  law: jc\n", "  law: jc\n  compact_fraction: 0.1 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "model.compact_fraction", "only semi_tl"},
    {"compact_fraction above 1", "  law: jc\n",
     "  law: jc\n  connectivity: semi_tl\n  compact_fraction: 2 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "model.compact_fraction", "[0, 1]"},
    {"failed_keeps_bonds with an elastic law", NULL, NULL, NULL, AT_LOAD, PDK_ERR_ARG,
     "model.failed_keeps_bonds", "only the jc law"},
    {"failed_keeps_bonds without damage", NULL, NULL, NULL, AT_LOAD, PDK_ERR_ARG,
     "model.failed_keeps_bonds", "damage is false"},
    {"ul with failed particles breaking bonds", "  law: jc\n", "  law: jc\n  connectivity: ul\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.connectivity", "failed_keeps_bonds: true"},
    {"ul_skin in TL", "  law: jc\n", "  law: jc\n  ul_skin: 0.5 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "model.ul_skin", "only ul connectivity"},
    {"softening without silling stabilization", "  law: jc\n",
     "  law: jc\n  stabilization: none\n  stabilization_softening: plastic #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "model.stabilization_softening", "stabilization silling"},
    {"softening in ul", "  law: jc\n",
     "  law: jc\n  connectivity: ul\n  failed_keeps_bonds: true\n"
     "  stabilization_softening: plastic #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.stabilization_softening", "not ul"},
    {"unknown softening", "  law: jc\n", "  law: jc\n  stabilization_softening: elastic #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.stabilization_softening", "allowed: none, plastic"},
    {"softening floor without softening", "  law: jc\n",
     "  law: jc\n  stabilization_softening_floor: 0.01 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "model.stabilization_softening_floor", "only used with model.stabilization_softening"},
    {"softening floor 0", "  law: jc\n",
     "  law: jc\n  stabilization_softening: plastic\n  stabilization_softening_floor: 0 #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.stabilization_softening_floor", "(0, 1]"},
    {"damage_triaxiality without damage", NULL, NULL, NULL, AT_LOAD, PDK_ERR_ARG,
     "model.damage_triaxiality", "damage on"},
    {"unknown damage_triaxiality", "  law: jc\n", "  law: jc\n  damage_triaxiality: nonlocal #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.damage_triaxiality", "allowed: local, family"},
    {"damage_triaxiality in ul", "  law: jc\n",
     "  law: jc\n  connectivity: ul\n  failed_keeps_bonds: true\n  damage_triaxiality: family #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.damage_triaxiality", "not ul"},
    {"break_stress with an elastic law", NULL, NULL, NULL, AT_LOAD, PDK_ERR_ARG,
     "model.break_stress", "model.law jc"},
    {"unknown break_stress", "  law: jc\n", "  law: jc\n  break_stress: smooth #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "model.break_stress", "allowed: refit, continuous"},
    {"break_stress in ul", "  law: jc\n",
     "  law: jc\n  connectivity: ul\n  failed_keeps_bonds: true\n  break_stress: continuous #<\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "model.break_stress", "not ul"},
    {"break_stress when nothing breaks", "  law: jc\n",
     "  law: jc\n  failed_keeps_bonds: true\n  break_stress: continuous #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "model.break_stress", "none can here"},
    /* output fields */
    {"von_mises with pmb", NULL, NULL, NULL, AT_BUILD, PDK_ERR_ARG, "output.fields[0]",
     "correspondence"},
    {"eps_p with an elastic law", NULL, NULL, NULL, AT_BUILD, PDK_ERR_NOT_FOUND, "output.fields[0]",
     "set model.law: jc"},
    /* overrides */
    {"override of D_c", NULL, NULL, "material.johnson_cook.D_c=0", AT_LOAD, PDK_ERR_ARG,
     "material.johnson_cook.D_c", "(0, 1]"},
    {"override of connectivity", NULL, NULL, "model.connectivity=semi", AT_LOAD, PDK_ERR_ARG,
     "model.connectivity", "allowed: tl, semi_tl, ul"},
};

/* A Johnson-Cook scene without damage whose model block ends with `line`. */
#define NO_DAMAGE_SCENE(line)                                                                      \
  "dimension: 2\n"                                                                                 \
  "geometry:\n"                                                                                    \
  "  spacing: 1.0e-3\n"                                                                            \
  "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"                                                        \
  "material:\n"                                                                                    \
  "  density: 7830\n"                                                                              \
  "  youngs_modulus: 200e9\n"                                                                      \
  "  poisson_ratio: 0.29\n"                                                                        \
  "  johnson_cook: {A: 792e6, B: 510e6, n: 0.26, damage: false}\n"                                 \
  "model:\n"                                                                                       \
  "  kind: correspondence\n"                                                                       \
  "  law: jc\n" line "solver:\n"                                                                   \
  "  steps: 10\n"

/* A Neo-Hooke correspondence scene whose model block ends with `line`. */
#define ELASTIC_CORR_SCENE(line)                                                                   \
  "dimension: 2\n"                                                                                 \
  "geometry:\n"                                                                                    \
  "  spacing: 1.0e-3\n"                                                                            \
  "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"                                                        \
  "material: {density: 7830, youngs_modulus: 200e9, poisson_ratio: 0.25}\n"                        \
  "model:\n"                                                                                       \
  "  kind: correspondence\n"                                                                       \
  "  law: neo_hooke\n" line "solver:\n"                                                            \
  "  steps: 10\n"

/* Scenes of the cases that need more than one edit. */
static const char *special_text(const char *what) {
  if (!strcmp(what, "failed_keeps_bonds without damage"))
    return NO_DAMAGE_SCENE("  failed_keeps_bonds: false #<\n");
  if (!strcmp(what, "damage_triaxiality without damage"))
    return NO_DAMAGE_SCENE("  damage_triaxiality: family #<\n");
  if (!strcmp(what, "break_stress with an elastic law"))
    return ELASTIC_CORR_SCENE("  critical_stretch: 0.1\n  break_stress: continuous #<\n");
  if (!strcmp(what, "failed_keeps_bonds with an elastic law"))
    return ELASTIC_CORR_SCENE("  failed_keeps_bonds: true #<\n");
  if (!strcmp(what, "von_mises with pmb"))
    return "dimension: 2\n"
           "geometry:\n"
           "  spacing: 1.0e-3\n"
           "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
           "material: {density: 7830, youngs_modulus: 200e9, poisson_ratio: 0.25}\n"
           "solver:\n"
           "  steps: 10\n"
           "output:\n"
           "  fields: [von_mises] #<\n";
  if (!strcmp(what, "eps_p with an elastic law"))
    return "dimension: 2\n"
           "geometry:\n"
           "  spacing: 1.0e-3\n"
           "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
           "material: {density: 7830, youngs_modulus: 200e9, poisson_ratio: 0.25}\n"
           "model: {kind: correspondence, law: neo_hooke}\n"
           "solver:\n"
           "  steps: 10\n"
           "output:\n"
           "  fields: [eps_p] #<\n";
  return NULL;
}

static char *edit(const char *text, const char *find, const char *repl) {
  if (!find) return strdup(text);
  const char *at = strstr(text, find);
  if (!at) T_FAIL("case text: '%s' not found in the base scene", find);
  size_t n = strlen(text) - strlen(find) + strlen(repl) + 1;
  char *out = malloc(n);
  size_t head = (size_t)(at - text);
  memcpy(out, text, head);
  strcpy(out + head, repl);
  strcat(out, at + strlen(find));
  return out;
}

static int marked_line(const char *text) {
  const char *mark = strstr(text, "#<");
  if (!mark) return 1;
  int line = 1;
  for (const char *c = text; c < mark; ++c)
    line += *c == '\n';
  return line;
}

/* 1-based line of the first "name:" that starts a key (after a space, '{' or a line start), or 0.
 */
static int key_line_of(const char *text, const char *name) {
  char pat[160];
  snprintf(pat, sizeof pat, "%s:", name);
  for (const char *at = strstr(text, pat); at; at = strstr(at + 1, pat)) {
    if (at != text && at[-1] != ' ' && at[-1] != '\n' && at[-1] != '{') continue;
    int line = 1;
    for (const char *c = text; c < at; ++c)
      line += *c == '\n';
    return line;
  }
  return 0;
}

/* Without a mark: the line of the key, or for an absent key (a default, or deleted by the case)
 * the line of its nearest present parent. */
static int key_line(const char *text, const char *key) {
  char path[128];
  snprintf(path, sizeof path, "%s", key);
  for (;;) {
    const char *last = strrchr(path, '.');
    const int line = key_line_of(text, last ? last + 1 : path);
    if (line) return line;
    char *dot = strrchr(path, '.');
    if (!dot) return 1;
    *dot = '\0';
  }
}

static void run_case(pdk_ctx *ctx, int k, const error_case *c) {
  char path[64];
  snprintf(path, sizeof path, "t063_case%02d.yaml", k);
  const char *special = special_text(c->what);
  char *text = special ? strdup(special) : edit(base_scene, c->find, c->replace);
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing %s", path);

  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  const char *ov[1] = {c->override};
  pdk_ctx_error_clear(ctx);
  int err = pdk_scene_load(ctx, path, ov, c->override ? 1 : 0, &s);
  if (c->stage == AT_BUILD) {
    if (err) T_FAIL("case '%s': load failed: %s", c->what, pdk_ctx_error_message(ctx));
    err = pdk_sim_create(ctx, s, &sim);
    T_ASSERT(sim == NULL || err == 0, "case '%s': sim set on failure", c->what);
  } else {
    T_ASSERT(!err || s == NULL, "case '%s': scene set on failure", c->what);
  }
  const char *msg = pdk_ctx_error_message(ctx);
  if (err != c->code)
    T_FAIL("case '%s': returned %d, expected %d; message: %s", c->what, err, c->code, msg);
  char want[512];
  if (c->override)
    snprintf(want, sizeof want, "%s: --set %s: %s: ", path, c->override, c->key);
  else {
    const int line = strstr(text, "#<") ? marked_line(text) : key_line(text, c->key);
    snprintf(want, sizeof want, "%s:%d: %s: ", path, line, c->key);
  }
  if (!strstr(msg, want))
    T_FAIL("case '%s': message does not start with '%s':\n  %s", c->what, want, msg);
  if (c->needle && !strstr(msg, c->needle))
    T_FAIL("case '%s': message does not mention '%s':\n  %s", c->what, c->needle, msg);
  if (!strchr(msg, ';') && !strstr(msg, "must"))
    T_FAIL("case '%s': message does not say what is allowed:\n  %s", c->what, msg);
  if (getenv("PDK_TEST_VERBOSE")) printf("%-40s %s\n", c->what, msg);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  free(text);
  remove(path);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const int n = (int)(sizeof cases / sizeof cases[0]);
  for (int k = 0; k < n; ++k)
    run_case(ctx, k, &cases[k]);
  /* The base scene itself is valid and builds. */
  FILE *f = fopen("t063_base.yaml", "wb");
  T_ASSERT(f && fputs(base_scene, f) >= 0 && !fclose(f), "writing t063_base.yaml");
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t063_base.yaml", NULL, 0, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove("t063_base.yaml");
  pdk_ctx_destroy(&ctx);
  return 0;
}
