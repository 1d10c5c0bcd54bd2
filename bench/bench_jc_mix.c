/* The Johnson-Cook update on a ductile scene's own material states.
 *
 *   bench_jc_mix [--scene PATH] [--at STEP ...] [--repeat R] [--set KEY=VALUE ...]
 *
 * bench_ductile times the update on a lattice where every particle takes its first plastic step;
 * a ductile run is mostly elastic calls (particles away from the plastic zones, particles that
 * unload) and plastic calls deep in the hardening curve. This program runs the scene (default
 * scenes/plate_two_holes.yaml, the README's default run) with the explicit solver and, at each
 * step given with --at (default 2000 4000 6000 8000 10000 of the shipped plate's 11 083: loading,
 * spreading plastic zones, about the peak force at step 6160, the tear, the torn plate), times the
 * update the correspondence kernels call (pdk_jc_update_kernel, kernels/ref/jc.c) over every
 * particle that has not failed, at its stored F and committed history, as a trial (the history is
 * not changed, so every repeat does the same work). The calls are the ones pass 1 of the next step
 * makes, in the store's order, without the family loop around them. Printed per snapshot: particles
 * updated, the share whose trial state is plastic, the median CPU time per call over R repeats (one
 * thread) and the same for the elastic and plastic calls alone (each set timed on its own; "nan" for
 * a set of fewer than 100 calls, which would time mostly the clock).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "kernels.h" /* pdk_jc_update_kernel */
#include "pdk/pdk.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double cpu_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
  double F[3][3];
  pdk_jc_state in;
  double sm;   /* family mean stress, or NAN for the point's own */
  int plastic; /* the trial was plastic */
} call;

/* Median CPU seconds per call of the calls with plastic == which (-1: all) over repeat runs; NAN
 * for fewer than 100 such calls. */
static double time_calls(const pdk_jc_params *jp, int dim, double dt, const call *c, size_t n,
                         int which, int repeat, double *sink) {
  double *t = malloc((size_t)repeat * sizeof *t);
  size_t m = 0;
  for (size_t i = 0; i < n; ++i)
    m += which < 0 || c[i].plastic == which;
  if (!t || m < 100) { /* a few dozen calls would time the loop and the clock */
    free(t);
    return NAN;
  }
  for (int r = 0; r < repeat; ++r) {
    const double t0 = cpu_now();
    for (size_t i = 0; i < n; ++i) {
      if (which >= 0 && c[i].plastic != which) continue;
      pdk_jc_state out;
      pdk_jc_result res;
      double P[3][3];
      pdk_jc_update_kernel(jp, dim, c[i].F, dt, isnan(c[i].sm) ? NULL : &c[i].sm, &c[i].in, &out, P,
                           &res);
      *sink += P[0][0] + out.eps_p;
    }
    t[r] = (cpu_now() - t0) / (double)m;
  }
  qsort(t, (size_t)repeat, sizeof *t, cmp_double);
  const double med = t[repeat / 2];
  free(t);
  return med;
}

static void usage(void) {
  fprintf(stderr, "usage: bench_jc_mix [--scene PATH] [--at STEP ...] [--repeat R] "
                  "[--set KEY=VALUE ...]\n");
  exit(2);
}

