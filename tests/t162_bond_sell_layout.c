/* PMB force pass and LPS dilation / force passes over the sliced layout (model layout sell,
 * SELL-C-sigma) against the CSR reference (kernel table "ref", layout csr), for every kernel
 * family this CPU runs (ref: C = 8, avx2: C = 4, avx512: C = 8), 2-D and 3-D, double and float
 * storage, 1 and 2 threads.
 *
 * Part 1, hand-made families (pdk_families_from_csr): particle counts 1, 3, 4, 5, 7, 8, 9, 17, 70
 * (C - 1, C, C + 1 for both widths, one slice and several), family lengths cycling through 0
 * (empty), 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33 (capped at n - 1) so slices mix empty and long
 * rows, random positions (bond lengths up to 5.2, past the partial-volume edge at 3.5), random
 * volumes, one bond of current length exactly 0, and a small sorting window (sell_sigma = 2 C, so
 * the 70-particle body has several windows, the last one partial). Part 2, jittered lattices
 * (Morton order, horizon 3.015 spacings, default window): a 9 x 8 x 7 cube and a 23 x 19 plate.
 * Both parts: a trial pass, then commit passes at growing displacements that break bonds, then a
 * trial pass, and a bond-state change written outside a pass (as a checkpoint restore does).
 * The layout of 0 particles is checked directly: no slice, no entry, padding 0. A scene with
 * model.layout: sell builds a model with that layout (and a correspondence one is refused, naming
 * the fix); the kinds without a sliced pass refuse it.
 *
 * What must hold, and why:
 *   - bond state, number broken: bit for bit the reference's (every bond's stretch is computed
 *     with the reference's operations in its order; src/space/sell.h keeps the layout's state equal to
 *     the CSR state);
 *   - f, W (and LPS theta): the reference's up to the order of the sums over a family. Two sums of
 *     the same n_b terms in different orders differ by at most 2 (n_b - 1) eps sum_b |term_b|
 *     (first order), so the test allows 2 n_b eps times the sum of the terms' sizes, evaluated
 *     here from the formulas over every bond (make_scale); LPS adds what the neighbours' dilation
 *     round-off carries into the force and the energy (twice its first-order size); the total
 *     energy sum_i V_i tol(W_i) plus n eps of it for the particle sum;
 *   - the layout sums each particle's bonds one after the other in CSR order whatever the lane,
 *     slice or window, so every sell variant (ref, avx2, avx512; any window) gives the same bits,
 *     and 1 and 2 threads give the same bits;
 *   - the sorted window leaves no more padding than the unsorted layout (sell_sigma = C).
 * labels: unit threads */
#include <float.h>
#include <stdint.h>

#include "bond_models_test.h"
#include "space/families_impl.h"
#include "kernels.h"
#include "models/model_bond.h"
#include "models/model_impl.h"
#include "core/pdk_impl.h"
#include "space/sell.h"

static const int row_sizes[] = {0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33};
#define NSIZES ((int)(sizeof row_sizes / sizeof row_sizes[0]))
static const pdk_index counts[] = {1, 3, 4, 5, 7, 8, 9, 17, 70};
#define NCOUNTS ((int)(sizeof counts / sizeof counts[0]))

/* A body: store, families, and what a run needs to rebuild it the same way. */
typedef struct body {
  int dim, lattice;
  pdk_index n;
  uint64_t seed;
} body;

static pdk_particles *make_store(pdk_ctx *ctx, const body *b) {
  if (b->lattice) {
    pdk_particles *p = bm_body(ctx, b->dim, 9, 8, 7, 1.0, 0.1, 0.2, b->seed);
    if (b->dim == 2) {
      pdk_particles_destroy(&p);
      p = bm_body(ctx, 2, 23, 19, 1, 1.0, 0.1, 0.2, b->seed);
    }
    T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, 3.015), NULL));
    return p;
  }
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, b->dim, b->n, &p));
  uint64_t s = b->seed;
  for (int c = 0; c < b->dim; ++c) {
    double *X = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < b->n; ++i)
      X[i] = 1.5 * (bm_rng_sym(&s) + 1.0); /* [0, 3) */
  }
  double *V = pdk_particles_volume(p);
  for (pdk_index i = 0; i < b->n; ++i)
    V[i] = 0.5 + 0.5 * (bm_rng_sym(&s) + 1.0);
  return p;
}

