/* Helpers of the Peridynamic Galerkin tests (t240-t243) and bench: the linear patch test of Bode
 * et al. 2022 (Table 2) and Bode 2021 (section 7.2.2, Table 7.2) on an irregular cloud.
 *
 * Cloud: [-1, 1]^2, a (n1 x n1) node lattice of spacing h = 2 / (n1 - 1) whose interior points are
 * moved by a uniform random offset in [-jitter h, jitter h] in each direction and whose edge
 * points (corners excepted) move along their edge only, so the boundary particles lie on the
 * boundary (as the papers' particles, collocated with the nodes of an irregular mesh). Volumes:
 * h^2, halved on the edges, quartered at the corners (sum 4). A fixed linear congruential
 * generator makes the cloud the same on every machine. Sets: "surface" (the four edges),
 * "dirichlet" (left, bottom, right edges), "top" (the top edge without its corners); field
 * "normal": the outward unit normal on the edges, 0 at the corners and inside.
 *
 * Problem: u = (0.1 X + 0.3 Y, 0.2 X + 0.4 Y) (Bode eq. 83, thesis eq. 7.1), E = 1e5, nu = 0.3,
 * plane strain, the linear law; P = lambda tr(eps) I + 2 mu eps (eq. 84 / 7.2). Dirichlet: u on
 * "dirichlet"; Neumann: the nodal force P A_k on "top", A_k the model's area vector (thesis eqs.
 * 4.31-4.32: the traction enters as the volume force P . A_k / V_k). pg_uniaxial: the affine
 * field of uniaxial stress along x in plane strain (P n = 0 on the top: a traction-free top). */
#ifndef PDK_TESTS_GALERKIN_UTIL_H
#define PDK_TESTS_GALERKIN_UTIL_H

#include <sys/resource.h>

#include "test_util.h"

static const double pg_H[2][2] = {{0.1, 0.3}, {0.2, 0.4}};
#define PG_E 1e5
#define PG_NU 0.3
static const double pg_uniaxial[2][2] = {{1e-2, 0.0}, {0.0, -1e-2 * PG_NU / (1 - PG_NU)}};

static inline double pg_lambda(void) { return PG_E * PG_NU / ((1 + PG_NU) * (1 - 2 * PG_NU)); }
static inline double pg_mu(void) { return PG_E / (2 * (1 + PG_NU)); }

static inline double pg_rand(uint64_t *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) / 9007199254740992.0; /* [0, 1) */
}

/* The cloud (n1 x n1 points, jitter in units of h, a seed). */
static inline pdk_particles *pg_cloud(pdk_ctx *ctx, int n1, double jitter, uint64_t seed) {
  pdk_particles *p;
  T_OK(ctx, pdk_particles_create(ctx, 2, (pdk_index)n1 * n1, &p));
  const double h = 2.0 / (n1 - 1);
  double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  T_OK(ctx, pdk_particles_field_add(p, "set:surface", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "set:dirichlet", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "set:top", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "normal", PDK_F64, 2));
  double *nx = pdk_particles_field_data(p, "normal", 0),
         *ny = pdk_particles_field_data(p, "normal", 1);
  uint8_t *surf = pdk_particles_field_data(p, "set:surface", 0);
  uint8_t *dir = pdk_particles_field_data(p, "set:dirichlet", 0);
  uint8_t *top = pdk_particles_field_data(p, "set:top", 0);
  uint64_t s = seed;
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n1; ++i) {
      const pdk_index k = (pdk_index)j * n1 + i;
      const int ex = i == 0 || i == n1 - 1, ey = j == 0 || j == n1 - 1;
      const double jx = (2 * pg_rand(&s) - 1) * jitter * h, jy = (2 * pg_rand(&s) - 1) * jitter * h;
      X[k] = -1.0 + i * h + (ex ? 0.0 : jx);
      Y[k] = -1.0 + j * h + (ey ? 0.0 : jy);
      if (i == 0) X[k] = -1.0;
      if (i == n1 - 1) X[k] = 1.0;
      if (j == 0) Y[k] = -1.0;
      if (j == n1 - 1) Y[k] = 1.0;
      V[k] = h * h * (ex ? 0.5 : 1.0) * (ey ? 0.5 : 1.0);
      surf[k] = (uint8_t)(ex || ey);
      dir[k] = (uint8_t)(i == 0 || i == n1 - 1 || j == 0);
      top[k] = (uint8_t)(j == n1 - 1 && !ex);
      nx[k] = ex && !ey ? (i == 0 ? -1.0 : 1.0) : 0.0;
      ny[k] = ey && !ex ? (j == 0 ? -1.0 : 1.0) : 0.0;
    }
  return p;
}

