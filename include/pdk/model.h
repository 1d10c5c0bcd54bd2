/* Force models: bond-based PMB, ordinary state-based LPS, correspondence, and Peridynamic
 * Galerkin.
 *
 * A model is built over a particle store and its families. It declares the particle fields it
 * needs (only those are allocated):
 *   "x"  f64 x dim  current position [length] (read; the solver advances it)
 *   "f"  f64 x dim  internal force density [force/length^dim] (written by pdk_model_force)
 * plus what its kind needs (LPS: "m" weighted volume, "theta" dilation; correspondence: "Kinv"
 * inverse shape tensor, "F" deformation gradient, "A" = P K^-1, "flag" family-spans-space flag;
 * galerkin: "F" the family's gradient at its own particle, "area" the area vector of the test
 * functions, src/models/model_galerkin.c).
 * Bond state (intact = 1, broken = 0) exists only when the model can break bonds: a critical
 * stretch is set, or the correspondence model uses the Johnson-Cook law with damage and failed
 * particles break their bonds.
 * PMB and LPS with bond state also declare
 *   "w_broken"   f64 x 1  energy released by bond breaking so far [energy/length^3]: the stored
 *                         energy the breaks removed at fixed positions, booked half at the pass
 *                         that broke the bonds and half at the next committing pass
 *                         (src/models/model_bond_book.c), so external work = kinetic + strain +
 *                         breaking closes to second order in the time step.
 *
 * Johnson-Cook law (PDK_LAW_JC, correspondence only; the material point is pdk/plasticity.h).
 * History, declared only with this law, committed by pdk_model_force and never touched by
 * pdk_model_force_trial (a field that exists already when the model is created is kept, as "x"):
 *   "cp_inv"     f64 x 6  plastic metric C_p^-1 (Voigt xx yy zz yz xz xy), identity at start
 *   "eps_p"      f64 x 1  equivalent plastic strain [-]
 *   "damage"     f64 x 1  Johnson-Cook damage D [-]
 *   "temp_rise"  f64 x 1  adiabatic temperature rise [K] (only with jc.thermal = 1)
 *   "failed"     u8  x 1  1 once D >= D_c: the particle carries no stress from then on
 *   "eps_p_rate" f64 x 1  plastic strain rate of the last committed step [1/time]
 *   "w_plastic"  f64 x 1  plastic dissipation so far [energy/length^3 of reference volume]
 *   "w_damage"   f64 x 1  energy released by damage so far [energy/length^3]
 * with stab_softening also
 *   "stab_factor" f64 x 1 factor on the particle's stabilization modulus, 1 at start
 *   "w_stab"     f64 x 1  Silling energy given up by the factor's changes so far [energy/length^3]
 *   "w_silling"  f64 x 1  the Silling term's energy density at the last commit [energy/length^3]
 * with damage_triaxiality family also
 *   "sigma_m"    f64 x 1  effective Cauchy mean stress of the last commit pass [pressure]
 *   "sigma_m_avg" f64 x 1 its family average, the pressure of the damage triaxiality [pressure]
 * and, whenever correspondence bonds can break,
 *   "w_broken"   f64 x 1  energy released by bond breaking so far [energy/length^3]: the drop
 *                         of the particle's stored energy (plus the plastic and damage work the
 *                         jump of F would cause) when its family lost bonds, at fixed positions.
 * Elastic constants: the Johnson-Cook parameters are the one source of truth. With law JC,
 * bulk_modulus, shear_modulus and density may be left 0 and are then set from jc (K = E/(3(1 -
 * 2 nu)), G = E/(2(1 + nu)), rho = jc.density; pdk_model_opts_get shows the values used); when
 * given they must agree with jc to a relative 1e-9, or creation fails naming both values.
 *
 * Units: any consistent set (SI or N-mm-s-tonne). Volumes in 2-D are area x thickness; 2-D
 * models are plane strain.
 *
 * Forces are force densities: the acceleration of particle i is f_i / rho. Every pass is a
 * gather over particle i's own family (bonds stored from both ends), so results do not depend on
 * the thread count.
 */
#ifndef PDK_MODEL_H
#define PDK_MODEL_H

