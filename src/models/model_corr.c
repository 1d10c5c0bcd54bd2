/* Correspondence model (non-ordinary state-based, total Lagrangian): the driver.
 *
 * Formulas and kernel contract: kernels/ref/corr.c. This file owns fields, threading, blocking and
 * the energy reduction:
 *   setup   declares "Kinv", "F", "A" (f64 x dim*dim, component [a][c] at a*dim + c) and "flag"
 *           (u8: PDK_CORR_FLAG_SPAN = the family does not span the space, PDK_CORR_FLAG_INVERTED
 *           = the law is undefined at F), computes omega per bond and K^-1 once (TL).
 *           Private arrays: bond_omega [num_bonds], W [n_pad] energy density, m [n_pad] weighted
 *           volume (stabilization only), num_alive [n] and s0_next [n_pad] (bond failure only).
 *   force   pass 1 (F, A, W) over all particles, then pass 2 (f, stabilization) over all
 *           particles; both are gathers over a particle's own family, split in fixed blocks of
 *           PDK_CORR_BLOCK particles, schedule(static). The strain energy sum_i V_i W_i is summed
 *           within each block in index order and then over blocks in block order, so it is bitwise
 *           the same for any thread count. A commit pass with critical stretch set then breaks
 *           bonds (LAMMPS s0 rule, the same as PMB) and swaps s0; the next pass 1 recomputes K^-1
 *           of every particle whose intact-bond count changed (broken bonds carry weight 0 in K,
 *           N, the force and the stabilization).
 *   Optimized kernels without hourglass stabilization (pdk_corr_pair_layout bit 32) read packed
 *   rows instead of gathering: ref4 (X, V) written here at setup, cur4 (x - X, 1) packed at the
 *   start of each force pass (its own barrier: both passes read neighbours' rows), and the
 *   pass-2 rows and own terms pass 1 writes (kernels/opt/corr_simd.h): 128 + 96 bytes per
 *   particle in double storage (the 128-byte pass-2 record), 64 + 96 in float, replacing the 80
 *   (40) bytes of kst and B.
 *   num_flagged counts particles with flag bit SPAN or INVERTED after a force pass (after setup:
 *   those whose family does not span). A flagged particle has F = A = 0 (F = 0 for SPAN only) and
 *   W = 0.
 *
 * Johnson-Cook law (law PDK_LAW_JC): setup also declares the history fields listed in
 * include/pdk/model.h ("cp_inv", "eps_p", "damage", ["temp_rise"], "failed", "eps_p_rate",
 * "w_plastic", "w_damage"); pass 1 calls pdk_jc_update_kernel (pdk_jc_update without the Cauchy
 * components) per particle, advancing the history in place in a commit pass and into a discarded
 * copy in a trial pass (kernels/ref/corr.c). Memory: 12 doubles + 1 byte per particle (13 with
 * temperature). Cost: one exponential-map update per particle per pass (an eigen-decomposition:
 * closed-form 2 x 2 in plane strain, cyclic Jacobi in 3-D; logs and exps), against a family loop
 * of tens of bonds: bench/README.md ("Ductile step") has the measured ratios.
 *
 * Johnson-Cook options (pdk_model_opts, include/pdk/model.h). stab_softening: fields
 * "stab_factor", "w_stab", "w_silling" and two scratch arrays (stab_prev, w_law; 16 bytes per
 * particle); pass 1 lowers the factors, and the block loop after pass 2 of a commit books what
 * the drop took from the Silling energy (kernels.h). damage_triaxiality family: fields "sigma_m"
 * (written by pass 1 of a commit) and "sigma_m_avg" (corr_pressure_average, one pass over the
 * intact bonds after each commit, so trial passes and the next commit read the same values).
 *
 * Bond breaking (bond state exists: critical stretch, or JC failure with failed_keeps_bonds = 0).
 * A commit pass runs the break kernel after pass 2 when there is something to decide: always with
 * a critical stretch (the s0 rule needs every bond's stretch), and with JC failure only when the
 * number of failed particles grew (a failed particle loses all its bonds in the pass it fails, so
 * older failures never break anything again). If bonds broke: the changed rows are reshaped (K, m
 * from the intact bonds, reference configuration); semi-TL detaches degenerate families (cut and
 * reshape until nothing more detaches); the released energy is booked into "w_broken"; semi-TL
 * may compact its list. Passes with nothing new cost nothing of this.
 *
 * semi-TL bond list. The families object is shared and never changed; the model keeps its own CSR
 * of intact bonds: c_start [n+1] (int64), c_j [len] (int32), c_omega [len] (double), c_alive
 * [len] (u8, so bonds broken since the last compaction can stay in the list with weight 0):
 * 8 bytes per particle + 13 bytes per bond still listed, allocated at the first compaction
 * (before it the passes walk the families' CSR with the model's bond state) and reallocated to the
 * intact count at each compaction (old and new lists coexist during it). Compaction is triggered
 * when the broken entries still listed exceed compact_fraction of the list, so its O(bonds) cost
 * comes in batches and never in a pass where nothing broke. A bond's entry order is kept, so every
 * sum runs over the same terms in the same order as in TL (where broken bonds add exact zeros),
 * which is why TL and semi-TL agree bit for bit until a particle is detached. The model's bond
 * state over the families' bonds (pdk_model_bond_alive, checkpoints) is kept current: rows that
 * lost bonds copy their compacted state back in the same pass. After a restore the model starts
 * without a compacted list (the bond state says everything) and compacts at the next batch.
 *
 * Zero-energy-mode control, and why this normalisation. Silling (CMAME 322 (2017) 42-57) adds to
 * the correspondence force state a term proportional to omega z, z = Y - F xi, with a dimensionless
 * coefficient times a bond-based stiffness. The codes read for this (not copied) normalise it
 * differently: Peridigm-derived correspondence code (PeriDoX/PeriLab's
 * computeCorrespondenceStabilityForce) uses 18 C_s K / (pi delta^5) omega z, omega unnormalised;
 * Peridynamics.jl uses C_s c_bond omega z / sum_j omega_ij (c_bond the PMB micromodulus, sum
 * without volumes, which is not dimensionally consistent); PeriFlakes uses p_stab omega z, with the
 * "C / w0" factor commented out. pdk uses k_i omega z with k_i = C_s c_d K / m_i, m_i = sum_j omega
 * V_j |xi|^2 the particle's weighted volume and c_d = 72/5 (3-D), 36/5 (2-D), so that
 *   - for omega = 1 and a full continuum family it equals the Peridigm coefficient
 *     18 C_s K / (pi delta^5) (3-D; 2-D: the plane-strain PMB micromodulus 72 K / (5 pi h delta^3)
 *     over delta), so coefficients carry over from the literature;
 *   - it is dimensionally consistent in 2-D and 3-D (volumes are length^3 in both);
 *   - it is invariant under omega -> c omega, like F and the correspondence force itself;
 *   - surface particles (smaller m) get stiffer bonds, as in LPS.
 * The Silling term is the gradient of E_s = sum_i V_i k_i/2 sum_j omega V_j |z_ij|^2 (F is the
 * least-squares fit of Y), so it conserves energy and angular momentum; its energy is included in
 * the strain energy. The hourglass form (Littlewood 2011, Peridigm's correspondence hourglass
 * force) projects the same vector on the current bond: k_i omega (delta/|xi|) (z.e) e, e = Y/|Y|;
 * it conserves linear and angular momentum but is not the gradient of an energy, and adds no
 * energy. C_s = opts.stab_coefficient for both.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "model_corr_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

static void corr_destroy(pdk_model *m) {
  corr_impl *c = m->impl;
  if (!c) return;
  pdk_free_aligned(c->bond_omega);
  pdk_free_aligned(c->W);
  pdk_free_aligned(c->m);
  pdk_free_aligned(c->num_alive);
  pdk_free_aligned(c->s0_next);
  pdk_free_aligned(c->block_energy);
  pdk_free_aligned(c->changed);
  pdk_free_aligned(c->detach);
  pdk_free_aligned(c->pair_d);
  pdk_free_aligned(c->pair_f);
  pdk_free_aligned(c->ref4);
  pdk_free_aligned(c->cur4);
  pdk_free_aligned(c->own);
  pdk_free_aligned(c->row);
  pdk_free_aligned(c->rowf);
  pdk_free_aligned(c->stab_prev);
  pdk_free_aligned(c->w_law);
  pdk_corr_free_compacted(c);
  free(c);
  m->impl = NULL;
}

/* damage_triaxiality family: sigma_m_avg_i = (V_i sigma_m_i + sum_b omega_b V_j sigma_m_j) /
 * (V_i + sum_b omega_b V_j) over i's intact bonds to particles that have not failed (a failed
 * particle carries no stress; it is a hole, not a zero pressure). Each i reads its own row only,
 * in bond order: the same bits for any thread count. Run after each commit pass (and at setup),
 * so every pass 1 until the next commit reads the same averages. */
