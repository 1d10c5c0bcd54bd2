/* Correspondence model, updated-Lagrangian (UL) connectivity: the driver.
 *
 * Formulas and kernel contract: kernels/ref/corr_ul.c; when to use it and what it costs:
 * docs/connectivity.md. This file owns the fields, the families of the last rebuild, threading,
 * blocking, the energy reduction and the rebuild policy.
 *
 * Fields (declared at creation; the last four describe the configuration r of the last rebuild
 * and are reset to the initial configuration by every pdk_model_create, because the families it
 * is given are those of "X"):
 *   "F"          f64 x dim*dim  total deformation gradient F^ F_ref (component [a][c] at a*d + c)
 *   "A"          f64 x dim*dim  tau_r M^-1, the tensor of the force state
 *   "flag"       u8             PDK_CORR_FLAG_* bits, as the TL model
 *   "ul_X"       f64 x dim      positions at the last rebuild [length]
 *   "ul_volume"  f64            volumes there, J_ref V0 [length^3]
 *   "ul_F"       f64 x dim*dim  F_ref, the deformation gradient there [-]
 *   "ul_J"       f64            J_ref = det F_ref [-]
 * plus the Johnson-Cook history of include/pdk/model.h with law JC. Private: bond_omega
 * [num_bonds] (of the families the passes walk), W [n_pad], and with stabilization m [n_pad] and
 * F_inc [dim*dim][n_pad] (F^, read by neighbours in pass 2). No "Kinv": UL never inverts K.
 *
 * Force pass: pass 1 and pass 2 over fixed blocks of PDK_UL_BLOCK particles, schedule(static),
 * the strain energy summed per block in index order and over blocks in block order, as the TL
 * driver: results are bitwise the same for any thread count.
 *
 * Rebuild policy (opts.ul_skin = s, a fraction of the horizon delta). After a committing pass,
 * with u_i = x_i - X_r,i the displacement since the last rebuild and c the centre of the bounding
 * box of the u_i (per component: (min + max)/2, so a common translation does not count), the
 * families are rebuilt when max_i |u_i - c| > s delta / 2. Two particles then moved relative to
 * each other by less than s delta since the rebuild, which bounds how stale the families are:
 * every pair now closer than delta (1 - s) is bonded, and every bonded pair is closer than
 * delta (1 + s). The check costs one read of x and X_r per committing pass (min/max reductions,
 * exact in any order). Rigid rotations do count (they trigger harmless rebuilds).
 * Weights. A bond of the families rebuilt at the positions x gets w = omega(min(r0, r)), r0 =
 * |X_j - X_i| its initial length and r = |x_j - x_i| its length at the rebuild (the initial
 * families: omega(r0)). Taking omega(r) alone (an Eulerian kernel) made rebuilt runs clump and
 * blow up in tension: the pair attraction omega(r) r then grows as a pair closes wherever it
 * decreases with r (beyond delta / 4 for the cubic weight), Swegle's tensile instability. With the
 * minimum a stretched bond keeps its initial weight (its attraction grows with r like a spring's)
 * and a compressed bond takes the weight of its current length, the stable choice in compression
 * (tests/t133_ul_tensile_instability.c, docs/connectivity.md). Influence functions that do not
 * vanish at the horizon (constant, 1/r, 1/r^2) still switch bonds on and off at full weight as
 * pairs cross the horizon, and clump under rebuilds in tension: use linear or cubic with rebuilds.
 * A rebuild, at the positions x of the committing pass that just ran:
 *   1. families from x (pdk_families_build_coords, the same horizon), minus the bonds whose
 *      initial segment crosses a pre-crack, omega per bond as above;
 *   2. per particle: F_ref <- F (this pass's total F), J_ref <- det F, V_r <- J_ref V0, X_r <- x.
 *      A flagged particle (SPAN or INVERTED) keeps its F_ref and J_ref;
 *   3. the rebuild shape (flag SPAN, m) over the new families.
 * The new families are built before anything is overwritten, so a failed rebuild (memory) leaves
 * the model as it was. F is continuous across a rebuild (at x = X_r the new F^ is I to round-off),
 * so the law's stress and energy are too; the force changes, because the family and the
 * quadrature weights do, and so does the Silling term's energy (z restarts at 0).
 *
 * Pre-cracks: the families keep the pre-cracks they were built with (in the initial
 * configuration); a rebuild removes every new bond whose initial segment X_i X_j crosses one
 * (pdk_families_remove_cut), so a pre-crack never heals (tests/t134_ul_precrack_restart.c).
 * Checkpoints (the kind's part of /model, src/core/state.h): the rebuilt families (ul_bond_start,
 * ul_bond_j; none before the first rebuild) and the rebuild count; ul_state_load takes them back
 * and recomputes the weights (from "ul_X", the positions they were weighed at) and the rebuild
 * shape, so a restored run continues bitwise.
 * Not supported (refused at creation or documented): bond breaking (critical stretch, Johnson-
 * Cook failure breaking bonds): a rebuild would re-bond broken pairs; float storage.
 */
