/* Particle store: SoA arrays in a field registry; see include/pdk/particles.h.
 *
 * fields: [num_fields] in declaration order; field k has num_comp arrays data[0..num_comp-1],
 * each of n_pad entries of its type, 64-byte aligned, padding entries zero.
 */
#include <math.h>
#include <string.h>

#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

#define PDK_MAX_COMP 9

typedef struct pdk_field {
  char name[PDK_FIELD_NAME_MAX];
  pdk_type type;
  int num_comp;
  void *data[PDK_MAX_COMP];
} pdk_field;

struct pdk_particles {
  pdk_ctx *ctx;
  int dim;
  pdk_index n, n_pad;
  int num_fields, cap_fields;
  pdk_field *fields;
};

size_t pdk_type_size(pdk_type type) {
  switch (type) {
  case PDK_F64: return 8;
  case PDK_F32: return 4;
  case PDK_I64: return 8;
  case PDK_I32: return 4;
  case PDK_U8: return 1;
  }
  return 0;
}

static const char *type_name(pdk_type t) {
  static const char *names[] = {"f64", "f32", "i64", "i32", "u8"};
  return (unsigned)t < 5 ? names[t] : "?";
}

static pdk_field *find_field(const pdk_particles *p, const char *name) {
  if (!p || !name) return NULL;
  for (int k = 0; k < p->num_fields; ++k)
    if (!strcmp(p->fields[k].name, name)) return &p->fields[k];
  return NULL;
}

static void free_field(pdk_field *f) {
  for (int c = 0; c < f->num_comp; ++c) pdk_free_aligned(f->data[c]);
  memset(f, 0, sizeof *f);
}

int pdk_particles_create(pdk_ctx *ctx, int dim, pdk_index n, pdk_particles **out) {
  int err = PDK_SUCCESS;
  pdk_particles *p = NULL;
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(dim == 2 || dim == 3, ctx, PDK_ERR_ARG, "dimension must be 2 or 3, got %d", dim);
  PDK_CHECK(n >= 1, ctx, PDK_ERR_ARG,
            "a particle store needs at least one particle, got %d (did a region or hole remove "
            "every particle?)", (int)n);
  PDK_CHECK(n <= INT32_MAX - PDK_PAD, ctx, PDK_ERR_ARG,
            "%d particles exceed the 32-bit particle index limit", (int)n);
  p = calloc(1, sizeof *p);
  PDK_CHECK(p, ctx, PDK_ERR_MEMORY, "out of memory creating a particle store");
  p->ctx = ctx;
  p->dim = dim;
  p->n = n;
  p->n_pad = pdk_pad_count(n);
  PDK_CALL_GOTO(pdk_particles_field_add(p, "id", PDK_I64, 1));
  PDK_CALL_GOTO(pdk_particles_field_add(p, "X", PDK_F64, dim));
  PDK_CALL_GOTO(pdk_particles_field_add(p, "volume", PDK_F64, 1));
  int64_t *id = pdk_particles_id(p);
  for (pdk_index i = 0; i < n; ++i) id[i] = i;
  *out = p;
  return PDK_SUCCESS;
cleanup:
  pdk_particles_destroy(&p);
  return err;
}

void pdk_particles_destroy(pdk_particles **pp) {
  if (!pp || !*pp) return;
  pdk_particles *p = *pp;
  for (int k = 0; k < p->num_fields; ++k) free_field(&p->fields[k]);
  free(p->fields);
  free(p);
  *pp = NULL;
}

int pdk_particles_dim(const pdk_particles *p) { return p ? p->dim : 0; }
pdk_index pdk_particles_count(const pdk_particles *p) { return p ? p->n : 0; }
pdk_index pdk_particles_count_padded(const pdk_particles *p) { return p ? p->n_pad : 0; }
pdk_ctx *pdk_particles_ctx(const pdk_particles *p) { return p ? p->ctx : NULL; }

