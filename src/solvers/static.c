/* Static solvers, the driver: options, conditions, load levels, and the level / commit loop that
 * calls ADR (adr.c) or Newton (newton.c) for each round. See include/pdk/static.h. What the two
 * methods share (the residual and its norms, coloring, difference perturbations) is in
 * static_common.c, below them.
 */
#include <math.h>
#include <string.h>

#include "bc.h"
#include "static_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/static.h"

pdk_static_opts pdk_static_opts_default(pdk_static_method method) {
  pdk_static_opts o;
  memset(&o, 0, sizeof o);
  o.method = method;
  o.num_levels = 1;
  o.rtol = method == PDK_STATIC_NEWTON ? 1e-10 : 1e-6;
  o.atol = 0.0;
  o.max_iterations = method == PDK_STATIC_NEWTON ? 50 : 200000;
  o.max_break_rounds = 1000;
  o.extrapolate = 1;
  o.adr_mass = PDK_ADR_MASS_AUTO;
  o.adr_safety = 1.0;
  o.tangent = PDK_TANGENT_AUTO;
  o.fd_scheme = PDK_FD_CENTRAL;
  o.fd_step = 0.0;
  o.linear_solver = PDK_LINEAR_AUTO;
  o.sym_rtol = 1e-6;
  o.singular_rtol = 1e-8;
  o.max_backtracks = 10;
  o.ls_decrease = 1e-4;
  o.reuse_tangent = 1;
  return o;
}

const char *pdk_static_method_name(pdk_static_method method) {
  switch (method) {
  case PDK_STATIC_ADR: return "adr";
  case PDK_STATIC_NEWTON: return "newton";
  }
  return "?";
}

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

static int check_opts(pdk_ctx *ctx, const pdk_static_opts *o) {
  PDK_CHECK((unsigned)o->method <= PDK_STATIC_NEWTON, ctx, PDK_ERR_ARG,
            "static solver method %d is not adr (0) or newton (1)", (int)o->method);
  const char *name = pdk_static_method_name(o->method);
  PDK_CHECK(o->num_bcs >= 0 && o->num_bcs <= PDK_STATIC_MAX_BCS, ctx, PDK_ERR_ARG,
            "%s: at most %d boundary conditions, got %d", name, PDK_STATIC_MAX_BCS, o->num_bcs);
  PDK_CHECK(o->num_bcs == 0 || o->bcs, ctx, PDK_ERR_ARG, "%s: %d conditions but bcs is NULL", name,
            o->num_bcs);
  PDK_CHECK(o->num_levels >= 1, ctx, PDK_ERR_ARG,
            "%s: the number of load levels must be >= 1, got %d", name, o->num_levels);
  PDK_CHECK(isfinite(o->rtol) && o->rtol >= 0 && isfinite(o->atol) && o->atol >= 0 &&
                o->rtol + o->atol > 0,
            ctx, PDK_ERR_ARG, "%s: tolerances must be >= 0 and not both 0, got rtol %g, atol %g",
            name, o->rtol, o->atol);
  PDK_CHECK(o->max_iterations > 0, ctx, PDK_ERR_ARG, "%s: max_iterations must be > 0, got %ld",
            name, o->max_iterations);
  PDK_CHECK(o->max_break_rounds >= 0, ctx, PDK_ERR_ARG, "%s: max_break_rounds must be >= 0, got %d",
            name, o->max_break_rounds);
  PDK_CHECK((unsigned)o->adr_mass <= PDK_ADR_MASS_LANCZOS, ctx, PDK_ERR_ARG,
            "%s: adr_mass %d is not auto (0), row_sum (1) or lanczos (2)", name, (int)o->adr_mass);
  PDK_CHECK(isfinite(o->adr_safety) && o->adr_safety > 0, ctx, PDK_ERR_ARG,
            "%s: adr_safety must be > 0, got %g", name, o->adr_safety);
  PDK_CHECK((unsigned)o->tangent <= PDK_TANGENT_DIFFERENCE, ctx, PDK_ERR_ARG,
            "%s: tangent %d is not auto (0), analytic (1) or difference (2)", name,
            (int)o->tangent);
  PDK_CHECK((unsigned)o->fd_scheme <= PDK_FD_FORWARD, ctx, PDK_ERR_ARG,
            "%s: fd_scheme %d is not central (0) or forward (1)", name, (int)o->fd_scheme);
  PDK_CHECK(isfinite(o->fd_step) && o->fd_step >= 0 && o->fd_step < 0.1, ctx, PDK_ERR_ARG,
            "%s: fd_step (relative to the horizon) must be in [0, 0.1), got %g", name, o->fd_step);
  PDK_CHECK((unsigned)o->linear_solver <= PDK_LINEAR_UMFPACK, ctx, PDK_ERR_ARG,
            "%s: linear_solver %d is not auto (0), cholmod (1) or umfpack (2)", name,
            (int)o->linear_solver);
  PDK_CHECK(isfinite(o->sym_rtol) && o->sym_rtol >= 0, ctx, PDK_ERR_ARG,
            "%s: sym_rtol must be >= 0, got %g", name, o->sym_rtol);
  PDK_CHECK(isfinite(o->singular_rtol) && o->singular_rtol >= 0 && o->singular_rtol < 1, ctx,
            PDK_ERR_ARG, "%s: singular_rtol must be in [0, 1), got %g", name, o->singular_rtol);
  PDK_CHECK(o->max_backtracks >= 0 && o->max_backtracks <= 60, ctx, PDK_ERR_ARG,
            "%s: max_backtracks must be in 0..60, got %d", name, o->max_backtracks);
  PDK_CHECK(isfinite(o->ls_decrease) && o->ls_decrease > 0 && o->ls_decrease < 1, ctx, PDK_ERR_ARG,
            "%s: ls_decrease (sufficient decrease of the line search) must be in (0, 1), got %g",
            name, o->ls_decrease);
  PDK_CHECK(isfinite(o->total_time) && o->total_time >= 0, ctx, PDK_ERR_ARG,
            "%s: total_time must be >= 0 (0: load factors without time), got %g", name,
            o->total_time);
  PDK_CHECK(o->num_reaction_sets >= 0 && o->num_reaction_sets <= PDK_STATIC_MAX_REACTION_SETS, ctx,
            PDK_ERR_ARG, "%s: at most %d reaction sets, got %d", name, PDK_STATIC_MAX_REACTION_SETS,
            o->num_reaction_sets);
  if (o->load_levels) {
    double prev = 0.0;
    for (int k = 0; k < o->num_levels; ++k) {
      PDK_CHECK(isfinite(o->load_levels[k]) && o->load_levels[k] > prev, ctx, PDK_ERR_ARG,
                "%s: load level %d is %g; levels must be finite, positive and increasing", name, k,
                o->load_levels[k]);
      prev = o->load_levels[k];
    }
  }
  return PDK_SUCCESS;
}

