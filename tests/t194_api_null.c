/* Every public pdk_* function of include/pdk/ that takes a handle or a pointer accepts NULL there
 * without crashing: functions that return a status return PDK_ERR_ARG (with a message naming the
 * argument in the context when one is reachable: the ctx argument or the ctx of another valid
 * handle), destroy and close functions do nothing, and getters return 0, NULL, "" or NaN (as
 * documented in include/pdk/ctx.h). Each function is called with NULL for every handle in turn,
 * also with a valid context and valid other handles. Before, most of them dereferenced the NULL
 * (the first call, pdk_ctx_create with out NULL, crashed the program).
 * Objects: a context, a 6 x 4 square lattice with families, a PMB model, its explicit solver, an
 * output folder (closed without success, so nothing stays), the scene
 * tests/scenes/t060_minimal.yaml and its simulation. labels: unit */
#include <float.h>

#include "pdk/scene.h"
#include "test_util.h"

/* A status call that must fail with PDK_ERR_ARG and, with a context, say what was NULL. */
#define NULL_ARG(ctx, expr)                                                                        \
  do {                                                                                             \
    if (ctx) {                                                                                     \
      T_FAILS(ctx, expr, PDK_ERR_ARG, "NULL");                                                     \
    } else {                                                                                       \
      const int t_rc_ = (expr);                                                                    \
      T_ASSERT(t_rc_ == PDK_ERR_ARG, "%s returned %d, expected PDK_ERR_ARG", #expr, t_rc_);        \
    }                                                                                              \
  } while (0)
/* A status call that must fail with PDK_ERR_ARG (its own message, existing wording). */
#define ARG_ERR(expr)                                                                              \
  do {                                                                                             \
    const int t_rc_ = (expr);                                                                      \
    T_ASSERT(t_rc_ == PDK_ERR_ARG, "%s returned %d, expected PDK_ERR_ARG", #expr, t_rc_);          \
  } while (0)
#define IS(cond) T_ASSERT(cond, "with NULL")

static pdk_ctx *const NOCTX = NULL;

static void ctx_api(pdk_ctx *ctx) {
  char buf[256] = "";
  T_ASSERT(pdk_ctx_create(NULL, NULL, buf, sizeof buf) == PDK_ERR_ARG && strstr(buf, "'out'"),
           "pdk_ctx_create(out NULL): '%s'", buf);
  pdk_ctx *none = NULL;
  pdk_ctx_destroy(NULL);
  pdk_ctx_destroy(&none);
  IS(pdk_ctx_num_threads(NULL) == 0);
  NULL_ARG(NOCTX, pdk_ctx_set_num_threads(NULL, 1));
  IS(pdk_ctx_bind_policy(NULL) == PDK_BIND_NONE);
  IS(pdk_ctx_isa(NULL) == 0);
  IS(pdk_ctx_kernels_name(NULL) && !pdk_ctx_kernels_name(NULL)[0]);
  IS(pdk_ctx_error_message(NULL) != NULL);
  IS(pdk_ctx_error_code(NULL) == PDK_ERR_ARG);
  pdk_ctx_error_clear(NULL);
  IS(pdk_ctx_error_set(NULL, PDK_ERR_IO, "here", "what %d", 1) == PDK_ERR_IO);
  NULL_ARG(NOCTX, pdk_ctx_print_info(NULL, stdout));
  NULL_ARG(ctx, pdk_ctx_print_info(ctx, NULL));
}

static void particles_api(pdk_ctx *ctx, pdk_particles *p) {
  pdk_particles *q = NULL;
  NULL_ARG(NOCTX, pdk_particles_create(NULL, 2, 4, &q));
  IS(!q);
  NULL_ARG(ctx, pdk_particles_create(ctx, 2, 4, NULL));
  pdk_particles_destroy(NULL);
  pdk_particles_destroy(&q);
  IS(pdk_particles_dim(NULL) == 0 && pdk_particles_count(NULL) == 0);
  IS(pdk_particles_count_padded(NULL) == 0 && pdk_particles_ctx(NULL) == NULL);
  NULL_ARG(NOCTX, pdk_particles_field_add(NULL, "a", PDK_F64, 1));
  ARG_ERR(pdk_particles_field_add(p, NULL, PDK_F64, 1));
  NULL_ARG(NOCTX, pdk_particles_field_remove(NULL, "a"));
  NULL_ARG(ctx, pdk_particles_field_remove(p, NULL));
  IS(!pdk_particles_field_exists(NULL, "X") && !pdk_particles_field_exists(p, NULL));
  void *data = p;
  NULL_ARG(NOCTX, pdk_particles_field_get(NULL, "X", 0, &data));
  NULL_ARG(ctx, pdk_particles_field_get(p, "X", 0, NULL));
  NULL_ARG(ctx, pdk_particles_field_get(p, NULL, 0, &data));
  IS(!pdk_particles_field_data(NULL, "X", 0) && !pdk_particles_field_data(p, NULL, 0));
  pdk_type type;
  int nc;
  NULL_ARG(NOCTX, pdk_particles_field_info(NULL, "X", &type, &nc));
  NULL_ARG(ctx, pdk_particles_field_info(p, NULL, &type, &nc));
  IS(pdk_particles_num_fields(NULL) == 0 && pdk_particles_field_name(NULL, 0) == NULL);
  IS(pdk_particles_field_bytes(NULL, "X") == 0 && pdk_particles_field_bytes(p, NULL) == 0);
  IS(pdk_particles_memory_bytes(NULL) == 0);
  pdk_particles_print_memory(NULL, stdout);
  pdk_particles_print_memory(p, NULL);
  IS(!pdk_particles_X(NULL, 0) && !pdk_particles_volume(NULL) && !pdk_particles_id(NULL));
  NULL_ARG(NOCTX, pdk_particles_check_finite(NULL));
  const pdk_index perm[1] = {0};
  const uint8_t keep[1] = {1};
  NULL_ARG(NOCTX, pdk_particles_permute(NULL, perm));
  NULL_ARG(ctx, pdk_particles_permute(p, NULL));
  NULL_ARG(NOCTX, pdk_particles_compact(NULL, keep));
  NULL_ARG(ctx, pdk_particles_compact(p, NULL));
  NULL_ARG(NOCTX, pdk_particles_reorder_morton(NULL, 1.0, NULL));
  NULL_ARG(NOCTX, pdk_particles_reorder_rows(NULL, 1.0, NULL));
}

static void geometry_api(pdk_ctx *ctx, pdk_particles *p) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  pdk_particles *q = NULL;
  pdk_index count = 0;
  NULL_ARG(NOCTX, pdk_lattice_create(NULL, &lo, &q));
  NULL_ARG(ctx, pdk_lattice_create(ctx, &lo, NULL));
  NULL_ARG(NOCTX, pdk_lattice_count(NULL, &lo, &count));
  NULL_ARG(ctx, pdk_lattice_count(ctx, &lo, NULL));
  pdk_region r = pdk_region_box(NULL, NULL); /* zeros */
  IS(r.kind == PDK_REGION_BOX && r.hi[0] == 0.0);
  r = pdk_region_ball(NULL, 1.0);
  r = pdk_region_halfspace(NULL, NULL);
  r = pdk_region_polygon(NULL, 0);
  const double lo3[3] = {-1, -1, -1}, hi3[3] = {1, 1, 1}, x[3] = {0, 0, 0};
  r = pdk_region_box(lo3, hi3);
  NULL_ARG(NOCTX, pdk_region_check(NULL, 2, &r));
  ARG_ERR(pdk_region_check(ctx, 2, NULL));
  IS(pdk_region_contains(NULL, 2, x) == 0 && pdk_region_contains(&r, 2, NULL) == 0);
  char buf[64];
  pdk_region_describe(NULL, 2, buf, sizeof buf);
  IS(strstr(buf, "NULL") != NULL);
  pdk_region_describe(&r, 2, NULL, 0);
  NULL_ARG(NOCTX, pdk_particles_cut(NULL, &r, NULL));
  ARG_ERR(pdk_particles_cut(p, NULL, NULL));
  NULL_ARG(NOCTX, pdk_particles_set_define(NULL, "a", &r, NULL));
  ARG_ERR(pdk_particles_set_define(p, NULL, &r, NULL));
  ARG_ERR(pdk_particles_set_define(p, "a", NULL, NULL));
  pdk_index *idx = NULL;
  NULL_ARG(NOCTX, pdk_particles_set_indices(NULL, "a", &idx, &count));
  NULL_ARG(ctx, pdk_particles_set_indices(p, "a", NULL, &count));
  ARG_ERR(pdk_particles_set_indices(p, NULL, &idx, &count));
}

static void families_api(pdk_ctx *ctx, pdk_particles *p) {
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 1.5;
  pdk_families *f = NULL;
  NULL_ARG(NOCTX, pdk_families_build(NULL, &fo, &f));
  NULL_ARG(ctx, pdk_families_build(p, &fo, NULL));
  const double *coords[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1), NULL};
  NULL_ARG(NOCTX,
           pdk_families_build_coords(NULL, 2, pdk_particles_count(p), coords, NULL, &fo, &f));
  NULL_ARG(ctx, pdk_families_build_coords(ctx, 2, pdk_particles_count(p), coords, NULL, &fo, NULL));
  ARG_ERR(pdk_families_build_coords(ctx, 2, pdk_particles_count(p), NULL, NULL, &fo, &f));
  pdk_families_destroy(NULL);
  pdk_families_destroy(&f);
  IS(pdk_families_num_particles(NULL) == 0 && pdk_families_num_bonds(NULL) == 0);
  IS(!pdk_families_bond_start(NULL) && !pdk_families_bond_j(NULL));
  IS(isnan(pdk_families_horizon(NULL)) && pdk_families_memory_bytes(NULL) == 0);
  IS(pdk_families_cell_edge(NULL, 1.0) == 0.0);
}

