/* Private to the scene loader (src/scene*.c): the data libcyaml loads a scene into, the schema
 * it is loaded against, and the loader that the resolution of each section shares (key paths,
 * checks, messages). src/scene/scene.c describes the steps of pdk_scene_load; the files:
 *   scene.c           pdk_scene_load, pdk_scene_destroy and the accessors; the order of the
 *                     resolution steps (scene_resolve)
 *   scene_schema.c    the libcyaml schema (built for the scene's dimension) and its name tables
 *   scene_cyaml.c     the schema load: value checks before libcyaml, libcyaml's errors turned into
 *                     scene messages
 *   scene_geometry.c  geometry (lattice or point cloud, holes, notches, pre-cracks) and sets
 *   scene_model.c     material, model (and Johnson-Cook) and the materials list
 *   scene_solver.c    boundary conditions and the solver (explicit, adr, newton; load steps)
 *   scene_output.c    output and limits (the memory estimate)
 * The YAML document itself (file, overrides, key lines) is src/scene/scene_yaml.c's (scene_yaml.h).
 */
#ifndef PDK_SCENE_LOAD_H
#define PDK_SCENE_LOAD_H

#include <ctype.h>
#include <cyaml/cyaml.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "scene_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"
#include "pdk/scene.h"

#define SC_MAX_FIELDS 32    /* keys per mapping, + 1 terminator (johnson_cook has 23) */
#define SC_MAX_NAMES 16     /* model kinds, laws */
#define MAX_REACTION_SETS 8 /* pdk_history.reaction holds 8 */
#define SC_NAME_MAX (PDK_FIELD_NAME_MAX - 8)
#define KEY_MAX 256

/* ---- data loaded by libcyaml -------------------------------------------------------------------
 */

typedef struct sc_box {
  double lo[3], hi[3];
} sc_box;
typedef struct sc_ball {
  double center[3];
  double radius;
} sc_ball;
typedef struct sc_halfspace {
  double point[3], normal[3];
} sc_halfspace;
typedef struct sc_cylinder {
  double axis[2][3];
  double radius;
} sc_cylinder;
typedef struct sc_polygon {
  double (*vertices)[3];
  unsigned vertices_count;
} sc_polygon;
/* A hole, a notch or a set: exactly one region kind. */
typedef struct sc_region {
  char *name; /* sets only */
  sc_box *box;
  sc_ball *disk, *ball;
  sc_halfspace *halfspace;
  sc_polygon *polygon;
  sc_cylinder *cylinder;
  bool invert; /* notches and sets */
  /* materials entries only */
  double density, youngs_modulus, poisson_ratio, bulk_modulus, shear_modulus;
} sc_region;
typedef struct sc_precrack {
  double (*segment)[3];
  unsigned segment_count;
  double (*polygon)[3];
  unsigned polygon_count;
} sc_precrack;
typedef struct sc_geometry {
  int lattice;
  double spacing, horizon_factor, jitter, seed, thickness;
  char *points;
  char *mesh;
  sc_box box;
  sc_region *holes;
  unsigned holes_count;
  sc_region *notches;
  unsigned notches_count;
  sc_precrack *precracks;
  unsigned precracks_count;
} sc_geometry;
/* material.johnson_cook: numbers as in pdk_jc_params, booleans and words as in the scene. */
typedef struct sc_jc {
  double A, B, n, C, reference_strain_rate;
  bool thermal;
  double m, T_room, T_melt, T_initial, beta, heat_capacity;
  bool damage;
  double D1, D2, D3, D4, D5, D_c;
  int coupling, failed_mode;
} sc_jc;
typedef struct sc_material {
  double density, youngs_modulus, poisson_ratio, bulk_modulus, shear_modulus;
  sc_jc *johnson_cook;
} sc_material;
/* model.galerkin (kind galerkin) */
typedef struct sc_galerkin {
  int basis, form, correction;
  char *surface;
  bool bond;
  int normals;
} sc_galerkin;
typedef struct sc_model {
  sc_galerkin *galerkin;
  int kind, influence, stabilization, law, precision, connectivity, layout, stencil, bond_lengths;
  int stabilization_softening, damage_triaxiality, break_stress;
  int oterkus_a;
  double gaussian_width, stabilization_coefficient, critical_stretch, alpha, compact_fraction,
      ul_skin, stabilization_softening_floor;
  bool partial_volume, failed_keeps_bonds;
} sc_model;
typedef struct sc_bc {
  char *set;
  int type, function;
  double x, y, z, duration, period;
  double direction[3], value;
  double point[3], normal[3], velocity[3]; /* type: wall */
  char *name;
} sc_bc;
typedef struct sc_initial {
  double velocity[3];
  double velocity_gradient[3][3];
} sc_initial;
typedef struct sc_solver {
  int type;
  double end_time, steps, dt, safety, threads;
  bool force_dt;
  int dt_update;
  double dt_update_interval;
  /* static solvers (adr, newton) */
  double load_steps;
  double *load_levels;
  unsigned load_levels_count;
  double tolerance, absolute_tolerance, max_iterations, max_break_rounds;
  bool extrapolate;
  int adr_mass;
  double adr_safety;
  int linear_solver, fd_scheme, tangent;
  double fd_step, line_search_backtracks, line_search_decrease, singular_tolerance,
      symmetry_tolerance;
  bool reuse_tangent;
} sc_solver;
typedef struct sc_output {
  double field_interval, history_interval, checkpoint_interval, compression;
  int units;
  char **fields;
  unsigned fields_count;
  char **reactions;
  unsigned reactions_count;
} sc_output;
/* limits: what the run may use */
typedef struct sc_limits {
  double memory;
} sc_limits;
typedef struct sc_scene {
  char *name, *description;
  double dimension;
  sc_geometry geometry;
  sc_material material;
  sc_model model;
  sc_region *sets;
  unsigned sets_count;
  sc_region *materials;
  unsigned materials_count;
  sc_bc *boundary_conditions;
  unsigned boundary_conditions_count;
  sc_initial initial_conditions;
  sc_solver solver;
  sc_output output;
  sc_limits limits;
} sc_scene;

