/* Scene loading: pdk_scene_load, pdk_scene_destroy and the accessors of a loaded scene
 * (src/scene/scene_impl.h). docs/scenes.md documents every key; keep the two in step.
 *
 * Steps of pdk_scene_load:
 *   1. read the file; parse it with libyaml, apply the overrides, record the line of every key
 *      path, emit the final YAML text (src/scene/scene_yaml.c);
 *   2. check every single value against the type the schema gives its key
 *      (pdk_scene_scalars_check: a number is the whole value, a boolean is true or false) and
 *      every list's length against its cap, then load that text with libcyaml against the schema
 *      (src/scene/scene_schema.c), which depends on the dimension only through the number of entries of
 *      a point ([x, y] or [x, y, z]); libcyaml's own errors come through the log callback as a
 *      message plus a backtrace of mapping fields and sequence entries, turned into a key path
 *      and from it into "<file>:<line>: <key.path>: ..." (src/scene/scene_cyaml.c);
 *   3. fill defaults for absent keys (a key is absent when step 1 did not record it), check
 *      ranges and consistency, convert units of choice (E, nu -> K, G), and store the option
 *      structs that pdk_sim_create (src/scene/sim.c) hands to the constructors (scene_resolve below;
 *      one file per section: src/scene/scene_geometry.c, scene_model.c, scene_solver.c and
 *      scene_output.c; the loader they share is src/scene/scene_load.h).
 *
 * Numbers that must be integers (dimension, steps, threads, intervals, seed) are loaded as floats
 * and checked here, because libcyaml 1.3.1 reads "1.5" as the integer 1 without complaint, and so
 * that 1e5 is accepted as a step count. libcyaml 1.3.1 also reads the longest number at the start
 * of a value ("7850kg" as 7850, "0,29" as 0) and any word but false, no, off, disable and 0 as
 * true; pdk_scene_scalars_check refuses such values before libcyaml sees them.
 */
#include <stdio.h>
#include <string.h>

#include "core/ext.h"
#include "space/points.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/scene.h"

/* The scene's name names its output files (<name>.h5, <name>_history.csv, ...) and appears in
 * the plot scripts: letters, digits and . _ + - only, not starting with '-' (an option to a
 * command) or '.' (a hidden file, ".."). */
static int valid_scene_name(const char *n) {
  if (!n || !n[0] || strlen(n) > SC_NAME_MAX || n[0] == '-' || n[0] == '.') return 0;
  for (const char *c = n; *c; ++c)
    if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
          strchr("._+-", *c)))
      return 0;
  return 1;
}

/* Step 3: defaults, checks, conversions. */
static int scene_resolve(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  REQUIRE(ld, d->dimension == 2 || d->dimension == 3, "dimension", "must be 2 or 3, got %g",
          d->dimension);
  char shown[128];
  if (has(ld, "name")) {
    REQUIRE(ld, valid_scene_name(d->name), "name",
            "'%s' is not a valid name (it names the output files and the plots); use 1 to %d "
            "letters, digits, '_', '-', '.' or '+', not starting with '-' or '.'",
            pdk_scene_quote(d->name, shown, sizeof shown), SC_NAME_MAX);
    free(s->name);
    s->name = strdup(d->name);
    if (!s->name) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  } else {
    REQUIRE(ld, valid_scene_name(s->name), "name",
            "the scene has no name: key, and its file name's stem '%s' cannot be the name (it "
            "names the output files and the plots); set name: in the scene (or --set name=...) to "
            "1 to %d letters, digits, '_', '-', '.' or '+', not starting with '-' or '.'",
            pdk_scene_quote(s->name, shown, sizeof shown), SC_NAME_MAX);
  }
  s->solver = pdk_explicit_opts_default();
  PDK_CALL(pdk_scene_resolve_geometry(ld, &d->geometry));
  PDK_CALL(pdk_scene_resolve_material_model(ld, &d->material, &d->model));
  PDK_CALL(pdk_scene_resolve_sets(ld, d));
  PDK_CALL(pdk_scene_resolve_materials(ld, d));
  PDK_CALL(pdk_scene_resolve_bcs(ld, d));
  PDK_CALL(pdk_scene_resolve_solver(ld, d));
  PDK_CALL(pdk_scene_resolve_output(ld, d));
  PDK_CALL(pdk_scene_resolve_limits(ld, d));
  return PDK_SUCCESS;
}

