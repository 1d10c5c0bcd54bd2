/* Point clouds: a body given as particles (positions, volumes, sets) read from a CSV file
 * (geometry.points in a scene; docs/scenes.md "Point clouds"). */
#ifndef PDK_POINTS_H
#define PDK_POINTS_H

#include "core/pdk_impl.h"
#include "pdk/ctx.h"

#define PDK_POINTS_MAX_SETS 64

typedef struct pdk_points {
  pdk_index n;
  int dim;
  double *X[3];   /* [n] per axis (z unused in 2-D) */
  double *volume; /* [n]: the volume column, or area x thickness in 2-D */
  int num_sets;
  char *set_name[PDK_POINTS_MAX_SETS]; /* without "set:" */
  uint8_t *set[PDK_POINTS_MAX_SETS];   /* [n] 1 = member */
  double lo[3], hi[3];                 /* bounding box of the positions */
} pdk_points;

/* Reads the CSV file at path: a header line naming the columns, then one line per particle.
 * Columns, in any order: x, y (, z in 3-D) the reference position; volume (the particle volume;
 * in 2-D area x thickness) or, in 2-D, area (multiplied by thickness); set:<name> (0 or 1) for
 * each set the cloud defines. Blank lines and lines starting with '#' are skipped. Every error
 * names the file and line and says what is wrong; *out is then left empty. */
int pdk_points_read_csv(pdk_ctx *ctx, const char *path, int dim, double thickness,
                        pdk_points *out);
/* Reads an HDF5 point cloud: the dataset X ([n][dim] or [n][3], reference positions), volume
 * ([n], the particle volumes as pdk counts them: in 2-D area x thickness) and, optionally, the
 * group sets with one dataset [n] of 0 and 1 per set; at the root, or under /static, so the
 * output file of a pdk run (its reference configuration) is a cloud too. */
int pdk_points_read_h5(pdk_ctx *ctx, const char *path, int dim, pdk_points *out);
void pdk_points_free(pdk_points *pts);

#endif
