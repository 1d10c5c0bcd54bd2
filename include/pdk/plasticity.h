/* Finite-strain J2 plasticity with Johnson-Cook hardening and Johnson-Cook damage, one material
 * point.
 *
 * The per-point update pdk_jc_update is a pure function (no allocation, no context, no globals):
 * the correspondence model calls it once per particle in its pass 1 with the particle's
 * deformation gradient F and history, and gets the first Piola-Kirchhoff stress P, the updated
 * history, energy densities and whether the particle failed. The formulation, the definitions
 * (yield in Kirchhoff stress, plastic strain rate, triaxiality, D_c) and why they were chosen are
 * in the header comment of kernels/ref/jc.c. In short:
 *
 *   F = Fe Fp, history C_p^-1 = Fp^-1 Fp^-T (reference frame, so the model is objective by
 *   construction), Hencky elasticity tau = K tr(eps_e) 1 + 2 mu dev(eps_e), eps_e = ln V_e,
 *   exponential-map radial return in principal logarithmic strains (Simo 1992, Eterovic-Bathe
 *   1990), von Mises yield in Kirchhoff stress q(tau) = sqrt(3/2 dev tau : dev tau) <= sigma_y,
 *     sigma_y = (A + B eps_p^n) [1 + C ln(rate*)] [1 - T*^m]
 *   (the bracketed factors only when switched on: C != 0, thermal != 0),
 *     D = sum d eps_p / eps_f,  eps_f = [D1 + D2 exp(D3 eta)] [1 + D4 ln(rate*)] [1 + D5 T*],
 *   the point fails when D >= D_c and then carries no stress (PDK_JC_FAILED_ZERO) or only a
 *   compressive pressure (PDK_JC_FAILED_COMPRESSION).
 *
 * Use in a model (correspondence pass 1, per particle i): F_i = N_i K_i^-1 as now; then
 *   pdk_jc_update(params, dim, F_i, dt, &hist_old[i], &hist_new[i], P_i, &res)
 * with hist_old the committed histories and hist_new a scratch copy (a trial force pass leaves
 * hist_old alone; a committing pass swaps or copies them), A_i = P_i K_i^-1, W_i = res.W, and
 * res.failed_now / hist.failed as the signal to degrade or break the particle's bonds. A nonzero
 * return (det F <= 0) should be handled like the Neo-Hooke inversion flag. Call
 * pdk_jc_params_check once at model creation; the update itself does not validate parameters.
 *
 * Units: any consistent set; the defaults are SI (Pa, kg/m^3, J/(kg K), K, 1/s). Energies are per
 * unit reference volume [energy/length^3] = [pressure].
 *
 * Tensors are row-major 3 x 3 arrays; in plane strain (dim = 2) only the top-left 2 x 2 block of F
 * is read and of P written (F33 = 1, F13 = F23 = F31 = F32 = 0 implied); the out-of-plane stress
 * is in pdk_jc_result.sigma. Symmetric tensors with 6 entries are in Voigt order
 * xx, yy, zz, yz, xz, xy.
 */
#ifndef PDK_PLASTICITY_H
#define PDK_PLASTICITY_H

#include "pdk/export.h"
#include "pdk/ctx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How damage degrades the stress before failure. */
typedef enum pdk_jc_coupling {
  PDK_JC_COUPLING_NONE = 0,     /* Johnson-Cook 1985: D is an indicator, the stress is undamaged
                                   until D >= D_c (default) */
  PDK_JC_COUPLING_EFFECTIVE = 1 /* continuum damage, strain equivalence: tau = (1 - D) tau~, the
                                   return map acting on the effective stress tau~ */
} pdk_jc_coupling;

/* What a failed point (D >= D_c) carries from the step it fails on. */
typedef enum pdk_jc_failed {
  PDK_JC_FAILED_ZERO = 0,       /* no stress at all: P = 0, W = 0 (default) */
  PDK_JC_FAILED_COMPRESSION = 1 /* a pressure only in compression: tau = K ln(J) 1 for J < 1,
                                   0 for J >= 1; no shear, no tension */
} pdk_jc_failed;

