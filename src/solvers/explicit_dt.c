/* The explicit solver's stable time step: the Lanczos estimate (at creation and at each
 * re-estimate of a dt_update) and the state-following trigger of dt_update: auto.
 *
 * auto. The stable step of a body that deforms much follows its deformed spacing: a family
 * crushed to a fraction r of its initial length along a direction stiffens its particle like
 * 1/r^2 (correspondence: the stress is pulled back through F^-1; updated-Lagrangian: the shape
 * is the current one), so the step falls like r. After every step the solver measures
 * r = min over intact bonds of the initial families of |x_j - x_i| / |X_j - X_i| (rigid motions
 * do not count; one read of the bonds, a min-reduction, exact in any order and thread count) and
 * re-runs the Lanczos estimate when r fell below AUTO_DROP times its value at the last estimate.
 * dt is lowered to safety x the estimate when above it, as with periodic. A run whose bonds never
 * shorten by AUTO_DROP keeps its first estimate, bit for bit the run of dt_update: none.
 * Checked every step: an impact crushes the first layer by 8% of a spacing per step
 * (tests/scenes/t261_taylor_proxy.yaml at 0.8 of its first estimate), so a check every 8 steps
 * re-estimated only once the step was 0.98 of the stable one. The bond read costs about a PMB
 * force pass (measured +38% and +80% CPU on the shipped bar and block), so it is skipped while
 * the particles' relative displacement since the last read cannot have crossed the trigger (an
 * O(n) read of x; pdk_explicit_auto_dt).
 * The energy account of the Taylor proxy (tests/t261, safety 0.8) then ends 1.2% off, a loss:
 * the plastic update's error at the impact's first steps, which shrinks like dt^2 (0.63% at
 * safety 0.6, 0.43% at 0.5); following the estimate more closely (a 5% trigger) or taking a
 * fraction of it once the body flows did not lower it (1.2%, 1.0%).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "explicit_impl.h"
#include "lanczos.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define AUTO_DROP 0.9

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

/* Largest eigenvalue of M^-1 K by Lanczos in the M-inner product (lanczos.h): trial forces, no
 * history changes; the estimate is a lower bound of lambda_max. "x" comes back bit for bit, "f"
 * and the fields derived from "x" are the last probe's. */
int pdk_explicit_estimate_dt(pdk_explicit *e, int mid_run) {
  pdk_lanczos_opts lo = {0};
  lo.steps = 40;
  lo.mass = 1;
  lo.horizon = pdk_families_horizon(e->m->fam);
  lo.salt = 1;
  lo.scale_by_inverse = 1;
  lo.restore_f = 0;
  double lmax = 0.0;
  PDK_CALL(pdk_lanczos_max_eig(e->m, &lo, &lmax, NULL));
  /* during a run a body may have lost every bond (fragments that fly apart): nothing limits
   * the step any more, and the last estimate stands */
  if (mid_run && !(isfinite(lmax) && lmax > 0)) return PDK_SUCCESS;
  PDK_CHECK(isfinite(lmax) && lmax > 0, e->ctx, PDK_ERR_NUMERIC,
            "the stable time step could not be estimated (largest stiffness eigenvalue %g); "
            "the body may have no stiffness (no bonds?)",
            lmax);
  e->dt_stable = 2.0 / sqrt(lmax);
  return PDK_SUCCESS;
}

/* dt_update: a new estimate at the current state (trial forces only), and dt lowered to safety x
 * it when above. The estimate moves "x" and overwrites "f" and the fields a force pass derives
 * from "x" ("F", "A", "theta", ...): positions come back bit for bit from the estimate itself, the
 * fields from one more trial pass at them, and "f" (what the next half kick reads) from a copy,
 * since a trial pass from the committed history need not give the committing pass's bits. */
int pdk_explicit_update_dt(pdk_explicit *e, double safety) {
  int err = PDK_SUCCESS;
  const size_t bytes = (size_t)e->n * sizeof(double);
  double *f_save[3] = {NULL, NULL, NULL};
  for (int c = 0; c < e->dim; ++c) {
    f_save[c] = malloc(bytes ? bytes : 1);
    PDK_CHECK_GOTO(f_save[c], e->ctx, PDK_ERR_MEMORY,
                   "out of memory re-estimating the stable time step");
    memcpy(f_save[c], field(e->p, "f", c), bytes);
  }
  PDK_CALL_GOTO(pdk_explicit_estimate_dt(e, 1));
  PDK_CALL_GOTO(pdk_model_force_trial(e->m, NULL));
  for (int c = 0; c < e->dim; ++c) memcpy(field(e->p, "f", c), f_save[c], bytes);
  e->num_estimates++;
  e->est_step = e->step;
  e->est_broken = pdk_model_num_broken(e->m);
  /* lowered when more than 0.1% above safety x the estimate: an estimate that moves by round-off
   * or a fraction of a percent (40 Lanczos steps resolve the top of the spectrum to about that)
   * does not change dt at every estimate */
  if (safety * e->dt_stable * (1.0 + 1e-3) < e->dt) {
    e->dt = safety * e->dt_stable;
    e->dt_step0 = e->step;
    e->dt_time0 = e->time;
    e->num_dt_changes++;
    PDK_CALL_GOTO(pdk_model_set_dt(e->m, e->dt));
  }
cleanup:
  for (int c = 0; c < 3; ++c) free(f_save[c]);
  return err;
}

