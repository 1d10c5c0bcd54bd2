/* Lanczos estimate of the largest stiffness eigenvalue (lanczos.h). */
#include <math.h>
#include <string.h>

#include "lanczos.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

/* Symmetric tridiagonal (alpha[0..k-1], beta[1..k-1]) largest eigenvalue by Sturm bisection. */
static double tridiag_max_eig(const double *alpha, const double *beta, int k) {
  double lo = alpha[0], hi = alpha[0];
  for (int i = 0; i < k; ++i) { /* Gershgorin interval */
    double r = (i > 0 ? fabs(beta[i]) : 0.0) + (i + 1 < k ? fabs(beta[i + 1]) : 0.0);
    lo = fmin(lo, alpha[i] - r);
    hi = fmax(hi, alpha[i] + r);
  }
  for (int it = 0; it < 200 && hi - lo > 1e-14 * fabs(hi); ++it) {
    double mid = 0.5 * (lo + hi);
    int count = 0; /* eigenvalues below mid */
    double d = 1.0;
    for (int i = 0; i < k; ++i) {
      d = alpha[i] - mid - (i > 0 ? beta[i] * beta[i] / d : 0.0);
      if (d == 0.0) d = -1e-300;
      if (d < 0) count++;
    }
    if (count == k)
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

/* Weight of particle i in the inner product: rho_i V_i (mass) or V_i. */
static inline double weight(const pdk_model *m, int mass, const double *vol, pdk_index i) {
  return mass ? pdk_model_density_of(m, i) * vol[i] : vol[i];
}

int pdk_lanczos_max_eig(pdk_model *m, const pdk_lanczos_opts *o, double *lambda_max, long *passes) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p), kmax = o->steps, mass = o->mass;
  const pdk_index n = pdk_particles_count(p);
  const double *vol = pdk_particles_volume(p);
  const int64_t *id = pdk_particles_id(p);
  double *x0[3] = {0}, *f0[3] = {0}, *q[3] = {0}, *qprev[3] = {0}, *w[3] = {0};
  double alpha[PDK_LANCZOS_MAX_STEPS], beta[PDK_LANCZOS_MAX_STEPS + 1];
  long num_passes = 0;
  *lambda_max = NAN;
  PDK_CHECK_GOTO(kmax >= 1 && kmax <= PDK_LANCZOS_MAX_STEPS, ctx, PDK_ERR_ARG,
                 "%d Lanczos steps: must lie in 1..%d", kmax, PDK_LANCZOS_MAX_STEPS);
  for (int c = 0; c < dim; ++c) {
    x0[c] = malloc((size_t)n * sizeof(double));
    f0[c] = malloc((size_t)n * sizeof(double));
    q[c] = calloc((size_t)n, sizeof(double));
    qprev[c] = calloc((size_t)n, sizeof(double));
    w[c] = malloc((size_t)n * sizeof(double));
    PDK_CHECK_GOTO(x0[c] && f0[c] && q[c] && qprev[c] && w[c], ctx, PDK_ERR_MEMORY,
                   "out of memory for the Lanczos estimate of the largest stiffness eigenvalue");
    memcpy(x0[c], field(p, "x", c), (size_t)n * sizeof(double));
  }
  PDK_CALL_GOTO(pdk_model_force_trial(m, NULL));
  num_passes++;
  for (int c = 0; c < dim; ++c)
    memcpy(f0[c], field(p, "f", c), (size_t)n * sizeof(double));
  /* Start vector: deterministic pseudo-random from the particle id (order independent). */
  double norm2 = 0.0;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i) {
      uint64_t h =
          (uint64_t)id[i] * 0x9E3779B97F4A7C15ull + (uint64_t)c * 0xBF58476D1CE4E5B9ull + o->salt;
      h ^= h >> 31;
      h *= 0x94D049BB133111EBull;
      h ^= h >> 29;
      q[c][i] = ((double)(h >> 11) / 9007199254740992.0) - 0.5;
      norm2 += weight(m, mass, vol, i) * q[c][i] * q[c][i];
    }
  if (o->scale_by_inverse) {
    double inv = 1.0 / sqrt(norm2);
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i)
        q[c][i] *= inv;
  } else {
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i)
        q[c][i] /= sqrt(norm2);
  }
  int k;
  beta[0] = 0.0;
  for (k = 0; k < kmax; ++k) {
    double qmax = 0.0;
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i)
        qmax = fmax(qmax, fabs(q[c][i]));
    const double eps = 1e-7 * o->horizon / qmax;
    for (int c = 0; c < dim; ++c) {
      double *x = field(p, "x", c);
      for (pdk_index i = 0; i < n; ++i)
        x[i] = x0[c][i] + eps * q[c][i];
    }
    PDK_CALL_GOTO(pdk_model_force_trial(m, NULL));
    num_passes++;
    /* w = M^-1 K q = -(f - f0) / (eps rho) (mass), V^-1 K q = -(f - f0) / eps (volume) */
    double a = 0.0;
    for (int c = 0; c < dim; ++c) {
      const double *f = field(p, "f", c);
      if (mass) {
        for (pdk_index i = 0; i < n; ++i) {
          const double rho_i = pdk_model_density_of(m, i);
          w[c][i] = -(f[i] - f0[c][i]) / (eps * rho_i);
          a += rho_i * vol[i] * w[c][i] * q[c][i];
        }
      } else {
        for (pdk_index i = 0; i < n; ++i) {
          w[c][i] = -(f[i] - f0[c][i]) / eps;
          a += vol[i] * w[c][i] * q[c][i];
        }
      }
    }
    alpha[k] = a;
    double b2 = 0.0;
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) {
        w[c][i] -= a * q[c][i] + beta[k] * qprev[c][i];
        b2 += weight(m, mass, vol, i) * w[c][i] * w[c][i];
      }
    beta[k + 1] = sqrt(b2);
    if (!(beta[k + 1] > 1e-12 * fabs(a)) || k + 1 == kmax) {
      ++k;
      break;
    }
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) {
        qprev[c][i] = q[c][i];
        q[c][i] = w[c][i] / beta[k + 1];
      }
  }
  *lambda_max = tridiag_max_eig(alpha, beta, k);
cleanup:
  for (int c = 0; c < dim; ++c) {
    if (x0[c]) memcpy(field(p, "x", c), x0[c], (size_t)n * sizeof(double));
    if (o->restore_f && f0[c] && err == PDK_SUCCESS)
      memcpy(field(p, "f", c), f0[c], (size_t)n * sizeof(double));
    free(x0[c]);
    free(f0[c]);
    free(q[c]);
    free(qprev[c]);
    free(w[c]);
  }
  if (passes) *passes = num_passes;
  return err;
}