static void model_api(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam, pdk_model *m) {
  pdk_model_opts mo = *pdk_model_opts_get(m);
  pdk_model *q = NULL;
  NULL_ARG(NOCTX, pdk_model_create(NULL, fam, &mo, &q));
  NULL_ARG(ctx, pdk_model_create(p, NULL, &mo, &q));
  NULL_ARG(ctx, pdk_model_create(p, fam, NULL, &q));
  NULL_ARG(ctx, pdk_model_create(p, fam, &mo, NULL));
  IS(!q);
  pdk_model_destroy(NULL);
  pdk_model_destroy(&q);
  double e = 0.0;
  NULL_ARG(NOCTX, pdk_model_force(NULL, &e));
  NULL_ARG(NOCTX, pdk_model_force_trial(NULL, &e));
  IS(!pdk_model_opts_get(NULL) && !pdk_model_particles(NULL) && !pdk_model_families(NULL));
  IS(!pdk_model_bond_alive(NULL) && pdk_model_num_broken(NULL) == 0);
  IS(pdk_model_num_flagged(NULL) == 0 && pdk_model_num_isolated(NULL) == 0);
  IS(pdk_model_float_stretch_ratio(NULL) == -1.0 && pdk_model_padding_fraction(NULL) == 0.0);
  IS(!pdk_model_stencil_active(NULL) && !pdk_model_stencil_reason(NULL)[0]);
  IS(pdk_model_num_failed(NULL) == 0 && pdk_model_damage_max(NULL) == 0.0);
  IS(pdk_model_num_compactions(NULL) == 0 && pdk_model_num_rebuilds(NULL) == 0);
  NULL_ARG(NOCTX, pdk_model_rebuild(NULL));
  IS(!pdk_model_current_families(NULL));
  NULL_ARG(NOCTX, pdk_model_set_dt(NULL, 1e-6));
  IS(isnan(pdk_model_get_dt(NULL)));
  IS(!pdk_model_opts_uses(NULL, "law") && !pdk_model_opts_uses(&mo, NULL));
  double a, b, c;
  NULL_ARG(NOCTX, pdk_model_plastic_work(NULL, &a, &b, &c));
  NULL_ARG(NOCTX, pdk_smooth_field(NULL, fam, PDK_INFLUENCE_CONSTANT, 0.0, "volume", "sm"));
  NULL_ARG(ctx, pdk_smooth_field(p, NULL, PDK_INFLUENCE_CONSTANT, 0.0, "volume", "sm"));
  ARG_ERR(pdk_smooth_field(p, fam, PDK_INFLUENCE_CONSTANT, 0.0, NULL, "sm"));
}

