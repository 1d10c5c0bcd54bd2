/* Scenes with a static solver (solver.type adr | newton): every key is read into the solver's
 * options, the defaults of a static scene differ where they must (history every load step, no
 * velocity field), and every mistake gives a message naming the file, the override or line, the
 * key, and what is allowed. Also: pdk_sim builds the static solver, and its load steps advance one
 * at a time with one history record each.
 * labels: unit
 */
#include "scene/scene_impl.h"
#include "test_util.h"

static const char *base_scene = "dimension: 2\n"
                                "geometry:\n"
                                "  spacing: 1.0e-3\n"
                                "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                                "material: {density: 7850, youngs_modulus: 200e9, "
                                "poisson_ratio: 0.3}\n"
                                "model: {kind: lps}\n"
                                "sets:\n"
                                "  - {name: bottom, box: {lo: [-1, -1], hi: [1, 0.0012]}}\n"
                                "  - {name: top, box: {lo: [-1, 0.0188], hi: [1, 1]}}\n"
                                "boundary_conditions:\n"
                                "  - {set: bottom, type: displacement, x: 0, y: 0}\n"
                                "  - {set: top, type: displacement, y: 1.0e-5}\n"
                                "solver:\n"
                                "  type: adr\n";

static const char *path = "t064_scene.yaml";

static void write_base(void) {
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fputs(base_scene, f) >= 0 && !fclose(f), "writing %s", path);
}

typedef struct error_case {
  const char *override[2]; /* applied in order; the message names the last one */
  const char *key;         /* key path the message must name */
  const char *needle;      /* another part it must contain */
} error_case;

static const error_case cases[] = {
    {{"solver.type=implicit"}, "solver.type", "explicit, adr, newton"},
    {{"solver.steps=10"}, "solver.steps", "key of the explicit solver"},
    {{"solver.dt_update=breaks"}, "solver.dt_update", "key of the explicit solver"},
    {{"solver.dt=1e-6"}, "solver.dt", "load_steps or load_levels"},
    {{"solver.load_steps=0"}, "solver.load_steps", "whole number"},
    {{"solver.load_steps=2.5"}, "solver.load_steps", "whole number"},
    {{"solver.load_steps=3", "solver.load_levels=[0.5, 1]"}, "solver.load_levels", "one of them"},
    {{"solver.load_levels=[0.5, 0.4]"}, "solver.load_levels[1]", "increasing"},
    {{"solver.load_levels=[0.5, 1.5]"}, "solver.load_levels[1]", "(0, 1]"},
    {{"solver.tolerance=0"}, "solver.tolerance", "(0, 1)"},
    {{"solver.absolute_tolerance=-1"}, "solver.absolute_tolerance", ">= 0"},
    {{"solver.max_iterations=0"}, "solver.max_iterations", "whole number"},
    {{"solver.max_break_rounds=-1"}, "solver.max_break_rounds", "whole number"},
    {{"solver.adr_mass=diagonal"}, "solver.adr_mass", "auto, row_sum, lanczos"},
    {{"solver.adr_safety=0.5"}, "solver.adr_safety", "stable bound"},
    {{"solver.linear_solver=cholmod"}, "solver.linear_solver", "key of the newton solver"},
    {{"solver.type=newton", "solver.adr_safety=2"}, "solver.adr_safety", "key of the adr solver"},
    {{"solver.type=newton", "solver.linear_solver=lu"},
     "solver.linear_solver",
     "auto, cholmod, umfpack"},
    {{"solver.type=newton", "solver.fd_scheme=backward"}, "solver.fd_scheme", "central, forward"},
    {{"solver.type=newton", "solver.tangent=exact"},
     "solver.tangent",
     "auto, analytic, difference"},
    {{"solver.tangent=analytic"}, "solver.tangent", "key of the newton solver"},
    {{"solver.type=newton", "solver.fd_step=0.5"}, "solver.fd_step", "(0, 0.1)"},
    {{"solver.type=newton", "solver.line_search_backtracks=61"},
     "solver.line_search_backtracks",
     "[0, 60]"},
    {{"solver.type=newton", "solver.line_search_decrease=1"},
     "solver.line_search_decrease",
     "(0, 1)"},
    {{"solver.type=newton", "solver.singular_tolerance=1"}, "solver.singular_tolerance", "[0, 1)"},
    {{"solver.type=newton", "solver.symmetry_tolerance=-1"}, "solver.symmetry_tolerance", ">= 0"},
    {{"solver.end_time=1e-3"}, "solver.end_time", "constant in time"},
    {{"solver.end_time=-1"}, "solver.end_time", "must be > 0"},
    {{"boundary_conditions[1].type=velocity"}, "boundary_conditions[1].type", "function: linear"},
    {{"initial_conditions.velocity=[0, 1]"}, "initial_conditions", "no velocities"},
    /* an explicit scene refuses the static keys */
    {{"solver.type=explicit", "solver.load_steps=4"},
     "solver.load_steps",
     "key of the static solvers"},
};

