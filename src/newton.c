/* Implicit static Newton-Raphson with an analytic or difference tangent and SuiteSparse (CHOLMOD /
 * UMFPACK).
 *
 * Unknowns: the free components (not prescribed), numbered particle-major: dof_of[c][i] is the
 * unknown of component c of particle i or -1. Residual r = V (f + lambda b) (static.c); tangent
 * K = -dr/dx restricted to the free components (Dirichlet by elimination: the prescribed rows and
 * columns are dropped, which keeps a symmetric K symmetric). One iteration solves K dx = r and
 * moves x by a dx, a from a backtracking line search on ||r||.
 *
 * Tangent storage, compressed sparse column over the free unknowns (int indices, CHOLMOD's and
 * UMFPACK's "di" interfaces):
 *   Ap   [nf+1]  column starts;  Ai [nnz] row indices, ascending within a column;  Ax [nnz] values
 *   tpos [nnz]   position of the transposed entry (the pattern is structurally symmetric)
 *   diag_pos [nf] position of the diagonal entry
 * Pattern: column (i, c) has a row (j, e) for every free (j, e) with j within `hops` family hops
 * of i (bonds counted whether intact or broken, so breaking never changes the pattern and the
 * symbolic analyses are done once). hops = 1 for PMB (f_i depends on the family of i), 2 for LPS
 * and correspondence (f_i depends on theta_j / A_j of the neighbours, which depend on theirs).
 *
 * Assembly by differences of trial forces, colored (static.c: particles of one color are more
 * than 2 hops delta apart, so no row couples to two of them): for each color k and component d,
 * every particle of color k is moved by +h (and -h for central differences) in component d; the
 * change of V_j f_j at the rows of the column (i, d) belongs to particle i alone:
 *   K[(j,e),(i,d)] = -V_j (f_je(x + h e_id) - f_je(x - h e_id)) / (h+ + h-),
 * with h+ = (x + h) - x and h- = x - (x - h) the perturbations actually applied (exact in floating
 * point). Error: central O(h^2) truncation + O(eps / h) round-off; with h = 1e-5 delta both are
 * near 1e-10 of the entries. The diagonal entries of prescribed components are measured too (they
 * cost nothing extra): their largest magnitude is the stiffness scale k_ref for the singularity
 * test.
 *
 * Analytic assembly (opts.tangent auto or analytic, models with pdk_model_ops.tangent_column: PMB,
 * LPS, the 2-D dilatation laws): the model's exact derivative, one column particle at a time
 * (assemble_analytic), into the same pattern; it replaces the 2 dim colors force passes.
 *
 * Factorization. A hyperelastic model's tangent is symmetric; the difference tangent is so up to
 * its error. If ||K - K^T||_F / ||K||_F <= sym_rtol, K <- (K + K^T)/2 (documented in static.h) and
 * CHOLMOD factorizes it (upper triangle, supernodal or simplicial as CHOLMOD chooses; the analysis
 * with AMD/METIS ordering is kept). If CHOLMOD finds it not positive definite (auto mode), UMFPACK
 * takes over for the rest of the solve. Other tangents go to UMFPACK (symbolic analysis kept; no
 * row scaling, so its pivots compare with k_ref). Pivots below singular_rtol k_ref mean singular.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "ext.h"
#include "static_impl.h"

typedef struct newton_state {
  long nf;                 /* free unknowns */
  int32_t *dof_of[3];      /* [n] */
  pdk_index *dof_particle; /* [nf] */
  uint8_t *dof_comp;       /* [nf] */
  int *Ap, *Ai, *tpos, *diag_pos;
  double *Ax;
  int64_t nnz;
  double *diag_full[3];           /* [n] diagonal of the full tangent, prescribed included */
  double *fa[3];                  /* [n] forces of the + pass (central) or the base (forward) */
  double *h_plus, *h_minus;       /* [n] */
  double *saved;                  /* [n] */
  double *x0[3];                  /* [n] line-search base */
  double *rhs, *dx;               /* [nf] */
  pdk_index *ident_start, *ident; /* [n+1], [n]: one particle per group (reference tangent) */
  double k_ref;
  double kfro; /* ||K||_F of the last tangent */
  int hyperelastic;
  int analytic; /* 1: the model's analytic tangent (opts.tangent), 0: differences */
  pdk_index *col_scratch; /* [num_threads][3 n] analytic assembly: stamp, list, loc */
  double *col_block;      /* [num_threads][n dim^2] analytic assembly: one column's blocks */
  pdk_index block_capacity; /* particles per thread in col_block */
  int use_lu; /* 1 after CHOLMOD found the tangent not positive definite */
  cholmod_common cc;
  int cc_started;
  cholmod_factor *L;
  void *symbolic, *numeric;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  int factor_kind; /* 1 CHOLMOD, 2 UMFPACK: which factor the solve uses */
  int have_null;   /* 1: ns->rhs holds the near-null vector of the current factor */
  int checked_level,
      checked_round; /* last (level, round) whose tangent was checked by inverse iteration */
} newton_state;

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

