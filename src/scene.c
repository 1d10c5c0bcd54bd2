/* Scene loading: the libcyaml schema, translation of libcyaml's errors, defaults, range and
 * consistency checks, and the resolved scene (src/scene_impl.h). docs/scenes.md documents every
 * key; keep the two in step.
 *
 * Steps of pdk_scene_load:
 *   1. read the file; parse it with libyaml, apply the overrides, record the line of every key
 *      path, emit the final YAML text (src/scene_yaml.c);
 *   2. check every single value against the type the schema gives its key (scalars_check: a
 *      number is the whole value, a boolean is true or false) and every list's length against its
 *      cap, then load that text with libcyaml against the schema below, which depends on the
 *      dimension only through the number of entries of a point ([x, y] or [x, y, z]); libcyaml's
 *      own errors come
 *      through the log callback as a message plus a backtrace of mapping fields and sequence
 *      entries, turned here into a key path and from it into "<file>:<line>: <key.path>: ...";
 *   3. fill defaults for absent keys (a key is absent when step 1 did not record it), check
 *      ranges and consistency, convert units of choice (E, nu -> K, G), and store the option
 *      structs that pdk_sim_create (src/sim.c) hands to the constructors.
 *
 * Numbers that must be integers (dimension, steps, threads, intervals, seed) are loaded as floats
 * and checked here, because libcyaml 1.3.1 reads "1.5" as the integer 1 without complaint, and so
 * that 1e5 is accepted as a step count. libcyaml 1.3.1 also reads the longest number at the start
 * of a value ("7850kg" as 7850, "0,29" as 0) and any word but false, no, off, disable and 0 as
 * true; scalars_check refuses such values before libcyaml sees them.
 */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "ext.h"
