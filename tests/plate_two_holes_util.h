/* Shared by t120 (plate with two holes, coarse, default suite) and t121 (its resolution study):
 * run scenes/plate_two_holes.yaml with overrides until the plate separates, and record what the
 * checks need.
 *
 * Geometry of the checks, from the scene's own holes (centres c1, c2, radius r):
 *   inner ligament  the corridor between the holes: points whose projection on the segment c1-c2
 *                   falls strictly between the centres and whose distance from the line c1-c2 is
 *                   at most r (it holds the facing half of each hole's edge);
 *   outer ligaments everything else outside the clamped and pulled rows.
 * Force: the bottom reaction -R_bottom,y (the thesis plots the force at the bottom clamp).
 * Separated: the bottom and top sets lie in different connected components of the intact bond
 * graph (jc_corr_util.h). Pieces: components holding more than 1% of the particles (a failed
 * particle loses all its bonds and is a component of its own).
 *
 * PDK_PLATE_EBAL=1 prints the energy account every 400 steps (and the softened stabilization's).
 * PDK_PLATE_DUMP=<prefix>: writes <prefix>_<mode>_first.csv (at the first failure) and
 * <prefix>_<mode>_end.csv (at the end) with X, Y, x, y, eps_p, damage, failed, component, for
 * plotting. PDK_TEST_VERBOSE=1 prints the numbers. */
#ifndef PDK_PLATE_TWO_HOLES_UTIL_H
#define PDK_PLATE_TWO_HOLES_UTIL_H

#include "jc_corr_util.h"
#include "pdk/scene.h"
#include "scene/scene_impl.h"

#define PH_MAX_OVERRIDES 16
#define PH_MAX_TRACE 200000

typedef struct ph_result {
  pdk_index num_particles;
  double dt;
  long steps;             /* steps run */
  double peak;            /* peak bottom force [N] */
  double t_peak, u_peak;  /* time and top displacement at the peak */
  double force_at_ref;    /* bottom force when the top has moved PH_U_REF, interpolated between
                             the chunks either side (-1: not reached) */
  double band_eps_p_at_ref; /* mean eps_p of the particles within one spacing of the midpoint of
                               the two hole centres, at the first chunk past PH_U_REF (-1: not
                               reached) */
  double t_first_inner;   /* first failure in the inner ligament (-1: none) */
  double t_first_outer;   /* first failure elsewhere outside the clamps (-1: none) */
  int first_all_inner;    /* every particle failed in the first failing chunk is in the inner
                             ligament */
  int num_first;          /* how many failed in that chunk */
  double first_edge_dist; /* largest distance of those particles from the nearest hole's edge */
  double horizon;         /* of the scene */
  double t_sep, u_sep;    /* time and top displacement at separation (-1: never) */
  double final_force;     /* |mean bottom force| over the last window after separation: the
                             force rings about zero once the pieces are apart */
  double final_abs_force; /* mean |bottom force| over the same window (the ringing) */
  double final_window;    /* its length [s] */
  int num_pieces;         /* components with more than 1% of the particles, at the end */
  pdk_index num_components;
  double crack_force; /* |sum V f| over the bottom piece at the end [N] */
  int pieces_ok;      /* the two pieces hold the bottom and the top sets */
  double plastic_work, damage_work, breaking_work, external_work;
  double worst_imbalance; /* largest |external - (kinetic + strain + plastic + damage + breaking)|
                             over the chunks [J] */
  double min_breaking;    /* smallest breaking work over the chunks [J] */
  pdk_bond_index broken;
  pdk_index failed;
  long compactions;
  double dt_final;       /* the step at the end (below dt after a solver.dt_update lowered it) */
  int num_estimates;     /* estimates of the stable step, the one at creation included */
  int num_dt_changes;    /* how many lowered the step */
  double wall; /* seconds */
} ph_result;

typedef struct ph_geometry {
  double c1[2], c2[2], r;
  double y_bottom, y_top; /* clamped rows: y <= y_bottom, pulled rows: y >= y_top */
} ph_geometry;

static inline int ph_inner(const ph_geometry *g, double x, double y) {
  const double ux = g->c2[0] - g->c1[0], uy = g->c2[1] - g->c1[1];
  const double len2 = ux * ux + uy * uy;
  const double t = ((x - g->c1[0]) * ux + (y - g->c1[1]) * uy) / len2;
  const double dist = fabs((x - g->c1[0]) * uy - (y - g->c1[1]) * ux) / sqrt(len2);
  return t > 0.0 && t < 1.0 && dist <= g->r;
}