static const char comp_name[3] = {'x', 'y', 'z'};


/* ---- rigid motions: are they all stopped by the displacement conditions? -------------------- */

/* Eigen-decomposition of a symmetric m x m matrix (m <= 6) by cyclic Jacobi rotations. */
static void jacobi_eig(int m, double A[6][6], double w[6], double V[6][6]) {
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      V[i][j] = i == j;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < m; ++p)
      for (int q = p + 1; q < m; ++q)
        off += A[p][q] * A[p][q];
    if (off == 0.0) break;
    for (int p = 0; p < m; ++p)
      for (int q = p + 1; q < m; ++q) {
        if (A[p][q] == 0.0) continue;
        const double theta = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
        const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < m; ++k) { /* A <- J^T A J */
          const double akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq;
          A[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < m; ++k) {
          const double apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk;
          A[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < m; ++k) {
          const double vkp = V[k][p], vkq = V[k][q];
          V[k][p] = c * vkp - s * vkq;
          V[k][q] = s * vkp + c * vkq;
        }
      }
  }
  for (int i = 0; i < m; ++i)
    w[i] = A[i][i];
}

/* Gram matrix of the rigid modes restricted to the prescribed components; a (numerically) zero
 * eigenvalue is a rigid motion no condition resists. */
static int check_held(pdk_static *s) {
  const int dim = s->dim;
  const pdk_index n = s->n;
  const int m = dim == 3 ? 6 : 3;
  static const char *names3[6] = {"translation in x", "translation in y", "translation in z",
                                  "rotation about x", "rotation about y", "rotation about z"};
  static const char *names2[3] = {"translation in x", "translation in y", "rotation about z"};
  const char **names = dim == 3 ? names3 : names2;
  const double *X[3] = {pdk_particles_X(s->p, 0), pdk_particles_X(s->p, 1),
                        dim == 3 ? pdk_particles_X(s->p, 2) : NULL};
  double centre[3] = {0, 0, 0}, lref = 0.0;
  for (int a = 0; a < dim; ++a) {
    for (pdk_index i = 0; i < n; ++i)
      centre[a] += X[a][i];
    centre[a] /= (double)n;
  }
  for (pdk_index i = 0; i < n; ++i) {
    double r2 = 0.0;
    for (int a = 0; a < dim; ++a)
      r2 += (X[a][i] - centre[a]) * (X[a][i] - centre[a]);
    lref = fmax(lref, sqrt(r2));
  }
  if (!(lref > 0)) lref = 1.0;
  double G[6][6] = {{0}}, w[6], V[6][6];
  for (pdk_index i = 0; i < n; ++i) {
    double r[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a)
      r[a] = (X[a][i] - centre[a]) / lref;
    for (int c = 0; c < dim; ++c) {
      if (!s->fixed[c][i]) continue;
      double phi[6] = {0};
      phi[c] = 1.0; /* translation c */
      if (dim == 2)
        phi[2] = c == 0 ? -r[1] : r[0];
      else {
        /* rotation about axis a: (e_a x r)_c */
        phi[3] = c == 0 ? 0.0 : (c == 1 ? -r[2] : r[1]);
        phi[4] = c == 0 ? r[2] : (c == 1 ? 0.0 : -r[0]);
        phi[5] = c == 0 ? -r[1] : (c == 1 ? r[0] : 0.0);
      }
      for (int k = 0; k < m; ++k)
        for (int l = 0; l < m; ++l)
          G[k][l] += phi[k] * phi[l];
    }
  }
  double trace = 0.0;
  for (int k = 0; k < m; ++k)
    trace += G[k][k];
  jacobi_eig(m, G, w, V);
  char free_modes[512] = "";
  int num_free = 0;
  for (int k = 0; k < m; ++k) {
    if (w[k] > 1e-10 * trace) continue;
    ++num_free;
    for (int l = 0; l < m; ++l) {
      if (fabs(V[l][k]) < 0.3) continue;
      if (strstr(free_modes, names[l])) continue;
      size_t len = strlen(free_modes);
      snprintf(free_modes + len, sizeof free_modes - len, "%s%s", len ? ", " : "", names[l]);
    }
  }
  if (!num_free) return PDK_SUCCESS;
  return pdk_ctx_error_set(
      s->ctx, PDK_ERR_ARG, "newton",
      "the body is not held: constrain at least one component in each direction (%s) and, "
      "against rotation, %s. The displacement conditions leave %d rigid motion%s free (%s), which "
      "the tangent cannot resist (it is singular); a self-equilibrated problem can be solved with "
      "ADR",
      dim == 3 ? "x, y and z" : "x and y",
      dim == 3 ? "components at three points not on one line (e.g. fix a whole face)"
               : "a component at a second point (e.g. u_y at two particles with different x)",
      num_free, num_free > 1 ? "s" : "", free_modes);
}