#include "pdk/export.h"
#include "pdk/families.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pdk_model_kind {
  PDK_MODEL_PMB = 0,           /* prototype microelastic brittle, as LAMMPS peri/pmb */
  PDK_MODEL_LPS = 1,           /* linear peridynamic solid, as LAMMPS peri/lps */
  PDK_MODEL_CORRESPONDENCE = 2, /* non-ordinary state-based, total Lagrangian */
  PDK_MODEL_OTERKUS = 3, /* Oterkus' dilatation law, plane strain, any influence function (2-D;
                           Queiruga & Moridis 2017 section 2.3; src/models/model_dil2.c) */
  PDK_MODEL_GALERKIN = 4 /* Peridynamic Galerkin (Bode et al. 2022; Bode 2021 ch. 4-5): the
                            correspondence weak form with shape functions inside each family,
                            deformation gradient and stress at every family member, optional
                            variationally consistent test functions (opts.galerkin;
                            src/models/model_galerkin.c, kernels/ref/galerkin.c) */
} pdk_model_kind;

/* Peridynamic Galerkin options (kind galerkin; docs/validation/galerkin.md). */
typedef enum pdk_galerkin_basis {
  PDK_GALERKIN_TAYLOR = 0, /* moving Taylor expansion MTE1 (Bode 2021 eq. 5.52, Table 5.1): linear,
                              centred at every evaluation point, moving weights 1/r^2 (5.42) */
  PDK_GALERKIN_WLS = 1     /* weighted least squares WLS1/WTE1 centred at the family's particle,
                              static weights 1/r^2 (5.41): one gradient per family, the classical
                              correspondence model without stabilization (t240 checks it) */
} pdk_galerkin_basis;

typedef enum pdk_galerkin_form {
  PDK_GALERKIN_BUBNOV = 0 /* PBG: test = trial, inverse averaging weights V_k V_j / V_H (eq. 4.25,
                             4.30): symmetric tangent for elastic laws */
} pdk_galerkin_form;

typedef enum pdk_galerkin_correction {
  PDK_GALERKIN_NONE = 0, /* the shape functions as they are */
  PDK_GALERKIN_VC1 = 1   /* first-order variational consistency (Bode 2021 section 5.3.2): the
                            derivatives get a correction alpha_k psi_ki, alpha from one global
                            sparse solve at creation, so a constant stress gives no force inside
                            the body; needs the surface set */
} pdk_galerkin_correction;

typedef struct pdk_galerkin_opts {
  pdk_galerkin_basis basis;           /* default taylor */
  pdk_galerkin_form form;             /* default bubnov */
  pdk_galerkin_correction correction; /* default none */
  /* VC1: the name of the particle set (uint8 field "set:<name>") of the particles on the body's
   * surface. Without normals their alpha is held at 0 and their area vector is what the
   * correction leaves, tangential components included (the thesis' correction boundary condition
   * "s"). */
  const char *surface;
  /* VC1, optional: the name of an f64 field of dim components holding the outward unit normal of
   * every surface particle (the thesis' default boundary condition "sn"): only the normal
   * component of alpha is held at 0 and only the normal component of the area vector is left
   * free, so the area vectors of the surface are normal to it (a traction-free surface carries no
   * force under a constant stress with P n = 0). A zero normal (corners, edges) means "s" at that
   * particle. NULL: "s" everywhere. */
  const char *normals;
  /* 1: the bond-mapping correction (Bode 2021 eq. 5.55; Bode et al. 2022 eq. 74): at every
   * evaluation point j != k of family k the derivatives are projected off the bond direction and
   * the bond added back, so F^{kj} maps the bond X_j - X_k exactly. With taylor it makes the
   * thesis' "Unl" shape functions; with vc1 the correction functions then carry the thesis' bond
   * projector (V5, eq. 5.64). 0: none (default). */
  int bond;
} pdk_galerkin_opts;

/* Oterkus law: how the dilatation coefficient a is set (src/models/model_dil2.c). */
typedef enum pdk_oterkus_a {
  PDK_OTERKUS_A_PUBLISHED = 0, /* a = (K - 2G)/2, K the 3-D bulk modulus: what Queiruga & Moridis'
                                  published results used; wrong for isotropic strain */
  PDK_OTERKUS_A_CALIBRATED = 1 /* a_i = (lambda + mu)/2 - G m_i / (8 D_i) per particle: an
                                  isotropic stretch has the plane-strain energy exactly */
} pdk_oterkus_a;

