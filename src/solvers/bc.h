/* Private: the boundary-condition checks the solvers share (explicit.c, static.c). Which kinds a
 * solver takes, and scale fields, stay the solver's to check. */
#ifndef PDK_BC_H
#define PDK_BC_H

#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/particles.h"

/* Checks condition k of a solver's list on store p: the component mask selects some of the
 * store's components, the set field it names (if any) exists, and the time function of every
 * selected component is valid (ramp, smooth and sine with a positive duration). *member gets the
 * set's membership, NULL for every particle. */
int pdk_bc_check(pdk_ctx *ctx, pdk_particles *p, const pdk_bc *bc, int k, const uint8_t **member);

/* Claims the components condition k prescribes (a displacement or velocity condition; body
 * forces prescribe none): owner[c][i] = k for the particles of member (NULL: every particle) and
 * the selected components, refusing a component another condition prescribes already
 * (owner >= 0). With fixed (may be NULL) also fixed[c][i] = 1, counted in *num_fixed. */
int pdk_bc_claim(pdk_ctx *ctx, pdk_particles *p, const pdk_bc *bc, int k, const uint8_t *member,
                 int32_t *const owner[3], uint8_t *const fixed[3], int *num_fixed);

#endif
