/* V-INV for PMB and LPS, 2-D (plane strain) and 3-D, partial volumes off and on:
 *  1. rigid rotation + translation: zero force;
 *  2. random displacements: sum_i V_i f_i = 0 and sum_i V_i x_i x f_i = 0 (forces along bonds);
 *  3. the forces are the gradient of the energy: V_i f_i = -dE/dx_i (central differences);
 *  4. LPS dilation: theta = d s exactly for an isotropic stretch s at every particle; theta =
 *     tr(H) for x = (I + H) X + c at particles with full (point-symmetric) families;
 *  5. isotropic stretch, energy density: LPS W = 9/2 K s^2 (3-D), 2 (lambda + mu) s^2 (plane
 * strain) at every particle (exact); PMB at interior particles within the lattice quadrature error.
 * Tolerances are given, with their reason, at each check.
 * labels: physics */
#include "bond_models_test.h"
#include "models/model_bond.h"

#define K_BULK 2.0
#define G_SHEAR 0.7
#define H_SPACING 0.37
#define M_RATIO 3.015

typedef struct body {
  pdk_particles *p;
  pdk_families *f;
  pdk_model *m;
  int dim;
  pdk_index n;
  double delta;
} body;

static body make_body(pdk_ctx *ctx, int dim, pdk_model_kind kind, double lc, double jitter,
                      double vol_noise) {
  body b;
  b.dim = dim;
  b.p = bm_body(ctx, dim, dim == 3 ? 12 : 36, dim == 3 ? 11 : 33, 10, H_SPACING, jitter, vol_noise,
                77 + (uint64_t)dim);
  b.n = pdk_particles_count(b.p);
  b.delta = M_RATIO * H_SPACING;
  b.f = bm_families(ctx, b.p, b.delta);
  b.m = bm_model(ctx, b.p, b.f, kind, K_BULK, G_SHEAR, lc, 0.0, 0.0);
  return b;
}

static void free_body(body *b) {
  pdk_model_destroy(&b->m);
  pdk_families_destroy(&b->f);
  pdk_particles_destroy(&b->p);
}

static double max_force(body *b) {
  double mx = 0;
  for (pdk_index i = 0; i < b->n; ++i) {
    double s = 0;
    for (int a = 0; a < b->dim; ++a) {
      double v = ((double *)pdk_particles_field_data(b->p, "f", a))[i];
      s += v * v;
    }
    mx = fmax(mx, sqrt(s));
  }
  return mx;
}

static void isotropic(body *b, double s) {
  double F[9] = {0}, t[3] = {0};
  for (int a = 0; a < b->dim; ++a)
    F[a * b->dim + a] = 1.0 + s;
  bm_displace_affine(b->p, F, t);
}

/* Rotation by `angle` about the unit axis (3-D) or in the plane (2-D), row-major. */
static void rotation(int dim, double angle, double *R) {
  double c = cos(angle), s = sin(angle);
  if (dim == 2) {
    R[0] = c, R[1] = -s, R[2] = s, R[3] = c;
    return;
  }
  double u[3] = {1.0, 2.0, 3.0}, nu = sqrt(14.0);
  for (int a = 0; a < 3; ++a)
    u[a] /= nu;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double cross = 0;
      if (a == 0 && b == 1) cross = -u[2];
      if (a == 0 && b == 2) cross = u[1];
      if (a == 1 && b == 0) cross = u[2];
      if (a == 1 && b == 2) cross = -u[0];
      if (a == 2 && b == 0) cross = -u[1];
      if (a == 2 && b == 1) cross = u[0];
      R[a * 3 + b] = (a == b ? c : 0.0) + s * cross + (1.0 - c) * u[a] * u[b];
    }
}

