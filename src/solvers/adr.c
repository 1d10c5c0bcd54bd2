/* Adaptive dynamic relaxation (Kilic & Madenci, Theor. Appl. Fract. Mech. 53 (2010) 194-204).
 *
 * Solves r(u) = 0 on the free components (r = V (f + lambda b), see static.h) as the steady state
 * of M u'' + c M u' = r with a fictitious diagonal mass M and a unit pseudo time step:
 *   v^{1/2}     = M^-1 r^0 / 2
 *   v^{n+1/2}   = ((2 - c^n) v^{n-1/2} + 2 M^-1 r^n) / (2 + c^n)
 *   u^{n+1}     = u^n + v^{n+1/2}
 *   c^n         = 2 sqrt(u^T K1 u / u^T u),  K1_ii = -(r_i^n - r_i^{n-1}) / (M_ii v_i^{n-1/2})
 * u^T K1 u / u^T u is the Rayleigh quotient of the mass-normalised stiffness measured along the
 * last step, an estimate of the lowest frequency squared: c^n damps that mode critically. c is 0
 * when the quotient is not positive and at most 1.9 (the update needs c < 2).
 *
 * Fictitious mass (per component, [force/length] with the unit step). The central-difference
 * scheme is stable for lambda_max(M^-1 K) <= 4; Gershgorin bounds lambda_max(M^-1 K) by
 * max_i sum_j |K_ij| / M_ii, so M_ii = 1/4 sum_j |K_ij| is stable (Kilic & Madenci's choice,
 * derived there from the PMB bond stiffness c/|xi| V_j). pdk measures the row sums for any model:
 * with the coloring of the coupling graph, all particles of one color are displaced together by h
 * in one component; each row of K then sees exactly one displaced column, so
 * |V_j (f_j(x + h e) - f_j(x))| / h summed over the dim x colors passes is sum_j |K_ij| (forward
 * differences of trial forces at the initial state; step 1e-6 delta). The bound is taken at the
 * initial state: broken bonds only lower the row sums, and geometric stiffening at the strains
 * where pd models live is small; adr_safety scales M for cases that need more margin.
 * Row sums cost dim x colors + 1 passes: 65 in 2-D at RF 1.5, ~470 in 3-D. They save about 30%
 * of the iterations against the Lanczos mass below (bench/README.md: 871 vs 1245 at 16641 particles
 * in 2-D, 330 vs 396 at 29791 in 3-D), which pays only when the passes are few; AUTO takes them up
 * to 128 passes. Otherwise (3-D, large horizons) a uniform density is used: M_ii = 1.1
 * lambda_max(V^-1 K) V_i / 4 from 40 Lanczos steps (V-inner product, trial force differences, as
 * the explicit solver's stable-step estimate); Lanczos approaches lambda_max from below, hence the
 * factor 1.1.
 *
 * All vector updates run over fixed blocks (static schedule); the two sums of the Rayleigh
 * quotient are formed per block and added in block order: bitwise the same for any thread count.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "lanczos.h"
#include "static_impl.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/static.h"

#define PDK_ADR_ROWSUM_MAX_PASSES 128
#define PDK_ADR_LANCZOS_STEPS 40

typedef struct adr_state {
  double *mass[3];  /* [n] fictitious mass per component */
  double *v[3];     /* [n] pseudo velocity */
  double *rprev[3]; /* [n] residual of the previous iteration */
} adr_state;

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

