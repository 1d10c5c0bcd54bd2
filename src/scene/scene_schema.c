/* Scene loading: the libcyaml schema of a scene (src/scene/scene_load.h). Built at run time, because a
 * point has one entry per axis, and because model.kind and model.law accept the names the model
 * registry lists. docs/scenes.md documents every key; keep the two in step.
 */
#include "models/model_registry.h"
#include "scene_load.h"
#include "pdk/explicit.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "pdk/plasticity.h"
#include "pdk/scene.h"
#include "pdk/static.h"

const cyaml_strval_t pdk_scene_lattice_names[] = {
    {"square", PDK_LATTICE_SQUARE}, {"hex", PDK_LATTICE_HEX}, {"cubic", PDK_LATTICE_CUBIC}};
static const cyaml_strval_t influence_names[] = {
    {"constant", PDK_INFLUENCE_CONSTANT}, {"inv_r", PDK_INFLUENCE_INV_R},
    {"inv_r2", PDK_INFLUENCE_INV_R2},     {"linear", PDK_INFLUENCE_LINEAR},
    {"cubic", PDK_INFLUENCE_CUBIC},       {"quadratic", PDK_INFLUENCE_QUADRATIC},
    {"gaussian", PDK_INFLUENCE_GAUSSIAN}};
static const cyaml_strval_t oterkus_a_names[] = {{"published", PDK_OTERKUS_A_PUBLISHED},
                                                 {"calibrated", PDK_OTERKUS_A_CALIBRATED}};
static const cyaml_strval_t stab_names[] = {
    {"none", PDK_STAB_NONE}, {"silling", PDK_STAB_SILLING}, {"hourglass", PDK_STAB_HOURGLASS}};
const cyaml_strval_t pdk_scene_connectivity_names[] = {{"tl", PDK_CONNECTIVITY_TL},
                                                       {"semi_tl", PDK_CONNECTIVITY_SEMI_TL},
                                                       {"ul", PDK_CONNECTIVITY_UL}};
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
static const cyaml_strval_t galerkin_normals_names[] = {{"box", 1}};
static const cyaml_strval_t precision_names[] = {{"double", PDK_PRECISION_DOUBLE},
                                                 {"float", PDK_PRECISION_FLOAT}};
static const cyaml_strval_t layout_names[] = {{"csr", PDK_LAYOUT_CSR}, {"sell", PDK_LAYOUT_SELL}};
static const cyaml_strval_t bond_lengths_names[] = {{"stored", PDK_BOND_LENGTHS_STORED},
                                                    {"computed", PDK_BOND_LENGTHS_COMPUTED}};
static const cyaml_strval_t stencil_names[] = {
    {"off", PDK_STENCIL_OFF}, {"auto", PDK_STENCIL_AUTO}, {"on", PDK_STENCIL_ON}};
static const cyaml_strval_t bc_type_names[] = {{"displacement", PDK_BC_DISPLACEMENT},
                                               {"velocity", PDK_BC_VELOCITY},
                                               {"body_force", PDK_BC_BODY_FORCE},
                                               {"wall", PDK_BC_WALL}};
const cyaml_strval_t pdk_scene_function_names[] = {{"constant", PDK_TFUN_CONSTANT},
                                                   {"linear", PDK_TFUN_LINEAR},
                                                   {"ramp", PDK_TFUN_RAMP},
                                                   {"smooth", PDK_TFUN_SMOOTH},
                                                   {"sine", PDK_TFUN_SINE}};
static const cyaml_strval_t solver_names[] = {
    {"explicit", PDK_SOLVER_EXPLICIT}, {"adr", PDK_SOLVER_ADR}, {"newton", PDK_SOLVER_NEWTON}};
static const cyaml_strval_t dt_update_names[] = {{"none", PDK_DT_UPDATE_NONE},
                                                 {"breaks", PDK_DT_UPDATE_BREAKS},
                                                 {"periodic", PDK_DT_UPDATE_PERIODIC},
                                                 {"auto", PDK_DT_UPDATE_AUTO}};
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

#define OPT (CYAML_FLAG_OPTIONAL)
#define OPT_PTR (CYAML_FLAG_OPTIONAL | CYAML_FLAG_POINTER)
#define ENUM_FLAGS (CYAML_FLAG_OPTIONAL | CYAML_FLAG_STRICT)

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
  field_add(f, (cyaml_schema_field_t)CYAML_FIELD_MAPPING_PTR("cylinder", OPT_PTR, sc_region,
                                                             cylinder, sc->cylinder));
}

