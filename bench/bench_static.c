/* Static solvers: time to solution of ADR and Newton against problem size, and the memory of the
 * Newton tangent and factor.
 *
 * Problems (both with an analytical solution, printed as a sanity column):
 *   2-D  the V-Q uniaxial block (Queiruga & Moridis 2017 section 4.1): NP x NP node grid on a
 *        10 mm square, bottom clamped, sides on rollers, top traction as a body force; correspondence, cubic
 *        influence, RF 1.5, small-strain law; E = 1000, nu = 0, T = 1 (strain 1e-3).
 *   3-D  the same in a cube: bottom face clamped, the four sides on rollers (normal component),
 *        top traction; correspondence with Silling stabilization, RF 1.5 (18 neighbours).
 * ADR stops at rtol 1e-6 (its default), Newton at 1e-10 (its default); both are timed from
 * creation (coloring, fictitious mass, pattern) to the converged state.
 *
 * --model pmb|lps replaces the correspondence model by PMB or LPS (K = E/3, G = E/2, so LPS has
 * nu = 0 like the correspondence problems; PMB fixes nu = 1/4: the sanity column then compares
 * with -T H / M, M = 3E/5 the constrained modulus lambda + 2 mu of that material), and
 * --tangent analytic|difference|both picks Newton's tangent (both: the two runs side by side, the
 * analytic one first; default: the solver's auto). --rf R changes the ratio horizon / spacing.
 *
 * Usage: bench_static [--dim 2|3] [--sizes a,b,c] [--method adr|newton|both] [--threads t]
 *                     [--mass auto|rowsum|lanczos] (ADR fictitious mass) [--repeat r]
 *                     [--model corr|pmb|lps] [--tangent auto|analytic|difference|both] [--rf R]
 *   defaults: 2-D NP 32,64,128 and 3-D n 10,14,20 (cubes of (n+1)^3 nodes), both methods.
 *   --newton-max N skips Newton above N particles (default 70000 in 2-D, 5000 in 3-D: the 3-D
 *   Cholesky factor grows as n^(4/3) and the netlib BLAS on this machine makes it slow).
 * Output: one line per run (see the header line): phase times (wall) from the solver's stats,
 * total wall and process CPU time (all threads) from creation to solution, tangent (K) and factor
 * (L) memory, nonzeros per tangent row, peak resident memory of the process so far, and the
 * relative error of the probe against -T H / E. Results are recorded in bench/README.md.
 */
#include <math.h>
#include <stdio.h>
#include <sys/resource.h>
#include <stdlib.h>
#include <string.h>

#include "pdk/pdk.h"

