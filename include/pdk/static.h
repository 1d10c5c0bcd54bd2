/* Static and quasi-static solvers: adaptive dynamic relaxation (ADR) and implicit Newton-Raphson.
 *
 * Both find x with r(x) = 0 on the free degrees of freedom, where the residual of particle i,
 * component c, is the out-of-balance force
 *   r_ic = V_i (f_ic(x) + lambda b_ic)                                            [force]
 * (f the model's internal force density, b the body-force density of the conditions at load
 * factor 1, lambda the load factor of the current level). Prescribed components are not unknowns:
 * x_ic = X_ic + lambda u_ic. A level is converged when
 *   ||r||_free <= rtol * ||F_ext|| + atol,
 *   ||F_ext||^2 = sum over free components of (V_i lambda b_ic)^2
 *               + sum over prescribed components of (V_i (f_ic + lambda b_ic))^2,
 * i.e. the residual is measured against every external force on the body: applied body forces
 * and support reactions (so a purely displacement-driven problem has a load scale too).
 * Round-off floor: positions are absolute, so a one-ulp change of the coordinates changes r by
 * about eps |x|_max ||K||_F (K = -dr/dx); no iteration gets below that. A level is also converged
 * when ||r|| reaches this floor (stats.residual_floor; Newton measures ||K||_F on its tangent, ADR
 * bounds it by the row sums of its mass): at small strains (1e-6) it can lie above rtol ||F_ext||.
 * Float storage (model precision float) adds round-off noise to every residual evaluation, far
 * above that floor for correspondence: Newton accepts a level whose residual lies below
 * FLT_EPSILON ||F_ext|| + atol when its last step no longer halved ||r|| or its line search
 * stalled (stats.storage_floor_levels counts such levels; residual_floor is raised to the residual).
 *
 * Load stepping. The levels lambda_1 < lambda_2 < ... (default: num_levels equal steps up to 1)
 * are the load steps, in one of two modes:
 *   scale (total_time = 0, the default): lambda multiplies the prescribed displacements and body
 *     forces, each taken at the value of its time function at t = 1 (for a constant function, its
 *     constant). There is no time: every pass uses the quasi-static limit of rate terms (no rate
 *     hardening, "eps_p_rate" 0), and a model with Johnson-Cook rate terms is refused at creation
 *     (give a total_time).
 *   time (total_time = T > 0): level k is the pseudo-time t_k = lambda_k T of the load path, and
 *     every condition takes the value of its time function at t_k, exactly as the explicit solver
 *     would at that time (so a scene runs the same load path with either solver: a displacement
 *     with function linear and value v is the pull at velocity v). Every pass of level k (trial
 *     and committing) runs with the model's time step set to dt_k = t_k - t_{k-1} (t_0 = 0) by
 *     pdk_model_set_dt: rate terms see the strain rate of the load step, and "eps_p_rate" is the
 *     plastic strain increment of the step over dt_k. Re-solves of a level after bonds broke
 *     commit with the same dt_k (the redistribution belongs to that step); finer levels make that
 *     choice matter less.
 * Each level is solved to equilibrium from the previous one (the displacement of the free
 * components is first scaled by the ratio of the norms of the prescribed displacements, or of the
 * body forces when no displacement is prescribed, of this level and the last: lambda_k /
 * lambda_{k-1} in scale mode, exact for a linear problem).
 * External work (event and stats): the trapezoidal sum over the load path of the external forces
 * (supports and body forces) times the displacement increments, between consecutive committed
 * equilibria; for a linear elastic body loaded proportionally it equals the strain energy.
 *
 * History. Every iterate of a relaxation or a Newton solve is evaluated with trial force passes
 * (pdk_model_force_trial): nothing breaks, no history moves (the trial passes of level k use the
 * same dt_k as its commit, so the committed state is the equilibrium that was found). When a
 * level has converged, one
 * committing pass (pdk_model_force) advances the history at that equilibrium. If it broke bonds,
 * the level is solved again from there, and so on until a commit breaks nothing (at most
 * max_break_rounds rounds). So history advances only from converged states.
 *
 * ADR (Kilic & Madenci 2010): M u'' + c M u' = r(u) with a fictitious diagonal mass M, unit
 * pseudo time step, central differences:
 *   v^{n+1/2} = ((2 - c^n) v^{n-1/2} + 2 M^-1 r^n) / (2 + c^n),   u^{n+1} = u^n + v^{n+1/2},
 *   v^{1/2} = M^-1 r^0 / 2 (the start of every relaxation),
 *   c^n = 2 sqrt(u^T K1 u / u^T u),  K1_ii = -(r_i^n - r_i^{n-1}) / (M_ii v_i^{n-1/2})
 * (the local Rayleigh quotient; c = 0 when it is not positive, at most 1.9). The scheme is stable
 * when lambda_max(M^-1 K) <= 4. M is chosen by opts.adr_mass:
 *   ROW_SUM  M_ii = safety/4 sum_j |K_ij| (Gershgorin, the Kilic-Madenci bound). The row sums of
 *            the tangent K = -d r/d x are measured at the initial state by forward differences
 *            of trial forces with the coloring of the Newton tangent (dim x colors passes), so it
 *            works for any model and law;
 *   LANCZOS  M_ii = safety/4 * 1.1 lambda_max(V^-1 K) V_i: a uniform fictitious density from a
 *            40-step Lanczos estimate of the top of the spectrum (40 passes; Lanczos converges
 *            from below, hence the 1.1), for horizons where the coloring is expensive;
 *   AUTO     ROW_SUM when it costs at most 128 force passes (2-D, small horizons), LANCZOS
 *            otherwise (row sums save ~30% of the iterations but cost dim x colors passes).
 *
 * Newton: K dx = r on the free components, K = -d r/d x assembled in compressed-column form by
 * finite differences of trial forces. Particles i and k are coupled when k lies within h hops of
 * i in the family graph (h = 1 for the bond-based PMB, 2 for the state-based LPS and
 * correspondence: every particle within 2 delta). Columns whose particles are more than 2 h hops
 * apart share no row, so they are perturbed together: a greedy distance-2 coloring of the coupling
 * graph (a breadth-first search to depth 2 h over the families; by distance 2 h delta over a cell
 * list when that search would be too costly) gives the groups, and one assembly costs 2 dim colors
 * trial passes (central differences) or dim colors (forward), independent of the number of
 * unknowns.
 * Analytic tangent (opts.tangent auto, the default, or analytic): PMB and LPS (omega = 1/r0, 2-D
 * and 3-D, partial volumes, float storage, broken bonds) and the 2-D dilatation laws (LPS with an
 * influence function, Oterkus) bring the exact derivative of their trial force at the current x
 * (src/models/model_pmb.c, src/models/model_lps.c, src/models/model_dil2.c), assembled column by column in the same
 * compressed-column pattern (so CHOLMOD/UMFPACK and the symbolic reuse are unchanged) in one sweep
 * over the particles: no force passes (passes_per_tangent 0, no coloring), no difference error,
 * and a nonlinear (large-stretch) problem converges quadratically. Correspondence uses the
 * difference tangent; tangent difference forces it for every model.
 * Prescribed components are eliminated (their rows and columns dropped), which keeps a symmetric
 * tangent symmetric.
 *   - Symmetry: a hyperelastic model (PMB, LPS, correspondence with an elastic law and no or
 *     Silling stabilization) has a symmetric tangent, but a difference tangent is symmetric only to
 *     its truncation and round-off error (the analytic one to round-off). If the measured asymmetry ||K - K^T||_F / ||K||_F is at
 *     most sym_rtol, K is replaced by (K + K^T)/2 and factorized by CHOLMOD (supernodal Cholesky);
 *     otherwise, or when CHOLMOD reports the matrix not positive definite, by UMFPACK (LU).
 *   - The symbolic analysis (ordering) is done once and reused while the coupling pattern is
 *     unchanged: the pattern follows the families, not the bond state, so broken bonds only zero
 *     entries and never force a new analysis.
 *   - Tangent reuse: within a round, an iteration keeps the factorized tangent of the previous one
 *     when that full step reduced ||r|| by at least 1000 (opts.reuse_tangent).
 *   - Each iteration does a backtracking line search on ||r||: step lengths 1, 1/2, 1/4, ...
 *     (at most max_backtracks halvings) until ||r(x + a dx)|| <= (1 - ls_decrease a) ||r(x)||
 *     (ls_decrease default 1e-4).
 *   - Before the first factorization the solver checks that the displacement conditions stop every
 *     rigid motion ("the body is not held: ..."). A singular or nearly singular tangent stops the
 *     solve with a message naming the particle and the likely cause. Singular means a pivot, or
 *     the smallest eigenvalue estimated by inverse iteration (4 solves, once per level and round;
 *     pivots alone miss near-singular matrices), below singular_rtol times the largest diagonal
 *     entry of the full tangent. The cause is read from the near-null vector: a particle without
 *     intact bonds or whose family does not span; else its non-affine fraction (the part of the
 *     vector that no local affine map fits, ~1 for a zero-energy pattern with vanishing discrete
 *     gradient, ~0 for a rigid motion of a part that is not held).
 *     Note (V-Z): a bounded lattice has no exact zero-energy modes besides rigid motions (the
 *     one-sided families at the surface break the periodic-lattice patterns), but the surviving
 *     spurious modes of unstabilized correspondence can be far softer than the physical ones
 *     (omega = 1/r^2 with RF 1.5: lambda_min/k_max ~ 2e-6 on a clamped 28 x 28 block against ~2e-2
 *     stabilized); raise singular_rtol to treat such a tangent as singular.
 *
 * Threads: force passes and vector updates run in parallel over fixed blocks; every sum is formed
 * in a fixed block order, so results are bitwise the same for any thread count.
 */
