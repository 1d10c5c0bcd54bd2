/* Force-loop benchmark: one force pass of the PMB, LPS (and correspondence, when that model is part
 * of the build) models on a free simple-cubic cube of side L (L^3 particles), horizon 3.015
 * spacings, LAMMPS partial volumes on (lattice constant = spacing), no bond breaking, particles in
 * Morton order of the family cells (or lattice order). Each configuration is timed R times after
 * two warm-up passes; the median is reported, per thread count.
 *
 *   bench_forces [--side L]... [--model pmb|lps|corr|pmb-r0]... [--threads T]... [--repeat R]
 *                [--order morton|lattice] [--s00 S] [--steps N] [--triad-mib M]
 *
 * --steps N: instead of single passes, run N velocity-Verlet steps (v += dt/2 f/rho, x += dt v,
 *   force, v += dt/2 f/rho; zero initial velocity, as the LAMMPS side-by-side in bench/lammps/)
 *   and report the loop time per step.
 * --s00 S: critical stretch (0: no bond state; > 0: bond state read and written every pass).
 *
 * Printed per configuration: pass time, ns per directed bond per core (time x threads / bonds),
 * bonds/s, modelled bytes per bond, the achieved bandwidth, the STREAM-like triad bandwidth this
 * program measures with the same thread count, the fraction of it (the memory roofline), and the
 * process CPU time per bond per thread (cpu_ns/b: equal to ns/b/c on an idle machine; lower when
 * other processes took the cores part of the time, so compare both).
 *
 * Byte model (compulsory DRAM traffic per pass, assuming the neighbour gathers hit in cache, which
 * spatial order makes nearly true): per bond, bond_j 4 B (+ 2 B bond state read and written when
 * breaking is on); per particle, bond_start 8 B, X and x (2 dim x 8 B) and the volume 8 B read,
 * the force written (dim x 8 B, counted twice for the write-allocate), plus for breaking s0 read
 * and the next s0 written (8 + 16 B). LPS makes two passes: the dilation pass reads the same plus
 * 1/m and writes theta (8 + 16 B), the force pass reads the same plus theta and 1/m (16 B).
 * Correspondence: as LPS plus the 9 entries of A_j read per particle (72 B) in the second pass, a
 * lower bound. Triad bytes follow STREAM: 24 B per element, write-allocate not counted.
 */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pdk/pdk.h"

/* src/model_impl.h declares the kinds' operation tables weak; a weak reference does not pull an
 * object out of the static archive, so reference the two this benchmark always uses strongly.
 * (The correspondence kind runs only when something else links src/model_corr.c in.) */
extern const struct pdk_model_ops pdk_model_ops_pmb, pdk_model_ops_lps;
__attribute__((used)) static const void *const link_models[] = {&pdk_model_ops_pmb,
                                                                &pdk_model_ops_lps};

#define MAX_LIST 8

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void usage(void) {
  fprintf(stderr,
          "usage: bench_forces [--side L]... [--model pmb|lps|corr]... [--threads T]...\n"
          "                    [--repeat R] [--order morton|lattice] [--s00 S] [--steps N]\n"
          "                    [--triad-mib M]\n");
  exit(2);
}

/* CPU time of the process [s]: under contention from other processes it stays closer to the work
 * done than the wall clock (1 thread); with more threads it also counts spinning at barriers. */
static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *short_name(pdk_model_kind kind) {
  return kind == PDK_MODEL_CORRESPONDENCE ? "corr"
         : kind == (pdk_model_kind)100    ? "pmb-r0"
                                          : pdk_model_kind_name(kind);
}

static void die(pdk_ctx *ctx, const char *what) {
  fprintf(stderr, "bench_forces: %s: %s\n", what, ctx ? pdk_ctx_error_message(ctx) : "");
  exit(1);
}

/* STREAM-like triad a = b + s c over `len` doubles per array, `threads` threads, best of 10. */
static double triad_gbs(size_t len, int threads) {
  double *a = malloc(len * sizeof *a), *b = malloc(len * sizeof *b), *c = malloc(len * sizeof *c);
  if (!a || !b || !c) {
    fprintf(stderr, "bench_forces: out of memory for the triad\n");
    exit(1);
  }
  const long n = (long)len;
#pragma omp parallel for default(none) shared(a, b, c, n) schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i)
    a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  double best = HUGE_VAL;
  const double s = 3.0;
  for (int r = 0; r < 10; ++r) {
    double t0 = omp_get_wtime();
#pragma omp parallel for default(none) shared(a, b, c, n, s) schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    double t = omp_get_wtime() - t0;
    if (t < best) best = t;
  }
  volatile double sink = a[n / 2];
  (void)sink;
  free(a), free(b), free(c);
  return 24.0 * (double)len / best * 1e-9;
}