static void explicit_api(pdk_ctx *ctx, pdk_model *m, pdk_explicit *e) {
  IS(isnan(pdk_tfun_value(NULL, 0.0)) && isnan(pdk_tfun_rate(NULL, 0.0)));
  IS(isnan(pdk_tfun_integral(NULL, 0.0, 1.0)));
  pdk_explicit *q = NULL;
  NULL_ARG(NOCTX, pdk_explicit_create(NULL, NULL, &q));
  NULL_ARG(ctx, pdk_explicit_create(m, NULL, NULL));
  pdk_explicit_destroy(NULL);
  pdk_explicit_destroy(&q);
  IS(isnan(pdk_explicit_stable_dt(NULL)) && isnan(pdk_explicit_dt(NULL)));
  long s0 = -1;
  double t0 = 0.0;
  pdk_explicit_dt_start(NULL, &s0, &t0);
  IS(s0 == 0 && isnan(t0));
  pdk_explicit_dt_start(e, NULL, NULL);
  IS(pdk_explicit_num_estimates(NULL) == 0 && pdk_explicit_num_dt_changes(NULL) == 0);
  IS(!pdk_explicit_opts_get(NULL));
  pdk_history h;
  NULL_ARG(NOCTX, pdk_explicit_run(NULL, 1, &h));
  T_OK(ctx, pdk_explicit_run(e, 1, NULL)); /* the history is optional */
  IS(isnan(pdk_explicit_time(NULL)) && pdk_explicit_step(NULL) == 0);
}

