/* Boundary-condition checks shared by the solvers (bc.h). */
#include <math.h>

#include "bc.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/particles.h"

int pdk_bc_check(pdk_ctx *ctx, pdk_particles *p, const pdk_bc *bc, int k, const uint8_t **member) {
  const int dim = pdk_particles_dim(p);
  *member = NULL;
  PDK_CHECK(bc->components && bc->components < (1u << dim), ctx, PDK_ERR_ARG,
            "boundary condition %d: component mask %u must select some of the %d components", k,
            bc->components, dim);
  if (bc->set) {
    *member = pdk_particles_field_data(p, bc->set, 0);
    PDK_CHECK(*member, ctx, PDK_ERR_NOT_FOUND,
              "boundary condition %d names the set field '%s', which does not exist; define "
              "the set first",
              k, bc->set);
  }
  for (int c = 0; c < dim; ++c) {
    if (!(bc->components & (1u << c))) continue;
    const pdk_tfun *tf = &bc->value[c];
    PDK_CHECK((unsigned)tf->kind <= PDK_TFUN_SINE && isfinite(tf->a) && isfinite(tf->b) &&
                  ((tf->kind != PDK_TFUN_RAMP && tf->kind != PDK_TFUN_SMOOTH &&
                    tf->kind != PDK_TFUN_SINE) ||
                   tf->b > 0),
              ctx, PDK_ERR_ARG,
              "boundary condition %d, component %d: bad time function (kind %d, a %g, b %g); "
              "ramp, smooth and sine need a positive duration b",
              k, c, (int)tf->kind, tf->a, tf->b);
  }
  return PDK_SUCCESS;
}

int pdk_bc_claim(pdk_ctx *ctx, pdk_particles *p, const pdk_bc *bc, int k, const uint8_t *member,
                 int32_t *const owner[3], uint8_t *const fixed[3], int *num_fixed) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  for (int c = 0; c < dim; ++c) {
    if (!(bc->components & (1u << c))) continue;
    for (pdk_index i = 0; i < n; ++i) {
      if (member && !member[i]) continue;
      PDK_CHECK(owner[c][i] < 0, ctx, PDK_ERR_ARG,
                "particle %d (id %lld), component %d is prescribed by both boundary "
                "conditions %d and %d; give each component of a particle one condition",
                (int)i, (long long)pdk_particles_id(p)[i], c, (int)owner[c][i], k);
      owner[c][i] = k;
      if (fixed) {
        fixed[c][i] = 1;
        (*num_fixed)++;
      }
    }
  }
  return PDK_SUCCESS;
}
