/* Updated-Lagrangian cost: a UL rebuild (families in the current configuration, bond weights,
 * rebuild shape, reference update) against one force pass of TL and of UL, on a simple-cubic cube
 * (3-D, L^3 particles) or a square (2-D, L^2), Morton order, correspondence with the SVK law,
 * constant influence, horizon m spacings, a small random displacement (so the families are built
 * from a disordered configuration, as in a run).
 *
 *   bench_ul [--dim 2|3] [--side L] [--m M] [--threads T] [--repeat R]
 *
 * Printed: the median wall time (and process CPU time) of a TL force pass, a UL force pass, a UL
 * rebuild alone (pdk_model_rebuild minus the trial force pass it starts with), and of
 * pdk_families_build_coords alone; the ratio rebuild / UL pass, i.e. how many steps one rebuild
 * costs, and the bytes of the rebuilt families. The rebuild cost per step of a run is that ratio
 * divided by the number of steps between rebuilds.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pdk/pdk.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define CHECK(ctx, expr)                                                                           \
  do {                                                                                             \
    if (expr) {                                                                                    \
      fprintf(stderr, "%s failed: %s\n", #expr, pdk_ctx_error_message(ctx));                       \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

#define MAX_REPEAT 64

int main(int argc, char **argv) {
  int dim = 3, side = 40, threads = 2, repeat = 5;
  double mfac = 3.015;
  for (int a = 1; a < argc; ++a) {
    if (!strcmp(argv[a], "--dim") && a + 1 < argc)
      dim = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--side") && a + 1 < argc)
      side = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--m") && a + 1 < argc)
      mfac = atof(argv[++a]);
    else if (!strcmp(argv[a], "--threads") && a + 1 < argc)
      threads = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--repeat") && a + 1 < argc)
      repeat = atoi(argv[++a]);
    else {
      fprintf(stderr,
              "usage: bench_ul [--dim 2|3] [--side L] [--m M] [--threads T] [--repeat R]\n");
      return 2;
    }
  }
  if (repeat < 1) repeat = 1;
  if (repeat > MAX_REPEAT) repeat = MAX_REPEAT;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  char why[256];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) {
    fprintf(stderr, "pdk_ctx_create: %s\n", why);
    return 1;
  }
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  lo.spacing = 1.0;
  for (int a = 0; a < 3; ++a)
    lo.hi[a] = a < dim ? side : 1.0;
  pdk_particles *p = NULL;
  CHECK(ctx, pdk_lattice_create(ctx, &lo, &p));
  CHECK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, mfac), NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = mfac;
  pdk_families *fam = NULL;
  CHECK(ctx, pdk_families_build(p, &fo, &fam));
  const pdk_index n = pdk_particles_count(p);

  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_SVK;
  mo.bulk_modulus = 2.0;
  mo.shear_modulus = 1.0;
  mo.density = 1.0;
  pdk_model *tl = NULL, *ul = NULL;
  CHECK(ctx, pdk_model_create(p, fam, &mo, &tl));
  /* x = X + 0.05 random */
  uint64_t s = 12345;
  for (int a = 0; a < dim; ++a) {
    double *x = pdk_particles_field_data(p, "x", a);
    const double *X = pdk_particles_X(p, a);
    for (pdk_index i = 0; i < n; ++i) {
      s = s * 6364136223846793005ULL + 1442695040888963407ULL;
      x[i] = X[i] + 0.05 * ((double)(s >> 11) * 0x1p-52 - 1.0);
    }
  }
  double t_tl[MAX_REPEAT], c_tl[MAX_REPEAT], t_ul[MAX_REPEAT], c_ul[MAX_REPEAT];
  double t_rb[MAX_REPEAT], c_rb[MAX_REPEAT], t_fb[MAX_REPEAT], c_fb[MAX_REPEAT];
  CHECK(ctx, pdk_model_force_trial(tl, NULL));
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_time(), t0 = pdk_wtime();
    CHECK(ctx, pdk_model_force_trial(tl, NULL));
    t_tl[r] = pdk_wtime() - t0, c_tl[r] = cpu_time() - c0;
  }
  pdk_model_destroy(&tl);
  mo.connectivity = PDK_CONNECTIVITY_UL;
  mo.ul_skin = 0.0;
  CHECK(ctx, pdk_model_create(p, fam, &mo, &ul));
  CHECK(ctx, pdk_model_force_trial(ul, NULL));
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_time(), t0 = pdk_wtime();
    CHECK(ctx, pdk_model_force_trial(ul, NULL));
    t_ul[r] = pdk_wtime() - t0, c_ul[r] = cpu_time() - c0;
  }
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_time(), t0 = pdk_wtime();
    CHECK(ctx, pdk_model_rebuild(ul)); /* a trial pass, then the rebuild */
    t_rb[r] = pdk_wtime() - t0, c_rb[r] = cpu_time() - c0;
  }
  const double *xc[3] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1),
                         dim == 3 ? pdk_particles_field_data(p, "x", 2) : NULL};
  size_t fam_bytes = 0;
  pdk_bond_index nb = 0;
  for (int r = 0; r < repeat; ++r) {
    pdk_families *f2 = NULL;
    const double c0 = cpu_time(), t0 = pdk_wtime();
    CHECK(ctx, pdk_families_build_coords(ctx, dim, n, xc, NULL, &fo, &f2));
    t_fb[r] = pdk_wtime() - t0, c_fb[r] = cpu_time() - c0;
    fam_bytes = pdk_families_memory_bytes(f2);
    nb = pdk_families_num_bonds(f2);
    pdk_families_destroy(&f2);
  }
  const double tl_w = median(t_tl, repeat), tl_c = median(c_tl, repeat);
  const double ul_w = median(t_ul, repeat), ul_c = median(c_ul, repeat);
  const double rb_w = median(t_rb, repeat) - ul_w, rb_c = median(c_rb, repeat) - ul_c;
  const double fb_w = median(t_fb, repeat), fb_c = median(c_fb, repeat);
  printf("%d-D, %d particles, m = %.3f, %.1f bonds per particle, %d threads, median of %d\n", dim,
         (int)n, mfac, (double)nb / (double)n, threads, repeat);
  printf("  TL force pass        %9.4f s wall %9.4f s cpu\n", tl_w, tl_c);
  printf("  UL force pass        %9.4f s wall %9.4f s cpu  (%.2f x TL)\n", ul_w, ul_c, ul_w / tl_w);
  printf("  UL rebuild           %9.4f s wall %9.4f s cpu  (%.2f UL passes)\n", rb_w, rb_c,
         rb_w / ul_w);
  printf("    of which families  %9.4f s wall %9.4f s cpu  (%.2f UL passes), %.1f MiB\n", fb_w,
         fb_c, fb_w / ul_w, (double)fam_bytes / 1048576.0);
  pdk_model_destroy(&ul);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
