/* PMB and LPS forces, dilations and energies against an independent evaluation written here: a
 * loop over every particle pair (not the library's families), the LAMMPS formulas written out as
 * LAMMPS writes them (omega = 1/r0 explicit, vfrac_scale in its original form, the 2-D LPS law in
 * the Queiruga-Moridis form t = (omega/m)[2(lambda - mu) theta r0 + 8 mu e], the 2-D PMB constant
 * from E = 3K(1 - 2 nu) with nu = 1/4, the LPS energy in its non-deviatoric form, see below).
 * Jittered lattices with random volumes and
 * random displacements, 2-D and 3-D, partial volumes on and off. Then the same runs on 2 threads
 * must give bitwise the same forces, dilations and total energy.
 *
 * Tolerances are round-off. Each bond term carries a relative error of a few ulp plus the
 * cancellation in e = r - r0: absolute error ~ eps r0, relative eps / |s| <= 1e-14 for the
 * stretches here (|s| >= ~1e-3 for almost all bonds; smaller s gives a smaller term and the
 * same absolute error). Summing ~120 terms adds at most 120 eps relative to the sum of their
 * magnitudes. So |f - f_ref| <= 1e-11 * sum_b |term_b| (and likewise for theta and W) holds with
 * a margin of ~100, while any formula error (a wrong constant, a missing factor, the wrong
 * neighbour's theta) is of the order of the terms themselves.
 * labels: unit physics threads */
#include "bond_models_test.h"

#define K_BULK 2.0
#define G_SHEAR 0.7
#define H_SPACING 0.37
#define M_RATIO 3.015

typedef struct result {
  double *f[3];  /* [n] */
  double *theta; /* [n] or NULL */
  double energy;
} result;

typedef struct reference {
  double *f[3], *fscale; /* force and sum of |bond force| magnitudes */
  double *theta, *tscale;
  double *W, *wscale;
} reference;

/* LAMMPS vfrac_scale, written as pair_peri_pmb.cpp writes it. */
static double vfrac_scale(double r0, double delta, double lc) {
  if (lc <= 0) return 1.0;
  double half_lc = 0.5 * lc;
  if (fabs(r0 - delta) <= half_lc)
    return (-1.0 / (2 * half_lc)) * r0 + (1.0 + ((delta - half_lc) / (2 * half_lc)));
  return 1.0;
}

static void reference_eval(pdk_model_kind kind, pdk_particles *p, double delta, double lc,
                           reference *R) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const double *X[3], *x[3];
  for (int a = 0; a < dim; ++a) {
    X[a] = pdk_particles_X(p, a);
    x[a] = pdk_particles_field_data(p, "x", a);
  }
  const double *V = pdk_particles_volume(p);
  int64_t *start;
  int32_t *nb;
  bm_pairs(p, delta, &start, &nb);
  for (int a = 0; a < 3; ++a)
    R->f[a] = calloc((size_t)n, sizeof(double));
  R->fscale = calloc((size_t)n, sizeof(double));
  R->theta = calloc((size_t)n, sizeof(double));
  R->tscale = calloc((size_t)n, sizeof(double));
  R->W = calloc((size_t)n, sizeof(double));
  R->wscale = calloc((size_t)n, sizeof(double));
  double *m = calloc((size_t)n, sizeof(double));

  /* Per bond: r0, r, dr = r - r0, del = x_i - x_j. */
