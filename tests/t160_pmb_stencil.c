/* The stencil path of the PMB and LPS force passes (model.stencil, src/models/model_stencil.c) against the
 * general path, on regular lattices.
 *
 * Tolerance. Both paths compute every bond term with the same operations on the same values (the
 * stencil recomputes r0 from the same reference coordinates, or takes the same float length), so
 * the terms are equal bit for bit and only the order of the family sum differs: the stencil adds
 * in lattice-offset order, the general path in neighbour-index order, in SIMD partial sums. Each
 * order's error is at most (n_i - 1) eps sum_b |t_b| for n_i terms, so the test allows
 *   |f_stencil - f_general| <= 2 n_i eps S_i,  S_i = sum_b c V_j |r - r0| / r0  >= sum_b |t_b|,
 * (beta <= 1, |eta_c| / r <= 1), and a relative 1e-12 on the strain energy (a sum of positive
 * terms). Bond failure and the critical stretches depend on each bond's stretch only, so the bond
 * state and the number broken must be equal bit for bit; forces after breaking, which read the
 * s0 of earlier passes, stay within the same bound.
 * LPS: the dilation is a family sum too, |theta_st - theta_gen| <= E_i = 2 n_i eps d/m_i sum_b |e|
 * beta V_j, and the force terms are t_b = beta V_j (A_b r0 + B_b e) q eta with A_b = c_dil
 * (theta_i/m_i + theta_j/m_j), B_b = c_dev (1/m_i + 1/m_j), so
 *   |f_st - f_gen| <= 2 n_i eps S_i + sum_b beta V_j |c_dil| (E_i/m_i + E_j/m_j),
 *   S_i = sum_b beta V_j |A_b r0 + B_b e| / r0  (theta and m as the pass computed them).
 * Every case runs for PMB, then for LPS.
 *
 * Cases: cubes with awkward row lengths (1 particle; 3, 5, 7, 9: the SIMD widths 4 and 8 plus or
 * minus one; 63 and 65; rows of 130, walked in tiles of rows), in lattice and in Morton order; a
 * 2-D plate with a hole; a 2-D plate with a pre-crack (bonds missing from interior families); bond
 * breaking over several committing passes (double and float storage); each kernel variant the CPU
 * has (baseline, AVX2, AVX-512); 1 vs 2 threads bitwise; a short explicit run (trajectories within
 * 1e-9 of the displacement scale: round-off amplified over 200 steps stays far below); refusals:
 * on for a jittered lattice and for lps with lps_use_influence, auto falling back there with the
 * general path's bits. labels: unit physics threads */
#include <float.h>
#include <stdint.h>

#include "bond_models_test.h"
#include "pdk/scene.h"

typedef struct run_out {
  pdk_index n;
  pdk_bond_index nb, broken;
  double *f[3];
  double energy;
  uint8_t *alive; /* [nb] or NULL */
  int active;
  double *theta;  /* LPS: [n] */
} run_out;

static int g_kind = PDK_MODEL_PMB; /* the model every case runs (main runs them all for both) */
#define KN (g_kind == PDK_MODEL_LPS ? "lps" : "pmb")

static void run_free(run_out *r) {
  for (int c = 0; c < 3; ++c) free(r->f[c]);
  free(r->alive);
  free(r->theta);
  memset(r, 0, sizeof *r);
}

static pdk_model_opts opts(int precision, double s00, pdk_stencil_mode st) {
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = (pdk_model_kind)g_kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.lattice_constant = 1.0;
  o.critical_stretch = s00;
  o.alpha = 0.25;
  o.precision = (pdk_precision)precision;
  o.stencil = st;
  return o;
}

