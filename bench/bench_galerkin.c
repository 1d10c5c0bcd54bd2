/* Peridynamic Galerkin force pass beside correspondence on the same particles.
 *
 *   build/bench/bench_galerkin [n1 [horizon_factor [threads [passes]]]]
 *
 * The irregular cloud of the patch test (tests/galerkin_util.h: [-1, 1]^2, n1 x n1 nodes, jitter
 * 0.3 h; default n1 = 201, 40 401 particles), families of horizon_factor h (default 2.51). Models,
 * each with the linear law on a random displacement: correspondence (omega 1/r^2, no
 * stabilization, and Silling stabilization, the scenes' default), galerkin taylor (no
 * correction), galerkin taylor vc1. Prints the model's setup time (creation: shape functions, and
 * the VC1 solve) and the median wall time of `passes` trial force passes (default 21), per particle
 * and per bond, and its ratio to the first model's. The models' passes are interleaved. */
#include "../tests/galerkin_util.h"

static int cmp(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  const int n1 = argc > 1 ? atoi(argv[1]) : 201;
  const double hf = argc > 2 ? atof(argv[2]) : 2.51;
  const int threads = argc > 3 ? atoi(argv[3]) : 1;
  const int passes = argc > 4 ? atoi(argv[4]) : 21;
  pdk_ctx *ctx = t_ctx(threads);
  const double h = 2.0 / (n1 - 1);
  pdk_particles *p = pg_cloud(ctx, n1, 0.3, 1);
  T_OK(ctx, pdk_particles_reorder_morton(p, hf * h, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = hf * h;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  const pdk_index n = pdk_particles_count(p);
  const double nb = (double)pdk_families_num_bonds(fam);
  printf("# %d particles, %.1f bonds per particle, %d thread(s), %s kernels, median of %d passes\n",
         (int)n, nb / n, threads, pdk_ctx_kernels_name(ctx), passes);
  printf("%-28s %10s %12s %12s %10s %8s\n", "model", "setup [s]", "pass [ms]", "ns/particle",
         "ns/bond", "ratio");
  const char *names[4] = {"correspondence (none)", "correspondence (silling)", "galerkin taylor",
                          "galerkin taylor vc1"};
  /* the four models live side by side on the store and their passes are interleaved (model 0,
   * 1, 2, 3, 0, 1, ...), so a change of the machine's load hits all of them alike */
  pdk_model *m[4];
  double setup[4], *t = malloc((size_t)4 * passes * sizeof(double));
  for (int v = 0; v < 4; ++v) {
    pdk_model_opts mo =
        pg_model_opts(PDK_GALERKIN_TAYLOR, v == 3 ? PDK_GALERKIN_VC1 : PDK_GALERKIN_NONE);
    if (v < 2) {
      mo.kind = PDK_MODEL_CORRESPONDENCE;
      mo.influence = PDK_INFLUENCE_INV_R2;
      mo.stabilization = v == 0 ? PDK_STAB_NONE : PDK_STAB_SILLING;
    }
    const double t0 = pdk_wtime();
    T_OK(ctx, pdk_model_create(p, fam, &mo, &m[v]));
    setup[v] = pdk_wtime() - t0;
  }
  uint64_t s = 2;
  for (int c = 0; c < 2; ++c) {
    double *x = pdk_particles_field_data(p, "x", c);
    const double *X = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = X[i] + 1e-3 * h * (2 * pg_rand(&s) - 1);
  }
  for (int k = 0; k < passes; ++k)
    for (int v = 0; v < 4; ++v) {
      const double a = pdk_wtime();
      T_OK(ctx, pdk_model_force_trial(m[v], NULL));
      t[v * passes + k] = pdk_wtime() - a;
    }
  double med[4];
  for (int v = 0; v < 4; ++v) {
    qsort(t + v * passes, (size_t)passes, sizeof *t, cmp);
    med[v] = t[v * passes + passes / 2];
  }
  for (int v = 0; v < 4; ++v) {
    printf("%-28s %10.3f %12.3f %12.1f %10.2f %8.1f\n", names[v], setup[v], 1e3 * med[v],
           1e9 * med[v] / n, 1e9 * med[v] / nb, med[v] / med[0]);
    pdk_model_destroy(&m[v]);
  }
  free(t);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