#include <math.h>
#include <string.h>

#include "space/families_impl.h"
#include "kernels.h"
#include "model_impl.h"
#include "model_stencil.h"
#include "core/state.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

/* Particles per block: the unit of work of both passes and of the energy reduction. */
#define PDK_UL_BLOCK 256

#define UL_BLOCK_RANGE(blk, n, i0, i1)                                                             \
  const pdk_index i0 = (blk)*PDK_UL_BLOCK;                                                         \
  const pdk_index i1 = i0 + PDK_UL_BLOCK < (n) ? i0 + PDK_UL_BLOCK : (n)

typedef struct ul_impl {
  pdk_corr_consts k;
  pdk_families *own;    /* families of the last rebuild; NULL before the first: m->fam */
  double *bond_omega;   /* [num_bonds of the families the passes walk] omega(|xi|) >= 0 */
  double *W;            /* [n_pad] strain energy density of the last pass */
  double *m;            /* [n_pad] weighted volume at the rebuild; NULL without stabilization */
  double *F_inc;        /* [dim*dim * n_pad] F^; NULL without stabilization */
  double *block_energy; /* [num_blocks] */
  pdk_index num_blocks;
} ul_impl;

static pdk_families *ul_families(const pdk_model *m) {
  const ul_impl *c = m->impl;
  return c && c->own ? c->own : m->fam;
}

static void ul_arrays(pdk_model *m, pdk_corr_ul_arrays *ua) {
  ul_impl *c = m->impl;
  pdk_particles *p = m->p;
  pdk_corr_arrays *a = &ua->base;
  const int dim = pdk_particles_dim(p);
  const pdk_index n_pad = pdk_particles_count_padded(p);
  pdk_families *fam = ul_families(m);
  memset(ua, 0, sizeof *ua);
  a->bond_start = pdk_families_bond_start(fam);
  a->bond_j = pdk_families_bond_j(fam);
  a->bond_omega = c->bond_omega;
  a->bond_alive = NULL;
  for (int d = 0; d < dim; ++d) {
    a->X[d] = pdk_particles_field_data(p, "ul_X", d);
    a->x[d] = pdk_particles_field_data(p, "x", d);
    a->f[d] = pdk_particles_field_data(p, "f", d);
  }
  a->volume = pdk_particles_field_data(p, "ul_volume", 0);
  for (int t = 0; t < dim * dim; ++t) {
    a->F[t] = pdk_particles_field_data(p, "F", t);
    a->A[t] = pdk_particles_field_data(p, "A", t);
    ua->F_ref[t] = pdk_particles_field_data(p, "ul_F", t);
    ua->F_inc[t] = c->F_inc ? c->F_inc + (size_t)t * (size_t)n_pad : NULL;
  }
  ua->J_ref = pdk_particles_field_data(p, "ul_J", 0);
  a->m = c->m;
  a->flag = pdk_particles_field_data(p, "flag", 0);
  a->W = c->W;
  if (m->opts.law == PDK_LAW_JC) pdk_corr_jc_arrays_of(p, a);
}

static void ul_destroy(pdk_model *m) {
  ul_impl *c = m->impl;
  if (!c) return;
  pdk_families_destroy(&c->own);
  pdk_free_aligned(c->bond_omega);
  pdk_free_aligned(c->W);
  pdk_free_aligned(c->m);
  pdk_free_aligned(c->F_inc);
  pdk_free_aligned(c->block_energy);
  free(c);
  m->impl = NULL;
}

/* omega per bond of `fam`: w = omega(r), r = |X_j - X_i| over the initial coordinates X (the
 * store's "X"), or, with x != NULL (a rebuild at the positions x), r = min(|X_j - X_i|,
 * |x_j - x_i|): a bond stretched since the start keeps its initial weight (Lagrangian), a
 * compressed one takes the weight of its current length (see the file comment, "Weights").
 * Returns the first particle with a zero-length bond in X, or n when there is none (such a bond
 * gets weight 0). */