#include "model_registry.h"
#include "points.h"
#include "scene_impl.h"

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
} sc_galerkin;
typedef struct sc_model {
  sc_galerkin *galerkin;
  int kind, influence, stabilization, law, precision, connectivity, layout, stencil;
  int stabilization_softening, damage_triaxiality, break_stress;
  double gaussian_width, stabilization_coefficient, critical_stretch, alpha, compact_fraction,
      ul_skin, stabilization_softening_floor;
  bool partial_volume, failed_keeps_bonds;
} sc_model;
typedef struct sc_bc {
  char *set;
  int type, function;
  double x, y, z, duration, period;
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

/* ---- the schema --------------------------------------------------------------------------------
 */

static const cyaml_strval_t lattice_names[] = {
    {"square", PDK_LATTICE_SQUARE}, {"hex", PDK_LATTICE_HEX}, {"cubic", PDK_LATTICE_CUBIC}};
static const cyaml_strval_t influence_names[] = {
    {"constant", PDK_INFLUENCE_CONSTANT}, {"inv_r", PDK_INFLUENCE_INV_R},
    {"inv_r2", PDK_INFLUENCE_INV_R2},     {"linear", PDK_INFLUENCE_LINEAR},
    {"cubic", PDK_INFLUENCE_CUBIC},       {"gaussian", PDK_INFLUENCE_GAUSSIAN}};
static const cyaml_strval_t stab_names[] = {
    {"none", PDK_STAB_NONE}, {"silling", PDK_STAB_SILLING}, {"hourglass", PDK_STAB_HOURGLASS}};
static const cyaml_strval_t connectivity_names[] = {{"tl", PDK_CONNECTIVITY_TL},
                                                    {"semi_tl", PDK_CONNECTIVITY_SEMI_TL},
                                                    {"ul", PDK_CONNECTIVITY_UL}};
/* output.units: the labels of the output files' columns and axes (pdk has no built-in units) */
enum { UNITS_NONE, UNITS_SI, UNITS_MM };
static const cyaml_strval_t units_names[] = {
    {"none", UNITS_NONE}, {"SI", UNITS_SI}, {"mm-N-s-tonne", UNITS_MM}};
static const cyaml_strval_t coupling_names[] = {{"none", PDK_JC_COUPLING_NONE},
                                                {"effective", PDK_JC_COUPLING_EFFECTIVE}};
static const cyaml_strval_t failed_mode_names[] = {{"zero", PDK_JC_FAILED_ZERO},
                                                   {"compression", PDK_JC_FAILED_COMPRESSION}};
static const cyaml_strval_t softening_names[] = {{"none", 0}, {"plastic", 1}};
static const cyaml_strval_t triaxiality_names[] = {{"local", PDK_TRIAX_LOCAL},
                                                   {"family", PDK_TRIAX_FAMILY}};
static const cyaml_strval_t break_stress_names[] = {{"refit", PDK_BREAK_STRESS_REFIT},
                                                    {"continuous", PDK_BREAK_STRESS_CONTINUOUS}};
static const cyaml_strval_t galerkin_basis_names[] = {{"taylor", PDK_GALERKIN_TAYLOR},
                                                      {"wls", PDK_GALERKIN_WLS}};
static const cyaml_strval_t galerkin_form_names[] = {{"bubnov", PDK_GALERKIN_BUBNOV}};
static const cyaml_strval_t galerkin_correction_names[] = {{"none", PDK_GALERKIN_NONE},
                                                           {"vc1", PDK_GALERKIN_VC1}};
static const cyaml_strval_t precision_names[] = {{"double", PDK_PRECISION_DOUBLE},
                                                 {"float", PDK_PRECISION_FLOAT}};
static const cyaml_strval_t layout_names[] = {{"csr", PDK_LAYOUT_CSR}, {"sell", PDK_LAYOUT_SELL}};
static const cyaml_strval_t stencil_names[] = {
    {"off", PDK_STENCIL_OFF}, {"auto", PDK_STENCIL_AUTO}, {"on", PDK_STENCIL_ON}};
static const cyaml_strval_t bc_type_names[] = {{"displacement", PDK_BC_DISPLACEMENT},
                                               {"velocity", PDK_BC_VELOCITY},
                                               {"body_force", PDK_BC_BODY_FORCE}};
static const cyaml_strval_t function_names[] = {{"constant", PDK_TFUN_CONSTANT},
                                                {"linear", PDK_TFUN_LINEAR},
                                                {"ramp", PDK_TFUN_RAMP},
                                                {"smooth", PDK_TFUN_SMOOTH},
                                                {"sine", PDK_TFUN_SINE}};
static const cyaml_strval_t solver_names[] = {
    {"explicit", PDK_SOLVER_EXPLICIT}, {"adr", PDK_SOLVER_ADR}, {"newton", PDK_SOLVER_NEWTON}};
static const cyaml_strval_t dt_update_names[] = {{"none", PDK_DT_UPDATE_NONE},
                                                 {"breaks", PDK_DT_UPDATE_BREAKS},
                                                 {"periodic", PDK_DT_UPDATE_PERIODIC}};
static const cyaml_strval_t adr_mass_names[] = {{"auto", PDK_ADR_MASS_AUTO},
                                                {"row_sum", PDK_ADR_MASS_ROW_SUM},
                                                {"lanczos", PDK_ADR_MASS_LANCZOS}};
static const cyaml_strval_t linear_solver_names[] = {
    {"auto", PDK_LINEAR_AUTO}, {"cholmod", PDK_LINEAR_CHOLMOD}, {"umfpack", PDK_LINEAR_UMFPACK}};
static const cyaml_strval_t fd_scheme_names[] = {{"central", PDK_FD_CENTRAL},
                                                 {"forward", PDK_FD_FORWARD}};
static const cyaml_strval_t tangent_names[] = {{"auto", PDK_TANGENT_AUTO},
                                               {"analytic", PDK_TANGENT_ANALYTIC},
                                               {"difference", PDK_TANGENT_DIFFERENCE}};

#define N_OF(a) ((uint32_t)(sizeof(a) / sizeof((a)[0])))
#define OPT (CYAML_FLAG_OPTIONAL)
#define OPT_PTR (CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER)
#define ENUM_FLAGS (CYAML_FLAG_OPTIONAL | CYAML_FLAG_STRICT)

/* Built at run time because a point has `dim` entries; lives on the loader's stack. */
typedef struct scene_schema {
  cyaml_schema_value_t num, str, point, region_entry, notch_entry, set_entry, material_entry,
      precrack_entry, bc_entry, top;
  cyaml_schema_field_t box[SC_MAX_FIELDS], ball[SC_MAX_FIELDS], halfspace[SC_MAX_FIELDS],
      polygon[SC_MAX_FIELDS], hole[SC_MAX_FIELDS], notch[SC_MAX_FIELDS], set[SC_MAX_FIELDS],
      precrack[SC_MAX_FIELDS], geometry[SC_MAX_FIELDS], material[SC_MAX_FIELDS],
      material_region[SC_MAX_FIELDS], jc[SC_MAX_FIELDS], model[SC_MAX_FIELDS], bc[SC_MAX_FIELDS],
      galerkin[SC_MAX_FIELDS],
      initial[SC_MAX_FIELDS], solver[SC_MAX_FIELDS], output[SC_MAX_FIELDS], limits[SC_MAX_FIELDS],
      scene[SC_MAX_FIELDS];
  /* model.kind and model.law: the names the model registry lists (src/model_registry.h) */
  cyaml_strval_t kind_names[SC_MAX_NAMES], law_names[SC_MAX_NAMES];
  uint32_t num_kinds, num_laws;
} scene_schema;

static void field_add(cyaml_schema_field_t *fields, cyaml_schema_field_t f) {
  int i = 0;
  while (fields[i].key)
    ++i;
  /* SC_MAX_FIELDS - 1 entries at most, leaving the zeroed terminator (CYAML_FIELD_END) */
  if (i < SC_MAX_FIELDS - 1) fields[i] = f;
}

#define ADD(arr, ...) field_add(sc->arr, (cyaml_schema_field_t)__VA_ARGS__)

/* The fields of a region kind, shared by holes, notches and sets. */
static void schema_region_kinds(scene_schema *sc, cyaml_schema_field_t *f) {
  field_add(f,
            (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("box", OPT_PTR, sc_region, box, sc->box));
  field_add(
      f, (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("disk", OPT_PTR, sc_region, disk, sc->ball));
  field_add(
      f, (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("ball", OPT_PTR, sc_region, ball, sc->ball));
  field_add(f, (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("halfspace", OPT_PTR, sc_region,
                                                             halfspace, sc->halfspace));
  field_add(f, (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("polygon", OPT_PTR, sc_region, polygon,
                                                             sc->polygon));
}

static void schema_build(scene_schema *sc, int dim) {
  memset(sc, 0, sizeof *sc);
  for (int i = 0; pdk_model_kind_at(i) && sc->num_kinds < SC_MAX_NAMES; ++i)
    if (pdk_model_kind_at(i)->caps & PDK_KIND_SCENE)
      sc->kind_names[sc->num_kinds++] =
          (cyaml_strval_t){pdk_model_kind_at(i)->name, (int64_t)pdk_model_kind_at(i)->kind};
  for (int i = 0; pdk_law_at(i) && sc->num_laws < SC_MAX_NAMES; ++i)
    sc->law_names[sc->num_laws++] =
        (cyaml_strval_t){pdk_law_at(i)->name, (int64_t)pdk_law_at(i)->law};
  const uint32_t d = (uint32_t)dim;
  sc->num = (cyaml_schema_value_t){CYAML_VALUE_FLOAT(CYAML_FLAG_DEFAULT, double)};
  sc->str = (cyaml_schema_value_t){CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 0, 255)};
  /* A point inside a list: libcyaml steps through a sequence by the sequence value's data_size
   * (the CYAML_FIELD_* macros set it to the entry size), so a point's data_size is one double,
   * and a list of points, declared double (*)[3], steps by sizeof(double[3]). */
  sc->point =
      (cyaml_schema_value_t){CYAML_VALUE_SEQUENCE_FIXED(CYAML_FLAG_DEFAULT, double, &sc->num, d)};

  ADD(box, CYAML_FIELD_SEQUENCE_FIXED("lo", 0, sc_box, lo, &sc->num, d));
  ADD(box, CYAML_FIELD_SEQUENCE_FIXED("hi", 0, sc_box, hi, &sc->num, d));
  ADD(ball, CYAML_FIELD_SEQUENCE_FIXED("center", 0, sc_ball, center, &sc->num, d));
  ADD(ball, CYAML_FIELD_FLOAT("radius", 0, sc_ball, radius));
  ADD(halfspace, CYAML_FIELD_SEQUENCE_FIXED("point", 0, sc_halfspace, point, &sc->num, d));
  ADD(halfspace, CYAML_FIELD_SEQUENCE_FIXED("normal", 0, sc_halfspace, normal, &sc->num, d));
  ADD(polygon, CYAML_FIELD_SEQUENCE("vertices", CYAML_FLAG_POINTER, sc_polygon, vertices,
                                    &sc->point, 3, 4096));

  schema_region_kinds(sc, sc->hole);
  schema_region_kinds(sc, sc->notch);
  ADD(notch, CYAML_FIELD_BOOL("invert", OPT, sc_region, invert));
  ADD(set, CYAML_FIELD_STRING_PTR("name", 0, sc_region, name, 1, 255));
  schema_region_kinds(sc, sc->set);
  ADD(set, CYAML_FIELD_BOOL("invert", OPT, sc_region, invert));
  ADD(material_region, CYAML_FIELD_STRING_PTR("name", 0, sc_region, name, 1, 255));
  schema_region_kinds(sc, sc->material_region);
  ADD(material_region, CYAML_FIELD_BOOL("invert", OPT, sc_region, invert));
  ADD(material_region, CYAML_FIELD_FLOAT("density", 0, sc_region, density));
  ADD(material_region, CYAML_FIELD_FLOAT("youngs_modulus", OPT, sc_region, youngs_modulus));
  ADD(material_region, CYAML_FIELD_FLOAT("poisson_ratio", OPT, sc_region, poisson_ratio));
  ADD(material_region, CYAML_FIELD_FLOAT("bulk_modulus", OPT, sc_region, bulk_modulus));
  ADD(material_region, CYAML_FIELD_FLOAT("shear_modulus", OPT, sc_region, shear_modulus));
  sc->material_entry = (cyaml_schema_value_t){
      CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_region, sc->material_region)};
  /* Holes, notches and sets load into the same struct; each accepts its own keys. */
  sc->region_entry =
      (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_region, sc->hole)};
  sc->notch_entry =
      (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_region, sc->notch)};
  sc->set_entry =
      (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_region, sc->set)};

  ADD(precrack, CYAML_FIELD_SEQUENCE("segment", OPT_PTR, sc_precrack, segment, &sc->point, 2, 2));
  ADD(precrack,
      CYAML_FIELD_SEQUENCE("polygon", OPT_PTR, sc_precrack, polygon, &sc->point, 3, 4096));
  sc->precrack_entry =
      (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_precrack, sc->precrack)};

  ADD(geometry, CYAML_FIELD_ENUM("lattice", ENUM_FLAGS, sc_geometry, lattice, lattice_names,
                                 N_OF(lattice_names)));
  ADD(geometry, CYAML_FIELD_FLOAT("spacing", 0, sc_geometry, spacing));
  ADD(geometry, CYAML_FIELD_FLOAT("horizon_factor", OPT, sc_geometry, horizon_factor));
  ADD(geometry, CYAML_FIELD_FLOAT("jitter", OPT, sc_geometry, jitter));
  ADD(geometry, CYAML_FIELD_FLOAT("seed", OPT, sc_geometry, seed));
  ADD(geometry, CYAML_FIELD_FLOAT("thickness", OPT, sc_geometry, thickness));
  ADD(geometry, CYAML_FIELD_MAPPING("box", OPT, sc_geometry, box, sc->box));
  ADD(geometry, CYAML_FIELD_STRING_PTR("points", OPT, sc_geometry, points, 1, 4095));
  ADD(geometry,
      CYAML_FIELD_SEQUENCE("holes", OPT_PTR, sc_geometry, holes, &sc->region_entry, 0, 10000));
  ADD(geometry,
      CYAML_FIELD_SEQUENCE("notches", OPT_PTR, sc_geometry, notches, &sc->notch_entry, 0, 10000));
  ADD(geometry, CYAML_FIELD_SEQUENCE("precracks", OPT_PTR, sc_geometry, precracks,
                                     &sc->precrack_entry, 0, 10000));

  ADD(material, CYAML_FIELD_FLOAT("density", 0, sc_material, density));
  ADD(material, CYAML_FIELD_FLOAT("youngs_modulus", OPT, sc_material, youngs_modulus));
  ADD(material, CYAML_FIELD_FLOAT("poisson_ratio", OPT, sc_material, poisson_ratio));
  ADD(material, CYAML_FIELD_FLOAT("bulk_modulus", OPT, sc_material, bulk_modulus));
  ADD(material, CYAML_FIELD_FLOAT("shear_modulus", OPT, sc_material, shear_modulus));
  ADD(material,
      CYAML_FIELD_MAPPING_PTR("johnson_cook", OPT_PTR, sc_material, johnson_cook, sc->jc));
  ADD(jc, CYAML_FIELD_FLOAT("A", 0, sc_jc, A));
  ADD(jc, CYAML_FIELD_FLOAT("B", 0, sc_jc, B));
  ADD(jc, CYAML_FIELD_FLOAT("n", 0, sc_jc, n));
  ADD(jc, CYAML_FIELD_FLOAT("C", OPT, sc_jc, C));
  ADD(jc, CYAML_FIELD_FLOAT("reference_strain_rate", OPT, sc_jc, reference_strain_rate));
  ADD(jc, CYAML_FIELD_BOOL("thermal", OPT, sc_jc, thermal));
  ADD(jc, CYAML_FIELD_FLOAT("m", OPT, sc_jc, m));
  ADD(jc, CYAML_FIELD_FLOAT("T_room", OPT, sc_jc, T_room));
  ADD(jc, CYAML_FIELD_FLOAT("T_melt", OPT, sc_jc, T_melt));
  ADD(jc, CYAML_FIELD_FLOAT("T_initial", OPT, sc_jc, T_initial));
  ADD(jc, CYAML_FIELD_FLOAT("beta", OPT, sc_jc, beta));
  ADD(jc, CYAML_FIELD_FLOAT("heat_capacity", OPT, sc_jc, heat_capacity));
  ADD(jc, CYAML_FIELD_BOOL("damage", OPT, sc_jc, damage));
  ADD(jc, CYAML_FIELD_FLOAT("D1", OPT, sc_jc, D1));
  ADD(jc, CYAML_FIELD_FLOAT("D2", OPT, sc_jc, D2));
  ADD(jc, CYAML_FIELD_FLOAT("D3", OPT, sc_jc, D3));
  ADD(jc, CYAML_FIELD_FLOAT("D4", OPT, sc_jc, D4));
  ADD(jc, CYAML_FIELD_FLOAT("D5", OPT, sc_jc, D5));
  ADD(jc, CYAML_FIELD_FLOAT("D_c", OPT, sc_jc, D_c));
  ADD(jc, CYAML_FIELD_ENUM("coupling", ENUM_FLAGS, sc_jc, coupling, coupling_names,
                           N_OF(coupling_names)));
  ADD(jc, CYAML_FIELD_ENUM("failed_mode", ENUM_FLAGS, sc_jc, failed_mode, failed_mode_names,
                           N_OF(failed_mode_names)));

  ADD(model,
      CYAML_FIELD_ENUM("kind", ENUM_FLAGS, sc_model, kind, sc->kind_names, sc->num_kinds));
  ADD(model, CYAML_FIELD_ENUM("influence", ENUM_FLAGS, sc_model, influence, influence_names,
                              N_OF(influence_names)));
  ADD(model, CYAML_FIELD_FLOAT("gaussian_width", OPT, sc_model, gaussian_width));
  ADD(model, CYAML_FIELD_ENUM("stabilization", ENUM_FLAGS, sc_model, stabilization, stab_names,
                              N_OF(stab_names)));
  ADD(model,
      CYAML_FIELD_FLOAT("stabilization_coefficient", OPT, sc_model, stabilization_coefficient));
  ADD(model, CYAML_FIELD_ENUM("stabilization_softening", ENUM_FLAGS, sc_model,
                              stabilization_softening, softening_names, N_OF(softening_names)));
  ADD(model, CYAML_FIELD_FLOAT("stabilization_softening_floor", OPT, sc_model,
                               stabilization_softening_floor));
  ADD(model, CYAML_FIELD_ENUM("damage_triaxiality", ENUM_FLAGS, sc_model, damage_triaxiality,
                              triaxiality_names, N_OF(triaxiality_names)));
  ADD(model, CYAML_FIELD_ENUM("break_stress", ENUM_FLAGS, sc_model, break_stress,
                              break_stress_names, N_OF(break_stress_names)));
  ADD(model, CYAML_FIELD_ENUM("law", ENUM_FLAGS, sc_model, law, sc->law_names, sc->num_laws));
  ADD(model, CYAML_FIELD_ENUM("precision", ENUM_FLAGS, sc_model, precision, precision_names,
                              N_OF(precision_names)));
  ADD(model, CYAML_FIELD_ENUM("layout", ENUM_FLAGS, sc_model, layout, layout_names,
                              N_OF(layout_names)));
  ADD(model, CYAML_FIELD_ENUM("stencil", ENUM_FLAGS, sc_model, stencil, stencil_names,
                              N_OF(stencil_names)));
  ADD(model, CYAML_FIELD_FLOAT("critical_stretch", OPT, sc_model, critical_stretch));
  ADD(model, CYAML_FIELD_FLOAT("alpha", OPT, sc_model, alpha));
  ADD(model, CYAML_FIELD_BOOL("partial_volume", OPT, sc_model, partial_volume));
  ADD(model, CYAML_FIELD_ENUM("connectivity", ENUM_FLAGS, sc_model, connectivity,
                              connectivity_names, N_OF(connectivity_names)));
  ADD(model, CYAML_FIELD_FLOAT("compact_fraction", OPT, sc_model, compact_fraction));
  ADD(model, CYAML_FIELD_FLOAT("ul_skin", OPT, sc_model, ul_skin));
  ADD(model, CYAML_FIELD_BOOL("failed_keeps_bonds", OPT, sc_model, failed_keeps_bonds));
  ADD(model, CYAML_FIELD_MAPPING_PTR("galerkin", OPT_PTR, sc_model, galerkin, sc->galerkin));
  ADD(galerkin, CYAML_FIELD_ENUM("basis", ENUM_FLAGS, sc_galerkin, basis, galerkin_basis_names,
                                 N_OF(galerkin_basis_names)));
  ADD(galerkin, CYAML_FIELD_ENUM("form", ENUM_FLAGS, sc_galerkin, form, galerkin_form_names,
                                 N_OF(galerkin_form_names)));
  ADD(galerkin, CYAML_FIELD_ENUM("correction", ENUM_FLAGS, sc_galerkin, correction,
                                 galerkin_correction_names, N_OF(galerkin_correction_names)));
  ADD(galerkin, CYAML_FIELD_STRING_PTR("surface", OPT, sc_galerkin, surface, 1, 255));

  ADD(bc, CYAML_FIELD_STRING_PTR("set", 0, sc_bc, set, 1, 255));
  ADD(bc,
      CYAML_FIELD_ENUM("type", CYAML_FLAG_STRICT, sc_bc, type, bc_type_names, N_OF(bc_type_names)));
  ADD(bc, CYAML_FIELD_FLOAT("x", OPT, sc_bc, x));
  ADD(bc, CYAML_FIELD_FLOAT("y", OPT, sc_bc, y));
  ADD(bc, CYAML_FIELD_FLOAT("z", OPT, sc_bc, z));
  ADD(bc, CYAML_FIELD_ENUM("function", ENUM_FLAGS, sc_bc, function, function_names,
                           N_OF(function_names)));
  ADD(bc, CYAML_FIELD_FLOAT("duration", OPT, sc_bc, duration));
  ADD(bc, CYAML_FIELD_FLOAT("period", OPT, sc_bc, period));
  sc->bc_entry = (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, sc_bc, sc->bc)};

  ADD(initial, CYAML_FIELD_SEQUENCE_FIXED("velocity", OPT, sc_initial, velocity, &sc->num, d));
  ADD(initial, CYAML_FIELD_SEQUENCE_FIXED("velocity_gradient", OPT, sc_initial, velocity_gradient,
                                          &sc->point, d));

  ADD(solver,
      CYAML_FIELD_ENUM("type", ENUM_FLAGS, sc_solver, type, solver_names, N_OF(solver_names)));
  ADD(solver, CYAML_FIELD_FLOAT("end_time", OPT, sc_solver, end_time));
  ADD(solver, CYAML_FIELD_FLOAT("steps", OPT, sc_solver, steps));
  ADD(solver, CYAML_FIELD_FLOAT("dt", OPT, sc_solver, dt));
  ADD(solver, CYAML_FIELD_FLOAT("safety", OPT, sc_solver, safety));
  ADD(solver, CYAML_FIELD_BOOL("force_dt", OPT, sc_solver, force_dt));
  ADD(solver, CYAML_FIELD_ENUM("dt_update", ENUM_FLAGS, sc_solver, dt_update, dt_update_names,
                               N_OF(dt_update_names)));
  ADD(solver, CYAML_FIELD_FLOAT("dt_update_interval", OPT, sc_solver, dt_update_interval));
  ADD(solver, CYAML_FIELD_FLOAT("threads", OPT, sc_solver, threads));
  ADD(solver, CYAML_FIELD_FLOAT("load_steps", OPT, sc_solver, load_steps));
  ADD(solver,
      CYAML_FIELD_SEQUENCE("load_levels", OPT_PTR, sc_solver, load_levels, &sc->num, 1, 100000));
  ADD(solver, CYAML_FIELD_FLOAT("tolerance", OPT, sc_solver, tolerance));
  ADD(solver, CYAML_FIELD_FLOAT("absolute_tolerance", OPT, sc_solver, absolute_tolerance));
  ADD(solver, CYAML_FIELD_FLOAT("max_iterations", OPT, sc_solver, max_iterations));
  ADD(solver, CYAML_FIELD_FLOAT("max_break_rounds", OPT, sc_solver, max_break_rounds));
  ADD(solver, CYAML_FIELD_BOOL("extrapolate", OPT, sc_solver, extrapolate));
  ADD(solver, CYAML_FIELD_ENUM("adr_mass", ENUM_FLAGS, sc_solver, adr_mass, adr_mass_names,
                               N_OF(adr_mass_names)));
  ADD(solver, CYAML_FIELD_FLOAT("adr_safety", OPT, sc_solver, adr_safety));
  ADD(solver, CYAML_FIELD_ENUM("linear_solver", ENUM_FLAGS, sc_solver, linear_solver,
                               linear_solver_names, N_OF(linear_solver_names)));
  ADD(solver, CYAML_FIELD_ENUM("tangent", ENUM_FLAGS, sc_solver, tangent, tangent_names,
                               N_OF(tangent_names)));
  ADD(solver, CYAML_FIELD_ENUM("fd_scheme", ENUM_FLAGS, sc_solver, fd_scheme, fd_scheme_names,
                               N_OF(fd_scheme_names)));
  ADD(solver, CYAML_FIELD_FLOAT("fd_step", OPT, sc_solver, fd_step));
  ADD(solver, CYAML_FIELD_FLOAT("line_search_backtracks", OPT, sc_solver, line_search_backtracks));
  ADD(solver, CYAML_FIELD_FLOAT("line_search_decrease", OPT, sc_solver, line_search_decrease));
  ADD(solver, CYAML_FIELD_BOOL("reuse_tangent", OPT, sc_solver, reuse_tangent));
  ADD(solver, CYAML_FIELD_FLOAT("singular_tolerance", OPT, sc_solver, singular_tolerance));
  ADD(solver, CYAML_FIELD_FLOAT("symmetry_tolerance", OPT, sc_solver, symmetry_tolerance));

  ADD(output, CYAML_FIELD_FLOAT("field_interval", OPT, sc_output, field_interval));
  ADD(output, CYAML_FIELD_SEQUENCE("fields", OPT_PTR, sc_output, fields, &sc->str, 0, 64));
  ADD(output, CYAML_FIELD_FLOAT("history_interval", OPT, sc_output, history_interval));
  ADD(output, CYAML_FIELD_SEQUENCE("reactions", OPT_PTR, sc_output, reactions, &sc->str, 0, 64));
  ADD(output, CYAML_FIELD_FLOAT("checkpoint_interval", OPT, sc_output, checkpoint_interval));
  ADD(output,
      CYAML_FIELD_ENUM("units", ENUM_FLAGS, sc_output, units, units_names, N_OF(units_names)));
  ADD(output, CYAML_FIELD_FLOAT("compression", OPT, sc_output, compression));

  ADD(scene, CYAML_FIELD_STRING_PTR("name", OPT, sc_scene, name, 1, 255));
  ADD(scene, CYAML_FIELD_STRING_PTR("description", OPT, sc_scene, description, 0, CYAML_UNLIMITED));
  ADD(scene, CYAML_FIELD_FLOAT("dimension", 0, sc_scene, dimension));
  ADD(scene, CYAML_FIELD_MAPPING("geometry", 0, sc_scene, geometry, sc->geometry));
  ADD(scene, CYAML_FIELD_MAPPING("material", 0, sc_scene, material, sc->material));
  ADD(scene, CYAML_FIELD_MAPPING("model", OPT, sc_scene, model, sc->model));
  ADD(scene, CYAML_FIELD_SEQUENCE("sets", OPT_PTR, sc_scene, sets, &sc->set_entry, 0, 10000));
  ADD(scene, CYAML_FIELD_SEQUENCE("materials", OPT_PTR, sc_scene, materials, &sc->material_entry,
                                  0, 255));
  ADD(scene, CYAML_FIELD_SEQUENCE("boundary_conditions", OPT_PTR, sc_scene, boundary_conditions,
                                  &sc->bc_entry, 0, 64));
  ADD(scene,
      CYAML_FIELD_MAPPING("initial_conditions", OPT, sc_scene, initial_conditions, sc->initial));
  ADD(scene, CYAML_FIELD_MAPPING("solver", 0, sc_scene, solver, sc->solver));
  ADD(scene, CYAML_FIELD_MAPPING("output", OPT, sc_scene, output, sc->output));
  ADD(limits, CYAML_FIELD_FLOAT("memory", OPT, sc_limits, memory));
  ADD(scene, CYAML_FIELD_MAPPING("limits", OPT, sc_scene, limits, sc->limits));
  sc->top = (cyaml_schema_value_t){CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, sc_scene, sc->scene)};
}

