/* Bond-based PMB model, as LAMMPS peri/pmb: driver over the context's kernel table (reference
 * kernels/ref/pmb.c; SIMD variants kernels/opt/bond_*.c over packed rows, src/models/model_bond.c).
 * precision float: bond lengths stored per bond as floats (kernels/kernels.h, pdk_bond_arrays).
 *
 * Constants. LAMMPS takes the micromodulus c from the user; pdk derives it from the bulk modulus K
 * and the horizon delta by matching the continuum strain energy density of an isotropic stretch s
 * (W = 1/4 integral over the horizon of c s^2 |xi| dV):
 *   3-D:          W = c pi delta^4 s^2 / 4  = 9/2 K s^2               ->  c = 18 K / (pi delta^4)
 *   plane strain: W = c pi delta^3 s^2 / 6  = 2 (lambda + mu) s^2     ->  c = 72 K / (5 pi delta^3)
 * A pair potential fixes the Poisson ratio: 1/4 in 3-D and in plane strain, so lambda = mu and
 * K = lambda + 2 mu/3 = 5 mu/3, lambda + mu = 6 K / 5 (the 2-D c is 48 E / (5 pi delta^3), the
 * known plane-strain value). The shear modulus option is ignored. In 2-D the sum over the family
 * runs over volumes V_j = area x t (t = opts.thickness), so the integral above carries a factor t
 * and c is divided by it: c = 72 K / (5 pi delta^3 t) (LPS needs nothing: m normalises).
 *
 * Partial volumes: opts.lattice_constant > 0 turns on LAMMPS's vfrac_scale (kernels/ref/pmb.c).
 * Bond failure: opts.critical_stretch > 0 turns on the LAMMPS s0 rule; model.c owns bond_alive and
 * s0, this driver keeps the second s0 buffer (written by a committing pass, then swapped in).
 *
 * Threads: one parallel region per pass, over fixed blocks of PDK_PMB_BLOCK particles with a
 * static schedule (first the packed rows, when the table reads them, then a barrier). Each block
 * calls the kernel on its particles and, when the energy is wanted, sums V_i W_i over the block
 * into its own slot; the slots are summed in block order afterwards. Every particle's force depends
 * only on its own row, so results are bitwise the same for any thread count.
 *
 * Layout sell (opts.layout): the pass walks a sliced copy of the families (src/space/sell.h)
 * through the table's pmb_force_sell, over blocks of PDK_PMB_BLOCK / C slices; the energy partials
 * are then summed over the same particle blocks as csr's, after a barrier (a slice's rows are
 * spread over its sorting window). The copy's bond state is kept equal to bond_alive by the kernels
 * and refreshed from it when m->bond_state_version moved (checkpoint restore).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
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

#define PDK_PMB_BLOCK 1024 /* particles per block: kernel call and energy partial sum */

typedef struct pmb_impl {
  pdk_pmb_consts k;
  int dim;
  pdk_index n;
  int64_t num_blocks;
  double *s0_next;      /* [n_pad] when bonds can break */
  double *w;            /* [n_pad] strain energy density, allocated on first request */
  double *block_energy; /* [num_blocks] */
  pdk_bond_data bd;     /* packed rows, float bond lengths */
  double *c_particle;   /* [n_pad] multi-material micromodulus per particle, or NULL */
  int use_sell;         /* layout sell: the pass walks `sell` */
  pdk_sell sell;
  unsigned long sell_version; /* m->bond_state_version sell.alive was last synced with */
} pmb_impl;

/* Partial-volume constants shared by PMB and LPS: beta = min(1, (vs_a - r0) * vs_b). */
static void partial_volume_consts(double delta, double lattice, double *vs_a, double *vs_b) {
  if (lattice > 0) {
    double half = 0.5 * lattice;
    *vs_a = delta + half;
    *vs_b = 1.0 / (2.0 * half);
  } else {
    *vs_a = HUGE_VAL;
    *vs_b = 1.0;
  }
}

/* The micromodulus of bulk modulus K (the header); 2-D divides by the out-of-plane thickness the
 * particle volumes include. */