/* The smallest ratio of current to initial length over the intact bonds of the initial families
 * (1 with no bonds); with xi_min, the smallest initial length over all bonds there too. */
double pdk_explicit_min_bond_ratio(pdk_explicit *e, double *xi_min) {
  const pdk_families *fam = e->m->fam;
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const uint8_t *alive = pdk_model_bond_alive(e->m);
  const int dim = e->dim;
  const double *x[3] = {NULL, NULL, NULL}, *X[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    x[c] = field(e->p, "x", c);
    X[c] = pdk_particles_X(e->p, c);
  }
  const pdk_index n = e->n;
  double rmin2 = INFINITY, ximin2 = INFINITY;
  const int want_xi = xi_min != NULL;
  int nthreads = e->ctx->num_threads;
#pragma omp parallel for default(none) shared(bs, bj, alive, dim, x, X, n, want_xi) reduction(min : rmin2, ximin2) schedule(static) num_threads(nthreads)
  for (pdk_index i = 0; i < n; ++i) {
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      if (j < i) continue; /* every bond is stored from both ends */
      double y2 = 0.0, r2 = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double y = x[c][j] - x[c][i], r = X[c][j] - X[c][i];
        y2 += y * y;
        r2 += r * r;
      }
      if (want_xi && r2 > 0.0 && r2 < ximin2) ximin2 = r2;
      if (alive && !alive[b]) continue;
      if (r2 > 0.0 && y2 < rmin2 * r2) rmin2 = y2 / r2;
    }
  }
  if (xi_min) *xi_min = isfinite(ximin2) ? sqrt(ximin2) : INFINITY;
  return isfinite(rmin2) ? sqrt(rmin2) : 1.0;
}

/* The largest relative displacement of two particles since the last full check, bounded by the
 * diagonal of the bounding box of x - auto_x (min/max reductions: exact in any order). */
static double moved_since_check(pdk_explicit *e) {
  double d2 = 0.0;
  const pdk_index n = e->n;
  int nthreads = e->ctx->num_threads;
  for (int c = 0; c < e->dim; ++c) {
    const double *x = field(e->p, "x", c), *x0 = e->auto_x + (size_t)c * (size_t)n;
    double lo = INFINITY, hi = -INFINITY;
#pragma omp parallel for default(none) shared(x, x0, n) reduction(min : lo) reduction(max : hi) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      const double u = x[i] - x0[i];
      lo = u < lo ? u : lo;
      hi = u > hi ? u : hi;
    }
    if (n) d2 += (hi - lo) * (hi - lo);
  }
  return sqrt(d2);
}

/* The trigger (file comment). The full check reads every bond; it is skipped when the positions
 * since the last one cannot have brought r below the trigger: a bond shortened by at most D (the
 * relative displacement bound) since then, so r >= r_last - D / xi_min. Skipping only where the
 * full check could not trigger, the decisions are those of a full check at every step (and a
 * restored run, whose first step checks in full, takes the same ones). */
int pdk_explicit_auto_dt(pdk_explicit *e) {
  if (e->opts.dt_update != PDK_DT_UPDATE_AUTO) return PDK_SUCCESS;
  if (e->auto_x && isfinite(e->auto_ximin)) {
    const double bound = e->auto_rlast - moved_since_check(e) / e->auto_ximin;
    if (bound - 1e-9 > AUTO_DROP * e->auto_ratio) return PDK_SUCCESS;
  }
  const double r = pdk_explicit_min_bond_ratio(e, NULL);
  if (!e->auto_x) {
    e->auto_x = malloc((size_t)e->dim * (size_t)(e->n ? e->n : 1) * sizeof *e->auto_x);
    PDK_CHECK(e->auto_x, e->ctx, PDK_ERR_MEMORY, "out of memory for the dt_update auto check");
  }
  for (int c = 0; c < e->dim; ++c)
    memcpy(e->auto_x + (size_t)c * (size_t)e->n, field(e->p, "x", c), (size_t)e->n * sizeof(double));
  e->auto_rlast = r;
  if (!(r < AUTO_DROP * e->auto_ratio)) return PDK_SUCCESS;
  PDK_CALL(pdk_explicit_update_dt(e, e->opts.safety));
  e->auto_ratio = r;
  return PDK_SUCCESS;
}
