/* Building a simulation from a loaded scene (include/pdk/scene.h).
 *
 * The order of construction, each step's failure blamed on the scene key that caused it:
 *   threads (solver.threads) -> lattice over geometry.box -> cut geometry.holes, geometry.notches
 *   -> define sets -> Morton reorder by the cells of the horizon -> families with
 *   geometry.precracks -> model -> solver: explicit (boundary_conditions, initial_conditions,
 *   solver) or static (solver.type adr | newton: boundary_conditions and the load steps of solver;
 *   pdk_sim_static_step solves one load step at a time) -> output fields ("u", and the model's
 *   derived fields such as "von_mises", when output.fields asks for them).
 *
 * Derived output fields, refreshed by pdk_sim_update_output_fields before each field output:
 *   "u"          f64 x dim  displacement x - X
 *   the model's derived fields (pdk_model_derived_at: its kind's, pdk_model_kind_info.derived in
 *   src/models/model_registry.h, and those of every model), f64 x 1, computed by the model
 *   (pdk_model_derived) from its state after the last force pass: the correspondence kinds derive
 *   "von_mises" (src/models/model_corr_derived.c), every model "bond_damage", and "damage" (the
 *   bond damage) when its law has no damage D of its own.
 *
 * The time step: the solver is created with force_dt set, and the scene's solver.dt is compared
 * here with the solver's stable estimate, so that a dt above it is refused with a message citing
 * solver.dt (the solver's own refusal cannot name the scene key).
 *
 * The simulation owns copies of everything its objects borrow (boundary-condition set names,
 * reaction set names), so it may outlive the scene.
 *
 * Restart (pdk_sim_restart): the checkpoint's time, step and time step are the run's. The scene
 * says where the run ends (solver.end_time, or solver.steps) and which step it asks for; when that
 * step is the one the checkpoint's run was created with (it stores it, "dt_created"), the run goes
 * on with the checkpoint's dt (which a dt_update may have lowered), exactly as if it had never
 * stopped. When the scene asks for another step (solver.dt, solver.safety or the material
 * changed), that step takes over at the checkpoint, like a dt_update change, and with
 * solver.end_time the run still ends at end_time; with solver.steps it is refused, since the same
 * step count at another step would end the run at another time.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/checkpoint_impl.h"
#include "core/state.h"         /* the restart sets dt where the checkpoint's run left off */
#include "models/model_registry.h"
#include "run_impl.h"
#include "space/points.h"
#include "scene_impl.h"
#include "pdk/comm.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/scene.h"
#include "pdk/static.h"

#define PDK_SIM_MAX_DERIVED 8

struct pdk_sim {
  pdk_ctx *ctx;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e; /* solver.type explicit */
  pdk_static *st;  /* solver.type adr or newton */
  pdk_solver_type type;
  long num_steps;  /* at the dt of creation */
  double end_time; /* solver.end_time, 0 with solver.steps */
  int has_u;
  /* the model's derived fields output.fields asks for (names from the registry) */
  const char *derived[PDK_SIM_MAX_DERIVED];
  int num_derived;
  pdk_bc *bcs;      /* [num_bcs], set names point into bc_fields */
  char **bc_fields; /* [num_bcs] "set:<name>" or NULL */
  int num_bcs;
  char **reaction_fields; /* [num_reactions] */
  int num_reactions;
};

/* model.galerkin.normals: box: the outward unit normal of the particles' bounding box at every
 * particle of the correction's surface set that lies on a face of it (within 1 % of the spacing);
 * on two or three faces (box edges and corners) the normalized sum of the faces' normals; 0 on
 * none (the correction's condition "s" there). */