#ifndef PDK_STATIC_H
#define PDK_STATIC_H

#include "pdk/export.h"
#include "pdk/explicit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pdk_static_method {
  PDK_STATIC_ADR = 0,   /* adaptive dynamic relaxation */
  PDK_STATIC_NEWTON = 1 /* Newton-Raphson with a sparse direct solver */
} pdk_static_method;

typedef enum pdk_adr_mass {
  PDK_ADR_MASS_AUTO = 0,
  PDK_ADR_MASS_ROW_SUM = 1, /* M_ii = safety/4 sum_j |K_ij| from difference row sums */
  PDK_ADR_MASS_LANCZOS = 2  /* uniform density from a Lanczos bound of lambda_max(V^-1 K) */
} pdk_adr_mass;

typedef enum pdk_fd_scheme {
  PDK_FD_CENTRAL = 0, /* 2 dim colors passes, error O(h^2) */
  PDK_FD_FORWARD = 1  /* dim colors passes (+1), error O(h) */
} pdk_fd_scheme;

typedef enum pdk_tangent_kind {
  PDK_TANGENT_AUTO = 0,      /* analytic when the model has one (PMB, LPS), else difference */
  PDK_TANGENT_ANALYTIC = 1,  /* the model's exact derivative; refused when it has none */
  PDK_TANGENT_DIFFERENCE = 2 /* colored finite differences of trial passes (any model) */
} pdk_tangent_kind;