/* Modelled bytes per directed bond per force pass (see the header). */
static double bytes_per_bond(pdk_model_kind kind, int dim, double bonds_per_particle,
                             int breaking) {
  double per_bond = 4.0 + (breaking ? 2.0 : 0.0);
  double per_particle = 8.0 + 2.0 * dim * 8.0 + 8.0 + 2.0 * dim * 8.0 + (breaking ? 24.0 : 0.0);
  if (kind == PDK_MODEL_PMB) return per_bond + per_particle / bonds_per_particle;
  /* two passes: dilation (or N, F, A) then force */
  double first = 4.0 + (8.0 + 2.0 * dim * 8.0 + 8.0 + 8.0 + 16.0) / bonds_per_particle;
  double second = per_bond + (per_particle + 16.0) / bonds_per_particle;
  if (kind == PDK_MODEL_CORRESPONDENCE) second += 72.0 / bonds_per_particle;
  return first + second;
}

/* ---- experiment: PMB with the bond length r0 stored per bond ------------------------------------
 * Not a library kernel: the same force as kernels/ref/pmb.c (no bond state, no energy), but r0 is
 * read from a per-bond array instead of recomputed from X (3 gathers and a sqrt fewer per bond,
 * 8 bytes per bond more to stream and to hold). Selected with --model pmb-r0, to measure the trade.
 */
#define PMB_R0 ((pdk_model_kind)100)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#pragma GCC push_options
#pragma GCC target("prefer-vector-width=256")
#endif
static void pmb_r0_rows(pdk_index i0, pdk_index i1, const pdk_bond_index *restrict bs,
                        const pdk_index *restrict bj, const double *restrict r0s,
                        const double *restrict x, const double *restrict y,
                        const double *restrict z, const double *restrict V, double c, double vs_a,
                        double vs_b, double *restrict fx, double *restrict fy,
                        double *restrict fz) {
  for (pdk_index i = i0; i < i1; ++i) {
    const double xi = x[i], yi = y[i], zi = z[i];
    double f0 = 0, f1 = 0, f2 = 0;
#pragma omp simd reduction(+ : f0, f1, f2)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      const double dx = x[j] - xi, dy = y[j] - yi, dz = z[j] - zi;
      const double r0 = r0s[b], r = sqrt(dx * dx + dy * dy + dz * dz);
      const double q = r > 0.0 ? 1.0 / (r0 * r) : 0.0;
      const double t = (vs_a - r0) * vs_b;
      const double g = c * V[j] * (t < 1.0 ? t : 1.0) * (r - r0) * q;
      f0 += g * dx;
      f1 += g * dy;
      f2 += g * dz;
    }
    fx[i] = f0, fy[i] = f1, fz[i] = f2;
  }
}
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#pragma GCC pop_options
#endif

typedef struct pmb_r0_case {
  pdk_particles *p;
  pdk_families *fam;
  double *r0; /* [num_bonds] */
  double c, vs_a, vs_b;
} pmb_r0_case;

static void pmb_r0_pass(const pmb_r0_case *e, int nt) {
  const pdk_index n = pdk_particles_count(e->p);
  const pdk_bond_index *bs = pdk_families_bond_start(e->fam);
  const pdk_index *bj = pdk_families_bond_j(e->fam);
  const double *x = pdk_particles_field_data(e->p, "x", 0),
               *y = pdk_particles_field_data(e->p, "x", 1),
               *z = pdk_particles_field_data(e->p, "x", 2), *V = pdk_particles_volume(e->p);
  double *fx = pdk_particles_field_data(e->p, "f", 0), *fy = pdk_particles_field_data(e->p, "f", 1),
         *fz = pdk_particles_field_data(e->p, "f", 2);
  const double *r0 = e->r0, c = e->c, vs_a = e->vs_a, vs_b = e->vs_b;
  const int64_t nblk = ((int64_t)n + 1023) / 1024;
#pragma omp parallel for default(none) shared(nblk, n, bs, bj, r0, x, y, z, V, c, vs_a, vs_b, fx,  \
                                              fy, fz) schedule(static) num_threads(nt)
  for (int64_t blk = 0; blk < nblk; ++blk) {
    const pdk_index i0 = (pdk_index)(blk * 1024), i1 = (pdk_index)(i0 + 1024 < n ? i0 + 1024 : n);
    pmb_r0_rows(i0, i1, bs, bj, r0, x, y, z, V, c, vs_a, vs_b, fx, fy, fz);
  }
}

