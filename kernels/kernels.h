/* Kernel prototypes. A kernel is a pure function: restrict pointers and counts in, results out;
 * no allocation, no error paths, no OpenMP region. kernels/ref/ holds the readable oracle of each;
 * kernels/opt/ holds the variants that src/core/kernels.c puts in the table. */
#ifndef PDK_KERNELS_H
#define PDK_KERNELS_H

#include "kernel_types.h"

/* Kernels whose result must match the reference bit for bit open with PDK_KERNEL_FP_EXACT: it turns
 * off floating-point contraction (a*b + c fused into one FMA), which the compiler would otherwise
 * apply to plain C and to vector intrinsics alike whenever the target has FMA, and which would
 * change the rounding of a sum of squares. */
#if defined(__clang__)
#define PDK_KERNEL_FP_EXACT _Pragma("STDC FP_CONTRACT OFF")
#elif defined(__GNUC__)
#define PDK_KERNEL_FP_EXACT _Pragma("GCC optimize(\"fp-contract=off\")")
#else
#define PDK_KERNEL_FP_EXACT
#endif

/* Family candidate scan.
 *   Appends to out[] the ids cand_id[k] of the candidates k in 0..n_cand-1 whose squared distance
 *   to (xi, yi[, zi]) is <= r2max, except the particle `self`, in candidate order; returns how many
 *   it appended.
 *   Squared distance, each operation rounded to double (no FMA), in this order:
 *     dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi;  r2 = (dx*dx + dy*dy) + dz*dz
 *   so every variant gives the same set, and r2(i, j) == r2(j, i) bit for bit.
 *   cx, cy, cz: [n_cand] candidate coordinates (cell-sorted copies); cand_id: [n_cand].
 *   out: room for n_cand + PDK_SCAN_OUT_PAD entries; a variant may write (but not count) entries
 *   past its result, up to that room. */
#define PDK_SCAN_OUT_PAD 16

pdk_index pdk_kernel_family_scan2_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, double xi, double yi,
                                      double r2max, pdk_index self,
                                      const pdk_index *restrict cand_id, pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, const double *restrict cz,
                                      double xi, double yi, double zi, double r2max,
                                      pdk_index self, const pdk_index *restrict cand_id,
                                      pdk_index *restrict out);

/* AVX2 variants (kernels/opt/family_scan_avx2.c): 4 candidates per step, compaction through a
 * byte-shuffle table. Call only when the CPU has AVX2 (PDK_ISA_AVX2). */
pdk_index pdk_kernel_family_scan2_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, double xi, double yi,
                                       double r2max, pdk_index self,
                                       const pdk_index *restrict cand_id, pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, const double *restrict cz,
                                       double xi, double yi, double zi, double r2max,
                                       pdk_index self, const pdk_index *restrict cand_id,
                                       pdk_index *restrict out);

/* AVX-512 variants (kernels/opt/family_scan_avx512.c): 16 candidates per step, compaction with
 * vpcompressd into a register. Call only when the CPU has AVX-512 F/VL/DQ/BW (PDK_ISA_AVX512). */
pdk_index pdk_kernel_family_scan2_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, double xi, double yi,
                                         double r2max, pdk_index self,
                                         const pdk_index *restrict cand_id,
                                         pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, const double *restrict cz,
                                         double xi, double yi, double zi, double r2max,
                                         pdk_index self, const pdk_index *restrict cand_id,
                                         pdk_index *restrict out);

/* Calls RANGE(dim, state, commit, energy) with the four as literals (dim 2 or 3, the others 0 or
 * 1), so the reference PMB and LPS ranges compile one loop per combination: bond state present,
 * a committing pass (only with state), energy wanted. */
#define PDK_BOND_RANGE_DISPATCH(RANGE, dim, has_state, commit, want_energy)                     \
  do {                                                                                          \
    if ((dim) == 3)                                                                             \
      PDK_BOND_RANGE_DISPATCH_D(RANGE, 3, has_state, commit, want_energy);                      \
    else                                                                                        \
      PDK_BOND_RANGE_DISPATCH_D(RANGE, 2, has_state, commit, want_energy);                      \
  } while (0)
#define PDK_BOND_RANGE_DISPATCH_D(RANGE, D, has_state, commit, want_energy)                     \
  do {                                                                                          \
    if (!(has_state)) {                                                                         \
      if (want_energy)                                                                          \
        RANGE(D, 0, 0, 1);                                                                      \
      else                                                                                      \
        RANGE(D, 0, 0, 0);                                                                      \
    } else if (!(commit)) {                                                                     \
      if (want_energy)                                                                          \
        RANGE(D, 1, 0, 1);                                                                      \
      else                                                                                      \
        RANGE(D, 1, 0, 0);                                                                      \
    } else {                                                                                    \
      if (want_energy)                                                                          \
        RANGE(D, 1, 1, 1);                                                                      \
      else                                                                                      \
        RANGE(D, 1, 1, 0);                                                                      \
    }                                                                                           \
  } while (0)

/* ---- Bond-based PMB and state-based LPS (kernels/ref/pmb.c, kernels/ref/lps.c) ----------------
 * Formulas and contracts at the top of each file. The arrays (pdk_bond_arrays below): particles
 * [i0, i1); CSR families bond_start [n+1], bond_j [num_bonds]; reference X, Y[, Z] and current
 * x, y[, z] positions, volume, outputs: [n_pad] each. bond_alive [num_bonds] (NULL: bonds never
 * break) is read, and written only by a committing force pass (s0_next != NULL), which also writes
 * s0_next[i] and returns the number of bonds it broke (the LAMMPS s0 rule). w (NULL: skip) gets
 * the strain energy density W_i [energy/volume]. */
typedef struct pdk_pmb_consts {
  double c;          /* micromodulus [pressure / length^(dim+1)] */
  double vs_a, vs_b; /* partial volume factor min(1, (vs_a - r0) * vs_b); vs_a = +inf: off */
  double s00, alpha; /* s0 rule: s0_next = max over intact bonds of (s00 - alpha s) */
  /* Multi-material: per-particle micromodulus [n_pad]; bond i-j uses 2 c_i c_j / (c_i + c_j)
   * instead of c. NULL: c for every bond. */
  const double *c_particle;
} pdk_pmb_consts;