/* Row sums of |K| by colored forward differences; mass = safety/4 * row sum. */
static int mass_row_sum(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  adr_state *a = s->adr;
  const int dim = s->dim;
  const pdk_index n = s->n;
  int err = PDK_SUCCESS;
  double *f0[3] = {NULL, NULL, NULL}, *saved = NULL;
  const double h = 1e-6 * s->horizon;
  const double *vol = pdk_particles_volume(s->p);
  for (int c = 0; c < dim; ++c) {
    f0[c] = malloc((size_t)n * sizeof(double));
    PDK_CHECK_GOTO(f0[c], ctx, PDK_ERR_MEMORY, "adr: out of memory for the mass estimate");
    memset(a->mass[c], 0, (size_t)n * sizeof(double));
  }
  saved = malloc((size_t)n * sizeof(double));
  PDK_CHECK_GOTO(saved, ctx, PDK_ERR_MEMORY, "adr: out of memory for the mass estimate");
  PDK_CALL_GOTO(pdk_model_force_trial(s->m, NULL));
  s->stats.force_passes++;
  for (int c = 0; c < dim; ++c)
    memcpy(f0[c], field(s->p, "f", c), (size_t)n * sizeof(double));
  for (int k = 0; k < s->num_colors; ++k)
    for (int d = 0; d < dim; ++d) {
      memcpy(saved, field(s->p, "x", d), (size_t)n * sizeof(double));
      pdk_static_perturb(s, k, d, h, NULL);
      PDK_CALL_GOTO(pdk_model_force_trial(s->m, NULL));
      s->stats.force_passes++;
      pdk_static_restore(s, k, d, saved);
      for (int c = 0; c < dim; ++c) {
        const double *f = field(s->p, "f", c);
        double *mc = a->mass[c];
        const double *f0c = f0[c];
        const int nt = ctx->num_threads;
#pragma omp parallel for default(none) shared(f, mc, f0c, vol, n, h) schedule(static)              \
    num_threads(nt)
        for (pdk_index i = 0; i < n; ++i)
          mc[i] += fabs(vol[i] * (f[i] - f0c[i])) / h;
      }
    }
  /* restore "f" to the forces at the current state */
  for (int c = 0; c < dim; ++c)
    memcpy(field(s->p, "f", c), f0[c], (size_t)n * sizeof(double));
cleanup:
  for (int c = 0; c < dim; ++c)
    free(f0[c]);
  free(saved);
  return err;
}

/* lambda_max(V^-1 K) by Lanczos in the V-inner product (lanczos.h); "x" and "f" are restored. */
static int mass_lanczos(pdk_static *s, double *lambda_max) {
  pdk_lanczos_opts lo = {0};
  lo.steps = PDK_ADR_LANCZOS_STEPS;
  lo.mass = 0;
  lo.horizon = s->horizon;
  lo.salt = 7;
  lo.scale_by_inverse = 0;
  lo.restore_f = 1;
  long passes = 0;
  const int err = pdk_lanczos_max_eig(s->m, &lo, lambda_max, &passes);
  s->stats.force_passes += passes;
  if (err) return err;
  PDK_CHECK(isfinite(*lambda_max) && *lambda_max > 0, s->ctx, PDK_ERR_NUMERIC,
            "adr: the stiffness bound for the fictitious mass is %g; the body has no stiffness "
            "(no bonds?)",
            *lambda_max);
  return PDK_SUCCESS;
}