int main(int argc, char **argv) {
  long sides[MAX_LIST] = {46, 100};
  int num_sides = 2, threads[MAX_LIST] = {1, 2}, num_threads = 2, user_sides = 0, user_threads = 0;
  pdk_model_kind models[MAX_LIST] = {PDK_MODEL_PMB, PDK_MODEL_LPS, PDK_MODEL_CORRESPONDENCE};
  int num_models = 3, user_models = 0, repeat = 10, steps = 0;
  const char *order = "morton";
  double s00 = 0.0, triad_mib = 512.0;
  for (int k = 1; k < argc; ++k) {
    if (!strcmp(argv[k], "--side") && k + 1 < argc) {
      if (!user_sides) num_sides = 0, user_sides = 1;
      if (num_sides < MAX_LIST) sides[num_sides++] = atol(argv[++k]);
    } else if (!strcmp(argv[k], "--model") && k + 1 < argc) {
      if (!user_models) num_models = 0, user_models = 1;
      const char *m = argv[++k];
      pdk_model_kind kind = !strcmp(m, "pmb-r0") ? PMB_R0
                            : !strcmp(m, "pmb")  ? PDK_MODEL_PMB
                            : !strcmp(m, "lps")  ? PDK_MODEL_LPS
                            : !strcmp(m, "corr") || !strcmp(m, "correspondence")
                                ? PDK_MODEL_CORRESPONDENCE
                                : (pdk_model_kind)-1;
      if ((int)kind < 0) usage();
      if (num_models < MAX_LIST) models[num_models++] = kind;
    } else if (!strcmp(argv[k], "--threads") && k + 1 < argc) {
      if (!user_threads) num_threads = 0, user_threads = 1;
      if (num_threads < MAX_LIST) threads[num_threads++] = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
      repeat = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--order") && k + 1 < argc) {
      order = argv[++k];
      if (strcmp(order, "morton") && strcmp(order, "lattice")) usage();
    } else if (!strcmp(argv[k], "--s00") && k + 1 < argc) {
      s00 = atof(argv[++k]);
    } else if (!strcmp(argv[k], "--steps") && k + 1 < argc) {
      steps = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--triad-mib") && k + 1 < argc) {
      triad_mib = atof(argv[++k]);
    } else {
      usage();
    }
  }
  if (repeat < 1 || steps < 0 || num_sides < 1 || num_threads < 1) usage();

  pdk_ctx *ctx = NULL;
  char why[512];
  pdk_ctx_opts co = pdk_ctx_opts_default();
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) {
    fprintf(stderr, "bench_forces: pdk_ctx_create: %s\n", why);
    return 1;
  }

  double triad[MAX_LIST];
  const size_t triad_len = (size_t)(triad_mib * (1 << 20) / 8.0);
  for (int t = 0; t < num_threads; ++t)
    triad[t] = triad_gbs(triad_len, threads[t]);

  const double dx = 5e-4, delta = 3.015 * dx, rho = 7800.0, dt = 1e-8;
  printf("# bench_forces: simple cubic, horizon 3.015 dx, partial volumes on, order %s, s00 %g, "
         "kernels %s, %s of %d\n",
         order, s00, pdk_ctx_kernels_name(ctx), steps ? "steps" : "median pass",
         steps ? steps : repeat);
  printf("# %-6s %8s %10s %7s %3s %10s %8s %10s %7s %7s %7s %7s %8s\n", "model", "n", "bonds",
         "b/p", "thr", steps ? "s/step" : "s/pass", "ns/b/c", "Gbond/s", "B/bond", "GB/s", "triad",
         "roof%", "cpu_ns/b");
  for (int is = 0; is < num_sides; ++is) {
    const long L = sides[is];
    pdk_lattice_opts lo = pdk_lattice_opts_default();
    lo.type = PDK_LATTICE_CUBIC;
    for (int a = 0; a < 3; ++a)
      lo.lo[a] = 0.0, lo.hi[a] = (double)L * dx;
    lo.spacing = dx;
    pdk_particles *p = NULL;
    if (pdk_lattice_create(ctx, &lo, &p)) die(ctx, "lattice");
    if (!strcmp(order, "morton") &&
        pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, delta), NULL))
      die(ctx, "reorder");
    const pdk_index n = pdk_particles_count(p);
    pdk_families_opts fo = pdk_families_opts_default();
    fo.horizon = delta;
    pdk_families *fam = NULL;
    if (pdk_families_build(p, &fo, &fam)) die(ctx, "families");
    const pdk_bond_index nb = pdk_families_num_bonds(fam);
    const double bpp = (double)nb / n;

    for (int im = 0; im < num_models; ++im) {
      const int experiment = models[im] == PMB_R0;
      pmb_r0_case ex = {
          p, fam, NULL, 18.0 * 1.6e11 / (M_PI * pow(delta, 4)), delta + 0.5 * dx, 1.0 / dx};
      pdk_model_opts mo = pdk_model_opts_default();
      mo.kind = experiment ? PDK_MODEL_PMB : models[im];
      mo.bulk_modulus = 1.6e11;
      mo.shear_modulus = 0.8e11;
      mo.density = rho;
      mo.lattice_constant = dx;
      mo.critical_stretch = s00;
      pdk_model *m = NULL;
      int err = pdk_model_create(p, fam, &mo, &m);
      if (err == PDK_ERR_UNSUPPORTED) {
        printf("  %-6s (not part of this build: %s)\n", short_name(models[im]),
               pdk_ctx_error_message(ctx));
        pdk_ctx_error_clear(ctx);
        continue;
      }
      if (err) die(ctx, "model");
      if (experiment) {
        const pdk_bond_index *bs = pdk_families_bond_start(fam);
        const pdk_index *bj = pdk_families_bond_j(fam);
        ex.r0 = malloc((size_t)nb * sizeof(double));
        if (!ex.r0) die(NULL, "out of memory for r0");
        for (pdk_index i = 0; i < n; ++i)
          for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
            double d2 = 0;
            for (int a = 0; a < 3; ++a) {
              double d = pdk_particles_X(p, a)[bj[b]] - pdk_particles_X(p, a)[i];
              d2 += d * d;
            }
            ex.r0[b] = sqrt(d2);
          }
      }
      for (int it = 0; it < num_threads; ++it) {
        if (pdk_ctx_set_num_threads(ctx, threads[it])) die(ctx, "threads");
        double t_med, cpu_med;
#define FORCE_PASS()                                                                               \
  do {                                                                                             \
    if (experiment)                                                                                \
      pmb_r0_pass(&ex, threads[it]);                                                               \
    else if (pdk_model_force(m, NULL))                                                             \
      die(ctx, "force");                                                                           \
  } while (0)
        for (int w = 0; w < 2; ++w)
          FORCE_PASS();
        if (!steps) {
          double *times = malloc(2 * (size_t)repeat * sizeof *times), *cpus = times + repeat;
          for (int r = 0; r < repeat; ++r) {
            double c0 = cpu_time(), t0 = pdk_wtime();
            FORCE_PASS();
            times[r] = pdk_wtime() - t0;
            cpus[r] = cpu_time() - c0;
          }
          t_med = median(times, repeat);
          cpu_med = median(cpus, repeat) / threads[it];
          free(times);
        } else {
          /* Velocity Verlet from rest, as LAMMPS fix nve. */
          const int dim = 3, nt = threads[it];
          double *v[3], *x[3], *f[3];
          for (int a = 0; a < dim; ++a) {
            v[a] = calloc((size_t)n, sizeof(double));
            x[a] = pdk_particles_field_data(p, "x", a);
            f[a] = pdk_particles_field_data(p, "f", a);
          }
          const double h = 0.5 * dt / rho;
          double c0 = cpu_time(), t0 = pdk_wtime();
          for (int s = 0; s < steps; ++s) {
#pragma omp parallel for default(none) shared(v, x, f, n, h, dim) schedule(static) num_threads(nt)
            for (pdk_index i = 0; i < n; ++i)
              for (int a = 0; a < dim; ++a) {
                v[a][i] += h * f[a][i];
                x[a][i] += dt * v[a][i];
              }
            FORCE_PASS();
#pragma omp parallel for default(none) shared(v, f, n, h, dim) schedule(static) num_threads(nt)
            for (pdk_index i = 0; i < n; ++i)
              for (int a = 0; a < dim; ++a)
                v[a][i] += h * f[a][i];
          }
          t_med = (pdk_wtime() - t0) / steps;
          cpu_med = (cpu_time() - c0) / steps / threads[it];
          for (int a = 0; a < dim; ++a)
            free(v[a]);
          /* back to the reference state for the next thread count */
          for (int a = 0; a < dim; ++a)
            memcpy(x[a], pdk_particles_X(p, a), (size_t)n * sizeof(double));
        }
        const double bb = bytes_per_bond(mo.kind, 3, bpp, s00 > 0) + (experiment ? 8.0 : 0.0);
        const double gbs = bb * (double)nb / t_med * 1e-9;
        printf("  %-6s %8d %10lld %7.2f %3d %10.5f %8.3f %10.4f %7.2f %7.2f %7.2f %7.1f %8.3f\n",
               short_name(models[im]), (int)n, (long long)nb, bpp, threads[it], t_med,
               t_med * threads[it] / (double)nb * 1e9, (double)nb / t_med * 1e-9, bb, gbs,
               triad[it], 100.0 * gbs / triad[it], cpu_med * threads[it] / (double)nb * 1e9);
        fflush(stdout);
      }
      pdk_model_destroy(&m);
      free(ex.r0);
    }
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