typedef enum pdk_influence {
  PDK_INFLUENCE_CONSTANT = 0, /* 1 */
  PDK_INFLUENCE_INV_R = 1,    /* delta / r */
  PDK_INFLUENCE_INV_R2 = 2,   /* (delta / r)^2 */
  PDK_INFLUENCE_LINEAR = 3,   /* 1 - r/delta */
  PDK_INFLUENCE_CUBIC = 4,    /* (1 - r/delta)^3 */
  PDK_INFLUENCE_GAUSSIAN = 5, /* exp(-(r / (gaussian_width*delta))^2) */
  PDK_INFLUENCE_QUADRATIC = 6 /* (1 - r/delta)^2 */
} pdk_influence;

typedef enum pdk_stabilization {
  PDK_STAB_NONE = 0,
  PDK_STAB_SILLING = 1,  /* Silling 2017: T += (C_s c / m_w) omega z, z = Y - F xi */
  PDK_STAB_HOURGLASS = 2 /* bond-projected hourglass force (Littlewood 2011 form) */
} pdk_stabilization;

typedef enum pdk_law {
  PDK_LAW_LINEAR_ELASTIC = 0, /* small strain: sigma = lambda tr(eps) I + 2 mu eps, P = sigma;
                                 not objective: rotations beyond a few degrees create strain
                                 energy (use svk or neo_hooke for large rotations) */
  PDK_LAW_SVK = 1,            /* St Venant-Kirchhoff: S = lambda tr(E) I + 2 mu E, P = F S */
  PDK_LAW_NEO_HOOKE = 2,      /* compressible: P = mu (F - F^-T) + lambda ln(J) F^-T */
  PDK_LAW_JC = 3 /* finite J2 plasticity, Johnson-Cook hardening and damage (opts.jc) */
} pdk_law;

/* How families follow broken bonds (correspondence; PMB and LPS are always TL). In both modes K
 * (and the weighted volume) of a particle whose family lost bonds is recomputed in the reference
 * configuration from its intact bonds, in the commit pass where they broke, so TL and semi-TL give
 * the same bits until semi-TL detaches a particle. */
typedef enum pdk_connectivity {
  PDK_CONNECTIVITY_TL = 0,      /* total Lagrangian: families fixed, broken bonds carry weight 0; a
                                   particle whose intact bonds no longer span the space is flagged
                                   (no stress of its own) but stays attached by its neighbours' */
  PDK_CONNECTIVITY_SEMI_TL = 1, /* semi-total Lagrangian: the model keeps its own CSR of intact
                                   bonds, compacted in batches (compact_fraction), so passes walk
                                   intact bonds only; a particle whose family no longer spans is
                                   detached: all its bonds break, it moves freely, carries no
                                   stress and counts in num_flagged (a cascade to neighbours that
                                   become degenerate in turn is followed in the same pass) */
  PDK_CONNECTIVITY_UL = 2 /* updated Lagrangian (Bergel & Li 2016), src/models/model_corr_ul.c: spatial
                             shape tensor M = sum omega V Y (x) Y, F^ = M N^-T relative to the
                             configuration of the last rebuild (times the F stored there), Cauchy
                             (Kirchhoff) stress force states sigma M^-1 Y; the families are rebuilt
                             in the current configuration by a committing pass when particles
                             moved more than ul_skin delta / 2 since the last rebuild, and the
                             reference data (positions, volumes, F) are updated there; a rebuild
                             never bonds across a pre-crack. No bond breaking, no float storage
                             yet.
                             Rebuilt bonds weigh omega(min(initial, current length)), which keeps
                             rebuilt runs stable in tension with an influence function that
                             vanishes at the horizon (linear, cubic; t133). docs/connectivity.md */
} pdk_connectivity;

typedef enum pdk_precision {
  PDK_PRECISION_DOUBLE = 0,
  PDK_PRECISION_FLOAT = 1 /* float storage of per-bond/neighbour data, double accumulation.
                             PMB and LPS: the reference bond length |X_j - X_i| is stored per bond
                             as a float (4 bytes per bond) instead of recomputed from X; the
                             stretch then carries an absolute error up to 2^-24 (6e-8), at rest
                             too, whatever the distance from the origin (t027 states the force
                             bound). Correspondence TL/semi-TL: the tensors pass 2 gathers from
                             neighbours (kernels/kernels.h, pdk_corr_arrays Bf, Gf) are floats;
                             kinds that do not implement it refuse it (PDK_ERR_UNSUPPORTED) */
} pdk_precision;

