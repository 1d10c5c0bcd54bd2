/* Correspondence kernels: every optimized variant this CPU runs (AVX2, AVX-512) against the
 * reference, shape, pass 1 and pass 2 each on the same inputs, 2-D and 3-D, every law (linear,
 * SVK, Neo-Hooke), influence function and stabilization (none, Silling, hourglass), double and
 * float storage, without and with a bond state (random broken bonds, a row with all bonds
 * broken), on awkward families: empty, 1 bond, 2, 3, width - 1, width, width + 1 for widths 4 and
 * 8, 15-17, 31-33, 64, and collinear (2-D) / coplanar (3-D) families that do not span. Rows of
 * random length make every row start at a different alignment. Also: the table installs the
 * variant for the CPU and PDK_KERNELS=ref installs the reference; a variant's result for a row
 * does not depend on how the particle range is split (1 call or 2 ranges, as 1 or 2 threads
 * would split it): bitwise. Without hourglass stabilization the variants run over packed rows
 * (kernels/opt/corr_simd.h): their pass 1 leaves rows and i's own terms for their pass 2, so pass 2
 * is checked from the variant's own pass-1 state, the reference's pass 2 run on a copy of it (pass
 * 1 itself is checked against the reference's pass 1 as before).
 *
 * Tolerances, from the sums the kernels compute (u = 2^-53). Both versions sum the same n terms,
 * the variant in another order (SIMD lanes, own terms factored out) and with FMA, so a sum
 * differs by at most about 2 (n + 8) u S, S the sum of the terms' magnitudes (written |.| below),
 * which the test computes from the inputs:
 *   shape   K: DK = 2 (n + 8) u sum w V |xi|^2; K^-1: 4 d^2 |K^-1|max^2 DK; m: DK (m = tr K in
 *           the variant); flags and intact counts exactly;
 *   pass 1  F: 2 (n + 8) u sum_c (sum_b w V |Y_r| |xi_c|) |K^-1|max d; A and W through the law
 *           (evaluated by the same code) from that F difference, with the law's Lipschitz bound
 *           near F = I: 20 (lambda + 2 mu) d^2 |DF| |K^-1|max for A, 20 (lambda + 2 mu) d^2 |DF|
 *           for W (positions move by at most 5 % of a spacing, so |F - I| < 0.3); flags exactly;
 *   pass 2  f: 2 (n + 8) u S_f, S_f = sum_b w V (sum_c (|A_i| + |A_j| + k_i |F_i| + k_j |F_j|)
 *           |xi_c| + (k_i + k_j) (|Y| + |xi|) + hourglass: the magnitudes in g times |Y|) +
 *           |B_i| |sum w V xi| (the factored own term), |.| 1-norms of vectors and largest
 *           entries of tensors; W: 2 (n + 8) u k_i sum w V |z|^2 plus its own value's rounding
 *           (the packed-row variant takes sum w V |z|^2 = sum w V |Y - xi|^2 - H : D from pass 1's
 *           sums, H = F - I, D = sum w V (Y - xi) (x) xi: its round-off is of the size of the
 *           first sum, below the bound, which counts |Y| + |F| |xi| for |z|).
 * labels: unit */
#include <stdint.h>

#include "kernels.h"
#include "models/model_impl.h"
#include "core/pdk_impl.h"
#include "test_util.h"

typedef pdk_index (*shape_fn)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index,
                              pdk_index);
typedef void (*pass_fn)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index);

static uint64_t rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1p-53; }

static const int row_len[] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 32, 33, 64, 6, 0, 11, 40};
enum { NROW = (int)(sizeof row_len / sizeof row_len[0]), NP = 120, NPAD = 128 };
#define U 0x1p-53

/* One set of arrays (every pointer the kernels may use). */
typedef struct set {
  double *pd[3 * 3 * 9 + 16]; /* per-particle doubles */
  float *pf[18];
  uint8_t *flag;
  int32_t *num_alive;
  double *rows[3]; /* ref4, cur4, own */
  void *row;       /* pdk_corr_row or pdk_corr_rowf [NPAD] */
  pdk_corr_arrays a;
} set;

