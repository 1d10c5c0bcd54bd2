/* Private: the model object and the per-kind operations table.
 *
 * src/models/model.c owns creation, options checking, bond state and dispatch; each kind lives in its
 * own file (model_pmb.c, model_lps.c, model_corr.c, model_corr_ul.c, model_dil2.c), fills a
 * pdk_model_ops and registers a pdk_model_kind_info (src/models/model_registry.h).
 */
#ifndef PDK_MODEL_IMPL_H
#define PDK_MODEL_IMPL_H

#include "pdk/model.h"
#include "model_registry.h"
#include "core/pdk_impl.h"
#include "core/state.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/particles.h"

struct pdk_state; /* a checkpoint part (src/core/state.h) */

typedef struct pdk_model_ops {
  /* Declares the kind's fields and precomputes fixed data; may set m->impl. */
  int (*setup)(pdk_model *m);
  /* Force density "f" from "x"; total strain energy into *energy when not NULL. With commit = 1
   * the pass also advances history (breaks bonds, updates s0); with commit = 0 it changes
   * nothing but "f" (and the kind's scratch fields). */
  int (*force)(pdk_model *m, int commit, double *energy);
  void (*destroy)(pdk_model *m);
  /* Analytic tangent for the Newton solver (both NULL when the kind has none; it then differences
   * trial passes). tangent_prepare (may be NULL) computes, at the current "x", the per-particle
   * quantities the columns read (LPS: dilatations). tangent_column adds the column block of
   * particle i of the full tangent K = -d(V f)/dx:
   *   block[(loc[a] dim + e) dim + c] += K[(a,e),(i,c)] = -V_a d f_ae / d x_ic
   * for every particle a coupled to i (within the kind's coupling hops: 1 for PMB, 2 for LPS);
   * loc[a] is a's index in the caller's list of those particles (set for all of them), block is
   * zeroed by the caller. It reads the model and writes only block: any number of threads may
   * call it at once, and a column's bits do not depend on which thread computes it. The derivative
   * is that of the trial pass (bond states as stored, nothing breaks). */
  int (*tangent_prepare)(pdk_model *m);
  void (*tangent_column)(const pdk_model *m, pdk_index i, const pdk_index *loc, double *block);
  /* The kind's own part of a checkpoint, beside the bond state and counters src/models/model_state.c
   * saves for every kind (src/core/state.h); NULL when the kind has none. state_check says whether a
   * checkpoint's /model part fits this kind (and names what differs) without changing anything;
   * state_load runs after the particle fields and the bond state are restored. */
  int (*state_save)(const pdk_model *m, struct pdk_state *s);
  int (*state_check)(const pdk_model *m, struct pdk_state *s);
  int (*state_load)(pdk_model *m, struct pdk_state *s);
  /* Derived output field `name` (one the kind lists in its pdk_model_kind_info.derived) of every
   * particle into out [n], from the state after the last force pass; dt: the step of that pass.
   * NULL when the kind lists none. */
  int (*derived)(const pdk_model *m, const char *name, double dt, double *out);
  /* Layout sell: the padding fraction of the sliced copy (NULL: 0). */
  double (*padding_fraction)(const pdk_model *m);
  /* Connectivity that follows the motion: rebuild the families at the current x now, and the
   * families the passes walk (both NULL for kinds whose families are fixed). */
  int (*rebuild)(pdk_model *m);
  pdk_families *(*current_families)(const pdk_model *m);
  /* 1: float storage keeps the reference bond lengths as floats (pdk_model_float_stretch_ratio
   * applies). */
  int float_bond_lengths;
  /* 1: layout sell is implemented. */
  int layout_sell;
  /* 1: a bond's volume V_j is scaled by the partial-volume factor min(1, (vs_a - r0) vs_b) of
   * opts.lattice_constant (PMB, LPS); the bond damage weighs the bonds the same way. */
  int partial_volumes;
  /* 1: the force passes split their rows over MPI ranks (src/models/model_ranks.c): each rank
   * computes the rows it owns and the ranks exchange them; kinds without it run on one rank.
   * ranks_refusal (may be NULL): why these options do not run on several ranks, NULL when they do
   * (asked first: it may name the option of a kind without ranks). */
  int ranks;
  const char *(*ranks_refusal)(const pdk_model_opts *o);
} pdk_model_ops;

