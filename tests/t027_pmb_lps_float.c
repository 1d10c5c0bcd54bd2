/* Float storage (opts.precision = float) of the PMB and LPS models: the bond length r0 is stored
 * per bond as a float, everything else stays double.
 *
 * Bound. Let u = 2^-24 (half an ulp of float): r0f = r0 (1 + t), |t| <= u. Per bond, to first order:
 *   PMB: the bond term c beta V_j s eta / r changes through s = (r - r0)/r0 (by up to u (1 + |s|))
 *        and through beta = min(1, (vs_a - r0) vs_b) (by up to vs_b r0 u where beta < 1), so
 *        |delta f_i| <= u sum_b c V_j [beta (1 + |s|) + |s| vs_b r0 [beta < 1]].
 *   LPS: m_i = sum r0 beta V changes by up to u (1 + vs_b r0 [beta < 1]) relative; theta_i = d/m_i
 *        sum e beta V by up to d u (1 + ...) absolute, since sum r0 beta V / m_i = 1; so with
 *        A = c_dil (theta_i/m_i + theta_j/m_j), B = c_dev (1/m_i + 1/m_j), bond term beta V (A + B s),
 *        |delta term| <= u beta V [|c_dil| (1/m_i + 1/m_j)(2 d + |theta_i| + |theta_j|) (1 + g_b)
 *                              + |B| (1 + 2 |s|)(1 + g_b) + |A + B s| g_b],  g_b = vs_b r0 [beta < 1] / beta.
 * The test allows twice these sums (second-order terms, and the double round-off of both runs,
 * which is ~1e-16 of the same scale), evaluated here from the double geometry, and asserts:
 *   - every particle's float force is within its bound of the double force, in 2-D and 3-D, near
 *     the origin and 10^4 spacings from it (the error is relative to the bond length, not to the
 *     coordinates, so the distance from the origin must not matter);
 *   - the float forces are not the double forces (the option is not silently ignored);
 *   - float runs give the same bits on 1 and 2 threads, with bond breaking on.
 * labels: unit physics threads */
#include <float.h>
#include <stdint.h>

#include "bond_models_test.h"
#include "models/model_bond.h"

static pdk_particles *body(pdk_ctx *ctx, int dim, double origin) {
  pdk_lattice_opts o = pdk_lattice_opts_default();
  o.type = dim == 3 ? PDK_LATTICE_CUBIC : PDK_LATTICE_SQUARE;
  const int nx[3] = {17, 13, dim == 3 ? 9 : 1};
  for (int a = 0; a < 3; ++a) {
    o.lo[a] = origin - 0.3;
    o.hi[a] = o.lo[a] + nx[a];
  }
  o.spacing = 1.0;
  o.jitter = 0.1;
  o.seed = 5;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  return p;
}

static pdk_model_opts opts(int kind, int precision, double s00) {
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = (pdk_model_kind)kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.lattice_constant = 1.0;
  o.critical_stretch = s00;
  o.alpha = 0.25;
  o.precision = (pdk_precision)precision;
  return o;
}

/* Forces of one trial pass at x = X + 1e-3 U(-1, 1) per component. f: [dim][n] out. */
static void forces(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam, int kind, int precision,
                   double **f) {
  pdk_model_opts o = opts(kind, precision, 0.0);
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  bm_displace_random(p, 1e-3, 31);
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  const pdk_index n = pdk_particles_count(p);
  for (int c = 0; c < pdk_particles_dim(p); ++c)
    memcpy(f[c], pdk_particles_field_data(p, "f", c), (size_t)n * sizeof(double));
  pdk_model_destroy(&m);
}

/* The per-particle bound of the header, from the double geometry. */
static void bounds(pdk_particles *p, pdk_families *fam, int kind, double *bound) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p);
  const double u = 0x1p-24, delta = pdk_families_horizon(fam);
  const pdk_model_opts o = opts(kind, 0, 0.0);
  const double K = o.bulk_modulus, G = o.shear_modulus;
  const double vs_a = delta + 0.5, vs_b = 1.0; /* lattice constant 1 */
  const double c = dim == 3 ? 18.0 * K / (M_PI * pow(delta, 4)) : 72.0 * K / (5.0 * M_PI * pow(delta, 3));
  const double d = dim;
  const double c_dil = dim == 3 ? 3 * K - 5 * G : 2 * (K - 2 * G / 3 - G);
  const double c_dev = dim == 3 ? 15 * G : 8 * G;
  double *m = calloc((size_t)n, sizeof *m), *theta = calloc((size_t)n, sizeof *theta);
  T_ASSERT(m && theta, "out of memory");