/* PMB and LPS with precision double on the general (csr) path: whether each bond's reference
 * length |X_j - X_i| is stored (8 bytes per bond, computed once when the model is created, with
 * the operations the force passes use, so the same bits) or recomputed from the reference
 * positions in every pass (a square root and, for PMB, the neighbour's reference row per bond).
 * Results are identical either way; stored is faster (bench/README.md, "Force loops") and costs
 * the memory: 8 bytes per bond, 0.94 GB on a 10^6-particle cube with 118 bonds per particle,
 * where the families themselves hold 4 bytes per bond. Nothing is stored with the SIMD kernels
 * off (PDK_KERNELS=ref), with precision float (which stores float lengths), layout sell or the
 * stencil path, and for the other kinds. */
typedef enum pdk_bond_lengths {
  PDK_BOND_LENGTHS_STORED = 0,  /* (default) stored per bond */
  PDK_BOND_LENGTHS_COMPUTED = 1 /* recomputed in every pass: 8 bytes per bond less */
} pdk_bond_lengths;

/* How the force passes store the families (PMB and LPS; src/space/sell.h, kernels/kernels.h). */
typedef enum pdk_layout {
  PDK_LAYOUT_CSR = 0, /* the families' CSR rows: the SIMD lanes run along one particle's bonds */
  PDK_LAYOUT_SELL = 1 /* sliced (SELL-C-sigma): slices of C consecutive particles (C = the SIMD
                         lanes of the kernel table: 8 AVX-512, 4 AVX2, 8 reference), bonds stored
                         column-major so each lane is one particle, rows sorted by family length
                         inside windows of sell_sigma particles (Morton order kept otherwise),
                         padded with weight-0 bonds. A copy of the families in that order (4 B per
                         entry, + 1 B bond state, + 4 B float storage). Forces equal csr's up to
                         summation order; bond failure bit for bit. Speed against csr:
                         bench/README.md, "Force loops" (an option, not the default) */
} pdk_layout;
/* The stencil path of the PMB, LPS and correspondence force passes (src/models/model_stencil.c,
 * kernels/opt/pmb_stencil.h, lps_stencil.h, corr_stencil.h; LPS with LAMMPS's influence function
 * only; correspondence with tl connectivity and stabilization none or silling, xi and omega taken
 * per offset, so particles on their lattice points to round-off): when the
 * particles sit on a simple cubic (3-D) or square (2-D) lattice aligned with the axes (reference
 * positions origin + integer index x spacing within 1e-6 spacings, one particle per site), every
 * family is a subset of one fixed list of site offsets, and the pass loops over the offsets outside
 * and over runs of sites along x inside, reading neighbours as contiguous vector loads (no bond
 * index stream, no gathers). Bonds missing from a family (boundaries, holes, pre-cracks) and
 * broken bonds are honoured exactly. Same per-bond arithmetic as the general path, so stretches and
 * bond failure are the same bits; forces and energies differ by the order of the family sums only
 * (round-off, tests/t160). */
typedef enum pdk_stencil_mode {
  PDK_STENCIL_OFF = 0,  /* the general (CSR) path */
  PDK_STENCIL_AUTO = 1, /* the stencil path when it applies, the general path otherwise */
  PDK_STENCIL_ON = 2    /* the stencil path; model creation fails, saying why, when it does not
                           apply (not a lattice, several materials for pmb and lps,
                           correspondence with semi_tl, ul or hourglass stabilization) */
} pdk_stencil_mode;

/* One material of a multi-material body (pdk_model_opts.materials). */
/* The mean stress in the Johnson-Cook damage triaxiality eta = sigma_m / sigma_vm (law jc). */
typedef enum pdk_damage_triaxiality {
  PDK_TRIAX_LOCAL = 0, /* the particle's own (default) */
  PDK_TRIAX_FAMILY = 1 /* the average of the previous commit pass's effective mean stresses over
                          the particle and its intact family, weights omega V (the particle's own
                          with weight V_i): removes a particle-to-particle alternation of the
                          pressure from the damage (it appears with softened stabilization) while
                          a smooth pressure field passes unchanged. Field "sigma_m" holds each
                          particle's own, "sigma_m_avg" the average. tl and semi_tl only. */
} pdk_damage_triaxiality;