static double *dalloc(void) { return calloc(NPAD, sizeof(double)); }

static void set_init(set *s, int d, unsigned layout, const pdk_bond_index *bs, const pdk_index *bj,
                     const double *omega, uint8_t *alive, double *const *X, double *const *x,
                     const double *V) {
  memset(s, 0, sizeof *s);
  int q = 0;
  pdk_corr_arrays *a = &s->a;
  a->bond_start = bs;
  a->bond_j = bj;
  a->bond_omega = omega;
  a->bond_alive = alive;
  for (int c = 0; c < d; ++c)
    a->X[c] = X[c], a->x[c] = x[c];
  a->volume = V;
  for (int t = 0; t < d * d; ++t) {
    a->Kinv[t] = s->pd[q++] = dalloc();
    a->F[t] = s->pd[q++] = dalloc();
    a->A[t] = s->pd[q++] = dalloc();
    if (layout & 2u) a->B[t] = s->pd[q++] = dalloc();
    if (layout & 4u) a->G[t] = s->pd[q++] = dalloc();
    if (layout & 8u) a->Bf[t] = s->pf[2 * t] = calloc(NPAD, sizeof(float));
    if (layout & 16u) a->Gf[t] = s->pf[2 * t + 1] = calloc(NPAD, sizeof(float));
  }
  if (layout & 1u) a->kst = s->pd[q++] = dalloc();
  a->m = s->pd[q++] = dalloc();
  a->W = s->pd[q++] = dalloc();
  for (int c = 0; c < d; ++c)
    a->f[c] = s->pd[q++] = dalloc();
  a->w_damage = s->pd[q++] = dalloc();
  a->flag = s->flag = calloc(NPAD, 1);
  if (alive) a->num_alive = s->num_alive = calloc(NPAD, sizeof(int32_t));
  if (layout & 32u) { /* packed rows: ref4 (X, V) and cur4 (x - X, 1) filled as the driver does */
    for (int r = 0; r < 3; ++r)
      s->rows[r] = aligned_alloc(64, 4 * NPAD * sizeof(double)), memset(s->rows[r], 0, 4 * NPAD * 8);
    for (pdk_index i = 0; i < NPAD; ++i) {
      for (int c = 0; c < d; ++c)
        s->rows[0][4 * i + c] = X[c][i];
      s->rows[0][4 * i + 3] = V[i];
    }
    pdk_corr_pack_cur(d, (const double *const *)X, (const double *const *)x, s->rows[1], 0, NPAD);
    a->ref4 = s->rows[0], a->cur4 = s->rows[1], a->own = s->rows[2];
    if (layout & 8u) {
      s->row = aligned_alloc(64, NPAD * sizeof(pdk_corr_rowf));
      a->rowf = s->row;
    } else {
      s->row = aligned_alloc(64, NPAD * sizeof(pdk_corr_row));
      a->row = s->row;
    }
  }
}

static void set_free(set *s) {
  for (size_t k = 0; k < sizeof s->pd / sizeof s->pd[0]; ++k)
    free(s->pd[k]);
  for (size_t k = 0; k < sizeof s->pf / sizeof s->pf[0]; ++k)
    free(s->pf[k]);
  free(s->flag);
  free(s->num_alive);
  for (int r = 0; r < 3; ++r)
    free(s->rows[r]);
  free(s->row);
}

/* Copies every per-particle output of src into dst (same layout). */
static void set_copy(set *dst, const set *src, int d) {
  const pdk_corr_arrays *a = &src->a;
  pdk_corr_arrays *b = &dst->a;
  const size_t z = NPAD * sizeof(double), zf = NPAD * sizeof(float);
  for (int t = 0; t < d * d; ++t) {
    memcpy(b->Kinv[t], a->Kinv[t], z);
    memcpy(b->F[t], a->F[t], z);
    memcpy(b->A[t], a->A[t], z);
    if (a->B[t]) memcpy(b->B[t], a->B[t], z);
    if (a->G[t]) memcpy(b->G[t], a->G[t], z);
    if (a->Bf[t]) memcpy(b->Bf[t], a->Bf[t], zf);
    if (a->Gf[t]) memcpy(b->Gf[t], a->Gf[t], zf);
  }
  if (a->kst) memcpy(b->kst, a->kst, z);
  memcpy(b->m, a->m, z);
  memcpy(b->W, a->W, z);
  memcpy(b->w_damage, a->w_damage, z);
  memcpy(dst->flag, src->flag, NPAD);
  if (src->num_alive) memcpy(dst->num_alive, src->num_alive, NPAD * sizeof(int32_t));
}

