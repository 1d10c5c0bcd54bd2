/* Scenes: a full scene maps onto the right option values, defaults fill in, overrides apply (and
 * their text reloads to the same scene), and the built simulation has the expected particles,
 * sets, pre-crack, boundary conditions and output fields.
 * labels: unit */
#include "pdk/scene.h"
#include "scene/scene_impl.h"
#include "test_util.h"

static char scene_dir[1024];

static const char *scene_path(const char *name) {
  static char buf[2048];
  snprintf(buf, sizeof buf, "%s/%s", scene_dir, name);
  return buf;
}

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  T_ASSERT(f, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  T_ASSERT(fread(b, 1, (size_t)n, f) == (size_t)n, "short read of %s", path);
  b[n] = '\0';
  fclose(f);
  return b;
}

/* Particles of the plate of t060_plate.yaml, counted independently of pdk's cut: lattice points
 * ((i + 1/2) dx, (j + 1/2) dx) outside the hole and the notch. */
static int plate_expected_count(void) {
  const double dx = 1e-3;
  int n = 0;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 20; ++i) {
      double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
      double r2 = (x - 0.01) * (x - 0.01) + (y - 0.02) * (y - 0.02);
      int in_hole = r2 <= 0.004 * 0.004;
      int in_notch = x <= 0.003 && y >= 0.0192 && y <= 0.0208;
      n += !in_hole && !in_notch;
    }
  return n;
}

static void check_full_mapping(const pdk_scene *s, const char *path) {
  T_ASSERT(!strcmp(pdk_scene_name(s), "plate_full"), "name %s", pdk_scene_name(s));
  T_ASSERT(!strcmp(pdk_scene_path(s), path), "path %s", pdk_scene_path(s));
  T_ASSERT(pdk_scene_dimension(s) == 2 && pdk_scene_threads(s) == 1, "dim/threads");
  /* geometry */
  T_ASSERT(s->lattice.type == PDK_LATTICE_SQUARE, "lattice %d", (int)s->lattice.type);
  T_ASSERT(s->lattice.spacing == 1e-3 && s->lattice.thickness == 2e-3 && s->lattice.seed == 7 &&
               s->lattice.jitter == 0,
           "lattice values");
  T_ASSERT(s->model.thickness == 2e-3, "model thickness %g: the 2-D volumes' thickness",
           s->model.thickness);
  T_ASSERT(s->lattice.lo[0] == 0 && s->lattice.hi[0] == 0.02 && s->lattice.hi[1] == 0.04, "box");
  T_NEAR(s->horizon, 3.015e-3, 1e-15, 0, "horizon = factor x spacing");
  T_ASSERT(s->num_holes == 1 && s->holes[0].region.kind == PDK_REGION_BALL &&
               s->holes[0].region.radius == 0.004 && s->holes[0].region.center[1] == 0.02,
           "hole");
  T_ASSERT(s->num_notches == 1 && s->notches[0].region.kind == PDK_REGION_BOX &&
               s->notches[0].region.hi[0] == 0.003,
           "notch");
  T_ASSERT(s->num_precracks == 1 && s->precracks[0].num_vertices == 2 &&
               s->precracks[0].vertices[0] == 0.014 && s->precracks[0].vertices[2] == 0.017 &&
               s->precracks[0].vertices[3] == 0.02,
           "pre-crack");
  /* material and model: K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)) */
  const pdk_model_opts *m = &s->model;
  T_ASSERT(m->kind == PDK_MODEL_CORRESPONDENCE && m->influence == PDK_INFLUENCE_CUBIC &&
               m->stabilization == PDK_STAB_SILLING && m->law == PDK_LAW_NEO_HOOKE &&
               m->precision == PDK_PRECISION_DOUBLE && m->stencil == PDK_STENCIL_OFF,
           "model enums");
  T_NEAR(m->bulk_modulus, 200e9 / 1.5, 1e-15, 0, "K from E, nu");
  T_NEAR(m->shear_modulus, 80e9, 1e-15, 0, "G from E, nu");
  T_ASSERT(m->density == 7850 && m->stab_coefficient == 0.2 && m->critical_stretch == 0.01 &&
               m->alpha == 0.25 && m->lattice_constant == 0,
           "model values");
  /* sets, conditions, solver */
  T_ASSERT(s->num_sets == 2 && !strcmp(s->sets[0].name, "bottom") &&
               !strcmp(s->sets[1].field, "set:top") &&
               s->sets[1].region.kind == PDK_REGION_HALFSPACE,
           "sets");
  T_ASSERT(s->num_bcs == 2 && s->solver.num_bcs == 2 && s->solver.bcs == s->bcs, "bc count");
  T_ASSERT(s->bcs[0].kind == PDK_BC_DISPLACEMENT && !strcmp(s->bcs[0].set, "set:bottom") &&
               s->bcs[0].components == 3 && s->bcs[0].value[0].kind == PDK_TFUN_CONSTANT &&
               s->bcs[0].value[1].a == 0,
           "bc 0");
  T_ASSERT(s->bcs[1].kind == PDK_BC_VELOCITY && !strcmp(s->bcs[1].set, "set:top") &&
               s->bcs[1].components == 2 && s->bcs[1].value[1].kind == PDK_TFUN_RAMP &&
               s->bcs[1].value[1].a == 2.0 && s->bcs[1].value[1].b == 1e-6,
           "bc 1");
  T_ASSERT(s->solver.v0_const[0] == 0.5 && s->solver.v0_const[1] == 0 &&
               s->solver.v0_grad[1][1] == 1.0 && s->solver.v0_grad[0][1] == 0,
           "initial velocity");
  T_ASSERT(s->solver.dt == 0 && s->solver.safety == 0.7 && !s->solver.force_dt &&
               s->end_time == 2e-6 && s->steps == 0,
           "solver");
  const pdk_scene_output *o = pdk_scene_output_get(s);
  T_ASSERT(o->field_interval == 100 && o->history_interval == 5 && o->checkpoint_interval == 1000,
           "output intervals");
  T_ASSERT(o->units && !strcmp(o->units, "SI"), "output units %s", o->units ? o->units : "none");
  T_ASSERT(o->num_fields == 3 && !strcmp(o->fields[0], "u") && !strcmp(o->fields[2], "f"),
           "output fields");
  T_ASSERT(o->num_reaction_sets == 2 && !strcmp(o->reaction_sets[0], "top") &&
               !strcmp(o->reaction_sets[1], "bottom") && s->solver.num_reaction_sets == 2 &&
               !strcmp(s->solver.reaction_sets[0], "set:top"),
           "reaction sets");
}

