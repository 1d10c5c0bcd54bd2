/* Geometry: lattice generators, region predicates, named particle sets.
 *
 * Generators fill a particle store with a lattice over a box, with optional jitter, and set each
 * particle's volume. Regions are small value types (no allocation except polygons, which point to
 * caller-owned vertices) used to cut holes and to name particle sets. Tests, benchmarks and scenes
 * all build their bodies with these functions.
 */
#ifndef PDK_GEOMETRY_H
#define PDK_GEOMETRY_H

#include "pdk/export.h"
#include "pdk/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pdk_lattice_type {
  PDK_LATTICE_SQUARE = 0, /* 2-D, points at lo + (i + 1/2) * spacing along each axis */
  PDK_LATTICE_HEX = 1,    /* 2-D, rows at lo + (j + 1/2) * spacing*sqrt(3)/2; even rows at
                             lo + (i + 1/4) * spacing, odd rows at lo + (i + 3/4) * spacing (shifted
                             by spacing/2, and symmetric in a box a whole number of spacings wide) */
  PDK_LATTICE_CUBIC = 2   /* 3-D simple cubic, points at lo + (i + 1/2) * spacing */
} pdk_lattice_type;

typedef struct pdk_lattice_opts {
  pdk_lattice_type type;
  double lo[3], hi[3]; /* box [length]; a point is generated when it lies inside [lo, hi) (2-D:
                          the third entries are ignored) */
  double spacing;      /* lattice spacing Delta x [length], > 0 */
  double jitter;       /* displacement per axis, uniform in +-jitter*spacing; 0 <= jitter < 0.5.
                          Applied after the inside-the-box test, so points may leave the box by up
                          to jitter*spacing */
  uint64_t seed;       /* jitter seed; the jitter of a point depends only on (seed, lattice index),
                          not on the thread count */
  double thickness;    /* 2-D only: out-of-plane thickness [length] for volumes (default 1) */
  int node_type;       /* 1: points at lo + i*spacing, i = 0..N, N = round((hi - lo)/spacing), so
                          both box faces get points (grid nodes); (hi - lo)/spacing must then be a
                          whole number (relative tolerance 1e-6). Square and cubic only. Volumes
                          stay the full cell volume, also on faces */
} pdk_lattice_opts;

PDK_EXPORT pdk_lattice_opts pdk_lattice_opts_default(void);

/* Creates a store holding the lattice points; X, volume and id set. Points are ordered x fastest,
 * then y, then z; id = index. Volume is the lattice cell volume (spacing^2 * thickness,
 * sqrt(3)/2 spacing^2 * thickness, spacing^3). opts NULL: the defaults. Errors (PDK_ERR_ARG, the
 * message names the value): non-positive or non-finite spacing, non-finite, empty or inverted box,
 * jitter out of range, thickness <= 0, unknown type or node_type, node_type with a box that is not
 * a whole number of spacings or with the hexagonal lattice, more than 2^31 - 1 - PDK_PAD points,
 * a box too small to hold any point. */
PDK_EXPORT int pdk_lattice_create(pdk_ctx *ctx, const pdk_lattice_opts *opts, pdk_particles **out);
/* Points pdk_lattice_create would make (same checks and errors), allocating nothing. */
PDK_EXPORT int pdk_lattice_count(pdk_ctx *ctx, const pdk_lattice_opts *opts, pdk_index *count);

typedef enum pdk_region_kind {
  PDK_REGION_BOX = 0,       /* lo <= x <= hi on every axis */
  PDK_REGION_BALL = 1,      /* |x - center| <= radius (a disk in 2-D) */
  PDK_REGION_HALFSPACE = 2, /* (x - point) . normal <= 0 (half-plane in 2-D) */
  PDK_REGION_POLYGON = 3,   /* 2-D: inside a simple polygon (crossing-number rule; a point exactly
                               on an edge may fall on either side) */
  PDK_REGION_CYLINDER = 4   /* 3-D: distance to the axis p0-p1 <= radius and the projection on
                               the axis between p0 and p1 (closed, flat ends) */
} pdk_region_kind;

typedef struct pdk_region {
  pdk_region_kind kind;
  double lo[3], hi[3];        /* BOX */
  double center[3], radius;   /* BALL; CYLINDER: radius */
  double point[3], normal[3]; /* HALFSPACE */
  const double *vertices;     /* POLYGON: [num_vertices][2], caller-owned */
  int num_vertices;
  int invert;          /* 1: the complement of the region */
  double p0[3], p1[3]; /* CYLINDER: the axis' two ends */
} pdk_region;

/* Constructors; every array has 3 entries (in 2-D the third is ignored but still read). */
PDK_EXPORT pdk_region pdk_region_box(const double lo[3], const double hi[3]);
PDK_EXPORT pdk_region pdk_region_ball(const double center[3], double radius);
PDK_EXPORT pdk_region pdk_region_halfspace(const double point[3], const double normal[3]);
PDK_EXPORT pdk_region pdk_region_polygon(const double *vertices, int num_vertices);
/* A closed circular cylinder (3-D): the axis from p0 to p1 (its flat ends lie there), radius. */
PDK_EXPORT pdk_region pdk_region_cylinder(const double p0[3], const double p1[3], double radius);

/* Checks a region's parameters (radius > 0, lo <= hi, normal non-zero, >= 3 vertices and 2-D for
 * polygons, 3-D and an axis of non-zero length for cylinders, all finite); PDK_ERR_ARG with a
 * message naming the bad value. */
PDK_EXPORT int pdk_region_check(pdk_ctx *ctx, int dim, const pdk_region *r);
/* 1 if the point x[0..dim-1] lies in the region. Assumes a region that passes pdk_region_check. */
PDK_EXPORT int pdk_region_contains(const pdk_region *r, int dim, const double *x);
/* A one-line description for messages, e.g. "the box [0, 0]..[1, 1]"; truncated to len bytes. */
PDK_EXPORT void pdk_region_describe(const pdk_region *r, int dim, char *buf, size_t len);

/* Removes the particles inside the region (cuts a hole); the rest keep their order and every field,
 * sets included. The region is checked first. Error (PDK_ERR_ARG) if it would remove every
 * particle; a region that holds no particle removes none and is not an error. `removed` (may be
 * NULL) receives how many went. */
PDK_EXPORT int pdk_particles_cut(pdk_particles *p, const pdk_region *r, pdk_index *removed);

/* Declares the set "set:<name>" (uint8 field) holding the particles inside the region; defining an
 * existing set again replaces its members. The region is checked first. A region that selects no
 * particle is an error (PDK_ERR_ARG) naming the set, the region and the body's extent; the store is
 * then unchanged. `count` (may be NULL) receives the member count. */
PDK_EXPORT int pdk_particles_set_define(pdk_particles *p, const char *name, const pdk_region *r,
                                        pdk_index *count);
/* Member indices of a set, ascending, in a malloc'ed array the caller frees (also when the count is
 * 0). PDK_ERR_NOT_FOUND if the set was never defined. */
PDK_EXPORT int pdk_particles_set_indices(pdk_particles *p, const char *name, pdk_index **indices,
                                         pdk_index *count);

#ifdef __cplusplus
}
#endif
#endif
