/* PMB force and LPS dilation / force kernels: every SIMD variant this CPU can run (AVX2, AVX-512)
 * against the reference, 2-D and 3-D, double and float storage (bond_r0), with the stored double
 * bond lengths (bond_r0d) and without, without bond state, with
 * state read (trial) and with state written (commit), with and without the energy.
 *
 * Families are hand-made CSR rows of awkward sizes: 0 (empty), 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33
 * bonds (width - 1, width, width + 1 for widths 4 and 8), so rows start at every alignment; random
 * neighbours (up to 5.2, past the partial-volume edge at 3.5, so 0 < beta < 1 for some), random volumes, a fifth of the
 * bonds broken, random s0, and one bond whose current length is exactly 0 (q = 0 branch). Each
 * call covers a sub-range [5, NP - 3) and must leave the outputs outside it untouched.
 *
 * What must hold, and why:
 *   - with the stored double lengths (bond_r0d from pdk_kernel_bond_lengths_ref), every output of
 *     a SIMD variant has the bits of the same variant computing r0 itself: the stored r0 is the
 *     value the kernel computes (same operations, same order, no FMA), and nothing else changes;
 *   - bond_alive after a committing pass, the number broken and s0_next: bit for bit the
 *     reference's (each bond's stretch is computed with the same operations in the same order, and
 *     a maximum does not depend on order);
 *   - f, w and theta: equal up to the order of the sum over the family. Both sums of n_b terms
 *     carry an error of at most (n_b - 1) eps sum_b |term_b| (first order), so the two differ by at
 *     most 2 n_b eps sum_b |term_b|, with sum_b |term_b| evaluated here from the formulas.
 * A second part runs the models on a jittered lattice with breaking through the context's table:
 * simd and ref contexts break the same bonds (symmetric from both ends), and 1 and 2 threads give
 * the same bits for f, W and the bond state.
 * labels: unit threads */
#include <float.h>
#include <stdint.h>

#include "bond_models_test.h"
#include "kernels.h"
#include "models/model_bond.h"
#include "core/pdk_impl.h"

#define NP 64
#define I0 5
#define I1 (NP - 3)
#define GUARD 1234.5

static const int row_sizes[] = {0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33};
#define NSIZES ((int)(sizeof row_sizes / sizeof row_sizes[0]))

static uint64_t seed = 12345;
static double U(void) { return 0.5 * (bm_rng_sym(&seed) + 1.0); } /* [0, 1) */

static void *zalloc(size_t bytes) {
  bytes = (bytes + 63) / 64 * 64;
  void *p = aligned_alloc(64, bytes ? bytes : 64);
  T_ASSERT(p, "out of memory");
  memset(p, 0, bytes ? bytes : 64);
  return p;
}

typedef struct problem {
  int dim;
  pdk_bond_index bs[NP + 1];
  pdk_index *bj;
  pdk_bond_index nb;
  double *X[3], *x[3], *V, *ref4, *cur4, *s0, *theta, *inv_m;
  float *r0f;
  double *r0d;
  uint8_t *alive0;
} problem;