#define BOND_GEOMETRY                                                                              \
  const int j = nb[b];                                                                             \
  double del[3] = {0, 0, 0}, del0[3] = {0, 0, 0};                                                  \
  for (int a = 0; a < dim; ++a) {                                                                  \
    del[a] = x[a][i] - x[a][j];                                                                    \
    del0[a] = X[a][i] - X[a][j];                                                                   \
  }                                                                                                \
  const double r = sqrt(del[0] * del[0] + del[1] * del[1] + del[2] * del[2]);                      \
  const double r0 = sqrt(del0[0] * del0[0] + del0[1] * del0[1] + del0[2] * del0[2]);               \
  const double dr = r - r0;                                                                        \
  const double scale = vfrac_scale(r0, delta, lc);

  if (kind == PDK_MODEL_PMB) {
    const double nu = 0.25, E = 3.0 * K_BULK * (1.0 - 2.0 * nu);
    const double c =
        dim == 3 ? 18.0 * K_BULK / (M_PI * pow(delta, 4)) : 48.0 * E / (5.0 * M_PI * pow(delta, 3));
    for (pdk_index i = 0; i < n; ++i)
      for (int64_t b = start[i]; b < start[i + 1]; ++b) {
        BOND_GEOMETRY
        const double stretch = dr / r0;
        const double rk = (c * V[j]) * scale * stretch;
        const double fbond = r > 0.0 ? -(rk / r) : 0.0;
        for (int a = 0; a < dim; ++a)
          R->f[a][i] += del[a] * fbond;
        R->fscale[i] += fabs(rk);
        R->W[i] += 0.25 * rk * dr; /* LAMMPS: 0.5 * evdwl, evdwl = 0.5 rk dr */
        R->wscale[i] += fabs(0.25 * rk * dr);
      }
  } else {
    const double d = dim; /* theta factor: 3 in 3-D, 2 in plane strain */
    for (pdk_index i = 0; i < n; ++i)
      for (int64_t b = start[i]; b < start[i + 1]; ++b) {
        BOND_GEOMETRY(void) dr;
        const double omega = 1.0 / r0;
        m[i] += omega * r0 * r0 * V[j] * scale;
      }
    for (pdk_index i = 0; i < n; ++i) {
      for (int64_t b = start[i]; b < start[i + 1]; ++b) {
        BOND_GEOMETRY
        const double omega = 1.0 / r0;
        R->theta[i] += omega * r0 * dr * V[j] * scale;
        R->tscale[i] += fabs(omega * r0 * dr * V[j] * scale);
      }
      R->theta[i] *= d / m[i];
      R->tscale[i] *= d / m[i];
    }
    const double K = K_BULK, G = G_SHEAR, lambda = K - 2.0 * G / 3.0, mu = G;
    for (pdk_index i = 0; i < n; ++i) {
      double dev = 0.0, devscale = 0.0;
      for (int64_t b = start[i]; b < start[i + 1]; ++b) {
        BOND_GEOMETRY
        const double omega = 1.0 / r0; /* omega_plus = omega_minus */
        double rk, rkscale;
        if (dim == 3) { /* pair_peri_lps.cpp */
          double a1 = ((3.0 * K) - (5.0 * G)) * V[j] * scale *
                      ((omega * R->theta[i] / m[i]) + (omega * R->theta[j] / m[j])) * r0;
          double a2 = 15.0 * (G * V[j] * scale) * ((omega / m[i]) + (omega / m[j])) * dr;
          rk = a1 + a2;
          rkscale = fabs(a1) + fabs(a2);
        } else { /* t = (omega/m)[2(lambda - mu) theta r0 + 8 mu e] from each end */
          double a1 = V[j] * scale * 2.0 * (lambda - mu) * r0 *
                      (omega / m[i] * R->theta[i] + omega / m[j] * R->theta[j]);
          double a2 = V[j] * scale * 8.0 * mu * dr * (omega / m[i] + omega / m[j]);
          rk = a1 + a2;
          rkscale = fabs(a1) + fabs(a2);
        }
        const double fbond = r > 0.0 ? -(rk / r) : 0.0;
        for (int a = 0; a < dim; ++a)
          R->f[a][i] += del[a] * fbond;
        R->fscale[i] += rkscale;
        dev += omega * dr * dr * V[j] * scale;
        devscale += fabs(omega * dr * dr * V[j] * scale);
      }
      /* Energy in the non-deviatoric form, equivalent to e_bulk theta^2/2 + e_dev/m sum omega
       * e_d^2 V (kernels/ref/lps.c) by the identity sum omega r0 e V = m theta / d:
       *   3-D: (K - 5G/3)/2 theta^2 + (15 G / 2m) sum omega e^2 V
       *   2-D: (lambda - mu)/2 theta^2 + (4 mu / m) sum omega e^2 V */
      const double a = dim == 3 ? 0.5 * (K - 5.0 * G / 3.0) : 0.5 * (lambda - mu);
      const double bdev = dim == 3 ? 7.5 * G : 4.0 * mu;
      R->W[i] = a * R->theta[i] * R->theta[i] + bdev / m[i] * dev;
      R->wscale[i] = fabs(a) * R->theta[i] * R->theta[i] + bdev / m[i] * devscale;
    }
  }
#undef BOND_GEOMETRY
  free(m);
  free(start);
  free(nb);
}

static void reference_free(reference *R) {
  for (int a = 0; a < 3; ++a)
    free(R->f[a]);
  free(R->fscale), free(R->theta), free(R->tscale), free(R->W), free(R->wscale);
}

