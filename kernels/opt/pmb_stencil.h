/* PMB force pass on a regular lattice (stencil layout): the body shared by kernels/opt/pmb_stencil.c
 * (baseline ISA), pmb_stencil_avx2.c and pmb_stencil_avx512.c, which define before including:
 *   SC_W            lanes per vector (sites per vector)
 *   SC_U            vectors per block (a block is SC_U * SC_W consecutive sites)
 *   SC_NAME(base)   the exported name
 *   SC_SQRT(v)      lane-wise correctly rounded square root of an sc_vd
 * and compile it for their ISA (target pragma); src/core/kernels.c installs the one the CPU runs.
 *
 * Layout (pdk_stencil_arrays in kernels/kernels.h, built by src/models/model_stencil.c): the particles sit
 * on the sites of a padded grid, site s = ix + nx (iy + ny iz); a bond is a fixed site offset
 * offset[o] (o < num_offsets, the same list for every particle), so the neighbour of site s along
 * offset o is site s + offset[o]. Positions, reference positions and volumes are stored per site
 * (empty sites: the ideal lattice point, volume 0), so a run of sites along x reads its neighbours
 * along one offset as contiguous vector loads: no index stream, no gather.
 *
 * Loops: rows [r0, r1) of the row list (row_lo[r] .. row_hi[r]-1: one grid row from its first to
 * its last occupied site), cut into blocks of SC_U * SC_W sites (lanes are sites), the rest of a
 * row into single vectors. Per block the
 * site's own data and the sums stay in registers while the offsets run in the outer loop; per
 * offset and vector, 7 contiguous loads (x, y, z, X, Y, Z, V of the neighbour sites). So particle
 * i's force is the sum of its bond terms in offset order, whatever the vector width and the
 * thread partition of the rows. The last block of a row computes its unused lanes on the sites
 * that follow (the arrays carry PDK_STENCIL_SLACK sites of slack past the grid); their results
 * are never stored and their bonds never change state.
 *
 * Each bond's terms are those of kernels/ref/pmb.c, with the same operations in the same order and
 * no FMA contraction (the including file opens with PDK_KERNEL_FP_EXACT), from the same values:
 * double storage recomputes r0 = |X_j - X_i| from the reference positions of the two sites (copies
 * of the particles' "X"); float storage takes r0 = r0_off[o], the offset's float bond length, which
 * set-up checked to equal every bond's stored float length (bond_r0 of the general path), and its
 * partial-volume factor beta_off[o]. So stretches, bond failure decisions, the number broken and
 * s0_next (a maximum) are the general path's bit for bit; forces and energy densities differ from
 * it by the order of the family sums only.
 *
 * mask [num_offsets][num_sites] (NULL: every bond to an occupied site exists and none can break):
 * 1 when bond (s, s + offset[o]) is in the family of the particle at s and intact, else 0; the
 * factor "on" of the reference. A committing pass (s0_next != NULL, needs mask and s0) clears the
 * entries of the bonds it breaks, sets changed[s] = 1 for their sites (the driver copies the new
 * state back to the model's bond list), and returns the count. Empty sites have volume 0 (and mask
 * 0), so without a mask their bonds add exact zeros.
 *
 * Outputs go to the particle site_particle[s] of each occupied site: f[c], w (NULL: skip),
 * s0_next. Contract: pure, no allocation, no OpenMP region; rows [r0, r1) write only their own
 * particles and the mask/changed entries of their own sites, so any partition of the rows gives
 * the same bits.
 */
#include <float.h>

#include "opt/stencil_simd.h"

/* One block of nu <= SC_U vectors (nu * SC_W sites from s, of which the first len are the row's). */
/* Reference length of the bonds to sites j .. j + SC_W - 1 from the reference positions X. */
SC_INLINE sc_vd sc_ref_length(const int dim, const double *const *X, const int64_t j,
                              const sc_vd Xi, const sc_vd Yi, const sc_vd Zi) {
  const sc_vd dX = sc_ld(X[0] + j) - Xi, dY = sc_ld(X[1] + j) - Yi;
  sc_vd rr0 = dX * dX + dY * dY;
  if (dim == 3) {
    const sc_vd dZ = sc_ld(X[2] + j) - Zi;
    rr0 = rr0 + dZ * dZ;
  }
  return SC_SQRT(rr0);
}