static double pmb_micromodulus(int dim, double K, double delta, double thickness) {
  return dim == 3 ? 18.0 * K / (M_PI * delta * delta * delta * delta)
                  : 72.0 * K / (5.0 * M_PI * delta * delta * delta * thickness);
}

static int pmb_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  const pdk_model_opts *o = &m->opts;
  pmb_impl *im = calloc(1, sizeof *im);
  PDK_CHECK(im, ctx, PDK_ERR_MEMORY, "out of memory creating the pmb model");
  m->impl = im;
  im->dim = pdk_particles_dim(m->p);
  im->n = pdk_particles_count(m->p);
  im->num_blocks = ((int64_t)im->n + PDK_PMB_BLOCK - 1) / PDK_PMB_BLOCK;
  const double delta = pdk_families_horizon(m->fam);
  PDK_CHECK(isfinite(delta) && delta > 0, ctx, PDK_ERR_ARG,
            "pmb model: the families' horizon must be positive, got %g", delta);
  im->k.c = pmb_micromodulus(im->dim, o->bulk_modulus, delta, o->thickness);
  if (m->mat_bulk) { /* multi-material: bond i-j takes the series value of c_i and c_j */
    im->c_particle = pdk_alloc_aligned((size_t)pdk_particles_count_padded(m->p), sizeof(double));
    PDK_CHECK(im->c_particle, ctx, PDK_ERR_MEMORY, "pmb model: out of memory for micromoduli");
    for (pdk_index i = 0; i < im->n; ++i)
      im->c_particle[i] = pmb_micromodulus(im->dim, m->mat_bulk[i], delta, o->thickness);
    im->k.c_particle = im->c_particle;
  }
  partial_volume_consts(delta, o->lattice_constant, &im->k.vs_a, &im->k.vs_b);
  im->k.s00 = o->critical_stretch;
  im->k.alpha = o->alpha;
  if (m->bond_alive && m->s0) {
    im->s0_next = pdk_alloc_aligned((size_t)pdk_particles_count_padded(m->p), sizeof(double));
    PDK_CHECK(im->s0_next, ctx, PDK_ERR_MEMORY,
              "pmb model: out of memory for %d critical stretches", (int)im->n);
  }
  im->block_energy = calloc((size_t)(im->num_blocks > 0 ? im->num_blocks : 1), sizeof(double));
  PDK_CHECK(im->block_energy, ctx, PDK_ERR_MEMORY, "pmb model: out of memory for energy blocks");
  PDK_CALL(pdk_bond_data_setup(m, &im->bd, "pmb"));
  PDK_CALL(pdk_bond_book_setup(m));
  PDK_CALL(pdk_stencil_model_setup(m, im->bd.bond_r0, im->c_particle != NULL));
  /* the stencil pass reads neither the packed rows nor the per-bond float lengths */
  if (m->stencil) pdk_bond_data_free(&im->bd);
  if (o->layout == PDK_LAYOUT_SELL && !m->stencil) { /* the stencil path, when taken, wins */
    PDK_CALL(pdk_sell_build(ctx, m->fam, ctx->kernels.sell_width, o->sell_sigma, m->bond_alive,
                            im->bd.bond_r0, &im->sell));
    im->use_sell = 1;
    im->sell_version = m->bond_state_version;
  }
  if (!m->stencil && !im->use_sell) PDK_CALL(pdk_bond_data_store_lengths(m, &im->bd, "pmb"));
  return PDK_SUCCESS;
}

