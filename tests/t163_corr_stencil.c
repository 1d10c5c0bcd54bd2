/* The stencil path of the correspondence passes (model.stencil for correspondence;
 * src/models/model_stencil.c, kernels/opt/corr_stencil.h) against the general path, on regular lattices.
 *
 * Tolerance. Both paths form the same bond terms from the same values (xi and omega per offset
 * equal every bond's to round-off: set-up checks it), but sum them in another order (lattice
 * offsets against neighbour index, SIMD partial sums, FMA contraction): not bit for bit. A sum of
 * n terms in any order is within (n - 1) eps sum |t| of the exact one, so two orders differ by at
 * most 2 n eps sum |t|. With w = omega V_j over the intact bonds of i, v = u_j - u_i, n_i bonds:
 *   D (pass 1):  |dD| <= 2 n_i eps SD_i,  SD_i = sum w |v| |xi|;
 *   F = I + D K^-1: |dF_rc| <= (2 n_i + 2 d) eps SD_i kn_i = tolF_i  (kn: largest row sum of
 *                |K^-1|; the 2 d eps the product's own rounding);
 *   the law and A = P K^-1, B = A - k (F - I) pass dF on with a Lipschitz factor: |dB| <=
 *                d (L + k_i) tolF_i kn_i, L = 3 (lambda + 2 mu) (the elastic modulus bound in the
 *                max norm at the strains used here, a few per cent; plastic flow only lowers it);
 *   f (pass 2): |df_i| <= 2 n_i eps Sf_i + sum_b w |xi| d (L + k_j) tolF_j kn_j,
 *                Sf_i = sum_b w (|B_j| |xi| + k_j |v|) + |B_i| sum w |xi| + k_i sum w |v|,
 *                |B| = d max |B_rc|;
 *   xi and omega: the stencil takes one bond's per offset; other bonds of that offset differ
 *                from it by round-off of X_j - X_i (rho = largest relative deviation of a bond
 *                from its ideal lattice vector): 18 rho more on the sums of F and f;
 *   float storage: the neighbours' B are rounded to float from doubles that may differ by the
 *                above, so one rounding can fall either side: + sum_b w |xi| 2^-24 |B_j|;
 *   energy sum_i V_i W_i: |dE| <= sum_i V_i (d^2 |P_i| tolF_i + k_i/2 dzz_i) + 2 n eps |E|, |P| <=
 *                |A| m (entries of K are at most tr K = m), dzz_i <= (2 n_i + 4 d^2) eps (sum w
 *                |v|^2 + 2 SD_i^2 kn_i) (zz = vv - H : D, H = D K^-1).
 * The general path of the ref kernel family forms F from N = sum w Y (x) xi instead of D; its
 * sums are then bounded with sum w |Y| |xi| in place of SD (the CPU without AVX2 case).
 * The bond state is the general path's code on both (breaking runs after pass 2 over the
 * families), so it and the number broken must be equal bit for bit.
 *
 * Cases: awkward row lengths (1 particle; 3, 5, 7, 9: the SIMD widths 4 and 8 plus or minus one;
 * 2-D rows of 63 and 65), every law x influence x stabilization (none, silling) in 2-D and 3-D,
 * Morton order, a plate with a hole and with a pre-crack, a two-material cube (per-particle
 * lambda, mu and stabilization modulus in the shared per-particle end), bond breaking over
 * committing passes,
 * float storage, Johnson-Cook plasticity (committing passes, the history advanced by the shared
 * per-particle end), every kernel variant the CPU has against the baseline C stencil, 1 vs 2
 * threads bitwise, a 200-step explicit run of a plate under tension (positions within 1e-9 of the
 * displacement scale of the general path's), refusals (hourglass, semi_tl, ul, off-lattice
 * particles) and auto's fall-back, and the scene key.
 * labels: unit physics threads */
#include <float.h>
#include <stdint.h>

#include "bond_models_test.h"
#include "corr_util.h"
#include "models/model_impl.h" /* pdk_influence_eval */
#include "pdk/scene.h"

#define EPS DBL_EPSILON

typedef struct res {
  pdk_index n;
  pdk_bond_index nb, broken;
  int dim, active;
  double *f[3], *F[9], *A[9], *Kinv[9], *x[3];
  double energy;
  uint8_t *alive;
} res;

static void res_free(res *r) {
  for (int t = 0; t < 9; ++t)
    free(r->F[t]), free(r->A[t]), free(r->Kinv[t]);
  for (int c = 0; c < 3; ++c)
    free(r->f[c]), free(r->x[c]);
  free(r->alive);
  memset(r, 0, sizeof *r);
}