/* Component c of a condition's scale field (pdk_bc.scale_field), NULL when it has none. */
static const double *bc_scale(pdk_static *s, const pdk_bc *bc, int c) {
  return bc->scale_field ? pdk_particles_field_data(s->p, bc->scale_field, c) : NULL;
}

/* Reads the displacement conditions into fixed / owner and checks every condition. */
static int setup_conditions(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i)
      s->owner[c][i] = -1;
  for (int k = 0; k < s->opts.num_bcs; ++k) {
    const pdk_bc *bc = &s->bcs[k];
    PDK_CHECK(bc->kind == PDK_BC_DISPLACEMENT || bc->kind == PDK_BC_BODY_FORCE, ctx, PDK_ERR_ARG,
              "boundary condition %d is a %s condition; static solvers take displacement and "
              "body-force conditions only (prescribe the displacement instead: from rest, a "
              "velocity v is the displacement v t, time function linear, with a total_time)",
              k,
              bc->kind == PDK_BC_VELOCITY ? "velocity"
              : bc->kind == PDK_BC_WALL   ? "wall (contact is explicit-only)"
                                          : "unknown");
    const uint8_t *mem = NULL;
    PDK_CALL(pdk_bc_check(ctx, s->p, bc, k, &mem));
    if (bc->scale_field) {
      pdk_type type = PDK_U8;
      int ncomp = 0;
      PDK_CHECK(pdk_particles_field_exists(s->p, bc->scale_field) &&
                    pdk_particles_field_info(s->p, bc->scale_field, &type, &ncomp) ==
                        PDK_SUCCESS &&
                    type == PDK_F64 && ncomp == dim,
                ctx, PDK_ERR_NOT_FOUND,
                "boundary condition %d: scale field '%s' must be an existing f64 field with %d "
                "components",
                k, bc->scale_field, dim);
      for (int c = 0; c < dim; ++c) {
        const double *sc = bc_scale(s, bc, c);
        if (!(bc->components & (1u << c))) continue;
        for (pdk_index i = 0; i < n; ++i)
          PDK_CHECK((mem && !mem[i]) || isfinite(sc[i]), ctx, PDK_ERR_ARG,
                    "boundary condition %d: scale field '%s' is not finite at particle %d (id "
                    "%lld), component %d",
                    k, bc->scale_field, (int)i, (long long)pdk_particles_id(s->p)[i], c);
      }
    }
    if (pdk_bc_directional(bc)) {
      PDK_CHECK(!bc->scale_field, ctx, PDK_ERR_UNSUPPORTED,
                "boundary condition %d: a condition along a direction takes no scale_field", k);
      if (!s->dir_of) {
        s->dir_of = malloc((size_t)n * sizeof(int32_t) + 1);
        s->dir_frame = calloc((size_t)s->opts.num_bcs, sizeof *s->dir_frame);
        PDK_CHECK(s->dir_of && s->dir_frame, ctx, PDK_ERR_MEMORY,
                  "static solver: out of memory for %d particles", (int)n);
        for (pdk_index i = 0; i < n; ++i)
          s->dir_of[i] = -1;
      }
      pdk_bc_frame(bc, dim, s->dir_frame[k]);
      PDK_CALL(pdk_bc_claim_direction(ctx, s->p, k, mem, s->dir_of));
    } else if (bc->kind == PDK_BC_BODY_FORCE)
      s->has_body_force = 1;
    else
      PDK_CALL(pdk_bc_claim(ctx, s->p, bc, k, mem, s->owner, s->fixed, &s->num_fixed));
  }
  if (s->dir_of) { /* the normal component (0 in the particle's frame) is prescribed */
    PDK_CALL(pdk_bc_direction_overlap(ctx, s->p, s->dir_of, s->owner));
    for (pdk_index i = 0; i < n; ++i)
      if (s->dir_of[i] >= 0) {
        s->fixed[0][i] = 1;
        s->owner[0][i] = s->dir_of[i];
        s->num_fixed++;
      }
  }
  return PDK_SUCCESS;
}

