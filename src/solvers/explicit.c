/* Explicit dynamics: velocity Verlet with boundary conditions, a Lanczos estimate of the stable
 * time step, energies and reactions; see include/pdk/explicit.h.
 *
 * Per-particle arrays: "x", "v", "f" (dim components each, n_pad entries). Constraint masks:
 * fixed_mask[i] bit c set when component c of particle i is prescribed (displacement or
 * velocity); the prescribing condition is bc_of[c][i] (index into bcs, -1 none).
 * Reductions (energies, reactions) go through per-block partial sums in block order, so the
 * result does not depend on the thread count.
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "bc.h"
#include "explicit_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

pdk_tfun pdk_tfun_constant(double a) {
  pdk_tfun f = {PDK_TFUN_CONSTANT, a, 0.0};
  return f;
}

double pdk_tfun_value(const pdk_tfun *f, double t) {
  if (!f) return NAN;
  switch (f->kind) {
  case PDK_TFUN_CONSTANT: return f->a;
  case PDK_TFUN_LINEAR: return f->a + f->b * t;
  case PDK_TFUN_RAMP: return f->a * (t < f->b ? t / f->b : 1.0);
  case PDK_TFUN_SMOOTH: {
    double r = t < f->b ? t / f->b : 1.0;
    return f->a * r * r * r * (10.0 - 15.0 * r + 6.0 * r * r);
  }
  case PDK_TFUN_SINE: return f->a * sin(2.0 * M_PI * t / f->b);
  }
  return 0.0;
}

double pdk_tfun_rate(const pdk_tfun *f, double t) {
  if (!f) return NAN;
  switch (f->kind) {
  case PDK_TFUN_CONSTANT: return 0.0;
  case PDK_TFUN_LINEAR: return f->b;
  case PDK_TFUN_RAMP: return t < f->b ? f->a / f->b : 0.0;
  case PDK_TFUN_SMOOTH: {
    if (t >= f->b) return 0.0;
    double r = t / f->b;
    return f->a / f->b * 30.0 * r * r * (1.0 - r) * (1.0 - r);
  }
  case PDK_TFUN_SINE: return f->a * 2.0 * M_PI / f->b * cos(2.0 * M_PI * t / f->b);
  }
  return 0.0;
}

pdk_explicit_opts pdk_explicit_opts_default(void) {
  pdk_explicit_opts o;
  memset(&o, 0, sizeof o);
  o.safety = 0.8;
  return o;
}

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

double pdk_tfun_integral(const pdk_tfun *f, double t0, double t1) {
  if (!f) return NAN;
  const double a = f->a, b = f->b;
  switch (f->kind) {
  case PDK_TFUN_CONSTANT: return a * (t1 - t0);
  case PDK_TFUN_LINEAR: return a * (t1 - t0) + 0.5 * b * (t1 * t1 - t0 * t0);
  case PDK_TFUN_RAMP: { /* G(t) = a t^2 / (2b) for t < b, a (t - b/2) after */
    double g1 = t1 < b ? a * t1 * t1 / (2.0 * b) : a * (t1 - 0.5 * b);
    double g0 = t0 < b ? a * t0 * t0 / (2.0 * b) : a * (t0 - 0.5 * b);
    return g1 - g0;
  }
  case PDK_TFUN_SMOOTH: { /* G(t) = a b (5/2 r^4 - 3 r^5 + r^6), r = t/b, for t < b */
    double r1 = t1 < b ? t1 / b : 1.0, r0 = t0 < b ? t0 / b : 1.0;
    double g1 = a * b * r1 * r1 * r1 * r1 * (2.5 - 3.0 * r1 + r1 * r1) + (t1 > b ? a * (t1 - b) : 0.0);
    double g0 = a * b * r0 * r0 * r0 * r0 * (2.5 - 3.0 * r0 + r0 * r0) + (t0 > b ? a * (t0 - b) : 0.0);
    return g1 - g0;
  }
  case PDK_TFUN_SINE: return -a * b / (2.0 * M_PI) * (cos(2.0 * M_PI * t1 / b) - cos(2.0 * M_PI * t0 / b));
  }
  return 0.0;
}

static void apply_direction_bcs(pdk_explicit *e, double t, int drifted);

/* Sets prescribed positions and velocities of constrained components at time t. With drifted = 1
 * (right after the drift x += dt v(t - dt)), a velocity-prescribed position is corrected to the
 * exact integral of the prescribed velocity over the step. */