typedef struct pdk_lps_consts {
  double vs_a, vs_b;   /* as pdk_pmb_consts */
  double theta_factor; /* d: 3 (3-D) or 2 (plane strain) */
  double c_dil, c_dev; /* bond force t = c_dil (theta_i/m_i + theta_j/m_j) + c_dev (1/m_i + 1/m_j) s */
  double e_bulk, e_dev; /* W = e_bulk theta^2/2 + e_dev/m sum omega (e - theta r0/d)^2 beta V */
  double s00, alpha;
} pdk_lps_consts;

/* ---- PMB and LPS through the kernel table -------------------------------------------------------
 * One entry per pass, 2-D and 3-D, with every array in one struct so variants that read other
 * layouts share the signature. The reference entries (kernels/ref/pmb.c, lps.c) read the SoA
 * arrays; the SIMD entries (kernels/opt/bond_avx2.c, bond_avx512.c) read the packed rows
 * instead: one 32-byte row per particle, so a bond's neighbour data is two aligned 256-bit loads
 * and a register transpose rather than 7 (PMB) to 9 (LPS) gathers. Padded entries [n, n_pad) of
 * the rows are never read. Both read bond_r0 when it is not NULL (float storage, see below).
 * Formulas, bond failure and the energy are those of the reference kernels; every variant computes
 * each bond's terms with the same operations in the same order (no FMA contraction), so bond
 * failure decisions and the s0 maxima equal the reference's bit for bit and forces, dilations and
 * energies differ only by the order of the sums over a family. */
typedef struct pdk_bond_arrays {
  int dim;                          /* 2 or 3 */
  const pdk_bond_index *bond_start; /* [n+1] */
  const pdk_index *bond_j;          /* [num_bonds] */
  const double *X[3], *x[3];        /* reference and current positions [n_pad] (X[2], x[2]: 3-D) */
  const double *volume;             /* [n_pad] */
  /* Packed rows (SIMD variants; NULL for the reference): ref4[4 i + c] = X_c (c < dim), 0 for the
   * other components up to 3, and at c = 3 the LPS 1/m_i (0 for PMB); cur4[4 i + c] = x_c (0
   * beyond dim), cur4[4 i + 3] = V_i. ref4 is filled once, cur4 before every pass. */
  const double *ref4, *cur4;
  /* Float storage (precision float): the reference bond length |X_j - X_i| per bond, rounded to
   * float, replaces r0 recomputed from X (3 loads and a sqrt fewer per bond, 4 bytes per bond more;
   * the stretch then carries an error up to 2^-24 r0 / r0 = 6e-8). NULL: double, from X. */
  const float *bond_r0;
  /* Stored bond lengths (precision double, bond_lengths stored, the default): |X_j - X_i| per
   * bond in double, computed once by pdk_kernel_bond_lengths_ref with the operations the kernels
   * use, so r0 has the bits the kernels would compute (8 bytes per bond; the SIMD variants then
   * skip a square root per bond, and PMB the reference row). The reference kernels ignore it and
   * compute the same values. NULL: computed every pass. Never set together with bond_r0. */
  const double *bond_r0d;
  uint8_t *bond_alive;              /* [num_bonds] or NULL (bonds never break) */
  const double *s0;                 /* [n_pad] */
  double *s0_next;                  /* [n_pad]; non-NULL: committing pass */
  const double *theta, *inv_m;      /* LPS [n_pad] */
  double *theta_out;                /* LPS dilation output [n_pad] */
  double *f[3];                     /* force density [n_pad] */
  double *w;                        /* strain energy density [n_pad] or NULL */
} pdk_bond_arrays;

typedef pdk_bond_index (*pdk_pmb_force_fn)(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                           pdk_index i0, pdk_index i1);
typedef void (*pdk_lps_dilation_fn)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                    pdk_index i0, pdk_index i1);
typedef pdk_bond_index (*pdk_lps_force_fn)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                           pdk_index i0, pdk_index i1);

pdk_bond_index pdk_kernel_pmb_force_ref(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1);
/* LPS dilation theta_i = d inv_m_i sum_b alive_b e beta V_j into theta_out; inv_m [n_pad] = 1/m
 * (0 for an empty family). */
void pdk_kernel_lps_dilation_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a, pdk_index i0,
                                 pdk_index i1);
/* LPS force pass; theta and inv_m must be complete for every particle (neighbours are read). */
pdk_bond_index pdk_kernel_lps_force_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1);
/* Set-up only (not in the table): m_i = sum_b r0 beta V_j over every bond (LPS weighted volume
 * with omega = 1/r0) from a's arrays, with bond_r0 when it is set. */
void pdk_kernel_lps_weighted_volume_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1, double *restrict m);
/* Set-up only: r0[b] = |X_j - X_i| for the bonds of particles [i0, i1), in double, with the
 * operations and their order of every PMB and LPS kernel ((dX dX + dY dY) + dZ dZ, no FMA,
 * correctly rounded sqrt), so a kernel reading r0 (pdk_bond_arrays.bond_r0d) gets the bits it
 * would have computed. Reads a's bond_start, bond_j, X. */
void pdk_kernel_bond_lengths_ref(const pdk_bond_arrays *a, pdk_index i0, pdk_index i1,
                                 double *restrict r0);
/* AVX2 + FMA CPUs (PDK_ISA_AVX2): 4 bonds per step. */
pdk_bond_index pdk_kernel_pmb_force_avx2(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                         pdk_index i0, pdk_index i1);
void pdk_kernel_lps_dilation_avx2(const pdk_lps_consts *k, const pdk_bond_arrays *a, pdk_index i0,
                                  pdk_index i1);
