/* Peridynamic Galerkin against correspondence, error against cost on the same particles
 * (docs/tradeoff.md, "Peridynamic Galerkin").
 *
 *   build/bench/bench_pg_tradeoff [max_n1 [threads]]
 *
 * The irregular cloud of the patch test (tests/galerkin_util.h: [-1, 1]^2, n1 x n1 nodes,
 * interior nodes jittered by 0.3 h, edge nodes on the edges; seed 1), n1 = 9, 17, 33, ... up to
 * max_n1 (default 65), families of horizon 2.51 h for every model, the linear law (E = 1e5,
 * nu = 0.3, plane strain), Dirichlet values on every edge particle, Newton (rtol 1e-12). Problems:
 *   patch  u = (0.1 X + 0.3 Y, 0.2 X + 0.4 Y) (Bode et al. eq. 83) on the edges, no load: the
 *          interior must reproduce it;
 *   sine   u = (sin(pi X/2) cos(pi Y/2), cos(pi X/2) sin(pi Y/2)) on the edges, the body force
 *          b = (pi^2/2)(lambda + 2 mu) u at every particle (Bode et al. section 7.3, eqs. 86-87).
 * Error: relative L2 of u, sum_k V_k |u - u_exact|^2 over sum_k V_k |u_exact|^2. Cost: the
 * process CPU time of the model's creation (shape functions, VC1 solve) and the Newton solve
 * (tangent by colored differences, factorization), one thread unless asked. Models:
 * correspondence with Silling stabilization C_s = 0.1 and constant influence (pdk's default),
 * correspondence without stabilization (omega 1/r^2), galerkin taylor vc1, galerkin taylor with
 * the bond correction and vc1 (VC1 surface: the edges, condition "s"). Prints one row per run and
 * the order of the error between successive resolutions. */
#include <sys/resource.h>

#include "../tests/galerkin_util.h"

static double cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static void exact(int problem, double X, double Y, double u[2]) {
  if (problem == 0) {
    u[0] = pg_H[0][0] * X + pg_H[0][1] * Y;
    u[1] = pg_H[1][0] * X + pg_H[1][1] * Y;
  } else {
    const double a = M_PI * X / 2, b = M_PI * Y / 2;
    u[0] = sin(a) * cos(b);
    u[1] = cos(a) * sin(b);
  }
}

static const char *const model_name[4] = {"correspondence silling", "correspondence none",
                                          "galerkin taylor vc1", "galerkin taylor bond vc1"};

/* One run: returns the error, *cpu the seconds, *nb the bonds per particle. */
static double run(pdk_ctx *ctx, int problem, int model, int n1, double *cpu, double *nbp,
                  long *iters) {
  const double h = 2.0 / (n1 - 1);
  pdk_particles *p = pg_cloud(ctx, n1, 0.3, 1);
  const pdk_index n = pdk_particles_count(p);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 2.51 * h;
  const double c0 = cpu_seconds();
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  *nbp = (double)pdk_families_num_bonds(fam) / (double)n;
  pdk_model_opts mo = pg_model_opts(PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1);
  if (model < 2) {
    mo.kind = PDK_MODEL_CORRESPONDENCE;
    mo.influence = model == 0 ? PDK_INFLUENCE_CONSTANT : PDK_INFLUENCE_INV_R2;
    mo.stabilization = model == 0 ? PDK_STAB_SILLING : PDK_STAB_NONE;
    mo.stab_coefficient = 0.1;
  }
  mo.galerkin.bond = model == 3;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  T_OK(ctx, pdk_particles_field_add(p, "u_exact", PDK_F64, 2));
  T_OK(ctx, pdk_particles_field_add(p, "b_mms", PDK_F64, 2));
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double kb = M_PI * M_PI / 2 * (pg_lambda() + 2 * pg_mu());
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    exact(problem, X[k], Y[k], u);
    for (int c = 0; c < 2; ++c) {
      ((double *)pdk_particles_field_data(p, "u_exact", c))[k] = u[c];
      ((double *)pdk_particles_field_data(p, "b_mms", c))[k] = problem == 1 ? kb * u[c] : 0.0;
    }
  }
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:surface";
  bcs[0].components = 3;
  bcs[0].value[0] = bcs[0].value[1] = pdk_tfun_constant(1.0);
  bcs[0].scale_field = "u_exact";
  bcs[1].kind = PDK_BC_BODY_FORCE;
  bcs[1].set = NULL;
  bcs[1].components = 3;
  bcs[1].value[0] = bcs[1].value[1] = pdk_tfun_constant(1.0);
  bcs[1].scale_field = "b_mms";
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = problem == 1 ? 2 : 1;
  so.rtol = 1e-12;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  *iters = pdk_static_stats_get(s)->iterations;
  pdk_static_destroy(&s);
  *cpu = cpu_seconds() - c0;
  const double *x[2] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1)};
  double e = 0.0, nn = 0.0;
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    exact(problem, X[k], Y[k], u);
    const double uh[2] = {x[0][k] - X[k], x[1][k] - Y[k]};
    for (int c = 0; c < 2; ++c) {
      e += V[k] * (uh[c] - u[c]) * (uh[c] - u[c]);
      nn += V[k] * u[c] * u[c];
    }
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return sqrt(e / nn);
}

int main(int argc, char **argv) {
  const int max_n1 = argc > 1 ? atoi(argv[1]) : 65;
  const int threads = argc > 2 ? atoi(argv[2]) : 1;
  pdk_ctx *ctx = t_ctx(threads);
  printf("# %d thread(s); horizon 2.51 h; CPU seconds of family build + model creation + Newton\n",
         threads);
  printf("%-7s %-26s %5s %7s %6s %5s %10s %10s %6s\n", "problem", "model", "n1", "parts",
         "bonds", "iters", "cpu [s]", "error", "order");
  for (int problem = 0; problem < 2; ++problem)
    for (int model = 0; model < 4; ++model) {
      double prev = 0.0;
      for (int n1 = 9; n1 <= max_n1; n1 = 2 * n1 - 1) {
        double cpu, nbp;
        long it;
        const double e = run(ctx, problem, model, n1, &cpu, &nbp, &it);
        printf("%-7s %-26s %5d %7d %6.1f %5ld %10.3f %10.3e", problem ? "sine" : "patch",
               model_name[model], n1, n1 * n1, nbp, it, cpu, e);
        if (prev > 0) printf(" %6.2f", log(prev / e) / log(2.0));
        printf("\n");
        fflush(stdout);
        prev = e;
      }
    }
  pdk_ctx_destroy(&ctx);
  return 0;
}
