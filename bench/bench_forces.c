/* Force-loop benchmark: one force pass of the PMB, LPS (and correspondence, when that model is part
 * of the build) models on a free simple-cubic cube of side L (L^3 particles), horizon 3.015
 * spacings, LAMMPS partial volumes on (lattice constant = spacing), no bond breaking, particles in
 * the order pdk_sim_create gives a scene (--order auto, the default: Morton order of the family
 * cells, and the lattice's rows for the correspondence stencil rows), or all in Morton order
 * (--order morton) or in the lattice's generation order (--order lattice). Each configuration is
 * timed R times after two warm-up passes; the median is reported, per thread count.
 *
 *   bench_forces [--side L]... [--plate L]... [--model pmb|lps|corr|pmb-r0]... [--threads T]...
 *                [--repeat R] [--order auto|morton|lattice] [--s00 S] [--steps N] [--triad-mib M]
 *                [--kernels ref|simd|avx2|avx512]... [--precision double|float]...
 *                [--law linear|svk|neo_hooke] [--stab none|silling|hourglass]
 *                [--layout csr|csrc|sell|stencil]... [--sell-sigma S]
 *
 * --plate L: also a 2-D plane-strain square plate of L x L particles (square lattice, the same
 *   spacing and horizon ratio, thickness one spacing). --kernels: run everything with each kernel
 *   family in turn (default: the context's, PDK_KERNELS). --precision: storage precision of the
 *   models (a kind that refuses one is reported and skipped). --law, --stab: correspondence law
 *   (default linear) and stabilization (default none; Silling and hourglass with C_s = 0.1).
 *
 * --layout: csr (default), the general path over the CSR families; sell, the PMB and LPS passes
 *   over the sliced SELL-C-sigma layout (model layout sell, src/space/sell.h); stencil, the PMB and LPS
 *   stencil path (model stencil on: bond offsets outside, runs of lattice sites inside,
 *   src/models/model_stencil.c; for corr the correspondence stencil passes, kernels/opt/corr_stencil.h);
 *   repeatable, so they run side by side on the same lattice (each configuration with each layout
 *   in turn). Other models skip sell and stencil (corr skips sell). csr runs PMB and LPS with the
 *   library's default bond_lengths stored (the reference length of each bond kept, 8 B per bond,
 *   counted in B/bond once per bond loop); csrc is csr with bond_lengths computed (recomputed every
 *   pass, the csr of earlier versions); only PMB and LPS run csrc.
 *   --sell-sigma S: the sell sorting window in particles (0, the default: 32 C). The `pad%` column
 *   gives the padding share of the sell entries (0 otherwise).
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
 * Correspondence (corr_bytes_per_bond): per sweep and bond, bond_j 4 B and the influence weight
 * 8 B; per particle, pass 1 reads bond_start, X, x, V, K^-1 and writes F, A, W, flag (and, for the
 * optimized kernels or float storage, the pass-2 data B [, G], k), pass 2 reads bond_start, X, x,
 * V, A, F, W, its own pass-2 data and writes f, W; writes count twice (write-allocate). Triad
 * bytes follow STREAM: 24 B per element, write-allocate not counted.
 */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pdk/pdk.h"

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
  fprintf(
      stderr,
      "usage: bench_forces [--side L]... [--plate L]... [--model pmb|lps|corr]...\n"
      "                    [--threads T]... [--repeat R] [--order auto|morton|lattice] [--s00 S]\n"
      "                    [--steps N] [--triad-mib M] [--kernels ref|simd|avx2|avx512]...\n"
      "                    [--precision double|float]... [--law linear|svk|neo_hooke]\n"
      "                    [--stab none|silling|hourglass] [--layout csr|csrc|sell|stencil]...\n"
      "                    [--sell-sigma S]\n");
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

/* PMB stencil path: no index stream; per bond the mask byte read and written when breaking is on;
 * per particle x read and copied to its site (written, write-allocate), the site's X, x, V read,
 * f written (write-allocate), and with breaking s0 read, copied to the site, s0_next written. */
