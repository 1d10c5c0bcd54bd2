/* Scene loading, step 3 (src/scene/scene.c): material, model (kind, law, options; the Johnson-Cook
 * parameters) and the materials list, resolved into pdk_model_opts; unit conversions of choice
 * (E, nu -> K, G) happen here (src/scene/scene_load.h).
 */
#include "models/model_registry.h"
#include "space/points.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/plasticity.h"
#include "pdk/scene.h"

/* A Johnson-Cook key that the chosen options do not use is an error naming what would use it. */
static int jc_unused(loader *ld, const char *const *keys, int num, const char *why) {
  char key[KEY_MAX];
  for (int k = 0; k < num; ++k) {
    snprintf(key, sizeof key, "material.johnson_cook.%s", keys[k]);
    REQUIRE(ld, !has(ld, key), key, "%s", why);
  }
  return PDK_SUCCESS;
}

/* A required Johnson-Cook number: present and finite. */
static int jc_needed(loader *ld, const char *name, double v, const char *why) {
  char key[KEY_MAX];
  snprintf(key, sizeof key, "material.johnson_cook.%s", name);
  REQUIRE(ld, has(ld, key), key, "is missing; %s", why);
  REQUIRE(ld, isfinite(v), key, "must be a finite number, got %g", v);
  return PDK_SUCCESS;
}

/* material.johnson_cook -> model.jc, for model.law: jc. The elastic constants and the density come
 * from `material` (the model checks they agree with jc to 1e-9, which they do by construction).
 * Every key is checked here against its own scene key; pdk_jc_params_check runs last as a
 * backstop. */