static problem make_problem(int dim) {
  problem P;
  memset(&P, 0, sizeof P);
  P.dim = dim;
  P.bs[0] = 0;
  for (int i = 0; i < NP; ++i) P.bs[i + 1] = P.bs[i] + row_sizes[(i * 7) % NSIZES];
  P.nb = P.bs[NP];
  P.bj = zalloc((size_t)P.nb * sizeof *P.bj);
  for (int c = 0; c < 3; ++c) {
    P.X[c] = zalloc(NP * sizeof(double));
    P.x[c] = zalloc(NP * sizeof(double));
  }
  P.V = zalloc(NP * sizeof(double));
  P.s0 = zalloc(NP * sizeof(double));
  P.theta = zalloc(NP * sizeof(double));
  P.inv_m = zalloc(NP * sizeof(double));
  P.ref4 = zalloc(4 * NP * sizeof(double));
  P.cur4 = zalloc(4 * NP * sizeof(double));
  P.r0f = zalloc((size_t)P.nb * sizeof(float));
  P.r0d = zalloc((size_t)P.nb * sizeof(double));
  P.alive0 = zalloc((size_t)P.nb);
  for (int i = 0; i < NP; ++i) {
    for (int c = 0; c < dim; ++c) {
      P.X[c][i] = 100.0 + 3.0 * U(); /* off the origin: differences are not exact */
      P.x[c][i] = P.X[c][i] + 0.02 * (U() - 0.5);
    }
    P.V[i] = 0.7 + 0.6 * U();
    P.s0[i] = 0.001 + 0.01 * U();
    P.theta[i] = 0.01 * (U() - 0.5);
    P.inv_m[i] = 0.2 + U();
  }
  for (int c = 0; c < dim; ++c) P.x[c][9] = P.x[c][2]; /* a bond of current length 0 below */
  for (int i = 0; i < NP; ++i)
    for (pdk_bond_index b = P.bs[i]; b < P.bs[i + 1]; ++b) {
      pdk_index j;
      do j = (pdk_index)(U() * NP);
      while (j == i);
      P.bj[b] = j;
      P.alive0[b] = U() < 0.8;
    }
  /* row 2 has bonds (size index 14 % 12 = 2: 3 bonds); make its first bond point at 9 */
  T_ASSERT(P.bs[3] > P.bs[2], "row 2 is not empty");
  P.bj[P.bs[2]] = 9;
  P.alive0[P.bs[2]] = 1;
  for (int i = 0; i < NP; ++i) {
    for (int c = 0; c < 4; ++c) {
      P.ref4[4 * i + c] = c < dim ? P.X[c][i] : c == 3 ? P.inv_m[i] : 0.0;
      P.cur4[4 * i + c] = c < dim ? P.x[c][i] : c == 3 ? P.V[i] : 0.0;
    }
    for (pdk_bond_index b = P.bs[i]; b < P.bs[i + 1]; ++b) {
      double r2 = 0;
      for (int c = 0; c < dim; ++c) {
        const double d = P.X[c][P.bj[b]] - P.X[c][i];
        r2 += d * d;
      }
      P.r0f[b] = (float)sqrt(r2);
    }
  }
  pdk_bond_arrays a;
  memset(&a, 0, sizeof a);
  a.dim = dim;
  a.bond_start = P.bs;
  a.bond_j = P.bj;
  for (int c = 0; c < dim; ++c) a.X[c] = P.X[c];
  pdk_kernel_bond_lengths_ref(&a, 0, NP, P.r0d);
  return P;
}

static void free_problem(problem *P) {
  free(P->bj);
  for (int c = 0; c < 3; ++c) free(P->X[c]), free(P->x[c]);
  free(P->V), free(P->s0), free(P->theta), free(P->inv_m), free(P->ref4), free(P->cur4);
  free(P->r0f), free(P->r0d), free(P->alive0);
}

typedef struct outputs {
  double *f[3], *w, *theta, *s0n;
  uint8_t *alive;
  pdk_bond_index broken;
} outputs;

static outputs make_outputs(const problem *P) {
  outputs o;
  for (int c = 0; c < 3; ++c) o.f[c] = zalloc(NP * sizeof(double));
  o.w = zalloc(NP * sizeof(double));
  o.theta = zalloc(NP * sizeof(double));
  o.s0n = zalloc(NP * sizeof(double));
  o.alive = zalloc((size_t)P->nb);
  o.broken = 0;
  return o;
}

static void free_outputs(outputs *o) {
  for (int c = 0; c < 3; ++c) free(o->f[c]);
  free(o->w), free(o->theta), free(o->s0n), free(o->alive);
}

static void reset_outputs(const problem *P, outputs *o) {
  for (int i = 0; i < NP; ++i) {
    for (int c = 0; c < 3; ++c) o->f[c][i] = GUARD;
    o->w[i] = o->theta[i] = o->s0n[i] = GUARD;
  }
  memcpy(o->alive, P->alive0, (size_t)P->nb);
  o->broken = 0;
}

