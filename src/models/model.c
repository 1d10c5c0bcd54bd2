/* Model creation, option checks, bond state, dispatch to the kind's operations. */
#include <math.h>
#include <string.h>

#include "model_bond.h"
#include "model_impl.h"
#include "model_stencil.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

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
  o.jc = pdk_jc_params_default();
  o.failed_keeps_bonds = 0;
  o.connectivity = PDK_CONNECTIVITY_TL;
  o.compact_fraction = 0.02;
  o.ul_skin = 0.25;
  o.thickness = 1.0;
  o.stab_softening_floor = 1e-3;
  return o;
}

static int check_opts(pdk_ctx *ctx, const pdk_model_opts *o) {
  PDK_CHECK(pdk_model_kind_info_of(o->kind), ctx, PDK_ERR_ARG,
            "model kind %d is not one of pmb (0), lps (1), correspondence (2), oterkus (3), "
            "galerkin (4)",
            (int)o->kind);
  PDK_CHECK(o->lps_use_influence == 0 || o->lps_use_influence == 1, ctx, PDK_ERR_ARG,
            "lps_use_influence must be 0 or 1, got %d", o->lps_use_influence);
  const char *name = pdk_model_kind_name(o->kind);
  PDK_CHECK(isfinite(o->bulk_modulus) && o->bulk_modulus > 0, ctx, PDK_ERR_ARG,
            "%s model: bulk modulus must be a positive finite pressure, got %g", name, o->bulk_modulus);
  PDK_CHECK(isfinite(o->density) && o->density > 0, ctx, PDK_ERR_ARG,
            "%s model: density must be positive and finite, got %g", name, o->density);
  if (pdk_model_opts_has(o, PDK_KIND_SHEAR))
    PDK_CHECK(isfinite(o->shear_modulus) && o->shear_modulus > 0, ctx, PDK_ERR_ARG,
              "%s model: shear modulus must be a positive finite pressure, got %g", name,
              o->shear_modulus);
  PDK_CHECK(isfinite(o->critical_stretch) && o->critical_stretch >= 0, ctx, PDK_ERR_ARG,
            "critical stretch must be >= 0 (0 disables bond breaking), got %g", o->critical_stretch);
  PDK_CHECK(isfinite(o->alpha) && o->alpha >= 0, ctx, PDK_ERR_ARG,
            "critical-stretch alpha must be >= 0, got %g", o->alpha);
  PDK_CHECK(isfinite(o->lattice_constant) && o->lattice_constant >= 0, ctx, PDK_ERR_ARG,
            "lattice constant for partial volumes must be >= 0 (0 disables), got %g", o->lattice_constant);
  PDK_CHECK((unsigned)o->influence <= PDK_INFLUENCE_QUADRATIC, ctx, PDK_ERR_ARG,
            "influence function %d unknown; use constant, 1/r, 1/r^2, linear, quadratic, cubic or "
            "gaussian",
            (int)o->influence);
  PDK_CHECK(o->influence != PDK_INFLUENCE_GAUSSIAN || (isfinite(o->gaussian_width) && o->gaussian_width > 0),
            ctx, PDK_ERR_ARG, "gaussian influence width must be > 0 (fraction of the horizon), got %g",
            o->gaussian_width);
  PDK_CHECK((unsigned)o->stabilization <= PDK_STAB_HOURGLASS, ctx, PDK_ERR_ARG,
            "stabilization %d unknown; use none, silling or hourglass", (int)o->stabilization);
  PDK_CHECK(isfinite(o->stab_coefficient) && o->stab_coefficient >= 0, ctx, PDK_ERR_ARG,
            "stabilization coefficient must be >= 0, got %g", o->stab_coefficient);
  PDK_CHECK(pdk_law_info_of(o->law), ctx, PDK_ERR_ARG,
            "material law %d unknown; use linear_elastic, svk, neo_hooke or jc", (int)o->law);
  PDK_CHECK((unsigned)o->connectivity <= PDK_CONNECTIVITY_UL, ctx, PDK_ERR_ARG,
            "connectivity mode %d unknown; use tl (0), semi_tl (1) or ul (2)",
            (int)o->connectivity);
  PDK_CHECK(o->connectivity == PDK_CONNECTIVITY_TL ||
                pdk_model_opts_scene_key(o, "model.connectivity"),
            ctx, PDK_ERR_UNSUPPORTED,
            "%s connectivity is implemented for the correspondence model only (model kind is "
            "%s); use tl",
            o->connectivity == PDK_CONNECTIVITY_UL ? "ul" : "semi_tl", name);
  PDK_CHECK(isfinite(o->ul_skin) && o->ul_skin >= 0 && o->ul_skin <= 1, ctx, PDK_ERR_ARG,
            "ul_skin must lie in [0, 1] (a fraction of the horizon; 0: never rebuild), got %g",
            o->ul_skin);
  PDK_CHECK(isfinite(o->compact_fraction) && o->compact_fraction >= 0 && o->compact_fraction <= 1,
            ctx, PDK_ERR_ARG, "compact_fraction must lie in [0, 1], got %g", o->compact_fraction);
  PDK_CHECK(o->failed_keeps_bonds == 0 || o->failed_keeps_bonds == 1, ctx, PDK_ERR_ARG,
            "failed_keeps_bonds must be 0 or 1, got %d", o->failed_keeps_bonds);
  if (pdk_law_info_of(o->law)->flags & PDK_LAWF_PLASTICITY) {
    PDK_CHECK(pdk_model_opts_has(o, PDK_KIND_LAWS), ctx, PDK_ERR_ARG,
              "the Johnson-Cook law needs the correspondence model (model kind is %s)", name);
    PDK_CALL(pdk_jc_params_check(ctx, &o->jc));
  }
  PDK_CHECK(o->stab_softening == 0 || o->stab_softening == 1, ctx, PDK_ERR_ARG,
            "stab_softening must be 0 (off) or 1 (plastic), got %d", o->stab_softening);
  if (o->stab_softening) {
    PDK_CHECK(isfinite(o->stab_softening_floor) && o->stab_softening_floor > 0 &&
                  o->stab_softening_floor <= 1,
              ctx, PDK_ERR_ARG,
              "stab_softening_floor must lie in (0, 1] (the smallest factor on the stabilization "
              "modulus; the thesis uses 1e-3), got %g",
              o->stab_softening_floor);
    PDK_CHECK(pdk_model_opts_law_has(o, PDK_LAWF_HISTORY) && o->stabilization == PDK_STAB_SILLING,
              ctx, PDK_ERR_UNSUPPORTED,
              "softened stabilization follows the plastic flow: it needs the correspondence "
              "model with law jc and silling stabilization (model kind %s, law %d, "
              "stabilization %d)",
              name, (int)o->law, (int)o->stabilization);
  }
  PDK_CHECK((unsigned)o->damage_triaxiality <= PDK_TRIAX_FAMILY, ctx, PDK_ERR_ARG,
            "damage_triaxiality %d unknown; use local (0) or family (1)",
            (int)o->damage_triaxiality);
  PDK_CHECK(o->damage_triaxiality == PDK_TRIAX_LOCAL ||
                (pdk_model_opts_law_has(o, PDK_LAWF_HISTORY) && o->jc.damage),
            ctx, PDK_ERR_UNSUPPORTED,
            "damage_triaxiality family averages the pressure of the Johnson-Cook damage law: it "
            "needs the correspondence model with law jc and damage on");
  PDK_CHECK((!o->stab_softening && o->damage_triaxiality == PDK_TRIAX_LOCAL) ||
                o->connectivity != PDK_CONNECTIVITY_UL,
            ctx, PDK_ERR_UNSUPPORTED,
            "%s is implemented for tl and semi_tl connectivity, not ul; use connectivity tl or "
            "semi_tl",
            o->stab_softening ? "softened stabilization" : "damage_triaxiality family");
  PDK_CHECK((unsigned)o->break_stress <= PDK_BREAK_STRESS_CONTINUOUS, ctx, PDK_ERR_ARG,
            "break_stress %d unknown; use refit (0) or continuous (1)", (int)o->break_stress);
  PDK_CHECK(o->break_stress == PDK_BREAK_STRESS_REFIT ||
                (pdk_model_opts_law_has(o, PDK_LAWF_HISTORY) &&
                 o->connectivity != PDK_CONNECTIVITY_UL),
            ctx, PDK_ERR_UNSUPPORTED,
            "break_stress continuous remaps the Johnson-Cook history of particles whose family "
            "lost bonds: it needs the correspondence model with law jc and connectivity tl or "
            "semi_tl (model kind %s, law %d)",
            name, (int)o->law);
  PDK_CHECK(isfinite(o->thickness) && o->thickness > 0, ctx, PDK_ERR_ARG,
            "thickness must be a finite length > 0 (2-D: the out-of-plane thickness the volumes "
            "include; default 1), got %g",
            o->thickness);
  PDK_CHECK((unsigned)o->layout <= PDK_LAYOUT_SELL, ctx, PDK_ERR_ARG,
            "layout %d unknown; use csr or sell", (int)o->layout);
  PDK_CHECK((unsigned)o->bond_lengths <= PDK_BOND_LENGTHS_COMPUTED, ctx, PDK_ERR_ARG,
            "bond_lengths %d unknown; use stored (0) or computed (1)", (int)o->bond_lengths);
  PDK_CHECK(o->sell_sigma >= 0, ctx, PDK_ERR_ARG,
            "sell_sigma must be >= 0 (0: the default window), got %d", o->sell_sigma);
  const pdk_model_kind_info *kind = pdk_model_kind_info_of(o->kind);
  PDK_CHECK(o->layout == PDK_LAYOUT_CSR || kind->ops_for(o)->layout_sell, ctx,
            PDK_ERR_UNSUPPORTED,
            "%s model%s: layout sell is implemented for pmb and lps (LAMMPS's omega) only; use "
            "layout csr",
            pdk_model_kind_name(o->kind), o->lps_use_influence ? " with lps_use_influence" : "");
  PDK_CHECK(o->layout == PDK_LAYOUT_CSR || o->num_materials == 0, ctx, PDK_ERR_UNSUPPORTED,
            "%s model: layout sell does not support multi-material bodies (%d materials); use "
            "layout csr",
            pdk_model_kind_name(o->kind), o->num_materials);
  PDK_CHECK((unsigned)o->stencil <= PDK_STENCIL_ON, ctx, PDK_ERR_ARG,
            "stencil mode %d unknown; use off (0), auto (1) or on (2)", (int)o->stencil);
  if (o->stencil == PDK_STENCIL_ON) {
    PDK_CHECK((kind->caps & PDK_KIND_STENCIL) && !(kind->no_stencil && kind->no_stencil(o)), ctx,
              PDK_ERR_UNSUPPORTED,
              "%s model%s: the stencil path is implemented for the pmb, lps (with LAMMPS's "
              "influence function) and correspondence models only; use stencil off or auto",
              name, o->lps_use_influence ? " with lps_use_influence" : "");
    const char *why = kind->stencil_refusal ? kind->stencil_refusal(o) : NULL;
    PDK_CHECK(!why, ctx, PDK_ERR_UNSUPPORTED, "%s", why);
  }
  PDK_CHECK((unsigned)o->precision <= PDK_PRECISION_FLOAT, ctx, PDK_ERR_ARG,
            "precision %d unknown; use double or float", (int)o->precision);
  /* Float storage is a speed/accuracy knob; a kind that does not implement it refuses it rather
   * than silently computing in double (PMB, LPS: bond lengths; correspondence TL and semi-TL:
   * pass-2 tensors, UL refuses it in its setup). */
  PDK_CHECK(o->precision == PDK_PRECISION_DOUBLE || pdk_model_opts_has(o, PDK_KIND_FLOAT),
            ctx, PDK_ERR_UNSUPPORTED,
            "%s model: float storage is not implemented yet; use precision double",
            pdk_model_kind_name(o->kind));
  return PDK_SUCCESS;
}