/* ---- schema lookup by key path (for messages) --------------------------------------------------
 */

/* The schema value at key path `path` (segments "a.b[2].c"), or NULL. */
static const cyaml_schema_value_t *schema_at(const cyaml_schema_value_t *v, const char *path) {
  const char *c = path;
  while (v && *c) {
    if (*c == '.') ++c;
    if (*c == '[') {
      if (v->type != CYAML_SEQUENCE && v->type != CYAML_SEQUENCE_FIXED) return NULL;
      v = v->sequence.entry;
      c = strchr(c, ']');
      if (!c) return NULL;
      ++c;
      continue;
    }
    size_t len = strcspn(c, ".[");
    if (v->type != CYAML_MAPPING) return NULL;
    const cyaml_schema_field_t *f = v->mapping.fields, *hit = NULL;
    for (; f && f->key; ++f)
      if (strlen(f->key) == len && !strncmp(f->key, c, len)) hit = f;
    if (!hit) return NULL;
    v = &hit->value;
    c += len;
  }
  return v;
}

static void list_keys(const cyaml_schema_value_t *v, int required_only, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  if (!v || v->type != CYAML_MAPPING) return;
  for (const cyaml_schema_field_t *f = v->mapping.fields; f && f->key; ++f) {
    if (required_only && (f->value.flags & CYAML_FLAG_OPTIONAL)) continue;
    int w = snprintf(buf + pos, len - pos, "%s%s", pos ? ", " : "", f->key);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
}

static void list_enum(const cyaml_schema_value_t *v, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  if (!v || v->type != CYAML_ENUM) return;
  for (uint32_t i = 0; i < v->enumeration.count; ++i) {
    int w = snprintf(buf + pos, len - pos, "%s%s", i ? ", " : "", v->enumeration.strings[i].str);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
}

static const char *type_words(const cyaml_schema_value_t *v) {
  if (!v) return "a value of another type";
  switch (v->type) {
  case CYAML_FLOAT: return "a number";
  case CYAML_INT:
  case CYAML_UINT: return "a whole number";
  case CYAML_BOOL: return "true or false";
  case CYAML_STRING: return "a word or quoted string";
  case CYAML_ENUM: return "one of the listed words";
  case CYAML_MAPPING: return "a mapping of keys (key: value)";
  case CYAML_SEQUENCE:
  case CYAML_SEQUENCE_FIXED: return "a list [a, b, ...]";
  default: return "a value of another type";
  }
}

/* What to write instead, for a value of the wrong type. */
static void type_hint(const cyaml_schema_value_t *v, char *buf, size_t len) {
  char keys[512];
  if (!v) {
    snprintf(buf, len, "see docs/scenes.md");
    return;
  }
  switch (v->type) {
  case CYAML_FLOAT:
  case CYAML_INT:
  case CYAML_UINT: snprintf(buf, len, "write for example 0.5, 2e-3 or 200e9"); break;
  case CYAML_BOOL: snprintf(buf, len, "write true or false"); break;
  case CYAML_STRING: snprintf(buf, len, "write a word or a quoted string"); break;
  case CYAML_MAPPING:
    list_keys(v, 0, keys, sizeof keys);
    snprintf(buf, len, "give its keys on the lines below it, or as {key: value, ...}; keys: %s",
             keys);
    break;
  case CYAML_SEQUENCE:
  case CYAML_SEQUENCE_FIXED: snprintf(buf, len, "write a list, [a, b, ...] or '- a' lines"); break;
  default: snprintf(buf, len, "see docs/scenes.md"); break;
  }
}

/* ---- libcyaml log capture and translation ------------------------------------------------------
 */

typedef struct cy_log {
  char text[4096];
  size_t len;
} cy_log;

static void cy_log_fn(cyaml_log_t level, void *ctx, const char *fmt, va_list args) {
  cy_log *log = ctx;
  if (level < CYAML_LOG_ERROR || log->len + 1 >= sizeof log->text) return;
  int w = vsnprintf(log->text + log->len, sizeof log->text - log->len, fmt, args);
  if (w > 0) log->len += (size_t)w;
  if (log->len >= sizeof log->text) log->len = sizeof log->text - 1;
}

/* Turns libcyaml's message and backtrace into a scene message. Returns 0 when the log holds
 * nothing recognizable (the caller keeps the generic libcyaml failure message). The backtrace is
 * innermost first: "  in mapping field 'k' (line ...)", "  in sequence entry 'n' (...)", "  in
 * mapping (...)". While an entry is being loaded, n counts it (1-based); for "Insufficient" and
 * "Excessive entries" n is the count reached, and the error is about the sequence itself. */
static int cy_translate(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc,
                        const cy_log *log) {
  char msg[512] = "";
  char frames[32][KEY_MAX];
  int is_entry[32];
  int nf = 0;
  const char *c = log->text;
  while (*c) {
    const char *eol = strchr(c, '\n');
    size_t len = eol ? (size_t)(eol - c) : strlen(c);
    char line[512];
    if (len >= sizeof line) len = sizeof line - 1;
    memcpy(line, c, len);
    line[len] = '\0';
    c += len + (eol ? 1 : 0);
    char name[KEY_MAX];
    unsigned idx;
    if (!strncmp(line, "Load: ", 6) && strcmp(line, "Load: Backtrace:")) {
      if (!msg[0]) snprintf(msg, sizeof msg, "%s", line + 6);
    } else if (sscanf(line, "  in mapping field '%255[^']'", name) == 1 && nf < 32) {
      snprintf(frames[nf], KEY_MAX, "%s", name);
      is_entry[nf++] = 0;
    } else if (sscanf(line, "  in sequence entry '%u'", &idx) == 1 && nf < 32) {
      snprintf(frames[nf], KEY_MAX, "%u", idx);
      is_entry[nf++] = 1;
    }
  }
  if (!msg[0]) return 0;
  int about_sequence =
      !strncmp(msg, "Insufficient entries", 20) || !strncmp(msg, "Excessive entries", 17);
  /* For a missing key, the innermost frame is the last field libcyaml saw in that mapping (or the
   * first field of an empty one): not part of the mapping's path. */
  const int missing = !strncmp(msg, "Missing required mapping field", 30);
  int first = 0;
  if (about_sequence && nf > 0 && is_entry[0]) first = 1;
  if (missing && nf > 0 && !is_entry[0]) first = 1;
  /* Key path, outermost first. */
  char path[KEY_MAX] = "";
  for (int f = nf - 1; f >= first; --f) {
    size_t pos = strlen(path);
    if (is_entry[f]) {
      unsigned n = (unsigned)strtoul(frames[f], NULL, 10);
      snprintf(path + pos, sizeof path - pos, "[%u]", n > 0 ? n - 1 : 0);
    } else {
      snprintf(path + pos, sizeof path - pos, "%s%s", pos ? "." : "", frames[f]);
    }
  }
  char arg[256] = "", allowed[512];
  const char *colon = strchr(msg, ':');
  if (colon) snprintf(arg, sizeof arg, "%s", colon + 2 <= msg + strlen(msg) ? colon + 2 : "");
  const pdk_scene_key *key = pdk_scene_key_get(s, path);
  const char *got = key && key->value ? key->value : NULL;

  if (!strncmp(msg, "Unexpected key", 14)) {
    list_keys(schema_at(&sc->top, path), 0, allowed, sizeof allowed);
    char full[2 * KEY_MAX + 2];
    snprintf(full, sizeof full, "%s%s%s", path, path[0] ? "." : "", arg);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, full, "unknown key '%s'; %s allows: %s", arg,
                           path[0] ? path : "the top level", allowed);
  }
  if (missing) {
    char full[2 * KEY_MAX + 2], parent[KEY_MAX];
    snprintf(full, sizeof full, "%s%s%s", path, path[0] ? "." : "", arg);
    snprintf(parent, sizeof parent, "%s", path);
    list_keys(schema_at(&sc->top, parent), 1, allowed, sizeof allowed);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, full,
                           "required key is missing; %s needs: %s (see docs/scenes.md)",
                           parent[0] ? parent : "the top level", allowed);
  }
  if (!strncmp(msg, "Invalid ENUM value", 18)) {
    list_enum(schema_at(&sc->top, path), allowed, sizeof allowed);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "unknown value '%s'; allowed: %s", arg,
                           allowed);
  }
  if (!strncmp(msg, "Invalid FLOAT value", 19) || !strncmp(msg, "Invalid INT value", 17) ||
      !strncmp(msg, "Invalid UINT value", 18))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path,
                           "must be a number, got '%s'; write for "
                           "example 0.5, 2e-3 or 200e9",
                           got ? got : arg);
  if (!strncmp(msg, "Expecting ", 10)) {
    const cyaml_schema_value_t *v = schema_at(&sc->top, path);
    char hint[600];
    type_hint(v, hint, sizeof hint);
    const char *what = strstr(msg, "SEQUENCE_START")  ? "a list"
                       : strstr(msg, "MAPPING_START") ? "a mapping"
                       : got                          ? NULL
                                                      : "a single value";
    if (v && v->type == CYAML_ENUM) {
      list_enum(v, allowed, sizeof allowed);
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be one word, got %s; allowed: %s",
                             what ? what : "something else", allowed);
    }
    if (what)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be %s, got %s; %s", type_words(v),
                             what, hint);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be %s, got '%s'; %s", type_words(v),
                           got, hint);
  }
  if (about_sequence) {
    const cyaml_schema_value_t *v = schema_at(&sc->top, path);
    unsigned have = 0, want = 0;
    const int is_point = v && v->type == CYAML_SEQUENCE_FIXED && v->sequence.entry &&
                         v->sequence.entry->type == CYAML_FLOAT;
    const int excess = !strncmp(msg, "Excessive", 9);
    if (excess)
      sscanf(msg, "Excessive entries (%u max)", &want);
    else
      sscanf(msg, "Insufficient entries (%u of %u min)", &have, &want);
    /* libcyaml stops at the first entry too many; the document says how many there are. */
    unsigned count = key && key->count >= 0 ? (unsigned)key->count : want + 1;
    if (!excess) count = have;
    if (is_point)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path,
                             "must have %u numbers, got %u; a point has one number per axis "
                             "(dimension is %d)",
                             want, count, s->dim);
    if (v && v->type == CYAML_SEQUENCE_FIXED)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must have %u entries, got %u", want,
                             count);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must have at %s %u entries, got %u",
                           excess ? "most" : "least", want, count);
  }
  if (!strncmp(msg, "Mapping field already seen", 26))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "given twice; give each key once");
  if (!strncmp(msg, "String length", 13) || strstr(msg, "string length"))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "%s; names are 1 to 255 characters", msg);
  return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "%s; see docs/scenes.md", msg);
}

/* A YAML decimal number, whole: [+-] digits [. digits] [e [+-] digits], or [+-] . digits [e ...];
 * `integer`: digits only. No hexadecimal, inf, nan, '_' or ','. */
static int is_number_text(const char *v, int integer) {
  const char *c = v;
  if (*c == '+' || *c == '-') ++c;
  int digits = 0;
  while (isdigit((unsigned char)*c)) {
    ++c;
    ++digits;
  }
  if (integer) return digits > 0 && !*c;
  if (*c == '.') {
    ++c;
    while (isdigit((unsigned char)*c)) {
      ++c;
      ++digits;
    }
  }
  if (!digits) return 0;
  if (*c == 'e' || *c == 'E') {
    ++c;
    if (*c == '+' || *c == '-') ++c;
    if (!isdigit((unsigned char)*c)) return 0;
    while (isdigit((unsigned char)*c))
      ++c;
  }
  return *c == '\0';
}

/* Step 2, before libcyaml: every single value whose key the schema types as a number or a boolean,
 * and every list against its cap. libcyaml would read "0,29" as 0 and "flase" as true; counting a
 * list first keeps a long one from costing more than reading it. */
static int scalars_check(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc) {
  for (int k = 0; k < s->num_keys; ++k) {
    const pdk_scene_key *key = &s->keys[k];
    const cyaml_schema_value_t *v = schema_at(&sc->top, key->path);
    if (!v) continue; /* an unknown key: libcyaml names it */
    if (key->count >= 0) {
      if (v->type == CYAML_SEQUENCE && v->sequence.max != CYAML_UNLIMITED &&
          key->count > (long)v->sequence.max)
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must have at most %u entries, got %ld", v->sequence.max,
                               key->count);
      continue;
    }
    if (!key->value) continue; /* a mapping */
    char shown[128];
    pdk_scene_quote(key->value, shown, sizeof shown);
    switch (v->type) {
    case CYAML_FLOAT:
    case CYAML_INT:
    case CYAML_UINT: {
      const int integer = v->type != CYAML_FLOAT;
      if (!key->value[0])
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be %s, got nothing; write for example %s", type_words(v),
                               integer ? "0, 10 or 250" : "0.5, 2e-3 or 200e9");
      if (!is_number_text(key->value, integer))
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be %s, got '%s'; write for example %s (the whole value is "
                               "the number: no unit, '_' or ',')",
                               type_words(v), shown,
                               integer ? "0, 10 or 250" : "0.5, 2e-3 or 200e9");
      if (!isfinite(strtod(key->value, NULL)))
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be a finite number, got '%s', beyond the largest double "
                               "(1.8e308)",
                               shown);
      break;
    }
    case CYAML_BOOL: {
      static const char *const words[] = {"true", "True", "TRUE", "false", "False", "FALSE"};
      int ok = 0;
      for (int w = 0; w < 6; ++w)
        ok |= !strcmp(key->value, words[w]);
      if (!ok)
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path, "must be true or false, got '%s'",
                               shown);
      break;
    }
    default: break;
    }
  }
  return PDK_SUCCESS;
}

static int scene_schema_load(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc,
                             const cyaml_config_t *cfg, const char *yaml, size_t len,
                             sc_scene **out) {
  int err = PDK_SUCCESS;
  PDK_CYAML_CALL_GOTO(
      ctx, cyaml_load_data((const uint8_t *)yaml, len, cfg, &sc->top, (cyaml_data_t **)out, NULL));
cleanup:
  if (err) {
    const cy_log *log = cfg->log_ctx;
    int translated = cy_translate(ctx, s, sc, log);
    if (translated) err = translated;
  }
  return err;
}

static int scene_schema_free(pdk_ctx *ctx, const scene_schema *sc, const cyaml_config_t *cfg,
                             sc_scene *data) {
  int err = PDK_SUCCESS;
  PDK_CYAML_CALL_GOTO(ctx, cyaml_free(cfg, &sc->top, data, 0));
cleanup:
  return err;
}

/* ---- checks ------------------------------------------------------------------------------------
 */

typedef struct loader {
  pdk_ctx *ctx;
  pdk_scene *s;
  char key[KEY_MAX];
} loader;

/* Formats a key path into ld->key and returns it. */
static const char *K(loader *ld, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static const char *K(loader *ld, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ld->key, sizeof ld->key, fmt, ap);
  va_end(ap);
  return ld->key;
}

static int has(const loader *ld, const char *path) {
  return pdk_scene_key_get(ld->s, path) != NULL;
}

