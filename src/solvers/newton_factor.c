/* Newton (newton.c), factorization and solve: CHOLMOD for symmetric positive definite tangents,
 * UMFPACK otherwise, the singularity test (inverse iteration, the near-null vector and the
 * particles it blames) and the symmetry test (described in newton.c). */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "newton_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/static.h"

/* ---- factorization and solve ------------------------------------------------------------------
 */

int pdk_newton_solve_linear(pdk_static *s) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  int err = PDK_SUCCESS;
  const double t0 = pdk_wtime();
  cholmod_dense *X = NULL;
  if (ns->factor_kind == 1) {
    cholmod_dense B;
    memset(&B, 0, sizeof B);
    B.nrow = (size_t)ns->nf;
    B.ncol = 1;
    B.nzmax = (size_t)ns->nf;
    B.d = (size_t)ns->nf;
    B.x = ns->rhs;
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    PDK_CHOLMOD_CALL_GOTO(ctx, &ns->cc, X = cholmod_solve(CHOLMOD_A, ns->L, &B, &ns->cc));
    memcpy(ns->dx, X->x, (size_t)ns->nf * sizeof(double));
  } else {
    PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_solve(UMFPACK_A, ns->Ap, ns->Ai, ns->Ax, ns->dx, ns->rhs,
                                                ns->numeric, ns->control, ns->info));
  }
  s->stats.solves++;
cleanup:
  if (X) cholmod_free_dense(&X, &ns->cc);
  s->stats.time_solve += pdk_wtime() - t0;
  return err;
}

/* Smallest eigenvalue (modulus) of the factorized tangent by inverse iteration: z <- K^-1 z /
 * ||z||, 4 solves from a fixed pseudo-random start; 1/||K^-1 z|| (||z|| = 1) is an upper bound of
 * the smallest singular value, so a small estimate is never a false alarm. The near-null vector
 * is left in ns->rhs (unit 2-norm). Returns -1 if no estimate could be made. */
static double inverse_iteration(pdk_static *s) {
  newton_state *ns = s->newton;
  if (!ns->factor_kind || ns->nf == 0) return -1.0;
  double nrm = 0.0;
  for (long k = 0; k < ns->nf; ++k) {
    uint64_t h = (uint64_t)k * 0x9E3779B97F4A7C15ull + 11;
    h ^= h >> 31;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 29;
    ns->rhs[k] = (double)(h >> 11) / 9007199254740992.0 - 0.5;
    nrm += ns->rhs[k] * ns->rhs[k];
  }
  for (long k = 0; k < ns->nf; ++k)
    ns->rhs[k] /= sqrt(nrm);
  double estimate = -1.0;
  for (int it = 0; it < 4; ++it) {
    if (pdk_newton_solve_linear(s)) {
      pdk_ctx_error_clear(s->ctx);
      return -1.0;
    }
    nrm = 0.0;
    for (long k = 0; k < ns->nf; ++k)
      nrm += ns->dx[k] * ns->dx[k];
    nrm = sqrt(nrm);
    if (!(nrm > 0) || !isfinite(nrm)) return -1.0;
    estimate = 1.0 / nrm;
    for (long k = 0; k < ns->nf; ++k)
      ns->rhs[k] = ns->dx[k] / nrm;
  }
  ns->have_null = 1;
  return estimate;
}

/* Non-affine fraction of the near-null vector in ns->rhs:
 *   rho = sum_i sum_j |u_j - u_i - G_i xi_ij|^2 / sum_i sum_j |u_j - u_i|^2
 * over intact bonds, G_i the least-squares gradient of u over the family of i (unit weights).
 * A rigid motion of a loose piece has u_j - u_i = W xi: rho ~ 0. A zero-energy mode has a vanishing
 * discrete gradient while u oscillates: rho ~ 1. *where receives the particle with the largest
 * |u|. Returns -1 when there is no vector. */
