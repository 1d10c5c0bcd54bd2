/* The stencil layout of a particle set on a regular lattice, and the PMB, LPS and correspondence
 * passes over it (correspondence: model_stencil_corr.c).
 *
 * Detection (pdk_stencil_create). The spacing h is the shortest bond of the families; the origin
 * is the smallest reference coordinate per axis. Every particle must sit within 1e-6 h of a lattice
 * point origin + k h (k integer per axis), no two on the same point, and every bond of every family
 * must join two lattice points (so the lattice is simple cubic or square and aligned with the
 * axes). The offset list is the union of the families' bond offsets (on a lattice, the family of
 * an interior particle), sorted by site offset. The grid is the lattice's bounding box padded by
 * the largest offset component P on every side, so a neighbour site is always inside it; it is
 * refused when it would hold more than 8 n + 2^20 sites (a sparse set).
 *
 * Bond state. Without a mask every offset's site is a bond of the particle when it is occupied
 * (empty sites have volume 0 and add zeros): that holds when each family has exactly the occupied
 * stencil sites and no bond can break. Otherwise mask[o][s] = 1 exactly for the bonds of the
 * families (pre-cracks, bonds dropped at the horizon by round-off) that are intact in
 * m->bond_alive. A committing pass breaks bonds in the mask and marks their sites; then the
 * particles of those sites copy the new state to m->bond_alive (the model's bond list stays the
 * one truth: checkpoints, counts and other passes read it). When something else rewrote
 * m->bond_alive (m->bond_state_version changed: checkpoint restore) the mask is reloaded.
 *
 * Float storage: every bond of one offset must store the same float length (the general path's
 * bond_r0); that value and its partial-volume factor become per-offset constants.
 *
 * Pass (pdk_stencil_pmb_force), one parallel region: copy "x" (and s0) of every particle to its
 * site; barrier; rows in a static schedule through the kernel table's pmb_stencil; barrier; in a
 * committing pass, the bond-state copy. Each particle's sums run in offset order whatever the
 * thread partition, so results are bitwise the same for any thread count.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model_stencil_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

void pdk_stencil_destroy(pdk_stencil **stp) {
  if (!stp || !*stp) return;
  pdk_stencil *st = *stp;
  free(st->offset);
  free(st->row_lo);
  free(st->row_hi);
  pdk_free_aligned(st->site_particle);
  pdk_free_aligned(st->particle_site);
  free(st->lut);
  for (int a = 0; a < 3; ++a) {
    pdk_free_aligned(st->X[a]);
    if (!st->cblk) pdk_free_aligned(st->x[a]);
  }
  if (!st->cblk) pdk_free_aligned(st->volume);
  pdk_free_aligned(st->s0);
  free(st->r0_off);
  free(st->beta_off);
  pdk_free_aligned(st->mask);
  pdk_free_aligned(st->changed);
  pdk_free_aligned(st->inv_m);
  pdk_free_aligned(st->theta);
  for (int a = 0; a < 3; ++a) {
    free(st->xi_off[a]);
    free(st->wxi_off[a]);
    pdk_free_aligned(st->cs[a]);
  }
  free(st->omega_off);
  pdk_free_aligned(st->cblk); /* x, volume, cB, ck point into it */
  pdk_free_aligned(st->cBfblk);
  free(st);
  *stp = NULL;
}

int pdk_stencil_model_setup(pdk_model *m, const float *bond_r0, int multi_material) {
  const pdk_model_opts *o = &m->opts;
  m->stencil_why[0] = '\0';
  if (o->stencil == PDK_STENCIL_OFF) return PDK_SUCCESS;
  if (m->row_start) { /* several ranks: on is refused (model_ranks.c), auto takes the general path */
    snprintf(m->stencil_why, sizeof m->stencil_why,
             "several MPI ranks (the stencil path runs on one rank so far)");
    return PDK_SUCCESS;
  }
  if (multi_material)
    snprintf(m->stencil_why, sizeof m->stencil_why,
             "several materials (the stencil path takes one modulus)");
  else
    PDK_CALL(pdk_stencil_create(m, bond_r0, &m->stencil, m->stencil_why, sizeof m->stencil_why));
  PDK_CHECK(m->stencil || o->stencil != PDK_STENCIL_ON, m->ctx, PDK_ERR_UNSUPPORTED,
            "%s model: stencil on, but the stencil path does not apply: %s; use stencil auto (the "
            "general path then) or off",
            m->info->name, m->stencil_why);
  return PDK_SUCCESS;
}