/* What a Johnson-Cook particle's stress does when its family loses bonds (law jc, bonds that
 * break, tl or semi_tl). F_i = N_i K_i^-1 is a fit over the intact family; when bonds break the
 * fit changes at the same positions, by much where the motion inside the family is far from
 * affine (a weakly stabilized plastic zone). */
typedef enum pdk_break_stress {
  PDK_BREAK_STRESS_REFIT = 0,     /* (default) the stress follows the new fit: the jump of F is
                                     a deformation increment of the law (elastic and plastic) */
  PDK_BREAK_STRESS_CONTINUOUS = 1 /* the history is remapped (pdk_jc_remap) so the elastic state,
                                     the stress and the stored energy do not jump: the new fit is
                                     a new estimate of the same material state, not a
                                     deformation. Measured on the two-hole plate with softened
                                     stabilization: the breaks no longer make energy (docs/
                                     validation/plate_two_holes.md item 9) */
} pdk_break_stress;

typedef struct pdk_material {
  double bulk_modulus;  /* K [pressure] */
  double shear_modulus; /* G [pressure] (PMB: ignored) */
  double density;       /* rho [mass / length^3] */
} pdk_material;

typedef struct pdk_model_opts {
  pdk_model_kind kind;
  double bulk_modulus;  /* K [pressure], 3-D bulk modulus (plane strain uses lambda = K - 2G/3) */
  double shear_modulus; /* G [pressure] (ignored by PMB, whose Poisson ratio is fixed) */
  double density;       /* rho [mass / length^3] */
  /* Critical-stretch failure (PMB, LPS; an extra criterion elsewhere), LAMMPS s0 rule:
   * a bond breaks when its stretch exceeds min(s0_i, s0_j); after each force pass
   * s0_i = s00 - alpha * min_j(stretch_ij). critical_stretch = s00 <= 0: no stretch criterion. */
  double critical_stretch;
  double alpha;
  /* LAMMPS partial-volume scaling of neighbours near the horizon edge (half_lc = lattice/2);
   * 0: off (full volumes). */
  double lattice_constant;
  pdk_influence influence; /* correspondence and oterkus; lps with lps_use_influence (otherwise
                              LPS uses LAMMPS's omega = 1/r and PMB a constant, as LAMMPS) */
  /* LPS: 0 (default) LAMMPS's omega = 1/r (2-D and 3-D, kernels/ref/lps.c); 1: omega = influence,
   * Silling's law in plane strain (2-D only, no bond breaking; src/models/model_dil2.c). */
  int lps_use_influence;
  pdk_oterkus_a oterkus_a; /* oterkus model (default published) */
  double gaussian_width;   /* for PDK_INFLUENCE_GAUSSIAN, fraction of delta (default 0.5) */
  pdk_stabilization stabilization;
  double stab_coefficient; /* C_s (Silling) or the hourglass coefficient; default 0.1 */
  /* Softened Silling stabilization (law jc, stabilization silling, connectivity tl or semi_tl):
   * 0 (default) off; 1: particle i's stabilization modulus is scaled by a factor f_i, 1 at start,
   * that every commit pass lowers to min(1, max(stab_softening_floor, sigma_vm,i / (E eps_p,i)))
   * once the particle has flowed (eps_p > 0) and never raises (Bode 2021 eq. 6.20: the
   * stabilization follows the plastic secant modulus E~ = sigma_vm / eps_p, so it does not hold
   * back localization with the elastic stiffness; the thesis' rule also lets f rise again on
   * reloading, which pumps energy into the modes the term controls, kernels/ref/corr.c). The
   * Silling energy a drop of f takes away is booked per particle in the field "w_stab" and
   * counted with the plastic work (pdk_model_plastic_work), so the energy balance holds. */
  int stab_softening;
  double stab_softening_floor; /* the factor's floor, in (0, 1]; default 1e-3 (the thesis') */
  pdk_damage_triaxiality damage_triaxiality; /* law jc with damage: the pressure of the damage
                                                triaxiality (default local) */
  pdk_break_stress break_stress; /* law jc with bond breaking (default refit) */
  pdk_law law;
  pdk_precision precision;
  /* Johnson-Cook material (law PDK_LAW_JC; default pdk_jc_params_default(), the V-JC steel). Its
   * coupling and failed_mode say how damage acts on the stress before and after failure. */
  pdk_jc_params jc;
  /* 1: a failed particle keeps its bonds (Bode 2021 section 8.1: continuum damage only, the
   * failed particle carries no stress of its own); 0 (default): it breaks all of them, from both
   * ends, in the commit pass where it fails, so no force crosses the crack. */
  int failed_keeps_bonds;
  pdk_connectivity connectivity;
  /* semi-TL: compact the bond list when the broken bonds still in it exceed this fraction of its
   * length (0: in every commit pass that broke bonds; default 0.02). Never when nothing broke. */
  double compact_fraction;
  /* UL: the skin, as a fraction of the horizon (default 0.25). A committing pass rebuilds the
   * families in the current configuration when max_i |u_i - c| > ul_skin delta / 2, u_i the
   * displacement since the last rebuild and c the centre of the displacements' bounding box (a
   * common translation never triggers), so no pair's distance changed by more than ul_skin delta
   * since: every pair now closer than delta (1 - ul_skin) is in the family, every family pair is
   * closer than delta (1 + ul_skin). 0: never rebuild (Bergel & Li's UL on the initial families).
   */
  double ul_skin;
  /* 2-D: the out-of-plane thickness the particle volumes include (volume = area x thickness, as
   * pdk_lattice_opts.thickness makes them) [length]; default 1, ignored in 3-D. PMB divides its
   * plane-strain micromodulus by it, so forces and energy densities do not depend on it. */
  double thickness;
  /* Multi-material bodies (num_materials >= 1): particle i is made of materials[k], k its entry in
   * the store's int32 field "material" (the caller fills it, values 0 .. num_materials - 1; the
   * scene does it from the regions of its materials list). bulk_modulus, shear_modulus and
   * density above are then ignored (pdk_model_opts_get shows materials[0]'s). How each model
   * uses them:
   *   PMB: bond i-j has the micromodulus c_ij = 2 c_i c_j / (c_i + c_j), c_k from material k's
   *        bulk modulus: half of the bond lies in each material, and two springs of half the
   *        length in series have this stiffness;
   *   correspondence (tl, semi_tl, ul; elastic laws): each particle's law uses its own lambda
   *        and mu, its stabilization modulus its own bulk modulus (the force stays conservative:
   *        particle i's energy is its own law's);
   *   LPS and law jc: refused (PDK_ERR_UNSUPPORTED).
   * The explicit solver takes each particle's density from its material, so its stable time step
   * follows the stiffest and lightest material. 0 (default): one material, the values above. */
  const pdk_material *materials;
  int num_materials;
  /* Family layout of the force passes (default csr). sell: PMB and LPS (LAMMPS's omega, not
   * lps_use_influence), one material; other kinds and multi-material bodies refuse it
   * (PDK_ERR_UNSUPPORTED). When the stencil path is taken (stencil on, or auto on a lattice) it
   * replaces both layouts and sell builds nothing. */
  pdk_layout layout;
  /* PMB and LPS, precision double, csr: reference bond lengths stored (default) or recomputed
   * every pass (see pdk_bond_lengths). */
  pdk_bond_lengths bond_lengths;
  /* sell: the sorting window in particles, rounded up to a multiple of C; 0 (default): 32 C (256
   * with AVX-512). C or less: no sorting. */
  int sell_sigma;
  /* PMB, LPS and correspondence force passes on a regular lattice (see pdk_stencil_mode); default
   * off here (scenes default to auto unless they name model.layout). lps with lps_use_influence
   * accepts off and auto (which then means off), refuses on. */
  pdk_stencil_mode stencil;
  /* Kind galerkin: basis, form, correction (see pdk_galerkin_opts); ignored by the others. */
  pdk_galerkin_opts galerkin;
} pdk_model_opts;