static pdk_families *make_families(pdk_ctx *ctx, pdk_particles *p, const body *b) {
  if (b->lattice) return bm_families(ctx, p, 3.015);
  const pdk_index n = b->n;
  pdk_bond_index *bs = calloc((size_t)n + 1, sizeof *bs);
  for (pdk_index i = 0; i < n; ++i) {
    int len = row_sizes[(i * 7) % NSIZES];
    if (len > n - 1) len = n - 1;
    bs[i + 1] = bs[i] + len;
  }
  pdk_index *bj = malloc((size_t)(bs[n] > 0 ? bs[n] : 1) * sizeof *bj);
  uint8_t *used = calloc((size_t)n, 1);
  uint64_t s = b->seed ^ 0xabcdefu;
  for (pdk_index i = 0; i < n; ++i) {
    memset(used, 0, (size_t)n);
    used[i] = 1;
    for (pdk_bond_index k = bs[i]; k < bs[i + 1]; ++k) {
      pdk_index j;
      if (i == 0 && k == bs[0] && n > 1)
        j = 1; /* particle 1 sits on 0 in the current state */
      else
        do
          j = (pdk_index)(bm_rng_next(&s) % (uint64_t)n);
        while (used[j]);
      used[j] = 1;
      bj[k] = j;
    }
  }
  pdk_families *f = NULL;
  T_OK(ctx, pdk_families_from_csr(ctx, n, 4.0, bs, bj, &f));
  free(bs), free(bj), free(used);
  return f;
}

/* x = X + amp U(-1, 1) (and, hand-made bodies, x_1 = x_0: a bond of current length 0). */
static void displace(pdk_particles *p, const body *b, double amp, uint64_t seed) {
  bm_displace_random(p, amp, seed);
  if (!b->lattice && b->n > 1)
    for (int c = 0; c < b->dim; ++c) {
      double *x = pdk_particles_field_data(p, "x", c);
      x[1] = x[0];
    }
}

#define NPASS 5
typedef struct run_out {
  pdk_index n;
  pdk_bond_index nb;
  double *f[NPASS][3], *w[NPASS], *theta[NPASS], *m, e[NPASS], padding;
  uint8_t *alive[NPASS];
  pdk_bond_index broken[NPASS];
} run_out;

static void free_run(run_out *r) {
  for (int k = 0; k < NPASS; ++k) {
    for (int c = 0; c < 3; ++c)
      free(r->f[k][c]);
    free(r->w[k]);
    free(r->theta[k]);
    free(r->alive[k]);
  }
  free(r->m);
}

/* The pass sequence on one configuration; NULL when the kernel family is not on this CPU. */
static int run(const body *b, pdk_model_kind kind, const char *kernels, int threads,
               pdk_layout layout, int sigma, pdk_precision prec, run_out *r) {
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  co.kernels = kernels;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) return 0;
  pdk_particles *p = make_store(ctx, b);
  pdk_families *fam = make_families(ctx, p, b);
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.critical_stretch = b->lattice ? 0.004 : 0.01;
  o.alpha = 0.25;
  o.lattice_constant = 1.0;
  o.precision = prec;
  o.layout = layout;
  o.sell_sigma = sigma;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  memset(r, 0, sizeof *r);
  r->n = pdk_particles_count(p);
  r->nb = pdk_families_num_bonds(fam);
  r->padding = pdk_model_padding_fraction(m);
  const int dim = b->dim;
  for (int k = 0; k < NPASS; ++k) {
    const double amp = b->lattice ? 0.004 : 0.02;
    if (k == 0) displace(p, b, amp, 5);
    if (k == 1 || k == 2) displace(p, b, amp * (k + 1), 5 + (uint64_t)k);
    if (k == 4) { /* bond state written outside a pass: every fifth intact bond of the CSR state */
      for (pdk_bond_index q = 0; q < r->nb; q += 5)
        m->bond_alive[q] = 0;
      ++m->bond_state_version;
    }
    if (k == 1 || k == 2)
      T_OK(ctx, pdk_model_force(m, &r->e[k]));
    else
      T_OK(ctx, pdk_model_force_trial(m, &r->e[k]));
    for (int c = 0; c < dim; ++c) {
      r->f[k][c] = malloc((size_t)r->n * sizeof(double));
      memcpy(r->f[k][c], pdk_particles_field_data(p, "f", c), (size_t)r->n * sizeof(double));
    }
    r->w[k] = malloc((size_t)r->n * sizeof(double));
    memcpy(r->w[k],
           kind == PDK_MODEL_PMB ? pdk_model_pmb_energy_density(m)
                                 : pdk_model_lps_energy_density(m),
           (size_t)r->n * sizeof(double));
    if (kind == PDK_MODEL_LPS) {
      r->theta[k] = malloc((size_t)r->n * sizeof(double));
      memcpy(r->theta[k], pdk_particles_field_data(p, "theta", 0), (size_t)r->n * sizeof(double));
      if (k == 0) {
        r->m = malloc((size_t)r->n * sizeof(double));
        memcpy(r->m, pdk_particles_field_data(p, "m", 0), (size_t)r->n * sizeof(double));
      }
    }
    r->alive[k] = malloc((size_t)(r->nb > 0 ? r->nb : 1));
    memcpy(r->alive[k], pdk_model_bond_alive(m), (size_t)r->nb);
    r->broken[k] = pdk_model_num_broken(m);
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 1;
}

