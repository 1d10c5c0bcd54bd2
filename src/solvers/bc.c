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
  if (pdk_bc_directional(bc)) {
    double d2 = 0.0;
    int finite = 1;
    for (int a = 0; a < 3; ++a) {
      finite &= isfinite(bc->direction[a]) && (a < dim || bc->direction[a] == 0.0);
      d2 += bc->direction[a] * bc->direction[a];
    }
    PDK_CHECK(finite && d2 > 0 && isfinite(d2), ctx, PDK_ERR_ARG,
              "boundary condition %d: the direction (%g, %g, %g) must be a finite, non-zero "
              "vector with %d components",
              k, bc->direction[0], bc->direction[1], bc->direction[2], dim);
    PDK_CHECK(bc->kind != PDK_BC_BODY_FORCE && bc->components == 1u, ctx, PDK_ERR_ARG,
              "boundary condition %d: a condition along a direction is a displacement or velocity "
              "condition whose value is value[0] (components 1), got kind %d, components %u",
              k, (int)bc->kind, bc->components);
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

void pdk_bc_frame(const pdk_bc *bc, int dim, double R[3][3]) {
  double n[3] = {bc->direction[0], bc->direction[1], dim == 3 ? bc->direction[2] : 0.0};
  const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int a = 0; a < 3; ++a)
    n[a] /= len;
  double t1[3], t2[3];
  if (dim == 2) {
    t1[0] = -n[1], t1[1] = n[0], t1[2] = 0.0;
    t2[0] = t2[1] = 0.0, t2[2] = 1.0;
  } else {
    /* t1: n x (the axis least aligned with n), normalized; t2 = n x t1 */
    int m = 0;
    for (int a = 1; a < 3; ++a)
      if (fabs(n[a]) < fabs(n[m])) m = a;
    double e[3] = {0, 0, 0};
    e[m] = 1.0;
    t1[0] = n[1] * e[2] - n[2] * e[1];
    t1[1] = n[2] * e[0] - n[0] * e[2];
    t1[2] = n[0] * e[1] - n[1] * e[0];
    const double l1 = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int a = 0; a < 3; ++a)
      t1[a] /= l1;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
  }
  for (int a = 0; a < 3; ++a) {
    R[a][0] = n[a];
    R[a][1] = t1[a];
    R[a][2] = t2[a];
  }
}

int pdk_bc_claim_direction(pdk_ctx *ctx, pdk_particles *p, int k, const uint8_t *member,
                           int32_t *dir_of) {
  const pdk_index n = pdk_particles_count(p);
  for (pdk_index i = 0; i < n; ++i) {
    if (member && !member[i]) continue;
    PDK_CHECK(dir_of[i] < 0, ctx, PDK_ERR_ARG,
              "particle %d (id %lld) is held along a direction by both boundary conditions %d and "
              "%d; one particle takes one condition along a direction (a corner between two "
              "inclined faces: fix it with x, y%s instead)",
              (int)i, (long long)pdk_particles_id(p)[i], (int)dir_of[i], k,
              pdk_particles_dim(p) == 3 ? ", z" : "");
    dir_of[i] = k;
  }
  return PDK_SUCCESS;
}

int pdk_bc_direction_overlap(pdk_ctx *ctx, pdk_particles *p, const int32_t *dir_of,
                             int32_t *const owner[3]) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  for (pdk_index i = 0; i < n; ++i) {
    if (dir_of[i] < 0) continue;
    for (int c = 0; c < dim; ++c)
      PDK_CHECK(owner[c][i] < 0, ctx, PDK_ERR_ARG,
                "particle %d (id %lld) is held along a direction by boundary condition %d and its "
                "component %c by boundary condition %d; give a particle either a condition along a "
                "direction or conditions on its components",
                (int)i, (long long)pdk_particles_id(p)[i], (int)dir_of[i], "xyz"[c],
                (int)owner[c][i]);
  }
  return PDK_SUCCESS;
}
