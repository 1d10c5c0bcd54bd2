/* Ordinary state-based LPS model, as LAMMPS peri/lps: driver over the context's kernel table
 * (reference kernels/ref/lps.c; SIMD variants kernels/opt/bond_*.c over packed rows, see
 * src/models/model_pmb.c). precision float: bond lengths stored per bond as floats, m_i computed
 * from them.
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
 * (e - theta r0/2)^2 beta V (Queiruga & Moridis 2017 section 2.2; checked for isotropic,
 * uniaxial and shear strain against sigma = lambda tr(eps) I + 2 mu eps.) For an isotropic stretch
 * s, theta = 3s (2s) exactly for any family and W = 9/2 K s^2 (2 (lambda + mu) s^2).
 *
 * Passes: (1) dilation theta_i for every particle; (2) force, which gathers theta_j and 1/m_j of
 * the neighbours, and with commit = 1 applies the LAMMPS s0 rule (bonds broken in pass 2 take
 * effect from the next pass). Both passes run in one parallel region over fixed blocks of
 * PDK_LPS_BLOCK particles (static schedule, barrier between); the energy is summed per block and
 * the blocks in order, so results are bitwise the same for any thread count.
 *
 * Layout sell (opts.layout): both passes walk a sliced copy of the families (src/space/sell.h)
 * through the table's lps_dilation_sell and lps_force_sell, over blocks of PDK_LPS_BLOCK / C
 * slices, as src/models/model_pmb.c does for PMB (energy over the csr particle blocks after a
 * barrier; the copy's bond state refreshed when m->bond_state_version moved). The weighted volume
 * is computed once at set-up over the CSR families.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "kernels.h"
#include "model_bond.h"
#include "model_impl.h"
#include "space/sell.h"
#include "model_stencil.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define PDK_LPS_BLOCK 1024 /* particles per block: kernel call and energy partial sum */

typedef struct lps_impl {
  pdk_lps_consts k;
  int dim;
  pdk_index n;
  int64_t num_blocks;
  double *inv_m;        /* [n_pad] 1/m_i, 0 for an empty family */
  double *s0_next;      /* [n_pad] when bonds can break */
  double *w;            /* [n_pad] strain energy density, allocated on first request */
  double *fix;          /* [n_pad] lps_fix_energy's differences, allocated on first use */
  double *block_energy; /* [num_blocks] */
  pdk_bond_data bd;     /* packed rows (extra column: 1/m), float bond lengths */
  /* analytic tangent, allocated on first use: q_i = theta_i / m_i and
   * s_i = sum_b alive_b beta V_j eta_b / |eta_b| at the x of the last tangent_prepare */
  double *tan_q;    /* [n] */
  double *tan_s[3]; /* [n] per component */
  int use_sell;     /* layout sell: the passes walk `sell` (src/space/sell.h) */
  pdk_sell sell;
  unsigned long sell_version; /* m->bond_state_version sell.alive was last synced with */
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
  PDK_CALL(pdk_bond_book_setup(m));
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
  /* model.stencil: the lattice layout (src/models/model_stencil.c) with this model's 1/m per site
   */
  PDK_CALL(pdk_stencil_model_setup(m, im->bd.bond_r0, 0));
  if (m->stencil) {
    PDK_CALL(pdk_stencil_lps_setup(m, m->stencil, im->inv_m));
    pdk_bond_data_free(&im->bd); /* neither rows nor per-bond lengths are read any more */
  }
  if (m->opts.layout == PDK_LAYOUT_SELL && !m->stencil) { /* the stencil path, when taken, wins */
    PDK_CALL(pdk_sell_build(ctx, m->fam, ctx->kernels.sell_width, m->opts.sell_sigma, m->bond_alive,
                            im->bd.bond_r0, &im->sell));
    im->use_sell = 1;
    im->sell_version = m->bond_state_version;
  }
  if (!m->stencil && !im->use_sell) PDK_CALL(pdk_bond_data_store_lengths(m, &im->bd, "lps"));
  return PDK_SUCCESS;
}

/* The general path on several ranks (src/models/model_ranks.c): the dilatations of this rank's
 * rows, exchanged (the force rows read their neighbours'), then its force rows, exchanged; the
 * energy blocks summed from the exchanged densities, as on one rank. */
