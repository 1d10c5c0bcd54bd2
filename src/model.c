/* Model creation, option checks, bond state, dispatch to the kind's operations. */
#include <math.h>
#include <string.h>

#include "model_impl.h"

pdk_model_opts pdk_model_opts_default(void) {
  pdk_model_opts o;
  memset(&o, 0, sizeof o);
  o.kind = PDK_MODEL_PMB;
  o.influence = PDK_INFLUENCE_CONSTANT;
  o.gaussian_width = 0.5;
  o.stabilization = PDK_STAB_NONE;
  o.stab_coefficient = 0.1;
  o.law = PDK_LAW_LINEAR_ELASTIC;
  o.precision = PDK_PRECISION_DOUBLE;
  return o;
}

const char *pdk_model_kind_name(pdk_model_kind kind) {
  switch (kind) {
  case PDK_MODEL_PMB: return "pmb";
  case PDK_MODEL_LPS: return "lps";
  case PDK_MODEL_CORRESPONDENCE: return "correspondence";
  }
  return "?";
}

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
  case PDK_INFLUENCE_GAUSSIAN: {
    double s = q / gaussian_width;
    return exp(-s * s);
  }
  }
  return 0.0;
}

static int check_opts(pdk_ctx *ctx, const pdk_model_opts *o) {
  PDK_CHECK((unsigned)o->kind <= PDK_MODEL_CORRESPONDENCE, ctx, PDK_ERR_ARG,
            "model kind %d is not one of pmb (0), lps (1), correspondence (2)", (int)o->kind);
  const char *name = pdk_model_kind_name(o->kind);
  PDK_CHECK(isfinite(o->bulk_modulus) && o->bulk_modulus > 0, ctx, PDK_ERR_ARG,
            "%s model: bulk modulus must be a positive finite pressure, got %g", name, o->bulk_modulus);
  PDK_CHECK(isfinite(o->density) && o->density > 0, ctx, PDK_ERR_ARG,
            "%s model: density must be positive and finite, got %g", name, o->density);
  if (o->kind != PDK_MODEL_PMB)
    PDK_CHECK(isfinite(o->shear_modulus) && o->shear_modulus > 0, ctx, PDK_ERR_ARG,
              "%s model: shear modulus must be a positive finite pressure, got %g", name,
              o->shear_modulus);
  PDK_CHECK(isfinite(o->critical_stretch) && o->critical_stretch >= 0, ctx, PDK_ERR_ARG,
            "critical stretch must be >= 0 (0 disables bond breaking), got %g", o->critical_stretch);
  PDK_CHECK(isfinite(o->alpha) && o->alpha >= 0, ctx, PDK_ERR_ARG,
            "critical-stretch alpha must be >= 0, got %g", o->alpha);
  PDK_CHECK(isfinite(o->lattice_constant) && o->lattice_constant >= 0, ctx, PDK_ERR_ARG,
            "lattice constant for partial volumes must be >= 0 (0 disables), got %g", o->lattice_constant);
  PDK_CHECK((unsigned)o->influence <= PDK_INFLUENCE_GAUSSIAN, ctx, PDK_ERR_ARG,
            "influence function %d unknown; use constant, 1/r, 1/r^2, linear, cubic or gaussian",
            (int)o->influence);
  PDK_CHECK(o->influence != PDK_INFLUENCE_GAUSSIAN || (isfinite(o->gaussian_width) && o->gaussian_width > 0),
            ctx, PDK_ERR_ARG, "gaussian influence width must be > 0 (fraction of the horizon), got %g",
            o->gaussian_width);
  PDK_CHECK((unsigned)o->stabilization <= PDK_STAB_HOURGLASS, ctx, PDK_ERR_ARG,
            "stabilization %d unknown; use none, silling or hourglass", (int)o->stabilization);
  PDK_CHECK(isfinite(o->stab_coefficient) && o->stab_coefficient >= 0, ctx, PDK_ERR_ARG,
            "stabilization coefficient must be >= 0, got %g", o->stab_coefficient);
  PDK_CHECK((unsigned)o->law <= PDK_LAW_NEO_HOOKE, ctx, PDK_ERR_ARG,
            "material law %d unknown; use linear_elastic, svk or neo_hooke", (int)o->law);
  PDK_CHECK((unsigned)o->precision <= PDK_PRECISION_FLOAT, ctx, PDK_ERR_ARG,
            "precision %d unknown; use double or float", (int)o->precision);
  return PDK_SUCCESS;
}