static pdk_index ul_omega(pdk_model *m, const pdk_families *fam, const double *const x[3],
                          double *omega) {
  const ul_impl *c = m->impl;
  const int dim = pdk_particles_dim(m->p);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_bond_index *bond_start = pdk_families_bond_start(fam);
  const pdk_index *bond_j = pdk_families_bond_j(fam);
  const pdk_influence kind = m->opts.influence;
  const double width = m->opts.gaussian_width, horizon = c->k.horizon;
  const pdk_index num_blocks = c->num_blocks;
  const double *X0 = pdk_particles_X(m->p, 0), *X1 = pdk_particles_X(m->p, 1);
  const double *X2 = dim == 3 ? pdk_particles_X(m->p, 2) : NULL;
  const double *x0 = x ? x[0] : NULL, *x1 = x ? x[1] : NULL, *x2 = x ? x[2] : NULL;
  const int nt = m->ctx->num_threads;
  pdk_index bad = n;
  /* clang-format off */
#pragma omp parallel for default(none) \
    shared(bond_start, bond_j, omega, kind, width, horizon, num_blocks, n, dim, X0, X1, X2, x0, \
           x1, x2) \
    reduction(min : bad) schedule(static) num_threads(nt)
  /* clang-format on */
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    UL_BLOCK_RANGE(blk, n, i0, i1);
    for (pdk_index i = i0; i < i1; ++i)
      for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
        const pdk_index j = bond_j[b];
        const double d0 = X0[j] - X0[i], d1 = X1[j] - X1[i], d2 = dim == 3 ? X2[j] - X2[i] : 0.0;
        const double r0 = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        double r = r0;
        if (x0) {
          const double e0 = x0[j] - x0[i], e1 = x1[j] - x1[i], e2 = dim == 3 ? x2[j] - x2[i] : 0.0;
          r = fmin(r0, sqrt(e0 * e0 + e1 * e1 + e2 * e2));
        }
        /* clamped at 0 as in the TL driver (a lattice point admitted at delta (1 + 1e-12)) */
        const double w = r > 0.0 ? fmax(pdk_influence_eval(kind, r, horizon, width), 0.0) : 0.0;
        omega[b] = isfinite(w) ? w : 0.0;
        if (!(r0 > 0.0) && i < bad) bad = i;
      }
  }
  return bad;
}

/* Rebuild shape over the current families; returns how many do not span. */
static pdk_index ul_shape(pdk_model *m) {
  ul_impl *c = m->impl;
  pdk_corr_ul_arrays ua;
  ul_arrays(m, &ua);
  const pdk_corr_consts *k = &c->k;
  const pdk_index n = pdk_particles_count(m->p), num_blocks = c->num_blocks;
  const int nt = m->ctx->num_threads;
  pdk_index flagged = 0;
#pragma omp parallel for default(none) shared(ua, k, num_blocks, n) reduction(+ : flagged)       \
    schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    UL_BLOCK_RANGE(blk, n, i0, i1);
    flagged += pdk_kernel_corr_ul_shape_ref(k, &ua, i0, i1);
  }
  return flagged;
}