static int lps_pass_ranked(pdk_model *m, const pdk_bond_arrays *a, int commit, double *energy) {
  pdk_ctx *ctx = m->ctx;
  lps_impl *im = m->impl;
  const pdk_index n = im->n, lo = m->row_lo, hi = m->row_hi;
  const int64_t num_blocks = im->num_blocks;
  const pdk_lps_consts *k = &im->k;
  const pdk_bond_data *bd = &im->bd;
  const pdk_lps_dilation_fn dilation = ctx->kernels.lps_dilation;
  const pdk_lps_force_fn force = ctx->kernels.lps_force;
  const int pack = bd->cur4 != NULL;
  const double *volume = a->volume, *w = a->w;
  double *block_energy = im->block_energy;
  pdk_bond_index broken = 0;
#pragma omp parallel default(none) num_threads(ctx->num_threads)                                 \
    shared(num_blocks, n, k, a, bd, dilation, pack, lo, hi)
  {
    if (pack) pdk_bond_pack_cur_blocks(bd, a, n, PDK_LPS_BLOCK); /* barrier: rows packed */
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0, i1;
      block_range(blk, n, &i0, &i1);
      if (i0 < lo) i0 = lo;
      if (i1 > hi) i1 = hi;
      if (i0 < i1) dilation(k, a, i0, i1);
    }
  }
  PDK_CALL(pdk_model_ranks_gather(m, a->theta_out));
#pragma omp parallel for default(none) num_threads(ctx->num_threads) reduction(+ : broken)       \
    schedule(static) shared(num_blocks, n, k, a, force, lo, hi)
  for (int64_t blk = 0; blk < num_blocks; ++blk) {
    pdk_index i0, i1;
    block_range(blk, n, &i0, &i1);
    if (i0 < lo) i0 = lo;
    if (i1 > hi) i1 = hi;
    if (i0 < i1) broken += force(k, a, i0, i1);
  }
  PDK_CALL(pdk_model_ranks_finish(m, a->w, a->s0_next, &broken));
  if (w) {
#pragma omp parallel default(none) shared(n, volume, w, block_energy) num_threads(ctx->num_threads)
    pdk_bond_block_energies(volume, w, n, PDK_LPS_BLOCK, block_energy);
  }
  pdk_bond_pass_finish(m, &im->s0_next, a->s0_next != NULL, broken, block_energy, num_blocks,
                       energy);
  (void)commit;
  return PDK_SUCCESS;
}

static int lps_pass(pdk_model *m, int commit, double *energy) {
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
  if (m->stencil) {
    double *theta = pdk_particles_field_data(p, "theta", 0);
    PDK_CHECK(theta, ctx, PDK_ERR_NOT_FOUND,
              "lps model: field \"theta\" is missing from the particle store");
    double *s0_next = commit && m->bond_alive && m->s0 ? im->s0_next : NULL;
    double *w = energy ? im->w : NULL;
    pdk_bond_index broken = 0;
    PDK_CALL(pdk_stencil_lps_force(m, m->stencil, k, theta, s0_next, w, &broken));
    if (w) {
      const double *volume = pdk_particles_volume(p);
      double *block_energy = im->block_energy;
#pragma omp parallel default(none) shared(n, volume, w, block_energy) num_threads(ctx->num_threads)
      pdk_bond_block_energies(volume, w, n, PDK_LPS_BLOCK, block_energy);
    }
    pdk_bond_pass_finish(m, &im->s0_next, s0_next != NULL, broken, im->block_energy, num_blocks,
                         energy);
    return PDK_SUCCESS;
  }
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
  if (im->use_sell) {
    if (im->sell_version != m->bond_state_version) {
      pdk_sell_sync_alive(ctx, &im->sell, m->fam, m->bond_alive);
      im->sell_version = m->bond_state_version;
    }
    const pdk_lps_dilation_sell_fn sdilation = ctx->kernels.lps_dilation_sell;
    const pdk_lps_force_sell_fn sforce = ctx->kernels.lps_force_sell;
    const pdk_sell_arrays *sa = &im->sell.a;
    const int64_t num_slices = im->sell.num_slices;
    const int64_t per_block = PDK_LPS_BLOCK / sa->width; /* slices per kernel call */
    const int64_t num_sblocks = (num_slices + per_block - 1) / per_block;
#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, k, a, bd, pack, volume, w, block_energy, sdilation, sforce, sa,          \
               num_slices, per_block, num_sblocks)
    {
      if (pack) pdk_bond_pack_cur_blocks(bd, a, n, PDK_LPS_BLOCK); /* barrier: rows packed */
#pragma omp for schedule(static)
      for (int64_t blk = 0; blk < num_sblocks; ++blk) {
        const int64_t s0 = blk * per_block;
        sdilation(k, a, sa, s0, s0 + per_block < num_slices ? s0 + per_block : num_slices);
      } /* implicit barrier: every theta is complete before any force is computed */
#pragma omp for schedule(static)
      for (int64_t blk = 0; blk < num_sblocks; ++blk) {
        const int64_t s0 = blk * per_block;
        broken += sforce(k, a, sa, s0, s0 + per_block < num_slices ? s0 + per_block : num_slices);
      } /* implicit barrier: the energy blocks below hold rows of any slice */
      if (w) pdk_bond_block_energies(volume, w, n, PDK_LPS_BLOCK, block_energy);
    }
    pdk_bond_pass_finish(m, &im->s0_next, arrays.s0_next != NULL, broken, block_energy, num_blocks,
                         energy);
    return PDK_SUCCESS;
  }

  if (m->row_start) return lps_pass_ranked(m, a, commit, energy);