struct pdk_model {
  pdk_ctx *ctx;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model_opts opts;
  const pdk_model_kind_info *info; /* its kind's registry entry (name, capabilities) */
  const pdk_model_ops *ops;
  void *impl;                  /* kind-private data */
  uint8_t *bond_alive;         /* [num_bonds] or NULL when bonds never break */
  double *s0;                  /* [n_pad] LAMMPS critical stretch per particle, or NULL */
  pdk_bond_index num_broken;
  pdk_index num_flagged;
  pdk_index num_failed;  /* Johnson-Cook: failed particles after the last pass */
  long num_compactions;  /* semi-TL bond-list compactions */
  long num_rebuilds;     /* UL family rebuilds */
  double rebuild_work;   /* UL: strain energy the rebuilds removed (before - after), summed */
  double dt;             /* time step for history updates; 0 until pdk_model_set_dt */
  /* Multi-material (opts.num_materials > 0): per-particle constants [n_pad], else NULL. */
  double *mat_bulk, *mat_shear, *mat_density;
  double *mat_lambda, *mat_stab; /* correspondence: lambda = K - 2G/3, stabilization modulus */
  pdk_material *materials; /* copy of opts.materials (opts.materials points here) */
  /* Incremented by whoever writes bond_alive from outside the force passes (checkpoint restore),
   * so a kind that keeps a copy of the bond state in another layout (the stencil, layout sell)
   * reloads it. */
  unsigned long bond_state_version;
  /* PMB and LPS: the lattice (stencil) layout the passes take (opts.stencil; src/models/model_stencil.c),
   * or NULL; why auto fell back to the general path. */
  struct pdk_stencil *stencil;
  char stencil_why[512];
  /* PMB and LPS with bonds that can break: the energy the breaks released, booked into
   * "w_broken" over two committing passes (src/models/model_bond_book.c): book_prev [num_bonds]
   * the bond state before the last committing pass that broke bonds (equal to bond_alive when
   * nothing is pending), book_pending [n_pad] the half booked at that pass's positions, not yet
   * added to "w_broken"; NULL for other kinds. */
  uint8_t *book_prev;
  double *book_pending;
  int book_has_pending;
  uint8_t *book_lost; /* [n_pad] 1: the particle's family in bond_alive has a broken bond */
  /* Several MPI ranks (src/models/model_ranks.c; NULL on one rank): rank r owns the particles
   * [row_start[r], row_start[r + 1]) and their bonds [bond_row_start[r], bond_row_start[r + 1]);
   * this rank's particles are [row_lo, row_hi). */
  int64_t *row_start, *bond_row_start;
  pdk_index row_lo, row_hi;
};

/* ---- several ranks (src/models/model_ranks.c) ---------------------------------------------------- */

/* At creation, before the kind's setup: on several ranks, refuses what does not run there yet and
 * splits the particles into contiguous ranges of about equal bond counts (nothing on one rank). */
int pdk_model_ranks_setup(pdk_model *m);
/* After a pass over this rank's rows: every rank gets every row of `data` (n_pad doubles). */
int pdk_model_ranks_gather(pdk_model *m, double *data);
/* After a force pass over this rank's rows: "f", w and s0_next (each when not NULL) of every row,
 * *broken summed over the ranks, and the bond state of every row when a bond broke. */
int pdk_model_ranks_finish(pdk_model *m, double *w, double *s0_next, pdk_bond_index *broken);

/* Density of particle i: the material's, or opts.density for a one-material body. */
static inline double pdk_model_density_of(const pdk_model *m, pdk_index i) {
  return m->mat_density ? m->mat_density[i] : m->opts.density;
}

extern const pdk_model_ops pdk_model_ops_pmb;
extern const pdk_model_ops pdk_model_ops_lps;
extern const pdk_model_ops pdk_model_ops_corr;
extern const pdk_model_ops pdk_model_ops_dil2; /* lps with influence, oterkus (model_dil2.c) */
extern const pdk_model_ops pdk_model_ops_corr_ul; /* correspondence, UL connectivity */
/* Derived fields of the correspondence kinds (TL and UL; src/models/model_corr_derived.c). */
int pdk_model_corr_derived(const pdk_model *m, const char *name, double dt, double *out);
/* Points the kernel arrays at the Johnson-Cook history fields (law jc; TL and UL;
 * src/models/model_corr_arrays.c). */
void pdk_corr_jc_arrays_of(pdk_particles *p, struct pdk_corr_arrays *a);
/* Correspondence with the Johnson-Cook law, after a committing pass (src/models/model_corr.c): the
 * particles whose update failed (their count, the first in *first) and the error naming it. */
pdk_index pdk_model_corr_jc_first_failure(const pdk_model *m, const uint8_t *flag,
                                          const uint8_t *failed, pdk_index *first);
int pdk_model_corr_jc_failure_error(pdk_model *m, pdk_index i, pdk_index count, const char *why);

/* Influence function omega(r) for r <= delta (see pdk_influence). */
double pdk_influence_eval(pdk_influence kind, double r, double delta, double gaussian_width);

/* ---- its checkpoint part (/model; src/models/model_state.c and the kinds, through src/core/state.h) --------------------------- */

/* num_broken, num_flagged, has_bond_state; bond_alive [num_bonds] and s0 [n] when the model has
 * them; then the kind's state (pdk_model_ops.state_save). */
int pdk_model_state_save(const pdk_model *m, pdk_state *s);
/* Whether the part fits the model (bond state, the kind's state), changing nothing. */
int pdk_model_state_check(const pdk_model *m, pdk_state *s);
/* Restores it, after the particle fields (a kind's state may be computed from them). */
int pdk_model_state_load(pdk_model *m, pdk_state *s);

#endif