static double *copy_field(pdk_particles *p, const char *name, int c) {
  const pdk_index n = pdk_particles_count(p);
  double *v = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
  T_ASSERT(v, "out of memory");
  memcpy(v, cu_field(p, name, c), (size_t)n * sizeof(double));
  return v;
}

/* A body: particles and families, built anew for every run (Johnson-Cook history lives in the
 * particle store). */
typedef struct body {
  int dim, nx, ny, nz;
  int hole, precrack, morton;
  double vol_noise;
  int two_materials; /* "material" 1 for x >= nx / 2 (the model then needs opts.materials) */
} body;

/* The two materials of the two-material case: stiffer and softer than CU_BULK, CU_SHEAR. */
static const pdk_material two_mats[2] = {{2.0, 1.0, 1.0}, {5.0, 1.7, 1.0}};

static void body_build(pdk_ctx *ctx, const body *b, pdk_particles **pp, pdk_families **ff) {
  pdk_particles *p = bm_body(ctx, b->dim, b->nx, b->ny, b->nz, 1.0, 0.0, b->vol_noise, 3);
  if (b->hole) {
    const double center[3] = {0.4 * b->nx, 0.5 * b->ny, b->dim == 3 ? 0.5 * b->nz : 0.0};
    pdk_region hole = pdk_region_ball(center, 0.2 * b->ny);
    pdk_index removed = 0;
    T_OK(ctx, pdk_particles_cut(p, &hole, &removed));
    T_ASSERT(removed > 0, "the hole removed nothing");
  }
  if (b->morton) T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, 3.015), NULL));
  if (b->two_materials) {
    T_OK(ctx, pdk_particles_field_add(p, "material", PDK_I32, 1));
    int32_t *mat = pdk_particles_field_data(p, "material", 0);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      mat[i] = pdk_particles_X(p, 0)[i] >= 0.5 * b->nx;
  }
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015;
  const double v[4] = {-1.0, 0.5 * b->ny - 0.05, 0.5 * b->nx, 0.5 * b->ny - 0.05};
  pdk_precrack pc = {2, v};
  if (b->precrack) fo.precracks = &pc, fo.num_precracks = 1;
  T_OK(ctx, pdk_families_build(p, &fo, ff));
  *pp = p;
}

static pdk_model_opts copts(int law, int infl, int stab, int prec, double s00,
                            pdk_stencil_mode st) {
  pdk_model_opts o = cu_opts(law, infl, stab, 0.1);
  o.precision = (pdk_precision)prec;
  o.critical_stretch = s00;
  o.alpha = 0.25;
  o.stencil = st;
  o.lattice_constant = 1.0;
  return o;
}

/* num_passes passes (committing when commit) at x = X + amp (k + 1) U(-1, 1), seed 11 + k. */
static res run(pdk_ctx *ctx, const body *b, pdk_model_opts o, double amp, int num_passes,
               int commit) {
  res r;
  memset(&r, 0, sizeof r);
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  body_build(ctx, b, &p, &fam);
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  if (o.law == PDK_LAW_JC) T_OK(ctx, pdk_model_set_dt(m, 1e-7));
  r.active = pdk_model_stencil_active(m);
  for (int k = 0; k < num_passes; ++k) {
    bm_displace_random(p, amp * (k + 1), 11 + (uint64_t)k);
    if (commit)
      T_OK(ctx, pdk_model_force(m, &r.energy));
    else
      T_OK(ctx, pdk_model_force_trial(m, &r.energy));
  }
  r.n = pdk_particles_count(p);
  r.nb = pdk_families_num_bonds(fam);
  r.dim = pdk_particles_dim(p);
  for (int c = 0; c < r.dim; ++c) {
    r.f[c] = copy_field(p, "f", c);
    r.x[c] = copy_field(p, "x", c);
  }
  for (int t = 0; t < r.dim * r.dim; ++t) {
    r.F[t] = copy_field(p, "F", t);
    r.A[t] = copy_field(p, "A", t);
    r.Kinv[t] = copy_field(p, "Kinv", t);
  }
  if (pdk_model_bond_alive(m)) {
    r.alive = malloc((size_t)(r.nb > 0 ? r.nb : 1));
    memcpy(r.alive, pdk_model_bond_alive(m), (size_t)r.nb);
  }
  r.broken = pdk_model_num_broken(m);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return r;
}

