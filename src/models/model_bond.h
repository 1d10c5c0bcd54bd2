/* Private to libpdk (tests, benchmarks): what the PMB and LPS drivers expose beyond
 * include/pdk/model.h.
 *
 * Strain energy density W_i [energy/volume], [n_pad] entries, of the last force pass that asked for
 * the energy (pdk_model_force or pdk_model_force_trial with strain_energy != NULL); NULL before
 * such a pass or when the model is of another kind. sum_i V_i W_i is the total those passes return
 * (summed in blocks, see src/models/model_pmb.c).
 */
#ifndef PDK_MODEL_BOND_H
#define PDK_MODEL_BOND_H

#include "kernels.h"
#include "pdk/model.h"
#include "model_impl.h"
#include "pdk/ctx.h"

/* Data the PMB and LPS drivers share (src/models/model_bond.c): the packed particle rows of the
 * SIMD kernels and the float bond lengths of precision float (pdk_bond_arrays in
 * kernels/kernels.h). */
typedef struct pdk_bond_data {
  int dim;
  pdk_index n;
  double *ref4;    /* [4 n_pad] X, Y, Z, extra; NULL when the kernel table reads SoA only */
  double *cur4;    /* [4 n_pad] x, y, z, V, refilled before every pass */
  float *bond_r0;  /* [num_bonds] |xi| rounded to float (precision float), else NULL */
  double *bond_r0d; /* [num_bonds] |xi| in double (bond_lengths stored, csr path), else NULL */
} pdk_bond_data;

/* Allocates what the context's kernel table and m->opts.precision need and fills ref4 (extra
 * column 0) and bond_r0. `who` names the model in messages. */
int pdk_bond_data_setup(pdk_model *m, pdk_bond_data *bd, const char *who);
void pdk_bond_data_free(pdk_bond_data *bd);
/* After the layout is chosen, when the general (csr) pass will run: stores the double bond lengths
 * bond_r0d when m->opts.bond_lengths is stored, precision double and the SIMD kernels (the rows)
 * are in use, the only kernels that read them (pdk_kernel_bond_lengths_ref). */
int pdk_bond_data_store_lengths(pdk_model *m, pdk_bond_data *bd, const char *who);
/* The pass's arrays: families, positions, volume, rows, bond_r0, bond state; the caller sets the
 * model-specific ones (s0_next, theta, inv_m, theta_out, w). Returns 0 when a field is missing. */
int pdk_bond_arrays_get(pdk_model *m, const pdk_bond_data *bd, pdk_bond_arrays *a);
/* cur4 rows [i0, i1) from x and the volumes (no-op without rows). */
void pdk_bond_pack_cur(const pdk_bond_data *bd, const pdk_bond_arrays *a, pdk_index i0,
                       pdk_index i1);
/* Worksharing loops over the blocks of `block` particles of [0, n), static schedule (the blocks
 * a thread gets depend only on the thread count), ending in the loop's implicit barrier. Called by
 * every thread of an enclosing parallel region (or outside one: one thread does all). */
/* cur4 rows of every particle (no-op without rows): every row is packed when it returns. */
void pdk_bond_pack_cur_blocks(const pdk_bond_data *bd, const pdk_bond_arrays *a, pdk_index n,
                              int64_t block);
/* block_energy[b] = pdk_bond_block_energy over block b, for every block. */
void pdk_bond_block_energies(const double *volume, const double *w, pdk_index n, int64_t block,
                             double *block_energy);

/* The bond j -> i stored in j's family (families are sorted by neighbour, so a binary search),
 * or -1 if there is none. The analytic tangents read the state of the bond from the other end. */
static inline pdk_bond_index pdk_bond_reverse(const pdk_bond_index *bond_start,
                                              const pdk_index *bond_j, pdk_index i, pdk_index j) {
  pdk_bond_index lo = bond_start[j], hi = bond_start[j + 1] - 1;
  while (lo <= hi) {
    const pdk_bond_index mid = lo + (hi - lo) / 2;
    if (bond_j[mid] == i) return mid;
    if (bond_j[mid] < i)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

/* sum_i V_i W_i over one block [i0, i1), in index order. */
static inline double pdk_bond_block_energy(const double *volume, const double *w, pdk_index i0,
                                           pdk_index i1) {
  double e = 0.0;
  for (pdk_index i = i0; i < i1; ++i)
    e += volume[i] * w[i];
  return e;
}

/* End of a PMB or LPS force pass, shared by both drivers: in a committing pass with bond state
 * the pass's critical stretches become the next pass's "previous" ones (buffer swap) and the
 * broken count grows; the strain energy is the sum of the per-block partials in block order, so
 * it has the same bits for any thread count. */
static inline void pdk_bond_pass_finish(pdk_model *m, double **s0_next, int swapped,
                                        pdk_bond_index broken, const double *block_energy,
                                        int64_t num_blocks, double *energy) {
  if (swapped) {
    double *t = m->s0;
    m->s0 = *s0_next;
    *s0_next = t;
    m->num_broken += broken;
  }
  if (energy) {
    double e = 0.0;
    for (int64_t blk = 0; blk < num_blocks; ++blk)
      e += block_energy[blk];
    *energy = e;
  }
}

/* The energy bond breaking releases (src/models/model_bond_book.c, which says what is booked and
 * why): W(m, a, i, alive) is particle i's strain energy density at the current "x" with bond state
 * `alive` ([num_bonds], the families' bonds), from i's own row, reading the families, positions,
 * volumes and bond_r0 of `a` (pdk_bond_arrays_get, fetched once per pass); it may be called by
 * several threads at once. setup (when bonds can break: declares "w_broken", copies the bond state)
 * at the kind's setup; start at the beginning of a committing pass (books what the last breaking
 * pass left pending); end after it, with the count it broke. */
typedef double (*pdk_bond_row_energy_fn)(const pdk_model *m, const pdk_bond_arrays *a, pdk_index i,
                                         const uint8_t *alive);
int pdk_bond_book_setup(pdk_model *m);
/* The arrays W reads (pdk_bond_arrays_get; an error naming the model when a field is missing). */
int pdk_bond_book_arrays(pdk_model *m, const pdk_bond_data *bd, pdk_bond_arrays *a);
int pdk_bond_book_start(pdk_model *m, const pdk_bond_arrays *a, pdk_bond_row_energy_fn W);
int pdk_bond_book_end(pdk_model *m, const pdk_bond_arrays *a, pdk_bond_index broken,
                      pdk_bond_row_energy_fn W);
/* book_lost from bond_alive (setup, checkpoint restore): 1 for every particle with a broken bond;
 * book_end keeps it current. */
void pdk_bond_book_mark_lost(pdk_model *m);

const double *pdk_model_pmb_energy_density(const pdk_model *m);
/* pdk_model_padding_fraction of a PMB or LPS model (0 for layout csr or another kind). */
double pdk_model_pmb_padding_fraction(const pdk_model *m);
double pdk_model_lps_padding_fraction(const pdk_model *m);
const double *pdk_model_lps_energy_density(const pdk_model *m);

#endif