/* stored: 0 r0 computed, 1 float lengths, 2 double lengths (bond_r0d);
 * state: 0 none, 1 trial (read), 2 commit (read and write) */
static pdk_bond_arrays arrays_for(const problem *P, outputs *o, int rows, int stored, int state,
                                  int energy) {
  pdk_bond_arrays a;
  memset(&a, 0, sizeof a);
  a.dim = P->dim;
  a.bond_start = P->bs;
  a.bond_j = P->bj;
  for (int c = 0; c < P->dim; ++c) {
    a.X[c] = P->X[c];
    a.x[c] = P->x[c];
    a.f[c] = o->f[c];
  }
  a.volume = P->V;
  a.ref4 = rows ? P->ref4 : NULL;
  a.cur4 = rows ? P->cur4 : NULL;
  a.bond_r0 = stored == 1 ? P->r0f : NULL;
  a.bond_r0d = stored == 2 ? P->r0d : NULL;
  a.bond_alive = state ? o->alive : NULL;
  a.s0 = P->s0;
  a.s0_next = state == 2 ? o->s0n : NULL;
  a.theta = P->theta;
  a.inv_m = P->inv_m;
  a.theta_out = o->theta;
  a.w = energy ? o->w : NULL;
  return a;
}

/* sum_b |term| per particle for the bound: force components, energy and dilation sums. */
typedef struct mags {
  double f[NP], w[NP], th[NP];
} mags;

static void magnitudes(const problem *P, int model_lps, int stored, int state,
                       const pdk_pmb_consts *kp, const pdk_lps_consts *kl, mags *M) {
  for (int i = 0; i < NP; ++i) {
    M->f[i] = M->w[i] = M->th[i] = 0;
    for (pdk_bond_index b = P->bs[i]; b < P->bs[i + 1]; ++b) {
      const pdk_index j = P->bj[b];
      double r2 = 0, R2 = 0, eta1 = 0;
      for (int c = 0; c < P->dim; ++c) {
        const double dx = P->x[c][j] - P->x[c][i], dX = P->X[c][j] - P->X[c][i];
        r2 += dx * dx;
        R2 += dX * dX;
        eta1 += fabs(dx);
      }
      const double r = sqrt(r2), r0 = stored == 1 ? (double)P->r0f[b] : sqrt(R2);
      const double on = state ? P->alive0[b] : 1.0;
      const double vs_a = model_lps ? kl->vs_a : kp->vs_a, vs_b = model_lps ? kl->vs_b : kp->vs_b;
      const double pv = fabs(P->V[j] * fmin(1.0, (vs_a - r0) * vs_b));
      const double q = r > 0 ? 1.0 / (r0 * r) : 0.0, e = r - r0;
      double g;
      if (!model_lps) {
        g = on * kp->c * pv * e * q;
        M->w[i] += fabs(0.25 * g * e * r);
      } else {
        g = on * pv *
            (fabs(kl->c_dil * (P->theta[i] * P->inv_m[i] + P->theta[j] * P->inv_m[j]) * r0) +
             fabs(kl->c_dev * (P->inv_m[i] + P->inv_m[j]) * e)) *
            q;
        const double ed = e - P->theta[i] / kl->theta_factor * r0;
        M->w[i] += ed * ed / r0 * on * pv;
        M->th[i] += fabs(on * e * pv);
      }
      M->f[i] += fabs(g) * eta1;
    }
  }
}

