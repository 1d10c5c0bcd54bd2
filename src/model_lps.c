/* Ordinary state-based LPS model, as LAMMPS peri/lps: driver over kernels/ref/lps.c.
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

  const pdk_bond_index *bond_start = pdk_families_bond_start(m->fam);
  const pdk_index *bond_j = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *Z = dim == 3 ? pdk_particles_X(p, 2) : NULL;
  const double *volume = pdk_particles_volume(p);
  double *mw = pdk_particles_field_data(p, "m", 0);
  double *inv_m = im->inv_m;
#pragma omp parallel for default(none) schedule(static) num_threads(ctx->num_threads)              \
    shared(num_blocks, n, dim, k, bond_start, bond_j, X, Y, Z, volume, mw, inv_m)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    pdk_index i0, i1;
    block_range(blk, n, &i0, &i1);
    if (dim == 3)
      pdk_kernel_lps_weighted_volume3_ref(i0, i1, bond_start, bond_j, X, Y, Z, volume, k, mw);
    else
      pdk_kernel_lps_weighted_volume2_ref(i0, i1, bond_start, bond_j, X, Y, volume, k, mw);
    for (pdk_index i = i0; i < i1; ++i)
      inv_m[i] = mw[i] > 0 ? 1.0 / mw[i] : 0.0;
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
  const int dim = im->dim;
  const pdk_index n = im->n;
  const int64_t num_blocks = im->num_blocks;
  const pdk_lps_consts *k = &im->k;
  const pdk_bond_index *bond_start = pdk_families_bond_start(m->fam);
  const pdk_index *bond_j = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *Z = dim == 3 ? pdk_particles_X(p, 2) : NULL;
  const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  const double *z = dim == 3 ? pdk_particles_field_data(p, "x", 2) : NULL;
  double *fx = pdk_particles_field_data(p, "f", 0), *fy = pdk_particles_field_data(p, "f", 1);
  double *fz = dim == 3 ? pdk_particles_field_data(p, "f", 2) : NULL;
  double *theta = pdk_particles_field_data(p, "theta", 0);
  const double *volume = pdk_particles_volume(p);
  PDK_CHECK(x && y && fx && fy && theta && (dim == 2 || (z && fz)), ctx, PDK_ERR_NOT_FOUND,
            "lps model: fields \"x\", \"f\" or \"theta\" are missing from the particle store");
  const double *inv_m = im->inv_m;
  uint8_t *alive = m->bond_alive;
  const double *s0 = m->s0;
  double *s0_next = commit && alive && s0 ? im->s0_next : NULL;
  double *w = energy ? im->w : NULL;
  double *block_energy = im->block_energy;
  pdk_bond_index broken = 0;

#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, dim, k, bond_start, bond_j, X, Y, Z, x, y, z, volume, theta, inv_m,      \
               alive, s0, s0_next, fx, fy, fz, w, block_energy)
  {
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0, i1;
      block_range(blk, n, &i0, &i1);
      if (dim == 3)
        pdk_kernel_lps_dilation3_ref(i0, i1, bond_start, bond_j, X, Y, Z, x, y, z, volume, k, alive,
                                     inv_m, theta);
      else
        pdk_kernel_lps_dilation2_ref(i0, i1, bond_start, bond_j, X, Y, x, y, volume, k, alive,
                                     inv_m, theta);
    } /* implicit barrier: every theta is complete before any force is computed */
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0, i1;
      block_range(blk, n, &i0, &i1);
      if (dim == 3)
        broken += pdk_kernel_lps_force3_ref(i0, i1, bond_start, bond_j, X, Y, Z, x, y, z, volume, k,
                                            theta, inv_m, alive, s0, s0_next, fx, fy, fz, w);
      else
        broken += pdk_kernel_lps_force2_ref(i0, i1, bond_start, bond_j, X, Y, x, y, volume, k,
                                            theta, inv_m, alive, s0, s0_next, fx, fy, w);
      if (w) {
        double e = 0.0;
        for (pdk_index i = i0; i < i1; ++i)
          e += volume[i] * w[i];
        block_energy[blk] = e;
      }
    }
  }

  pdk_bond_pass_finish(m, &im->s0_next, s0_next != NULL, broken, block_energy, num_blocks, energy);
  return PDK_SUCCESS;
}

static void lps_destroy(pdk_model *m) {
  lps_impl *im = m->impl;
  if (!im) return;
  pdk_free_aligned(im->inv_m);
  pdk_free_aligned(im->s0_next);
  pdk_free_aligned(im->w);
  free(im->block_energy);
  free(im);
  m->impl = NULL;
}

const pdk_model_ops pdk_model_ops_lps = {lps_setup, lps_force, lps_destroy};

const double *pdk_model_lps_energy_density(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_lps || !m->impl) return NULL;
  return ((lps_impl *)m->impl)->w;
}