static void corr_pressure_average(pdk_model *m) {
  corr_impl *c = m->impl;
  pdk_corr_arrays a;
  pdk_corr_arrays_of(m, &a);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const int nt = m->ctx->num_threads;
  const double *sm = a.sigma_m;
  double *avg = pdk_particles_field_data(m->p, "sigma_m_avg", 0);
#pragma omp parallel for default(none) shared(a, sm, avg, n, num_blocks) schedule(static)          \
    num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    for (pdk_index i = i0; i < i1; ++i) {
      double sw = a.volume[i], sp = a.volume[i] * sm[i];
      for (pdk_bond_index b = a.bond_start[i]; b < a.bond_start[i + 1]; ++b) {
        const pdk_index j = a.bond_j[b];
        if ((a.bond_alive && !a.bond_alive[b]) || a.failed[j]) continue;
        const double w = a.bond_omega[b] * a.volume[j];
        sw += w;
        sp += w * sm[j];
      }
      avg[i] = sp / sw;
    }
  }
}

static int corr_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const pdk_model_opts *o = &m->opts;
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_index n_pad = pdk_particles_count_padded(p);
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  const double horizon = pdk_families_horizon(m->fam);

  corr_impl *c = calloc(1, sizeof *c);
  PDK_CHECK(c, ctx, PDK_ERR_MEMORY, "out of memory creating the correspondence model");
  m->impl = c;
  c->shape = ctx->kernels.corr_shape;
  c->pass1 = ctx->kernels.corr_pass1;
  c->pass2 = ctx->kernels.corr_pass2;
  c->num_blocks = (n + PDK_CORR_BLOCK - 1) / PDK_CORR_BLOCK;
  /* streamed once per sweep, 8 B per bond (4 KiB pages: bench/log.md, "Transparent huge
   * pages, dropped") */
  c->bond_omega = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(double));
  c->W = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
  c->block_energy = pdk_alloc_aligned((size_t)c->num_blocks, sizeof(double));
  int ok = c->bond_omega && c->W && c->block_energy;
  if (o->stabilization != PDK_STAB_NONE) {
    c->m = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    ok = ok && c->m;
  }
  if (m->bond_alive) {
    c->num_alive = pdk_alloc_aligned((size_t)n_pad, sizeof(int32_t));
    c->changed = pdk_alloc_aligned((size_t)n_pad, 1);
    ok = ok && c->num_alive && c->changed;
    if (o->connectivity == PDK_CONNECTIVITY_SEMI_TL) {
      c->detach = pdk_alloc_aligned((size_t)n_pad, 1);
      ok = ok && c->detach;
    }
  }
  if (m->s0) {
    c->s0_next = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    ok = ok && c->s0_next;
  }
  if (o->stab_softening) {
    c->stab_prev = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    c->w_law = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    ok = ok && c->stab_prev && c->w_law;
  }
  /* Pass-2 data: each of B, G, Bf, Gf is dim*dim arrays of n_pad; kst one. */
  const unsigned layout = pdk_corr_pair_layout(
      (int)o->stabilization, o->precision == PDK_PRECISION_FLOAT, ctx->kernels.corr_opt);
  const int dd = dim * dim;
  const size_t nd = (size_t)((layout & 1u) ? 1 : 0) + (size_t)((layout & 2u) ? dd : 0) +
                    (size_t)((layout & 4u) ? dd : 0);
  const size_t nf = (size_t)((layout & 8u) ? dd : 0) + (size_t)((layout & 16u) ? dd : 0);
  if (nd) {
    double *q = c->pair_d = pdk_alloc_aligned(nd * (size_t)n_pad, sizeof(double));
    ok = ok && q;
    if (q) {
      if (layout & 1u) c->kst = q, q += n_pad;
      for (int t = 0; t < dd && (layout & 2u); ++t)
        c->B[t] = q, q += n_pad;
      for (int t = 0; t < dd && (layout & 4u); ++t)
        c->G[t] = q, q += n_pad;
    }
  }
  if (nf) {
    float *q = c->pair_f = pdk_alloc_aligned(nf * (size_t)n_pad, sizeof(float));
    ok = ok && q;
    if (q) {
      for (int t = 0; t < dd && (layout & 8u); ++t)
        c->Bf[t] = q, q += n_pad;
      for (int t = 0; t < dd && (layout & 16u); ++t)
        c->Gf[t] = q, q += n_pad;
    }
  }
  if (layout & 32u) {
    /* ref4, cur4 and the rows are read at the neighbours' places */
    c->ref4 = pdk_alloc_aligned(4 * (size_t)n_pad, sizeof(double));
    c->cur4 = pdk_alloc_aligned(4 * (size_t)n_pad, sizeof(double));
    c->own = pdk_alloc_aligned(4 * (size_t)n_pad, sizeof(double));
    if (o->precision == PDK_PRECISION_FLOAT)
      c->rowf = pdk_alloc_aligned((size_t)n_pad, sizeof(pdk_corr_rowf));
    else
      c->row = pdk_alloc_aligned((size_t)n_pad, sizeof(pdk_corr_row));
    ok = ok && c->ref4 && c->cur4 && c->own && (c->rowf || c->row);
    if (ok) {
      const double *V = pdk_particles_volume(p);
      for (int d = 0; d < dim; ++d) {
        const double *X = pdk_particles_X(p, d);
        for (pdk_index i = 0; i < n; ++i)
          c->ref4[4 * (size_t)i + (size_t)d] = X[i];
      }
      for (pdk_index i = 0; i < n; ++i)
        c->ref4[4 * (size_t)i + 3] = V[i];
    }
  }
  c->c_len = nb;
  PDK_CHECK(ok, ctx, PDK_ERR_MEMORY,
            "out of memory for the correspondence model's arrays (%lld bonds, %d particles)",
            (long long)nb, (int)n);

  PDK_CALL(pdk_particles_field_add(p, "Kinv", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "F", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "A", PDK_F64, dim * dim));
  PDK_CALL(pdk_particles_field_add(p, "flag", PDK_U8, 1));
  if (m->bond_alive) PDK_CALL(pdk_particles_field_add(p, "w_broken", PDK_F64, 1));
  if (o->law == PDK_LAW_JC) {
    /* History: a field declared here starts virgin (zero, C_p^-1 = 1); one that exists already
     * (a store reused from an earlier model) is kept, as "x" is. */
    const int fresh = !pdk_particles_field_exists(p, "cp_inv");
    PDK_CALL(pdk_particles_field_add(p, "cp_inv", PDK_F64, 6));
    PDK_CALL(pdk_particles_field_add(p, "eps_p", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "damage", PDK_F64, 1));
    if (o->jc.thermal) PDK_CALL(pdk_particles_field_add(p, "temp_rise", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "failed", PDK_U8, 1));
    PDK_CALL(pdk_particles_field_add(p, "eps_p_rate", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "w_plastic", PDK_F64, 1));
    PDK_CALL(pdk_particles_field_add(p, "w_damage", PDK_F64, 1));
    if (o->stab_softening) {
      const int fresh_factor = !pdk_particles_field_exists(p, "stab_factor");
      PDK_CALL(pdk_particles_field_add(p, "stab_factor", PDK_F64, 1));
      PDK_CALL(pdk_particles_field_add(p, "w_stab", PDK_F64, 1));
      PDK_CALL(pdk_particles_field_add(p, "w_silling", PDK_F64, 1));
      double *f = pdk_particles_field_data(p, "stab_factor", 0);
      if (fresh_factor)
        for (pdk_index i = 0; i < n_pad; ++i)
          f[i] = 1.0;
    }
    if (o->damage_triaxiality == PDK_TRIAX_FAMILY) {
      PDK_CALL(pdk_particles_field_add(p, "sigma_m", PDK_F64, 1));
      PDK_CALL(pdk_particles_field_add(p, "sigma_m_avg", PDK_F64, 1));
    }
    if (fresh)
      for (int t = 0; t < 3; ++t) {
        double *cp = pdk_particles_field_data(p, "cp_inv", t);
        for (pdk_index i = 0; i < n; ++i)
          cp[i] = 1.0;
      }
    const uint8_t *failed = pdk_particles_field_data(p, "failed", 0);
    for (pdk_index i = 0; i < n; ++i)
      c->failed_seen += failed[i] != 0;
  }

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
  k->horizon = horizon;
  k->span_rtol = PDK_CORR_SPAN_RTOL;
  k->s00 = o->critical_stretch;
  k->alpha = o->alpha;
  k->jc = o->law == PDK_LAW_JC ? &m->opts.jc : NULL;
  k->dt = 0.0;
  k->commit = 0;
  k->break_failed = o->law == PDK_LAW_JC && o->jc.damage && !o->failed_keeps_bonds;
  k->stab_floor = o->stab_softening ? o->stab_softening_floor : 0.0;

  /* Influence weight per bond (first touch in the pass order). A bond of zero length would give
   * omega = infinity (1/r) and a singular family; it is an input error. */
  pdk_corr_arrays a;
  pdk_corr_arrays_of(m, &a);
  const pdk_bond_index *bond_start = a.bond_start;
  const pdk_index *bond_j = a.bond_j;
  double *omega = c->bond_omega;
  const pdk_influence kind = o->influence;
  const double width = o->gaussian_width;
  const pdk_index num_blocks = c->num_blocks;
  const int nt = ctx->num_threads;
  pdk_index bad = n; /* first particle with a zero-length bond, n if none */
  /* clang-format off */
