/* Private to libpdk (tests, benchmarks): what the PMB and LPS drivers expose beyond
 * include/pdk/model.h.
 *
 * Strain energy density W_i [energy/volume], [n_pad] entries, of the last force pass that asked for
 * the energy (pdk_model_force or pdk_model_force_trial with strain_energy != NULL); NULL before
 * such a pass or when the model is of another kind. sum_i V_i W_i is the total those passes return
 * (summed in blocks, see src/model_pmb.c).
 */
#ifndef PDK_MODEL_BOND_H
#define PDK_MODEL_BOND_H

#include "pdk/model.h"
#include "model_impl.h"

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
    for (int64_t blk = 0; blk < num_blocks; ++blk) e += block_energy[blk];
    *energy = e;
  }
}

const double *pdk_model_pmb_energy_density(const pdk_model *m);
const double *pdk_model_lps_energy_density(const pdk_model *m);

#endif