static int pmb_pass(pdk_model *m, int commit, double *energy) {
  pdk_ctx *ctx = m->ctx;
  pmb_impl *im = m->impl;
  pdk_particles *p = m->p;
  if (energy && !im->w) {
    im->w = pdk_alloc_aligned((size_t)pdk_particles_count_padded(p), sizeof(double));
    PDK_CHECK(im->w, ctx, PDK_ERR_MEMORY, "pmb model: out of memory for the energy densities");
  }
  const pdk_index n = im->n;
  const int64_t num_blocks = im->num_blocks;
  const pdk_pmb_consts *k = &im->k;
  if (m->stencil) {
    double *s0_next = commit && m->bond_alive && m->s0 ? im->s0_next : NULL;
    double *w = energy ? im->w : NULL;
    pdk_bond_index broken = 0;
    PDK_CALL(pdk_stencil_pmb_force(m, m->stencil, k, s0_next, w, &broken));
    if (w) {
      const double *volume = pdk_particles_volume(p);
      double *block_energy = im->block_energy;
#pragma omp parallel default(none) shared(n, volume, w, block_energy) num_threads(ctx->num_threads)
      pdk_bond_block_energies(volume, w, n, PDK_PMB_BLOCK, block_energy);
    }
    pdk_bond_pass_finish(m, &im->s0_next, s0_next != NULL, broken, im->block_energy, num_blocks,
                         energy);
    return PDK_SUCCESS;
  }
  pdk_bond_arrays arrays;
  PDK_CHECK(pdk_bond_arrays_get(m, &im->bd, &arrays), ctx, PDK_ERR_NOT_FOUND,
            "pmb model: fields \"x\" and \"f\" are missing from the particle store");
  arrays.s0_next = commit && m->bond_alive && m->s0 ? im->s0_next : NULL;
  arrays.w = energy ? im->w : NULL;
  const pdk_bond_arrays *a = &arrays;
  const pdk_bond_data *bd = &im->bd;
  /* A multi-material body takes the reference kernel: only it reads the per-particle micromoduli
   * (the SIMD kernels use the one constant c). */
  const pdk_pmb_force_fn kernel =
      im->c_particle ? pdk_kernel_pmb_force_ref : ctx->kernels.pmb_force;
  const int pack = bd->cur4 != NULL && !im->c_particle;
  const double *volume = a->volume, *w = a->w;
  double *block_energy = im->block_energy;
  pdk_bond_index broken = 0;
  if (im->use_sell) {
    if (im->sell_version != m->bond_state_version) {
      pdk_sell_sync_alive(ctx, &im->sell, m->fam, m->bond_alive);
      im->sell_version = m->bond_state_version;
    }
    const pdk_pmb_force_sell_fn skernel = ctx->kernels.pmb_force_sell;
    const pdk_sell_arrays *sa = &im->sell.a;
    const int64_t num_slices = im->sell.num_slices;
    const int64_t per_block = PDK_PMB_BLOCK / sa->width; /* slices per kernel call */
    const int64_t num_sblocks = (num_slices + per_block - 1) / per_block;
#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, k, a, bd, pack, volume, w, block_energy, skernel, sa, num_slices,        \
               per_block, num_sblocks)
    {
      if (pack) pdk_bond_pack_cur_blocks(bd, a, n, PDK_PMB_BLOCK); /* barrier: rows packed */
#pragma omp for schedule(static)
      for (int64_t blk = 0; blk < num_sblocks; ++blk) {
        const int64_t s0 = blk * per_block;
        const int64_t s1 = s0 + per_block < num_slices ? s0 + per_block : num_slices;
        broken += skernel(k, a, sa, s0, s1);
      } /* implicit barrier: the energy blocks below hold rows of any slice */
      if (w) pdk_bond_block_energies(volume, w, n, PDK_PMB_BLOCK, block_energy);
    }
    pdk_bond_pass_finish(m, &im->s0_next, arrays.s0_next != NULL, broken, block_energy, num_blocks,
                         energy);
    return PDK_SUCCESS;
  }

  /* several ranks (src/models/model_ranks.c): this rank's rows [lo, hi), then the exchange */
  const int ranked = m->row_start != NULL;
  const pdk_index lo = ranked ? m->row_lo : 0, hi = ranked ? m->row_hi : n;