int main(int argc, char **argv) {
  const char *scene_path = "scenes/plate_two_holes.yaml";
  long at[32];
  int num_at = 0, repeat = 7, num_set = 0;
  const char *sets[32];
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "--scene") && i + 1 < argc)
      scene_path = argv[++i];
    else if (!strcmp(argv[i], "--at") && i + 1 < argc && num_at < 32)
      at[num_at++] = atol(argv[++i]);
    else if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--set") && i + 1 < argc && num_set < 32)
      sets[num_set++] = argv[++i];
    else
      usage();
  }
  if (repeat < 1) usage();
  if (num_at == 0) {
    const long def[5] = {2000, 4000, 6000, 8000, 10000};
    for (num_at = 0; num_at < 5; ++num_at)
      at[num_at] = def[num_at];
  }
  for (int k = 1; k < num_at; ++k)
    if (at[k] <= at[k - 1]) {
      fprintf(stderr, "bench_jc_mix: --at steps must increase\n");
      return 2;
    }

  char err[512];
  pdk_ctx *ctx = NULL;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = 1;
  if (pdk_ctx_create(&co, &ctx, err, sizeof err)) {
    fprintf(stderr, "bench_jc_mix: %s\n", err);
    return 1;
  }
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  if (pdk_scene_load(ctx, scene_path, sets, num_set, &scene) || pdk_sim_create(ctx, scene, &sim)) {
    fprintf(stderr, "bench_jc_mix: %s\n", pdk_ctx_error_message(ctx));
    return 1;
  }
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_model *m = pdk_sim_model(sim);
  const pdk_model_opts *mo = pdk_model_opts_get(m);
  pdk_particles *p = pdk_sim_particles(sim);
  const int dim = pdk_particles_dim(p);
  if (!e || mo->law != PDK_LAW_JC) {
    fprintf(stderr, "bench_jc_mix: %s: needs the explicit solver and the Johnson-Cook law\n",
            scene_path);
    return 2;
  }
  const pdk_index n = pdk_particles_count(p);
  call *calls = malloc((size_t)n * sizeof *calls);
  if (!calls) return 1;
  printf("bench_jc_mix: %s, %ld particles, dim %d, 1 thread, repeat %d\n", scene_path, (long)n, dim,
         repeat);
  printf("%8s %10s %9s %10s %10s %13s %13s\n", "step", "time [ms]", "updated", "plastic", "ns/call",
         "ns/elastic", "ns/plastic");
  double sink = 0.0;
  for (int k = 0; k < num_at; ++k) {
    const long todo = at[k] - pdk_explicit_step(e);
    if (todo > 0 && pdk_explicit_run(e, todo, NULL)) {
      fprintf(stderr, "bench_jc_mix: %s\n", pdk_ctx_error_message(ctx));
      return 1;
    }
    const double dt = pdk_model_get_dt(m);
    const double *F[9], *cp[6];
    for (int c = 0; c < dim * dim; ++c)
      F[c] = pdk_particles_field_data(p, "F", c);
    for (int c = 0; c < 6; ++c)
      cp[c] = pdk_particles_field_data(p, "cp_inv", c);
    const double *eps_p = pdk_particles_field_data(p, "eps_p", 0);
    const double *damage = pdk_particles_field_data(p, "damage", 0);
    const double *temp = pdk_particles_field_data(p, "temp_rise", 0);
    const uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
    const double *sm = pdk_particles_field_data(p, "sigma_m_avg", 0);
    size_t nc = 0, np = 0;
    for (pdk_index i = 0; i < n; ++i) {
      if (failed[i]) continue;
      call *c = &calls[nc++];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          c->F[a][b] = (a < dim && b < dim) ? F[a * dim + b][i] : (a == b ? 1.0 : 0.0);
      for (int t = 0; t < 6; ++t)
        c->in.cp_inv[t] = cp[t][i];
      c->in.eps_p = eps_p[i];
      c->in.damage = damage[i];
      c->in.temp_rise = temp ? temp[i] : 0.0;
      c->in.failed = 0;
      c->sm = sm ? sm[i] : NAN;
      pdk_jc_state out;
      pdk_jc_result res;
      double P[3][3];
      if (pdk_jc_update_kernel(&mo->jc, dim, c->F, dt, sm ? &c->sm : NULL, &c->in, &out, P, &res))
        --nc; /* the kernel marks such a particle inverted; not a material update */
      else
        np += (size_t)(c->plastic = res.plastic);
    }
    const double t_all = time_calls(&mo->jc, dim, dt, calls, nc, -1, repeat, &sink);
    const double t_el = time_calls(&mo->jc, dim, dt, calls, nc, 0, repeat, &sink);
    const double t_pl = time_calls(&mo->jc, dim, dt, calls, nc, 1, repeat, &sink);
    printf("%8ld %10.4g %9zu %9.1f%% %10.1f %13.1f %13.1f\n", pdk_explicit_step(e),
           1e3 * pdk_explicit_time(e), nc, 100.0 * (double)np / (double)(nc ? nc : 1), 1e9 * t_all,
           1e9 * t_el, 1e9 * t_pl);
    fflush(stdout);
  }
  if (sink == 12345.678) printf("(sink)\n");
  free(calls);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  pdk_ctx_destroy(&ctx);
  return 0;
}