static int resolve_johnson_cook(loader *ld, const sc_material *mat, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  const int hjc = has(ld, "material.johnson_cook") && mat->johnson_cook;
  if (!pdk_model_opts_law_has(m, PDK_LAWF_PLASTICITY)) {
    REQUIRE(ld, !has(ld, "material.johnson_cook"), "material.johnson_cook",
            "only the jc law uses it (model.law is %s); remove it or set model.law: jc",
            pdk_law_name(m->law));
    REQUIRE(ld, !has(ld, "model.failed_keeps_bonds"), "model.failed_keeps_bonds",
            "only the jc law with damage has failed particles (model.law is %s); remove it",
            pdk_law_name(m->law));
    return PDK_SUCCESS;
  }
  REQUIRE(ld, hjc, "material.johnson_cook",
          "is missing; model.law is jc, so give the Johnson-Cook parameters as a mapping "
          "material.johnson_cook with at least A, B, n (and D1, D2, D3, D_c for damage; see "
          "docs/scenes.md)");
  const sc_jc *j = mat->johnson_cook;
  pdk_jc_params jc = pdk_jc_params_default();
  jc.density = m->density;
  jc.young_modulus =
      9 * m->bulk_modulus * m->shear_modulus / (3 * m->bulk_modulus + m->shear_modulus);
  jc.poisson_ratio =
      (3 * m->bulk_modulus - 2 * m->shear_modulus) / (2 * (3 * m->bulk_modulus + m->shear_modulus));
  if (has(ld, "material.youngs_modulus")) { /* as given, not through K and G */
    jc.young_modulus = mat->youngs_modulus;
    jc.poisson_ratio = mat->poisson_ratio;
  }
  /* hardening */
  REQUIRE(ld, isfinite(j->A) && j->A >= 0, "material.johnson_cook.A",
          "must be >= 0, got %g (the initial yield stress, a pressure)", j->A);
  REQUIRE(ld, isfinite(j->B) && j->B >= 0, "material.johnson_cook.B",
          "must be >= 0, got %g (the hardening modulus, a pressure)", j->B);
  REQUIRE(ld, j->A + j->B > 0, "material.johnson_cook.B",
          "A and B are both 0, a material with no strength; give A + B > 0");
  REQUIRE(ld, isfinite(j->n) && j->n > 0, "material.johnson_cook.n",
          "must be > 0, got %g (the hardening exponent)", j->n);
  jc.A = j->A;
  jc.B = j->B;
  jc.n = j->n;
  jc.C = has(ld, "material.johnson_cook.C") ? j->C : 0.0;
  REQUIRE(ld, isfinite(jc.C) && jc.C >= 0, "material.johnson_cook.C",
          "must be >= 0, got %g (the strain-rate sensitivity; 0 turns the rate term off)", jc.C);
  /* damage (read first: D4 also uses the reference rate) */
  jc.damage = has(ld, "material.johnson_cook.damage") ? (j->damage ? 1 : 0) : 1;
  const char *damage_keys[] = {"D1", "D2", "D3", "D4", "D5", "D_c", "coupling", "failed_mode"};
  if (!jc.damage) {
    PDK_CALL(jc_unused(ld, damage_keys, 8, "only used with damage (damage is false); remove it"));
    REQUIRE(ld, !has(ld, "model.failed_keeps_bonds"), "model.failed_keeps_bonds",
            "only used with Johnson-Cook damage (material.johnson_cook.damage is false); remove "
            "it");
  } else {
    const char *why = "damage is on (damage: true, the default), so the Johnson-Cook failure "
                      "strain D1 + D2 exp(D3 eta) and the critical damage D_c are needed; give "
                      "them, or set damage: false";
    PDK_CALL(jc_needed(ld, "D1", j->D1, why));
    PDK_CALL(jc_needed(ld, "D2", j->D2, why));
    PDK_CALL(jc_needed(ld, "D3", j->D3, why));
    PDK_CALL(jc_needed(ld, "D_c", j->D_c, why));
    REQUIRE(ld, j->D1 + j->D2 > 0, "material.johnson_cook.D2",
            "D1 + D2 = %g: the failure strain at zero triaxiality must be > 0", j->D1 + j->D2);
    REQUIRE(ld, j->D_c > 0 && j->D_c <= 1, "material.johnson_cook.D_c",
            "must lie in (0, 1], got %g (the point fails when D >= D_c; 1 is plain Johnson-Cook "
            "1985, the thesis uses 0.3)",
            j->D_c);
    jc.D1 = j->D1;
    jc.D2 = j->D2;
    jc.D3 = j->D3;
    jc.D_c = j->D_c;
    jc.D4 = has(ld, "material.johnson_cook.D4") ? j->D4 : 0.0;
    REQUIRE(ld, isfinite(jc.D4) && jc.D4 >= 0, "material.johnson_cook.D4",
            "must be >= 0, got %g (the rate term of the failure strain; 0 turns it off)", jc.D4);
    jc.D5 = has(ld, "material.johnson_cook.D5") ? j->D5 : 0.0;
    REQUIRE(ld, isfinite(jc.D5) && jc.D5 >= -1, "material.johnson_cook.D5",
            "must be >= -1, got %g (so that 1 + D5 T* >= 0)", jc.D5);
    REQUIRE(ld, jc.D5 == 0 || j->thermal, "material.johnson_cook.D5",
            "the temperature term of the failure strain needs thermal: true (temperature is not "
            "tracked otherwise); set thermal: true or remove D5");
    if (has(ld, "material.johnson_cook.coupling")) jc.coupling = (pdk_jc_coupling)j->coupling;
    if (has(ld, "material.johnson_cook.failed_mode"))
      jc.failed_mode = (pdk_jc_failed)j->failed_mode;
  }
  /* rate */
  if (jc.C > 0 || jc.D4 > 0) {
    jc.ref_rate =
        has(ld, "material.johnson_cook.reference_strain_rate") ? j->reference_strain_rate : 1.0;
    REQUIRE(ld, isfinite(jc.ref_rate) && jc.ref_rate > 0,
            "material.johnson_cook.reference_strain_rate",
            "must be > 0, got %g (1/s; plastic strain rates below it give no rate effect)",
            jc.ref_rate);
  } else {
    const char *rate_keys[] = {"reference_strain_rate"};
    PDK_CALL(jc_unused(ld, rate_keys, 1,
                       "only the rate terms use it (C and D4 are 0); set C > 0 or D4 > 0, or "
                       "remove it"));
  }
  /* temperature */
  jc.thermal = j->thermal ? 1 : 0;
  const char *thermal_keys[] = {"m", "T_room", "T_melt", "T_initial", "beta", "heat_capacity"};
  if (!jc.thermal) {
    PDK_CALL(jc_unused(ld, thermal_keys, 6,
                       "only used with thermal softening (thermal is false); set thermal: true "
                       "or remove it"));
  } else {
    const char *why = "thermal is true, so the softening exponent m, the temperatures T_room "
                      "and T_melt and the heat capacity are needed";
    PDK_CALL(jc_needed(ld, "m", j->m, why));
    PDK_CALL(jc_needed(ld, "T_room", j->T_room, why));
    PDK_CALL(jc_needed(ld, "T_melt", j->T_melt, why));
    PDK_CALL(jc_needed(ld, "heat_capacity", j->heat_capacity, why));
    REQUIRE(ld, j->m > 0, "material.johnson_cook.m", "must be > 0, got %g", j->m);
    REQUIRE(ld, j->T_melt > j->T_room, "material.johnson_cook.T_melt",
            "must exceed T_room (%g), got %g (temperatures in K)", j->T_room, j->T_melt);
    REQUIRE(ld, j->heat_capacity > 0, "material.johnson_cook.heat_capacity",
            "must be > 0, got %g (J/(kg K) in SI)", j->heat_capacity);
    jc.m = j->m;
    jc.T_room = j->T_room;
    jc.T_melt = j->T_melt;
    jc.heat_capacity = j->heat_capacity;
    jc.T_initial = has(ld, "material.johnson_cook.T_initial") ? j->T_initial : j->T_room;
    REQUIRE(ld, isfinite(jc.T_initial), "material.johnson_cook.T_initial",
            "must be a finite temperature, got %g", jc.T_initial);
    jc.beta = has(ld, "material.johnson_cook.beta") ? j->beta : 0.9;
    REQUIRE(ld, isfinite(jc.beta) && jc.beta >= 0 && jc.beta <= 1, "material.johnson_cook.beta",
            "must lie in [0, 1], got %g (the Taylor-Quinney fraction of plastic work turned into "
            "heat)",
            jc.beta);
  }
  int err = pdk_jc_params_check(ld->ctx, &jc);
  if (err) return pdk_scene_blame(s, ld->ctx, err, "material.johnson_cook");
  m->jc = jc;
  m->failed_keeps_bonds = mo->failed_keeps_bonds ? 1 : 0;
  return PDK_SUCCESS;
}

