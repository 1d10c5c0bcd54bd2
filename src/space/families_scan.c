/* The candidate scan of a family build: per cell, the candidates of the neighbour cells in
 * ascending particle index, each particle's family from the family_scan kernel, and the bonds
 * pre-cracks cut (src/space/families.c, file comment steps 3 and 4; src/space/families_build.h).
 */
#include <math.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "families_build.h"
#include "pdk/ctx.h"

/* ---- the scan ------------------------------------------------------------------------------- */

void pdk_families_scan_buf_free(scan_buf *t) {
  if (!t) return;
  void *ptrs[] = {t->cx,  t->cy,   t->cz,       t->cid, t->tx,         t->ty,    t->tz,
                  t->tid, t->perm, t->perm_tmp, t->out, t->crack_list, t->side_i};
  for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; ++k)
    pdk_free_aligned(ptrs[k]);
  memset(t, 0, sizeof *t);
}

int pdk_families_scan_buf_alloc(scan_buf *t, const scan_shared *sh) {
  const size_t m = (size_t)sh->max_cand + PDK_SCAN_OUT_PAD;
  memset(t, 0, sizeof *t);
  t->cx = pdk_alloc_aligned(m, sizeof(double));
  t->cy = pdk_alloc_aligned(m, sizeof(double));
  t->cz = pdk_alloc_aligned(m, sizeof(double));
  t->tx = pdk_alloc_aligned(m, sizeof(double));
  t->ty = pdk_alloc_aligned(m, sizeof(double));
  t->tz = pdk_alloc_aligned(m, sizeof(double));
  t->cid = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->tid = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->perm = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->perm_tmp = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->out = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->crack_list = pdk_alloc_aligned((size_t)sh->num_cracks + 1, sizeof(int));
  t->side_i = pdk_alloc_aligned((size_t)sh->num_cracks + 1, sizeof(int));
  if (t->cx && t->cy && t->cz && t->tx && t->ty && t->tz && t->cid && t->tid && t->perm &&
      t->perm_tmp && t->out && t->crack_list && t->side_i)
    return 0;
  pdk_families_scan_buf_free(t);
  return 1;
}

/* Sorts the candidate buffer by particle index. It holds num_runs ascending runs starting at
 * run_start[r] (run_start[num_runs] = m); runs are merged pairwise, bottom-up, through a
 * permutation, and the coordinates gathered once at the end. Indices are unique, so the result is
 * the one ascending order. */
static void merge_runs(scan_buf *t, pdk_index m, pdk_index *run_start, int num_runs) {
  pdk_index *a = t->perm, *b = t->perm_tmp;
  for (pdk_index k = 0; k < m; ++k)
    a[k] = k;
  const pdk_index *id = t->cid;
  while (num_runs > 1) {
    int r_out = 0;
    for (int r = 0; r < num_runs; r += 2) {
      pdk_index lo = run_start[r], mid = run_start[r + 1];
      pdk_index hi = r + 2 <= num_runs ? run_start[r + 2] : mid;
      pdk_index i = lo, j = mid, k = lo;
      while (i < mid && j < hi)
        b[k++] = id[a[i]] < id[a[j]] ? a[i++] : a[j++];
      while (i < mid)
        b[k++] = a[i++];
      while (j < hi)
        b[k++] = a[j++];
      run_start[r_out++] = lo;
    }
    run_start[r_out] = m;
    num_runs = r_out;
    pdk_index *s = a;
    a = b;
    b = s;
  }
  for (pdk_index k = 0; k < m; ++k) {
    const pdk_index q = a[k];
    t->tx[k] = t->cx[q];
    t->ty[k] = t->cy[q];
    t->tz[k] = t->cz[q];
    t->tid[k] = t->cid[q];
  }
  double *d;
  d = t->cx, t->cx = t->tx, t->tx = d;
  d = t->cy, t->cy = t->ty, t->ty = d;
  d = t->cz, t->cz = t->tz, t->tz = d;
  pdk_index *p = t->cid;
  t->cid = t->tid, t->tid = p;
}