void pdk_scene_schema_build(scene_schema *sc, int dim) {
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
  ADD(cylinder, CYAML_FIELD_SEQUENCE_FIXED("axis", 0, sc_cylinder, axis, &sc->point, 2));
  ADD(cylinder, CYAML_FIELD_FLOAT("radius", 0, sc_cylinder, radius));

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

  ADD(geometry, CYAML_FIELD_ENUM("lattice", ENUM_FLAGS, sc_geometry, lattice,
                                 pdk_scene_lattice_names, N_OF(pdk_scene_lattice_names)));
  ADD(geometry, CYAML_FIELD_FLOAT("spacing", 0, sc_geometry, spacing));
  ADD(geometry, CYAML_FIELD_FLOAT("horizon_factor", OPT, sc_geometry, horizon_factor));
  ADD(geometry, CYAML_FIELD_FLOAT("jitter", OPT, sc_geometry, jitter));
  ADD(geometry, CYAML_FIELD_FLOAT("seed", OPT, sc_geometry, seed));
  ADD(geometry, CYAML_FIELD_FLOAT("thickness", OPT, sc_geometry, thickness));
  ADD(geometry, CYAML_FIELD_MAPPING("box", OPT, sc_geometry, box, sc->box));
  ADD(geometry, CYAML_FIELD_STRING_PTR("points", OPT, sc_geometry, points, 1, 4095));
  ADD(geometry, CYAML_FIELD_STRING_PTR("mesh", OPT, sc_geometry, mesh, 1, 4095));
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
  ADD(model, CYAML_FIELD_ENUM("bond_lengths", ENUM_FLAGS, sc_model, bond_lengths,
                              bond_lengths_names, N_OF(bond_lengths_names)));
  ADD(model, CYAML_FIELD_FLOAT("critical_stretch", OPT, sc_model, critical_stretch));
  ADD(model, CYAML_FIELD_FLOAT("alpha", OPT, sc_model, alpha));
  ADD(model, CYAML_FIELD_BOOL("partial_volume", OPT, sc_model, partial_volume));
  ADD(model, CYAML_FIELD_ENUM("connectivity", ENUM_FLAGS, sc_model, connectivity,
                              pdk_scene_connectivity_names, N_OF(pdk_scene_connectivity_names)));
  ADD(model, CYAML_FIELD_FLOAT("compact_fraction", OPT, sc_model, compact_fraction));
  ADD(model, CYAML_FIELD_FLOAT("ul_skin", OPT, sc_model, ul_skin));
  ADD(model, CYAML_FIELD_BOOL("failed_keeps_bonds", OPT, sc_model, failed_keeps_bonds));
  ADD(model, CYAML_FIELD_ENUM("oterkus_a", ENUM_FLAGS, sc_model, oterkus_a, oterkus_a_names,
                              N_OF(oterkus_a_names)));
  ADD(model, CYAML_FIELD_MAPPING_PTR("galerkin", OPT_PTR, sc_model, galerkin, sc->galerkin));
  ADD(galerkin, CYAML_FIELD_ENUM("basis", ENUM_FLAGS, sc_galerkin, basis, galerkin_basis_names,
                                 N_OF(galerkin_basis_names)));
  ADD(galerkin, CYAML_FIELD_ENUM("form", ENUM_FLAGS, sc_galerkin, form, galerkin_form_names,
                                 N_OF(galerkin_form_names)));
  ADD(galerkin, CYAML_FIELD_ENUM("correction", ENUM_FLAGS, sc_galerkin, correction,
                                 galerkin_correction_names, N_OF(galerkin_correction_names)));
  ADD(galerkin, CYAML_FIELD_STRING_PTR("surface", OPT, sc_galerkin, surface, 1, 255));
  ADD(galerkin, CYAML_FIELD_BOOL("bond", OPT, sc_galerkin, bond));
  ADD(galerkin, CYAML_FIELD_ENUM("normals", ENUM_FLAGS, sc_galerkin, normals, galerkin_normals_names,
                                 N_OF(galerkin_normals_names)));

  ADD(bc, CYAML_FIELD_STRING_PTR("set", 0, sc_bc, set, 1, 255));
  ADD(bc,
      CYAML_FIELD_ENUM("type", CYAML_FLAG_STRICT, sc_bc, type, bc_type_names, N_OF(bc_type_names)));
  ADD(bc, CYAML_FIELD_FLOAT("x", OPT, sc_bc, x));
  ADD(bc, CYAML_FIELD_FLOAT("y", OPT, sc_bc, y));
  ADD(bc, CYAML_FIELD_FLOAT("z", OPT, sc_bc, z));
  ADD(bc, CYAML_FIELD_ENUM("function", ENUM_FLAGS, sc_bc, function, pdk_scene_function_names,
                           N_OF(pdk_scene_function_names)));
  ADD(bc, CYAML_FIELD_FLOAT("duration", OPT, sc_bc, duration));
  ADD(bc, CYAML_FIELD_FLOAT("period", OPT, sc_bc, period));
  ADD(bc, CYAML_FIELD_SEQUENCE_FIXED("direction", OPT, sc_bc, direction, &sc->num, d));
  ADD(bc, CYAML_FIELD_FLOAT("value", OPT, sc_bc, value));
  ADD(bc, CYAML_FIELD_SEQUENCE_FIXED("point", OPT, sc_bc, point, &sc->num, d));
  ADD(bc, CYAML_FIELD_SEQUENCE_FIXED("normal", OPT, sc_bc, normal, &sc->num, d));
  ADD(bc, CYAML_FIELD_SEQUENCE_FIXED("velocity", OPT, sc_bc, velocity, &sc->num, d));
  ADD(bc, CYAML_FIELD_STRING_PTR("name", OPT, sc_bc, name, 1, 255));
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
