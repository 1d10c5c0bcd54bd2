/* Peridynamic Galerkin model (kind galerkin): the driver. Formulas and kernel contract:
 * kernels/ref/galerkin.c; the formulation with its equation numbers and the results:
 * docs/validation/galerkin.md.
 *
 *   setup   checks the options (elastic laws, one material, no bond breaking, tl, double), builds
 *           rev (each bond's member index in the neighbour's family: the families must be
 *           symmetric), V_H, the derivative table dN^{kji} of every family (O(N_k^2 dim) doubles
 *           per particle, N_k the family size: ~7 kB per particle in 2-D with 20 neighbours), and
 *           with correction vc1 the first-order variationally consistent correction (below);
 *           declares "F" (f64 x dim*dim: F^{kk}, the family's gradient at its own particle, after
 *           each force pass) and "area" (f64 x dim: the area vector A_k of thesis eq. 4.35 with the
 *           final derivatives; 0 inside the body after vc1; a constant stress P gives the nodal
 *           force -P A_k, so a traction is applied as the body force P A_k / V_k).
 *   force   pass 1 over families (F^{kj} and the law at every member, per-member forces G), pass 2
 *           over particles (gather of G, f = -G / V); fixed blocks of PDK_GALERKIN_BLOCK, energies
 *           summed per block in index order and then in block order: bitwise the same for any
 *           thread count. Trial and committing passes are the same (no history).
 *
 * VC1 (Bode 2021 section 5.3.2, eqs. 5.56, 5.64-5.68): dN^{kji} <- dN^{kji} + psi^{ki} alpha_k
 * (componentwise, the same alpha_k for every evaluation point j). Since sum_j w_kj = V_k, the area
 * vectors become A_m(alpha) = A_m(0) + sum_{k : m in H_k} V_k psi^{km} alpha_k: sparse,
 * unsymmetric, with the pattern of the families. Conditions (thesis Table 7.1): A_m = 0 inside;
 * on the surface set either "s" (no normals given, or a zero normal: alpha_m = 0, A_m free) or
 * "sn" (normals given: alpha_m . n_m = 0, A_m . t = 0 for the tangents t, so A_m is normal; the
 * thesis imposes the same with Lagrange multipliers, here alpha_m = T_m beta_m is parametrized by
 * the tangents and the normal equation dropped, which gives the same solution). Per particle a
 * basis B_m (identity, tangents or nothing), unknowns beta_m, equations B_m^T A_m = 0: one square
 * system, assembled in compressed columns, factorized and solved once by UMFPACK.
 * With the bond correction (opts.galerkin.bond) the correction functions are the thesis' V5 (eq.
 * 5.64) as printed: the bond projector applied to sum_d e_d, i.e. component c of the correction at
 * evaluation point j is psi^{ki} alpha_kc o^{kj}_c with o^{kj} = (1 - n (x) n)(1, .., 1) (j != k;
 * o = 1 at j = k); the area vectors then take sum_j w_kj o^{kj} in place of V_k. This componentwise
 * form is what reproduces Bode et al.'s Table 1 (docs/validation/galerkin.md); it keeps the
 * consistency conditions but maps bonds exactly only where alpha_k has equal components.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/ext.h"
#include "kernels.h"
#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define PDK_GALERKIN_BLOCK 256

typedef struct galerkin_impl {
  pdk_galerkin_consts k;
  pdk_index n;
  int64_t num_blocks;
  int32_t *rev;    /* [num_bonds] */
  int64_t *dstart; /* [n] */
  double *d;       /* derivative table */
  double *vfam;    /* [n] */
  double *G;       /* [dim][n + num_bonds] */
  double *W;       /* [n] */
  double *block_energy;
  double *alpha; /* [dim][n] the VC1 coefficients (NULL without) */
  int64_t num_members;
} galerkin_impl;

static void galerkin_destroy(pdk_model *m) {
  galerkin_impl *im = m->impl;
  if (!im) return;
  free(im->rev);
  free(im->dstart);
  free(im->d);
  free(im->vfam);
  free(im->G);
  free(im->W);
  free(im->block_energy);
  free(im->alpha);
  free(im);
  m->impl = NULL;
}

