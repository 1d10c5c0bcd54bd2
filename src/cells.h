/* Cell list (private to libpdk): particles binned into a uniform grid and counting-sorted by cell,
 * so that a neighbour scan over one cell is a contiguous loop over cell-sorted coordinates.
 *
 * Grid: origin lo = the particles' bounding-box low corner; cubic cells of edge `edge`; num[a]
 * cells along axis a (num[2] = 1 in 2-D). Cell (cx, cy, cz) has the linear index
 *   c = cx + num[0] * (cy + num[1] * cz)          (x fastest)
 * and a particle at X lies in cell coordinate cx = (int)((X_0 - lo_0) * inv_edge) per axis,
 * computed exactly as pdk_particles_reorder_morton computes its Morton cells, so a store reordered
 * with the same edge (pdk_cells_edge) has every cell as one contiguous range of particle indices.
 *
 * Guarantee: two particles whose squared distance, computed as the family kernels compute it
 * (kernels.h), is <= horizon^2 (1 + PDK_HORIZON_RTOL) lie in the same or in adjacent cells (cell
 * coordinates differing by at most 1 on every axis). The edge is therefore a little larger than
 * the horizon (see pdk_cells_edge in cells.c for the margin and why), and larger still when the
 * grid had to be coarsened to keep the cell count bounded (huge box or tiny horizon).
 *
 * Arrays:
 *   cell_start: [num_cells+1]; slots of cell c are cell_start[c] .. cell_start[c+1]-1
 *   slot_id:    [n]; the particle index held by each slot; ascending within a cell (stable sort)
 *   x[a]:       [n_pad] for a < dim; x[a][s] = X_a of particle slot_id[s]; padding entries 0
 *   cell_of:    [n]; linear cell index of particle i (in store order)
 */
#ifndef PDK_CELLS_H
#define PDK_CELLS_H

#include "pdk_impl.h"

/* Bounds of the grid. An axis holds at most PDK_CELLS_MAX_AXIS cells (the 3-D Morton key's 21 bits,
 * which also bounds the round-off of the cell coordinate, see cells.c); the grid holds at most
 * 4 n + 4096 cells (and < 2^31). Beyond either, the edge grows until both hold. */
#define PDK_CELLS_MAX_AXIS ((1 << 21) - 2)

typedef struct pdk_cells {
  int dim;
  pdk_index n;
  double lo[3];      /* grid origin [length] */
  double edge;       /* cell edge [length], > horizon */
  double inv_edge;   /* 1 / edge, as used for the cell coordinate */
  int64_t num[3];    /* cells per axis; 1 on unused axes */
  int64_t num_cells; /* num[0] * num[1] * num[2] */
  pdk_index *cell_start;
  pdk_index *slot_id;
  double *x[3];
  pdk_index *cell_of;
} pdk_cells;

/* The cell edge (and grid) pdk_cells_build uses for store p and this horizon. horizon must be
 * positive and finite, coordinates finite (checked; errors name the value). */
int pdk_cells_edge(pdk_particles *p, double horizon, double *edge);

/* Bins the particles of p into cells for `horizon` (see the guarantee above). */
int pdk_cells_build(pdk_particles *p, double horizon, pdk_cells **out);
void pdk_cells_destroy(pdk_cells **cells);

/* Cell coordinates of cell c along each axis. */
static inline void pdk_cells_coords(const pdk_cells *cl, int64_t c, int64_t cc[3]) {
  cc[0] = c % cl->num[0];
  cc[1] = (c / cl->num[0]) % cl->num[1];
  cc[2] = c / (cl->num[0] * cl->num[1]);
}

#endif