/* ---- the schema (src/scene/scene_schema.c) -----------------------------------------------------------
 */

/* output.units: the labels of the output files' columns and axes (pdk has no built-in units) */
enum { UNITS_NONE, UNITS_SI, UNITS_MM };

#define N_OF(a) ((uint32_t)(sizeof(a) / sizeof((a)[0])))

/* Built at run time because a point has `dim` entries; lives on the loader's stack. */
typedef struct scene_schema {
  cyaml_schema_value_t num, str, point, region_entry, notch_entry, set_entry, material_entry,
      precrack_entry, bc_entry, top;
  cyaml_schema_field_t box[SC_MAX_FIELDS], ball[SC_MAX_FIELDS], halfspace[SC_MAX_FIELDS],
      polygon[SC_MAX_FIELDS], cylinder[SC_MAX_FIELDS], hole[SC_MAX_FIELDS], notch[SC_MAX_FIELDS],
      set[SC_MAX_FIELDS], precrack[SC_MAX_FIELDS], geometry[SC_MAX_FIELDS], material[SC_MAX_FIELDS],
      material_region[SC_MAX_FIELDS], jc[SC_MAX_FIELDS], model[SC_MAX_FIELDS], bc[SC_MAX_FIELDS],
      galerkin[SC_MAX_FIELDS],
      initial[SC_MAX_FIELDS], solver[SC_MAX_FIELDS], output[SC_MAX_FIELDS], limits[SC_MAX_FIELDS],
      scene[SC_MAX_FIELDS];
  /* model.kind and model.law: the names the model registry lists (src/models/model_registry.h) */
  cyaml_strval_t kind_names[SC_MAX_NAMES], law_names[SC_MAX_NAMES];
  uint32_t num_kinds, num_laws;
} scene_schema;

/* Name tables of the schema that messages quote (the word for a loaded value). */
extern const cyaml_strval_t pdk_scene_lattice_names[];
extern const cyaml_strval_t pdk_scene_connectivity_names[];
extern const cyaml_strval_t pdk_scene_function_names[];

/* Builds the schema for a scene of dimension dim (the entries of a point). */
void pdk_scene_schema_build(scene_schema *sc, int dim);

/* ---- the schema load (src/scene/scene_cyaml.c) -------------------------------------------------------
 */

