/* SIMD PMB force and LPS dilation / force passes over the sliced layout (SELL-C-sigma, C = BS_W):
 * included by kernels/opt/bond_avx2.c (C = 4) and bond_avx512.c (C = 8) after opt/bond_simd.h,
 * whose macros (BS_LOAD4, BS_GATHER, BS_SQRT, BS_CVT_F, BS_SET1) and helpers it uses.
 *
 * Layout and contract: kernels/kernels.h (pdk_sell_arrays); formula and failure rule:
 * kernels/ref/pmb.c; the scalar oracle of this layout: kernels/ref/bond_sell.c. One vector of C
 * lanes is C particles (the rows of a slice) at the same bond rank: per column, one aligned load of
 * C neighbour indices, the neighbours' packed rows (cur4 = (x, y, z, V), ref4 = (X, Y, Z, -)) by
 * C 32-byte loads and a register transpose, as the CSR variant; the particle's own rows are loaded
 * once per slice. Each lane accumulates its own particle's sums in CSR bond order, so no
 * horizontal sum and no partial step; padding entries add an exact +0 (r0 = r = 0, q = 0).
 * Every bond's terms use the reference's operations in its order (no FMA: the including file
 * opens with PDK_KERNEL_FP_EXACT), so failure decisions and s0_next are the reference's bits.
 */

/* One column of C bonds: the reference length from the neighbours' reference rows t (X, Y, Z),
 * and the bond-state mask (1 intact, 0 broken or padding; 1 everywhere without bond state). */
BS_INLINE bs_vd sell_ref_length(const int dim, const bs_vd *t, const bs_vd Xi, const bs_vd Yi,
                                const bs_vd Zi) {
  const bs_vd dX = t[0] - Xi, dY = t[1] - Yi;
  bs_vd rr0 = dX * dX + dY * dY;
  if (dim == 3) {
    const bs_vd dZ = t[2] - Zi;
    rr0 = rr0 + dZ * dZ;
  }
  return BS_SQRT(rr0);
}

/* One column of C bonds, current side: the neighbours' cur4 rows (x, y, z, V) at j give the bond
 * vector (dx, dy, dz) from the lane particles at (xi, yi, zi), V_j, and returns r = |dx|. */
BS_INLINE bs_vd sell_cur_bond(const int dim, const double *cur4, const pdk_index *j, const bs_vd xi,
                              const bs_vd yi, const bs_vd zi, bs_vd *dx, bs_vd *dy, bs_vd *dz,
                              bs_vd *vj) {
  bs_vd t[4];
  BS_LOAD4(cur4, j, t);
  *dx = t[0] - xi, *dy = t[1] - yi, *dz = t[2] - zi, *vj = t[3];
  bs_vd rr = *dx * *dx + *dy * *dy;
  if (dim == 3) rr = rr + *dz * *dz;
  return BS_SQRT(rr);
}

/* The reference length of column e: the stored float length (stored) or from the neighbours'
 * reference rows at j. */
BS_INLINE bs_vd sell_r0(const int dim, const int stored, const pdk_bond_arrays *a,
                        const pdk_sell_arrays *s, const int64_t e, const pdk_index *j,
                        const bs_vd Xi, const bs_vd Yi, const bs_vd Zi) {
  if (stored) return BS_CVT_F(s->r0 + e);
  bs_vd t[4];
  BS_LOAD4(a->ref4, j, t);
  return sell_ref_length(dim, t, Xi, Yi, Zi);
}

BS_INLINE bs_vd sell_alive(const int has_state, const pdk_sell_arrays *s, const int64_t e,
                           const bs_vd one) {
  bs_vd on = one;
  if (has_state) {
    double o[BS_W];
    for (int l = 0; l < BS_W; ++l)
      o[l] = (double)s->alive[e + l];
    memcpy(&on, o, sizeof o);
  }
  return on;
}

