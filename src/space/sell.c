/* The sliced family layout (SELL-C-sigma) of the PMB force pass: build, bond-state sync, padding
 * (data structure and rules in src/space/sell.h, kernels in kernels/ref/bond_sell.c and
 * kernels/opt/sell_simd.h). */
#include <string.h>

#include "sell.h"
#include "pdk/ctx.h"
#include "pdk/families.h"

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

void pdk_sell_free(pdk_sell *s) {
  if (!s) return;
  pdk_free_aligned(s->row_i);
  pdk_free_aligned(s->slice_start);
  pdk_free_aligned(s->sj);
  pdk_free_aligned(s->alive);
  pdk_free_aligned(s->r0);
  memset(s, 0, sizeof *s);
}

double pdk_sell_padding_fraction(const pdk_sell *s) {
  return s->num_entries > 0 ? (double)(s->num_entries - s->num_bonds) / (double)s->num_entries
                            : 0.0;
}

/* Copies per-bond data of the CSR order into the layout's order: elements of `size` bytes, 1 or
 * 4. Padding entries keep 0 (the arrays are zeroed at allocation and padding never changes). */
static void sell_scatter(pdk_ctx *ctx, const pdk_sell *s, const pdk_families *fam, void *dst,
                         const void *src, int size) {
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const int C = s->a.width;
  const int64_t ns = s->num_slices;
  const pdk_index n = s->a.n;
  const pdk_index *rows = s->row_i;
  const int64_t *ss = s->slice_start;
#pragma omp parallel for default(none) shared(bs, C, ns, n, rows, ss, dst, src, size)              \
    schedule(static) num_threads(ctx->num_threads)
  for (int64_t sl = 0; sl < ns; ++sl)
    for (int l = 0; l < C && sl * C + l < n; ++l) {
      const pdk_index i = rows[sl * C + l];
      const pdk_bond_index len = bs[i + 1] - bs[i];
      if (size == 1)
        for (pdk_bond_index col = 0; col < len; ++col)
          ((uint8_t *)dst)[ss[sl] + col * C + l] = ((const uint8_t *)src)[bs[i] + col];
      else
        for (pdk_bond_index col = 0; col < len; ++col)
          ((float *)dst)[ss[sl] + col * C + l] = ((const float *)src)[bs[i] + col];
    }
}

void pdk_sell_sync_alive(pdk_ctx *ctx, pdk_sell *s, const pdk_families *fam,
                         const uint8_t *csr_alive) {
  if (!s->alive || !csr_alive) return;
  sell_scatter(ctx, s, fam, s->alive, csr_alive, 1);
}

