/* Scene errors: one case per kind of mistake. Each case edits a small valid scene, writes it, and
 * checks the status code and that the message has the form
 *   <file>:<line>: <key.path>: ...      (or <file>: --set <override>: <key.path>: ...)
 * with the line of the offending key, marked "#<" in the case's text (no mark: line 1).
 * Load errors come from pdk_scene_load, the rest (sets that select nothing, dt above the stable
 * step, conflicting conditions) from pdk_sim_create.
 * labels: unit */
#include "pdk/scene.h"
#include "test_util.h"

static const char *base_scene = "dimension: 2\n"
                                "geometry:\n"
                                "  spacing: 1.0e-3\n"
                                "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                                "material:\n"
                                "  density: 7850\n"
                                "  youngs_modulus: 200e9\n"
                                "  poisson_ratio: 0.3\n"
                                "sets:\n"
                                "  - name: bottom\n"
                                "    box: {lo: [-1, -1], hi: [1, 0.0012]}\n"
                                "  - name: top\n"
                                "    box: {lo: [-1, 0.0188], hi: [1, 1]}\n"
                                "boundary_conditions:\n"
                                "  - {set: bottom, type: displacement, x: 0, y: 0}\n"
                                "  - {set: top, type: velocity, y: 1.0}\n"
                                "solver:\n"
                                "  steps: 10\n";

enum { AT_LOAD = 0, AT_BUILD = 1 };

typedef struct error_case {
  const char *what;
  const char *find, *replace; /* edit of base_scene; find NULL: replace is the whole text */
  const char *override;       /* NULL or one "key=value" */
  int stage;                  /* AT_LOAD or AT_BUILD */
  int code;
  const char *key;    /* key path the message must name */
  const char *needle; /* another part the message must contain (may be NULL) */
} error_case;