/* Law JC: the Johnson-Cook parameters are the one source of truth for the elastic constants and
 * the density. Zero model values are taken from them; given values must agree. */
static int resolve_jc_constants(pdk_ctx *ctx, pdk_model_opts *o) {
  if (!(pdk_law_info_of(o->law)->flags & PDK_LAWF_PLASTICITY)) return PDK_SUCCESS;
  const double E = o->jc.young_modulus, nu = o->jc.poisson_ratio;
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  const double rtol = 1e-9;
  const double *have[3] = {&o->bulk_modulus, &o->shear_modulus, &o->density};
  const double want[3] = {K, G, o->jc.density};
  const char *what[3] = {"bulk modulus", "shear modulus", "density"};
  for (int k = 0; k < 3; ++k) {
    if (*have[k] == 0.0) continue;
    PDK_CHECK(fabs(*have[k] - want[k]) <= rtol * fabs(want[k]), ctx, PDK_ERR_ARG,
              "Johnson-Cook law: the model's %s %.17g disagrees with %.17g from the Johnson-Cook "
              "parameters (E %g, nu %g, density %g); leave it 0 to take the Johnson-Cook value",
              what[k], *have[k], want[k], E, nu, o->jc.density);
  }
  o->bulk_modulus = K;
  o->shear_modulus = G;
  o->density = o->jc.density;
  return PDK_SUCCESS;
}