/* ---- pattern -------------------------------------------------------------------------------- */

static int cmp_index(const void *a, const void *b) {
  const pdk_index x = *(const pdk_index *)a, y = *(const pdk_index *)b;
  return (x > y) - (x < y);
}

/* Particles within `hops` family hops of i (i included), sorted. stamp[j] == i marks members. */
static pdk_index coupled(const pdk_bond_index *restrict bs, const pdk_index *restrict bj, int hops,
                         pdk_index i, pdk_index *restrict stamp, pdk_index *restrict list) {
  pdk_index cnt = 0;
  list[cnt++] = i;
  stamp[i] = i;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    if (stamp[j] != i) {
      stamp[j] = i;
      list[cnt++] = j;
    }
  }
  if (hops > 1) {
    const pdk_index first = cnt;
    for (pdk_index q = 1; q < first; ++q) {
      const pdk_index j = list[q];
      for (pdk_bond_index b = bs[j]; b < bs[j + 1]; ++b) {
        const pdk_index k = bj[b];
        if (stamp[k] != i) {
          stamp[k] = i;
          list[cnt++] = k;
        }
      }
    }
  }
  qsort(list, (size_t)cnt, sizeof *list, cmp_index);
  return cnt;
}

static int build_pattern(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  newton_state *ns = s->newton;
  const int dim = s->dim, hops = s->hops;
  const pdk_index n = s->n;
  const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
  const pdk_index *bj = pdk_families_bond_j(s->fam);
  int32_t *const *dof_of = ns->dof_of;
  const int nt = ctx->num_threads;
  int err = PDK_SUCCESS;
  int64_t *rows_of = NULL;   /* [n] free rows coupled to particle i */
  pdk_index *scratch = NULL; /* [nt][2n]: stamp and list per thread */
  rows_of = malloc((size_t)n * sizeof *rows_of);
  scratch = malloc((size_t)nt * 2 * (size_t)n * sizeof *scratch);
  PDK_CHECK_GOTO(rows_of && scratch, ctx, PDK_ERR_MEMORY,
                 "newton: out of memory building the tangent pattern (%d particles)", (int)n);
  for (size_t k = 0; k < (size_t)nt * 2 * (size_t)n; ++k)
    scratch[k] = -1;
#pragma omp parallel default(none) shared(bs, bj, hops, n, dim, dof_of, rows_of, scratch)          \
    num_threads(nt)
  {
    pdk_index *stamp = scratch + (size_t)2 * n * (size_t)omp_get_thread_num();
    pdk_index *list = stamp + n;
#pragma omp for schedule(static)
    for (pdk_index i = 0; i < n; ++i) {
      const pdk_index cnt = coupled(bs, bj, hops, i, stamp, list);
      int64_t rows = 0;
      for (pdk_index q = 0; q < cnt; ++q)
        for (int e = 0; e < dim; ++e)
          rows += dof_of[e][list[q]] >= 0;
      rows_of[i] = rows;
    }
  }
  int64_t nnz = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c)
      if (dof_of[c][i] >= 0) nnz += rows_of[i];
  PDK_CHECK_GOTO(nnz <= INT_MAX, ctx, PDK_ERR_MEMORY,
                 "newton: the tangent would have %lld nonzeros, more than the 32-bit indices of "
                 "CHOLMOD/UMFPACK's int interface allow (%d); use ADR or a smaller horizon",
                 (long long)nnz, INT_MAX);
  ns->nnz = nnz;
  ns->Ap = malloc(((size_t)ns->nf + 1) * sizeof *ns->Ap);
  ns->Ai = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *ns->Ai);
  ns->Ax = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *ns->Ax);
  ns->tpos = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *ns->tpos);
  ns->diag_pos = malloc((size_t)(ns->nf > 0 ? ns->nf : 1) * sizeof *ns->diag_pos);
  PDK_CHECK_GOTO(ns->Ap && ns->Ai && ns->Ax && ns->tpos && ns->diag_pos, ctx, PDK_ERR_MEMORY,
                 "newton: out of memory for a tangent of %lld nonzeros (%.1f MiB)", (long long)nnz,
                 (double)nnz * 20.0 / 1048576.0);
  {
    int *Ap = ns->Ap;
    int64_t pos = 0;
    Ap[0] = 0;
    for (pdk_index i = 0; i < n; ++i)
      for (int c = 0; c < dim; ++c)
        if (dof_of[c][i] >= 0) {
          pos += rows_of[i];
          Ap[dof_of[c][i] + 1] = (int)pos;
        }
  }
  for (size_t k = 0; k < (size_t)nt * 2 * (size_t)n; ++k)
    scratch[k] = -1;
  int *Ap = ns->Ap, *Ai = ns->Ai, *diag_pos = ns->diag_pos;