/* Pseudo-time of level k (time mode) or its load factor (scale mode); 0 before the first. */
double pdk_static_level_time(const pdk_static *s, int k) {
  if (!s) return NAN;
  if (k < 0) return 0.0;
  return s->time_mode ? s->levels[k] * s->opts.total_time : s->levels[k];
}

/* The prescribed displacements and body forces of level k: time mode, the time functions at t_k;
 * scale mode, lambda_k times their values at t = 1. Sets s->load_measure. */
static void set_level_values(pdk_static *s, int k) {
  const int dim = s->dim;
  const pdk_index n = s->n;
  const double t = s->time_mode ? pdk_static_level_time(s, k) : 1.0;
  const double scale = s->time_mode ? 1.0 : s->levels[k];
  double value[PDK_STATIC_MAX_BCS][3];
  for (int b = 0; b < s->opts.num_bcs; ++b)
    for (int c = 0; c < dim; ++c)
      value[b][c] =
          (s->bcs[b].components & (1u << c)) ? scale * pdk_tfun_value(&s->bcs[b].value[c], t) : 0.0;
  double u2 = 0.0, b2 = 0.0;
  for (int c = 0; c < dim; ++c) {
    double *u = s->u_level[c], *bl = s->b_level[c];
    const int32_t *own = s->owner[c];
    for (pdk_index i = 0; i < n; ++i) {
      u[i] = 0.0;
      if (own[i] >= 0) {
        const double *sc = bc_scale(s, &s->bcs[own[i]], c);
        u[i] = sc ? value[own[i]][c] * sc[i] : value[own[i]][c];
      }
      u2 += u[i] * u[i];
      bl[i] = 0.0;
    }
    for (int b = 0; b < s->opts.num_bcs; ++b) {
      const pdk_bc *bc = &s->bcs[b];
      if (bc->kind != PDK_BC_BODY_FORCE || !(bc->components & (1u << c))) continue;
      const uint8_t *mem = bc->set ? pdk_particles_field_data(s->p, bc->set, 0) : NULL;
      const double *sc = bc_scale(s, bc, c);
      for (pdk_index i = 0; i < n; ++i)
        if (!mem || mem[i]) bl[i] += sc ? value[b][c] * sc[i] : value[b][c];
    }
    for (pdk_index i = 0; i < n; ++i)
      b2 += bl[i] * bl[i];
  }
  s->load_measure = u2 > 0.0 ? sqrt(u2) : sqrt(b2);
}

