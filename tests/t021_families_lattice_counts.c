/* V-NB lattice family sizes. Bulk families on the square lattice (m = 1.5, 2.0, 2.5, 3.015, 3.5,
 * 4.015 -> 8, 12, 20, 28, 36, 48) and the simple cubic lattice (18, 32, 80, 122, 178, 256), with
 * positions origin + i * spacing for spacings 0.1 and 1e-3 and an offset origin, so the distances
 * carry real round-off; the boundary rule at exactly delta (a point at delta (1 + 1e-15) is in,
 * at delta (1 + 1e-9) out); and the total bond count of free blocks against the exact count
 * sum over offsets o with |o| <= m of prod_a (N_a - |o_a|), which gives the notes' 117.84 bonds
 * per particle for the free 100^3 cube at m = 3.015.
 * labels: unit physics */
#include <stdint.h>

#include "test_util.h"

static const double m_values[6] = {1.5, 2.0, 2.5, 3.015, 3.5, 4.015};
static const int bulk_2d[6] = {8, 12, 20, 28, 36, 48};
static const int bulk_3d[6] = {18, 32, 80, 122, 178, 256};

/* Store with the lattice origin + i * spacing, i in 0..num-1 per axis, x fastest. */
static pdk_particles *lattice(pdk_ctx *ctx, int dim, int num, double spacing,
                              const double origin[3]) {
  const int total = dim == 3 ? num * num * num : num * num;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, dim, total, &p));
  for (int q = 0; q < total; ++q) {
    int idx[3] = {q % num, (q / num) % num, q / (num * num)};
    for (int a = 0; a < dim; ++a)
      pdk_particles_X(p, a)[q] = origin[a] + idx[a] * spacing;
  }
  return p;
}

/* Exact directed bond count of a free N^dim block at horizon m spacings: every lattice offset o
 * with |o|^2 <= m^2 (o != 0) joins prod_a (N - |o_a|) ordered pairs. */
static int64_t exact_block_bonds(int dim, int N, double m) {
  const int R = (int)m + 1;
  int64_t total = 0;
  for (int c = (dim == 3 ? -R : 0); c <= (dim == 3 ? R : 0); ++c)
    for (int b = -R; b <= R; ++b)
      for (int a = -R; a <= R; ++a) {
        if (!a && !b && !c) continue;
        if (a * a + b * b + c * c > m * m) continue;
        if (abs(a) >= N || abs(b) >= N || abs(c) >= N) continue;
        total += (int64_t)(N - abs(a)) * (N - abs(b)) * (dim == 3 ? N - abs(c) : 1);
      }
  return total;
}