#pragma omp parallel default(none) shared(bs, bj, hops, n, dim, dof_of, scratch, Ap, Ai, diag_pos) \
    num_threads(nt)
  {
    pdk_index *stamp = scratch + (size_t)2 * n * (size_t)omp_get_thread_num();
    pdk_index *list = stamp + n;
#pragma omp for schedule(static)
    for (pdk_index i = 0; i < n; ++i) {
      const pdk_index cnt = coupled(bs, bj, hops, i, stamp, list);
      for (int c = 0; c < dim; ++c) {
        const int col = dof_of[c][i];
        if (col < 0) continue;
        int k = Ap[col];
        for (pdk_index q = 0; q < cnt; ++q)
          for (int e = 0; e < dim; ++e) {
            const int row = dof_of[e][list[q]];
            if (row < 0) continue;
            if (row == col) diag_pos[col] = k;
            Ai[k++] = row;
          }
      }
    }
  }
  /* Transposed positions: row r of column col sits in column r at the position of row col. */
  {
    const long nf = ns->nf;
    int *tpos = ns->tpos;
    int bad = 0;
    /* clang-format off */
#pragma omp parallel for default(none) shared(Ap, Ai, tpos, nf) reduction(| : bad) \
    schedule(static) num_threads(nt)
    /* clang-format on */
    for (long col = 0; col < nf; ++col)
      for (int k = Ap[col]; k < Ap[col + 1]; ++k) {
        const int r = Ai[k];
        int lo = Ap[r], hi = Ap[r + 1] - 1, found = -1;
        while (lo <= hi) {
          const int mid = lo + (hi - lo) / 2;
          if (Ai[mid] == (int)col) {
            found = mid;
            break;
          }
          if (Ai[mid] < (int)col)
            lo = mid + 1;
          else
            hi = mid - 1;
        }
        if (found < 0) bad = 1;
        tpos[k] = found < 0 ? k : found;
      }
    PDK_CHECK_GOTO(!bad, ctx, PDK_ERR_NUMERIC,
                   "newton: the tangent pattern is not structurally symmetric; the families are "
                   "not stored from both ends");
  }
cleanup:
  free(rows_of);
  free(scratch);
  return err;
}

/* ---- setup ---------------------------------------------------------------------------------- */

int pdk_newton_setup(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  const double t0 = pdk_wtime();
  newton_state *ns = calloc(1, sizeof *ns);
  PDK_CHECK(ns, ctx, PDK_ERR_MEMORY, "newton: out of memory");
  s->newton = ns;
  for (int c = 0; c < dim; ++c) {
    ns->dof_of[c] = malloc((size_t)n * sizeof(int32_t));
    ns->diag_full[c] = calloc((size_t)n, sizeof(double));
    ns->fa[c] = malloc((size_t)n * sizeof(double));
    ns->x0[c] = malloc((size_t)n * sizeof(double));
    PDK_CHECK(ns->dof_of[c] && ns->diag_full[c] && ns->fa[c] && ns->x0[c], ctx, PDK_ERR_MEMORY,
              "newton: out of memory for %d particles", (int)n);
  }
  ns->h_plus = malloc((size_t)n * sizeof(double));
  ns->h_minus = malloc((size_t)n * sizeof(double));
  ns->saved = malloc((size_t)n * sizeof(double));
  PDK_CHECK(ns->h_plus && ns->h_minus && ns->saved, ctx, PDK_ERR_MEMORY,
            "newton: out of memory for %d particles", (int)n);
  long nf = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c)
      ns->dof_of[c][i] = s->fixed[c][i] ? -1 : (int32_t)nf++;
  PDK_CHECK(nf <= INT_MAX - 1, ctx, PDK_ERR_MEMORY, "newton: %ld unknowns exceed 32-bit indices",
            nf);
  ns->nf = nf;
  ns->dof_particle = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *ns->dof_particle);
  ns->dof_comp = malloc((size_t)(nf > 0 ? nf : 1));
  ns->rhs = malloc((size_t)(nf > 0 ? nf : 1) * sizeof(double));
  ns->dx = malloc((size_t)(nf > 0 ? nf : 1) * sizeof(double));
  PDK_CHECK(ns->dof_particle && ns->dof_comp && ns->rhs && ns->dx, ctx, PDK_ERR_MEMORY,
            "newton: out of memory for %ld unknowns", nf);
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c)
      if (ns->dof_of[c][i] >= 0) {
        ns->dof_particle[ns->dof_of[c][i]] = i;
        ns->dof_comp[ns->dof_of[c][i]] = (uint8_t)c;
      }
  ns->hyperelastic = pdk_model_opts_hyperelastic(&s->m->opts);
  {
    const int has = pdk_model_has_tangent(s->m);
    char kinds[128];
    PDK_CHECK(s->opts.tangent != PDK_TANGENT_ANALYTIC || has, ctx, PDK_ERR_UNSUPPORTED,
              "newton: tangent analytic was requested but model '%s' has no analytic tangent "
              "(%s have one); use tangent auto or difference",
              pdk_model_kind_name(s->m->opts.kind),
              pdk_model_kinds_list(PDK_KIND_TANGENT, PDK_KIND_TANGENT, " and ", kinds,
                                   sizeof kinds));
    ns->analytic = has && s->opts.tangent != PDK_TANGENT_DIFFERENCE;
  }
  s->stats.analytic_tangent = ns->analytic;
  s->stats.num_unknowns = nf;
  if (nf == 0) return PDK_SUCCESS; /* everything prescribed: nothing to solve */
  PDK_CALL(check_held(s));
  if (!ns->analytic) PDK_CALL(pdk_static_color(s)); /* the analytic tangent needs no coloring */
  PDK_CALL(build_pattern(s));
  cholmod_start(&ns->cc);
  ns->cc_started = 1;
  ns->checked_level = -1;
  ns->cc.quick_return_if_not_posdef = 1;
  umfpack_di_defaults(ns->control);
  ns->control[UMFPACK_SCALE] = UMFPACK_SCALE_NONE; /* pivots comparable with k_ref */
  s->stats.tangent_nnz = ns->nnz;
  s->stats.tangent_nnz_per_row = (double)ns->nnz / (double)nf;
  s->stats.tangent_bytes =
      ((size_t)nf + 1) * sizeof(int) + (size_t)ns->nnz * (2 * sizeof(int) + sizeof(double));
  s->stats.passes_per_tangent = ns->analytic                         ? 0
                                : s->opts.fd_scheme == PDK_FD_CENTRAL ? 2L * dim * s->num_colors
                                                                      : (long)dim * s->num_colors + 1;
  s->stats.time_setup += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