static double stencil_bytes_per_bond(pdk_model_kind kind, int dim, double bonds_per_particle,
                                     int breaking) {
  const double per_bond = breaking ? 2.0 : 0.0;
  const double per_particle = dim * 8.0 + 2.0 * dim * 8.0 + (2.0 * dim * 8.0 + 8.0) +
                              2.0 * dim * 8.0 + (breaking ? 8.0 + 16.0 + 16.0 : 0.0);
  if (kind != PDK_MODEL_LPS) return per_bond + per_particle / bonds_per_particle;
  /* LPS: the dilation sweep reads the sites' X, x, V, 1/m and writes theta (site and particle,
   * write-allocate); the force sweep reads theta and 1/m per site too */
  const double dil = 2.0 * dim * 8.0 + 8.0 + 8.0 + 2.0 * 2.0 * 8.0;
  return (breaking ? 2.0 : 0.0) + (per_particle + dil + 16.0) / bonds_per_particle;
}

/* Correspondence stencil path, modelled compulsory bytes per directed bond (both sweeps, every
 * site's data read once per sweep, i.e. the neighbour planes stay in cache): per particle x, X
 * read and u written to its site (write-allocate); pass 1 the site's u, V, K^-1, m, flag read,
 * F, A, W written (write-allocate), B and k written per site (and the float copy); pass 2 the
 * site's u, V, k, B (double for the own term, the float copy for neighbours) read, f written;
 * with a mask 1 byte per bond and sweep. */
static double corr_stencil_bytes_per_bond(int dim, double bpp, int fl, int masked) {
  const double dd = dim * dim;
  const double scatter = 2.0 * dim * 8.0 + 2.0 * dim * 8.0;
  const double p1 = (dim + 1) * 8.0 + dd * 8.0 + 8.0 + 1.0 + 2.0 * (2.0 * dd * 8.0 + 8.0) +
                    2.0 * (dd * 8.0 + 8.0) + (fl ? 2.0 * dd * 4.0 : 0.0);
  const double p2 = (dim + 2) * 8.0 + dd * 8.0 + (fl ? dd * 4.0 : 0.0) + 2.0 * dim * 8.0;
  return (masked ? 2.0 : 0.0) + (scatter + p1 + p2) / bpp;
}

