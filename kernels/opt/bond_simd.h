/* SIMD PMB force and LPS dilation / force passes over packed particle rows: the body shared by
 * kernels/opt/bond_avx2.c (BS_W = 4) and bond_avx512.c (BS_W = 8), which define before including:
 *   BS_W                 lanes (bonds per step)
 *   BS_NAME(base)        the exported name, base ## _avx2 or base ## _avx512
 *   BS_LOAD4(p, j, c)    c[0..3] = the 4 doubles of rows p + 4 j[l], l < BS_W, transposed
 *   BS_SQRT(v)           lane-wise square root (correctly rounded)
 *   BS_GATHER(p, j)      lane l = p[j[l]]
 *   BS_CVT_F(p)          lane l = (double)p[l] (floats)
 *   BS_SET1(a)           every lane a
 *   BS_MIN(a, b)         lane-wise a < b ? a : b (vminpd)
 * and compile the file for their ISA (target pragma), so the baseline build runs anywhere and
 * src/core/kernels.c installs the variants only when the CPU has the ISA.
 *
 * Formulas, contracts and failure rules: kernels/ref/pmb.c and kernels/ref/lps.c. Each bond's
 * terms are computed with the operations of the reference in the same order, no FMA (the file
 * opens with PDK_KERNEL_FP_EXACT), from the same values (the rows are copies), so they are the
 * reference's bit for bit; only the sums over a family are taken in another order (BS_W partial
 * sums, added lane by lane at the end of the row). Bond failure decisions, the number broken and
 * s0_next (a maximum) are therefore exactly the reference's.
 *
 * r0 comes from bond_r0 (float storage, `stored` 1), from bond_r0d (the stored double lengths,
 * `stored` 2: the values bs_lengths would compute, pdk_kernel_bond_lengths_ref) or from the
 * reference rows (`stored` 0); with a stored r0 the PMB and dilation passes read no reference row.
 *
 * A row is walked in steps of BS_W bonds; the last, partial step repeats the row's last neighbour
 * in the missing lanes and gives them weight on = 0, so they add exact zeros and no array is read
 * past its end. The neighbour data come from the packed rows (pdk_bond_arrays): cur4 = (x, y, z,
 * V), ref4 = (X, Y, Z, 1/m): one 32-byte load per row and a transpose in registers, instead of one
 * gather per component.
 */
#include <float.h>
#include <string.h>

typedef double bs_vd __attribute__((vector_size(BS_W * 8), aligned(BS_W * 8)));
typedef long long bs_vl __attribute__((vector_size(BS_W * 8), aligned(BS_W * 8)));

#define BS_INLINE static inline __attribute__((always_inline))

BS_INLINE bs_vd bs_set1(double a) { return BS_SET1(a); }
/* m ? a : b, m all ones or all zeros per lane */
BS_INLINE bs_vd bs_sel(bs_vl m, bs_vd a, bs_vd b) { return (bs_vd)(((bs_vl)a & m) | ((bs_vl)b & ~m)); }
BS_INLINE bs_vd bs_min1(bs_vd t) { /* t < 1 ? t : 1 (NaN gives 1) */
  const bs_vd one = bs_set1(1.0);
  /* BS_MIN(a, b) = a < b ? a : b lane-wise (vminpd): the same result for every input, NaN and
   * signed zeros included, in one instruction instead of a comparison and a selection */
  return BS_MIN(t, one);
}
BS_INLINE double bs_hsum(bs_vd v) {
  double s = v[0];
  for (int l = 1; l < BS_W; ++l) s += v[l];
  return s;
}
BS_INLINE double bs_hmax(bs_vd v) {
  double s = v[0];
  for (int l = 1; l < BS_W; ++l) s = v[l] > s ? v[l] : s;
  return s;
}

/* One step's neighbour data. nv valid lanes (1..BS_W), full = (nv == BS_W) known at compile
 * time in the main loop. */
typedef struct bs_step {
  pdk_index j[BS_W] __attribute__((aligned(32)));
  bs_vd on;                 /* 1 intact, 0 broken or missing lane */
  bs_vd cx, cy, cz, cv;     /* current row */
  bs_vd rx, ry, rz, rm;     /* reference row (rm: LPS 1/m_j) */
  bs_vd r0;                 /* from bond_r0 (stored 1) or bond_r0d (stored 2) when stored */
} bs_step;

