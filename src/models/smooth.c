/* Influence-weighted smoothing of a particle field (pdk_smooth_field in pdk/model.h). */
#include <math.h>
#include <string.h>

#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

int pdk_smooth_field(pdk_particles *p, pdk_families *fam, pdk_influence w, double gaussian_width,
                     const char *in, const char *out) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(fam, ctx);
  PDK_CHECK(in && out && strcmp(in, out) != 0, ctx, PDK_ERR_ARG,
            "smoothing: give two different field names (in '%s', out '%s')", in ? in : "(null)",
            out ? out : "(null)");
  PDK_CHECK((unsigned)w <= PDK_INFLUENCE_QUADRATIC, ctx, PDK_ERR_ARG,
            "smoothing: influence function %d unknown", (int)w);
  PDK_CHECK(w != PDK_INFLUENCE_GAUSSIAN || (isfinite(gaussian_width) && gaussian_width > 0), ctx,
            PDK_ERR_ARG, "smoothing: gaussian width must be > 0, got %g", gaussian_width);
  PDK_CHECK(pdk_families_num_particles(fam) == pdk_particles_count(p), ctx, PDK_ERR_ARG,
            "smoothing: families of %d particles, store of %d; rebuild the families",
            (int)pdk_families_num_particles(fam), (int)pdk_particles_count(p));
  pdk_type type = PDK_U8;
  int ncomp = 0;
  PDK_CHECK(pdk_particles_field_exists(p, in), ctx, PDK_ERR_NOT_FOUND,
            "smoothing: field '%s' does not exist", in);
  PDK_CALL(pdk_particles_field_info(p, in, &type, &ncomp));
  PDK_CHECK(type == PDK_F64, ctx, PDK_ERR_ARG, "smoothing: field '%s' must be f64", in);
  PDK_CALL(pdk_particles_field_add(p, out, PDK_F64, ncomp));
  const double delta = pdk_families_horizon(fam);
  const double w0 = (w == PDK_INFLUENCE_INV_R || w == PDK_INFLUENCE_INV_R2)
                        ? 10.0
                        : pdk_influence_eval(w, 0.0, delta, gaussian_width);
  const pdk_index n = pdk_particles_count(p);
  const int dim = pdk_particles_dim(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const double *V = pdk_particles_volume(p);
  const double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                        dim == 3 ? pdk_particles_X(p, 2) : NULL};
  for (int c = 0; c < ncomp; ++c) {
    const double *u = pdk_particles_field_data(p, in, c);
    double *us = pdk_particles_field_data(p, out, c);
#pragma omp parallel for schedule(static) num_threads(ctx->num_threads)
    for (pdk_index i = 0; i < n; ++i) {
      double num = w0 * V[i] * u[i], den = w0 * V[i];
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const pdk_index j = bj[b];
        double r2 = 0.0;
        for (int a = 0; a < dim; ++a) r2 += (X[a][j] - X[a][i]) * (X[a][j] - X[a][i]);
        const double r = sqrt(r2);
        const double wj = r > 0.0 ? pdk_influence_eval(w, r, delta, gaussian_width) * V[j] : 0.0;
        num += wj * u[j];
        den += wj;
      }
      us[i] = den > 0.0 ? num / den : u[i];
    }
  }
  return PDK_SUCCESS;
}