void pdk_newton_free(pdk_static *s) {
  newton_state *ns = s->newton;
  if (!ns) return;
  if (ns->cc_started) {
    cholmod_free_factor(&ns->L, &ns->cc);
    cholmod_finish(&ns->cc);
  }
  if (ns->numeric) umfpack_di_free_numeric(&ns->numeric);
  if (ns->symbolic) umfpack_di_free_symbolic(&ns->symbolic);
  for (int c = 0; c < 3; ++c) {
    free(ns->dof_of[c]);
    free(ns->diag_full[c]);
    free(ns->fa[c]);
    free(ns->x0[c]);
  }
  free(ns->dof_particle);
  free(ns->dof_comp);
  free(ns->Ap);
  free(ns->Ai);
  free(ns->Ax);
  free(ns->tpos);
  free(ns->diag_pos);
  free(ns->h_plus);
  free(ns->h_minus);
  free(ns->saved);
  free(ns->rhs);
  free(ns->dx);
  free(ns->ident_start);
  free(ns->ident);
  free(ns->col_scratch);
  free(ns->col_block);
  free(ns);
  s->newton = NULL;
}

/* ---- assembly ------------------------------------------------------------------------------- */

/* Writes the columns (and full-tangent diagonals) of the particles members[0..count-1], moved in
 * component d: upper = forces after the + move, lower = after the - move (central) or at the base
 * (forward). */
static void scatter(pdk_static *s, const pdk_index *members, pdk_index count, int d,
                    double *const *upper, double *const *lower, int central) {
  newton_state *ns = s->newton;
  const double *vol = pdk_particles_volume(s->p);
  const int *Ap = ns->Ap, *Ai = ns->Ai;
  double *Ax = ns->Ax;
  const pdk_index *dof_particle = ns->dof_particle;
  const uint8_t *dof_comp = ns->dof_comp;
  const int32_t *dof_d = ns->dof_of[d];
  double *diag_d = ns->diag_full[d];
  const double *hp = ns->h_plus, *hm = ns->h_minus;
  const int nt = s->ctx->num_threads;
#pragma omp parallel for default(none)                                                             \
    shared(members, count, d, upper, lower, central, vol, Ap, Ai, Ax, dof_particle, dof_comp,      \
           dof_d, diag_d, hp, hm) schedule(static) num_threads(nt)
  for (pdk_index q = 0; q < count; ++q) {
    const pdk_index i = members[q];
    const double denom = central ? hp[i] + hm[i] : hp[i];
    diag_d[i] = -vol[i] * (upper[d][i] - lower[d][i]) / denom;
    const int col = dof_d[i];
    if (col < 0) continue;
    for (int k = Ap[col]; k < Ap[col + 1]; ++k) {
      const int row = Ai[k];
      const pdk_index j = dof_particle[row];
      const int e = dof_comp[row];
      Ax[k] = -vol[j] * (upper[e][j] - lower[e][j]) / denom;
    }
  }
}