int pdk_adr_setup(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  adr_state *a = calloc(1, sizeof *a);
  PDK_CHECK(a, ctx, PDK_ERR_MEMORY, "adr: out of memory");
  s->adr = a;
  for (int c = 0; c < dim; ++c) {
    a->mass[c] = calloc((size_t)n, sizeof(double));
    a->v[c] = calloc((size_t)n, sizeof(double));
    a->rprev[c] = calloc((size_t)n, sizeof(double));
    PDK_CHECK(a->mass[c] && a->v[c] && a->rprev[c], ctx, PDK_ERR_MEMORY,
              "adr: out of memory for %d particles", (int)n);
  }
  const double t0 = pdk_wtime();
  pdk_adr_mass kind = s->opts.adr_mass;
  if (kind != PDK_ADR_MASS_LANCZOS) PDK_CALL(pdk_static_color(s));
  if (kind == PDK_ADR_MASS_AUTO)
    kind = (long)dim * s->num_colors + 1 <= PDK_ADR_ROWSUM_MAX_PASSES ? PDK_ADR_MASS_ROW_SUM
                                                                      : PDK_ADR_MASS_LANCZOS;
  const double safety = s->opts.adr_safety;
  double mmin = HUGE_VAL, mmax = 0.0;
  if (kind == PDK_ADR_MASS_ROW_SUM) {
    PDK_CALL(mass_row_sum(s));
    s->stats.passes_per_tangent = (long)dim * s->num_colors + 1;
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) {
        a->mass[c][i] *= 0.25 * safety;
        if (a->mass[c][i] > mmax) mmax = a->mass[c][i];
      }
    /* A component without stiffness (no intact bonds) gets the largest mass: it drifts slowly
     * under its load instead of jumping. */
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) {
        if (!(a->mass[c][i] > 1e-12 * mmax)) a->mass[c][i] = mmax;
        if (a->mass[c][i] < mmin) mmin = a->mass[c][i];
      }
    PDK_CHECK(mmax > 0 && isfinite(mmax), ctx, PDK_ERR_NUMERIC,
              "adr: the stiffness row sums are %g; the body has no stiffness (no bonds?)", mmax);
  } else {
    double lmax = 0.0;
    PDK_CALL(mass_lanczos(s, &lmax));
    const double *vol = pdk_particles_volume(s->p);
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) {
        a->mass[c][i] = 0.25 * safety * 1.1 * lmax * vol[i];
        if (a->mass[c][i] > mmax) mmax = a->mass[c][i];
        if (a->mass[c][i] < mmin) mmin = a->mass[c][i];
      }
  }
  /* A particle held along a direction moves in its frame (static_impl.h), whose rows mix the
   * components': its mass, in every component, is sqrt(dim) times its largest (a bound of the
   * rotated rows' sums by the components' ones). */
  for (pdk_index i = 0; s->dir_of && i < n; ++i) {
    if (s->dir_of[i] < 0) continue;
    double mi = 0.0;
    for (int c = 0; c < dim; ++c)
      mi = fmax(mi, a->mass[c][i]);
    for (int c = 0; c < dim; ++c)
      a->mass[c][i] = sqrt((double)dim) * mi;
  }
  /* Round-off floor (static.h): eps |x|_max ||K||_F, with ||K||_F bounded by the row sums
   * (sum_j K_ij^2 <= (sum_j |K_ij|)^2): ROW_SUM gives them exactly (4 M / safety); for the
   * Lanczos mass ||K||_F <= sqrt(N) lambda_max(K) <= sqrt(N) 4 max M / safety. */
  {
    double xmax = 4.0 * s->horizon, sum2 = 0.0;
    long count = 0;
    for (int c = 0; c < dim; ++c) {
      const double *x = field(s->p, "x", c);
      for (pdk_index i = 0; i < n; ++i) {
        xmax = fmax(xmax, fabs(x[i]));
        sum2 += a->mass[c][i] * a->mass[c][i];
        count++;
      }
    }
    const double kfro = kind == PDK_ADR_MASS_ROW_SUM ? 4.0 / safety * sqrt(sum2)
                                                     : 4.0 / safety * mmax * sqrt((double)count);
    s->floor = DBL_EPSILON * xmax * kfro;
  }
  s->stats.adr_mass = kind;
  s->stats.mass_min = mmin;
  s->stats.mass_max = mmax;
  s->stats.time_mass += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

void pdk_adr_free(pdk_static *s) {
  adr_state *a = s->adr;
  if (!a) return;
  for (int c = 0; c < 3; ++c) {
    free(a->mass[c]);
    free(a->v[c]);
    free(a->rprev[c]);
  }
  free(a);
  s->adr = NULL;
}

/* Sums u^T K1 u and u^T u over free components (block order). */
static void rayleigh_sums(pdk_static *s, double *num, double *den) {
  adr_state *a = s->adr;
  const int dim = s->dim;
  const pdk_index n = s->n, num_blocks = s->num_blocks;
  const double *x[3] = {0}, *X[3] = {0}, *r[3] = {0}, *rp[3] = {0}, *v[3] = {0}, *M[3] = {0};
  const uint8_t *fixed[3] = {0};
  for (int c = 0; c < dim; ++c) {
    x[c] = field(s->p, "x", c);
    X[c] = pdk_particles_X(s->p, c);
    r[c] = s->r[c];
    rp[c] = a->rprev[c];
    v[c] = a->v[c];
    M[c] = a->mass[c];
    fixed[c] = s->fixed[c];
  }
  double *part = s->block_part;
  const int nt = s->ctx->num_threads;
#pragma omp parallel for default(none) shared(s, x, X, r, rp, v, M, fixed, part, n, num_blocks,     \
                                                  dim)                                             \
    schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = blk * PDK_STATIC_BLOCK;
    const pdk_index i1 = i0 + PDK_STATIC_BLOCK < n ? i0 + PDK_STATIC_BLOCK : n;
    double sn = 0.0, sd = 0.0;
    for (pdk_index i = i0; i < i1; ++i)
      for (int c = 0; c < dim; ++c) {
        if (fixed[c][i]) continue;
        double u = x[c][i] - X[c][i];
        const double(*R)[3] = pdk_static_frame(s, i);
        if (R) { /* held along a direction: u in the particle's frame, as r and v are */
          u = 0.0;
          for (int e = 0; e < dim; ++e)
            u += R[e][c] * (x[e][i] - X[e][i]);
        }
        if (v[c][i] != 0.0) sn += u * u * (-(r[c][i] - rp[c][i]) / (M[c][i] * v[c][i]));
        sd += u * u;
      }
    part[2 * blk] = sn;
    part[2 * blk + 1] = sd;
  }
  double sn = 0.0, sd = 0.0;
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    sn += part[2 * blk];
    sd += part[2 * blk + 1];
  }
  *num = sn;
  *den = sd;
}