/* ---- public API --------------------------------------------------------------------------------
 */

static char *file_stem(const char *path) {
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  size_t len = strlen(base);
  const char *dot = strrchr(base, '.');
  if (dot && dot != base) len = (size_t)(dot - base);
  char *out = malloc(len + 1);
  if (!out) return NULL;
  memcpy(out, base, len);
  out[len] = '\0';
  return out;
}

int pdk_scene_load(pdk_ctx *ctx, const char *path, const char *const *overrides, int num_overrides,
                   pdk_scene **out) {
  int err = PDK_SUCCESS;
  pdk_scene *s = NULL;
  char *file_text = NULL, *yaml = NULL;
  size_t file_len = 0, yaml_len = 0;
  sc_scene *data = NULL;
  scene_schema sc;
  cy_log log;
  cyaml_config_t cfg;
  loader ld;
  int dim = 2;
  memset(&log, 0, sizeof log);
  memset(&cfg, 0, sizeof cfg);
  cfg.log_fn = pdk_scene_cyaml_log;
  cfg.log_ctx = &log;
  cfg.mem_fn = cyaml_mem;
  cfg.log_level = CYAML_LOG_ERROR;
  cfg.flags = CYAML_CFG_DEFAULT;
  pdk_scene_schema_build(&sc, 2);

  PDK_CHECK(out, ctx, PDK_ERR_ARG, "pdk_scene_load: out is NULL");
  *out = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(path, ctx, PDK_ERR_ARG, "pdk_scene_load: no scene path given");
  PDK_CHECK(num_overrides >= 0 && (num_overrides == 0 || overrides), ctx, PDK_ERR_ARG,
            "pdk_scene_load: %d overrides but no array", num_overrides);
  s = calloc(1, sizeof *s);
  PDK_CHECK(s, ctx, PDK_ERR_MEMORY, "out of memory loading a scene");
  s->dim = 2;
  s->path = strdup(path);
  s->name = file_stem(path);
  s->overrides = calloc((size_t)num_overrides + 1, sizeof(char *));
  PDK_CHECK_GOTO(s->path && s->name && s->overrides, ctx, PDK_ERR_MEMORY,
                 "out of memory loading a scene");
  for (int k = 0; k < num_overrides; ++k) {
    PDK_CHECK_GOTO(overrides[k], ctx, PDK_ERR_ARG, "pdk_scene_load: override %d is NULL", k);
    s->overrides[k] = strdup(overrides[k]);
    s->num_overrides = k + 1;
    PDK_CHECK_GOTO(s->overrides[k], ctx, PDK_ERR_MEMORY, "out of memory loading a scene");
  }

  /* 1. file -> document -> overrides -> key lines -> final YAML */
  PDK_CALL_GOTO(pdk_scene_read_file(ctx, path, &file_text, &file_len));
  PDK_CALL_GOTO(pdk_scene_yaml_prepare(ctx, s, file_text, file_len, &yaml, &yaml_len, &dim));
  s->dim = dim;

  /* 2. value types and list lengths, then the schema load */
  pdk_scene_schema_build(&sc, dim);
  PDK_CALL_GOTO(pdk_scene_scalars_check(ctx, s, &sc));
  PDK_CALL_GOTO(pdk_scene_schema_load(ctx, s, &sc, &cfg, yaml, yaml_len, &data));
  if (!data) {
    err = pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                            "%s:1: (scene): the scene is empty; it needs at least dimension, "
                            "geometry, material and solver (see docs/scenes.md)",
                            path);
    goto cleanup;
  }

  /* 3. defaults and checks */
  ld.ctx = ctx;
  ld.s = s;
  ld.key[0] = '\0';
  PDK_CALL_GOTO(scene_resolve(&ld, data));

  if (num_overrides == 0) {
    s->text = file_text;
    file_text = NULL;
  } else {
    size_t hlen = strlen(path) + 64;
    for (int k = 0; k < num_overrides; ++k)
      hlen += strlen(overrides[k]) + 8;
    s->text = malloc(hlen + yaml_len + 1);
    PDK_CHECK_GOTO(s->text, ctx, PDK_ERR_MEMORY, "out of memory loading a scene");
    size_t pos = (size_t)snprintf(s->text, hlen, "# %s with overrides:", path);
    for (int k = 0; k < num_overrides; ++k)
      pos += (size_t)snprintf(s->text + pos, hlen - pos, " --set %s", overrides[k]);
    for (size_t i = 0; i < pos; ++i) /* keep the header one comment line */
      if (s->text[i] == '\n' || s->text[i] == '\r') s->text[i] = ' ';
    s->text[pos++] = '\n';
    memcpy(s->text + pos, yaml, yaml_len + 1);
  }
  *out = s;