int pdk_static_create(pdk_model *m, const pdk_static_opts *opts_in, pdk_static **out) {
  PDK_CHECK_ARG(m, NULL);
  pdk_ctx *ctx = m->ctx;
  PDK_CHECK_ARG(out, ctx);
  int err = PDK_SUCCESS;
  pdk_static *s = NULL;
  *out = NULL;
  PDK_CHECK(opts_in, ctx, PDK_ERR_ARG,
            "static solver: options are NULL; start from "
            "pdk_static_opts_default(method)");
  PDK_CALL(check_opts(ctx, opts_in));
  s = calloc(1, sizeof *s);
  PDK_CHECK(s, ctx, PDK_ERR_MEMORY, "out of memory creating the static solver");
  s->ctx = ctx;
  s->m = m;
  s->p = m->p;
  s->fam = m->fam;
  s->opts = *opts_in;
  s->dim = pdk_particles_dim(s->p);
  s->n = pdk_particles_count(s->p);
  s->horizon = pdk_families_horizon(s->fam);
  s->hops = pdk_model_opts_hops(&m->opts);
  s->num_blocks = (s->n + PDK_STATIC_BLOCK - 1) / PDK_STATIC_BLOCK;
  s->stats.coupling_hops = s->hops;
  if (s->opts.num_bcs) {
    s->bcs = malloc((size_t)s->opts.num_bcs * sizeof *s->bcs);
    PDK_CHECK_GOTO(s->bcs, ctx, PDK_ERR_MEMORY, "out of memory copying boundary conditions");
    memcpy(s->bcs, opts_in->bcs, (size_t)s->opts.num_bcs * sizeof *s->bcs);
  }
  s->opts.bcs = s->bcs;
  s->num_levels = s->opts.num_levels;
  s->levels = malloc((size_t)s->num_levels * sizeof *s->levels);
  PDK_CHECK_GOTO(s->levels, ctx, PDK_ERR_MEMORY, "out of memory for load levels");
  for (int k = 0; k < s->num_levels; ++k)
    s->levels[k] = opts_in->load_levels ? opts_in->load_levels[k] : (double)(k + 1) / s->num_levels;
  s->opts.load_levels = s->levels;
  if (s->opts.fd_step == 0.0) s->opts.fd_step = s->opts.fd_scheme == PDK_FD_CENTRAL ? 1e-5 : 1e-7;
  s->time_mode = s->opts.total_time > 0.0;
  for (int c = 0; c < s->dim; ++c) {
    s->fixed[c] = calloc((size_t)s->n, 1);
    s->owner[c] = malloc((size_t)s->n * sizeof(int32_t));
    s->u_level[c] = calloc((size_t)s->n, sizeof(double));
    s->b_level[c] = calloc((size_t)s->n, sizeof(double));
    s->r[c] = calloc((size_t)s->n, sizeof(double));
    s->x_prev[c] = malloc((size_t)s->n * sizeof(double));
    s->fext_prev[c] = calloc((size_t)s->n, sizeof(double));
    PDK_CHECK_GOTO(s->fixed[c] && s->owner[c] && s->u_level[c] && s->b_level[c] && s->r[c] &&
                       s->x_prev[c] && s->fext_prev[c],
                   ctx, PDK_ERR_MEMORY, "static solver: out of memory for %d particles", (int)s->n);
    memcpy(s->x_prev[c], field(s->p, "x", c), (size_t)s->n * sizeof(double));
  }
  char rate_terms[160];
  if (!s->time_mode && pdk_model_opts_rate_terms(&m->opts, rate_terms, sizeof rate_terms)) {
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_ARG,
                   "%s: %s need strain rates, so the load steps need a pseudo-time: set "
                   "total_time > 0 (scene: solver.end_time) and give the conditions time "
                   "functions (e.g. a displacement with function linear)",
                   pdk_static_method_name(s->opts.method), rate_terms);
  }
  s->block_part = calloc((size_t)(s->num_blocks > 0 ? s->num_blocks : 1) * 2, sizeof(double));
  PDK_CHECK_GOTO(s->block_part, ctx, PDK_ERR_MEMORY, "static solver: out of memory");
  PDK_CALL_GOTO(setup_conditions(s));
  s->last.level = -1;
  s->last.broken = pdk_model_num_broken(m);
  for (int k = 0; k < s->opts.num_reaction_sets; ++k) {
    s->reaction_member[k] = pdk_particles_field_data(s->p, s->opts.reaction_sets[k], 0);
    PDK_CHECK_GOTO(s->reaction_member[k], ctx, PDK_ERR_NOT_FOUND,
                   "reaction set field '%s' does not exist", s->opts.reaction_sets[k]);
  }
  s->num_reaction = s->opts.num_reaction_sets;
  s->opts.reaction_sets = NULL; /* not kept: the caller's strings may go away */
  if (s->opts.method == PDK_STATIC_ADR)
    PDK_CALL_GOTO(pdk_adr_setup(s));
  else
    PDK_CALL_GOTO(pdk_newton_setup(s));
  *out = s;
  return PDK_SUCCESS;
