/* Data shared by the PMB and LPS drivers: packed particle rows for the SIMD kernels and float
 * bond lengths for precision float (src/models/model_bond.h, pdk_bond_arrays in kernels/kernels.h).
 */
#include <math.h>
#include <string.h>

#include "model_bond.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

int pdk_bond_data_setup(pdk_model *m, pdk_bond_data *bd, const char *who) {
  pdk_ctx *ctx = m->ctx;
  pdk_particles *p = m->p;
  const int dim = bd->dim = pdk_particles_dim(p);
  const pdk_index n = bd->n = pdk_particles_count(p);
  const size_t n_pad = (size_t)pdk_particles_count_padded(p);
  if (ctx->kernels.bond_rows) {
    bd->ref4 = pdk_alloc_aligned(4 * n_pad, sizeof(double));
    bd->cur4 = pdk_alloc_aligned(4 * n_pad, sizeof(double));
    PDK_CHECK(bd->ref4 && bd->cur4, ctx, PDK_ERR_MEMORY,
              "%s model: out of memory for the packed rows of %d particles (%zu bytes)", who,
              (int)n, 64 * n_pad);
    for (int c = 0; c < dim; ++c) {
      const double *X = pdk_particles_X(p, c);
      for (pdk_index i = 0; i < n; ++i)
        bd->ref4[4 * (size_t)i + (size_t)c] = X[i];
    }
  }
  if (m->opts.precision == PDK_PRECISION_FLOAT) {
    const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
    bd->bond_r0 = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(float));
    PDK_CHECK(bd->bond_r0, ctx, PDK_ERR_MEMORY,
              "%s model: out of memory for the float bond lengths of %lld bonds (%lld bytes); use "
              "precision double",
              who, (long long)nb, (long long)(4 * nb));
    const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
    const pdk_index *bj = pdk_families_bond_j(m->fam);
    const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
    const double *Z = dim == 3 ? pdk_particles_X(p, 2) : NULL;
    float *r0 = bd->bond_r0;
#pragma omp parallel for default(none) shared(n, bs, bj, X, Y, Z, r0, dim) schedule(static)        \
    num_threads(ctx->num_threads)
    for (pdk_index i = 0; i < n; ++i)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const pdk_index j = bj[b];
        const double dX = X[j] - X[i], dY = Y[j] - Y[i], dZ = dim == 3 ? Z[j] - Z[i] : 0.0;
        r0[b] = (float)sqrt(dX * dX + dY * dY + dZ * dZ); /* as the kernels order it */
      }
  }
  return PDK_SUCCESS;
}

int pdk_bond_data_store_lengths(pdk_model *m, pdk_bond_data *bd, const char *who) {
  pdk_ctx *ctx = m->ctx;
  if (m->opts.bond_lengths != PDK_BOND_LENGTHS_STORED ||
      m->opts.precision != PDK_PRECISION_DOUBLE || !bd->ref4 || bd->bond_r0d)
    return PDK_SUCCESS;
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  bd->bond_r0d = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), sizeof(double));
  PDK_CHECK(bd->bond_r0d, ctx, PDK_ERR_MEMORY,
            "%s model: out of memory for the bond lengths of %lld bonds (%lld bytes); use "
            "bond_lengths computed",
            who, (long long)nb, (long long)(8 * nb));
  pdk_bond_arrays a;
  memset(&a, 0, sizeof a);
  a.dim = bd->dim;
  a.bond_start = pdk_families_bond_start(m->fam);
  a.bond_j = pdk_families_bond_j(m->fam);
  for (int c = 0; c < bd->dim; ++c) a.X[c] = pdk_particles_X(m->p, c);
  const pdk_index n = bd->n;
  const int64_t block = 1024, num_blocks = ((int64_t)n + block - 1) / block;
  double *r0 = bd->bond_r0d;
  const pdk_bond_arrays *ap = &a;
#pragma omp parallel for default(none) shared(ap, r0, n, num_blocks) schedule(static)             \
    num_threads(ctx->num_threads)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = (pdk_index)(blk * block);
    pdk_kernel_bond_lengths_ref(ap, i0, (pdk_index)(i0 + block < (int64_t)n ? i0 + block : n), r0);
  }
  return PDK_SUCCESS;
}

void pdk_bond_data_free(pdk_bond_data *bd) {
  pdk_free_aligned(bd->bond_r0d);
  pdk_free_aligned(bd->ref4);
  pdk_free_aligned(bd->cur4);
  pdk_free_aligned(bd->bond_r0);
  memset(bd, 0, sizeof *bd);
}

int pdk_bond_arrays_get(pdk_model *m, const pdk_bond_data *bd, pdk_bond_arrays *a) {
  pdk_particles *p = m->p;
  const int dim = pdk_particles_dim(p); /* also when bd was not set up (layout stencil) */
  memset(a, 0, sizeof *a);
  a->dim = dim;
  a->bond_start = pdk_families_bond_start(m->fam);
  a->bond_j = pdk_families_bond_j(m->fam);
  for (int c = 0; c < dim; ++c) {
    a->X[c] = pdk_particles_X(p, c);
    a->x[c] = pdk_particles_field_data(p, "x", c);
    a->f[c] = pdk_particles_field_data(p, "f", c);
    if (!a->x[c] || !a->f[c]) return 0;
  }
  a->volume = pdk_particles_volume(p);
  a->ref4 = bd->ref4;
  a->cur4 = bd->cur4;
  a->bond_r0 = bd->bond_r0;
  a->bond_r0d = bd->bond_r0d;
  a->bond_alive = m->bond_alive;
  a->s0 = m->s0;
  return 1;
}

void pdk_bond_pack_cur(const pdk_bond_data *bd, const pdk_bond_arrays *a, pdk_index i0,
                       pdk_index i1) {
  double *restrict c4 = bd->cur4;
  if (!c4) return;
  const double *restrict x = a->x[0], *restrict y = a->x[1], *restrict V = a->volume;
  if (bd->dim == 3) {
    const double *restrict z = a->x[2];
    for (pdk_index i = i0; i < i1; ++i) {
      c4[4 * (size_t)i] = x[i];
      c4[4 * (size_t)i + 1] = y[i];
      c4[4 * (size_t)i + 2] = z[i];
      c4[4 * (size_t)i + 3] = V[i];
    }
  } else {
    for (pdk_index i = i0; i < i1; ++i) {
      c4[4 * (size_t)i] = x[i];
      c4[4 * (size_t)i + 1] = y[i];
      c4[4 * (size_t)i + 2] = 0.0;
      c4[4 * (size_t)i + 3] = V[i];
    }
  }
}

void pdk_bond_pack_cur_blocks(const pdk_bond_data *bd, const pdk_bond_arrays *a, pdk_index n,
                              int64_t block) {
  if (!bd->cur4) return;
  const int64_t num_blocks = ((int64_t)n + block - 1) / block;
#pragma omp for schedule(static)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = (pdk_index)(blk * block);
    pdk_bond_pack_cur(bd, a, i0, (pdk_index)(i0 + block < (int64_t)n ? i0 + block : n));
  }
}

void pdk_bond_block_energies(const double *volume, const double *w, pdk_index n, int64_t block,
                             double *block_energy) {
  const int64_t num_blocks = ((int64_t)n + block - 1) / block;
#pragma omp for schedule(static)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = (pdk_index)(blk * block);
    block_energy[blk] =
        pdk_bond_block_energy(volume, w, i0, (pdk_index)(i0 + block < (int64_t)n ? i0 + block : n));
  }
}