static void galerkin_arrays(pdk_model *m, pdk_galerkin_arrays *a) {
  galerkin_impl *im = m->impl;
  pdk_particles *p = m->p;
  const int dim = im->k.dim;
  memset(a, 0, sizeof *a);
  a->bond_start = pdk_families_bond_start(m->fam);
  a->bond_j = pdk_families_bond_j(m->fam);
  a->rev = im->rev;
  a->dstart = im->dstart;
  a->d = im->d;
  for (int c = 0; c < dim; ++c) {
    a->X[c] = pdk_particles_X(p, c);
    a->x[c] = pdk_particles_field_data(p, "x", c);
    a->G[c] = im->G + (size_t)c * (size_t)im->num_members;
    a->f[c] = pdk_particles_field_data(p, "f", c);
  }
  for (int t = 0; t < dim * dim; ++t)
    a->F[t] = pdk_particles_field_data(p, "F", t);
  a->volume = pdk_particles_volume(p);
  a->vfam = im->vfam;
  a->W = im->W;
}

/* Area vectors of the current derivative table into the field "area" (a unit pass 1 and a
 * pass 2 writing into "area" instead of "f"). */
static void galerkin_area(pdk_model *m) {
  galerkin_impl *im = m->impl;
  pdk_galerkin_arrays a;
  galerkin_arrays(m, &a);
  for (int c = 0; c < im->k.dim; ++c)
    a.f[c] = pdk_particles_field_data(m->p, "area", c);
  const pdk_galerkin_consts *k = &im->k;
  const int64_t nb = im->num_blocks;
  const pdk_index n = im->n;
  const pdk_kernel_table *kt = &m->ctx->kernels;
#pragma omp parallel for default(none) shared(a, k, nb, n, kt) schedule(static)                    \
    num_threads(m->ctx->num_threads)
  for (int64_t b = 0; b < nb; ++b) {
    const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
    const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
    kt->galerkin_pass1(k, &a, 1, i0, i1);
  }
#pragma omp parallel for default(none) shared(a, k, nb, n, kt) schedule(static)                    \
    num_threads(m->ctx->num_threads)
  for (int64_t b = 0; b < nb; ++b) {
    const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
    const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
    kt->galerkin_pass2(k, &a, 1, i0, i1);
  }
}

typedef struct row_val {
  int row;
  double val;
} row_val;

static int row_val_cmp(const void *x, const void *y) {
  const row_val *a = x, *b = y;
  return (a->row > b->row) - (a->row < b->row);
}

/* The unknowns and equations of particle i (VC1): nb[i] basis vectors B_i (columns, in
 * basis[i][e][c]): the identity inside; the tangents of the normal on a surface particle with a
 * normal ("sn"); none on one without ("s"). alpha_i = B_i beta_i, equations B_i^T A_i = 0. */
static int particle_basis(int dim, int surface, const double nrm[3], double B[3][3]) {
  if (!surface) {
    for (int e = 0; e < dim; ++e)
      for (int c = 0; c < dim; ++c)
        B[e][c] = e == c ? 1.0 : 0.0;
    return dim;
  }
  double len = 0.0;
  for (int c = 0; c < dim; ++c)
    len += nrm[c] * nrm[c];
  if (!(len > 0)) return 0;
  len = sqrt(len);
  const double n[3] = {nrm[0] / len, nrm[1] / len, dim == 3 ? nrm[2] / len : 0.0};
  if (dim == 2) {
    B[0][0] = -n[1];
    B[0][1] = n[0];
    return 1;
  }
  /* two unit tangents: the axis least aligned with n, projected, then n x t1 */
  int ax = 0;
  for (int c = 1; c < 3; ++c)
    if (fabs(n[c]) < fabs(n[ax])) ax = c;
  double t[3] = {0, 0, 0}, tl = 0.0;
  for (int c = 0; c < 3; ++c) {
    t[c] = (c == ax ? 1.0 : 0.0) - n[ax] * n[c];
    tl += t[c] * t[c];
  }
  tl = sqrt(tl);
  for (int c = 0; c < 3; ++c)
    B[0][c] = t[c] / tl;
  B[1][0] = n[1] * B[0][2] - n[2] * B[0][1];
  B[1][1] = n[2] * B[0][0] - n[0] * B[0][2];
  B[1][2] = n[0] * B[0][1] - n[1] * B[0][0];
  return 2;
}

/* The componentwise factor o^{kj} of the correction functions at member pj of family k: with
 * the bond correction the thesis' V5 projector applied to sum_d e_d, o = (1 - n (x) n) (1, .., 1)
 * with n = (X_pj - X_k)/|X_pj - X_k| (j != k); 1 in every component otherwise. */