#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, k, a, bd, dilation, force, pack, volume, w, block_energy)
  {
    if (pack) pdk_bond_pack_cur_blocks(bd, a, n, PDK_LPS_BLOCK); /* barrier: rows packed */
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

/* The energy whose gradient the LPS force is, with broken bonds too. The force (LAMMPS's, pdk's
 * kernels) is -grad of E = sum_i V_i W_i with
 *   W_i = c_dil theta_i^2 / (2 d) + c_dev / (2 m_i) sum_b alive_b e^2 / r0 beta V_j,
 * m_i the weighted volume of all bonds (fixed at setup, as LAMMPS's wvolume). The kernels report
 * W_i in the form e_bulk theta_i^2 / 2 + e_dev / m_i sum_b alive_b (e - theta_i r0 / d)^2 / r0
 * beta V_j (kernels/ref/lps.c), which equals it while i's family is intact but differs by
 *   W_i - W_kernel,i = e_dev theta_i^2 (m_i - m'_i) / (m_i d^2),
 *   m'_i = sum_b alive_b r0 beta V_j,
 * once i lost bonds (expand the square, use sum_b alive_b e beta V_j = theta_i m_i / d and the
 * constants of lps_setup: c_dil = d e_bulk - 2 e_dev / d, c_dev = 2 e_dev). lps_fix_energy adds
 * that difference for the particles whose family (in the state the pass read) lost bonds, so the
 * strain energy of a run with breaking is the force's potential and the energy account closes;
 * a particle with an intact family gets nothing, and a run in which no bond broke never gets
 * here. */

/* m'_i over i's bonds intact in `alive`, as the kernels compute r0 and beta. */
static double lps_row_volume(const pdk_model *m, const pdk_bond_arrays *a, pdk_index i,
                             const uint8_t *alive, double *all) {
  const lps_impl *im = m->impl;
  const pdk_bond_index *bs = a->bond_start;
  const pdk_index *bj = a->bond_j;
  const double *V = a->volume;
  const int float_r0 = m->opts.precision == PDK_PRECISION_FLOAT;
  const double *const *X = a->X;
  double sum = 0.0, sum_all = 0.0;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    double r0 = 0.0;
    for (int c = 0; c < im->dim; ++c) {
      const double d0 = X[c][j] - X[c][i];
      r0 += d0 * d0;
    }
    r0 = float_r0 ? (double)(float)sqrt(r0) : sqrt(r0); /* as bond_r0, also on the stencil path */
    const double t = r0 * V[j] * fmin(1.0, (im->k.vs_a - r0) * im->k.vs_b);
    sum_all += t;
    if (alive[b]) sum += t;
  }
  *all = sum_all;
  return sum;
}

/* After a pass that reported the energy with bond state `alive` (the state it read): W_i of
 * every particle whose family lost bonds (lost[i], one byte per particle: the pass costs a scan
 * of n bytes and the rows of those particles) gets the difference above, and *energy its sum
 * (V_i-weighted, in index order: the same bits for any thread count). */