/* num_passes force passes (committing when s00 > 0) at x = X + amp (k+1) U(-1, 1), seed 11 + k. */
static run_out run(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam, pdk_model_opts o, double amp,
                   int num_passes) {
  run_out r;
  memset(&r, 0, sizeof r);
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  r.active = pdk_model_stencil_active(m);
  for (int k = 0; k < num_passes; ++k) {
    bm_displace_random(p, amp * (k + 1), 11 + (uint64_t)k);
    if (o.critical_stretch > 0)
      T_OK(ctx, pdk_model_force(m, &r.energy));
    else
      T_OK(ctx, pdk_model_force_trial(m, &r.energy));
  }
  r.n = pdk_particles_count(p);
  r.nb = pdk_families_num_bonds(fam);
  for (int c = 0; c < pdk_particles_dim(p); ++c) {
    r.f[c] = malloc((size_t)r.n * sizeof(double));
    memcpy(r.f[c], pdk_particles_field_data(p, "f", c), (size_t)r.n * sizeof(double));
  }
  if (pdk_model_bond_alive(m)) {
    r.alive = malloc((size_t)(r.nb > 0 ? r.nb : 1));
    memcpy(r.alive, pdk_model_bond_alive(m), (size_t)r.nb);
  }
  r.broken = pdk_model_num_broken(m);
  if (g_kind == PDK_MODEL_LPS) {
    r.theta = malloc((size_t)r.n * sizeof(double));
    memcpy(r.theta, pdk_particles_field_data(p, "theta", 0), (size_t)r.n * sizeof(double));
  }
  pdk_model_destroy(&m);
  return r;
}

/* LPS: the bound of the header on theta (i) and on f (*fbound), at the current "x", from the
 * fields "m" and "theta" the last pass left. */
static double lps_theta_bound(pdk_particles *p, pdk_families *fam, pdk_index i) {
  const int dim = pdk_particles_dim(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p), *mw = pdk_particles_field_data(p, "m", 0);
  const double vs_a = pdk_families_horizon(fam) + 0.5;
  double T = 0.0;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    double R2 = 0, r2 = 0;
    for (int a = 0; a < dim; ++a) {
      const double dX = pdk_particles_X(p, a)[bj[b]] - pdk_particles_X(p, a)[i];
      const double dx = ((double *)pdk_particles_field_data(p, "x", a))[bj[b]] -
                        ((double *)pdk_particles_field_data(p, "x", a))[i];
      R2 += dX * dX, r2 += dx * dx;
    }
    const double r0 = sqrt(R2);
    T += fabs(sqrt(r2) - r0) * fmin(1.0, vs_a - r0) * V[bj[b]];
  }
  return mw[i] > 0 ? 2.0 * (double)(bs[i + 1] - bs[i]) * DBL_EPSILON * dim / mw[i] * T : 0.0;
}

static double lps_force_bound(pdk_particles *p, pdk_families *fam, pdk_index i, const double *E) {
  const int dim = pdk_particles_dim(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p), *mw = pdk_particles_field_data(p, "m", 0);
  const double *th = pdk_particles_field_data(p, "theta", 0);
  const double vs_a = pdk_families_horizon(fam) + 0.5, K = 2.0, G = 0.9, lambda = K - 2 * G / 3;
  const double c_dil = dim == 3 ? 3 * K - 5 * G : 2 * (lambda - G), c_dev = dim == 3 ? 15 * G : 8 * G;
  const double Ei = E[i];
  double S = 0.0, D = 0.0;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    double R2 = 0, r2 = 0;
    for (int a = 0; a < dim; ++a) {
      const double dX = pdk_particles_X(p, a)[j] - pdk_particles_X(p, a)[i];
      const double dx = ((double *)pdk_particles_field_data(p, "x", a))[j] -
                        ((double *)pdk_particles_field_data(p, "x", a))[i];
      R2 += dX * dX, r2 += dx * dx;
    }
    const double r0 = sqrt(R2), e = sqrt(r2) - r0, bv = fmin(1.0, vs_a - r0) * V[j];
    const double A = c_dil * (th[i] / mw[i] + th[j] / mw[j]), B = c_dev * (1 / mw[i] + 1 / mw[j]);
    S += bv * fabs(A * r0 + B * e) / r0;
    D += bv * fabs(c_dil) * (Ei / mw[i] + E[j] / mw[j]);
  }
  return 2.0 * (double)(bs[i + 1] - bs[i]) * DBL_EPSILON * S + D + 1e-300;
}

