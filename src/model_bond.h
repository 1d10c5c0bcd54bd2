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

const double *pdk_model_pmb_energy_density(const pdk_model *m);
const double *pdk_model_lps_energy_density(const pdk_model *m);

#endif
