/* Correspondence passes 1 and 2 on a regular lattice (stencil layout): the body shared by
 * kernels/opt/corr_stencil.c (baseline ISA), corr_stencil_avx2.c and corr_stencil_avx512.c, which
 * define SC_W, SC_U and SC_NAME(base) as for kernels/opt/pmb_stencil.h and include this file.
 * Unlike the PMB and LPS stencil passes these compile with FMA contraction where the ISA has it
 * (nothing here has to equal another path bit for bit).
 *
 * Layout: kernels/opt/pmb_stencil.h (sites of a padded grid, a bond is a fixed site offset, rows
 * of sites cut into blocks whose lanes are sites). On a lattice the reference bond xi and the
 * influence omega depend on the offset only (set-up checked both against every bond), so per
 * offset o they are broadcast constants (omega_o and a_o = omega_o xi_o) and the neighbour data
 * of a vector of sites are contiguous loads: the volume V_j, the displacement u_j, and in pass 2
 * the 9 (2-D: 4) entries of B_j and k_j. Empty sites have V = 0 (and u = 0, B = 0, k = 0): their
 * bonds add exact zeros. mask (NULL: every bond to an occupied site is in the family and intact)
 * multiplies V_j by 0 / 1 per bond. Formulas: kernels/ref/corr.c; the split into own and
 * neighbour terms is that of the packed-row general path (kernels/opt/corr_simd.h). With
 * w = omega_o V_j mask, e = xi_o, v = u_j - u_i:
 *
 * Pass 1, per site i: D = sum w v (x) e, vv = sum w |v|^2 (Silling), and with a mask the intact
 * count. The offsets come in pairs o, o' = no - 1 - o with offset[o'] = -offset[o] (the list is
 * symmetric and sorted), e' = -e, omega' = omega, so a pair adds (V_+ v_+ - V_- v_-) (x) a_o to D
 * with one set of d^2 FMAs (about 30% fewer operations per bond than one offset at a time). Then
 * the general path's per-particle end: the reference shape where the count differs from
 * num_alive (bonds broke since K^-1, or a restored checkpoint); F = I + D K^-1, the law, A, W,
 * flags (pdk_corr_end_elastic inline for the elastic laws, pdk_kernel_corr_point_disp_ref for
 * Johnson-Cook and families that do not span); k_i = pdk_corr_kst, B_i = A - k_i (F - I)
 * (Silling) or A, stored per site for the neighbours (cB, and the float copy cBf with float
 * storage), and the Silling energy W_i += k_i/2 zz_i, zz = pdk_corr_silling_zz (in the commit
 * pass where i fails, w_damage as the general pass 2).
 * Pass 2, per site i: f_i = sum_o V_j (B_j a_o + omega_o (k_j + k_i) v) + B_i s_i, the general
 * path's sum w (B_j e + k_j v) + B_i s + k_i U with k_i U folded into the bond term; s = sum w e
 * depends on the reference configuration only and is kept per site (cs, recomputed where bonds
 * break). B_i in double from cB; B_j from cBf with float storage. Pass 2 addresses its
 * neighbour streams (u, V, k, B) from one pointer with a fixed stride between them (cbase,
 * cstride: the driver allocates them as one block), so they take one general register, not 14.
 *
 * So every family sum runs in offset order, per site, whatever the vector width and the thread
 * partition of the rows: results are bitwise the same for any number of threads. Against the
 * general path they differ by the order of the sums and by FMA contraction (round-off).
 *
 * Contract: pure, no allocation, no OpenMP region; rows [r0, r1) write only their own particles'
 * entries (through c) and their own sites' cB, cBf, ck; pass 2 reads the neighbours' site data
 * pass 1 wrote (the driver puts a barrier between the passes).
 */
#include "opt/stencil_simd.h"
#include "ref/corr_law.h"

typedef float sc_vf __attribute__((vector_size(SC_W * 4)));

/* a in every lane as one broadcast (sc_set1's lane loop compiles to a masked broadcast per lane
 * with GCC 12 at 8 lanes); exact: a - (+0) = a for every a, -0 included. */
SC_INLINE sc_vd sc_bcast(double a) { return a - (sc_vd){0}; }

SC_INLINE sc_vd sc_ldf(const float *p) { /* unaligned load of SC_W floats, widened */
  sc_vf v;
  memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, sc_vd);
}

/* ---- pass 1 ------------------------------------------------------------------------------------
 */