cleanup:
  pdk_static_destroy(&s);
  return err;
}

void pdk_static_destroy(pdk_static **sp) {
  if (!sp || !*sp) return;
  pdk_static *s = *sp;
  pdk_adr_free(s);
  pdk_newton_free(s);
  for (int c = 0; c < 3; ++c) {
    free(s->fixed[c]);
    free(s->owner[c]);
    if (c == 0) {
      free(s->dir_of);
      free(s->dir_frame);
    }
    free(s->u_level[c]);
    free(s->b_level[c]);
    free(s->r[c]);
    free(s->x_prev[c]);
    free(s->fext_prev[c]);
  }
  free(s->bcs);
  free(s->levels);
  free(s->color_of);
  free(s->color_start);
  free(s->color_members);
  free(s->block_part);
  free(s);
  *sp = NULL;
}

const pdk_static_stats *pdk_static_stats_get(const pdk_static *s) { return s ? &s->stats : NULL; }

/* Reactions -sum_{i in set} V_i f_i from the current "f", in index order. */
static void reactions(pdk_static *s, double out[][3]) {
  const double *vol = pdk_particles_volume(s->p);
  for (int k = 0; k < s->num_reaction; ++k) {
    const uint8_t *mem = s->reaction_member[k];
    for (int c = 0; c < 3; ++c)
      out[k][c] = 0.0;
    for (int c = 0; c < s->dim; ++c) {
      const double *f = field(s->p, "f", c);
      double sum = 0.0;
      for (pdk_index i = 0; i < s->n; ++i)
        if (mem[i]) sum += vol[i] * f[i];
      out[k][c] = -sum;
    }
  }
}

static void emit(pdk_static *s, pdk_static_phase phase, long iterations, double strain,
                 pdk_bond_index broken_now) {
  if (!s->opts.monitor && phase != PDK_STATIC_COMMITTED) return;
  pdk_static_event ev;
  memset(&ev, 0, sizeof ev);
  ev.phase = phase;
  ev.level = s->level;
  ev.load_factor = s->lambda;
  ev.time = pdk_static_level_time(s, s->level);
  ev.round = s->round;
  ev.iterations = iterations;
  ev.residual = s->rnorm;
  ev.load_norm = s->fnorm;
  ev.tolerance = fmax(s->opts.rtol * s->fnorm + s->opts.atol, s->floor);
  ev.strain = strain;
  ev.broken = pdk_model_num_broken(s->m);
  ev.broken_now = broken_now;
  ev.external_work = s->stats.external_work;
  reactions(s, ev.reaction);
  if (phase == PDK_STATIC_COMMITTED) s->last = ev;
  if (s->opts.monitor) s->opts.monitor(s->opts.monitor_user, &ev);
}

/* The external force on particle i held along a direction n, component c: the body force on the
 * tangents plus the support along n, from the residual (r holds it in the particle's frame: the
 * support is V b.n - r.n) or, with commit, from the forces (-V f.n). */
static double dir_external(const pdk_static *s, pdk_index i, int c, const double *vol,
                           int commit) {
  const double(*R)[3] = pdk_static_frame(s, i);
  double bn = 0.0, fn = 0.0;
  for (int a = 0; a < s->dim; ++a) {
    bn += s->b_level[a][i] * R[a][0];
    fn += field(s->p, "f", a)[i] * R[a][0];
  }
  const double support = commit ? -vol[i] * fn : vol[i] * bn - s->r[0][i];
  return vol[i] * (s->b_level[c][i] - bn * R[c][0]) + support * R[c][0];
}