static int ul_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const pdk_model_opts *o = &m->opts;
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_index n_pad = pdk_particles_count_padded(p);
  if (o->stencil != PDK_STENCIL_OFF)
    snprintf(m->stencil_why, sizeof m->stencil_why, "%s", pdk_stencil_corr_refusal(o));
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  PDK_CHECK(o->precision == PDK_PRECISION_DOUBLE, ctx, PDK_ERR_UNSUPPORTED,
            "correspondence model, ul connectivity: float storage is not implemented; use "
            "precision double");
  PDK_CHECK(!m->bond_alive, ctx, PDK_ERR_UNSUPPORTED,
            "correspondence model, ul connectivity: bonds cannot break in ul (a rebuild in the "
            "current configuration would bond broken pairs again), but critical_stretch is %g%s; "
            "use tl or semi_tl connectivity, or no critical stretch%s",
            o->critical_stretch,
            o->law == PDK_LAW_JC ? " or the Johnson-Cook law breaks the bonds of failed particles"
                                 : "",
            o->law == PDK_LAW_JC ? " and failed_keeps_bonds = 1 (or jc.damage = 0)" : "");

  ul_impl *c = calloc(1, sizeof *c);
  PDK_CHECK(c, ctx, PDK_ERR_MEMORY, "out of memory creating the correspondence model (ul)");
  m->impl = c;
  c->num_blocks = (n + PDK_UL_BLOCK - 1) / PDK_UL_BLOCK;
  c->bond_omega = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(double));
  c->W = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
  c->block_energy = pdk_alloc_aligned((size_t)c->num_blocks, sizeof(double));
  int ok = c->bond_omega && c->W && c->block_energy;
  if (o->stabilization != PDK_STAB_NONE) {
    c->m = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    c->F_inc = pdk_alloc_aligned((size_t)dim * (size_t)dim * (size_t)n_pad, sizeof(double));
    ok = ok && c->m && c->F_inc;
  }
  PDK_CHECK(ok, ctx, PDK_ERR_MEMORY,
            "out of memory for the correspondence model's arrays (ul; %lld bonds, %d particles)",
            (long long)nb, (int)n);
  if (c->F_inc) memset(c->F_inc, 0, (size_t)dim * (size_t)dim * (size_t)n_pad * sizeof(double));

  PDK_CALL(pdk_particles_field_add(p, "F", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "A", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "flag", PDK_U8, 1));
  PDK_CALL(pdk_particles_field_add(p, "ul_X", PDK_F64, dim));
  PDK_CALL(pdk_particles_field_add(p, "ul_volume", PDK_F64, 1));
  PDK_CALL(pdk_particles_field_add(p, "ul_F", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "ul_J", PDK_F64, 1));
  if (o->law == PDK_LAW_JC) {
    /* History as in the TL driver: a field declared here starts virgin, one that exists is kept. */
    const int fresh = !pdk_particles_field_exists(p, "cp_inv");
    PDK_CALL(pdk_particles_field_add(p, "cp_inv", PDK_F64, 6));
    PDK_CALL(pdk_particles_field_add(p, "eps_p", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "damage", PDK_F64, 1));
    if (o->jc.thermal) PDK_CALL(pdk_particles_field_add(p, "temp_rise", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "failed", PDK_U8, 1));
    PDK_CALL(pdk_particles_field_add(p, "eps_p_rate", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "w_plastic", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "w_damage", PDK_F64, 1));
    if (fresh)
      for (int t = 0; t < 3; ++t) {
        double *cp = pdk_particles_field_data(p, "cp_inv", t);
        for (pdk_index i = 0; i < n; ++i)
          cp[i] = 1.0;
      }
  }
  /* The reference of the given families: the initial configuration. */
  for (int a = 0; a < dim; ++a)
    memcpy(pdk_particles_field_data(p, "ul_X", a), pdk_particles_X(p, a),
           (size_t)n * sizeof(double));
  memcpy(pdk_particles_field_data(p, "ul_volume", 0), pdk_particles_volume(p),
         (size_t)n * sizeof(double));
  for (int t = 0; t < dim * dim; ++t) {
    double *Fr = pdk_particles_field_data(p, "ul_F", t);
    const double v = t % (dim + 1) == 0 ? 1.0 : 0.0;
    for (pdk_index i = 0; i < n; ++i)
      Fr[i] = v;
  }
  double *J = pdk_particles_field_data(p, "ul_J", 0);
  for (pdk_index i = 0; i < n; ++i)
    J[i] = 1.0;

  pdk_corr_consts *k = &c->k;
  k->dim = dim;
  k->law = (int)o->law;
  k->mu = o->shear_modulus;
  k->lambda = o->bulk_modulus - 2.0 * o->shear_modulus / 3.0;
  k->stab = (int)o->stabilization;
  k->stab_modulus = o->stab_coefficient * (dim == 3 ? 72.0 / 5.0 : 36.0 / 5.0) * o->bulk_modulus;
  k->lambda_p = m->mat_lambda; /* multi-material (NULL for one material) */
  k->mu_p = m->mat_lambda ? m->mat_shear : NULL;
  k->stab_p = m->mat_stab;
  k->horizon = pdk_families_horizon(m->fam);
  k->span_rtol = PDK_CORR_SPAN_RTOL;
  k->jc = o->law == PDK_LAW_JC ? &m->opts.jc : NULL;

  const pdk_index bad = ul_omega(m, m->fam, NULL, c->bond_omega);
  if (bad < n)
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                             "correspondence model: particle id %lld has a neighbour at the same "
                             "reference position; remove duplicates before building families",
                             (long long)pdk_particles_id(p)[bad]);
  m->num_flagged = ul_shape(m);
  return PDK_SUCCESS;
}