static void output_api(pdk_ctx *ctx, pdk_particles *p, pdk_explicit *e) {
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = "t194_api_null.out";
  oo.name = "t194";
  oo.plot = 0;
  pdk_output *o = NULL;
  NULL_ARG(NOCTX, pdk_output_open(NULL, &oo, p, &o));
  ARG_ERR(pdk_output_open(ctx, &oo, NULL, &o));
  NULL_ARG(ctx, pdk_output_open(ctx, &oo, p, NULL));
  pdk_history h;
  memset(&h, 0, sizeof h);
  const char *fields[1] = {"volume"};
  ARG_ERR(pdk_output_write_fields(NULL, p, 0, 0.0, fields, 1));
  ARG_ERR(pdk_output_write_fields(NULL, NULL, 0, 0.0, fields, 1));
  NULL_ARG(NOCTX, pdk_output_write_history(NULL, &h));
  IS(!pdk_output_will_plot(NULL) && pdk_output_num_field_steps(NULL) == 0);
  IS(pdk_output_num_history_rows(NULL) == 0);
  IS(pdk_output_close(NULL, 1) == PDK_SUCCESS && pdk_output_close(&o, 1) == PDK_SUCCESS);
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  ARG_ERR(pdk_output_write_fields(o, NULL, 0, 0.0, fields, 1));
  NULL_ARG(ctx, pdk_output_write_history(o, NULL));
  NULL_ARG(NOCTX, pdk_output_adopt(NULL, "a.part", "a"));
  ARG_ERR(pdk_output_adopt(o, NULL, "a"));
  ARG_ERR(pdk_output_adopt(o, "a.part", NULL));
  pdk_output_close(&o, 0);
  const char *ck = "t194_api_null.out/ck.h5";
  NULL_ARG(NOCTX, pdk_checkpoint_write(NULL, ck, e, NULL));
  ARG_ERR(pdk_checkpoint_write(ctx, NULL, e, NULL));
  ARG_ERR(pdk_checkpoint_write(ctx, ck, NULL, NULL));
  NULL_ARG(NOCTX, pdk_checkpoint_read(NULL, ck, e));
  ARG_ERR(pdk_checkpoint_read(ctx, NULL, e));
  ARG_ERR(pdk_checkpoint_read(ctx, ck, NULL));
  long step;
  double time;
  NULL_ARG(NOCTX, pdk_checkpoint_info(NULL, ck, &step, &time, NULL));
  ARG_ERR(pdk_checkpoint_info(ctx, NULL, &step, &time, NULL));
}