BS_INLINE void bs_load(bs_step *st, const int dim, const int has_state, const int stored,
                       const int want_ref, const int full, int nv, pdk_bond_index b,
                       const pdk_bond_arrays *a) {
  const pdk_index *restrict bj = a->bond_j;
  if (full) {
    memcpy(st->j, bj + b, sizeof st->j);
  } else {
    for (int l = 0; l < BS_W; ++l) st->j[l] = bj[b + (l < nv ? l : nv - 1)];
  }
  if (has_state || !full) {
    const uint8_t *restrict al = has_state ? a->bond_alive + b : NULL;
    double on[BS_W];
    for (int l = 0; l < BS_W; ++l)
      on[l] = full || l < nv ? (has_state ? (double)al[l] : 1.0) : 0.0;
    memcpy(&st->on, on, sizeof on);
  } else {
    st->on = bs_set1(1.0);
  }
  bs_vd c[4];
  BS_LOAD4(a->cur4, st->j, c);
  st->cx = c[0], st->cy = c[1], st->cz = c[2], st->cv = c[3];
  if (want_ref) {
    BS_LOAD4(a->ref4, st->j, c);
    st->rx = c[0], st->ry = c[1], st->rz = c[2], st->rm = c[3];
  }
  if (stored == 1) {
    if (full) {
      st->r0 = BS_CVT_F(a->bond_r0 + b);
    } else {
      float t[BS_W];
      for (int l = 0; l < BS_W; ++l) t[l] = a->bond_r0[b + (l < nv ? l : nv - 1)];
      st->r0 = BS_CVT_F(t);
    }
  } else if (stored == 2) {
    if (full) {
      memcpy(&st->r0, a->bond_r0d + b, sizeof st->r0); /* unaligned vector load */
    } else {
      double t[BS_W];
      for (int l = 0; l < BS_W; ++l) t[l] = a->bond_r0d[b + (l < nv ? l : nv - 1)];
      memcpy(&st->r0, t, sizeof t);
    }
  }
  (void)dim;
}

/* r0 and r of the step's bonds from particle i's rows (same operation order as the reference:
 * (dX*dX + dY*dY) + dZ*dZ). */
BS_INLINE void bs_lengths(const int dim, const int stored, bs_step *st, const double *ri,
                          const double *ci, bs_vd *dx, bs_vd *dy, bs_vd *dz, bs_vd *r0, bs_vd *r) {
  *dx = st->cx - bs_set1(ci[0]);
  *dy = st->cy - bs_set1(ci[1]);
  bs_vd rr = *dx * *dx + *dy * *dy;
  if (dim == 3) {
    *dz = st->cz - bs_set1(ci[2]);
    rr = rr + *dz * *dz;
  }
  *r = BS_SQRT(rr);
  if (stored) {
    *r0 = st->r0;
  } else {
    const bs_vd dX = st->rx - bs_set1(ri[0]), dY = st->ry - bs_set1(ri[1]);
    bs_vd rr0 = dX * dX + dY * dY;
    if (dim == 3) {
      const bs_vd dZ = st->rz - bs_set1(ri[2]);
      rr0 = rr0 + dZ * dZ;
    }
    *r0 = BS_SQRT(rr0);
  }
}

/* The s0 rule of a committing pass for one step (reference: kernels/ref/pmb.c). */
BS_INLINE void bs_commit(const bs_step *st, int nv, pdk_bond_index b, bs_vd d, bs_vd r, bs_vd q,
                         bs_vd r0, double s0_i, double s00, double alpha,
                         const pdk_bond_arrays *a, bs_vd *s0_max, pdk_bond_index *broken) {
  const bs_vd zero = bs_set1(0.0);
  const bs_vd s = bs_sel(r > zero, d * (r * q), bs_set1(-1.0));
  const bs_vd s0j = BS_GATHER(a->s0, st->j);
  const bs_vd s0i = bs_set1(s0_i);
  const bs_vd s0_min = bs_sel(s0j < s0i, s0j, s0i);
  const bs_vl alive = st->on != zero;
  const bs_vl brk = alive & (d > s0_min * r0);
  const bs_vd cand = bs_sel(alive, bs_set1(s00) - bs_set1(alpha) * s, bs_set1(-DBL_MAX));
  *s0_max = bs_sel(cand > *s0_max, cand, *s0_max);
  uint8_t *restrict al = a->bond_alive + b;
  for (int l = 0; l < nv; ++l) {
    *broken += brk[l] != 0;
    al[l] = (uint8_t)(alive[l] != 0 && brk[l] == 0);
  }
}