#define FAIL(ld, key, ...)                                                                         \
  return pdk_scene_error((ld)->s, (ld)->ctx, PDK_ERR_ARG, (key), __VA_ARGS__)
#define REQUIRE(ld, cond, key, ...)                                                                \
  do {                                                                                             \
    if (!(cond)) FAIL(ld, key, __VA_ARGS__);                                                       \
  } while (0)

static int check_whole(loader *ld, const char *key, double v, double lo, double hi, long *out) {
  if (hi >= 1e15)
    REQUIRE(ld, isfinite(v) && v == floor(v) && v >= lo && v <= hi, key,
            "must be a whole number >= %.0f, got %g", lo, v);
  REQUIRE(ld, isfinite(v) && v == floor(v) && v >= lo && v <= hi, key,
          "must be a whole number in [%.0f, %.0f], got %g", lo, hi, v);
  *out = (long)v;
  return PDK_SUCCESS;
}

static int check_point(loader *ld, const char *key, const double *v) {
  for (int a = 0; a < ld->s->dim; ++a)
    REQUIRE(ld, isfinite(v[a]), key, "entry %d is %g; coordinates must be finite numbers", a, v[a]);
  return PDK_SUCCESS;
}

static void fmt_point(char *buf, size_t len, int dim, const double *v) {
  if (dim == 2)
    snprintf(buf, len, "[%g, %g]", v[0], v[1]);
  else
    snprintf(buf, len, "[%g, %g, %g]", v[0], v[1], v[2]);
}

static int valid_name(const char *n) {
  if (!n || !n[0] || strlen(n) > SC_NAME_MAX) return 0;
  for (const char *c = n; *c; ++c)
    if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-' && *c != '.') return 0;
  return 1;
}

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

/* Region kind of an sc_region: fills out->region (and its polygon vertices) and out->key.
 * `base` is the region's key path ("geometry.holes[0]", "sets[1]"). */
static int region_resolve(loader *ld, const sc_region *r, const char *base, int allow_halfspace,
                          pdk_scene_region *out) {
  const int dim = ld->s->dim;
  const char *kinds[5] = {"box", "disk", "ball", "halfspace", "polygon"};
  const void *given[5] = {r->box, r->disk, r->ball, r->halfspace, r->polygon};
  int which = -1, count = 0;
  for (int k = 0; k < 5; ++k)
    if (given[k]) {
      if (which >= 0 && count == 1)
        FAIL(ld, base,
             "gives both %s and %s; give exactly one region: box, disk (ball), "
             "halfspace or polygon",
             kinds[which], kinds[k]);
      which = k;
      ++count;
    }
  REQUIRE(ld, which >= 0, base,
          "gives no region; give one of box, disk (2-D) or ball, halfspace, "
          "polygon (2-D)");
  snprintf(out->key, sizeof out->key, "%s.%s", base, kinds[which]);
  char sub[KEY_MAX];
  switch (which) {
  case 0:
    snprintf(sub, sizeof sub, "%s.lo", out->key);
    PDK_CALL(check_point(ld, sub, r->box->lo));
    snprintf(sub, sizeof sub, "%s.hi", out->key);
    PDK_CALL(check_point(ld, sub, r->box->hi));
    for (int a = 0; a < dim; ++a)
      REQUIRE(ld, r->box->lo[a] <= r->box->hi[a], sub,
              "must be >= lo on every axis; axis %d has lo %g > hi %g", a, r->box->lo[a],
              r->box->hi[a]);
    out->region = pdk_region_box(r->box->lo, r->box->hi);
    break;
  case 1:
  case 2: {
    const sc_ball *b = which == 1 ? r->disk : r->ball;
    snprintf(sub, sizeof sub, "%s.center", out->key);
    PDK_CALL(check_point(ld, sub, b->center));
    snprintf(sub, sizeof sub, "%s.radius", out->key);
    REQUIRE(ld, isfinite(b->radius) && b->radius > 0, sub, "must be > 0, got %g", b->radius);
    out->region = pdk_region_ball(b->center, b->radius);
    break;
  }
  case 3:
    REQUIRE(ld, allow_halfspace, out->key,
            "a half-space is unbounded, so it cannot be a hole; use geometry.notches for cuts "
            "that reach the boundary");
    snprintf(sub, sizeof sub, "%s.point", out->key);
    PDK_CALL(check_point(ld, sub, r->halfspace->point));
    snprintf(sub, sizeof sub, "%s.normal", out->key);
    PDK_CALL(check_point(ld, sub, r->halfspace->normal));
    {
      double n2 = 0;
      for (int a = 0; a < dim; ++a)
        n2 += r->halfspace->normal[a] * r->halfspace->normal[a];
      REQUIRE(ld, n2 > 0, sub, "must not be zero; it points out of the half-space");
    }
    out->region = pdk_region_halfspace(r->halfspace->point, r->halfspace->normal);
    break;
  case 4: {
    REQUIRE(ld, dim == 2, out->key, "a polygon is a 2-D region; in 3-D use box, ball or halfspace");
    int nv = (int)r->polygon->vertices_count;
    out->vertices = malloc((size_t)nv * 2 * sizeof(double));
    if (!out->vertices)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for a polygon");
    for (int v = 0; v < nv; ++v) {
      snprintf(sub, sizeof sub, "%s.vertices[%d]", out->key, v);
      PDK_CALL(check_point(ld, sub, r->polygon->vertices[v]));
      out->vertices[2 * v] = r->polygon->vertices[v][0];
      out->vertices[2 * v + 1] = r->polygon->vertices[v][1];
    }
    out->region = pdk_region_polygon(out->vertices, nv);
    break;
  }
  }
  out->region.invert = r->invert ? 1 : 0;
  int err = pdk_region_check(ld->ctx, dim, &out->region);
  if (err) return pdk_scene_blame(ld->s, ld->ctx, err, out->key);
  return PDK_SUCCESS;
}

/* A hole must leave material and lie inside the body's box. */
static int hole_check(loader *ld, const pdk_scene_region *h) {
  const int dim = ld->s->dim;
  const double *blo = ld->s->lattice.lo, *bhi = ld->s->lattice.hi;
  char lo_s[96], hi_s[96];
  fmt_point(lo_s, sizeof lo_s, dim, blo);
  fmt_point(hi_s, sizeof hi_s, dim, bhi);
  int corners_in = 1;
  for (int m = 0; m < (1 << dim); ++m) {
    double x[3];
    for (int a = 0; a < dim; ++a)
      x[a] = (m >> a) & 1 ? bhi[a] : blo[a];
    corners_in &= pdk_region_contains(&h->region, dim, x);
  }
  REQUIRE(ld, !corners_in, h->key,
          "covers the whole body (geometry.box %s..%s), so nothing would remain; a hole must "
          "leave material",
          lo_s, hi_s);
  double rlo[3] = {0, 0, 0}, rhi[3] = {0, 0, 0};
  const pdk_region *r = &h->region;
  for (int a = 0; a < dim; ++a) {
    switch (r->kind) {
    case PDK_REGION_BOX:
      rlo[a] = r->lo[a];
      rhi[a] = r->hi[a];
      break;
    case PDK_REGION_BALL:
      rlo[a] = r->center[a] - r->radius;
      rhi[a] = r->center[a] + r->radius;
      break;
    case PDK_REGION_POLYGON:
      rlo[a] = rhi[a] = r->vertices[a];
      for (int v = 1; v < r->num_vertices; ++v) {
        rlo[a] = fmin(rlo[a], r->vertices[2 * v + a]);
        rhi[a] = fmax(rhi[a], r->vertices[2 * v + a]);
      }
      break;
    case PDK_REGION_HALFSPACE: break;
    }
  }
  for (int a = 0; a < dim; ++a)
    REQUIRE(ld, rlo[a] >= blo[a] && rhi[a] <= bhi[a], h->key,
            "reaches outside the body (geometry.box %s..%s): it spans [%g, %g] on axis %c; a hole "
            "must lie inside the box (use geometry.notches for cuts that reach the boundary)",
            lo_s, hi_s, rlo[a], rhi[a], "xyz"[a]);
  return PDK_SUCCESS;
}

/* geometry.holes, notches and precracks, over the body (lattice or cloud) resolved before. */
static int resolve_cuts(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const int dim = s->dim;
  s->num_holes = (int)g->holes_count;
  s->num_notches = (int)g->notches_count;
  s->holes = calloc(g->holes_count + 1, sizeof *s->holes);
  s->notches = calloc(g->notches_count + 1, sizeof *s->notches);
  if (!s->holes || !s->notches)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for holes");
  for (int k = 0; k < s->num_holes; ++k) {
    PDK_CALL(region_resolve(ld, &g->holes[k], K(ld, "geometry.holes[%d]", k), 0, &s->holes[k]));
    PDK_CALL(hole_check(ld, &s->holes[k]));
  }
  for (int k = 0; k < s->num_notches; ++k)
    PDK_CALL(
        region_resolve(ld, &g->notches[k], K(ld, "geometry.notches[%d]", k), 1, &s->notches[k]));

  /* Pre-cracks: segments in 2-D, planar polygons in 3-D. */
  size_t nvert = 0;
  for (unsigned k = 0; k < g->precracks_count; ++k)
    nvert += g->precracks[k].segment_count + g->precracks[k].polygon_count;
  s->num_precracks = (int)g->precracks_count;
  s->precracks = calloc(g->precracks_count + 1, sizeof *s->precracks);
  s->crack_vertices = malloc((nvert + 1) * 3 * sizeof(double));
  if (!s->precracks || !s->crack_vertices)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for pre-cracks");
  double *v = s->crack_vertices;
  for (int k = 0; k < s->num_precracks; ++k) {
    const sc_precrack *c = &g->precracks[k];
    const char *base = K(ld, "geometry.precracks[%d]", k);
    REQUIRE(ld, !(c->segment && c->polygon), base,
            "gives both segment and polygon; a 2-D "
            "pre-crack is a segment, a 3-D one a polygon");
    REQUIRE(ld, c->segment || c->polygon, base, "gives no crack; give %s",
            dim == 2 ? "segment: [[x0, y0], [x1, y1]]" : "polygon: [[x, y, z], ...] (>= 3 points)");
    if (dim == 2)
      REQUIRE(ld, c->segment, K(ld, "geometry.precracks[%d].polygon", k),
              "a 2-D pre-crack is a segment: [[x0, y0], [x1, y1]]");
    else
      REQUIRE(ld, c->polygon, K(ld, "geometry.precracks[%d].segment", k),
              "a 3-D pre-crack is a planar polygon: [[x, y, z], ...] with >= 3 points");
    const double(*pts)[3] = (const double(*)[3])(c->segment ? c->segment : c->polygon);
    int np = (int)(c->segment ? c->segment_count : c->polygon_count);
    char sub[KEY_MAX];
    snprintf(sub, sizeof sub, "geometry.precracks[%d].%s", k, c->segment ? "segment" : "polygon");
    for (int p = 0; p < np; ++p) {
      char pk[KEY_MAX + 16];
      snprintf(pk, sizeof pk, "%s[%d]", sub, p);
      PDK_CALL(check_point(ld, pk, pts[p]));
      for (int a = 0; a < dim; ++a)
        v[p * dim + a] = pts[p][a];
    }
    if (dim == 2) {
      double dx = v[2] - v[0], dy = v[3] - v[1];
      REQUIRE(ld, dx * dx + dy * dy > 0, sub, "has zero length; give two different end points");
    }
    s->precracks[k].num_vertices = np;
    s->precracks[k].vertices = v;
    v += (size_t)np * (size_t)dim;
  }
  return PDK_SUCCESS;
}

/* geometry.points: the body is the particles of a CSV file (src/points.h), its path relative to
 * the scene's folder. geometry.spacing stays the nominal spacing (horizon = horizon_factor x
 * spacing); box, lattice, jitter and seed describe a lattice and are refused. */
static int resolve_points(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const char *lattice_keys[] = {"geometry.box", "geometry.lattice", "geometry.jitter",
                                "geometry.seed"};
  for (int k = 0; k < 4; ++k)
    REQUIRE(ld, !has(ld, lattice_keys[k]), lattice_keys[k],
            "describes a lattice, but geometry.points gives the particles; remove one of them");
  char path[8192];
  if (g->points[0] == '/' || !strchr(s->path, '/'))
    snprintf(path, sizeof path, "%s", g->points);
  else
    snprintf(path, sizeof path, "%.*s/%s", (int)(strrchr(s->path, '/') - s->path), s->path,
             g->points);
  s->points = calloc(1, sizeof *s->points);
  if (!s->points) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  const double thickness = s->dim == 2 ? s->lattice.thickness : 1.0;
  const size_t plen = strlen(path);
  const int h5 = (plen > 3 && !strcmp(path + plen - 3, ".h5")) ||
                 (plen > 5 && !strcmp(path + plen - 5, ".hdf5"));
  int err = h5 ? pdk_points_read_h5(ld->ctx, path, s->dim, s->points)
               : pdk_points_read_csv(ld->ctx, path, s->dim, thickness, s->points);
  if (err) {
    free(s->points);
    s->points = NULL;
    return pdk_scene_blame(s, ld->ctx, err, "geometry.points");
  }
  s->num_points = s->points->n;
  memcpy(s->lattice.lo, s->points->lo, sizeof s->lattice.lo);
  memcpy(s->lattice.hi, s->points->hi, sizeof s->lattice.hi);
  return resolve_cuts(ld, g);
}

