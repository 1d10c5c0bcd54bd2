/* Force passes over several MPI ranks (docs/scaling.md).
 *
 * The first slice of the domain decomposition: every rank holds the whole body (particles,
 * families, bond state) and advances it the same way; the force passes, where the time goes, are
 * split. The particles, in their order (the cells' Morton order, or the lattice's rows: ranges of
 * it are compact pieces of the body), are cut into one contiguous range per rank with about equal
 * weights, a particle weighing its bond count + 1. A pass computes the rows of its rank's range
 * only, with the same kernels on the same rows as one rank does, and the ranks then exchange
 * their rows (MPI_Allgatherv, src/core/comm.c): the force density, the energy density, the next
 * critical stretches, and the bond state when a bond broke; a pass that gathers a per-particle
 * quantity first (the LPS dilatation) exchanges it before the rows that read it. A row's sum runs
 * over its family in the family's order, whichever rank computes it, and every sum over particles
 * (the energies in fixed blocks, the histories) runs on the exchanged arrays in index order as on
 * one rank: the results are bitwise those of one rank, for any rank and thread count.
 */
#include <stdlib.h>

#include "core/comm.h"
#include "model_impl.h"
#include "pdk/comm.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

int pdk_model_ranks_setup(pdk_model *m) {
  const int size = pdk_comm_size();
  if (size == 1) return PDK_SUCCESS;
  pdk_ctx *ctx = m->ctx;
  const char *why = m->ops->ranks_refusal ? m->ops->ranks_refusal(&m->opts) : NULL;
  PDK_CHECK(!why, ctx, PDK_ERR_UNSUPPORTED,
            "model kind '%s' with %s runs on one rank only so far; this run has %d ranks: "
            "run it without mpiexec (or with mpiexec -n 1)",
            m->info->name, why ? why : "", size);
  PDK_CHECK(m->ops->ranks, ctx, PDK_ERR_UNSUPPORTED,
            "model kind '%s' runs on one rank only so far (on several ranks pdk runs the kinds "
            "pmb, lps and correspondence); this run has %d ranks: "
            "run it without mpiexec (or with mpiexec -n 1)",
            m->info->name, size);
  PDK_CHECK(m->opts.layout != PDK_LAYOUT_SELL, ctx, PDK_ERR_UNSUPPORTED,
            "model.layout sell runs on one rank only so far; this run has %d ranks: use layout "
            "csr (the default), or run without mpiexec (or with mpiexec -n 1)",
            size);
  PDK_CHECK(m->opts.stencil != PDK_STENCIL_ON, ctx, PDK_ERR_UNSUPPORTED,
            "model.stencil on runs on one rank only so far; this run has %d ranks: use stencil "
            "off (several ranks then equal one rank with stencil off bit for bit; auto takes the "
            "general path on several ranks), or run without mpiexec (or with mpiexec -n 1)",
            size);
  m->row_start = malloc(2 * ((size_t)size + 1) * sizeof *m->row_start);
  PDK_CHECK(m->row_start, ctx, PDK_ERR_MEMORY, "out of memory for the ranks' particle ranges");
  m->bond_row_start = m->row_start + size + 1;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index n = pdk_particles_count(m->p);
  /* weight of the particles before i: bs[i] + i; the cut r is the first i whose weight reaches
   * r / size of the total (a binary search: bs is nondecreasing) */
  const double total = (double)bs[n] + (double)n;
  m->row_start[0] = 0;
  for (int r = 1; r < size; ++r) {
    const double target = total * r / size;
    pdk_index lo = (pdk_index)m->row_start[r - 1], hi = n;
    while (lo < hi) {
      const pdk_index mid = lo + (hi - lo) / 2;
      if ((double)bs[mid] + (double)mid < target) lo = mid + 1;
      else hi = mid;
    }
    m->row_start[r] = lo;
  }
  m->row_start[size] = n;
  for (int r = 0; r <= size; ++r) m->bond_row_start[r] = bs[m->row_start[r]];
  const int me = pdk_comm_rank();
  m->row_lo = (pdk_index)m->row_start[me];
  m->row_hi = (pdk_index)m->row_start[me + 1];
  return PDK_SUCCESS;
}

int pdk_model_ranks_gather(pdk_model *m, double *data) {
  if (!m->row_start || !data) return PDK_SUCCESS;
  return pdk_comm_allgather_rows(m->ctx, data, sizeof(double), m->row_start);
}

int pdk_model_ranks_finish(pdk_model *m, double *w, double *s0_next, pdk_bond_index *broken) {
  if (!m->row_start) return PDK_SUCCESS;
  const int dim = pdk_particles_dim(m->p);
  for (int c = 0; c < dim; ++c)
    PDK_CALL(pdk_model_ranks_gather(m, pdk_particles_field_data(m->p, "f", c)));
  PDK_CALL(pdk_model_ranks_gather(m, w));
  PDK_CALL(pdk_model_ranks_gather(m, s0_next));
  int64_t all = (int64_t)*broken;
  PDK_CALL(pdk_comm_sum_i64(m->ctx, &all));
  *broken = (pdk_bond_index)all;
  if (all > 0 && m->bond_alive)
    PDK_CALL(pdk_comm_allgather_rows(m->ctx, m->bond_alive, 1, m->bond_row_start));
  return PDK_SUCCESS;
}