static void vc1_factor(const double *const X[3], int dim, int bond, pdk_index k, pdk_index pj,
                       double o[3]) {
  for (int c = 0; c < 3; ++c)
    o[c] = 1.0;
  if (!bond || pj == k) return;
  double r[3] = {0, 0, 0}, r2 = 0.0, rs = 0.0;
  for (int c = 0; c < dim; ++c) {
    r[c] = X[c][pj] - X[c][k];
    r2 += r[c] * r[c];
    rs += r[c];
  }
  for (int c = 0; c < dim; ++c)
    o[c] = 1.0 - r[c] * rs / r2;
}

/* VC1: psi, the system, alpha, the corrected table (see the top of the file). */
static int galerkin_vc1(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  galerkin_impl *im = m->impl;
  const int dim = im->k.dim;
  const pdk_index n = im->n;
  const char *sname = m->opts.galerkin.surface, *nname = m->opts.galerkin.normals;
  int err = PDK_SUCCESS;
  double *psi = NULL, *Ax = NULL, *rhs = NULL, *sol = NULL, *basis = NULL;
  int *Ap = NULL, *Ai = NULL, *off = NULL;
  row_val *col = NULL;
  void *symbolic = NULL, *numeric = NULL;
  PDK_CHECK(sname && sname[0], ctx, PDK_ERR_ARG,
            "galerkin model: correction vc1 needs the surface set (opts.galerkin.surface; scene "
            "model.galerkin.surface): the particles on the body's surface");
  char field[PDK_FIELD_NAME_MAX];
  snprintf(field, sizeof field, "set:%s", sname);
  const uint8_t *surf = pdk_particles_field_data(m->p, field, 0);
  PDK_CHECK(surf, ctx, PDK_ERR_ARG,
            "galerkin model: the surface set '%s' does not exist (no field \"%s\")", sname, field);
  const double *nrm[3] = {NULL, NULL, NULL};
  if (nname) {
    pdk_type type;
    int comp = 0;
    PDK_CHECK(
        pdk_particles_field_exists(m->p, nname) &&
            !pdk_particles_field_info(m->p, nname, &type, &comp) && type == PDK_F64 && comp == dim,
        ctx, PDK_ERR_ARG,
        "galerkin model: the normals field '%s' must exist, f64 with %d components", nname, dim);
    for (int c = 0; c < dim; ++c)
      nrm[c] = pdk_particles_field_data(m->p, nname, c);
  }
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *vol = pdk_particles_volume(m->p);
  const size_t nn = (size_t)(n > 0 ? n : 1);
  psi = malloc((size_t)im->num_members * sizeof(double));
  off = malloc((nn + 1) * sizeof(int));
  basis = malloc(nn * 9 * sizeof(double));
  PDK_CHECK_GOTO(psi && off && basis, ctx, PDK_ERR_MEMORY, "galerkin model: out of memory for vc1");
  pdk_galerkin_arrays a;
  galerkin_arrays(m, &a);
  pdk_index bad = 0;
  {
    const pdk_galerkin_consts *k = &im->k;
    const int64_t nb = im->num_blocks;
    const pdk_kernel_table *kt = &ctx->kernels;
#pragma omp parallel for default(none) shared(a, k, nb, n, psi, kt) schedule(static)                \
    num_threads(ctx->num_threads) reduction(+ : bad)
    for (int64_t b = 0; b < nb; ++b) {
      const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
      const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
      bad += kt->galerkin_psi(k, &a, psi, i0, i1);
    }
  }
  PDK_CHECK_GOTO(bad == 0, ctx, PDK_ERR_ARG,
                 "galerkin model: %d families are too small or flat for the linear moving least "
                 "squares of the vc1 correction (at least dim + 1 members not on one line or "
                 "plane); raise the horizon",
                 (int)bad);
  /* unknowns: off[i] .. off[i+1] belong to particle i */
  off[0] = 0;
  for (pdk_index i = 0; i < n; ++i) {
    double ni[3] = {0, 0, 0};
    for (int c = 0; c < dim && nrm[0]; ++c)
      ni[c] = nrm[c][i];
    double(*Bi)[3] = (double(*)[3])(basis + 9 * (size_t)i);
    const int nbas = particle_basis(dim, surf[i] != 0, ni, Bi);
    PDK_CHECK_GOTO((int64_t)off[i] + nbas < INT32_MAX, ctx, PDK_ERR_UNSUPPORTED,
                   "galerkin model: the vc1 system is too large for UMFPACK's int interface");
    off[i + 1] = off[i] + nbas;
  }
  const int nu = off[n];
  /* the matrix in compressed columns: column (k, e), rows (m, r) for the members m of k:
   * V_k psi^{km} (B_m^T B_k)[r][e] */
  int64_t nnz = 0;
  for (pdk_index k = 0; k < n; ++k) {
    const int64_t ck = off[k + 1] - off[k];
    nnz += ck * (off[k + 1] - off[k]);
    for (pdk_bond_index b = bs[k]; b < bs[k + 1]; ++b)
      nnz += ck * (off[bj[b] + 1] - off[bj[b]]);
  }
  PDK_CHECK_GOTO(nnz < INT32_MAX, ctx, PDK_ERR_UNSUPPORTED,
                 "galerkin model: the vc1 system has %lld entries, more than UMFPACK's int "
                 "interface takes",
                 (long long)nnz);
  Ap = malloc((size_t)(nu + 1) * sizeof(int));
  Ai = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(int));
  Ax = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(double));
  rhs = malloc((size_t)(nu > 0 ? nu : 1) * sizeof(double));
  sol = malloc((size_t)(nu > 0 ? nu : 1) * sizeof(double));
  im->alpha = calloc((size_t)dim * nn, sizeof(double));
  pdk_index maxlen = 0;
  for (pdk_index k = 0; k < n; ++k)
    maxlen = bs[k + 1] - bs[k] > maxlen ? (pdk_index)(bs[k + 1] - bs[k]) : maxlen;
  col = malloc((size_t)(maxlen + 1) * (size_t)dim * sizeof *col);
  PDK_CHECK_GOTO(Ap && Ai && Ax && rhs && sol && im->alpha && col, ctx, PDK_ERR_MEMORY,
                 "galerkin model: out of memory for the vc1 system (%lld entries)", (long long)nnz);
  nnz = 0;
  const double *X[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c)
    X[c] = pdk_particles_X(m->p, c);
  const int bond = im->k.bond;
  for (pdk_index k = 0; k < n; ++k) {
    const double(*Bk)[3] = (const double(*)[3])(basis + 9 * (size_t)k);
    const double *pk = psi + bs[k] + k;
    /* q_k = sum_j w_kj o^{kj} (V_k in every component without the bond correction) */
    double q[3] = {0, 0, 0};
    for (pdk_index jj = 0; jj <= (pdk_index)(bs[k + 1] - bs[k]); ++jj) {
      const pdk_index pj = jj == 0 ? k : bj[bs[k] + jj - 1];
      double o[3];
      vc1_factor(X, dim, bond, k, pj, o);
      for (int c = 0; c < dim; ++c)
        q[c] += vol[k] * vol[pj] / im->vfam[k] * o[c];
    }
    for (int e = 0; e < off[k + 1] - off[k]; ++e) {
      Ap[off[k] + e] = (int)nnz;
      int len = 0;
      for (pdk_index mm = 0; mm <= (pdk_index)(bs[k + 1] - bs[k]); ++mm) {
        const pdk_index mi = mm == 0 ? k : bj[bs[k] + mm - 1];
        const double(*Bm)[3] = (const double(*)[3])(basis + 9 * (size_t)mi);
        for (int r = 0; r < off[mi + 1] - off[mi]; ++r) {
          double dot = 0.0;
          for (int c = 0; c < dim; ++c)
            dot += Bm[r][c] * (bond ? q[c] : 1.0) * Bk[e][c];
          col[len++] = (row_val){off[mi] + r, (bond ? 1.0 : vol[k]) * pk[mm] * dot};
        }
      }
      qsort(col, (size_t)len, sizeof *col, row_val_cmp);
      for (int t = 0; t < len; ++t) {
        Ai[nnz] = col[t].row;
        Ax[nnz++] = col[t].val;
      }
    }
  }
  Ap[nu] = (int)nnz;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  umfpack_di_defaults(control);
  galerkin_area(m);
  if (nu > 0) {
    PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_symbolic(nu, nu, Ap, Ai, Ax, &symbolic, control, info));
    PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_numeric(Ap, Ai, Ax, symbolic, &numeric, control, info));
    const double *A[3] = {NULL, NULL, NULL};
    for (int c = 0; c < dim; ++c)
      A[c] = pdk_particles_field_data(m->p, "area", c);
    for (pdk_index i = 0; i < n; ++i) {
      const double(*Bi)[3] = (const double(*)[3])(basis + 9 * (size_t)i);
      for (int r = 0; r < off[i + 1] - off[i]; ++r) {
        double dot = 0.0;
        for (int c = 0; c < dim; ++c)
          dot += Bi[r][c] * A[c][i];
        rhs[off[i] + r] = -dot;
      }
    }
    PDK_UMFPACK_CALL_GOTO(
        ctx, umfpack_di_solve(UMFPACK_A, Ap, Ai, Ax, sol, rhs, numeric, control, info));
    for (pdk_index i = 0; i < n; ++i) {
      const double(*Bi)[3] = (const double(*)[3])(basis + 9 * (size_t)i);
      for (int c = 0; c < dim; ++c) {
        double v = 0.0;
        for (int r = 0; r < off[i + 1] - off[i]; ++r)
          v += Bi[r][c] * sol[off[i] + r];
        im->alpha[(size_t)c * n + i] = v;
      }
    }
  }
  /* the corrected table: dN^{kji} += psi^{ki} alpha_k for every j */
  {
    const double *alpha = im->alpha;
    double *d = im->d;
    const int64_t *dstart = im->dstart;
#pragma omp parallel for default(none) shared(n, bs, bj, psi, alpha, d, dstart, dim, X, bond)      \
    schedule(static) num_threads(ctx->num_threads)
    for (pdk_index k = 0; k < n; ++k) {
      const int nm = (int)(bs[k + 1] - bs[k]) + 1;
      const double *pk = psi + bs[k] + k;
      double *dk = d + dstart[k];
      for (int j = 0; j < nm; ++j) {
        double o[3];
        vc1_factor(X, dim, bond, k, j == 0 ? k : bj[bs[k] + j - 1], o);
        for (int i = 0; i < nm; ++i)
          for (int c = 0; c < dim; ++c)
            dk[((size_t)j * nm + i) * dim + c] += pk[i] * alpha[(size_t)c * n + k] * o[c];
      }
    }
  }
