/* Private to the Newton solver (newton*.c): its state and the pieces its files share. The method
 * and the tangent's storage are described in newton.c. */
#ifndef PDK_NEWTON_IMPL_H
#define PDK_NEWTON_IMPL_H

#include "core/ext.h"
#include "static_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"
#include "pdk/static.h"

typedef struct newton_state {
  long nf;                 /* free unknowns */
  int32_t *dof_of[3];      /* [n] */
  pdk_index *dof_particle; /* [nf] */
  uint8_t *dof_comp;       /* [nf] */
  int *Ap, *Ai, *tpos, *diag_pos;
  double *Ax;
  int64_t nnz;
  double *diag_full[3];           /* [n] diagonal of the full tangent, prescribed included */
  double *fa[3];                  /* [n] forces of the + pass (central) or the base (forward) */
  double *h_plus, *h_minus;       /* [n] */
  double *saved;                  /* [n] */
  double *x0[3];                  /* [n] line-search base */
  double *rhs, *dx;               /* [nf] */
  pdk_index *ident_start, *ident; /* [n+1], [n]: one particle per group (reference tangent) */
  double k_ref;
  double kfro; /* ||K||_F of the last tangent */
  int hyperelastic;
  int analytic;             /* 1: the model's analytic tangent (opts.tangent), 0: differences */
  pdk_index *col_scratch;   /* [num_threads][3 n] analytic assembly: stamp, list, loc */
  double *col_block;        /* [num_threads][n dim^2] analytic assembly: one column's blocks */
  pdk_index block_capacity; /* particles per thread in col_block */
  int use_lu;               /* 1 after CHOLMOD found the tangent not positive definite */
  cholmod_common cc;
  int cc_started;
  cholmod_factor *L;
  void *symbolic, *numeric;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  int factor_kind; /* 1 CHOLMOD, 2 UMFPACK: which factor the solve uses */
  int have_null;   /* 1: ns->rhs holds the near-null vector of the current factor */
  int checked_level,
      checked_round; /* last (level, round) whose tangent was checked by inverse iteration */
} newton_state;

static inline double *pdk_newton_field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

static const char pdk_newton_comp_name[3] = {'x', 'y', 'z'};

/* newton_pattern.c */
int pdk_newton_check_held(pdk_static *s);
int pdk_newton_build_pattern(pdk_static *s);
pdk_index pdk_newton_coupled(const pdk_bond_index *restrict bs, const pdk_index *restrict bj,
                             int hops, pdk_index i, pdk_index *restrict stamp,
                             pdk_index *restrict list);
/* newton_assemble.c */
int pdk_newton_assemble_tangent(pdk_static *s);
/* newton_factor.c */
int pdk_newton_solve_linear(pdk_static *s);
int pdk_newton_factor_and_solve(pdk_static *s);

#endif