/* The tolerances of pass k (header), per particle, from the test's own evaluation of the terms'
 * sizes over the CSR bonds (all of them, intact or not: an upper bound) at that pass's positions;
 * LPS takes theta and m of the reference run. tol_n = 2 n_b eps with n_b the longest family. */
typedef struct scale {
  double *tf, *tw, *tt; /* force (per component), energy density, dilation */
  double te;            /* total energy */
} scale;

static scale make_scale(pdk_ctx *ctx, const body *b, int k, pdk_model_kind kind,
                        const run_out *ref) {
  pdk_particles *p = make_store(ctx, b);
  pdk_families *fam = make_families(ctx, p, b);
  const double amp = b->lattice ? 0.004 : 0.02;
  const int kk = k == 0 ? 0 : k == 1 ? 1 : 2;
  displace(p, b, kk == 0 ? amp : amp * (kk + 1), 5 + (uint64_t)kk);
  const int dim = b->dim;
  const pdk_index n = pdk_particles_count(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double delta = pdk_families_horizon(fam);
  const double K = 2.0, G = 0.9, dd = dim;
  const double c =
      dim == 3 ? 18.0 * K / (M_PI * pow(delta, 4)) : 72.0 * K / (5.0 * M_PI * pow(delta, 3) * 1.0);
  const double lambda = K - 2.0 * G / 3.0;
  const double c_dil = dim == 3 ? 3.0 * K - 5.0 * G : 2.0 * (lambda - G);
  const double c_dev = dim == 3 ? 15.0 * G : 8.0 * G;
  const double e_bulk = dim == 3 ? K : lambda + G, e_dev = dim == 3 ? 7.5 * G : 4.0 * G;
  const double *V = pdk_particles_volume(p);
  pdk_bond_index nbmax = 1;
  for (pdk_index i = 0; i < n; ++i)
    if (bs[i + 1] - bs[i] > nbmax) nbmax = bs[i + 1] - bs[i];
  const double tol_n = 2.0 * (double)nbmax * DBL_EPSILON;
  scale sc = {calloc((size_t)n, sizeof(double)), calloc((size_t)n, sizeof(double)),
              calloc((size_t)n, sizeof(double)), 0.0};
  const double *th = kind == PDK_MODEL_LPS ? ref->theta[k] : NULL;
  double *inv_m = calloc((size_t)n, sizeof(double));
  for (pdk_index i = 0; i < n && th; ++i)
    inv_m[i] = ref->m[i] > 0 ? 1.0 / ref->m[i] : 0.0;
  /* bond lengths, once */
  for (int pass = 0; pass < (th ? 2 : 1); ++pass)
    for (pdk_index i = 0; i < n; ++i) {
      double sf = 0, sw = 0, st = 0, sp = 0, sd = 0;
      for (pdk_bond_index q = bs[i]; q < bs[i + 1]; ++q) {
        const pdk_index j = bj[q];
        double r0 = 0, r = 0;
        for (int a = 0; a < dim; ++a) {
          const double dX = pdk_particles_X(p, a)[j] - pdk_particles_X(p, a)[i];
          const double dx = ((double *)pdk_particles_field_data(p, "x", a))[j] -
                            ((double *)pdk_particles_field_data(p, "x", a))[i];
          r0 += dX * dX, r += dx * dx;
        }
        r0 = sqrt(r0), r = sqrt(r);
        const double e = r - r0, pv = V[j] * fmin(1.0, (delta + 0.5 - r0) / 1.0);
        if (!th) {
          sf += c * fabs(e) / r0 * pv;
          sw += 0.25 * c * e * e / r0 * pv;
        } else if (pass == 0) {
          st += fabs(e) * pv;
        } else {
          sf += pv *
                (fabs(c_dil) * (fabs(th[i]) * inv_m[i] + fabs(th[j]) * inv_m[j]) * r0 +
                 c_dev * (inv_m[i] + inv_m[j]) * fabs(e)) /
                r0;
          sp += pv * fabs(c_dil) * (sc.tt[i] * inv_m[i] + sc.tt[j] * inv_m[j]);
          const double ed = e - th[i] / dd * r0;
          sw += ed * ed / r0 * pv;
          sd += 2.0 * fabs(ed) * pv / dd;
        }
      }
      if (!th) {
        sc.tf[i] = tol_n * sf;
        sc.tw[i] = tol_n * sw;
      } else if (pass == 0) {
        sc.tt[i] = tol_n * dd * inv_m[i] * st;
      } else {
        /* summation order of this particle's sums, plus what the neighbours' dilation round-off
         * carries into the force and the energy (twice the first-order bound) */
        sc.tf[i] = tol_n * sf + 2.0 * sp;
        sc.tw[i] = tol_n * (0.5 * e_bulk * th[i] * th[i] + e_dev * inv_m[i] * sw) +
                   2.0 * sc.tt[i] * (e_bulk * fabs(th[i]) + e_dev * inv_m[i] * sd);
      }
    }
  for (pdk_index i = 0; i < n; ++i)
    sc.te += V[i] * sc.tw[i];
  free(inv_m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return sc;
}

static void free_scale(scale *sc) { free(sc->tf), free(sc->tw), free(sc->tt); }

static int same_bits(const double *a, const double *b, pdk_index n) {
  return memcmp(a, b, (size_t)n * sizeof(double)) == 0;
}

/* v, a sell run, against r, the CSR reference (tolerances in the header and make_scale). */
static void check_close(const body *b, const scale *scales, const run_out *v, const run_out *r,
                        const char *what) {
  T_ASSERT(v->n == r->n && v->nb == r->nb, "%s: sizes", what);
  for (int k = 0; k < NPASS; ++k) {
    T_ASSERT(v->broken[k] == r->broken[k], "%s pass %d: %lld bonds broken vs %lld", what, k,
             (long long)v->broken[k], (long long)r->broken[k]);
    T_ASSERT(memcmp(v->alive[k], r->alive[k], (size_t)r->nb) == 0,
             "%s pass %d: bond state differs from csr", what, k);
    const scale *sc = &scales[k];
    for (pdk_index i = 0; i < r->n; ++i) {
      for (int c = 0; c < b->dim; ++c)
        T_NEAR(v->f[k][c][i], r->f[k][c][i], 0.0, sc->tf[i], "%s pass %d f%d of %d", what, k, c,
               (int)i);
      T_NEAR(v->w[k][i], r->w[k][i], 0.0, sc->tw[i], "%s pass %d W of %d", what, k, (int)i);
      if (r->theta[k])
        T_NEAR(v->theta[k][i], r->theta[k][i], 0.0, sc->tt[i], "%s pass %d theta of %d", what, k,
               (int)i);
    }
    T_NEAR(v->e[k], r->e[k], 0.0, sc->te + (double)r->n * DBL_EPSILON * fabs(r->e[k]),
           "%s pass %d energy", what, k);
  }
}

static void check_bits(const body *b, const run_out *v, const run_out *r, const char *what) {
  for (int k = 0; k < NPASS; ++k) {
    for (int c = 0; c < b->dim; ++c)
      T_ASSERT(same_bits(v->f[k][c], r->f[k][c], r->n), "%s pass %d: f%d not bitwise equal", what,
               k, c);
    T_ASSERT(same_bits(v->w[k], r->w[k], r->n), "%s pass %d: W not bitwise equal", what, k);
    T_ASSERT(!r->theta[k] || same_bits(v->theta[k], r->theta[k], r->n),
             "%s pass %d: theta not bitwise equal", what, k);
    T_ASSERT(memcmp(&v->e[k], &r->e[k], sizeof(double)) == 0, "%s pass %d: energy %.17g vs %.17g",
             what, k, v->e[k], r->e[k]);
    T_ASSERT(memcmp(v->alive[k], r->alive[k], (size_t)r->nb) == 0, "%s pass %d: bond state", what,
             k);
  }
}

static void check_body(pdk_ctx *ctx, const body *b, pdk_model_kind kind) {
  static const char *const fams[] = {"ref", "avx2", "avx512"};
  for (int pr = 0; pr < 2; ++pr) {
    const pdk_precision prec = pr ? PDK_PRECISION_FLOAT : PDK_PRECISION_DOUBLE;
    run_out ref, first;
    T_ASSERT(run(b, kind, "ref", 1, PDK_LAYOUT_CSR, 0, prec, &ref), "no ref kernels");
    scale scales[NPASS];
    for (int k = 0; k < NPASS; ++k)
      scales[k] = make_scale(ctx, b, k, kind, &ref);
    int have_first = 0;
    for (int kf = 0; kf < 3; ++kf) {
      run_out v1, v2, vu;
      const int C = kf == 1 ? 4 : 8;
      const int sigma = b->lattice ? 0 : 2 * C;
      if (!run(b, kind, fams[kf], 1, PDK_LAYOUT_SELL, sigma, prec, &v1))
        continue; /* not on this CPU */
      T_ASSERT(run(b, kind, fams[kf], 2, PDK_LAYOUT_SELL, sigma, prec, &v2), "2 threads");
      T_ASSERT(run(b, kind, fams[kf], 1, PDK_LAYOUT_SELL, C, prec, &vu), "unsorted");
      char what[160];
      snprintf(what, sizeof what, "%s %d-D %s n=%d %s sell %s", pdk_model_kind_name(kind), b->dim,
               b->lattice ? "lattice" : "hand", (int)b->n, prec ? "float" : "double", fams[kf]);
      check_close(b, scales, &v1, &ref, what);
      check_bits(b, &v2, &v1, what); /* 1 vs 2 threads */
      check_bits(b, &vu, &v1, what); /* window C (unsorted) vs sorted */
      T_ASSERT(v1.padding <= vu.padding, "%s: padding sorted %g > unsorted %g", what, v1.padding,
               vu.padding);
      T_ASSERT(v1.padding >= 0 && v1.padding < 1, "%s: padding %g", what, v1.padding);
      if (!have_first) {
        first = v1, have_first = 1;
      } else {
        check_bits(b, &v1, &first, what); /* every sell variant: the same bits */
        free_run(&v1);
      }
      free_run(&v2);
      free_run(&vu);
    }
    if (b->lattice) { /* the passes must have broken some bonds, not all */
      T_ASSERT(ref.broken[2] > 0 && ref.broken[2] < ref.nb, "%d-D lattice: %lld of %lld broke",
               b->dim, (long long)ref.broken[2], (long long)ref.nb);
    }
    if (have_first) free_run(&first);
    free_run(&ref);
    for (int k = 0; k < NPASS; ++k)
      free_scale(&scales[k]);
  }
}

/* The layout of 0 particles, and the refusals. */
static void edge_cases(void) {
  pdk_ctx *ctx = NULL;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  char why[512];
  T_ASSERT(!pdk_ctx_create(&co, &ctx, why, sizeof why), "%s", why);
  pdk_bond_index bs0 = 0;
  pdk_index bj0 = 0;
  pdk_families *f0 = NULL;
  T_OK(ctx, pdk_families_from_csr(ctx, 0, 1.0, &bs0, &bj0, &f0));
  pdk_sell s;
  uint8_t alive = 1;
  T_OK(ctx, pdk_sell_build(ctx, f0, 8, 0, &alive, NULL, &s));
  T_ASSERT(s.num_slices == 0 && s.num_entries == 0 && pdk_sell_padding_fraction(&s) == 0.0,
           "0 particles: %lld slices, %lld entries", (long long)s.num_slices,
           (long long)s.num_entries);
  pdk_bond_arrays a;
  memset(&a, 0, sizeof a);
  a.dim = 3;
  pdk_pmb_consts k;
  memset(&k, 0, sizeof k);
  T_ASSERT(pdk_kernel_pmb_force_sell_ref(&k, &a, &s.a, 0, 0) == 0, "empty pass");
  pdk_sell_free(&s);
  T_FAILS(ctx, pdk_sell_build(ctx, f0, 17, 0, NULL, NULL, &s), PDK_ERR_ARG, "width 17");
  pdk_families_destroy(&f0);

  /* refusals: layout sell with correspondence and LPS with an influence function, multi-material
   * PMB, an unknown layout */
  body b = {3, 0, 5, 3};
  pdk_particles *p = make_store(ctx, &b);
  pdk_families *fam = make_families(ctx, p, &b);
  pdk_model_opts o = pdk_model_opts_default();
  o.bulk_modulus = 2.0, o.shear_modulus = 1.0, o.density = 1.0;
  o.layout = PDK_LAYOUT_SELL;
  o.kind = PDK_MODEL_CORRESPONDENCE;
  pdk_model *m = NULL;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "layout csr");
  o.kind = PDK_MODEL_LPS;
  o.lps_use_influence = 1;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "lps_use_influence");
  o.lps_use_influence = 0;
  o.kind = PDK_MODEL_PMB;
  o.layout = (pdk_layout)7;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_ARG, "use csr or sell");
  o.layout = PDK_LAYOUT_SELL;
  o.sell_sigma = -1;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_ARG, "sell_sigma");
  o.sell_sigma = 0;
  pdk_material mats[2] = {{2.0, 1.0, 1.0}, {3.0, 1.0, 1.0}};
  o.materials = mats, o.num_materials = 2;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "multi-material");
  T_ASSERT(m == NULL, "no model on refusal");
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
}

