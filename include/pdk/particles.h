/* Particle store: structure of arrays with a field registry.
 *
 * A store holds n particles in `dim` (2 or 3) dimensions. Every field is a set of components, and
 * every component is its own array (SoA): 64-byte aligned, allocated for n_pad = n rounded up to
 * PDK_PAD (the widest SIMD width in doubles) entries. Padding entries are zero, so a padded lane
 * has zero volume and contributes nothing to a sum.
 *
 * A field exists only once something declares it (pdk_particles_field_add). Three fields exist from
 * creation:
 *   "id"     int64 x1   original particle id, kept through every reordering (for output)
 *   "X"      f64 x dim  reference position [length]
 *   "volume" f64 x1     particle volume [length^dim; in 2-D, area times thickness]
 * Named particle sets are uint8 fields "set:<name>" (1 = member), so they follow reordering.
 *
 * Reordering (pdk_particles_permute, pdk_particles_reorder_morton) carries every registered field.
 */
#ifndef PDK_PARTICLES_H
#define PDK_PARTICLES_H

#include "pdk/export.h"
#include "pdk/ctx.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PDK_PAD 8       /* padding unit in entries: 8 doubles = 64 bytes = one AVX-512 register */
#define PDK_ALIGN 64    /* byte alignment of every field array */
#define PDK_FIELD_NAME_MAX 64

typedef enum pdk_type { PDK_F64 = 0, PDK_F32 = 1, PDK_I64 = 2, PDK_I32 = 3, PDK_U8 = 4 } pdk_type;

typedef struct pdk_particles pdk_particles;

/* Creates a store of n particles (n >= 1) in dim 2 or 3; fields id = 0..n-1, X = 0, volume = 0. */
PDK_EXPORT int pdk_particles_create(pdk_ctx *ctx, int dim, pdk_index n, pdk_particles **out);
PDK_EXPORT void pdk_particles_destroy(pdk_particles **p);

PDK_EXPORT int pdk_particles_dim(const pdk_particles *p);
PDK_EXPORT pdk_index pdk_particles_count(const pdk_particles *p);
PDK_EXPORT pdk_index pdk_particles_count_padded(const pdk_particles *p);
PDK_EXPORT pdk_ctx *pdk_particles_ctx(const pdk_particles *p);

/* Declares a field of num_comp components (1..9). Adding a field that exists with the same type
 * and component count is a no-op; with a different shape it is an error. New arrays are zero. */
PDK_EXPORT int pdk_particles_field_add(pdk_particles *p, const char *name, pdk_type type,
                                       int num_comp);
PDK_EXPORT int pdk_particles_field_remove(pdk_particles *p, const char *name);
PDK_EXPORT int pdk_particles_field_exists(const pdk_particles *p, const char *name); /* 1 or 0 */
/* Component `comp` of field `name`: pointer to n_pad entries of the field's type. */
PDK_EXPORT int pdk_particles_field_get(pdk_particles *p, const char *name, int comp, void **out);
/* Same as field_get but returns NULL when the field or component does not exist (no error). */
PDK_EXPORT void *pdk_particles_field_data(pdk_particles *p, const char *name, int comp);
PDK_EXPORT int pdk_particles_field_info(const pdk_particles *p, const char *name, pdk_type *type,
                                        int *num_comp);
PDK_EXPORT int pdk_particles_num_fields(const pdk_particles *p);
/* k in 0..num_fields-1 */
PDK_EXPORT const char *pdk_particles_field_name(const pdk_particles *p, int k);
/* 0 if absent */
PDK_EXPORT size_t pdk_particles_field_bytes(const pdk_particles *p, const char *name);
PDK_EXPORT size_t pdk_particles_memory_bytes(const pdk_particles *p); /* all fields */
/* One line per field: name, type, components, bytes; then the total. */
PDK_EXPORT void pdk_particles_print_memory(const pdk_particles *p, FILE *out);
PDK_EXPORT size_t pdk_type_size(pdk_type type);

/* Convenience accessors for the three built-in fields. */
PDK_EXPORT double *pdk_particles_X(pdk_particles *p, int comp);
PDK_EXPORT double *pdk_particles_volume(pdk_particles *p);
PDK_EXPORT int64_t *pdk_particles_id(pdk_particles *p);

/* Checks that every reference coordinate is finite; the error names the first bad particle. */
PDK_EXPORT int pdk_particles_check_finite(pdk_particles *p);

/* Reorders every field: new index k takes old index perm[k]; perm is a permutation of 0..n-1. */
PDK_EXPORT int pdk_particles_permute(pdk_particles *p, const pdk_index *perm);
/* Keeps only particles with keep[i] != 0, in their order; error if none would remain. */
PDK_EXPORT int pdk_particles_compact(pdk_particles *p, const uint8_t *keep);

/* Sorts particles by the Morton (Z-order) key of the cell of edge `cell_edge` that holds X (cell
 * index floor((X - lo) / cell_edge) per axis, lo the bounding box's low corner). Stable: ties keep their current order. If perm_out
 * is not NULL it receives n entries (new -> old). */
PDK_EXPORT int pdk_particles_reorder_morton(pdk_particles *p, double cell_edge,
                                            pdk_index *perm_out);

/* Sorts particles by rows of a lattice of the given spacing: the nearest lattice index
 * round((X - lo) / spacing) per axis, z slowest and x fastest (lo the bounding box's low corner).
 * Stable. On a regular lattice this is the site order of the stencil path (model.stencil), whose
 * per-particle arrays are then walked in order; used by pdk_sim_create for the correspondence
 * stencil path. perm_out as for pdk_particles_reorder_morton. */
PDK_EXPORT int pdk_particles_reorder_rows(pdk_particles *p, double spacing, pdk_index *perm_out);

/* Morton key of integer cell coordinates (21 bits per axis in 3-D, 32 in 2-D). */
PDK_EXPORT uint64_t pdk_morton2(uint32_t cx, uint32_t cy);
PDK_EXPORT uint64_t pdk_morton3(uint32_t cx, uint32_t cy, uint32_t cz);

#ifdef __cplusplus
}
#endif
#endif