static void apply_kinematic_bcs(pdk_explicit *e, double t, int drifted) {
  const int dim = e->dim;
  const pdk_index n = e->n;
  for (int c = 0; c < dim; ++c) {
    const int32_t *bc_of = e->bc_of[c];
    double *x = field(e->p, "x", c), *v = field(e->p, "v", c);
    const double *X = pdk_particles_X(e->p, c);
    const pdk_bc *bcs = e->bcs;
    int nthreads = e->ctx->num_threads;
    const double dt = e->dt;
#pragma omp parallel for default(none) shared(bc_of, x, v, X, bcs, n, c, t, dt, drifted) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      int k = bc_of[i];
      if (k < 0) continue;
      const pdk_bc *bc = &bcs[k];
      if (bc->kind == PDK_BC_DISPLACEMENT) {
        x[i] = X[i] + pdk_tfun_value(&bc->value[c], t);
        v[i] = pdk_tfun_rate(&bc->value[c], t);
      } else {
        /* the drift moved x by dt v(t - dt); v still holds v(t - dt) (kicks skip it) */
        if (drifted) x[i] += pdk_tfun_integral(&bc->value[c], t - dt, t) - dt * v[i];
        v[i] = pdk_tfun_value(&bc->value[c], t);
      }
    }
  }
  if (e->num_dir) apply_direction_bcs(e, t, drifted);
}

/* The prescribed normal velocity of directional condition bc at t (its value's rate for a
 * displacement). */
static double dir_rate(const pdk_bc *bc, double t) {
  return bc->kind == PDK_BC_DISPLACEMENT ? pdk_tfun_rate(&bc->value[0], t)
                                         : pdk_tfun_value(&bc->value[0], t);
}

/* Conditions along a direction n at time t: the component of x - X (displacement) along n set to
 * its value, that of v to its rate; with drifted, a velocity condition's position corrected to the
 * exact integral over the step, as apply_kinematic_bcs does per component. */
static void apply_direction_bcs(pdk_explicit *e, double t, int drifted) {
  const int dim = e->dim;
  double *x[3] = {NULL, NULL, NULL}, *v[3] = {NULL, NULL, NULL};
  const double *X[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    x[c] = field(e->p, "x", c);
    v[c] = field(e->p, "v", c);
    X[c] = pdk_particles_X(e->p, c);
  }
  for (pdk_index q = 0; q < e->num_dir; ++q) {
    const pdk_index i = e->dir_list[q];
    const pdk_bc *bc = &e->bcs[e->dir_bc[q]];
    const double(*R)[3] = e->dir_frame[e->dir_bc[q]];
    double un = 0.0, vn = 0.0;
    for (int c = 0; c < dim; ++c) {
      un += (x[c][i] - X[c][i]) * R[c][0];
      vn += v[c][i] * R[c][0];
    }
    double dx = 0.0;
    if (bc->kind == PDK_BC_DISPLACEMENT)
      dx = pdk_tfun_value(&bc->value[0], t) - un;
    else if (drifted)
      dx = pdk_tfun_integral(&bc->value[0], t - e->dt, t) - e->dt * vn;
    const double dv = dir_rate(bc, t) - vn;
    for (int c = 0; c < dim; ++c) {
      x[c][i] += dx * R[c][0];
      v[c][i] += dv * R[c][0];
    }
  }
}

/* Body force density at time t on particle i, component c. */
static double body_force(const pdk_explicit *e, const uint8_t *const *member, pdk_index i, int c, double t) {
  double b = 0.0;
  for (int k = 0; k < e->opts.num_bcs; ++k) {
    const pdk_bc *bc = &e->bcs[k];
    if (bc->kind != PDK_BC_BODY_FORCE || !(bc->components & (1u << c))) continue;
    if (member[k] && !member[k][i]) continue;
    b += pdk_tfun_value(&bc->value[c], t);
  }
  return b;
}

static int num_body_forces(const pdk_explicit *e) {
  int nb = 0;
  for (int k = 0; k < e->opts.num_bcs; ++k) nb += e->bcs[k].kind == PDK_BC_BODY_FORCE;
  return nb;
}

/* v += dt/2 (f + b) / rho on free components. */
static void half_kick(pdk_explicit *e, double t) {
  const int dim = e->dim;
  const pdk_index n = e->n;
  const double h = 0.5 * e->dt / e->rho;
  const double half_dt = 0.5 * e->dt;
  const double *rho_p = e->m->mat_density; /* multi-material: per-particle density */
  const int nb = num_body_forces(e);
  const uint8_t *member[64] = {0};
  for (int k = 0; k < e->opts.num_bcs && k < 64; ++k)
    member[k] = e->bcs[k].set ? pdk_particles_field_data(e->p, e->bcs[k].set, 0) : NULL;
  for (int c = 0; c < dim; ++c) {
    double *v = field(e->p, "v", c);
    const double *f = field(e->p, "f", c);
    const int32_t *bc_of = e->bc_of[c];
    int nthreads = e->ctx->num_threads;
    const pdk_explicit *ec = e;
#pragma omp parallel for default(none) shared(v, f, bc_of, n, h, half_dt, rho_p, nb, ec, member, c, t) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      if (bc_of[i] >= 0) continue;
      double b = nb ? body_force(ec, member, i, c, t) : 0.0;
      v[i] += (rho_p ? half_dt / rho_p[i] : h) * (f[i] + b);
    }
  }
  /* along a direction n: the kick moves the free (tangential) components only */
  for (pdk_index q = 0; q < e->num_dir; ++q) {
    const pdk_index i = e->dir_list[q];
    const double(*R)[3] = e->dir_frame[e->dir_bc[q]];
    double vn = 0.0;
    for (int c = 0; c < dim; ++c)
      vn += field(e->p, "v", c)[i] * R[c][0];
    const double dv = dir_rate(&e->bcs[e->dir_bc[q]], t) - vn;
    for (int c = 0; c < dim; ++c)
      field(e->p, "v", c)[i] += dv * R[c][0];
  }
}