/* Multi-material: checks the materials and the "material" field, copies the materials, and fills
 * the per-particle constants. One-material bodies: nothing. */
static int setup_materials(pdk_model *m, const pdk_model_opts *in) {
  pdk_ctx *ctx = m->ctx;
  const int nm = in->num_materials;
  if (nm == 0) return PDK_SUCCESS;
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index n_pad = pdk_particles_count_padded(m->p);
  pdk_type type;
  int comp;
  PDK_CHECK(pdk_particles_field_exists(m->p, "material"), ctx, PDK_ERR_ARG,
            "%d materials given but the particle store has no \"material\" field; add an int32 "
            "field \"material\" holding each particle's material index",
            nm);
  PDK_CALL(pdk_particles_field_info(m->p, "material", &type, &comp));
  PDK_CHECK(type == PDK_I32 && comp == 1, ctx, PDK_ERR_ARG,
            "the \"material\" field must be int32 with one component (type %d, %d components)",
            (int)type, comp);
  const int32_t *mat = pdk_particles_field_data(m->p, "material", 0);
  for (pdk_index i = 0; i < n; ++i)
    PDK_CHECK(mat[i] >= 0 && mat[i] < nm, ctx, PDK_ERR_ARG,
              "particle id %lld has material %d; materials are 0 .. %d",
              (long long)pdk_particles_id(m->p)[i], (int)mat[i], nm - 1);
  m->materials = malloc((size_t)nm * sizeof *m->materials);
  m->mat_bulk = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
  m->mat_shear = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
  m->mat_density = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
  PDK_CHECK(m->materials && m->mat_bulk && m->mat_shear && m->mat_density, ctx, PDK_ERR_MEMORY,
            "out of memory for the per-particle material constants");
  memcpy(m->materials, in->materials, (size_t)nm * sizeof *m->materials);
  m->opts.materials = m->materials;
  for (pdk_index i = 0; i < n; ++i) {
    const pdk_material *q = &m->materials[mat[i]];
    m->mat_bulk[i] = q->bulk_modulus;
    m->mat_shear[i] = q->shear_modulus;
    m->mat_density[i] = q->density;
  }
  if (pdk_model_opts_has(in, PDK_KIND_LAWS)) {
    /* As the one-material drivers compute lambda and the stabilization modulus. */
    const double c_d = pdk_particles_dim(m->p) == 3 ? 72.0 / 5.0 : 36.0 / 5.0;
    m->mat_lambda = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    m->mat_stab = pdk_alloc_aligned((size_t)n_pad, sizeof(double));
    PDK_CHECK(m->mat_lambda && m->mat_stab, ctx, PDK_ERR_MEMORY,
              "out of memory for the per-particle material constants");
    for (pdk_index i = 0; i < n; ++i) {
      m->mat_lambda[i] = m->mat_bulk[i] - 2.0 * m->mat_shear[i] / 3.0;
      m->mat_stab[i] = in->stab_coefficient * c_d * m->mat_bulk[i];
    }
  }
  return PDK_SUCCESS;
}