int pdk_model_create(pdk_particles *p, pdk_families *fam, const pdk_model_opts *opts,
                     pdk_model **out) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  int err = PDK_SUCCESS;
  pdk_model *m = NULL;
  *out = NULL;
  PDK_CALL(check_opts(ctx, opts));
  PDK_CHECK(pdk_families_num_particles(fam) == pdk_particles_count(p), ctx, PDK_ERR_ARG,
            "families were built for %d particles but the store holds %d; rebuild the families",
            (int)pdk_families_num_particles(fam), (int)pdk_particles_count(p));
  m = calloc(1, sizeof *m);
  PDK_CHECK(m, ctx, PDK_ERR_MEMORY, "out of memory creating a model");
  m->ctx = ctx;
  m->p = p;
  m->fam = fam;
  m->opts = *opts;
  switch (opts->kind) {
  case PDK_MODEL_PMB: m->ops = &pdk_model_ops_pmb; break;
  case PDK_MODEL_LPS: m->ops = &pdk_model_ops_lps; break;
  case PDK_MODEL_CORRESPONDENCE: m->ops = &pdk_model_ops_corr; break;
  }
  PDK_CHECK_GOTO(m->ops && m->ops->setup, ctx, PDK_ERR_UNSUPPORTED,
                 "model kind '%s' is not part of this build", pdk_model_kind_name(opts->kind));
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  if (!pdk_particles_field_exists(p, "x")) {
    PDK_CALL_GOTO(pdk_particles_field_add(p, "x", PDK_F64, dim));
    for (int c = 0; c < dim; ++c)
      memcpy(pdk_particles_field_data(p, "x", c), pdk_particles_X(p, c), (size_t)n * sizeof(double));
  }
  PDK_CALL_GOTO(pdk_particles_field_add(p, "f", PDK_F64, dim));
  if (opts->critical_stretch > 0) {
    pdk_bond_index nb = pdk_families_num_bonds(fam);
    m->bond_alive = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), 1);
    m->s0 = pdk_alloc_aligned((size_t)pdk_particles_count_padded(p), sizeof(double));
    PDK_CHECK_GOTO(m->bond_alive && m->s0, ctx, PDK_ERR_MEMORY,
                   "out of memory for the bond state of %lld bonds", (long long)nb);
    memset(m->bond_alive, 1, (size_t)nb);
    for (pdk_index i = 0; i < n; ++i) m->s0[i] = opts->critical_stretch;
  }
  PDK_CALL_GOTO(m->ops->setup(m));
  *out = m;
  return PDK_SUCCESS;
cleanup:
  pdk_model_destroy(&m);
  return err;
}

void pdk_model_destroy(pdk_model **mp) {
  if (!mp || !*mp) return;
  pdk_model *m = *mp;
  if (m->ops && m->ops->destroy) m->ops->destroy(m);
  pdk_free_aligned(m->bond_alive);
  pdk_free_aligned(m->s0);
  free(m);
  *mp = NULL;
}

int pdk_model_force(pdk_model *m, double *strain_energy) { return m->ops->force(m, 1, strain_energy); }
int pdk_model_force_trial(pdk_model *m, double *strain_energy) {
  return m->ops->force(m, 0, strain_energy);
}

const pdk_model_opts *pdk_model_opts_get(const pdk_model *m) { return &m->opts; }
pdk_particles *pdk_model_particles(const pdk_model *m) { return m->p; }
pdk_families *pdk_model_families(const pdk_model *m) { return m->fam; }
const uint8_t *pdk_model_bond_alive(const pdk_model *m) { return m->bond_alive; }
pdk_bond_index pdk_model_num_broken(const pdk_model *m) { return m->num_broken; }
pdk_index pdk_model_num_flagged(const pdk_model *m) { return m->num_flagged; }