static inline void ph_dump(pdk_sim *sim, const pdk_index *comp, const char *prefix,
                           const char *mode, const char *when) {
  char path[1024];
  snprintf(path, sizeof path, "%s_%s_%s.csv", prefix, mode, when);
  FILE *f = fopen(path, "w");
  T_ASSERT(f, "cannot write %s", path);
  pdk_particles *p = pdk_sim_particles(sim);
  const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  const double *ep = pdk_particles_field_data(p, "eps_p", 0);
  const double *dmg = pdk_particles_field_data(p, "damage", 0);
  const uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
  const pdk_model_opts *mo = pdk_model_opts_get(pdk_sim_model(sim));
  double *Fc[4], *cp[6];
  for (int t = 0; t < 4; ++t)
    Fc[t] = pdk_particles_field_data(p, "F", t);
  for (int t = 0; t < 6; ++t)
    cp[t] = pdk_particles_field_data(p, "cp_inv", t);
  fprintf(f, "X,Y,x,y,eps_p,damage,failed,component,sigma_vm,eta,eps_p_rate,sxx,syy,szz,sxy\n");
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    double F[3][3] = {{Fc[0][i], Fc[1][i], 0}, {Fc[2][i], Fc[3][i], 0}, {0, 0, 1}}, P[3][3];
    pdk_jc_state in = pdk_jc_state_initial(), out;
    for (int t = 0; t < 6; ++t)
      in.cp_inv[t] = cp[t][i];
    in.eps_p = ep[i];
    in.damage = dmg[i];
    in.failed = failed[i];
    pdk_jc_result res;
    memset(&res, 0, sizeof res);
    if (pdk_jc_update(&mo->jc, 2, F, 1e-7, &in, &out, P, &res)) memset(&res, 0, sizeof res);
    const double *sg = res.sigma;
    const double sm = (sg[0] + sg[1] + sg[2]) / 3.0;
    fprintf(f, "%g,%g,%g,%g,%g,%g,%d,%d,%g,%g,%g,%g,%g,%g,%g\n", pdk_particles_X(p, 0)[i],
            pdk_particles_X(p, 1)[i], x[i], y[i], ep[i], dmg[i], failed[i], comp ? (int)comp[i] : 0,
            res.sigma_vm, res.sigma_vm > 0 ? sm / res.sigma_vm : 0.0,
            ((const double *)pdk_particles_field_data(p, "eps_p_rate", 0))[i], sg[0], sg[1], sg[2],
            sg[5]);
  }
  fclose(f);
}

/* Particle index of the first member of a set field. */
static inline pdk_index ph_first_of(pdk_particles *p, const char *set) {
  const uint8_t *mem = pdk_particles_field_data(p, set, 0);
  T_ASSERT(mem, "no set %s", set);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    if (mem[i]) return i;
  T_FAIL("set %s is empty", set);
}

/* Top displacement at which force_at_ref is read: before any failure at every spacing, where the
 * finite-element reference (docs/validation/plate_two_holes_fe) gives 40.4 kN. */
#define PH_U_REF 1.2e-3

/* Loads the scene with the overrides, runs until the plate separates and then `after` seconds
 * more (or until max_time), checking components every `check_every` steps. */
/* out = $PDK_SOURCE_DIR/scenes/<name> (ctest sets PDK_SOURCE_DIR). */
static inline void ph_scene_path(const char *name, char *out, size_t n) {
  const char *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(src, "PDK_SOURCE_DIR is not set (ctest sets it)");
  snprintf(out, n, "%s/scenes/%s", src, name);
}