static void compare(const char *what, const problem *P, const outputs *ref, const outputs *opt,
                    const mags *M, int state, int energy, int check_f, int check_theta,
                    const pdk_lps_consts *kl) {
  const double eps = DBL_EPSILON;
  for (int i = 0; i < NP; ++i) {
    const int in = i >= I0 && i < I1;
    const double nbi = (double)(P->bs[i + 1] - P->bs[i]);
    if (check_f)
      for (int c = 0; c < P->dim; ++c) {
        if (!in) {
          T_ASSERT(opt->f[c][i] == GUARD, "%s: f[%d][%d] written outside [%d, %d)", what, c, i, I0, I1);
          continue;
        }
        T_NEAR(opt->f[c][i], ref->f[c][i], 0, 2 * nbi * eps * M->f[i] + DBL_MIN,
               "%s: f[%d] of particle %d (%g bonds)", what, c, i, nbi);
      }
    if (check_f && energy && in) {
      double scale = M->w[i];
      if (kl) scale = kl->e_dev * P->inv_m[i] * M->w[i] + 0.5 * kl->e_bulk * P->theta[i] * P->theta[i];
      T_NEAR(opt->w[i], ref->w[i], 0, 2 * (nbi + 2) * eps * scale + DBL_MIN,
             "%s: w of particle %d", what, i);
    }
    if (check_f && !energy) T_ASSERT(opt->w[i] == GUARD, "%s: w written without request", what);
    if (check_theta) {
      if (!in) {
        T_ASSERT(opt->theta[i] == GUARD, "%s: theta[%d] written outside the range", what, i);
        continue;
      }
      const double scale = kl->theta_factor * P->inv_m[i] * M->th[i];
      T_NEAR(opt->theta[i], ref->theta[i], 0, 2 * (nbi + 2) * eps * scale + DBL_MIN,
             "%s: theta of particle %d", what, i);
    }
    if (state == 2 && check_f) {
      T_ASSERT(memcmp(&opt->s0n[i], &ref->s0n[i], sizeof(double)) == 0,
               "%s: s0_next[%d] %.17g vs reference %.17g", what, i, opt->s0n[i], ref->s0n[i]);
    }
  }
  if (check_f) {
    T_ASSERT(memcmp(opt->alive, ref->alive, (size_t)P->nb) == 0, "%s: bond state differs", what);
    T_ASSERT(opt->broken == ref->broken, "%s: broke %lld bonds, reference %lld", what,
             (long long)opt->broken, (long long)ref->broken);
  }
}

/* Every output bit for bit (bond_r0d against r0 computed by the same variant). */
static void same_bits(const char *what, const problem *P, const outputs *a, const outputs *b) {
  for (int c = 0; c < 3; ++c)
    T_ASSERT(memcmp(a->f[c], b->f[c], NP * sizeof(double)) == 0, "%s: f[%d] bits differ", what, c);
  T_ASSERT(memcmp(a->w, b->w, NP * sizeof(double)) == 0, "%s: w bits differ", what);
  T_ASSERT(memcmp(a->theta, b->theta, NP * sizeof(double)) == 0, "%s: theta bits differ", what);
  T_ASSERT(memcmp(a->s0n, b->s0n, NP * sizeof(double)) == 0, "%s: s0_next bits differ", what);
  T_ASSERT(memcmp(a->alive, b->alive, (size_t)P->nb) == 0, "%s: bond state differs", what);
  T_ASSERT(a->broken == b->broken, "%s: broken counts differ", what);
}

typedef struct variant {
  const char *name;
  unsigned need;
  pdk_pmb_force_fn pmb;
  pdk_lps_dilation_fn dil;
  pdk_lps_force_fn lps;
} variant;