static void run_case(pdk_ctx *ctx, int dim, pdk_model_kind kind, double lc, result *out,
                     reference *R) {
  const int nx = dim == 3 ? 14 : 50, ny = dim == 3 ? 13 : 45, nz = 12;
  pdk_particles *p = bm_body(ctx, dim, nx, ny, nz, H_SPACING, 0.2, 0.2, 1234 + (uint64_t)dim);
  const double delta = M_RATIO * H_SPACING;
  pdk_families *f = bm_families(ctx, p, delta);
  bm_displace_random(p, 0.03 * H_SPACING, 99 + (uint64_t)dim);
  pdk_model *m = bm_model(ctx, p, f, kind, K_BULK, G_SHEAR, lc, 0.0, 0.0);
  T_OK(ctx, pdk_model_force(m, &out->energy));
  const pdk_index n = pdk_particles_count(p);
  for (int a = 0; a < 3; ++a) {
    out->f[a] = calloc((size_t)n, sizeof(double));
    if (a < dim) memcpy(out->f[a], pdk_particles_field_data(p, "f", a), (size_t)n * sizeof(double));
  }
  out->theta = NULL;
  if (kind == PDK_MODEL_LPS) {
    out->theta = malloc((size_t)n * sizeof(double));
    memcpy(out->theta, pdk_particles_field_data(p, "theta", 0), (size_t)n * sizeof(double));
    T_ASSERT(pdk_particles_field_exists(p, "m"), "lps declares \"m\"");
  } else {
    T_ASSERT(!pdk_particles_field_exists(p, "theta") && !pdk_particles_field_exists(p, "m"),
             "pmb declares no lps fields");
  }
  T_ASSERT(pdk_model_bond_alive(m) == NULL, "no bond state without a critical stretch");
  if (R) reference_eval(kind, p, delta, lc, R);

  if (R) {
    const double *V = pdk_particles_volume(p);
    double e_ref = 0.0, e_scale = 0.0;
    for (pdk_index i = 0; i < n; ++i) {
      for (int a = 0; a < dim; ++a)
        T_NEAR(out->f[a][i], R->f[a][i], 0.0, 1e-11 * R->fscale[i],
               "%s %d-D lc=%g: force component %d of particle %d", pdk_model_kind_name(kind), dim,
               lc, a, (int)i);
      if (kind == PDK_MODEL_LPS)
        T_NEAR(out->theta[i], R->theta[i], 0.0, 1e-11 * R->tscale[i] + 1e-300,
               "%d-D lc=%g: dilation of particle %d", dim, lc, (int)i);
      e_ref += V[i] * R->W[i];
      e_scale += V[i] * R->wscale[i];
    }
    T_NEAR(out->energy, e_ref, 0.0, 1e-10 * e_scale, "%s %d-D lc=%g: total strain energy",
           pdk_model_kind_name(kind), dim, lc);
    T_ASSERT(out->energy > 0, "positive strain energy");
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&f);
  pdk_particles_destroy(&p);
}

static void result_free(result *r) {
  for (int a = 0; a < 3; ++a)
    free(r->f[a]);
  free(r->theta);
}

int main(void) {
  pdk_ctx *ctx1 = t_ctx(1), *ctx2 = t_ctx(2);
  for (int dim = 2; dim <= 3; ++dim)
    for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind)
      for (int with_lc = 0; with_lc <= 1; ++with_lc) {
        const double lc = with_lc ? H_SPACING : 0.0;
        result r1, r2;
        reference R;
        run_case(ctx1, dim, (pdk_model_kind)kind, lc, &r1, &R);
        run_case(ctx2, dim, (pdk_model_kind)kind, lc, &r2, NULL);
        const size_t n = (size_t)(dim == 3 ? 14 * 13 * 12 : 50 * 45);
        for (int a = 0; a < dim; ++a)
          T_ASSERT(!memcmp(r1.f[a], r2.f[a], n * sizeof(double)),
                   "%s %d-D lc=%g: forces differ between 1 and 2 threads",
                   pdk_model_kind_name((pdk_model_kind)kind), dim, lc);
        if (r1.theta)
          T_ASSERT(!memcmp(r1.theta, r2.theta, n * sizeof(double)),
                   "%d-D: dilation differs between 1 and 2 threads", dim);
        T_ASSERT(!memcmp(&r1.energy, &r2.energy, sizeof(double)),
                 "%s %d-D: energy %.17g (1 thread) vs %.17g (2 threads)",
                 pdk_model_kind_name((pdk_model_kind)kind), dim, r1.energy, r2.energy);
        result_free(&r1);
        result_free(&r2);
        reference_free(&R);
      }
  pdk_ctx_destroy(&ctx1);
  pdk_ctx_destroy(&ctx2);
  return 0;
}
