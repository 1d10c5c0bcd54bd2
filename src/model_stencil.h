/* Private: the stencil layout of a particle set on a regular lattice, for the PMB force pass
 * (src/model_stencil.c builds it and drives kernels/opt/pmb_stencil.h; src/model_pmb.c calls it). */
#ifndef PDK_MODEL_STENCIL_H
#define PDK_MODEL_STENCIL_H

#include "kernels.h"
#include "model_impl.h"

typedef struct pdk_stencil pdk_stencil;

/* Builds the stencil layout of m's particles and families (bond_r0: the float bond lengths of
 * float storage, or NULL). When the set is not a lattice the stencil does not apply: returns
 * PDK_SUCCESS with *out = NULL and the reason in why[why_len]. Errors: memory. */
int pdk_stencil_create(pdk_model *m, const float *bond_r0, pdk_stencil **out, char *why,
                       size_t why_len);
void pdk_stencil_destroy(pdk_stencil **st);

/* One PMB force pass over m's particles: "f" (and w, s0_next when not NULL: s0_next non-NULL is a
 * committing pass, which breaks bonds in m->bond_alive too) from "x"; *broken gets the number of
 * bonds broken. Bitwise the same for any thread count. */
int pdk_stencil_pmb_force(pdk_model *m, pdk_stencil *st, const pdk_pmb_consts *k,
                          double *s0_next, double *w, pdk_bond_index *broken);

/* opts.stencil of m: off does nothing; auto and on build the layout into m->stencil when it
 * applies (multi_material: it does not, the passes take one modulus), else record why in
 * m->stencil_why; on then fails (PDK_ERR_UNSUPPORTED) with that reason. */
int pdk_stencil_model_setup(pdk_model *m, const float *bond_r0, int multi_material);

/* LPS: copies 1/m_i (inv_m [n], the model's) to the sites; once, after pdk_stencil_create. */
int pdk_stencil_lps_setup(pdk_model *m, pdk_stencil *st, const double *inv_m);
/* One LPS force pass (dilation, then force) over m's particles: theta [n_pad] (the "theta"
 * field), "f", w and s0_next as pdk_stencil_pmb_force. */
int pdk_stencil_lps_force(pdk_model *m, pdk_stencil *st, const pdk_lps_consts *k, double *theta,
                          double *s0_next, double *w, pdk_bond_index *broken);

/* Memory the layout holds [bytes]. */
size_t pdk_stencil_memory_bytes(const pdk_stencil *st);

#endif