/* The bounds of the header, from the reference run g (its fields and final x). */
typedef struct bounds {
  double *F; /* [n] tolF */
  double *f; /* [n] */
  double E;
} bounds;

static double maxabs(double *const *T, int dd, pdk_index i) {
  double a = 0;
  for (int t = 0; t < dd; ++t)
    a = fmax(a, fabs(T[t][i]));
  return a;
}

static bounds make_bounds(pdk_ctx *ctx, const body *b, const pdk_model_opts *o, const res *g,
                          int float_storage, int n_form) {
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  body_build(ctx, b, &p, &fam);
  const int d = g->dim, dd = d * d;
  const pdk_index n = g->n;
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p);
  const double delta = pdk_families_horizon(fam);
  const double G = o->law == PDK_LAW_JC ? o->jc.young_modulus / (2 * (1 + o->jc.poisson_ratio))
                                        : o->shear_modulus;
  const double K = o->law == PDK_LAW_JC ? o->jc.young_modulus / (3 * (1 - 2 * o->jc.poisson_ratio))
                                        : o->bulk_modulus;
  double Kmax = K, Gmax = G; /* multi-material: the stiffest */
  for (int t = 0; t < o->num_materials; ++t) {
    Kmax = fmax(Kmax, o->materials[t].bulk_modulus);
    Gmax = fmax(Gmax, o->materials[t].shear_modulus);
  }
  const double L = 3.0 * (Kmax - 2.0 * Gmax / 3.0 + 2.0 * Gmax);
  const double ks = o->stabilization == PDK_STAB_SILLING
                        ? o->stab_coefficient * (d == 3 ? 72.0 / 5.0 : 36.0 / 5.0) * Kmax
                        : 0.0;
  /* rho: the largest relative deviation of a bond's xi from its ideal lattice vector (spacing 1):
   * the stencil's per-offset xi and omega are some bond's, so they differ from another bond's by
   * up to 2 rho in xi and (influence functions up to the Gaussian's d ln omega / d ln r = 8) 16
   * rho in omega; its terms carry that relative difference */
  double rho = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index e = bs[i]; e < bs[i + 1]; ++e) {
      double r2 = 0, dev = 0;
      for (int c = 0; c < d; ++c) {
        const double xi = pdk_particles_X(p, c)[bj[e]] - pdk_particles_X(p, c)[i];
        r2 += xi * xi;
        dev = fmax(dev, fabs(xi - nearbyint(xi)));
      }
      rho = fmax(rho, dev / sqrt(r2));
    }
  const double geo = 18.0 * rho;
  double *kk = calloc((size_t)n, sizeof(double)), *kn = calloc((size_t)n, sizeof(double));
  double *Bn = calloc((size_t)n, sizeof(double)), *mw = calloc((size_t)n, sizeof(double));
  bounds bd = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double)), 0.0};
  T_ASSERT(kk && kn && Bn && mw && bd.F && bd.f, "out of memory");
  /* per particle: m, k, kn, |B|, tolF */
  for (pdk_index i = 0; i < n; ++i) {
    double m = 0, SD = 0, vv = 0;
    int nb = 0;
    for (pdk_bond_index e = bs[i]; e < bs[i + 1]; ++e) {
      if (g->alive && !g->alive[e]) continue;
      const pdk_index j = bj[e];
      double r2 = 0, vn = 0, yn = 0;
      for (int c = 0; c < d; ++c) {
        const double xi = pdk_particles_X(p, c)[j] - pdk_particles_X(p, c)[i];
        const double y = g->x[c][j] - g->x[c][i], v = y - xi;
        r2 += xi * xi, vn += v * v, yn += y * y;
      }
      const double w =
          fmax(pdk_influence_eval(o->influence, sqrt(r2), delta, o->gaussian_width), 0.0) * V[j];
      m += w * r2;
      SD += w * (n_form ? sqrt(yn) : sqrt(vn)) * sqrt(r2);
      vv += w * vn;
      ++nb;
    }
    mw[i] = m;
    kk[i] = m > 0 && ks > 0 ? ks / m : 0.0;
    for (int r = 0; r < d; ++r) {
      double s = 0;
      for (int c = 0; c < d; ++c)
        s += fabs(g->Kinv[r * d + c][i]);
      kn[i] = fmax(kn[i], s);
    }
    double Bmax = 0;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        Bmax = fmax(Bmax, fabs(g->A[r * d + c][i] - kk[i] * (g->F[r * d + c][i] - (r == c))));
    Bn[i] = d * Bmax;
    bd.F[i] = ((2.0 * nb + 2.0 * d) * EPS + geo) * SD * kn[i] + 4 * EPS;
    const double Pn = d * maxabs(g->A, dd, i) * m;
    const double dzz = (2.0 * nb + 4.0 * dd) * EPS * (vv + 2.0 * SD * SD * kn[i]);
    bd.E += V[i] * (dd * Pn * bd.F[i] + 0.5 * kk[i] * dzz);
  }
  bd.E += 2.0 * (double)n * EPS * fabs(g->energy) + 1e-300;
  for (pdk_index i = 0; i < n; ++i) {
    double S = 0, prop = 0, sw = 0, su = 0, fl = 0;
    int nb = 0;
    for (pdk_bond_index e = bs[i]; e < bs[i + 1]; ++e) {
      if (g->alive && !g->alive[e]) continue;
      const pdk_index j = bj[e];
      double r2 = 0, vn = 0;
      for (int c = 0; c < d; ++c) {
        const double xi = pdk_particles_X(p, c)[j] - pdk_particles_X(p, c)[i];
        const double v = g->x[c][j] - g->x[c][i] - xi;
        r2 += xi * xi, vn += v * v;
      }
      const double w =
          fmax(pdk_influence_eval(o->influence, sqrt(r2), delta, o->gaussian_width), 0.0) * V[j];
      S += w * (Bn[j] * sqrt(r2) + kk[j] * sqrt(vn));
      sw += w * sqrt(r2);
      su += w * sqrt(vn);
      prop += w * sqrt(r2) * d * (L + kk[j]) * bd.F[j] * kn[j];
      if (float_storage) fl += w * sqrt(r2) * 0x1p-24 * Bn[j];
      ++nb;
    }
    S += Bn[i] * sw + kk[i] * su;
    bd.f[i] = (2.0 * nb * EPS + geo) * S + prop + fl + 1e-300;
  }
  free(kk), free(kn), free(Bn), free(mw);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return bd;
}