/* libcyaml's log, captured for the translation of its errors (cyaml_config_t.log_ctx). */
typedef struct cy_log {
  char text[4096];
  size_t len;
} cy_log;

/* cyaml_config_t.log_fn: appends libcyaml's error messages to the cy_log at ctx. */
void pdk_scene_cyaml_log(cyaml_log_t level, void *ctx, const char *fmt, va_list args);
/* Step 2, before libcyaml: number and boolean values, and list lengths against their caps. */
int pdk_scene_scalars_check(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc);
/* Loads the final YAML against the schema; libcyaml's errors become scene messages. */
int pdk_scene_schema_load(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc,
                          const cyaml_config_t *cfg, const char *yaml, size_t len, sc_scene **out);
int pdk_scene_schema_free(pdk_ctx *ctx, const scene_schema *sc, const cyaml_config_t *cfg,
                          sc_scene *data);

/* ---- checks ------------------------------------------------------------------------------------
 */

typedef struct loader {
  pdk_ctx *ctx;
  pdk_scene *s;
  char key[KEY_MAX];
} loader;

/* Formats a key path into ld->key and returns it. */
static inline const char *K(loader *ld, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static inline const char *K(loader *ld, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ld->key, sizeof ld->key, fmt, ap);
  va_end(ap);
  return ld->key;
}

static inline int has(const loader *ld, const char *path) {
  return pdk_scene_key_get(ld->s, path) != NULL;
}

#define FAIL(ld, key, ...)                                                                         \
  return pdk_scene_error((ld)->s, (ld)->ctx, PDK_ERR_ARG, (key), __VA_ARGS__)
#define REQUIRE(ld, cond, key, ...)                                                                \
  do {                                                                                             \
    if (!(cond)) FAIL(ld, key, __VA_ARGS__);                                                       \
  } while (0)

static inline int check_whole(loader *ld, const char *key, double v, double lo, double hi,
                              long *out) {
  if (hi >= 1e15)
    REQUIRE(ld, isfinite(v) && v == floor(v) && v >= lo && v <= hi, key,
            "must be a whole number >= %.0f, got %g", lo, v);
  REQUIRE(ld, isfinite(v) && v == floor(v) && v >= lo && v <= hi, key,
          "must be a whole number in [%.0f, %.0f], got %g", lo, hi, v);
  *out = (long)v;
  return PDK_SUCCESS;
}

static inline int valid_name(const char *n) {
  if (!n || !n[0] || strlen(n) > SC_NAME_MAX) return 0;
  for (const char *c = n; *c; ++c)
    if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-' && *c != '.') return 0;
  return 1;
}

static inline int find_set(const pdk_scene *s, const char *name) {
  for (int k = 0; k < s->num_sets; ++k)
    if (!strcmp(s->sets[k].name, name)) return k;
  return -1;
}

static inline void list_sets(const pdk_scene *s, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  for (int k = 0; k < s->num_sets; ++k) {
    int w = snprintf(buf + pos, len - pos, "%s%s", k ? ", " : "", s->sets[k].name);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
  if (!s->num_sets) snprintf(buf, len, "(no sets are defined)");
}

/* ---- resolution of each section (step 3) -------------------------------------------------------
 */

/* src/scene/scene_geometry.c: a region (box, disk or ball, halfspace, polygon) of a hole, notch, set or
 * materials entry. */
int pdk_scene_region_resolve(loader *ld, const sc_region *r, const char *base, int allow_halfspace,
                             pdk_scene_region *out);
int pdk_scene_resolve_geometry(loader *ld, const sc_geometry *g);
int pdk_scene_resolve_sets(loader *ld, const sc_scene *d);
/* src/scene/scene_model.c */
int pdk_scene_resolve_material_model(loader *ld, const sc_material *mat, const sc_model *mo);
int pdk_scene_resolve_materials(loader *ld, const sc_scene *d);
/* src/scene/scene_solver.c */
int pdk_scene_resolve_bcs(loader *ld, const sc_scene *d);
int pdk_scene_resolve_solver(loader *ld, const sc_scene *d);
/* src/scene/scene_output.c */
int pdk_scene_resolve_output(loader *ld, const sc_scene *d);
int pdk_scene_resolve_limits(loader *ld, const sc_scene *d);

#endif