static void static_api(pdk_ctx *ctx, pdk_model *m) {
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_ADR);
  pdk_static *s = NULL;
  NULL_ARG(NOCTX, pdk_static_create(NULL, &so, &s));
  ARG_ERR(pdk_static_create(m, NULL, &s));
  NULL_ARG(ctx, pdk_static_create(m, &so, NULL));
  pdk_static_destroy(NULL);
  pdk_static_destroy(&s);
  NULL_ARG(NOCTX, pdk_static_solve(NULL));
  NULL_ARG(NOCTX, pdk_static_solve_level(NULL));
  IS(pdk_static_num_levels(NULL) == 0 && pdk_static_levels_solved(NULL) == 0);
  IS(isnan(pdk_static_total_time(NULL)) && isnan(pdk_static_level_time(NULL, 0)));
  IS(!pdk_static_last_event(NULL) && !pdk_static_stats_get(NULL));
  pdk_static_stats st;
  memset(&st, 0, sizeof st);
  pdk_static_stats_print(NULL, stdout);
  pdk_static_stats_print(&st, NULL);
}

static void plasticity_api(pdk_ctx *ctx) {
  pdk_jc_params jp = pdk_jc_params_default();
  NULL_ARG(NOCTX, pdk_jc_params_check(NULL, &jp));
  ARG_ERR(pdk_jc_params_check(ctx, NULL));
  pdk_jc_state in = pdk_jc_state_initial(), out;
  pdk_jc_result res;
  double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, P[3][3];
  ARG_ERR(pdk_jc_update(NULL, 2, F, 1e-6, &in, &out, P, &res));
  ARG_ERR(pdk_jc_update(&jp, 2, NULL, 1e-6, &in, &out, P, &res));
  ARG_ERR(pdk_jc_update(&jp, 2, F, 1e-6, NULL, &out, P, &res));
  ARG_ERR(pdk_jc_update(&jp, 2, F, 1e-6, &in, NULL, P, &res));
  ARG_ERR(pdk_jc_update(&jp, 2, F, 1e-6, &in, &out, NULL, &res));
  IS(pdk_jc_update(&jp, 2, F, 1e-6, &in, &out, P, NULL) == PDK_SUCCESS); /* res is optional */
  ARG_ERR(pdk_jc_update_avg(NULL, 2, F, 1e-6, 0.0, &in, &out, P, &res));
  ARG_ERR(pdk_jc_update_avg(&jp, 2, NULL, 1e-6, 0.0, &in, &out, P, &res));
  ARG_ERR(pdk_jc_update_avg(&jp, 2, F, 1e-6, 0.0, NULL, &out, P, &res));
  ARG_ERR(pdk_jc_update_avg(&jp, 2, F, 1e-6, 0.0, &in, NULL, P, &res));
  ARG_ERR(pdk_jc_update_avg(&jp, 2, F, 1e-6, 0.0, &in, &out, NULL, &res));
  ARG_ERR(pdk_jc_remap(2, NULL, F, &in));
  ARG_ERR(pdk_jc_remap(2, F, NULL, &in));
  ARG_ERR(pdk_jc_remap(2, F, F, NULL));
  IS(isnan(pdk_jc_flow_stress(NULL, 0.1, 1.0, 0.0)));
  IS(isnan(pdk_jc_failure_strain(NULL, 0.3, 1.0, 0.0)));
}