/* model.connectivity and model.compact_fraction (correspondence; checked as such by the caller). */
static int resolve_connectivity(loader *ld, const sc_model *mo) {
  pdk_model_opts *m = &ld->s->model;
  if (has(ld, "model.connectivity")) m->connectivity = (pdk_connectivity)mo->connectivity;
  if (has(ld, "model.compact_fraction")) {
    REQUIRE(ld, m->connectivity == PDK_CONNECTIVITY_SEMI_TL, "model.compact_fraction",
            "only semi_tl connectivity compacts its bond list (connectivity is tl); set "
            "model.connectivity: semi_tl or remove it");
    REQUIRE(ld,
            isfinite(mo->compact_fraction) && mo->compact_fraction >= 0 &&
                mo->compact_fraction <= 1,
            "model.compact_fraction",
            "must lie in [0, 1], got %g (the fraction of broken entries in the bond list that "
            "triggers a compaction; 0: whenever bonds broke)",
            mo->compact_fraction);
    m->compact_fraction = mo->compact_fraction;
  }
  if (has(ld, "model.ul_skin")) {
    REQUIRE(ld, m->connectivity == PDK_CONNECTIVITY_UL, "model.ul_skin",
            "only ul connectivity rebuilds its families (connectivity is %s); set "
            "model.connectivity: ul or remove it",
            pdk_scene_connectivity_names[m->connectivity].str);
    REQUIRE(ld, isfinite(mo->ul_skin) && mo->ul_skin >= 0 && mo->ul_skin <= 1, "model.ul_skin",
            "must lie in [0, 1], got %g (a fraction of the horizon; 0: never rebuild)",
            mo->ul_skin);
    m->ul_skin = mo->ul_skin;
  }
  if (m->connectivity == PDK_CONNECTIVITY_UL) {
    const int jc_breaks = pdk_model_opts_law_breaks(m);
    REQUIRE(ld, m->critical_stretch == 0 && !jc_breaks, "model.connectivity",
            "ul cannot break bonds (a rebuild in the current configuration would bond broken "
            "pairs again), but %s; use tl or semi_tl, or %s",
            jc_breaks ? "failed Johnson-Cook particles break theirs" : "critical_stretch is set",
            jc_breaks ? "set model.failed_keeps_bonds: true (failed particles then carry no stress "
                        "but keep their bonds)"
                      : "remove model.critical_stretch");
  }
  return PDK_SUCCESS;
}

/* model.stabilization_softening, stabilization_softening_floor, damage_triaxiality,
 * break_stress: Johnson-Cook refinements of the correspondence model (tl, semi_tl). After the law
 * and connectivity. */
