/* LPS dilation and force passes on a regular lattice (stencil layout): included after
 * kernels/opt/pmb_stencil.h by the same files (kernels/opt/pmb_stencil*.c), whose layout, blocks,
 * lanes and conventions it shares (see there). Formulas: kernels/ref/lps.c; each bond's terms use
 * the reference's operations in its order, no FMA, so theta, the stretches and bond failure are
 * the general path's bits up to the order of the family sums (theta, f, W differ by round-off).
 *
 * Extra arrays (pdk_stencil_arrays): inv_m [sites] 1/m per site (0 at empty sites; the model's
 * own 1/m_i, computed once by the general path); theta [sites], the dilation per site, written by
 * the dilation pass (its own sites only) and read by the force pass; theta_out [n_pad] the
 * particles' dilation. Empty sites have volume 0, 1/m 0 and theta 0, so their bonds add zeros.
 */

/* ---- dilation: theta_i = d inv_m_i sum_b on (r - r0) beta V_j -------------------------------- */

SC_INLINE void sc_lps_theta_block(const int nu, const int dim, const int stored,
                                  const int has_mask, const pdk_lps_consts *k,
                                  const pdk_stencil_arrays *a, int64_t s, int len) {
  const sc_vd zero = sc_set1(0.0), one = sc_set1(1.0);
  const sc_vd vs_a = sc_set1(k->vs_a), vs_b = sc_set1(k->vs_b);
  const int64_t ns = a->num_sites;
  sc_vd xi[SC_U], yi[SC_U], zi[SC_U], Xi[SC_U], Yi[SC_U], Zi[SC_U], sum[SC_U];
  for (int u = 0; u < nu; ++u) {
    const int64_t t = s + u * SC_W;
    xi[u] = sc_ld(a->x[0] + t);
    yi[u] = sc_ld(a->x[1] + t);
    zi[u] = dim == 3 ? sc_ld(a->x[2] + t) : zero;
    Xi[u] = stored ? zero : sc_ld(a->X[0] + t);
    Yi[u] = stored ? zero : sc_ld(a->X[1] + t);
    Zi[u] = !stored && dim == 3 ? sc_ld(a->X[2] + t) : zero;
    sum[u] = zero;
  }
  for (int o = 0; o < a->num_offsets; ++o) {
    const int64_t j0 = s + a->offset[o];
    const sc_vd r0_o = stored ? sc_set1(a->r0_off[o]) : zero;
    const sc_vd beta_o = stored ? sc_set1(a->beta_off[o]) : zero;
    for (int u = 0; u < nu; ++u) {
      const int64_t j = j0 + u * SC_W;
      const sc_vd dx = sc_ld(a->x[0] + j) - xi[u], dy = sc_ld(a->x[1] + j) - yi[u];
      const sc_vd r0 = stored ? r0_o : sc_ref_length(dim, a->X, j, Xi[u], Yi[u], Zi[u]);
      sc_vd rr = dx * dx + dy * dy;
      if (dim == 3) {
        const sc_vd dz = sc_ld(a->x[2] + j) - zi[u];
        rr = rr + dz * dz;
      }
      const sc_vd r = SC_SQRT(rr);
      sc_vd beta;
      if (stored) {
        beta = beta_o;
      } else {
        beta = sc_min1((vs_a - r0) * vs_b);
      }
      const sc_vd pv = sc_ld(a->volume + j) * beta;
      if (has_mask) {
        const sc_vd on = sc_mask_lanes(a->mask + (int64_t)o * ns + s + u * SC_W, len - u * SC_W);
        sum[u] += on * (r - r0) * pv;
      } else {
        sum[u] += one * (r - r0) * pv; /* the reference's on = 1.0: same bits */
      }
    }
  }
  const double d = k->theta_factor;
  const pdk_index *restrict sp = a->site_particle + s;
  for (int t = 0; t < len; ++t) {
    const pdk_index p = sp[t];
    if (p < 0) continue;
    const double th = d * a->inv_m[s + t] * sum[t / SC_W][t % SC_W];
    a->theta_out[p] = th;
    a->theta_site[s + t] = th;
  }
}

/* ---- force: f_i = sum_b on beta V_j t_b eta / r ---------------------------------------------- */