pdk_bond_index pdk_kernel_lps_force_avx2(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                         pdk_index i0, pdk_index i1);
/* AVX-512 CPUs (PDK_ISA_AVX512): 8 bonds per step. */
pdk_bond_index pdk_kernel_pmb_force_avx512(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                           pdk_index i0, pdk_index i1);
void pdk_kernel_lps_dilation_avx512(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                    pdk_index i0, pdk_index i1);
pdk_bond_index pdk_kernel_lps_force_avx512(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                           pdk_index i0, pdk_index i1);

/* ---- PMB and LPS over the sliced layout (SELL-C-sigma) --------------------------------------------------
 * The families of pdk_bond_arrays re-stored in slices of C consecutive rows (src/space/sell.h): row r of
 * slice s = r / C is particle row_i[r]; within a slice the bonds are stored column-major, entry
 * slice_start[s] + col C + l holding bond col of lane l's particle, so one SIMD vector of C lanes
 * is C particles at the same bond rank and a particle's force is one lane's running sum, without
 * a horizontal sum or a partial last step. A slice has as many columns as its longest family;
 * shorter families are padded with entries pointing at the particle itself (bond length 0: the
 * force term g = c s beta V / r takes the r = 0 branch, q = 0, and adds an exact +0) that are
 * flagged broken (alive = 0, so a committing pass neither breaks them nor takes their stretch into
 * s0). Rows r >= n fill the last slice (row_i a real particle, results discarded).
 * Each bond's terms are computed with the operations of kernels/ref/pmb.c in the same order (no
 * FMA), so bond failure decisions, the number broken and s0_next equal the reference's bit for
 * bit; a particle's force and energy are summed over its bonds in CSR order, one after the other
 * (the reference may regroup the sum when the compiler vectorizes it), so they differ from the
 * reference by summation order only. */
typedef struct pdk_sell_arrays {
  int width;                   /* C lanes per slice (1..16) */
  pdk_index n;                 /* particles: rows r >= n are padding */
  const pdk_index *row_i;      /* [num_slices C] particle of each row, 64-byte aligned */
  const int64_t *slice_start;  /* [num_slices + 1] first entry of each slice (multiples of C) */
  const pdk_index *sj;         /* [num_entries] neighbour; padding: the row's own particle */
  uint8_t *alive;              /* [num_entries] 1 intact, 0 broken or padding; NULL: no state */
  const float *r0;             /* [num_entries] float bond lengths (precision float) or NULL */
} pdk_sell_arrays;

/* Force pass over slices [s0, s1): a's positions, volume, packed rows (SIMD variants), s0,
 * s0_next, f, w as pdk_pmb_force_fn; a->bond_j and bond_r0 are not read; a->bond_alive (the CSR
 * bond state) is written only where a committing pass breaks a bond, in step with s->alive, which
 * is what every pass reads: entry column col of row i is CSR bond a->bond_start[i] + col. Returns
 * the bonds broken. */
typedef pdk_bond_index (*pdk_pmb_force_sell_fn)(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                                const pdk_sell_arrays *s, int64_t s0, int64_t s1);
pdk_bond_index pdk_kernel_pmb_force_sell_ref(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                             const pdk_sell_arrays *s, int64_t s0, int64_t s1);
/* SIMD variants (kernels/opt/sell_simd.h in bond_avx2.c, bond_avx512.c): C must equal the ISA's
 * lanes, 4 (AVX2) and 8 (AVX-512), and the packed rows ref4, cur4 must be set. */
pdk_bond_index pdk_kernel_pmb_force_sell_avx2(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                              const pdk_sell_arrays *s, int64_t s0, int64_t s1);
pdk_bond_index pdk_kernel_pmb_force_sell_avx512(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                                const pdk_sell_arrays *s, int64_t s0, int64_t s1);
/* LPS dilation and force passes over slices [s0, s1), the same layout and rules (dilation: a's
 * positions, volume, rows, inv_m in, theta_out out; force: theta, inv_m of every particle in, as
 * pdk_lps_force_fn). The padding's deviatoric energy term is skipped (r0 = 0). */
typedef void (*pdk_lps_dilation_sell_fn)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                         const pdk_sell_arrays *s, int64_t s0, int64_t s1);
typedef pdk_bond_index (*pdk_lps_force_sell_fn)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                                const pdk_sell_arrays *s, int64_t s0, int64_t s1);
void pdk_kernel_lps_dilation_sell_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                      const pdk_sell_arrays *s, int64_t s0, int64_t s1);
pdk_bond_index pdk_kernel_lps_force_sell_ref(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                             const pdk_sell_arrays *s, int64_t s0, int64_t s1);
void pdk_kernel_lps_dilation_sell_avx2(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                       const pdk_sell_arrays *s, int64_t s0, int64_t s1);
pdk_bond_index pdk_kernel_lps_force_sell_avx2(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                              const pdk_sell_arrays *s, int64_t s0, int64_t s1);
void pdk_kernel_lps_dilation_sell_avx512(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                         const pdk_sell_arrays *s, int64_t s0, int64_t s1);
pdk_bond_index pdk_kernel_lps_force_sell_avx512(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                                const pdk_sell_arrays *s, int64_t s0, int64_t s1);
/* ---- PMB on a regular lattice: the stencil layout (kernels/opt/pmb_stencil.h) ----------------
 * Built by src/models/model_stencil.c when the particles sit on a simple cubic (3-D) or square (2-D)
 * lattice. Sites of a padded grid, s = ix + nx (iy + ny iz); a bond is a fixed site offset. Per-site
 * arrays are [num_sites + PDK_STENCIL_SLACK] (the slack: sites past the grid that a row's last,
 * partial vector block reads; empty); particle arrays (f, w, s0_next) are [n_pad]. */