static const error_case cases[] = {
    /* unknown keys */
    {"unknown top-level key", "solver:\n", "geometri: 1 #<\nsolver:\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "geometri", "allows: name, description, dimension, geometry"},
    {"unknown nested key", "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  spaceing: 2 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "geometry.spaceing", "geometry allows: lattice, spacing"},
    {"unknown key in a list entry", "{set: top, type: velocity, y: 1.0}",
     "{set: top, type: velocity, y: 1.0, fnction: ramp} #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "boundary_conditions[1].fnction", "function"},
    /* wrong types */
    {"list for a number", "  spacing: 1.0e-3", "  spacing: [1, 2] #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "geometry.spacing", "must be a number, got a list"},
    {"word for a number", "  density: 7850", "  density: heavy #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "got 'heavy'"},
    {"number for a mapping",
     "material:\n  density: 7850\n  youngs_modulus: 200e9\n  poisson_ratio: 0.3\n",
     "material: 5 #<\n", NULL, AT_LOAD, PDK_ERR_ARG, "material", "must be a mapping"},
    {"unknown enum word", "{set: top, type: velocity, y: 1.0}",
     "{set: top, type: speed, y: 1.0} #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "boundary_conditions[1].type", "allowed: displacement, velocity, body_force"},
    {"3 numbers in a 2-D point", "hi: [0.01, 0.02]}", "hi: [0.01, 0.02, 0.03]} #<", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.box.hi", "must have 2 numbers"},
    {"whole number expected", "  steps: 10", "  steps: 10.5 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "solver.steps", "whole number"},
    {"key given twice", "  density: 7850\n", "  density: 7850\n  density: 7800 #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "material.density", "twice"},
    /* missing keys */
    {"missing nested key", "geometry:\n  spacing: 1.0e-3\n", "geometry: #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.spacing", "required key is missing"},
    {"missing top-level key", "solver:\n  steps: 10\n", "", NULL, AT_LOAD, PDK_ERR_ARG, "solver",
     "required key is missing"},
    {"missing modulus",
     "material:\n  density: 7850\n  youngs_modulus: 200e9\n  poisson_ratio: 0.3\n",
     "material: #<\n  density: 7850\n  youngs_modulus: 200e9\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.poisson_ratio", "youngs_modulus is given"},
    {"ramp without duration", "{set: top, type: velocity, y: 1.0}",
     "{set: top, type: velocity, y: 1.0, function: ramp} #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "boundary_conditions[1].duration", "duration > 0"},
    /* out of range */
    {"negative spacing", "  spacing: 1.0e-3", "  spacing: -0.001 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "geometry.spacing", "must be > 0, got -0.001"},
    {"jitter 0.5", "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  jitter: 0.5 #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.jitter", "[0, 0.5)"},
    {"poisson 0.5", "  poisson_ratio: 0.3", "  poisson_ratio: 0.5 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.poisson_ratio", "(-1, 0.5)"},
    {"horizon factor 1", "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  horizon_factor: 1 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "geometry.horizon_factor", "must be > 1"},
    {"dimension 4", "dimension: 2", "dimension: 4 #<", NULL, AT_LOAD, PDK_ERR_ARG, "dimension",
     "must be 2 or 3"},
    /* inconsistent */
    {"3-D lattice in 2-D", "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  lattice: cubic #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "geometry.lattice", "use square or hex"},
    {"hole outside the plate", "  spacing: 1.0e-3\n",
     "  spacing: 1.0e-3\n  holes:\n    - disk: {center: [0.009, 0.01], radius: 0.002} #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "geometry.holes[0].disk", "outside the body"},
    {"hole covering everything", "  spacing: 1.0e-3\n",
     "  spacing: 1.0e-3\n  holes: [{box: {lo: [-1, -1], hi: [1, 1]}}] #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.holes[0].box", "whole body"},
    {"hole between lattice points", "  spacing: 1.0e-3\n",
     "  spacing: 1.0e-3\n  holes: [{disk: {center: [0.005, 0.01], radius: 1e-5}}] #<\n", NULL,
     AT_BUILD, PDK_ERR_ARG, "geometry.holes[0].disk", "removes no particle"},
    {"condition names an unknown set", "{set: top, type: velocity, y: 1.0}",
     "{set: topp, type: velocity, y: 1.0} #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "boundary_conditions[1].set", "defined sets: bottom, top"},
    {"z in a 2-D scene", "x: 0, y: 0}", "x: 0, z: 0} #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "boundary_conditions[0].z", "2-D"},
    {"E with K", "  poisson_ratio: 0.3\n", "  poisson_ratio: 0.3\n  bulk_modulus: 1e9 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "material.bulk_modulus", "either youngs_modulus and poisson_ratio"},
    {"correspondence key with pmb", "solver:\n", "model: {influence: cubic} #<\nsolver:\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "model.influence", "only the correspondence and oterkus models"},
    {"duplicate set name", "  - name: top\n", "  - name: bottom #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "sets[1].name", "already defined"},
    {"set selects nothing", "  - name: top\n    box: {lo: [-1, 0.0188], hi: [1, 1]}\n",
     "  - name: top #<\n    box: {lo: [-1, 5], hi: [1, 6]}\n", NULL, AT_BUILD, PDK_ERR_ARG,
     "sets[1]", "top"},
    {"unknown dt_update", "  steps: 10\n", "  steps: 10\n  dt_update: always #<\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "solver.dt_update", "allowed: none, breaks, periodic"},
    {"dt_update_interval without dt_update", "  steps: 10\n",
     "  steps: 10\n  dt_update_interval: 50 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "solver.dt_update_interval", "solver.dt_update is none"},
    {"dt_update_interval 0", "  steps: 10\n",
     "  steps: 10\n  dt_update: breaks\n  dt_update_interval: 0 #<\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "solver.dt_update_interval", "whole number >= 1"},
    {"dt above the stable step", "  steps: 10\n", "  steps: 10\n  dt: 1.0e-3 #<\n", NULL, AT_BUILD,
     PDK_ERR_ARG, "solver.dt", "exceeds the estimated stable time step"},
    {"component prescribed twice", "  - {set: top, type: velocity, y: 1.0}\n",
     "  - {set: top, type: velocity, y: 1.0}\n  - {set: all, type: velocity, x: 1} #<\n", NULL,
     AT_BUILD, PDK_ERR_ARG, "boundary_conditions[2]", "boundary_conditions[0] prescribes too"},
    {"end_time and steps", "  steps: 10\n", "  steps: 10 #<\n  end_time: 1e-6\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "solver.steps", "give one of them"},
    {"unknown reaction set", "solver:\n", "output: {reactions: [nowhere]} #<\nsolver:\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "output.reactions[0]", "not defined"},
    {"unknown output field", "solver:\n", "output: {fields: [u, stress]} #<\nsolver:\n", NULL,
     AT_BUILD, PDK_ERR_NOT_FOUND, "output.fields[1]", "'stress' is not a field"},
    {"unknown output units", "solver:\n", "output: {units: mm} #<\nsolver:\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "output.units", "allowed: none, SI, mm-N-s-tonne"},
    {"compression level above 9", "solver:\n", "output: {compression: 12} #<\nsolver:\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "output.compression", "whole number in [0, 9], got 12"},
    /* YAML syntax */
    {"YAML syntax", "  spacing: 1.0e-3", "  spacing: 1.0e-3: 2 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "YAML syntax", "mapping values are not allowed"},
    {"not a mapping", NULL, "- 1\n- 2\n", NULL, AT_LOAD, PDK_ERR_ARG, "(scene)", "a list"},
    {"empty scene", NULL, "# nothing here\n", NULL, AT_LOAD, PDK_ERR_ARG, "(scene)", "empty"},
    /* overrides: the same checks, blamed on the override */
    {"override out of range", NULL, NULL, "geometry.spacing=-1e-3", AT_LOAD, PDK_ERR_ARG,
     "geometry.spacing", "must be > 0"},
    {"override of an unknown key", NULL, NULL, "geometry.spaceing=1", AT_LOAD, PDK_ERR_ARG,
     "geometry.spaceing", "unknown key"},
    {"override with a bad type", NULL, NULL, "solver.threads=many", AT_LOAD, PDK_ERR_ARG,
     "solver.threads", "must be a number"},
    {"override adding a key", NULL, NULL, "model.stabilization=silling", AT_LOAD, PDK_ERR_ARG,
     "model.stabilization", "only the correspondence model"},
    {"override without '='", NULL, NULL, "solver.threads", AT_LOAD, PDK_ERR_ARG, NULL,
     "not of the form key.path=value"},
    {"override index out of range", NULL, NULL, "sets[5].name=x", AT_LOAD, PDK_ERR_ARG, NULL,
     "out of range"},
    {"override value not YAML", NULL, NULL, "geometry.box.lo=[0, 0", AT_LOAD, PDK_ERR_ARG, NULL,
     "not valid YAML"},
    /* numbers: the whole value is the number (no unit, digit separator or decimal comma) */
    {"number with a unit", "  density: 7850", "  density: 7850kg #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "must be a number, got '7850kg'"},
    {"decimal comma", "  poisson_ratio: 0.3", "  poisson_ratio: 0,3 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.poisson_ratio", "must be a number, got '0,3'"},
    {"digit separator", "  density: 7850", "  density: 7_850 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "must be a number, got '7_850'"},
    {"trailing text in a point", "hi: [0.01, 0.02]}", "hi: [0.01, 0.02m]} #<", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.box.hi[1]", "must be a number, got '0.02m'"},
    {"hexadecimal number", "  density: 7850", "  density: 0x1EA2 #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "got '0x1EA2'"},
    {"infinity", "  density: 7850", "  density: inf #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "must be a number, got 'inf'"},
    {"number beyond double range", "  spacing: 1.0e-3", "  spacing: 1e999 #<", NULL, AT_LOAD,
     PDK_ERR_ARG, "geometry.spacing", "must be a finite number"},
    {"empty number", "  density: 7850", "  density: #<", NULL, AT_LOAD, PDK_ERR_ARG,
     "material.density", "must be a number, got nothing"},
    {"override number with a decimal comma", NULL, NULL, "material.poisson_ratio=0,29", AT_LOAD,
     PDK_ERR_ARG, "material.poisson_ratio", "must be a number, got '0,29'"},
    /* booleans: true or false */
    {"misspelt boolean", NULL, NULL, "solver.force_dt=flase", AT_LOAD, PDK_ERR_ARG,
     "solver.force_dt", "must be true or false, got 'flase'"},
    {"yes for a boolean", "solver:\n", "model: {partial_volume: yes} #<\nsolver:\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "model.partial_volume", "must be true or false, got 'yes'"},
    /* the scene name names files and plot scripts */
    {"name starting with '-'", NULL, NULL, "name=-rf", AT_LOAD, PDK_ERR_ARG, "name",
     "not a valid name"},
    {"name starting with '.'", "dimension: 2\n", "name: ..bar #<\ndimension: 2\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "name", "not starting with '-' or '.'"},
    {"name with a newline", "dimension: 2\n", "name: \"m\\nsystem('touch X')\" #<\ndimension: 2\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "name", "'m\\nsystem('touch X')' is not a valid name"},
    /* limits and YAML features a scene has no use for */
    {"alias bomb", "solver:\n",
     "description:\n"
     "  - &a [x, x, x, x, x, x, x, x, x, x]\n"
     "  - &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
     "  - &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\n"
     "  - &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
     "  - &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\n"
     "  - &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e] #<\n"
     "  - &g [*f, *f, *f, *f, *f, *f, *f, *f, *f, *f]\n"
     "  - &h [*g, *g, *g, *g, *g, *g, *g, *g, *g, *g]\n"
     "  - &i [*h, *h, *h, *h, *h, *h, *h, *h, *h, *h]\n"
     "solver:\n",
     NULL, AT_LOAD, PDK_ERR_ARG, "description[5]", "more than 1000000 values"},
    {"recursive alias", "solver:\n", "description: &a [1, *a] #<\nsolver:\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "description", "recursive alias"},
    {"recursive alias in an override", NULL, NULL, "description=&a [*a]", AT_LOAD, PDK_ERR_ARG,
     "description", "recursive alias"},
    /* an empty scene (a comment only) gets its root mapping before an override's value is
     * copied in: the value once took the root's place and the key walk made it contain itself */
    {"mapping override into an empty scene", NULL, "# nothing yet\n", "solver.x=a: {b: 1}",
     AT_LOAD, PDK_ERR_ARG, "solver.x", "unknown key 'x'"},
    {"undefined alias", "solver:\n", "description: *nowhere #<\nsolver:\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "description", "no anchor"},
    {"second document in an override", NULL, NULL, "description=a\n---\nb", AT_LOAD, PDK_ERR_ARG,
     "description", "second YAML document"},
    {"second document in the file", NULL, "dimension: 2\n--- #<\ndimension: 3\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "(scene)", "second YAML document"},
    {"list as a key", "solver:\n", "? [a, b] #<\n: 1\nsolver:\n", NULL, AT_LOAD, PDK_ERR_ARG,
     "(scene)", "a list is used as a key"},
    {"mapping as a key", "  spacing: 1.0e-3\n", "  spacing: 1.0e-3\n  {a: 1}: 2 #<\n", NULL,
     AT_LOAD, PDK_ERR_ARG, "geometry", "a mapping is used as a key"},
    {"NUL in a value", "solver:\n", "description: \"a\\0b\" #<\nsolver:\n", NULL, AT_LOAD,
     PDK_ERR_ARG, "description", "NUL"},
};

/* Replaces the first `find` in `text` with `repl` (malloc'ed result). */
static char *edit(const char *text, const char *find, const char *repl) {
  if (!find) return strdup(repl ? repl : text);
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

/* 1-based line of the "#<" mark, or 1. */
static int marked_line(const char *text) {
  const char *mark = strstr(text, "#<");
  if (!mark) return 1;
  int line = 1;
  for (const char *c = text; c < mark; ++c)
    line += *c == '\n';
  return line;
}

static void run_case(pdk_ctx *ctx, int k, const error_case *c) {
  char path[64];
  snprintf(path, sizeof path, "t061_case%02d.yaml", k);
  char *text = c->find || c->replace ? edit(base_scene, c->find, c->replace) : strdup(base_scene);
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
    T_ASSERT(err || s, "case '%s': no scene and no error", c->what);
    T_ASSERT(!err || s == NULL, "case '%s': scene set on failure", c->what);
  }
  const char *msg = pdk_ctx_error_message(ctx);
  if (err != c->code)
    T_FAIL("case '%s': returned %d, expected %d; message: %s", c->what, err, c->code, msg);
  char want[512];
  if (c->override && c->key)
    snprintf(want, sizeof want, "%s: --set %s: %s: ", path, c->override, c->key);
  else if (c->override)
    snprintf(want, sizeof want, "%s: --set %s: ", path, c->override);
  else
    snprintf(want, sizeof want, "%s:%d: %s: ", path, marked_line(text), c->key);
  if (!strstr(msg, want))
    T_FAIL("case '%s': message does not start with '%s':\n  %s", c->what, want, msg);
  if (c->needle && !strstr(msg, c->needle))
    T_FAIL("case '%s': message does not mention '%s':\n  %s", c->what, c->needle, msg);
  /* What is allowed: after a ';', or in a "must ..." clause. */
  if (!strchr(msg, ';') && !strstr(msg, "must"))
    T_FAIL("case '%s': message does not say what is allowed:\n  %s", c->what, msg);
  if (getenv("PDK_TEST_VERBOSE")) printf("%-32s %s\n", c->what, msg);
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

  /* The base scene itself is valid, and force_dt accepts a dt above the estimate. */
  FILE *f = fopen("t061_base.yaml", "wb");
  T_ASSERT(f && fputs(base_scene, f) >= 0 && !fclose(f), "writing t061_base.yaml");
  const char *force[] = {"solver.dt=1e-3", "solver.force_dt=true"};
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t061_base.yaml", force, 2, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(pdk_explicit_dt(pdk_sim_explicit(sim)) == 1e-3, "forced dt is used");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove("t061_base.yaml");

  /* Nesting 100 000 levels deep is refused at the documented depth, naming it (the parse stops
   * there; reading the whole nest took a minute). */
  {
    const int depth = 100000;
    const char *head = "dimension: 2\ndescription: ";
    char *text = malloc(strlen(head) + (size_t)depth + 2);
    strcpy(text, head);
    memset(text + strlen(head), '[', (size_t)depth);
    strcpy(text + strlen(head) + depth, "\n");
    f = fopen("t061_deep.yaml", "wb");
    T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing t061_deep.yaml");
    T_FAILS(ctx, pdk_scene_load(ctx, "t061_deep.yaml", NULL, 0, &s), PDK_ERR_ARG,
            "t061_deep.yaml:2: description[0][0]");
    T_ASSERT(strstr(pdk_ctx_error_message(ctx), "nested deeper than 64 levels"),
             "deep nesting names the limit: %s", pdk_ctx_error_message(ctx));
    T_ASSERT(s == NULL, "no scene for deep nesting");
    free(text);
    remove("t061_deep.yaml");
  }

  /* The default name is the file's stem; one that cannot name files and plot scripts is an error
   * that asks for `name:`, and `name:` (here an override) fixes it. */
  {
    const char *stems[] = {"t061_bad\nsystem(\"touch X\")\n#.yaml", "-t061.yaml", ".t061.yaml",
                           "t061 space.yaml"};
    for (int k = 0; k < 4; ++k) {
      f = fopen(stems[k], "wb");
      T_ASSERT(f && fputs(base_scene, f) >= 0 && !fclose(f), "writing a scene named '%s'",
               stems[k]);
      T_FAILS(ctx, pdk_scene_load(ctx, stems[k], NULL, 0, &s), PDK_ERR_ARG, ":1: name: ");
      const char *msg = pdk_ctx_error_message(ctx);
      T_ASSERT(strstr(msg, "set name:") && strstr(msg, "file name"),
               "the message asks for name: %s", msg);
      T_ASSERT(!strchr(strstr(msg, ":1: name: "), '\n'),
               "the message shows the stem without raw newlines: %s", msg);
      T_ASSERT(s == NULL, "no scene for a bad stem");
      const char *named[] = {"name=t061_ok"};
      T_OK(ctx, pdk_scene_load(ctx, stems[k], named, 1, &s));
      T_ASSERT(!strcmp(pdk_scene_name(s), "t061_ok"), "name: replaces the stem");
      pdk_scene_destroy(&s);
      remove(stems[k]);
    }
  }

  /* A missing file. */
  T_FAILS(ctx, pdk_scene_load(ctx, "t061_no_such_file.yaml", NULL, 0, &s), PDK_ERR_IO,
          "t061_no_such_file.yaml");
  T_ASSERT(s == NULL, "no scene for a missing file");
  pdk_ctx_destroy(&ctx);
  return 0;
}