int pdk_particles_field_add(pdk_particles *p, const char *name, pdk_type type, int num_comp) {
  PDK_CHECK_ARG(p, NULL);
  pdk_ctx *ctx = p->ctx;
  PDK_CHECK(name && name[0] && strlen(name) < PDK_FIELD_NAME_MAX, ctx, PDK_ERR_ARG,
            "field name must be 1 to %d characters", PDK_FIELD_NAME_MAX - 1);
  PDK_CHECK(num_comp >= 1 && num_comp <= PDK_MAX_COMP, ctx, PDK_ERR_ARG,
            "field '%s': %d components; allowed 1 to %d", name, num_comp, PDK_MAX_COMP);
  PDK_CHECK(pdk_type_size(type) > 0, ctx, PDK_ERR_ARG, "field '%s': unknown type %d", name, (int)type);
  pdk_field *f = find_field(p, name);
  if (f) {
    PDK_CHECK(f->type == type && f->num_comp == num_comp, ctx, PDK_ERR_ARG,
              "field '%s' exists as %s x %d; cannot redeclare it as %s x %d", name,
              type_name(f->type), f->num_comp, type_name(type), num_comp);
    return PDK_SUCCESS;
  }
  if (p->num_fields == p->cap_fields) {
    int cap = p->cap_fields ? 2 * p->cap_fields : 8;
    pdk_field *nf = realloc(p->fields, (size_t)cap * sizeof *nf);
    PDK_CHECK(nf, ctx, PDK_ERR_MEMORY, "out of memory growing the field registry");
    p->fields = nf;
    p->cap_fields = cap;
  }
  pdk_field nfld;
  memset(&nfld, 0, sizeof nfld);
  strcpy(nfld.name, name);
  nfld.type = type;
  nfld.num_comp = num_comp;
  for (int c = 0; c < num_comp; ++c) {
    nfld.data[c] = pdk_alloc_aligned((size_t)p->n_pad, pdk_type_size(type));
    if (!nfld.data[c]) {
      free_field(&nfld);
      return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__,
                               "out of memory allocating field '%s' (%d x %d entries of %zu bytes)",
                               name, num_comp, (int)p->n_pad, pdk_type_size(type));
    }
  }
  p->fields[p->num_fields++] = nfld;
  return PDK_SUCCESS;
}

int pdk_particles_field_remove(pdk_particles *p, const char *name) {
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(name, p->ctx);
  pdk_field *f = find_field(p, name);
  PDK_CHECK(f, p->ctx, PDK_ERR_NOT_FOUND, "no field '%s' to remove", name);
  PDK_CHECK(strcmp(name, "id") && strcmp(name, "X") && strcmp(name, "volume"), p->ctx, PDK_ERR_ARG,
            "field '%s' is built in and cannot be removed", name);
  int k = (int)(f - p->fields);
  free_field(f);
  memmove(&p->fields[k], &p->fields[k + 1], (size_t)(p->num_fields - k - 1) * sizeof *f);
  p->num_fields--;
  return PDK_SUCCESS;
}

int pdk_particles_field_exists(const pdk_particles *p, const char *name) {
  return find_field(p, name) != NULL;
}

void *pdk_particles_field_data(pdk_particles *p, const char *name, int comp) {
  pdk_field *f = find_field(p, name);
  if (!f || comp < 0 || comp >= f->num_comp) return NULL;
  return f->data[comp];
}

int pdk_particles_field_get(pdk_particles *p, const char *name, int comp, void **out) {
  pdk_field *f = find_field(p, name);
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(out, p->ctx);
  *out = NULL;
  PDK_CHECK_ARG(name, p->ctx);
  PDK_CHECK(f, p->ctx, PDK_ERR_NOT_FOUND,
            "field '%s' does not exist: no model or solver of this run declared it", name);
  PDK_CHECK(comp >= 0 && comp < f->num_comp, p->ctx, PDK_ERR_ARG,
            "field '%s' has %d components; component %d does not exist", name, f->num_comp, comp);
  *out = f->data[comp];
  return PDK_SUCCESS;
}

int pdk_particles_field_info(const pdk_particles *p, const char *name, pdk_type *type, int *num_comp) {
  pdk_field *f = find_field(p, name);
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(name, p->ctx);
  PDK_CHECK(f, p->ctx, PDK_ERR_NOT_FOUND, "field '%s' does not exist", name);
  if (type) *type = f->type;
  if (num_comp) *num_comp = f->num_comp;
  return PDK_SUCCESS;
}

int pdk_particles_num_fields(const pdk_particles *p) { return p ? p->num_fields : 0; }
const char *pdk_particles_field_name(const pdk_particles *p, int k) {
  return p && k >= 0 && k < p->num_fields ? p->fields[k].name : NULL;
}