#define PDK_STENCIL_SLACK 64
typedef struct pdk_stencil_arrays {
  int dim;                       /* 2 or 3 */
  int num_offsets;               /* bonds per full family */
  const int64_t *offset;         /* [num_offsets] site offset of each bond, ascending */
  int64_t num_sites;
  int64_t num_rows;
  const int64_t *row_lo, *row_hi; /* [num_rows] sites row_lo[r] .. row_hi[r]-1 of one grid row */
  const pdk_index *site_particle; /* [num_sites] particle at the site, -1 when empty */
  const double *X[3], *x[3];     /* reference, current positions per site (X[2], x[2]: 3-D) */
  const double *volume;          /* [num_sites] 0 at empty sites */
  /* Float storage: per offset, the bond length (the float every bond of that offset stores, as a
   * double) and its partial-volume factor; NULL: r0 recomputed from X (double storage). */
  const double *r0_off, *beta_off;
  uint8_t *mask;                 /* [num_offsets * num_sites] bond present and intact, or NULL */
  const double *s0;              /* [num_sites] critical stretches (committing pass) */
  uint8_t *changed;              /* [num_sites] set to 1 where a bond broke (committing pass) */
  double *s0_next;               /* [n_pad]; non-NULL: committing pass */
  double *f[3];                  /* [n_pad] */
  double *w;                     /* [n_pad] or NULL */
  /* LPS (kernels/opt/lps_stencil.h): 1/m and the dilation per site (0 at empty sites), the
   * dilation pass's outputs per site and per particle. */
  const double *inv_m, *theta;   /* [num_sites + slack] */
  double *theta_site;            /* [num_sites + slack] (the array theta points to) */
  double *theta_out;             /* [n_pad] */
  /* Correspondence (kernels/opt/corr_stencil.h): u [sites] the displacement x - X per site (0 at
   * empty sites; the grid's x arrays hold it); per offset the influence omega_off[o] and the
   * weighted reference bond wxi_off[c][o] = omega xi_c, which set-up checked against every bond
   * of that offset (the list is symmetric: offset[no - 1 - o] = -offset[o], same omega, opposite
   * xi); per site cs[c] = sum over the intact bonds of omega V_j xi_c (a reference-configuration
   * sum, 0 at empty sites, kept current by the driver when bonds break), and the pass-2 data pass
   * 1 writes: cB[r d + c] = B_rc (B = A - k (F - I) with Silling, A without; 0 at empty sites),
   * ck = k, and with float storage cBf, the float copy neighbours read. */
  const double *u[3];
  const double *wxi_off[3], *omega_off;
  const double *cs[3];
  double *cB[9], *ck;
  float *cBf[9];
  /* the same per-site arrays as one block with a fixed stride (pass 2 addresses them from one
   * pointer): component c of site s at cbase[c * cstride + s], c = 0 .. d-1 u, d V, d + 1 k,
   * d + 2 + t cB[t]; cbase_f[t * cstride + s] = cBf[t][s] (NULL without float storage) */
  const double *cbase;
  const float *cbase_f;
  int64_t cstride;
} pdk_stencil_arrays;

/* Rows [r0, r1) of a; returns the bonds broken (committing pass). */
typedef pdk_bond_index (*pdk_pmb_stencil_fn)(const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                             int64_t r0, int64_t r1);
pdk_bond_index pdk_kernel_pmb_stencil_base(const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                           int64_t r0, int64_t r1);
pdk_bond_index pdk_kernel_pmb_stencil_avx2(const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                           int64_t r0, int64_t r1);
pdk_bond_index pdk_kernel_pmb_stencil_avx512(const pdk_pmb_consts *k,
                                             const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
/* LPS dilation (writes theta_site and theta_out) and force passes, rows [r0, r1). */
typedef void (*pdk_lps_stencil_dilation_fn)(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                            int64_t r0, int64_t r1);
typedef pdk_bond_index (*pdk_lps_stencil_force_fn)(const pdk_lps_consts *k,
                                                   const pdk_stencil_arrays *a, int64_t r0,
                                                   int64_t r1);
void pdk_kernel_lps_stencil_dilation_base(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                          int64_t r0, int64_t r1);
void pdk_kernel_lps_stencil_dilation_avx2(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                          int64_t r0, int64_t r1);
void pdk_kernel_lps_stencil_dilation_avx512(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                            int64_t r0, int64_t r1);
pdk_bond_index pdk_kernel_lps_stencil_force_base(const pdk_lps_consts *k,
                                                 const pdk_stencil_arrays *a, int64_t r0,
                                                 int64_t r1);
pdk_bond_index pdk_kernel_lps_stencil_force_avx2(const pdk_lps_consts *k,
                                                 const pdk_stencil_arrays *a, int64_t r0,
                                                 int64_t r1);
pdk_bond_index pdk_kernel_lps_stencil_force_avx512(const pdk_lps_consts *k,
                                                   const pdk_stencil_arrays *a, int64_t r0,
                                                   int64_t r1);

/* ---- Johnson-Cook material point (kernels/ref/jc.c; formulation in its header) -------------- */
/* The functions of pdk/plasticity.h are these kernels: src/models/plasticity.c defines each public one as
 * a call of its kernel here, after checking the arguments (NULL pointers, a non-finite
 * sigma_m_avg: PDK_ERR_ARG). The kernels take valid pointers.
 * pdk_jc_update_full_kernel: pdk_jc_update (sigma_m_avg NULL) or pdk_jc_update_avg (sigma_m_avg
 * the family average; not finite: PDK_ERR_ARG).
 * pdk_jc_update_kernel: the same update for the model kernels, except that res->sigma is left 0:
 * they read sigma_vm, W, the energies and sigma_m_eff, not the six Cauchy components. */
int pdk_jc_update_full_kernel(const pdk_jc_params *p, int dim, const double F[3][3], double dt,
                              const double *sigma_m_avg, const pdk_jc_state *in, pdk_jc_state *out,
                              double P[3][3], pdk_jc_result *res);
int pdk_jc_update_kernel(const pdk_jc_params *p, int dim, const double F[3][3], double dt,
                         const double *sigma_m_avg, const pdk_jc_state *in, pdk_jc_state *out,
                         double P[3][3], pdk_jc_result *res);
/* pdk_jc_remap: checks dim and the pointers itself (PDK_ERR_ARG). */
int pdk_jc_remap_kernel(int dim, const double F_old[3][3], const double F_new[3][3],
                        pdk_jc_state *s);
/* pdk_jc_flow_stress, pdk_jc_failure_strain: NaN for p NULL. */
double pdk_jc_flow_stress_kernel(const pdk_jc_params *p, double eps_p, double rate_star,
                                 double T_star);
double pdk_jc_failure_strain_kernel(const pdk_jc_params *p, double eta, double rate_star,
                                    double T_star);

/* ---- Correspondence (kernels/ref/corr.c; formulas and contract in its header) ---------------- */

#define PDK_CORR_FLAG_SPAN 1u     /* the family does not span the space: K singular */
#define PDK_CORR_FLAG_INVERTED 2u /* the law is undefined at F (Neo-Hooke or JC with J <= 0) */
#define PDK_CORR_FLAG_FAILED 4u   /* Johnson-Cook: the particle has failed (no stress) */
#define PDK_CORR_FLAG_FAILED_NOW 8u /* ... in this commit pass (its Silling energy is booked as
                                       damage by pass 2) */