typedef enum pdk_linear_solver {
  PDK_LINEAR_AUTO = 0,    /* CHOLMOD if symmetric and positive definite, else UMFPACK */
  PDK_LINEAR_CHOLMOD = 1, /* symmetric tangents only; not positive definite is an error */
  PDK_LINEAR_UMFPACK = 2  /* always LU */
} pdk_linear_solver;

/* When the solver reports to the monitor. */
typedef enum pdk_static_phase {
  PDK_STATIC_CONVERGED = 0, /* a level (or a re-solve round) reached equilibrium by trial passes;
                               nothing has been committed yet */
  PDK_STATIC_COMMITTED = 1  /* the committing pass at that equilibrium has run */
} pdk_static_phase;

typedef struct pdk_static_event {
  pdk_static_phase phase;
  int level;             /* 0-based index of the load level */
  double load_factor;    /* lambda of the level */
  int round;             /* 0 for the first solve of the level, then one per re-solve */
  long iterations;       /* ADR iterations or Newton iterations of this round */
  double time;           /* pseudo-time t_k of the level (time mode), else the load factor */
  double residual;       /* ||r||_free [force] at the equilibrium */
  double load_norm;      /* ||F_ext|| [force] */
  double tolerance;      /* the residual bound that was met: max(rtol ||F_ext|| + atol, round-off
                            floor) [force] */
  double strain;         /* strain energy (COMMITTED only) */
  pdk_bond_index broken; /* directed bonds broken so far (model total) */
  pdk_bond_index broken_now; /* bonds this commit broke (COMMITTED only) */
  double reaction[8][3];     /* on opts.reaction_sets: -sum_{i in set} V_i f_i (as the explicit
                                solver: the force the supports or loads exert on the set) */
  double external_work;      /* work of the supports and body forces so far (COMMITTED only) */
} pdk_static_event;