BS_INLINE pdk_bond_index sell_pmb_slices(const int dim, const int has_state, const int commit,
                                         const int want_energy, const int stored,
                                         const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                         const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  pdk_bond_index broken = 0;
  const bs_vd zero = bs_set1(0.0), one = bs_set1(1.0);
  const bs_vd c = bs_set1(k->c), vs_a = bs_set1(k->vs_a), vs_b = bs_set1(k->vs_b);
  const bs_vd quarter = bs_set1(0.25);
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * BS_W;
    bs_vd t[4];
    BS_LOAD4(a->cur4, rows, t);
    const bs_vd xi = t[0], yi = t[1], zi = t[2];
    bs_vd Xi = zero, Yi = zero, Zi = zero;
    if (!stored) {
      BS_LOAD4(a->ref4, rows, t);
      Xi = t[0], Yi = t[1], Zi = t[2];
    }
    const bs_vd s0_i = has_state && commit ? BS_GATHER(a->s0, rows) : zero;
    bs_vd f0 = zero, f1 = zero, f2 = zero, wi = zero, s0_max = bs_set1(-DBL_MAX);
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += BS_W) {
      const pdk_index *j = s->sj + e;
      bs_vd dx, dy, dz, vj;
      const bs_vd r = sell_cur_bond(dim, a->cur4, j, xi, yi, zi, &dx, &dy, &dz, &vj);
      const bs_vd r0 = sell_r0(dim, stored, a, s, e, j, Xi, Yi, Zi);
      const bs_vd on = sell_alive(has_state, s, e, one);
      const bs_vd d = r - r0;
      const bs_vd q = bs_sel(r > zero, one / (r0 * r), zero);
      const bs_vd vol = vj * bs_min1((vs_a - r0) * vs_b);
      const bs_vd g = on * c * vol * d * q;
      f0 += g * dx;
      f1 += g * dy;
      if (dim == 3) f2 += g * dz;
      if (want_energy) wi += quarter * g * d * r;
      if (has_state && commit) {
        const bs_vd sv = bs_sel(r > zero, d * (r * q), bs_set1(-1.0));
        const bs_vd s0j = BS_GATHER(a->s0, j);
        const bs_vd s0_min = bs_sel(s0j < s0_i, s0j, s0_i);
        const bs_vl alive = on != zero;
        const bs_vl brk = alive & (d > s0_min * r0);
        const bs_vd cand =
            bs_sel(alive, bs_set1(k->s00) - bs_set1(k->alpha) * sv, bs_set1(-DBL_MAX));
        s0_max = bs_sel(cand > s0_max, cand, s0_max);
        long long any = 0;
        for (int l = 0; l < BS_W; ++l)
          any |= brk[l];
        if (any) /* rare: clear the bond in both layouts */
          for (int l = 0; l < BS_W; ++l)
            if (brk[l]) {
              ++broken;
              s->alive[e + l] = 0;
              a->bond_alive[a->bond_start[rows[l]] + (e - e0) / BS_W] = 0;
            }
      }
    }
    for (int l = 0; l < BS_W; ++l) {
      if (sl * BS_W + l >= s->n) break;
      const pdk_index i = rows[l];
      a->f[0][i] = f0[l];
      a->f[1][i] = f1[l];
      if (dim == 3) a->f[2][i] = f2[l];
      if (want_energy) a->w[i] = wi[l];
      if (has_state && commit) a->s0_next[i] = s0_max[l] == -DBL_MAX ? DBL_MAX : s0_max[l];
    }
  }
  return broken;
}

#define SELL_S(dim, st, cm, en)                                                                    \
  (s->r0 ? sell_pmb_slices(dim, st, cm, en, 1, k, a, s, s0, s1)                                    \
         : sell_pmb_slices(dim, st, cm, en, 0, k, a, s, s0, s1))
#define SELL_E(dim, st, cm) (a->w ? SELL_S(dim, st, cm, 1) : SELL_S(dim, st, cm, 0))
#define SELL_D(dim)                                                                                \
  (!s->alive ? SELL_E(dim, 0, 0) : !a->s0_next ? SELL_E(dim, 1, 0) : SELL_E(dim, 1, 1))

pdk_bond_index BS_NAME(pdk_kernel_pmb_force_sell)(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                                  const pdk_sell_arrays *s, int64_t s0,
                                                  int64_t s1) {
  return a->dim == 3 ? SELL_D(3) : SELL_D(2);
}

