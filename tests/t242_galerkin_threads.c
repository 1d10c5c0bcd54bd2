/* Peridynamic Galerkin: setup (derivative table, VC1 correction, area vectors) and the force pass
 * give the same bits with 1 and 2 threads (families are written by their own particle and
 * gathered in bond order; the energy is summed per fixed block, then over blocks), for the taylor
 * basis with VC1 and the neo-Hooke law under a random displacement.
 * labels: unit galerkin threads */
#include "galerkin_util.h"

static void run(int threads, double **out, double *energy, pdk_index *n_out) {
  pdk_ctx *ctx = t_ctx(threads);
  const int n1 = 31;
  const double h = 2.0 / (n1 - 1);
  pdk_particles *p = pg_cloud(ctx, n1, 0.3, 11);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 2.51 * h;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pg_model_opts(PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1);
  mo.law = PDK_LAW_NEO_HOOKE;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  const pdk_index n = *n_out = pdk_particles_count(p);
  uint64_t s = 5;
  for (int c = 0; c < 2; ++c) {
    double *x = pdk_particles_field_data(p, "x", c);
    const double *X = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = X[i] + 0.05 * h * (2 * pg_rand(&s) - 1);
  }
  T_OK(ctx, pdk_model_force(m, energy));
  *out = malloc((size_t)8 * n * sizeof(double));
  const char *fields[3] = {"f", "area", "F"};
  const int comps[3] = {2, 2, 4};
  size_t at = 0;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < comps[k]; ++c, at += (size_t)n)
      memcpy(*out + at, pdk_particles_field_data(p, fields[k], c), (size_t)n * sizeof(double));
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  double *a, *b, ea, eb;
  pdk_index n;
  run(1, &a, &ea, &n);
  run(2, &b, &eb, &n);
  T_ASSERT(!memcmp(&ea, &eb, sizeof ea), "energy %.17g (1 thread) vs %.17g (2)", ea, eb);
  for (size_t k = 0; k < (size_t)8 * n; ++k)
    T_ASSERT(!memcmp(&a[k], &b[k], sizeof(double)), "entry %zu (f, area, F): %.17g vs %.17g", k,
             a[k], b[k]);
  double fm = 0.0;
  for (size_t k = 0; k < (size_t)2 * n; ++k)
    fm = fmax(fm, fabs(a[k]));
  T_ASSERT(fm > 0, "the displacement makes forces");
  free(a);
  free(b);
  return 0;
}
