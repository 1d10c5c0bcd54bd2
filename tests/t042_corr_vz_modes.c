/* Correspondence model, V-Z: zero-energy modes of the stiffness of periodic lattices, and
 * families that do not span the space.
 * labels: physics
 *
 * Periodic stiffness. The library has no periodic families, so the test embeds the periodic
 * n^d lattice (unit spacing) as the central block of an (n + 2g)^d lattice with g = ceil(2m)
 * ghost layers, and gives every particle the displacement of its periodic image in the central
 * block. The force on a central particle depends on positions within 2 delta of it (its own and its
 * neighbours' F), and every neighbour's family is complete, so the forces on the central block are
 * exactly those of the periodic lattice. The stiffness K = -d(V f)/du (V = 1) is then a linear map
 * on the n^d d displacement vector; the lattice is translation invariant, so K[q][p] = K[q-p][0]:
 * the d columns of central particle 0 (central differences of the library's force; exact for the
 * linear laws, whose force is linear in u) give the whole matrix, and one more column, of another
 * particle, checks the invariance. Zero eigenvalues are counted with LAPACKE: dsyev for the
 * symmetric cases (no stabilization, Silling), singular values (dgesvd) for the hourglass form,
 * whose linearisation is not symmetric.
 *
 * Expected count (V-Z, docs/validation/targets.md): d times the number of grid wave vectors
 * q = 2 pi k / n with g(q) = sum_k omega_k sin(q . xi_k) xi_k = 0 (the discrete gradient of e^{i q.X} vanishes);
 * computed here and checked against the table values. A stabilized model keeps only the d
 * translations.
 *
 * Thresholds. Linear cases: f is linear in u, the FD step h = 0.1 is exact but for the round-off of
 * x ~ eps (n + 2g) / h ~ 1e-13 relative; an eigenvalue is zero below 1e-9 of the largest.
 * Hourglass: f is nonlinear, h = 1e-5 balances truncation (h^2) and cancellation (eps N / h),
 * ~1e-10 relative; zero below 1e-7 of the largest singular value.
 */
#include <lapacke.h>

#include "corr_util.h"
#include "kernels.h" /* PDK_CORR_FLAG_SPAN */

/* ---- expected count from the gradient symbol ---------------------------------------------- */

static int expected_zeros(int d, int n, double m, int infl) {
  int off[512][3], noff = 0;
  const int R = cu_reach(m);
  double w[512];
  for (int a = -R; a <= R; ++a)
    for (int b = -R; b <= R; ++b)
      for (int c = (d == 3 ? -R : 0); c <= (d == 3 ? R : 0); ++c) {
        const double r2 = (double)(a * a + b * b + c * c);
        if (r2 == 0.0 || r2 > m * m * (1.0 + 1e-12)) continue;
        off[noff][0] = a, off[noff][1] = b, off[noff][2] = c;
        w[noff] = cu_omega(infl, sqrt(r2), m);
        ++noff;
      }
  double wsum = 0.0;
  for (int k = 0; k < noff; ++k)
    wsum += w[k] * sqrt(off[k][0] * off[k][0] + off[k][1] * off[k][1] + off[k][2] * off[k][2]);
  int zeros = 0;
  const int nz = d == 3 ? n : 1;
  const double two_pi = 6.283185307179586;
  for (int ka = 0; ka < n; ++ka)
    for (int kb = 0; kb < n; ++kb)
      for (int kc = 0; kc < nz; ++kc) {
        const double q[3] = {two_pi * ka / n, two_pi * kb / n, two_pi * kc / n};
        double g[3] = {0, 0, 0};
        for (int k = 0; k < noff; ++k) {
          const double s = sin(q[0] * off[k][0] + q[1] * off[k][1] + q[2] * off[k][2]);
          for (int a = 0; a < 3; ++a)
            g[a] += w[k] * s * off[k][a];
        }
        zeros += sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) <= 1e-9 * wsum;
      }
  return d * zeros;
}

/* ---- periodic stiffness ------------------------------------------------------------------- */

typedef struct periodic {
  int d, n, g, N;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_index *image;   /* [num particles] central index of each particle's periodic image */
  pdk_index *central; /* [n^d] particle index of each central lattice site */
} periodic;