PDK_EXPORT pdk_model_opts pdk_model_opts_default(void);

typedef struct pdk_model pdk_model;

/* Creates the model, declares its fields, precomputes what is fixed (weighted volumes, shape
 * tensors). "x" is initialised to "X" if it did not exist. */
PDK_EXPORT int pdk_model_create(pdk_particles *p, pdk_families *fam, const pdk_model_opts *opts,
                                pdk_model **out);
PDK_EXPORT void pdk_model_destroy(pdk_model **m);

/* Computes the force density "f" from the current positions "x". If strain_energy is not NULL
 * it receives the total strain energy sum_i V_i W_i [energy], summed in a fixed order. Breaks
 * bonds per the failure criterion (state read from the previous pass, written for the next). */
PDK_EXPORT int pdk_model_force(pdk_model *m, double *strain_energy);
/* The same forces, but a trial: no history changes (bond state, critical stretches, plastic
 * strain stay as they are). Used by time-step estimates, relaxation iterates and tangents. */
PDK_EXPORT int pdk_model_force_trial(pdk_model *m, double *strain_energy);

PDK_EXPORT const pdk_model_opts *pdk_model_opts_get(const pdk_model *m);
PDK_EXPORT pdk_particles *pdk_model_particles(const pdk_model *m);
PDK_EXPORT pdk_families *pdk_model_families(const pdk_model *m);
/* Bond state: [num_bonds] uint8, 1 intact, 0 broken; NULL when the model never breaks bonds. */
PDK_EXPORT const uint8_t *pdk_model_bond_alive(const pdk_model *m);
/* Directed bonds broken so far. */
PDK_EXPORT pdk_bond_index pdk_model_num_broken(const pdk_model *m);
/* Particles whose family no longer spans the space (correspondence): count, after a force pass. */
PDK_EXPORT pdk_index pdk_model_num_flagged(const pdk_model *m);
/* Particles without an intact bond (every bond broken, or an empty family from the start): they
 * move freely and carry no force. Counted on demand over the bond state (one pass over the
 * bonds), after the last force pass. */