/* Fills t's candidate buffer for cell c (see the file comment, step 3) and its crack list;
 * returns the number of candidates. */
static pdk_index gather_candidates(const scan_shared *sh, int64_t c, scan_buf *t) {
  const pdk_cells *cl = sh->cl;
  const int dim = sh->dim;
  const pdk_index *cs = cl->cell_start, *slot_id = cl->slot_id;
  const double *x0 = cl->x[0], *x1 = cl->x[1], *x2 = cl->x[2];
  /* Bounding box of the cell's own particles. */
  double blo[3] = {0, 0, 0}, bhi[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a) {
    const double *x = cl->x[a];
    blo[a] = bhi[a] = x[cs[c]];
    for (pdk_index s = cs[c] + 1; s < cs[c + 1]; ++s) {
      blo[a] = x[s] < blo[a] ? x[s] : blo[a];
      bhi[a] = x[s] > bhi[a] ? x[s] : bhi[a];
    }
  }
  /* Neighbour cells, ordered by their first (smallest) particle index (insertion sort). */
  int64_t nb[27];
  pdk_index first[27];
  int num_nb = 0;
  FOR_EACH_NEIGHBOUR_CELL(cl, c, c2, {
    const pdk_index f = slot_id[cs[c2]];
    int k = num_nb++;
    while (k > 0 && first[k - 1] > f) {
      first[k] = first[k - 1];
      nb[k] = nb[k - 1];
      --k;
    }
    first[k] = f;
    nb[k] = c2;
  });
  /* Copy the candidates within reach of the box (a conservative test: the kernel decides);
   * branch-free append, two candidates per step with SSE2 (baseline x86-64). */
  pdk_index run_start[28];
  int num_runs = 0, sorted = 1;
  pdk_index m = 0;
  double *cx = t->cx, *cy = t->cy, *cz = t->cz;
  pdk_index *cid = t->cid;
  const double prune2 = sh->prune2;
  /* Distance of a point to the box per axis: max(lo - x, 0) + max(x - hi, 0) (at most one term is
   * positive), branch free. */
  const double lo0 = blo[0], lo1 = blo[1], lo2 = blo[2], hi0 = bhi[0], hi1 = bhi[1], hi2 = bhi[2];
  for (int k = 0; k < num_nb; ++k) {
    const pdk_index s0 = cs[nb[k]], s1 = cs[nb[k] + 1];
    const pdk_index m0 = m;
    if (dim == 3) {
      pdk_index s = s0;
#if defined(__SSE2__)
      /* two candidates per step; the same arithmetic as the scalar loop below */
      const __m128d vlo0 = _mm_set1_pd(lo0), vlo1 = _mm_set1_pd(lo1), vlo2 = _mm_set1_pd(lo2);
      const __m128d vhi0 = _mm_set1_pd(hi0), vhi1 = _mm_set1_pd(hi1), vhi2 = _mm_set1_pd(hi2);
      const __m128d zero = _mm_setzero_pd(), vprune2 = _mm_set1_pd(prune2);
      for (; s + 2 <= s1; s += 2) {
        const __m128d px = _mm_loadu_pd(x0 + s), py = _mm_loadu_pd(x1 + s),
                      pz = _mm_loadu_pd(x2 + s);
        const __m128d ex = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo0, px), zero),
                                      _mm_max_pd(_mm_sub_pd(px, vhi0), zero));
        const __m128d ey = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo1, py), zero),
                                      _mm_max_pd(_mm_sub_pd(py, vhi1), zero));
        const __m128d ez = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo2, pz), zero),
                                      _mm_max_pd(_mm_sub_pd(pz, vhi2), zero));
        const __m128d d2 =
            _mm_add_pd(_mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey)), _mm_mul_pd(ez, ez));
        const int keep = _mm_movemask_pd(_mm_cmple_pd(d2, vprune2));
        const pdk_index id0 = slot_id[s], id1 = slot_id[s + 1];
        _mm_storel_pd(cx + m, px); /* stores from registers: no reload after a store */
        _mm_storel_pd(cy + m, py);
        _mm_storel_pd(cz + m, pz);
        cid[m] = id0;
        m += keep & 1;
        _mm_storeh_pd(cx + m, px);
        _mm_storeh_pd(cy + m, py);
        _mm_storeh_pd(cz + m, pz);
        cid[m] = id1;
        m += keep >> 1;
      }