typedef struct pdk_static_opts {
  pdk_static_method method;
  const pdk_bc *bcs; /* displacement and body-force conditions (velocity conditions are refused) */
  int num_bcs;
  const double *load_levels; /* [num_levels] increasing, > 0; NULL: k / num_levels, k = 1..num */
  int num_levels;            /* default 1 */
  double total_time;         /* 0 (default): scale mode; > 0: time mode, level k at pseudo-time
                                load_levels[k] total_time (see "Load stepping" above) */
  double rtol;               /* residual tolerance relative to ||F_ext|| (ADR 1e-6, Newton 1e-10;
                                the round-off floor applies when it is higher) */
  double atol;               /* absolute floor [force] (default 0) */
  long max_iterations;       /* per solve round: ADR iterations (default 200000) or Newton
                                iterations (default 50) */
  int max_break_rounds;      /* re-solves of one level after bonds broke (default 1000) */
  int extrapolate;           /* 1 (default): start a level from the previous one scaled */
  /* ADR */
  pdk_adr_mass adr_mass;
  double adr_safety; /* multiplies the fictitious mass (default 1; > 1 is safer, slower) */
  /* Newton */
  pdk_tangent_kind tangent; /* default auto (see "Newton" above) */
  pdk_fd_scheme fd_scheme;
  double fd_step; /* perturbation relative to the horizon; 0: 1e-5 central, 1e-7 forward */
  pdk_linear_solver linear_solver;
  double sym_rtol;      /* asymmetry accepted as difference error (default 1e-6) */
  double singular_rtol; /* singular when a pivot or the smallest eigenvalue is below this times the
                           largest diagonal (default 1e-8, above the difference error; 0: off) */
  int max_backtracks;   /* line-search halvings (default 10; 0: full steps only) */
  double ls_decrease;   /* sufficient decrease of the line search, in (0, 1) (default 1e-4) */
  int reuse_tangent;    /* 1 (default): within a round, keep the factorized tangent for the next
                           iteration when the last full step reduced ||r|| by at least 1000 (the
                           problem behaves linearly: a linear problem costs one assembly; a looser
                           rule turns Newton into a slow chord method); 0: assemble every iteration */
  /* Output */
  const char *const *reaction_sets; /* set fields ("set:<name>"), at most 8 */
  int num_reaction_sets;
  void (*monitor)(void *user, const pdk_static_event *event); /* may be NULL */
  void *monitor_user;
} pdk_static_opts;

/* Defaults for a method (tolerances and iteration limits differ). */
PDK_EXPORT pdk_static_opts pdk_static_opts_default(pdk_static_method method);

