/* The model's part of a checkpoint (/model; src/core/state.h): what a force pass reads besides the
 * particle fields, for every kind, then the kind's own state (pdk_model_ops.state_*):
 *   num_broken, num_flagged      the counters
 *   has_bond_state               1 when bonds can break (the model keeps bond_alive)
 *   bond_alive  u8  [num_bonds]  the bond state, indexed by the families given at creation
 *   s0          f64 [n]          LAMMPS's critical stretch per particle, when the model keeps it
 *   book_prev   u8  [num_bonds]  PMB, LPS: the breaking energy's pending state
 *   book_pending f64 [n]         (src/models/model_bond_book.c), and book_has_pending; a
 *                                checkpoint without them (older) restarts with nothing pending
 * Everything else a kind keeps is rebuilt identically from the scene or is scratch that the next
 * force pass overwrites (PMB/LPS s0_next, correspondence W). The correspondence model's private
 * num_alive (intact bonds when K^-1 was last computed) is not stored: after a restore it holds the
 * full family counts, so the next pass recomputes K^-1 for every particle with broken bonds, from
 * the same bond state, giving the same bits as the stored "Kinv" field it overwrites.
 */
#include <string.h>

#include "model_bond.h"
#include "model_impl.h"
#include "core/state.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

int pdk_model_state_save(const pdk_model *m, pdk_state *s) {
  const pdk_index n = pdk_particles_count(m->p);
  PDK_CALL(pdk_state_put_i64(s, "num_broken", m->num_broken));
  PDK_CALL(pdk_state_put_i64(s, "num_flagged", m->num_flagged));
  PDK_CALL(pdk_state_put_i64(s, "has_bond_state", m->bond_alive != NULL));
  if (m->bond_alive)
    PDK_CALL(pdk_state_put_array(s, "bond_alive", PDK_U8, (size_t)pdk_families_num_bonds(m->fam),
                                 m->bond_alive));
  if (m->s0) PDK_CALL(pdk_state_put_array(s, "s0", PDK_F64, (size_t)n, m->s0));
  if (m->book_prev) {
    PDK_CALL(pdk_state_put_i64(s, "book_has_pending", m->book_has_pending));
    PDK_CALL(pdk_state_put_array(s, "book_prev", PDK_U8, (size_t)pdk_families_num_bonds(m->fam),
                                 m->book_prev));
    PDK_CALL(pdk_state_put_array(s, "book_pending", PDK_F64, (size_t)n, m->book_pending));
  }
  if (m->ops->state_save) PDK_CALL(m->ops->state_save(m, s));
  return PDK_SUCCESS;
}

int pdk_model_state_check(const pdk_model *m, pdk_state *s) {
  int64_t v;
  PDK_CALL(pdk_state_get_i64(s, "has_bond_state", &v));
  if ((v != 0) != (m->bond_alive != NULL))
    return pdk_state_mismatch(s, "bonds %s break in the checkpoint but %s here (critical stretch)",
                              v ? "can" : "cannot", m->bond_alive ? "can" : "cannot");
  if (m->s0 && !pdk_state_has(s, "s0")) return pdk_state_missing(s, "s0");
  if (m->ops->state_check) PDK_CALL(m->ops->state_check(m, s));
  return PDK_SUCCESS;
}

int pdk_model_state_load(pdk_model *m, pdk_state *s) {
  int64_t v;
  const pdk_index n = pdk_particles_count(m->p);
  if (m->bond_alive) {
    ++m->bond_state_version; /* a kind's own copy of the state is stale from here on */
    PDK_CALL(pdk_state_get_array(s, "bond_alive", PDK_U8, (size_t)pdk_families_num_bonds(m->fam),
                                 m->bond_alive));
  }
  if (m->s0) PDK_CALL(pdk_state_get_array(s, "s0", PDK_F64, (size_t)n, m->s0));
  if (m->book_prev) {
    const size_t nb = (size_t)pdk_families_num_bonds(m->fam);
    if (pdk_state_has(s, "book_prev")) {
      PDK_CALL(pdk_state_get_i64(s, "book_has_pending", &v));
      m->book_has_pending = v != 0;
      PDK_CALL(pdk_state_get_array(s, "book_prev", PDK_U8, nb, m->book_prev));
      PDK_CALL(pdk_state_get_array(s, "book_pending", PDK_F64, (size_t)n, m->book_pending));
    } else {
      memcpy(m->book_prev, m->bond_alive, nb);
      memset(m->book_pending, 0, (size_t)n * sizeof(double));
      m->book_has_pending = 0;
    }
    pdk_bond_book_mark_lost(m);
  }
  if (m->ops->state_load) PDK_CALL(m->ops->state_load(m, s));
  PDK_CALL(pdk_state_get_i64(s, "num_broken", &v));
  m->num_broken = (pdk_bond_index)v;
  PDK_CALL(pdk_state_get_i64(s, "num_flagged", &v));
  m->num_flagged = (pdk_index)v;
  return PDK_SUCCESS;
}
