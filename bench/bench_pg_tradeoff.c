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
#include "../tests/galerkin_util.h"

static const char *const model_name[4] = {"correspondence silling", "correspondence none",
                                          "galerkin taylor vc1", "galerkin taylor bond vc1"};

int main(int argc, char **argv) {
  const int max_n1 = argc > 1 ? atoi(argv[1]) : 65;
  const int threads = argc > 2 ? atoi(argv[2]) : 1;
  pdk_ctx *ctx = t_ctx(threads);
  printf("# %d thread(s); horizon 2.51 h; CPU seconds of family build + model creation + Newton\n",
         threads);
  printf("%-7s %-26s %5s %7s %6s %5s %10s %10s %6s\n", "problem", "model", "n1", "parts", "bonds",
         "iters", "cpu [s]", "error", "order");
  for (int problem = 0; problem < 2; ++problem)
    for (int model = 0; model < 4; ++model) {
      double prev = 0.0;
      for (int n1 = 9; n1 <= max_n1; n1 = 2 * n1 - 1) {
        double cpu, nbp;
        long it;
        const double e = pg_mms_run(ctx, problem, model, n1, &cpu, &nbp, &it);
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
