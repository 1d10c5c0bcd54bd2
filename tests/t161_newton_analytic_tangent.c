/* Newton's analytic tangent (PMB, LPS, the 2-D dilatation laws; src/models/model_pmb.c, src/models/model_lps.c,
 * src/models/model_dil2.c) against the colored central-difference tangent, and what it does to a solve.
 * labels: physics threads
 *
 * 1. Entry by entry, on a deformed configuration (a smooth nonlinear field with stretches of a few
 *    per cent, plus a deterministic jitter), with bonds broken across a pre-crack (both ends) and,
 *    in a second pass, a few bonds broken from one end only (the force of each end reads its own
 *    bond state, so the reverse-bond lookup is exercised), 2-D and 3-D, partial volumes on, and
 *    float storage of the bond lengths for one case; and the 2-D dilatation laws (Silling's with
 *    a cubic influence, Oterkus published and calibrated with a Gaussian one) on a body with a
 *    pre-crack (they have no bond state nor partial volumes); and a two-material PMB body:
 *      |K_analytic - K_difference| <= 1e-7 max|K|.
 *    Reason: central differences with h = 1e-5 delta have truncation error ~ (h / delta)^2 ~ 1e-10
 *    of the entries (the force is smooth on the scale delta at these stretches) and round-off
 *    ~ eps |x| / h ~ 1e-16 * 20 delta / 1e-5 delta = 2e-10 of max|K| (positions are absolute and
 *    the bodies span ~20 horizons); 1e-7 leaves a factor ~500 over both, and an error of the
 *    derivation (a missing term, a wrong end's volume or state) is of the order of the entries.
 *    The analytic tangent has exactly the pattern, so the comparison is entry by entry.
 * 2. Symmetry: with bonds broken from both ends the model is hyperelastic and the analytic K is
 *    symmetric to round-off: ||K - K^T||_F <= 1e-12 ||K||_F (each entry is a sum of a few hundred
 *    terms of one sign pattern; eps times that count ~ 1e-13).
 * 3. Threads: the analytic tangent with 1 and 2 threads is bitwise the same (each column is one
 *    thread's work, in a fixed order).
 * 4. Newton on a nonlinear problem (a 2-D bar clamped at one end, its other end moved by 5% of the
 *    length axially and 25% transversely: large rotations), no tangent reuse: the residual
 *    sequence of the analytic tangent converges quadratically. Once the residual is below 1e-2 of
 *    the load and the next one is above 1e3 times the round-off floor, log(e_{k+1}) / log(e_k)
 *    >= 1.7 (e = ||r|| / ||F_ext||; 2 for exact quadratic convergence, less when e_k is not yet
 *    small; the difference tangent's own errors ~1e-10 would show only near the floor).
 *    Both tangents end at the same equilibrium: max|u_analytic - u_difference| <= 1e-6 max|u|
 *    (both stop at rtol 1e-10 of the load; the displacement error ~ cond(K) e, and cond(K) of
 *    these bars is below 1e4).
 * 5. tangent analytic is refused for a model without one (correspondence), with a message naming
 *    the model; auto falls back to the difference tangent there.
 */
#include "solvers/static_impl.h"
#include "test_util.h"

typedef struct body {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
} body;

/* Lattice block [0, L] x [0, H] (x [0, H]), set "left" (x = 0) and "right" (x = L). */
/* variant: 0 PMB/LPS as given; 1 LPS with an influence function (Silling's 2-D law, cubic);
 * 2 Oterkus published, 3 Oterkus calibrated (Gaussian influence); 1-3 have a pre-crack (bonds
 * through the segment x = L/2, y < H/2 do not exist) instead of bond state; 4 PMB with two
 * materials (K ratio 10 across x = 0.3 L: bonds across take the series micromodulus). */
