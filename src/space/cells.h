/* Cell list (private to libpdk): particles binned into a uniform grid and sorted by cell, so that a
 * neighbour scan over one cell is a contiguous loop over cell-sorted coordinates.
 *
 * Grid: origin lo = the particles' bounding-box low corner; cubic cells of edge `edge`; num[a]
 * cells along axis a (num[2] = 1 in 2-D). Grid cell (cx, cy, cz) has the key
 *   key = cx + num[0] * (cy + num[1] * cz)          (x fastest; < 2^63)
 * and a particle at X lies in cell coordinate cx = (int)((X_0 - lo_0) * inv_edge) per axis,
 * computed exactly as pdk_particles_reorder_morton computes its Morton cells, so a store reordered
 * with the same edge (pdk_cells_edge) has every cell as one contiguous range of particle indices.
 *
 * Only occupied cells are stored, numbered 0..num_cells-1 in ascending key order, each with the
 * list of its occupied neighbours. So the memory is O(n) however large the box: two bodies far
 * apart cost no more than each alone. (A dense grid indexes cells directly; it is used to bin when
 * it has at most 4 n + 4096 cells, and a sort by key otherwise.)
 *
 * Guarantee: two particles whose squared distance, computed as the family kernels compute it
 * (kernels.h), is <= horizon^2 (1 + PDK_HORIZON_RTOL) lie in the same or in neighbouring cells
 * (cell coordinates differing by at most 1 on every axis). The edge is therefore a little larger
 * than the horizon (see cells.c for the margin and why), and larger still only if the box spans
 * more than PDK_CELLS_MAX_AXIS cells along an axis.
 *
 * Arrays (cells indexed by occupied-cell number c):
 *   key:        [num_cells] grid key of each cell, ascending
 *   cell_start: [num_cells+1]; slots of cell c are cell_start[c] .. cell_start[c+1]-1
 *   neighbours: [num_cells][PDK_CELLS_NB]; the occupied cells among the 3^dim grid cells around c
 *               (c included), in (dz, dy, dx) nested order, -1 where a cell is empty or outside
 *   slot_id:    [n]; the particle index held by each slot; ascending within a cell (stable)
 *   x[a]:       [n_pad] for a < dim; x[a][s] = X_a of particle slot_id[s]; padding entries 0
 *   cell_of:    [n]; the cell of particle i (store order)
 */
#ifndef PDK_CELLS_H
#define PDK_CELLS_H

#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

/* At most this many cells along an axis (the 3-D Morton key's 21 bits, which also bounds the
 * round-off of the cell coordinate, see cells.c); beyond it the edge grows. */
#define PDK_CELLS_MAX_AXIS ((1 << 21) - 2)
#define PDK_CELLS_NB 27 /* entries per cell in `neighbours` (9 used in 2-D) */

typedef struct pdk_cells {
  int dim;
  pdk_index n;
  double lo[3];        /* grid origin [length] */
  double edge;         /* cell edge [length], > horizon */
  double inv_edge;     /* 1 / edge, as used for the cell coordinate */
  int64_t num[3];      /* grid cells per axis; 1 on unused axes */
  pdk_index num_cells; /* occupied cells */
  int sparse;          /* 1: binned by sorting keys (the dense grid would have been too large) */
  int64_t *key;
  pdk_index *cell_start;
  pdk_index *neighbours;
  pdk_index *slot_id;
  double *x[3];
  pdk_index *cell_of;
} pdk_cells;

/* The cell edge pdk_cells_build uses for store p and this horizon. horizon must be positive and
 * finite, coordinates finite (checked; errors name the value). */
int pdk_cells_edge(pdk_particles *p, double horizon, double *edge);

/* Bins the particles of p into cells for `horizon` (see the guarantee above). */
int pdk_cells_build(pdk_particles *p, double horizon, pdk_cells **out);
void pdk_cells_destroy(pdk_cells **cells);

#endif