size_t pdk_particles_field_bytes(const pdk_particles *p, const char *name) {
  pdk_field *f = find_field(p, name);
  return f ? (size_t)f->num_comp * (size_t)p->n_pad * pdk_type_size(f->type) : 0;
}

size_t pdk_particles_memory_bytes(const pdk_particles *p) {
  size_t total = 0;
  if (!p) return 0;
  for (int k = 0; k < p->num_fields; ++k) total += pdk_particles_field_bytes(p, p->fields[k].name);
  return total;
}

void pdk_particles_print_memory(const pdk_particles *p, FILE *out) {
  if (!p || !out) return;
  fprintf(out, "particle fields (%d particles, %d padded):\n", (int)p->n, (int)p->n_pad);
  for (int k = 0; k < p->num_fields; ++k) {
    const pdk_field *f = &p->fields[k];
    fprintf(out, "  %-24s %-3s x %d  %12zu bytes\n", f->name, type_name(f->type), f->num_comp,
            pdk_particles_field_bytes(p, f->name));
  }
  fprintf(out, "  %-24s          %12zu bytes\n", "total", pdk_particles_memory_bytes(p));
}

double *pdk_particles_X(pdk_particles *p, int comp) { return pdk_particles_field_data(p, "X", comp); }
double *pdk_particles_volume(pdk_particles *p) { return pdk_particles_field_data(p, "volume", 0); }
int64_t *pdk_particles_id(pdk_particles *p) { return pdk_particles_field_data(p, "id", 0); }

int pdk_particles_check_finite(pdk_particles *p) {
  PDK_CHECK_ARG(p, NULL);
  int64_t *id = pdk_particles_id(p);
  for (int c = 0; c < p->dim; ++c) {
    const double *x = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < p->n; ++i)
      PDK_CHECK(isfinite(x[i]), p->ctx, PDK_ERR_NUMERIC,
                "particle %d (id %lld) has a non-finite coordinate X[%d] = %g; every position must "
                "be a finite number", (int)i, (long long)id[i], c, x[i]);
  }
  return PDK_SUCCESS;
}

/* Gathers every array through `src_index` into arrays of new_n (padded new_pad) entries. */
static int regather(pdk_particles *p, const pdk_index *src_index, pdk_index new_n) {
  pdk_index new_pad = pdk_pad_count(new_n);
  int nthreads = p->ctx->num_threads;
  for (int k = 0; k < p->num_fields; ++k) {
    pdk_field *f = &p->fields[k];
    size_t es = pdk_type_size(f->type);
    for (int c = 0; c < f->num_comp; ++c) {
      char *dst = pdk_alloc_aligned((size_t)new_pad, es);
      PDK_CHECK(dst, p->ctx, PDK_ERR_MEMORY, "out of memory reordering field '%s'", f->name);
      const char *src = f->data[c];
#pragma omp parallel for default(none) shared(dst, src, src_index, new_n, es) schedule(static) num_threads(nthreads)
      for (pdk_index i = 0; i < new_n; ++i) memcpy(dst + (size_t)i * es, src + (size_t)src_index[i] * es, es);
      pdk_free_aligned(f->data[c]);
      f->data[c] = dst;
    }
  }
  p->n = new_n;
  p->n_pad = new_pad;
  return PDK_SUCCESS;
}

int pdk_particles_permute(pdk_particles *p, const pdk_index *perm) {
  int err = PDK_SUCCESS;
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(perm, p->ctx);
  uint8_t *seen = calloc((size_t)p->n, 1);
  PDK_CHECK(seen, p->ctx, PDK_ERR_MEMORY, "out of memory checking a permutation");
  for (pdk_index k = 0; k < p->n; ++k) {
    PDK_CHECK_GOTO(perm[k] >= 0 && perm[k] < p->n && !seen[perm[k]], p->ctx, PDK_ERR_ARG,
                   "perm[%d] = %d: not a permutation of 0..%d", (int)k, (int)perm[k], (int)p->n - 1);
    seen[perm[k]] = 1;
  }
  PDK_CALL_GOTO(regather(p, perm, p->n));
cleanup:
  free(seen);
  return err;
}