PDK_EXPORT pdk_index pdk_model_num_isolated(const pdk_model *m);
/* Float storage of bond lengths (PMB and LPS with precision float) rounds each reference length
 * to a relative 2^-24, a stretch error of up to 2^-24 = 6.0e-8 on every bond whatever the
 * deformation, so round-off, not discretization, dominates the forces when the stretches are
 * small. Returns max |stretch| / 2^-24 over the intact bonds at the current positions (one pass
 * over the bonds): the float error of the forces is up to 1/ratio of the largest bond force. 0
 * for a body at rest. Returns -1 when the model stores nothing that bounds the stretch resolution
 * (precision double; correspondence, whose float tensors carry a relative 2^-24 of the stress
 * instead). The CLI warns at the end of a run when 0 <= ratio < PDK_FLOAT_STRETCH_WARN. */
#define PDK_FLOAT_STRETCH_WARN 1e4
PDK_EXPORT double pdk_model_float_stretch_ratio(const pdk_model *m);
/* Layout sell: the fraction of the stored bond entries that are padding, (entries - bonds) /
 * entries, the share of the SIMD lanes' work spent on nothing; 0 for layout csr. */
PDK_EXPORT double pdk_model_padding_fraction(const pdk_model *m);
/* 1 when the force passes take the stencil path (opts.stencil on, or auto on a lattice), else 0.
 * pdk_model_stencil_reason: why auto fell back to the general path ("" when it did not, or the
 * stencil is off). */
PDK_EXPORT int pdk_model_stencil_active(const pdk_model *m);
PDK_EXPORT const char *pdk_model_stencil_reason(const pdk_model *m);
/* Particles that have failed (D >= D_c, Johnson-Cook law), after the last force pass. */
PDK_EXPORT pdk_index pdk_model_num_failed(const pdk_model *m);
/* Bond damage of every particle into out [n]: d_i = 1 - (sum over i's intact bonds of w_b) /
 * (sum over all its bonds at creation of w_b), with w_b = V_j, the volume of the bond's other
 * end, times the partial-volume factor min(1, (vs_a - |xi|) vs_b) where the model scales V_j with
 * it (pmb and lps with lattice_constant > 0; 1 otherwise) -- LAMMPS's compute damage/atom and
 * Peridigm's damage, which weigh by V_j. In [0, 1]: 0 with every bond intact, 1 once a particle
 * lost all its bonds; 0 for a particle that had none, and 0 everywhere when bonds cannot break
 * (no critical stretch, no failing law, ul connectivity). From the bond state after the last
 * committing pass; bitwise the same for any thread count. Scenes: output field "bond_damage"
 * (and "damage" for every model whose law has no damage D of its own). */
