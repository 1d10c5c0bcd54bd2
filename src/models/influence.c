/* Influence functions of the bond models (pdk_influence_eval, src/models/model_impl.h): below the
 * kinds, which weight their bonds with them. */
#include <math.h>

#include "model_impl.h"
#include "pdk/model.h"

double pdk_influence_eval(pdk_influence kind, double r, double delta, double gaussian_width) {
  /* Families admit r up to delta (1 + PDK_HORIZON_RTOL); q is clamped to 1 so the weights that
   * vanish at the horizon (linear, cubic) never turn negative by round-off. */
  double q = r / delta;
  if (q > 1.0) q = 1.0;
  switch (kind) {
  case PDK_INFLUENCE_CONSTANT: return 1.0;
  case PDK_INFLUENCE_INV_R: return 1.0 / q;
  case PDK_INFLUENCE_INV_R2: return 1.0 / (q * q);
  case PDK_INFLUENCE_LINEAR: return 1.0 - q;
  case PDK_INFLUENCE_CUBIC: return (1.0 - q) * (1.0 - q) * (1.0 - q);
  case PDK_INFLUENCE_QUADRATIC: return (1.0 - q) * (1.0 - q);
  case PDK_INFLUENCE_GAUSSIAN: {
    double s = q / gaussian_width;
    return exp(-s * s);
  }
  }
  return 0.0;
}