int pdk_particles_compact(pdk_particles *p, const uint8_t *keep) {
  int err = PDK_SUCCESS;
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(keep, p->ctx);
  pdk_index m = 0;
  for (pdk_index i = 0; i < p->n; ++i) m += keep[i] != 0;
  PDK_CHECK(m > 0, p->ctx, PDK_ERR_ARG,
            "removing particles would leave none of %d (a hole or cut covers the whole body)", (int)p->n);
  pdk_index *src = malloc((size_t)m * sizeof *src);
  PDK_CHECK(src, p->ctx, PDK_ERR_MEMORY, "out of memory compacting particles");
  m = 0;
  for (pdk_index i = 0; i < p->n; ++i)
    if (keep[i]) src[m++] = i;
  PDK_CALL_GOTO(regather(p, src, m));
cleanup:
  free(src);
  return err;
}

static uint64_t spread2(uint64_t v) { /* 32 bits -> every other bit of 64 */
  v &= 0xffffffffull;
  v = (v | (v << 16)) & 0x0000ffff0000ffffull;
  v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
  v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
  v = (v | (v << 2)) & 0x3333333333333333ull;
  v = (v | (v << 1)) & 0x5555555555555555ull;
  return v;
}

static uint64_t spread3(uint64_t v) { /* 21 bits -> every third bit of 63 */
  v &= 0x1fffffull;
  v = (v | (v << 32)) & 0x001f00000000ffffull;
  v = (v | (v << 16)) & 0x001f0000ff0000ffull;
  v = (v | (v << 8)) & 0x100f00f00f00f00full;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ull;
  v = (v | (v << 2)) & 0x1249249249249249ull;
  return v;
}

uint64_t pdk_morton2(uint32_t cx, uint32_t cy) { return spread2(cx) | (spread2(cy) << 1); }
uint64_t pdk_morton3(uint32_t cx, uint32_t cy, uint32_t cz) {
  return spread3(cx) | (spread3(cy) << 1) | (spread3(cz) << 2);
}

/* Stable LSD radix sort of the particles by key[0..n) (8 bits per pass; a pass whose byte is 0 in
 * every key is skipped), then every field regathered. key is overwritten; the caller frees it.
 * perm_out (n entries, new -> old) when not NULL. */
static int reorder_by_key(pdk_particles *p, uint64_t *key, pdk_index *perm_out) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = p->ctx;
  const pdk_index n = p->n;
  uint64_t *const key_buf = malloc((size_t)n * sizeof *key_buf);
  pdk_index *const perm_buf = malloc((size_t)n * sizeof *perm_buf);
  pdk_index *const perm_buf2 = malloc((size_t)n * sizeof *perm_buf2);
  PDK_CHECK_GOTO(key_buf && perm_buf && perm_buf2, ctx, PDK_ERR_MEMORY,
                 "out of memory sorting %d particles", (int)n);
  uint64_t *k_cur = key, *k_tmp = key_buf;
  pdk_index *perm = perm_buf, *perm_tmp = perm_buf2;
  for (pdk_index i = 0; i < n; ++i)
    perm[i] = i;
  for (int shift = 0; shift < 64; shift += 8) {
    size_t count[257] = {0};
    int any = 0;
    for (pdk_index i = 0; i < n; ++i) {
      unsigned b = (unsigned)(k_cur[i] >> shift) & 0xffu;
      count[b + 1]++;
      any |= b != 0;
    }
    if (!any) continue;
    for (int b = 0; b < 256; ++b) count[b + 1] += count[b];
    for (pdk_index i = 0; i < n; ++i) {
      unsigned b = (unsigned)(k_cur[i] >> shift) & 0xffu;
      size_t dst = count[b]++;
      k_tmp[dst] = k_cur[i];
      perm_tmp[dst] = perm[i];
    }
    uint64_t *tk = k_cur;
    k_cur = k_tmp;
    k_tmp = tk;
    pdk_index *tp = perm;
    perm = perm_tmp;
    perm_tmp = tp;
  }
  PDK_CALL_GOTO(regather(p, perm, n));
  if (perm_out) memcpy(perm_out, perm, (size_t)n * sizeof *perm);
cleanup:
  free(key_buf);
  free(perm_buf);
  free(perm_buf2);
  return err;
}