static int resolve_geometry(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const int dim = s->dim;
  pdk_lattice_opts *lo = &s->lattice;
  *lo = pdk_lattice_opts_default();
  if (has(ld, "geometry.lattice")) {
    lo->type = (pdk_lattice_type)g->lattice;
    REQUIRE(ld, (dim == 3) == (lo->type == PDK_LATTICE_CUBIC), "geometry.lattice",
            "'%s' is a %d-D lattice but dimension is %d; use %s", lattice_names[g->lattice].str,
            lo->type == PDK_LATTICE_CUBIC ? 3 : 2, dim, dim == 2 ? "square or hex" : "cubic");
  } else {
    lo->type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  }
  REQUIRE(ld, isfinite(g->spacing) && g->spacing > 0, "geometry.spacing",
          "must be > 0, got %g; the lattice spacing is a length", g->spacing);
  lo->spacing = g->spacing;
  s->horizon_factor = has(ld, "geometry.horizon_factor") ? g->horizon_factor : 3.015;
  REQUIRE(ld, isfinite(s->horizon_factor) && s->horizon_factor > 1, "geometry.horizon_factor",
          "must be > 1, got %g; the horizon is horizon_factor x spacing (3.015 is usual)",
          s->horizon_factor);
  s->horizon = s->horizon_factor * g->spacing;
  lo->jitter = g->jitter;
  REQUIRE(ld, isfinite(g->jitter) && g->jitter >= 0 && g->jitter < 0.5, "geometry.jitter",
          "must be in [0, 0.5) (a fraction of the spacing), got %g", g->jitter);
  long seed = 1;
  if (has(ld, "geometry.seed"))
    PDK_CALL(check_whole(ld, "geometry.seed", g->seed, 0, 9007199254740992.0, &seed));
  lo->seed = (uint64_t)seed;
  if (has(ld, "geometry.thickness")) {
    REQUIRE(ld, dim == 2, "geometry.thickness",
            "only 2-D scenes have a thickness (dimension is 3); remove it");
    REQUIRE(ld, isfinite(g->thickness) && g->thickness > 0, "geometry.thickness",
            "must be > 0, got %g (the out-of-plane thickness, a length)", g->thickness);
    lo->thickness = g->thickness;
  }
  if (has(ld, "geometry.points")) return resolve_points(ld, g);
  REQUIRE(ld, has(ld, "geometry.box"), "geometry",
          "has no body: give geometry.box (a lattice over the box) or geometry.points (a point "
          "cloud file)");
  PDK_CALL(check_point(ld, "geometry.box.lo", g->box.lo));
  PDK_CALL(check_point(ld, "geometry.box.hi", g->box.hi));
  for (int a = 0; a < dim; ++a)
    REQUIRE(ld, g->box.hi[a] > g->box.lo[a], "geometry.box.hi",
            "must exceed lo on every axis; axis %c has lo %g, hi %g", "xyz"[a], g -> box.lo[a],
            g->box.hi[a]);
  memcpy(lo->lo, g->box.lo, sizeof lo->lo);
  memcpy(lo->hi, g->box.hi, sizeof lo->hi);
  pdk_index count = 0;
  int err = pdk_lattice_count(ld->ctx, lo, &count);
  s->num_points = count;
  if (err) {
    /* Too many points: the spacing is the usual culprit; too few: the box. */
    double cells = 1;
    for (int a = 0; a < dim; ++a)
      cells *= (g->box.hi[a] - g->box.lo[a]) / g->spacing;
    return pdk_scene_blame(s, ld->ctx, err, cells > 1e9 ? "geometry.spacing" : "geometry.box");
  }

  return resolve_cuts(ld, g);
}

/* A Johnson-Cook key that the chosen options do not use is an error naming what would use it. */
static int jc_unused(loader *ld, const char *const *keys, int num, const char *why) {
  char key[KEY_MAX];
  for (int k = 0; k < num; ++k) {
    snprintf(key, sizeof key, "material.johnson_cook.%s", keys[k]);
    REQUIRE(ld, !has(ld, key), key, "%s", why);
  }
  return PDK_SUCCESS;
}

/* A required Johnson-Cook number: present and finite. */
static int jc_needed(loader *ld, const char *name, double v, const char *why) {
  char key[KEY_MAX];
  snprintf(key, sizeof key, "material.johnson_cook.%s", name);
  REQUIRE(ld, has(ld, key), key, "is missing; %s", why);
  REQUIRE(ld, isfinite(v), key, "must be a finite number, got %g", v);
  return PDK_SUCCESS;
}

/* material.johnson_cook -> model.jc, for model.law: jc. The elastic constants and the density come
 * from `material` (the model checks they agree with jc to 1e-9, which they do by construction).
 * Every key is checked here against its own scene key; pdk_jc_params_check runs last as a
 * backstop. */
static int resolve_johnson_cook(loader *ld, const sc_material *mat, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  const int hjc = has(ld, "material.johnson_cook") && mat->johnson_cook;
  if (!pdk_model_opts_law_has(m, PDK_LAWF_PLASTICITY)) {
    REQUIRE(ld, !has(ld, "material.johnson_cook"), "material.johnson_cook",
            "only the jc law uses it (model.law is %s); remove it or set model.law: jc",
            pdk_law_name(m->law));
    REQUIRE(ld, !has(ld, "model.failed_keeps_bonds"), "model.failed_keeps_bonds",
            "only the jc law with damage has failed particles (model.law is %s); remove it",
            pdk_law_name(m->law));
    return PDK_SUCCESS;
  }
  REQUIRE(ld, hjc, "material.johnson_cook",
          "is missing; model.law is jc, so give the Johnson-Cook parameters as a mapping "
          "material.johnson_cook with at least A, B, n (and D1, D2, D3, D_c for damage; see "
          "docs/scenes.md)");
  const sc_jc *j = mat->johnson_cook;
  pdk_jc_params jc = pdk_jc_params_default();
  jc.density = m->density;
  jc.young_modulus =
      9 * m->bulk_modulus * m->shear_modulus / (3 * m->bulk_modulus + m->shear_modulus);
  jc.poisson_ratio =
      (3 * m->bulk_modulus - 2 * m->shear_modulus) / (2 * (3 * m->bulk_modulus + m->shear_modulus));
  if (has(ld, "material.youngs_modulus")) { /* as given, not through K and G */
    jc.young_modulus = mat->youngs_modulus;
    jc.poisson_ratio = mat->poisson_ratio;
  }
  /* hardening */
  REQUIRE(ld, isfinite(j->A) && j->A >= 0, "material.johnson_cook.A",
          "must be >= 0, got %g (the initial yield stress, a pressure)", j->A);
  REQUIRE(ld, isfinite(j->B) && j->B >= 0, "material.johnson_cook.B",
          "must be >= 0, got %g (the hardening modulus, a pressure)", j->B);
  REQUIRE(ld, j->A + j->B > 0, "material.johnson_cook.B",
          "A and B are both 0, a material with no strength; give A + B > 0");
  REQUIRE(ld, isfinite(j->n) && j->n > 0, "material.johnson_cook.n",
          "must be > 0, got %g (the hardening exponent)", j->n);
  jc.A = j->A;
  jc.B = j->B;
  jc.n = j->n;
  jc.C = has(ld, "material.johnson_cook.C") ? j->C : 0.0;
  REQUIRE(ld, isfinite(jc.C) && jc.C >= 0, "material.johnson_cook.C",
          "must be >= 0, got %g (the strain-rate sensitivity; 0 turns the rate term off)", jc.C);
  /* damage (read first: D4 also uses the reference rate) */
  jc.damage = has(ld, "material.johnson_cook.damage") ? (j->damage ? 1 : 0) : 1;
  const char *damage_keys[] = {"D1", "D2", "D3", "D4", "D5", "D_c", "coupling", "failed_mode"};
  if (!jc.damage) {
    PDK_CALL(jc_unused(ld, damage_keys, 8, "only used with damage (damage is false); remove it"));
    REQUIRE(ld, !has(ld, "model.failed_keeps_bonds"), "model.failed_keeps_bonds",
            "only used with Johnson-Cook damage (material.johnson_cook.damage is false); remove "
            "it");
  } else {
    const char *why = "damage is on (damage: true, the default), so the Johnson-Cook failure "
                      "strain D1 + D2 exp(D3 eta) and the critical damage D_c are needed; give "
                      "them, or set damage: false";
    PDK_CALL(jc_needed(ld, "D1", j->D1, why));
    PDK_CALL(jc_needed(ld, "D2", j->D2, why));
    PDK_CALL(jc_needed(ld, "D3", j->D3, why));
    PDK_CALL(jc_needed(ld, "D_c", j->D_c, why));
    REQUIRE(ld, j->D1 + j->D2 > 0, "material.johnson_cook.D2",
            "D1 + D2 = %g: the failure strain at zero triaxiality must be > 0", j->D1 + j->D2);
    REQUIRE(ld, j->D_c > 0 && j->D_c <= 1, "material.johnson_cook.D_c",
            "must lie in (0, 1], got %g (the point fails when D >= D_c; 1 is plain Johnson-Cook "
            "1985, the thesis uses 0.3)",
            j->D_c);
    jc.D1 = j->D1;
    jc.D2 = j->D2;
    jc.D3 = j->D3;
    jc.D_c = j->D_c;
    jc.D4 = has(ld, "material.johnson_cook.D4") ? j->D4 : 0.0;
    REQUIRE(ld, isfinite(jc.D4) && jc.D4 >= 0, "material.johnson_cook.D4",
            "must be >= 0, got %g (the rate term of the failure strain; 0 turns it off)", jc.D4);
    jc.D5 = has(ld, "material.johnson_cook.D5") ? j->D5 : 0.0;
    REQUIRE(ld, isfinite(jc.D5) && jc.D5 >= -1, "material.johnson_cook.D5",
            "must be >= -1, got %g (so that 1 + D5 T* >= 0)", jc.D5);
    REQUIRE(ld, jc.D5 == 0 || j->thermal, "material.johnson_cook.D5",
            "the temperature term of the failure strain needs thermal: true (temperature is not "
            "tracked otherwise); set thermal: true or remove D5");
    if (has(ld, "material.johnson_cook.coupling")) jc.coupling = (pdk_jc_coupling)j->coupling;
    if (has(ld, "material.johnson_cook.failed_mode"))
      jc.failed_mode = (pdk_jc_failed)j->failed_mode;
  }
  /* rate */
  if (jc.C > 0 || jc.D4 > 0) {
    jc.ref_rate =
        has(ld, "material.johnson_cook.reference_strain_rate") ? j->reference_strain_rate : 1.0;
    REQUIRE(ld, isfinite(jc.ref_rate) && jc.ref_rate > 0,
            "material.johnson_cook.reference_strain_rate",
            "must be > 0, got %g (1/s; plastic strain rates below it give no rate effect)",
            jc.ref_rate);
  } else {
    const char *rate_keys[] = {"reference_strain_rate"};
    PDK_CALL(jc_unused(ld, rate_keys, 1,
                       "only the rate terms use it (C and D4 are 0); set C > 0 or D4 > 0, or "
                       "remove it"));
  }
  /* temperature */
  jc.thermal = j->thermal ? 1 : 0;
  const char *thermal_keys[] = {"m", "T_room", "T_melt", "T_initial", "beta", "heat_capacity"};
  if (!jc.thermal) {
    PDK_CALL(jc_unused(ld, thermal_keys, 6,
                       "only used with thermal softening (thermal is false); set thermal: true "
                       "or remove it"));
  } else {
    const char *why = "thermal is true, so the softening exponent m, the temperatures T_room "
                      "and T_melt and the heat capacity are needed";
    PDK_CALL(jc_needed(ld, "m", j->m, why));
    PDK_CALL(jc_needed(ld, "T_room", j->T_room, why));
    PDK_CALL(jc_needed(ld, "T_melt", j->T_melt, why));
    PDK_CALL(jc_needed(ld, "heat_capacity", j->heat_capacity, why));
    REQUIRE(ld, j->m > 0, "material.johnson_cook.m", "must be > 0, got %g", j->m);
    REQUIRE(ld, j->T_melt > j->T_room, "material.johnson_cook.T_melt",
            "must exceed T_room (%g), got %g (temperatures in K)", j->T_room, j->T_melt);
    REQUIRE(ld, j->heat_capacity > 0, "material.johnson_cook.heat_capacity",
            "must be > 0, got %g (J/(kg K) in SI)", j->heat_capacity);
    jc.m = j->m;
    jc.T_room = j->T_room;
    jc.T_melt = j->T_melt;
    jc.heat_capacity = j->heat_capacity;
    jc.T_initial = has(ld, "material.johnson_cook.T_initial") ? j->T_initial : j->T_room;
    REQUIRE(ld, isfinite(jc.T_initial), "material.johnson_cook.T_initial",
            "must be a finite temperature, got %g", jc.T_initial);
    jc.beta = has(ld, "material.johnson_cook.beta") ? j->beta : 0.9;
    REQUIRE(ld, isfinite(jc.beta) && jc.beta >= 0 && jc.beta <= 1, "material.johnson_cook.beta",
            "must lie in [0, 1], got %g (the Taylor-Quinney fraction of plastic work turned into "
            "heat)",
            jc.beta);
  }
  int err = pdk_jc_params_check(ld->ctx, &jc);
  if (err) return pdk_scene_blame(s, ld->ctx, err, "material.johnson_cook");
  m->jc = jc;
  m->failed_keeps_bonds = mo->failed_keeps_bonds ? 1 : 0;
  return PDK_SUCCESS;
}

/* model.connectivity and model.compact_fraction (correspondence; checked as such by the caller). */
static int resolve_connectivity(loader *ld, const sc_model *mo) {
  pdk_model_opts *m = &ld->s->model;
  if (has(ld, "model.connectivity")) m->connectivity = (pdk_connectivity)mo->connectivity;
  if (has(ld, "model.compact_fraction")) {
    REQUIRE(ld, m->connectivity == PDK_CONNECTIVITY_SEMI_TL, "model.compact_fraction",
            "only semi_tl connectivity compacts its bond list (connectivity is tl); set "
            "model.connectivity: semi_tl or remove it");
    REQUIRE(ld,
            isfinite(mo->compact_fraction) && mo->compact_fraction >= 0 &&
                mo->compact_fraction <= 1,
            "model.compact_fraction",
            "must lie in [0, 1], got %g (the fraction of broken entries in the bond list that "
            "triggers a compaction; 0: whenever bonds broke)",
            mo->compact_fraction);
    m->compact_fraction = mo->compact_fraction;
  }
  if (has(ld, "model.ul_skin")) {
    REQUIRE(ld, m->connectivity == PDK_CONNECTIVITY_UL, "model.ul_skin",
            "only ul connectivity rebuilds its families (connectivity is %s); set "
            "model.connectivity: ul or remove it",
            connectivity_names[m->connectivity].str);
    REQUIRE(ld, isfinite(mo->ul_skin) && mo->ul_skin >= 0 && mo->ul_skin <= 1, "model.ul_skin",
            "must lie in [0, 1], got %g (a fraction of the horizon; 0: never rebuild)",
            mo->ul_skin);
    m->ul_skin = mo->ul_skin;
  }
  if (m->connectivity == PDK_CONNECTIVITY_UL) {
    const int jc_breaks = pdk_model_opts_law_breaks(m);
    REQUIRE(ld, m->critical_stretch == 0 && !jc_breaks, "model.connectivity",
            "ul cannot break bonds (a rebuild in the current configuration would bond broken "
            "pairs again), but %s; use tl or semi_tl, or %s",
            jc_breaks ? "failed Johnson-Cook particles break theirs" : "critical_stretch is set",
            jc_breaks ? "set model.failed_keeps_bonds: true (failed particles then carry no stress "
                        "but keep their bonds)"
                      : "remove model.critical_stretch");
  }
  return PDK_SUCCESS;
}

/* model.stabilization_softening, stabilization_softening_floor, damage_triaxiality,
 * break_stress: Johnson-Cook refinements of the correspondence model (tl, semi_tl). After the law
 * and connectivity. */