static int resolve_softening(loader *ld, const sc_model *mo) {
  pdk_model_opts *m = &ld->s->model;
  const int corr_jc = pdk_model_opts_law_has(m, PDK_LAWF_HISTORY);
  if (has(ld, "model.stabilization_softening")) {
    m->stab_softening = mo->stabilization_softening;
    REQUIRE(ld, !m->stab_softening || (corr_jc && m->stabilization == PDK_STAB_SILLING),
            "model.stabilization_softening",
            "plastic softens the Silling stabilization where the Johnson-Cook material flowed: it "
            "needs model.kind correspondence, model.law jc and model.stabilization silling; use "
            "none or remove it");
    REQUIRE(ld, !m->stab_softening || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.stabilization_softening",
            "plastic is implemented for tl and semi_tl connectivity, not ul; set "
            "model.connectivity: tl or semi_tl, or use none");
  }
  if (has(ld, "model.stabilization_softening_floor")) {
    REQUIRE(ld, m->stab_softening, "model.stabilization_softening_floor",
            "only used with model.stabilization_softening: plastic; set it or remove the floor");
    const double f = mo->stabilization_softening_floor;
    REQUIRE(ld, isfinite(f) && f > 0 && f <= 1, "model.stabilization_softening_floor",
            "must lie in (0, 1], got %g (the smallest factor on the stabilization modulus; the "
            "thesis uses 1e-3, the default)",
            f);
    m->stab_softening_floor = f;
  }
  if (has(ld, "model.damage_triaxiality")) {
    m->damage_triaxiality = (pdk_damage_triaxiality)mo->damage_triaxiality;
    REQUIRE(ld, m->damage_triaxiality == PDK_TRIAX_LOCAL || (corr_jc && m->jc.damage),
            "model.damage_triaxiality",
            "family averages the pressure of the Johnson-Cook damage law: it needs model.kind "
            "correspondence, model.law jc and material.johnson_cook.damage on; use local or "
            "remove it");
    REQUIRE(ld,
            m->damage_triaxiality == PDK_TRIAX_LOCAL || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.damage_triaxiality",
            "family is implemented for tl and semi_tl connectivity, not ul; set "
            "model.connectivity: tl or semi_tl, or use local");
  }
  if (has(ld, "model.break_stress")) {
    m->break_stress = (pdk_break_stress)mo->break_stress;
    REQUIRE(ld, m->break_stress == PDK_BREAK_STRESS_REFIT || corr_jc, "model.break_stress",
            "continuous remaps the Johnson-Cook history when a particle's family loses bonds: it "
            "needs model.kind correspondence and model.law jc; use refit or remove it");
    REQUIRE(ld,
            m->break_stress == PDK_BREAK_STRESS_REFIT || m->connectivity != PDK_CONNECTIVITY_UL,
            "model.break_stress",
            "continuous is implemented for tl and semi_tl connectivity, not ul (which breaks no "
            "bonds); set model.connectivity: tl or semi_tl, or use refit");
    const int breaks = (m->jc.damage && !m->failed_keeps_bonds) || m->critical_stretch > 0;
    REQUIRE(ld, m->break_stress == PDK_BREAK_STRESS_REFIT || breaks, "model.break_stress",
            "continuous acts when bonds break, and none can here (%s); turn on "
            "material.johnson_cook.damage with model.failed_keeps_bonds: false, or set "
            "model.critical_stretch, or remove it",
            m->jc.damage ? "failed particles keep their bonds" : "no damage, no critical stretch");
  }
  return PDK_SUCCESS;
}

/* model.galerkin (kind galerkin; refused for the others by its scene_keys entry). */
static int resolve_galerkin(loader *ld, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_galerkin_opts *g = &s->model.galerkin;
  const sc_galerkin *sg = mo->galerkin;
  if (!sg || !has(ld, "model.galerkin")) return PDK_SUCCESS;
  if (has(ld, "model.galerkin.basis")) g->basis = (pdk_galerkin_basis)sg->basis;
  if (has(ld, "model.galerkin.form")) g->form = (pdk_galerkin_form)sg->form;
  if (has(ld, "model.galerkin.correction")) g->correction = (pdk_galerkin_correction)sg->correction;
  if (has(ld, "model.galerkin.bond")) g->bond = sg->bond ? 1 : 0;
  if (has(ld, "model.galerkin.surface")) {
    REQUIRE(ld, g->correction == PDK_GALERKIN_VC1, "model.galerkin.surface",
            "only the vc1 correction uses it; set model.galerkin.correction: vc1 or remove it");
    s->galerkin_surface = strdup(sg->surface);
    REQUIRE(ld, s->galerkin_surface, "model.galerkin.surface", "out of memory");
    g->surface = s->galerkin_surface;
  }
  if (has(ld, "model.galerkin.normals")) {
    REQUIRE(ld, g->correction == PDK_GALERKIN_VC1, "model.galerkin.normals",
            "only the vc1 correction uses it; set model.galerkin.correction: vc1 or remove it");
    s->galerkin_normals_box = 1;
    g->normals = PDK_SCENE_NORMAL_FIELD;
  }
  REQUIRE(ld, g->correction != PDK_GALERKIN_VC1 || g->surface, "model.galerkin.correction",
          "vc1 needs model.galerkin.surface: the name of the set of the particles on the body's "
          "surface");
  return PDK_SUCCESS;
}