/* Worst ratio of difference to bound over f and F; fails past 1. */
static double check(const char *what, const res *g, const res *s, const bounds *bd) {
  double worst = 0;
  T_ASSERT(g->broken == s->broken, "%s: %lld bonds broke on the general path, %lld on the stencil",
           what, (long long)g->broken, (long long)s->broken);
  if (g->alive)
    T_ASSERT(!memcmp(g->alive, s->alive, (size_t)g->nb), "%s: bond state differs", what);
  const double dE = fabs(s->energy - g->energy);
  T_ASSERT(dE <= bd->E,
           "%s: energy %.17g (stencil) vs %.17g (general): difference %.3e above "
           "the bound %.3e",
           what, s->energy, g->energy, dE, bd->E);
  worst = fmax(worst, dE / bd->E);
  for (pdk_index i = 0; i < g->n; ++i) {
    for (int t = 0; t < g->dim * g->dim; ++t) {
      const double diff = fabs(s->F[t][i] - g->F[t][i]);
      T_ASSERT(diff <= bd->F[i],
               "%s: particle %d: F[%d] %.17g (stencil) vs %.17g (general), "
               "difference %.3e above the bound %.3e",
               what, (int)i, t, s->F[t][i], g->F[t][i], diff, bd->F[i]);
      worst = fmax(worst, diff / bd->F[i]);
    }
    for (int c = 0; c < g->dim; ++c) {
      const double diff = fabs(s->f[c][i] - g->f[c][i]);
      T_ASSERT(diff <= bd->f[i],
               "%s: particle %d: f[%d] %.17g (stencil) vs %.17g (general), "
               "difference %.3e above the bound %.3e",
               what, (int)i, c, s->f[c][i], g->f[c][i], diff, bd->f[i]);
      worst = fmax(worst, diff / bd->f[i]);
    }
  }
  return worst;
}

/* Stencil on vs off on body b; returns the worst ratio to the bound. */
static double compare(pdk_ctx *ctx, const body *b, pdk_model_opts o, double amp, int passes,
                      int commit, const char *what) {
  if (b->two_materials) o.materials = two_mats, o.num_materials = 2;
  o.stencil = PDK_STENCIL_OFF;
  res g = run(ctx, b, o, amp, passes, commit);
  o.stencil = PDK_STENCIL_ON;
  res s = run(ctx, b, o, amp, passes, commit);
  T_ASSERT(!g.active && s.active, "%s: stencil active %d / %d", what, g.active, s.active);
  const int n_form = !strcmp(pdk_ctx_kernels_name(ctx), "ref");
  bounds bd = make_bounds(ctx, b, &o, &g, o.precision == PDK_PRECISION_FLOAT, n_form);
  const double w = check(what, &g, &s, &bd);
  free(bd.F), free(bd.f);
  res_free(&g);
  res_free(&s);
  return w;
}