#define PDK_CORR_SPAN_RTOL 1e-6   /* flag when det K < PDK_CORR_SPAN_RTOL * (tr K / d)^d */

typedef struct pdk_corr_consts {
  int dim;             /* 2 (plane strain) or 3 */
  int law;             /* PDK_KERNEL_LAW_* (pdk_law) */
  double lambda, mu;   /* Lame constants [pressure] */
  int stab;            /* PDK_KERNEL_STAB_* (pdk_stabilization) */
  double stab_modulus; /* C_s c_d K [pressure]; particle i's coefficient is stab_modulus / m_i */
  double horizon;      /* delta [length] (hourglass form) */
  double span_rtol;    /* PDK_CORR_SPAN_RTOL */
  double s00, alpha;   /* critical stretch and its alpha (bond failure) */
  /* Johnson-Cook law (law == PDK_KERNEL_LAW_JC) */
  const pdk_jc_params *jc;        /* material; NULL for the elastic laws */
  double dt;                      /* step length passed to the update [time] (> 0) */
  int commit;                     /* pass 1: 1 writes the history, 0 leaves it alone (trial) */
  int break_failed;               /* 1: bonds of failed particles break (both ends) */
  /* Softened stabilization (Johnson-Cook; arrays stab_factor, stab_prev, w_law, w_stab): a commit
   * pass 1 lowers particle i's factor to min(1, max(stab_floor, sigma_vm / (E eps_p))) once it has
   * flowed (Bode 2021 eq. 6.20, E~ = min[E, max(1e-3 E, sigma_vm / eps_p)]), never raising it;
   * 0: off. */
  double stab_floor;
  /* Multi-material: per-particle lambda, mu and stab_modulus [n_pad]; NULL: the scalars above. */
  const double *lambda_p, *mu_p, *stab_p;
} pdk_corr_consts;

/* The constants of particle i: k itself for a one-material body, else a copy in *tmp with i's
 * lambda, mu and stab_modulus. */
static inline const pdk_corr_consts *pdk_corr_consts_at(const pdk_corr_consts *k, pdk_index i,
                                                         pdk_corr_consts *tmp) {
  if (!k->mu_p) return k;
  *tmp = *k;
  tmp->lambda = k->lambda_p[i];
  tmp->mu = k->mu_p[i];
  tmp->stab_modulus = k->stab_p[i];
  return tmp;
}

/* Arrays the kernels read and write. Per-particle arrays are [n_pad]; tensors are dim*dim such
 * arrays, component [a][c] at index a*dim + c. Kernels copy these into restrict locals. */