#define CHECK(ctx, expr)                                                                           \
  do {                                                                                             \
    int err_ = (expr);                                                                             \
    if (err_) {                                                                                    \
      fprintf(stderr, "%s failed: %s\n", #expr, pdk_ctx_error_message(ctx));                       \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

typedef struct run_result {
  pdk_index n;
  double wall, cpu, probe_error;
  pdk_static_stats st;
  size_t peak;
} run_result;

/* Process CPU time (user + system, all threads) in seconds: less sensitive than wall time to other
 * jobs on a shared machine. */
static double cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static run_result run(pdk_ctx *ctx, int dim, int np, pdk_static_method method, pdk_adr_mass mass,
                      pdk_model_kind kind, pdk_tangent_kind tangent, double rf) {
  const double W = 10.0, E = 1000.0, T = 1.0, h = W / np;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  lo.node_type = 1;
  lo.spacing = h;
  for (int a = 0; a < 3; ++a)
    lo.hi[a] = W;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  CHECK(ctx, pdk_lattice_create(ctx, &lo, &p));
  CHECK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, rf * h), NULL));
  const int up = dim - 1; /* the loaded axis */
  const double e = 0.25 * h, big = 2 * W;
  /* bottom (up = 0) clamped; sides: the other axes' end faces above the bottom, on rollers */
  double b0[3] = {-big, -big, -big}, b1[3] = {big, big, big};
  b1[up] = e;
  pdk_region bottom = pdk_region_box(b0, b1);
  CHECK(ctx, pdk_particles_set_define(p, "bottom", &bottom, NULL));
  const char *side_names[2][2] = {{"side0lo", "side0hi"}, {"side1lo", "side1hi"}};
  for (int a = 0; a < dim - 1; ++a)
    for (int hi = 0; hi < 2; ++hi) {
      double s0[3] = {-big, -big, -big}, s1[3] = {big, big, big};
      s0[up] = e;
      if (hi)
        s0[a] = W - e;
      else
        s1[a] = e;
      pdk_region side = pdk_region_box(s0, s1);
      CHECK(ctx, pdk_particles_set_define(p, side_names[a][hi], &side, NULL));
    }
  double t0[3] = {-big, -big, -big}, t1[3] = {big, big, big};
  t0[up] = W - e;
  pdk_region top = pdk_region_box(t0, t1);
  pdk_index n_top;
  CHECK(ctx, pdk_particles_set_define(p, "top", &top, &n_top));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf * h;
  CHECK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = E / 3.0;
  mo.shear_modulus = E / 2.0;
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = dim == 3 ? PDK_STAB_SILLING : PDK_STAB_NONE;
  CHECK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_bc bcs[6];
  memset(bcs, 0, sizeof bcs);
  int nb = 0;
  bcs[nb].kind = PDK_BC_DISPLACEMENT;
  bcs[nb].set = "set:bottom";
  bcs[nb++].components = dim == 3 ? 7u : 3u;
  char names[2][2][32];
  for (int a = 0; a < dim - 1; ++a)
    for (int hi = 0; hi < 2; ++hi) {
      snprintf(names[a][hi], sizeof names[a][hi], "set:%s", side_names[a][hi]);
      bcs[nb].kind = PDK_BC_DISPLACEMENT;
      bcs[nb].set = names[a][hi];
      bcs[nb++].components = 1u << a;
    }
  const double area = dim == 3 ? W * W : W;
  bcs[nb].kind = PDK_BC_BODY_FORCE;
  bcs[nb].set = "set:top";
  bcs[nb].components = 1u << up;
  bcs[nb++].value[up] = pdk_tfun_constant(-T * area / (n_top * pdk_particles_volume(p)[0]));
  pdk_static_opts so = pdk_static_opts_default(method);
  so.bcs = bcs;
  so.num_bcs = nb;
  so.adr_mass = mass;
  so.tangent = tangent;
  run_result r;
  memset(&r, 0, sizeof r);
  r.n = pdk_particles_count(p);
  const double w0 = pdk_wtime(), c0 = cpu_seconds();
  pdk_static *s;
  CHECK(ctx, pdk_static_create(m, &so, &s));
  CHECK(ctx, pdk_static_solve(s));
  r.wall = pdk_wtime() - w0;
  r.cpu = cpu_seconds() - c0;
  r.st = *pdk_static_stats_get(s);
  r.peak = pdk_peak_memory_bytes();
  /* probe: mean top displacement over the middle fifth, against -T H / E */
  const double *x = pdk_particles_field_data(p, "x", up), *X = pdk_particles_X(p, up);
  const uint8_t *in_top = pdk_particles_field_data(p, "set:top", 0);
  double sum = 0.0;
  int count = 0;
  for (pdk_index i = 0; i < r.n; ++i) {
    if (!in_top[i]) continue;
    int mid = 1;
    for (int a = 0; a < dim - 1; ++a) {
      const double xa = pdk_particles_X(p, a)[i];
      mid = mid && xa >= 0.4 * W - 1e-9 && xa <= 0.6 * W + 1e-9;
    }
    if (mid) {
      sum += x[i] - X[i];
      ++count;
    }
  }
  const double M = kind == PDK_MODEL_PMB ? 0.6 * E : E; /* constrained modulus, see the top */
  r.probe_error = (sum / count) / (-T * W / M) - 1.0;
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return r;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  int dims[2] = {2, 3}, num_dims = 2, threads = 0, sizes[16], num_sizes = 0;
  int methods[2] = {PDK_STATIC_ADR, PDK_STATIC_NEWTON}, num_methods = 2;
  long newton_max = -1;
  pdk_adr_mass mass = PDK_ADR_MASS_AUTO;
  int repeat = 1;
  pdk_model_kind kind = PDK_MODEL_CORRESPONDENCE;
  int tangents[2] = {PDK_TANGENT_AUTO, 0}, num_tangents = 1;
  double rf = 1.5;
  for (int a = 1; a < argc; ++a) {
    if (!strcmp(argv[a], "--dim") && a + 1 < argc) {
      dims[0] = atoi(argv[++a]);
      num_dims = 1;
    } else if (!strcmp(argv[a], "--sizes") && a + 1 < argc) {
      char *tok = strtok(argv[++a], ",");
      while (tok && num_sizes < 16) {
        sizes[num_sizes++] = atoi(tok);
        tok = strtok(NULL, ",");
      }
    } else if (!strcmp(argv[a], "--method") && a + 1 < argc) {
      const char *mth = argv[++a];
      num_methods = 1;
      if (!strcmp(mth, "adr"))
        methods[0] = PDK_STATIC_ADR;
      else if (!strcmp(mth, "newton"))
        methods[0] = PDK_STATIC_NEWTON;
      else
        num_methods = 2;
    } else if (!strcmp(argv[a], "--repeat") && a + 1 < argc) {
      repeat = atoi(argv[++a]);
      if (repeat < 1 || repeat > 15) repeat = 1;
    } else if (!strcmp(argv[a], "--threads") && a + 1 < argc) {
      threads = atoi(argv[++a]);
    } else if (!strcmp(argv[a], "--mass") && a + 1 < argc) {
      const char *mm = argv[++a];
      mass = !strcmp(mm, "rowsum")    ? PDK_ADR_MASS_ROW_SUM
             : !strcmp(mm, "lanczos") ? PDK_ADR_MASS_LANCZOS
                                      : PDK_ADR_MASS_AUTO;
    } else if (!strcmp(argv[a], "--model") && a + 1 < argc) {
      const char *mk = argv[++a];
      kind = !strcmp(mk, "pmb")   ? PDK_MODEL_PMB
             : !strcmp(mk, "lps") ? PDK_MODEL_LPS
                                  : PDK_MODEL_CORRESPONDENCE;
    } else if (!strcmp(argv[a], "--tangent") && a + 1 < argc) {
      const char *tk = argv[++a];
      num_tangents = 1;
      if (!strcmp(tk, "analytic"))
        tangents[0] = PDK_TANGENT_ANALYTIC;
      else if (!strcmp(tk, "difference"))
        tangents[0] = PDK_TANGENT_DIFFERENCE;
      else if (!strcmp(tk, "both")) {
        tangents[0] = PDK_TANGENT_ANALYTIC;
        tangents[1] = PDK_TANGENT_DIFFERENCE;
        num_tangents = 2;
      } else
        tangents[0] = PDK_TANGENT_AUTO;
    } else if (!strcmp(argv[a], "--rf") && a + 1 < argc) {
      rf = atof(argv[++a]);
      if (!(rf >= 1.0 && rf <= 6.0)) rf = 1.5;
    } else if (!strcmp(argv[a], "--newton-max") && a + 1 < argc) {
      newton_max = atol(argv[++a]);
    } else {
      fprintf(stderr,
              "usage: %s [--dim 2|3] [--sizes a,b,c] [--method adr|newton|both] "
              "[--mass auto|rowsum|lanczos] [--threads t] [--newton-max particles] "
              "[--model corr|pmb|lps] [--tangent auto|analytic|difference|both] [--rf R]\n",
              argv[0]);
      return 2;
    }
  }
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  char why[512];
  pdk_ctx *ctx;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) {
    fprintf(stderr, "%s\n", why);
    return 1;
  }
  printf("# model %s, RF %g, threads %d, %d repeat(s) (total, cpu, assem: medians; other phases: "
         "last run); times in s, memory in MiB; passes = trial force passes; tangent a = "
         "analytic, d = difference\n",
         pdk_model_kind_name(kind), rf, pdk_ctx_num_threads(ctx), repeat);
  printf("%-3s %8s %-6s %2s %8s %6s %7s %8s %6s %7s %7s %7s %7s %7s %7s %8s %6s %8s %8s %9s\n",
         "dim", "particles", "method", "K", "unknowns", "iters", "passes", "setup", "mass", "assem",
         "analys", "factor", "solve", "total", "cpu", "K_MiB", "nnz/r", "L_MiB", "peak", "err");
  for (int d = 0; d < num_dims; ++d) {
    const int dim = dims[d];
    const int def2[3] = {32, 64, 128}, def3[3] = {10, 14, 20};
    const int ns = num_sizes ? num_sizes : 3;
    const long nmax = newton_max >= 0 ? newton_max : (dim == 2 ? 70000 : 5000);
    for (int k = 0; k < ns; ++k) {
      const int np = num_sizes ? sizes[k] : (dim == 2 ? def2[k] : def3[k]);
      for (int q = 0; q < num_methods; ++q) {
        const long particles =
            dim == 2 ? (long)(np + 1) * (np + 1) : (long)(np + 1) * (np + 1) * (np + 1);
        if (methods[q] == PDK_STATIC_NEWTON && particles > nmax) continue;
        const int nt = methods[q] == PDK_STATIC_NEWTON ? num_tangents : 1;
        /* medians of the wall, CPU and assembly times over the repeats; stats from the last run.
         * With --tangent both the two tangents alternate within each repeat (side by side). */
        double walls[2][15], cpus[2][15], assems[2][15];
        run_result res[2];
        for (int t = 0; t < repeat; ++t)
          for (int tq = 0; tq < nt; ++tq) {
            res[tq] = run(ctx, dim, np, (pdk_static_method)methods[q], mass, kind,
                          (pdk_tangent_kind)tangents[tq], rf);
            walls[tq][t] = res[tq].wall;
            cpus[tq][t] = res[tq].cpu;
            assems[tq][t] = res[tq].st.time_assembly;
          }
        for (int tq = 0; tq < nt; ++tq) {
          run_result r = res[tq];
          qsort(walls[tq], (size_t)repeat, sizeof(double), cmp_double);
          qsort(cpus[tq], (size_t)repeat, sizeof(double), cmp_double);
          qsort(assems[tq], (size_t)repeat, sizeof(double), cmp_double);
          r.wall = walls[tq][repeat / 2];
          r.cpu = cpus[tq][repeat / 2];
          r.st.time_assembly = assems[tq][repeat / 2];
          const pdk_static_stats *st = &r.st;
          const double mib = 1.0 / 1048576.0;
          printf("%-3d %8d %-6s %2s %8ld %6ld %7ld %8.3f %6.3f %7.3f %7.3f %7.3f %7.3f %7.2f "
                 "%7.2f %8.1f %6.1f %8.1f %8.1f %9.2e\n",
                 dim, (int)r.n, pdk_static_method_name((pdk_static_method)methods[q]),
                 methods[q] != PDK_STATIC_NEWTON ? "-" : (st->analytic_tangent ? "a" : "d"),
                 methods[q] == PDK_STATIC_NEWTON ? st->num_unknowns : 0L, st->iterations,
                 st->force_passes, st->time_setup, st->time_mass, st->time_assembly,
                 st->time_analysis, st->time_factorization, st->time_solve, r.wall, r.cpu,
                 (double)st->tangent_bytes * mib, st->tangent_nnz_per_row,
                 (double)st->factor_bytes * mib, (double)r.peak * mib, r.probe_error);
          fflush(stdout);
        }
      }
    }
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
