/* The energy bond breaking releases in the PMB and LPS models, booked into "w_broken"
 * (src/models/model_bond.h; the state lives in pdk_model: book_prev, book_pending).
 *
 * What is booked. A committing pass at positions x_n takes its forces and its energy from the
 * bonds intact at entry (state S_{n-1}) and then breaks the bonds whose stretch exceeds the
 * critical one (state S_n; kernels/ref/pmb.c, lps.c, as LAMMPS). So the energy the pass reports
 * is U(S_{n-1}, x_n), and the next pass's is U(S_n, x_{n+1}). Let
 * dU(x) = U(S_{n-1}, x) - U(S_n, x), the stored energy the breaks remove at fixed positions (for
 * PMB the energy of the broken bonds, half at each end; for LPS, state-based, also the change of
 * the dilatation terms of the particles that lost bonds). Velocity Verlet's kinetic energy grows
 * over the step by the trapezoid (f_n + f_{n+1}) . (x_{n+1} - x_n) / 2, where f_n still holds the
 * broken bonds' force -grad dU(x_n). The account kinetic + strain + breaking against the
 * external work then closes over the step to second order when the breaking work grows by
 *     dU(x_n) / 2 + dU(x_{n+1}) / 2  =  dU(x_n) - grad dU(x_n) . (x_{n+1} - x_n) / 2 + O(dt^2),
 * the trapezoid in time of the energy the breaks removed: half at the positions they broke at,
 * half at the next committing pass's. Booking dU(x_n) alone at x_n (as the correspondence model
 * does) leaves grad dU . dx / 2 per break, an error of first order in dt. The LPS strain energy
 * is the potential of its force also once families lost bonds (src/models/model_lps.c), which
 * dU needs.
 *
 * How. Per particle i, W_i(S, x) is a sum over i's own row (the kind's row energy function), so
 * dU = sum_i V_i (W_i(S_{n-1}) - W_i(S_n)) over the particles whose row changed. The end of a
 * committing pass that broke bonds (pdk_bond_book_end) stores book_pending_i = (W_i(S_{n-1}, x_n)
 * - W_i(S_n, x_n)) / 2, with S_{n-1} = book_prev. The start of the next committing pass
 * (pdk_bond_book_start, before its kernels change the state) adds book_pending_i + (W_i(book_prev,
 * x_{n+1}) - W_i(S_n, x_{n+1})) / 2 to "w_broken", and book_prev takes the new state. Until then
 * the broken bonds' energy is part of the strain energy the pass reported (they gave its
 * forces), so the account holds at every step, not only one step after a break. A pass that
 * breaks nothing, and a pass with nothing pending, costs one test of a counter. Trial passes
 * book nothing.
 *
 * Every row is computed by one thread from the model's arrays: bitwise the same for any thread
 * count. Checkpoints store book_prev, book_pending and the flag (src/models/model_state.c), so a
 * restart books what a run without it would.
 */
#include <string.h>

#include "model_bond.h"
#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

int pdk_bond_book_setup(pdk_model *m) {
  if (!m->bond_alive) return PDK_SUCCESS;
  pdk_ctx *ctx = m->ctx;
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  const size_t n_pad = (size_t)pdk_particles_count_padded(m->p);
  PDK_CALL(pdk_particles_field_add(m->p, "w_broken", PDK_F64, 1));
  m->book_prev = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), 1);
  m->book_pending = pdk_alloc_aligned(n_pad > 0 ? n_pad : 1, sizeof(double));
  m->book_lost = pdk_alloc_aligned(n_pad > 0 ? n_pad : 1, 1);
  PDK_CHECK(m->book_prev && m->book_pending && m->book_lost, ctx, PDK_ERR_MEMORY,
            "%s model: out of memory for the bond state of the breaking energy (%lld bonds)",
            m->info->name, (long long)nb);
  memcpy(m->book_prev, m->bond_alive, (size_t)nb);
  memset(m->book_pending, 0, n_pad * sizeof(double));
  m->book_has_pending = 0;
  pdk_bond_book_mark_lost(m);
  return PDK_SUCCESS;
}

void pdk_bond_book_mark_lost(pdk_model *m) {
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index n = pdk_particles_count(m->p);
  const uint8_t *alive = m->bond_alive;
  uint8_t *lost = m->book_lost;
#pragma omp parallel for default(none) shared(bs, n, alive, lost) schedule(static)                 \
    num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i)
    lost[i] = bs[i + 1] > bs[i] && memchr(alive + bs[i], 0, (size_t)(bs[i + 1] - bs[i])) != NULL;
}

static inline int row_changed(const uint8_t *prev, const uint8_t *alive, pdk_bond_index b0,
                              pdk_bond_index b1) {
  return b1 > b0 && memcmp(prev + b0, alive + b0, (size_t)(b1 - b0)) != 0;
}

int pdk_bond_book_arrays(pdk_model *m, const pdk_bond_data *bd, pdk_bond_arrays *a) {
  PDK_CHECK(pdk_bond_arrays_get(m, bd, a), m->ctx, PDK_ERR_NOT_FOUND,
            "%s model: fields \"x\" and \"f\" are missing from the particle store", m->info->name);
  return PDK_SUCCESS;
}

int pdk_bond_book_start(pdk_model *m, const pdk_bond_arrays *a, pdk_bond_row_energy_fn W) {
  if (!m->book_prev || !m->book_has_pending) return PDK_SUCCESS;
  double *w_broken = pdk_particles_field_data(m->p, "w_broken", 0);
  PDK_CHECK(w_broken, m->ctx, PDK_ERR_NOT_FOUND,
            "%s model: the field \"w_broken\" is missing from the particle store", m->info->name);
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index n = pdk_particles_count(m->p);
  uint8_t *prev = m->book_prev;
  const uint8_t *alive = m->bond_alive;
  double *pending = m->book_pending;
  const pdk_model *mc = m;
#pragma omp parallel for default(none) shared(bs, n, prev, alive, pending, w_broken, W, mc, a)     \
    schedule(static) num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i) {
    if (!row_changed(prev, alive, bs[i], bs[i + 1])) continue;
    const double half = 0.5 * (W(mc, a, i, prev) - W(mc, a, i, alive));
    w_broken[i] += pending[i] + half;
    pending[i] = 0.0;
    memcpy(prev + bs[i], alive + bs[i], (size_t)(bs[i + 1] - bs[i]));
  }
  m->book_has_pending = 0;
  return PDK_SUCCESS;
}

int pdk_bond_book_end(pdk_model *m, const pdk_bond_arrays *a, pdk_bond_index broken,
                      pdk_bond_row_energy_fn W) {
  if (!m->book_prev || broken == 0) return PDK_SUCCESS;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index n = pdk_particles_count(m->p);
  const uint8_t *prev = m->book_prev, *alive = m->bond_alive;
  double *pending = m->book_pending;
  uint8_t *lost = m->book_lost;
  const pdk_model *mc = m;
#pragma omp parallel for default(none) shared(bs, n, prev, alive, pending, lost, W, mc, a)         \
    schedule(static) num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i)
    if (row_changed(prev, alive, bs[i], bs[i + 1])) {
      pending[i] = 0.5 * (W(mc, a, i, prev) - W(mc, a, i, alive));
      lost[i] = 1;
    }
  m->book_has_pending = 1;
  return PDK_SUCCESS;
}
