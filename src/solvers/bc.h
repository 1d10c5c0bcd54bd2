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

/* 1 when the condition acts along a direction (pdk_bc.direction not all zero). */
static inline int pdk_bc_directional(const pdk_bc *bc) {
  return bc->direction[0] != 0.0 || bc->direction[1] != 0.0 || bc->direction[2] != 0.0;
}

/* The frame of a directional condition: R[a][q] is component a of axis q, axis 0 the unit
 * direction n, axes 1 (and 2 in 3-D) unit tangents, orthonormal. */
void pdk_bc_frame(const pdk_bc *bc, int dim, double R[3][3]);

/* Claims the particles of directional condition k: dir_of[i] = k for the members (NULL: every
 * particle), refusing a particle another directional condition holds already. */
int pdk_bc_claim_direction(pdk_ctx *ctx, pdk_particles *p, int k, const uint8_t *member,
                           int32_t *dir_of);

/* After every claim: refuses a particle held both by a directional condition and by a condition
 * on its components (owner). */
int pdk_bc_direction_overlap(pdk_ctx *ctx, pdk_particles *p, const int32_t *dir_of,
                             int32_t *const owner[3]);

#endif