int pdk_scene_resolve_material_model(loader *ld, const sc_material *mat, const sc_model *mo) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  *m = pdk_model_opts_default();
  m->kind = has(ld, "model.kind") ? (pdk_model_kind)mo->kind : pdk_model_kind_at(0)->kind;
  const char *kname = pdk_model_kind_name(m->kind);
  REQUIRE(ld, isfinite(mat->density) && mat->density > 0, "material.density",
          "must be > 0, got %g (mass per volume, e.g. 7850 kg/m^3 for steel)", mat->density);
  m->density = mat->density;
  const int hE = has(ld, "material.youngs_modulus"), hnu = has(ld, "material.poisson_ratio");
  const int hK = has(ld, "material.bulk_modulus"), hG = has(ld, "material.shear_modulus");
  if ((hE || hnu) && (hK || hG))
    FAIL(ld, hK ? "material.bulk_modulus" : "material.shear_modulus",
         "mixes with %s; give either youngs_modulus and poisson_ratio, or bulk_modulus and "
         "shear_modulus",
         hE ? "youngs_modulus" : "poisson_ratio");
  if (hE || hnu) {
    REQUIRE(ld, hE, "material.youngs_modulus",
            "is missing; poisson_ratio is given, so youngs_modulus is needed too");
    REQUIRE(ld, hnu, "material.poisson_ratio",
            "is missing; youngs_modulus is given, so poisson_ratio is needed too");
    const double E = mat->youngs_modulus, nu = mat->poisson_ratio;
    REQUIRE(ld, isfinite(E) && E > 0, "material.youngs_modulus", "must be > 0, got %g", E);
    REQUIRE(ld, isfinite(nu) && nu > -1 && nu < 0.5, "material.poisson_ratio",
            "must be in (-1, 0.5), got %g (0.5 is incompressible, which has no finite bulk "
            "modulus)",
            nu);
    m->bulk_modulus = E / (3 * (1 - 2 * nu));
    m->shear_modulus = E / (2 * (1 + nu));
  } else if (hK || hG) {
    REQUIRE(ld, hK, "material.bulk_modulus",
            "is missing; shear_modulus is given, so bulk_modulus "
            "is needed too");
    char bulk_only[128];
    REQUIRE(ld, hG || !pdk_model_opts_has(m, PDK_KIND_SHEAR), "material.shear_modulus",
            "is missing; the %s model needs bulk_modulus and shear_modulus (only %s needs the "
            "bulk modulus alone)",
            kname,
            pdk_model_kinds_list(PDK_KIND_SHEAR | PDK_KIND_SCENE, PDK_KIND_SCENE, " or ",
                                 bulk_only, sizeof bulk_only));
    REQUIRE(ld, isfinite(mat->bulk_modulus) && mat->bulk_modulus > 0, "material.bulk_modulus",
            "must be > 0, got %g", mat->bulk_modulus);
    if (hG)
      REQUIRE(ld, isfinite(mat->shear_modulus) && mat->shear_modulus > 0, "material.shear_modulus",
              "must be > 0, got %g", mat->shear_modulus);
    m->bulk_modulus = mat->bulk_modulus;
    m->shear_modulus = hG ? mat->shear_modulus : 0;
  } else {
    FAIL(ld, "material",
         "gives no elastic constants; give youngs_modulus and poisson_ratio, or "
         "bulk_modulus and shear_modulus");
  }

  /* the keys only some kinds accept (the kinds' pdk_model_kind_info.scene_keys) */
  for (int k = 0; pdk_model_scene_key_at(k); ++k) {
    const char *key = pdk_model_scene_key_at(k);
    if (pdk_model_opts_scene_key(m, key) || !has(ld, key)) continue;
    char users[128], alt[128];
    int count;
    pdk_model_key_kinds(key, " and ", users, sizeof users, &count);
    FAIL(ld, key, "only the %s model%s %s it (model.kind is %s); remove it or set model.kind: %s",
         users, count > 1 ? "s" : "", count > 1 ? "use" : "uses", kname,
         pdk_model_key_kinds(key, " or ", alt, sizeof alt, NULL));
  }
  if (has(ld, "model.influence")) m->influence = (pdk_influence)mo->influence;
  if (has(ld, "model.oterkus_a")) m->oterkus_a = (pdk_oterkus_a)mo->oterkus_a;
  if (has(ld, "model.gaussian_width")) {
    REQUIRE(ld, m->influence == PDK_INFLUENCE_GAUSSIAN, "model.gaussian_width",
            "only the gaussian influence function uses it; set model.influence: gaussian or "
            "remove it");
    REQUIRE(ld, isfinite(mo->gaussian_width) && mo->gaussian_width > 0, "model.gaussian_width",
            "must be > 0 (a fraction of the horizon), got %g", mo->gaussian_width);
    m->gaussian_width = mo->gaussian_width;
  }
  m->stabilization = has(ld, "model.stabilization")
                         ? (pdk_stabilization)mo->stabilization
                         : pdk_model_kind_info_of(m->kind)->scene_stabilization;
  if (has(ld, "model.stabilization_coefficient")) {
    REQUIRE(ld, isfinite(mo->stabilization_coefficient) && mo->stabilization_coefficient >= 0,
            "model.stabilization_coefficient", "must be >= 0, got %g",
            mo->stabilization_coefficient);
    m->stab_coefficient = mo->stabilization_coefficient;
  }
  if (has(ld, "model.law")) m->law = (pdk_law)mo->law;
  if (has(ld, "model.precision")) m->precision = (pdk_precision)mo->precision;
  if (has(ld, "model.layout")) m->layout = (pdk_layout)mo->layout;
  if (has(ld, "model.bond_lengths")) m->bond_lengths = (pdk_bond_lengths)mo->bond_lengths;
  /* Scenes take the lattice path where it applies (auto) unless they name a layout or a stencil
   * mode; the C API's default stays off (pdk_model_opts_default), so code chooses its path. */
  if (!has(ld, "model.layout")) m->stencil = PDK_STENCIL_AUTO;
  if (has(ld, "model.stencil")) {
    m->stencil = (pdk_stencil_mode)mo->stencil;
    char stencil_kinds[128];
    REQUIRE(ld, m->stencil != PDK_STENCIL_ON || pdk_model_opts_has(m, PDK_KIND_STENCIL),
            "model.stencil",
            "on needs model.kind %s (the stencil path exists for those models only; model.kind "
            "is %s); use auto or off",
            pdk_model_kinds_list(PDK_KIND_STENCIL | PDK_KIND_SCENE,
                                 PDK_KIND_STENCIL | PDK_KIND_SCENE, " or ", stencil_kinds,
                                 sizeof stencil_kinds),
            kname);
  }
  REQUIRE(ld, isfinite(mo->critical_stretch) && mo->critical_stretch >= 0, "model.critical_stretch",
          "must be >= 0 (0: bonds never break), got %g", mo->critical_stretch);
  m->critical_stretch = mo->critical_stretch;
  REQUIRE(ld, isfinite(mo->alpha) && mo->alpha >= 0, "model.alpha", "must be >= 0, got %g",
          mo->alpha);
  REQUIRE(ld, mo->alpha == 0 || mo->critical_stretch > 0, "model.alpha",
          "only acts with bond breaking; set model.critical_stretch > 0 or remove alpha");
  m->alpha = mo->alpha;
  m->lattice_constant = mo->partial_volume ? s->lattice.spacing : 0;
  m->thickness = s->lattice.thickness; /* 2-D volumes include it (lattice default 1) */
  PDK_CALL(resolve_johnson_cook(ld, mat, mo));
  PDK_CALL(resolve_connectivity(ld, mo));
  PDK_CALL(resolve_softening(ld, mo));
  PDK_CALL(resolve_galerkin(ld, mo));
  return PDK_SUCCESS;
}