static void drift(pdk_explicit *e) {
  const pdk_index n = e->n;
  const double dt = e->dt;
  for (int c = 0; c < e->dim; ++c) {
    double *x = field(e->p, "x", c);
    const double *v = field(e->p, "v", c);
    int nthreads = e->ctx->num_threads;
#pragma omp parallel for default(none) shared(x, v, n, dt) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) x[i] += dt * v[i];
  }
}

/* Checks x and v for non-finite values; names the first bad particle (lowest index). */
static int check_state(pdk_explicit *e) {
  const pdk_index n = e->n;
  pdk_index bad = n;
  int bad_c = 0;
  for (int c = 0; c < e->dim; ++c) {
    const double *x = field(e->p, "x", c), *v = field(e->p, "v", c), *f = field(e->p, "f", c);
    pdk_index first = n;
    int nthreads = e->ctx->num_threads;
#pragma omp parallel for default(none) shared(x, v, f, n) reduction(min : first) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i)
      if (!isfinite(x[i]) || !isfinite(v[i]) || !isfinite(f[i])) first = i < first ? i : first;
    if (first < bad) {
      bad = first;
      bad_c = c;
    }
  }
  if (bad == n) {
    PDK_CHECK(isfinite(e->strain), e->ctx, PDK_ERR_NUMERIC,
              "the strain energy became non-finite (%g) at step %ld (time %g); the time step %g may "
              "exceed the stable limit %g, or a particle's deformation left the law's domain",
              e->strain, e->step, e->time, e->dt, e->dt_stable);
    return PDK_SUCCESS;
  }
  const int64_t *id = pdk_particles_id(e->p);
  return pdk_ctx_error_set(e->ctx, PDK_ERR_NUMERIC, __func__,
                           "the state became non-finite at step %ld (time %g): particle %d (id %lld) "
                           "has x[%d] = %g, v[%d] = %g, f[%d] = %g; the time step %g may exceed the "
                           "stable limit %g, or a load or material parameter is too large",
                           e->step, e->time, (int)bad, (long long)id[bad], bad_c,
                           field(e->p, "x", bad_c)[bad], bad_c, field(e->p, "v", bad_c)[bad], bad_c,
                           field(e->p, "f", bad_c)[bad], e->dt, e->dt_stable);
}

static double kinetic_energy(pdk_explicit *e);

/* Blow-up: an elastic or dissipative body never holds more energy than it started with plus the
 * work done on it. Kinetic + strain energy above 100 times that budget (and above a round-off
 * floor) means the integration is unstable; the run stops naming the fastest particle. */
static int check_blowup(pdk_explicit *e) {
  double energy = kinetic_energy(e) + e->strain;
  double budget = e->energy0 + fabs(e->external_work);
  if (!(energy > 100.0 * budget && energy > e->energy_floor)) return PDK_SUCCESS;
  pdk_index fastest = 0;
  double vmax = -1.0;
  for (pdk_index i = 0; i < e->n; ++i) {
    double s = 0.0;
    for (int c = 0; c < e->dim; ++c) s += field(e->p, "v", c)[i] * field(e->p, "v", c)[i];
    if (s > vmax) {
      vmax = s;
      fastest = i;
    }
  }
  return pdk_ctx_error_set(e->ctx, PDK_ERR_NUMERIC, __func__,
                           "the run is blowing up at step %ld (time %g): kinetic + strain energy %g "
                           "is %.3g times the initial energy plus the work done (%g); fastest "
                           "particle %d (id %lld), |v| = %g; the time step %g may exceed the stable "
                           "limit %g (estimated at the start; stiffening under large deformation "
                           "lowers it): reduce solver.safety or solver.dt",
                           e->step, e->time, energy, budget > 0 ? energy / budget : INFINITY,
                           budget, (int)fastest, (long long)pdk_particles_id(e->p)[fastest],
                           sqrt(vmax), e->dt, e->dt_stable);
}