typedef struct pdk_jc_params {
  /* elasticity (Hencky) */
  double density;       /* rho0 [mass/length^3], reference density (adiabatic heating) */
  double young_modulus; /* E [pressure] */
  double poisson_ratio; /* nu, -1 < nu < 0.5 */
  /* Johnson-Cook hardening: sigma_y = (A + B eps_p^n)(1 + C ln rate*)(1 - T*^m) */
  double A, B, n;       /* [pressure], [pressure], [-]; A >= 0, B >= 0, A + B > 0, n > 0 */
  double C;             /* rate sensitivity [-], >= 0; C == 0: the rate term is absent */
  double ref_rate;      /* reference plastic strain rate [1/time] > 0 (used when C or D4 != 0);
                           rate* = max(eps_p_rate / ref_rate, 1) */
  int thermal;          /* 0: no temperature (T* = 0, no m term, no heating, D5 term absent);
                           1: T* = (T - T_room)/(T_melt - T_room) clamped to [0, 1],
                           T = T_initial + temp_rise, adiabatic heating with beta */
  double m;             /* thermal softening exponent [-] > 0 (thermal = 1) */
  double T_room;        /* reference (room) temperature of the fit [K] */
  double T_melt;        /* melting temperature [K] > T_room */
  double T_initial;     /* temperature of the material before any heating [K] */
  double beta;          /* Taylor-Quinney fraction of plastic work turned into heat, 0..1 */
  double heat_capacity; /* c_p [energy/(mass K)] > 0 */
  /* Johnson-Cook damage: eps_f = [D1 + D2 exp(D3 eta)][1 + D4 ln rate*][1 + D5 T*] */
  int damage; /* 0: no damage, no failure; 1: accumulate D and fail at D >= D_c */
  double D1, D2, D3, D4, D5;
  double D_c; /* critical damage, 0 < D_c <= 1: the point fails when D >= D_c */
  pdk_jc_coupling coupling;
  pdk_jc_failed failed_mode;
} pdk_jc_params;

/* Defaults: the V-JC steel of the thesis fracture case (Bode 2021 section 8.1, parameters of
 * Broumand & Khoei 2015, 4340-type): rho0 7830 kg/m^3, E 200 GPa, nu 0.29, A 792 MPa,
 * B 510 MPa, n 0.26, D1 0.05, D2 3.44, D3 -2.12, D_c 0.3, rate and thermal terms off (C = 0,
 * D4 = 0, D5 = 0, thermal = 0), no stress coupling, failed points carry no stress. The values for
 * the optional terms are Johnson-Cook's 4340 steel ones, ready to switch on: ref_rate 1/s,
 * m 1.03, T_room 293 K, T_melt 1793 K, T_initial = T_room, beta 0.9, c_p 477 J/(kg K);
 * (C = 0.014, D4 = 0.002, D5 = 0.61 in Johnson & Cook 1983/1985, left at 0 here). */
PDK_EXPORT pdk_jc_params pdk_jc_params_default(void);

/* Checks every parameter; on failure records a message naming the parameter, its value and the
 * allowed range in ctx and returns PDK_ERR_ARG. */
PDK_EXPORT int pdk_jc_params_check(pdk_ctx *ctx, const pdk_jc_params *params);

/* History of one material point. */
typedef struct pdk_jc_state {
  double cp_inv[6]; /* C_p^-1 = Fp^-1 Fp^-T (Voigt xx yy zz yz xz xy); identity at start, det 1
                       unless pdk_jc_remap changed it (plastic steps keep the det) */
  double eps_p;     /* equivalent plastic strain [-] (logarithmic) */
  double damage;    /* D [-], in [0, 1] (capped at 1 on the step the point fails) */
  double temp_rise; /* adiabatic temperature rise [K] */
  int failed;       /* 1 once D >= D_c; the history is frozen from then on */
} pdk_jc_state;

/* Virgin state: C_p^-1 = 1, eps_p = D = temp_rise = 0, not failed. */
PDK_EXPORT pdk_jc_state pdk_jc_state_initial(void);