/* The bound of the header for particle i at the current "x". */
static double bound(pdk_particles *p, pdk_families *fam, pdk_index i, const double *E) {
  if (g_kind == PDK_MODEL_LPS) return lps_force_bound(p, fam, i, E);
  const int dim = pdk_particles_dim(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p);
  const double delta = pdk_families_horizon(fam), K = 2.0;
  const double c = dim == 3 ? 18.0 * K / (M_PI * pow(delta, 4)) : 72.0 * K / (5.0 * M_PI * pow(delta, 3));
  double S = 0.0;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    double R2 = 0, r2 = 0;
    for (int a = 0; a < dim; ++a) {
      const double dX = pdk_particles_X(p, a)[bj[b]] - pdk_particles_X(p, a)[i];
      const double dx = ((double *)pdk_particles_field_data(p, "x", a))[bj[b]] -
                        ((double *)pdk_particles_field_data(p, "x", a))[i];
      R2 += dX * dX, r2 += dx * dx;
    }
    S += c * V[bj[b]] * fabs(sqrt(r2) - sqrt(R2)) / sqrt(R2);
  }
  return 2.0 * (double)(bs[i + 1] - bs[i]) * DBL_EPSILON * S + 1e-300;
}

/* Stencil on vs off: forces within the bound, energy within 1e-12, bond state equal. Returns the
 * largest ratio of difference to bound. */
static double compare(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam, int precision, double s00,
                      double amp, int num_passes, const char *what_case) {
  char what[128];
  snprintf(what, sizeof what, "%s%s%s", strncmp(what_case, KN, 3) ? KN : "",
           strncmp(what_case, KN, 3) ? " " : "", what_case);
  run_out g = run(ctx, p, fam, opts(precision, s00, PDK_STENCIL_OFF), amp, num_passes);
  run_out s = run(ctx, p, fam, opts(precision, s00, PDK_STENCIL_ON), amp, num_passes);
  T_ASSERT(!g.active && s.active, "%s: stencil active %d / %d", what, g.active, s.active);
  T_ASSERT(g.broken == s.broken, "%s: %lld bonds broke on the general path, %lld on the stencil",
           what, (long long)g.broken, (long long)s.broken);
  if (g.alive)
    for (pdk_bond_index b = 0; b < g.nb; ++b)
      T_ASSERT(g.alive[b] == s.alive[b], "%s: bond %lld: state %d (general) vs %d (stencil)", what,
               (long long)b, g.alive[b], s.alive[b]);
  T_NEAR(s.energy, g.energy, 1e-12, 1e-300, "%s: strain energy", what);
  double worst = 0.0;
  double *E = calloc((size_t)g.n, sizeof *E);
  T_ASSERT(E, "out of memory");
  if (g_kind == PDK_MODEL_LPS)
    for (pdk_index i = 0; i < g.n; ++i) {
      E[i] = lps_theta_bound(p, fam, i);
      const double tol = E[i] + 1e-300;
      T_ASSERT(fabs(s.theta[i] - g.theta[i]) <= tol,
               "%s: particle %d: theta %.17g (stencil) vs %.17g (general), bound %.3e", what,
               (int)i, s.theta[i], g.theta[i], tol);
    }
  for (pdk_index i = 0; i < g.n; ++i) {
    const double tol = bound(p, fam, i, E);
    for (int c = 0; c < pdk_particles_dim(p); ++c) {
      const double diff = fabs(s.f[c][i] - g.f[c][i]);
      T_ASSERT(diff <= tol, "%s: particle %d component %d: f = %.17g (stencil) vs %.17g "
               "(general), difference %.3e above the round-off bound %.3e",
               what, (int)i, c, s.f[c][i], g.f[c][i], diff, tol);
      worst = fmax(worst, diff / tol);
    }
  }
  free(E);
  run_free(&g);
  run_free(&s);
  return worst;
}