SC_INLINE void sc_corr1_block(const int nu, const int d, const int has_mask, const int silling,
                              const int fl, const pdk_corr_consts *k, const pdk_corr_arrays *c,
                              const pdk_stencil_arrays *a, int64_t s, int len) {
  const sc_vd zero = sc_bcast(0.0);
  const int64_t ns = a->num_sites;
  sc_vd ui[SC_U][3], D[SC_U][3][3], Q[SC_U], cnt[SC_U];
  for (int u = 0; u < nu; ++u) {
    for (int r = 0; r < 3; ++r) {
      ui[u][r] = r < d ? sc_ld(a->u[r] + s + u * SC_W) : zero;
      for (int q = 0; q < 3; ++q)
        D[u][r][q] = zero;
    }
    Q[u] = cnt[u] = zero;
  }
  /* offsets in pairs o, o' = no - 1 - o with offset[o'] = -offset[o] (the list is symmetric and
   * sorted; set-up checked it): xi' = -xi, omega' = omega, so the pair adds
   * (V_+ v_+ - V_- v_-) (x) (omega xi) to D with one set of FMAs, and omega (V_+ |v_+|^2 + V_-
   * |v_-|^2) to vv. Each accumulator takes one FMA or add per pair: the loop-carried chains stay
   * one operation long. */
  const int no = a->num_offsets;
  for (int o = 0; o < no / 2; ++o) {
    const int o2 = no - 1 - o;
    const int64_t jp0 = s + a->offset[o], jm0 = s + a->offset[o2];
    sc_vd e[3];
    for (int q = 0; q < d; ++q)
      e[q] = sc_bcast(a->wxi_off[q][o]);
    const sc_vd om = sc_bcast(a->omega_off[o]);
    for (int u = 0; u < nu; ++u) {
      const int64_t jp = jp0 + u * SC_W, jm = jm0 + u * SC_W;
      sc_vd Vp = sc_ld(a->volume + jp), Vm = sc_ld(a->volume + jm);
      if (has_mask) {
        const int nv = len - u * SC_W;
        const sc_vd onp = sc_mask_lanes(a->mask + (int64_t)o * ns + s + u * SC_W, nv);
        const sc_vd onm = sc_mask_lanes(a->mask + (int64_t)o2 * ns + s + u * SC_W, nv);
        Vp *= onp;
        Vm *= onm;
        cnt[u] += onp + onm;
      }
      sc_vd qq = zero;
      for (int r = 0; r < d; ++r) {
        const sc_vd vp = sc_ld(a->u[r] + jp) - ui[u][r], vm = sc_ld(a->u[r] + jm) - ui[u][r];
        const sc_vd tp = Vp * vp, tm = Vm * vm;
        const sc_vd t = tp - tm;
        for (int q = 0; q < d; ++q)
          D[u][r][q] += t * e[q];
        if (silling) qq = r ? qq + tp * vp + tm * vm : tp * vp + tm * vm;
      }
      if (silling) Q[u] += om * qq;
    }
  }
  const pdk_index *restrict sp = a->site_particle + s;
  for (int t = 0; t < len; ++t) {
    const pdk_index p = sp[t];
    if (p < 0) continue;
    const int u = t / SC_W, l = t % SC_W;
    double Dp[3][3] = {{0}};
    for (int r = 0; r < d; ++r)
      for (int q = 0; q < d; ++q)
        Dp[r][q] = D[u][r][q][l];
    if (has_mask && c->num_alive && (int32_t)cnt[u][l] != c->num_alive[p])
      pdk_kernel_corr_shape_ref(k, c, p, p + 1);
    /* the per-particle end: inline for the elastic laws (F, A stay in registers), the
     * reference's otherwise, as the packed-row path's rows_end */
    double A[3][3] = {{0}}, F[3][3] = {{0}};
    if (k->law == PDK_KERNEL_LAW_JC || (c->flag[p] & PDK_CORR_FLAG_SPAN)) {
      pdk_kernel_corr_point_disp_ref(k, c, p, Dp);
      for (int r = 0; r < d; ++r)
        for (int q = 0; q < d; ++q) {
          A[r][q] = c->A[r * d + q][p];
          F[r][q] = c->F[r * d + q][p];
        }
    } else {
      pdk_corr_end_elastic(d, k, c, p, Dp, F, A);
    }
    const double ki = pdk_corr_kst(k, c, p);
    for (int r = 0; r < d; ++r)
      for (int q = 0; q < d; ++q) {
        const double B = silling ? A[r][q] - ki * (F[r][q] - (r == q ? 1.0 : 0.0)) : A[r][q];
        a->cB[r * d + q][s + t] = B;
        if (fl) a->cBf[r * d + q][s + t] = (float)B;
      }
    a->ck[s + t] = ki;
    if (silling) {
      const double zz = pdk_corr_silling_zz(d, Dp, c, p, Q[u][l]);
      c->W[p] += 0.5 * ki * zz;
      if ((c->flag[p] & PDK_CORR_FLAG_FAILED_NOW) && c->m[p] > 0.0)
        c->w_damage[p] += 0.5 * pdk_corr_kst_unflagged(k, c, p) * zz;
    }
  }
}

/* ---- pass 2 ------------------------------------------------------------------------------------
 */