/* Multi-material options: each material's constants, and the models that support them. */
static int check_materials(pdk_ctx *ctx, const pdk_model_opts *o) {
  PDK_CHECK(o->num_materials >= 0 && o->num_materials <= 65536, ctx, PDK_ERR_ARG,
            "num_materials must lie in [0, 65536], got %d", o->num_materials);
  if (o->num_materials == 0) return PDK_SUCCESS;
  PDK_CHECK(o->materials, ctx, PDK_ERR_ARG, "num_materials is %d but materials is NULL",
            o->num_materials);
  char kinds[128];
  PDK_CHECK(!pdk_model_kind_info_of(o->kind) || pdk_model_opts_has(o, PDK_KIND_MATERIALS), ctx,
            PDK_ERR_UNSUPPORTED,
            "%s model: several materials are not implemented; use %s, or one material",
            pdk_model_kind_name(o->kind),
            pdk_model_kinds_list(PDK_KIND_MATERIALS | PDK_KIND_SCENE,
                                 PDK_KIND_MATERIALS | PDK_KIND_SCENE, " or ", kinds, sizeof kinds));
  PDK_CHECK(!pdk_model_opts_law_has(o, PDK_LAWF_ONE_MATERIAL), ctx, PDK_ERR_UNSUPPORTED,
            "the Johnson-Cook law takes one material (its parameters); several materials work "
            "with the elastic laws");
  for (int k = 0; k < o->num_materials; ++k) {
    const pdk_material *q = &o->materials[k];
    PDK_CHECK(isfinite(q->bulk_modulus) && q->bulk_modulus > 0, ctx, PDK_ERR_ARG,
              "material %d: bulk modulus must be a positive finite pressure, got %g", k,
              q->bulk_modulus);
    PDK_CHECK(!pdk_model_opts_has(o, PDK_KIND_SHEAR) ||
                  (isfinite(q->shear_modulus) && q->shear_modulus > 0),
              ctx, PDK_ERR_ARG,
              "material %d: shear modulus must be a positive finite pressure, got %g", k,
              q->shear_modulus);
    PDK_CHECK(isfinite(q->density) && q->density > 0, ctx, PDK_ERR_ARG,
              "material %d: density must be positive and finite, got %g", k, q->density);
  }
  return PDK_SUCCESS;
}