static double maxabs(double *const *T, int dd, pdk_index i) {
  double m = 0.0;
  for (int t = 0; t < dd; ++t)
    m = fmax(m, fabs(T[t][i]));
  return m;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const unsigned isa = t_isa(ctx);
  struct {
    const char *name;
    unsigned need;
    shape_fn shape;
    pass_fn pass1, pass2;
  } variants[] = {
      {"avx2", PDK_ISA_AVX2, pdk_kernel_corr_shape_avx2, pdk_kernel_corr_pass1_avx2,
       pdk_kernel_corr_pass2_avx2},
      {"avx512", PDK_ISA_AVX512, pdk_kernel_corr_shape_avx512, pdk_kernel_corr_pass1_avx512,
       pdk_kernel_corr_pass2_avx512},
  };
  /* The table: the variant for the CPU, or the reference. */
  pdk_kernel_table t;
  T_ASSERT(pdk_kernels_select("simd", isa, &t) == 0, "select simd");
  if (isa & PDK_ISA_AVX512)
    T_ASSERT(t.corr_pass2 == pdk_kernel_corr_pass2_avx512 && t.corr_opt, "AVX-512 installed");
  else if (isa & PDK_ISA_AVX2)
    T_ASSERT(t.corr_pass2 == pdk_kernel_corr_pass2_avx2 && t.corr_opt, "AVX2 installed");
  T_ASSERT(pdk_kernels_select("ref", isa, &t) == 0 && t.corr_pass1 == pdk_kernel_corr_pass1_ref &&
               t.corr_shape == pdk_kernel_corr_shape_ref && !t.corr_opt,
           "ref table");
  if (isa & PDK_ISA_AVX2)
    T_ASSERT(pdk_kernels_select("avx2", isa, &t) == 0 && t.corr_pass2 == pdk_kernel_corr_pass2_avx2,
             "avx2 forced");

  uint64_t seed = 11;
  int tested = 0;
  for (int d = 2; d <= 3; ++d) {
    /* Particles: jittered points in a box of side 6 (spacing ~1), current positions moved by at
     * most 5 % of a spacing. */
    double *X[3], *x[3], *V = dalloc();
    for (int c = 0; c < d; ++c) {
      X[c] = dalloc(), x[c] = dalloc();
      for (pdk_index i = 0; i < NP; ++i)
        X[c][i] = 6.0 * rng_unit(&seed);
    }
    for (pdk_index i = 0; i < NP; ++i)
      V[i] = 0.5 + rng_unit(&seed);
    /* Rows 0..NROW-1 take row_len bonds (rows 3 and 9: neighbours on a line through i (2-D) or a
     * plane (3-D), so K is singular); every other row 0..40 random bonds. */
    pdk_bond_index bs[NP + 1];
    pdk_index *bj = malloc(NP * 70 * sizeof *bj);
    bs[0] = 0;
    for (pdk_index i = 0; i < NP; ++i) {
      int len = i < NROW ? row_len[i] : (int)(rng_next(&seed) % 41);
      const int flat = i == 3 || i == 9;
      pdk_bond_index b = bs[i];
      for (int e = 0; e < len; ++e) {
        pdk_index j = (pdk_index)(rng_next(&seed) % NP);
        if (j == i) j = (j + 1) % NP;
        if (flat && j < NROW) j += NROW; /* keep rows 0..NROW-1 of other tests unmoved */
        bj[b++] = j;
      }
      bs[i + 1] = b;
    }
    /* Make the flat rows' neighbours exact: j on the line X_i + s (1, 2) (2-D) or the plane z =
     * z_i (3-D), small integer offsets so the points are exactly collinear / coplanar. */
    for (int i = 3; i <= 9; i += 6)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const pdk_index j = bj[b];
        const double s = (double)(b - bs[i] + 1) * 0.25;
        X[0][j] = X[0][i] + s;
        X[1][j] = X[1][i] + (d == 2 ? 2.0 * s : -s * 0.5);
        if (d == 3) X[2][j] = X[2][i];
      }
    for (int c = 0; c < d; ++c)
      for (pdk_index i = 0; i < NP; ++i)
        x[c][i] = X[c][i] + 0.05 * (2.0 * rng_unit(&seed) - 1.0);
    const pdk_bond_index nb = bs[NP];
    double *omega = malloc((size_t)(nb + 1) * sizeof *omega);
    uint8_t *alive = malloc((size_t)nb + 1);
    double horizon = 0.0;
    for (pdk_index i = 0; i < NP; ++i)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        double r2 = 0.0;
        for (int c = 0; c < d; ++c)
          r2 += (X[c][bj[b]] - X[c][i]) * (X[c][bj[b]] - X[c][i]);
        horizon = fmax(horizon, sqrt(r2));
        alive[b] = rng_next(&seed) % 5 != 0;
        if (i == 18) alive[b] = 0; /* a row with every bond broken */
      }
    for (int infl = 0; infl <= PDK_INFLUENCE_GAUSSIAN; ++infl) {
      for (pdk_index i = 0; i < NP; ++i)
        for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
          double r2 = 0.0;
          for (int c = 0; c < d; ++c)
            r2 += (X[c][bj[b]] - X[c][i]) * (X[c][bj[b]] - X[c][i]);
          omega[b] = fmax(pdk_influence_eval((pdk_influence)infl, sqrt(r2), horizon, 0.5), 0.0);
        }
      for (int law = 0; law <= PDK_LAW_NEO_HOOKE; ++law)
        for (int stab = 0; stab <= PDK_STAB_HOURGLASS; ++stab)
          for (int fl = 0; fl <= 1; ++fl)
            for (int with_alive = 0; with_alive <= 1; ++with_alive) {
              /* Not every combination: all laws with Silling, every stabilization with Neo-Hooke,
               * both storages and bond states throughout. */
              if (law != PDK_LAW_NEO_HOOKE && stab != PDK_STAB_SILLING) continue;
              pdk_corr_consts k;
              memset(&k, 0, sizeof k);
              k.dim = d;
              k.law = law;
              k.mu = 1.0;
              k.lambda = 4.0 / 3.0;
              k.stab = stab;
              k.stab_modulus = 0.1 * (d == 3 ? 72.0 / 5.0 : 36.0 / 5.0) * 2.0;
              k.horizon = horizon;
              k.span_rtol = PDK_CORR_SPAN_RTOL;
              /* The arrays of both kinds: the variant's (packed rows except for hourglass) and
               * the reference's (kst, and Bf, Gf in float storage), so either pass 2 can run on
               * one pass-1 state. */
              const unsigned layout = pdk_corr_pair_layout(stab, fl, 1) |
                                      pdk_corr_pair_layout(stab, fl, 0) | (stab ? 1u : 0u);
              uint8_t *al = with_alive ? alive : NULL;
              set ref, var, var2;
              set_init(&ref, d, layout, bs, bj, omega, al, X, x, V);
              pdk_index flagged_ref = pdk_kernel_corr_shape_ref(&k, &ref.a, 0, NP);
              for (size_t v = 0; v < sizeof variants / sizeof variants[0]; ++v) {
                if (!(isa & variants[v].need)) continue;
                const char *vn = variants[v].name;
                set_init(&var, d, layout, bs, bj, omega, al, X, x, V);
                set_init(&var2, d, layout, bs, bj, omega, al, X, x, V);
                /* shape */
                const pdk_index flagged = variants[v].shape(&k, &var.a, 0, NP);
                T_ASSERT(flagged == flagged_ref, "%s d %d: %d flagged vs %d", vn, d, (int)flagged,
                         (int)flagged_ref);
                T_ASSERT(flagged >= 4, "empty, 1-bond and flat rows flagged (%d)", (int)flagged);
                for (pdk_index i = 0; i < NP; ++i) {
                  double S = 0.0;
                  int n = 0;
                  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b, ++n)
                    for (int c = 0; c < d; ++c)
                      S += omega[b] * V[bj[b]] * (X[c][bj[b]] - X[c][i]) * (X[c][bj[b]] - X[c][i]);
                  const double DK = 2.0 * (n + 8) * U * S;
                  const double kmax = maxabs(ref.a.Kinv, d * d, i);
                  T_ASSERT(var.flag[i] == ref.flag[i], "%s: flag of %d", vn, (int)i);
                  if (al) T_ASSERT(var.num_alive[i] == ref.num_alive[i], "%s: count", vn);
                  T_NEAR(var.a.m[i], ref.a.m[i], 0.0, DK, "%s d %d: m of %d", vn, d, (int)i);
                  for (int c = 0; c < d * d; ++c)
                    T_NEAR(var.a.Kinv[c][i], ref.a.Kinv[c][i], 0.0,
                           4.0 * d * d * kmax * kmax * DK + 1e-300, "%s d %d: Kinv[%d] of %d", vn,
                           d, c, (int)i);
                }
                /* pass 1 from the same shape */
                set_copy(&var, &ref, d);
                set_copy(&var2, &ref, d);
                set ref1;
                set_init(&ref1, d, layout, bs, bj, omega, al, X, x, V);
                set_copy(&ref1, &ref, d);
                pdk_kernel_corr_pass1_ref(&k, &ref1.a, 0, NP);
                variants[v].pass1(&k, &var.a, 0, NP);
                variants[v].pass1(&k, &var2.a, 0, 37); /* split ranges: bitwise the same */
                variants[v].pass1(&k, &var2.a, 37, NP);
                for (pdk_index i = 0; i < NP; ++i) {
                  double S[3][3] = {{0}};
                  int n = 0;
                  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b, ++n) {
                    if (al && !al[b]) continue;
                    const pdk_index j = bj[b];
                    for (int r = 0; r < d; ++r)
                      for (int c = 0; c < d; ++c)
                        S[r][c] +=
                            omega[b] * V[j] * fabs(x[r][j] - x[r][i]) * fabs(X[c][j] - X[c][i]);
                  }
                  const double kmax = maxabs(ref1.a.Kinv, d * d, i);
                  double DF = 0.0;
                  for (int r = 0; r < d; ++r)
                    for (int c = 0; c < d; ++c)
                      DF = fmax(DF, 2.0 * (n + 8) * U * S[r][c] * kmax * d);
                  const double Lip = 20.0 * (k.lambda + 2.0 * k.mu) * d * d;
                  T_ASSERT(var.flag[i] == ref1.flag[i], "%s: pass-1 flag of %d", vn, (int)i);
                  for (int c = 0; c < d * d; ++c) {
                    T_NEAR(var.a.F[c][i], ref1.a.F[c][i], 0.0, DF, "%s d %d: F[%d] of %d", vn, d, c,
                           (int)i);
                    T_NEAR(var.a.A[c][i], ref1.a.A[c][i], 0.0, Lip * (DF + 4 * U) * kmax + 1e-300,
                           "%s d %d law %d: A[%d] of %d", vn, d, law, c, (int)i);
                  }
                  T_NEAR(var.a.W[i], ref1.a.W[i], 0.0, Lip * (DF + 4 * U) + 1e-300,
                         "%s d %d: W of %d", vn, d, (int)i);
                  for (int c = 0; c < d * d; ++c)
                    T_ASSERT(var2.a.A[c][i] == var.a.A[c][i] && var2.a.F[c][i] == var.a.F[c][i],
                             "%s: pass 1 depends on the range split (particle %d)", vn, (int)i);
                }
                /* pass 2 from the same pass-1 state: the variant's own (its pass 1 leaves data
                 * for its pass 2 that the reference does not make: the packed rows, i's own
                 * terms), the reference's pass 2 on a copy of it. var2 continues from its split
                 * pass 1, bitwise the same state (checked above). */
                set_free(&ref1);
                set_init(&ref1, d, layout, bs, bj, omega, al, X, x, V);
                set_copy(&ref1, &var, d);
                pdk_kernel_corr_pass2_ref(&k, &ref1.a, 0, NP);
                variants[v].pass2(&k, &var.a, 0, NP);
                variants[v].pass2(&k, &var2.a, 0, 61);
                variants[v].pass2(&k, &var2.a, 61, NP);
                for (pdk_index i = 0; i < NP; ++i) {
                  const double ki = ref1.a.kst ? ref1.a.kst[i] : 0.0;
                  double Sf = 0.0, Sz = 0.0, s[3] = {0};
                  int n = 0;
                  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b, ++n) {
                    if (al && !al[b]) continue;
                    const pdk_index j = bj[b];
                    const double wv = omega[b] * V[j], kj = ref1.a.kst ? ref1.a.kst[j] : 0.0;
                    double xi1 = 0.0, y1 = 0.0, x2 = 0.0, y2 = 0.0;
                    for (int c = 0; c < d; ++c) {
                      const double e = X[c][j] - X[c][i], y = x[c][j] - x[c][i];
                      xi1 += fabs(e), y1 += fabs(y), x2 += e * e, y2 += y * y;
                      s[c] += wv * e;
                    }
                    const double Fm = maxabs(ref1.a.F, d * d, i), Fj = maxabs(ref1.a.F, d * d, j);
                    const double Am =
                        maxabs(ref1.a.A, d * d, i) + maxabs(ref1.a.A, d * d, j) + ki * Fm + kj * Fj;
                    double term = Am * xi1 + (ki + kj) * (y1 + xi1);
                    if (stab == PDK_STAB_HOURGLASS && y2 > 0.0)
                      term += horizon / sqrt(x2) *
                              ((ki + kj) * (y1 + xi1) + (ki * (Fm + 1) + kj * (Fj + 1)) * xi1) *
                              y1 * y1 / y2;
                    Sf += wv * term;
                    Sz += wv * (y1 + Fm * xi1) * (y1 + Fm * xi1);
                  }
                  const double Bm = maxabs(ref1.a.A, d * d, i) + ki * maxabs(ref1.a.F, d * d, i);
                  Sf += Bm * (fabs(s[0]) + fabs(s[1]) + fabs(s[2]));
                  const double tol = 2.0 * (n + 8) * U * Sf + 1e-300;
                  for (int r = 0; r < d; ++r) {
                    T_NEAR(var.a.f[r][i], ref1.a.f[r][i], 0.0, tol,
                           "%s d %d infl %d law %d stab %d float %d alive %d: f[%d] of %d", vn, d,
                           infl, law, stab, fl, with_alive, r, (int)i);
                    T_ASSERT(var2.a.f[r][i] == var.a.f[r][i],
                             "%s: pass 2 depends on the range split (particle %d)", vn, (int)i);
                  }
                  T_NEAR(var.a.W[i], ref1.a.W[i], 0.0,
                         2.0 * (n + 8) * U * (ki * Sz + fabs(ref1.a.W[i])) + 1e-300,
                         "%s d %d stab %d: W of %d", vn, d, stab, (int)i);
                  T_ASSERT(var2.a.W[i] == var.a.W[i], "%s: W depends on the split", vn);
                }
                set_free(&ref1);
                set_free(&var);
                set_free(&var2);
                ++tested;
              }
              set_free(&ref);
            }
    }
    for (int c = 0; c < d; ++c)
      free(X[c]), free(x[c]);
    free(V), free(bj), free(omega), free(alive);
  }
  if (isa & PDK_ISA_AVX2) T_ASSERT(tested > 0, "no variant tested");
  if (getenv("PDK_TEST_VERBOSE"))
    printf("t044: %d variant x case combinations agree with the reference\n", tested);
  pdk_ctx_destroy(&ctx);
  if (!tested) T_SKIP("t044: no AVX2 or AVX-512 on this CPU: no variant to test (the table was)");
  return 0;
}
