/* Updated-Lagrangian correspondence, V-BL (Prop. 3.5) and V-INV, for every elastic law x influence
 * function x stabilization, 2-D and 3-D:
 *   - affine motion x = G X + c: the material F = N K^-1 (TL model) and the spatial F^ = M N^-T
 *     (UL model) both equal G at every particle whose family spans (not only interior ones: for an
 *     affine motion neither needs a symmetric family), and the UL force vanishes at interior
 *     particles (families and neighbours' families full);
 *   - after a rebuild at x = G1 X + c the UL model holds F = G2 G1 exactly for x = G2 G1 X + c
 *     (F^ = G2 over the rebuilt families times F_ref = G1), and interior forces vanish again;
 *   - rigid rotation gives zero UL force everywhere, from the initial configuration and through a
 *     sequence of rotations with a rebuild after each (F_ref = R_k), on a jittered lattice too;
 *   - random motion after a rebuild: forces sum to zero and (objective laws) so does their moment,
 *     which UL conserves exactly (A M = tau symmetric, Bergel & Li eq. 87); 1 and 2 threads give
 *     bitwise identical F, A, f, strain energy and rebuilt families.
 * labels: physics threads
 *
 * Tolerances (round-off), as tests/t040_corr_invariants.c: forces against f_scale = (lambda +
 * 2 mu) / dx with 1e-12; F entries 1e-12 absolute (one inverse and two 3 x 3 products of O(1)
 * entries over ~20 bonds; measured <= 2e-15); momentum and moment 1e-13 of the sum of magnitudes.
 * The small-strain law is not objective: its rotations are 1e-7 rad and its moment is not tested.
 */
#include "corr_util.h"

static pdk_model *ul_model(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam, int law, int infl,
                           int stab) {
  pdk_model_opts o = cu_opts(law, infl, stab, 0.5);
  o.connectivity = PDK_CONNECTIVITY_UL;
  o.ul_skin = 0.0; /* rebuilds only where the test asks */
  return cu_model(ctx, p, fam, &o);
}

static void mat_mul(int d, const double *A, const double *B, double *C) {
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int k = 0; k < d; ++k)
        s += A[r * d + k] * B[k * d + c];
      C[r * d + c] = s;
    }
}

/* x += amp * random */
static void add_noise(pdk_particles *p, double amp, uint64_t seed) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  uint64_t s = seed;
  for (int a = 0; a < d; ++a) {
    double *x = cu_field(p, "x", a);
    for (pdk_index i = 0; i < n; ++i)
      x[i] += amp * cu_rand(&s);
  }
}

/* x = G (X + 0.05 random) + c */
static void deformed_noisy(pdk_particles *p, const double *G, const double *c, uint64_t seed) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  cu_random_x(p, 0.05, seed);
  double *x[3] = {cu_field(p, "x", 0), cu_field(p, "x", 1), d == 3 ? cu_field(p, "x", 2) : NULL};
  for (pdk_index i = 0; i < n; ++i) {
    double X[3], y[3];
    for (int a = 0; a < d; ++a)
      X[a] = x[a][i];
    for (int a = 0; a < d; ++a) {
      y[a] = c[a];
      for (int b = 0; b < d; ++b)
        y[a] += G[a * d + b] * X[b];
    }
    for (int a = 0; a < d; ++a)
      x[a][i] = y[a];
  }
}

/* F == G at every particle not flagged; returns how many were checked. */
static pdk_index check_F(pdk_particles *p, const double *G, const char *what, const char *stage) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
  pdk_index checked = 0;
  for (pdk_index i = 0; i < n; ++i) {
    if (flag[i]) continue;
    ++checked;
    for (int t = 0; t < d * d; ++t)
      T_NEAR(cu_field(p, "F", t)[i], G[t], 0.0, 1e-12, "%s, %s: F[%d] at particle %d", what, stage,
             t, (int)i);
  }
  return checked;
}

/* |f| <= tol at particles whose lattice index lies `margin` from every face (all if margin < 0). */
static void check_zero_force(pdk_particles *p, int N, int margin, double tol, const char *what,
                             const char *stage) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  pdk_index checked = 0;
  for (pdk_index i = 0; i < n; ++i) {
    if (margin >= 0 && !cu_inside(p, i, N, margin)) continue;
    ++checked;
    for (int a = 0; a < d; ++a)
      T_NEAR(cu_field(p, "f", a)[i], 0.0, 0.0, tol, "%s, %s: f[%d] at particle %d", what, stage, a,
             (int)i);
  }
  T_ASSERT(checked > 0, "%s, %s: no particle checked", what, stage);
}