static int resolve_softening(loader *ld, const sc_model *mo) {
  pdk_model_opts *m = &ld->s->model;
  const int corr_jc = pdk_model_opts_law_has(m, PDK_LAWF_HISTORY);
  if (has(ld, "model.stabilization_softening")) {
    m->stab_softening = mo->stabilization_softening;
    REQUIRE(ld, !m->stab_softening || (corr_jc && m->stabilization == PDK_STAB_SILLING),
            "model.stabilization_softening",
            "plastic softens the Silling stabilization where the Johnson-Cook material flowed: it "
            "needs model.kind correspondence, model.law jc and model.stabilization silling; use "
            "none or remove it");
    REQUIRE(ld, !m->stab_softening || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.stabilization_softening",
            "plastic is implemented for tl and semi_tl connectivity, not ul; set "
            "model.connectivity: tl or semi_tl, or use none");
  }
  if (has(ld, "model.stabilization_softening_floor")) {
    REQUIRE(ld, m->stab_softening, "model.stabilization_softening_floor",
            "only used with model.stabilization_softening: plastic; set it or remove the floor");
    const double f = mo->stabilization_softening_floor;
    REQUIRE(ld, isfinite(f) && f > 0 && f <= 1, "model.stabilization_softening_floor",
            "must lie in (0, 1], got %g (the smallest factor on the stabilization modulus; the "
            "thesis uses 1e-3, the default)",
            f);
    m->stab_softening_floor = f;
  }
  if (has(ld, "model.damage_triaxiality")) {
    m->damage_triaxiality = (pdk_damage_triaxiality)mo->damage_triaxiality;
    REQUIRE(ld, m->damage_triaxiality == PDK_TRIAX_LOCAL || (corr_jc && m->jc.damage),
            "model.damage_triaxiality",
            "family averages the pressure of the Johnson-Cook damage law: it needs model.kind "
            "correspondence, model.law jc and material.johnson_cook.damage on; use local or "
            "remove it");
    REQUIRE(ld,
            m->damage_triaxiality == PDK_TRIAX_LOCAL || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.damage_triaxiality",
            "family is implemented for tl and semi_tl connectivity, not ul; set "
            "model.connectivity: tl or semi_tl, or use local");
  }
  if (has(ld, "model.break_stress")) {
    m->break_stress = (pdk_break_stress)mo->break_stress;
    REQUIRE(ld, m->break_stress == PDK_BREAK_STRESS_REFIT || corr_jc, "model.break_stress",
            "continuous remaps the Johnson-Cook history when a particle's family loses bonds: it "
            "needs model.kind correspondence and model.law jc; use refit or remove it");
    REQUIRE(ld,
            m->break_stress == PDK_BREAK_STRESS_REFIT || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.break_stress",
            "continuous is implemented for tl and semi_tl connectivity, not ul (which breaks no "
            "bonds); set model.connectivity: tl or semi_tl, or use refit");
    const int breaks = (m->jc.damage && !m->failed_keeps_bonds) || m->critical_stretch > 0;
    REQUIRE(ld, m->break_stress == PDK_BREAK_STRESS_REFIT || breaks, "model.break_stress",
            "continuous acts when bonds break, and none can here (%s); turn on "
            "material.johnson_cook.damage with model.failed_keeps_bonds: false, or set "
            "model.critical_stretch, or remove it",
            m->jc.damage ? "failed particles keep their bonds" : "no damage, no critical stretch");
  }
  return PDK_SUCCESS;
}

/* model.galerkin (kind galerkin; refused for the others by its scene_keys entry). */
static int resolve_galerkin(loader *ld, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_galerkin_opts *g = &s->model.galerkin;
  const sc_galerkin *sg = mo->galerkin;
  if (!sg || !has(ld, "model.galerkin")) return PDK_SUCCESS;
  if (has(ld, "model.galerkin.basis")) g->basis = (pdk_galerkin_basis)sg->basis;
  if (has(ld, "model.galerkin.form")) g->form = (pdk_galerkin_form)sg->form;
  if (has(ld, "model.galerkin.correction")) g->correction = (pdk_galerkin_correction)sg->correction;
  if (has(ld, "model.galerkin.surface")) {
    REQUIRE(ld, g->correction == PDK_GALERKIN_VC1, "model.galerkin.surface",
            "only the vc1 correction uses it; set model.galerkin.correction: vc1 or remove it");
    s->galerkin_surface = strdup(sg->surface);
    REQUIRE(ld, s->galerkin_surface, "model.galerkin.surface", "out of memory");
    g->surface = s->galerkin_surface;
  }
  REQUIRE(ld, g->correction != PDK_GALERKIN_VC1 || g->surface, "model.galerkin.correction",
          "vc1 needs model.galerkin.surface: the name of the set of the particles on the body's "
          "surface");
  return PDK_SUCCESS;
}

static int resolve_material_model(loader *ld, const sc_material *mat, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  *m = pdk_model_opts_default();
  m->kind = has(ld, "model.kind") ? (pdk_model_kind)mo->kind : pdk_model_kind_at(0)->kind;
  const char *kname = pdk_model_kind_name(m->kind);
  REQUIRE(ld, isfinite(mat->density) && mat->density > 0, "material.density",
          "must be > 0, got %g (mass per volume, e.g. 7850 kg/m^3 for steel)", mat->density);
  m->density = mat->density;
  const int hE = has(ld, "material.youngs_modulus"), hnu = has(ld, "material.poisson_ratio");
  const int hK = has(ld, "material.bulk_modulus"), hG = has(ld, "material.shear_modulus");
  if ((hE || hnu) && (hK || hG))
    FAIL(ld, hK ? "material.bulk_modulus" : "material.shear_modulus",
         "mixes with %s; give either youngs_modulus and poisson_ratio, or bulk_modulus and "
         "shear_modulus",
         hE ? "youngs_modulus" : "poisson_ratio");
  if (hE || hnu) {
    REQUIRE(ld, hE, "material.youngs_modulus",
            "is missing; poisson_ratio is given, so youngs_modulus is needed too");
    REQUIRE(ld, hnu, "material.poisson_ratio",
            "is missing; youngs_modulus is given, so poisson_ratio is needed too");
    const double E = mat->youngs_modulus, nu = mat->poisson_ratio;
    REQUIRE(ld, isfinite(E) && E > 0, "material.youngs_modulus", "must be > 0, got %g", E);
    REQUIRE(ld, isfinite(nu) && nu > -1 && nu < 0.5, "material.poisson_ratio",
            "must be in (-1, 0.5), got %g (0.5 is incompressible, which has no finite bulk "
            "modulus)",
            nu);
    m->bulk_modulus = E / (3 * (1 - 2 * nu));
    m->shear_modulus = E / (2 * (1 + nu));
  } else if (hK || hG) {
    REQUIRE(ld, hK, "material.bulk_modulus",
            "is missing; shear_modulus is given, so bulk_modulus "
            "is needed too");
    char bulk_only[128];
    REQUIRE(ld, hG || !pdk_model_opts_has(m, PDK_KIND_SHEAR), "material.shear_modulus",
            "is missing; the %s model needs bulk_modulus and shear_modulus (only %s needs the "
            "bulk modulus alone)",
            kname,
            pdk_model_kinds_list(PDK_KIND_SHEAR | PDK_KIND_SCENE, PDK_KIND_SCENE, " or ",
                                 bulk_only, sizeof bulk_only));
    REQUIRE(ld, isfinite(mat->bulk_modulus) && mat->bulk_modulus > 0, "material.bulk_modulus",
            "must be > 0, got %g", mat->bulk_modulus);
    if (hG)
      REQUIRE(ld, isfinite(mat->shear_modulus) && mat->shear_modulus > 0, "material.shear_modulus",
              "must be > 0, got %g", mat->shear_modulus);
    m->bulk_modulus = mat->bulk_modulus;
    m->shear_modulus = hG ? mat->shear_modulus : 0;
  } else {
    FAIL(ld, "material",
         "gives no elastic constants; give youngs_modulus and poisson_ratio, or "
         "bulk_modulus and shear_modulus");
  }

  /* the keys only some kinds accept (the kinds' pdk_model_kind_info.scene_keys) */
  for (int k = 0; pdk_model_scene_key_at(k); ++k) {
    const char *key = pdk_model_scene_key_at(k);
    if (pdk_model_opts_scene_key(m, key) || !has(ld, key)) continue;
    char users[128], alt[128];
    int count;
    pdk_model_key_kinds(key, " and ", users, sizeof users, &count);
    FAIL(ld, key, "only the %s model%s %s it (model.kind is %s); remove it or set model.kind: %s",
         users, count > 1 ? "s" : "", count > 1 ? "use" : "uses", kname,
         pdk_model_key_kinds(key, " or ", alt, sizeof alt, NULL));
  }
  if (has(ld, "model.influence")) m->influence = (pdk_influence)mo->influence;
  if (has(ld, "model.gaussian_width")) {
    REQUIRE(ld, m->influence == PDK_INFLUENCE_GAUSSIAN, "model.gaussian_width",
            "only the gaussian influence function uses it; set model.influence: gaussian or "
            "remove it");
    REQUIRE(ld, isfinite(mo->gaussian_width) && mo->gaussian_width > 0, "model.gaussian_width",
            "must be > 0 (a fraction of the horizon), got %g", mo->gaussian_width);
    m->gaussian_width = mo->gaussian_width;
  }
  m->stabilization = has(ld, "model.stabilization")
                         ? (pdk_stabilization)mo->stabilization
                         : pdk_model_kind_info_of(m->kind)->scene_stabilization;
  if (has(ld, "model.stabilization_coefficient")) {
    REQUIRE(ld, isfinite(mo->stabilization_coefficient) && mo->stabilization_coefficient >= 0,
            "model.stabilization_coefficient", "must be >= 0, got %g",
            mo->stabilization_coefficient);
    m->stab_coefficient = mo->stabilization_coefficient;
  }
  if (has(ld, "model.law")) m->law = (pdk_law)mo->law;
  if (has(ld, "model.precision")) m->precision = (pdk_precision)mo->precision;
  if (has(ld, "model.layout")) m->layout = (pdk_layout)mo->layout;
  /* Scenes take the lattice path where it applies (auto) unless they name a layout or a stencil
   * mode; the C API's default stays off (pdk_model_opts_default), so code chooses its path. */
  if (!has(ld, "model.layout")) m->stencil = PDK_STENCIL_AUTO;
  if (has(ld, "model.stencil")) {
    m->stencil = (pdk_stencil_mode)mo->stencil;
    char stencil_kinds[128];
    REQUIRE(ld, m->stencil != PDK_STENCIL_ON || pdk_model_opts_has(m, PDK_KIND_STENCIL),
            "model.stencil",
            "on needs model.kind %s (the stencil path exists for those models only; model.kind "
            "is %s); use auto or off",
            pdk_model_kinds_list(PDK_KIND_STENCIL | PDK_KIND_SCENE,
                                 PDK_KIND_STENCIL | PDK_KIND_SCENE, " or ", stencil_kinds,
                                 sizeof stencil_kinds),
            kname);
  }
  REQUIRE(ld, isfinite(mo->critical_stretch) && mo->critical_stretch >= 0, "model.critical_stretch",
          "must be >= 0 (0: bonds never break), got %g", mo->critical_stretch);
  m->critical_stretch = mo->critical_stretch;
  REQUIRE(ld, isfinite(mo->alpha) && mo->alpha >= 0, "model.alpha", "must be >= 0, got %g",
          mo->alpha);
  REQUIRE(ld, mo->alpha == 0 || mo->critical_stretch > 0, "model.alpha",
          "only acts with bond breaking; set model.critical_stretch > 0 or remove alpha");
  m->alpha = mo->alpha;
  m->lattice_constant = mo->partial_volume ? s->lattice.spacing : 0;
  m->thickness = s->lattice.thickness; /* 2-D volumes include it (lattice default 1) */
  PDK_CALL(resolve_johnson_cook(ld, mat, mo));
  PDK_CALL(resolve_connectivity(ld, mo));
  PDK_CALL(resolve_softening(ld, mo));
  PDK_CALL(resolve_galerkin(ld, mo));
  return PDK_SUCCESS;
}

static int find_set(const pdk_scene *s, const char *name) {
  for (int k = 0; k < s->num_sets; ++k)
    if (!strcmp(s->sets[k].name, name)) return k;
  return -1;
}