static void run_case(pdk_ctx *ctx, const error_case *c) {
  const char *ov[2];
  int n = 0;
  while (n < 2 && c->override[n]) {
    ov[n] = c->override[n];
    ++n;
  }
  pdk_scene *s = NULL;
  pdk_ctx_error_clear(ctx);
  const int err = pdk_scene_load(ctx, path, ov, n, &s);
  const char *msg = pdk_ctx_error_message(ctx);
  if (err != PDK_ERR_ARG || s)
    T_FAIL("case %s: returned %d (scene %p), expected PDK_ERR_ARG; message: %s", ov[n - 1], err,
           (void *)s, msg);
  char want[512];
  snprintf(want, sizeof want, "%s: --set %s: %s: ", path, ov[n - 1], c->key);
  if (!strstr(msg, want))
    T_FAIL("case %s: message does not start with '%s':\n  %s", ov[n - 1], want, msg);
  if (!strstr(msg, c->needle))
    T_FAIL("case %s: message does not mention '%s':\n  %s", ov[n - 1], c->needle, msg);
  if (getenv("PDK_TEST_VERBOSE")) printf("%s\n", msg);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  write_base();

  /* Defaults of an ADR scene. */
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  T_ASSERT(pdk_scene_solver_type(s) == PDK_SOLVER_ADR, "type adr");
  const pdk_static_opts *o = &s->static_opts;
  T_ASSERT(o->method == PDK_STATIC_ADR && o->num_levels == 1 && o->load_levels == NULL &&
               o->rtol == 1e-6 && o->atol == 0 && o->total_time == 0 && o->num_bcs == 2 &&
               o->max_break_rounds == 1000 && o->extrapolate == 1 &&
               o->adr_mass == PDK_ADR_MASS_AUTO && o->adr_safety == 1.0,
           "adr defaults");
  T_ASSERT(o->num_reaction_sets == 2 && !strcmp(o->reaction_sets[0], "set:bottom"),
           "reaction sets default to the displacement conditions' sets");
  const pdk_scene_output *out = pdk_scene_output_get(s);
  T_ASSERT(out->history_interval == 1 && out->num_fields == 1 && !strcmp(out->fields[0], "u"),
           "static output defaults: every load step, field u (there is no velocity)");
  pdk_scene_destroy(&s);

  /* Every key of a Newton scene, in time mode. */
  const char *newton[] = {"solver.type=newton",
                          "solver.load_levels=[0.25, 0.5, 1]",
                          "solver.end_time=2e-3",
                          "boundary_conditions[1].function=linear",
                          "solver.tolerance=1e-9",
                          "solver.absolute_tolerance=1e-12",
                          "solver.max_iterations=20",
                          "solver.max_break_rounds=7",
                          "solver.extrapolate=false",
                          "solver.linear_solver=umfpack",
                          "solver.tangent=difference",
                          "solver.fd_scheme=forward",
                          "solver.fd_step=1e-6",
                          "solver.line_search_backtracks=4",
                          "solver.line_search_decrease=0.01",
                          "solver.reuse_tangent=false",
                          "solver.singular_tolerance=1e-9",
                          "solver.symmetry_tolerance=1e-5",
                          "solver.threads=2"};
  T_OK(ctx, pdk_scene_load(ctx, path, newton, (int)(sizeof newton / sizeof newton[0]), &s));
  o = &s->static_opts;
  T_ASSERT(pdk_scene_solver_type(s) == PDK_SOLVER_NEWTON && o->method == PDK_STATIC_NEWTON,
           "type newton");
  T_ASSERT(o->num_levels == 3 && o->load_levels && o->load_levels[0] == 0.25 &&
               o->load_levels[2] == 1.0 && o->total_time == 2e-3,
           "levels and total time");
  T_ASSERT(o->rtol == 1e-9 && o->atol == 1e-12 && o->max_iterations == 20 &&
               o->max_break_rounds == 7 && o->extrapolate == 0,
           "convergence keys");
  T_ASSERT(o->linear_solver == PDK_LINEAR_UMFPACK && o->tangent == PDK_TANGENT_DIFFERENCE &&
               o->fd_scheme == PDK_FD_FORWARD &&
               o->fd_step == 1e-6 && o->max_backtracks == 4 && o->ls_decrease == 0.01 &&
               o->reuse_tangent == 0 && o->singular_rtol == 1e-9 && o->sym_rtol == 1e-5 &&
               pdk_scene_threads(s) == 2,
           "newton keys");
  T_ASSERT(s->bcs[1].value[1].kind == PDK_TFUN_LINEAR && s->bcs[1].value[1].b == 1e-5,
           "a linear displacement: value is the rate");

  /* Build it and step: one record per load step, at the levels' pseudo-times, the top pulled to
   * 1e-5 m/s x t (the linear function at t_k = level x 2e-3 s), history advancing monotonically.
   */
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(pdk_sim_explicit(sim) == NULL && pdk_sim_static(sim) != NULL &&
               pdk_sim_num_steps(sim) == 3 && pdk_sim_solver_type(sim) == PDK_SOLVER_NEWTON,
           "static simulation");
  pdk_history h;
  T_OK(ctx, pdk_sim_static_history(sim, &h));
  T_ASSERT(h.step == 0 && h.time == 0 && h.strain == 0 && h.external_work == 0,
           "the unloaded record");
  const double levels[3] = {0.25, 0.5, 1.0};
  double last_reaction = 0.0;
  for (int k = 0; k < 3; ++k) {
    T_OK(ctx, pdk_sim_static_step(sim, &h));
    T_ASSERT(h.step == k + 1, "step %ld", h.step);
    T_NEAR(h.time, levels[k] * 2e-3, 1e-15, 0, "pseudo-time of load step %d", k);
    T_NEAR(pdk_model_get_dt(pdk_sim_model(sim)), (levels[k] - (k ? levels[k - 1] : 0)) * 2e-3,
           1e-12, 0, "the model's time step is the load step's pseudo-time increment");
    /* linear problem pulled proportionally: the reaction on the top grows with the pull */
    T_ASSERT(h.reaction[1][1] > last_reaction, "reaction on top grows (%g)", h.reaction[1][1]);
    last_reaction = h.reaction[1][1];
    /* Newton at rtol 1e-9: external work (trapezoid, exact for a linear problem) = strain
     * energy to well within 1e-6 */
    T_NEAR(h.external_work, h.strain, 1e-6, 0, "work = strain energy at load step %d", k);
  }
  const double *x = pdk_particles_field_data(pdk_sim_particles(sim), "x", 1);
  const double *X = pdk_particles_X(pdk_sim_particles(sim), 1);
  const uint8_t *top = pdk_particles_field_data(pdk_sim_particles(sim), "set:top", 0);
  for (pdk_index i = 0; i < pdk_particles_count(pdk_sim_particles(sim)); ++i)
    if (top[i]) T_NEAR(x[i] - X[i], 1e-5 * 2e-3, 1e-9, 0, "top displacement = rate x t_end");
  T_FAILS(ctx, pdk_sim_static_step(sim, &h), PDK_ERR_ARG, "all 3 load levels are solved");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);

  /* The mistakes. */
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
    run_case(ctx, &cases[k]);

  /* Johnson-Cook rate terms need a pseudo-time. */
  const char *jc[] = {"model={kind: correspondence, law: jc}",
                      "material.johnson_cook={A: 792e6, B: 510e6, n: 0.26, C: 0.014, damage: "
                      "false}"};
  T_FAILS(ctx, pdk_scene_load(ctx, path, jc, 2, &s), PDK_ERR_ARG, "give solver.end_time");
  T_ASSERT(s == NULL, "no scene on failure");

  remove(path);
  pdk_ctx_destroy(&ctx);
  return 0;
}