/* The common start of a reordering by lattice cells of size `unit`: checks unit (`unit_name`
 * names it in the message) and the reference positions, gives the low corner lo of their bounding
 * box, and allocates the n sort keys (*key; the caller frees it). Error when the body spans
 * `max_units` or more units along an axis (`what` and `key_name` word the message). */
static int sort_setup(pdk_particles *p, double unit, const char *unit_name, double max_units,
                      const char *what, const char *key_name, double lo[3], uint64_t **key) {
  PDK_CHECK(isfinite(unit) && unit > 0, p->ctx, PDK_ERR_ARG,
            "%s must be a positive finite length, got %g", unit_name, unit);
  PDK_CALL(pdk_particles_check_finite(p));
  for (int c = 0; c < 3; ++c)
    lo[c] = 0.0;
  for (int c = 0; c < p->dim; ++c) {
    const double *x = pdk_particles_X(p, c);
    double mn = x[0], mx = x[0];
    for (pdk_index i = 1; i < p->n; ++i) {
      mn = x[i] < mn ? x[i] : mn;
      mx = x[i] > mx ? x[i] : mx;
    }
    lo[c] = mn;
    PDK_CHECK((mx - mn) / unit < max_units, p->ctx, PDK_ERR_ARG,
              "the body spans %g %s %g along axis %d; at most %.0f fit a %s key", (mx - mn) / unit,
              what, unit, c, max_units, key_name);
  }
  *key = malloc((size_t)p->n * sizeof **key);
  PDK_CHECK(*key, p->ctx, PDK_ERR_MEMORY, "out of memory sorting %d particles", (int)p->n);
  return PDK_SUCCESS;
}

int pdk_particles_reorder_morton(pdk_particles *p, double cell_edge, pdk_index *perm_out) {
  PDK_CHECK_ARG(p, NULL);
  const int dim = p->dim;
  const pdk_index n = p->n;
  double lo[3];
  uint64_t *key = NULL;
  PDK_CALL(sort_setup(p, cell_edge, "Morton cell edge", dim == 2 ? 4294967295.0 : 2097151.0,
                      "cells of edge", "Morton", lo, &key));
  const int nthreads = p->ctx->num_threads;
  const double *x0 = pdk_particles_X(p, 0), *x1 = pdk_particles_X(p, 1);
  const double *x2 = dim == 3 ? pdk_particles_X(p, 2) : NULL;
#pragma omp parallel for default(none) shared(key, x0, x1, x2, lo, n, dim, cell_edge)              \
    schedule(static) num_threads(nthreads)
  for (pdk_index i = 0; i < n; ++i) {
    /* cell = floor((x - lo) / edge), by division so the rule is exact as documented */
    uint32_t cx = (uint32_t)((x0[i] - lo[0]) / cell_edge);
    uint32_t cy = (uint32_t)((x1[i] - lo[1]) / cell_edge);
    key[i] = dim == 2 ? pdk_morton2(cx, cy)
                      : pdk_morton3(cx, cy, (uint32_t)((x2[i] - lo[2]) / cell_edge));
  }
  const int err = reorder_by_key(p, key, perm_out);
  free(key);
  return err;
}

int pdk_particles_reorder_rows(pdk_particles *p, double spacing, pdk_index *perm_out) {
  PDK_CHECK_ARG(p, NULL);
  const int dim = p->dim;
  const pdk_index n = p->n;
  double lo[3];
  uint64_t *key = NULL;
  PDK_CALL(sort_setup(p, spacing, "row order: the lattice spacing",
                      dim == 2 ? 4294967294.0 : 2097150.0, "lattice spacings of", "row", lo, &key));
  const int nthreads = p->ctx->num_threads;
  const double *x[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                        dim == 3 ? pdk_particles_X(p, 2) : NULL};
  /* index = nearest lattice point (x - lo) / spacing; key = (k, j, i) in 21 (2-D: 32) bits each */
  const int bits = dim == 2 ? 32 : 21;
#pragma omp parallel for default(none) shared(key, x, lo, n, dim, spacing, bits) schedule(static)  \
    num_threads(nthreads)
  for (pdk_index i = 0; i < n; ++i) {
    uint64_t k = 0;
    for (int c = dim - 1; c >= 0; --c)
      k = (k << bits) | (uint64_t)llround((x[c][i] - lo[c]) / spacing);
    key[i] = k;
  }
  const int err = reorder_by_key(p, key, perm_out);
  free(key);
  return err;
}
