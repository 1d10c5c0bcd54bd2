/* Ordinary state-based LPS model, as LAMMPS peri/lps: driver over the context's kernel table
 * (reference kernels/ref/lps.c; SIMD variants kernels/opt/bond_*.c over packed rows, see
 * src/model_pmb.c). precision float: bond lengths stored per bond as floats, m_i computed from them.
 *
 * Fields declared: "m" (f64 x1, weighted volume m_i = sum_b omega r0^2 beta V_j with LAMMPS's
 * omega = 1/r0, computed once here, over all bonds, and never updated, as LAMMPS's wvolume) and
 * "theta" (f64 x1, dilation of the last pass).
 *
 * Constants (K bulk, G = mu shear modulus; see kernels/ref/lps.c for the formulas):
 *   3-D (LAMMPS):    theta = 3/m sum omega r0 e beta V,  t = (omega/m) [(3K - 5G) theta r0 + 15 G
 * e] W = K theta^2/2 + (15 G / 2m) sum omega (e - theta r0/3)^2 beta V plane strain:    lambda = K
 * - 2G/3 (the 3-D Lame constant, plane strain keeps it) theta = 2/m sum omega r0 e beta V,  t =
 * (omega/m) [2 (lambda - mu) theta r0 + 8 mu e] W = (lambda + mu) theta^2/2 + (4 mu / m) sum omega
 * (e - theta r0/2)^2 beta V (Queiruga & Moridis 2017 section 2.2; seeds/notes/002 checks isotropic,
 * uniaxial and shear strain against sigma = lambda tr(eps) I + 2 mu eps.) For an isotropic stretch
 * s, theta = 3s (2s) exactly for any family and W = 9/2 K s^2 (2 (lambda + mu) s^2).
 *
 * Passes: (1) dilation theta_i for every particle; (2) force, which gathers theta_j and 1/m_j of
 * the neighbours, and with commit = 1 applies the LAMMPS s0 rule (bonds broken in pass 2 take
 * effect from the next pass). Both passes run in one parallel region over fixed blocks of
 * PDK_LPS_BLOCK particles (static schedule, barrier between); the energy is summed per block and
 * the blocks in order, so results are bitwise the same for any thread count.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "kernels.h"
#include "model_bond.h"
#include "model_impl.h"

#define PDK_LPS_BLOCK 1024 /* particles per block: kernel call and energy partial sum */

typedef struct lps_impl {
  pdk_lps_consts k;
  int dim;
  pdk_index n;
  int64_t num_blocks;
  double *inv_m;        /* [n_pad] 1/m_i, 0 for an empty family */
  double *s0_next;      /* [n_pad] when bonds can break */
  double *w;            /* [n_pad] strain energy density, allocated on first request */
  double *block_energy; /* [num_blocks] */
  pdk_bond_data bd;     /* packed rows (extra column: 1/m), float bond lengths */
} lps_impl;

static int64_t block_count(pdk_index n) { return ((int64_t)n + PDK_LPS_BLOCK - 1) / PDK_LPS_BLOCK; }

static void block_range(int64_t blk, pdk_index n, pdk_index *i0, pdk_index *i1) {
  *i0 = (pdk_index)(blk * PDK_LPS_BLOCK);
  *i1 = (pdk_index)(*i0 + PDK_LPS_BLOCK < (int64_t)n ? *i0 + PDK_LPS_BLOCK : n);
}

static int lps_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  const pdk_model_opts *o = &m->opts;
  pdk_particles *p = m->p;
  lps_impl *im = calloc(1, sizeof *im);
  PDK_CHECK(im, ctx, PDK_ERR_MEMORY, "out of memory creating the lps model");
  m->impl = im;
  const int dim = im->dim = pdk_particles_dim(p);
  const pdk_index n = im->n = pdk_particles_count(p);
  const int64_t num_blocks = im->num_blocks = block_count(n);
  const size_t n_pad = (size_t)pdk_particles_count_padded(p);
  const double delta = pdk_families_horizon(m->fam);
  PDK_CHECK(isfinite(delta) && delta > 0, ctx, PDK_ERR_ARG,
            "lps model: the families' horizon must be positive, got %g", delta);

  const double K = o->bulk_modulus, G = o->shear_modulus;
  pdk_lps_consts *k = &im->k;
  if (o->lattice_constant > 0) { /* LAMMPS vfrac_scale, see kernels/ref/pmb.c */
    k->vs_a = delta + 0.5 * o->lattice_constant;
    k->vs_b = 1.0 / o->lattice_constant;
  } else {
    k->vs_a = HUGE_VAL;
    k->vs_b = 1.0;
  }
  if (dim == 3) {
    k->theta_factor = 3.0;
    k->c_dil = 3.0 * K - 5.0 * G;
    k->c_dev = 15.0 * G;
    k->e_bulk = K;
    k->e_dev = 7.5 * G;
  } else {
    const double lambda = K - 2.0 * G / 3.0, mu = G;
    k->theta_factor = 2.0;
    k->c_dil = 2.0 * (lambda - mu);
    k->c_dev = 8.0 * mu;
    k->e_bulk = lambda + mu;
    k->e_dev = 4.0 * mu;
  }
  k->s00 = o->critical_stretch;
  k->alpha = o->alpha;

  PDK_CALL(pdk_particles_field_add(p, "m", PDK_F64, 1));
  PDK_CALL(pdk_particles_field_add(p, "theta", PDK_F64, 1));
  im->inv_m = pdk_alloc_aligned(n_pad, sizeof(double));
  im->block_energy = calloc((size_t)(num_blocks > 0 ? num_blocks : 1), sizeof(double));
  PDK_CHECK(im->inv_m && im->block_energy, ctx, PDK_ERR_MEMORY,
            "lps model: out of memory for %d particles", (int)n);
  if (m->bond_alive && m->s0) {
    im->s0_next = pdk_alloc_aligned(n_pad, sizeof(double));
    PDK_CHECK(im->s0_next, ctx, PDK_ERR_MEMORY,
              "lps model: out of memory for %d critical stretches", (int)n);
  }

  PDK_CALL(pdk_bond_data_setup(m, &im->bd, "lps"));
  pdk_bond_arrays arrays;
  PDK_CHECK(pdk_bond_arrays_get(m, &im->bd, &arrays), ctx, PDK_ERR_NOT_FOUND,
            "lps model: fields \"x\" and \"f\" are missing from the particle store");
  const pdk_bond_arrays *a = &arrays;
  double *mw = pdk_particles_field_data(p, "m", 0);
  double *inv_m = im->inv_m, *ref4 = im->bd.ref4;