static double null_vector_rho(pdk_static *s, pdk_index *where) {
  newton_state *ns = s->newton;
  const int dim = s->dim;
  const pdk_index n = s->n;
  *where = -1;
  if (!ns->have_null && inverse_iteration(s) < 0) return -1.0;
  double *u[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    u[c] = calloc((size_t)n, sizeof(double));
    if (!u[c]) {
      for (int d = 0; d < c; ++d)
        free(u[d]);
      return -1.0;
    }
  }
  double umax = -1.0;
  for (long k = 0; k < ns->nf; ++k) {
    const pdk_index i = ns->dof_particle[k];
    u[ns->dof_comp[k]][i] = ns->rhs[k];
    if (fabs(ns->rhs[k]) > umax) {
      umax = fabs(ns->rhs[k]);
      *where = i;
    }
  }
  for (pdk_index i = 0; s->dir_of && i < n; ++i) { /* held along a direction: back to x, y, z */
    const double(*R)[3] = pdk_static_frame(s, i);
    if (!R) continue;
    double g[3] = {0, 0, 0};
    for (int c = 0; c < dim; ++c)
      for (int q = 0; q < dim; ++q)
        g[c] += R[c][q] * u[q][i];
    for (int c = 0; c < dim; ++c)
      u[c][i] = g[c];
  }
  const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
  const pdk_index *bj = pdk_families_bond_j(s->fam);
  const uint8_t *alive = pdk_model_bond_alive(s->m);
  const double *X[3] = {pdk_particles_X(s->p, 0), pdk_particles_X(s->p, 1),
                        dim == 3 ? pdk_particles_X(s->p, 2) : NULL};
  double num = 0.0, den = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    double A[3][3] = {{0}}, B[3][3] = {{0}}; /* sum xi xi^T, sum du xi^T */
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      if (alive && !alive[b]) continue;
      const pdk_index j = bj[b];
      for (int a = 0; a < dim; ++a)
        for (int c = 0; c < dim; ++c) {
          A[a][c] += (X[a][j] - X[a][i]) * (X[c][j] - X[c][i]);
          B[a][c] += (u[a][j] - u[a][i]) * (X[c][j] - X[c][i]);
        }
    }
    /* Ainv by cofactors (2x2 or 3x3); a family that does not span is skipped */
    double Ai[3][3] = {{0}}, det;
    if (dim == 2) {
      det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
      if (!(fabs(det) > 1e-12 * (A[0][0] * A[1][1] + 1e-300))) continue;
      Ai[0][0] = A[1][1] / det;
      Ai[1][1] = A[0][0] / det;
      Ai[0][1] = -A[0][1] / det;
      Ai[1][0] = -A[1][0] / det;
    } else {
      Ai[0][0] = A[1][1] * A[2][2] - A[1][2] * A[2][1];
      Ai[0][1] = A[0][2] * A[2][1] - A[0][1] * A[2][2];
      Ai[0][2] = A[0][1] * A[1][2] - A[0][2] * A[1][1];
      Ai[1][0] = A[1][2] * A[2][0] - A[1][0] * A[2][2];
      Ai[1][1] = A[0][0] * A[2][2] - A[0][2] * A[2][0];
      Ai[1][2] = A[0][2] * A[1][0] - A[0][0] * A[1][2];
      Ai[2][0] = A[1][0] * A[2][1] - A[1][1] * A[2][0];
      Ai[2][1] = A[0][1] * A[2][0] - A[0][0] * A[2][1];
      Ai[2][2] = A[0][0] * A[1][1] - A[0][1] * A[1][0];
      det = A[0][0] * Ai[0][0] + A[0][1] * Ai[1][0] + A[0][2] * Ai[2][0];
      if (!(fabs(det) > 1e-12 * (A[0][0] * A[1][1] * A[2][2] + 1e-300))) continue;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          Ai[a][c] /= det;
    }
    double G[3][3] = {{0}};
    for (int a = 0; a < dim; ++a)
      for (int c = 0; c < dim; ++c)
        for (int k = 0; k < dim; ++k)
          G[a][c] += B[a][k] * Ai[k][c];
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      if (alive && !alive[b]) continue;
      const pdk_index j = bj[b];
      for (int a = 0; a < dim; ++a) {
        const double du = u[a][j] - u[a][i];
        double fit = 0.0;
        for (int c = 0; c < dim; ++c)
          fit += G[a][c] * (X[c][j] - X[c][i]);
        num += (du - fit) * (du - fit);
        den += du * du;
      }
    }
  }
  for (int c = 0; c < dim; ++c)
    free(u[c]);
  return den > 0 ? num / den : -1.0;
}