/* Energy-account runaway. The energy created since the baseline (the first step of this solver
 * or of its restore) is C = (kinetic + strain + dissipated) - (baseline + external work done
 * since). A run the step resolves keeps |C| to a few percent of the energy in play (velocity Verlet
 * conserves a shadow energy: measured up to 24% swings at 0.99 of the stable step, tests/t145);
 * a step too large for the current state creates energy without bound. The run stops when C
 * exceeds RUNAWAY_FRAC of the scale max(baseline + |work|, current total) and grew at each of the
 * last RUNAWAY_CHECKS checks (one every 8 steps), or at once when C exceeds the energy put in
 * (baseline + |work|: the body holds more than twice what it was given).
 * Losses (C < 0: bonds whose energy a model does not book, a remap) never trip it. Reads only;
 * costs a kinetic-energy and a dissipation sum every 8 steps. */
#define RUNAWAY_FRAC 0.3
#define RUNAWAY_CHECKS 4
static int acct_energy(pdk_explicit *e, double *total) {
  double pl = 0.0, dm = 0.0, br = 0.0;
  PDK_CALL(pdk_model_plastic_work(e->m, &pl, &dm, &br));
  *total = kinetic_energy(e) + e->strain + pl + dm + br + pdk_model_rebuild_work(e->m);
  return PDK_SUCCESS;
}

static double accel2(pdk_explicit *e, pdk_index i) {
  double s = 0.0;
  for (int c = 0; c < e->dim; ++c) {
    const double f = field(e->p, "f", c)[i];
    s += f * f;
  }
  const double rho = e->m->mat_density ? e->m->mat_density[i] : e->rho;
  return s / (rho * rho);
}

static int check_runaway(pdk_explicit *e) {
  if (!e->acct_set) return PDK_SUCCESS;
  double total;
  PDK_CALL(acct_energy(e, &total));
  const double work = e->external_work - e->acct_w0;
  const double created = total - e->acct_e0 - work;
  const double put_in = e->acct_e0 + fabs(work);
  const double scale = total > put_in ? total : put_in;
  if (!(created > e->energy_floor && created > RUNAWAY_FRAC * scale)) {
    e->acct_streak = 0;
    free(e->acct_a2);
    e->acct_a2 = NULL;
    e->acct_prev = created;
    return PDK_SUCCESS;
  }
  if (created > e->acct_prev) e->acct_streak++;
  else e->acct_streak = 0;
  e->acct_prev = created;
  if (e->acct_streak == 1 && !e->acct_a2) { /* the accelerations the growth is measured from */
    e->acct_a2 = malloc((size_t)(e->n ? e->n : 1) * sizeof *e->acct_a2);
    if (e->acct_a2)
      for (pdk_index i = 0; i < e->n; ++i) e->acct_a2[i] = accel2(e, i);
    e->acct_a2_step = e->step;
  }
  const int doubled = created > put_in;
  if (e->acct_streak < RUNAWAY_CHECKS && !doubled) return PDK_SUCCESS;
  /* the particle whose acceleration grew most since the streak began (or, when the energy
   * doubled before a streak could start, the largest acceleration) */
  const int since = e->acct_a2 && e->acct_a2_step < e->step;
  pdk_index worst = 0;
  double grow = -INFINITY, a_was = 0.0, a_now = 0.0;
  for (pdk_index i = 0; i < e->n; ++i) {
    const double a = sqrt(accel2(e, i)), a0 = since ? sqrt(e->acct_a2[i]) : 0.0;
    if (a - a0 > grow) {
      grow = a - a0;
      worst = i;
      a_was = a0;
      a_now = a;
    }
  }
  double xw[3] = {0.0, 0.0, 0.0}, vw = 0.0;
  for (int c = 0; c < e->dim; ++c) {
    xw[c] = field(e->p, "x", c)[worst];
    vw += field(e->p, "v", c)[worst] * field(e->p, "v", c)[worst];
  }
  char why[160], where[160];
  if (doubled)
    snprintf(why, sizeof why, "more than the energy at step %ld plus the work done since (%g): "
             "the body holds over twice what it was given", e->acct_step0, put_in);
  else
    snprintf(why, sizeof why, "%.3g%% of the energy in play (%g), and growing at each of the "
             "last %d checks (8 steps apart)", 100.0 * created / scale, scale, e->acct_streak);
  if (since)
    snprintf(where, sizeof where, "the acceleration grew most (from %g to %g m/s^2 since step %ld)",
             a_was, a_now, e->acct_a2_step);
  else
    snprintf(where, sizeof where, "the acceleration is largest (%g m/s^2)", a_now);
  return pdk_ctx_error_set(
      e->ctx, PDK_ERR_NUMERIC, __func__,
      "the energy account runs away at step %ld (time %g): the integration created %g J since "
      "step %ld (kinetic + strain + dissipated energy %g), %s; %s at particle %d (id %lld) at "
      "(%g, %g, %g), |v| = %g m/s; the time step %g does not resolve this state (stable limit "
      "%g, estimated at step %ld): lower solver.safety (now %g) or set a smaller solver.dt, or "
      "let solver.dt_update: periodic follow the stable step",
      e->step, e->time, created, e->acct_step0, total, why, where, (int)worst,
      (long long)pdk_particles_id(e->p)[worst], xw[0], xw[1], xw[2], sqrt(vw), e->dt,
      e->dt_stable, e->est_step, e->opts.safety);
}