/* No bond of the built plate crosses the pre-crack segment (0.014, 0.02)-(0.017, 0.02); some bonds
 * cross the line y = 0.02 elsewhere. */
static void check_precrack_bonds(pdk_sim *sim) {
  pdk_particles *p = pdk_sim_particles(sim);
  pdk_families *f = pdk_sim_families(sim);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const pdk_bond_index *start = pdk_families_bond_start(f);
  const pdk_index *bj = pdk_families_bond_j(f);
  long crossing_elsewhere = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    for (pdk_bond_index b = start[i]; b < start[i + 1]; ++b) {
      pdk_index j = bj[b];
      if ((Y[i] - 0.02) * (Y[j] - 0.02) >= 0) continue;
      double x = X[i] + (X[j] - X[i]) * (0.02 - Y[i]) / (Y[j] - Y[i]);
      T_ASSERT(!(x > 0.014 + 1e-9 && x < 0.017 - 1e-9), "bond %d-%d crosses the pre-crack at x %g",
               (int)i, (int)j, x);
      crossing_elsewhere += x > 0.018;
    }
  T_ASSERT(crossing_elsewhere > 0, "no bond crosses y = 0.02 right of the crack");
}

static void check_full_sim(pdk_ctx *ctx, const pdk_scene *s) {
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(pdk_ctx_num_threads(ctx) == 1, "solver.threads sets the context's threads, got %d",
           pdk_ctx_num_threads(ctx));
  pdk_particles *p = pdk_sim_particles(sim);
  T_ASSERT(pdk_particles_count(p) == plate_expected_count(), "particles %d, expected %d",
           (int)pdk_particles_count(p), plate_expected_count());
  pdk_index *idx = NULL, nb = 0, nt = 0;
  T_OK(ctx, pdk_particles_set_indices(p, "bottom", &idx, &nb));
  free(idx);
  T_OK(ctx, pdk_particles_set_indices(p, "top", &idx, &nt));
  free(idx);
  T_ASSERT(nb == 40 && nt == 60, "set sizes bottom %d (40), top %d (60)", (int)nb, (int)nt);
  /* Morton order: particles are no longer in lattice order (ids are a permutation). */
  const int64_t *id = pdk_particles_id(p);
  int in_order = 1;
  for (pdk_index i = 1; i < pdk_particles_count(p); ++i)
    in_order &= id[i] > id[i - 1];
  T_ASSERT(!in_order, "particles were not reordered");
  check_precrack_bonds(sim);
  T_ASSERT(pdk_model_opts_get(pdk_sim_model(sim))->kind == PDK_MODEL_CORRESPONDENCE, "model kind");
  pdk_explicit *e = pdk_sim_explicit(sim);
  double dt = pdk_explicit_dt(e);
  T_NEAR(dt, 0.7 * pdk_explicit_stable_dt(e), 1e-15, 0, "dt = safety x stable");
  long n = pdk_sim_num_steps(sim);
  T_ASSERT(n == (long)ceil(2e-6 / dt * (1 - 1e-12)) && (n - 1) * dt < 2e-6 &&
               n * dt >= 2e-6 * (1 - 1e-12),
           "num_steps %ld for end_time 2e-6, dt %g", n, dt);
  /* Run two steps; the bottom stays fixed, the top moves up at the ramped velocity, u = x - X. */
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(e, 2, &h));
  T_OK(ctx, pdk_sim_update_output_fields(sim));
  const uint8_t *top = pdk_particles_field_data(p, "set:top", 0);
  const uint8_t *bottom = pdk_particles_field_data(p, "set:bottom", 0);
  const double *vy = pdk_particles_field_data(p, "v", 1);
  const double *uy = pdk_particles_field_data(p, "u", 1), *ux = pdk_particles_field_data(p, "u", 0);
  const double *xy = pdk_particles_field_data(p, "x", 1);
  T_ASSERT(uy && ux, "u declared because output.fields lists it");
  double t = pdk_explicit_time(e);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    T_ASSERT(uy[i] == xy[i] - pdk_particles_X(p, 1)[i], "u = x - X at %d", (int)i);
    if (bottom[i]) T_ASSERT(ux[i] == 0 && uy[i] == 0, "bottom fixed at %d", (int)i);
    if (top[i]) T_NEAR(vy[i], 2.0 * t / 1e-6, 1e-12, 0, "top velocity ramp at %d", (int)i);
  }
  T_ASSERT(h.reaction[1][1] != 0, "bottom reaction recorded");
  pdk_sim_destroy(&sim);
  T_ASSERT(sim == NULL, "destroy clears the pointer");
}

