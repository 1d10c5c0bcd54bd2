/* Private: the static solvers' shared state (src/solvers/static.c), ADR (src/solvers/adr.c) and Newton
 * (src/solvers/newton.c).
 *
 * static.c owns options, conditions, load levels, the residual, the coloring of the coupling
 * graph, difference perturbations, the level/commit loop and the monitor; adr.c and newton.c each
 * bring the current level to equilibrium with trial passes only.
 *
 * Per-particle arrays are [n] per component c < dim (not padded: solver-private):
 *   fixed[c]    1 if component c of particle i is prescribed
 *   owner[c]    index of the displacement condition that prescribes it, -1 if free
 *   u_level[c]  prescribed displacement of the current level [length] (0 where free)
 *   b_level[c]  body-force density of the current level [force / length^dim]
 *   r[c]        residual V_i (f_ic + b_ic) of the last evaluation [force]; on prescribed
 *               components it holds the same expression (minus the support reaction)
 *   x_prev[c], fext_prev[c]  position and external force (support + body force) after the last
 *               commit, for the trapezoidal external work
 * Coloring: color_of [n]; particles of color k are color_members[color_start[k] ..
 * color_start[k+1]-1], ascending.
 */
#ifndef PDK_STATIC_IMPL_H
#define PDK_STATIC_IMPL_H

#include "models/model_impl.h"
#include "pdk/static.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define PDK_STATIC_BLOCK                                                                           \
  4096 /* particles per reduction block: fixed, so sums are thread-independent */
#define PDK_STATIC_MAX_BCS 64
#define PDK_STATIC_MAX_REACTION_SETS 8

struct pdk_static {
  pdk_ctx *ctx;
  pdk_model *m;
  pdk_particles *p;
  pdk_families *fam;
  pdk_static_opts opts;
  pdk_bc *bcs;    /* [num_bcs], copied */
  double *levels; /* [num_levels], copied or generated */
  int num_levels;
  int dim;
  pdk_index n;
  int hops; /* coupling radius in family hops: 1 (PMB) or 2 */
  double horizon;
  uint8_t *fixed[3];
  int32_t *owner[3];
  double *u_level[3];
  double *b_level[3];
  double *r[3];
  double *x_prev[3], *fext_prev[3];
  int time_mode;         /* opts.total_time > 0 */
  pdk_static_event last; /* last COMMITTED event */
  /* conditions along a direction (pdk_bc.direction): dir_of[i] is the condition holding
   * particle i (-1: none; NULL: no such condition), dir_frame[k] its frame (bc.h). For such a
   * particle the solvers work in that frame: component 0 is the normal n (fixed[0] = 1, owner[0]
   * = k, u_level[0] = the prescribed u.n), components 1.. the free tangents, and r holds the
   * residual's components in the frame; x, f and the reactions stay in x, y, z. */
  int32_t *dir_of;
  double (*dir_frame)[3][3];
  int has_body_force;
  int num_fixed;                                          /* prescribed components */
  uint8_t *reaction_member[PDK_STATIC_MAX_REACTION_SETS]; /* borrowed set fields */
  int num_reaction;
  double lambda;       /* load factor of the current level (0 before the first) */
  double load_measure; /* norm of u_level (or of b_level without displacements) of the level */
  double rnorm;        /* ||r||_free of the last evaluation [force] */
  double fnorm;        /* ||F_ext|| of the last evaluation [force] */
  double floor;        /* round-off floor of ||r|| [force] (0 until known), see static.h */
  int level, round;
  /* coloring of the coupling graph, built on first use */
  int num_colors;
  pdk_index *color_of;
  pdk_index *color_start;   /* [num_colors + 1] */
  pdk_index *color_members; /* [n] */
  double *block_part;       /* [num_blocks * 2] reduction scratch */
  pdk_index num_blocks;
  pdk_static_stats stats;
  void *adr;    /* adr.c state */
  void *newton; /* newton.c state */
};

/* The frame of particle i (NULL unless a condition holds it along a direction). */
static inline const double (*pdk_static_frame(const pdk_static *s, pdk_index i))[3] {
  return s->dir_of && s->dir_of[i] >= 0 ? (const double(*)[3])s->dir_frame[s->dir_of[i]] : NULL;
}

/* static.c */
/* Trial force pass at the current x, then r and the norms (rnorm, fnorm). */
int pdk_static_residual(pdk_static *s);
/* 1 if the last residual meets the tolerance or lies at the round-off floor. */
int pdk_static_converged(const pdk_static *s);
/* Sets x = X + u_level on prescribed components. */
void pdk_static_apply_prescribed(pdk_static *s);
/* Greedy coloring: particles closer than 2 hops delta get different colors (built once). */
int pdk_static_color(pdk_static *s);
/* Adds `step` (times the sign) to component c of every particle of color k; writes the exactly
 * representable perturbation (x + h) - x into h_actual[i] for those particles. Returns nothing. */
void pdk_static_perturb(pdk_static *s, int k, int c, double step, double *h_actual);
/* Restores component c of the particles of color k to saved[i]. */
void pdk_static_restore(pdk_static *s, int k, int c, const double *saved);
/* Non-finite residual: a message naming the level, iteration and first bad particle. */
int pdk_static_nonfinite(pdk_static *s, const char *method, long iteration, const char *hint);

/* adr.c */
int pdk_adr_setup(pdk_static *s);
int pdk_adr_relax(pdk_static *s, long *iterations);
void pdk_adr_free(pdk_static *s);

/* newton.c */
int pdk_newton_setup(pdk_static *s);
int pdk_newton_solve_level(pdk_static *s, long *iterations);
void pdk_newton_free(pdk_static *s);
/* Tests: assembles a tangent at the current x into the solver's compressed-column arrays (free
 * components only; not symmetrized) and returns them. colored 1: the colored differences (the
 * coloring is built if the solver had none); 0: differences one particle at a time (reference:
 * 2 n dim passes); 2: the model's analytic tangent (PDK_ERR_UNSUPPORTED when it has none). */
int pdk_newton_tangent(pdk_static *s, int colored, int *num_cols, const int **col_start,
                       const int **row_index, const double **values);

#endif