/* Sum over particles of g(i) through fixed blocks: the same bits for any thread count. */
static double kinetic_energy(pdk_explicit *e) {
  const pdk_index n = e->n;
  const int dim = e->dim;
  const double *vol = pdk_particles_volume(e->p);
  const double *v0 = field(e->p, "v", 0), *v1 = field(e->p, "v", 1);
  const double *v2 = dim == 3 ? field(e->p, "v", 2) : NULL;
  pdk_index nblk = (n + PDK_RED_BLOCK - 1) / PDK_RED_BLOCK;
  double *part = malloc((size_t)nblk * sizeof *part);
  if (!part) return NAN;
  int nthreads = e->ctx->num_threads;
  const double *rho_p = e->m->mat_density; /* multi-material: per-particle density */
#pragma omp parallel for default(none) shared(part, nblk, n, vol, v0, v1, v2, dim, rho_p) schedule(static) num_threads(nthreads)
  for (pdk_index b = 0; b < nblk; ++b) {
    pdk_index lo = b * PDK_RED_BLOCK, hi = lo + PDK_RED_BLOCK < n ? lo + PDK_RED_BLOCK : n;
    double s = 0.0;
    for (pdk_index i = lo; i < hi; ++i) {
      double w2 = v0[i] * v0[i] + v1[i] * v1[i] + (dim == 3 ? v2[i] * v2[i] : 0.0);
      s += (rho_p ? rho_p[i] * vol[i] : vol[i]) * w2;
    }
    part[b] = s;
  }
  double total = 0.0;
  for (pdk_index b = 0; b < nblk; ++b) total += part[b];
  free(part);
  return 0.5 * (rho_p ? 1.0 : e->rho) * total;
}

/* Reaction on a set: R = -sum_{i in set} V_i f_i, in index order (serial: sets are small). */
static void reactions(pdk_explicit *e, double out[][3]) {
  const double *vol = pdk_particles_volume(e->p);
  for (int k = 0; k < e->num_reaction; ++k) {
    const uint8_t *mem = e->reaction_member[k];
    for (int c = 0; c < 3; ++c) out[k][c] = 0.0;
    for (int c = 0; c < e->dim; ++c) {
      const double *f = field(e->p, "f", c);
      double s = 0.0;
      for (pdk_index i = 0; i < e->n; ++i)
        if (mem[i]) s += vol[i] * f[i];
      out[k][c] = -s;
    }
  }
}

/* Kinetic energy of the prescribed components: the constraints supply its changes. */
static double constrained_kinetic(pdk_explicit *e) {
  const double *vol = pdk_particles_volume(e->p);
  const double *rho_p = e->m->mat_density;
  double s = 0.0;
  for (int c = 0; c < e->dim; ++c) {
    const double *v = field(e->p, "v", c);
    const int32_t *bc_of = e->bc_of[c];
    for (pdk_index i = 0; i < e->n; ++i)
      if (bc_of[i] >= 0) s += (rho_p ? rho_p[i] * vol[i] : vol[i]) * v[i] * v[i];
  }
  for (pdk_index q = 0; q < e->num_dir; ++q) { /* the normal component */
    const pdk_index i = e->dir_list[q];
    const double(*R)[3] = e->dir_frame[e->dir_bc[q]];
    double vn = 0.0;
    for (int c = 0; c < e->dim; ++c)
      vn += field(e->p, "v", c)[i] * R[c][0];
    s += (rho_p ? rho_p[i] * vol[i] : vol[i]) * vn * vn;
  }
  return 0.5 * (rho_p ? 1.0 : e->rho) * s;
}

/* Power of the constraints and body forces on the body at the current state:
 * P = sum over constrained components of (-V_i f_i) v_i + sum over free components of V_i b_i v_i. */
static double external_power(pdk_explicit *e, double t) {
  const double *vol = pdk_particles_volume(e->p);
  const int nb = num_body_forces(e);
  const uint8_t *member[64] = {0};
  for (int k = 0; k < e->opts.num_bcs && k < 64; ++k)
    member[k] = e->bcs[k].set ? pdk_particles_field_data(e->p, e->bcs[k].set, 0) : NULL;
  double power = 0.0;
  for (int c = 0; c < e->dim; ++c) {
    const double *f = field(e->p, "f", c), *v = field(e->p, "v", c);
    const int32_t *bc_of = e->bc_of[c];
    for (pdk_index i = 0; i < e->n; ++i) {
      if (bc_of[i] >= 0) power += -vol[i] * f[i] * v[i];
      else if (nb) power += vol[i] * body_force(e, member, i, c, t) * v[i];
    }
  }
  /* along a direction: the support force -V (f.n) n on the normal velocity; the body force's
   * normal part does no work there (the support takes it) */
  for (pdk_index q = 0; q < e->num_dir; ++q) {
    const pdk_index i = e->dir_list[q];
    const double(*R)[3] = e->dir_frame[e->dir_bc[q]];
    double fn = 0.0, vn = 0.0, bn = 0.0;
    for (int c = 0; c < e->dim; ++c) {
      fn += field(e->p, "f", c)[i] * R[c][0];
      vn += field(e->p, "v", c)[i] * R[c][0];
      if (nb) bn += body_force(e, member, i, c, t) * R[c][0];
    }
    power += -vol[i] * fn * vn - vol[i] * bn * vn;
  }
  return power;
}

