/* Implicit static Newton-Raphson with an analytic or difference tangent and SuiteSparse (CHOLMOD /
 * UMFPACK).
 *
 * Unknowns: the free components (not prescribed), numbered particle-major: dof_of[c][i] is the
 * unknown of component c of particle i or -1. Residual r = V (f + lambda b) (static.c); tangent
 * K = -dr/dx restricted to the free components (Dirichlet by elimination: the prescribed rows and
 * columns are dropped, which keeps a symmetric K symmetric). One iteration solves K dx = r and
 * moves x by a dx, a from a backtracking line search on ||r||.
 *
 * Tangent storage, compressed sparse column over the free unknowns (int indices, CHOLMOD's and
 * UMFPACK's "di" interfaces):
 *   Ap   [nf+1]  column starts;  Ai [nnz] row indices, ascending within a column;  Ax [nnz] values
 *   tpos [nnz]   position of the transposed entry (the pattern is structurally symmetric)
 *   diag_pos [nf] position of the diagonal entry
 * Pattern: column (i, c) has a row (j, e) for every free (j, e) with j within `hops` family hops
 * of i (bonds counted whether intact or broken, so breaking never changes the pattern and the
 * symbolic analyses are done once). hops = 1 for PMB (f_i depends on the family of i), 2 for LPS
 * and correspondence (f_i depends on theta_j / A_j of the neighbours, which depend on theirs).
 *
 * Assembly by differences of trial forces, colored (static.c: particles of one color are more
 * than 2 hops delta apart, so no row couples to two of them): for each color k and component d,
 * every particle of color k is moved by +h (and -h for central differences) in component d; the
 * change of V_j f_j at the rows of the column (i, d) belongs to particle i alone:
 *   K[(j,e),(i,d)] = -V_j (f_je(x + h e_id) - f_je(x - h e_id)) / (h+ + h-),
 * with h+ = (x + h) - x and h- = x - (x - h) the perturbations actually applied (exact in floating
 * point). Error: central O(h^2) truncation + O(eps / h) round-off; with h = 1e-5 delta both are
 * near 1e-10 of the entries. The diagonal entries of prescribed components are measured too (they
 * cost nothing extra): their largest magnitude is the stiffness scale k_ref for the singularity
 * test.
 *
 * Analytic assembly (opts.tangent auto or analytic, models with pdk_model_ops.tangent_column: PMB,
 * LPS, the 2-D dilatation laws): the model's exact derivative, one column particle at a time
 * (assemble_analytic), into the same pattern; it replaces the 2 dim colors force passes.
 *
 * Factorization. A hyperelastic model's tangent is symmetric; the difference tangent is so up to
 * its error. If ||K - K^T||_F / ||K||_F <= sym_rtol, K <- (K + K^T)/2 (documented in static.h) and
 * CHOLMOD factorizes it (upper triangle, supernodal or simplicial as CHOLMOD chooses; the analysis
 * with AMD/METIS ordering is kept). If CHOLMOD finds it not positive definite (auto mode), UMFPACK
 * takes over for the rest of the solve. Other tangents go to UMFPACK (symbolic analysis kept; no
 * row scaling, so its pivots compare with k_ref). Pivots below singular_rtol k_ref mean singular.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "newton_impl.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/static.h"

/* ---- setup ---------------------------------------------------------------------------------- */