/* Rebuild at the positions of the last force pass (see the file comment). */
static int ul_rebuild_now(pdk_model *m) {
  ul_impl *c = m->impl;
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  pdk_families *fam = NULL;
  double *omega = NULL;
  const double *x[3] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1),
                        dim == 3 ? pdk_particles_field_data(p, "x", 2) : NULL};
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = c->k.horizon;
  PDK_CALL(pdk_families_build_coords(ctx, dim, n, x, pdk_particles_id(p), &fo, &fam));
  {
    /* Pre-cracks live in the initial configuration: a pair whose initial segment crosses one is
     * never bonded again, whatever its current distance. */
    const pdk_precrack *pc = NULL;
    const int num_pc = pdk_families_precracks(m->fam, &pc);
    const double *X0[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                           dim == 3 ? pdk_particles_X(p, 2) : NULL};
    const int e = pdk_families_remove_cut(fam, dim, X0, pc, num_pc);
    if (e) {
      pdk_families_destroy(&fam);
      return e;
    }
  }
  const pdk_bond_index nb = pdk_families_num_bonds(fam);
  omega = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(double));
  if (!omega) {
    pdk_families_destroy(&fam);
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory for the bond weights of a ul rebuild (%lld bonds)",
                             (long long)nb);
  }
  (void)ul_omega(m, fam, x, omega); /* particles that met: weight 0 */

  /* The new reference: F_ref, J_ref, V_r, X_r. */
  {
    double *Xr[3] = {pdk_particles_field_data(p, "ul_X", 0), pdk_particles_field_data(p, "ul_X", 1),
                     dim == 3 ? pdk_particles_field_data(p, "ul_X", 2) : NULL};
    double *Vr = pdk_particles_field_data(p, "ul_volume", 0);
    double *Jr = pdk_particles_field_data(p, "ul_J", 0);
    const double *V0 = pdk_particles_volume(p);
    const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
    double *Fr[9];
    const double *F[9];
    for (int t = 0; t < dim * dim; ++t) {
      Fr[t] = pdk_particles_field_data(p, "ul_F", t);
      F[t] = pdk_particles_field_data(p, "F", t);
    }
    const int nt = ctx->num_threads;
    const pdk_index num_blocks = c->num_blocks;
#pragma omp parallel for default(none) shared(Xr, x, Vr, Jr, V0, flag, Fr, F, n, dim, num_blocks)  \
    schedule(static) num_threads(nt)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      UL_BLOCK_RANGE(blk, n, i0, i1);
      for (pdk_index i = i0; i < i1; ++i) {
        for (int a = 0; a < dim; ++a)
          Xr[a][i] = x[a][i];
        if (flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) continue;
        double J;
        if (dim == 2)
          J = F[0][i] * F[3][i] - F[1][i] * F[2][i];
        else
          J = F[0][i] * (F[4][i] * F[8][i] - F[5][i] * F[7][i]) -
              F[1][i] * (F[3][i] * F[8][i] - F[5][i] * F[6][i]) +
              F[2][i] * (F[3][i] * F[7][i] - F[4][i] * F[6][i]);
        if (!(J > 0.0) || !isfinite(J)) continue;
        for (int t = 0; t < dim * dim; ++t)
          Fr[t][i] = F[t][i];
        Jr[i] = J;
        Vr[i] = J * V0[i];
      }
    }
  }
  pdk_families_destroy(&c->own);
  c->own = fam;
  pdk_free_aligned(c->bond_omega);
  c->bond_omega = omega;
  (void)ul_shape(m); /* SPAN bits and m for the new families; counted by the next pass */
  m->num_rebuilds++;
  return PDK_SUCCESS;
}

/* 1 when a particle moved more than ul_skin delta / 2 since the last rebuild, relative to the
 * centre of the displacements' bounding box. */
static int ul_over_skin(pdk_model *m) {
  ul_impl *c = m->impl;
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const double *x0 = pdk_particles_field_data(p, "x", 0), *x1 = pdk_particles_field_data(p, "x", 1);
  const double *x2 = dim == 3 ? pdk_particles_field_data(p, "x", 2) : x0;
  const double *X0 = pdk_particles_field_data(p, "ul_X", 0);
  const double *X1 = pdk_particles_field_data(p, "ul_X", 1);
  const double *X2 = dim == 3 ? pdk_particles_field_data(p, "ul_X", 2) : X0;
  const int nt = m->ctx->num_threads;
  double lo0 = INFINITY, lo1 = INFINITY, lo2 = INFINITY;
  double hi0 = -INFINITY, hi1 = -INFINITY, hi2 = -INFINITY;
#pragma omp parallel for default(none) shared(x0, x1, x2, X0, X1, X2, n) schedule(static)          \
    reduction(min                                                                                  \
              : lo0, lo1, lo2) reduction(max                                                       \
                                         : hi0, hi1, hi2) num_threads(nt)
  for (pdk_index i = 0; i < n; ++i) {
    const double u0 = x0[i] - X0[i], u1 = x1[i] - X1[i], u2 = x2[i] - X2[i];
    lo0 = fmin(lo0, u0), hi0 = fmax(hi0, u0);
    lo1 = fmin(lo1, u1), hi1 = fmax(hi1, u1);
    lo2 = fmin(lo2, u2), hi2 = fmax(hi2, u2);
  }
  const double c0 = 0.5 * (lo0 + hi0), c1 = 0.5 * (lo1 + hi1), c2 = 0.5 * (lo2 + hi2);
  double r2 = 0.0;
#pragma omp parallel for default(none) shared(x0, x1, x2, X0, X1, X2, n) schedule(static)          \
    firstprivate(c0, c1, c2) reduction(max                                                         \
                                       : r2) num_threads(nt)
  for (pdk_index i = 0; i < n; ++i) {
    const double u0 = x0[i] - X0[i] - c0, u1 = x1[i] - X1[i] - c1, u2 = x2[i] - X2[i] - c2;
    r2 = fmax(r2, u0 * u0 + u1 * u1 + u2 * u2);
  }
  const double limit = 0.5 * m->opts.ul_skin * c->k.horizon;
  return !(r2 <= limit * limit); /* NaN positions count as moved */
}