/* What a step produced besides P and the history. Energies per unit reference volume. */
typedef struct pdk_jc_result {
  double W;            /* stored (elastic) energy density after the step, (1 - D) W~ with coupling,
                          0 for a failed point (K/2 ln(J)^2 for J < 1 with FAILED_COMPRESSION) */
  double dW_plastic;   /* plastic dissipation of the step: (1 - D_mid) int sigma_y d eps_p over
                          the step (exact integral of the hardening curve; D_mid = (D_n + D)/2
                          with coupling, 0 without), >= 0 */
  double dW_damage;    /* energy released by damage this step: W~ dD with coupling, plus, on the
                          step the point fails, the stored energy minus what the failed point keeps */
  double tau_vm;       /* von Mises Kirchhoff stress of the returned stress, sqrt(3/2 s:s) */
  double sigma_vm;     /* von Mises Cauchy stress, tau_vm / J */
  double sigma[6];     /* Cauchy stress (Voigt), 3-D also in plane strain (sigma_zz) */
  double J;            /* det F */
  double yield_stress; /* sigma_y at the end of the step (effective, before (1 - D)) */
  double d_eps_p;      /* plastic strain increment of the step */
  double eps_p_rate;   /* d_eps_p / dt [1/time] (0 if dt <= 0) */
  double triaxiality;  /* eta = sigma_m / sigma_vm used for the damage increment (0 if no flow) */
  double sigma_m_eff;  /* effective Cauchy mean stress tau_m / J (before (1 - D) with coupling),
                          the point's own pressure input to eta; 0 for a failed point */
  double failure_strain; /* eps_f used for the damage increment (0 if no flow) */
  int plastic;           /* 1 if the step yielded */
  int failed_now;        /* 1 if the point failed in this step */
} pdk_jc_result;

/* One step of one material point. Pure: reads params, F and *in, writes *out, P and *res (res may
 * be NULL). in and out may be the same object; with different objects the call is a trial that
 * leaves the committed history alone.
 *   dim: 2 (plane strain) or 3.   F: deformation gradient at the end of the step, det F > 0.
 *   dt:  step length [time]; only read when a rate term is on (C != 0 or D4 != 0), then > 0.
 *   P:   first Piola-Kirchhoff stress [pressure], d x d block written.
 * Returns 0, or PDK_ERR_ARG (dim not 2 or 3, dt <= 0 with a rate term), or PDK_ERR_NUMERIC
 * (F not finite or det F <= 0); on error nothing is written. A failed point (in->failed) returns
 * P = 0 (or the compressive pressure) and copies the history unchanged. */
PDK_EXPORT int pdk_jc_update(const pdk_jc_params *params, int dim, const double F[3][3], double dt,
                             const pdk_jc_state *in, pdk_jc_state *out, double P[3][3],
                             pdk_jc_result *res);

/* The same step with the damage triaxiality taken from a given mean stress instead of the
 * point's own: eta = sigma_m_avg J / q (q the von Mises Kirchhoff stress of the returned effective
 * stress), i.e. sigma_m_avg over the point's own von Mises Cauchy stress. sigma_m_avg is an
 * effective Cauchy mean stress, as pdk_jc_result.sigma_m_eff; the correspondence model passes the
 * family average of its neighbours' sigma_m_eff from the previous step (pdk_model_opts
 * damage_triaxiality). Everything else is pdk_jc_update's; with sigma_m_avg equal to the point's
 * own sigma_m_eff the two agree to round-off. */
PDK_EXPORT int pdk_jc_update_avg(const pdk_jc_params *params, int dim, const double F[3][3],
                                 double dt, double sigma_m_avg, const pdk_jc_state *in,
                                 pdk_jc_state *out, double P[3][3], pdk_jc_result *res);

/* Remap of the history when the deformation gradient of a point changes for a reason other than
 * motion (a correspondence particle's family lost bonds, so its fitted F jumped from F_old to
 * F_new at the same positions): C_p^-1 <- F_new^-1 (F_old C_p^-1 F_old^T) F_new^-T, so the
 * elastic state b_e, the stress and the stored energy at F_new are those at F_old. det C_p^-1
 * then differs from 1 (by (J_old / J_new)^2: the jump of the fitted volume is not an elastic
 * volume change), and later plastic steps keep it. eps_p, D and the temperature are unchanged; a
 * failed point is left alone. Returns PDK_ERR_NUMERIC (s unchanged) for a non-finite F or
 * det F <= 0. */
PDK_EXPORT int pdk_jc_remap(int dim, const double F_old[3][3], const double F_new[3][3],
                            pdk_jc_state *s);

/* The law's pieces, for outputs and tests: the flow stress at plastic strain eps_p, rate
 * factor argument rate_star (ignored unless C != 0) and homologous temperature T_star (ignored
 * unless thermal); the failure strain at triaxiality eta. Both apply the clamps of the update. */
PDK_EXPORT double pdk_jc_flow_stress(const pdk_jc_params *params, double eps_p, double rate_star,
                                     double T_star);
PDK_EXPORT double pdk_jc_failure_strain(const pdk_jc_params *params, double eta, double rate_star,
                                        double T_star);

#ifdef __cplusplus
}
#endif
#endif