static body build_variant(pdk_ctx *ctx, int dim, double L, double H, double dx, double rf,
                          pdk_model_kind kind, int breakable, int float_storage, int variant) {
  body b;
  memset(&b, 0, sizeof b);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  lo.node_type = 1;
  lo.spacing = dx;
  lo.hi[0] = L;
  lo.hi[1] = H;
  lo.hi[2] = H;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &b.p));
  T_OK(ctx, pdk_particles_reorder_morton(b.p, rf * dx, NULL));
  const double e = 0.25 * dx;
  double a0[3] = {-1, -1, -1}, a1[3] = {e, H + 1, H + 1};
  double c0[3] = {L - e, -1, -1}, c1[3] = {L + 1, H + 1, H + 1};
  pdk_region left = pdk_region_box(a0, a1), right = pdk_region_box(c0, c1);
  T_OK(ctx, pdk_particles_set_define(b.p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(b.p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf * dx;
  double seg[4] = {0.5 * L + 0.01 * dx, -1.0, 0.5 * L + 0.01 * dx, 0.5 * H};
  pdk_precrack crack = {2, seg};
  if (variant >= 1 && variant <= 3) {
    fo.precracks = &crack;
    fo.num_precracks = 1;
  }
  T_OK(ctx, pdk_families_build(b.p, &fo, &b.fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = 1000.0 / 3.0 * 1.3; /* not the nu = 0 pair: c_dil != 0 in both dimensions */
  mo.shear_modulus = 400.0;
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = PDK_STAB_SILLING;
  mo.law = PDK_LAW_LINEAR_ELASTIC;
  mo.lattice_constant = dx; /* partial volumes */
  if (breakable) mo.critical_stretch = 10.0; /* bond state exists; nothing breaks by itself */
  if (float_storage) mo.precision = PDK_PRECISION_FLOAT;
  pdk_material mats[2] = {{mo.bulk_modulus, mo.shear_modulus, 1.0},
                          {0.1 * mo.bulk_modulus, 0.1 * mo.shear_modulus, 1.0}};
  if (variant == 4) {
    T_OK(ctx, pdk_particles_field_add(b.p, "material", PDK_I32, 1));
    int32_t *mat = pdk_particles_field_data(b.p, "material", 0);
    const double *X0 = pdk_particles_X(b.p, 0);
    for (pdk_index i = 0; i < pdk_particles_count(b.p); ++i)
      mat[i] = X0[i] < 0.3 * L ? 0 : 1;
    mo.materials = mats;
    mo.num_materials = 2;
  }
  if (variant >= 1 && variant <= 3) {
    mo.lattice_constant = 0.0; /* not implemented by the dilatation laws */
    mo.critical_stretch = 0.0;
    mo.kind = variant == 1 ? PDK_MODEL_LPS : PDK_MODEL_OTERKUS;
    mo.lps_use_influence = variant == 1;
    mo.influence = variant == 1 ? PDK_INFLUENCE_CUBIC : PDK_INFLUENCE_GAUSSIAN;
    mo.oterkus_a = variant == 3 ? PDK_OTERKUS_A_CALIBRATED : PDK_OTERKUS_A_PUBLISHED;
  }
  T_OK(ctx, pdk_model_create(b.p, b.fam, &mo, &b.m));
  return b;
}

static body build(pdk_ctx *ctx, int dim, double L, double H, double dx, double rf,
                  pdk_model_kind kind, int breakable, int float_storage) {
  return build_variant(ctx, dim, L, H, dx, rf, kind, breakable, float_storage, 0);
}

static void destroy(body *b) {
  pdk_model_destroy(&b->m);
  pdk_families_destroy(&b->fam);
  pdk_particles_destroy(&b->p);
}

/* Deterministic pseudo-random number in [-1, 1] from an integer. */
static double jitter(uint64_t k) {
  k = k * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;
  k ^= k >> 29;
  k *= 0xBF58476D1CE4E5B9ull;
  k ^= k >> 32;
  return (double)(k >> 11) / (double)(1ull << 52) - 1.0;
}

/* x = X + a smooth nonlinear field (stretches of a few per cent) + jitter of 0.5% of dx. */
static void deform(body *b, int dim, double L, double dx) {
  const pdk_index n = pdk_particles_count(b->p);
  const double *X[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c)
    X[c] = pdk_particles_X(b->p, c);
  for (int c = 0; c < dim; ++c) {
    double *x = pdk_particles_field_data(b->p, "x", c);
    for (pdk_index i = 0; i < n; ++i) {
      const double s = X[0][i] / L, t = X[1][i] / L, w = dim == 3 ? X[2][i] / L : 0.0;
      double u = 0.0;
      if (c == 0) u = 0.04 * L * s * s + 0.02 * L * sin(3.0 * t + w);
      if (c == 1) u = -0.03 * L * s * t + 0.05 * L * s * s * s;
      if (c == 2) u = 0.02 * L * sin(2.0 * s) * (1.0 + t);
      x[i] = X[c][i] + u + 0.005 * dx * jitter((uint64_t)i * 3u + (uint64_t)c);
    }
  }
}

/* Breaks every bond crossing the plane x = L/2 for y < H/2 (a pre-crack, both ends); with
 * one_sided, also every 7th bond of the particles with i % 11 == 0 from that end only. */
static void break_bonds(body *b, int dim, double L, double H, int one_sided) {
  uint8_t *alive = b->m->bond_alive;
  T_ASSERT(alive, "the model has no bond state");
  const pdk_bond_index *bs = pdk_families_bond_start(b->fam);
  const pdk_index *bj = pdk_families_bond_j(b->fam);
  const double *X = pdk_particles_X(b->p, 0), *Y = pdk_particles_X(b->p, 1);
  const pdk_index n = pdk_particles_count(b->p);
  (void)dim;
  pdk_bond_index cut = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index k = bs[i]; k < bs[i + 1]; ++k) {
      const pdk_index j = bj[k];
      const double xm = 0.5 * L;
      if ((X[i] - xm) * (X[j] - xm) < 0 && 0.5 * (Y[i] + Y[j]) < 0.5 * H) {
        alive[k] = 0;
        ++cut;
      }
      if (one_sided && i % 11 == 0 && (k - bs[i]) % 7 == 0) alive[k] = 0;
    }
  T_ASSERT(cut > 0, "the pre-crack cut no bond");
}

static pdk_static *newton(pdk_ctx *ctx, body *b, int dim, pdk_tangent_kind tangent) {
  pdk_bc bc;
  memset(&bc, 0, sizeof bc);
  bc.kind = PDK_BC_DISPLACEMENT;
  bc.set = "set:left";
  bc.components = dim == 3 ? 7u : 3u;
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = &bc;
  so.num_bcs = 1;
  so.tangent = tangent;
  pdk_static *s = NULL;
  T_OK(ctx, pdk_static_create(b->m, &so, &s));
  return s;
}

/* Copies the analytic (mode 2) or colored difference (mode 1) tangent. */
static double *tangent(pdk_ctx *ctx, pdk_static *s, int mode, int *nnz) {
  int ncol;
  const int *Ap, *Ai;
  const double *Ax;
  T_OK(ctx, pdk_newton_tangent(s, mode, &ncol, &Ap, &Ai, &Ax));
  *nnz = Ap[ncol];
  double *K = malloc((size_t)*nnz * sizeof *K);
  memcpy(K, Ax, (size_t)*nnz * sizeof *K);
  return K;
}

static void compare_tangents(int dim, pdk_model_kind kind, int float_storage, int variant) {
  const double L = 1.0, H = dim == 2 ? 0.5 : 0.4, dx = dim == 2 ? 0.05 : 0.1, rf = 3.0;
  const char *label = variant == 1   ? "lps (influence)"
                      : variant == 2 ? "oterkus (published)"
                      : variant == 3 ? "oterkus (calibrated)"
                      : variant == 4 ? "pmb (two materials)"
                                     : pdk_model_kind_name(kind);
  const int has_state = variant == 0 || variant == 4;
  for (int one_sided = 0; one_sided < (has_state ? 2 : 1); ++one_sided) {
    double *Kt[2] = {NULL, NULL};
    int nnz_t[2] = {0, 0};
    for (int threads = 1; threads <= 2; ++threads) {
      pdk_ctx *ctx = t_ctx(threads);
      body b = build_variant(ctx, dim, L, H, dx, rf, kind, 1, float_storage, variant);
      deform(&b, dim, L, dx);
      if (has_state) break_bonds(&b, dim, L, H, one_sided);
      pdk_static *s = newton(ctx, &b, dim, PDK_TANGENT_AUTO);
      T_ASSERT(pdk_static_stats_get(s)->analytic_tangent == 1 &&
                   pdk_static_stats_get(s)->passes_per_tangent == 0,
               "auto did not choose the analytic tangent for %s", label);
      Kt[threads - 1] = tangent(ctx, s, 2, &nnz_t[threads - 1]);
      if (threads == 1) {
        int nnz;
        double *Kd = tangent(ctx, s, 1, &nnz);
        const double *Ka = Kt[0];
        T_ASSERT(nnz == nnz_t[0], "pattern sizes differ");
        double kmax = 0.0, worst = 0.0;
        int at = -1;
        for (int k = 0; k < nnz; ++k)
          kmax = fmax(kmax, fabs(Kd[k]));
        for (int k = 0; k < nnz; ++k)
          if (fabs(Ka[k] - Kd[k]) > worst) {
            worst = fabs(Ka[k] - Kd[k]);
            at = k;
          }
        if (getenv("PDK_TEST_VERBOSE"))
          printf("%dD %s%s%s: max |K_a - K_d| = %.2e of max|K| (%d nonzeros)\n", dim,
                 label, float_storage ? " float" : "",
                 one_sided ? " one-sided breaks" : "", worst / kmax, nnz);
        T_ASSERT(kmax > 0, "empty tangent");
        T_ASSERT(worst <= 1e-7 * kmax,
                 "%dD %s%s: analytic and difference tangents differ by %.3e of max|K| at entry %d "
                 "(%.10e vs %.10e)",
                 dim, label, one_sided ? " (one-sided breaks)" : "",
                 worst / kmax, at, Ka[at], Kd[at]);
        if (!one_sided) { /* symmetry of the analytic tangent */
          int ncol;
          const int *Ap, *Ai;
          const double *Ax;
          T_OK(ctx, pdk_newton_tangent(s, 2, &ncol, &Ap, &Ai, &Ax));
          double num = 0.0, den = 0.0;
          for (int c = 0; c < ncol; ++c)
            for (int k = Ap[c]; k < Ap[c + 1]; ++k) {
              const int r = Ai[k];
              int t = -1;
              for (int q = Ap[r]; q < Ap[r + 1]; ++q)
                if (Ai[q] == c) t = q;
              T_ASSERT(t >= 0, "pattern not structurally symmetric");
              num += (Ax[k] - Ax[t]) * (Ax[k] - Ax[t]);
              den += Ax[k] * Ax[k];
            }
          T_ASSERT(sqrt(num) <= 1e-12 * sqrt(den),
                   "%dD %s: analytic tangent asymmetric: %.3e of ||K||_F", dim,
                   label, sqrt(num / den));
        }
        free(Kd);
      }
      pdk_static_destroy(&s);
      destroy(&b);
      pdk_ctx_destroy(&ctx);
    }
    T_ASSERT(nnz_t[0] == nnz_t[1] && !memcmp(Kt[0], Kt[1], (size_t)nnz_t[0] * sizeof(double)),
             "%dD %s: analytic tangent differs between 1 and 2 threads", dim,
             label);
    free(Kt[0]);
    free(Kt[1]);
  }
}

/* Nonlinear bar: returns the displacements; residual history into hist. */
static double *solve_bar(pdk_ctx *ctx, pdk_model_kind kind, pdk_tangent_kind tangent_kind,
                         double *hist, int *hist_len, double *floor_rel, long *passes,
                         pdk_index *num) {
  const int dim = 2;
  const double L = 1.0, H = 0.2, dx = 0.025, rf = 3.0;
  body b = build(ctx, dim, L, H, dx, rf, kind, 0, 0);
  pdk_bc bc[2];
  memset(bc, 0, sizeof bc);
  bc[0].kind = PDK_BC_DISPLACEMENT;
  bc[0].set = "set:left";
  bc[0].components = 3u;
  bc[1].kind = PDK_BC_DISPLACEMENT;
  bc[1].set = "set:right";
  bc[1].components = 3u;
  bc[1].value[0] = pdk_tfun_constant(0.05 * L);
  bc[1].value[1] = pdk_tfun_constant(0.25 * L);
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bc;
  so.num_bcs = 2;
  so.tangent = tangent_kind;
  so.reuse_tangent = 0;
  so.num_levels = 2;
  pdk_static *s = NULL;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  const pdk_static_stats *st = pdk_static_stats_get(s);
  *hist_len = st->residual_history_len;
  for (int k = 0; k < st->residual_history_len; ++k)
    hist[k] = st->residual_history[k] / st->load_norm;
  *floor_rel = st->residual_floor / st->load_norm;
  *passes = st->force_passes;
  const pdk_index n = *num = pdk_particles_count(b.p);
  double *u = malloc((size_t)dim * (size_t)n * sizeof *u);
  for (int c = 0; c < dim; ++c) {
    const double *x = pdk_particles_field_data(b.p, "x", c), *X = pdk_particles_X(b.p, c);
    for (pdk_index i = 0; i < n; ++i)
      u[(size_t)c * (size_t)n + (size_t)i] = x[i] - X[i];
  }
  pdk_static_destroy(&s);
  destroy(&b);
  return u;
}

static void nonlinear_bar(pdk_model_kind kind) {
  pdk_ctx *ctx = t_ctx(2);
  double hist[2][16], floor_rel[2];
  int len[2];
  long passes[2];
  double *u[2];
  pdk_index n = 0;
  u[0] = solve_bar(ctx, kind, PDK_TANGENT_ANALYTIC, hist[0], &len[0], &floor_rel[0], &passes[0],
                   &n);
  u[1] = solve_bar(ctx, kind, PDK_TANGENT_DIFFERENCE, hist[1], &len[1], &floor_rel[1], &passes[1],
                   &n);
  if (getenv("PDK_TEST_VERBOSE"))
    for (int t = 0; t < 2; ++t) {
      printf("%s %s (passes %ld, floor %.2e):", pdk_model_kind_name(kind),
             t ? "difference" : "analytic", passes[t], floor_rel[t]);
      for (int k = 0; k < len[t]; ++k)
        printf(" %.2e", hist[t][k]);
      printf("\n");
    }
  /* quadratic convergence of the analytic tangent's last level */
  int checked = 0;
  for (int k = 0; k + 1 < len[0]; ++k) {
    const double e0 = hist[0][k], e1 = hist[0][k + 1];
    if (e0 < 1e-2 && e1 > 1e3 * floor_rel[0]) {
      const double order = log(e1) / log(e0);
      T_ASSERT(order >= 1.7, "%s: residual %.3e -> %.3e of the load is not quadratic (order %.2f)",
               pdk_model_kind_name(kind), e0, e1, order);
      ++checked;
    }
  }
  T_ASSERT(checked >= 1, "%s: no pair of residuals in the quadratic range (%d iterations)",
           pdk_model_kind_name(kind), len[0] - 1);
  T_ASSERT(len[0] >= 4, "%s: the problem is not nonlinear enough (%d iterations)",
           pdk_model_kind_name(kind), len[0] - 1);
  T_ASSERT(passes[0] < passes[1], "the analytic solve used %ld force passes, the difference %ld",
           passes[0], passes[1]);
  const pdk_index n2 = 2 * n;
  double dmax = 0.0, umax = 0.0;
  for (pdk_index k = 0; k < n2; ++k) {
    dmax = fmax(dmax, fabs(u[0][k] - u[1][k]));
    umax = fmax(umax, fabs(u[1][k]));
  }
  T_ASSERT(dmax <= 1e-6 * umax, "%s: analytic and difference solutions differ by %.3e of max|u|",
           pdk_model_kind_name(kind), dmax / umax);
  free(u[0]);
  free(u[1]);
  pdk_ctx_destroy(&ctx);
}

static void refusal(void) {
  pdk_ctx *ctx = t_ctx(1);
  body b = build(ctx, 2, 1.0, 0.5, 0.1, 1.5, PDK_MODEL_CORRESPONDENCE, 0, 0);
  pdk_bc bc;
  memset(&bc, 0, sizeof bc);
  bc.kind = PDK_BC_DISPLACEMENT;
  bc.set = "set:left";
  bc.components = 3u;
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = &bc;
  so.num_bcs = 1;
  so.tangent = PDK_TANGENT_ANALYTIC;
  pdk_static *s = NULL;
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_UNSUPPORTED, "no analytic tangent");
  so.tangent = PDK_TANGENT_AUTO;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_ASSERT(pdk_static_stats_get(s)->analytic_tangent == 0 &&
               pdk_static_stats_get(s)->passes_per_tangent > 0,
           "auto chose an analytic tangent for correspondence");
  pdk_static_destroy(&s);
  so.tangent = (pdk_tangent_kind)7;
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_ARG, "tangent 7");
  destroy(&b);
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  compare_tangents(2, PDK_MODEL_PMB, 0, 0);
  compare_tangents(2, PDK_MODEL_LPS, 0, 0);
  compare_tangents(3, PDK_MODEL_PMB, 0, 0);
  compare_tangents(3, PDK_MODEL_LPS, 0, 0);
  compare_tangents(2, PDK_MODEL_LPS, 1, 0);
  for (int variant = 1; variant <= 3; ++variant)
    compare_tangents(2, PDK_MODEL_LPS, 0, variant);
  compare_tangents(2, PDK_MODEL_PMB, 0, 4);
  nonlinear_bar(PDK_MODEL_PMB);
  nonlinear_bar(PDK_MODEL_LPS);
  refusal();
  return 0;
}