typedef struct pdk_corr_arrays {
  const pdk_bond_index *bond_start; /* [n+1] */
  const pdk_index *bond_j;          /* [num_bonds] */
  const double *bond_omega;         /* [num_bonds] influence omega(|xi|) >= 0 */
  uint8_t *bond_alive;              /* [num_bonds] 1 intact, 0 broken; NULL: all intact */
  const double *X[3];               /* reference positions [length] */
  const double *x[3];               /* current positions [length] */
  const double *volume;             /* [length^3] (2-D: area x thickness) */
  double *Kinv[9];                  /* K^-1 [1/length^5] */
  double *F[9];                     /* deformation gradient [-] */
  double *A[9];                     /* P K^-1 [pressure/length^5] */
  /* Pass-2 data of each particle, written by pass 1 from its final A, F, flag (each NULL when the
   * driver does not provide it; which it provides: pdk_corr_pair_layout):
   *   kst   [n_pad] stabilization coefficient k_i = stab_modulus / m_i (0 when flagged)
   *   B     A - k (F - I) (Silling); double storage, optimized variants
   *   G     k (F - I) (hourglass); double storage, optimized variants
   *   Bf    float copy of A - k (F - I) (Silling) or of A (none, hourglass); float storage
   *   Gf    float copy of k (F - I) (hourglass); float storage
   * Pass 2 of every variant reads the neighbour's tensors from Bf, Gf when Bf is set (float
   * storage). Otherwise the reference reads A, F and the optimized variants read B (A when B is
   * NULL), G. */
  double *kst;
  double *B[9];
  double *G[9];
  float *Bf[9];
  float *Gf[9];
  /* Packed rows of the optimized variants without hourglass stabilization (layout bit 32; all
   * NULL otherwise), so a bond's neighbour data is a few aligned vector loads instead of one
   * emulated gather per value (kernels/opt/corr_simd.h):
   *   ref4 [4 n_pad] (X, Y, Z, V) of each particle, 0 for Z in 2-D; written at setup
   *   cur4 [4 n_pad] (u_x, u_y, u_z, 1), u = x - X the displacement (u_z = 0 in 2-D); written by
   *        the driver before pass 1 (pdk_corr_pack_cur)
   *   row  [n_pad]   (double storage) or rowf [n_pad] (float storage): B_i and k_i of
   *        pdk_corr_row (with V_i, X_i, -u_i: a neighbour's whole pass-2 bond) / pdk_corr_rowf,
   *        written by pass 1 for its neighbours' pass 2
   *   own  [4 n_pad] i's own terms from pass 1 for its pass 2: (B_i s_i + k_i u_i, zz_i), see
   *        corr_simd.h */
  const double *ref4, *cur4;
  struct pdk_corr_row *row;
  struct pdk_corr_rowf *rowf;
  double *own;
  double *m;                        /* weighted volume sum w V |xi|^2 [length^5]; NULL if unused */
  uint8_t *flag;                    /* PDK_CORR_FLAG_* bits */
  int32_t *num_alive;               /* intact bonds when K^-1 was computed; NULL if no failure */
  double *W;                        /* strain energy density [energy/length^3] */
  double *f[3];                     /* force density [force/length^3] */
  const double *s0;                 /* critical stretch per particle, previous pass; NULL: no
                                       stretch criterion */
  double *s0_next;                  /* critical stretch per particle, next pass */
  /* Johnson-Cook history (committed state; NULL unless law == PDK_KERNEL_LAW_JC) */
  double *cp_inv[6];  /* C_p^-1, Voigt xx yy zz yz xz xy */
  double *eps_p;      /* equivalent plastic strain */
  double *damage;     /* D */
  double *temp_rise;  /* [K]; NULL without the thermal term */
  uint8_t *failed;    /* 1 once D >= D_c */
  double *eps_p_rate; /* plastic strain rate of the last committed step [1/time] */
  double *w_plastic;  /* accumulated plastic work [energy/length^3] */
  double *w_damage;   /* accumulated damage energy [energy/length^3] */
  /* Softened stabilization (k->stab_floor > 0; all NULL otherwise): particle i's stabilization
   * coefficient is k_i = factor_i stab_modulus_i / m_i. A commit pass 1 keeps the factor it found
   * in stab_prev, writes the new one and the law's energy density W_law (W before the Silling
   * term); after pass 2 the driver books the Silling energy the factor's change took away,
   * (f_old - f_new)/2 (S_old / f_old + S / f_new) with S = W - W_law this pass's Silling energy
   * density and S_old = w_silling the last commit's (the change of f at the mean of the step's
   * two ends: second order in dt, as the integrator), into w_stab, and sets w_silling = S. */
  double *stab_factor; /* [n_pad] 1 at start */
  double *stab_prev;   /* [n_pad] scratch of the commit pass: the factor before it */
  double *w_law;       /* [n_pad] scratch of the commit pass */
  double *w_silling;   /* [n_pad] Silling energy density at the last commit [energy/length^3] */
  double *w_stab;      /* [n_pad] accumulated Silling energy given up [energy/length^3] */
  /* Family-averaged damage triaxiality (NULL: each particle's own pressure): a commit pass 1
   * writes sigma_m (the effective Cauchy mean stress of pdk_jc_result.sigma_m_eff), every pass 1
   * reads sigma_m_avg (the average the driver formed from the previous commit's sigma_m). */
  double *sigma_m;
  const double *sigma_m_avg;
  /* Bond breaking bookkeeping (NULL when bonds never break) */
  double *w_broken; /* accumulated energy released by breaking [energy/length^3] */
  uint8_t *changed; /* [n] bit 0: row lost bonds in this round, bit 1: in this commit pass */
  uint8_t *detach;  /* [n] semi-TL: particle detached in this round; NULL in TL */
} pdk_corr_arrays;

/* Stabilization coefficient k_i = stab_modulus_i / m_i of particle i (0 when flagged, without a
 * weighted volume or without stabilization): the value pass 1 stores for pass 2. */
static inline double pdk_corr_kst(const struct pdk_corr_consts *k, const pdk_corr_arrays *a,
                                  pdk_index i) {
  if (k->stab == PDK_KERNEL_STAB_NONE || a->flag[i] || !(a->m[i] > 0.0)) return 0.0;
  return (k->stab_p ? k->stab_p[i] : k->stab_modulus) *
         (a->stab_factor ? a->stab_factor[i] : 1.0) / a->m[i];
}

/* The same coefficient ignoring the flags (m_i > 0 assumed): what the Silling term of a particle
 * failing in this commit pass held, booked as damage by pass 2. */
static inline double pdk_corr_kst_unflagged(const struct pdk_corr_consts *k,
                                            const pdk_corr_arrays *a, pdk_index i) {
  return (k->stab_p ? k->stab_p[i] : k->stab_modulus) *
         (a->stab_factor ? a->stab_factor[i] : 1.0) / a->m[i];
}

/* Silling energy sum of particle i, zz = sum w |v - H xi|^2 = vv - H : D with H = D K^-1,
 * vv = sum w |v|^2, D = sum w v (x) xi (v = u_j - u_i; H K = D with the same weights), clamped at
 * 0 against round-off. */
static inline double pdk_corr_silling_zz(const int d, const double D[3][3],
                                         const pdk_corr_arrays *a, pdk_index i, double vv) {
  double HD = 0.0;
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double h = 0.0;
      for (int e = 0; e < d; ++e)
        h += D[r][e] * a->Kinv[e * d + c][i];
      HD += h * D[r][c];
    }
  const double zz = vv - HD;
  return zz > 0.0 ? zz : 0.0;
}

/* Pass-2 record of particle i (double storage), 128 bytes, 64-byte aligned (two cache lines):
 * everything a neighbour's pass-2 bond reads of i, so a bond is one index and loads at fixed
 * offsets from one address. The three columns of V_i B_i (B = A - k (F - I) for Silling, A
 * without stabilization; V_i the volume) in c[0..2], c[4..6], c[8..10] (column c of the d x d
 * tensor, rows 0..d-1, zeros beyond), V_i k_i in c[3], X_i in c[7], c[11], c[15] (Z = 0 in 2-D),
 * and -u_i = X_i - x_i in c[12..14] (0 for z in 2-D). */
typedef struct pdk_corr_row {
  double c[16];
} pdk_corr_row;
/* The same in float storage, 64 bytes (one cache line): the columns as floats (the values of
 * Bf), k_i in double (it multiplies the relative displacement, as the double kst does). */