static pdk_particles *plate_with_hole(pdk_ctx *ctx, int nx, int ny) {
  pdk_particles *p = bm_body(ctx, 2, nx, ny, 1, 1.0, 0.0, 0.0, 1);
  const double center[3] = {0.4 * nx, 0.5 * ny, 0.0};
  pdk_region hole = pdk_region_ball(center, 0.2 * ny);
  pdk_index removed = 0;
  T_OK(ctx, pdk_particles_cut(p, &hole, &removed));
  T_ASSERT(removed > 0, "the hole removed nothing");
  return p;
}

static void awkward_sizes(pdk_ctx *ctx) {
  const int widths[] = {1, 3, 5, 7, 9};
  double worst = 0;
  for (int k = 0; k < 5; ++k) {
    const int w = widths[k];
    pdk_particles *p = bm_body(ctx, 3, w, w == 1 ? 1 : 6, w == 1 ? 1 : 5, 1.0, 0.0, 0.2, 3);
    pdk_families *fam = bm_families(ctx, p, 3.015);
    char what[64];
    snprintf(what, sizeof what, "3-D row of %d", w);
    worst = fmax(worst, compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.0, 0.02, 1, what));
    if (w == 1) { /* one particle: no bonds, no force */
      run_out s = run(ctx, p, fam, opts(0, 0.0, PDK_STENCIL_ON), 0.02, 1);
      T_ASSERT(s.n == 1 && s.f[0][0] == 0 && s.f[1][0] == 0 && s.f[2][0] == 0,
               "one particle: force (%g, %g, %g)", s.f[0][0], s.f[1][0], s.f[2][0]);
      run_free(&s);
    }
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  const int rows[] = {63, 65};
  for (int k = 0; k < 2; ++k) {
    pdk_particles *p = bm_body(ctx, 2, rows[k], 7, 1, 1.0, 0.0, 0.2, 4);
    pdk_families *fam = bm_families(ctx, p, 3.015);
    worst = fmax(worst, compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.0, 0.02, 1, "2-D rows 63/65"));
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  /* long rows: the 3-D row list is then walked in tiles of rows along y (8 rows here, 26 in the
   * padded grid: tiles of 8, 8, 8, 2) */
  pdk_particles *p = bm_body(ctx, 3, 130, 20, 12, 1.0, 0.0, 0.2, 13);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  worst = fmax(worst, compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.02, 0.01, 2, "long rows"));
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  T_INFO("%s awkward sizes: largest difference %.3f of the bound\n", KN, worst);
}

/* A cube in Morton order (particles not in lattice order), double and float storage. */
static void cube_morton(pdk_ctx *ctx) {
  pdk_particles *p = bm_body(ctx, 3, 13, 11, 10, 1.0, 0.0, 0.0, 5);
  T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, 3.015), NULL));
  pdk_families *fam = bm_families(ctx, p, 3.015);
  const double w0 = compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.0, 0.02, 1, "cube double");
  const double w1 = compare(ctx, p, fam, PDK_PRECISION_FLOAT, 0.0, 0.02, 1, "cube float");
  T_INFO("%s cube (Morton order): largest difference %.3f (double), %.3f (float) of the bound\n",
         KN, w0, w1);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

static void plate_hole_precrack(pdk_ctx *ctx) {
  pdk_particles *p = plate_with_hole(ctx, 40, 30);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  const double w0 = compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.0, 0.02, 1, "plate with a hole");
  const pdk_bond_index nb_whole = pdk_families_num_bonds(fam);
  pdk_families_destroy(&fam);
  /* a pre-crack from the left edge to the middle, between lattice rows */
  const double v[4] = {-1.0, 14.95, 20.0, 14.95};
  pdk_precrack pc = {2, v};
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015;
  fo.precracks = &pc;
  fo.num_precracks = 1;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  T_ASSERT(pdk_families_num_bonds(fam) < nb_whole - 100, "the pre-crack cut %lld bonds; want many",
           (long long)(nb_whole - pdk_families_num_bonds(fam)));
  const double w1 = compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.0, 0.02, 1, "pre-crack");
  const double w2 = compare(ctx, p, fam, PDK_PRECISION_FLOAT, 0.0, 0.02, 1, "pre-crack float");
  T_INFO("%s plate with a hole: %.3f; with a pre-crack: %.3f (double), %.3f (float) of the bound\n",
         KN, w0, w1, w2);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* Bond breaking over 4 committing passes of growing random displacement. */
