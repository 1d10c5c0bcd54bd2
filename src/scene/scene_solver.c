/* Scene loading, step 3 (src/scene/scene.c): boundary conditions and the solver (explicit: time steps;
 * adr and newton: load steps and levels), resolved into pdk_explicit_opts and pdk_static_opts
 * (src/scene/scene_load.h).
 */
#include "models/model_registry.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/scene.h"
#include "pdk/static.h"

/* type: wall: a plane through point (moving at velocity) with the normal out of the wall; the
 * name labels its history columns. No components, no time function. */
static int resolve_wall(loader *ld, const sc_bc *b, const char *base, pdk_bc *bc) {
  pdk_scene *s = ld->s;
  const int dim = s->dim;
  static const char *const comp_keys[] = {"x", "y", "z", "function", "duration", "period"};
  for (int j = 0; j < 6; ++j)
    REQUIRE(ld, !has(ld, K(ld, "%s.%s", base, comp_keys[j])), K(ld, "%s.%s", base, comp_keys[j]),
            "a wall has no components or time function; it is given by point, normal and "
            "(optionally) velocity; remove %s",
            comp_keys[j]);
  REQUIRE(ld, has(ld, K(ld, "%s.point", base)), base,
          "a wall needs point: a point of its plane at time 0, e.g. [0, 0%s]",
          dim == 3 ? ", 0" : "");
  REQUIRE(ld, has(ld, K(ld, "%s.normal", base)), base,
          "a wall needs normal: the direction out of the wall, towards the body");
  double n2 = 0;
  for (int a = 0; a < dim; ++a) {
    REQUIRE(ld, isfinite(b->point[a]), K(ld, "%s.point", base),
            "entry %d is %g; coordinates must be finite numbers", a, b->point[a]);
    REQUIRE(ld, isfinite(b->normal[a]), K(ld, "%s.normal", base),
            "entry %d is %g; components must be finite numbers", a, b->normal[a]);
    REQUIRE(ld, isfinite(b->velocity[a]), K(ld, "%s.velocity", base),
            "entry %d is %g; components must be finite numbers", a, b->velocity[a]);
    n2 += b->normal[a] * b->normal[a];
  }
  REQUIRE(ld, n2 > 0, K(ld, "%s.normal", base),
          "must not be zero; it points out of the wall, towards the body");
  const int w = s->output.num_walls;
  REQUIRE(ld, w < PDK_MAX_WALLS, base, "at most %d walls; list fewer", PDK_MAX_WALLS);
  char name[SC_NAME_MAX + 8];
  if (b->name) {
    REQUIRE(ld, valid_name(b->name), K(ld, "%s.name", base),
            "'%s' is not a valid wall name; use 1 to %d letters, digits, '_', '-' or '.'", b->name,
            SC_NAME_MAX);
    snprintf(name, sizeof name, "%s", b->name);
  } else {
    snprintf(name, sizeof name, "wall%d", w);
  }
  for (int j = 0; j < w; ++j)
    REQUIRE(ld, strcmp(s->wall_names[j], name), b->name ? K(ld, "%s.name", base) : base,
            "two walls are named '%s'; give each its own name", name);
  s->wall_names[w] = strdup(name);
  if (!s->wall_names[w])
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for walls");
  s->output.num_walls = w + 1;
  s->output.walls = (const char *const *)s->wall_names;
  for (int a = 0; a < dim; ++a) {
    bc->point[a] = b->point[a];
    bc->normal[a] = b->normal[a];
    bc->velocity[a] = b->velocity[a];
  }
  bc->name = NULL; /* the scene keeps the names (output.walls); the solver needs none */
  return PDK_SUCCESS;
}