static int lps_fix_energy(pdk_model *m, const uint8_t *alive, const uint8_t *lost, double *energy) {
  lps_impl *im = m->impl;
  const double *theta = pdk_particles_field_data(m->p, "theta", 0);
  const double *V = pdk_particles_volume(m->p);
  const pdk_index n = im->n;
  const double d2 = im->k.theta_factor * im->k.theta_factor, e_dev = im->k.e_dev;
  double *w = im->w, *fix = im->fix;
  const double *inv_m = im->inv_m;
  const pdk_model *mc = m;
  pdk_bond_arrays arrays;
  PDK_CALL(pdk_bond_book_arrays(m, &im->bd, &arrays));
  const pdk_bond_arrays *a = &arrays;
#pragma omp parallel for default(none) schedule(static) num_threads(m->ctx->num_threads)           \
    shared(theta, n, d2, e_dev, w, fix, inv_m, alive, lost, mc, a)
  for (pdk_index i = 0; i < n; ++i) {
    fix[i] = 0.0;
    if (!lost[i]) continue;
    double m_all;
    const double m_alive = lps_row_volume(mc, a, i, alive, &m_all);
    fix[i] = e_dev * theta[i] * theta[i] * inv_m[i] * (m_all - m_alive) / d2;
    w[i] += fix[i];
  }
  double sum = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    sum += V[i] * fix[i];
  *energy += sum;
  return PDK_SUCCESS;
}

/* W_i at the current x with bond state `alive` (the potential above, its dilatation from the same
 * state; families' bonds; src/models/model_bond_book.c). */
static double lps_row_energy(const pdk_model *m, const pdk_bond_arrays *a, pdk_index i,
                             const uint8_t *alive) {
  const lps_impl *im = m->impl;
  const pdk_lps_consts *k = &im->k;
  const int dim = im->dim;
  const pdk_bond_index *bs = a->bond_start;
  const pdk_index *bj = a->bond_j;
  const double *const *X = a->X, *const *x = a->x;
  const double *V = a->volume;
  const int float_r0 = m->opts.precision == PDK_PRECISION_FLOAT;
  const double inv_m_i = im->inv_m[i], d = k->theta_factor;
  double sum_e = 0.0, sum_e2 = 0.0;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    if (!alive[b]) continue;
    const pdk_index j = bj[b];
    double r0 = 0.0, r = 0.0;
    for (int c = 0; c < dim; ++c) {
      const double d0 = X[c][j] - X[c][i], d1 = x[c][j] - x[c][i];
      r0 += d0 * d0;
      r += d1 * d1;
    }
    r0 = float_r0 ? (double)(float)sqrt(r0) : sqrt(r0); /* as bond_r0, also on the stencil path */
    const double e = sqrt(r) - r0;
    const double vol = V[j] * fmin(1.0, (k->vs_a - r0) * k->vs_b);
    sum_e += e * vol;
    sum_e2 += e * e / r0 * vol;
  }
  const double theta = d * inv_m_i * sum_e;
  return k->c_dil * theta * theta / (2.0 * d) + 0.5 * k->c_dev * inv_m_i * sum_e2;
}

/* A pass, with the energy the breaks release booked (src/models/model_bond_book.c) and, once
 * bonds broke, the strain energy made the force's potential (above). */
static int lps_force(pdk_model *m, int commit, double *energy) {
  lps_impl *im = m->impl;
  const int book = commit && m->book_prev; /* bonds can break: book their energy */
  pdk_bond_arrays a; /* the geometry the booking reads, fetched once per pass */
  if (book) PDK_CALL(pdk_bond_book_arrays(m, &im->bd, &a));
  if (book) PDK_CALL(pdk_bond_book_start(m, &a, lps_row_energy));
  const pdk_bond_index before = m->num_broken;
  PDK_CALL(lps_pass(m, commit, energy));
  /* the state the pass read: book_prev after book_start in a committing pass, else bond_alive */
  if (energy && before > 0) {
    if (!im->fix) {
      im->fix = pdk_alloc_aligned((size_t)pdk_particles_count_padded(m->p), sizeof(double));
      PDK_CHECK(im->fix, m->ctx, PDK_ERR_MEMORY, "lps model: out of memory for %d particles",
                (int)im->n);
    }
    /* book_lost marks the families of that state with a broken bond until book_end */
    PDK_CALL(lps_fix_energy(m, commit ? m->book_prev : m->bond_alive, m->book_lost, energy));
  }
  if (book) PDK_CALL(pdk_bond_book_end(m, &a, m->num_broken - before, lps_row_energy));
  return PDK_SUCCESS;
}