/* Why pass 1 flagged particle i before reaching the law, as its test (kernels/ref/corr_ul.c): N
 * not positive or M not spanning at the current positions (F is not written then); NULL when
 * the family passed it (the law failed at the F the pass wrote). */
static const char *ul_family_why(const pdk_corr_ul_arrays *ua, const pdk_corr_consts *k,
                                 pdk_index i, char *buf, size_t len) {
  const pdk_corr_arrays *a = &ua->base;
  const int d = k->dim;
  double N[3][3] = {{0}}, M[3][3] = {{0}};
  for (pdk_bond_index b = a->bond_start[i]; b < a->bond_start[i + 1]; ++b) {
    const pdk_index j = a->bond_j[b];
    const double wv = a->bond_omega[b] * a->volume[j];
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) {
        N[r][c] += wv * (a->x[r][j] - a->x[r][i]) * (a->X[c][j] - a->X[c][i]);
        M[r][c] += wv * (a->x[r][j] - a->x[r][i]) * (a->x[c][j] - a->x[c][i]);
      }
  }
  double detN = N[0][0] * N[1][1] - N[0][1] * N[1][0], detM = M[0][0] * M[1][1] - M[0][1] * M[1][0];
  double trM = M[0][0] + M[1][1];
  if (d == 3) {
    detN = N[0][0] * (N[1][1] * N[2][2] - N[1][2] * N[2][1]) -
           N[0][1] * (N[1][0] * N[2][2] - N[1][2] * N[2][0]) +
           N[0][2] * (N[1][0] * N[2][1] - N[1][1] * N[2][0]);
    detM = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
           M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
           M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    trM += M[2][2];
  }
  const double mean = trM / d, scale = d == 2 ? mean * mean : mean * mean * mean;
  if (detN > 0.0 && isfinite(detN) && trM > 0.0 && isfinite(detM) && detM >= k->span_rtol * scale)
    return NULL;
  snprintf(buf, len,
           "its family is turned inside out or collapsed at the current positions (det N = %.3g, "
           "N the weighted sum of current x reference bond vectors)",
           detN);
  return buf;
}

static int ul_passes(pdk_model *m, int commit, double *energy);

/* The rebuild's energy: the strain energy of a trial pass over the new families at the same
 * positions (the committing pass's "f" kept: the next half kick reads it), subtracted from the
 * committing pass's, booked in m->rebuild_work. */
static int ul_rebuild_booked(pdk_model *m, double e_before) {
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  const size_t bytes = (size_t)pdk_particles_count(p) * sizeof(double);
  double *f_save = malloc(dim * bytes + 1);
  PDK_CHECK(f_save, m->ctx, PDK_ERR_MEMORY, "out of memory booking a ul rebuild's energy");
  for (int c = 0; c < dim; ++c)
    memcpy(f_save + (size_t)c * (bytes / sizeof(double)), pdk_particles_field_data(p, "f", c), bytes);
  int err = ul_rebuild_now(m);
  double e_after = e_before;
  if (!err) err = ul_passes(m, 0, &e_after);
  for (int c = 0; c < dim; ++c)
    memcpy(pdk_particles_field_data(p, "f", c), f_save + (size_t)c * (bytes / sizeof(double)), bytes);
  free(f_save);
  if (!err) m->rebuild_work += e_before - e_after;
  return err;
}

static int ul_force(pdk_model *m, int commit, double *energy) {
  double e = 0.0;
  PDK_CALL(ul_passes(m, commit, &e));
  if (energy) *energy = e;
  if (commit && m->opts.ul_skin > 0.0 && ul_over_skin(m)) PDK_CALL(ul_rebuild_booked(m, e));
  return PDK_SUCCESS;
}