#endif
      for (; s < s1; ++s) {
        const double px = x0[s], py = x1[s], pz = x2[s];
        const double ex = max_d(lo0 - px, 0.0) + max_d(px - hi0, 0.0);
        const double ey = max_d(lo1 - py, 0.0) + max_d(py - hi1, 0.0);
        const double ez = max_d(lo2 - pz, 0.0) + max_d(pz - hi2, 0.0);
        cx[m] = px;
        cy[m] = py;
        cz[m] = pz;
        cid[m] = slot_id[s];
        m += (ex * ex + ey * ey) + ez * ez <= prune2;
      }
    } else {
      pdk_index s = s0;
#if defined(__SSE2__)
      const __m128d vlo0 = _mm_set1_pd(lo0), vlo1 = _mm_set1_pd(lo1);
      const __m128d vhi0 = _mm_set1_pd(hi0), vhi1 = _mm_set1_pd(hi1);
      const __m128d zero = _mm_setzero_pd(), vprune2 = _mm_set1_pd(prune2);
      for (; s + 2 <= s1; s += 2) {
        const __m128d px = _mm_loadu_pd(x0 + s), py = _mm_loadu_pd(x1 + s);
        const __m128d ex = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo0, px), zero),
                                      _mm_max_pd(_mm_sub_pd(px, vhi0), zero));
        const __m128d ey = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo1, py), zero),
                                      _mm_max_pd(_mm_sub_pd(py, vhi1), zero));
        const __m128d d2 = _mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey));
        const int keep = _mm_movemask_pd(_mm_cmple_pd(d2, vprune2));
        const pdk_index id0 = slot_id[s], id1 = slot_id[s + 1];
        _mm_storel_pd(cx + m, px);
        _mm_storel_pd(cy + m, py);
        cid[m] = id0;
        m += keep & 1;
        _mm_storeh_pd(cx + m, px);
        _mm_storeh_pd(cy + m, py);
        cid[m] = id1;
        m += keep >> 1;
      }
#endif
      for (; s < s1; ++s) {
        const double px = x0[s], py = x1[s];
        const double ex = max_d(lo0 - px, 0.0) + max_d(px - hi0, 0.0);
        const double ey = max_d(lo1 - py, 0.0) + max_d(py - hi1, 0.0);
        cx[m] = px;
        cy[m] = py;
        cid[m] = slot_id[s];
        m += ex * ex + ey * ey <= prune2;
      }
    }
    if (m > m0) {
      if (num_runs > 0 && cid[m0] < cid[m0 - 1]) sorted = 0;
      run_start[num_runs++] = m0;
    }
  }
  run_start[num_runs] = m;
  if (!sorted) merge_runs(t, m, run_start, num_runs);
  /* Cracks that may cut a bond of this cell: every such bond lies in the cell's box grown by the
   * reach (plus a margin for the rounding of the growth), so a crack whose box misses it, or whose
   * line/plane has that whole box strictly on one side, cuts none. */
  t->num_crack_list = 0;
  if (sh->num_cracks) {
    double glo[3] = {0, 0, 0}, ghi[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) {
      const double grow = sh->reach * (1.0 + 1e-6) + 1e-12 * (fabs(blo[a]) + fabs(bhi[a]));
      glo[a] = blo[a] - grow;
      ghi[a] = bhi[a] + grow;
    }
    for (int k = 0; k < sh->num_cracks; ++k) {
      const crack *cr = &sh->cracks[k];
      int near = 1;
      for (int a = 0; a < dim; ++a)
        near = near && cr->lo[a] <= ghi[a] && cr->hi[a] >= glo[a];
      if (near && !pdk_crack_box_one_side(cr, dim, glo, ghi))
        t->crack_list[t->num_crack_list++] = k;
    }
  }
  return m;
}