static void scene_api(pdk_ctx *ctx) {
  char path[1024];
  snprintf(path, sizeof path, "%s/tests/scenes/t060_minimal.yaml", getenv("PDK_SOURCE_DIR"));
  pdk_scene *s = NULL;
  NULL_ARG(NOCTX, pdk_scene_load(NULL, path, NULL, 0, &s));
  ARG_ERR(pdk_scene_load(ctx, NULL, NULL, 0, &s));
  ARG_ERR(pdk_scene_load(ctx, path, NULL, 0, NULL));
  ARG_ERR(pdk_scene_load(ctx, path, NULL, 1, &s));
  pdk_scene_destroy(NULL);
  pdk_scene_destroy(&s);
  IS(!pdk_scene_path(NULL)[0] && !pdk_scene_name(NULL)[0] && !pdk_scene_text(NULL)[0]);
  IS(pdk_scene_threads(NULL) == 0 && pdk_scene_dimension(NULL) == 0);
  IS(pdk_scene_solver_type(NULL) == PDK_SOLVER_EXPLICIT && !pdk_scene_output_get(NULL));
  char buf[128];
  pdk_scene_key_location(NULL, "solver", buf, sizeof buf);
  IS(strstr(buf, "no scene") != NULL);
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  pdk_scene_key_location(s, "solver", NULL, 0);
  pdk_scene_key_location(s, NULL, buf, sizeof buf);
  IS(pdk_scene_error(NULL, ctx, PDK_ERR_ARG, "solver", "bad %d", 1) == PDK_ERR_ARG);
  IS(pdk_scene_error(s, NULL, PDK_ERR_ARG, "solver", "bad %d", 1) == PDK_ERR_ARG);
  IS(pdk_scene_error(s, ctx, PDK_ERR_ARG, NULL, NULL) == PDK_ERR_ARG);
  pdk_sim *sim = NULL;
  NULL_ARG(NOCTX, pdk_sim_create(NULL, s, &sim));
  ARG_ERR(pdk_sim_create(ctx, NULL, &sim));
  ARG_ERR(pdk_sim_create(ctx, s, NULL));
  pdk_sim_destroy(NULL);
  pdk_sim_destroy(&sim);
  IS(!pdk_sim_particles(NULL) && !pdk_sim_families(NULL) && !pdk_sim_model(NULL));
  IS(!pdk_sim_explicit(NULL) && pdk_sim_num_steps(NULL) == 0 && !pdk_sim_static(NULL));
  IS(pdk_sim_solver_type(NULL) == PDK_SOLVER_EXPLICIT);
  pdk_history h;
  NULL_ARG(NOCTX, pdk_sim_static_step(NULL, &h));
  NULL_ARG(NOCTX, pdk_sim_static_history(NULL, &h));
  NULL_ARG(NOCTX, pdk_sim_update_output_fields(NULL));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  NULL_ARG(ctx, pdk_sim_static_history(sim, NULL));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  ctx_api(ctx);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1.0;
  lo.hi[0] = 6.0;
  lo.hi[1] = 4.0;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 1.5;
  pdk_families *fam = NULL;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.bulk_modulus = 1.0;
  mo.density = 1.0;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_explicit *e = NULL;
  T_OK(ctx, pdk_explicit_create(m, NULL, &e));

  particles_api(ctx, p);
  geometry_api(ctx, p);
  families_api(ctx, p);
  model_api(ctx, p, fam, m);
  explicit_api(ctx, m, e);
  output_api(ctx, p, e);
  static_api(ctx, m);
  plasticity_api(ctx);
  scene_api(ctx);

  pdk_explicit_destroy(&e);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