/* The scene key model.layout reaches the model. */
static void scene_key(void) {
  const char *src = getenv("PDK_SOURCE_DIR");
  char path[2048];
  snprintf(path, sizeof path, "%s/tests/scenes/t060_minimal.yaml", src ? src : "..");
  pdk_ctx *ctx = NULL;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  char why[512];
  T_ASSERT(!pdk_ctx_create(&co, &ctx, why, sizeof why), "%s", why);
  const char *ov[] = {"model.layout=sell", "model.kind=correspondence",
                      "material.shear_modulus=0.5e9"};
  pdk_scene *sc = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 1, &sc));
  T_OK(ctx, pdk_sim_create(ctx, sc, &sim));
  const pdk_model *m = pdk_sim_model(sim);
  T_ASSERT(pdk_model_opts_get(m)->layout == PDK_LAYOUT_SELL, "scene layout not passed on");
  const double pad = pdk_model_padding_fraction(m);
  /* 6 x 4 x 4: mirror-symmetric, each family length comes 8 times, so sorting leaves none */
  T_ASSERT(pad == 0.0, "padding %g of a 96-particle block", pad);
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), 2, NULL));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&sc);
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 3, &sc));
  T_FAILS(ctx, pdk_sim_create(ctx, sc, &sim), PDK_ERR_UNSUPPORTED, "use layout csr");
  pdk_scene_destroy(&sc);
  const char *bad[] = {"model.layout=blocked"};
  pdk_ctx_error_clear(ctx);
  T_ASSERT(pdk_scene_load(ctx, path, bad, 1, &sc) != 0 && sc == NULL, "layout blocked accepted");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "layout"), "message: %s", pdk_ctx_error_message(ctx));
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  edge_cases();
  scene_key();
  pdk_ctx *ctx = NULL;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  char why[512];
  T_ASSERT(!pdk_ctx_create(&co, &ctx, why, sizeof why), "%s", why);
  for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind)
    for (int dim = 2; dim <= 3; ++dim) {
      for (int q = 0; q < NCOUNTS; ++q) {
        body b = {dim, 0, counts[q], 1000 + (uint64_t)q};
        check_body(ctx, &b, (pdk_model_kind)kind);
      }
      body lat = {dim, 1, 0, 77};
      check_body(ctx, &lat, (pdk_model_kind)kind);
    }
  pdk_ctx_destroy(&ctx);
  return 0;
}