cleanup:
  if (numeric) umfpack_di_free_numeric(&numeric);
  if (symbolic) umfpack_di_free_symbolic(&symbolic);
  free(psi);
  free(off);
  free(basis);
  free(Ap);
  free(Ai);
  free(Ax);
  free(rhs);
  free(sol);
  free(col);
  return err;
}

static int galerkin_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  const pdk_model_opts *o = &m->opts;
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  const pdk_law_info *law = pdk_law_info_of(o->law);
  PDK_CHECK(dim == 2 || dim == 3, ctx, PDK_ERR_UNSUPPORTED,
            "galerkin model: 2-D (plane strain) or 3-D, not %d-D", dim);
  PDK_CHECK(law && (law->flags & PDK_LAWF_HYPERELASTIC), ctx, PDK_ERR_UNSUPPORTED,
            "galerkin model: the elastic laws (linear_elastic, svk, neo_hooke) are implemented; "
            "law %s is not yet",
            pdk_law_name(o->law));
  PDK_CHECK(o->critical_stretch == 0, ctx, PDK_ERR_UNSUPPORTED,
            "galerkin model: bond breaking is not implemented; set critical_stretch = 0");
  PDK_CHECK(o->stabilization == PDK_STAB_NONE, ctx, PDK_ERR_UNSUPPORTED,
            "galerkin model: it needs no stabilization (every family member is an integration "
            "point); set stabilization none");
  PDK_CHECK((unsigned)o->galerkin.basis <= PDK_GALERKIN_WLS, ctx, PDK_ERR_ARG,
            "galerkin model: basis %d unknown; use taylor (0) or wls (1)", (int)o->galerkin.basis);
  PDK_CHECK(o->galerkin.form == PDK_GALERKIN_BUBNOV, ctx, PDK_ERR_ARG,
            "galerkin model: form %d unknown; bubnov (0) is implemented (petrov-galerkin is not "
            "yet)",
            (int)o->galerkin.form);
  PDK_CHECK((unsigned)o->galerkin.correction <= PDK_GALERKIN_VC1, ctx, PDK_ERR_ARG,
            "galerkin model: correction %d unknown; use none (0) or vc1 (1)",
            (int)o->galerkin.correction);
  PDK_CHECK(o->galerkin.bond == 0 || o->galerkin.bond == 1, ctx, PDK_ERR_ARG,
            "galerkin model: bond %d unknown; use 0 (none) or 1 (the bond-mapping correction)",
            o->galerkin.bond);
  if (o->stencil == PDK_STENCIL_AUTO)
    snprintf(m->stencil_why, sizeof m->stencil_why, "the galerkin model has no stencil path");
  galerkin_impl *im = calloc(1, sizeof *im);
  PDK_CHECK(im, ctx, PDK_ERR_MEMORY, "out of memory creating the galerkin model");
  m->impl = im;
  const pdk_index n = im->n = pdk_particles_count(p);
  im->num_blocks = ((int64_t)n + PDK_GALERKIN_BLOCK - 1) / PDK_GALERKIN_BLOCK;
  im->k.dim = dim;
  im->k.basis = (int)o->galerkin.basis;
  im->k.bond = o->galerkin.bond;
  im->k.law = (int)o->law;
  im->k.lambda = o->bulk_modulus - 2.0 * o->shear_modulus / 3.0;
  im->k.mu = o->shear_modulus;
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  im->num_members = (int64_t)n + nb;
  const size_t nn = (size_t)(n > 0 ? n : 1);
  im->rev = malloc((size_t)(nb > 0 ? nb : 1) * sizeof(int32_t));
  im->dstart = malloc(nn * sizeof(int64_t));
  im->vfam = malloc(nn * sizeof(double));
  im->W = calloc(nn, sizeof(double));
  im->G =
      malloc((size_t)dim * (size_t)(im->num_members > 0 ? im->num_members : 1) * sizeof(double));
  im->block_energy = calloc((size_t)(im->num_blocks > 0 ? im->num_blocks : 1), sizeof(double));
  PDK_CHECK(im->rev && im->dstart && im->vfam && im->W && im->G && im->block_energy, ctx,
            PDK_ERR_MEMORY, "galerkin model: out of memory for %lld bonds", (long long)nb);
  /* rev: the member index of k in the family of j, by a scan of j's list */
  pdk_index missing = -1;
  for (pdk_index k = 0; k < n && missing < 0; ++k)
    for (pdk_bond_index b = bs[k]; b < bs[k + 1]; ++b) {
      const pdk_index j = bj[b];
      pdk_bond_index e = bs[j];
      while (e < bs[j + 1] && bj[e] != k)
        ++e;
      if (e == bs[j + 1]) {
        missing = k;
        break;
      }
      im->rev[b] = (int32_t)(e - bs[j] + 1);
    }
  PDK_CHECK(missing < 0, ctx, PDK_ERR_ARG,
            "galerkin model: the families are not symmetric (particle id %lld has a neighbour "
            "whose family does not hold it); build them with one horizon",
            (long long)pdk_particles_id(p)[missing]);
  pdk_index big = -1;
  for (pdk_index k = 0; k < n && big < 0; ++k)
    if (bs[k + 1] - bs[k] >= PDK_GALERKIN_MAX_MEMBERS) big = k;
  PDK_CHECK(big < 0, ctx, PDK_ERR_UNSUPPORTED,
            "galerkin model: particle id %lld has %lld neighbours, more than the %d the passes "
            "take (and its shape functions would need %.3g MB); lower the horizon",
            (long long)pdk_particles_id(p)[big], big >= 0 ? (long long)(bs[big + 1] - bs[big]) : 0LL,
            PDK_GALERKIN_MAX_MEMBERS - 1,
            big >= 0 ? 8e-6 * dim * (double)(bs[big + 1] - bs[big] + 1) * (bs[big + 1] - bs[big] + 1)
                     : 0.0);
  const double *vol = pdk_particles_volume(p);
  int64_t total = 0;
  for (pdk_index k = 0; k < n; ++k) {
    const int64_t nm = (int64_t)(bs[k + 1] - bs[k]) + 1;
    im->dstart[k] = total;
    total += nm * nm * dim;
    double v = vol[k];
    for (pdk_bond_index b = bs[k]; b < bs[k + 1]; ++b)
      v += vol[bj[b]];
    im->vfam[k] = v;
  }
  im->d = malloc((size_t)(total > 0 ? total : 1) * sizeof(double));
  PDK_CHECK(im->d, ctx, PDK_ERR_MEMORY,
            "galerkin model: out of memory for the shape-function derivatives (%.3g GB: N^2 dim "
            "doubles per family)",
            (double)total * 8e-9);
  PDK_CALL(pdk_particles_field_add(p, "F", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "area", PDK_F64, dim));
  pdk_galerkin_arrays a;
  galerkin_arrays(m, &a);
  pdk_index bad = 0;
  {
    const pdk_galerkin_consts *k = &im->k;
    const int64_t nblk = im->num_blocks;
    const pdk_kernel_table *kt = &ctx->kernels;
#pragma omp parallel for default(none) shared(a, k, nblk, n, kt) schedule(static)                   \
    num_threads(ctx->num_threads) reduction(+ : bad)
    for (int64_t b = 0; b < nblk; ++b) {
      const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
      const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
      bad += kt->galerkin_shape(k, &a, i0, i1);
    }
  }
  PDK_CHECK(bad == 0, ctx, PDK_ERR_ARG,
            "galerkin model: %d (family, point) moment matrices are singular: a family has too "
            "few members off one line (plane in 3-D) around one of its points; raise the horizon",
            (int)bad);
  if (o->galerkin.correction == PDK_GALERKIN_VC1) PDK_CALL(galerkin_vc1(m));
  galerkin_area(m);
  /* F at the reference state */
  for (int r = 0; r < dim; ++r)
    for (int c = 0; c < dim; ++c) {
      double *F = pdk_particles_field_data(p, "F", r * dim + c);
      for (pdk_index i = 0; i < n; ++i)
        F[i] = r == c ? 1.0 : 0.0;
    }
  return PDK_SUCCESS;
}

