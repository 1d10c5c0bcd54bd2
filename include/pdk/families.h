/* Cell list and bond families.
 *
 * Cells: a uniform grid of edge >= horizon over the particles' bounding box; a counting sort gives
 * cell_start[num_cells+1] and the particles of each cell. A neighbour search visits the 3^dim
 * cells around a particle's cell.
 *
 * Families, in CSR form with every bond stored from both ends:
 *   bond_start: [n+1] int64; bonds of particle i are bond_start[i] .. bond_start[i+1]-1
 *   bond_j:     [num_bonds] int32; the neighbour of each bond
 * Neighbour rule: j != i is in the family of i when |X_j - X_i|^2 <= delta^2 * (1 + PDK_HORIZON_RTOL),
 * the squared distance summed over axes in x, y, z order (bit-for-bit symmetric in i and j). The
 * relative tolerance makes lattice points at exactly distance delta (up to the round-off of their
 * generation) members, deterministically; with PDK_HORIZON_RTOL = 1e-12 a point farther than
 * delta*(1 + 5e-13) is never a member.
 * Bonds crossing a pre-crack are not created: a bond i-j is cut when the closed segment X_i X_j
 * meets the crack segment (2-D) or the crack polygon (3-D, a planar convex or non-convex polygon);
 * a bond lying in the crack's plane (3-D) or on its line (2-D) is not cut.
 * Within a family, bonds are sorted by ascending j. The result does not depend on the thread count
 * (bitwise) nor on the kernel family ("ref" or "simd").
 *
 * Exact rule: with r2max = (delta * delta) * (1 + PDK_HORIZON_RTOL) evaluated in double, j is a
 * neighbour of i when r2 <= r2max, where r2 = (dx*dx + dy*dy) + dz*dz, dx = X_j - X_i (x, y, z),
 * each operation rounded to double, no fused multiply-add.
 * The tolerance covers the round-off of generated lattice coordinates (about 1e-16 |X| each) while
 * |X| stays within a few thousand horizons of the origin (a square lattice at m = 2 kept every bond
 * at 4000 horizons and lost some at 10^4 for a spacing of 1e-3): with a horizon that is an exact
 * multiple of the spacing (m = 2, 3), generate lattices near the origin, or use a factor without
 * exact ties such as m = 3.015.
 *
 * Speed: the build is fastest when the store was first reordered by the cells it uses:
 *   pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, delta), NULL);
 * then every cell is one contiguous index range and families come out sorted without merging.
 * Any order gives the same families (up to the renumbering), only slower.
 */
#ifndef PDK_FAMILIES_H
#define PDK_FAMILIES_H

#include "pdk/export.h"
#include "pdk/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PDK_HORIZON_RTOL 1e-12

typedef struct pdk_precrack {
  int num_vertices;        /* 2 in 2-D (a segment); >= 3 in 3-D (a planar polygon) */
  const double *vertices;  /* [num_vertices][dim], caller-owned */
} pdk_precrack;

typedef struct pdk_families_opts {
  double horizon;                   /* delta [length], > 0, uniform */
  const char *horizon_field;        /* reserved for a per-particle horizon field; must be NULL now */
  const pdk_precrack *precracks;    /* [num_precracks] */
  int num_precracks;
  size_t max_bytes;                 /* refuse to build if the bonds would take more; 0: 3/4 of RAM */
} pdk_families_opts;

PDK_EXPORT pdk_families_opts pdk_families_opts_default(void);

typedef struct pdk_families pdk_families;

/* Builds the families of every particle of p (n >= 1; a single particle has an empty family).
 * Errors: non-positive or non-finite horizon (PDK_ERR_ARG), horizon_field set
 * (PDK_ERR_UNSUPPORTED), non-finite coordinates (PDK_ERR_NUMERIC, names the particle), bond count
 * beyond the memory limit (PDK_ERR_MEMORY, names the count and bytes; checked before the bonds are
 * allocated), bad pre-crack geometry (PDK_ERR_ARG: wrong vertex count, non-finite, zero length or
 * area, not planar). */
PDK_EXPORT int pdk_families_build(pdk_particles *p, const pdk_families_opts *opts,
                                  pdk_families **out);
/* The same families over explicit coordinates: coords[a] [n] for a < dim (coords[2] unused in
 * 2-D), ids [n] (may be NULL: messages then name indices) for error messages. Gives the bonds
 * pdk_families_build gives on a store whose "X" holds these coordinates, bit for bit; used to
 * rebuild families in the current configuration (updated-Lagrangian connectivity). Same errors. */
PDK_EXPORT int pdk_families_build_coords(pdk_ctx *ctx, int dim, pdk_index n,
                                         const double *const coords[3], const int64_t *ids,
                                         const pdk_families_opts *opts, pdk_families **out);
PDK_EXPORT void pdk_families_destroy(pdk_families **f);

PDK_EXPORT pdk_index pdk_families_num_particles(const pdk_families *f);
PDK_EXPORT pdk_bond_index pdk_families_num_bonds(const pdk_families *f); /* directed bonds */
PDK_EXPORT const pdk_bond_index *pdk_families_bond_start(const pdk_families *f);
PDK_EXPORT const pdk_index *pdk_families_bond_j(const pdk_families *f);
PDK_EXPORT double pdk_families_horizon(const pdk_families *f);
PDK_EXPORT size_t pdk_families_memory_bytes(const pdk_families *f); /* bond_start + bond_j */

/* The cell edge pdk_families_build uses for store p and this horizon: a relative 1.5e-8 above the
 * horizon (so round-off can never put two neighbours two cells apart), more only when the body
 * spans more than 2^21 horizons along an axis. Pass it to pdk_particles_reorder_morton for the
 * fastest build. Returns 0 and records an error in the context for a bad horizon or coordinates. */
PDK_EXPORT double pdk_families_cell_edge(pdk_particles *p, double horizon);

#ifdef __cplusplus
}
#endif
#endif