SC_INLINE pdk_bond_index sc_lps_force_block(const int nu, const int dim, const int stored,
                                            const int has_mask, const int commit,
                                            const int want_energy, const pdk_lps_consts *k,
                                            const pdk_stencil_arrays *a, int64_t s, int len) {
  const sc_vd zero = sc_set1(0.0), one = sc_set1(1.0);
  const sc_vd vs_a = sc_set1(k->vs_a), vs_b = sc_set1(k->vs_b);
  const sc_vd c_dil = sc_set1(k->c_dil), c_dev = sc_set1(k->c_dev);
  const sc_vd s00 = sc_set1(k->s00), alpha = sc_set1(k->alpha);
  const sc_vd neg_max = sc_set1(-DBL_MAX), minus_one = sc_set1(-1.0);
  const double d = k->theta_factor;
  const int64_t ns = a->num_sites;
  sc_vd xi[SC_U], yi[SC_U], zi[SC_U], Xi[SC_U], Yi[SC_U], Zi[SC_U], s0i[SC_U];
  sc_vd qi[SC_U], imi[SC_U], sdi[SC_U];
  sc_vd f0[SC_U], f1[SC_U], f2[SC_U], wd[SC_U], s0m[SC_U];
  for (int u = 0; u < nu; ++u) {
    const int64_t t = s + u * SC_W;
    xi[u] = sc_ld(a->x[0] + t);
    yi[u] = sc_ld(a->x[1] + t);
    zi[u] = dim == 3 ? sc_ld(a->x[2] + t) : zero;
    Xi[u] = stored ? zero : sc_ld(a->X[0] + t);
    Yi[u] = stored ? zero : sc_ld(a->X[1] + t);
    Zi[u] = !stored && dim == 3 ? sc_ld(a->X[2] + t) : zero;
    s0i[u] = commit ? sc_ld(a->s0 + t) : zero;
    const sc_vd th = sc_ld(a->theta + t);
    imi[u] = sc_ld(a->inv_m + t);
    qi[u] = th * imi[u];
    sdi[u] = th / sc_set1(d);
    f0[u] = f1[u] = f2[u] = wd[u] = zero;
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
      const sc_vd e = r - r0;
      const sc_vl pos = r > zero;
      const sc_vd q = sc_sel(pos, one / (r0 * r), zero);
      sc_vd beta;
      if (stored) {
        beta = beta_o;
      } else {
        beta = sc_min1((vs_a - r0) * vs_b);
      }
      const sc_vd on =
          has_mask ? sc_mask_lanes(a->mask + (int64_t)o * ns + s + u * SC_W, len - u * SC_W) : one;
      const sc_vd vol = on * (sc_ld(a->volume + j) * beta);
      const sc_vd th_j = sc_ld(a->theta + j), im_j = sc_ld(a->inv_m + j);
      const sc_vd g = vol * (c_dil * (qi[u] + th_j * im_j) * r0 + c_dev * (imi[u] + im_j) * e) * q;
      f0[u] += g * dx;
      f1[u] += g * dy;
      if (dim == 3) f2[u] += g * dz;
      if (want_energy) {
        const sc_vd ed = e - sdi[u] * r0;
        wd[u] += ed * ed / r0 * vol;
      }
      if (commit) {
        const sc_vd st = sc_sel(pos, e * (r * q), minus_one);
        const sc_vd s0j = sc_ld(a->s0 + j);
        const sc_vd s0_min = sc_sel(s0j < s0i[u], s0j, s0i[u]);
        const sc_vl alive = on != zero;
        const sc_vl brk = alive & (e > s0_min * r0);
        const sc_vd cand = sc_sel(alive, s00 - alpha * st, neg_max);
        s0m[u] = sc_sel(cand > s0m[u], cand, s0m[u]);
        const int nv = len - u * SC_W;
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
    if (want_energy) {
      const double th = a->theta[s + t];
      a->w[p] = 0.5 * k->e_bulk * th * th + k->e_dev * a->inv_m[s + t] * wd[u][l];
    }
    if (commit) a->s0_next[p] = s0m[u][l] == -DBL_MAX ? DBL_MAX : s0m[u][l];
  }
  return broken;
}

SC_INLINE pdk_bond_index sc_lps_rows(const int pass, const int dim, const int stored,
                                     const int has_mask, const int commit, const int want_energy,
                                     const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                     int64_t r0, int64_t r1) {
  pdk_bond_index broken = 0;
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t hi = a->row_hi[r];
    int64_t s = a->row_lo[r];
    for (; s + SC_B <= hi; s += SC_B) {
      if (pass == 0)
        sc_lps_theta_block(SC_U, dim, stored, has_mask, k, a, s, SC_B);
      else
        broken += sc_lps_force_block(SC_U, dim, stored, has_mask, commit, want_energy, k, a, s,
                                     SC_B);
    }
    for (; s < hi; s += SC_W) {
      const int len = (int)(hi - s < SC_W ? hi - s : SC_W);
      if (pass == 0)
        sc_lps_theta_block(1, dim, stored, has_mask, k, a, s, len);
      else
        broken +=
            sc_lps_force_block(1, dim, stored, has_mask, commit, want_energy, k, a, s, len);
    }
  }
  return broken;
}

#define SC_LE(dim, st, mk, cm)                                                                     \
  (a->w ? sc_lps_rows(1, dim, st, mk, cm, 1, k, a, r0, r1)                                         \
        : sc_lps_rows(1, dim, st, mk, cm, 0, k, a, r0, r1))
#define SC_LM(dim, st)                                                                             \
  (!a->mask ? SC_LE(dim, st, 0, 0) : a->s0_next ? SC_LE(dim, st, 1, 1) : SC_LE(dim, st, 1, 0))
#define SC_LS(dim) (a->r0_off ? SC_LM(dim, 1) : SC_LM(dim, 0))

pdk_bond_index SC_NAME(pdk_kernel_lps_stencil_force)(const pdk_lps_consts *k,
                                                     const pdk_stencil_arrays *a, int64_t r0,
                                                     int64_t r1) {
  return a->dim == 3 ? SC_LS(3) : SC_LS(2);
}

#define SC_TM(dim, st)                                                                             \
  (a->mask ? sc_lps_rows(0, dim, st, 1, 0, 0, k, a, r0, r1)                                        \
           : sc_lps_rows(0, dim, st, 0, 0, 0, k, a, r0, r1))
#define SC_TS(dim) (a->r0_off ? SC_TM(dim, 1) : SC_TM(dim, 0))

void SC_NAME(pdk_kernel_lps_stencil_dilation)(const pdk_lps_consts *k,
                                              const pdk_stencil_arrays *a, int64_t r0,
                                              int64_t r1) {
  (void)(a->dim == 3 ? SC_TS(3) : SC_TS(2));
}