/* A mesh's physical groups of body elements named like materials entries become a material
 * column (keys: the entry names, and index 0 for the elements in no such group). */
static int mesh_materials(loader *ld, const sc_scene *d, pdk_points *pts) {
  int which[PDK_POINTS_MAX_SETS], any = 0;
  for (int k = 0; k < pts->num_sets; ++k) {
    which[k] = -1;
    for (int q = 0; pts->set_body[k] && q < (int)d->materials_count; ++q)
      if (d->materials[q].name && !strcmp(d->materials[q].name, pts->set_name[k]))
        which[k] = q, any = 1;
  }
  if (!any) return PDK_SUCCESS;
  pts->mkey = calloc(PDK_POINTS_MAX_MKEYS, sizeof *pts->mkey);
  pts->material = malloc((size_t)pts->n * sizeof(int32_t) + 1);
  if (!pts->mkey || !pts->material)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
  for (pdk_index i = 0; i < pts->n; ++i) {
    int g = -1;
    for (int k = 0; k < pts->num_sets; ++k) {
      if (which[k] < 0 || !pts->set[k][i]) continue;
      REQUIRE(ld, g < 0 || which[g] == which[k], ld->s->points_key,
              "element %ld of %s is in the physical groups '%s' and '%s', which name two "
              "materials; an element takes one material",
              (long)i, pts->path, pts->set_name[g], pts->set_name[k]);
      g = k;
    }
    const char *name = g >= 0 ? pts->set_name[g] : NULL;
    const int key = pdk_points_mkey_find(pts, name, name ? strlen(name) : 0, 0, 0, i);
    if (key < 0)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
    pts->material[i] = key;
  }
  return PDK_SUCCESS;
}