static inline void ph_run(pdk_ctx *ctx, const char *scene_path, const char *const *overrides,
                          int num_overrides, const char *mode, double after, double max_time,
                          long check_every, ph_result *r) {
  memset(r, 0, sizeof *r);
  r->t_first_inner = r->t_first_outer = r->t_sep = r->u_sep = r->force_at_ref = -1.0;
  r->band_eps_p_at_ref = -1.0;
  double u_prev = 0.0, force_prev = 0.0;
  const double wall0 = pdk_wtime();
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, scene_path, overrides, num_overrides, &s));
  T_ASSERT(s->num_holes == 2 && s->holes[0].region.kind == PDK_REGION_BALL &&
               s->holes[1].region.kind == PDK_REGION_BALL,
           "%s: the scene must have two disk holes", mode);
  ph_geometry g;
  for (int a = 0; a < 2; ++a) {
    g.c1[a] = s->holes[0].region.center[a];
    g.c2[a] = s->holes[1].region.center[a];
  }
  g.r = s->holes[0].region.radius;
  r->horizon = s->horizon;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  pdk_model *m = pdk_sim_model(sim);
  pdk_explicit *e = pdk_sim_explicit(sim);
  const pdk_index n = pdk_particles_count(p);
  r->num_particles = n;
  r->dt = pdk_explicit_dt(e);
  /* reaction sets: top first, bottom second (output.reactions of the scene) */
  T_ASSERT(s->output.num_reaction_sets == 2 && !strcmp(s->output.reaction_sets[0], "top") &&
               !strcmp(s->output.reaction_sets[1], "bottom"),
           "%s: the scene must record reactions [top, bottom]", mode);
  const uint8_t *in_top = pdk_particles_field_data(p, "set:top", 0);
  const uint8_t *in_bottom = pdk_particles_field_data(p, "set:bottom", 0);
  const pdk_index i_top = ph_first_of(p, "set:top"), i_bottom = ph_first_of(p, "set:bottom");
  const double *x_y = pdk_particles_field_data(p, "x", 1), *X_y = pdk_particles_X(p, 1);
  pdk_index *comp = malloc((size_t)n * sizeof *comp);
  double *trace_t = malloc(PH_MAX_TRACE * sizeof(double));
  double *trace_f = malloc(PH_MAX_TRACE * sizeof(double));
  T_ASSERT(comp && trace_t && trace_f, "out of memory");
  long num_trace = 0;
  const char *dump = getenv("PDK_PLATE_DUMP");
  const long chunk = 10;
  long since_check = 0;
  double end_time = max_time;
  pdk_history h;
  while (pdk_explicit_time(e) < end_time - 0.5 * r->dt) {
    T_OK(ctx, pdk_explicit_run(e, chunk, &h));
    r->steps += chunk;
    since_check += chunk;
    const double force = -h.reaction[1][1];
    r->worst_imbalance =
        fmax(r->worst_imbalance, fabs(h.external_work - h.kinetic - h.strain - h.plastic_work -
                                      h.damage_work - h.breaking_work));
    r->min_breaking = fmin(r->min_breaking, h.breaking_work);
    if (getenv("PDK_PLATE_EBAL") && r->steps % 400 == 0) /* exploring: the energy account */
      printf("EBAL t %.4e ext %.4f K %.4f S %.4f P %.4f D %.4f B %.4f imb %.4f failed %d\n", h.time,
             h.external_work, h.kinetic, h.strain, h.plastic_work, h.damage_work, h.breaking_work,
             h.external_work - h.kinetic - h.strain - h.plastic_work - h.damage_work -
                 h.breaking_work,
             (int)pdk_model_num_failed(m));
    if (getenv("PDK_PLATE_EBAL") && r->steps % 400 == 0 &&
        pdk_particles_field_exists(p, "w_stab")) {
      const double *ws = pdk_particles_field_data(p, "w_stab", 0), *V = pdk_particles_volume(p);
      const double *fac = pdk_particles_field_data(p, "stab_factor", 0);
      double sum = 0.0, fmin = 1.0;
      for (pdk_index i = 0; i < n; ++i) {
        sum += V[i] * ws[i];
        fmin = fac[i] < fmin ? fac[i] : fmin;
      }
      printf("   w_stab %.4f J, smallest factor %.3g\n", sum, fmin);
    }
    const double u_top = x_y[i_top] - X_y[i_top];
    if (num_trace < PH_MAX_TRACE) {
      trace_t[num_trace] = h.time;
      trace_f[num_trace++] = force;
    }
    if (r->force_at_ref < 0.0 && u_top >= PH_U_REF && u_top > u_prev) {
      r->force_at_ref = force_prev + (force - force_prev) * (PH_U_REF - u_prev) / (u_top - u_prev);
      const double *ep = pdk_particles_field_data(p, "eps_p", 0);
      const double *X_x = pdk_particles_X(p, 0);
      const double mid[2] = {0.5 * (g.c1[0] + g.c2[0]), 0.5 * (g.c1[1] + g.c2[1])};
      const double reach = 1.0001 * s->lattice.spacing;
      double sum = 0.0;
      int count = 0;
      for (pdk_index i = 0; i < n; ++i)
        if (hypot(X_x[i] - mid[0], X_y[i] - mid[1]) <= reach) {
          sum += ep[i];
          ++count;
        }
      T_ASSERT(count > 0, "%s: no particle within %g m of the band's middle", mode, reach);
      r->band_eps_p_at_ref = sum / count;
    }
    u_prev = u_top;
    force_prev = force;
    if (force > r->peak) {
      r->peak = force;
      r->t_peak = h.time;
      r->u_peak = u_top;
    }
    if (dump && getenv("PDK_PLATE_DUMP_AT") && h.time >= atof(getenv("PDK_PLATE_DUMP_AT")) &&
        h.time < atof(getenv("PDK_PLATE_DUMP_AT")) + chunk * r->dt)
      ph_dump(sim, NULL, dump, mode, "at");
    /* failure order */
    if (r->t_first_inner < 0 || r->t_first_outer < 0) {
      const uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
      const int first_chunk = r->t_first_inner < 0 && r->t_first_outer < 0;
      int any = 0, all_inner = 1, count = 0;
      double edge = 0.0;
      for (pdk_index i = 0; i < n; ++i) {
        if (!failed[i] || in_top[i] || in_bottom[i]) continue;
        const double X = pdk_particles_X(p, 0)[i], Y = pdk_particles_X(p, 1)[i];
        const int inner = ph_inner(&g, X, Y);
        const double d1 = hypot(X - g.c1[0], Y - g.c1[1]) - g.r;
        const double d2 = hypot(X - g.c2[0], Y - g.c2[1]) - g.r;
        edge = fmax(edge, fmin(d1, d2));
        any = 1;
        ++count;
        all_inner &= inner;
        if (inner && r->t_first_inner < 0) r->t_first_inner = h.time;
        if (!inner && r->t_first_outer < 0) r->t_first_outer = h.time;
      }
      if (first_chunk && any) {
        r->first_all_inner = all_inner;
        r->num_first = count;
        r->first_edge_dist = edge;
        if (dump) ph_dump(sim, NULL, dump, mode, "first");
      }
    }
    /* separation */
    if (r->t_sep < 0 && since_check >= check_every) {
      since_check = 0;
      jcu_components(m, comp);
      if (comp[i_top] != comp[i_bottom]) {
        r->t_sep = h.time;
        r->u_sep = u_top;
        end_time = fmin(max_time, h.time + after);
      }
    }
  }
  /* final force: mean |F| over the last window after separation (or the last 10% of the run) */
  const double t_end = pdk_explicit_time(e);
  const double window = r->t_sep >= 0 ? fmin(after, t_end - r->t_sep) * 0.5 : 0.1 * t_end;
  double sum = 0.0, sum_abs = 0.0;
  long cnt = 0;
  for (long k = 0; k < num_trace; ++k)
    if (trace_t[k] >= t_end - window) {
      sum += trace_f[k];
      sum_abs += fabs(trace_f[k]);
      ++cnt;
    }
  r->final_force = cnt ? fabs(sum) / (double)cnt : NAN;
  r->final_abs_force = cnt ? sum_abs / (double)cnt : NAN;
  r->final_window = window;

  /* pieces, and the force across the crack on the bottom piece */
  r->num_components = jcu_components(m, comp);
  pdk_index *size = calloc((size_t)n, sizeof *size);
  T_ASSERT(size, "out of memory");
  for (pdk_index i = 0; i < n; ++i)
    size[comp[i]]++;
  pdk_index big[2] = {-1, -1};
  for (pdk_index i = 0; i < n; ++i)
    if (size[i] * 100 > n) {
      if (r->num_pieces < 2) big[r->num_pieces] = i;
      r->num_pieces++;
    }
  r->pieces_ok = r->num_pieces == 2 && ((comp[i_top] == big[0] && comp[i_bottom] == big[1]) ||
                                        (comp[i_top] == big[1] && comp[i_bottom] == big[0]));
  const double *vol = pdk_particles_volume(p);
  for (int c = 0; c < 2; ++c) {
    const double *f = pdk_particles_field_data(p, "f", c);
    double fs = 0.0;
    for (pdk_index i = 0; i < n; ++i)
      if (comp[i] == comp[i_bottom]) fs += vol[i] * f[i];
    r->crack_force = fmax(r->crack_force, fabs(fs));
  }
  free(size);
  r->plastic_work = h.plastic_work;
  r->damage_work = h.damage_work;
  r->breaking_work = h.breaking_work;
  r->external_work = h.external_work;
  r->broken = pdk_model_num_broken(m);
  r->failed = pdk_model_num_failed(m);
  r->compactions = pdk_model_num_compactions(m);
  if (dump) ph_dump(sim, comp, dump, mode, "end");
  if (getenv("PDK_PLATE_PATH") && comp[i_top] == comp[i_bottom]) {
    /* BFS from the top to the bottom particle: print the path */
    pdk_families *fam = pdk_sim_families(sim);
    const pdk_bond_index *bs = pdk_families_bond_start(fam);
    const pdk_index *bj = pdk_families_bond_j(fam);
    const uint8_t *alive = pdk_model_bond_alive(m);
    const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
    pdk_index *prev = malloc((size_t)n * sizeof *prev), *queue = malloc((size_t)n * sizeof *queue);
    for (pdk_index i = 0; i < n; ++i)
      prev[i] = -2;
    pdk_index qh = 0, qt = 0;
    queue[qt++] = i_top;
    prev[i_top] = -1;
    while (qh < qt) {
      pdk_index i = queue[qh++];
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b)
        if (alive[b] && prev[bj[b]] == -2) {
          prev[bj[b]] = i;
          queue[qt++] = bj[b];
        }
    }
    for (pdk_index i = i_bottom; i >= 0; i = prev[i]) {
      pdk_index na = 0;
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b)
        na += alive[b];
      printf("path %d X (%g, %g) x (%g, %g) flag %d alive %d\n", (int)i, pdk_particles_X(p, 0)[i],
             pdk_particles_X(p, 1)[i], ((const double *)pdk_particles_field_data(p, "x", 0))[i],
             x_y[i], flag[i], (int)na);
    }
    free(prev);
    free(queue);
  }
  if (getenv("PDK_PLATE_TRACE")) {
    char path[1024];
    snprintf(path, sizeof path, "%s_%s_force.csv", getenv("PDK_PLATE_TRACE"), mode);
    FILE *f = fopen(path, "w");
    if (f) {
      for (long k = 0; k < num_trace; ++k)
        fprintf(f, "%g,%g\n", trace_t[k], trace_f[k]);
      fclose(f);
    }
  }
  free(comp);
  free(trace_t);
  free(trace_f);
  r->dt_final = pdk_explicit_dt(e);
  r->num_estimates = pdk_explicit_num_estimates(e);
  r->num_dt_changes = pdk_explicit_num_dt_changes(e);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  r->wall = pdk_wtime() - wall0;
}