/* Returns the number of variants tested. */
static int kernel_tests(unsigned isa) {
  const variant vs[] = {
      {"avx2", PDK_ISA_AVX2, pdk_kernel_pmb_force_avx2, pdk_kernel_lps_dilation_avx2,
       pdk_kernel_lps_force_avx2},
      {"avx512", PDK_ISA_AVX512, pdk_kernel_pmb_force_avx512, pdk_kernel_lps_dilation_avx512,
       pdk_kernel_lps_force_avx512},
  };
  int ran = 0, broke_some = 0;
  for (int dim = 2; dim <= 3; ++dim) {
    problem P = make_problem(dim);
    outputs ref = make_outputs(&P), opt = make_outputs(&P), own = make_outputs(&P);
    pdk_pmb_consts kp = {.c = 3.0, .vs_a = 5.5, .vs_b = 0.5, .s00 = 0.005, .alpha = 0.25};
    pdk_lps_consts kl = {.vs_a = 5.5, .vs_b = 0.5, .theta_factor = dim, .c_dil = -1.3,
                         .c_dev = 4.0, .e_bulk = 1.1, .e_dev = 2.0, .s00 = 0.005, .alpha = 0.25};
    for (size_t v = 0; v < sizeof vs / sizeof vs[0]; ++v) {
      if (!(isa & vs[v].need)) continue;
      ++ran;
      for (int stored = 0; stored <= 2; ++stored)
        for (int state = 0; state <= 2; ++state)
          for (int energy = 0; energy <= 1; ++energy) {
            char what[160];
            mags M;
            /* PMB force */
            snprintf(what, sizeof what, "%s pmb %d-D stored %d state %d energy %d", vs[v].name, dim,
                     stored, state, energy);
            reset_outputs(&P, &ref);
            reset_outputs(&P, &opt);
            pdk_bond_arrays ar = arrays_for(&P, &ref, 0, stored, state, energy);
            pdk_bond_arrays ao = arrays_for(&P, &opt, 1, stored, state, energy);
            ref.broken = pdk_kernel_pmb_force_ref(&kp, &ar, I0, I1);
            opt.broken = vs[v].pmb(&kp, &ao, I0, I1);
            magnitudes(&P, 0, stored, state, &kp, NULL, &M);
            compare(what, &P, &ref, &opt, &M, state, energy, 1, 0, NULL);
            broke_some += ref.broken > 0;
            if (stored == 2) {
              reset_outputs(&P, &own);
              pdk_bond_arrays a0 = arrays_for(&P, &own, 1, 0, state, energy);
              own.broken = vs[v].pmb(&kp, &a0, I0, I1);
              same_bits(what, &P, &opt, &own);
            }
            /* LPS dilation */
            snprintf(what, sizeof what, "%s lps dilation %d-D stored %d state %d", vs[v].name, dim,
                     stored, state);
            reset_outputs(&P, &ref);
            reset_outputs(&P, &opt);
            ar = arrays_for(&P, &ref, 0, stored, state, energy);
            ao = arrays_for(&P, &opt, 1, stored, state, energy);
            pdk_kernel_lps_dilation_ref(&kl, &ar, I0, I1);
            vs[v].dil(&kl, &ao, I0, I1);
            magnitudes(&P, 1, stored, state, NULL, &kl, &M);
            compare(what, &P, &ref, &opt, &M, 0, 0, 0, 1, &kl);
            if (stored == 2) {
              reset_outputs(&P, &own);
              pdk_bond_arrays a0 = arrays_for(&P, &own, 1, 0, state, energy);
              vs[v].dil(&kl, &a0, I0, I1);
              same_bits(what, &P, &opt, &own);
            }
            /* LPS force */
            snprintf(what, sizeof what, "%s lps force %d-D stored %d state %d energy %d",
                     vs[v].name, dim, stored, state, energy);
            reset_outputs(&P, &ref);
            reset_outputs(&P, &opt);
            ar = arrays_for(&P, &ref, 0, stored, state, energy);
            ao = arrays_for(&P, &opt, 1, stored, state, energy);
            ref.broken = pdk_kernel_lps_force_ref(&kl, &ar, I0, I1);
            opt.broken = vs[v].lps(&kl, &ao, I0, I1);
            compare(what, &P, &ref, &opt, &M, state, energy, 1, 0, &kl);
            if (stored == 2) {
              reset_outputs(&P, &own);
              pdk_bond_arrays a0 = arrays_for(&P, &own, 1, 0, state, energy);
              own.broken = vs[v].lps(&kl, &a0, I0, I1);
              same_bits(what, &P, &opt, &own);
            }
          }
    }
    free_outputs(&ref), free_outputs(&opt), free_outputs(&own), free_problem(&P);
  }
  T_ASSERT(!(isa & PDK_ISA_AVX2) || ran > 0, "no variant ran on an AVX2 CPU");
  T_ASSERT(!ran || broke_some > 0, "the commit passes broke no bond: the failure path is untested");
  return ran;
}

/* ---- model level: table, threads, breaking -------------------------------------------------- */