int pdk_newton_setup(pdk_static *s) {
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  const double t0 = pdk_wtime();
  newton_state *ns = calloc(1, sizeof *ns);
  PDK_CHECK(ns, ctx, PDK_ERR_MEMORY, "newton: out of memory");
  s->newton = ns;
  for (int c = 0; c < dim; ++c) {
    ns->dof_of[c] = malloc((size_t)n * sizeof(int32_t));
    ns->diag_full[c] = calloc((size_t)n, sizeof(double));
    ns->fa[c] = malloc((size_t)n * sizeof(double));
    ns->x0[c] = malloc((size_t)n * sizeof(double));
    PDK_CHECK(ns->dof_of[c] && ns->diag_full[c] && ns->fa[c] && ns->x0[c], ctx, PDK_ERR_MEMORY,
              "newton: out of memory for %d particles", (int)n);
  }
  ns->h_plus = malloc((size_t)n * sizeof(double));
  ns->h_minus = malloc((size_t)n * sizeof(double));
  ns->saved = malloc((size_t)n * sizeof(double));
  PDK_CHECK(ns->h_plus && ns->h_minus && ns->saved, ctx, PDK_ERR_MEMORY,
            "newton: out of memory for %d particles", (int)n);
  long nf = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c)
      ns->dof_of[c][i] = s->fixed[c][i] ? -1 : (int32_t)nf++;
  PDK_CHECK(nf <= INT_MAX - 1, ctx, PDK_ERR_MEMORY, "newton: %ld unknowns exceed 32-bit indices",
            nf);
  ns->nf = nf;
  ns->dof_particle = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *ns->dof_particle);
  ns->dof_comp = malloc((size_t)(nf > 0 ? nf : 1));
  ns->rhs = malloc((size_t)(nf > 0 ? nf : 1) * sizeof(double));
  ns->dx = malloc((size_t)(nf > 0 ? nf : 1) * sizeof(double));
  PDK_CHECK(ns->dof_particle && ns->dof_comp && ns->rhs && ns->dx, ctx, PDK_ERR_MEMORY,
            "newton: out of memory for %ld unknowns", nf);
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < dim; ++c)
      if (ns->dof_of[c][i] >= 0) {
        ns->dof_particle[ns->dof_of[c][i]] = i;
        ns->dof_comp[ns->dof_of[c][i]] = (uint8_t)c;
      }
  ns->hyperelastic = pdk_model_opts_hyperelastic(&s->m->opts);
  {
    const int has = pdk_model_has_tangent(s->m);
    char kinds[128];
    PDK_CHECK(
        s->opts.tangent != PDK_TANGENT_ANALYTIC || has, ctx, PDK_ERR_UNSUPPORTED,
        "newton: tangent analytic was requested but model '%s' has no analytic tangent "
        "(%s have one); use tangent auto or difference",
        pdk_model_kind_name(s->m->opts.kind),
        pdk_model_kinds_list(PDK_KIND_TANGENT, PDK_KIND_TANGENT, " and ", kinds, sizeof kinds));
    ns->analytic = has && s->opts.tangent != PDK_TANGENT_DIFFERENCE;
    PDK_CHECK(ns->analytic || !s->dir_of, ctx, PDK_ERR_UNSUPPORTED,
              "newton: a boundary condition along a direction needs the analytic tangent (%s "
              "have one; tangent auto or analytic), not the difference tangent of model '%s'; "
              "use solver type adr or explicit for it",
              kinds, pdk_model_kind_name(s->m->opts.kind));
  }
  s->stats.analytic_tangent = ns->analytic;
  s->stats.num_unknowns = nf;
  if (nf == 0) return PDK_SUCCESS; /* everything prescribed: nothing to solve */
  PDK_CALL(pdk_newton_check_held(s));
  if (!ns->analytic) PDK_CALL(pdk_static_color(s)); /* the analytic tangent needs no coloring */
  PDK_CALL(pdk_newton_build_pattern(s));
  cholmod_start(&ns->cc);
  ns->cc_started = 1;
  ns->checked_level = -1;
  ns->cc.quick_return_if_not_posdef = 1;
  umfpack_di_defaults(ns->control);
  ns->control[UMFPACK_SCALE] = UMFPACK_SCALE_NONE; /* pivots comparable with k_ref */
  s->stats.tangent_nnz = ns->nnz;
  s->stats.tangent_nnz_per_row = (double)ns->nnz / (double)nf;
  s->stats.tangent_bytes =
      ((size_t)nf + 1) * sizeof(int) + (size_t)ns->nnz * (2 * sizeof(int) + sizeof(double));
  s->stats.passes_per_tangent = ns->analytic ? 0
                                : s->opts.fd_scheme == PDK_FD_CENTRAL
                                    ? 2L * dim * s->num_colors
                                    : (long)dim * s->num_colors + 1;
  s->stats.time_setup += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

void pdk_newton_free(pdk_static *s) {
  newton_state *ns = s->newton;
  if (!ns) return;
  if (ns->cc_started) {
    cholmod_free_factor(&ns->L, &ns->cc);
    cholmod_finish(&ns->cc);
  }
  if (ns->numeric) umfpack_di_free_numeric(&ns->numeric);
  if (ns->symbolic) umfpack_di_free_symbolic(&ns->symbolic);
  for (int c = 0; c < 3; ++c) {
    free(ns->dof_of[c]);
    free(ns->diag_full[c]);
    free(ns->fa[c]);
    free(ns->x0[c]);
  }
  free(ns->dof_particle);
  free(ns->dof_comp);
  free(ns->Ap);
  free(ns->Ai);
  free(ns->Ax);
  free(ns->tpos);
  free(ns->diag_pos);
  free(ns->h_plus);
  free(ns->h_minus);
  free(ns->saved);
  free(ns->rhs);
  free(ns->dx);
  free(ns->ident_start);
  free(ns->ident);
  free(ns->col_scratch);
  free(ns->col_block);
  free(ns);
  s->newton = NULL;
}

/* ---- Newton iterations ----------------------------------------------------------------------- */

/* Float storage rounds what the force pass stores per neighbour (correspondence: the tensors of
 * pass 2, a relative 2^-24 of the stress) at every evaluation, so the residual carries round-off
 * noise that no Newton step removes, while rtol defaults to 1e-10: near the solution the steps
 * stop contracting (V-Q, manufactured and bar problems: at 1e-9 to 3e-8 of the load norm) and the
 * line search finally stalls. With float storage, a residual below FLT_EPSILON of the load norm
 * (+ atol) that the last step reduced by less than half (`previous` its value before that step;
 * 0 after a stalled line search) is that floor: the level is accepted there, the floor
 * raised to the residual and the level counted in stats.storage_floor_levels. A quadratically
 * converging step reduces ||r|| by far more than half, so the test does not stop a healthy
 * iteration early; double storage never takes this exit. */
