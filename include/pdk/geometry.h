/* Geometry: lattice generators, region predicates, named particle sets.
 *
 * Generators fill a particle store with a lattice over a box, with optional jitter, and set each
 * particle's volume. Regions are small value types (no allocation except polygons, which point to
 * caller-owned vertices) used to cut holes and to name particle sets. Tests, benchmarks and scenes
 * all build their bodies with these functions.
 */
#ifndef PDK_GEOMETRY_H
#define PDK_GEOMETRY_H

#include "pdk/particles.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pdk_lattice_type {
  PDK_LATTICE_SQUARE = 0, /* 2-D, points at lo + (i + 1/2) * spacing along each axis */
  PDK_LATTICE_HEX = 1,    /* 2-D, rows spacing*sqrt(3)/2 apart, odd rows shifted by spacing/2 */
  PDK_LATTICE_CUBIC = 2   /* 3-D simple cubic, points at lo + (i + 1/2) * spacing */
} pdk_lattice_type;

typedef struct pdk_lattice_opts {
  pdk_lattice_type type;
  double lo[3], hi[3];  /* box [length]; a point is generated when it lies inside [lo, hi) */
  double spacing;       /* lattice spacing Delta x [length], > 0 */
  double jitter;        /* random displacement per axis, uniform in +-jitter*spacing; 0 <= jitter < 0.5 */
  uint64_t seed;        /* jitter seed; the jitter of a point depends only on (seed, lattice index) */
  double thickness;     /* 2-D only: out-of-plane thickness [length] for volumes (default 1) */
  int node_type;        /* 1: points at lo + i*spacing, including both box faces (grid nodes) */
} pdk_lattice_opts;

pdk_lattice_opts pdk_lattice_opts_default(void);

/* Creates a store holding the lattice points; X, volume and id set. Volume is the lattice cell
 * volume (spacing^2 * thickness, sqrt(3)/2 spacing^2 * thickness, spacing^3). Errors: non-positive
 * or non-finite spacing, empty or inverted box, jitter out of range, too many points. */
int pdk_lattice_create(pdk_ctx *ctx, const pdk_lattice_opts *opts, pdk_particles **out);

typedef enum pdk_region_kind {
  PDK_REGION_BOX = 0,       /* lo <= x <= hi on every axis */
  PDK_REGION_BALL = 1,      /* |x - center| <= radius (a disk in 2-D) */
  PDK_REGION_HALFSPACE = 2, /* (x - point) . normal <= 0 (half-plane in 2-D) */
  PDK_REGION_POLYGON = 3    /* 2-D: inside a simple polygon (crossing-number rule) */
} pdk_region_kind;

typedef struct pdk_region {
  pdk_region_kind kind;
  double lo[3], hi[3];       /* BOX */
  double center[3], radius;  /* BALL */
  double point[3], normal[3];/* HALFSPACE */
  const double *vertices;    /* POLYGON: [num_vertices][2], caller-owned */
  int num_vertices;
  int invert;                /* 1: the complement of the region */
} pdk_region;

pdk_region pdk_region_box(const double lo[3], const double hi[3]);
pdk_region pdk_region_ball(const double center[3], double radius);
pdk_region pdk_region_halfspace(const double point[3], const double normal[3]);
pdk_region pdk_region_polygon(const double *vertices, int num_vertices);

/* Checks a region's parameters (radius > 0, lo <= hi, normal non-zero, >= 3 vertices, finite). */
int pdk_region_check(pdk_ctx *ctx, int dim, const pdk_region *r);
/* 1 if the point x[0..dim-1] lies in the region. */
int pdk_region_contains(const pdk_region *r, int dim, const double *x);

/* Removes the particles inside the region (cuts a hole). Error if it would remove every particle.
 * `removed` (may be NULL) receives how many went. */
int pdk_particles_cut(pdk_particles *p, const pdk_region *r, pdk_index *removed);

/* Declares the set "set:<name>" (uint8 field) holding the particles inside the region. A region that
 * selects no particle is an error naming the set. `count` (may be NULL) receives the member count. */
int pdk_particles_set_define(pdk_particles *p, const char *name, const pdk_region *r, pdk_index *count);
/* Member indices of a set, ascending, in a malloc'ed array the caller frees. */
int pdk_particles_set_indices(pdk_particles *p, const char *name, pdk_index **indices, pdk_index *count);

#ifdef __cplusplus
}
#endif
#endif