int pdk_scene_resolve_bcs(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const int nb = (int)d->boundary_conditions_count;
  s->bcs = calloc((size_t)nb + 1, sizeof *s->bcs);
  s->bc_fields = calloc((size_t)nb + 1, sizeof *s->bc_fields);
  if (!s->bcs || !s->bc_fields)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory for boundary conditions");
  s->num_bcs = nb;
  s->wall_names = calloc((size_t)PDK_MAX_WALLS + 1, sizeof *s->wall_names);
  if (!s->wall_names)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for walls");
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
    if (bc->kind == PDK_BC_WALL) {
      PDK_CALL(resolve_wall(ld, b, base, bc));
      continue;
    }
    static const char *const wall_keys[] = {"point", "normal", "velocity", "name"};
    for (int j = 0; j < 4; ++j)
      REQUIRE(ld, !has(ld, K(ld, "%s.%s", base, wall_keys[j])), K(ld, "%s.%s", base, wall_keys[j]),
              "only a wall (type: wall) has a %s; remove it", wall_keys[j]);
    const double comp[3] = {b->x, b->y, b->z};
    const pdk_tfun_kind fk =
        has(ld, K(ld, "%s.function", base)) ? (pdk_tfun_kind)b->function : PDK_TFUN_CONSTANT;
    const int hdur = has(ld, K(ld, "%s.duration", base)), hper = has(ld, K(ld, "%s.period", base));
    const int needs_dur = fk == PDK_TFUN_RAMP || fk == PDK_TFUN_SMOOTH;
    const char *fname = pdk_scene_function_names[fk].str;
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
    const int hdir = has(ld, K(ld, "%s.direction", base));
    if (hdir) { /* along a direction: value on the unit direction, the tangents free */
      for (int c = 0; c < 3; ++c)
        REQUIRE(ld, !has(ld, K(ld, "%s.%c", base, "xyz"[c])), K(ld, "%s.%c", base, "xyz"[c]),
                "a condition along a direction gives its value as value, the component along "
                "the direction; remove %c (a particle takes either a direction or components)",
                "xyz"[c]);
      snprintf(sub, sizeof sub, "%s.direction", base);
      REQUIRE(ld, bc->kind != PDK_BC_BODY_FORCE, sub,
              "a body force acts along x, y%s: give its components; direction is for "
              "displacement and velocity conditions",
              s->dim == 3 ? ", z" : "");
      double d2 = 0.0;
      for (int a = 0; a < s->dim; ++a) {
        REQUIRE(ld, isfinite(b->direction[a]), sub, "entry %d is %g; give finite numbers", a,
                b->direction[a]);
        d2 += b->direction[a] * b->direction[a];
      }
      REQUIRE(ld, d2 > 0 && isfinite(d2), sub,
              "must not be zero; it is the direction (need not be unit) along which the "
              "condition prescribes the %s",
              bc->kind == PDK_BC_DISPLACEMENT ? "displacement" : "velocity");
      snprintf(sub, sizeof sub, "%s.value", base);
      REQUIRE(ld, has(ld, sub), sub,
              "is missing; a condition along a direction needs value, the %s along it",
              bc->kind == PDK_BC_DISPLACEMENT ? "displacement" : "velocity");
      for (int a = 0; a < s->dim; ++a)
        bc->direction[a] = b->direction[a];
    } else {
      snprintf(sub, sizeof sub, "%s.value", base);
      REQUIRE(ld, !has(ld, sub), sub,
              "only a condition along a direction takes value; give direction, or the "
              "components x, y%s",
              s->dim == 3 ? ", z" : "");
    }
    for (int c = 0; c < 3; ++c) {
      snprintf(sub, sizeof sub, "%s.%c", base, "xyz"[c]);
      if (hdir && c == 0) snprintf(sub, sizeof sub, "%s.value", base);
      else if (!has(ld, sub) || hdir) continue;
      REQUIRE(ld, c < s->dim, sub, "z is not a component in a 2-D scene; use x and y");
      const double cv = hdir ? b->value : comp[c];
      REQUIRE(ld, isfinite(cv), sub, "must be a finite number, got %g", cv);
      bc->components |= 1u << c;
      pdk_tfun *tf = &bc->value[c];
      tf->kind = fk;
      switch (fk) {
      case PDK_TFUN_CONSTANT: tf->a = cv; break;
      case PDK_TFUN_LINEAR:
        tf->a = 0;
        tf->b = cv;
        break;
      case PDK_TFUN_RAMP:
      case PDK_TFUN_SMOOTH:
        tf->a = cv;
        tf->b = b->duration;
        break;
      case PDK_TFUN_SINE:
        tf->a = cv;
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
    REQUIRE(ld, s->bcs[k].kind != PDK_BC_WALL, K(ld, "boundary_conditions[%d].type", k),
            "a wall is a contact of the explicit solver; the static solvers (solver.type %s) do not "
            "take it yet: use solver.type explicit, or a displacement condition on the contact set",
            tname);
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

int pdk_scene_resolve_solver(loader *ld, const sc_scene *d) {
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
    REQUIRE(ld, e->dt_update == PDK_DT_UPDATE_BREAKS || e->dt_update == PDK_DT_UPDATE_PERIODIC,
            "solver.dt_update_interval",
            "is given but solver.dt_update is %s, which %s; set dt_update (breaks or periodic) "
            "or remove the interval",
            e->dt_update == PDK_DT_UPDATE_NONE ? "none" : "auto",
            e->dt_update == PDK_DT_UPDATE_NONE ? "re-estimates nothing"
                                               : "re-estimates when bonds shorten, not by steps");
    PDK_CALL(check_whole(ld, "solver.dt_update_interval", so->dt_update_interval, 1, 1e15,
                         &e->dt_update_interval));
  }
  return PDK_SUCCESS;
}