static int site_index(int d, int n, const int *k) {
  return d == 2 ? k[0] + n * k[1] : k[0] + n * (k[1] + n * k[2]);
}

static void periodic_build(pdk_ctx *ctx, periodic *P, int d, int n, double mh,
                           const pdk_model_opts *o) {
  P->d = d, P->n = n, P->g = (int)ceil(2.0 * mh), P->N = n + 2 * P->g;
  P->p = cu_lattice(ctx, d, P->N, 0.0, 0);
  P->fam = cu_families(ctx, P->p, mh);
  P->m = cu_model(ctx, P->p, P->fam, o);
  const pdk_index np = pdk_particles_count(P->p);
  int nc = 1;
  for (int a = 0; a < d; ++a)
    nc *= n;
  P->image = malloc((size_t)np * sizeof *P->image);
  P->central = malloc((size_t)nc * sizeof *P->central);
  for (pdk_index i = 0; i < np; ++i) {
    int k[3] = {0, 0, 0}, inside = 1;
    for (int a = 0; a < d; ++a) {
      const int ka = cu_index(P->p, a, i) - P->g;
      inside = inside && ka >= 0 && ka < n;
      k[a] = ((ka % n) + n) % n;
    }
    P->image[i] = site_index(d, n, k);
    if (inside) P->central[P->image[i]] = i;
  }
}

static void periodic_free(periodic *P) {
  pdk_model_destroy(&P->m);
  pdk_families_destroy(&P->fam);
  pdk_particles_destroy(&P->p);
  free(P->image);
  free(P->central);
}

/* col[(c*d + b)] = -d(V f_b of central site c)/d(u_a of site s), by central differences. */
static void periodic_column(pdk_ctx *ctx, periodic *P, pdk_index s, int a, double h, double *col) {
  const int d = P->d;
  const pdk_index np = pdk_particles_count(P->p);
  int nc = 1;
  for (int t = 0; t < d; ++t)
    nc *= P->n;
  double *x = cu_field(P->p, "x", a);
  const double *V = pdk_particles_volume(P->p);
  for (int sign = 1; sign >= -1; sign -= 2) {
    cu_reset_x(P->p);
    for (pdk_index i = 0; i < np; ++i)
      if (P->image[i] == s) x[i] += sign * h;
    T_OK(ctx, pdk_model_force_trial(P->m, NULL));
    for (int c = 0; c < nc; ++c)
      for (int b = 0; b < d; ++b) {
        const pdk_index i = P->central[c];
        const double v = -V[i] * cu_field(P->p, "f", b)[i] / (2.0 * h);
        col[c * d + b] = sign > 0 ? v : col[c * d + b] - v;
      }
  }
  cu_reset_x(P->p);
}

/* Assembles the dense stiffness [ndof x ndof], row-major. */
static double *periodic_stiffness(pdk_ctx *ctx, periodic *P, double h, int *ndof_out) {
  const int d = P->d, n = P->n;
  int nc = 1;
  for (int t = 0; t < d; ++t)
    nc *= n;
  const int ndof = nc * d;
  double *col[3], *check = malloc((size_t)ndof * sizeof(double));
  for (int a = 0; a < d; ++a) {
    col[a] = malloc((size_t)ndof * sizeof(double));
    periodic_column(ctx, P, 0, a, h, col[a]);
  }
  double *K = malloc((size_t)ndof * (size_t)ndof * sizeof(double));
  double kmax = 0.0;
  for (int q = 0; q < nc; ++q) {
    const int kq[3] = {q % n, (q / n) % n, q / (n * n)};
    for (int p = 0; p < nc; ++p) {
      const int kp[3] = {p % n, (p / n) % n, p / (n * n)};
      int ks[3] = {0, 0, 0};
      for (int t = 0; t < d; ++t)
        ks[t] = ((kq[t] - kp[t]) % n + n) % n;
      const int r = site_index(d, n, ks);
      for (int b = 0; b < d; ++b)
        for (int a = 0; a < d; ++a) {
          const double v = col[a][r * d + b];
          K[(size_t)(q * d + b) * ndof + (size_t)(p * d + a)] = v;
          kmax = fmax(kmax, fabs(v));
        }
    }
  }
  /* Translation invariance: the column of another site equals the shifted column of site 0. */
  const int kshift[3] = {1 % n, 2 % n, d == 3 ? 3 % n : 0};
  const int s = site_index(d, n, kshift);
  periodic_column(ctx, P, s, d - 1, h, check);
  for (int i = 0; i < ndof; ++i)
    if (fabs(check[i] - K[(size_t)i * ndof + (size_t)(s * d + d - 1)]) > 1e-9 * kmax)
      T_FAIL("%d-D n = %d: the stiffness is not translation invariant (row %d: %.17g vs %.17g); "
             "the ghost layers do not reproduce the periodic lattice",
             d, n, i, check[i], K[(size_t)i * ndof + (size_t)(s * d + d - 1)]);
  for (int a = 0; a < d; ++a)
    free(col[a]);
  free(check);
  *ndof_out = ndof;
  return K;
}