int pdk_stencil_lps_setup(pdk_model *m, pdk_stencil *st, const double *inv_m) {
  const size_t ns_all = (size_t)(st->num_sites + PDK_STENCIL_SLACK);
  st->inv_m = pdk_alloc_aligned(ns_all, sizeof(double));
  st->theta = pdk_alloc_aligned(ns_all, sizeof(double));
  PDK_CHECK(st->inv_m && st->theta, m->ctx, PDK_ERR_MEMORY,
            "stencil: out of memory for a grid of %lld sites", (long long)st->num_sites);
  for (pdk_index i = 0; i < st->n; ++i)
    st->inv_m[st->particle_site[i]] = inv_m[i];
  return PDK_SUCCESS;
}

static int cmp_i64(const void *a, const void *b) {
  const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

/* Correspondence: cs of particle i's site, sum over the offsets whose bond is present (mask, or
 * an occupied site without one) of omega V_j xi. */
void pdk_stencil_corr_s(pdk_stencil *st, pdk_index i) {
  const int64_t si = st->particle_site[i], ns = st->num_sites;
  double acc[3] = {0, 0, 0};
  for (int o = 0; o < st->num_offsets; ++o) {
    const int64_t sj = si + st->offset[o];
    const double on = st->mask ? (double)st->mask[(int64_t)o * ns + si] : 1.0;
    for (int a = 0; a < st->dim; ++a)
      acc[a] += on * st->volume[sj] * st->wxi_off[a][o];
  }
  for (int a = 0; a < st->dim; ++a)
    st->cs[a][si] = acc[a];
}

/* mask[o][s] = bond present in the family and intact; the whole mask from m's families. */
void pdk_stencil_load_mask(pdk_model *m, pdk_stencil *st) {
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const uint8_t *alive = m->bond_alive;
  const pdk_index n = st->n;
  const int64_t ns = st->num_sites;
  memset(st->mask, 0, (size_t)ns * (size_t)st->num_offsets);
  const pdk_stencil *cst = st;
  uint8_t *mask = st->mask;
#pragma omp parallel for default(none) shared(n, bs, bj, alive, cst, mask, ns) schedule(static)    \
    num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i) {
    const int64_t si = cst->particle_site[i];
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const int o = pdk_stencil_offset_of(cst, si, cst->particle_site[bj[b]]);
      mask[(int64_t)o * ns + si] = alive ? alive[b] : 1;
    }
    if (cst->cs[0]) pdk_stencil_corr_s((pdk_stencil *)cst, i);
  }
  st->version = m->bond_state_version;
}

/* The row list: each grid row from its first to its last occupied site. 3-D: in tiles of `tile`
 * rows along y, z outer within a tile, so the 2P + 1 planes of neighbour rows a tile reads (about
 * 768 KiB for site_bytes bytes read per neighbour site) stay in the L2 cache while z advances;
 * each row is then read from memory about (tile + 2P) / tile times instead of 2P + 1. The order
 * does not change any result. Returns -1 when out of memory. */
int pdk_stencil_make_rows(pdk_stencil *st, double site_bytes) {
  const int64_t nx = st->nx, ny = st->ny;
  const int pad = st->pad, dim = st->dim;
  const int64_t nrow_max = ny * st->nz;
  if (!st->row_lo) {
    st->row_lo = malloc((size_t)nrow_max * sizeof *st->row_lo);
    st->row_hi = malloc((size_t)nrow_max * sizeof *st->row_hi);
    if (!st->row_lo || !st->row_hi) return -1;
  }
  const double row_bytes = (double)nx * site_bytes;
  int64_t tile = (int64_t)(768.0 * 1024.0 / ((2 * pad + 1) * row_bytes)) - 2 * pad;
  if (tile < 2 * pad + 1) tile = 2 * pad + 1;
  if (dim == 2 || tile > ny) tile = ny;
  int64_t nr = 0;
  for (int64_t row_k = 0; row_k < nrow_max; ++row_k) {
    /* row_k counts rows in tile order: tile, then z, then y within the tile */
    const int64_t y0 = (row_k / (tile * st->nz)) * tile;
    const int64_t th = y0 + tile <= ny ? tile : ny - y0; /* this tile's height */
    const int64_t in = row_k - y0 * st->nz;
    const int64_t iz = in / th, iy = y0 + in % th;
    const int64_t row = iy + ny * iz;
    const int64_t s0 = row * nx;
    int64_t lo = -1, hi = -1;
    for (int64_t ix = 0; ix < nx; ++ix)
      if (st->site_particle[s0 + ix] >= 0) {
        if (lo < 0) lo = s0 + ix;
        hi = s0 + ix + 1;
      }
    if (lo >= 0) st->row_lo[nr] = lo, st->row_hi[nr] = hi, ++nr;
  }
  st->num_rows = nr;
  st->tile = tile;
  return 0;
}