/* Removes from the family out[0..count-1] of particle i the bonds a listed crack cuts; returns the
 * new count. Each bond is tested with its lower-index end first, so i-j and j-i agree. */
static pdk_index cut_bonds(const scan_shared *sh, scan_buf *t, pdk_index i, pdk_index *out,
                           pdk_index count) {
  const int dim = sh->dim;
  double xi[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a)
    xi[a] = sh->X[a][i];
  /* the side of i, once per crack; exact, so the same from either end of a bond */
  for (int k = 0; k < t->num_crack_list; ++k)
    t->side_i[k] = pdk_crack_side(&sh->cracks[t->crack_list[k]], dim, xi);
  pdk_index kept = 0;
  for (pdk_index b = 0; b < count; ++b) {
    const pdk_index j = out[b];
    double xj[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a)
      xj[a] = sh->X[a][j];
    int cut = 0;
    for (int k = 0; k < t->num_crack_list && !cut; ++k) {
      const crack *cr = &sh->cracks[t->crack_list[k]];
      int touch = 1;
      for (int a = 0; a < dim; ++a)
        touch = touch && min_d(xi[a], xj[a]) <= cr->hi[a] && max_d(xi[a], xj[a]) >= cr->lo[a];
      if (!touch) continue;
      const int si = t->side_i[k], sj = pdk_crack_side(cr, dim, xj);
      if (si * sj > 0) continue;
      /* the rest of the test in floating point (3-D crossing point) from the lower index */
      if (i < j)
        cut = dim == 2 ? pdk_crack_cuts2(cr, xi, xj, si, sj) : pdk_crack_cuts3(cr, xi, xj, si, sj);
      else
        cut = dim == 2 ? pdk_crack_cuts2(cr, xj, xi, sj, si) : pdk_crack_cuts3(cr, xj, xi, sj, si);
    }
    if (!cut) out[kept++] = j;
  }
  return kept;
}

/* Scans cell c: the family of each of its particles, written to t->out then stored. With
 * bond_j == NULL (count pass) the size of each family goes to count[i]; otherwise the family goes
 * to bond_j + bond_start[i]. Returns the cell's bond count. */
int64_t pdk_families_scan_cell(const scan_shared *sh, int64_t c, scan_buf *t, pdk_index *count,
                               const pdk_bond_index *bond_start, pdk_index *bond_j) {
  const pdk_cells *cl = sh->cl;
  const pdk_index m = gather_candidates(sh, c, t);
  int64_t total = 0;
  for (pdk_index s = cl->cell_start[c]; s < cl->cell_start[c + 1]; ++s) {
    const pdk_index i = cl->slot_id[s];
    pdk_index nb;
    if (sh->dim == 3)
      nb = sh->kern.family_scan3(m, t->cx, t->cy, t->cz, cl->x[0][s], cl->x[1][s], cl->x[2][s],
                                 sh->r2max, i, t->cid, t->out);
    else
      nb = sh->kern.family_scan2(m, t->cx, t->cy, cl->x[0][s], cl->x[1][s], sh->r2max, i, t->cid,
                                 t->out);
    if (t->num_crack_list) nb = cut_bonds(sh, t, i, t->out, nb);
    if (bond_j)
      memcpy(bond_j + bond_start[i], t->out, (size_t)nb * sizeof *bond_j);
    else
      count[i] = nb;
    total += nb;
  }
  return total;
}