static void list_sets(const pdk_scene *s, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  for (int k = 0; k < s->num_sets; ++k) {
    int w = snprintf(buf + pos, len - pos, "%s%s", k ? ", " : "", s->sets[k].name);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
  if (!s->num_sets) snprintf(buf, len, "(no sets are defined)");
}

static int resolve_sets(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  s->sets = calloc(d->sets_count + (s->points ? (size_t)s->points->num_sets : 0) + 1,
                   sizeof *s->sets);
  if (!s->sets)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
  for (int k = 0; k < (int)d->sets_count; ++k) {
    const sc_region *r = &d->sets[k];
    const char *nk = K(ld, "sets[%d].name", k);
    REQUIRE(ld, valid_name(r->name), nk,
            "'%s' is not a valid set name; use 1 to %d letters, digits, '_', '-' or '.'", r->name,
            SC_NAME_MAX);
    REQUIRE(
        ld, strcmp(r->name, "all"), nk,
        "'all' is reserved (it means every particle in boundary conditions); pick another name");
    int prev = find_set(s, r->name);
    REQUIRE(ld, prev < 0, nk, "the set '%s' is already defined by sets[%d]; set names are unique",
            r->name, prev);
    pdk_scene_region *out = &s->sets[k];
    out->name = strdup(r->name);
    size_t flen = strlen(r->name) + 5;
    out->field = malloc(flen);
    s->num_sets = k + 1;
    if (!out->name || !out->field)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
    snprintf(out->field, flen, "set:%s", r->name);
    PDK_CALL(region_resolve(ld, r, K(ld, "sets[%d]", k), 1, out));
    /* The set's messages name the set entry, whose line is the start of "- name: ...". */
    snprintf(out->key, sizeof out->key, "sets[%d]", k);
  }
  /* then the set:<name> columns of a point cloud */
  const pdk_points *pts = s->points;
  for (int k = 0; pts && k < pts->num_sets; ++k) {
    const char *name = pts->set_name[k];
    REQUIRE(ld, valid_name(name) && strcmp(name, "all"), "geometry.points",
            "the column set:%s names no valid set ('all' is reserved; 1 to %d letters, digits, "
            "'_', '-' or '.')",
            name, SC_NAME_MAX);
    const int prev = find_set(s, name);
    REQUIRE(ld, prev < 0, "geometry.points",
            "the column set:%s defines the set that sets[%d] defines too; rename one", name, prev);
    pdk_index count = 0;
    for (pdk_index i = 0; i < pts->n; ++i)
      count += pts->set[k][i];
    REQUIRE(ld, count > 0, "geometry.points",
            "the column set:%s selects no particle (every value is 0); remove it or mark members",
            name);
    pdk_scene_region *out = &s->sets[s->num_sets];
    memset(out, 0, sizeof *out);
    out->name = strdup(name);
    const size_t flen = strlen(name) + 5;
    out->field = malloc(flen);
    if (out->field) snprintf(out->field, flen, "set:%s", name);
    out->from_points = 1;
    s->num_sets++;
    if (!out->name || !out->field)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
    snprintf(out->key, sizeof out->key, "geometry.points");
  }
  return PDK_SUCCESS;
}

/* materials: further materials over regions (material 0 is `material`). Each entry's elastic
 * constants as `material`'s: E and nu, or K and G (pmb: K alone). */
static int resolve_materials(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  const int nm = (int)d->materials_count;
  if (nm == 0) return PDK_SUCCESS;
  char with[128], alt[128];
  const unsigned mats = PDK_KIND_MATERIALS | PDK_KIND_SCENE;
  REQUIRE(ld, pdk_model_opts_has(m, PDK_KIND_MATERIALS), "materials",
          "several materials are implemented for %s, not %s; use one material or model.kind %s",
          pdk_model_kinds_list(mats, mats, " and ", with, sizeof with),
          pdk_model_kind_name(m->kind), pdk_model_kinds_list(mats, mats, " or ", alt, sizeof alt));
  REQUIRE(ld, !pdk_model_opts_law_has(m, PDK_LAWF_ONE_MATERIAL), "materials", "%s",
          pdk_law_info_of(m->law)->one_material_why);
  s->mat_regions = calloc((size_t)nm + 1, sizeof *s->mat_regions);
  s->materials = calloc((size_t)nm + 2, sizeof *s->materials);
  if (!s->mat_regions || !s->materials)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
  s->materials[0] = (pdk_material){m->bulk_modulus, m->shear_modulus, m->density};
  for (int k = 0; k < nm; ++k) {
    const sc_region *r = &d->materials[k];
    const char *nk = K(ld, "materials[%d].name", k);
    REQUIRE(ld, valid_name(r->name), nk,
            "'%s' is not a valid material name; use 1 to %d letters, digits, '_', '-' or '.'",
            r->name, SC_NAME_MAX);
    for (int q = 0; q < k; ++q)
      REQUIRE(ld, strcmp(s->mat_regions[q].name, r->name), nk,
              "the material '%s' is already defined by materials[%d]; names are unique", r->name,
              q);
    pdk_scene_region *out = &s->mat_regions[k];
    out->name = strdup(r->name);
    s->num_mat_regions = k + 1;
    if (!out->name)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
    PDK_CALL(region_resolve(ld, r, K(ld, "materials[%d]", k), 1, out));
    snprintf(out->key, sizeof out->key, "materials[%d]", k);
    pdk_material *q = &s->materials[k + 1];
    REQUIRE(ld, isfinite(r->density) && r->density > 0, K(ld, "materials[%d].density", k),
            "must be > 0, got %g (mass per volume)", r->density);
    q->density = r->density;
    const int hE = has(ld, K(ld, "materials[%d].youngs_modulus", k));
    const int hnu = has(ld, K(ld, "materials[%d].poisson_ratio", k));
    const int hK = has(ld, K(ld, "materials[%d].bulk_modulus", k));
    const int hG = has(ld, K(ld, "materials[%d].shear_modulus", k));
    char bulk_only[128];
    REQUIRE(ld,
            (hE && hnu && !hK && !hG) ||
                (!hE && !hnu && hK && (hG || !pdk_model_opts_has(m, PDK_KIND_SHEAR))),
            K(ld, "materials[%d]", k),
            "needs its elastic constants: youngs_modulus and poisson_ratio, or bulk_modulus and "
            "shear_modulus (%s: bulk_modulus alone), not a mix",
            pdk_model_kinds_list(PDK_KIND_SHEAR | PDK_KIND_SCENE, PDK_KIND_SCENE, " and ",
                                 bulk_only, sizeof bulk_only));
    if (hE) {
      const double E = r->youngs_modulus, nu = r->poisson_ratio;
      REQUIRE(ld, isfinite(E) && E > 0, K(ld, "materials[%d].youngs_modulus", k),
              "must be > 0, got %g", E);
      REQUIRE(ld, isfinite(nu) && nu > -1 && nu < 0.5, K(ld, "materials[%d].poisson_ratio", k),
              "must be in (-1, 0.5), got %g", nu);
      q->bulk_modulus = E / (3 * (1 - 2 * nu));
      q->shear_modulus = E / (2 * (1 + nu));
    } else {
      REQUIRE(ld, isfinite(r->bulk_modulus) && r->bulk_modulus > 0,
              K(ld, "materials[%d].bulk_modulus", k), "must be > 0, got %g", r->bulk_modulus);
      REQUIRE(ld, !hG || (isfinite(r->shear_modulus) && r->shear_modulus > 0),
              K(ld, "materials[%d].shear_modulus", k), "must be > 0, got %g", r->shear_modulus);
      q->bulk_modulus = r->bulk_modulus;
      q->shear_modulus = hG ? r->shear_modulus : 0.0;
    }
  }
  m->materials = s->materials;
  m->num_materials = nm + 1;
  return PDK_SUCCESS;
}

static int resolve_bcs(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const int nb = (int)d->boundary_conditions_count;
  s->bcs = calloc((size_t)nb + 1, sizeof *s->bcs);
  s->bc_fields = calloc((size_t)nb + 1, sizeof *s->bc_fields);
  if (!s->bcs || !s->bc_fields)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory for boundary conditions");
  s->num_bcs = nb;
  for (int k = 0; k < nb; ++k) {
    const sc_bc *b = &d->boundary_conditions[k];
    pdk_bc *bc = &s->bcs[k];
    char base[64], sub[KEY_MAX];
    snprintf(base, sizeof base, "boundary_conditions[%d]", k);
    snprintf(sub, sizeof sub, "%s.set", base);
    if (strcmp(b->set, "all")) {
      int set = find_set(s, b->set);
      char names[512];
      list_sets(s, names, sizeof names);
      REQUIRE(ld, set >= 0, sub,
              "names the set '%s', which is not defined; defined sets: %s (or "
              "'all' for every particle)",
              b->set, names);
      s->bc_fields[k] = strdup(s->sets[set].field);
      if (!s->bc_fields[k])
        return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__,
                                 "out of memory for boundary conditions");
    }
    bc->set = s->bc_fields[k];
    bc->kind = (pdk_bc_kind)b->type;
    const double comp[3] = {b->x, b->y, b->z};
    const pdk_tfun_kind fk =
        has(ld, K(ld, "%s.function", base)) ? (pdk_tfun_kind)b->function : PDK_TFUN_CONSTANT;
    const int hdur = has(ld, K(ld, "%s.duration", base)), hper = has(ld, K(ld, "%s.period", base));
    const int needs_dur = fk == PDK_TFUN_RAMP || fk == PDK_TFUN_SMOOTH;
    const char *fname = function_names[fk].str;
    snprintf(sub, sizeof sub, "%s.duration", base);
    if (needs_dur) {
      REQUIRE(ld, hdur, sub, "is missing; function %s rises over a duration; give duration > 0",
              fname);
      REQUIRE(ld, isfinite(b->duration) && b->duration > 0, sub, "must be > 0, got %g",
              b->duration);
    } else {
      REQUIRE(ld, !hdur, sub,
              "only the ramp and smooth functions use a duration (function is "
              "%s); remove it",
              fname);
    }
    snprintf(sub, sizeof sub, "%s.period", base);
    if (fk == PDK_TFUN_SINE) {
      REQUIRE(ld, hper, sub, "is missing; function sine needs a period > 0");
      REQUIRE(ld, isfinite(b->period) && b->period > 0, sub, "must be > 0, got %g", b->period);
    } else {
      REQUIRE(ld, !hper, sub, "only the sine function uses a period (function is %s); remove it",
              fname);
    }
    for (int c = 0; c < 3; ++c) {
      snprintf(sub, sizeof sub, "%s.%c", base, "xyz"[c]);
      if (!has(ld, sub)) continue;
      REQUIRE(ld, c < s->dim, sub, "z is not a component in a 2-D scene; use x and y");
      REQUIRE(ld, isfinite(comp[c]), sub, "must be a finite number, got %g", comp[c]);
      bc->components |= 1u << c;
      pdk_tfun *tf = &bc->value[c];
      tf->kind = fk;
      switch (fk) {
      case PDK_TFUN_CONSTANT: tf->a = comp[c]; break;
      case PDK_TFUN_LINEAR:
        tf->a = 0;
        tf->b = comp[c];
        break;
      case PDK_TFUN_RAMP:
      case PDK_TFUN_SMOOTH:
        tf->a = comp[c];
        tf->b = b->duration;
        break;
      case PDK_TFUN_SINE:
        tf->a = comp[c];
        tf->b = b->period;
        break;
      }
    }
    REQUIRE(ld, bc->components, base,
            "gives no component; give x, y%s with the value of each "
            "constrained component",
            s->dim == 3 ? " or z" : "");
  }
  s->solver.bcs = s->bcs;
  s->solver.num_bcs = nb;
  return PDK_SUCCESS;
}

/* Keys of one solver family given in a scene that runs another. */
static const char *const explicit_keys[] = {"steps",     "dt",       "safety",
                                            "force_dt",  "dt_update", "dt_update_interval"};
static const char *const static_keys[] = {"load_steps",
                                          "load_levels",
                                          "tolerance",
                                          "absolute_tolerance",
                                          "max_iterations",
                                          "max_break_rounds",
                                          "extrapolate",
                                          "adr_mass",
                                          "adr_safety",
                                          "linear_solver",
                                          "tangent",
                                          "fd_scheme",
                                          "fd_step",
                                          "line_search_backtracks",
                                          "line_search_decrease",
                                          "reuse_tangent",
                                          "singular_tolerance",
                                          "symmetry_tolerance"};
static const char *const adr_keys[] = {"adr_mass", "adr_safety"};
static const char *const newton_keys[] = {"linear_solver",
                                          "tangent",
                                          "fd_scheme",
                                          "fd_step",
                                          "line_search_backtracks",
                                          "line_search_decrease",
                                          "reuse_tangent",
                                          "singular_tolerance",
                                          "symmetry_tolerance"};

static int refuse_keys(loader *ld, const char *const *keys, int num, const char *why) {
  for (int k = 0; k < num; ++k) {
    const char *key = K(ld, "solver.%s", keys[k]);
    REQUIRE(ld, !has(ld, key), key, "%s; remove it", why);
  }
  return PDK_SUCCESS;
}

static int resolve_static_solver(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const sc_solver *so = &d->solver;
  const int newton = s->solver_type == PDK_SOLVER_NEWTON;
  const char *tname = newton ? "newton" : "adr";
  char why[160];
  snprintf(why, sizeof why,
           "is a key of the explicit solver (solver.type is %s: a static solve has load_steps or "
           "load_levels, no time steps)",
           tname);
  PDK_CALL(refuse_keys(ld, explicit_keys, N_OF(explicit_keys), why));
  snprintf(why, sizeof why, "is a key of the %s solver (solver.type is %s)",
           newton ? "adr" : "newton", tname);
  if (newton)
    PDK_CALL(refuse_keys(ld, adr_keys, N_OF(adr_keys), why));
  else
    PDK_CALL(refuse_keys(ld, newton_keys, N_OF(newton_keys), why));
  REQUIRE(ld, !has(ld, "initial_conditions"), "initial_conditions",
          "a static solve (solver.type %s) has no velocities; remove initial_conditions", tname);
  for (int k = 0; k < s->num_bcs; ++k)
    REQUIRE(ld, s->bcs[k].kind != PDK_BC_VELOCITY, K(ld, "boundary_conditions[%d].type", k),
            "velocity conditions have no meaning in a static solve (solver.type %s); prescribe "
            "the displacement instead: from rest, a pull at velocity v is type: displacement, "
            "function: linear with the value v, and solver.end_time the duration of the pull",
            tname);
  pdk_static_opts *o = &s->static_opts;
  *o = pdk_static_opts_default(newton ? PDK_STATIC_NEWTON : PDK_STATIC_ADR);
  o->bcs = s->bcs;
  o->num_bcs = s->num_bcs;

  /* Load steps: equal steps or explicit levels (fractions of the load path). */
  const int hsteps = has(ld, "solver.load_steps"), hlevels = has(ld, "solver.load_levels");
  REQUIRE(ld, !(hsteps && hlevels), "solver.load_levels",
          "given together with solver.load_steps; give one of them (load_steps: that many equal "
          "steps; load_levels: the fractions of the load at which to stop)");
  if (hlevels) {
    const int nl = (int)so->load_levels_count;
    s->load_levels = malloc((size_t)nl * sizeof(double));
    if (!s->load_levels)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
    double prev = 0.0;
    for (int k = 0; k < nl; ++k) {
      const double v = so->load_levels[k];
      REQUIRE(ld, isfinite(v) && v > prev && v <= 1.0, K(ld, "solver.load_levels[%d]", k),
              "is %g; load levels are fractions of the load path: increasing, in (0, 1]%s", v,
              k ? " and above the previous one" : "");
      s->load_levels[k] = prev = v;
    }
    o->load_levels = s->load_levels;
    o->num_levels = nl;
  } else {
    long steps = 1;
    if (hsteps) PDK_CALL(check_whole(ld, "solver.load_steps", so->load_steps, 1, 1e6, &steps));
    o->num_levels = (int)steps;
  }

  /* Pseudo-time. */
  if (has(ld, "solver.end_time")) {
    REQUIRE(ld, isfinite(so->end_time) && so->end_time > 0, "solver.end_time",
            "must be > 0, got %g (the duration of the load path, which sets the strain rates)",
            so->end_time);
    int timed = 0;
    for (int k = 0; k < s->num_bcs; ++k)
      for (int c = 0; c < s->dim; ++c)
        if ((s->bcs[k].components & (1u << c)) && s->bcs[k].value[c].kind != PDK_TFUN_CONSTANT)
          timed = 1;
    REQUIRE(ld, timed, "solver.end_time",
            "every boundary condition is constant in time, so every load step would apply the "
            "whole load at once; give the conditions a function of time (linear, ramp, smooth) "
            "to load along the time, or remove end_time to scale them by the load steps");
    o->total_time = so->end_time;
    s->end_time = so->end_time;
  } else {
    char rate_terms[160];
    REQUIRE(ld, !pdk_model_opts_rate_terms(&s->model, rate_terms, sizeof rate_terms), "solver",
            "%s need strain rates, so the load steps need a pseudo-time; give solver.end_time "
            "(the duration of the load path) and conditions with functions of time",
            rate_terms);
  }

  /* Convergence. */
  if (has(ld, "solver.tolerance")) {
    REQUIRE(ld, isfinite(so->tolerance) && so->tolerance > 0 && so->tolerance < 1,
            "solver.tolerance",
            "must be in (0, 1), got %g (the residual force relative to the external forces)",
            so->tolerance);
    o->rtol = so->tolerance;
  }
  if (has(ld, "solver.absolute_tolerance")) {
    REQUIRE(ld, isfinite(so->absolute_tolerance) && so->absolute_tolerance >= 0,
            "solver.absolute_tolerance", "must be >= 0, got %g (a force)", so->absolute_tolerance);
    o->atol = so->absolute_tolerance;
  }
  if (has(ld, "solver.max_iterations"))
    PDK_CALL(
        check_whole(ld, "solver.max_iterations", so->max_iterations, 1, 1e15, &o->max_iterations));
  if (has(ld, "solver.max_break_rounds")) {
    long v = 0;
    PDK_CALL(check_whole(ld, "solver.max_break_rounds", so->max_break_rounds, 0, 1e9, &v));
    o->max_break_rounds = (int)v;
  }
  if (has(ld, "solver.extrapolate")) o->extrapolate = so->extrapolate ? 1 : 0;
  /* ADR */
  if (has(ld, "solver.adr_mass")) o->adr_mass = (pdk_adr_mass)so->adr_mass;
  if (has(ld, "solver.adr_safety")) {
    REQUIRE(ld, isfinite(so->adr_safety) && so->adr_safety >= 1, "solver.adr_safety",
            "must be >= 1, got %g (it multiplies the fictitious mass; 1 is the stable bound)",
            so->adr_safety);
    o->adr_safety = so->adr_safety;
  }
  /* Newton */
  if (has(ld, "solver.linear_solver")) o->linear_solver = (pdk_linear_solver)so->linear_solver;
  if (has(ld, "solver.tangent")) o->tangent = (pdk_tangent_kind)so->tangent;
  if (has(ld, "solver.fd_scheme")) o->fd_scheme = (pdk_fd_scheme)so->fd_scheme;
  if (has(ld, "solver.fd_step")) {
    REQUIRE(ld, isfinite(so->fd_step) && so->fd_step > 0 && so->fd_step < 0.1, "solver.fd_step",
            "must be in (0, 0.1), got %g (the difference step as a fraction of the horizon)",
            so->fd_step);
    o->fd_step = so->fd_step;
  }
  if (has(ld, "solver.line_search_backtracks")) {
    long v = 0;
    PDK_CALL(
        check_whole(ld, "solver.line_search_backtracks", so->line_search_backtracks, 0, 60, &v));
    o->max_backtracks = (int)v;
  }
  if (has(ld, "solver.line_search_decrease")) {
    REQUIRE(ld,
            isfinite(so->line_search_decrease) && so->line_search_decrease > 0 &&
                so->line_search_decrease < 1,
            "solver.line_search_decrease",
            "must be in (0, 1), got %g (a step is taken when it reduces the residual by this "
            "fraction of the step length)",
            so->line_search_decrease);
    o->ls_decrease = so->line_search_decrease;
  }
  if (has(ld, "solver.reuse_tangent")) o->reuse_tangent = so->reuse_tangent ? 1 : 0;
  if (has(ld, "solver.singular_tolerance")) {
    REQUIRE(ld,
            isfinite(so->singular_tolerance) && so->singular_tolerance >= 0 &&
                so->singular_tolerance < 1,
            "solver.singular_tolerance", "must be in [0, 1), got %g (0: no singularity test)",
            so->singular_tolerance);
    o->singular_rtol = so->singular_tolerance;
  }
  if (has(ld, "solver.symmetry_tolerance")) {
    REQUIRE(ld, isfinite(so->symmetry_tolerance) && so->symmetry_tolerance >= 0,
            "solver.symmetry_tolerance", "must be >= 0, got %g", so->symmetry_tolerance);
    o->sym_rtol = so->symmetry_tolerance;
  }
  return PDK_SUCCESS;
}

