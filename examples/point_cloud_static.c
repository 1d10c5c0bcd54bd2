/* Point cloud to static solve: particles that are not a lattice.
 *
 * Reads a 2-D point cloud from a CSV file (one particle per line: x, y, area; a first line that is
 * not numbers is a header), or, without a file, makes one: a 0.1 m x 0.02 m bar sampled on a 1 mm
 * grid with every point moved at random by up to 0.25 mm in each direction. An LPS model
 * (state-based, E = 70 GPa, nu = 1/3; pdk's 2-D models are plane strain) on families of radius 3.015 mm; the left end
 * (x < 1.5 mm from the leftmost point) is held, the right end pulled by 0.01 mm, and Newton's method
 * finds the equilibrium. Prints the reaction at the pulled end and the modulus it implies,
 * R L / (H u), against the plane-strain modulus of a bar free at its sides, E / (1 - nu^2): they
 * differ by the bar's free-surface layers and the cloud's irregularity.
 *
 *   example_point_cloud_static [cloud.csv]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pdk/pdk.h>

#define CHECK(call)                                                                                \
  do {                                                                                             \
    if (call) {                                                                                    \
      fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx));                                         \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)

typedef struct cloud {
  long n, cap;
  double *x, *y, *a;
} cloud;

static int cloud_add(cloud *c, double x, double y, double a) {
  if (c->n == c->cap) {
    c->cap = c->cap ? 2 * c->cap : 1024;
    c->x = realloc(c->x, (size_t)c->cap * sizeof(double));
    c->y = realloc(c->y, (size_t)c->cap * sizeof(double));
    c->a = realloc(c->a, (size_t)c->cap * sizeof(double));
    if (!c->x || !c->y || !c->a) return 1;
  }
  c->x[c->n] = x, c->y[c->n] = y, c->a[c->n] = a;
  ++c->n;
  return 0;
}

/* x, y, area per line; returns 0, or 1 with a message. */
static int cloud_read(const char *path, cloud *c) {
  FILE *f = fopen(path, "r");
  if (!f) {
    perror(path);
    return 1;
  }
  char line[512];
  long lineno = 0;
  while (fgets(line, sizeof line, f)) {
    ++lineno;
    double x, y, a;
    if (sscanf(line, "%lf , %lf , %lf", &x, &y, &a) != 3) {
      if (lineno == 1) continue; /* a header */
      fprintf(stderr, "%s:%ld: expected three numbers x, y, area\n", path, lineno);
      fclose(f);
      return 1;
    }
    if (!(a > 0.0) || !isfinite(x) || !isfinite(y)) {
      fprintf(stderr, "%s:%ld: the area must be positive and the coordinates finite\n", path, lineno);
      fclose(f);
      return 1;
    }
    if (cloud_add(c, x, y, a)) {
      fclose(f);
      return 1;
    }
  }
  fclose(f);
  return 0;
}

/* The bar, sampled on a grid of spacing h with a random shift of up to h/4 per coordinate. */
static int cloud_make(cloud *c, double L, double H, double h) {
  unsigned long long state = 12345;
  for (int j = 0; j < (int)lround(H / h); ++j)
    for (int i = 0; i < (int)lround(L / h); ++i) {
      double shift[2];
      for (int k = 0; k < 2; ++k) { /* 64-bit LCG (Knuth), the top 53 bits as a uniform [0, 1) */
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        shift[k] = 0.25 * h * (2.0 * (double)(state >> 11) / 9007199254740992.0 - 1.0);
      }
      if (cloud_add(c, (i + 0.5) * h + shift[0], (j + 0.5) * h + shift[1], h * h)) return 1;
    }
  return 0;
}

int main(int argc, char **argv) {
  const double h = 1e-3, E = 70e9, nu = 1.0 / 3.0, u_end = 1e-5;
  cloud c = {0};
  if (argc > 1 ? cloud_read(argv[1], &c) : cloud_make(&c, 0.1, 0.02, h)) return 1;
  if (c.n < 10) {
    fprintf(stderr, "the cloud has %ld points; a bar needs more\n", c.n);
    return 1;
  }
  char why[256];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(NULL, &ctx, why, sizeof why)) {
    fprintf(stderr, "%s\n", why);
    return 1;
  }

  /* The particles: positions and areas (2-D: volume = area x thickness 1). */
  pdk_particles *p = NULL;
  CHECK(pdk_particles_create(ctx, 2, (pdk_index)c.n, &p));
  double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (long i = 0; i < c.n; ++i) {
    X[i] = c.x[i], Y[i] = c.y[i], V[i] = c.a[i];
    lo[0] = fmin(lo[0], X[i]), hi[0] = fmax(hi[0], X[i]);
    lo[1] = fmin(lo[1], Y[i]), hi[1] = fmax(hi[1], Y[i]);
  }
  const double horizon = 3.015 * h;
  CHECK(pdk_particles_reorder_morton(p, horizon, NULL));

  /* The two ends as sets: 1.5 h from the extreme points. */
  const double big = 1e3;
  double a0[3] = {-big, -big, 0}, a1[3] = {lo[0] + 1.5 * h, big, 0};
  double b0[3] = {hi[0] - 1.5 * h, -big, 0}, b1[3] = {big, big, 0};
  pdk_region left = pdk_region_box(a0, a1), right = pdk_region_box(b0, b1);
  pdk_index n_left = 0, n_right = 0;
  CHECK(pdk_particles_set_define(p, "left", &left, &n_left));
  CHECK(pdk_particles_set_define(p, "right", &right, &n_right));

  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = horizon;
  pdk_families *fam = NULL;
  CHECK(pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_LPS;
  mo.bulk_modulus = E / (3.0 * (1.0 - 2.0 * nu)); /* the 3-D constants; 2-D is plane strain */
  mo.shear_modulus = E / (2.0 * (1.0 + nu));
  mo.density = 2700.0;
  pdk_model *m = NULL;
  CHECK(pdk_model_create(p, fam, &mo, &m));

  /* Left end held, right end moved by u_end along x; Newton to equilibrium. */
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  bcs[1].value[0] = pdk_tfun_constant(u_end);
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 2;
  pdk_static *s = NULL;
  CHECK(pdk_static_create(m, &so, &s));
  CHECK(pdk_static_solve(s));

  /* Reaction at the pulled end: minus the internal force on its particles, sum of V f_x. */
  CHECK(pdk_model_force_trial(m, NULL));
  const double *f = pdk_particles_field_data(p, "f", 0);
  const uint8_t *in_right = pdk_particles_field_data(p, "set:right", 0);
  V = pdk_particles_volume(p);
  double R = 0.0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    if (in_right[i]) R -= V[i] * f[i];
  const double L = hi[0] - lo[0], H = hi[1] - lo[1] + h;
  printf("%ld particles (%ld held, %ld pulled), %ld bonds\n", c.n, (long)n_left, (long)n_right,
         (long)pdk_families_num_bonds(fam));
  printf("reaction %.6g N per m of thickness; modulus R L / (H u) = %.4g GPa, "
         "E / (1 - nu^2) = %.4g GPa\n",
         R, R * L / (H * u_end) / 1e9, E / (1.0 - nu * nu) / 1e9);

  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  free(c.x), free(c.y), free(c.a);
  return 0;
}