SC_INLINE pdk_bond_index sc_block(const int nu, const int dim, const int stored, const int has_mask,
                                  const int commit, const int want_energy,
                                  const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                  int64_t s, int len) {
  const sc_vd zero = sc_set1(0.0), one = sc_set1(1.0);
  const sc_vd c = sc_set1(k->c), vs_a = sc_set1(k->vs_a), vs_b = sc_set1(k->vs_b);
  const sc_vd s00 = sc_set1(k->s00), alpha = sc_set1(k->alpha), quarter = sc_set1(0.25);
  const sc_vd neg_max = sc_set1(-DBL_MAX), minus_one = sc_set1(-1.0);
  const int64_t ns = a->num_sites;
  sc_vd xi[SC_U], yi[SC_U], zi[SC_U], Xi[SC_U], Yi[SC_U], Zi[SC_U], s0i[SC_U];
  sc_vd f0[SC_U], f1[SC_U], f2[SC_U], wi[SC_U], s0m[SC_U];
  for (int u = 0; u < nu; ++u) {
    const int64_t t = s + u * SC_W;
    xi[u] = sc_ld(a->x[0] + t);
    yi[u] = sc_ld(a->x[1] + t);
    zi[u] = dim == 3 ? sc_ld(a->x[2] + t) : zero;
    Xi[u] = stored ? zero : sc_ld(a->X[0] + t);
    Yi[u] = stored ? zero : sc_ld(a->X[1] + t);
    Zi[u] = !stored && dim == 3 ? sc_ld(a->X[2] + t) : zero;
    s0i[u] = commit ? sc_ld(a->s0 + t) : zero;
    f0[u] = f1[u] = f2[u] = wi[u] = zero;
    s0m[u] = neg_max;
  }
  pdk_bond_index broken = 0;
  for (int o = 0; o < a->num_offsets; ++o) {
    const int64_t j0 = s + a->offset[o];
    const sc_vd r0_o = stored ? sc_set1(a->r0_off[o]) : zero;
    const sc_vd beta_o = stored ? sc_set1(a->beta_off[o]) : zero;
    for (int u = 0; u < nu; ++u) {
      const int64_t j = j0 + u * SC_W;
      const sc_vd dx = sc_ld(a->x[0] + j) - xi[u], dy = sc_ld(a->x[1] + j) - yi[u];
      const sc_vd dz = dim == 3 ? sc_ld(a->x[2] + j) - zi[u] : zero;
      const sc_vd r0 = stored ? r0_o : sc_ref_length(dim, a->X, j, Xi[u], Yi[u], Zi[u]);
      sc_vd rr = dx * dx + dy * dy;
      if (dim == 3) rr = rr + dz * dz;
      const sc_vd r = SC_SQRT(rr);
      const sc_vd d = r - r0;
      const sc_vl pos = r > zero;
      const sc_vd q = sc_sel(pos, one / (r0 * r), zero); /* r = 0 lanes: selected away */
      sc_vd beta;
      if (stored) {
        beta = beta_o;
      } else {
        beta = sc_min1((vs_a - r0) * vs_b);
      }
      const sc_vd vol = sc_ld(a->volume + j) * beta;
      const sc_vd on =
          has_mask ? sc_mask_lanes(a->mask + (int64_t)o * ns + s + u * SC_W, len - u * SC_W) : one;
      const sc_vd g = on * c * vol * d * q;
      f0[u] += g * dx;
      f1[u] += g * dy;
      if (dim == 3) f2[u] += g * dz;
      if (want_energy) wi[u] += quarter * g * d * r;
      if (commit) {
        const sc_vd st = sc_sel(pos, d * (r * q), minus_one);
        const sc_vd s0j = sc_ld(a->s0 + j);
        const sc_vd s0_min = sc_sel(s0j < s0i[u], s0j, s0i[u]);
        const sc_vl alive = on != zero;
        const sc_vl brk = alive & (d > s0_min * r0);
        const sc_vd cand = sc_sel(alive, s00 - alpha * st, neg_max);
        s0m[u] = sc_sel(cand > s0m[u], cand, s0m[u]);
        const int nv = len - u * SC_W; /* valid lanes of this vector (may be <= 0) */
        uint8_t *restrict mk = a->mask + (int64_t)o * ns + s + u * SC_W;
        uint8_t *restrict chg = a->changed + s + u * SC_W;
        for (int l = 0; l < SC_W && l < nv; ++l) {
          broken += brk[l] != 0;
          mk[l] = (uint8_t)(alive[l] != 0 && brk[l] == 0);
          chg[l] = (uint8_t)(chg[l] | (brk[l] != 0));
        }
      }
    }
  }
  const pdk_index *restrict sp = a->site_particle + s;
  for (int t = 0; t < len; ++t) {
    const pdk_index p = sp[t];
    if (p < 0) continue;
    const int u = t / SC_W, l = t % SC_W;
    a->f[0][p] = f0[u][l];
    a->f[1][p] = f1[u][l];
    if (dim == 3) a->f[2][p] = f2[u][l];
    if (want_energy) a->w[p] = wi[u][l];
    if (commit) a->s0_next[p] = s0m[u][l] == -DBL_MAX ? DBL_MAX : s0m[u][l];
  }
  return broken;
}

SC_INLINE pdk_bond_index sc_rows(const int dim, const int stored, const int has_mask,
                                 const int commit, const int want_energy, const pdk_pmb_consts *k,
                                 const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  pdk_bond_index broken = 0;
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t hi = a->row_hi[r];
    int64_t s = a->row_lo[r];
    for (; s + SC_B <= hi; s += SC_B) /* whole blocks */
      broken += sc_block(SC_U, dim, stored, has_mask, commit, want_energy, k, a, s, SC_B);
    for (; s < hi; s += SC_W) /* the rest one vector at a time: at most SC_W - 1 idle lanes */
      broken += sc_block(1, dim, stored, has_mask, commit, want_energy, k, a, s,
                         (int)(hi - s < SC_W ? hi - s : SC_W));
  }
  return broken;
}

/* One specialised loop per (dim, storage, mask, commit, energy); a commit needs the mask. */
#define SC_E(dim, st, mk, cm)                                                                      \
  (a->w ? sc_rows(dim, st, mk, cm, 1, k, a, r0, r1) : sc_rows(dim, st, mk, cm, 0, k, a, r0, r1))
#define SC_M(dim, st)                                                                              \
  (!a->mask ? SC_E(dim, st, 0, 0) : a->s0_next ? SC_E(dim, st, 1, 1) : SC_E(dim, st, 1, 0))
#define SC_S(dim) (a->r0_off ? SC_M(dim, 1) : SC_M(dim, 0))

pdk_bond_index SC_NAME(pdk_kernel_pmb_stencil)(const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                               int64_t r0, int64_t r1) {
  return a->dim == 3 ? SC_S(3) : SC_S(2);
}