static int galerkin_force(pdk_model *m, int commit, double *energy) {
  (void)commit; /* no history */
  galerkin_impl *im = m->impl;
  pdk_galerkin_arrays a;
  galerkin_arrays(m, &a);
  const pdk_galerkin_consts *k = &im->k;
  const int64_t nb = im->num_blocks;
  const pdk_index n = im->n;
  double *W = im->W, *be = im->block_energy;
  pdk_index bad = 0;
  const pdk_kernel_table *kt = &m->ctx->kernels;
#pragma omp parallel default(none) shared(a, k, nb, n, W, be, kt) num_threads(m->ctx->num_threads)   \
    reduction(+ : bad)
  {
#pragma omp for schedule(static)
    for (int64_t b = 0; b < nb; ++b) {
      const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
      const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
      bad += kt->galerkin_pass1(k, &a, 0, i0, i1);
      double e = 0.0;
      for (pdk_index i = i0; i < i1; ++i)
        e += W[i];
      be[b] = e;
    }
#pragma omp for schedule(static)
    for (int64_t b = 0; b < nb; ++b) {
      const pdk_index i0 = (pdk_index)(b * PDK_GALERKIN_BLOCK);
      const pdk_index i1 = i0 + PDK_GALERKIN_BLOCK < n ? i0 + PDK_GALERKIN_BLOCK : n;
      kt->galerkin_pass2(k, &a, 0, i0, i1);
    }
  }
  m->num_flagged = bad;
  if (energy) {
    double e = 0.0;
    for (int64_t b = 0; b < nb; ++b)
      e += be[b];
    *energy = e;
  }
  return PDK_SUCCESS;
}

static const pdk_model_ops pdk_model_ops_galerkin = {
    .setup = galerkin_setup, .force = galerkin_force, .destroy = galerkin_destroy};

static const pdk_model_ops *galerkin_ops_for(const pdk_model_opts *o) {
  (void)o;
  return &pdk_model_ops_galerkin;
}

static const char *const galerkin_scene_keys[] = {"model.law", "model.galerkin", NULL};

const pdk_model_kind_info pdk_model_kind_galerkin = {
    .kind = PDK_MODEL_GALERKIN,
    .name = "galerkin",
    .caps = PDK_KIND_SCENE | PDK_KIND_SHEAR | PDK_KIND_LAWS,
    /* f_i depends on the members of every family holding i: within two family hops */
    .hops = 2,
    .scene_stabilization = PDK_STAB_NONE,
    .scene_keys = galerkin_scene_keys,
    /* measured on the patch test (2-D, ~20 neighbours): the derivative table dominates */
    .mem_point = 1024,
    .mem_bond = 400,
    .mem_bond_float = 400,
    .mem_newton_bond = 250,
    .ops_for = galerkin_ops_for};