PDK_EXPORT int pdk_model_bond_damage(const pdk_model *m, double *out);
/* Largest Johnson-Cook damage D of any particle (the "damage" field); 0 without it. */
PDK_EXPORT double pdk_model_damage_max(const pdk_model *m);
/* semi-TL: how many times the bond list was compacted (0 in TL). */
PDK_EXPORT long pdk_model_num_compactions(const pdk_model *m);
/* UL: how many times the families were rebuilt in the current configuration (0 in TL, semi-TL). */
PDK_EXPORT long pdk_model_num_rebuilds(const pdk_model *m);
/* UL: the strain energy the rebuilds of the committing passes removed so far (the energy of the
 * pass before each rebuild less that of a trial pass over the new families at the same positions;
 * mostly the stabilization's, whose non-affine part restarts at 0), booked so that
 * external_work = kinetic + strain + dissipated + rebuild_work closes; 0 in TL and semi-TL. */
PDK_EXPORT double pdk_model_rebuild_work(const pdk_model *m);
/* UL: rebuilds the families at the current "x" now (a trial pass at x first gives the F to store
 * as the new reference deformation), whatever the displacement since the last rebuild. Refused
 * (PDK_ERR_ARG) for other connectivity modes. */
PDK_EXPORT int pdk_model_rebuild(pdk_model *m);
/* UL: the families the passes walk now (the ones given to pdk_model_create until the first
 * rebuild); for other modes the model's families. Valid until the next committing pass. */
PDK_EXPORT pdk_families *pdk_model_current_families(const pdk_model *m);
/* Time step [time] the history update uses (rate terms and "eps_p_rate"); dt > 0. The explicit
 * solver sets it. Until it is set, a commit pass of a law with rate terms is refused and trial
 * passes take the quasi-static limit (dt = infinity: no rate hardening). */
PDK_EXPORT int pdk_model_set_dt(pdk_model *m, double dt);
/* The time step of the history update: as set, or 0 (none: quasi-static limit). The static
 * solvers set it for each load step (include/pdk/static.h). */
PDK_EXPORT double pdk_model_get_dt(const pdk_model *m);
/* Energy dissipated so far [energy], each summed over particles in a fixed order (thread-count
 * independent): plastic work (with what softened stabilization gave up, "w_stab"), damage, and
 * what bond breaking released (see "w_broken"). A
 * quantity the model does not track is 0. Any pointer may be NULL. Together with the strain
 * energy of pdk_model_force: external work = kinetic + strain + plastic + damage + breaking. */
PDK_EXPORT int pdk_model_plastic_work(pdk_model *m, double *plastic, double *damage,
                                      double *breaking);
PDK_EXPORT const char *pdk_model_kind_name(pdk_model_kind kind);
/* Whether option `name` (a pdk_model_opts member, as the scene key model.<name>) can act with
 * these options' kind and law: 1 when it does, 0 when the kind or law ignores or refuses it. The
 * options only some kinds take (influence, gaussian_width, stabilization,
 * stabilization_coefficient, law, connectivity: correspondence), and those of laws with history
 * (stab_softening, damage_triaxiality, break_stress: law jc with tl or semi_tl connectivity);
 * 1 for any other name. */
PDK_EXPORT int pdk_model_opts_uses(const pdk_model_opts *o, const char *name);

/* Influence-weighted smoothing of a particle field (Queiruga & Moridis 2017, eq. (49), the
 * post-process that removes the oscillations of unstabilized correspondence):
 *   out_i = (w0 V_i in_i + sum_j w(|X_j - X_i|) V_j in_j) / (w0 V_i + sum_j w(|X_j - X_i|) V_j)
 * over the family of i (so bonds cut by a pre-crack are not averaged across), w the influence
 * function over the families' horizon, w0 = w(0) (10 for 1/r and 1/r^2, whose w(0) is infinite,
 * as the authors' code). `in` is an f64 field; `out` (a different name) is created with the same
 * component count if absent, or must have it. Bitwise the same for any thread count. */
PDK_EXPORT int pdk_smooth_field(pdk_particles *p, pdk_families *fam, pdk_influence w,
                                double gaussian_width, const char *in, const char *out);

#ifdef __cplusplus
}
#endif
#endif