/* Replaces the context's message by "<prefix; >the tangent is singular ... Likely cause: ...",
 * naming the unknown `dof` (-1: unknown place) and the likely cause: a particle without intact
 * bonds or with a family that does not span, else what the near-null vector looks like (zero-energy
 * pattern or rigid motion of a loose part). */
static int blame_singular(pdk_static *s, long dof, double ratio, int keep_prefix) {
  newton_state *ns = s->newton;
  char prefix[PDK_ERRMSG_MAX / 2] = "";
  if (keep_prefix) snprintf(prefix, sizeof prefix, "%s; ", pdk_ctx_error_message(s->ctx));
  char where[256] = "";
  char cause[768];
  const pdk_model_opts *mo = &s->m->opts;
  pdk_index i = -1;
  long long id = -1;
  if (dof >= 0 && dof < ns->nf) {
    i = ns->dof_particle[dof];
    id = (long long)pdk_particles_id(s->p)[i];
    snprintf(where, sizeof where, " at particle %d (id %lld), component %c", (int)i, id,
             pdk_newton_comp_name[ns->dof_comp[dof]]);
  }
  int intact = -1, flagged = 0;
  if (i >= 0) {
    const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
    const uint8_t *alive = pdk_model_bond_alive(s->m);
    intact = 0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b)
      intact += alive ? alive[b] != 0 : 1;
    const uint8_t *flag = pdk_particles_field_data(s->p, "flag", 0);
    flagged = flag && pdk_model_opts_has(mo, PDK_KIND_SPAN_FLAG) ? flag[i] != 0 : 0;
  }
  pdk_index peak = -1;
  const double rho = intact == 0 || flagged ? -1.0 : null_vector_rho(s, &peak);
  s->stats.null_nonaffine = rho;
  const long long peak_id = peak >= 0 ? (long long)pdk_particles_id(s->p)[peak] : -1;
  const int corr_unstab = pdk_model_opts_unstabilized(mo);
  if (intact == 0)
    snprintf(cause, sizeof cause,
             "particle id %lld has no intact bonds (it came loose); Newton cannot place a free "
             "particle: solve with ADR, or remove detached particles",
             id);
  else if (flagged)
    snprintf(cause, sizeof cause,
             "the family of particle id %lld no longer spans the space, so its deformation "
             "gradient (and stiffness) is undefined; solve with ADR or use semi-TL connectivity",
             id);
  else if (rho > 0.5)
    snprintf(cause, sizeof cause,
             "zero-energy modes: the near-null displacement (largest at particle id %lld) "
             "oscillates between neighbours while its discrete deformation gradient vanishes "
             "(non-affine fraction %.2f; V-Z in docs/validation/targets.md). %s",
             peak_id, rho,
             corr_unstab ? "Correspondence without stabilization has them; set the model's "
                           "stabilization to silling or hourglass, or solve with ADR"
                         : "Raise the stabilization coefficient, or solve with ADR");
  else if (rho >= 0.0)
    snprintf(cause, sizeof cause,
             "a part of the body is not held: the near-null displacement is a rigid motion "
             "(non-affine fraction %.2f) largest at particle id %lld, i.e. that part is not "
             "connected to the prescribed particles through intact bonds or the displacement "
             "conditions leave it free; constrain it, or solve with ADR",
             rho, peak_id);
  else
    snprintf(cause, sizeof cause, "%s; constrain the part that is not held, or solve with ADR",
             corr_unstab ? "zero-energy modes of correspondence without stabilization (V-Z), or "
                           "a part of the body that is not held"
                         : "a part of the body that is not held (not connected to the prescribed "
                           "particles through intact bonds)");
  return pdk_ctx_error_set(s->ctx, PDK_ERR_NUMERIC, "newton",
                           "%sthe tangent stiffness is singular at load level %d (load factor %g), "
                           "round %d: smallest pivot or eigenvalue %.2e of the largest diagonal "
                           "entry (singular_rtol %g)%s. "
                           "Likely cause: %s",
                           prefix, s->level, s->lambda, s->round, ratio, s->opts.singular_rtol,
                           where, cause);
}