SC_INLINE void sc_corr2_block(const int nu, const int d, const int has_mask, const int silling,
                              const int fl, const pdk_corr_arrays *c, const pdk_stencil_arrays *a,
                              int64_t s, int len) {
  const sc_vd zero = sc_bcast(0.0);
  const int64_t ns = a->num_sites;
  sc_vd ui[SC_U][3], ki[SC_U], f[SC_U][3];
  /* the 2 + d + d^2 neighbour streams from one pointer: component c of site j at
   * cb[c * S + j] (u, V, k, B; pdk_stencil_arrays cbase), B's float copy at cbf[t * S + j] */
  const double *restrict cb = a->cbase;
  const float *restrict cbf = a->cbase_f;
  const int64_t S = a->cstride;
  for (int u = 0; u < nu; ++u) {
    ki[u] = silling ? sc_ld(cb + (d + 1) * S + s + u * SC_W) : zero;
    for (int r = 0; r < 3; ++r) {
      ui[u][r] = r < d ? sc_ld(cb + r * S + s + u * SC_W) : zero;
      f[u][r] = zero;
    }
  }
  /* per bond: f += V_j (B_j (omega xi) + omega (k_j + k_i) v), i.e. the k_i U part of the own
   * terms folded into the bond (B_i s stays outside: s is a reference-configuration sum, kept
   * per site, pdk_stencil_arrays cs) */
  for (int o = 0; o < a->num_offsets; ++o) {
    const int64_t j0 = s + a->offset[o];
    sc_vd e[3];
    for (int q = 0; q < d; ++q)
      e[q] = sc_bcast(a->wxi_off[q][o]);
    const sc_vd om = sc_bcast(a->omega_off[o]);
    for (int u = 0; u < nu; ++u) {
      const int64_t j = j0 + u * SC_W;
      const double *restrict pj = cb + j;
      sc_vd V = sc_ld(pj + d * S);
      if (has_mask) V *= sc_mask_lanes(a->mask + (int64_t)o * ns + s + u * SC_W, len - u * SC_W);
      const sc_vd okk = silling ? om * (sc_ld(pj + (d + 1) * S) + ki[u]) : zero;
      for (int r = 0; r < d; ++r) {
        sc_vd g = zero;
        for (int q = 0; q < d; ++q) {
          const sc_vd Bj =
              fl ? sc_ldf(cbf + (r * d + q) * S + j) : sc_ld(pj + (d + 2 + r * d + q) * S);
          g = q ? g + e[q] * Bj : e[q] * Bj;
        }
        if (silling) g += okk * (sc_ld(pj + r * S) - ui[u][r]);
        f[u][r] += V * g;
      }
    }
  }
  const pdk_index *restrict sp = a->site_particle + s;
  for (int t = 0; t < len; ++t) {
    const pdk_index p = sp[t];
    if (p < 0) continue;
    const int u = t / SC_W, l = t % SC_W;
    for (int r = 0; r < d; ++r) {
      double own = 0.0;
      for (int q = 0; q < d; ++q)
        own += a->cB[r * d + q][s + t] * a->cs[q][s + t];
      c->f[r][p] = own + f[u][r][l];
    }
  }
}

/* ---- rows and dispatch -------------------------------------------------------------------------
 */

SC_INLINE void sc_corr_rows(const int pass, const int d, const int has_mask, const int silling,
                            const int fl, const pdk_corr_consts *k, const pdk_corr_arrays *c,
                            const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t hi = a->row_hi[r];
    int64_t s = a->row_lo[r];
    for (; s + SC_B <= hi; s += SC_B) {
      if (pass == 1)
        sc_corr1_block(SC_U, d, has_mask, silling, fl, k, c, a, s, SC_B);
      else
        sc_corr2_block(SC_U, d, has_mask, silling, fl, c, a, s, SC_B);
    }
    for (; s < hi; s += SC_W) {
      const int len = (int)(hi - s < SC_W ? hi - s : SC_W);
      if (pass == 1)
        sc_corr1_block(1, d, has_mask, silling, fl, k, c, a, s, len);
      else
        sc_corr2_block(1, d, has_mask, silling, fl, c, a, s, len);
    }
  }
}

#define SC_CF(pass, d, mk, si)                                                                     \
  (a->cBf[0] ? sc_corr_rows(pass, d, mk, si, 1, k, c, a, r0, r1)                                   \
             : sc_corr_rows(pass, d, mk, si, 0, k, c, a, r0, r1))
#define SC_CS(pass, d, mk)                                                                         \
  (k->stab == PDK_KERNEL_STAB_SILLING ? SC_CF(pass, d, mk, 1) : SC_CF(pass, d, mk, 0))
#define SC_CM(pass, d) (a->mask ? SC_CS(pass, d, 1) : SC_CS(pass, d, 0))

void SC_NAME(pdk_kernel_corr_stencil_pass1)(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                            const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  if (a->dim == 3)
    SC_CM(1, 3);
  else
    SC_CM(1, 2);
}

void SC_NAME(pdk_kernel_corr_stencil_pass2)(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                            const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  if (a->dim == 3)
    SC_CM(2, 3);
  else
    SC_CM(2, 2);
}