/* Number of zero eigenvalues (symmetric) or singular values, relative threshold rtol. */
static int count_zeros(double *K, int ndof, int symmetric, double rtol, double *next_out) {
  double *ev = malloc((size_t)ndof * sizeof(double));
  lapack_int info;
  if (symmetric) {
    info = LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', ndof, K, ndof, ev);
    for (int i = 0; i < ndof; ++i)
      ev[i] = fabs(ev[i]);
  } else {
    double *superb = malloc((size_t)ndof * sizeof(double));
    info = LAPACKE_dgesvd(LAPACK_ROW_MAJOR, 'N', 'N', ndof, ndof, K, ndof, ev, NULL, 1, NULL, 1,
                          superb);
    free(superb);
  }
  T_ASSERT(info == 0, "LAPACKE %s failed with info %d", symmetric ? "dsyev" : "dgesvd", (int)info);
  double emax = 0.0;
  for (int i = 0; i < ndof; ++i)
    emax = fmax(emax, ev[i]);
  int zeros = 0;
  double next = emax;
  for (int i = 0; i < ndof; ++i) {
    if (ev[i] <= rtol * emax)
      ++zeros;
    else
      next = fmin(next, ev[i]);
  }
  *next_out = next / emax;
  free(ev);
  return zeros;
}

static void check_modes(pdk_ctx *ctx, int d, int n, double mh, int infl, int stab, int table) {
  const int expect = stab == PDK_STAB_NONE ? expected_zeros(d, n, mh, infl) : d;
  if (table >= 0)
    T_ASSERT(expect == table,
             "%d-D n = %d m = %g influence %s: g(q) gives %d zero modes, the "
             "V-Z table says %d",
             d, n, mh, cu_infl_name[infl], expect, table);
  pdk_model_opts o = cu_opts(PDK_LAW_LINEAR_ELASTIC, infl, stab, 0.1);
  periodic P;
  periodic_build(ctx, &P, d, n, mh, &o);
  const int hourglass = stab == PDK_STAB_HOURGLASS;
  int ndof = 0;
  double *K = periodic_stiffness(ctx, &P, hourglass ? 1e-5 : 0.1, &ndof);
  if (!hourglass) {
    double kmax = 0.0, asym = 0.0;
    for (int i = 0; i < ndof; ++i)
      for (int j = 0; j < ndof; ++j) {
        kmax = fmax(kmax, fabs(K[(size_t)i * ndof + j]));
        asym = fmax(asym, fabs(K[(size_t)i * ndof + j] - K[(size_t)j * ndof + i]));
      }
    T_ASSERT(asym <= 1e-10 * kmax, "%d-D n = %d: stiffness not symmetric (%.3g of %.3g)", d, n,
             asym, kmax);
  }
  double next = 0.0;
  const int zeros = count_zeros(K, ndof, !hourglass, hourglass ? 1e-7 : 1e-9, &next);
  T_ASSERT(zeros == expect,
           "%d-D n = %d m = %g influence %s stabilization %s: %d zero "
           "eigenvalues, expected %d (smallest non-zero: %.3g of the largest)",
           d, n, mh, cu_infl_name[infl], cu_stab_name[stab], zeros, expect, next);
  T_ASSERT(next > 1e-6, "%d-D n = %d m = %g: no clear gap above the zero eigenvalues (%.3g)", d, n,
           mh, next);
  free(K);
  periodic_free(&P);
}

/* ---- families that do not span ------------------------------------------------------------ */