#pragma omp parallel for default(none) \
    shared(a, bond_start, bond_j, omega, kind, width, horizon, num_blocks, n, dim) \
    reduction(min : bad) schedule(static) num_threads(nt)
  /* clang-format on */
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = blk * PDK_CORR_BLOCK;
    const pdk_index i1 = i0 + PDK_CORR_BLOCK < n ? i0 + PDK_CORR_BLOCK : n;
    for (pdk_index i = i0; i < i1; ++i)
      for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
        const pdk_index j = bond_j[b];
        double r2 = 0.0;
        for (int d = 0; d < dim; ++d) {
          const double xi = a.X[d][j] - a.X[d][i];
          r2 += xi * xi;
        }
        const double r = sqrt(r2);
        /* Clamp at 0: a lattice point admitted at delta (1 + 1e-12) would get a weight of
         * -1e-12 from 1 - r/delta. */
        const double w = r > 0.0 ? fmax(pdk_influence_eval(kind, r, horizon, width), 0.0) : 0.0;
        omega[b] = isfinite(w) ? w : 0.0;
        if (!(r > 0.0) && i < bad) bad = i;
      }
  }
  if (bad < n) {
    const int64_t *id = pdk_particles_id(p);
    pdk_index j = -1;
    for (pdk_bond_index b = bond_start[bad]; b < bond_start[bad + 1]; ++b) {
      double r2 = 0.0;
      for (int d = 0; d < dim; ++d) {
        const double xi = a.X[d][bond_j[b]] - a.X[d][bad];
        r2 += xi * xi;
      }
      if (!(r2 > 0.0)) j = bond_j[b];
    }
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                             "correspondence model: particles with ids %lld and %lld sit at the "
                             "same reference position; remove duplicates before building families",
                             (long long)id[bad], (long long)(j >= 0 ? id[j] : -1));
  }

  /* Shape tensors, once (TL). */
  pdk_index flagged = 0;