/* Bonds can break: a critical stretch, or failed particles of the law that break theirs. */
static int model_can_break(const pdk_model_opts *o) {
  return o->critical_stretch > 0 || pdk_model_opts_law_breaks(o);
}

int pdk_model_create(pdk_particles *p, pdk_families *fam, const pdk_model_opts *opts_in,
                     pdk_model **out) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  int err = PDK_SUCCESS;
  pdk_model *m = NULL;
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(fam, ctx);
  PDK_CHECK_ARG(opts_in, ctx);
  pdk_model_opts resolved = *opts_in;
  const pdk_model_opts *opts = &resolved;
  if (pdk_model_opts_law_has(&resolved, PDK_LAWF_PLASTICITY)) {
    PDK_CALL(pdk_jc_params_check(ctx, &resolved.jc));
    PDK_CALL(resolve_jc_constants(ctx, &resolved));
  }
  PDK_CALL(check_materials(ctx, &resolved));
  if (resolved.num_materials > 0) {
    resolved.bulk_modulus = resolved.materials[0].bulk_modulus;
    resolved.shear_modulus = resolved.materials[0].shear_modulus;
    resolved.density = resolved.materials[0].density;
  }
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
  m->info = pdk_model_kind_info_of(opts->kind);
  m->ops = m->info->ops_for(opts);
  PDK_CHECK_GOTO(m->ops && m->ops->setup, ctx, PDK_ERR_UNSUPPORTED,
                 "model kind '%s' is not part of this build", pdk_model_kind_name(opts->kind));
  PDK_CALL_GOTO(setup_materials(m, opts));
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  if (!pdk_particles_field_exists(p, "x")) {
    PDK_CALL_GOTO(pdk_particles_field_add(p, "x", PDK_F64, dim));
    for (int c = 0; c < dim; ++c)
      memcpy(pdk_particles_field_data(p, "x", c), pdk_particles_X(p, c), (size_t)n * sizeof(double));
  }
  PDK_CALL_GOTO(pdk_particles_field_add(p, "f", PDK_F64, dim));
  if (model_can_break(opts)) {
    pdk_bond_index nb = pdk_families_num_bonds(fam);
    m->bond_alive = pdk_alloc_aligned((size_t)(nb > 0 ? nb : 1), 1);
    PDK_CHECK_GOTO(m->bond_alive, ctx, PDK_ERR_MEMORY,
                   "out of memory for the bond state of %lld bonds", (long long)nb);
    memset(m->bond_alive, 1, (size_t)nb);
  }
  if (opts->critical_stretch > 0) {
    m->s0 = pdk_alloc_aligned((size_t)pdk_particles_count_padded(p), sizeof(double));
    PDK_CHECK_GOTO(m->s0, ctx, PDK_ERR_MEMORY, "out of memory for the critical stretches");
    for (pdk_index i = 0; i < n; ++i) m->s0[i] = opts->critical_stretch;
  }
  PDK_CALL_GOTO(pdk_model_ranks_setup(m));
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
  pdk_stencil_destroy(&m->stencil);
  pdk_free_aligned(m->bond_alive);
  pdk_free_aligned(m->s0);
  pdk_free_aligned(m->book_prev);
  pdk_free_aligned(m->book_pending);
  pdk_free_aligned(m->book_lost);
  pdk_free_aligned(m->mat_bulk);
  pdk_free_aligned(m->mat_shear);
  pdk_free_aligned(m->mat_density);
  pdk_free_aligned(m->mat_lambda);
  pdk_free_aligned(m->mat_stab);
  free(m->materials);
  free(m->row_start);
  free(m);
  *mp = NULL;
}

