/* Correspondence, total and semi-total Lagrangian (model_corr.c): the kernels' arrays of the
 * current fields, and freeing the semi-TL compacted list; used by the passes and by the bond
 * breaking (model_corr_bonds.c). */
#include <string.h>

#include "model_corr_impl.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

/* Points the kernel arrays at the current fields. */
void pdk_corr_jc_arrays_of(pdk_particles *p, struct pdk_corr_arrays *a) {
  for (int t = 0; t < 6; ++t)
    a->cp_inv[t] = pdk_particles_field_data(p, "cp_inv", t);
  a->eps_p = pdk_particles_field_data(p, "eps_p", 0);
  a->damage = pdk_particles_field_data(p, "damage", 0);
  a->temp_rise = pdk_particles_field_data(p, "temp_rise", 0); /* NULL unless thermal */
  a->failed = pdk_particles_field_data(p, "failed", 0);
  a->eps_p_rate = pdk_particles_field_data(p, "eps_p_rate", 0);
  a->w_plastic = pdk_particles_field_data(p, "w_plastic", 0);
  a->w_damage = pdk_particles_field_data(p, "w_damage", 0);
}

void pdk_corr_arrays_of(pdk_model *m, pdk_corr_arrays *a) {
  corr_impl *c = m->impl;
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p);
  memset(a, 0, sizeof *a);
  if (c->c_start) {
    a->bond_start = c->c_start;
    a->bond_j = c->c_j;
    a->bond_omega = c->c_omega;
    a->bond_alive = c->c_alive;
  } else {
    a->bond_start = pdk_families_bond_start(m->fam);
    a->bond_j = pdk_families_bond_j(m->fam);
    a->bond_omega = c->bond_omega;
    a->bond_alive = m->bond_alive;
  }
  for (int d = 0; d < dim; ++d) {
    a->X[d] = pdk_particles_X(p, d);
    a->x[d] = pdk_particles_field_data(p, "x", d);
    a->f[d] = pdk_particles_field_data(p, "f", d);
  }
  a->volume = pdk_particles_volume(p);
  for (int t = 0; t < dim * dim; ++t) {
    a->Kinv[t] = pdk_particles_field_data(p, "Kinv", t);
    a->F[t] = pdk_particles_field_data(p, "F", t);
    a->A[t] = pdk_particles_field_data(p, "A", t);
  }
  a->kst = c->kst;
  for (int t = 0; t < 9; ++t) {
    a->B[t] = c->B[t];
    a->G[t] = c->G[t];
    a->Bf[t] = c->Bf[t];
    a->Gf[t] = c->Gf[t];
  }
  a->ref4 = c->ref4;
  a->cur4 = c->cur4;
  a->own = c->own;
  a->row = c->row;
  a->rowf = c->rowf;
  a->m = c->m;
  a->flag = pdk_particles_field_data(p, "flag", 0);
  a->num_alive = c->num_alive;
  a->W = c->W;
  a->s0 = m->s0;
  a->s0_next = c->s0_next;
  if (m->opts.law == PDK_LAW_JC) {
    pdk_corr_jc_arrays_of(p, a);
    if (m->opts.stab_softening) {
      a->stab_factor = pdk_particles_field_data(p, "stab_factor", 0);
      a->w_stab = pdk_particles_field_data(p, "w_stab", 0);
      a->w_silling = pdk_particles_field_data(p, "w_silling", 0);
      a->stab_prev = c->stab_prev;
      a->w_law = c->w_law;
    }
    if (m->opts.damage_triaxiality == PDK_TRIAX_FAMILY) {
      a->sigma_m = pdk_particles_field_data(p, "sigma_m", 0);
      a->sigma_m_avg = pdk_particles_field_data(p, "sigma_m_avg", 0);
    }
  }
  a->w_broken = pdk_particles_field_data(p, "w_broken", 0);
  a->changed = c->changed;
  a->detach = c->detach;
}

void pdk_corr_free_compacted(corr_impl *c) {
  pdk_free_aligned(c->c_start);
  pdk_free_aligned(c->c_j);
  pdk_free_aligned(c->c_omega);
  pdk_free_aligned(c->c_alive);
  c->c_start = NULL;
  c->c_j = NULL;
  c->c_omega = NULL;
  c->c_alive = NULL;
}
