/* Families over explicit coordinate arrays (pdk_families_build_coords, include/pdk/families.h).
 *
 * The updated-Lagrangian correspondence model rebuilds its families in the current configuration
 * "x", not in the store's reference "X". pdk_families_build reads the coordinates of a particle
 * store, so this wrapper copies the given arrays into a scratch store (ids, coordinates; volumes
 * stay 0) and builds there: the same neighbour rule, the same cell list, the same kernels, hence
 * the same bonds bit for bit as pdk_families_build on a store whose "X" holds these coordinates,
 * and the same independence of the thread count.
 *
 * Cost of the copy: (dim + 2) x 8 bytes per particle written once, against a build that scans
 * tens to hundreds of candidates per particle (not measured separately; bench/bench_ul.c times
 * the whole call).
 * Why not thread the coordinates through the cell list and the scan instead: those are another
 * concept's files (src/space/cells.c, src/space/families.c) and the copy is cheap.
 */
#include <string.h>

#include "core/pdk_impl.h"
#include "pdk/families.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

int pdk_families_build_coords(pdk_ctx *ctx, int dim, pdk_index n, const double *const coords[3],
                              const int64_t *ids, const pdk_families_opts *opts,
                              pdk_families **out) {
  int err = PDK_SUCCESS;
  pdk_particles *scratch = NULL;
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(coords && coords[0] && coords[1] && (dim == 2 || coords[2]), ctx, PDK_ERR_ARG,
            "pdk_families_build_coords: %d coordinate arrays are needed in %d-D", dim, dim);
  PDK_CALL(pdk_particles_create(ctx, dim, n, &scratch));
  for (int a = 0; a < dim; ++a)
    memcpy(pdk_particles_X(scratch, a), coords[a], (size_t)n * sizeof(double));
  if (ids) memcpy(pdk_particles_id(scratch), ids, (size_t)n * sizeof(int64_t));
  PDK_CALL_GOTO(pdk_families_build(scratch, opts, out));
cleanup:
  pdk_particles_destroy(&scratch);
  return err;
}