#pragma omp parallel for default(none) schedule(static) num_threads(ctx->num_threads)              \
    shared(num_blocks, n, k, a, mw, inv_m, ref4)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    pdk_index i0, i1;
    block_range(blk, n, &i0, &i1);
    pdk_kernel_lps_weighted_volume_ref(k, a, i0, i1, mw);
    for (pdk_index i = i0; i < i1; ++i) {
      inv_m[i] = mw[i] > 0 ? 1.0 / mw[i] : 0.0;
      if (ref4) ref4[4 * (size_t)i + 3] = inv_m[i]; /* the rows' extra column */
    }
  }
  return PDK_SUCCESS;
}

static int lps_force(pdk_model *m, int commit, double *energy) {
  pdk_ctx *ctx = m->ctx;
  lps_impl *im = m->impl;
  pdk_particles *p = m->p;
  if (energy && !im->w) {
    im->w = pdk_alloc_aligned((size_t)pdk_particles_count_padded(p), sizeof(double));
    PDK_CHECK(im->w, ctx, PDK_ERR_MEMORY, "lps model: out of memory for the energy densities");
  }
  const pdk_index n = im->n;
  const int64_t num_blocks = im->num_blocks;
  const pdk_lps_consts *k = &im->k;
  pdk_bond_arrays arrays;
  double *theta = pdk_particles_field_data(p, "theta", 0);
  PDK_CHECK(pdk_bond_arrays_get(m, &im->bd, &arrays) && theta, ctx, PDK_ERR_NOT_FOUND,
            "lps model: fields \"x\", \"f\" or \"theta\" are missing from the particle store");
  arrays.s0_next = commit && m->bond_alive && m->s0 ? im->s0_next : NULL;
  arrays.w = energy ? im->w : NULL;
  arrays.theta = arrays.theta_out = theta;
  arrays.inv_m = im->inv_m;
  const pdk_bond_arrays *a = &arrays;
  const pdk_bond_data *bd = &im->bd;
  const pdk_lps_dilation_fn dilation = ctx->kernels.lps_dilation;
  const pdk_lps_force_fn force = ctx->kernels.lps_force;
  const int pack = bd->cur4 != NULL;
  const double *volume = a->volume, *w = a->w;
  double *block_energy = im->block_energy;
  pdk_bond_index broken = 0;

#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, k, a, bd, dilation, force, pack, volume, w, block_energy)
  {
    if (pack) {
#pragma omp for schedule(static)
      for (int64_t blk = 0; blk < num_blocks; ++blk) {
        pdk_index i0, i1;
        block_range(blk, n, &i0, &i1);
        pdk_bond_pack_cur(bd, a, i0, i1);
      } /* implicit barrier: every row is packed before a neighbour reads it */
    }
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0, i1;
      block_range(blk, n, &i0, &i1);
      dilation(k, a, i0, i1);
    } /* implicit barrier: every theta is complete before any force is computed */
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0, i1;
      block_range(blk, n, &i0, &i1);
      broken += force(k, a, i0, i1);
      if (w) block_energy[blk] = pdk_bond_block_energy(volume, w, i0, i1);
    }
  }

  pdk_bond_pass_finish(m, &im->s0_next, arrays.s0_next != NULL, broken, block_energy, num_blocks,
                       energy);
  return PDK_SUCCESS;
}

static void lps_destroy(pdk_model *m) {
  lps_impl *im = m->impl;
  if (!im) return;
  pdk_free_aligned(im->inv_m);
  pdk_free_aligned(im->s0_next);
  pdk_free_aligned(im->w);
  free(im->block_energy);
  pdk_bond_data_free(&im->bd);
  free(im);
  m->impl = NULL;
}

const pdk_model_ops pdk_model_ops_lps = {lps_setup, lps_force, lps_destroy};

const double *pdk_model_lps_energy_density(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_lps || !m->impl) return NULL;
  return ((lps_impl *)m->impl)->w;
}
