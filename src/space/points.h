/* Point clouds: a body given as particles (positions, volumes, sets) read from a CSV file
 * (geometry.points in a scene; docs/scenes.md "Point clouds"). */
#ifndef PDK_POINTS_H
#define PDK_POINTS_H

#include "core/pdk_impl.h"
#include "pdk/ctx.h"

#define PDK_POINTS_MAX_SETS 64

#define PDK_POINTS_MAX_MKEYS 1024

/* One distinct value of a cloud's material column: a material's name, or (name NULL) its index
 * (0 = the scene's `material`, k = materials[k - 1]); where it first occurs: the CSV line, or for
 * HDF5 (line 0) the particle's row. */
typedef struct pdk_points_mkey {
  char *name;
  long index;
  long line, row;
} pdk_points_mkey;

typedef struct pdk_points {
  pdk_index n;
  int dim;
  double *X[3];   /* [n] per axis (z unused in 2-D) */
  double *volume; /* [n]: the volume column, or area x thickness in 2-D */
  int num_sets;
  char *set_name[PDK_POINTS_MAX_SETS]; /* without "set:" */
  uint8_t *set[PDK_POINTS_MAX_SETS];   /* [n] 1 = member */
  uint8_t set_body[PDK_POINTS_MAX_SETS]; /* a mesh's physical group of body elements (a scene
                                            materials entry of its name makes it a material) */
  double lo[3], hi[3];                 /* bounding box of the positions */
  /* The material column (CSV) or dataset (HDF5), when the file has one: material[i] is the key
   * (an index into mkey) of particle i; the scene maps each key to a material index. */
  int32_t *material;
  char *path; /* the file, for messages (set by the caller; freed with the cloud) */
  int num_mkeys;
  pdk_points_mkey *mkey;
} pdk_points;

/* Reads the CSV file at path: a header line naming the columns, then one line per particle.
 * Columns, in any order: x, y (, z in 3-D) the reference position; volume (the particle volume;
 * in 2-D area x thickness) or, in 2-D, area (multiplied by thickness); set:<name> (0 or 1) for
 * each set the cloud defines; material (a material's name or index, optional). Blank lines and lines starting with '#' are skipped. Every error
 * names the file and line and says what is wrong; *out is then left empty. */
int pdk_points_read_csv(pdk_ctx *ctx, const char *path, int dim, double thickness,
                        pdk_points *out);
/* Reads an HDF5 point cloud: the dataset X ([n][dim] or [n][3], reference positions), volume
 * ([n], the particle volumes as pdk counts them: in 2-D area x thickness) and, optionally, the
 * group sets with one dataset [n] of 0 and 1 per set, and an integer dataset material [n] (the
 * particles' material indices), optional; at the root, or under /static, so the
 * output file of a pdk run (its reference configuration) is a cloud too. */
int pdk_points_read_h5(pdk_ctx *ctx, const char *path, int dim, pdk_points *out);
/* src/space/mesh.c: a Gmsh mesh (ASCII MSH 4.1 or 2.2) as a cloud: one particle per element of
 * dimension dim (triangles and quadrangles in 2-D, their area x thickness; tetrahedra and
 * hexahedra in 3-D, their volume) at the element's centroid, in the file's element order; a set
 * per physical group: of the elements of a body group (set_body 1), of the elements with a node
 * on a lower-dimension group (its lines, points, faces). Unnamed groups are named
 * physical_<dim>_<tag>. Every error names the file and line and what to do. */
int pdk_points_read_msh(pdk_ctx *ctx, const char *path, int dim, double thickness,
                        pdk_points *out);
void pdk_points_free(pdk_points *pts);
/* The key of a material value (name of len chars, or index when name is NULL) in p->mkey, added
 * with its line and row when new; -1 past PDK_POINTS_MAX_MKEYS keys or out of memory. */
int pdk_points_mkey_find(pdk_points *p, const char *name, size_t len, long index, long line,
                         long row);

#endif