#define GEOM()                                                                                     \
  const pdk_index j = bj[b];                                                                       \
  double R2 = 0, r2 = 0;                                                                           \
  for (int a = 0; a < dim; ++a) {                                                                  \
    const double dX = pdk_particles_X(p, a)[j] - pdk_particles_X(p, a)[i];                         \
    const double dx = ((double *)pdk_particles_field_data(p, "x", a))[j] -                         \
                      ((double *)pdk_particles_field_data(p, "x", a))[i];                          \
    R2 += dX * dX, r2 += dx * dx;                                                                  \
  }                                                                                                \
  const double r0 = sqrt(R2), r = sqrt(r2), s = (r - r0) / r0;                                     \
  const double beta = fmin(1.0, (vs_a - r0) * vs_b);                                              \
  const double gb = beta < 1.0 ? vs_b * r0 / beta : 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      GEOM();
      m[i] += r0 * beta * V[j];
      theta[i] += (r - r0) * beta * V[j];
      (void)s, (void)gb;
    }
    theta[i] = m[i] > 0 ? d * theta[i] / m[i] : 0.0;
  }
  for (pdk_index i = 0; i < n; ++i) {
    double sum = 0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      GEOM();
      if (kind == PDK_MODEL_PMB) {
        sum += c * V[j] * (beta * (1 + fabs(s)) + (beta < 1.0 ? fabs(s) * vs_b * r0 : 0.0));
      } else {
        const double im = 1 / m[i] + 1 / m[j];
        const double A = c_dil * (theta[i] / m[i] + theta[j] / m[j]), B = c_dev * im;
        sum += beta * V[j] *
               (fabs(c_dil) * im * (2 * d + fabs(theta[i]) + fabs(theta[j])) * (1 + gb) +
                fabs(B) * (1 + 2 * fabs(s)) * (1 + gb) + fabs(A + B * s) * gb);
      }
    }
    bound[i] = 2.0 * u * sum;
  }
#undef GEOM
  free(m);
  free(theta);
}

static void float_vs_double(pdk_ctx *ctx, int dim, int kind, double origin) {
  pdk_particles *p = body(ctx, dim, origin);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  const pdk_index n = pdk_particles_count(p);
  double *fd[3], *ff[3], *bound = malloc((size_t)n * sizeof *bound);
  for (int c = 0; c < dim; ++c) {
    fd[c] = malloc((size_t)n * sizeof(double));
    ff[c] = malloc((size_t)n * sizeof(double));
  }
  forces(ctx, p, fam, kind, PDK_PRECISION_DOUBLE, fd);
  forces(ctx, p, fam, kind, PDK_PRECISION_FLOAT, ff);
  bounds(p, fam, kind, bound);
  double max_diff = 0, max_ratio = 0, max_f = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c) {
      const double diff = fabs(ff[c][i] - fd[c][i]);
      T_ASSERT(diff <= bound[i], "%d-D %s at origin %g: particle %d component %d: |f_float - "
               "f_double| = %.3e > bound %.3e (f = %.3e)", dim, kind ? "lps" : "pmb", origin,
               (int)i, c, diff, bound[i], fd[c][i]);
      max_diff = fmax(max_diff, diff);
      max_ratio = fmax(max_ratio, diff / bound[i]);
      max_f = fmax(max_f, fabs(fd[c][i]));
    }
  T_ASSERT(max_diff > 0, "%d-D %s: float forces equal double ones: float storage not used", dim,
           kind ? "lps" : "pmb");
  T_INFO("%d-D %-3s origin %-6g: max |f_float - f_double| = %.3e (%.2e of max |f|), max ratio to "
         "bound %.3f\n",
         dim, kind ? "lps" : "pmb", origin, max_diff, max_diff / max_f, max_ratio);
  for (int c = 0; c < dim; ++c) free(fd[c]), free(ff[c]);
  free(bound);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* Float, breaking on, four committing passes: f, W and bond state after them. */
static void float_threads(int dim, int kind) {
  double *f[2][3];
  uint8_t *alive[2];
  pdk_bond_index nb = 0, broken[2];
  pdk_index n = 0;
  for (int t = 0; t < 2; ++t) {
    pdk_ctx *ctx = t_ctx(t + 1);
    pdk_particles *p = body(ctx, dim, 0.0);
    pdk_families *fam = bm_families(ctx, p, 3.015);
    pdk_model_opts o = opts(kind, PDK_PRECISION_FLOAT, 0.003);
    pdk_model *m = NULL;
    T_OK(ctx, pdk_model_create(p, fam, &o, &m));
    for (int pass = 0; pass < 4; ++pass) {
      bm_displace_random(p, 0.003 * (pass + 1), 7 + (uint64_t)pass);
      double e;
      T_OK(ctx, pdk_model_force(m, &e));
    }
    n = pdk_particles_count(p);
    nb = pdk_families_num_bonds(fam);
    for (int c = 0; c < dim; ++c) {
      f[t][c] = malloc((size_t)n * sizeof(double));
      memcpy(f[t][c], pdk_particles_field_data(p, "f", c), (size_t)n * sizeof(double));
    }
    alive[t] = malloc((size_t)nb);
    memcpy(alive[t], pdk_model_bond_alive(m), (size_t)nb);
    broken[t] = pdk_model_num_broken(m);
    pdk_model_destroy(&m);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
  }
  T_ASSERT(broken[0] > 0 && broken[0] < nb, "%d-D: %lld of %lld bonds broke; want some", dim,
           (long long)broken[0], (long long)nb);
  T_ASSERT(broken[0] == broken[1] && !memcmp(alive[0], alive[1], (size_t)nb),
           "%d-D float: bond state differs between 1 and 2 threads", dim);
  for (int c = 0; c < dim; ++c) {
    T_ASSERT(!memcmp(f[0][c], f[1][c], (size_t)n * sizeof(double)),
             "%d-D float: f differs between 1 and 2 threads", dim);
    free(f[0][c]), free(f[1][c]);
  }
  free(alive[0]), free(alive[1]);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int dim = 2; dim <= 3; ++dim)
    for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
      float_vs_double(ctx, dim, kind, 0.0);
      float_vs_double(ctx, dim, kind, 1e4);
      float_threads(dim, kind);
    }
  pdk_ctx_destroy(&ctx);
  return 0;
}