static void lps_destroy(pdk_model *m) {
  lps_impl *im = m->impl;
  if (!im) return;
  pdk_free_aligned(im->inv_m);
  pdk_free_aligned(im->s0_next);
  pdk_free_aligned(im->w);
  pdk_free_aligned(im->fix);
  free(im->block_energy);
  free(im->tan_q);
  for (int c = 0; c < 3; ++c)
    free(im->tan_s[c]);
  pdk_bond_data_free(&im->bd);
  pdk_sell_free(&im->sell);
  free(im);
  m->impl = NULL;
}

/* ---- analytic tangent (the Newton solver's, see pdk_model_ops) --------------------------------
 *
 * For a bond b of particle a to j (kernels/ref/lps.c): nu_b = alive_b beta V_j, eta = x_j - x_a,
 * r = |eta|, n = eta / r, e = r - r0, q_a = theta_a / m_a, P = 1/m_a + 1/m_j,
 *   f_a = sum_b nu_b T_b n / r0,   T_b = c_dil (q_a + q_j) r0 + c_dev P e,
 *   theta_a = d / m_a sum_b nu_b e.
 * Differentiating, with dn = (I - n n^T) deta / r:
 *   df_a = sum_b nu_b H_b deta_b + c_dil (s_a / m_a) dtheta_a + c_dil sum_b nu_b n_b dtheta_j /
 * m_j, H_b = (c_dev P n n^T + T_b / r (I - n n^T)) / r0,   s_a = sum_b nu_b n_b, dtheta_a = d / m_a
 * sum_b nu_b n_b . deta_b. The column of particle i (K = -d(V f)/dx, deta_b = dx_j - dx_a): local,
 * per bond b of i to j:  K[i,i] += V_i nu_b H_b,  K[j,i] -= V_j nu'_b H_b (nu'_b: the bond j -> i
 * from j's end, beta V_i and its own state; H is the same from both ends); dilatation, per particle
 * p whose theta depends on x_i (p = i, and every j whose bond j -> i is intact) with g_p = dtheta_p
 * / dx_i (g_i = -d s_i / m_i, g_j = d nu'_b n_ji / m_j): K[p, i] -= V_p c_dil s_p g_p^T / m_p,  and
 * for every bond p -> a, with nu_ap the bond a -> p from a's end (beta V_p, its state): K[a, i] +=
 * V_a c_dil nu_ap n_pa g_p^T / m_p (a bond a -> p pulls a along n_ap = -n_pa). Rows reach 2 hops:
 * the coupling of the pattern. Bonds with r = 0 carry no force and no dilatation derivative (n
 * undefined), as in the pass. */
static int lps_tangent_prepare(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  lps_impl *im = m->impl;
  const int dim = im->dim;
  const pdk_index n = im->n;
  if (!im->tan_q) {
    im->tan_q = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    for (int c = 0; c < dim; ++c)
      im->tan_s[c] = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    PDK_CHECK(im->tan_q && im->tan_s[0] && im->tan_s[1] && (dim < 3 || im->tan_s[2]), ctx,
              PDK_ERR_MEMORY, "lps model: out of memory for the tangent of %d particles", (int)n);
  }
  pdk_bond_arrays arrays;
  PDK_CALL(pdk_bond_book_arrays(m, &im->bd, &arrays));
  const pdk_bond_index *bs = arrays.bond_start;
  const pdk_index *bj = arrays.bond_j;
  const double *const *X = arrays.X, *const *x = arrays.x;
  const double *V = arrays.volume;
  const float *bond_r0 = arrays.bond_r0;
  const uint8_t *alive = m->bond_alive;
  const pdk_lps_consts *k = &im->k;
  const double *inv_m = im->inv_m;
  double *tq = im->tan_q, *ts0 = im->tan_s[0], *ts1 = im->tan_s[1], *ts2 = im->tan_s[2];
#pragma omp parallel for default(none) schedule(static) num_threads(ctx->num_threads)              \
    shared(n, dim, bs, bj, X, x, V, bond_r0, alive, k, inv_m, tq, ts0, ts1, ts2)
  for (pdk_index i = 0; i < n; ++i) {
    double sum = 0.0, sv[3] = {0, 0, 0};
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      double xi2 = 0.0, r2 = 0.0, eta[3] = {0, 0, 0};
      for (int c = 0; c < dim; ++c) {
        const double dX = X[c][j] - X[c][i];
        eta[c] = x[c][j] - x[c][i];
        xi2 += dX * dX;
        r2 += eta[c] * eta[c];
      }
      const double r0 = bond_r0 ? (double)bond_r0[b] : sqrt(xi2);
      const double r = sqrt(r2);
      const double nu =
          (alive ? (double)alive[b] : 1.0) * V[j] * fmin(1.0, (k->vs_a - r0) * k->vs_b);
      sum += nu * (r - r0);
      if (r > 0.0)
        for (int c = 0; c < dim; ++c)
          sv[c] += nu * eta[c] / r;
    }
    tq[i] = k->theta_factor * inv_m[i] * sum * inv_m[i];
    ts0[i] = sv[0];
    ts1[i] = sv[1];
    if (dim == 3) ts2[i] = sv[2];
  }
  return PDK_SUCCESS;
}