static inline void ph_print(const char *what, const ph_result *r) {
  printf("%s: %d particles, dt %.3g s, %ld steps, %.1f s wall\n"
         "  peak force %.5g N at t %.4g s, top displacement %.4g m; force at top displacement "
         "%.3g m: %.5g N, eps_p in the middle of the band %.4f\n"
         "  first failure: inner ligament t %.4g s, outer t %.4g s (%d particles in the first "
         "chunk, all inner: %d, at most %.3g m from a hole's edge)\n"
         "  separated at t %.4g s, top displacement %.4g m; final |mean force| %.4g N (%.2f%% of "
         "peak, over %.3g s; mean |force| %.4g N)\n"
         "  %d pieces (%d components), pieces hold top and bottom: %d, |force across the crack| "
         "%.3g N\n"
         "  work: external %.4g J, plastic %.4g J, damage %.4g J, breaking %.4g J (least %.3g J); "
         "worst energy imbalance %.3g J; %lld bonds broken, %d failed, %ld compactions\n"
         "  time step: %d estimate(s), lowered %d time(s), final dt %.3g s\n",
         what, (int)r->num_particles, r->dt, r->steps, r->wall, r->peak, r->t_peak, r->u_peak,
         PH_U_REF, r->force_at_ref, r->band_eps_p_at_ref, r->t_first_inner, r->t_first_outer, r->num_first,
         r->first_all_inner, r->first_edge_dist, r->t_sep, r->u_sep, r->final_force,
         100.0 * r->final_force / r->peak, r->final_window, r->final_abs_force, r->num_pieces,
         (int)r->num_components, r->pieces_ok, r->crack_force, r->external_work, r->plastic_work,
         r->damage_work, r->breaking_work, r->min_breaking, r->worst_imbalance, (long long)r->broken,
         (int)r->failed, r->compactions, r->num_estimates, r->num_dt_changes, r->dt_final);
}

#endif