static void awkward_sizes(pdk_ctx *ctx) {
  const int widths[] = {1, 3, 5, 7, 9};
  double worst = 0;
  const pdk_model_opts o =
      copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.0, PDK_STENCIL_ON);
  for (int k = 0; k < 5; ++k) {
    const int w = widths[k];
    const body b = {3, w, w == 1 ? 1 : 6, w == 1 ? 1 : 5, 0, 0, 0, 0.2, 0};
    char what[64];
    snprintf(what, sizeof what, "3-D rows of %d", w);
    worst = fmax(worst, compare(ctx, &b, o, 0.02, 1, 0, what));
  }
  const int rows[] = {63, 65};
  for (int k = 0; k < 2; ++k) {
    const body b = {2, rows[k], 7, 1, 0, 0, 0, 0.2, 0};
    worst = fmax(worst, compare(ctx, &b, o, 0.02, 1, 0, "2-D rows of 63 / 65"));
  }
  T_INFO("awkward sizes: largest difference %.3g of the bound\n", worst);
}

/* Every law x influence x stabilization (none, silling), 2-D and 3-D, Morton order. */
static void laws_influences(pdk_ctx *ctx) {
  double worst = 0;
  for (int dim = 2; dim <= 3; ++dim) {
    const body b =
        dim == 3 ? (body){3, 8, 7, 6, 0, 0, 1, 0.1, 0} : (body){2, 17, 13, 1, 0, 0, 1, 0.1, 0};
    for (int law = PDK_LAW_LINEAR_ELASTIC; law <= PDK_LAW_NEO_HOOKE; ++law)
      for (int infl = PDK_INFLUENCE_CONSTANT; infl <= PDK_INFLUENCE_QUADRATIC; ++infl)
        for (int stab = PDK_STAB_NONE; stab <= PDK_STAB_SILLING; ++stab) {
          char what[96];
          snprintf(what, sizeof what, "%d-D %s influence %d %s", dim, cu_law_name[law], infl,
                   cu_stab_name[stab]);
          worst = fmax(worst, compare(ctx, &b, copts(law, infl, stab, 0, 0.0, PDK_STENCIL_ON), 0.03,
                                      1, 0, what));
        }
  }
  T_INFO("laws x influences x stabilizations: largest difference %.3g of the bound\n", worst);
}

static void hole_precrack_float(pdk_ctx *ctx) {
  const pdk_model_opts o =
      copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_LINEAR, PDK_STAB_SILLING, 0, 0.0, PDK_STENCIL_ON);
  pdk_model_opts of = o;
  of.precision = PDK_PRECISION_FLOAT;
  const body hole = {2, 40, 30, 1, 1, 0, 0, 0.0, 0};
  const body crack = {2, 40, 30, 1, 1, 1, 0, 0.0, 0};
  const body cube = {3, 12, 10, 9, 0, 0, 1, 0.0, 0};
  const double w0 = compare(ctx, &hole, o, 0.02, 1, 0, "plate with a hole");
  const double w1 = compare(ctx, &crack, o, 0.02, 1, 0, "pre-crack");
  const double w2 = compare(ctx, &crack, of, 0.02, 1, 0, "pre-crack float");
  const double w3 = compare(ctx, &cube, of, 0.02, 1, 0, "cube float");
  const double w4 = compare(ctx, &cube, o, 0.02, 1, 0, "cube double");
  const body two = {3, 12, 10, 9, 0, 0, 1, 0.0, 1};
  const double w5 = compare(ctx, &two, o, 0.02, 1, 0, "two materials");
  T_INFO("hole %.3g, pre-crack %.3g, pre-crack float %.3g, cube float %.3g, cube double %.3g, two "
         "materials %.3g of the bound\n",
         w0, w1, w2, w3, w4, w5);
}

/* Bond breaking over 4 committing passes (2-D with a hole, 3-D; double and float); then
 * Johnson-Cook over 3 committing passes. */