/* ---- LPS (formulas: kernels/ref/lps.c; the padding's deviatoric energy term, 0/0, is skipped
 * where r0 = 0, as in kernels/ref/bond_sell.c) ------------------------------------------------ */

BS_INLINE void sell_lps_theta_slices(const int dim, const int has_state, const int stored,
                                     const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                     const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  const bs_vd zero = bs_set1(0.0), one = bs_set1(1.0);
  const bs_vd vs_a = bs_set1(k->vs_a), vs_b = bs_set1(k->vs_b);
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * BS_W;
    bs_vd t[4];
    BS_LOAD4(a->cur4, rows, t);
    const bs_vd xi = t[0], yi = t[1], zi = t[2];
    bs_vd Xi = zero, Yi = zero, Zi = zero;
    if (!stored) {
      BS_LOAD4(a->ref4, rows, t);
      Xi = t[0], Yi = t[1], Zi = t[2];
    }
    bs_vd sum = zero;
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += BS_W) {
      const pdk_index *j = s->sj + e;
      bs_vd dx, dy, dz, vj;
      const bs_vd r = sell_cur_bond(dim, a->cur4, j, xi, yi, zi, &dx, &dy, &dz, &vj);
      const bs_vd r0 = sell_r0(dim, stored, a, s, e, j, Xi, Yi, Zi);
      const bs_vd on = sell_alive(has_state, s, e, one);
      sum += on * (r - r0) * (vj * bs_min1((vs_a - r0) * vs_b));
    }
    for (int l = 0; l < BS_W; ++l) {
      if (sl * BS_W + l >= s->n) break;
      const pdk_index i = rows[l];
      a->theta_out[i] = k->theta_factor * a->inv_m[i] * sum[l];
    }
  }
}

BS_INLINE pdk_bond_index sell_lps_force_slices(const int dim, const int has_state, const int commit,
                                               const int want_energy, const int stored,
                                               const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                               const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  pdk_bond_index broken = 0;
  const bs_vd zero = bs_set1(0.0), one = bs_set1(1.0);
  const bs_vd vs_a = bs_set1(k->vs_a), vs_b = bs_set1(k->vs_b);
  const bs_vd c_dil = bs_set1(k->c_dil), c_dev = bs_set1(k->c_dev), d = bs_set1(k->theta_factor);
  for (int64_t sl = s0; sl < s1; ++sl) {
    const pdk_index *rows = s->row_i + sl * BS_W;
    bs_vd t[4];
    BS_LOAD4(a->cur4, rows, t);
    const bs_vd xi = t[0], yi = t[1], zi = t[2];
    BS_LOAD4(a->ref4, rows, t);
    const bs_vd Xi = t[0], Yi = t[1], Zi = t[2], inv_m_i = t[3];
    const bs_vd theta_i = BS_GATHER(a->theta, rows);
    const bs_vd q_i = theta_i * inv_m_i, sd_i = theta_i / d;
    const bs_vd s0_i = has_state && commit ? BS_GATHER(a->s0, rows) : zero;
    bs_vd f0 = zero, f1 = zero, f2 = zero, wdev = zero, s0_max = bs_set1(-DBL_MAX);
    const int64_t e0 = s->slice_start[sl], e1 = s->slice_start[sl + 1];
    for (int64_t e = e0; e < e1; e += BS_W) {
      const pdk_index *j = s->sj + e;
      bs_vd dx, dy, dz, vj;
      const bs_vd r = sell_cur_bond(dim, a->cur4, j, xi, yi, zi, &dx, &dy, &dz, &vj);
      BS_LOAD4(a->ref4, j, t);
      const bs_vd inv_m_j = t[3];
      const bs_vd r0 = stored ? BS_CVT_F(s->r0 + e) : sell_ref_length(dim, t, Xi, Yi, Zi);
      const bs_vd on = sell_alive(has_state, s, e, one);
      const bs_vd ext = r - r0;
      const bs_vd q = bs_sel(r > zero, one / (r0 * r), zero);
      const bs_vd vol = on * (vj * bs_min1((vs_a - r0) * vs_b));
      const bs_vd theta_j = BS_GATHER(a->theta, j);
      const bs_vd g =
          vol * (c_dil * (q_i + theta_j * inv_m_j) * r0 + c_dev * (inv_m_i + inv_m_j) * ext) * q;
      f0 += g * dx;
      f1 += g * dy;
      if (dim == 3) f2 += g * dz;
      if (want_energy) {
        const bs_vd ed = ext - sd_i * r0;
        wdev += bs_sel(r0 > zero, ed * ed / r0 * vol, zero);
      }
      if (has_state && commit) {
        const bs_vd sv = bs_sel(r > zero, ext * (r * q), bs_set1(-1.0));
        const bs_vd s0j = BS_GATHER(a->s0, j);
        const bs_vd s0_min = bs_sel(s0j < s0_i, s0j, s0_i);
        const bs_vl alive = on != zero;
        const bs_vl brk = alive & (ext > s0_min * r0);
        const bs_vd cand =
            bs_sel(alive, bs_set1(k->s00) - bs_set1(k->alpha) * sv, bs_set1(-DBL_MAX));
        s0_max = bs_sel(cand > s0_max, cand, s0_max);
        long long any = 0;
        for (int l = 0; l < BS_W; ++l)
          any |= brk[l];
        if (any)
          for (int l = 0; l < BS_W; ++l)
            if (brk[l]) {
              ++broken;
              s->alive[e + l] = 0;
              a->bond_alive[a->bond_start[rows[l]] + (e - e0) / BS_W] = 0;
            }
      }
    }
    for (int l = 0; l < BS_W; ++l) {
      if (sl * BS_W + l >= s->n) break;
      const pdk_index i = rows[l];
      a->f[0][i] = f0[l];
      a->f[1][i] = f1[l];
      if (dim == 3) a->f[2][i] = f2[l];
      if (want_energy) {
        const double th = a->theta[i];
        a->w[i] = 0.5 * k->e_bulk * th * th + k->e_dev * a->inv_m[i] * wdev[l];
      }
      if (has_state && commit) a->s0_next[i] = s0_max[l] == -DBL_MAX ? DBL_MAX : s0_max[l];
    }
  }
  return broken;
}