static int box_normals(pdk_sim *sim, const pdk_scene *s) {
  pdk_particles *p = sim->p;
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  char set[PDK_FIELD_NAME_MAX];
  snprintf(set, sizeof set, "set:%s", s->model.galerkin.surface);
  const uint8_t *surf = pdk_particles_field_data(p, set, 0);
  if (!surf) return PDK_SUCCESS; /* the model names the missing set */
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int c = 0; c < dim; ++c) {
    const double *X = pdk_particles_X(p, c);
    lo[c] = hi[c] = n > 0 ? X[0] : 0.0;
    for (pdk_index k = 1; k < n; ++k) {
      lo[c] = fmin(lo[c], X[k]);
      hi[c] = fmax(hi[c], X[k]);
    }
  }
  const double tol = 0.01 * s->lattice.spacing;
  int err = pdk_particles_field_add(p, PDK_SCENE_NORMAL_FIELD, PDK_F64, dim);
  if (err) return err;
  double *nrm[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c)
    nrm[c] = pdk_particles_field_data(p, PDK_SCENE_NORMAL_FIELD, c);
  for (pdk_index k = 0; k < n; ++k) {
    double v[3] = {0, 0, 0}, len = 0.0;
    for (int c = 0; c < dim && surf[k]; ++c) {
      const double x = pdk_particles_X(p, c)[k];
      v[c] = (x - lo[c] <= tol ? -1.0 : 0.0) + (hi[c] - x <= tol ? 1.0 : 0.0);
      len += v[c] * v[c];
    }
    for (int c = 0; c < dim; ++c)
      nrm[c][k] = len > 0 ? v[c] / sqrt(len) : 0.0;
  }
  return PDK_SUCCESS;
}

static char *dup_or_null(const char *s, int *fail) {
  if (!s) return NULL;
  char *d = strdup(s);
  if (!d) *fail = 1;
  return d;
}