static void breaking(pdk_ctx *ctx) {
  for (int dim = 2; dim <= 3; ++dim)
    for (int prec = 0; prec <= 1; ++prec) {
      pdk_particles *p = dim == 3 ? bm_body(ctx, 3, 11, 9, 8, 1.0, 0.0, 0.1, 6)
                                  : plate_with_hole(ctx, 30, 20);
      pdk_families *fam = bm_families(ctx, p, 3.015);
      char what[64];
      snprintf(what, sizeof what, "%s %d-D breaking %s", KN, dim, prec ? "float" : "double");
      run_out g = run(ctx, p, fam, opts(prec, 0.02, PDK_STENCIL_OFF), 0.01, 4);
      T_ASSERT(g.broken > 0 && g.broken < g.nb / 2, "%s: %lld of %lld bonds broke; want some",
               what, (long long)g.broken, (long long)g.nb);
      run_free(&g);
      const double w = compare(ctx, p, fam, prec, 0.02, 0.01, 4, what);
      T_INFO("%s: largest difference %.3f of the bound\n", what, w);
      pdk_families_destroy(&fam);
      pdk_particles_destroy(&p);
    }
}

/* Every kernel variant the CPU has gives results within the bound. */
static void variants(void) {
  const char *names[] = {"ref", "avx2", "avx512"};
  for (int k = 0; k < 3; ++k) {
    pdk_ctx_opts co = pdk_ctx_opts_default();
    co.kernels = names[k];
    co.num_threads = 2;
    pdk_ctx *ctx = NULL;
    char why[512];
    if (pdk_ctx_create(&co, &ctx, why, sizeof why)) continue; /* the CPU lacks it */
    pdk_particles *p = bm_body(ctx, 3, 9, 7, 6, 1.0, 0.0, 0.1, 8);
    pdk_families *fam = bm_families(ctx, p, 3.015);
    char what[64];
    snprintf(what, sizeof what, "kernels %s", names[k]);
    compare(ctx, p, fam, PDK_PRECISION_DOUBLE, 0.02, 0.01, 3, what);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
  }
}

/* 1 vs 2 threads: the same bits (forces, energy, bond state). */
static void threads(void) {
  for (int dim = 2; dim <= 3; ++dim) {
    run_out r[2];
    for (int t = 0; t < 2; ++t) {
      pdk_ctx *ctx = t_ctx(t + 1);
      pdk_particles *p = dim == 3 ? bm_body(ctx, 3, 13, 12, 11, 1.0, 0.0, 0.1, 9)
                                  : plate_with_hole(ctx, 50, 40);
      pdk_families *fam = bm_families(ctx, p, 3.015);
      r[t] = run(ctx, p, fam, opts(0, 0.02, PDK_STENCIL_ON), 0.01, 4);
      T_ASSERT(r[t].active && r[t].broken > 0, "%d-D: stencil %d, %lld broken", dim, r[t].active,
               (long long)r[t].broken);
      pdk_families_destroy(&fam);
      pdk_particles_destroy(&p);
      pdk_ctx_destroy(&ctx);
    }
    T_ASSERT(r[0].broken == r[1].broken && !memcmp(r[0].alive, r[1].alive, (size_t)r[0].nb),
             "%d-D: bond state differs between 1 and 2 threads", dim);
    T_ASSERT(!memcmp(&r[0].energy, &r[1].energy, sizeof(double)),
             "%d-D: energy %.17g (1 thread) vs %.17g (2)", dim, r[0].energy, r[1].energy);
    for (int c = 0; c < dim; ++c)
      T_ASSERT(!memcmp(r[0].f[c], r[1].f[c], (size_t)r[0].n * sizeof(double)),
               "%d-D: f differs between 1 and 2 threads", dim);
    run_free(&r[0]);
    run_free(&r[1]);
  }
}