typedef struct pdk_corr_rowf {
  float c[12];
  double k;
  double pad;
} pdk_corr_rowf;

/* Which pass-2 arrays (pdk_corr_arrays kst, B, G, Bf, Gf, rows) a pass needs: bit 1 kst, 2 B, 4 G,
 * 8 Bf, 16 Gf, 32 the packed rows (ref4, cur4, own and row or, with fl, rowf), for stabilization
 * `stab`, float storage `fl`, optimized variant `opt`. The optimized variants use the rows except
 * with hourglass stabilization. */
static inline unsigned pdk_corr_pair_layout(int stab, int fl, int opt) {
  const unsigned k = stab != PDK_KERNEL_STAB_NONE ? 1u : 0u;
  if (opt && stab != PDK_KERNEL_STAB_HOURGLASS) return 32u;
  if (fl) return k | 8u | (stab == PDK_KERNEL_STAB_HOURGLASS ? 16u : 0u);
  if (!opt) return 0u;
  return k | 4u;
}

/* cur4 rows of particles [i0, i1) from x and X (pdk_corr_arrays cur4). */
static inline void pdk_corr_pack_cur(int dim, const double *const *X, const double *const *x,
                                     double *restrict cur4, pdk_index i0, pdk_index i1) {
  for (pdk_index i = i0; i < i1; ++i) {
    double *r = cur4 + 4 * (size_t)i;
    r[0] = x[0][i] - X[0][i];
    r[1] = x[1][i] - X[1][i];
    r[2] = dim == 3 ? x[2][i] - X[2][i] : 0.0;
    r[3] = 1.0;
  }
}

/* Shape: K^-1, m, flag bit SPAN, num_alive for i in [i0, i1); returns how many do not span. */
pdk_index pdk_kernel_corr_shape_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i0, pdk_index i1);
/* Pass 1: F, A = P K^-1, W (and the shape again where bonds broke). */
void pdk_kernel_corr_pass1_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                               pdk_index i1);
/* Pass 2: f (and W += Silling stabilization energy); reads A, F of neighbours from pass 1. */
void pdk_kernel_corr_pass2_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                               pdk_index i1);
/* Per-particle ends of the shape and of pass 1, shared by every variant (the family sums are the
 * variant's): shape_point stores K^-1 (or 0), m, num_alive, flag bit SPAN from K = sum w V xi xi,
 * m = sum w V |xi|^2 and the intact count, returning 1 if the family does not span; point takes
 * N = sum w V Y xi (d x d in 3 x 3) and stores F, A, W, the flags, the JC history and the pass-2
 * data. */
int pdk_kernel_corr_shape_point_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i, const double K[3][3], double m, int32_t count);
void pdk_kernel_corr_point_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                               const double N[3][3]);
/* The same end from D = sum w V (Y - xi) (x) xi instead of N: F = I + D K^-1 (which keeps F - I
 * to the relative precision of the displacements). */
void pdk_kernel_corr_point_disp_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i, const double D[3][3]);

/* Optimized variants of shape, pass 1 and pass 2 (kernels/opt/corr_avx2.c, corr_avx512.c: one
 * source, kernels/opt/corr_simd.h, compiled for each ISA). Same contract and results as the
 * reference up to round-off (sums regrouped and vectorized across a family's bonds, contractions
 * to FMA). Call only when the CPU has the ISA. */
pdk_index pdk_kernel_corr_shape_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                     pdk_index i0, pdk_index i1);
void pdk_kernel_corr_pass1_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                                pdk_index i1);
void pdk_kernel_corr_pass2_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                                pdk_index i1);
pdk_index pdk_kernel_corr_shape_avx512(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                       pdk_index i0, pdk_index i1);
void pdk_kernel_corr_pass1_avx512(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                  pdk_index i0, pdk_index i1);
void pdk_kernel_corr_pass2_avx512(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                  pdk_index i0, pdk_index i1);

/* Correspondence passes 1 and 2 on the lattice (stencil layout; kernels/opt/corr_stencil.h, driven
 * by src/models/model_stencil.c): rows r0 .. r1-1 of the site grid a; c is the model's arrays (the
 * per-particle end writes F, A, W, flags, history through it; its pass-2 arrays are NULL).
 * Baseline ISA, AVX2 + FMA, AVX-512 variants; results equal the general path's up to the order
 * of the family sums (round-off, tests/t163). */
typedef void (*pdk_corr_stencil_fn)(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                    const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass1_base(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass2_base(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass1_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass2_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass1_avx512(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                          const pdk_stencil_arrays *a, int64_t r0, int64_t r1);
void pdk_kernel_corr_stencil_pass2_avx512(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                          const pdk_stencil_arrays *a, int64_t r0, int64_t r1);

/* Bond failure (commit passes): the s0 rule (when s0 != NULL) and, with break_failed, every bond
 * with a failed end; sets changed[i] to 3 for rows that lost bonds, 0 otherwise. Returns the
 * directed bonds broken. */
pdk_bond_index pdk_kernel_corr_break_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                         pdk_index i0, pdk_index i1);
/* Shape again for rows with changed bit 0; with detach != NULL (semi-TL) sets detach[i] = 1 for
 * those whose intact family no longer spans but still has bonds (0 for every other i). Returns
 * how many it detached. */
pdk_index pdk_kernel_corr_reshape_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                      pdk_index i0, pdk_index i1);
/* semi-TL detachment: breaks every intact bond of row i with detach[i] or detach[j]; changed[i]
 * bit 0 = row lost bonds now, bit 1 kept and set. Returns the directed bonds broken. */
pdk_bond_index pdk_kernel_corr_cut_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                       pdk_index i0, pdk_index i1);
/* Energy released by breaking, for rows with changed bit 1 (after their shape was recomputed):
 * w_broken[i] += W[i] - (stored energy at the current x with the new family, plus the plastic
 * and damage work of the jump of F, history frozen). With remap (Johnson-Cook,
 * pdk_model_opts.break_stress = PDK_BREAK_STRESS_CONTINUOUS) a row that still carries stress
 * first has its C_p^-1 remapped from a->F (this pass's F, the old family) to the new family's F
 * at the same x (pdk_jc_remap), so the stress does not jump at the break. Returns sum_i V_i
 * (that increment) over the range, in index order. */