/* v = (cv v + 2 r / M) / cd on free components (v = r / (2M) for the first step: cv = 0,
 * cd = 4), then x += v. */
static void update(pdk_static *s, double cv, double cd) {
  adr_state *a = s->adr;
  const pdk_index n = s->n;
  const int nt = s->ctx->num_threads;
  const int32_t *dir_of = s->dir_of;
  for (int c = 0; c < s->dim; ++c) {
    double *x = field(s->p, "x", c), *v = a->v[c];
    const double *r = s->r[c], *M = a->mass[c];
    const uint8_t *fixed = s->fixed[c];
#pragma omp parallel for default(none) shared(x, v, r, M, fixed, dir_of, n, cv, cd)               \
    schedule(static)                                                                               \
    num_threads(nt)
    for (pdk_index i = 0; i < n; ++i) {
      if (fixed[i]) {
        v[i] = 0.0;
        continue;
      }
      v[i] = (cv * v[i] + 2.0 * r[i] / M[i]) / cd;
      if (!dir_of || dir_of[i] < 0) x[i] += v[i];
    }
  }
  /* held along a direction: v is in the particle's frame (its normal 0); x moves by R v */
  for (pdk_index i = 0; dir_of && i < n; ++i) {
    const double(*R)[3] = pdk_static_frame(s, i);
    if (!R) continue;
    for (int c = 0; c < s->dim; ++c) {
      double dx = 0.0;
      for (int q = 1; q < s->dim; ++q)
        dx += R[c][q] * a->v[q][i];
      field(s->p, "x", c)[i] += dx;
    }
  }
}

int pdk_adr_relax(pdk_static *s, long *iterations) {
  pdk_ctx *ctx = s->ctx;
  adr_state *a = s->adr;
  static const char *hint = "the fictitious mass may be too small for this state (raise "
                            "adr_safety) or the load too large for the model";
  *iterations = 0;
  PDK_CALL(pdk_static_residual(s));
  if (!isfinite(s->rnorm) || !isfinite(s->fnorm)) return pdk_static_nonfinite(s, "adr", 0, hint);
  if (pdk_static_converged(s)) return PDK_SUCCESS;
  update(s, 0.0, 4.0); /* v^{1/2} = M^-1 r^0 / 2 */
  for (long it = 1; it <= s->opts.max_iterations; ++it) {
    for (int c = 0; c < s->dim; ++c) { /* r^{n-1} -> rprev (swap buffers) */
      double *t = a->rprev[c];
      a->rprev[c] = s->r[c];
      s->r[c] = t;
    }
    PDK_CALL(pdk_static_residual(s));
    *iterations = it;
    if (!isfinite(s->rnorm) || !isfinite(s->fnorm)) return pdk_static_nonfinite(s, "adr", it, hint);
    if (pdk_static_converged(s)) return PDK_SUCCESS;
    double num, den;
    rayleigh_sums(s, &num, &den);
    double cdamp = num > 0.0 && den > 0.0 ? 2.0 * sqrt(num / den) : 0.0;
    if (!(cdamp <= 1.9)) cdamp = 1.9;
    update(s, 2.0 - cdamp, 2.0 + cdamp);
  }
  return pdk_ctx_error_set(
      ctx, PDK_ERR_NUMERIC, "adr",
      "adaptive dynamic relaxation did not converge in %ld iterations at load level %d (load "
      "factor %g), round %d: residual %.3e against a tolerance of %.3e (rtol %g x load norm %.3e "
      "+ atol %g). Raise max_iterations, loosen rtol or add load levels; a residual that stalls "
      "means the body is not held (an unbalanced load accelerates it) or a piece came loose",
      s->opts.max_iterations, s->level, s->lambda, s->round, s->rnorm,
      s->opts.rtol * s->fnorm + s->opts.atol, s->opts.rtol, s->fnorm, s->opts.atol);
}