static double asymmetry(const newton_state *ns) {
  double num = 0.0, den = 0.0;
  for (int64_t k = 0; k < ns->nnz; ++k) {
    const double a = ns->Ax[k], d = a - ns->Ax[ns->tpos[k]];
    num += d * d;
    den += a * a;
  }
  ((newton_state *)ns)->kfro = sqrt(den);
  return den > 0 ? sqrt(num / den) : 0.0;
}

static void symmetrize(newton_state *ns) {
  for (int64_t k = 0; k < ns->nnz; ++k) {
    const int t = ns->tpos[k];
    if (t > k) {
      const double avg = 0.5 * (ns->Ax[k] + ns->Ax[t]);
      ns->Ax[k] = avg;
      ns->Ax[t] = avg;
    }
  }
}

/* Smallest pivot of a CHOLMOD factor (LL': L_jj^2; LDL': D_jj), its column, and whether any pivot
 * is <= 0. */
static void cholmod_pivots(const cholmod_factor *L, double *min_pivot, long *min_col, int *nonpos) {
  const double *x = L->x;
  double mn = HUGE_VAL;
  long at = -1;
  int bad = 0;
  if (L->is_super) {
    const int *super = L->super, *pi = L->pi, *px = L->px;
    for (size_t sn = 0; sn < L->nsuper; ++sn) {
      const int k1 = super[sn], k2 = super[sn + 1];
      const int nsrow = pi[sn + 1] - pi[sn];
      const int psx = px[sn];
      for (int k = k1; k < k2; ++k) {
        const double d = x[psx + (k - k1) + (size_t)(k - k1) * (size_t)nsrow];
        const double piv = d * d;
        if (!(d > 0)) bad = 1;
        if (piv < mn) {
          mn = piv;
          at = k;
        }
      }
    }
  } else {
    const int *p = L->p;
    for (size_t k = 0; k < L->n; ++k) {
      const double d = x[p[k]];
      const double piv = L->is_ll ? d * d : d;
      if (!(d > 0)) bad = 1;
      if (piv < mn) {
        mn = piv;
        at = (long)k;
      }
    }
  }
  *min_pivot = mn;
  *min_col = at;
  *nonpos = bad;
}

/* CHOLMOD on the (symmetrized) tangent: returns 0 and sets *not_posdef when it is not positive
 * definite (the caller falls back), or an error. */
static int factor_cholmod(pdk_static *s, int *not_posdef) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  int err = PDK_SUCCESS;
  cholmod_common *cc = &ns->cc;
  cholmod_sparse A;
  memset(&A, 0, sizeof A);
  A.nrow = A.ncol = (size_t)ns->nf;
  A.nzmax = (size_t)ns->nnz;
  A.p = ns->Ap;
  A.i = ns->Ai;
  A.x = ns->Ax;
  A.stype = 1; /* symmetric, upper triangle used (the lower is stored too and ignored) */
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  *not_posdef = 0;
  if (!ns->L) {
    const double t0 = pdk_wtime();
    PDK_CHOLMOD_CALL_GOTO(ctx, cc, ns->L = cholmod_analyze(&A, cc));
    s->stats.analyses++;
    s->stats.time_analysis += pdk_wtime() - t0;
  }
  {
    const double t0 = pdk_wtime();
    PDK_CHOLMOD_CALL_GOTO(ctx, cc, cholmod_factorize(&A, ns->L, cc));
    s->stats.factorizations++;
    s->stats.cholmod_factorizations++;
    s->stats.time_factorization += pdk_wtime() - t0;
  }
  if (cc->status == CHOLMOD_NOT_POSDEF || ns->L->minor < ns->L->n) {
    *not_posdef = 1;
    goto cleanup;
  }
  double min_pivot;
  long min_col;
  int nonpos;
  cholmod_pivots(ns->L, &min_pivot, &min_col, &nonpos);
  if (nonpos) {
    *not_posdef = 1;
    goto cleanup;
  }
  s->stats.min_pivot_ratio = min_pivot / ns->k_ref;
  {
    const cholmod_factor *L = ns->L;
    s->stats.factor_nnz = (int64_t)cc->lnz;
    s->stats.factor_bytes =
        L->is_super
            ? L->xsize * sizeof(double) + L->ssize * sizeof(int) + (L->nsuper + 1) * 3 * sizeof(int)
            : L->nzmax * (sizeof(double) + sizeof(int)) + (L->n + 1) * 4 * sizeof(int);
    s->stats.factor_bytes += L->n * 2 * sizeof(int); /* Perm, ColCount */
  }
  ns->factor_kind = 1;
  if (min_pivot < s->opts.singular_rtol * ns->k_ref) {
    const int *perm = ns->L->Perm;
    err =
        blame_singular(s, min_col >= 0 && perm ? perm[min_col] : min_col, min_pivot / ns->k_ref, 0);
    goto cleanup;
  }
  ns->factor_kind = 1;