/* Relative L2 error of u and H1 (seminorm) error of grad u = F - I (the field "F", F^{kk}) against
 * the affine field, quadrature sum_k V_k; also the absolute ones (the papers' eq. 85 / 7.3). */
typedef struct pg_errors {
  double l2, h1;         /* relative */
  double l2_abs, h1_abs; /* absolute */
} pg_errors;

static inline pg_errors pg_measure(pdk_particles *p, const double Hx[2][2]) {
  const pdk_index n = pdk_particles_count(p);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  const double *F[4];
  for (int t = 0; t < 4; ++t)
    F[t] = pdk_particles_field_data(p, "F", t);
  double e0 = 0, n0 = 0, e1 = 0, n1 = 0;
  for (pdk_index k = 0; k < n; ++k) {
    const double ue[2] = {Hx[0][0] * X[k] + Hx[0][1] * Y[k], Hx[1][0] * X[k] + Hx[1][1] * Y[k]};
    const double uh[2] = {x[k] - X[k], y[k] - Y[k]};
    for (int c = 0; c < 2; ++c) {
      e0 += V[k] * (uh[c] - ue[c]) * (uh[c] - ue[c]);
      n0 += V[k] * ue[c] * ue[c];
    }
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) {
        const double g = F[r * 2 + c][k] - (r == c ? 1.0 : 0.0);
        e1 += V[k] * (g - Hx[r][c]) * (g - Hx[r][c]);
        n1 += V[k] * Hx[r][c] * Hx[r][c];
      }
  }
  pg_errors r = {sqrt(e0 / n0), sqrt(e1 / n1), sqrt(e0), sqrt(e1)};
  return r;
}

/* Model options of the patch test. */
static inline pdk_model_opts pg_model_opts(pdk_galerkin_basis basis, pdk_galerkin_correction corr) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_GALERKIN;
  mo.shear_modulus = pg_mu();
  mo.bulk_modulus = pg_lambda() + 2.0 * pg_mu() / 3.0;
  mo.density = 1.0;
  mo.law = PDK_LAW_LINEAR_ELASTIC;
  mo.galerkin.basis = basis;
  mo.galerkin.correction = corr;
  mo.galerkin.surface = "surface";
  return mo;
}

/* Solves the patch test of the affine field Hx (Hx or pg_uniaxial) with Newton on a model
 * built over p (fields "u_exact" and "t_load" are added: the Dirichlet values and, with load, the
 * Neumann body force P A_k / V_k on "top"; without, the top is free); returns the errors. */
static inline pg_errors pg_solve(pdk_ctx *ctx, pdk_particles *p, pdk_model *m,
                                 const double Hx[2][2], int load, pdk_static_stats *stats) {
  const pdk_index n = pdk_particles_count(p);
  const double lam = pg_lambda(), mu = pg_mu();
  const double tr = Hx[0][0] + Hx[1][1];
  double P[2][2];
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      P[r][c] = mu * (Hx[r][c] + Hx[c][r]) + (r == c ? lam * tr : 0.0);
  T_OK(ctx, pdk_particles_field_add(p, "u_exact", PDK_F64, 2));
  T_OK(ctx, pdk_particles_field_add(p, "t_load", PDK_F64, 2));
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double *A[2] = {pdk_particles_field_data(p, "area", 0),
                        pdk_particles_field_data(p, "area", 1)};
  for (int c = 0; c < 2; ++c) {
    double *ue = pdk_particles_field_data(p, "u_exact", c);
    double *tl = pdk_particles_field_data(p, "t_load", c);
    for (pdk_index k = 0; k < n; ++k) {
      ue[k] = Hx[c][0] * X[k] + Hx[c][1] * Y[k];
      tl[k] = (P[c][0] * A[0][k] + P[c][1] * A[1][k]) / V[k];
    }
  }
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:dirichlet";
  bcs[0].components = 3;
  bcs[0].value[0] = bcs[0].value[1] = pdk_tfun_constant(1.0);
  bcs[0].scale_field = "u_exact";
  bcs[1].kind = PDK_BC_BODY_FORCE;
  bcs[1].set = "set:top";
  bcs[1].components = 3;
  bcs[1].value[0] = bcs[1].value[1] = pdk_tfun_constant(1.0);
  bcs[1].scale_field = "t_load";
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = load ? 2 : 1;
  so.rtol = 1e-15; /* to the round-off floor: the discretization error is what is measured */
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  if (stats) *stats = *pdk_static_stats_get(s);
  pdk_static_destroy(&s);
  T_OK(ctx, pdk_model_force_trial(m, NULL)); /* F at the solution */
  return pg_measure(p, Hx);
}