#pragma omp parallel for default(none) shared(a, k, c, num_blocks, n)                           \
    reduction(+ : flagged) schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = blk * PDK_CORR_BLOCK;
    const pdk_index i1 = i0 + PDK_CORR_BLOCK < n ? i0 + PDK_CORR_BLOCK : n;
    flagged += c->shape(k, &a, i0, i1);
  }
  m->num_flagged = flagged;
  if (o->damage_triaxiality == PDK_TRIAX_FAMILY) corr_pressure_average(m); /* of a restored state */

  /* model.stencil: the lattice layout (src/models/model_stencil.c) for TL with no or Silling
   * stabilization; K^-1 and m above stay the general path's. When it is taken the packed rows
   * are not needed. */
  if (o->stencil != PDK_STENCIL_OFF) {
    const char *refusal = pdk_stencil_corr_refusal(o);
    if (refusal) {
      snprintf(m->stencil_why, sizeof m->stencil_why, "%s", refusal);
      PDK_CHECK(o->stencil != PDK_STENCIL_ON, ctx, PDK_ERR_UNSUPPORTED,
                "correspondence model: stencil on, but the stencil path does not apply: %s; use "
                "stencil auto (the general path then) or off",
                m->stencil_why);
    } else {
      PDK_CALL(pdk_stencil_model_setup(m, NULL, 0));
      PDK_CALL(pdk_stencil_corr_setup(m, c->bond_omega, o->precision == PDK_PRECISION_FLOAT));
    }
  }
  if (m->stencil) {
    pdk_free_aligned(c->ref4);
    pdk_free_aligned(c->cur4);
    pdk_free_aligned(c->own);
    pdk_free_aligned(c->row);
    pdk_free_aligned(c->rowf);
    pdk_free_aligned(c->pair_d);
    pdk_free_aligned(c->pair_f);
    c->ref4 = c->cur4 = c->own = NULL;
    c->row = NULL;
    c->rowf = NULL;
    c->pair_d = c->pair_f = NULL;
    c->kst = NULL;
    for (int t = 0; t < 9; ++t) {
      c->B[t] = c->G[t] = NULL;
      c->Bf[t] = c->Gf[t] = NULL;
    }
  }
  return PDK_SUCCESS;
}