/* External work of the step from the last commit to this equilibrium (r: the trial residual at
 * it): trapezoid of the external force (supports and body forces: V b - r on prescribed
 * components, V b on free ones) times the displacement increment, summed in index order. */
static void work_to_equilibrium(pdk_static *s) {
  const double *vol = pdk_particles_volume(s->p);
  double w = 0.0;
  for (int c = 0; c < s->dim; ++c) {
    const double *x = field(s->p, "x", c);
    const double *b = s->b_level[c], *r = s->r[c], *xp = s->x_prev[c], *fp = s->fext_prev[c];
    const uint8_t *fixed = s->fixed[c];
    for (pdk_index i = 0; i < s->n; ++i) {
      const double fe = pdk_static_frame(s, i) ? dir_external(s, i, c, vol, 0)
                                               : vol[i] * b[i] - (fixed[i] ? r[i] : 0.0);
      w += 0.5 * (fp[i] + fe) * (x[i] - xp[i]);
    }
  }
  s->stats.external_work += w;
}

/* After a commit: the external force there (the commit's forces on prescribed components: bonds
 * that broke changed them) and the positions, the start of the next step's trapezoid. */
static void work_commit_state(pdk_static *s) {
  const double *vol = pdk_particles_volume(s->p);
  for (int c = 0; c < s->dim; ++c) {
    const double *x = field(s->p, "x", c), *f = field(s->p, "f", c), *b = s->b_level[c];
    const uint8_t *fixed = s->fixed[c];
    double *fp = s->fext_prev[c];
    for (pdk_index i = 0; i < s->n; ++i)
      fp[i] = pdk_static_frame(s, i) ? dir_external(s, i, c, vol, 1)
              : fixed[i]             ? -vol[i] * f[i]
                                     : vol[i] * b[i];
    memcpy(s->x_prev[c], x, (size_t)s->n * sizeof(double));
  }
}

/* Scales the displacement of the free components by `factor` (extrapolation between levels). */
static void scale_free(pdk_static *s, double factor) {
  for (int c = 0; c < s->dim; ++c) {
    double *x = field(s->p, "x", c);
    const double *X = pdk_particles_X(s->p, c);
    const uint8_t *fixed = s->fixed[c];
    for (pdk_index i = 0; i < s->n; ++i) /* along a direction: the normal is set again after */
      if (!fixed[i] || pdk_static_frame(s, i)) x[i] = X[i] + factor * (x[i] - X[i]);
  }
}

int pdk_static_num_levels(const pdk_static *s) { return s ? s->num_levels : 0; }
double pdk_static_total_time(const pdk_static *s) { return s ? s->opts.total_time : NAN; }
int pdk_static_levels_solved(const pdk_static *s) { return s ? s->stats.levels_done : 0; }
const pdk_static_event *pdk_static_last_event(const pdk_static *s) { return s ? &s->last : NULL; }