static void check_minimal(pdk_ctx *ctx) {
  const char *path = scene_path("t060_minimal.yaml");
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  char *file = slurp(path);
  T_ASSERT(!strcmp(pdk_scene_text(s), file), "without overrides the text is the file");
  free(file);
  T_ASSERT(!strcmp(pdk_scene_name(s), "t060_minimal"), "default name is the file stem: %s",
           pdk_scene_name(s));
  T_ASSERT(s->dim == 3 && s->lattice.type == PDK_LATTICE_CUBIC && s->horizon_factor == 3.015 &&
               s->lattice.jitter == 0 && s->lattice.seed == 1 && s->num_holes == 0 &&
               s->num_notches == 0 && s->num_precracks == 0,
           "geometry defaults");
  T_ASSERT(s->model.kind == PDK_MODEL_PMB && s->model.bulk_modulus == 1e9 &&
               s->model.stabilization == PDK_STAB_NONE && s->model.critical_stretch == 0 &&
               s->model.influence == PDK_INFLUENCE_CONSTANT &&
               s->model.stencil == PDK_STENCIL_AUTO && s->model.layout == PDK_LAYOUT_CSR,
           "model defaults");
  T_ASSERT(s->steps == 3 && s->end_time == 0 && s->solver.dt == 0 && s->solver.safety == 0.8 &&
               !s->solver.force_dt && s->threads == 0 && s->num_bcs == 0 && s->num_sets == 0,
           "solver defaults");
  const pdk_scene_output *o = pdk_scene_output_get(s);
  T_ASSERT(o->field_interval == 0 && o->history_interval == 10 && o->checkpoint_interval == 0 &&
               o->num_fields == 2 && !strcmp(o->fields[0], "u") && !strcmp(o->fields[1], "v") &&
               o->num_reaction_sets == 0 && !o->units,
           "output defaults");
  pdk_sim *sim = NULL;
  int threads_before = pdk_ctx_num_threads(ctx);
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(pdk_ctx_num_threads(ctx) == threads_before, "threads: 0 leaves the context alone");
  T_ASSERT(pdk_particles_count(pdk_sim_particles(sim)) == 6 * 4 * 4, "3-D particle count %d",
           (int)pdk_particles_count(pdk_sim_particles(sim)));
  T_ASSERT(pdk_sim_num_steps(sim) == 3, "steps");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  T_ASSERT(s == NULL, "destroy clears the pointer");
}