#define SELL_LS(dim, st, cm, en)                                                                   \
  (s->r0 ? sell_lps_force_slices(dim, st, cm, en, 1, k, a, s, s0, s1)                              \
         : sell_lps_force_slices(dim, st, cm, en, 0, k, a, s, s0, s1))
#define SELL_LE(dim, st, cm) (a->w ? SELL_LS(dim, st, cm, 1) : SELL_LS(dim, st, cm, 0))
#define SELL_LD(dim)                                                                               \
  (!s->alive ? SELL_LE(dim, 0, 0) : !a->s0_next ? SELL_LE(dim, 1, 0) : SELL_LE(dim, 1, 1))

void BS_NAME(pdk_kernel_lps_dilation_sell)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                           const pdk_sell_arrays *s, int64_t s0, int64_t s1) {
  const int st = s->alive != NULL, stored = s->r0 != NULL;
  if (a->dim == 3) {
    if (st)
      stored ? sell_lps_theta_slices(3, 1, 1, k, a, s, s0, s1)
             : sell_lps_theta_slices(3, 1, 0, k, a, s, s0, s1);
    else
      stored ? sell_lps_theta_slices(3, 0, 1, k, a, s, s0, s1)
             : sell_lps_theta_slices(3, 0, 0, k, a, s, s0, s1);
  } else {
    if (st)
      stored ? sell_lps_theta_slices(2, 1, 1, k, a, s, s0, s1)
             : sell_lps_theta_slices(2, 1, 0, k, a, s, s0, s1);
    else
      stored ? sell_lps_theta_slices(2, 0, 1, k, a, s, s0, s1)
             : sell_lps_theta_slices(2, 0, 0, k, a, s, s0, s1);
  }
}

pdk_bond_index BS_NAME(pdk_kernel_lps_force_sell)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                                  const pdk_sell_arrays *s, int64_t s0,
                                                  int64_t s1) {
  return a->dim == 3 ? SELL_LD(3) : SELL_LD(2);
}