/* Several ranks: the force and energy densities of every row, then the energy blocks summed as
 * the pass-2 loop sums them on one rank. */
static int corr_ranks_exchange(pdk_model *m, pdk_index num_blocks, pdk_index n) {
  corr_impl *c = m->impl;
  pdk_bond_index none = 0;
  PDK_CALL(pdk_model_ranks_finish(m, c->W, NULL, &none));
  const double *volume = pdk_particles_volume(m->p), *W = c->W;
  double *block_energy = c->block_energy;
#pragma omp parallel for default(none) shared(num_blocks, n, volume, W, block_energy)             \
    schedule(static) num_threads(m->ctx->num_threads)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    double e = 0.0;
    for (pdk_index i = i0; i < i1; ++i) e += volume[i] * W[i];
    block_energy[blk] = e;
  }
  return PDK_SUCCESS;
}

static int corr_force(pdk_model *m, int commit, double *energy) {
  corr_impl *c = m->impl;
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
  pdk_corr_arrays a;
  pdk_corr_arrays_of(m, &a);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const double *volume = a.volume;
  const double *W = c->W;
  const uint8_t *flag = a.flag;
  const uint8_t *failed = a.failed;
  double *block_energy = c->block_energy;
  const int nt = m->ctx->num_threads;
  pdk_index flagged = 0, num_failed = 0;
  void (*const pass1)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index) =
      c->pass1;
  void (*const pass2)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index) =
      c->pass2;
  const int dim = k->dim;
  double *cur4 = c->cur4;

  /* softened stabilization: what the commit pass's new factors took from the Silling energy */
  const int book = commit && a.stab_factor != NULL;

  pdk_stencil *st = m->stencil;
  if (st) PDK_CALL(pdk_stencil_corr_passes(m, st, k, &a));
  /* several ranks (src/models/model_ranks.c): pass 1 runs whole on every rank (its many
   * per-particle outputs need no exchange), pass 2 on this rank's rows [lo, hi), whose force and
   * energy densities the ranks then exchange; the energy blocks are summed after that */
  const int ranked = m->row_start != NULL;
  const pdk_index lo = ranked ? m->row_lo : 0, hi = ranked ? m->row_hi : n;