static void breaking_jc(pdk_ctx *ctx) {
  for (int dim = 2; dim <= 3; ++dim)
    for (int prec = 0; prec <= 1; ++prec) {
      const body b =
          dim == 3 ? (body){3, 11, 9, 8, 0, 0, 0, 0.1, 0} : (body){2, 30, 20, 1, 1, 0, 0, 0, 0};
      char what[64];
      snprintf(what, sizeof what, "%d-D breaking %s", dim, prec ? "float" : "double");
      pdk_model_opts o = copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CONSTANT, PDK_STAB_SILLING, prec,
                               0.02, PDK_STENCIL_OFF);
      res g = run(ctx, &b, o, 0.01, 4, 1);
      T_ASSERT(g.broken > 0 && g.broken < g.nb / 2, "%s: %lld of %lld bonds broke; want some", what,
               (long long)g.broken, (long long)g.nb);
      res_free(&g);
      const double w = compare(ctx, &b, o, 0.01, 4, 1, what);
      T_INFO("%s: largest difference %.3g of the bound\n", what, w);
    }
  pdk_model_opts o = copts(0, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.0, PDK_STENCIL_OFF);
  o.law = PDK_LAW_JC;
  o.bulk_modulus = o.shear_modulus = o.density = 0.0; /* from o.jc */
  const body b = {3, 9, 8, 7, 0, 0, 0, 0.0, 0};
  const double w = compare(ctx, &b, o, 0.004, 3, 1, "Johnson-Cook");
  T_INFO("Johnson-Cook: largest difference %.3g of the bound\n", w);
}

/* Every kernel variant the CPU has against the baseline C stencil (the ref family's). */
static void variants(void) {
  const char *names[] = {"ref", "avx2", "avx512"};
  const body b = {3, 11, 9, 7, 1, 0, 0, 0.1, 0};
  const body b2 = {2, 37, 21, 1, 1, 1, 0, 0.1, 0};
  res base[2];
  for (int k = 0; k < 3; ++k) {
    pdk_ctx_opts co = pdk_ctx_opts_default();
    co.kernels = names[k];
    co.num_threads = 2;
    pdk_ctx *ctx = NULL;
    char why[512];
    if (pdk_ctx_create(&co, &ctx, why, sizeof why)) continue; /* the CPU lacks it */
    for (int c = 0; c < 2; ++c) {
      const pdk_model_opts o =
          copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.02, PDK_STENCIL_ON);
      res s = run(ctx, c ? &b2 : &b, o, 0.01, 3, 1);
      T_ASSERT(s.active && s.broken > 0, "kernels %s: stencil %d, %lld broken", names[k], s.active,
               (long long)s.broken);
      if (k == 0) {
        base[c] = s;
        continue;
      }
      bounds bd = make_bounds(ctx, c ? &b2 : &b, &o, &base[c], 0, 0);
      char what[64];
      snprintf(what, sizeof what, "kernels %s against the baseline stencil (%d-D)", names[k],
               c ? 2 : 3);
      const double w = check(what, &base[c], &s, &bd);
      T_INFO("%s: largest difference %.3g of the bound\n", what, w);
      free(bd.F), free(bd.f);
      res_free(&s);
    }
    pdk_ctx_destroy(&ctx);
  }
  res_free(&base[0]);
  res_free(&base[1]);
}

/* 1 vs 2 threads: the same bits (forces, F, energy, bond state). */
static void threads(void) {
  for (int dim = 2; dim <= 3; ++dim) {
    res r[2];
    const body b =
        dim == 3 ? (body){3, 13, 12, 11, 0, 0, 1, 0.1, 0} : (body){2, 50, 40, 1, 1, 0, 0, 0, 0};
    for (int t = 0; t < 2; ++t) {
      pdk_ctx *ctx = t_ctx(t + 1);
      r[t] = run(
          ctx, &b,
          copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.02, PDK_STENCIL_ON),
          0.01, 4, 1);
      T_ASSERT(r[t].active && r[t].broken > 0, "%d-D: stencil %d, %lld broken", dim, r[t].active,
               (long long)r[t].broken);
      pdk_ctx_destroy(&ctx);
    }
    T_ASSERT(r[0].broken == r[1].broken && !memcmp(r[0].alive, r[1].alive, (size_t)r[0].nb),
             "%d-D: bond state differs between 1 and 2 threads", dim);
    T_ASSERT(!memcmp(&r[0].energy, &r[1].energy, sizeof(double)),
             "%d-D: energy %.17g (1 thread) vs %.17g (2)", dim, r[0].energy, r[1].energy);
    for (int c = 0; c < dim; ++c)
      T_ASSERT(!memcmp(r[0].f[c], r[1].f[c], (size_t)r[0].n * sizeof(double)),
               "%d-D: f differs between 1 and 2 threads", dim);
    for (int t = 0; t < dim * dim; ++t)
      T_ASSERT(!memcmp(r[0].F[t], r[1].F[t], (size_t)r[0].n * sizeof(double)),
               "%d-D: F differs between 1 and 2 threads", dim);
    res_free(&r[0]);
    res_free(&r[1]);
  }
}