static int64_t family_size(const pdk_families *f, int i) {
  const pdk_bond_index *s = pdk_families_bond_start(f);
  return s[i + 1] - s[i];
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);

  /* The exact-count formula reproduces the notes' free 100^3 average. */
  T_NEAR((double)exact_block_bonds(3, 100, 3.015) / 1e6, 117.844248, 0, 1e-9,
         "free 100^3 cube at m = 3.015 (docs/validation/targets.md: 117.84)");

  /* Bulk family sizes: every particle at least ceil(m) spacings from the faces. */
  const double spacings[2] = {0.1, 1e-3};
  /* Offsets of a few hundred spacings: the round-off of X = origin + i * spacing is then about
   * 1e-14 of the horizon, inside the 1e-12 tolerance. (An origin 1e5 spacings away would put the
   * generation round-off of points at exactly delta beyond the tolerance.) */
  const double origins[2][3] = {{12.345, -7.89, 3.21}, {-0.5123, 1.0007, 0.3}};
  for (int s = 0; s < 2; ++s) {
    for (int dim = 2; dim <= 3; ++dim) {
      const int num = 13;
      pdk_particles *p = lattice(ctx, dim, num, spacings[s], origins[s]);
      for (int k = 0; k < 6; ++k) {
        pdk_families_opts o = pdk_families_opts_default();
        o.horizon = m_values[k] * spacings[s];
        pdk_families *f = NULL;
        T_OK(ctx, pdk_families_build(p, &o, &f));
        const int margin = (int)ceil(m_values[k]);
        const int expect = dim == 2 ? bulk_2d[k] : bulk_3d[k];
        int checked = 0;
        for (int q = 0; q < pdk_particles_count(p); ++q) {
          int idx[3] = {q % num, (q / num) % num, q / (num * num)};
          int interior = 1;
          for (int a = 0; a < dim; ++a)
            interior = interior && idx[a] >= margin && idx[a] < num - margin;
          if (!interior) continue;
          if (family_size(f, q) != expect)
            T_FAIL("%d-D lattice, spacing %g, m = %g: interior particle %d has %lld bonds, "
                   "V-NB table says %d",
                   dim, spacings[s], m_values[k], q, (long long)family_size(f, q), expect);
          ++checked;
        }
        T_ASSERT(checked > 0, "no interior particle at m = %g", m_values[k]);
        pdk_families_destroy(&f);
      }
      pdk_particles_destroy(&p);
    }
  }

  /* The boundary rule at exactly delta: in at delta (1 + 1e-15), out at delta (1 + 1e-9). With
   * the origin at 0 the offset is exactly the stated distance; with an offset origin it also
   * carries the round-off of the subtraction, far below the 1e-12 tolerance. */
  for (int dim = 2; dim <= 3; ++dim) {
    const double delta = 0.3;
    const double rel[4] = {1e-15, 1e-9, 0.0, -1e-15};
    const int in[4] = {1, 0, 1, 1};
    const double base[2] = {0.0, 123.456};
    for (int b = 0; b < 2; ++b)
      for (int axis = 0; axis < dim; ++axis)
        for (int k = 0; k < 4; ++k) {
          pdk_particles *p = NULL;
          T_OK(ctx, pdk_particles_create(ctx, dim, 2, &p));
          for (int a = 0; a < dim; ++a)
            pdk_particles_X(p, a)[0] = pdk_particles_X(p, a)[1] = base[b];
          pdk_particles_X(p, axis)[1] = base[b] + delta * (1.0 + rel[k]);
          pdk_families_opts o = pdk_families_opts_default();
          o.horizon = delta;
          pdk_families *f = NULL;
          T_OK(ctx, pdk_families_build(p, &o, &f));
          T_ASSERT(pdk_families_num_bonds(f) == 2 * in[k],
                   "%d-D, axis %d, base %g: a point at delta (1 %+g) should be %s (bonds: %lld)",
                   dim, axis, base[b], rel[k], in[k] ? "in" : "out",
                   (long long)pdk_families_num_bonds(f));
          pdk_families_destroy(&f);
          pdk_particles_destroy(&p);
        }
  }

  /* Free blocks: total directed bonds equal the exact lattice count (every particle, boundary
   * ones included), for every m of the table. */
  {
    const struct { int dim, N; } blocks[2] = {{2, 60}, {3, 24}};
    for (int b = 0; b < 2; ++b) {
      pdk_particles *p = lattice(ctx, blocks[b].dim, blocks[b].N, 1e-3, origins[1]);
      T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, 3.015e-3), NULL));
      for (int k = 0; k < 6; ++k) {
        pdk_families_opts o = pdk_families_opts_default();
        o.horizon = m_values[k] * 1e-3;
        pdk_families *f = NULL;
        T_OK(ctx, pdk_families_build(p, &o, &f));
        const int64_t expect = exact_block_bonds(blocks[b].dim, blocks[b].N, m_values[k]);
        T_ASSERT(pdk_families_num_bonds(f) == expect,
                 "free %d^%d block, m = %g: %lld bonds, exact lattice count %lld", blocks[b].N,
                 blocks[b].dim, m_values[k], (long long)pdk_families_num_bonds(f),
                 (long long)expect);
        pdk_families_destroy(&f);
      }
      pdk_particles_destroy(&p);
    }
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