typedef struct run_out {
  double *f[3], *w;
  uint8_t *alive;
  pdk_bond_index nb, broken;
  pdk_index n;
} run_out;

static run_out model_run(const char *kernels, int threads, int dim, int kind, int precision) {
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  co.kernels = kernels;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  pdk_particles *p = bm_body(ctx, dim, 23, 19, dim == 3 ? 11 : 1, 1.0, 0.1, 0.2, 77);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = (pdk_model_kind)kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.critical_stretch = 0.004;
  o.alpha = 0.25;
  o.lattice_constant = 1.0;
  o.precision = (pdk_precision)precision;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  run_out r;
  r.n = pdk_particles_count(p);
  double *w = NULL;
  for (int pass = 0; pass < 4; ++pass) {
    bm_displace_random(p, 0.004 * (pass + 1), 99 + (uint64_t)pass);
    double e;
    T_OK(ctx, pdk_model_force(m, &e));
  }
  w = (double *)(kind == PDK_MODEL_PMB ? pdk_model_pmb_energy_density(m)
                                       : pdk_model_lps_energy_density(m));
  for (int c = 0; c < 3; ++c) r.f[c] = NULL;
  for (int c = 0; c < dim; ++c) {
    r.f[c] = malloc((size_t)r.n * sizeof(double));
    memcpy(r.f[c], pdk_particles_field_data(p, "f", c), (size_t)r.n * sizeof(double));
  }
  r.w = malloc((size_t)r.n * sizeof(double));
  memcpy(r.w, w, (size_t)r.n * sizeof(double));
  r.nb = pdk_families_num_bonds(fam);
  r.alive = malloc((size_t)r.nb);
  memcpy(r.alive, pdk_model_bond_alive(m), (size_t)r.nb);
  r.broken = pdk_model_num_broken(m);
  /* symmetric bond state: bond (i, j) broken iff (j, i) broken */
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  for (pdk_index i = 0; i < r.n; ++i)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const int64_t back = bm_find_bond(bs, bj, bj[b], i);
      T_ASSERT(back >= 0 && r.alive[back] == r.alive[b], "bond %d-%d state not symmetric", (int)i,
               (int)bj[b]);
    }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return r;
}

static void free_run(run_out *r) {
  for (int c = 0; c < 3; ++c) free(r->f[c]);
  free(r->w);
  free(r->alive);
}

static void model_tests(void) {
  for (int dim = 2; dim <= 3; ++dim)
    for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
      run_out a = model_run("simd", 1, dim, kind, 0), b = model_run("simd", 2, dim, kind, 0);
      run_out r = model_run("ref", 2, dim, kind, 0);
      T_ASSERT(a.broken > 0 && a.broken < a.nb, "%d-D kind %d: %lld of %lld bonds broke; the test "
               "needs some but not all", dim, kind, (long long)a.broken, (long long)a.nb);
      for (int c = 0; c < dim; ++c)
        T_ASSERT(memcmp(a.f[c], b.f[c], (size_t)a.n * sizeof(double)) == 0,
                 "%d-D kind %d: f differs between 1 and 2 threads", dim, kind);
      T_ASSERT(memcmp(a.w, b.w, (size_t)a.n * sizeof(double)) == 0, "W differs, 1 vs 2 threads");
      T_ASSERT(memcmp(a.alive, b.alive, (size_t)a.nb) == 0, "bond state differs, 1 vs 2 threads");
      /* simd and ref break the same bonds (same stretches bit for bit) */
      T_ASSERT(memcmp(a.alive, r.alive, (size_t)a.nb) == 0 && a.broken == r.broken,
               "%d-D kind %d: simd broke %lld bonds, ref %lld", dim, kind, (long long)a.broken,
               (long long)r.broken);
      free_run(&a), free_run(&b), free_run(&r);
    }
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const int ran = kernel_tests(t_isa(ctx));
  pdk_ctx_destroy(&ctx);
  model_tests();
  if (!ran)
    T_SKIP("t026: this CPU has neither AVX2 nor AVX-512: no variant to test (the model part ran)");
  return 0;
}