int pdk_sell_build(pdk_ctx *ctx, const pdk_families *fam, int width, int sigma,
                   const uint8_t *csr_alive, const float *csr_r0, pdk_sell *out) {
  int err = PDK_SUCCESS;
  memset(out, 0, sizeof *out);
  PDK_CHECK(width >= 1 && width <= 16, ctx, PDK_ERR_ARG,
            "sliced layout: width %d out of range 1..16", width);
  if (sigma <= 0) sigma = PDK_SELL_SIGMA_SLICES * width;
  sigma = (sigma + width - 1) / width * width;
  const int C = width;
  const pdk_index n = pdk_families_num_particles(fam);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const int64_t num_slices = ((int64_t)n + C - 1) / C;
  const int64_t num_windows = ((int64_t)n + sigma - 1) / sigma;
  out->a.width = C;
  out->a.n = n;
  out->sigma = sigma;
  out->num_slices = num_slices;
  out->num_bonds = pdk_families_num_bonds(fam);
  out->row_i = pdk_alloc_aligned((size_t)(num_slices > 0 ? num_slices * C : 1), sizeof(pdk_index));
  out->slice_start = pdk_alloc_aligned((size_t)num_slices + 1, sizeof(int64_t));
  PDK_CHECK_GOTO(out->row_i && out->slice_start, ctx, PDK_ERR_MEMORY,
                 "sliced layout: out of memory for the rows of %lld particles", (long long)n);
  pdk_index *row_i = out->row_i;
  int64_t *slice_start = out->slice_start;

  /* Rows: windows of sigma rows sorted by descending length, ties by index (a deterministic
   * order whatever the thread count). Key = (max length - length) << 32 | i. */
  int bad = 0;
#pragma omp parallel default(none) shared(n, bs, sigma, num_windows, row_i, bad)                   \
    num_threads(ctx->num_threads)
  {
    uint64_t *key = malloc((size_t)sigma * sizeof *key);
    if (!key) {
#pragma omp atomic write
      bad = 1;
    }
#pragma omp for schedule(static)
    for (int64_t w = 0; w < num_windows; ++w) {
      if (!key) continue;
      const pdk_index r0 = (pdk_index)(w * sigma);
      const pdk_index r1 = (pdk_index)((int64_t)r0 + sigma < (int64_t)n ? r0 + sigma : n);
      for (pdk_index i = r0; i < r1; ++i) {
        const uint64_t len = (uint64_t)(bs[i + 1] - bs[i]);
        key[i - r0] = ((UINT64_C(0xffffffff) - (len < 0xffffffffu ? len : 0xffffffffu)) << 32) |
                      (uint64_t)(uint32_t)i;
      }
      qsort(key, (size_t)(r1 - r0), sizeof *key, cmp_u64);
      for (pdk_index r = r0; r < r1; ++r)
        row_i[r] = (pdk_index)(key[r - r0] & 0xffffffffu);
    }
    free(key);
  }
  PDK_CHECK_GOTO(!bad, ctx, PDK_ERR_MEMORY, "sliced layout: out of memory sorting the rows");
  /* Padding rows: the slice's first particle (its data is read, its results are discarded). */
  for (int64_t r = n; r < num_slices * C; ++r)
    row_i[r] = row_i[(r / C) * C];

  /* Slice lengths, then offsets (serial prefix sum). */
  for (int64_t sl = 0; sl < num_slices; ++sl) {
    pdk_bond_index len = 0;
    for (int l = 0; l < C && sl * C + l < n; ++l) {
      const pdk_index i = row_i[sl * C + l];
      if (bs[i + 1] - bs[i] > len) len = bs[i + 1] - bs[i];
    }
    slice_start[sl + 1] = slice_start[sl] + len * C;
  }
  const int64_t ne = slice_start[num_slices];
  out->num_entries = ne;
  const size_t per_entry = sizeof(pdk_index) + (csr_alive ? 1 : 0) + (csr_r0 ? sizeof(float) : 0);
  out->sj = pdk_alloc_aligned((size_t)(ne > 0 ? ne : 1), sizeof(pdk_index));
  if (csr_alive) out->alive = pdk_alloc_aligned((size_t)(ne > 0 ? ne : 1), 1);
  if (csr_r0) out->r0 = pdk_alloc_aligned((size_t)(ne > 0 ? ne : 1), sizeof(float));
  PDK_CHECK_GOTO(out->sj && (!csr_alive || out->alive) && (!csr_r0 || out->r0), ctx, PDK_ERR_MEMORY,
                 "sliced layout: out of memory for %lld entries (%lld bytes); use layout csr",
                 (long long)ne, (long long)(ne * (int64_t)per_entry));
  pdk_index *sj = out->sj;
  /* Neighbours; padding points at the row's own particle (first touch with the kernels'
   * schedule over slices). */
#pragma omp parallel for default(none) shared(num_slices, C, n, row_i, slice_start, bs, bj, sj)    \
    schedule(static) num_threads(ctx->num_threads)
  for (int64_t sl = 0; sl < num_slices; ++sl)
    for (int l = 0; l < C; ++l) {
      const pdk_index i = row_i[sl * C + l];
      const pdk_bond_index len = sl * C + l < n ? bs[i + 1] - bs[i] : 0;
      const int64_t cols = (slice_start[sl + 1] - slice_start[sl]) / C;
      for (int64_t col = 0; col < cols; ++col)
        sj[slice_start[sl] + col * C + l] = col < len ? bj[bs[i] + col] : i;
    }
  if (csr_alive) pdk_sell_sync_alive(ctx, out, fam, csr_alive);
  if (csr_r0) sell_scatter(ctx, out, fam, out->r0, csr_r0, 4);
  out->a.row_i = out->row_i;
  out->a.slice_start = out->slice_start;
  out->a.sj = out->sj;
  out->a.alive = out->alive;
  out->a.r0 = out->r0;
  return PDK_SUCCESS;
cleanup:
  pdk_sell_free(out);
  return err;
}