#pragma omp parallel default(none)                                                              \
    shared(a, k, num_blocks, n, volume, W, flag, failed, block_energy, pass1, pass2, dim, cur4,  \
               st, book, lo, hi) reduction(+ : flagged, num_failed) num_threads(nt)
  {
    if (cur4) {
      /* the displacement rows pass 1 and pass 2 read from neighbours (implicit barrier) */
#pragma omp for schedule(static)
      for (pdk_index blk = 0; blk < num_blocks; ++blk) {
        CORR_BLOCK_RANGE(blk, n, i0, i1);
        pdk_corr_pack_cur(dim, a.X, a.x, cur4, i0, i1);
      }
    }
    if (!st) {
#pragma omp for schedule(static)
      for (pdk_index blk = 0; blk < num_blocks; ++blk) {
        CORR_BLOCK_RANGE(blk, n, i0, i1);
        pass1(k, &a, i0, i1);
      }
    }
    /* implicit barrier: pass 2 reads A and F of neighbours in other blocks */
#pragma omp for schedule(static)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      CORR_BLOCK_RANGE(blk, n, i0, i1);
      const pdk_index p0 = i0 < lo ? lo : i0, p1 = i1 > hi ? hi : i1;
      if (!st && p0 < p1) pass2(k, &a, p0, p1);
      if (book)
        for (pdk_index i = i0; i < i1; ++i) {
          const double S = W[i] - a.w_law[i], f0 = a.stab_prev[i], f1 = a.stab_factor[i];
          if (f0 != f1) a.w_stab[i] += 0.5 * (f0 - f1) * (a.w_silling[i] / f0 + S / f1);
          a.w_silling[i] = S;
        }
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
  if (ranked) PDK_CALL(corr_ranks_exchange(m, num_blocks, n));
  m->num_flagged = flagged;
  m->num_failed = num_failed;
  if (commit && flagged && m->opts.law == PDK_LAW_JC) {
    pdk_index first;
    const pdk_index count = pdk_model_corr_jc_first_failure(m, flag, failed, &first);
    if (count) return pdk_model_corr_jc_failure_error(m, first, count, NULL);
  }
  if (energy) {
    double e = 0.0;
    for (pdk_index blk = 0; blk < num_blocks; ++blk)
      e += block_energy[blk];
    *energy = e;
  }

  /* Bond breaking, commit passes only: state read by this pass, written for the next. */
  const int new_failures = k->break_failed && num_failed != c->failed_seen;
  if (commit && m->bond_alive && (m->s0 || new_failures)) {
    pdk_bond_index broken = 0;
#pragma omp parallel for default(none) shared(a, k, num_blocks, n) reduction(+ : broken)         \
    schedule(static) num_threads(nt)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      CORR_BLOCK_RANGE(blk, n, i0, i1);
      broken += pdk_kernel_corr_break_ref(k, &a, i0, i1);
    }
    c->failed_seen = num_failed;
    if (m->s0) {
      double *t = m->s0; /* the next pass reads the critical stretches just written */
      m->s0 = c->s0_next;
      c->s0_next = t;
    }
    if (broken) {
      /* The energy returned is that of the state the next step starts from: the pass's, less
       * what the breaks released (the plastic and damage work of the jump of F stays in it until
       * the next commit books it), so external work = kinetic + strain + plastic + damage +
       * breaking holds at every step, not only one step after a break. */
      double released = 0.0;
      PDK_CALL(pdk_corr_after_breaking(m, k, broken, &released));
      if (energy) *energy -= released;
      if (m->stencil) pdk_stencil_mask_rows(m, m->stencil, c->changed);
    }
  }
  if (commit && a.sigma_m_avg) corr_pressure_average(m);
  return PDK_SUCCESS;
}