/* Bond b of particle a (neighbour j): unit vector n, lengths, and nu from a's end. */
typedef struct lps_bond_geom {
  double n[3], r, r0, nu;
} lps_bond_geom;

static inline void lps_bond(const lps_impl *im, const pdk_model *m, const double *const *X,
                            const double *const *x, pdk_index a, pdk_bond_index b, pdk_index j,
                            lps_bond_geom *g) {
  const int dim = im->dim;
  double xi2 = 0.0, r2 = 0.0;
  g->n[0] = g->n[1] = g->n[2] = 0.0;
  for (int c = 0; c < dim; ++c) {
    const double dX = X[c][j] - X[c][a];
    g->n[c] = x[c][j] - x[c][a];
    xi2 += dX * dX;
    r2 += g->n[c] * g->n[c];
  }
  g->r0 = im->bd.bond_r0 ? (double)im->bd.bond_r0[b] : sqrt(xi2);
  g->r = sqrt(r2);
  if (g->r > 0.0)
    for (int c = 0; c < dim; ++c)
      g->n[c] /= g->r;
  g->nu = (m->bond_alive ? (double)m->bond_alive[b] : 1.0) * pdk_particles_volume(m->p)[j] *
          fmin(1.0, (im->k.vs_a - g->r0) * im->k.vs_b);
}

/* State of the bond j -> i seen from j (1 without bond state; 0 if j's family lacks i). */
static inline double lps_reverse_on(const pdk_model *m, const pdk_bond_index *bs,
                                    const pdk_index *bj, pdk_index i, pdk_index j) {
  if (!m->bond_alive) return 1.0;
  const pdk_bond_index rb = pdk_bond_reverse(bs, bj, i, j);
  return rb >= 0 ? (double)m->bond_alive[rb] : 0.0;
}

/* K[p, i] and K[a, i] of the dilatation of p (gradient g with respect to x_i), see above. */
static void lps_dilatation_rows(const lps_impl *im, const pdk_model *m, const double *const *X,
                                const double *const *x, pdk_index p, const double *g,
                                const pdk_index *loc, double *block) {
  const int dim = im->dim;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *V = pdk_particles_volume(m->p);
  const double c_dil = im->k.c_dil, inv_m_p = im->inv_m[p];
  const double sp[3] = {im->tan_s[0][p], im->tan_s[1][p], dim == 3 ? im->tan_s[2][p] : 0.0};
  double *Kp = block + (size_t)loc[p] * dim * dim;
  const double wp = -V[p] * c_dil * inv_m_p;
  for (int e = 0; e < dim; ++e)
    for (int c = 0; c < dim; ++c)
      Kp[e * dim + c] += wp * sp[e] * g[c];
  for (pdk_bond_index b = bs[p]; b < bs[p + 1]; ++b) {
    const pdk_index a = bj[b];
    lps_bond_geom gb;
    lps_bond(im, m, X, x, p, b, a, &gb);
    if (!(gb.r > 0.0)) continue;
    /* nu of the bond a -> p from a's end: beta (same r0) V_p and the state of that bond */
    const double nu_ap =
        lps_reverse_on(m, bs, bj, p, a) * V[p] * fmin(1.0, (im->k.vs_a - gb.r0) * im->k.vs_b);
    const double wa = V[a] * c_dil * nu_ap * inv_m_p;
    double *Ka = block + (size_t)loc[a] * dim * dim;
    for (int e = 0; e < dim; ++e)
      for (int c = 0; c < dim; ++c)
        Ka[e * dim + c] += wa * gb.n[e] * g[c];
  }
}