/* Difference tangent at the current x over groups of particles moved together:
 * group g holds members[group_start[g] .. group_start[g+1]-1]. x and "f" are left as they were. */
static int assemble(pdk_static *s, int num_groups, const pdk_index *group_start,
                    const pdk_index *members) {
  newton_state *ns = s->newton;
  const int dim = s->dim;
  const pdk_index n = s->n;
  const int central = s->opts.fd_scheme == PDK_FD_CENTRAL;
  const double h = s->opts.fd_step * s->horizon;
  const double t0 = pdk_wtime();
  double *f[3] = {NULL, NULL, NULL};
  double *fbase[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c)
    f[c] = field(s->p, "f", c);
  /* "f" holds the forces at x (the last residual evaluation): keep them to put back */
  for (int c = 0; c < dim; ++c)
    fbase[c] = ns->x0[c]; /* x0 is free until the line search */
  for (int c = 0; c < dim; ++c)
    memcpy(fbase[c], f[c], (size_t)n * sizeof(double));
  if (!central) /* base forces at x for forward differences */
    for (int c = 0; c < dim; ++c)
      memcpy(ns->fa[c], f[c], (size_t)n * sizeof(double));
  for (int g = 0; g < num_groups; ++g) {
    const pdk_index *mem = members + group_start[g];
    const pdk_index count = group_start[g + 1] - group_start[g];
    for (int d = 0; d < dim; ++d) {
      double *x = field(s->p, "x", d);
      for (pdk_index q = 0; q < count; ++q) {
        const pdk_index i = mem[q];
        ns->saved[i] = x[i];
        x[i] = ns->saved[i] + h;
        ns->h_plus[i] = x[i] - ns->saved[i];
      }
      int err = pdk_model_force_trial(s->m, NULL);
      s->stats.force_passes++;
      if (!err && central) {
        for (int c = 0; c < dim; ++c)
          memcpy(ns->fa[c], f[c], (size_t)n * sizeof(double));
        for (pdk_index q = 0; q < count; ++q) {
          const pdk_index i = mem[q];
          x[i] = ns->saved[i] - h;
          ns->h_minus[i] = ns->saved[i] - x[i];
        }
        err = pdk_model_force_trial(s->m, NULL);
        s->stats.force_passes++;
      }
      for (pdk_index q = 0; q < count; ++q)
        x[mem[q]] = ns->saved[mem[q]]; /* also on failure */
      if (err) return err;
      if (central)
        scatter(s, mem, count, d, ns->fa, f, 1);
      else
        scatter(s, mem, count, d, f, ns->fa, 0);
    }
  }
  for (int c = 0; c < dim; ++c)
    memcpy(f[c], fbase[c], (size_t)n * sizeof(double));
  double kmax = 0.0;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i)
      kmax = fmax(kmax, fabs(ns->diag_full[c][i]));
  ns->k_ref = kmax;
  s->stats.assemblies++;
  s->stats.time_assembly += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

/* Analytic tangent at the current x (the model's tangent_column, see model_impl.h): one column
 * particle per iteration of a static parallel loop; each column is computed whole by one thread
 * into a dense block over its coupled particles (the pattern's list, same order), then copied to
 * the free entries. No sums cross columns, so the bits do not depend on the thread count. */
static int assemble_analytic(pdk_static *s) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  pdk_model *m = s->m;
  const int dim = s->dim, hops = s->hops, nt = ctx->num_threads;
  const pdk_index n = s->n;
  const double t0 = pdk_wtime();
  if (m->ops->tangent_prepare) PDK_CALL(m->ops->tangent_prepare(m));
  const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
  const pdk_index *bj = pdk_families_bond_j(s->fam);
  if (!ns->col_scratch) {
    /* largest coupled list: bounds the dense column block */
    pdk_index fmax_ = 0;
    for (pdk_index i = 0; i < n; ++i)
      fmax_ = bs[i + 1] - bs[i] > fmax_ ? (pdk_index)(bs[i + 1] - bs[i]) : fmax_;
    double cap = 1.0 + (double)fmax_ + (hops > 1 ? (double)fmax_ * (double)fmax_ : 0.0);
    ns->block_capacity = cap < (double)n ? (pdk_index)cap : n;
    ns->col_scratch = malloc((size_t)nt * 3 * (size_t)n * sizeof *ns->col_scratch);
    ns->col_block = malloc((size_t)nt * (size_t)ns->block_capacity * (size_t)(dim * dim) *
                           sizeof *ns->col_block);
    PDK_CHECK(ns->col_scratch && ns->col_block, ctx, PDK_ERR_MEMORY,
              "newton: out of memory for the analytic tangent's scratch (%d threads, %d particles)",
              nt, (int)n);
  }
  pdk_index *scratch = ns->col_scratch;
  double *blocks = ns->col_block;
  const size_t cap = (size_t)ns->block_capacity;
  const int *Ap = ns->Ap;
  double *Ax = ns->Ax;
  int32_t *const *dof_of = ns->dof_of;
  double *const *diag_full = ns->diag_full;
  void (*column)(const pdk_model *, pdk_index, const pdk_index *, double *) =
      m->ops->tangent_column;
  const pdk_model *mc = m;