/* A short explicit run: a 2-D plate with a hole pulled at both ends, 200 steps. */
static void explicit_run(pdk_ctx *ctx) {
  double *x[2][2];
  pdk_index n = 0;
  double scale = 0, energy[2];
  const body b = {2, 40, 24, 1, 1, 0, 0, 0.0, 0};
  for (int k = 0; k < 2; ++k) {
    pdk_particles *p = NULL;
    pdk_families *fam = NULL;
    body_build(ctx, &b, &p, &fam);
    n = pdk_particles_count(p);
    const double lo[3] = {-1, -1, -1}, hi[3] = {2.5, 100, 1};
    const double lo2[3] = {36.5, -1, -1}, hi2[3] = {100, 100, 1};
    pdk_region left = pdk_region_box(lo, hi), right = pdk_region_box(lo2, hi2);
    T_OK(ctx, pdk_particles_set_define(p, "left", &left, NULL));
    T_OK(ctx, pdk_particles_set_define(p, "right", &right, NULL));
    pdk_model_opts o = copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.0,
                             k ? PDK_STENCIL_ON : PDK_STENCIL_OFF);
    pdk_model *m = NULL;
    T_OK(ctx, pdk_model_create(p, fam, &o, &m));
    T_ASSERT(pdk_model_stencil_active(m) == k, "explicit run: stencil active %d",
             pdk_model_stencil_active(m));
    pdk_bc bcs[2];
    memset(bcs, 0, sizeof bcs);
    bcs[0].kind = bcs[1].kind = PDK_BC_VELOCITY;
    bcs[0].set = "set:left";
    bcs[1].set = "set:right";
    bcs[0].components = bcs[1].components = 1;
    bcs[0].value[0] = pdk_tfun_constant(-0.01);
    bcs[1].value[0] = pdk_tfun_constant(0.01);
    pdk_explicit_opts eo = pdk_explicit_opts_default();
    eo.bcs = bcs;
    eo.num_bcs = 2;
    pdk_explicit *e = NULL;
    T_OK(ctx, pdk_explicit_create(m, &eo, &e));
    pdk_history h;
    T_OK(ctx, pdk_explicit_run(e, 200, &h));
    energy[k] = h.strain;
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
  T_ASSERT(scale > 0.5, "explicit run: the plate barely moved (%.3g)", scale);
  double worst = 0;
  for (int c = 0; c < 2; ++c)
    for (pdk_index i = 0; i < n; ++i)
      worst = fmax(worst, fabs(x[1][c][i] - x[0][c][i]));
  T_ASSERT(worst <= 1e-9 * scale,
           "explicit run: positions differ by %.3e (displacement scale %.3e)", worst, scale);
  T_NEAR(energy[1], energy[0], 1e-9, 1e-300, "explicit run: strain energy");
  T_INFO("explicit run (200 steps): positions within %.3e of the general path (%.2e of the "
         "displacement), strain energy %.3e relative\n",
         worst, worst / scale, fabs(energy[1] - energy[0]) / fabs(energy[0]));
  for (int k = 0; k < 2; ++k)
    free(x[k][0]), free(x[k][1]);
}

