/* Rigid frictionless walls of the explicit solver (PDK_BC_WALL, include/pdk/explicit.h).
 *
 * Kinematic contact, after each drift (and the prescribed positions) of a step ending at t1: with
 * n the unit normal (out of the wall) and P(t1) = point + velocity t1, a particle of the wall's set
 * with g = (x - P(t1)) . n < 0 is moved by -g n onto the plane, and when its half-step velocity
 * relative to the wall has a normal part v_n = (v - w) . n < 0, that part is removed: v -= v_n n.
 * The particle then takes the force pass and the second half kick as any other, so it leaves the
 * wall as soon as the forces pull it away (unilateral). The tangential velocity is untouched
 * (frictionless).
 *
 * Momentum: the wall gives the body the impulse sum m_i (-v_n) along n per step (m_i = rho_i V_i),
 * accumulated in wall_impulse[k]; the position correction moves no momentum.
 * Energy: what the wall takes is booked as external work (contact_work). It is the change the
 * correction (dx, dv) makes to the integrator's energy K + S at the step's end, to first order:
 * with v the half-step velocity and f the force density of the last pass (the one the first half
 * kick used),
 *   dE = 1/2 m (|v + dv|^2 - |v|^2)   the half-step kinetic energy removed,
 *      + dt/2 V f . dv                 the second half kick then starts from v + dv,
 *      - V f . dx                      the strain energy the position correction adds.
 * A particle that rests on the wall under a steady push (v = dt a into it, dx = -dt^2 a back,
 * dv = -dt a) gets dE = 0, as it should: the rigid wall does no work on it, and bookings without
 * the last two terms gain +-1/2 m dt^2 a^2 per contact step, an O(dt) error that is large for
 * stiff bodies. At the impact (f ~ 0) dE = -1/2 m v_n^2: the energy of the impact is lost
 * (inelastic for the particle, as a kinematic contact must be). With a moving wall dE is the
 * change in the lab frame, the work the wall does on the body. The remaining error is the
 * integrator's, O(dt^2) per step.
 * The loops are serial over the wall's members in index order: the sums do not depend on the thread
 * count (contacts are few; a wall over every particle of a large body costs one pass per step).
 */
#include <math.h>
#include <string.h>

#include "explicit_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/particles.h"

int pdk_walls_init(pdk_explicit *e) {
  pdk_ctx *ctx = e->ctx;
  e->num_walls = 0;
  for (int k = 0; k < e->opts.num_bcs; ++k) {
    const pdk_bc *bc = &e->bcs[k];
    if (bc->kind != PDK_BC_WALL) continue;
    PDK_CHECK(e->num_walls < PDK_MAX_WALLS, ctx, PDK_ERR_ARG,
              "boundary condition %d: at most %d walls", k, PDK_MAX_WALLS);
    double n2 = 0;
    for (int a = 0; a < e->dim; ++a) {
      PDK_CHECK(isfinite(bc->point[a]) && isfinite(bc->normal[a]) && isfinite(bc->velocity[a]), ctx,
                PDK_ERR_ARG,
                "boundary condition %d (wall): point, normal and velocity must be finite", k);
      n2 += bc->normal[a] * bc->normal[a];
    }
    PDK_CHECK(n2 > 0, ctx, PDK_ERR_ARG,
              "boundary condition %d (wall): the normal is zero; give the direction out of the "
              "wall, towards the body",
              k);
    if (bc->set)
      PDK_CHECK(pdk_particles_field_data(e->p, bc->set, 0), ctx, PDK_ERR_NOT_FOUND,
                "boundary condition %d (wall): set field '%s' does not exist", k, bc->set);
    e->wall_bc[e->num_walls++] = k;
  }
  return PDK_SUCCESS;
}

void pdk_walls_apply(pdk_explicit *e, double t1) {
  const int dim = e->dim;
  const pdk_index n = e->n;
  const double *vol = pdk_particles_volume(e->p);
  const double *rho_p = e->m->mat_density;
  double *x[3] = {NULL, NULL, NULL}, *v[3] = {NULL, NULL, NULL};
  const double *f[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    x[c] = pdk_particles_field_data(e->p, "x", c);
    v[c] = pdk_particles_field_data(e->p, "v", c);
    f[c] = pdk_particles_field_data(e->p, "f", c);
  }
  for (int w = 0; w < e->num_walls; ++w) {
    const pdk_bc *bc = &e->bcs[e->wall_bc[w]];
    const uint8_t *mem = bc->set ? pdk_particles_field_data(e->p, bc->set, 0) : NULL;
    double nrm[3] = {0, 0, 0}, P[3] = {0, 0, 0}, len = 0;
    for (int c = 0; c < dim; ++c)
      len += bc->normal[c] * bc->normal[c];
    len = sqrt(len);
    double wn = 0; /* the wall's normal speed */
    for (int c = 0; c < dim; ++c) {
      nrm[c] = bc->normal[c] / len;
      P[c] = bc->point[c] + bc->velocity[c] * t1;
      wn += bc->velocity[c] * nrm[c];
    }
    double impulse = 0, work = 0;
    for (pdk_index i = 0; i < n; ++i) {
      if (mem && !mem[i]) continue;
      double g = 0;
      for (int c = 0; c < dim; ++c)
        g += (x[c][i] - P[c]) * nrm[c];
      if (!(g < 0)) continue;
      int prescribed = 0;
      for (int c = 0; c < dim; ++c)
        prescribed |= e->bc_of[c][i] >= 0;
      if (prescribed) continue;
      const double m = (rho_p ? rho_p[i] : e->rho) * vol[i];
      double vn = -wn, fdx = 0;
      for (int c = 0; c < dim; ++c) {
        x[c][i] -= g * nrm[c];
        fdx += f[c][i] * (-g * nrm[c]);
        vn += v[c][i] * nrm[c];
      }
      work -= vol[i] * fdx;
      if (vn < 0) {
        double k0 = 0, k1 = 0, fdv = 0;
        for (int c = 0; c < dim; ++c) {
          k0 += v[c][i] * v[c][i];
          v[c][i] -= vn * nrm[c];
          k1 += v[c][i] * v[c][i];
          fdv += f[c][i] * (-vn * nrm[c]);
        }
        impulse += -m * vn;
        work += 0.5 * m * (k1 - k0) + 0.5 * e->dt * vol[i] * fdv;
      }
    }
    e->wall_impulse[w] += impulse;
    e->contact_work += work;
    e->external_work += work;
  }
}