/* Checkpoints: no state of its own beyond the bond state (src/models/model_state.c); a checkpoint of the
 * updated-Lagrangian connectivity (its rebuild state, src/models/model_corr_ul.c) does not fit. */
static int corr_state_check(const pdk_model *m, pdk_state *s) {
  (void)m;
  if (pdk_state_has(s, "ul_rebuilt"))
    return pdk_state_mismatch(s, "it is of a ul (updated-Lagrangian) model, this simulation's "
                                 "connectivity is not ul");
  return PDK_SUCCESS;
}

static const char *corr_ranks_refusal(const pdk_model_opts *o);

const pdk_model_ops pdk_model_ops_corr = {.setup = corr_setup,
                                          .force = corr_force,
                                          .destroy = corr_destroy,
                                          .state_check = corr_state_check,
                                          .derived = pdk_model_corr_derived,
                                          .ranks = 1,
                                          .ranks_refusal = corr_ranks_refusal};

/* Several ranks split pass 2 only; a law with history, semi-TL's compacted list and the particle
 * order the stencil options choose are not split yet. */
static const char *corr_ranks_refusal(const pdk_model_opts *o) {
  if (o->law == PDK_LAW_JC) return "a law with history (model.law jc)";
  if (o->connectivity != PDK_CONNECTIVITY_TL) return "model.connectivity semi_tl";
  if (o->stencil != PDK_STENCIL_OFF)
    return "model.stencil auto or on (set model.stencil off: on a lattice auto also renumbers "
           "the particles)";
  return NULL;
}