#define WHY(...)                                                                                   \
  do {                                                                                             \
    snprintf(why, why_len, __VA_ARGS__);                                                           \
    goto not_lattice;                                                                              \
  } while (0)

int pdk_stencil_create(pdk_model *m, const float *bond_r0, pdk_stencil **out, char *why,
                       size_t why_len) {
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  int err = PDK_SUCCESS;
  *out = NULL;
  if (why_len) why[0] = '\0';
  const int dim = pdk_particles_dim(p), nt = ctx->num_threads;
  const pdk_index n = pdk_particles_count(p);
  const int64_t *ids = pdk_particles_id(p);
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  const double delta = pdk_families_horizon(m->fam);
  const double *X[3] = {NULL, NULL, NULL};
  for (int a = 0; a < dim; ++a)
    X[a] = pdk_particles_X(p, a);
  int32_t *kidx = NULL; /* [n * 3] lattice indices */
  int *table = NULL;    /* [(2R+1)^dim] offset index of each integer offset, -1 none */
  pdk_stencil *st = NULL;

  /* 1. spacing, origin, lattice indices */
  double h = delta;
  if (nb > 0) {
    double hmin = HUGE_VAL;
#pragma omp parallel for default(none) shared(n, bs, bj, X, dim) reduction(min                     \
                                                                           : hmin)                 \
    schedule(static) num_threads(nt)
    for (pdk_index i = 0; i < n; ++i)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        double r2 = 0.0;
        for (int a = 0; a < dim; ++a) {
          const double d = X[a][bj[b]] - X[a][i];
          r2 += d * d;
        }
        hmin = r2 < hmin ? r2 : hmin;
      }
    h = sqrt(hmin);
  }
  if (!(h > 0 && isfinite(h))) WHY("two particles share a position (shortest bond %g)", h);
  double origin[3] = {0, 0, 0};
  int64_t ext[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    double lo = HUGE_VAL;
    for (pdk_index i = 0; i < n; ++i)
      lo = X[a][i] < lo ? X[a][i] : lo;
    origin[a] = lo;
  }
  kidx = malloc((size_t)n * 3 * sizeof *kidx);
  PDK_CHECK_GOTO(kidx, ctx, PDK_ERR_MEMORY, "stencil: out of memory for %d lattice indices",
                 (int)n);
  for (pdk_index i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      if (a >= dim) {
        kidx[3 * (size_t)i + (size_t)a] = 0;
        continue;
      }
      const double t = (X[a][i] - origin[a]) / h;
      if (!(t < 1e9)) WHY("the lattice would span more than 1e9 spacings along axis %d", a);
      const double k = nearbyint(t);
      if (fabs(t - k) > STENCIL_POS_TOL)
        WHY("particle id %lld lies %.3g spacings off the nearest lattice point (origin + index x "
            "spacing along axis %c, origin %.17g, spacing %.17g: the shortest bond); the stencil "
            "path needs particles on a simple cubic or square lattice aligned with the axes, "
            "within %g spacings",
            (long long)ids[i], fabs(t - k), "xyz"[a], origin[a], h, STENCIL_POS_TOL);
      kidx[3 * (size_t)i + (size_t)a] = (int32_t)k;
      if ((int64_t)k + 1 > ext[a]) ext[a] = (int64_t)k + 1;
    }
  }

  /* 2. offsets: the union of the families' bond offsets */
  /* the reach in double first: a horizon of billions of spacings must not reach the int */
  const double reach = ceil(delta / h * (1.0 + 1e-9));
  if (!(reach <= STENCIL_MAX_REACH))
    WHY("the horizon spans %.4g spacings (more than %d)", reach, STENCIL_MAX_REACH);
  const int R = (int)reach;
  const int side = 2 * R + 1;
  const int64_t tsize = dim == 3 ? (int64_t)side * side * side : (int64_t)side * side;
  table = malloc((size_t)tsize * sizeof *table);
  PDK_CHECK_GOTO(table, ctx, PDK_ERR_MEMORY, "stencil: out of memory for the offset table");
  for (int64_t t = 0; t < tsize; ++t)
    table[t] = -1;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      int64_t t = 0;
      for (int a = dim - 1; a >= 0; --a) {
        const int d = kidx[3 * (size_t)j + (size_t)a] - kidx[3 * (size_t)i + (size_t)a];
        if (d < -R || d > R)
          WHY("the bond between particles id %lld and %lld spans %d spacings along axis %c, more "
              "than the horizon allows on a lattice",
              (long long)ids[i], (long long)ids[j], d, "xyz"[a]);
        t = t * side + (d + R);
      }
      table[t] = 1;
    }
  int num_off = 0, pad = 0;
  for (int64_t t = 0; t < tsize; ++t)
    if (table[t] >= 0) {
      ++num_off;
      int64_t u = t;
      for (int a = 0; a < dim; ++a, u /= side) {
        const int d = (int)(u % side) - R;
        pad = abs(d) > pad ? abs(d) : pad;
      }
    }

  /* 3. grid */
  st = calloc(1, sizeof *st);
  PDK_CHECK_GOTO(st, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
  st->dim = dim;
  st->n = n;
  st->pad = pad;
  st->nx = ext[0] + 2 * pad;
  st->ny = ext[1] + 2 * pad;
  st->nz = dim == 3 ? ext[2] + 2 * pad : 1;
  if ((double)st->nx * (double)st->ny * (double)st->nz > 8.0 * (double)n + 1048576.0)
    WHY("the lattice's padded bounding box holds %.3g sites for %d particles (more than 8 per "
        "particle): the set is too sparse for a grid",
        (double)st->nx * (double)st->ny * (double)st->nz, (int)n);
  const int64_t nx = st->nx, ny = st->ny, ns = st->num_sites = st->nx * st->ny * st->nz;
  st->num_offsets = num_off;
  st->offset = malloc((size_t)(num_off > 0 ? num_off : 1) * sizeof *st->offset);
  PDK_CHECK_GOTO(st->offset, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
  {
    int o = 0;
    for (int64_t t = 0; t < tsize; ++t)
      if (table[t] >= 0) {
        int64_t u = t, comp[3] = {0, 0, 0};
        for (int a = 0; a < dim; ++a, u /= side)
          comp[a] = (int)(u % side) - R;
        st->offset[o++] = comp[0] + nx * (comp[1] + ny * comp[2]);
      }
    qsort(st->offset, (size_t)num_off, sizeof *st->offset, cmp_i64);
  }
  const int64_t max_d = pad + nx * (pad + ny * (dim == 3 ? pad : 0));
  st->lut_min = -max_d;
  st->lut_len = 2 * max_d + 1;
  st->lut = malloc((size_t)st->lut_len * sizeof *st->lut);
  PDK_CHECK_GOTO(st->lut && num_off < 32767, ctx, PDK_ERR_MEMORY,
                 "stencil: out of memory for the offset lookup (%lld entries)",
                 (long long)st->lut_len);
  for (int64_t t = 0; t < st->lut_len; ++t)
    st->lut[t] = -1;
  for (int o = 0; o < num_off; ++o)
    st->lut[st->offset[o] - st->lut_min] = (int16_t)o;

  const int64_t ns_all = ns + PDK_STENCIL_SLACK; /* per-site arrays: the grid and the slack */
  st->site_particle = pdk_alloc_aligned((size_t)ns_all, sizeof *st->site_particle);
  st->particle_site = pdk_alloc_aligned((size_t)n, sizeof *st->particle_site);
  st->volume = pdk_alloc_aligned((size_t)ns_all, sizeof(double));
  PDK_CHECK_GOTO(st->site_particle && st->particle_site && st->volume, ctx, PDK_ERR_MEMORY,
                 "stencil: out of memory for a grid of %lld sites", (long long)ns);
  for (int a = 0; a < dim; ++a) {
    st->X[a] = pdk_alloc_aligned((size_t)ns_all, sizeof(double));
    st->x[a] = pdk_alloc_aligned((size_t)ns_all, sizeof(double));
    PDK_CHECK_GOTO(st->X[a] && st->x[a], ctx, PDK_ERR_MEMORY,
                   "stencil: out of memory for a grid of %lld sites", (long long)ns);
  }
  for (int64_t s = 0; s < ns_all; ++s)
    st->site_particle[s] = -1;
  const double *V = pdk_particles_volume(p);
  for (pdk_index i = 0; i < n; ++i) {
    const int32_t *k = kidx + 3 * (size_t)i;
    const int64_t s = (k[0] + pad) + nx * ((k[1] + pad) + ny * (dim == 3 ? k[2] + pad : 0));
    if (st->site_particle[s] >= 0)
      WHY("particles id %lld and %lld fall on the same lattice site",
          (long long)ids[st->site_particle[s]], (long long)ids[i]);
    st->site_particle[s] = i;
    st->particle_site[i] = s;
  }
  /* positions: the ideal lattice point at empty sites (and the slack: points of the rows past the
   * grid), the particle's own X at occupied ones */
  for (int64_t s = 0; s < ns_all; ++s) {
    const int64_t idx[3] = {s % nx, (s / nx) % ny, s / (nx * ny)};
    const pdk_index i = st->site_particle[s];
    for (int a = 0; a < dim; ++a) {
      const double v = i >= 0 ? X[a][i] : origin[a] + (double)(idx[a] - pad) * h;
      st->X[a][s] = v;
      st->x[a][s] = v;
    }
    st->volume[s] = i >= 0 ? V[i] : 0.0;
  }

  /* 4. rows (stencil_rows) */
  PDK_CHECK_GOTO(pdk_stencil_make_rows(st, 8.0 * (2 * dim + 1)) == 0, ctx, PDK_ERR_MEMORY,
                 "stencil: out of memory");

  /* 5. float storage: one float length per offset */
  if (bond_r0) {
    st->r0_off = malloc((size_t)(num_off > 0 ? num_off : 1) * sizeof(double));
    st->beta_off = malloc((size_t)(num_off > 0 ? num_off : 1) * sizeof(double));
    PDK_CHECK_GOTO(st->r0_off && st->beta_off, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
    for (int o = 0; o < num_off; ++o)
      st->r0_off[o] = -1.0;
    for (pdk_index i = 0; i < n; ++i)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const int o = pdk_stencil_offset_of(st, st->particle_site[i], st->particle_site[bj[b]]);
        const double r0 = (double)bond_r0[b];
        if (st->r0_off[o] < 0)
          st->r0_off[o] = r0;
        else if (st->r0_off[o] != r0)
          WHY("float storage: the bond from particle id %lld to %lld stores the length %.9g, "
              "another bond along the same lattice offset %.9g; the stencil path takes one float "
              "length per offset",
              (long long)ids[i], (long long)ids[bj[b]], r0, st->r0_off[o]);
      }
  }

  /* 6. bond state: a mask unless every family is the full stencil and no bond can break */
  int complete = 1;
  {
    const pdk_stencil *cst = st;
#pragma omp parallel for default(none) shared(n, bs, cst) reduction(&& : complete)               \
    schedule(static) num_threads(nt)
    for (pdk_index i = 0; i < n; ++i) {
      pdk_bond_index count = 0;
      for (int o = 0; o < cst->num_offsets; ++o)
        count += cst->site_particle[cst->particle_site[i] + cst->offset[o]] >= 0;
      complete = complete && count == bs[i + 1] - bs[i];
    }
  }
  if (!complete || m->bond_alive) {
    st->mask =
        pdk_alloc_aligned((size_t)ns * (size_t)(num_off > 0 ? num_off : 1) + PDK_STENCIL_SLACK, 1);
    PDK_CHECK_GOTO(st->mask, ctx, PDK_ERR_MEMORY,
                   "stencil: out of memory for the bond mask (%lld sites x %d offsets); use "
                   "stencil off",
                   (long long)ns, num_off);
    pdk_stencil_load_mask(m, st);
  }
  if (m->bond_alive && m->s0) {
    st->s0 = pdk_alloc_aligned((size_t)ns_all, sizeof(double));
    st->changed = pdk_alloc_aligned((size_t)ns_all, 1);
    PDK_CHECK_GOTO(st->s0 && st->changed, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
    for (int64_t s = 0; s < ns_all; ++s)
      st->s0[s] = DBL_MAX;
  }
  free(kidx);
  free(table);
  *out = st;
  return PDK_SUCCESS;
not_lattice:
  free(kidx);
  free(table);
  pdk_stencil_destroy(&st);
  return PDK_SUCCESS;
cleanup:
  free(kidx);
  free(table);
  pdk_stencil_destroy(&st);
  return err;
}

/* The lattice part of the kernels' arrays (dimension, offsets, sites, rows), the rest zeroed. */
void pdk_stencil_arrays_lattice(const pdk_stencil *st, pdk_stencil_arrays *arr) {
  memset(arr, 0, sizeof *arr);
  arr->dim = st->dim;
  arr->num_offsets = st->num_offsets;
  arr->offset = st->offset;
  arr->num_sites = st->num_sites;
  arr->num_rows = st->num_rows;
  arr->row_lo = st->row_lo;
  arr->row_hi = st->row_hi;
  arr->site_particle = st->site_particle;
}

/* The kernels' arrays for one pass; xp: the particles' "x". */
static int stencil_arrays(pdk_model *m, pdk_stencil *st, double vs_a, double vs_b, double *s0_next,
                          double *w, pdk_stencil_arrays *out, const double *xp[3]) {
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const int dim = st->dim;
  const int commit = s0_next != NULL;
  PDK_CHECK(!commit || (st->mask && st->s0 && m->bond_alive && m->s0), ctx, PDK_ERR_ARG,
            "stencil: a committing pass needs the bond state");
  if (st->mask && st->version != m->bond_state_version) pdk_stencil_load_mask(m, st);
  if (st->r0_off) /* partial-volume factor of each offset's float length, as the kernels do */
    for (int o = 0; o < st->num_offsets; ++o) {
      const double t = (vs_a - st->r0_off[o]) * vs_b;
      st->beta_off[o] = t < 1.0 ? t : 1.0;
    }
  pdk_stencil_arrays arr;
  pdk_stencil_arrays_lattice(st, &arr);
  for (int a = 0; a < 3; ++a)
    xp[a] = NULL;
  for (int a = 0; a < dim; ++a) {
    arr.X[a] = st->X[a];
    arr.x[a] = st->x[a];
    xp[a] = pdk_particles_field_data(p, "x", a);
    arr.f[a] = pdk_particles_field_data(p, "f", a);
    PDK_CHECK(xp[a] && arr.f[a], ctx, PDK_ERR_NOT_FOUND,
              "pmb model: fields \"x\" and \"f\" are missing from the particle store");
  }
  arr.volume = st->volume;
  arr.r0_off = st->r0_off;
  arr.beta_off = st->r0_off ? st->beta_off : NULL;
  arr.mask = st->mask;
  arr.s0 = commit ? st->s0 : NULL;
  arr.changed = commit ? st->changed : NULL;
  arr.s0_next = s0_next;
  arr.w = w;
  arr.inv_m = st->inv_m;
  arr.theta = arr.theta_site = st->theta;
  *out = arr;
  return PDK_SUCCESS;
}

/* The particles' x (and s0) onto their sites; a parallel loop inside the caller's region. */
#define STENCIL_SCATTER()                                                                          \
  do {                                                                                             \
    _Pragma("omp for schedule(static)") for (pdk_index i = 0; i < n; ++i) {                        \
      const int64_t s_ = cst->particle_site[i];                                                    \
      gx[s_] = xp[0][i];                                                                           \
      gy[s_] = xp[1][i];                                                                           \
      if (dim == 3) gz[s_] = xp[2][i];                                                             \
      if (commit) gs0[s_] = s0p[i];                                                                \
    }                                                                                              \
  } while (0)

/* The new bond state back into the model's bond list, for the particles that lost bonds. */
#define STENCIL_SYNC()                                                                             \
  do {                                                                                             \
    _Pragma("omp for schedule(static)") for (pdk_index i = 0; i < n; ++i) {                        \
      const int64_t si_ = cst->particle_site[i];                                                   \
      if (!changed[si_]) continue;                                                                 \
      changed[si_] = 0;                                                                            \
      for (pdk_bond_index b_ = bs[i]; b_ < bs[i + 1]; ++b_) {                                      \
        const int o_ = pdk_stencil_offset_of(cst, si_, cst->particle_site[bj[b_]]);                \
        alive[b_] = mask[(int64_t)o_ * ns + si_];                                                  \
      }                                                                                            \
    }                                                                                              \
  } while (0)

int pdk_stencil_pmb_force(pdk_model *m, pdk_stencil *st, const pdk_pmb_consts *k, double *s0_next,
                          double *w, pdk_bond_index *broken_out) {
  pdk_ctx *ctx = m->ctx;
  const int dim = st->dim;
  const int commit = s0_next != NULL;
  pdk_stencil_arrays arr;
  const double *xp[3];
  PDK_CALL(stencil_arrays(m, st, k->vs_a, k->vs_b, s0_next, w, &arr, xp));
  const pdk_stencil_arrays *a = &arr;
  const pdk_stencil *cst = st;
  const pdk_pmb_stencil_fn kernel = ctx->kernels.pmb_stencil;
  const pdk_index n = st->n;
  const int64_t num_rows = st->num_rows, ns = st->num_sites;
  const double *s0p = m->s0;
  double *gx = st->x[0], *gy = st->x[1], *gz = dim == 3 ? st->x[2] : NULL, *gs0 = st->s0;
  uint8_t *changed = st->changed, *alive = m->bond_alive, *mask = st->mask;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  pdk_bond_index broken = 0;

#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)            \
    shared(n, cst, xp, gx, gy, gz, gs0, s0p, commit, dim, num_rows, kernel, k, a, changed, alive, \
               mask, bs, bj, ns)
  {
    STENCIL_SCATTER(); /* implicit barrier: every site is filled before a neighbour reads it */
#pragma omp for schedule(static)
    for (int64_t r = 0; r < num_rows; ++r)
      broken += kernel(k, a, r, r + 1);
    if (commit) STENCIL_SYNC();
  }
  *broken_out = broken;
  return PDK_SUCCESS;
}

int pdk_stencil_lps_force(pdk_model *m, pdk_stencil *st, const pdk_lps_consts *k, double *theta,
                          double *s0_next, double *w, pdk_bond_index *broken_out) {
  pdk_ctx *ctx = m->ctx;
  const int dim = st->dim;
  const int commit = s0_next != NULL;
  PDK_CHECK(st->inv_m && st->theta, ctx, PDK_ERR_ARG, "stencil: the lps arrays were not set up");
  pdk_stencil_arrays arr;
  const double *xp[3];
  PDK_CALL(stencil_arrays(m, st, k->vs_a, k->vs_b, s0_next, w, &arr, xp));
  arr.theta_out = theta;
  const pdk_stencil_arrays *a = &arr;
  const pdk_stencil *cst = st;
  const pdk_lps_stencil_dilation_fn dilation = ctx->kernels.lps_stencil_dilation;
  const pdk_lps_stencil_force_fn force = ctx->kernels.lps_stencil_force;
  const pdk_index n = st->n;
  const int64_t num_rows = st->num_rows, ns = st->num_sites;
  const double *s0p = m->s0;
  double *gx = st->x[0], *gy = st->x[1], *gz = dim == 3 ? st->x[2] : NULL, *gs0 = st->s0;
  uint8_t *changed = st->changed, *alive = m->bond_alive, *mask = st->mask;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  pdk_bond_index broken = 0;

#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)            \
    shared(n, cst, xp, gx, gy, gz, gs0, s0p, commit, dim, num_rows, dilation, force, k, a,       \
               changed, alive, mask, bs, bj, ns)
  {
    STENCIL_SCATTER(); /* implicit barrier: every site is filled before a neighbour reads it */
#pragma omp for schedule(static)
    for (int64_t r = 0; r < num_rows; ++r)
      dilation(k, a, r, r + 1);
      /* implicit barrier: every theta is complete before any force is computed */
#pragma omp for schedule(static)
    for (int64_t r = 0; r < num_rows; ++r)
      broken += force(k, a, r, r + 1);
    if (commit) STENCIL_SYNC();
  }
  *broken_out = broken;
  return PDK_SUCCESS;
}