#pragma omp parallel default(none) num_threads(ctx->num_threads) reduction(+ : broken)           \
    shared(num_blocks, n, k, a, bd, kernel, pack, volume, w, block_energy, ranked, lo, hi)
  {
    if (pack) pdk_bond_pack_cur_blocks(bd, a, n, PDK_PMB_BLOCK); /* barrier: rows packed */
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      pdk_index i0 = (pdk_index)(blk * PDK_PMB_BLOCK);
      pdk_index i1 = (pdk_index)(i0 + PDK_PMB_BLOCK < (int64_t)n ? i0 + PDK_PMB_BLOCK : n);
      if (i0 < lo) i0 = lo;
      if (i1 > hi) i1 = hi;
      if (i0 < i1) broken += kernel(k, a, i0, i1);
      if (w && !ranked) block_energy[blk] = pdk_bond_block_energy(volume, w, i0, i1);
    }
  }
  if (ranked) {
    PDK_CALL(pdk_model_ranks_finish(m, arrays.w, arrays.s0_next, &broken));
    if (w) {
#pragma omp parallel default(none) shared(n, volume, w, block_energy) num_threads(ctx->num_threads)
      pdk_bond_block_energies(volume, w, n, PDK_PMB_BLOCK, block_energy);
    }
  }

  pdk_bond_pass_finish(m, &im->s0_next, arrays.s0_next != NULL, broken, block_energy, num_blocks,
                       energy);
  return PDK_SUCCESS;
}

/* W_i at the current x with bond state `alive` (the force pass's energy of row i, with the
 * families' bonds; src/models/model_bond_book.c). */
static double pmb_row_energy(const pdk_model *m, const pdk_bond_arrays *a, pdk_index i,
                             const uint8_t *alive) {
  const pmb_impl *im = m->impl;
  const pdk_pmb_consts *k = &im->k;
  const int dim = im->dim;
  const pdk_bond_index *bs = a->bond_start;
  const pdk_index *bj = a->bond_j;
  const double *const *X = a->X, *const *x = a->x;
  const double *V = a->volume;
  const int float_r0 = m->opts.precision == PDK_PRECISION_FLOAT;
  const double *cp = k->c_particle;
  double wi = 0.0;
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
    r = sqrt(r);
    const double d = r - r0, q = r > 0.0 ? 1.0 / (r0 * r) : 0.0;
    const double vol = V[j] * fmin(1.0, (k->vs_a - r0) * k->vs_b);
    const double c_b = cp ? 2.0 * (cp[i] * cp[j]) / (cp[i] + cp[j]) : k->c;
    const double g = c_b * vol * d * q;
    wi += 0.25 * g * d * r; /* c s^2 r0 beta V_j / 4, as kernels/ref/pmb.c */
  }
  return wi;
}

/* A pass, with the energy of the bonds it breaks booked (src/models/model_bond_book.c). */
static int pmb_force(pdk_model *m, int commit, double *energy) {
  const pmb_impl *im = m->impl;
  const int book = commit && m->book_prev; /* bonds can break: book their energy */
  pdk_bond_arrays a; /* the geometry the booking reads, fetched once per pass */
  if (book) PDK_CALL(pdk_bond_book_arrays(m, &im->bd, &a));
  if (book) PDK_CALL(pdk_bond_book_start(m, &a, pmb_row_energy));
  const pdk_bond_index before = m->num_broken;
  PDK_CALL(pmb_pass(m, commit, energy));
  if (book) PDK_CALL(pdk_bond_book_end(m, &a, m->num_broken - before, pmb_row_energy));
  return PDK_SUCCESS;
}

static void pmb_destroy(pdk_model *m) {
  pmb_impl *im = m->impl;
  if (!im) return;
  pdk_free_aligned(im->s0_next);
  pdk_free_aligned(im->w);
  pdk_free_aligned(im->c_particle);
  free(im->block_energy);
  pdk_bond_data_free(&im->bd);
  pdk_sell_free(&im->sell);
  free(im);
  m->impl = NULL;
}

/* Analytic tangent (the Newton solver's, see pdk_model_ops). For a bond b of i to j with
 * eta = x_j - x_i, r = |eta|, e = r - r0, the force term is g eta with g = on c_b beta V_j e / (r0
 * r) (kernels/ref/pmb.c), whose derivative with respect to eta is M_b = on c_b beta V_j H,   H = e
 * / (r0 r) I + eta eta^T / r^3 (the second term from dg/deta = on c_b beta V_j eta^T / r^3). f_i
 * depends on x_i through every bond of i and on x_j through bond b only, so the column of particle
 * i holds K[i, i] = V_i sum_b M_b,   K[j, i] = -V_j M'_b   (M'_b: bond j -> i, seen from j: V_i,
 * its own bond state, the same r0, c_b and H). A bond with r = 0 contributes nothing (the force
 * pass sets its force to 0). Float storage reads r0 from bond_r0 as the force pass does; a
 * multi-material body uses c_b = 2 c_i c_j / (c_i + c_j). */
