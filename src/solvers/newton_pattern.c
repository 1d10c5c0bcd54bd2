/* Newton (newton.c), the tangent's sparsity pattern: whether the displacement conditions stop every
 * rigid motion, and the pattern of the free unknowns coupled within `hops` family hops (the
 * storage is described in newton.c). */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "newton_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/particles.h"
#include "pdk/static.h"

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
int pdk_newton_check_held(pdk_static *s) {
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
    const double(*R)[3] = pdk_static_frame(s, i);
    for (int c = 0; c < dim; ++c) {
      if (!s->fixed[c][i]) continue;
      /* the constrained direction: axis c, or the normal n of a condition along a direction */
      double d[3] = {0, 0, 0};
      for (int a = 0; a < dim; ++a)
        d[a] = R ? R[a][c] : (double)(a == c);
      double phi[6] = {0};
      for (int a = 0; a < dim; ++a)
        phi[a] = d[a]; /* translations */
      if (dim == 2)
        phi[2] = -r[1] * d[0] + r[0] * d[1];
      else {
        /* rotation about axis a: (e_a x r).d */
        phi[3] = -r[2] * d[1] + r[1] * d[2];
        phi[4] = r[2] * d[0] - r[0] * d[2];
        phi[5] = -r[1] * d[0] + r[0] * d[1];
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
pdk_index pdk_newton_coupled(const pdk_bond_index *restrict bs, const pdk_index *restrict bj,
                             int hops, pdk_index i, pdk_index *restrict stamp,
                             pdk_index *restrict list) {
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

int pdk_newton_build_pattern(pdk_static *s) {
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
      const pdk_index cnt = pdk_newton_coupled(bs, bj, hops, i, stamp, list);
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
      const pdk_index cnt = pdk_newton_coupled(bs, bj, hops, i, stamp, list);
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