static void check_overrides(pdk_ctx *ctx) {
  const char *path = scene_path("t060_minimal.yaml");
  const char *ov[] = {"geometry.spacing=2e-3",
                      "solver.threads=2",
                      "model.kind=lps",
                      "material.shear_modulus=0.5e9",
                      "geometry.box.hi=[0.008, 0.004, 0.004]",
                      "name=renamed",
                      "output.history_interval=2",
                      "sets=[{name: left, box: {lo: [-1, -1, -1], hi: [0.001, 1, 1]}}]",
                      "boundary_conditions=[{set: left, type: displacement, x: 0}]",
                      "boundary_conditions[0].y=0",
                      "boundary_conditions.0.x=1e-6"};
  const int nov = (int)(sizeof ov / sizeof ov[0]);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, nov, &s));
  T_ASSERT(s->lattice.spacing == 2e-3 && s->threads == 2 && s->model.kind == PDK_MODEL_LPS &&
               s->model.shear_modulus == 0.5e9 && s->lattice.hi[0] == 0.008 &&
               !strcmp(pdk_scene_name(s), "renamed") && s->output.history_interval == 2,
           "overrides applied");
  T_ASSERT(s->num_sets == 1 && s->num_bcs == 1 && s->bcs[0].components == 3 &&
               s->bcs[0].value[0].a == 1e-6 && s->bcs[0].value[1].a == 0,
           "list overrides and indexed overrides");
  T_ASSERT(s->output.num_reaction_sets == 1 && !strcmp(s->output.reaction_sets[0], "left"),
           "default reaction sets: sets with displacement or velocity conditions");
  char where[512];
  pdk_scene_key_location(s, "geometry.spacing", where, sizeof where);
  char want[2600];
  snprintf(want, sizeof want, "%s: --set geometry.spacing=2e-3", path);
  T_ASSERT(!strcmp(where, want), "override location '%s', expected '%s'", where, want);
  pdk_scene_key_location(s, "geometry.box.lo", where, sizeof where);
  snprintf(want, sizeof want, "%s:5", path);
  T_ASSERT(!strcmp(where, want), "file location '%s', expected '%s'", where, want);
  pdk_scene_key_location(s, "model.law", where, sizeof where);
  snprintf(want, sizeof want, "%s: --set model.kind=lps", path);
  T_ASSERT(!strcmp(where, want), "absent key under an override's mapping: '%s'", where);

  /* The final text names the overrides and loads to the same scene. */
  const char *text = pdk_scene_text(s);
  T_ASSERT(strstr(text, "--set geometry.spacing=2e-3") && strstr(text, "renamed"), "text: %s",
           text);
  FILE *f = fopen("t060_roundtrip.yaml", "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing t060_roundtrip.yaml");
  pdk_scene *r = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t060_roundtrip.yaml", NULL, 0, &r));
  T_ASSERT(r->lattice.spacing == s->lattice.spacing && r->threads == 2 &&
               r->model.kind == PDK_MODEL_LPS && r->num_bcs == 1 && r->bcs[0].value[0].a == 1e-6 &&
               !strcmp(pdk_scene_name(r), "renamed"),
           "reloaded text gives the same scene");
  pdk_scene_destroy(&r);
  remove("t060_roundtrip.yaml");

  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(pdk_ctx_num_threads(ctx) == 2, "threads from the override");
  T_ASSERT(pdk_particles_count(pdk_sim_particles(sim)) == 4 * 2 * 2,
           "count after spacing "
           "override: %d",
           (int)pdk_particles_count(pdk_sim_particles(sim)));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);

  /* The full scene with a few overrides on lists. */
  const char *ov2[] = {"boundary_conditions[1].y=3.5", "geometry.holes[0].disk.radius=0.003"};
  T_OK(ctx, pdk_scene_load(ctx, scene_path("t060_plate.yaml"), ov2, 2, &s));
  T_ASSERT(s->bcs[1].value[1].a == 3.5 && s->bcs[1].value[1].kind == PDK_TFUN_RAMP &&
               s->holes[0].region.radius == 0.003,
           "indexed overrides in the full scene");
  pdk_scene_destroy(&s);
}

int main(void) {
  const char *src = getenv("PDK_SOURCE_DIR");
  snprintf(scene_dir, sizeof scene_dir, "%s/tests/scenes", src ? src : "..");
  pdk_ctx *ctx = t_ctx(2);

  pdk_scene *s = NULL;
  const char *path = scene_path("t060_plate.yaml");
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
  check_full_mapping(s, path);
  check_full_sim(ctx, s);
  pdk_scene_destroy(&s);

  T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
  check_minimal(ctx);
  check_overrides(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