static int ul_passes(pdk_model *m, int commit, double *energy) {
  ul_impl *c = m->impl;
  pdk_corr_consts kc = c->k;
  const pdk_corr_consts *k = &kc;
  kc.commit = commit;
  if (m->opts.law == PDK_LAW_JC) {
    const pdk_jc_params *jc = &m->opts.jc;
    const int rate_needed = jc->C != 0.0 || (jc->damage && jc->D4 != 0.0);
    if (m->dt > 0.0)
      kc.dt = m->dt;
    else if (commit)
      PDK_CHECK(!rate_needed, m->ctx, PDK_ERR_ARG,
                "correspondence model: the Johnson-Cook rate terms (C = %g, D4 = %g) need the time "
                "step; call pdk_model_set_dt before a committing force pass",
                jc->C, jc->damage ? jc->D4 : 0.0);
    else
      kc.dt = INFINITY; /* trial before any step: the quasi-static limit */
  }
  pdk_corr_ul_arrays ua;
  ul_arrays(m, &ua);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const double *volume = pdk_particles_volume(m->p); /* W is per initial volume */
  const double *W = c->W;
  const uint8_t *flag = ua.base.flag;
  const uint8_t *failed = ua.base.failed;
  double *block_energy = c->block_energy;
  const int nt = m->ctx->num_threads;
  pdk_index flagged = 0, num_failed = 0;

#pragma omp parallel default(none)                                                              \
    shared(ua, k, num_blocks, n, volume, W, flag, failed, block_energy)                         \
    reduction(+ : flagged, num_failed) num_threads(nt)
  {
#pragma omp for schedule(static)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      UL_BLOCK_RANGE(blk, n, i0, i1);
      pdk_kernel_corr_ul_pass1_ref(k, &ua, i0, i1);
    }
    /* implicit barrier: pass 2 reads A and F^ of neighbours in other blocks */
#pragma omp for schedule(static)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      UL_BLOCK_RANGE(blk, n, i0, i1);
      pdk_kernel_corr_ul_pass2_ref(k, &ua, i0, i1);
      double e = 0.0;
      for (pdk_index i = i0; i < i1; ++i) {
        e += volume[i] * W[i];
        flagged += (flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) != 0;
      }
      if (failed)
        for (pdk_index i = i0; i < i1; ++i)
          num_failed += failed[i] != 0;
      block_energy[blk] = e;
    }
  }
  m->num_flagged = flagged;
  m->num_failed = num_failed;
  if (commit && flagged && m->opts.law == PDK_LAW_JC) {
    pdk_index first;
    const pdk_index count = pdk_model_corr_jc_first_failure(m, flag, failed, &first);
    if (count) {
      char why[160];
      return pdk_model_corr_jc_failure_error(m, first, count,
                                             ul_family_why(&ua, k, first, why, sizeof why));
    }
  }
  if (energy) {
    double e = 0.0;
    for (pdk_index blk = 0; blk < num_blocks; ++blk)
      e += block_energy[blk];
    *energy = e;
  }
  return PDK_SUCCESS;
}

/* Makes `fam` (owned from now on; NULL: the families given at creation) the families the passes
 * walk, as a rebuild left them: weights from "ul_X", rebuild shape; num_rebuilds set. */
static int ul_restore(pdk_model *m, pdk_families *fam, long num_rebuilds) {
  ul_impl *c = m->impl;
  pdk_families *use = fam ? fam : m->fam;
  const pdk_bond_index nb = pdk_families_num_bonds(use);
  double *omega = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(double));
  if (!omega) {
    pdk_families_destroy(&fam);
    return pdk_ctx_error_set(m->ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory for the bond weights of restored ul families (%lld "
                             "bonds)",
                             (long long)nb);
  }
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  /* The positions of the last rebuild: the "x" the rebuild weighed its bonds with. */
  const double *xr[3] = {pdk_particles_field_data(p, "ul_X", 0),
                         pdk_particles_field_data(p, "ul_X", 1),
                         dim == 3 ? pdk_particles_field_data(p, "ul_X", 2) : NULL};
  (void)ul_omega(m, use, fam ? xr : NULL, omega);
  pdk_families_destroy(&c->own);
  c->own = fam;
  pdk_free_aligned(c->bond_omega);
  c->bond_omega = omega;
  (void)ul_shape(m);
  m->num_rebuilds = num_rebuilds;
  return PDK_SUCCESS;
}