cleanup:
  return err;
}

/* UMFPACK LU of the tangent; the symbolic analysis is kept. */
static int factor_umfpack(pdk_static *s) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  int err = PDK_SUCCESS;
  int st = UMFPACK_OK;
  int *Q = NULL;
  double *D = NULL;
  const int nf = (int)ns->nf;
  if (!ns->symbolic) {
    const double t0 = pdk_wtime();
    PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_symbolic(nf, nf, ns->Ap, ns->Ai, ns->Ax, &ns->symbolic,
                                                   ns->control, ns->info));
    s->stats.analyses++;
    s->stats.time_analysis += pdk_wtime() - t0;
  }
  if (ns->numeric) umfpack_di_free_numeric(&ns->numeric);
  Q = malloc((size_t)nf * sizeof *Q);
  D = malloc((size_t)nf * sizeof *D);
  PDK_CHECK_GOTO(Q && D, ctx, PDK_ERR_MEMORY, "newton: out of memory for the LU pivots");
  {
    const double t0 = pdk_wtime();
    PDK_UMFPACK_CALL_GOTO(ctx, st = umfpack_di_numeric(ns->Ap, ns->Ai, ns->Ax, ns->symbolic,
                                                       &ns->numeric, ns->control, ns->info));
    s->stats.factorizations++;
    s->stats.umfpack_factorizations++;
    s->stats.time_factorization += pdk_wtime() - t0;
  }
  s->stats.factor_nnz = (int64_t)(ns->info[UMFPACK_LNZ] + ns->info[UMFPACK_UNZ]);
  s->stats.factor_bytes = (size_t)(ns->info[UMFPACK_NUMERIC_SIZE] * ns->info[UMFPACK_SIZE_OF_UNIT]);
  PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_get_numeric(NULL, NULL, NULL, NULL, NULL, NULL, NULL, Q, D,
                                                    NULL, NULL, ns->numeric));
  {
    double mn = HUGE_VAL;
    long at = -1;
    for (int k = 0; k < nf; ++k)
      if (fabs(D[k]) < mn) {
        mn = fabs(D[k]);
        at = Q[k];
      }
    s->stats.min_pivot_ratio = mn / ns->k_ref;
    ns->factor_kind = 2;
    if (mn < s->opts.singular_rtol * ns->k_ref) {
      err = blame_singular(s, at, mn / ns->k_ref, 0);
      goto cleanup;
    }
  }
  ns->factor_kind = 2;
cleanup:
  if (err && st == UMFPACK_WARNING_singular_matrix && ns->numeric) {
    ns->factor_kind = 0; /* a zero pivot: no near-null vector by inverse iteration */
    /* name the zero pivot: the wrapper's message stays as the prefix */
    long at = -1;
    if (Q && D &&
        umfpack_di_get_numeric(NULL, NULL, NULL, NULL, NULL, NULL, NULL, Q, D, NULL, NULL,
                               ns->numeric) == UMFPACK_OK)
      for (int k = 0; k < nf; ++k)
        if (D[k] == 0.0) {
          at = Q[k];
          break;
        }
    err = blame_singular(s, at, 0.0, 1);
  }
  free(Q);
  free(D);
  return err;
}