static const pdk_model_ops *corr_ops_for(const pdk_model_opts *o) {
  return o->connectivity == PDK_CONNECTIVITY_UL ? &pdk_model_ops_corr_ul : &pdk_model_ops_corr;
}

/* The particles are ordered by lattice rows where the stencil path will walk them in site order
 * (its per-particle end reads K^-1 and writes F, A: bench/README.md "Particle order on the
 * correspondence stencil path"). */
static int corr_stencil_rows(const pdk_model_opts *o) {
  return o->stencil != PDK_STENCIL_OFF && !pdk_stencil_corr_refusal(o);
}

/* stencil on: the stencil path implements tl connectivity and stabilization none or silling. */
static const char *corr_stencil_refusal(const pdk_model_opts *o) {
  if (o->connectivity == PDK_CONNECTIVITY_UL)
    return "correspondence model with ul connectivity: the stencil path implements tl only (ul "
           "rebuilds its families in the current configuration); use stencil off or auto, or "
           "connectivity tl";
  if (o->connectivity != PDK_CONNECTIVITY_TL)
    return "correspondence model with semi_tl connectivity: the stencil path implements tl only "
           "(semi_tl compacts its bond list); use stencil off or auto, or connectivity tl";
  if (o->stabilization == PDK_STAB_HOURGLASS)
    return "correspondence model with hourglass stabilization: the stencil path implements "
           "stabilization none and silling only (the hourglass force needs |Y| per bond); use "
           "stencil off or auto, or stabilization silling";
  return NULL;
}

static int corr_hyperelastic(const pdk_model_opts *o) {
  const pdk_law_info *l = pdk_law_info_of(o->law);
  return l && (l->flags & PDK_LAWF_HYPERELASTIC) && o->stabilization != PDK_STAB_HOURGLASS;
}

static int corr_unstabilized(const pdk_model_opts *o) { return o->stabilization == PDK_STAB_NONE; }

static const char *const corr_scene_keys[] = {"model.influence",
                                              "model.gaussian_width",
                                              "model.stabilization",
                                              "model.stabilization_coefficient",
                                              "model.law",
                                              "model.connectivity",
                                              NULL};
static const pdk_model_derived_info corr_derived[] = {{"von_mises", "stress"}, {NULL, NULL}};

const pdk_model_kind_info pdk_model_kind_corr = {
    .kind = PDK_MODEL_CORRESPONDENCE,
    .name = "correspondence",
    .caps = PDK_KIND_SCENE | PDK_KIND_SHEAR | PDK_KIND_STENCIL | PDK_KIND_MATERIALS |
            PDK_KIND_LAWS | PDK_KIND_FLOAT | PDK_KIND_SPAN_FLAG,
    .hops = 2,
    .scene_stabilization = PDK_STAB_SILLING,
    .scene_keys = corr_scene_keys,
    .derived = corr_derived,
    .mem_point = 1024,
    .mem_bond = 16,
    .mem_bond_float = 16,
    .mem_newton_bond = 250,
    .ops_for = corr_ops_for,
    .stencil_rows = corr_stencil_rows,
    .hyperelastic = corr_hyperelastic,
    .unstabilized = corr_unstabilized,
    .stencil_refusal = corr_stencil_refusal};