/* The patch (problem 0) and manufactured sine (problem 1) fields of bench/bench_pg_tradeoff.c and
 * t271: exact u at (X, Y). */
static inline void pg_mms_exact(int problem, double X, double Y, double u[2]) {
  if (problem == 0) {
    u[0] = pg_H[0][0] * X + pg_H[0][1] * Y;
    u[1] = pg_H[1][0] * X + pg_H[1][1] * Y;
  } else {
    const double a = M_PI * X / 2, b = M_PI * Y / 2;
    u[0] = sin(a) * cos(b);
    u[1] = cos(a) * sin(b);
  }
}

static inline double pg_cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

/* One solve of problem 0 or 1 on the n1 x n1 cloud (seed 1, horizon 2.51 h), every edge particle
 * held at the exact field; model 0 correspondence with Silling 0.1, 1 correspondence without
 * stabilization (omega 1/r^2), 2 galerkin taylor vc1, 3 the same with the bond correction.
 * Returns the relative L2 error of u; *cpu the process CPU seconds of families, model and solve,
 * *nbp the bonds per particle, *iters Newton's iterations. */
static inline double pg_mms_run(pdk_ctx *ctx, int problem, int model, int n1, double *cpu,
                                double *nbp, long *iters) {
  const double h = 2.0 / (n1 - 1);
  pdk_particles *p = pg_cloud(ctx, n1, 0.3, 1);
  const pdk_index n = pdk_particles_count(p);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 2.51 * h;
  const double c0 = pg_cpu_seconds();
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  if (nbp) *nbp = (double)pdk_families_num_bonds(fam) / (double)n;
  pdk_model_opts mo = pg_model_opts(PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1);
  if (model < 2) {
    mo.kind = PDK_MODEL_CORRESPONDENCE;
    mo.influence = model == 0 ? PDK_INFLUENCE_CONSTANT : PDK_INFLUENCE_INV_R2;
    mo.stabilization = model == 0 ? PDK_STAB_SILLING : PDK_STAB_NONE;
    mo.stab_coefficient = 0.1;
  }
  mo.galerkin.bond = model == 3;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  T_OK(ctx, pdk_particles_field_add(p, "u_exact", PDK_F64, 2));
  T_OK(ctx, pdk_particles_field_add(p, "b_mms", PDK_F64, 2));
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double kb = M_PI * M_PI / 2 * (pg_lambda() + 2 * pg_mu());
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    pg_mms_exact(problem, X[k], Y[k], u);
    for (int c = 0; c < 2; ++c) {
      ((double *)pdk_particles_field_data(p, "u_exact", c))[k] = u[c];
      ((double *)pdk_particles_field_data(p, "b_mms", c))[k] = problem == 1 ? kb * u[c] : 0.0;
    }
  }
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:surface";
  bcs[0].components = 3;
  bcs[0].value[0] = bcs[0].value[1] = pdk_tfun_constant(1.0);
  bcs[0].scale_field = "u_exact";
  bcs[1].kind = PDK_BC_BODY_FORCE;
  bcs[1].set = NULL;
  bcs[1].components = 3;
  bcs[1].value[0] = bcs[1].value[1] = pdk_tfun_constant(1.0);
  bcs[1].scale_field = "b_mms";
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = problem == 1 ? 2 : 1;
  so.rtol = 1e-12;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  if (iters) *iters = pdk_static_stats_get(s)->iterations;
  pdk_static_destroy(&s);
  if (cpu) *cpu = pg_cpu_seconds() - c0;
  const double *x[2] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1)};
  double e = 0.0, nn = 0.0;
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    pg_mms_exact(problem, X[k], Y[k], u);
    const double uh[2] = {x[0][k] - X[k], x[1][k] - Y[k]};
    for (int c = 0; c < 2; ++c) {
      e += V[k] * (uh[c] - u[c]) * (uh[c] - u[c]);
      nn += V[k] * u[c] * u[c];
    }
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return sqrt(e / nn);
}

#endif