static int at_storage_floor(pdk_static *s, double previous) {
  if (s->m->opts.precision != PDK_PRECISION_FLOAT) return 0;
  if (!(s->rnorm <= FLT_EPSILON * s->fnorm + s->opts.atol)) return 0;
  if (!(s->rnorm > 0.5 * previous)) return 0;
  s->floor = fmax(s->floor, s->rnorm);
  s->stats.storage_floor_levels++;
  return 1;
}

int pdk_newton_solve_level(pdk_static *s, long *iterations) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  const int dim = s->dim;
  const pdk_index n = s->n;
  static const char *hint = "the load step may be too large (add load levels) or the model "
                            "undefined at this deformation";
  *iterations = 0;
  PDK_CALL(pdk_static_residual(s));
  if (!isfinite(s->rnorm) || !isfinite(s->fnorm)) return pdk_static_nonfinite(s, "newton", 0, hint);
  int reuse = 0;              /* never across rounds or levels: bonds broke or the load moved */
  double previous = INFINITY; /* ||r|| before the last step */
  s->stats.residual_history_len = 0;
  for (long it = 0;; ++it) {
    if (s->stats.residual_history_len < 16)
      s->stats.residual_history[s->stats.residual_history_len++] = s->rnorm;
    if (pdk_static_converged(s) || at_storage_floor(s, previous)) return PDK_SUCCESS;
    previous = s->rnorm;
    if (it == s->opts.max_iterations)
      return pdk_ctx_error_set(
          ctx, PDK_ERR_NUMERIC, "newton",
          "Newton did not converge in %ld iterations at load level %d (load factor %g), round %d: "
          "residual %.3e against a tolerance of %.3e (rtol %g x load norm %.3e + atol %g); add "
          "load levels or raise max_iterations",
          it, s->level, s->lambda, s->round, s->rnorm, s->opts.rtol * s->fnorm + s->opts.atol,
          s->opts.rtol, s->fnorm, s->opts.atol);
    if (reuse) { /* the last full step contracted ||r|| by >= 1000: keep the factorized tangent */
      for (long k = 0; k < ns->nf; ++k)
        ns->rhs[k] = s->r[ns->dof_comp[k]][ns->dof_particle[k]];
      PDK_CALL(pdk_newton_solve_linear(s));
      s->stats.tangent_reuses++;
    } else {
      PDK_CALL(pdk_newton_assemble_tangent(s));
      PDK_CALL(pdk_newton_factor_and_solve(s));
    }
    /* Backtracking line search on ||r||. */
    const double phi0 = s->rnorm;
    for (int c = 0; c < dim; ++c)
      memcpy(ns->x0[c], pdk_newton_field(s->p, "x", c), (size_t)n * sizeof(double));
    double alpha = 1.0;
    int accepted = 0;
    for (int bt = 0; bt <= s->opts.max_backtracks; ++bt) {
      for (long k = 0; k < ns->nf; ++k) {
        const pdk_index i = ns->dof_particle[k];
        const int c = ns->dof_comp[k];
        if (!pdk_static_frame(s, i)) pdk_newton_field(s->p, "x", c)[i] = ns->x0[c][i] + alpha * ns->dx[k];
      }
      for (pdk_index i = 0; s->dir_of && i < n; ++i) { /* dx in the particle's frame: x += R dx */
        const double(*R)[3] = pdk_static_frame(s, i);
        if (!R) continue;
        for (int c = 0; c < dim; ++c) {
          double d = 0.0;
          for (int q = 1; q < dim; ++q)
            d += R[c][q] * ns->dx[ns->dof_of[q][i]];
          pdk_newton_field(s->p, "x", c)[i] = ns->x0[c][i] + alpha * d;
        }
      }
      PDK_CALL(pdk_static_residual(s));
      if (isfinite(s->rnorm) && isfinite(s->fnorm) &&
          (s->rnorm <= (1.0 - s->opts.ls_decrease * alpha) * phi0 || pdk_static_converged(s))) {
        accepted = 1;
        break;
      }
      alpha *= 0.5;
      s->stats.line_search_cuts++;
    }
    *iterations = it + 1;
    reuse = s->opts.reuse_tangent && accepted && alpha == 1.0 && s->rnorm <= 1e-3 * phi0;
    if (!accepted) {
      for (int c = 0; c < dim; ++c)
        memcpy(pdk_newton_field(s->p, "x", c), ns->x0[c], (size_t)n * sizeof(double));
      const double tried = s->rnorm;
      PDK_CALL(pdk_static_residual(s));
      if (at_storage_floor(s, 0.0)) return PDK_SUCCESS;
      return pdk_ctx_error_set(
          ctx, PDK_ERR_NUMERIC, "newton",
          "the line search failed at load level %d (load factor %g), round %d, iteration %ld: "
          "residual %.3e (%.2e of the load norm) did not decrease along the Newton direction "
          "(%.3e at step %g; round-off floor %.3e). Add load levels (the step is too large for the "
          "tangent) or check that the model is smooth at this deformation",
          s->level, s->lambda, s->round, it + 1, phi0, s->fnorm > 0 ? phi0 / s->fnorm : 0.0, tried,
          2.0 * alpha, s->floor);
    }
  }
}
