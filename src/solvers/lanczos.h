/* Private: the largest eigenvalue of a model's stiffness by Lanczos on trial-force differences,
 * shared by the explicit solver's stable-step estimate (explicit.c) and adaptive dynamic
 * relaxation's uniform fictitious mass (adr.c). */
#ifndef PDK_LANCZOS_H
#define PDK_LANCZOS_H

#include "models/model_impl.h"
#include "pdk/model.h"

#define PDK_LANCZOS_MAX_STEPS 40

typedef struct pdk_lanczos_opts {
  int steps; /* Lanczos steps, 1..PDK_LANCZOS_MAX_STEPS (fewer when the Krylov space closes) */
  /* The inner product and the operator: 1 with the mass, lambda_max(M^-1 K) in the M-inner
   * product, M_ii = rho_i V_i (pdk_model_density_of); 0 with the volume, lambda_max(V^-1 K) in
   * the V-inner product (a unit density). */
  int mass;
  double horizon; /* the probe step is 1e-7 horizon / max |q_i| */
  uint64_t salt;  /* start vector: pseudo-random from the particle id, c and this salt */
  /* Normalization of the start vector: 1 multiplies by 1 / |q|, 0 divides by |q| (the two callers
   * were written apart; each keeps the bits it had). */
  int scale_by_inverse;
  /* 1: "f" is left as the forces at the current state (an extra copy); 0: "f" and the fields a
   * force pass derives from "x" are left as the last probe's. "x" is always restored bit for bit.
   */
  int restore_f;
} pdk_lanczos_opts;

/* Largest eigenvalue of M^-1 K (or V^-1 K, opts.mass) at the current "x" by Lanczos, with
 * K q ~ -V (f(x + eps q) - f(x)) / eps from trial force passes (no history changes). Converges
 * to lambda_max from below: 40 steps give the top of the spectrum to about a percent on lattices.
 * *lambda_max is the Sturm-bisection top of the tridiagonal matrix; it may be 0, negative or not
 * finite (a body without stiffness): the caller decides. *passes (may be NULL) gets the number of
 * force passes done. Errors: memory, and those of pdk_model_force_trial. */
int pdk_lanczos_max_eig(pdk_model *m, const pdk_lanczos_opts *opts, double *lambda_max,
                        long *passes);

#endif