int pdk_model_force(pdk_model *m, double *strain_energy) {
  PDK_CHECK_ARG(m, NULL);
  return m->ops->force(m, 1, strain_energy);
}
int pdk_model_force_trial(pdk_model *m, double *strain_energy) {
  PDK_CHECK_ARG(m, NULL);
  return m->ops->force(m, 0, strain_energy);
}

const pdk_model_opts *pdk_model_opts_get(const pdk_model *m) { return m ? &m->opts : NULL; }
pdk_particles *pdk_model_particles(const pdk_model *m) { return m ? m->p : NULL; }
pdk_families *pdk_model_families(const pdk_model *m) { return m ? m->fam : NULL; }
const uint8_t *pdk_model_bond_alive(const pdk_model *m) { return m ? m->bond_alive : NULL; }
pdk_bond_index pdk_model_num_broken(const pdk_model *m) { return m ? m->num_broken : 0; }
pdk_index pdk_model_num_flagged(const pdk_model *m) { return m ? m->num_flagged : 0; }
int pdk_model_stencil_active(const pdk_model *m) { return m && m->stencil != NULL; }
const char *pdk_model_stencil_reason(const pdk_model *m) { return m ? m->stencil_why : ""; }
pdk_index pdk_model_num_failed(const pdk_model *m) { return m ? m->num_failed : 0; }

/* 1 when the model's law declares history field `name` (law jc: "damage", ...). */
static int law_declares(const pdk_model *m, const char *name) {
  if (!pdk_model_opts_has(&m->opts, PDK_KIND_LAWS)) return 0;
  const pdk_law_info *law = pdk_law_info_of(m->opts.law);
  for (const char *const *h = law ? law->history_fields : NULL; h && *h; ++h)
    if (!strcmp(*h, name)) return 1;
  return 0;
}

double pdk_model_damage_max(const pdk_model *m) {
  /* the law's D only: a scene's output field "damage" of another model is the bond damage */
  if (!m || !law_declares(m, "damage")) return 0.0;
  const double *D = pdk_particles_field_data(m->p, "damage", 0);
  if (!D) return 0.0;
  const pdk_index n = pdk_particles_count(m->p);
  double dmax = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    dmax = D[i] > dmax ? D[i] : dmax;
  return dmax;
}

double pdk_model_padding_fraction(const pdk_model *m) {
  if (!m || !m->ops->padding_fraction) return 0.0;
  return m->ops->padding_fraction(m);
}