/* Correspondence, modelled compulsory bytes per directed bond for one force pass (both sweeps). */
static double corr_bytes_per_bond(int dim, double bpp, int stab, int fl, int opt) {
  const double dd = dim * dim;
  const unsigned layout = (stab ? 1u : 0u) |
                          (fl ? 8u | (stab == 2 ? 16u : 0u)
                              : (opt ? (stab == 1 ? 2u : 0u) | (stab == 2 ? 4u : 0u) : 0u));
  const double pair = ((layout & 1u) ? 8.0 : 0.0) + ((layout & 2u) ? 8.0 * dd : 0.0) +
                      ((layout & 4u) ? 8.0 * dd : 0.0) + ((layout & 8u) ? 4.0 * dd : 0.0) +
                      ((layout & 16u) ? 4.0 * dd : 0.0);
  const double own = 8.0 + 2.0 * dim * 8.0 + 8.0; /* bond_start, X, x, V */
  const double p1 = own + 8.0 * dd + 2.0 * (2.0 * 8.0 * dd + 8.0 + 1.0 + pair);
  const double p2 = own + 2.0 * 8.0 * dd + 8.0 + pair + 2.0 * (dim * 8.0 + 8.0);
  return 2.0 * (4.0 + 8.0) + (p1 + p2) / bpp;
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

/* ---- in-core bound ---------------------------------------------------------------------------
 * What the core needs per bond if memory were free: the loops' operations per directed bond
 * (counted from the SIMD kernels' source, 3-D, no bond state, no energy; lane operations, an FMA
 * counted once) times the time this CPU takes per operation, measured here at the kernels' vector
 * width (the bench/bench_ops harness: 4 independent accumulators over an L1-resident array for the
 * square root and the division, 8 independent FMA chains for the other FP operations; process
 * CPU time per instruction, median of 5, so other jobs' turns do not count):
 *   bound = max(n_sqrt t_sqrt + n_div t_div, n_fp t_fp)   [ns per bond]
 * the first term the divide/square-root unit (one per core, not pipelined, shared by both), the
 * second the FP pipes. Loads, gathers, row transposes and shuffles are not counted (the bound
 * errs low where they dominate: correspondence). Counts (sqrt, div, fp):
 *   PMB csr (lengths stored), stencil 1, 1, 24; csr lengths computed (csrc), sell 2, 1, 32
 *   LPS csr (stored), stencil 2, 1, 44 (dilation 1, 0, 15 + force 1, 1, 29); csrc, sell 4, 1, 60
 *   correspondence (Silling) csr 0, 0, 70 (pass 1 19, pass 2 51); stencil 0, 0, 64
 * core% = 100 bound / cpu_ns/b: the share of the in-core bound the loop reaches. */
typedef struct op_ns {
  int width;                  /* doubles per vector; 0: not measured (printed as -) */
  double sqrt_, div_, fp;     /* ns per double */
} op_ns;

static double thread_cpu(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,avx2,fma")
static double op_in[1024] __attribute__((aligned(64)));
static volatile double op_sink;
#define OP_BODY(name, T, W, load, add, zero, set1, store, expr)                                    \
  static double name(long reps) {                                                                  \
    T s0 = zero(), s1 = s0, s2 = s0, s3 = s0;                                                      \
    const T one = set1(1.0);                                                                       \
    (void)one;                                                                                     \
    const double t0 = thread_cpu();                                                                \
    for (long r = 0; r < reps; ++r)                                                                \
      for (int k = 0; k < 1024; k += 4 * W) {                                                      \
        T a = load(op_in + k);                                                                     \
        s0 = add(s0, (expr));                                                                      \
        a = load(op_in + k + W);                                                                   \
        s1 = add(s1, (expr));                                                                      \
        a = load(op_in + k + 2 * W);                                                               \
        s2 = add(s2, (expr));                                                                      \
        a = load(op_in + k + 3 * W);                                                               \
        s3 = add(s3, (expr));                                                                      \
      }                                                                                            \
    const double t = thread_cpu() - t0;                                                            \
    double o[8];                                                                                   \
    store(o, add(add(s0, s1), add(s2, s3)));                                                       \
    op_sink = o[0];                                                                                \
    return 1e9 * t / ((double)reps * 1024);                                                        \
  }
#define OP_FMA(name, T, W, fma, set1, store)                                                       \
  static double name(long reps) {                                                                  \
    T c[8];                                                                                        \
    for (int l = 0; l < 8; ++l) c[l] = set1(1.0 + l);                                              \
    const T m = set1(0.999999), p = set1(1e-7);                                                    \
    const double t0 = thread_cpu();                                                                \
    for (long r = 0; r < reps * 64; ++r)                                                           \
      for (int l = 0; l < 8; ++l) c[l] = fma(c[l], m, p);                                          \
    const double t = thread_cpu() - t0;                                                            \
    double o[8];                                                                                   \
    store(o, c[0] + c[7]);                                                                         \
    op_sink = o[0];                                                                                \
    return 1e9 * t / ((double)reps * 64 * 8 * W);                                                  \
  }
OP_BODY(op_sqrt8, __m512d, 8, _mm512_load_pd, _mm512_add_pd, _mm512_setzero_pd, _mm512_set1_pd,
        _mm512_storeu_pd, _mm512_sqrt_pd(a))
OP_BODY(op_div8, __m512d, 8, _mm512_load_pd, _mm512_add_pd, _mm512_setzero_pd, _mm512_set1_pd,
        _mm512_storeu_pd, _mm512_div_pd(one, a))
OP_FMA(op_fma8, __m512d, 8, _mm512_fmadd_pd, _mm512_set1_pd, _mm512_storeu_pd)
OP_BODY(op_sqrt4, __m256d, 4, _mm256_load_pd, _mm256_add_pd, _mm256_setzero_pd, _mm256_set1_pd,
        _mm256_storeu_pd, _mm256_sqrt_pd(a))
OP_BODY(op_div4, __m256d, 4, _mm256_load_pd, _mm256_add_pd, _mm256_setzero_pd, _mm256_set1_pd,
        _mm256_storeu_pd, _mm256_div_pd(one, a))
OP_FMA(op_fma4, __m256d, 4, _mm256_fmadd_pd, _mm256_set1_pd, _mm256_storeu_pd)
#pragma GCC pop_options

static double op_median5(double (*f)(long), long reps) {
  double t[5];
  for (int k = 0; k < 5; ++k) t[k] = f(reps);
  return median(t, 5);
}

/* The operation times at the width of the context's bond kernels (AVX-512: 8, AVX2: 4). */
static op_ns measure_ops(const pdk_ctx *ctx) {
  op_ns o = {0, 0, 0, 0};
  const char *kn = pdk_ctx_kernels_name(ctx);
  const unsigned isa = pdk_ctx_isa(ctx);
  const int w = !strcmp(kn, "avx2") ? 4
                : !strcmp(kn, "avx512") || !strcmp(kn, "simd") ? (isa & PDK_ISA_AVX512 ? 8
                                                                  : isa & PDK_ISA_AVX2 ? 4 : 0)
                                                               : 0;
  if (!w) return o;
  for (int k = 0; k < 1024; ++k) op_in[k] = 1.0 + (double)k / 1024.0;
  o.width = w;
  o.sqrt_ = op_median5(w == 8 ? op_sqrt8 : op_sqrt4, 2000);
  o.div_ = op_median5(w == 8 ? op_div8 : op_div4, 2000);
  o.fp = op_median5(w == 8 ? op_fma8 : op_fma4, 2000);
  return o;
}
#else
static op_ns measure_ops(const pdk_ctx *ctx) {
  (void)ctx;
  op_ns o = {0, 0, 0, 0};
  return o;
}
#endif

/* The in-core bound in ns per directed bond (see above), 0 when not modelled (2-D, ref kernels,
 * other stabilizations). layout 0 csr, 1 sell, 2 stencil. */
static double incore_bound(const op_ns *o, pdk_model_kind kind, int layout, int computed,
                           int stab, int dim) {
  if (!o->width || dim != 3) return 0.0;
  double ns = 0, nd = 0, nf = 0;
  if (kind == PDK_MODEL_PMB) {
    const int full = layout == 1 || (layout == 0 && computed);
    ns = full ? 2 : 1, nd = 1, nf = full ? 32 : 24;
  } else if (kind == PDK_MODEL_LPS) {
    const int full = layout == 1 || (layout == 0 && computed);
    ns = full ? 4 : 2, nd = 1, nf = full ? 60 : 44;
  } else if (kind == PDK_MODEL_CORRESPONDENCE && stab == PDK_STAB_SILLING) {
    nf = layout == 2 ? 64 : 70;
  } else {
    return 0.0;
  }
  const double unit = ns * o->sqrt_ + nd * o->div_, pipes = nf * o->fp;
  return unit > pipes ? unit : pipes;
}

/* 1 when the model stores the double bond lengths (pdk_bond_lengths): PMB and LPS, precision
 * double, layout csr, bond_lengths stored, SIMD kernels. */
static int r0_stored(pdk_model_kind kind, pdk_precision prec, int layout, int computed,
                     pdk_ctx *ctx) {
  return (kind == PDK_MODEL_PMB || kind == PDK_MODEL_LPS) && prec == PDK_PRECISION_DOUBLE &&
         layout == 0 && !computed && strcmp(pdk_ctx_kernels_name(ctx), "ref") != 0;
}
/* Bond loops per force pass: LPS makes two (dilation, force). */
static double passes(pdk_model_kind kind) { return kind == PDK_MODEL_LPS ? 2.0 : 1.0; }

int main(int argc, char **argv) {
  long sides[MAX_LIST] = {46, 100};
  int num_sides = 2, threads[MAX_LIST] = {1, 2}, num_threads = 2, user_sides = 0, user_threads = 0;
  pdk_model_kind models[MAX_LIST] = {PDK_MODEL_PMB, PDK_MODEL_LPS, PDK_MODEL_CORRESPONDENCE};
  int num_models = 3, user_models = 0, repeat = 10, steps = 0;
  const char *order = "auto";
  double s00 = 0.0, triad_mib = 512.0;
  long plates[MAX_LIST];
  int num_plates = 0, num_kernels = 0, num_prec = 1, user_prec = 0;
  const char *kernels[MAX_LIST] = {NULL};
  pdk_precision precs[MAX_LIST] = {PDK_PRECISION_DOUBLE};
  pdk_law law = PDK_LAW_LINEAR_ELASTIC;
  pdk_stabilization stab = PDK_STAB_NONE;
  /* 0 csr, 1 sell, 2 stencil, 3 csrc (csr with bond_lengths computed) */
  int layouts[MAX_LIST] = {0}, num_layouts = 1, user_layouts = 0;
  int sell_sigma = 0;
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
      if (strcmp(order, "auto") && strcmp(order, "morton") && strcmp(order, "lattice")) usage();
    } else if (!strcmp(argv[k], "--s00") && k + 1 < argc) {
      s00 = atof(argv[++k]);
    } else if (!strcmp(argv[k], "--steps") && k + 1 < argc) {
      steps = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--plate") && k + 1 < argc) {
      if (num_plates < MAX_LIST) plates[num_plates++] = atol(argv[++k]);
    } else if (!strcmp(argv[k], "--kernels") && k + 1 < argc) {
      if (num_kernels < MAX_LIST) kernels[num_kernels++] = argv[++k];
    } else if (!strcmp(argv[k], "--precision") && k + 1 < argc) {
      if (!user_prec) num_prec = 0, user_prec = 1;
      const char *v = argv[++k];
      if (strcmp(v, "double") && strcmp(v, "float")) usage();
      if (num_prec < MAX_LIST)
        precs[num_prec++] = !strcmp(v, "float") ? PDK_PRECISION_FLOAT : PDK_PRECISION_DOUBLE;
    } else if (!strcmp(argv[k], "--law") && k + 1 < argc) {
      const char *v = argv[++k];
      law = !strcmp(v, "linear")      ? PDK_LAW_LINEAR_ELASTIC
            : !strcmp(v, "svk")       ? PDK_LAW_SVK
            : !strcmp(v, "neo_hooke") ? PDK_LAW_NEO_HOOKE
                                      : (pdk_law)-1;
      if ((int)law < 0) usage();
    } else if (!strcmp(argv[k], "--stab") && k + 1 < argc) {
      const char *v = argv[++k];
      stab = !strcmp(v, "none")        ? PDK_STAB_NONE
             : !strcmp(v, "silling")   ? PDK_STAB_SILLING
             : !strcmp(v, "hourglass") ? PDK_STAB_HOURGLASS
                                       : (pdk_stabilization)-1;
      if ((int)stab < 0) usage();
    } else if (!strcmp(argv[k], "--layout") && k + 1 < argc) {
      if (!user_layouts) num_layouts = 0, user_layouts = 1;
      const char *v = argv[++k];
      if (strcmp(v, "csr") && strcmp(v, "sell") && strcmp(v, "stencil") && strcmp(v, "csrc"))
        usage();
      if (num_layouts < MAX_LIST)
        layouts[num_layouts++] = !strcmp(v, "sell")      ? 1
                                 : !strcmp(v, "stencil") ? 2
                                 : !strcmp(v, "csrc")    ? 3
                                                         : 0;
    } else if (!strcmp(argv[k], "--sell-sigma") && k + 1 < argc) {
      sell_sigma = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--triad-mib") && k + 1 < argc) {
      triad_mib = atof(argv[++k]);
    } else {
      usage();
    }
  }
  if (repeat < 1 || steps < 0 || num_sides + num_plates < 1 || num_threads < 1) usage();
  if (user_sides == 0 && num_plates > 0) num_sides = 0; /* --plate alone: plates only */
  if (num_kernels == 0) num_kernels = 1;                /* kernels[0] NULL: the default */

  pdk_ctx *ctx0 = NULL; /* the default kernels: only to check that a context can be made */
  char why[512];
  pdk_ctx_opts co = pdk_ctx_opts_default();
  if (pdk_ctx_create(&co, &ctx0, why, sizeof why)) {
    fprintf(stderr, "bench_forces: pdk_ctx_create: %s\n", why);
    return 1;
  }
  static const char *const law_name[] = {"linear", "svk", "neo_hooke"};
  static const char *const stab_name[] = {"none", "silling", "hourglass"};

  double triad[MAX_LIST];
  const size_t triad_len = (size_t)(triad_mib * (1 << 20) / 8.0);
  for (int t = 0; t < num_threads; ++t)
    triad[t] = triad_gbs(triad_len, threads[t]);

  const double dx = 5e-4, delta = 3.015 * dx, rho = 7800.0, dt = 1e-8;
  printf("# bench_forces: simple cubic cube (3-D) / square plate (2-D), horizon 3.015 dx, partial "
         "volumes on, order %s, s00 %g, %s of %d; corr: law %s, stabilization %s\n",
         order, s00, steps ? "steps" : "median pass", steps ? steps : repeat, law_name[law],
         stab_name[stab]);
  printf("# %-6s %-6s %-6s %-7s %2s %8s %10s %7s %3s %10s %8s %10s %7s %7s %7s %7s %8s %6s %7s "
         "%6s\n",
         "model", "kern", "prec", "layout", "d", "n", "bonds", "b/p", "thr",
         steps ? "s/step" : "s/pass", "ns/b/c", "Gbond/s", "B/bond", "GB/s", "triad", "roof%",
         "cpu_ns/b", "pad%", "core_ns", "core%");
  pdk_ctx *kctx = NULL;
  for (int ik = 0; ik < num_kernels; ++ik)
  for (int is = 0; is < num_sides + num_plates; ++is) {
    const int dim = is < num_sides ? 3 : 2;
    const long L = is < num_sides ? sides[is] : plates[is - num_sides];
    if (is == 0) {
      pdk_ctx_destroy(&kctx);
      pdk_ctx_opts ko = pdk_ctx_opts_default();
      ko.kernels = kernels[ik];
      if (pdk_ctx_create(&ko, &kctx, why, sizeof why)) {
        fprintf(stderr, "bench_forces: kernels %s: %s\n", kernels[ik], why);
        return 1;
      }
    }
    pdk_ctx *ctx = kctx;
    static op_ns ops;
    if (is == 0) {
      ops = measure_ops(ctx);
      if (ops.width)
        printf("# in-core: %s kernels, %d doubles per vector: sqrt %.3f, div %.3f, fp op %.4f ns per "
               "double (CPU time)\n",
               pdk_ctx_kernels_name(ctx), ops.width, ops.sqrt_, ops.div_, ops.fp);
    }
    pdk_lattice_opts lo = pdk_lattice_opts_default();
    lo.type = dim == 3 ? PDK_LATTICE_CUBIC : PDK_LATTICE_SQUARE;
    for (int a = 0; a < 3; ++a)
      lo.lo[a] = 0.0, lo.hi[a] = a < dim ? (double)L * dx : dx;
    lo.spacing = dx;
    lo.thickness = dx;
    /* the particle sets: [0] Morton (lattice with --order lattice), [1] rows, built when a
     * correspondence stencil configuration first needs it (--order auto) */
    pdk_particles *sets_p[2] = {NULL, NULL};
    pdk_families *sets_fam[2] = {NULL, NULL};
    pdk_families_opts fo = pdk_families_opts_default();
    fo.horizon = delta;
    if (pdk_lattice_create(ctx, &lo, &sets_p[0])) die(ctx, "lattice");
    if (strcmp(order, "lattice") &&
        pdk_particles_reorder_morton(sets_p[0], pdk_families_cell_edge(sets_p[0], delta), NULL))
      die(ctx, "reorder");
    if (pdk_families_build(sets_p[0], &fo, &sets_fam[0])) die(ctx, "families");
    const pdk_index n = pdk_particles_count(sets_p[0]);
    const pdk_bond_index nb = pdk_families_num_bonds(sets_fam[0]);
    const double bpp = (double)nb / n;

    for (int iml = 0; iml < num_models * num_prec * num_layouts; ++iml) {
      const int im = iml / num_layouts, layout_arg = layouts[iml % num_layouts];
      const int computed = layout_arg == 3, layout = computed ? 0 : layout_arg;
      static const char *const layout_name[] = {"csr", "sell", "stencil", "csrc"};
      const int stencil = layout == 2;
      const pdk_precision prec = precs[im % num_prec];
      const int experiment = models[im / num_prec] == PMB_R0;
      if (computed && (experiment || (models[im / num_prec] != PDK_MODEL_PMB &&
                                      models[im / num_prec] != PDK_MODEL_LPS)))
        continue;
      if (layout &&
          (experiment ||
           (models[im / num_prec] != PDK_MODEL_PMB && models[im / num_prec] != PDK_MODEL_LPS &&
            !(stencil && models[im / num_prec] == PDK_MODEL_CORRESPONDENCE))))
        continue;
      if (experiment && prec != PDK_PRECISION_DOUBLE) continue;
      if (experiment && dim != 3) continue;
      /* --order auto: the correspondence stencil path on particles in row order, as pdk_sim_create
       * numbers a scene that takes it */
      const int rows =
          !strcmp(order, "auto") && stencil && models[im / num_prec] == PDK_MODEL_CORRESPONDENCE;
      if (rows && !sets_p[1]) {
        if (pdk_lattice_create(ctx, &lo, &sets_p[1])) die(ctx, "lattice");
        if (pdk_particles_reorder_rows(sets_p[1], dx, NULL)) die(ctx, "reorder");
        if (pdk_families_build(sets_p[1], &fo, &sets_fam[1])) die(ctx, "families");
      }
      pdk_particles *p = sets_p[rows];
      pdk_families *fam = sets_fam[rows];
      pmb_r0_case ex = {
          p, fam, NULL, 18.0 * 1.6e11 / (M_PI * pow(delta, 4)), delta + 0.5 * dx, 1.0 / dx};
      pdk_model_opts mo = pdk_model_opts_default();
      mo.kind = experiment ? PDK_MODEL_PMB : models[im / num_prec];
      mo.precision = prec;
      if (mo.kind == PDK_MODEL_CORRESPONDENCE) mo.law = law, mo.stabilization = stab;
      mo.bulk_modulus = 1.6e11;
      mo.shear_modulus = 0.8e11;
      mo.density = rho;
      mo.lattice_constant = dx;
      mo.critical_stretch = s00;
      mo.stencil = stencil ? PDK_STENCIL_ON : PDK_STENCIL_OFF;
      mo.layout = layout == 1 ? PDK_LAYOUT_SELL : PDK_LAYOUT_CSR;
      mo.sell_sigma = sell_sigma;
      mo.bond_lengths = computed ? PDK_BOND_LENGTHS_COMPUTED : PDK_BOND_LENGTHS_STORED;
      if (dim == 2) mo.thickness = lo.thickness;
      pdk_model *m = NULL;
      int err = pdk_model_create(p, fam, &mo, &m);
      if (err == PDK_ERR_UNSUPPORTED) {
        printf("  %-6s %-6s %-6s %-7s (unsupported: %s)\n", short_name(models[im / num_prec]),
               pdk_ctx_kernels_name(ctx), prec == PDK_PRECISION_FLOAT ? "float" : "double",
               layout_name[layout_arg], pdk_ctx_error_message(ctx));
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
          const int nt = threads[it];
          double *v[3], *x[3], *f[3];
          for (int a = 0; a < dim; ++a) {
            v[a] = calloc((size_t)n, sizeof(double));
            x[a] = pdk_particles_field_data(p, "x", a);
            f[a] = pdk_particles_field_data(p, "f", a);
          }
          const double h = 0.5 * dt / rho;
          double c0 = cpu_time(), t0 = pdk_wtime();
          for (int s = 0; s < steps; ++s) {
#pragma omp parallel for default(none) shared(v, x, f, n, h, dt, dim) schedule(static) num_threads(nt)
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
        const double bb =
            mo.kind == PDK_MODEL_CORRESPONDENCE && stencil
                ? corr_stencil_bytes_per_bond(dim, bpp, prec == PDK_PRECISION_FLOAT, s00 > 0)
            : mo.kind == PDK_MODEL_CORRESPONDENCE
                ? corr_bytes_per_bond(dim, bpp, (int)stab, prec == PDK_PRECISION_FLOAT,
                                      strcmp(pdk_ctx_kernels_name(ctx), "ref") != 0)
            : stencil ? stencil_bytes_per_bond(mo.kind, dim, bpp, s00 > 0)
                      : bytes_per_bond(mo.kind, dim, bpp, s00 > 0) + (experiment ? 8.0 : 0.0) +
                            (r0_stored(mo.kind, prec, layout, computed, ctx) ? 8.0 * passes(mo.kind)
                                                                             : 0.0);
        const double gbs = bb * (double)nb / t_med * 1e-9;
        const double core =
            experiment ? 0.0 : incore_bound(&ops, mo.kind, layout, computed, (int)stab, dim);
        const double cpu_nsb = cpu_med * threads[it] / (double)nb * 1e9;
        char core_s[16] = "-", corep_s[16] = "-";
        if (core > 0)
          snprintf(core_s, sizeof core_s, "%.3f", core),
              snprintf(corep_s, sizeof corep_s, "%.1f", 100.0 * core / cpu_nsb);
        printf("  %-6s %-6s %-6s %-7s %2d %8d %10lld %7.2f %3d %10.5f %8.3f %10.4f %7.2f %7.2f "
               "%7.2f %7.1f %8.3f %6.3f %7s %6s\n",
               short_name(mo.kind == PDK_MODEL_PMB && experiment ? PMB_R0 : mo.kind),
               pdk_ctx_kernels_name(ctx), prec == PDK_PRECISION_FLOAT ? "float" : "double",
               layout_name[layout_arg], dim,
               (int)n, (long long)nb, bpp, threads[it], t_med,
               t_med * threads[it] / (double)nb * 1e9, (double)nb / t_med * 1e-9, bb, gbs,
               triad[it], 100.0 * gbs / triad[it], cpu_nsb, 100.0 * pdk_model_padding_fraction(m),
               core_s, corep_s);
        fflush(stdout);
      }
      pdk_model_destroy(&m);
      free(ex.r0);
    }
    for (int k = 0; k < 2; ++k) {
      pdk_families_destroy(&sets_fam[k]);
      pdk_particles_destroy(&sets_p[k]);
    }
  }
  pdk_ctx_destroy(&kctx);
  pdk_ctx_destroy(&ctx0);
  return 0;
}