/* The material column of a cloud: each key (a name or an index) to its material index, then
 * points->material from keys to indices; every entry of the list must be used. */
static int points_materials(loader *ld, pdk_points *pts, int nm) {
  pdk_scene *s = ld->s;
  int32_t idx[PDK_POINTS_MAX_MKEYS];
  char names[1024];
  size_t pos = 0;
  names[0] = '\0';
  for (int k = 0; k < nm && pos < sizeof names; ++k)
    pos += (size_t)snprintf(names + pos, sizeof names - pos, "%s%s (%d)", k ? ", " : "",
                            s->mat_regions[k].name, k + 1);
  for (int q = 0; q < pts->num_mkeys; ++q) {
    const pdk_points_mkey *m = &pts->mkey[q];
    char at[64];
    if (m->line)
      snprintf(at, sizeof at, "line %ld", m->line);
    else
      snprintf(at, sizeof at, "material[%ld]", m->row);
    idx[q] = -1;
    if (m->name) {
      for (int k = 0; k < nm; ++k)
        if (!strcmp(s->mat_regions[k].name, m->name)) idx[q] = k + 1;
      REQUIRE(ld, idx[q] > 0, s->points_key,
              "the material column of %s names '%s' (%s), which is no entry of materials; the "
              "materials are %s, and 0 for `material`",
              pts->path, m->name, at, names);
    } else {
      REQUIRE(ld, m->index <= nm, s->points_key,
              "the material column of %s gives the index %ld (%s), but the scene has materials "
              "0 (`material`) to %d: %s",
              pts->path, m->index, at, nm, names);
      idx[q] = (int32_t)m->index;
    }
  }
  for (int k = 1; k <= nm; ++k) {
    int used = 0;
    for (int q = 0; q < pts->num_mkeys; ++q)
      used |= idx[q] == k;
    REQUIRE(ld, used, K(ld, "materials[%d]", k - 1),
            "the material '%s' is given to no particle by the material column (or the physical "
            "groups) of %s; remove the entry, or name it (or its index %d) in the column",
            s->mat_regions[k - 1].name, pts->path, k);
  }
  for (pdk_index i = 0; i < pts->n; ++i)
    pts->material[i] = idx[pts->material[i]];
  s->mat_from_points = 1;
  return PDK_SUCCESS;
}

/* materials: further materials over regions (material 0 is `material`). Each entry's elastic
 * constants as `material`'s: E and nu, or K and G (pmb: K alone). */