#pragma omp parallel default(none) shared(n, dim, hops, bs, bj, scratch, blocks, cap, Ap, Ax,                                                   dof_of, diag_full, column, mc) num_threads(nt)
  {
    const size_t tid = (size_t)omp_get_thread_num();
    pdk_index *stamp = scratch + 3 * (size_t)n * tid;
    pdk_index *list = stamp + n, *loc = list + n;
    double *block = blocks + cap * (size_t)(dim * dim) * tid;
    for (pdk_index k = 0; k < n; ++k) /* marks of the last assembly would hide neighbours */
      stamp[k] = -1;
#pragma omp for schedule(static)
    for (pdk_index i = 0; i < n; ++i) {
      const pdk_index cnt = coupled(bs, bj, hops, i, stamp, list);
      for (pdk_index q = 0; q < cnt; ++q)
        loc[list[q]] = q;
      memset(block, 0, (size_t)cnt * (size_t)(dim * dim) * sizeof *block);
      column(mc, i, loc, block);
      const double *Kii = block + (size_t)loc[i] * (size_t)(dim * dim);
      for (int c = 0; c < dim; ++c) {
        diag_full[c][i] = Kii[c * dim + c];
        const int col = dof_of[c][i];
        if (col < 0) continue;
        int k = Ap[col];
        for (pdk_index q = 0; q < cnt; ++q)
          for (int e = 0; e < dim; ++e)
            if (dof_of[e][list[q]] >= 0) Ax[k++] = block[((size_t)q * dim + e) * dim + c];
      }
    }
  }
  double kmax = 0.0;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i)
      kmax = fmax(kmax, fabs(ns->diag_full[c][i]));
  ns->k_ref = kmax;
  s->stats.assemblies++;
  s->stats.time_assembly += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

/* The solver's tangent: analytic or colored differences (opts.tangent). */
static int assemble_tangent(pdk_static *s) {
  newton_state *ns = s->newton;
  if (ns->analytic) return assemble_analytic(s);
  return assemble(s, s->num_colors, s->color_start, s->color_members);
}

int pdk_newton_tangent(pdk_static *s, int colored, int *num_cols, const int **col_start,
                       const int **row_index, const double **values) {
  newton_state *ns = s->newton;
  PDK_CHECK(ns && ns->Ap, s->ctx, PDK_ERR_ARG,
            "newton: no tangent (not a Newton solver, or no unknowns)");
  PDK_CHECK(colored != 2 || s->m->ops->tangent_column, s->ctx, PDK_ERR_UNSUPPORTED,
            "newton: model '%s' has no analytic tangent", pdk_model_kind_name(s->m->opts.kind));
  if (colored == 2)
    PDK_CALL(assemble_analytic(s));
  else if (colored) {
    PDK_CALL(pdk_static_color(s));
    PDK_CALL(assemble(s, s->num_colors, s->color_start, s->color_members));
  } else {
    if (!ns->ident) {
      ns->ident_start = malloc(((size_t)s->n + 1) * sizeof *ns->ident_start);
      ns->ident = malloc((size_t)s->n * sizeof *ns->ident);
      PDK_CHECK(ns->ident_start && ns->ident, s->ctx, PDK_ERR_MEMORY, "newton: out of memory");
      for (pdk_index i = 0; i <= s->n; ++i)
        ns->ident_start[i] = i;
      for (pdk_index i = 0; i < s->n; ++i)
        ns->ident[i] = i;
    }
    PDK_CALL(assemble(s, (int)s->n, ns->ident_start, ns->ident));
  }
  *num_cols = (int)ns->nf;
  *col_start = ns->Ap;
  *row_index = ns->Ai;
  *values = ns->Ax;
  return PDK_SUCCESS;
}

/* ---- factorization and solve ------------------------------------------------------------------
 */