double pdk_kernel_corr_release_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                   pdk_index i0, pdk_index i1, int remap);
/* The elastic laws of pass 1 at one F (d x d block of 3 x 3, row-major): P and W; returns 0 where
 * the law is undefined (Neo-Hooke with J <= 0). Not for law JC. */
int pdk_kernel_corr_law_ref(const pdk_corr_consts *k, const double F[3][3], double P[3][3],
                            double *W);

/* ---- Correspondence, updated Lagrangian (kernels/ref/corr_ul.c; formulas in its header) ------
 * The arrays of the TL kernels with these meanings changed: bond_* the families of the last
 * rebuild (bond_alive NULL: UL breaks no bonds), X the positions at the last rebuild, volume the
 * volumes there, A = tau_r M^-1, F the total deformation gradient F^ F_ref, m the weighted volume
 * at the rebuild; Kinv, num_alive, s0*, changed, detach, w_broken unused. */
typedef struct pdk_corr_ul_arrays {
  pdk_corr_arrays base;
  const double *J_ref;    /* [n_pad] det F_ref [-] */
  double *F_ref[9];       /* deformation gradient at the last rebuild [-] (read only) */
  double *F_inc[9];       /* F^ = M N^-T relative to the rebuild; NULL without stabilization */
} pdk_corr_ul_arrays;

/* Rebuild shape: m, flag bit SPAN (K of the rebuild configuration, TL's criterion); returns how
 * many do not span. */
pdk_index pdk_kernel_corr_ul_shape_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *a,
                                       pdk_index i0, pdk_index i1);
/* Pass 1: N, M, F^, F, the law, A = tau_r M^-1, W. */
void pdk_kernel_corr_ul_pass1_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *a,
                                  pdk_index i0, pdk_index i1);
/* Pass 2: f (and W += Silling energy); reads A, F_inc of neighbours from pass 1. */
void pdk_kernel_corr_ul_pass2_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *a,
                                  pdk_index i0, pdk_index i1);

/* ---- Peridynamic Galerkin (kernels/ref/galerkin.c; formulas at the top of that file) ----------
 * Families: particle k's family is the list of its members m = 0 .. N_k, member 0 the particle
 * itself and member m >= 1 its bond bond_start[k] + m - 1 (neighbour bond_j of it). A member's
 * slot, for the per-member arrays, is bond_start[k] + k + m (n + num_bonds slots in all). rev[b]
 * of bond b = (k -> j) is the member index (>= 1) of k in j's family (the families are
 * symmetric). The derivative table of family k starts at dstart[k] and holds
 * d[(j (N_k + 1) + i) dim + c], the c-th component of dN^{kji}/dX: family k, evaluation point
 * (member) j, support node (member) i. */
/* Members of a family at most (the particle and its neighbours): the passes keep a family's
 * displacements and forces in local arrays of this size; the driver refuses larger families. */
#define PDK_GALERKIN_MAX_MEMBERS 512

typedef struct pdk_galerkin_consts {
  int dim;       /* 2 (plane strain) or 3 */
  int basis;     /* pdk_galerkin_basis: 0 taylor (MTE1), 1 wls (WLS1) */
  int bond;      /* 1: the bond-mapping correction (thesis eq. 5.55) in the shape kernel */
  int law;       /* PDK_KERNEL_LAW_* (elastic laws) */
  double lambda; /* Lame constants of the law */
  double mu;
} pdk_galerkin_consts;

typedef struct pdk_galerkin_arrays {
  const pdk_bond_index *bond_start; /* [n+1] */
  const pdk_index *bond_j;          /* [num_bonds] */
  const int32_t *rev;               /* [num_bonds] */
  const int64_t *dstart;            /* [n] */
  double *d;                        /* derivative table (written by the shape kernel) */
  const double *X[3], *x[3];        /* reference and current positions [n] */
  const double *volume;             /* [n] */
  const double *vfam;               /* [n] V_H of each family: the sum of its members' volumes */
  double *G[3];                     /* [n + num_bonds] per-member force of a family (pass 1) */
  double *F[9];                     /* [n] F^{kk} (pass 1), component [a][c] at a dim + c */
  double *W;                        /* [n] family energy sum_j w_kj W(F^{kj}) [energy] (pass 1) */
  double *f[3];                     /* [n] force density (pass 2) */
} pdk_galerkin_arrays;

/* Shape: the derivative table of families [k0, k1) from X and the volumes. Returns how many
 * (family, point) moment matrices were singular (their derivatives are set to 0). */
pdk_index pdk_kernel_galerkin_shape_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                        pdk_index k0, pdk_index k1);
/* psi[slot] = N^{kki}_MLS1 - delta_ki (the VC1 correction functions) of families [k0, k1):
 * returns how many moment matrices were singular (psi = 0 there). */
pdk_index pdk_kernel_galerkin_psi_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                      double *psi, pdk_index k0, pdk_index k1);
/* Pass 1 over families [k0, k1): F^{kj} at every member, the law, G, F, W. Returns how many
 * points the law is undefined at (their stress and energy are 0). With unit = 1 no law is
 * evaluated: G gets sum_j w_kj d^{kji} (the terms of the area vectors, eq. 4.35) instead. */
pdk_index pdk_kernel_galerkin_pass1_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                        int unit, pdk_index k0, pdk_index k1);
/* Pass 2 over particles [i0, i1): f_i = -(1/V_i) (G of i's own member 0 + G of i's member in
 * each neighbour's family, in bond order). With area = 1 the sum without -1/V_i (the area vector
 * after a unit pass 1). */
void pdk_kernel_galerkin_pass2_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                   int area, pdk_index i0, pdk_index i1);

#endif
