/* Correspondence model, V-INV, for every law x influence function x stabilization, 2-D and 3-D:
 * rigid translation and large rotation give zero force; an affine motion gives F = F0 exactly at
 * particles with full point-symmetric families (and there P = A K equals the law's P(F0), computed
 * here independently) and zero force where the neighbours' families are full too; forces sum to
 * zero and (objective laws) the net moment is zero; 1 and 2 threads give bitwise identical F, A, f
 * and strain energy. labels: physics threads
 *
 * Tolerances (round-off). Force densities are compared with f_scale = (lambda + 2 mu) / dx, the
 * force density of a unit strain varying over one spacing. Positions are O(L) = O(25 dx), so a
 * bond vector Y carries an absolute error of ~eps L; F = N K^-1 sums ~20 such bonds with
 * cond(K) <= ~10, and A, f multiply by another K^-1 and sum again: |f| ~ 10..100 eps (L/dx)
 * f_scale; measured at most 1.5e-13 f_scale. Tolerance 1e-12 f_scale. F itself: 1e-12 absolute
 * (one K^-1 product of O(1) entries). Momentum and moment: 1e-13 of the sum of magnitudes
 * (measured 2e-17).
 * The small-strain linear elastic law is not objective (eps = sym(F) - I != 0 under a finite
 * rotation), so for it the rotation is 1e-7 rad (strain 5e-15) and the moment test is skipped; the
 * same holds for the moment of sigma F^T, which is symmetric only for frame-indifferent laws.
 */
#include "corr_util.h"

typedef struct run_out {
  double *f[3], *F[9], *A[9], energy;
  uint8_t *flag;
} run_out;

/* Small dense helpers, row-major d x d. */
static void mat_mul(int d, const double *A, const double *B, double *C) {
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int k = 0; k < d; ++k)
        s += A[r * d + k] * B[k * d + c];
      C[r * d + c] = s;
    }
}

static void mat_inverse(int d, const double *A, double *R) { /* Gauss-Jordan, partial pivoting */
  double M[3][6];
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < 2 * d; ++c)
      M[r][c] = c < d ? A[r * d + c] : (c - d == r ? 1.0 : 0.0);
  for (int c = 0; c < d; ++c) {
    int piv = c;
    for (int r = c + 1; r < d; ++r)
      if (fabs(M[r][c]) > fabs(M[piv][c])) piv = r;
    for (int k = 0; k < 2 * d; ++k) {
      const double t = M[c][k];
      M[c][k] = M[piv][k], M[piv][k] = t;
    }
    const double s = 1.0 / M[c][c];
    for (int k = 0; k < 2 * d; ++k)
      M[c][k] *= s;
    for (int r = 0; r < d; ++r)
      if (r != c) {
        const double f = M[r][c];
        for (int k = 0; k < 2 * d; ++k)
          M[r][k] -= f * M[c][k];
      }
  }
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      R[r * d + c] = M[r][c + d];
}

/* First Piola-Kirchhoff stress of each law at F (2-D: plane strain, out-of-plane stretch 1).
 * Neo-Hooke through the Kirchhoff stress tau = mu (F F^T - I) + lambda ln J I, P = tau F^-T. */
static void law_P(int d, int law, const double *F, double *P) {
  const double lambda = CU_BULK - 2.0 * CU_SHEAR / 3.0, mu = CU_SHEAR;
  double Ft[9], M[9], S[9];
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c)
      Ft[r * d + c] = F[c * d + r];
  if (law == PDK_LAW_LINEAR_ELASTIC) {
    double tr = 0.0;
    for (int a = 0; a < d; ++a)
      tr += F[a * d + a] - 1.0;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        P[r * d + c] =
            mu * (F[r * d + c] + Ft[r * d + c]) - (r == c ? 2.0 * mu - lambda * tr : 0.0);
  } else if (law == PDK_LAW_SVK) {
    mat_mul(d, Ft, F, M); /* C */
    double tr = 0.0;
    for (int a = 0; a < d; ++a)
      tr += 0.5 * (M[a * d + a] - 1.0);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        S[r * d + c] = mu * (M[r * d + c] - (r == c)) + (r == c ? lambda * tr : 0.0);
    mat_mul(d, F, S, P);
  } else {
    double Finv[9], FinvT[9];
    mat_inverse(d, F, Finv);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        FinvT[r * d + c] = Finv[c * d + r];
    mat_mul(d, F, Ft, M); /* b = F F^T */
    const double J = d == 2
                         ? F[0] * F[3] - F[1] * F[2]
                         : F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                               F[2] * (F[3] * F[7] - F[4] * F[6]);
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        S[r * d + c] = mu * (M[r * d + c] - (r == c)) + (r == c ? lambda * log(J) : 0.0);
    mat_mul(d, S, FinvT, P);
  }
}