int pdk_explicit_create(pdk_model *m, const pdk_explicit_opts *opts_in, pdk_explicit **out) {
  PDK_CHECK_ARG(m, NULL);
  pdk_ctx *ctx = m->ctx;
  PDK_CHECK_ARG(out, ctx);
  int err = PDK_SUCCESS;
  pdk_explicit_opts opts = opts_in ? *opts_in : pdk_explicit_opts_default();
  pdk_explicit *e = NULL;
  *out = NULL;
  PDK_CHECK(isfinite(opts.dt) && opts.dt >= 0, ctx, PDK_ERR_ARG,
            "time step must be >= 0 (0 picks the estimate), got %g", opts.dt);
  PDK_CHECK(isfinite(opts.safety) && opts.safety > 0 && opts.safety <= 1, ctx, PDK_ERR_ARG,
            "time-step safety factor must be in (0, 1], got %g", opts.safety);
  PDK_CHECK((unsigned)opts.dt_update <= PDK_DT_UPDATE_AUTO, ctx, PDK_ERR_ARG,
            "dt_update %d is not none (0), breaks (1), periodic (2) or auto (3)",
            (int)opts.dt_update);
  PDK_CHECK(opts.dt_update_interval >= 0, ctx, PDK_ERR_ARG,
            "dt_update_interval must be >= 0 steps (0: 100), got %ld", opts.dt_update_interval);
  if (opts.dt_update_interval == 0) opts.dt_update_interval = 100;
  PDK_CHECK(opts.num_bcs >= 0 && opts.num_bcs <= 64, ctx, PDK_ERR_ARG,
            "at most 64 boundary conditions, got %d", opts.num_bcs);
  PDK_CHECK(opts.num_reaction_sets >= 0 && opts.num_reaction_sets <= PDK_MAX_REACTION_SETS, ctx,
            PDK_ERR_ARG, "at most %d reaction sets, got %d", PDK_MAX_REACTION_SETS, opts.num_reaction_sets);
  e = calloc(1, sizeof *e);
  PDK_CHECK(e, ctx, PDK_ERR_MEMORY, "out of memory creating the explicit solver");
  e->ctx = ctx;
  e->m = m;
  e->p = m->p;
  e->opts = opts;
  e->dim = pdk_particles_dim(e->p);
  e->n = pdk_particles_count(e->p);
  e->rho = m->opts.density;
  if (opts.num_bcs) {
    e->bcs = malloc((size_t)opts.num_bcs * sizeof *e->bcs);
    PDK_CHECK_GOTO(e->bcs, ctx, PDK_ERR_MEMORY, "out of memory copying boundary conditions");
    memcpy(e->bcs, opts.bcs, (size_t)opts.num_bcs * sizeof *e->bcs);
  }
  e->opts.bcs = e->bcs;
  PDK_CALL_GOTO(pdk_particles_field_add(e->p, "v", PDK_F64, e->dim));
  for (int c = 0; c < e->dim; ++c) {
    e->bc_of[c] = malloc((size_t)e->n * sizeof(int32_t));
    PDK_CHECK_GOTO(e->bc_of[c], ctx, PDK_ERR_MEMORY, "out of memory for constraint maps");
    for (pdk_index i = 0; i < e->n; ++i) e->bc_of[c][i] = -1;
  }
  for (int k = 0; k < opts.num_bcs; ++k) {
    const pdk_bc *bc = &e->bcs[k];
    PDK_CHECK_GOTO((unsigned)bc->kind <= PDK_BC_WALL, ctx, PDK_ERR_ARG,
                   "boundary condition %d: unknown kind %d", k, (int)bc->kind);
    if (bc->kind == PDK_BC_WALL) continue; /* pdk_walls_init */
    PDK_CHECK_GOTO(!bc->scale_field, ctx, PDK_ERR_UNSUPPORTED,
                   "boundary condition %d: scale_field ('%s') is supported by the static solvers "
                   "only; the explicit solver takes uniform values per set",
                   k, bc->scale_field);
    const uint8_t *mem = NULL;
    PDK_CALL_GOTO(pdk_bc_check(ctx, e->p, bc, k, &mem));
    if (pdk_bc_directional(bc)) {
      if (!e->dir_frame) {
        e->dir_frame = calloc((size_t)opts.num_bcs, sizeof *e->dir_frame);
        e->dir_bc = malloc((size_t)e->n * sizeof(int32_t) + 1);
        PDK_CHECK_GOTO(e->dir_frame && e->dir_bc, ctx, PDK_ERR_MEMORY,
                       "out of memory for constraint maps");
        for (pdk_index i = 0; i < e->n; ++i)
          e->dir_bc[i] = -1;
      }
      pdk_bc_frame(bc, e->dim, e->dir_frame[k]);
      PDK_CALL_GOTO(pdk_bc_claim_direction(ctx, e->p, k, mem, e->dir_bc));
    } else if (bc->kind != PDK_BC_BODY_FORCE)
      PDK_CALL_GOTO(pdk_bc_claim(ctx, e->p, bc, k, mem, e->bc_of, NULL, NULL));
  }
  if (e->dir_bc) { /* dir_bc per particle -> the list of held particles and their conditions */
    PDK_CALL_GOTO(pdk_bc_direction_overlap(ctx, e->p, e->dir_bc, e->bc_of));
    e->dir_list = malloc((size_t)e->n * sizeof *e->dir_list + 1);
    PDK_CHECK_GOTO(e->dir_list, ctx, PDK_ERR_MEMORY, "out of memory for constraint maps");
    for (pdk_index i = 0; i < e->n; ++i)
      if (e->dir_bc[i] >= 0) {
        e->dir_bc[e->num_dir] = e->dir_bc[i]; /* num_dir <= i: overwrites entries read already */
        e->dir_list[e->num_dir++] = i;
      }
  }
  for (int k = 0; k < opts.num_reaction_sets; ++k) {
    e->reaction_member[k] = pdk_particles_field_data(e->p, opts.reaction_sets[k], 0);
    PDK_CHECK_GOTO(e->reaction_member[k], ctx, PDK_ERR_NOT_FOUND,
                   "reaction set field '%s' does not exist", opts.reaction_sets[k]);
  }
  e->num_reaction = opts.num_reaction_sets;
  PDK_CALL_GOTO(pdk_walls_init(e));
  /* Initial velocity: affine field. */
  for (int c = 0; c < e->dim; ++c) {
    double *v = field(e->p, "v", c);
    for (pdk_index i = 0; i < e->n; ++i) {
      double s = opts.v0_const[c];
      for (int d = 0; d < e->dim; ++d) s += opts.v0_grad[c][d] * pdk_particles_X(e->p, d)[i];
      v[i] = s;
    }
  }
  PDK_CALL_GOTO(pdk_explicit_estimate_dt(e, 0));
  e->num_estimates = 1;
  e->auto_ratio = pdk_explicit_min_bond_ratio(e, &e->auto_ximin);
  e->est_broken = pdk_model_num_broken(m);
  if (opts.dt == 0) e->dt = opts.safety * e->dt_stable;
  else {
    PDK_CHECK_GOTO(opts.dt <= e->dt_stable || opts.force_dt, ctx, PDK_ERR_ARG,
                   "time step %g exceeds the estimated stable limit %g (%.2f times it); use dt <= %g, "
                   "leave dt at 0 to pick %g x the limit, or force it if you know better",
                   opts.dt, e->dt_stable, opts.dt / e->dt_stable, e->dt_stable, opts.safety);
    e->dt = opts.dt;
  }
  e->dt_created = e->dt;
  PDK_CALL_GOTO(pdk_model_set_dt(m, e->dt)); /* history updates (rate terms) use the step */
  apply_kinematic_bcs(e, 0.0, 0);
  PDK_CALL_GOTO(pdk_model_force(m, &e->strain));
  e->energy0 = kinetic_energy(e) + e->strain;
  {
    /* round-off floor: the energy of a uniform strain of 1e-6 in the whole body */
    double vol = 0.0;
    const double *V = pdk_particles_volume(e->p);
    for (pdk_index i = 0; i < e->n; ++i) vol += V[i];
    e->energy_floor = 0.5 * m->opts.bulk_modulus * 1e-12 * vol;
  }
  *out = e;
  return PDK_SUCCESS;
cleanup:
  pdk_explicit_destroy(&e);
  return err;
}