/* Distance of particle i from the body's bounding box faces, in units of the horizon. */
static int interior(body *b, pdk_index i, double margin) {
  for (int a = 0; a < b->dim; ++a) {
    const double *X = pdk_particles_X(b->p, a);
    double lo = X[0], hi = X[0];
    for (pdk_index k = 0; k < b->n; ++k)
      lo = fmin(lo, X[k]), hi = fmax(hi, X[k]);
    if (X[i] - lo < margin || hi - X[i] < margin) return 0;
  }
  return 1;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double K = K_BULK, G = G_SHEAR, lambda = K - 2.0 * G / 3.0, mu = G;

  for (int dim = 2; dim <= 3; ++dim)
    for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind)
      for (int with_lc = 0; with_lc <= 1; ++with_lc) {
        const char *name = pdk_model_kind_name((pdk_model_kind)kind);
        const double lc = with_lc ? H_SPACING : 0.0;
        body b = make_body(ctx, dim, (pdk_model_kind)kind, lc, 0.2, 0.2);

        /* Force of a unit strain: boundary forces of an isotropic stretch s, divided by s. */
        const double s_unit = 1e-3;
        isotropic(&b, s_unit);
        T_OK(ctx, pdk_model_force(b.m, NULL));
        const double f_unit = max_force(&b) / s_unit;
        T_ASSERT(f_unit > 0, "%s: nonzero boundary force under stretch", name);

        /* 1. Rigid motion. x = R X + c with |x| up to ~20 h: coordinates carry round-off
         * ~20 eps h, so bond stretches are ~40 eps ~ 1e-14 and forces ~1e-14 f_unit summed over
         * ~120 bonds (random signs): tolerance 1e-11 f_unit, far below any physical strain. */
        {
          double R[9], t[3] = {5.1 * H_SPACING, -3.3 * H_SPACING, 2.7 * H_SPACING};
          rotation(dim, 0.7, R);
          bm_displace_affine(b.p, R, t);
          double e = -1;
          T_OK(ctx, pdk_model_force(b.m, &e));
          double fr = max_force(&b);
          T_ASSERT(fr <= 1e-11 * f_unit,
                   "%s %d-D lc=%g: rigid motion gives |f| = %g (unit-strain "
                   "force %g)",
                   name, dim, lc, fr, f_unit);
          /* Energy ~ K s^2 sum V with s ~ 1e-14 (see above): tolerance 1e-20 K sum V. */
          double vsum = 0;
          for (pdk_index i = 0; i < b.n; ++i)
            vsum += pdk_particles_volume(b.p)[i];
          T_ASSERT(fabs(e) <= 1e-20 * K * vsum, "%s %d-D: rigid motion energy %g", name, dim, e);
        }

        /* 2. Momentum and moment under random displacements. Each bond force appears twice (from
         * i and from j) with independent rounding of a few ulp, so the sums vanish to
         * ~eps * sqrt(#bonds) * sum V |f|; tolerance 1e-12 sum V |f| (margin ~ 100). */
        {
          bm_displace_random(b.p, 0.03 * H_SPACING, 4242);
          T_OK(ctx, pdk_model_force(b.m, NULL));
          const double *V = pdk_particles_volume(b.p);
          double P[3] = {0}, L[3] = {0}, Pscale = 0, Lscale = 0;
          for (pdk_index i = 0; i < b.n; ++i) {
            double f[3] = {0}, x[3] = {0};
            for (int a = 0; a < dim; ++a) {
              f[a] = ((double *)pdk_particles_field_data(b.p, "f", a))[i];
              x[a] = ((double *)pdk_particles_field_data(b.p, "x", a))[i];
              P[a] += V[i] * f[a];
            }
            L[0] += V[i] * (x[1] * f[2] - x[2] * f[1]);
            L[1] += V[i] * (x[2] * f[0] - x[0] * f[2]);
            L[2] += V[i] * (x[0] * f[1] - x[1] * f[0]);
            double fn = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
            Pscale += V[i] * fn;
            Lscale += V[i] * fn * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
          }
          for (int a = 0; a < 3; ++a) {
            T_NEAR(P[a], 0.0, 0.0, 1e-12 * Pscale, "%s %d-D lc=%g: net force component %d", name,
                   dim, lc, a);
            T_NEAR(L[a], 0.0, 0.0, 1e-12 * Lscale, "%s %d-D lc=%g: net moment component %d", name,
                   dim, lc, a);
          }

          /* 3. V_i f_i = -dE/dx_i by central differences with step eps_x = 1e-6 h: truncation
           * ~eps_x^2 E''' (relative 1e-10 here), round-off ~ 1e-16 E / eps_x. */
          const double hx = 1e-6 * H_SPACING;
          double E0 = 0;
          T_OK(ctx, pdk_model_force_trial(b.m, &E0));
          const pdk_index probe[3] = {0, b.n / 2 + 3, b.n - 5};
          for (int q = 0; q < 3; ++q)
            for (int a = 0; a < dim; ++a) {
              const pdk_index i = probe[q];
              double *x = pdk_particles_field_data(b.p, "x", a);
              T_OK(ctx, pdk_model_force_trial(b.m, NULL)); /* f at the unperturbed x */
              const double f = ((double *)pdk_particles_field_data(b.p, "f", a))[i];
              const double x0 = x[i];
              double Ep = 0, Em = 0;
              x[i] = x0 + hx;
              T_OK(ctx, pdk_model_force_trial(b.m, &Ep));
              x[i] = x0 - hx;
              T_OK(ctx, pdk_model_force_trial(b.m, &Em));
              x[i] = x0;
              const double dEdx = (Ep - Em) / (2 * hx);
              T_NEAR(V[i] * f, -dEdx, 1e-6, 1e-15 * E0 / hx,
                     "%s %d-D lc=%g: V f vs -dE/dx, particle %d component %d", name, dim, lc,
                     (int)i, a);
            }
        }

        /* 4./5. Isotropic stretch s: LPS theta = d s and W = e_bulk d^2 s^2 / 2 at every
         * particle, whatever its family (theta = d/m sum e beta V with e = s r0 exactly in
         * exact arithmetic). Round-off: e = r - r0 from coordinates of size ~10 h carries
         * ~20 eps r0 absolute, so relative 20 eps / s = 4.4e-12 at s = 1e-3: tolerance 1e-10. */
        {
          const double s = 1e-3;
          isotropic(&b, s);
          double E = 0;
          T_OK(ctx, pdk_model_force(b.m, &E));
          const double *W = kind == PDK_MODEL_PMB ? pdk_model_pmb_energy_density(b.m)
                                                  : pdk_model_lps_energy_density(b.m);
          T_ASSERT(W != NULL, "energy density available after a pass with energy");
          /* PMB fixes nu = 1/4: lambda = mu = 3K/5 whatever G; LPS uses K and G. */
          const double W_cont = dim == 3                ? 4.5 * K * s * s
                                : kind == PDK_MODEL_PMB ? 2.0 * 1.2 * K * s * s
                                                        : 2.0 * (lambda + mu) * s * s;
          const double *V = pdk_particles_volume(b.p);
          double Esum = 0;
          int num_interior = 0;
          double wmin = HUGE_VAL, wmax = 0;
          for (pdk_index i = 0; i < b.n; ++i) {
            Esum += V[i] * W[i];
            if (kind == PDK_MODEL_LPS) {
              const double th = ((double *)pdk_particles_field_data(b.p, "theta", 0))[i];
              T_NEAR(th, dim * s, 1e-10, 0.0, "%d-D lc=%g: lps dilation at particle %d", dim, lc,
                     (int)i);
              T_NEAR(W[i], W_cont, 1e-9, 0.0, "%d-D lc=%g: lps energy density at particle %d", dim,
                     lc, (int)i);
            } else if (interior(&b, i, b.delta + 0.5 * H_SPACING)) {
              ++num_interior;
              wmin = fmin(wmin, W[i] / W_cont);
              wmax = fmax(wmax, W[i] / W_cont);
            }
          }
          T_NEAR(E, Esum, 1e-12, 0.0, "%s %d-D: total energy = sum V W", name, dim);
          if (kind == PDK_MODEL_PMB) {
            /* PMB interior W = (c/4) s^2 sum_j r0 beta V_j: a lattice quadrature of
             * integral |xi| dV over the horizon. On the exact lattice at m = 3.015 it is 1.099
             * (3-D) and 1.025 (2-D) of the integral with full volumes, 0.890 and 0.862 with
             * LAMMPS's partial volumes (checked exactly further down). Here the lattice is
             * jittered by +-0.2 h, which moves points across the horizon and the partial-volume
             * band, and volumes carry +-20 % noise: single particles scatter over 0.70 .. 1.17
             * (measured). Tolerance: W / W_continuum within [0.6, 1.4]. */
            T_ASSERT(num_interior > 0, "the body has interior particles");
            T_ASSERT(wmin >= 0.6 && wmax <= 1.4,
                     "pmb %d-D lc=%g: interior W / W_continuum in [%g, %g], outside [0.6, 1.4]",
                     dim, lc, wmin, wmax);
          }
        }
        free_body(&b);
      }

  /* Exact quadrature checks on unjittered lattices with uniform volumes. */
  for (int dim = 2; dim <= 3; ++dim)
    for (int with_lc = 0; with_lc <= 1; ++with_lc) {
      const double lc = with_lc ? H_SPACING : 0.0;
      /* LPS: theta = tr(H) for x = (I + H) X + c at interior particles: the family is point
       * symmetric with cubic (square) symmetry, so sum_j omega xi xi beta V = (m/d) I and the
       * linearised extension gives theta = tr(H) exactly. Second-order terms are <= 1.5 |H|^2
       * (|H| ~ 3e-6 here: 1.4e-11); round-off of e as above ~1e-13: tolerance 1.5|H|_F^2 + 1e-12,
       * against theta ~ 1e-6 (jittered families are off by ~1e-8). */
      body b = make_body(ctx, dim, PDK_MODEL_LPS, lc, 0.0, 0.0);
      double H[9] = {0}, F[9] = {0}, t[3] = {0.3, -0.2, 0.1}, trH = 0, H2 = 0;
      uint64_t seed = 31;
      for (int a = 0; a < dim; ++a)
        for (int c = 0; c < dim; ++c) {
          H[a * dim + c] = 1e-6 * bm_rng_sym(&seed);
          F[a * dim + c] = (a == c ? 1.0 : 0.0) + H[a * dim + c];
          H2 += H[a * dim + c] * H[a * dim + c];
        }
      for (int a = 0; a < dim; ++a)
        trH += H[a * dim + a];
      bm_displace_affine(b.p, F, t);
      T_OK(ctx, pdk_model_force(b.m, NULL));
      const double *theta = pdk_particles_field_data(b.p, "theta", 0);
      int num_interior = 0;
      for (pdk_index i = 0; i < b.n; ++i) {
        if (!interior(&b, i, b.delta + 0.5 * H_SPACING)) continue;
        ++num_interior;
        T_NEAR(theta[i], trH, 0.0, 1.5 * H2 + 1e-12,
               "%d-D lc=%g: lps dilation of an affine deformation at interior particle %d", dim, lc,
               (int)i);
      }
      T_ASSERT(num_interior > 0, "the body has interior particles");
      free_body(&b);

      /* PMB on the exact lattice: interior W / W_continuum equals the lattice sum
       * sum_j |xi_j| beta_j V / integral |xi| dV computed here, to round-off. */
      b = make_body(ctx, dim, PDK_MODEL_PMB, lc, 0.0, 0.0);
      const double s = 1e-3;
      isotropic(&b, s);
      double E = 0;
      T_OK(ctx, pdk_model_force(b.m, &E));
      const double *W = pdk_model_pmb_energy_density(b.m);
      double sum = 0;
      const int R = 4;
      for (int i = -R; i <= R; ++i)
        for (int j = -R; j <= R; ++j)
          for (int k = (dim == 3 ? -R : 0); k <= (dim == 3 ? R : 0); ++k) {
            double r2 = (double)(i * i + j * j + k * k);
            if (r2 == 0 || r2 > M_RATIO * M_RATIO) continue;
            double r = sqrt(r2), beta = lc > 0 ? fmin(1.0, M_RATIO + 0.5 - r) : 1.0;
            sum += r * beta;
          }
      const double ratio =
          dim == 3 ? sum / (M_PI * pow(M_RATIO, 4)) : sum / (2.0 * M_PI * pow(M_RATIO, 3) / 3.0);
      const double W_cont = dim == 3 ? 4.5 * K * s * s : 2.0 * 1.2 * K * s * s; /* lambda = mu */
      for (pdk_index i = 0; i < b.n; ++i)
        if (interior(&b, i, b.delta + 0.5 * H_SPACING))
          T_NEAR(W[i] / W_cont, ratio, 1e-9, 0.0, "pmb %d-D lc=%g: interior W at particle %d", dim,
                 lc, (int)i);
      free_body(&b);
    }
  pdk_ctx_destroy(&ctx);
  return 0;
}