double pdk_model_float_stretch_ratio(const pdk_model *m) {
  if (!m || m->opts.precision != PDK_PRECISION_FLOAT || !m->ops->float_bond_lengths) return -1.0;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const pdk_index n = pdk_families_num_particles(m->fam);
  const int dim = pdk_particles_dim(m->p);
  const double *X[3] = {NULL, NULL, NULL}, *x[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    X[c] = pdk_particles_X(m->p, c);
    x[c] = pdk_particles_field_data(m->p, "x", c);
  }
  const uint8_t *alive = m->bond_alive;
  double smax = 0.0;
#pragma omp parallel for default(none) shared(bs, bj, n, dim, X, x, alive) reduction(max : smax)     \
    num_threads(m->ctx->num_threads) schedule(static)
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      if (alive && !alive[b]) continue;
      const pdk_index j = bj[b];
      double r0 = 0.0, r = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double d0 = X[c][j] - X[c][i], d = x[c][j] - x[c][i];
        r0 += d0 * d0;
        r += d * d;
      }
      smax = fmax(smax, fabs(sqrt(r) / sqrt(r0) - 1.0));
    }
  return smax / 0x1p-24;
}
pdk_index pdk_model_num_isolated(const pdk_model *m) {
  if (!m) return 0;
  /* The bond state indexes the families given at creation; ul (no bond state) walks its own. */
  const pdk_families *fam = m->bond_alive ? m->fam : pdk_model_current_families(m);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index n = pdk_families_num_particles(fam);
  pdk_index count = 0;
  for (pdk_index i = 0; i < n; ++i) {
    int intact = 0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1] && !intact; ++b)
      intact = !m->bond_alive || m->bond_alive[b];
    count += !intact;
  }
  return count;
}
long pdk_model_num_compactions(const pdk_model *m) { return m ? m->num_compactions : 0; }
long pdk_model_num_rebuilds(const pdk_model *m) { return m ? m->num_rebuilds : 0; }
double pdk_model_rebuild_work(const pdk_model *m) { return m ? m->rebuild_work : 0.0; }

int pdk_model_rebuild(pdk_model *m) {
  PDK_CHECK_ARG(m, NULL);
  PDK_CHECK(m->ops->rebuild, m->ctx, PDK_ERR_ARG,
            "pdk_model_rebuild: only the ul connectivity rebuilds its families (this %s model "
            "uses %s)",
            pdk_model_kind_name(m->opts.kind),
            m->opts.connectivity == PDK_CONNECTIVITY_SEMI_TL ? "semi_tl" : "tl");
  return m->ops->rebuild(m);
}

pdk_families *pdk_model_current_families(const pdk_model *m) {
  if (!m) return NULL;
  return m->ops->current_families ? m->ops->current_families(m) : m->fam;
}

int pdk_model_set_dt(pdk_model *m, double dt) {
  PDK_CHECK_ARG(m, NULL);
  PDK_CHECK(isfinite(dt) && dt > 0, m->ctx, PDK_ERR_ARG, "model time step must be > 0 and finite, got %g",
            dt);
  m->dt = dt;
  return PDK_SUCCESS;
}

double pdk_model_get_dt(const pdk_model *m) { return m ? m->dt : NAN; }

/* Particles per block of the energy sums: a constant, so the order of the sum is fixed. */
#define PDK_MODEL_SUM_BLOCK 4096

/* sum_i V_i w_i over field `name` (0 when the field does not exist), in fixed blocks. */
static int volume_sum(pdk_model *m, const char *name, double *out) {
  *out = 0.0;
  const double *w = pdk_particles_field_data(m->p, name, 0);
  if (!w) return PDK_SUCCESS;
  const double *volume = pdk_particles_volume(m->p);
  const pdk_index n = pdk_particles_count(m->p);
  const pdk_index num_blocks = (n + PDK_MODEL_SUM_BLOCK - 1) / PDK_MODEL_SUM_BLOCK;
  double *part = malloc((size_t)(num_blocks > 0 ? num_blocks : 1) * sizeof *part);
  PDK_CHECK(part, m->ctx, PDK_ERR_MEMORY, "out of memory summing energies");
  const int nt = m->ctx->num_threads;
#pragma omp parallel for default(none) shared(part, w, volume, n, num_blocks) schedule(static)    \
    num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = blk * PDK_MODEL_SUM_BLOCK;
    const pdk_index i1 = i0 + PDK_MODEL_SUM_BLOCK < n ? i0 + PDK_MODEL_SUM_BLOCK : n;
    double s = 0.0;
    for (pdk_index i = i0; i < i1; ++i)
      s += volume[i] * w[i];
    part[blk] = s;
  }
  double total = 0.0;
  for (pdk_index blk = 0; blk < num_blocks; ++blk)
    total += part[blk];
  free(part);
  *out = total;
  return PDK_SUCCESS;
}

int pdk_model_plastic_work(pdk_model *m, double *plastic, double *damage, double *breaking) {
  PDK_CHECK_ARG(m, NULL);
  if (plastic) {
    PDK_CALL(volume_sum(m, "w_plastic", plastic));
    if (pdk_particles_field_exists(m->p, "w_stab")) {
      double stab;
      PDK_CALL(volume_sum(m, "w_stab", &stab));
      *plastic += stab;
    }
  }
  if (damage) PDK_CALL(volume_sum(m, "w_damage", damage));
  if (breaking) PDK_CALL(volume_sum(m, "w_broken", breaking));
  return PDK_SUCCESS;
}