/* ---- PMB ------------------------------------------------------------------------------------ */

BS_INLINE void pmb_step(const int dim, const int has_state, const int commit, const int want_energy,
                        const int stored, const int full, int nv, pdk_bond_index b, pdk_index i,
                        const pdk_pmb_consts *k, const pdk_bond_arrays *a, const double *ri,
                        const double *ci, double s0_i, bs_vd *f0, bs_vd *f1, bs_vd *f2, bs_vd *wi,
                        bs_vd *s0_max, pdk_bond_index *broken) {
  bs_step st;
  bs_load(&st, dim, has_state, stored, !stored, full, nv, b, a);
  bs_vd dx, dy, dz, r0, r;
  bs_lengths(dim, stored, &st, ri, ci, &dx, &dy, &dz, &r0, &r);
  const bs_vd zero = bs_set1(0.0);
  const bs_vd d = r - r0;
  const bs_vd q = bs_sel(r > zero, bs_set1(1.0) / (r0 * r), zero);
  const bs_vd vol = st.cv * bs_min1((bs_set1(k->vs_a) - r0) * bs_set1(k->vs_b));
  const bs_vd g = st.on * bs_set1(k->c) * vol * d * q;
  *f0 += g * dx;
  *f1 += g * dy;
  if (dim == 3) *f2 += g * dz;
  if (want_energy) *wi += bs_set1(0.25) * g * d * r;
  if (has_state && commit)
    bs_commit(&st, nv, b, d, r, q, r0, s0_i, k->s00, k->alpha, a, s0_max, broken);
  (void)i;
}

BS_INLINE pdk_bond_index pmb_rows(const int dim, const int has_state, const int commit,
                                  const int want_energy, const int stored,
                                  const pdk_pmb_consts *k, const pdk_bond_arrays *a, pdk_index i0,
                                  pdk_index i1) {
  pdk_bond_index broken = 0;
  for (pdk_index i = i0; i < i1; ++i) {
    const double *ri = a->ref4 + 4 * (size_t)i, *ci = a->cur4 + 4 * (size_t)i;
    const double s0_i = has_state && commit ? a->s0[i] : 0.0;
    bs_vd f0 = bs_set1(0.0), f1 = f0, f2 = f0, wi = f0, s0_max = bs_set1(-DBL_MAX);
    const pdk_bond_index b0 = a->bond_start[i], b1 = a->bond_start[i + 1];
    pdk_bond_index b = b0;
    for (; b + BS_W <= b1; b += BS_W)
      pmb_step(dim, has_state, commit, want_energy, stored, 1, BS_W, b, i, k, a, ri, ci, s0_i, &f0,
               &f1, &f2, &wi, &s0_max, &broken);
    if (b < b1)
      pmb_step(dim, has_state, commit, want_energy, stored, 0, (int)(b1 - b), b, i, k, a, ri, ci,
               s0_i, &f0, &f1, &f2, &wi, &s0_max, &broken);
    a->f[0][i] = bs_hsum(f0);
    a->f[1][i] = bs_hsum(f1);
    if (dim == 3) a->f[2][i] = bs_hsum(f2);
    if (want_energy) a->w[i] = bs_hsum(wi);
    if (has_state && commit) {
      const double m = bs_hmax(s0_max);
      a->s0_next[i] = m == -DBL_MAX ? DBL_MAX : m;
    }
  }
  return broken;
}

/* ---- LPS ------------------------------------------------------------------------------------ */

