/* Private: a loaded scene, resolved into the option structs of the objects it describes, shared by
 * src/scene*.c (loading and validation; src/scene/scene_load.h) and src/scene/sim.c (building).
 *
 * Everything here is owned by the scene: strings, region vertices, boundary conditions and the
 * "set:<name>" field names they point to. The option structs (lattice, model, solver) hold the
 * values after defaults and unit conversions (E, nu -> K, G), ready to hand to the constructors.
 *
 * Key locations: every key path present in the final YAML document ("geometry.spacing",
 * "sets[1].box.lo", ...) is recorded with the line of its key in the scene file, or with the
 * override that set it. pdk_scene_error formats messages as
 *   <file>:<line>: <key.path>: <what is wrong>; <what is allowed>
 *   <file>: --set <key.path>=<value>: <key.path>: ...        (a key set or replaced by an override)
 * For a key that is absent (a default), the nearest present parent gives the line.
 */
#ifndef PDK_SCENE_IMPL_H
#define PDK_SCENE_IMPL_H

#include "pdk/scene.h"
#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "pdk/static.h"

/* Limits checked before the work they bound (docs/scenes.md, "Limits"). */
#define PDK_SCENE_MAX_FILE_BYTES (8L << 20) /* a scene file: 8 MiB, checked before reading it */
#define PDK_SCENE_MAX_DEPTH 64              /* nesting levels, checked while parsing */
#define PDK_SCENE_MAX_VALUES 1000000L       /* values (nodes) with every alias expanded */

typedef struct pdk_scene_key {
  char *path;  /* "geometry.holes[0].disk.center" */
  int line;    /* 1-based line of the key (of the entry, for sequence entries) in the file */
  int origin;  /* -1: from the file; k >= 0: set by override k */
  char *value; /* the scalar value as written, NULL for lists and mappings */
  long count;  /* entries of a list, -1 for scalars and mappings */
} pdk_scene_key;

/* A region used as a hole, a notch or a named set. */
typedef struct pdk_scene_region {
  pdk_region region;
  double *vertices; /* polygon: [num_vertices][2], owned; region.vertices points here */
  char *name;       /* sets: the set name; NULL for holes and notches */
  char *field;      /* sets: "set:<name>"; NULL otherwise */
  char key[64];     /* key path of the region's kind, e.g. "geometry.holes[0].disk", "sets[2]" */
  int from_points;  /* sets: a set:<name> column of geometry.points (region unused) */
} pdk_scene_region;

struct pdk_scene {
  char *path; /* as given to pdk_scene_load */
  char *name;
  char *text; /* final YAML */
  int dim;

  pdk_scene_key *keys; /* [num_keys] */
  int num_keys;
  int *key_slots; /* [num_key_slots] hash index of keys by path (the last record of a path): a
                     key index or -1; see pdk_scene_key_get */
  size_t num_key_slots;
  char **overrides; /* [num_overrides] copies of the "key.path=value" strings */
  int num_overrides;

  pdk_lattice_opts lattice; /* lo, hi: the cloud's bounding box when points is set */
  pdk_index num_points; /* lattice points (or the cloud's) before holes and notches */
  struct pdk_points *points; /* geometry.points or mesh: the body as read (NULL for a lattice) */
  const char *points_key;    /* "geometry.points" or "geometry.mesh" (with points) */
  double horizon_factor;
  double horizon; /* horizon_factor * spacing */
  pdk_scene_region *holes, *notches, *sets;
  int num_holes, num_notches, num_sets;
  pdk_precrack *precracks; /* [num_precracks]; vertices point into crack_vertices */
  double *crack_vertices;
  int num_precracks;

#define PDK_SCENE_NORMAL_FIELD "surface_normal"
  pdk_model_opts model; /* model.materials points to materials below */
  pdk_scene_region *mat_regions; /* [num_mat_regions] the materials list: material k + 1 */
  int num_mat_regions;
  pdk_material *materials; /* [num_mat_regions + 1]; 0 is `material` (NULL without a list) */
  int mat_from_points;     /* the cloud's material column places the materials (points->material
                              then holds each particle's material index; the regions are unused) */
  char *galerkin_surface;  /* model.galerkin.surface (model.galerkin.surface points here) */
  int galerkin_normals_box; /* model.galerkin.normals: box: pdk_sim_create fills the field
                               PDK_SCENE_NORMAL_FIELD of the surface particles (sim.c) */

  pdk_solver_type solver_type;
  pdk_explicit_opts solver; /* bcs, reaction_sets point into the arrays below */
  pdk_static_opts static_opts; /* solver.type adr or newton: the same bcs and reaction sets; its
                                  load_levels point to load_levels (NULL: equal steps) */
  double *load_levels;         /* [static_opts.num_levels] when solver.load_levels is given */
  pdk_bc *bcs;              /* [num_bcs] */
  char **bc_fields;         /* [num_bcs] "set:<name>", NULL for the whole body ("all") */
  char **wall_names;        /* [output.num_walls] the names of the wall conditions */
  int num_bcs;
  char **reaction_fields; /* [output.num_reaction_sets] "set:<name>" */
  double end_time;
  long steps;
  int threads;

  pdk_scene_output output;
  char **fields;         /* [output.num_fields] */
  char **reaction_names; /* [output.num_reaction_sets] */
};

/* src/scene/scene_yaml.c: reads a file into a NUL-terminated malloc'ed buffer; a file larger than
 * PDK_SCENE_MAX_FILE_BYTES is refused before it is read (a regular file) or once that many bytes
 * were read (a device, a pipe). */
int pdk_scene_read_file(pdk_ctx *ctx, const char *path, char **text, size_t *len);
/* src/scene/scene_yaml.c: parses the file text, applies s->overrides, records s->keys, and returns the
 * final document as YAML text (malloc'ed) and the top-level dimension (2 unless it says 3; it
 * selects the schema, and is validated later). */
int pdk_scene_yaml_prepare(pdk_ctx *ctx, pdk_scene *s, const char *file_text, size_t file_len,
                           char **yaml_out, size_t *yaml_len, int *dim_out);
void pdk_scene_keys_free(pdk_scene_key *keys, int num);
/* The record of a key path present in the document (the last one of a path given twice), or
 * NULL; constant time. */
const pdk_scene_key *pdk_scene_key_get(const pdk_scene *s, const char *path);
/* Prefixes the context's current message (from a lower-level call that failed with err) with
 * "<location>: <key>: " and returns err. */
int pdk_scene_blame(const pdk_scene *s, pdk_ctx *ctx, int err, const char *key);
/* Writes `text` into buf for a message: printable ASCII as is, other bytes escaped (\n, \t,
 * \xNN), at most about 60 characters (then "..."). Returns buf. */
const char *pdk_scene_quote(const char *text, char *buf, size_t len);

#endif