static int solve_linear(pdk_static *s) {
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
    if (solve_linear(s)) {
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
             comp_name[ns->dof_comp[dof]]);
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
static int factor_and_solve(pdk_static *s) {
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
      const double *x = field(s->p, "x", c);
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
  return solve_linear(s);
}

/* ---- Newton iterations ----------------------------------------------------------------------- */

/* Float storage rounds what the force pass stores per neighbour (correspondence: the tensors of
 * pass 2, a relative 2^-24 of the stress) at every evaluation, so the residual carries round-off
 * noise that no Newton step removes, while rtol defaults to 1e-10: near the solution the steps
 * stop contracting (V-Q, manufactured and bar problems: at 1e-9 to 3e-8 of the load norm) and the
 * line search finally stalls. With float storage, a residual below FLT_EPSILON of the load norm
 * (+ atol) that the last step reduced by less than half (`previous` its value before that step;
 * 0 after a stalled line search) is that floor: the level is accepted there, the floor
 * raised to the residual and the level counted in stats.storage_floor_levels. A quadratically
 * converging step reduces ||r|| by far more than half, so the test does not stop a healthy
 * iteration early; double storage never takes this exit. */
static int at_storage_floor(pdk_static *s, double previous) {
  if (s->m->opts.precision != PDK_PRECISION_FLOAT) return 0;
  if (!(s->rnorm <= FLT_EPSILON * s->fnorm + s->opts.atol)) return 0;
  if (!(s->rnorm > 0.5 * previous)) return 0;
  s->floor = fmax(s->floor, s->rnorm);
  s->stats.storage_floor_levels++;
  return 1;
}

int pdk_newton_solve_level(pdk_static *s, long *iterations) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  static const char *hint = "the load step may be too large (add load levels) or the model "
                            "undefined at this deformation";
  *iterations = 0;
  PDK_CALL(pdk_static_residual(s));
  if (!isfinite(s->rnorm) || !isfinite(s->fnorm)) return pdk_static_nonfinite(s, "newton", 0, hint);
  int reuse = 0; /* never across rounds or levels: bonds broke or the load moved */
  double previous = INFINITY; /* ||r|| before the last step */
  s->stats.residual_history_len = 0;
  for (long it = 0;; ++it) {
    if (s->stats.residual_history_len < 16)
      s->stats.residual_history[s->stats.residual_history_len++] = s->rnorm;
    if (pdk_static_converged(s) || at_storage_floor(s, previous)) return PDK_SUCCESS;
    previous = s->rnorm;
    if (it == s->opts.max_iterations)
      return pdk_ctx_error_set(
          ctx, PDK_ERR_NUMERIC, "newton",
          "Newton did not converge in %ld iterations at load level %d (load factor %g), round %d: "
          "residual %.3e against a tolerance of %.3e (rtol %g x load norm %.3e + atol %g); add "
          "load levels or raise max_iterations",
          it, s->level, s->lambda, s->round, s->rnorm, s->opts.rtol * s->fnorm + s->opts.atol,
          s->opts.rtol, s->fnorm, s->opts.atol);
    if (reuse) { /* the last full step contracted ||r|| by >= 1000: keep the factorized tangent */
      for (long k = 0; k < ns->nf; ++k)
        ns->rhs[k] = s->r[ns->dof_comp[k]][ns->dof_particle[k]];
      PDK_CALL(solve_linear(s));
      s->stats.tangent_reuses++;
    } else {
      PDK_CALL(assemble_tangent(s));
      PDK_CALL(factor_and_solve(s));
    }
    /* Backtracking line search on ||r||. */
    const double phi0 = s->rnorm;
    for (int c = 0; c < dim; ++c)
      memcpy(ns->x0[c], field(s->p, "x", c), (size_t)n * sizeof(double));
    double alpha = 1.0;
    int accepted = 0;
    for (int bt = 0; bt <= s->opts.max_backtracks; ++bt) {
      for (long k = 0; k < ns->nf; ++k) {
        const pdk_index i = ns->dof_particle[k];
        const int c = ns->dof_comp[k];
        field(s->p, "x", c)[i] = ns->x0[c][i] + alpha * ns->dx[k];
      }
      PDK_CALL(pdk_static_residual(s));
      if (isfinite(s->rnorm) && isfinite(s->fnorm) &&
          (s->rnorm <= (1.0 - s->opts.ls_decrease * alpha) * phi0 || pdk_static_converged(s))) {
        accepted = 1;
        break;
      }
      alpha *= 0.5;
      s->stats.line_search_cuts++;
    }
    *iterations = it + 1;
    reuse = s->opts.reuse_tangent && accepted && alpha == 1.0 && s->rnorm <= 1e-3 * phi0;
    if (!accepted) {
      for (int c = 0; c < dim; ++c)
        memcpy(field(s->p, "x", c), ns->x0[c], (size_t)n * sizeof(double));
      const double tried = s->rnorm;
      PDK_CALL(pdk_static_residual(s));
      if (at_storage_floor(s, 0.0)) return PDK_SUCCESS;
      return pdk_ctx_error_set(
          ctx, PDK_ERR_NUMERIC, "newton",
          "the line search failed at load level %d (load factor %g), round %d, iteration %ld: "
          "residual %.3e (%.2e of the load norm) did not decrease along the Newton direction "
          "(%.3e at step %g; round-off floor %.3e). Add load levels (the step is too large for the "
          "tangent) or check that the model is smooth at this deformation",
          s->level, s->lambda, s->round, it + 1, phi0, s->fnorm > 0 ? phi0 / s->fnorm : 0.0, tried,
          2.0 * alpha, s->floor);
    }
  }
}