BS_INLINE void lps_theta_step(const int dim, const int has_state, const int stored, const int full,
                              int nv, pdk_bond_index b, const pdk_lps_consts *k,
                              const pdk_bond_arrays *a, const double *ri, const double *ci,
                              bs_vd *sum) {
  bs_step st;
  bs_load(&st, dim, has_state, stored, !stored, full, nv, b, a);
  bs_vd dx, dy, dz, r0, r;
  bs_lengths(dim, stored, &st, ri, ci, &dx, &dy, &dz, &r0, &r);
  const bs_vd pv = st.cv * bs_min1((bs_set1(k->vs_a) - r0) * bs_set1(k->vs_b));
  *sum += st.on * (r - r0) * pv;
}

BS_INLINE void lps_theta_rows(const int dim, const int has_state, const int stored,
                              const pdk_lps_consts *k, const pdk_bond_arrays *a, pdk_index i0,
                              pdk_index i1) {
  for (pdk_index i = i0; i < i1; ++i) {
    const double *ri = a->ref4 + 4 * (size_t)i, *ci = a->cur4 + 4 * (size_t)i;
    bs_vd sum = bs_set1(0.0);
    const pdk_bond_index b0 = a->bond_start[i], b1 = a->bond_start[i + 1];
    pdk_bond_index b = b0;
    for (; b + BS_W <= b1; b += BS_W)
      lps_theta_step(dim, has_state, stored, 1, BS_W, b, k, a, ri, ci, &sum);
    if (b < b1) lps_theta_step(dim, has_state, stored, 0, (int)(b1 - b), b, k, a, ri, ci, &sum);
    a->theta_out[i] = k->theta_factor * a->inv_m[i] * bs_hsum(sum);
  }
}

BS_INLINE void lps_force_step(const int dim, const int has_state, const int commit,
                              const int want_energy, const int stored, const int full, int nv,
                              pdk_bond_index b, const pdk_lps_consts *k, const pdk_bond_arrays *a,
                              const double *ri, const double *ci, double q_i, double inv_m_i,
                              double sd_i, double s0_i, bs_vd *f0, bs_vd *f1, bs_vd *f2,
                              bs_vd *wdev, bs_vd *s0_max, pdk_bond_index *broken) {
  bs_step st;
  bs_load(&st, dim, has_state, stored, 1, full, nv, b, a);
  bs_vd dx, dy, dz, r0, r;
  bs_lengths(dim, stored, &st, ri, ci, &dx, &dy, &dz, &r0, &r);
  const bs_vd zero = bs_set1(0.0);
  const bs_vd e = r - r0;
  const bs_vd q = bs_sel(r > zero, bs_set1(1.0) / (r0 * r), zero);
  const bs_vd vol = st.on * (st.cv * bs_min1((bs_set1(k->vs_a) - r0) * bs_set1(k->vs_b)));
  const bs_vd theta_j = BS_GATHER(a->theta, st.j);
  const bs_vd inv_m_j = st.rm;
  const bs_vd g = vol *
                  (bs_set1(k->c_dil) * (bs_set1(q_i) + theta_j * inv_m_j) * r0 +
                   bs_set1(k->c_dev) * (bs_set1(inv_m_i) + inv_m_j) * e) *
                  q;
  *f0 += g * dx;
  *f1 += g * dy;
  if (dim == 3) *f2 += g * dz;
  if (want_energy) {
    const bs_vd ed = e - bs_set1(sd_i) * r0;
    *wdev += ed * ed / r0 * vol;
  }
  if (has_state && commit)
    bs_commit(&st, nv, b, e, r, q, r0, s0_i, k->s00, k->alpha, a, s0_max, broken);
}