/* Factorizes the assembled tangent (choosing the solver) and solves K dx = r. */
int pdk_newton_factor_and_solve(pdk_static *s) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  const pdk_linear_solver want = s->opts.linear_solver;
  ns->factor_kind = 0;
  ns->have_null = 0;
  /* A free component without stiffness: name it before a factorization blames some other one. */
  for (long col = 0; col < ns->nf; ++col) {
    const double dkk = ns->Ax[ns->diag_pos[col]];
    if (!(fabs(dkk) > s->opts.singular_rtol * ns->k_ref))
      return blame_singular(s, col, ns->k_ref > 0 ? fabs(dkk) / ns->k_ref : 0.0, 0);
  }
  const double asym = asymmetry(ns);
  s->stats.asymmetry = asym;
  /* Round-off floor of the residual: a one-ulp change of the positions changes r by about
   * eps |x|_max ||K||_F (random rounding of every coordinate); no iteration gets below it. */
  {
    double xmax = 4.0 * s->horizon;
    for (int c = 0; c < s->dim; ++c) {
      const double *x = pdk_newton_field(s->p, "x", c);
      for (pdk_index i = 0; i < s->n; ++i)
        xmax = fmax(xmax, fabs(x[i]));
    }
    s->floor = DBL_EPSILON * xmax * ns->kfro;
  }
  const int sym = ns->hyperelastic && asym <= s->opts.sym_rtol;
  PDK_CHECK(want != PDK_LINEAR_CHOLMOD || sym, ctx, PDK_ERR_ARG,
            "newton: CHOLMOD was requested but the tangent is not symmetric (%s; asymmetry %.2e, "
            "sym_rtol %g); use the auto or umfpack linear solver",
            ns->hyperelastic ? "difference error above the tolerance"
                             : "the model is not hyperelastic",
            asym, s->opts.sym_rtol);
  if (sym) symmetrize(ns);
  s->stats.symmetric = 0;
  int done = 0;
  if (sym && want != PDK_LINEAR_UMFPACK && !ns->use_lu) {
    int not_posdef = 0;
    PDK_CALL(factor_cholmod(s, &not_posdef));
    if (not_posdef) {
      if (want == PDK_LINEAR_CHOLMOD)
        return pdk_ctx_error_set(ctx, PDK_ERR_NUMERIC, "newton",
                                 "CHOLMOD: the tangent is not positive definite at load level %d "
                                 "(load factor %g), round %d (the body softens, buckles or is not "
                                 "held); use the auto or umfpack linear solver",
                                 s->level, s->lambda, s->round);
      ns->use_lu = 1; /* indefinite: LU from now on */
    } else {
      s->stats.symmetric = 1;
      done = 1;
    }
  }
  if (!done) PDK_CALL(factor_umfpack(s));
  /* Nearly singular tangents have tiny eigenvalues but not always tiny pivots: estimate the
   * smallest eigenvalue once per level and round (4 solves). */
  if (s->opts.singular_rtol > 0 &&
      (ns->checked_level != s->level || ns->checked_round != s->round)) {
    ns->checked_level = s->level;
    ns->checked_round = s->round;
    const double lmin = inverse_iteration(s);
    if (lmin >= 0) {
      s->stats.min_eig_ratio = lmin / ns->k_ref;
      if (lmin < s->opts.singular_rtol * ns->k_ref) {
        long dof = -1;
        double peak = -1.0;
        for (long k = 0; k < ns->nf; ++k)
          if (fabs(ns->rhs[k]) > peak) {
            peak = fabs(ns->rhs[k]);
            dof = k;
          }
        return blame_singular(s, dof, lmin / ns->k_ref, 0);
      }
    }
  }
  for (long k = 0; k < ns->nf; ++k) /* rhs = r on the free components */
    ns->rhs[k] = s->r[ns->dof_comp[k]][ns->dof_particle[k]];
  return pdk_newton_solve_linear(s);
}