/* on refused where the stencil does not apply, naming why; auto then takes the general path. */
static void refusals(pdk_ctx *ctx) {
  const body b = {2, 20, 15, 1, 0, 0, 0, 0.0, 0};
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  body_build(ctx, &b, &p, &fam);
  pdk_model *m = NULL;
  pdk_model_opts o =
      copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_HOURGLASS, 0, 0.0, PDK_STENCIL_ON);
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "hourglass");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "stencil off or auto"), "what to do: %s",
           pdk_ctx_error_message(ctx));
  o.stencil = PDK_STENCIL_AUTO;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(!pdk_model_stencil_active(m) && strstr(pdk_model_stencil_reason(m), "hourglass"),
           "auto with hourglass: active %d, reason '%s'", pdk_model_stencil_active(m),
           pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  o = copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.01, PDK_STENCIL_ON);
  o.connectivity = PDK_CONNECTIVITY_SEMI_TL;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "semi_tl");
  o.stencil = PDK_STENCIL_AUTO;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(!pdk_model_stencil_active(m) && strstr(pdk_model_stencil_reason(m), "semi_tl"),
           "auto with semi_tl: reason '%s'", pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  o.connectivity = PDK_CONNECTIVITY_UL;
  o.stencil = PDK_STENCIL_ON;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "ul");
  /* particles about 1e-7 spacings off their lattice points: on the lattice for the detection
   * (1e-6), but their bonds' xi differ from their offsets' by more than round-off */
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  p = bm_body(ctx, 2, 20, 15, 1, 1.0, 1e-8, 0.0, 10);
  fam = bm_families(ctx, p, 3.015);
  o = copts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_INV_R, PDK_STAB_SILLING, 0, 0.0, PDK_STENCIL_ON);
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "round-off");
  o.stencil = PDK_STENCIL_AUTO;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  T_ASSERT(!pdk_model_stencil_active(m) && strstr(pdk_model_stencil_reason(m), "offset"),
           "auto off the lattice: reason '%s'", pdk_model_stencil_reason(m));
  pdk_model_destroy(&m);
  /* jittered: off the lattice for the detection */
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  p = bm_body(ctx, 2, 20, 15, 1, 1.0, 0.05, 0.0, 10);
  fam = bm_families(ctx, p, 3.015);
  o.stencil = PDK_STENCIL_ON;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED,
          "off the nearest lattice point");
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* 1 when the particles' reference positions run along the lattice's rows (z, then y, then x
 * never decreasing, x fastest), 0 otherwise. */
static int in_rows(pdk_particles *p) {
  const int dim = pdk_particles_dim(p);
  for (pdk_index i = 1; i < pdk_particles_count(p); ++i) {
    int cmp = 0;
    for (int c = dim - 1; c >= 0 && !cmp; --c) {
      const double a = pdk_particles_X(p, c)[i], b = pdk_particles_X(p, c)[i - 1];
      cmp = (a > b) - (a < b);
    }
    if (cmp < 0) return 0;
  }
  return 1;
}

/* The scene key: model.stencil on with correspondence builds a stencil model, and the scene
 * numbers the particles along the lattice's rows (the stencil's site order), where with stencil
 * off, or where the options refuse the stencil path (semi_tl under auto), they stay in the cells'
 * Morton order. */
static void scene_key(pdk_ctx *ctx) {
  const char *src = getenv("PDK_SOURCE_DIR");
  char path[2048];
  snprintf(path, sizeof path, "%s/tests/scenes/t060_minimal.yaml", src ? src : "..");
  const char *on[] = {"model.kind=correspondence", "material.shear_modulus=4e8",
                      "model.stabilization=silling", "model.stencil=on"};
  const char *off[] = {"model.kind=correspondence", "material.shear_modulus=4e8",
                       "model.stabilization=silling", "model.stencil=off"};
  const char *refused[] = {"model.kind=correspondence", "material.shear_modulus=4e8",
                           "model.stabilization=silling", "model.stencil=auto",
                           "model.connectivity=semi_tl"};
  const char **keys[3] = {on, off, refused};
  const int num_keys[3] = {4, 4, 5};
  for (int v = 0; v < 3; ++v) {
    pdk_scene *sc = NULL;
    T_OK(ctx, pdk_scene_load(ctx, path, keys[v], num_keys[v], &sc));
    pdk_sim *sim = NULL;
    T_OK(ctx, pdk_sim_create(ctx, sc, &sim));
    const int active = pdk_model_stencil_active(pdk_sim_model(sim));
    const int rows = in_rows(pdk_sim_particles(sim));
    T_ASSERT(active == (v == 0), "scene %s: stencil path %s", keys[v][3],
             active ? "taken" : "not taken");
    T_ASSERT(rows == (v == 0), "scene %s%s: particles %s in row order", keys[v][3],
             v == 2 ? " with semi_tl" : "", rows ? "are" : "are not");
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&sc);
  }
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  awkward_sizes(ctx);
  laws_influences(ctx);
  hole_precrack_float(ctx);
  breaking_jc(ctx);
  explicit_run(ctx);
  refusals(ctx);
  scene_key(ctx);
  pdk_ctx_destroy(&ctx);
  variants();
  threads();
  return 0;
}