void pdk_explicit_destroy(pdk_explicit **ep) {
  if (!ep || !*ep) return;
  pdk_explicit *e = *ep;
  for (int c = 0; c < 3; ++c) free(e->bc_of[c]);
  free(e->dir_list);
  free(e->dir_bc);
  free(e->dir_frame);
  free(e->acct_a2);
  free(e->auto_x);
  free(e->bcs);
  free(e);
  *ep = NULL;
}

double pdk_explicit_stable_dt(const pdk_explicit *e) { return e ? e->dt_stable : NAN; }
double pdk_explicit_dt(const pdk_explicit *e) { return e ? e->dt : NAN; }
double pdk_explicit_time(const pdk_explicit *e) { return e ? e->time : NAN; }
void pdk_explicit_dt_start(const pdk_explicit *e, long *step0, double *time0) {
  if (step0) *step0 = e ? e->dt_step0 : 0;
  if (time0) *time0 = e ? e->dt_time0 : NAN;
}
int pdk_explicit_num_estimates(const pdk_explicit *e) { return e ? e->num_estimates : 0; }
int pdk_explicit_num_dt_changes(const pdk_explicit *e) { return e ? e->num_dt_changes : 0; }
const pdk_explicit_opts *pdk_explicit_opts_get(const pdk_explicit *e) {
  return e ? &e->opts : NULL;
}
long pdk_explicit_step(const pdk_explicit *e) { return e ? e->step : 0; }