static void field_list(pdk_particles *p, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  for (int k = 0; k < pdk_particles_num_fields(p); ++k) {
    int w = snprintf(buf + pos, len - pos, "%s%s", k ? ", " : "", pdk_particles_field_name(p, k));
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
}

/* Holes, then notches. A hole that removes no particle is an error (it sits between lattice points
 * or misses the body: a mistake); a notch that removes none is allowed, so that a shape can be
 * carved by many notches of which some cut nothing (a polygon of half-spaces around a rod). */
static int cut_regions(pdk_sim *sim, const pdk_scene *s, const pdk_scene_region *r, int n,
                       int is_hole) {
  for (int k = 0; k < n; ++k) {
    pdk_index removed = 0;
    int err = pdk_particles_cut(sim->p, &r[k].region, &removed);
    if (err) return pdk_scene_blame(s, sim->ctx, err, r[k].key);
    if (removed == 0 && is_hole) {
      char what[256];
      pdk_region_describe(&r[k].region, s->dim, what, sizeof what);
      return pdk_scene_error(s, sim->ctx, PDK_ERR_ARG, r[k].key,
                             "%s removes no particle: it fits between lattice points; make it "
                             "larger than the spacing %g or remove it",
                             what, s->lattice.spacing);
    }
  }
  return PDK_SUCCESS;
}

static int pdk_bc_directional_scene(const pdk_bc *bc) {
  return bc->direction[0] != 0.0 || bc->direction[1] != 0.0 || bc->direction[2] != 0.0;
}

/* Two displacement or velocity conditions must not prescribe the same component of a particle.
 * The solver refuses that too, but checking here lets the message name the scene entries. */
static int check_bc_overlap(pdk_sim *sim, const pdk_scene *s) {
  const pdk_index n = pdk_particles_count(sim->p);
  for (int k = 0; k < s->num_bcs; ++k)
    for (int j = 0; j < k; ++j) {
      const pdk_bc *a = &s->bcs[j], *b = &s->bcs[k];
      if (a->kind == PDK_BC_BODY_FORCE || b->kind == PDK_BC_BODY_FORCE) continue;
      /* a condition along a direction holds every component of its particles */
      const int dir = pdk_bc_directional_scene(a) || pdk_bc_directional_scene(b);
      const unsigned all = (1u << s->dim) - 1;
      unsigned both = (pdk_bc_directional_scene(a) ? all : a->components) &
                      (pdk_bc_directional_scene(b) ? all : b->components);
      if (!both) continue;
      const uint8_t *ma = a->set ? pdk_particles_field_data(sim->p, a->set, 0) : NULL;
      const uint8_t *mb = b->set ? pdk_particles_field_data(sim->p, b->set, 0) : NULL;
      pdk_index count = 0, first = -1;
      for (pdk_index i = 0; i < n; ++i)
        if ((!ma || ma[i]) && (!mb || mb[i])) {
          if (first < 0) first = i;
          ++count;
        }
      if (!count) continue;
      char key[64];
      int c = 0;
      while (!(both & (1u << c)))
        ++c;
      snprintf(key, sizeof key, "boundary_conditions[%d]", k);
      if (dir)
        return pdk_scene_error(
            s, sim->ctx, PDK_ERR_ARG, key,
            "holds %d particles that boundary_conditions[%d] holds too (the first at X = [%g, "
            "%g%s]), and one of them acts along a direction; a particle under a condition along "
            "a direction takes no other displacement or velocity condition: make the sets "
            "disjoint",
            (int)count, j, pdk_particles_X(sim->p, 0)[first], pdk_particles_X(sim->p, 1)[first],
            s->dim == 3 ? ", ..." : "");
      return pdk_scene_error(
          s, sim->ctx, PDK_ERR_ARG, key,
          "prescribes %c on %d particles that boundary_conditions[%d] prescribes too (the first "
          "at X = [%g, %g%s]); give each component of a particle one condition: make the sets "
          "disjoint or drop the component from one of them",
          "xyz"[c], (int)count, j, pdk_particles_X(sim->p, 0)[first],
          pdk_particles_X(sim->p, 1)[first], s -> dim == 3 ? ", ..." : "");
    }
  return PDK_SUCCESS;
}

/* The explicit solver of the scene, and the number of steps. */
/* Steps of dt that cover a time span: ceil(span / dt), not counting a last step that round-off
 * alone would add; 0 for an empty span. */
static long steps_to_cover(double span, double dt) {
  const double q = span / dt;
  return q > 0 ? (long)ceil(q * (1 - 1e-12)) : 0;
}

static int create_explicit(pdk_sim *sim, const pdk_scene *s) {
  pdk_ctx *ctx = sim->ctx;
  int err = PDK_SUCCESS;
  pdk_explicit_opts eo = s->solver;
  eo.bcs = sim->bcs;
  eo.num_bcs = sim->num_bcs;
  eo.reaction_sets = (const char *const *)sim->reaction_fields;
  eo.num_reaction_sets = sim->num_reactions;
  eo.force_dt = 1; /* checked below, against the scene's force_dt, to cite solver.dt */
  err = pdk_explicit_create(sim->m, &eo, &sim->e);
  if (err) {
    const char *msg = pdk_ctx_error_message(ctx);
    err = pdk_scene_blame(s, ctx, err,
                          s->num_bcs && strstr(msg, "boundary condition") ? "boundary_conditions"
                                                                          : "solver");
    return err;
  }
  const double stable = pdk_explicit_stable_dt(sim->e);
  if (s->solver.dt > stable && !s->solver.force_dt) {
    err = pdk_scene_error(s, ctx, PDK_ERR_ARG, "solver.dt",
                          "%g exceeds the estimated stable time step %g (%.3g times it); use "
                          "dt <= %g, leave dt at 0 to step at solver.safety (%g) x the estimate, "
                          "or set solver.force_dt: true if you know better",
                          s->solver.dt, stable, s->solver.dt / stable, stable, s->solver.safety);
    return err;
  }
  const double dt = pdk_explicit_dt(sim->e);
  sim->end_time = s->steps > 0 ? 0.0 : s->end_time;
  if (s->steps > 0) {
    sim->num_steps = s->steps;
  } else {
    const double q = s->end_time / dt;
    PDK_CHECK(q < 1e15, ctx, PDK_ERR_ARG,
              "%s: solver.end_time %g needs %g steps of %g; shorten it or raise dt", s->path,
              s->end_time, q, dt);
    sim->num_steps = steps_to_cover(s->end_time, dt);
    if (sim->num_steps < 1) sim->num_steps = 1;
  }

  return PDK_SUCCESS;
}

/* The static solver of the scene (solver.type adr or newton); its load steps are the steps. */
static int create_static(pdk_sim *sim, const pdk_scene *s) {
  pdk_ctx *ctx = sim->ctx;
  pdk_static_opts so = s->static_opts;
  so.bcs = sim->bcs;
  so.num_bcs = sim->num_bcs;
  so.reaction_sets = (const char *const *)sim->reaction_fields;
  so.num_reaction_sets = sim->num_reactions;
  int err = pdk_static_create(sim->m, &so, &sim->st);
  if (err) {
    const char *msg = pdk_ctx_error_message(ctx);
    return pdk_scene_blame(s, ctx, err,
                           s->num_bcs && strstr(msg, "boundary condition") ? "boundary_conditions"
                                                                           : "solver");
  }
  sim->num_steps = pdk_static_num_levels(sim->st);
  return PDK_SUCCESS;
}

/* The particles of a point cloud: positions, volumes and its set columns as "set:<name>". */
static int body_from_points(pdk_ctx *ctx, const pdk_points *pts, int materials,
                            pdk_particles **out) {
  int err = PDK_SUCCESS;
  pdk_particles *p = NULL;
  PDK_CALL(pdk_particles_create(ctx, pts->dim, pts->n, &p));
  for (int a = 0; a < pts->dim; ++a)
    memcpy(pdk_particles_X(p, a), pts->X[a], (size_t)pts->n * sizeof(double));
  memcpy(pdk_particles_volume(p), pts->volume, (size_t)pts->n * sizeof(double));
  for (int k = 0; k < pts->num_sets; ++k) {
    char field[PDK_FIELD_NAME_MAX];
    snprintf(field, sizeof field, "set:%s", pts->set_name[k]);
    PDK_CALL_GOTO(pdk_particles_field_add(p, field, PDK_U8, 1));
    memcpy(pdk_particles_field_data(p, field, 0), pts->set[k], (size_t)pts->n);
  }
  if (materials) { /* the material column, resolved to material indices */
    PDK_CALL_GOTO(pdk_particles_field_add(p, "material", PDK_I32, 1));
    memcpy(pdk_particles_field_data(p, "material", 0), pts->material,
           (size_t)pts->n * sizeof(int32_t));
  }
  *out = p;
  return PDK_SUCCESS;
cleanup:
  pdk_particles_destroy(&p);
  return err;
}

int pdk_sim_create(pdk_ctx *ctx, const pdk_scene *s, pdk_sim **out) {
  int err = PDK_SUCCESS;
  pdk_sim *sim = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(out && s, ctx, PDK_ERR_ARG, "pdk_sim_create: scene or out is NULL");
  *out = NULL;
  sim = calloc(1, sizeof *sim);
  PDK_CHECK(sim, ctx, PDK_ERR_MEMORY, "out of memory creating a simulation");
  sim->ctx = ctx;
  /* several MPI ranks (docs/scaling.md): the explicit solver only, so far */
  PDK_CHECK_GOTO(pdk_comm_size() == 1 || s->solver_type == PDK_SOLVER_EXPLICIT, ctx,
                 PDK_ERR_UNSUPPORTED,
                 "solver.type %s runs on one rank only so far (on several ranks pdk runs solver.type "
                 "explicit); this run has %d ranks: run it without mpiexec (or with mpiexec -n 1)",
                 pdk_solver_type_name(s->solver_type), pdk_comm_size());

  if (s->threads > 0) {
    err = pdk_ctx_set_num_threads(ctx, s->threads);
    if (err) {
      err = pdk_scene_blame(s, ctx, err, "solver.threads");
      goto cleanup;
    }
  }

  /* Body: lattice (or point cloud), holes, notches, sets. */
  if (s->points)
    err = body_from_points(ctx, s->points, s->mat_from_points, &sim->p);
  else
    err = pdk_lattice_create(ctx, &s->lattice, &sim->p);
  if (err) {
    err = pdk_scene_blame(s, ctx, err, s->points ? s->points_key : "geometry");
    goto cleanup;
  }
  PDK_CALL_GOTO(cut_regions(sim, s, s->holes, s->num_holes, 1));
  PDK_CALL_GOTO(cut_regions(sim, s, s->notches, s->num_notches, 0));
  for (int k = 0; k < s->num_sets; ++k) {
    if (s->sets[k].from_points) continue; /* a column of the cloud: made with the body */
    err = pdk_particles_set_define(sim->p, s->sets[k].name, &s->sets[k].region, NULL);
    if (err) {
      err = pdk_scene_blame(s, ctx, err, s->sets[k].key);
      goto cleanup;
    }
  }

  /* Materials: "material" = 0 (`material`), then each entry of the materials list over its region
   * (a later entry wins where regions overlap); or the cloud's material column (made with the
   * body). */
  if (s->num_mat_regions > 0 && !s->mat_from_points) {
    PDK_CALL_GOTO(pdk_particles_field_add(sim->p, "material", PDK_I32, 1));
    int32_t *mat = pdk_particles_field_data(sim->p, "material", 0);
    const int dim = pdk_particles_dim(sim->p);
    const pdk_index n = pdk_particles_count(sim->p);
    for (int k = 0; k < s->num_mat_regions; ++k) {
      pdk_index count = 0;
      for (pdk_index i = 0; i < n; ++i) {
        double x[3] = {0, 0, 0};
        for (int a = 0; a < dim; ++a)
          x[a] = pdk_particles_X(sim->p, a)[i];
        if (pdk_region_contains(&s->mat_regions[k].region, dim, x)) mat[i] = k + 1, ++count;
      }
      if (!count) {
        err = pdk_scene_error(s, ctx, PDK_ERR_ARG, s->mat_regions[k].key,
                              "the region of material '%s' holds no particle of the body; move "
                              "or enlarge it, or remove the entry",
                              s->mat_regions[k].name);
        goto cleanup;
      }
    }
  }

  /* Order by the cells of the horizon (Morton), or by the lattice's rows where the model's
   * stencil path will walk the particles' own arrays in site order (the correspondence kind's:
   * 0.85 x the pass time on a 97 336-particle cube, bench/README.md "Particle order on the
   * correspondence stencil path"); then families. */
  double edge = pdk_families_cell_edge(sim->p, s->horizon);
  if (edge <= 0) {
    err = pdk_scene_blame(s, ctx, pdk_ctx_error_code(ctx) ? pdk_ctx_error_code(ctx) : PDK_ERR_ARG,
                          "geometry.horizon_factor");
    goto cleanup;
  }
  const int rows = pdk_model_opts_stencil_rows(&s->model) && s->lattice.type != PDK_LATTICE_HEX &&
                   s->lattice.jitter == 0.0 && !s->points;
  if (rows)
    PDK_CALL_GOTO(pdk_particles_reorder_rows(sim->p, s->lattice.spacing, NULL));
  else
    PDK_CALL_GOTO(pdk_particles_reorder_morton(sim->p, edge, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = s->horizon;
  fo.precracks = s->precracks;
  fo.num_precracks = s->num_precracks;
  err = pdk_families_build(sim->p, &fo, &sim->fam);
  if (err) {
    err = pdk_scene_blame(s, ctx, err, s->num_precracks ? "geometry.precracks" : "geometry");
    goto cleanup;
  }

  /* Model. */
  if (s->galerkin_normals_box && (err = box_normals(sim, s)) != PDK_SUCCESS) {
    err = pdk_scene_blame(s, ctx, err, "model.galerkin.normals");
    goto cleanup;
  }
  err = pdk_model_create(sim->p, sim->fam, &s->model, &sim->m);
  if (err) {
    const char *key = err == PDK_ERR_UNSUPPORTED && s->model.precision == PDK_PRECISION_FLOAT
                          ? "model.precision"
                          : "model";
    err = pdk_scene_blame(s, ctx, err, key);
    goto cleanup;
  }

  /* Solver, with copies of the names it borrows. */
  PDK_CALL_GOTO(check_bc_overlap(sim, s));
  int fail = 0;
  sim->num_bcs = s->num_bcs;
  sim->bcs = calloc((size_t)s->num_bcs + 1, sizeof *sim->bcs);
  sim->bc_fields = calloc((size_t)s->num_bcs + 1, sizeof *sim->bc_fields);
  sim->num_reactions = s->solver.num_reaction_sets;
  sim->reaction_fields = calloc((size_t)sim->num_reactions + 1, sizeof *sim->reaction_fields);
  PDK_CHECK_GOTO(sim->bcs && sim->bc_fields && sim->reaction_fields, ctx, PDK_ERR_MEMORY,
                 "out of memory creating a simulation");
  for (int k = 0; k < s->num_bcs; ++k) {
    sim->bcs[k] = s->bcs[k];
    sim->bc_fields[k] = dup_or_null(s->bc_fields[k], &fail);
    sim->bcs[k].set = sim->bc_fields[k];
  }
  for (int k = 0; k < sim->num_reactions; ++k)
    sim->reaction_fields[k] = dup_or_null(s->reaction_fields[k], &fail);
  PDK_CHECK_GOTO(!fail, ctx, PDK_ERR_MEMORY, "out of memory creating a simulation");
  sim->type = s->solver_type;
  if (s->solver_type != PDK_SOLVER_EXPLICIT)
    PDK_CALL_GOTO(create_static(sim, s));
  else
    PDK_CALL_GOTO(create_explicit(sim, s));

  /* Output fields. */
  for (int k = 0; k < s->output.num_fields; ++k) {
    if (!strcmp(s->output.fields[k], "u")) {
      PDK_CALL_GOTO(pdk_particles_field_add(sim->p, "u", PDK_F64, s->dim));
      sim->has_u = 1;
    }
    const char *name = s->output.fields[k];
    const pdk_model_derived_info *dv = pdk_model_derived_of(sim->m, name), *od = NULL;
    const pdk_model_kind_info *owner = pdk_model_derived_owner(name, &od);
    if (!dv && owner) {
      char key[64];
      snprintf(key, sizeof key, "output.fields[%d]", k);
      err = pdk_scene_error(s, ctx, PDK_ERR_ARG, key,
                            "%s is the %s of the %s model (model.kind is %s, which has no %s "
                            "tensor); remove it or set model.kind: %s",
                            name, od->what, owner->name, pdk_model_kind_name(s->model.kind),
                            od->what, owner->name);
      goto cleanup;
    }
    if (dv) {
      PDK_CALL_GOTO(pdk_particles_field_add(sim->p, dv->name, PDK_F64, 1));
      int listed = 0;
      for (int q = 0; q < sim->num_derived; ++q)
        listed = listed || !strcmp(sim->derived[q], dv->name);
      if (!listed && sim->num_derived < PDK_SIM_MAX_DERIVED)
        sim->derived[sim->num_derived++] = dv->name;
    }
  }
  for (int k = 0; k < s->output.num_fields; ++k) {
    if (pdk_particles_field_exists(sim->p, s->output.fields[k])) continue;
    char names[1024], key[64], derived[256] = "";
    field_list(sim->p, names, sizeof names);
    snprintf(key, sizeof key, "output.fields[%d]", k);
    const char *name = s->output.fields[k];
    /* a field of a law's history: which law declares it */
    const char *hint = "";
    for (int l = 0; pdk_law_at(l); ++l)
      for (const char *const *h = pdk_law_at(l)->history_fields; h && *h; ++h)
        if (!strcmp(*h, name) && !*hint) hint = pdk_law_at(l)->history_hint;
    /* the derived fields the kind offers and the scene did not ask for */
    const pdk_model_derived_info *d;
    for (int q = 0; (d = pdk_model_derived_at(sim->m, q)) != NULL; ++q)
      if (!pdk_particles_field_exists(sim->p, d->name)) {
        const size_t len = strlen(derived);
        snprintf(derived + len, sizeof derived - len, ", %s (%s)", d->name, d->what);
      }
    err = pdk_scene_error(s, ctx, PDK_ERR_NOT_FOUND, key,
                          "'%s' is not a field of this simulation%s; fields: %s%s%s", name, hint,
                          names, sim->has_u ? "" : ", u (displacement)", derived);
    goto cleanup;
  }
  PDK_CALL_GOTO(pdk_sim_update_output_fields(sim));
  *out = sim;
  return PDK_SUCCESS;
cleanup:
  pdk_sim_destroy(&sim);
  return err;
}

void pdk_sim_destroy(pdk_sim **simp) {
  if (!simp || !*simp) return;
  pdk_sim *sim = *simp;
  pdk_explicit_destroy(&sim->e);
  pdk_static_destroy(&sim->st);
  pdk_model_destroy(&sim->m);
  pdk_families_destroy(&sim->fam);
  pdk_particles_destroy(&sim->p);
  if (sim->bc_fields)
    for (int k = 0; k < sim->num_bcs; ++k)
      free(sim->bc_fields[k]);
  if (sim->reaction_fields)
    for (int k = 0; k < sim->num_reactions; ++k)
      free(sim->reaction_fields[k]);
  free(sim->bc_fields);
  free(sim->reaction_fields);
  free(sim->bcs);
  free(sim);
  *simp = NULL;
}

pdk_particles *pdk_sim_particles(pdk_sim *sim) { return sim ? sim->p : NULL; }
pdk_families *pdk_sim_families(pdk_sim *sim) { return sim ? sim->fam : NULL; }
pdk_model *pdk_sim_model(pdk_sim *sim) { return sim ? sim->m : NULL; }
pdk_explicit *pdk_sim_explicit(pdk_sim *sim) { return sim ? sim->e : NULL; }
/* The last step of the run when dt took its current value at (step0, time0). */
static long end_step(const pdk_sim *sim, long step0, double time0, double dt) {
  if (!sim->e || sim->end_time <= 0) return sim->num_steps;
  if (step0 == 0) return sim->num_steps; /* dt as at creation */
  /* dt changed at step0 (a dt_update, or a restart at another step): the rest of the run at it */
  return step0 + steps_to_cover(sim->end_time - time0, dt);
}

long pdk_sim_num_steps(const pdk_sim *sim) {
  long step0 = 0;
  double time0 = 0.0;
  if (!sim) return 0;
  if (sim->e) pdk_explicit_dt_start(sim->e, &step0, &time0);
  return end_step(sim, step0, time0, sim->e ? pdk_explicit_dt(sim->e) : 0.0);
}

/* pdk_sim_restart's decision, once the checkpoint is known to fit: the step and the end. */
typedef struct restart_decision {
  pdk_sim *sim;
  const pdk_scene *s;
  const char *path;
  pdk_checkpoint_solver cs;
  int changed;
} restart_decision;

static int decide_restart(void *arg, const pdk_checkpoint_solver *cs) {
  restart_decision *rd = arg;
  pdk_sim *sim = rd->sim;
  const pdk_scene *s = rd->s;
  pdk_ctx *ctx = sim->ctx;
  const double dt_scene = pdk_explicit_dt_created(sim->e); /* what the scene asks for */
  rd->cs = *cs;
  rd->changed = dt_scene != cs->dt_created;
  char how[160] = "";
  if (s->solver.dt == 0)
    snprintf(how, sizeof how, " (solver.dt 0: solver.safety %g x the stable estimate %g)",
             s->solver.safety, pdk_explicit_stable_dt(sim->e));
  if (rd->changed && sim->end_time <= 0)
    return pdk_scene_error(
        s, ctx, PDK_ERR_ARG, "solver.dt",
        "the scene steps at %.6g%s, the run of checkpoint '%s' at %.6g (it is at step %ld, t = "
        "%.6g); with solver.steps the step count is fixed, so another step would end the run at "
        "another time: give solver.end_time to say where the run ends, or restart with the "
        "checkpoint's step (solver.dt: %.17g)",
        dt_scene, how, rd->path, cs->dt_created, cs->step, cs->time, cs->dt_created);
  if (rd->changed && dt_scene > cs->dt_stable && !s->solver.force_dt)
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, "solver.dt",
                           "%.6g%s exceeds the stable step %.6g estimated at checkpoint '%s' "
                           "(step %ld, t = %.6g); use dt <= %.6g, or solver.force_dt: true if "
                           "you know better",
                           dt_scene, how, cs->dt_stable, rd->path, cs->step, cs->time,
                           cs->dt_stable);
  /* the end, from where dt takes its value */
  const long end = rd->changed ? end_step(sim, cs->step, cs->time, dt_scene)
                               : end_step(sim, cs->dt_step0, cs->dt_time0, cs->dt);
  /* (by the time too: with another step the count starts at the checkpoint; 1e-12 is the
   * round-off of a time summed over the steps, which may end a hair past end_time) */
  if ((end < cs->step || sim->end_time < cs->time * (1.0 - 1e-12)) && sim->end_time > 0)
    return pdk_scene_error(
        s, ctx, PDK_ERR_ARG, "solver.end_time",
        "%.6g ends before the time of checkpoint '%s' (step %ld, t = %.6g): a restart runs on "
        "from the checkpoint to the scene's end; give a later end_time, or restart from an "
        "earlier checkpoint",
        sim->end_time, rd->path, cs->step, cs->time);
  if (end < cs->step)
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, "solver.steps",
                           "%ld ends before the step of checkpoint '%s' (step %ld, t = %.6g): a "
                           "restart runs on from the checkpoint to the scene's end; give more "
                           "steps, or restart from an earlier checkpoint",
                           sim->num_steps, rd->path, cs->step, cs->time);
  return PDK_SUCCESS;
}

int pdk_sim_restart(pdk_sim *sim, const pdk_scene *s, const char *path,
                    pdk_sim_restart_info *info) {
  return pdk_sim_restart_text(sim, s, path, info, NULL);
}

int pdk_sim_restart_text(pdk_sim *sim, const pdk_scene *s, const char *path,
                         pdk_sim_restart_info *info, char **scene_text) {
  if (scene_text) *scene_text = NULL;
  if (!sim || !s || !info) return PDK_ERR_ARG;
  pdk_ctx *ctx = sim->ctx;
  pdk_explicit *e = sim->e;
  memset(info, 0, sizeof *info);
  PDK_CHECK(e, ctx, PDK_ERR_ARG,
            "a restart continues explicit runs only; this scene's solver is %s, which writes no "
            "checkpoints",
            pdk_solver_type_name(sim->type));
  PDK_CHECK(pdk_explicit_step(e) == 0, ctx, PDK_ERR_ARG,
            "pdk_sim_restart: the simulation has run %ld steps; restart a freshly built one",
            pdk_explicit_step(e));
  restart_decision rd;
  memset(&rd, 0, sizeof rd);
  rd.sim = sim;
  rd.s = s;
  rd.path = path;
  const double dt_scene = pdk_explicit_dt_created(e);
  PDK_CALL(pdk_checkpoint_restore(ctx, path, e, decide_restart, &rd, scene_text));
  if (rd.changed) /* the scene's step from the checkpoint on */
    pdk_explicit_restart_dt(e, dt_scene, rd.cs.step, rd.cs.time);
  info->step = pdk_explicit_step(e);
  info->time = pdk_explicit_time(e);
  info->end_step = pdk_sim_num_steps(sim);
  info->dt = pdk_explicit_dt(e);
  info->dt_changed = rd.changed;
  info->dt_before = rd.cs.dt;
  info->dt_created_before = rd.cs.dt_created;
  return PDK_SUCCESS;
}
pdk_solver_type pdk_sim_solver_type(const pdk_sim *sim) {
  return sim ? sim->type : PDK_SOLVER_EXPLICIT;
}
pdk_static *pdk_sim_static(pdk_sim *sim) { return sim ? sim->st : NULL; }

int pdk_sim_static_history(pdk_sim *sim, pdk_history *h) {
  PDK_CHECK_ARG(sim, NULL);
  PDK_CHECK_ARG(h, sim->ctx);
  PDK_CHECK(sim->st, sim->ctx, PDK_ERR_ARG,
            "pdk_sim_static_history: the scene's solver is explicit, not static");
  const pdk_static_event *ev = pdk_static_last_event(sim->st);
  memset(h, 0, sizeof *h);
  h->step = pdk_static_levels_solved(sim->st);
  h->time = ev->level >= 0 ? ev->time : 0.0;
  h->kinetic = 0.0;
  h->strain = ev->strain;
  h->external_work = ev->external_work;
  memcpy(h->reaction, ev->reaction, sizeof h->reaction);
  h->broken = pdk_model_num_broken(sim->m);
  h->failed = pdk_model_num_failed(sim->m);
  h->damage_max = pdk_model_damage_max(sim->m);
  return pdk_model_plastic_work(sim->m, &h->plastic_work, &h->damage_work, &h->breaking_work);
}

int pdk_sim_static_step(pdk_sim *sim, pdk_history *h) {
  PDK_CHECK_ARG(sim, NULL);
  PDK_CHECK(sim->st, sim->ctx, PDK_ERR_ARG,
            "pdk_sim_static_step: the scene's solver is explicit, not static");
  PDK_CALL(pdk_static_solve_level(sim->st));
  if (h) PDK_CALL(pdk_sim_static_history(sim, h));
  return PDK_SUCCESS;
}

int pdk_sim_update_output_fields(pdk_sim *sim) {
  PDK_CHECK_ARG(sim, NULL);
  if (sim->num_derived) {
    /* the step of the last pass: the explicit time step, or the static load step's pseudo-time */
    const double dt = sim->e ? pdk_explicit_dt(sim->e) : pdk_model_get_dt(sim->m);
    for (int k = 0; k < sim->num_derived; ++k)
      PDK_CALL(pdk_model_derived(sim->m, sim->derived[k], dt,
                                 pdk_particles_field_data(sim->p, sim->derived[k], 0)));
  }
  if (!sim->has_u) return PDK_SUCCESS;
  const int dim = pdk_particles_dim(sim->p);
  const pdk_index n = pdk_particles_count(sim->p);
  for (int c = 0; c < dim; ++c) {
    double *u = pdk_particles_field_data(sim->p, "u", c);
    const double *x = pdk_particles_field_data(sim->p, "x", c);
    const double *X = pdk_particles_X(sim->p, c);
    PDK_CHECK(u && x, sim->ctx, PDK_ERR_NOT_FOUND, "the fields u and x must exist to update u");
    for (pdk_index i = 0; i < n; ++i)
      u[i] = x[i] - X[i];
  }
  return PDK_SUCCESS;
}