int pdk_model_bond_damage(const pdk_model *m, double *out) {
  PDK_CHECK_ARG(m, NULL);
  PDK_CHECK_ARG(out, m->ctx);
  const pdk_index n = pdk_particles_count(m->p);
  const uint8_t *alive = m->bond_alive;
  if (!alive) { /* bonds cannot break */
    memset(out, 0, (size_t)n * sizeof *out);
    return PDK_SUCCESS;
  }
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const int dim = pdk_particles_dim(m->p);
  const double *X[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) X[c] = pdk_particles_X(m->p, c);
  const double *V = pdk_particles_volume(m->p);
  /* the partial-volume factor of the kinds that scale V_j with it (kernels/ref/pmb.c) */
  const double lattice = m->ops->partial_volumes ? m->opts.lattice_constant : 0.0;
  const double delta = pdk_families_horizon(m->fam);
  const double vs_a = lattice > 0 ? delta + 0.5 * lattice : HUGE_VAL;
  const double vs_b = lattice > 0 ? 1.0 / lattice : 1.0;
#pragma omp parallel for default(none) shared(n, alive, bs, bj, dim, X, V, vs_a, vs_b, out)           schedule(static) num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i) {
    double all = 0.0, intact = 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      double r0 = 0.0;
      for (int c = 0; c < dim; ++c) r0 += (X[c][j] - X[c][i]) * (X[c][j] - X[c][i]);
      const double w = V[j] * fmin(1.0, (vs_a - sqrt(r0)) * vs_b);
      all += w;
      if (alive[b]) intact += w;
    }
    out[i] = all > 0.0 ? 1.0 - intact / all : 0.0;
  }
  return PDK_SUCCESS;
}

/* Derived fields of every model: the bond damage, also as "damage" when the law has no damage
 * variable of its own. */
static const pdk_model_derived_info common_derived[] = {{"bond_damage", "bond damage"},
                                                        {"damage", "bond damage"}};

const pdk_model_derived_info *pdk_model_derived_at(const pdk_model *m, int i) {
  if (!m || i < 0) return NULL;
  const pdk_model_derived_info *own = m->info->derived;
  int count = 0;
  while (own && own[count].name) ++count;
  if (i < count) return &own[i];
  i -= count;
  if (i == 1 && law_declares(m, "damage")) return NULL;
  return i < 2 ? &common_derived[i] : NULL;
}

const pdk_model_derived_info *pdk_model_derived_of(const pdk_model *m, const char *name) {
  const pdk_model_derived_info *d;
  for (int i = 0; name && (d = pdk_model_derived_at(m, i)) != NULL; ++i)
    if (!strcmp(d->name, name)) return d;
  return NULL;
}

int pdk_model_derived(const pdk_model *m, const char *name, double dt, double *out) {
  PDK_CHECK_ARG(m, NULL);
  const pdk_model_derived_info *d = pdk_model_derived_of(m, name);
  if (d && (d == &common_derived[0] || d == &common_derived[1]))
    return pdk_model_bond_damage(m, out);
  PDK_CHECK(m->ops->derived && pdk_model_kind_derived(m->opts.kind, name), m->ctx,
            PDK_ERR_NOT_FOUND, "the %s model derives no field '%s'",
            pdk_model_kind_name(m->opts.kind), name);
  return m->ops->derived(m, name, dt, out);
}

int pdk_model_opts_uses(const pdk_model_opts *o, const char *name) {
  if (!o || !name) return 0;
  if (!strcmp(name, "stab_softening") || !strcmp(name, "damage_triaxiality") ||
      !strcmp(name, "break_stress"))
    return pdk_model_opts_law_has(o, PDK_LAWF_HISTORY) && o->connectivity != PDK_CONNECTIVITY_UL;
  char key[64];
  snprintf(key, sizeof key, "model.%s", name);
  return pdk_model_opts_scene_key(o, key);
}

int pdk_model_has_tangent(const pdk_model *m) { return m && m->ops->tangent_column != NULL; }