/* on refused where the stencil does not apply, naming why; auto then takes the general path. */
static void refusals(pdk_ctx *ctx) {
  pdk_particles *p = bm_body(ctx, 2, 20, 15, 1, 1.0, 0.05, 0.0, 10);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  pdk_model *m = NULL;
  pdk_model_opts o = opts(0, 0.0, PDK_STENCIL_ON);
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "off the nearest lattice point");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "stencil auto") != NULL, "the message says what to do: %s",
           pdk_ctx_error_message(ctx));
  run_out g = run(ctx, p, fam, opts(0, 0.0, PDK_STENCIL_OFF), 0.02, 1);
  run_out a = run(ctx, p, fam, opts(0, 0.0, PDK_STENCIL_AUTO), 0.02, 1);
  T_ASSERT(!a.active, "auto on a jittered lattice took the stencil path");
  for (int c = 0; c < 2; ++c)
    T_ASSERT(!memcmp(g.f[c], a.f[c], (size_t)g.n * sizeof(double)),
             "auto fallback: forces differ from the general path's");
  o = opts(0, 0.0, PDK_STENCIL_AUTO);
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(strstr(pdk_model_stencil_reason(m), "lattice"), "auto's reason: '%s'",
           pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  run_free(&g);
  run_free(&a);
  o = opts(0, 0.0, PDK_STENCIL_ON);
  o.kind = PDK_MODEL_LPS;
  o.lps_use_influence = 1;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "correspondence models only");
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  /* a lattice: auto takes the stencil */
  p = bm_body(ctx, 3, 6, 5, 4, 1.0, 0.0, 0.0, 12);
  fam = bm_families(ctx, p, 3.015);
  o = opts(0, 0.0, PDK_STENCIL_AUTO);
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(pdk_model_stencil_active(m) && !pdk_model_stencil_reason(m)[0],
           "auto on a lattice: active %d, reason '%s'", pdk_model_stencil_active(m),
           pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* A short explicit run: a 2-D plate pulled at both ends, 200 steps, with bond breaking. */
static void explicit_run(pdk_ctx *ctx) {
  double *x[2][2];
  pdk_bond_index broken[2];
  pdk_index n = 0;
  double scale = 0;
  for (int k = 0; k < 2; ++k) {
    pdk_particles *p = plate_with_hole(ctx, 40, 24);
    n = pdk_particles_count(p);
    const double lo[3] = {-1, -1, -1}, hi[3] = {2.5, 100, 1};
    const double lo2[3] = {36.5, -1, -1}, hi2[3] = {100, 100, 1};
    pdk_region left = pdk_region_box(lo, hi), right = pdk_region_box(lo2, hi2);
    T_OK(ctx, pdk_particles_set_define(p, "left", &left, NULL));
    T_OK(ctx, pdk_particles_set_define(p, "right", &right, NULL));
    pdk_families *fam = bm_families(ctx, p, 3.015);
    pdk_model_opts o = opts(0, 0.004, k ? PDK_STENCIL_ON : PDK_STENCIL_OFF);
    pdk_model *m = NULL;
    T_OK(ctx, pdk_model_create(p, fam, &o, &m));
    pdk_bc bcs[2];
    memset(bcs, 0, sizeof bcs);
    bcs[0].kind = bcs[1].kind = PDK_BC_VELOCITY;
    bcs[0].set = "set:left";
    bcs[1].set = "set:right";
    bcs[0].components = bcs[1].components = 1;
    bcs[0].value[0] = pdk_tfun_constant(-0.02);
    bcs[1].value[0] = pdk_tfun_constant(0.02);
    pdk_explicit_opts eo = pdk_explicit_opts_default();
    eo.bcs = bcs;
    eo.num_bcs = 2;
    pdk_explicit *e = NULL;
    T_OK(ctx, pdk_explicit_create(m, &eo, &e));
    pdk_history h;
    T_OK(ctx, pdk_explicit_run(e, 200, &h));
    broken[k] = h.broken;
    for (int c = 0; c < 2; ++c) {
      x[k][c] = malloc((size_t)n * sizeof(double));
      memcpy(x[k][c], pdk_particles_field_data(p, "x", c), (size_t)n * sizeof(double));
    }
    if (k == 0)
      for (pdk_index i = 0; i < n; ++i)
        scale = fmax(scale, fabs(x[0][0][i] - pdk_particles_X(p, 0)[i]));
    pdk_explicit_destroy(&e);
    pdk_model_destroy(&m);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  T_ASSERT(broken[0] > 0, "the explicit run broke no bond; the case should tear the plate");
  T_ASSERT(broken[0] == broken[1], "explicit run: %lld bonds broke (general) vs %lld (stencil)",
           (long long)broken[0], (long long)broken[1]);
  double worst = 0;
  for (int c = 0; c < 2; ++c)
    for (pdk_index i = 0; i < n; ++i) worst = fmax(worst, fabs(x[1][c][i] - x[0][c][i]));
  T_ASSERT(worst <= 1e-9 * scale, "explicit run: positions differ by %.3e (displacement scale %.3e)",
           worst, scale);
  T_INFO("%s explicit run: %lld bonds broke, positions within %.3e of the general path (%.2e of "
         "the displacement)\n",
         KN, (long long)broken[0], worst, worst / scale);
  for (int k = 0; k < 2; ++k) free(x[k][0]), free(x[k][1]);
}

/* The scene key model.stencil: on builds a stencil model, a scene without it takes the stencil
 * path unless it names model.layout; bad values and kinds are refused naming the key. */
static void scene_key(pdk_ctx *ctx) {
  const char *src = getenv("PDK_SOURCE_DIR");
  char path[2048];
  snprintf(path, sizeof path, "%s/tests/scenes/t060_minimal.yaml", src ? src : "..");
  const char *on[] = {"model.stencil=on"};
  pdk_scene *sc = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, on, 1, &sc));
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, sc, &sim));
  T_ASSERT(pdk_model_stencil_active(pdk_sim_model(sim)), "scene model.stencil: on not applied");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&sc);
  /* a scene that names neither key takes the stencil path where it applies (auto); one that names
   * a layout keeps it (off) */
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &sc));
  T_OK(ctx, pdk_sim_create(ctx, sc, &sim));
  T_ASSERT(pdk_model_opts_get(pdk_sim_model(sim))->stencil == PDK_STENCIL_AUTO,
           "scene default stencil %d, not auto",
           (int)pdk_model_opts_get(pdk_sim_model(sim))->stencil);
  T_ASSERT(pdk_model_stencil_active(pdk_sim_model(sim)), "scene default: no stencil on a lattice");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&sc);
  const char *csr[] = {"model.layout=csr"};
  T_OK(ctx, pdk_scene_load(ctx, path, csr, 1, &sc));
  T_OK(ctx, pdk_sim_create(ctx, sc, &sim));
  T_ASSERT(!pdk_model_stencil_active(pdk_sim_model(sim)),
           "model.layout=csr named, yet the stencil path was taken");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&sc);
  const char *bad[] = {"model.stencil=yes"};
  pdk_ctx_error_clear(ctx);
  T_ASSERT(pdk_scene_load(ctx, path, bad, 1, &sc) != 0 &&
               strstr(pdk_ctx_error_message(ctx), "stencil"),
           "model.stencil=yes accepted or not named: %s", pdk_ctx_error_message(ctx));
  pdk_scene_destroy(&sc); /* correspondence with stencil on: tests/t163_corr_stencil.c */
}

int main(void) {
  for (g_kind = PDK_MODEL_PMB; g_kind <= PDK_MODEL_LPS; ++g_kind) {
    pdk_ctx *ctx = t_ctx(2);
    awkward_sizes(ctx);
    cube_morton(ctx);
    plate_hole_precrack(ctx);
    breaking(ctx);
    refusals(ctx);
    explicit_run(ctx);
    if (g_kind == PDK_MODEL_PMB) scene_key(ctx);
    pdk_ctx_destroy(&ctx);
    variants();
    threads();
  }
  return 0;
}