static void lps_tangent_column(const pdk_model *m, pdk_index i, const pdk_index *loc,
                               double *block) {
  const lps_impl *im = m->impl;
  const int dim = im->dim;
  const pdk_lps_consts *k = &im->k;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X[3] = {NULL, NULL, NULL}, *x[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    X[c] = pdk_particles_X(m->p, c);
    x[c] = pdk_particles_field_data(m->p, "x", c);
  }
  const double *V = pdk_particles_volume(m->p);
  const double *inv_m = im->inv_m, *q = im->tan_q, d = k->theta_factor;
  double *Kii = block + (size_t)loc[i] * dim * dim;
  /* local terms and the dilatations of the neighbours */
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    lps_bond_geom gb;
    lps_bond(im, m, X, x, i, b, j, &gb);
    if (!(gb.r > 0.0)) continue;
    const double on_j = lps_reverse_on(m, bs, bj, i, j);
    const double nu_j = on_j * V[i] * fmin(1.0, (k->vs_a - gb.r0) * k->vs_b); /* j -> i */
    const double P = inv_m[i] + inv_m[j];
    const double T = k->c_dil * (q[i] + q[j]) * gb.r0 + k->c_dev * P * (gb.r - gb.r0);
    const double a_nn = (k->c_dev * P - T / gb.r) / gb.r0, a_id = T / (gb.r * gb.r0);
    const double wi = V[i] * gb.nu, wj = -V[j] * nu_j;
    double *Kji = block + (size_t)loc[j] * dim * dim;
    for (int e = 0; e < dim; ++e)
      for (int c = 0; c < dim; ++c) {
        const double H = (e == c ? a_id : 0.0) + a_nn * gb.n[e] * gb.n[c];
        Kii[e * dim + c] += wi * H;
        Kji[e * dim + c] += wj * H;
      }
    if (k->c_dil != 0.0 && nu_j != 0.0) {
      /* theta_j depends on x_i through its bond j -> i: n_ji = -n */
      double g[3];
      for (int c = 0; c < dim; ++c)
        g[c] = -d * inv_m[j] * nu_j * gb.n[c];
      lps_dilatation_rows(im, m, X, x, j, g, loc, block);
    }
  }
  if (k->c_dil != 0.0) { /* theta_i depends on x_i through every bond of i */
    double g[3];
    for (int c = 0; c < dim; ++c)
      g[c] = -d * inv_m[i] * im->tan_s[c][i];
    lps_dilatation_rows(im, m, X, x, i, g, loc, block);
  }
}

const pdk_model_ops pdk_model_ops_lps = {.setup = lps_setup,
                                         .force = lps_force,
                                         .destroy = lps_destroy,
                                         .tangent_prepare = lps_tangent_prepare,
                                         .tangent_column = lps_tangent_column,
                                         .padding_fraction = pdk_model_lps_padding_fraction,
                                         .float_bond_lengths = 1,
                                         .layout_sell = 1,
                                         .partial_volumes = 1,
                                         .ranks = 1};

double pdk_model_lps_padding_fraction(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_lps || !m->impl) return 0.0;
  const lps_impl *im = m->impl;
  return im->use_sell ? pdk_sell_padding_fraction(&im->sell) : 0.0;
}

const double *pdk_model_lps_energy_density(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_lps || !m->impl) return NULL;
  return ((lps_impl *)m->impl)->w;
}

static const pdk_model_ops *lps_ops_for(const pdk_model_opts *o) {
  return o->lps_use_influence ? &pdk_model_ops_dil2 : &pdk_model_ops_lps;
}

/* The stencil path implements LAMMPS's influence function only. */
static int lps_no_stencil(const pdk_model_opts *o) { return o->lps_use_influence; }

const pdk_model_kind_info pdk_model_kind_lps = {
    .kind = PDK_MODEL_LPS,
    .name = "lps",
    .caps = PDK_KIND_SCENE | PDK_KIND_SHEAR | PDK_KIND_STENCIL | PDK_KIND_FLOAT | PDK_KIND_TANGENT,
    .hops = 2,
    .scene_stabilization = PDK_STAB_NONE,
    .mem_point = 640,
    .mem_bond = 8,
    .mem_bond_float = 12,
    .mem_bond_lengths = 8,
    .mem_newton_bond = 100,
    .ops_for = lps_ops_for,
    .no_stencil = lps_no_stencil};