static int resolve_solver(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const sc_solver *so = &d->solver;
  pdk_explicit_opts *e = &s->solver;
  s->solver_type = has(ld, "solver.type") ? (pdk_solver_type)so->type : PDK_SOLVER_EXPLICIT;
  long threads = 0;
  PDK_CALL(check_whole(ld, "solver.threads", so->threads, 0, 4096, &threads));
  s->threads = (int)threads;
  if (s->solver_type != PDK_SOLVER_EXPLICIT) return resolve_static_solver(ld, d);
  PDK_CALL(refuse_keys(ld, static_keys, N_OF(static_keys),
                       "is a key of the static solvers (solver.type adr or newton); the explicit "
                       "solver takes end_time or steps"));
  for (int c = 0; c < s->dim; ++c) {
    REQUIRE(ld, isfinite(d->initial_conditions.velocity[c]), "initial_conditions.velocity",
            "entry %d is %g; velocities must be finite", c, d->initial_conditions.velocity[c]);
    e->v0_const[c] = d->initial_conditions.velocity[c];
    for (int a = 0; a < s->dim; ++a) {
      REQUIRE(ld, isfinite(d->initial_conditions.velocity_gradient[c][a]),
              K(ld, "initial_conditions.velocity_gradient[%d]", c),
              "entry %d is %g; entries must be finite", a,
              d->initial_conditions.velocity_gradient[c][a]);
      e->v0_grad[c][a] = d->initial_conditions.velocity_gradient[c][a];
    }
  }
  const int hend = has(ld, "solver.end_time"), hsteps = has(ld, "solver.steps");
  REQUIRE(ld, !(hend && hsteps), "solver.steps",
          "given together with solver.end_time; give one "
          "of them (end_time: the run lasts that long; steps: that many steps)");
  REQUIRE(ld, hend || hsteps, "solver", "gives neither end_time nor steps; give one of them");
  if (hend) {
    REQUIRE(ld, isfinite(so->end_time) && so->end_time > 0, "solver.end_time",
            "must be > 0, got %g (a time)", so->end_time);
    s->end_time = so->end_time;
  } else {
    PDK_CALL(check_whole(ld, "solver.steps", so->steps, 1, 1e15, &s->steps));
  }
  REQUIRE(ld, isfinite(so->dt) && so->dt >= 0, "solver.dt",
          "must be >= 0 (0: safety x the estimated stable step), got %g", so->dt);
  e->dt = so->dt;
  e->safety = has(ld, "solver.safety") ? so->safety : 0.8;
  REQUIRE(ld, isfinite(e->safety) && e->safety > 0 && e->safety <= 1, "solver.safety",
          "must be in (0, 1] (the fraction of the stable time step used), got %g", e->safety);
  e->force_dt = so->force_dt ? 1 : 0;
  e->dt_update = has(ld, "solver.dt_update") ? (pdk_dt_update)so->dt_update : PDK_DT_UPDATE_NONE;
  if (has(ld, "solver.dt_update_interval")) {
    REQUIRE(ld, e->dt_update != PDK_DT_UPDATE_NONE, "solver.dt_update_interval",
            "is given but solver.dt_update is none, so nothing is re-estimated; set dt_update "
            "(breaks or periodic) or remove the interval");
    PDK_CALL(check_whole(ld, "solver.dt_update_interval", so->dt_update_interval, 1, 1e15,
                         &e->dt_update_interval));
  }
  return PDK_SUCCESS;
}

static int resolve_output(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const sc_output *o = &d->output;
  pdk_scene_output *out = &s->output;
  PDK_CALL(
      check_whole(ld, "output.field_interval", o->field_interval, 0, 1e15, &out->field_interval));
  const int is_static = s->solver_type != PDK_SOLVER_EXPLICIT;
  out->history_interval = is_static ? 1 : 10;
  if (has(ld, "output.history_interval"))
    PDK_CALL(check_whole(ld, "output.history_interval", o->history_interval, 1, 1e15,
                         &out->history_interval));
  PDK_CALL(check_whole(ld, "output.checkpoint_interval", o->checkpoint_interval, 0, 1e15,
                       &out->checkpoint_interval));
  out->units = o->units == UNITS_SI ? "SI" : o->units == UNITS_MM ? "mm-N-s-tonne" : NULL;
  {
    long level = 0;
    PDK_CALL(check_whole(ld, "output.compression", o->compression, 0, 9, &level));
    out->compression = (int)level;
  }

  const char *default_fields[] = {"u", "v"};
  const int hf = has(ld, "output.fields");
  const int nf = hf ? (int)o->fields_count : is_static ? 1 : 2; /* static: no velocities */
  s->fields = calloc((size_t)nf + 1, sizeof *s->fields);
  if (!s->fields) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  for (int k = 0; k < nf; ++k) {
    const char *f = hf ? o->fields[k] : default_fields[k];
    const char *key = K(ld, "output.fields[%d]", k);
    REQUIRE(ld, valid_name(f) || !strncmp(f, "set:", 4), key,
            "'%s' is not a field name; fields are names such as u, v, f, x", f);
    for (int j = 0; j < k; ++j)
      REQUIRE(ld, strcmp(s->fields[j], f), key, "'%s' is listed twice; list each field once", f);
    s->fields[k] = strdup(f);
    out->num_fields = k + 1;
    if (!s->fields[k]) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  }
  out->fields = (const char *const *)s->fields;

  /* Reaction sets: given, or by default the sets of the displacement and velocity conditions. */
  int nr = 0;
  const char *names[MAX_REACTION_SETS];
  if (has(ld, "output.reactions")) {
    for (int k = 0; k < (int)o->reactions_count; ++k) {
      const char *key = K(ld, "output.reactions[%d]", k);
      char sets[512];
      list_sets(s, sets, sizeof sets);
      REQUIRE(ld, find_set(s, o->reactions[k]) >= 0, key,
              "names the set '%s', which is not defined; defined sets: %s", o->reactions[k], sets);
      for (int j = 0; j < nr; ++j)
        REQUIRE(ld, strcmp(names[j], o->reactions[k]), key, "'%s' is listed twice",
                o->reactions[k]);
      REQUIRE(ld, nr < MAX_REACTION_SETS, key, "at most %d reaction sets are recorded; list fewer",
              MAX_REACTION_SETS);
      names[nr++] = o->reactions[k];
    }
  } else {
    for (int k = 0; k < s->num_bcs && nr < MAX_REACTION_SETS; ++k) {
      const char *set = d->boundary_conditions[k].set;
      if (s->bcs[k].kind == PDK_BC_BODY_FORCE || !strcmp(set, "all")) continue;
      int dup = 0;
      for (int j = 0; j < nr; ++j)
        dup |= !strcmp(names[j], set);
      if (!dup) names[nr++] = set;
    }
  }
  s->reaction_names = calloc((size_t)nr + 1, sizeof(char *));
  s->reaction_fields = calloc((size_t)nr + 1, sizeof(char *));
  if (!s->reaction_names || !s->reaction_fields)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  for (int k = 0; k < nr; ++k) {
    size_t len = strlen(names[k]) + 5;
    s->reaction_names[k] = strdup(names[k]);
    s->reaction_fields[k] = malloc(len);
    out->num_reaction_sets = k + 1;
    if (!s->reaction_names[k] || !s->reaction_fields[k])
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
    snprintf(s->reaction_fields[k], len, "set:%s", names[k]);
  }
  out->reaction_sets = (const char *const *)s->reaction_names;
  s->solver.reaction_sets = (const char *const *)s->reaction_fields;
  s->solver.num_reaction_sets = nr;
  s->static_opts.reaction_sets = (const char *const *)s->reaction_fields;
  s->static_opts.num_reaction_sets = nr;
  return PDK_SUCCESS;
}

/* Memory available to this process now, in bytes: MemAvailable of /proc/meminfo (what the kernel
 * can hand out without swapping), else the free pages; 0 when neither is known. */
static double memory_available(const char **source) {
  FILE *f = fopen("/proc/meminfo", "r");
  if (f) {
    char line[256];
    double kb = -1;
    while (fgets(line, sizeof line, f))
      if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) break;
    fclose(f);
    if (kb > 0) {
      *source = "available (MemAvailable in /proc/meminfo)";
      return kb * 1024.0;
    }
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) {
    *source = "free (sysconf _SC_AVPHYS_PAGES)";
    return (double)pages * (double)page;
  }
#endif
  return 0;
}

/* The memory a run of the scene needs, estimated before anything is allocated: a base, bytes per
 * lattice point (positions, velocities, forces, model state, cells) and bytes per bond (neighbour
 * lists, bond state; a Newton solve also its tangent and factor), the bonds per point from the
 * horizon's area or volume over a lattice cell. Measured with pdk check and pdk run (peak resident
 * set) on the shipped scenes refined to 1e5 to 5e5 points: PMB and LPS 380 to 540 B per point and
 * 4 B per bond (float: 8), correspondence 640 to 730 B and 12 to 14 B, Newton about 700 B per bond
 * (correspondence, 2-D) and 270 B (PMB); the figures below are those rounded up. */
static double memory_estimate(const pdk_scene *s, double *per_point, double *per_bond,
                              double *bonds) {
  const double m = s->horizon_factor, pi = 3.14159265358979323846;
  double nb = s->dim == 3 ? 4.0 / 3.0 * pi * m * m * m : pi * m * m;
  if (s->lattice.type == PDK_LATTICE_HEX) nb *= 2.0 / sqrt(3.0);
  const double n = (double)s->num_points;
  if (nb > n - 1) nb = n - 1;
  const pdk_model_kind_info *k = pdk_model_kind_info_of(s->model.kind);
  const int single = s->model.precision == PDK_PRECISION_FLOAT;
  *per_point = k->mem_point;
  *per_bond = single ? k->mem_bond_float : k->mem_bond;
  if (s->solver_type == PDK_SOLVER_NEWTON) *per_bond += k->mem_newton_bond * s->dim * s->dim;
  *bonds = n * nb;
  return 32.0 * 1024 * 1024 + n * *per_point + *bonds * *per_bond;
}

static void fmt_bytes(char *buf, size_t len, double bytes) {
  if (bytes >= 1e12)
    snprintf(buf, len, "%.3g TB", bytes / 1e12);
  else if (bytes >= 1e9)
    snprintf(buf, len, "%.3g GB", bytes / 1e9);
  else
    snprintf(buf, len, "%.3g MB", bytes / 1e6);
}

/* limits.memory: the estimate against the memory the run may use, before pdk_sim_create
 * allocates anything. */
static int resolve_limits(loader *ld, const sc_scene *d) {
  const pdk_scene *s = ld->s;
  const char *source = NULL;
  double limit;
  if (has(ld, "limits.memory")) {
    limit = d->limits.memory;
    REQUIRE(ld, isfinite(limit) && limit > 0, "limits.memory",
            "must be > 0, got %g (bytes the run may use, for example 64e9)", limit);
    source = "that limits.memory allows";
  } else {
    limit = memory_available(&source);
    if (limit <= 0) return PDK_SUCCESS; /* unknown: nothing to compare with */
  }
  double per_point, per_bond, bonds;
  const double need = memory_estimate(s, &per_point, &per_bond, &bonds);
  const int given = has(ld, "limits.memory");
  char need_s[32], limit_s[32];
  fmt_bytes(need_s, sizeof need_s, need);
  fmt_bytes(limit_s, sizeof limit_s, limit);
  REQUIRE(ld, need <= limit, given ? "limits.memory" : "geometry.spacing",
          "the run needs about %s by pdk's estimate (%.4g particles x %.0f B + %.4g bonds x "
          "%.0f B), more than the %s of memory %s; increase geometry.spacing or shrink "
          "geometry.box, or %s limits.memory (bytes, for example limits.memory: %.0fe9) to run "
          "it anyway",
          need_s, (double)s->num_points, per_point, bonds, per_bond, limit_s, source,
          given ? "raise" : "set", ceil(need / 1e9));
  return PDK_SUCCESS;
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
  PDK_CALL(resolve_geometry(ld, &d->geometry));
  PDK_CALL(resolve_material_model(ld, &d->material, &d->model));
  PDK_CALL(resolve_sets(ld, d));
  PDK_CALL(resolve_materials(ld, d));
  PDK_CALL(resolve_bcs(ld, d));
  PDK_CALL(resolve_solver(ld, d));
  PDK_CALL(resolve_output(ld, d));
  PDK_CALL(resolve_limits(ld, d));
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
  cfg.log_fn = cy_log_fn;
  cfg.log_ctx = &log;
  cfg.mem_fn = cyaml_mem;
  cfg.log_level = CYAML_LOG_ERROR;
  cfg.flags = CYAML_CFG_DEFAULT;
  schema_build(&sc, 2);

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
  schema_build(&sc, dim);
  PDK_CALL_GOTO(scalars_check(ctx, s, &sc));
  PDK_CALL_GOTO(scene_schema_load(ctx, s, &sc, &cfg, yaml, yaml_len, &data));
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
    int free_err = scene_schema_free(ctx, &sc, &cfg, data);
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