static int ul_rebuild(pdk_model *m) {
  PDK_CALL(ul_force(m, 0, NULL)); /* F at the current x, history untouched */
  return ul_rebuild_now(m);
}

/* ---- checkpoint: the families of the last rebuild and the rebuild count ----------------------
 */

static int ul_state_save(const pdk_model *m, pdk_state *s) {
  const pdk_families *cur = ul_families(m);
  const int rebuilt = cur != m->fam;
  PDK_CALL(pdk_state_put_i64(s, "ul_rebuilt", rebuilt));
  PDK_CALL(pdk_state_put_i64(s, "ul_num_rebuilds", m->num_rebuilds));
  PDK_CALL(pdk_state_put_f64(s, "ul_rebuild_work", m->rebuild_work));
  if (rebuilt) {
    const pdk_index n = pdk_particles_count(m->p);
    PDK_CALL(pdk_state_put_array(s, "ul_bond_start", PDK_I64, (size_t)n + 1,
                                 pdk_families_bond_start(cur)));
    PDK_CALL(pdk_state_put_array(s, "ul_bond_j", PDK_I32, (size_t)pdk_families_num_bonds(cur),
                                 pdk_families_bond_j(cur)));
  }
  return PDK_SUCCESS;
}

static int ul_state_check(const pdk_model *m, pdk_state *s) {
  int64_t v;
  (void)m;
  if (!pdk_state_has(s, "ul_rebuilt"))
    return pdk_state_mismatch(s, "this simulation's model is ul (updated-Lagrangian), the "
                                 "checkpoint's is not");
  PDK_CALL(pdk_state_get_i64(s, "ul_rebuilt", &v));
  return pdk_state_get_i64(s, "ul_num_rebuilds", &v);
}

/* After the fields, whose "ul_X" the weights are computed from: the families of the last rebuild,
 * or the initial families when none was stored. */
static int ul_state_load(pdk_model *m, pdk_state *s) {
  int err = PDK_SUCCESS;
  pdk_bond_index *bs = NULL;
  pdk_index *bj = NULL;
  pdk_families *fam = NULL;
  int64_t rebuilt = 0, num_rebuilds = 0;
  pdk_ctx *ctx = m->ctx;
  const pdk_index n = pdk_particles_count(m->p);
  PDK_CALL(pdk_state_get_i64(s, "ul_rebuilt", &rebuilt));
  PDK_CALL(pdk_state_get_i64(s, "ul_num_rebuilds", &num_rebuilds));
  m->rebuild_work = 0.0; /* files from before the booking: none booked */
  if (pdk_state_has(s, "ul_rebuild_work"))
    PDK_CALL(pdk_state_get_f64(s, "ul_rebuild_work", &m->rebuild_work));
  if (rebuilt) {
    bs = malloc(((size_t)n + 1) * sizeof *bs);
    PDK_CHECK_GOTO(bs, ctx, PDK_ERR_MEMORY, "out of memory reading ul families");
    PDK_CALL_GOTO(pdk_state_get_array(s, "ul_bond_start", PDK_I64, (size_t)n + 1, bs));
    PDK_CHECK_GOTO(bs[n] >= 0, ctx, PDK_ERR_IO, "checkpoint: ul_bond_start ends at %lld",
                   (long long)bs[n]);
    bj = malloc(((size_t)bs[n] + 1) * sizeof *bj);
    PDK_CHECK_GOTO(bj, ctx, PDK_ERR_MEMORY, "out of memory reading %lld ul bonds",
                   (long long)bs[n]);
    PDK_CALL_GOTO(pdk_state_get_array(s, "ul_bond_j", PDK_I32, (size_t)bs[n], bj));
    PDK_CALL_GOTO(pdk_families_from_csr(ctx, n, pdk_families_horizon(m->fam), bs, bj, &fam));
  }
  err = ul_restore(m, fam, (long)num_rebuilds); /* takes fam */
cleanup:
  free(bs);
  free(bj);
  return err;
}

/* Several ranks: refused (the families follow the motion; particles would migrate). */
static const char *ul_ranks_refusal(const pdk_model_opts *o) {
  (void)o;
  return "model.connectivity ul";
}

const pdk_model_ops pdk_model_ops_corr_ul = {.setup = ul_setup,
                                             .force = ul_force,
                                             .destroy = ul_destroy,
                                             .state_save = ul_state_save,
                                             .state_check = ul_state_check,
                                             .state_load = ul_state_load,
                                             .derived = pdk_model_corr_derived,
                                             .rebuild = ul_rebuild,
                                             .current_families = ul_families,
                                             .ranks_refusal = ul_ranks_refusal};
