/* Private: the stencil layout of a particle set on a regular lattice, for the PMB, LPS and
 * correspondence passes (src/models/model_stencil.c builds it and drives kernels/opt/pmb_stencil.h,
 * lps_stencil.h, corr_stencil.h; src/models/model_pmb.c, model_lps.c, model_corr.c call it). */
#ifndef PDK_MODEL_STENCIL_H
#define PDK_MODEL_STENCIL_H

#include "kernels.h"
#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/model.h"

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

/* Correspondence: NULL when the options allow the stencil path (tl connectivity, stabilization none
 * or silling), else why not; the lattice itself is checked by pdk_stencil_create. */
const char *pdk_stencil_corr_refusal(const pdk_model_opts *o);
/* Correspondence: xi and omega per offset from the families (bond_omega: the model's [num_bonds])
 * and the per-site pass-2 arrays (float_storage: also their float copy); once, after
 * pdk_stencil_model_setup built m->stencil. When some bond's xi or omega differs from its
 * offset's beyond round-off, the stencil does not apply: m->stencil is destroyed and the reason
 * recorded (stencil on: PDK_ERR_UNSUPPORTED with it). */
int pdk_stencil_corr_setup(pdk_model *m, const double *bond_omega, int float_storage);
/* Correspondence passes 1 and 2 over the grid (one parallel region): the per-particle outputs
 * through c (the model's arrays, pass-2 arrays NULL), "f" included. */
int pdk_stencil_corr_passes(pdk_model *m, pdk_stencil *st, const pdk_corr_consts *k,
                            const pdk_corr_arrays *c);
/* The mask entries of the particles with changed[i] & 2 (rows that lost bonds in this commit
 * pass, pdk_kernel_corr_break_ref) from m->bond_alive. */
void pdk_stencil_mask_rows(pdk_model *m, pdk_stencil *st, const uint8_t *changed);

#endif
