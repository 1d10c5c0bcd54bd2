/* Correspondence, total and semi-total Lagrangian (model_corr.c): what follows the breaking of
 * bonds in a commit pass (changed rows reshaped, families detached, histories remapped, released
 * energy booked), and the semi-TL compacted bond list. */
#include <math.h>
#include <string.h>

#include "model_corr_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

/* semi-TL: rebuilds the compacted list from the intact bonds of the list the passes walk now (the
 * families' CSR with the model's bond state before the first compaction). Row order and entry
 * order are kept. */
static int corr_compact(pdk_model *m) {
  corr_impl *c = m->impl;
  pdk_ctx *ctx = m->ctx;
  pdk_corr_arrays a;
  pdk_corr_arrays_of(m, &a);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const int nt = ctx->num_threads;
  const pdk_bond_index *old_start = a.bond_start;
  const pdk_index *old_j = a.bond_j;
  const double *old_omega = a.bond_omega;
  const uint8_t *old_alive = a.bond_alive;
  pdk_bond_index *start = pdk_alloc_aligned((size_t)n + 1, sizeof *start);
  PDK_CHECK(start, ctx, PDK_ERR_MEMORY, "out of memory compacting the bond list (semi-TL)");
#pragma omp parallel for default(none) shared(old_start, old_alive, start, n, num_blocks)          \
    schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    for (pdk_index i = i0; i < i1; ++i) {
      pdk_bond_index count = 0;
      for (pdk_bond_index b = old_start[i]; b < old_start[i + 1]; ++b)
        count += old_alive[b] != 0;
      start[i + 1] = count;
    }
  }
  start[0] = 0;
  for (pdk_index i = 0; i < n; ++i)
    start[i + 1] += start[i];
  const pdk_bond_index len = start[n];
  const size_t alloc = (size_t)(len > 0 ? len : 1);
  pdk_index *bj = pdk_alloc_aligned(alloc, sizeof *bj);
  double *omega = pdk_alloc_aligned(alloc, sizeof *omega);
  uint8_t *alive = pdk_alloc_aligned(alloc, 1);
  if (!bj || !omega || !alive) {
    pdk_free_aligned(start);
    pdk_free_aligned(bj);
    pdk_free_aligned(omega);
    pdk_free_aligned(alive);
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory compacting the bond list (semi-TL): %lld bonds",
                             (long long)len);
  }
#pragma omp parallel for default(none)                                                             \
    shared(old_start, old_j, old_omega, old_alive, start, bj, omega, alive, n, num_blocks)         \
        schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    for (pdk_index i = i0; i < i1; ++i) {
      pdk_bond_index out = start[i];
      for (pdk_bond_index b = old_start[i]; b < old_start[i + 1]; ++b) {
        if (!old_alive[b]) continue;
        bj[out] = old_j[b];
        omega[out] = old_omega[b];
        alive[out] = 1;
        ++out;
      }
    }
  }
  pdk_corr_free_compacted(c);
  c->c_start = start;
  c->c_j = bj;
  c->c_omega = omega;
  c->c_alive = alive;
  c->c_len = len;
  c->c_dead = 0;
  m->num_compactions++;
  return PDK_SUCCESS;
}

/* semi-TL with a compacted list: copies the broken state of the rows that lost bonds in this pass
 * back to the model's bond state over the families' bonds. The compacted row is a subsequence of
 * the families' row in the same order, so one forward walk pairs the entries. */
static void corr_sync_bond_state(pdk_model *m) {
  corr_impl *c = m->impl;
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const int nt = m->ctx->num_threads;
  const pdk_bond_index *fam_start = pdk_families_bond_start(m->fam);
  const pdk_index *fam_j = pdk_families_bond_j(m->fam);
  const pdk_bond_index *c_start = c->c_start;
  const pdk_index *c_j = c->c_j;
  const uint8_t *c_alive = c->c_alive;
  const uint8_t *changed = c->changed;
  uint8_t *alive = m->bond_alive;
#pragma omp parallel for default(none)                                                             \
    shared(fam_start, fam_j, c_start, c_j, c_alive, changed, alive, n, num_blocks)                 \
        schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    for (pdk_index i = i0; i < i1; ++i) {
      if (!(changed[i] & 2u)) continue;
      pdk_bond_index b = fam_start[i];
      for (pdk_bond_index e = c_start[i]; e < c_start[i + 1]; ++e) {
        while (fam_j[b] != c_j[e])
          ++b;
        if (!c_alive[e]) alive[b] = 0;
        ++b;
      }
    }
  }
}

/* After the break kernel broke bonds in a commit pass: reshape the changed rows, detach
 * degenerate families (semi-TL), remap their Johnson-Cook histories (break_stress continuous) and
 * book the released energy (its total, sum_i V_i dw_broken_i
 * summed in block order, into *released), keep the bond state current, compact in batches
 * (semi-TL). `broken` is what the break kernel broke. */
int pdk_corr_after_breaking(pdk_model *m, const pdk_corr_consts *k, pdk_bond_index broken,
                            double *released) {
  corr_impl *c = m->impl;
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = c->num_blocks;
  const int nt = m->ctx->num_threads;
  pdk_corr_arrays a;
  pdk_corr_arrays_of(m, &a);
  pdk_bond_index total = broken;
  for (;;) {
    pdk_index detached = 0;
#pragma omp parallel for default(none) shared(a, k, n, num_blocks) reduction(+ : detached)        \
    schedule(static) num_threads(nt)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      CORR_BLOCK_RANGE(blk, n, i0, i1);
      detached += pdk_kernel_corr_reshape_ref(k, &a, i0, i1);
    }
    if (!detached) break;
    pdk_bond_index cut = 0;
#pragma omp parallel for default(none) shared(a, k, n, num_blocks) reduction(+ : cut)             \
    schedule(static) num_threads(nt)
    for (pdk_index blk = 0; blk < num_blocks; ++blk) {
      CORR_BLOCK_RANGE(blk, n, i0, i1);
      cut += pdk_kernel_corr_cut_ref(k, &a, i0, i1);
    }
    total += cut;
  }
  m->num_broken += total;
  if (c->c_start) corr_sync_bond_state(m);
  const uint8_t *flag = a.flag;
  double *block_released = c->block_energy; /* free again: the pass's energy is summed */
  const int remap = m->opts.break_stress == PDK_BREAK_STRESS_CONTINUOUS;
  pdk_index flagged = 0;
#pragma omp parallel for default(none)                                                          \
    shared(a, k, n, num_blocks, flag, block_released, remap) reduction(+ : flagged)              \
    schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    CORR_BLOCK_RANGE(blk, n, i0, i1);
    block_released[blk] = pdk_kernel_corr_release_ref(k, &a, i0, i1, remap);
    for (pdk_index i = i0; i < i1; ++i)
      flagged += (flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) != 0;
  }
  m->num_flagged = flagged;
  double sum = 0.0;
  for (pdk_index blk = 0; blk < num_blocks; ++blk)
    sum += block_released[blk];
  *released = sum;
  if (m->opts.connectivity == PDK_CONNECTIVITY_SEMI_TL) {
    c->c_dead += total;
    if (c->c_dead > 0 && (double)c->c_dead > m->opts.compact_fraction * (double)c->c_len)
      PDK_CALL(corr_compact(m));
  }
  return PDK_SUCCESS;
}