static double max_abs_force(pdk_particles *p, const pdk_index *sel, pdk_index nsel) {
  const int d = pdk_particles_dim(p);
  double mx = 0.0;
  for (pdk_index s = 0; s < nsel; ++s)
    for (int a = 0; a < d; ++a)
      mx = fmax(mx, fabs(cu_field(p, "f", a)[sel[s]]));
  return mx;
}

static void check_case(pdk_ctx *ctx, int dim, int law, int infl, int stab) {
  /* Jittered lattice for rigid motion, momentum and threads; regular lattice for affine. */
  const int N = dim == 2 ? 24 : 9;
  const double mh = dim == 2 ? 2.015 : 1.5;
  const double lambda = CU_BULK - 2.0 * CU_SHEAR / 3.0, mu = CU_SHEAR;
  const double f_scale = lambda + 2.0 * mu; /* dx = 1 */
  const double ftol = 1e-12 * f_scale;
  char what[160];
  snprintf(what, sizeof what, "%d-D law %s influence %s stabilization %s", dim, cu_law_name[law],
           cu_infl_name[infl], cu_stab_name[stab]);
  pdk_model_opts o = cu_opts(law, infl, stab, 0.5);

  for (int jit = 0; jit < 2; ++jit) {
    pdk_particles *p = cu_lattice(ctx, dim, N, jit ? 0.2 : 0.0, 17);
    pdk_families *fam = cu_families(ctx, p, mh);
    pdk_model *m = cu_model(ctx, p, fam, &o);
    const pdk_index n = pdk_particles_count(p);
    pdk_index *all = malloc((size_t)n * sizeof *all);
    for (pdk_index i = 0; i < n; ++i)
      all[i] = i;
    T_ASSERT(pdk_model_num_flagged(m) == 0, "%s: no family should be flagged, got %d", what,
             (int)pdk_model_num_flagged(m));
    double e = 0.0;

    /* Rigid translation. */
    double c[3] = {3.25, -1.5, 0.75}, I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, F0[9];
    if (dim == 2) I[2] = 0, I[3] = 1;
    cu_affine(p, I, c);
    T_OK(ctx, pdk_model_force(m, &e));
    double fmax = max_abs_force(p, all, n);
    T_ASSERT(fmax <= ftol, "%s, jitter %d: translation gives force %.3g > %.3g", what, jit, fmax,
             ftol);
    T_ASSERT(fabs(e) <= 1e-14 * f_scale * n, "%s: translation gives strain energy %.3g", what, e);

    /* Rigid rotation: large, except for the small-strain law. */
    const double angle = law == PDK_LAW_LINEAR_ELASTIC ? 1e-7 : 1.1;
    cu_rotation(dim, angle, F0);
    cu_affine(p, F0, c);
    T_OK(ctx, pdk_model_force(m, &e));
    fmax = max_abs_force(p, all, n);
    T_ASSERT(fmax <= ftol, "%s, jitter %d: rotation by %g rad gives force %.3g > %.3g", what, jit,
             angle, fmax, ftol);
    /* Energy: W(F) carries terms linear in the round-off of F (Neo-Hooke: F:F - d and ln J),
     * so ~10 eps (lambda + 2 mu) per unit-volume particle. */
    T_ASSERT(fabs(e) <= 1e-14 * f_scale * n, "%s: rotation gives strain energy %.3g", what, e);

    if (!jit) {
      /* Affine motion: F = F0 at full families, f = 0 where neighbours' families are full. */
      const double G2[4] = {1.08, 0.21, -0.07, 0.93};
      const double G3[9] = {1.08, 0.21, -0.05, -0.07, 0.93, 0.12, 0.03, -0.11, 1.04};
      const double *G = dim == 2 ? G2 : G3;
      cu_affine(p, G, c);
      T_OK(ctx, pdk_model_force(m, &e));
      const int M = cu_reach(mh);
      pdk_index nfull = 0, nzero = 0;
      for (pdk_index i = 0; i < n; ++i) {
        if (cu_inside(p, i, N, M)) {
          ++nfull;
          for (int t = 0; t < dim * dim; ++t)
            T_NEAR(cu_field(p, "F", t)[i], G[t], 0.0, 1e-12, "%s: F[%d] at particle %d", what, t,
                   (int)i);
          /* The stress: P = A K must be the law's P(F0), computed here independently. */
          double Kinv[9], K[9], A[9], P[9], Pw[9];
          for (int t = 0; t < dim * dim; ++t) {
            Kinv[t] = cu_field(p, "Kinv", t)[i];
            A[t] = cu_field(p, "A", t)[i];
          }
          mat_inverse(dim, Kinv, K);
          mat_mul(dim, A, K, P);
          law_P(dim, law, G, Pw);
          for (int t = 0; t < dim * dim; ++t)
            T_NEAR(P[t], Pw[t], 0.0, 1e-12 * f_scale, "%s: P[%d] at particle %d", what, t, (int)i);
        }
        if (cu_inside(p, i, N, 2 * M)) {
          ++nzero;
          for (int a = 0; a < dim; ++a)
            T_NEAR(cu_field(p, "f", a)[i], 0.0, 0.0, ftol,
                   "%s: affine force[%d] at interior particle %d", what, a, (int)i);
        }
      }
      T_ASSERT(nfull > 0 && nzero > 0, "%s: the lattice has no interior", what);
    }

    /* Random motion: momentum, moment, threads. */
    cu_random_x(p, 0.05, 99 + (uint64_t)jit);
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
    double e1 = 0.0;
    T_OK(ctx, pdk_model_force(m, &e1));
    run_out r1;
    for (int a = 0; a < dim; ++a) {
      r1.f[a] = malloc((size_t)n * sizeof(double));
      memcpy(r1.f[a], cu_field(p, "f", a), (size_t)n * sizeof(double));
    }
    for (int t = 0; t < dim * dim; ++t) {
      r1.F[t] = malloc((size_t)n * sizeof(double));
      r1.A[t] = malloc((size_t)n * sizeof(double));
      memcpy(r1.F[t], cu_field(p, "F", t), (size_t)n * sizeof(double));
      memcpy(r1.A[t], cu_field(p, "A", t), (size_t)n * sizeof(double));
    }
    /* Momentum and moment, summed in long double for a clean reference. */
    const double *V = pdk_particles_volume(p);
    long double P[3] = {0, 0, 0}, Mz[3] = {0, 0, 0}, Pabs = 0, Mabs = 0;
    const double *x[3] = {cu_field(p, "x", 0), cu_field(p, "x", 1),
                          dim == 3 ? cu_field(p, "x", 2) : NULL};
    for (pdk_index i = 0; i < n; ++i) {
      double fi[3] = {r1.f[0][i], r1.f[1][i], dim == 3 ? r1.f[2][i] : 0.0};
      double xi[3] = {x[0][i], x[1][i], dim == 3 ? x[2][i] : 0.0};
      for (int a = 0; a < dim; ++a) {
        P[a] += (long double)V[i] * fi[a];
        Pabs += fabsl((long double)V[i] * fi[a]);
      }
      const double mom[3] = {xi[1] * fi[2] - xi[2] * fi[1], xi[2] * fi[0] - xi[0] * fi[2],
                             xi[0] * fi[1] - xi[1] * fi[0]};
      for (int a = 0; a < 3; ++a) {
        Mz[a] += (long double)V[i] * mom[a];
        Mabs += fabsl((long double)V[i] * mom[a]);
      }
    }
    for (int a = 0; a < dim; ++a)
      T_ASSERT(fabsl(P[a]) <= 1e-13L * Pabs, "%s, jitter %d: sum V f [%d] = %.3Lg of %.3Lg", what,
               jit, a, P[a], Pabs);
    if (law != PDK_LAW_LINEAR_ELASTIC)
      for (int a = 0; a < 3; ++a)
        T_ASSERT(fabsl(Mz[a]) <= 1e-13L * Mabs, "%s, jitter %d: net moment [%d] = %.3Lg of %.3Lg",
                 what, jit, a, Mz[a], Mabs);

    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
    double e2 = 0.0;
    T_OK(ctx, pdk_model_force(m, &e2));
    T_ASSERT(memcmp(&e1, &e2, sizeof e1) == 0, "%s: energy %.17g (1 thread) vs %.17g (2)", what, e1,
             e2);
    for (int a = 0; a < dim; ++a)
      T_ASSERT(memcmp(r1.f[a], cu_field(p, "f", a), (size_t)n * sizeof(double)) == 0,
               "%s: f[%d] differs between 1 and 2 threads", what, a);
    for (int t = 0; t < dim * dim; ++t) {
      T_ASSERT(memcmp(r1.F[t], cu_field(p, "F", t), (size_t)n * sizeof(double)) == 0,
               "%s: F[%d] differs between 1 and 2 threads", what, t);
      T_ASSERT(memcmp(r1.A[t], cu_field(p, "A", t), (size_t)n * sizeof(double)) == 0,
               "%s: A[%d] differs between 1 and 2 threads", what, t);
    }
    T_ASSERT(isfinite(e1) && e1 > 0.0, "%s: strain energy %g under random motion", what, e1);
    for (int a = 0; a < dim; ++a)
      free(r1.f[a]);
    for (int t = 0; t < dim * dim; ++t)
      free(r1.F[t]), free(r1.A[t]);
    free(all);
    pdk_model_destroy(&m);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int dim = 2; dim <= 3; ++dim)
    for (int law = 0; law < 3; ++law)
      for (int infl = 0; infl < 6; ++infl)
        for (int stab = 0; stab < 3; ++stab)
          check_case(ctx, dim, law, infl, stab);
  pdk_ctx_destroy(&ctx);
  return 0;
}