static void pmb_tangent_column(const pdk_model *m, pdk_index i, const pdk_index *loc,
                               double *block) {
  const pmb_impl *im = m->impl;
  const int dim = im->dim;
  const pdk_pmb_consts *k = &im->k;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X[3] = {NULL, NULL, NULL}, *x[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    X[c] = pdk_particles_X(m->p, c);
    x[c] = pdk_particles_field_data(m->p, "x", c);
  }
  const double *V = pdk_particles_volume(m->p);
  const float *bond_r0 = im->bd.bond_r0;
  const uint8_t *alive = m->bond_alive;
  const double *cp = k->c_particle;
  double *Kii = block + (size_t)loc[i] * dim * dim;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    double xi[3] = {0, 0, 0}, eta[3] = {0, 0, 0};
    for (int c = 0; c < dim; ++c) {
      xi[c] = X[c][j] - X[c][i];
      eta[c] = x[c][j] - x[c][i];
    }
    const double r0 =
        bond_r0 ? (double)bond_r0[b] : sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
    const double r = sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]);
    if (!(r > 0.0)) continue;
    const double beta = fmin(1.0, (k->vs_a - r0) * k->vs_b);
    const double c_b = cp ? 2.0 * (cp[i] * cp[j]) / (cp[i] + cp[j]) : k->c;
    const double on_i = alive ? (double)alive[b] : 1.0;
    double on_j = 1.0;
    if (alive) {
      const pdk_bond_index rb = pdk_bond_reverse(bs, bj, i, j);
      on_j = rb >= 0 ? (double)alive[rb] : 0.0;
    }
    const double a1 = (r - r0) / (r0 * r), a2 = 1.0 / (r * r * r);
    const double wi = V[i] * on_i * c_b * beta * V[j];  /* K[i,i] += wi H */
    const double wj = -V[j] * on_j * c_b * beta * V[i]; /* K[j,i] += wj H */
    double *Kji = block + (size_t)loc[j] * dim * dim;
    for (int e = 0; e < dim; ++e)
      for (int c = 0; c < dim; ++c) {
        const double H = (e == c ? a1 : 0.0) + a2 * eta[e] * eta[c];
        Kii[e * dim + c] += wi * H;
        Kji[e * dim + c] += wj * H;
      }
  }
}

const pdk_model_ops pdk_model_ops_pmb = {.setup = pmb_setup,
                                         .force = pmb_force,
                                         .destroy = pmb_destroy,
                                         .tangent_column = pmb_tangent_column,
                                         .padding_fraction = pdk_model_pmb_padding_fraction,
                                         .float_bond_lengths = 1,
                                         .layout_sell = 1,
                                         .partial_volumes = 1,
                                         .ranks = 1};

double pdk_model_pmb_padding_fraction(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_pmb || !m->impl) return 0.0;
  const pmb_impl *im = m->impl;
  return im->use_sell ? pdk_sell_padding_fraction(&im->sell) : 0.0;
}

const double *pdk_model_pmb_energy_density(const pdk_model *m) {
  if (!m || m->ops != &pdk_model_ops_pmb || !m->impl) return NULL;
  return ((pmb_impl *)m->impl)->w;
}

static const pdk_model_ops *pmb_ops_for(const pdk_model_opts *o) {
  (void)o;
  return &pdk_model_ops_pmb;
}

const pdk_model_kind_info pdk_model_kind_pmb = {
    .kind = PDK_MODEL_PMB,
    .name = "pmb",
    .caps = PDK_KIND_SCENE | PDK_KIND_STENCIL | PDK_KIND_MATERIALS | PDK_KIND_FLOAT |
            PDK_KIND_TANGENT,
    .hops = 1,
    .scene_stabilization = PDK_STAB_NONE,
    .mem_point = 640,
    .mem_bond = 8,
    .mem_bond_float = 12,
    .mem_bond_lengths = 8,
    .mem_newton_bond = 100,
    .ops_for = pmb_ops_for};