cleanup:
  if (data) {
    int free_err = pdk_scene_schema_free(ctx, &sc, &cfg, data);
    if (!err) err = free_err;
  }
  free(yaml);
  free(file_text);
  if (err) {
    *out = NULL;
    pdk_scene_destroy(&s);
  }
  return err;
}

static void regions_free(pdk_scene_region *r, int n) {
  if (!r) return;
  for (int k = 0; k < n; ++k) {
    free(r[k].vertices);
    free(r[k].name);
    free(r[k].field);
  }
  free(r);
}

static void strings_free(char **v, int n) {
  if (!v) return;
  for (int k = 0; k < n; ++k)
    free(v[k]);
  free(v);
}

void pdk_scene_destroy(pdk_scene **sp) {
  if (!sp || !*sp) return;
  pdk_scene *s = *sp;
  free(s->path);
  free(s->name);
  free(s->text);
  pdk_scene_keys_free(s->keys, s->num_keys);
  free(s->key_slots);
  strings_free(s->overrides, s->num_overrides);
  regions_free(s->holes, s->num_holes);
  regions_free(s->notches, s->num_notches);
  regions_free(s->sets, s->num_sets);
  regions_free(s->mat_regions, s->num_mat_regions);
  free(s->materials);
  free(s->galerkin_surface);
  free(s->precracks);
  free(s->crack_vertices);
  if (s->points) pdk_points_free(s->points);
  free(s->points);
  free(s->bcs);
  free(s->load_levels);
  strings_free(s->bc_fields, s->num_bcs);
  strings_free(s->wall_names, s->output.num_walls);
  strings_free(s->reaction_fields, s->output.num_reaction_sets);
  strings_free(s->fields, s->output.num_fields);
  strings_free(s->reaction_names, s->output.num_reaction_sets);
  free(s);
  *sp = NULL;
}

const char *pdk_scene_path(const pdk_scene *s) { return s ? s->path : ""; }
const char *pdk_scene_name(const pdk_scene *s) { return s ? s->name : ""; }
const char *pdk_scene_text(const pdk_scene *s) { return s ? s->text : ""; }
int pdk_scene_threads(const pdk_scene *s) { return s ? s->threads : 0; }
int pdk_scene_dimension(const pdk_scene *s) { return s ? s->dim : 0; }
pdk_solver_type pdk_scene_solver_type(const pdk_scene *s) {
  return s ? s->solver_type : PDK_SOLVER_EXPLICIT;
}
const char *pdk_solver_type_name(pdk_solver_type type) {
  switch (type) {
  case PDK_SOLVER_EXPLICIT: return "explicit";
  case PDK_SOLVER_ADR: return "adr";
  case PDK_SOLVER_NEWTON: return "newton";
  }
  return "?";
}
const pdk_scene_output *pdk_scene_output_get(const pdk_scene *s) { return s ? &s->output : NULL; }