BS_INLINE pdk_bond_index lps_force_rows(const int dim, const int has_state, const int commit,
                                        const int want_energy, const int stored,
                                        const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                        pdk_index i0, pdk_index i1) {
  pdk_bond_index broken = 0;
  const double d = k->theta_factor;
  for (pdk_index i = i0; i < i1; ++i) {
    const double *ri = a->ref4 + 4 * (size_t)i, *ci = a->cur4 + 4 * (size_t)i;
    const double theta_i = a->theta[i], inv_m_i = a->inv_m[i], q_i = theta_i * inv_m_i;
    const double sd_i = theta_i / d;
    const double s0_i = has_state && commit ? a->s0[i] : 0.0;
    bs_vd f0 = bs_set1(0.0), f1 = f0, f2 = f0, wdev = f0, s0_max = bs_set1(-DBL_MAX);
    const pdk_bond_index b0 = a->bond_start[i], b1 = a->bond_start[i + 1];
    pdk_bond_index b = b0;
    for (; b + BS_W <= b1; b += BS_W)
      lps_force_step(dim, has_state, commit, want_energy, stored, 1, BS_W, b, k, a, ri, ci, q_i,
                     inv_m_i, sd_i, s0_i, &f0, &f1, &f2, &wdev, &s0_max, &broken);
    if (b < b1)
      lps_force_step(dim, has_state, commit, want_energy, stored, 0, (int)(b1 - b), b, k, a, ri,
                     ci, q_i, inv_m_i, sd_i, s0_i, &f0, &f1, &f2, &wdev, &s0_max, &broken);
    a->f[0][i] = bs_hsum(f0);
    a->f[1][i] = bs_hsum(f1);
    if (dim == 3) a->f[2][i] = bs_hsum(f2);
    if (want_energy)
      a->w[i] = 0.5 * k->e_bulk * theta_i * theta_i + k->e_dev * inv_m_i * bs_hsum(wdev);
    if (has_state && commit) {
      const double m = bs_hmax(s0_max);
      a->s0_next[i] = m == -DBL_MAX ? DBL_MAX : m;
    }
  }
  return broken;
}

/* ---- dispatch: one specialised loop per (dim, state, commit, energy, storage) -------------- */

#define BS_DISPATCH_S(call, dim, st, cm, en)                                                       \
  (a->bond_r0 ? call(dim, st, cm, en, 1, k, a, i0, i1)                                             \
   : a->bond_r0d ? call(dim, st, cm, en, 2, k, a, i0, i1)                                          \
                 : call(dim, st, cm, en, 0, k, a, i0, i1))
#define BS_DISPATCH_E(call, dim, st, cm)                                                           \
  (a->w ? BS_DISPATCH_S(call, dim, st, cm, 1) : BS_DISPATCH_S(call, dim, st, cm, 0))
#define BS_DISPATCH(call)                                                                          \
  (a->dim == 3 ? (!a->bond_alive  ? BS_DISPATCH_E(call, 3, 0, 0)                                   \
                  : !a->s0_next   ? BS_DISPATCH_E(call, 3, 1, 0)                                   \
                                  : BS_DISPATCH_E(call, 3, 1, 1))                                  \
               : (!a->bond_alive  ? BS_DISPATCH_E(call, 2, 0, 0)                                   \
                  : !a->s0_next   ? BS_DISPATCH_E(call, 2, 1, 0)                                   \
                                  : BS_DISPATCH_E(call, 2, 1, 1)))

pdk_bond_index BS_NAME(pdk_kernel_pmb_force)(const pdk_pmb_consts *k, const pdk_bond_arrays *a,
                                             pdk_index i0, pdk_index i1) {
  return BS_DISPATCH(pmb_rows);
}

void BS_NAME(pdk_kernel_lps_dilation)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                      pdk_index i0, pdk_index i1) {
  /* energy and commit do not matter to the dilation: fold them */
#define BS_THETA_S(dim, st)                                                                        \
  (a->bond_r0 ? lps_theta_rows(dim, st, 1, k, a, i0, i1)                                           \
   : a->bond_r0d ? lps_theta_rows(dim, st, 2, k, a, i0, i1)                                        \
                 : lps_theta_rows(dim, st, 0, k, a, i0, i1))
  if (a->dim == 3) {
    if (a->bond_alive)
      BS_THETA_S(3, 1);
    else
      BS_THETA_S(3, 0);
  } else {
    if (a->bond_alive)
      BS_THETA_S(2, 1);
    else
      BS_THETA_S(2, 0);
  }
#undef BS_THETA_S
}

pdk_bond_index BS_NAME(pdk_kernel_lps_force)(const pdk_lps_consts *k, const pdk_bond_arrays *a,
                                             pdk_index i0, pdk_index i1) {
  return BS_DISPATCH(lps_force_rows);
}