int pdk_scene_resolve_materials(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  pdk_model_opts *m = &s->model;
  const int nm = (int)d->materials_count;
  pdk_points *pts = s->points;
  if (pts && !pts->mkey && nm > 0) PDK_CALL(mesh_materials(ld, d, pts));
  const int column = pts && pts->mkey;
  if (column && nm == 0) {
    const pdk_points_mkey *mk = &pts->mkey[0];
    char at[64];
    if (mk->line)
      snprintf(at, sizeof at, "line %ld", mk->line);
    else
      snprintf(at, sizeof at, "material[%ld]", mk->row);
    FAIL(ld, s->points_key,
         "the cloud %s has a material column (%s: %s%s), but the scene has no materials list; add "
         "`materials` entries (name, density, elastic constants; no region) for the materials the "
         "column names, or remove the column",
         pts->path, at, mk->name ? mk->name : "index ", mk->name ? "" : K(ld, "%ld", mk->index));
  }
  if (nm == 0) return PDK_SUCCESS;
  char with[128], alt[128];
  const unsigned mats = PDK_KIND_MATERIALS | PDK_KIND_SCENE;
  REQUIRE(ld, pdk_model_opts_has(m, PDK_KIND_MATERIALS), "materials",
          "several materials are implemented for %s, not %s; use one material or model.kind %s",
          pdk_model_kinds_list(mats, mats, " and ", with, sizeof with),
          pdk_model_kind_name(m->kind), pdk_model_kinds_list(mats, mats, " or ", alt, sizeof alt));
  REQUIRE(ld, !pdk_model_opts_law_has(m, PDK_LAWF_ONE_MATERIAL), "materials", "%s",
          pdk_law_info_of(m->law)->one_material_why);
  s->mat_regions = calloc((size_t)nm + 1, sizeof *s->mat_regions);
  s->materials = calloc((size_t)nm + 2, sizeof *s->materials);
  if (!s->mat_regions || !s->materials)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
  s->materials[0] = (pdk_material){m->bulk_modulus, m->shear_modulus, m->density};
  for (int k = 0; k < nm; ++k) {
    const sc_region *r = &d->materials[k];
    const char *nk = K(ld, "materials[%d].name", k);
    REQUIRE(ld, valid_name(r->name), nk,
            "'%s' is not a valid material name; use 1 to %d letters, digits, '_', '-' or '.'",
            r->name, SC_NAME_MAX);
    for (int q = 0; q < k; ++q)
      REQUIRE(ld, strcmp(s->mat_regions[q].name, r->name), nk,
              "the material '%s' is already defined by materials[%d]; names are unique", r->name,
              q);
    pdk_scene_region *out = &s->mat_regions[k];
    out->name = strdup(r->name);
    s->num_mat_regions = k + 1;
    if (!out->name)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for materials");
    const int region = r->box || r->disk || r->ball || r->halfspace || r->polygon;
    if (column)
      REQUIRE(ld, !region, K(ld, "materials[%d]", k),
              "gives a region, but the material column (or a mesh's physical groups named as "
              "materials) of %s places every particle's material; remove the region (the entry "
              "then only names the material), or the column",
              pts->path);
    else
      PDK_CALL(pdk_scene_region_resolve(ld, r, K(ld, "materials[%d]", k), 1, out));
    snprintf(out->key, sizeof out->key, "materials[%d]", k);
    pdk_material *q = &s->materials[k + 1];
    REQUIRE(ld, isfinite(r->density) && r->density > 0, K(ld, "materials[%d].density", k),
            "must be > 0, got %g (mass per volume)", r->density);
    q->density = r->density;
    const int hE = has(ld, K(ld, "materials[%d].youngs_modulus", k));
    const int hnu = has(ld, K(ld, "materials[%d].poisson_ratio", k));
    const int hK = has(ld, K(ld, "materials[%d].bulk_modulus", k));
    const int hG = has(ld, K(ld, "materials[%d].shear_modulus", k));
    char bulk_only[128];
    REQUIRE(ld,
            (hE && hnu && !hK && !hG) ||
                (!hE && !hnu && hK && (hG || !pdk_model_opts_has(m, PDK_KIND_SHEAR))),
            K(ld, "materials[%d]", k),
            "needs its elastic constants: youngs_modulus and poisson_ratio, or bulk_modulus and "
            "shear_modulus (%s: bulk_modulus alone), not a mix",
            pdk_model_kinds_list(PDK_KIND_SHEAR | PDK_KIND_SCENE, PDK_KIND_SCENE, " and ",
                                 bulk_only, sizeof bulk_only));
    if (hE) {
      const double E = r->youngs_modulus, nu = r->poisson_ratio;
      REQUIRE(ld, isfinite(E) && E > 0, K(ld, "materials[%d].youngs_modulus", k),
              "must be > 0, got %g", E);
      REQUIRE(ld, isfinite(nu) && nu > -1 && nu < 0.5, K(ld, "materials[%d].poisson_ratio", k),
              "must be in (-1, 0.5), got %g", nu);
      q->bulk_modulus = E / (3 * (1 - 2 * nu));
      q->shear_modulus = E / (2 * (1 + nu));
    } else {
      REQUIRE(ld, isfinite(r->bulk_modulus) && r->bulk_modulus > 0,
              K(ld, "materials[%d].bulk_modulus", k), "must be > 0, got %g", r->bulk_modulus);
      REQUIRE(ld, !hG || (isfinite(r->shear_modulus) && r->shear_modulus > 0),
              K(ld, "materials[%d].shear_modulus", k), "must be > 0, got %g", r->shear_modulus);
      q->bulk_modulus = r->bulk_modulus;
      q->shear_modulus = hG ? r->shear_modulus : 0.0;
    }
  }
  m->materials = s->materials;
  m->num_materials = nm + 1;
  if (column) PDK_CALL(points_materials(ld, pts, nm));
  return PDK_SUCCESS;
}