static void check_all_finite(pdk_particles *p, const char *what) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  for (pdk_index i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a)
      T_ASSERT(isfinite(cu_field(p, "f", a)[i]), "%s: f[%d] of particle %d is %g", what, a, (int)i,
               cu_field(p, "f", a)[i]);
    for (int t = 0; t < d * d; ++t) {
      T_ASSERT(isfinite(cu_field(p, "F", t)[i]) && isfinite(cu_field(p, "A", t)[i]) &&
                   isfinite(cu_field(p, "Kinv", t)[i]),
               "%s: F, A or Kinv[%d] of particle %d not finite", what, t, (int)i);
    }
  }
}

static void check_singular(pdk_ctx *ctx) {
  /* 2-D: a 6 x 6 block, a whisker of 6 particles along x from its middle row, an isolated one. */
  const int nb = 36, nw = 6, n = nb + nw + 1;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, 2, n, &p));
  double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  for (int i = 0; i < nb; ++i)
    X[i] = 0.5 + i % 6, Y[i] = 0.5 + i / 6;
  for (int k = 0; k < nw; ++k)
    X[nb + k] = 6.5 + k, Y[nb + k] = 3.5;
  X[n - 1] = 40.0, Y[n - 1] = 40.0;
  for (int i = 0; i < n; ++i)
    V[i] = 1.0;
  pdk_families *fam = cu_families(ctx, p, 1.5);
  for (int law = 0; law < 3; ++law)
    for (int stab = 0; stab < 3; ++stab) {
      pdk_model_opts o = cu_opts(law, PDK_INFLUENCE_CONSTANT, stab, 0.1);
      pdk_model *m = cu_model(ctx, p, fam, &o);
      /* Whisker particles 1..5 see only collinear bonds; the isolated one none. */
      T_ASSERT(pdk_model_num_flagged(m) == nw - 1 + 1, "flagged after setup: %d, expected %d",
               (int)pdk_model_num_flagged(m), nw);
      cu_random_x(p, 0.05, 3);
      double e = 0.0;
      T_OK(ctx, pdk_model_force(m, &e));
      T_ASSERT(isfinite(e), "strain energy %g", e);
      check_all_finite(p, "2-D whisker");
      const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
      for (int i = 0; i < n; ++i) {
        const int expect = (i > nb && i < nb + nw) || i == n - 1;
        T_ASSERT((flag[i] != 0) == expect, "particle %d flag %d, expected %d", i, flag[i], expect);
        if (expect)
          for (int t = 0; t < 4; ++t)
            T_ASSERT(cu_field(p, "A", t)[i] == 0.0, "A of flagged %d", i);
      }
      T_ASSERT(pdk_model_num_flagged(m) == nw, "flagged after force: %d",
               (int)pdk_model_num_flagged(m));
      pdk_model_destroy(&m);
    }
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);

  /* 3-D: one plane of particles; every family is coplanar. */
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_CUBIC;
  lo.lo[0] = lo.lo[1] = lo.lo[2] = 0.0;
  lo.hi[0] = lo.hi[1] = 5.0, lo.hi[2] = 1.0;
  lo.spacing = 1.0;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  fam = cu_families(ctx, p, 1.5);
  pdk_model_opts o3 = cu_opts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CUBIC, PDK_STAB_SILLING, 0.1);
  pdk_model *m = cu_model(ctx, p, fam, &o3);
  T_ASSERT(pdk_model_num_flagged(m) == pdk_particles_count(p), "3-D sheet: %d of %d flagged",
           (int)pdk_model_num_flagged(m), (int)pdk_particles_count(p));
  cu_random_x(p, 0.05, 4);
  double e = 0.0;
  T_OK(ctx, pdk_model_force(m, &e));
  T_ASSERT(e == 0.0, "3-D sheet: every particle flagged, yet energy %g", e);
  check_all_finite(p, "3-D sheet");
  for (int a = 0; a < 3; ++a)
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      T_ASSERT(cu_field(p, "f", a)[i] == 0.0, "3-D sheet: force on particle %d", (int)i);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);

  /* Bonds broken by critical stretch: a particle pulled out of an 8 x 8 lattice loses every
   * bond, is flagged, and its neighbours' shape tensors are recomputed without it. */
  p = cu_lattice(ctx, 2, 8, 0.0, 0);
  fam = cu_families(ctx, p, 2.015);
  pdk_model_opts ob = cu_opts(PDK_LAW_SVK, PDK_INFLUENCE_CUBIC, PDK_STAB_SILLING, 0.1);
  ob.critical_stretch = 0.02;
  m = cu_model(ctx, p, fam, &ob);
  const pdk_index victim = 3 + 8 * 4, nfam = 12; /* m = 2.015: 12 neighbours */
  T_OK(ctx, pdk_model_force(m, NULL));
  T_ASSERT(pdk_model_num_broken(m) == 0 && pdk_model_num_flagged(m) == 0, "undeformed: %d broken",
           (int)pdk_model_num_broken(m));
  cu_field(p, "x", 0)[victim] += 50.0;
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  T_ASSERT(pdk_model_num_broken(m) == 0, "a trial pass broke bonds");
  T_OK(ctx, pdk_model_force(m, NULL));
  T_ASSERT(pdk_model_num_broken(m) == 2 * nfam, "%d directed bonds broken, expected %d",
           (int)pdk_model_num_broken(m), (int)(2 * nfam));
  cu_reset_x(p); /* back home: the bonds stay broken */
  T_OK(ctx, pdk_model_force(m, &e));
  T_ASSERT(pdk_model_num_flagged(m) == 1, "after breaking: %d flagged",
           (int)pdk_model_num_flagged(m));
  T_ASSERT(((const uint8_t *)pdk_particles_field_data(p, "flag", 0))[victim] == PDK_CORR_FLAG_SPAN,
           "the isolated particle is not flagged as not spanning");
  check_all_finite(p, "broken bonds");
  /* At x = X the remaining body is undeformed: F = I, no force, no energy anywhere. */
  T_ASSERT(fabs(e) <= 1e-20, "energy %g at x = X after breaking", e);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    if (i == victim) continue;
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c)
        T_NEAR(cu_field(p, "F", a * 2 + c)[i], a == c ? 1.0 : 0.0, 0.0, 1e-13,
               "F of particle %d after its neighbour's bonds broke", (int)i);
    for (int a = 0; a < 2; ++a)
      T_NEAR(cu_field(p, "f", a)[i], 0.0, 0.0, 1e-12, "force on particle %d", (int)i);
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  /* Table values of V-Z (ω = 1 is PDK_INFLUENCE_CONSTANT, 1/r^2 is PDK_INFLUENCE_INV_R2). */
  check_modes(ctx, 2, 8, 1.5, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 8);
  check_modes(ctx, 2, 8, 2.015, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 8);
  check_modes(ctx, 2, 8, 1.5, PDK_INFLUENCE_INV_R2, PDK_STAB_NONE, 32);
  check_modes(ctx, 2, 10, 2.015, PDK_INFLUENCE_INV_R2, PDK_STAB_NONE, 8);
  check_modes(ctx, 3, 5, 1.5, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 3);
  check_modes(ctx, 3, 6, 1.5, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 60);
  check_modes(ctx, 3, 8, 1.5, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 24);
  check_modes(ctx, 3, 8, 2.015, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 24);
  check_modes(ctx, 3, 8, 3.015, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 24);
  /* Other influence functions: the count from g(q) alone. */
  check_modes(ctx, 2, 6, 1.5, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 16);
  check_modes(ctx, 2, 8, 2.015, PDK_INFLUENCE_CUBIC, PDK_STAB_NONE, -1);
  check_modes(ctx, 2, 8, 3.015, PDK_INFLUENCE_GAUSSIAN, PDK_STAB_NONE, -1);
  check_modes(ctx, 2, 9, 2.015, PDK_INFLUENCE_INV_R, PDK_STAB_NONE, -1);
  /* Stabilized: only the d translations. */
  for (int stab = PDK_STAB_SILLING; stab <= PDK_STAB_HOURGLASS; ++stab) {
    check_modes(ctx, 2, 8, 1.5, PDK_INFLUENCE_CONSTANT, stab, 2);
    check_modes(ctx, 2, 8, 1.5, PDK_INFLUENCE_INV_R2, stab, 2);
    check_modes(ctx, 3, 6, 1.5, PDK_INFLUENCE_CONSTANT, stab, 3);
  }
  check_singular(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