static void check_case(pdk_ctx *ctx, int dim, int law, int infl, int stab) {
  const int N = dim == 2 ? 24 : 11;
  const double mh = dim == 2 ? 2.015 : 1.5;
  const double lambda = CU_BULK - 2.0 * CU_SHEAR / 3.0, mu = CU_SHEAR;
  const double ftol = 1e-12 * (lambda + 2.0 * mu);
  const int M = cu_reach(mh);
  /* After the rebuild at G1 (singular values >= 0.8) a family reaches mh / 0.8 lattice steps. */
  const int M1 = cu_reach(mh / 0.8);
  char what[160];
  snprintf(what, sizeof what, "%d-D law %s influence %s stabilization %s", dim, cu_law_name[law],
           cu_infl_name[infl], cu_stab_name[stab]);
  const double c[3] = {0.75, -1.25, 0.5};
  const double G2d[4] = {1.08, 0.21, -0.07, 0.93},
               G3d[9] = {1.08, 0.21, -0.05, -0.07, 0.93, 0.12, 0.03, -0.11, 1.04};
  const double H2d[4] = {0.95, -0.12, 0.09, 1.1},
               H3d[9] = {0.95, -0.12, 0.04, 0.09, 1.1, -0.06, -0.02, 0.07, 0.97};
  const double *G = dim == 2 ? G2d : G3d, *H = dim == 2 ? H2d : H3d;

  /* ---- affine motion: TL F, UL F^, UL interior force; then a rebuild and a second map -------- */
  {
    pdk_particles *p = cu_lattice(ctx, dim, N, 0.0, 0);
    pdk_families *fam = cu_families(ctx, p, mh);
    pdk_model_opts to = cu_opts(law, infl, stab, 0.5);
    pdk_model *tl = cu_model(ctx, p, fam, &to);
    cu_affine(p, G, c);
    T_OK(ctx, pdk_model_force(tl, NULL));
    T_ASSERT(check_F(p, G, what, "TL affine") == pdk_particles_count(p), "%s: TL flagged", what);
    pdk_model_destroy(&tl);

    pdk_model *ul = ul_model(ctx, p, fam, law, infl, stab);
    T_OK(ctx, pdk_model_force(ul, NULL));
    T_ASSERT(check_F(p, G, what, "UL affine") == pdk_particles_count(p), "%s: UL flagged", what);
    check_zero_force(p, N, 2 * M, ftol, what, "UL affine");

    T_OK(ctx, pdk_model_rebuild(ul));
    T_ASSERT(pdk_model_num_rebuilds(ul) == 1, "%s: %ld rebuilds", what, pdk_model_num_rebuilds(ul));
    T_ASSERT(pdk_model_current_families(ul) != fam, "%s: the rebuild kept the families", what);
    double HG[9];
    mat_mul(dim, H, G, HG);
    cu_affine(p, HG, c);
    T_OK(ctx, pdk_model_force(ul, NULL));
    T_ASSERT(check_F(p, HG, what, "UL affine after a rebuild") == pdk_particles_count(p),
             "%s: UL flagged after the rebuild", what);
    check_zero_force(p, N, 2 * M1, ftol, what, "UL affine after a rebuild");
    pdk_model_destroy(&ul);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }

  /* ---- rigid rotation: zero force everywhere, through rebuilds; regular and jittered -------- */
  for (int jit = 0; jit < 2; ++jit) {
    pdk_particles *p = cu_lattice(ctx, dim, N, jit ? 0.2 : 0.0, 17);
    pdk_families *fam = cu_families(ctx, p, mh);
    pdk_model *ul = ul_model(ctx, p, fam, law, infl, stab);
    const double step = law == PDK_LAW_LINEAR_ELASTIC ? 1e-7 : 0.35;
    double e = 0.0;
    for (int k = 1; k <= 4; ++k) {
      double R[9];
      cu_rotation(dim, k * step, R);
      cu_affine(p, R, c);
      T_OK(ctx, pdk_model_force(ul, &e));
      char stage[64];
      snprintf(stage, sizeof stage, "jitter %d, rotation %d (%ld rebuilds)", jit, k,
               pdk_model_num_rebuilds(ul));
      check_zero_force(p, N, -1, ftol, what, stage);
      T_ASSERT(fabs(e) <= 1e-14 * (lambda + 2.0 * mu) * pdk_particles_count(p),
               "%s, %s: strain energy %.3g", what, stage, e);
      if (!jit) check_F(p, R, what, stage);
      T_OK(ctx, pdk_model_rebuild(ul));
    }
    pdk_model_destroy(&ul);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }

  /* ---- random motion after a rebuild: momentum, moment, 1 vs 2 threads ---------------------- */
  {
    pdk_particles *p = cu_lattice(ctx, dim, N, 0.2, 5);
    pdk_families *fam = cu_families(ctx, p, mh);
    pdk_model *ul = ul_model(ctx, p, fam, law, infl, stab);
    const pdk_index n = pdk_particles_count(p);
    deformed_noisy(p, G, c, 7);
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
    T_OK(ctx, pdk_model_rebuild(ul));
    add_noise(p, 0.05, 8);
    double e1 = 0.0;
    T_OK(ctx, pdk_model_force(ul, &e1));
    const pdk_families *fam1 = pdk_model_current_families(ul);
    const pdk_bond_index nb1 = pdk_families_num_bonds(fam1);
    pdk_index *bj1 = malloc((size_t)(nb1 > 0 ? nb1 : 1) * sizeof *bj1);
    memcpy(bj1, pdk_families_bond_j(fam1), (size_t)nb1 * sizeof *bj1);
    double *f1[3], *F1[9], *A1[9];
    for (int a = 0; a < dim; ++a) {
      f1[a] = malloc((size_t)n * sizeof(double));
      memcpy(f1[a], cu_field(p, "f", a), (size_t)n * sizeof(double));
    }
    for (int t = 0; t < dim * dim; ++t) {
      F1[t] = malloc((size_t)n * sizeof(double));
      A1[t] = malloc((size_t)n * sizeof(double));
      memcpy(F1[t], cu_field(p, "F", t), (size_t)n * sizeof(double));
      memcpy(A1[t], cu_field(p, "A", t), (size_t)n * sizeof(double));
    }
    const double *V = pdk_particles_volume(p);
    const double *x[3] = {cu_field(p, "x", 0), cu_field(p, "x", 1),
                          dim == 3 ? cu_field(p, "x", 2) : NULL};
    long double P[3] = {0, 0, 0}, Mo[3] = {0, 0, 0}, Pabs = 0, Mabs = 0;
    for (pdk_index i = 0; i < n; ++i) {
      const double fi[3] = {f1[0][i], f1[1][i], dim == 3 ? f1[2][i] : 0.0};
      const double xi[3] = {x[0][i], x[1][i], dim == 3 ? x[2][i] : 0.0};
      for (int a = 0; a < dim; ++a) {
        P[a] += (long double)V[i] * fi[a];
        Pabs += fabsl((long double)V[i] * fi[a]);
      }
      const double mom[3] = {xi[1] * fi[2] - xi[2] * fi[1], xi[2] * fi[0] - xi[0] * fi[2],
                             xi[0] * fi[1] - xi[1] * fi[0]};
      for (int a = 0; a < 3; ++a) {
        Mo[a] += (long double)V[i] * mom[a];
        Mabs += fabsl((long double)V[i] * mom[a]);
      }
    }
    for (int a = 0; a < dim; ++a)
      T_ASSERT(fabsl(P[a]) <= 1e-13L * Pabs, "%s: sum V f [%d] = %.3Lg of %.3Lg", what, a, P[a],
               Pabs);
    /* The hourglass form is parallel to Y pair by pair; the Silling term's pair force k_i z_i +
     * k_j z_j' is not, so its moment is only O(z) small: test the moment without Silling. */
    if (law != PDK_LAW_LINEAR_ELASTIC && stab != PDK_STAB_SILLING)
      for (int a = 0; a < 3; ++a)
        T_ASSERT(fabsl(Mo[a]) <= 1e-13L * Mabs, "%s: net moment [%d] = %.3Lg of %.3Lg", what, a,
                 Mo[a], Mabs);
    T_ASSERT(isfinite(e1) && e1 > 0.0, "%s: strain energy %g under random motion", what, e1);

    /* The same history on 2 threads, from a fresh model. */
    pdk_model_destroy(&ul);
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
    ul = ul_model(ctx, p, fam, law, infl, stab);
    deformed_noisy(p, G, c, 7);
    T_OK(ctx, pdk_model_rebuild(ul));
    add_noise(p, 0.05, 8);
    double e2 = 0.0;
    T_OK(ctx, pdk_model_force(ul, &e2));
    const pdk_families *fam2 = pdk_model_current_families(ul);
    T_ASSERT(pdk_families_num_bonds(fam2) == nb1 &&
                 !memcmp(pdk_families_bond_j(fam2), bj1, (size_t)nb1 * sizeof *bj1),
             "%s: rebuilt families differ between 1 and 2 threads", what);
    free(bj1);
    T_ASSERT(memcmp(&e1, &e2, sizeof e1) == 0, "%s: energy %.17g (1 thread) vs %.17g (2)", what, e1,
             e2);
    for (int a = 0; a < dim; ++a)
      T_ASSERT(memcmp(f1[a], cu_field(p, "f", a), (size_t)n * sizeof(double)) == 0,
               "%s: f[%d] differs between 1 and 2 threads", what, a);
    for (int t = 0; t < dim * dim; ++t) {
      T_ASSERT(memcmp(F1[t], cu_field(p, "F", t), (size_t)n * sizeof(double)) == 0,
               "%s: F[%d] differs between 1 and 2 threads", what, t);
      T_ASSERT(memcmp(A1[t], cu_field(p, "A", t), (size_t)n * sizeof(double)) == 0,
               "%s: A[%d] differs between 1 and 2 threads", what, t);
    }
    for (int a = 0; a < dim; ++a)
      free(f1[a]);
    for (int t = 0; t < dim * dim; ++t)
      free(F1[t]), free(A1[t]);
    pdk_model_destroy(&ul);
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

  /* Options: ul is correspondence only, refuses bond breaking and a skin outside [0, 1]. */
  {
    pdk_particles *p = cu_lattice(ctx, 2, 6, 0.0, 0);
    pdk_families *fam = cu_families(ctx, p, 1.5);
    pdk_model *m = NULL;
    pdk_model_opts o = cu_opts(PDK_LAW_SVK, 0, 0, 0.0);
    o.connectivity = PDK_CONNECTIVITY_UL;
    o.critical_stretch = 0.01;
    T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "bonds cannot break");
    o.critical_stretch = 0.0;
    o.ul_skin = 1.5;
    T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_ARG, "ul_skin");
    o.ul_skin = 0.25;
    o.kind = PDK_MODEL_LPS;
    T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "ul connectivity");
    o = cu_opts(PDK_LAW_SVK, 0, 0, 0.0);
    T_OK(ctx, pdk_model_create(p, fam, &o, &m));
    T_FAILS(ctx, pdk_model_rebuild(m), PDK_ERR_ARG, "only the ul connectivity");
    /* pdk_families_build_coords over "X" gives the families of pdk_families_build. */
    const double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1), NULL};
    pdk_families_opts fo = pdk_families_opts_default();
    fo.horizon = 1.5;
    pdk_families *f2 = NULL;
    T_OK(ctx, pdk_families_build_coords(ctx, 2, pdk_particles_count(p), X, NULL, &fo, &f2));
    T_ASSERT(pdk_families_num_bonds(f2) == pdk_families_num_bonds(fam) &&
                 !memcmp(pdk_families_bond_start(f2), pdk_families_bond_start(fam),
                         (size_t)(pdk_particles_count(p) + 1) * sizeof(pdk_bond_index)) &&
                 !memcmp(pdk_families_bond_j(f2), pdk_families_bond_j(fam),
                         (size_t)pdk_families_num_bonds(fam) * sizeof(pdk_index)),
             "pdk_families_build_coords differs from pdk_families_build");
    pdk_families_destroy(&f2);
    T_ASSERT(pdk_model_current_families(m) == fam, "TL: current families are the given ones");
    pdk_model_destroy(&m);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