int pdk_static_solve_level(pdk_static *s) {
  PDK_CHECK_ARG(s, NULL);
  pdk_ctx *ctx = s->ctx;
  const int k = s->stats.levels_done;
  PDK_CHECK(k < s->num_levels, ctx, PDK_ERR_ARG, "%s: all %d load levels are solved already",
            pdk_static_method_name(s->opts.method), s->num_levels);
  const double t0 = pdk_wtime();
  int err = PDK_SUCCESS;
  const double lambda = s->levels[k];
  const double previous_measure = s->load_measure;
  set_level_values(s, k);
  if (s->opts.extrapolate && s->lambda > 0.0 && previous_measure > 0.0)
    scale_free(s, s->load_measure / previous_measure);
  s->lambda = lambda;
  s->level = k;
  /* The model's time step: the pseudo-time increment of this level (time mode), or none (scale
   * mode: quasi-static limit, no rate terms; refused at creation when the law has them). */
  if (s->time_mode)
    PDK_CALL_GOTO(
        pdk_model_set_dt(s->m, pdk_static_level_time(s, k) - pdk_static_level_time(s, k - 1)));
  else
    s->m->dt = 0.0;
  pdk_static_apply_prescribed(s);
  for (int round = 0;; ++round) {
    s->round = round;
    long iterations = 0;
    if (s->opts.method == PDK_STATIC_ADR)
      PDK_CALL_GOTO(pdk_adr_relax(s, &iterations));
    else
      PDK_CALL_GOTO(pdk_newton_solve_level(s, &iterations));
    s->stats.iterations += iterations;
    work_to_equilibrium(s);
    emit(s, PDK_STATIC_CONVERGED, iterations, 0.0, 0);
    /* History advances here, and only here: one committing pass at the equilibrium. */
    const pdk_bond_index before = pdk_model_num_broken(s->m);
    double strain = 0.0;
    PDK_CALL_GOTO(pdk_model_force(s->m, &strain));
    s->stats.commit_passes++;
    work_commit_state(s);
    const pdk_bond_index broken_now = pdk_model_num_broken(s->m) - before;
    emit(s, PDK_STATIC_COMMITTED, iterations, strain, broken_now);
    if (broken_now == 0) break;
    PDK_CHECK_GOTO(round < s->opts.max_break_rounds, ctx, PDK_ERR_NUMERIC,
                   "%s: load level %d (load factor %g) still breaks bonds after %d re-solves "
                   "(%lld broken in the last); the body is probably failing at this load: "
                   "stop at a lower level or raise max_break_rounds",
                   pdk_static_method_name(s->opts.method), k, lambda, round, (long long)broken_now);
    s->stats.break_rounds++;
  }
  s->stats.levels_done++;
  s->stats.residual = s->rnorm;
  s->stats.load_norm = s->fnorm;
  s->stats.residual_floor = s->floor;
cleanup:
  s->stats.time_total += pdk_wtime() - t0;
  return err;
}

int pdk_static_solve(pdk_static *s) {
  PDK_CHECK_ARG(s, NULL);
  while (s->stats.levels_done < s->num_levels)
    PDK_CALL(pdk_static_solve_level(s));
  return PDK_SUCCESS;
}

void pdk_static_stats_print(const pdk_static_stats *st, FILE *out) {
  if (!st || !out) return;
  const double mib = 1.0 / (1024.0 * 1024.0);
  fprintf(out, "levels %d, iterations %ld, force passes %ld (+%ld commits), re-solves %d\n",
          st->levels_done, st->iterations, st->force_passes, st->commit_passes, st->break_rounds);
  fprintf(out, "residual %.3e of load %.3e\n", st->residual, st->load_norm);
  if (st->storage_floor_levels)
    fprintf(out,
            "%d level(s) stopped at the float-storage round-off of the residual (%.2e of the "
            "load; precision double goes below it)\n",
            st->storage_floor_levels, st->load_norm > 0 ? st->residual / st->load_norm : 0.0);
  if (st->num_colors)
    fprintf(out, "coloring: %d colors (coupling %d hops), %ld passes per difference tangent\n",
            st->num_colors, st->coupling_hops, st->passes_per_tangent);
  if (st->analytic_tangent)
    fprintf(out, "analytic tangent (coupling %d hops): no force passes\n", st->coupling_hops);
  if (st->mass_max > 0)
    fprintf(out, "ADR mass (%s): %.3e .. %.3e\n",
            st->adr_mass == PDK_ADR_MASS_ROW_SUM ? "row sums" : "Lanczos", st->mass_min,
            st->mass_max);
  if (st->num_unknowns) {
    fprintf(out, "tangent: %ld unknowns, %lld nonzeros (%.1f per row), %.1f MiB; asymmetry %.2e\n",
            st->num_unknowns, (long long)st->tangent_nnz, st->tangent_nnz_per_row,
            (double)st->tangent_bytes * mib, st->asymmetry);
    fprintf(out,
            "factor: %lld nonzeros, %.1f MiB; cholmod %d, umfpack %d; min pivot %.2e, min eig %.2e "
            "(of max diag)\n",
            (long long)st->factor_nnz, (double)st->factor_bytes * mib, st->cholmod_factorizations,
            st->umfpack_factorizations, st->min_pivot_ratio, st->min_eig_ratio);
  }
  fprintf(out,
          "time [s]: setup %.3f, mass %.3f, assembly %.3f (%d, %d reuses), analysis %.3f (%d), "
          "factorization %.3f (%d), solve %.3f (%d), total %.3f\n",
          st->time_setup, st->time_mass, st->time_assembly, st->assemblies, st->tangent_reuses,
          st->time_analysis, st->analyses, st->time_factorization, st->factorizations,
          st->time_solve, st->solves, st->time_total);
}