/* A force pass of the step ending at t1 failed: its message, prefixed with the step and time. */
static int step_failed(pdk_explicit *e, int err, double t1) {
  if (!err) return PDK_SUCCESS;
  char msg[PDK_ERRMSG_MAX];
  snprintf(msg, sizeof msg, "%s", pdk_ctx_error_message(e->ctx));
  return pdk_ctx_error_set(e->ctx, err, NULL, "step %ld (time %g): %s", e->step + 1, t1, msg);
}

int pdk_explicit_run(pdk_explicit *e, long num_steps, pdk_history *hist) {
  PDK_CHECK_ARG(e, NULL);
  PDK_CHECK(num_steps >= 0, e->ctx, PDK_ERR_ARG, "number of steps must be >= 0, got %ld", num_steps);
  PDK_CALL(pdk_model_set_dt(e->m, e->dt)); /* a restore may have changed e->dt */
  /* The power and the prescribed kinetic energy at a step's start are those at the previous
   * step's end: computed once per step (the state cannot change between steps of one call). */
  double p0 = num_steps > 0 ? external_power(e, e->time) : 0.0;
  double k0 = num_steps > 0 ? constrained_kinetic(e) : 0.0;
  if (num_steps > 0 && !e->acct_set) { /* the runaway check's baseline (check_runaway) */
    PDK_CALL(acct_energy(e, &e->acct_e0));
    e->acct_w0 = e->external_work;
    e->acct_step0 = e->step;
    e->acct_prev = 0.0;
    e->acct_streak = 0;
    e->acct_set = 1;
  }
  for (long s = 0; s < num_steps; ++s) {
    double t0 = e->time, t1 = e->time + e->dt;
    half_kick(e, t0);
    drift(e);
    apply_kinematic_bcs(e, t1, 1);
    if (e->num_walls) pdk_walls_apply(e, t1);
    PDK_CALL(step_failed(e, pdk_model_force(e->m, &e->strain), t1));
    half_kick(e, t1);
    apply_kinematic_bcs(e, t1, 0);
    e->time = t1;
    e->step++;
    PDK_CALL(check_state(e));
    /* work of the constraints: the trapezoid of their power against the internal forces, plus
     * the change of the prescribed particles' kinetic energy (their inertia) */
    const double p1 = external_power(e, t1), k1 = constrained_kinetic(e);
    e->external_work += 0.5 * e->dt * (p0 + p1) + k1 - k0;
    p0 = p1;
    k0 = k1;
    if (e->opts.dt_update == PDK_DT_UPDATE_AUTO) /* before the checks: it may lower dt */
      PDK_CALL(pdk_explicit_auto_dt(e)); /* the next step uses the new dt, as below */
    if (e->step % 8 == 0) {
      PDK_CALL(check_runaway(e)); /* first: it trips earlier and names more */
      PDK_CALL(check_blowup(e));
    }
    const pdk_dt_update du = e->opts.dt_update;
    if ((du == PDK_DT_UPDATE_BREAKS || du == PDK_DT_UPDATE_PERIODIC) &&
        e->step - e->est_step >= e->opts.dt_update_interval &&
        (du == PDK_DT_UPDATE_PERIODIC || pdk_model_num_broken(e->m) != e->est_broken))
      PDK_CALL(pdk_explicit_update_dt(e, e->opts.safety)); /* the next step uses the new dt;
                                                              p0 and k0 stand (x, v, f do) */
  }
  if (hist) {
    memset(hist, 0, sizeof *hist);
    hist->step = e->step;
    hist->time = e->time;
    hist->dt = e->dt;
    hist->kinetic = kinetic_energy(e);
    hist->strain = e->strain;
    hist->external_work = e->external_work;
    reactions(e, hist->reaction);
    hist->broken = pdk_model_num_broken(e->m);
    PDK_CALL(pdk_model_plastic_work(e->m, &hist->plastic_work, &hist->damage_work,
                                    &hist->breaking_work));
    hist->failed = pdk_model_num_failed(e->m);
    hist->damage_max = pdk_model_damage_max(e->m);
    for (int w = 0; w < e->num_walls; ++w)
      hist->wall_impulse[w] = e->wall_impulse[w];
    hist->contact_work = e->contact_work;
    hist->rebuild_work = pdk_model_rebuild_work(e->m);
  }
  return PDK_SUCCESS;
}