/* Work and memory of a solve, accumulated over pdk_static_solve calls. Times are wall seconds. */
typedef struct pdk_static_stats {
  int levels_done;
  long iterations;   /* ADR iterations or Newton iterations, all levels and rounds */
  long force_passes; /* trial force passes, everything included */
  long commit_passes;
  int break_rounds;           /* re-solves caused by broken bonds */
  double residual, load_norm; /* of the last converged state [force] */
  double external_work;       /* of the supports and body forces so far [energy] */
  /* coloring of the coupling graph (Newton, ADR row sums) */
  int num_colors;
  int coupling_hops;       /* 1 (bond-based) or 2 (state-based) */
  int coloring_geometric;  /* 1: colored by distance (R = 2 hops delta), not by the graph */
  long passes_per_tangent; /* trial passes of one difference tangent: 2 dim colors or dim colors + 1;
                              0 for the analytic tangent */
  int analytic_tangent;    /* 1: Newton assembles the model's analytic tangent */
  /* ADR */
  pdk_adr_mass adr_mass;     /* the mass actually used */
  double mass_min, mass_max; /* fictitious mass range [force / length] (unit pseudo time step) */
  /* Newton: tangent and factor */
  long num_unknowns;
  int64_t tangent_nnz;
  double tangent_nnz_per_row;
  size_t tangent_bytes; /* column pointers, row indices and values */
  int64_t factor_nnz;   /* CHOLMOD: nnz(L); UMFPACK: nnz(L) + nnz(U) */
  size_t factor_bytes;
  int cholmod_factorizations, umfpack_factorizations;
  int symmetric;          /* 1 if the last tangent was symmetrized and passed to CHOLMOD */
  double asymmetry;       /* ||K - K^T||_F / ||K||_F of the last difference tangent */
  double min_pivot_ratio; /* smallest pivot / largest diagonal of the last factorization */
  double min_eig_ratio;   /* inverse-iteration estimate of lambda_min / largest diagonal */
  double residual_floor;  /* round-off floor of ||r||: eps |x|_max ||K||_F [force], raised to
                             the stalled residual on a level accepted at the float-storage floor */
  int storage_floor_levels; /* Newton levels whose line search stalled at the round-off of float
                               storage (precision float, residual <= FLT_EPSILON ||F_ext|| + atol)
                               and were accepted there rather than failed */
  double null_nonaffine;  /* singular tangent: non-affine fraction of its near-null vector
                             (~1 zero-energy mode, ~0 rigid motion of a loose part; -1 n/a) */
  int assemblies, analyses, factorizations, solves, line_search_cuts, tangent_reuses;
  /* Newton: ||r||_free [force] at the start of each iteration of the last solve round, then at
   * its end (the first 16 values), to show the rate of convergence */
  double residual_history[16];
  int residual_history_len;
  double time_setup; /* coloring, pattern, transpose map */
  double time_mass;  /* ADR fictitious mass */
  double time_assembly, time_analysis, time_factorization, time_solve;
  double time_total;
} pdk_static_stats;

typedef struct pdk_static pdk_static;

/* Checks options and conditions and prepares the solver over model m (which it borrows). */
PDK_EXPORT int pdk_static_create(pdk_model *m, const pdk_static_opts *opts, pdk_static **out);
PDK_EXPORT void pdk_static_destroy(pdk_static **s);

/* Solves every load level not solved yet. On success the particles' "x" holds the equilibrium of
 * the last level and "f" its internal forces. On failure the message names the level, the round
 * and why. */
PDK_EXPORT int pdk_static_solve(pdk_static *s);
/* Solves the next load level only (with its re-solve rounds), so a caller can write output after
 * each one; pdk_static_solve is a loop over it. Refused (PDK_ERR_ARG) when every level is done. */
PDK_EXPORT int pdk_static_solve_level(pdk_static *s);
/* Load levels in all, and how many are solved. */
PDK_EXPORT int pdk_static_num_levels(const pdk_static *s);
PDK_EXPORT int pdk_static_levels_solved(const pdk_static *s);
/* opts.total_time: > 0 in time mode, 0 in scale mode. */
PDK_EXPORT double pdk_static_total_time(const pdk_static *s);
/* Pseudo-time of level k (time mode), or its load factor (scale mode); 0 for k < 0. */
PDK_EXPORT double pdk_static_level_time(const pdk_static *s, int k);
/* The last COMMITTED event (the equilibrium after the last solved level, every field of it), or
 * the unloaded state (level -1, everything 0 but broken) before the first level. */
PDK_EXPORT const pdk_static_event *pdk_static_last_event(const pdk_static *s);

PDK_EXPORT const pdk_static_stats *pdk_static_stats_get(const pdk_static *s);
PDK_EXPORT const char *pdk_static_method_name(pdk_static_method method);

/* Prints the stats in a few lines (memory in MiB, times in seconds). */
PDK_EXPORT void pdk_static_stats_print(const pdk_static_stats *st, FILE *out);

#ifdef __cplusplus
}
#endif
#endif
