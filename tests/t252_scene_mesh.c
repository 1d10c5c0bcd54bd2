/* geometry.mesh: a Gmsh mesh (ASCII MSH 4.1 and 2.2) as the body, one particle per element
 * (docs/scenes.md "Meshes"). The meshes are written here.
 * 1. A structured quadrangle mesh of the rectangle 30 x 6 mm (1 mm elements; physical groups: the
 *    curves `left` and `right`, the surfaces `steel` (x < 15 mm) and `soft`), against the square
 *    lattice over the same box with spacing 1 mm: the same 180 particles, positions within
 *    1e-17 m (round-off of the centroid, area-weighted over the element's two triangles: a few
 *    ulp of 1e-2) and volumes within 1e-13 relative (area x thickness; the element's sides are
 *    differences of node coordinates, exact to a few ulp). The curve groups become sets of the
 *    particles whose elements have a node on them (the first and last column), the surface
 *    groups sets of their elements; `soft`, named in the scene's materials, also makes those
 *    elements material 1 (the material field; `steel`, not a materials entry, stays a set only).
 *    The same mesh as MSH 2.2 gives the very same particles, sets and materials (bit for bit), and
 *    a Newton solve with the left curve held and the right one pulled runs (the pulled set's
 *    reaction is positive).
 * 2. A triangle mesh of the rectangle (each cell split in two, interior nodes moved by up to 0.3
 *    cell): the particles' volumes add up to the area x thickness (2 mm) within 1e-13 relative
 *    (round-off of 360 triangle areas). A 3-D tetrahedron mesh of a 4 x 4 x 6 mm box (each cube
 *    split in 6, interior nodes moved) adds up to the box's volume within 1e-13; a hexahedron mesh
 *    of it gives the cubic lattice's particles (positions within 1e-17 m, volumes 1e-13).
 * 3. Refusals, each naming geometry.mesh, the file and line, and the fix: a binary file, version
 *    3.0, a second-order element, a missing $Nodes, a coordinate that is no number, an element on
 *    an undefined node, a 3-D element in a 2-D scene, a physical name with a space, an element in
 *    two material groups, geometry.box or geometry.points beside geometry.mesh.
 * Files: $PDK_BUILD_DIR/tests/t252_scene_mesh.work.
 * labels: scene */
#include <sys/stat.h>

#include "work_util.h"

static const double H = 1e-3;
#define NX 30
#define NY 6

static long node2(int i, int j) { return 1 + i + (long)j * (NX + 1); }

/* Node coordinates of the rectangle's grid, interior nodes moved by `jiggle` cells. */
static void grid_xy(int i, int j, double jiggle, double *x, double *y) {
  *x = i * H, *y = j * H;
  if (jiggle > 0 && i > 0 && i < NX && j > 0 && j < NY) {
    *x += jiggle * H * sin(1.7 * i + 2.3 * j);
    *y += jiggle * H * cos(2.9 * i - 1.1 * j);
  }
}

/* The rectangle: quadrangles (tri 0) or triangles (tri 1), MSH 4.1 (v4) or 2.2. Groups: curves
 * left (1) and right (2), surfaces steel (3, i < 15) and soft (4). */
static void write_rect(const char *name, int v4, int tri, double jiggle) {
  FILE *f = work_open(name);
  const long nn = (long)(NX + 1) * (NY + 1);
  fprintf(f, "$MeshFormat\n%s 0 8\n$EndMeshFormat\n", v4 ? "4.1" : "2.2");
  fprintf(f, "$PhysicalNames\n4\n1 1 \"left\"\n1 2 \"right\"\n2 3 \"steel\"\n2 4 \"soft\"\n"
             "$EndPhysicalNames\n");
  if (v4)
    fprintf(f, "$Entities\n0 2 2 0\n1 0 0 0 0 0.006 0 1 1 0\n2 0.03 0 0 0.03 0.006 0 1 2 0\n"
               "1 0 0 0 0.015 0.006 0 1 3 0\n2 0.015 0 0 0.03 0.006 0 1 4 0\n$EndEntities\n");
  fprintf(f, "$Nodes\n");
  if (v4) {
    fprintf(f, "1 %ld 1 %ld\n2 1 0 %ld\n", nn, nn, nn);
    for (long t = 1; t <= nn; ++t)
      fprintf(f, "%ld\n", t);
  } else
    fprintf(f, "%ld\n", nn);
  for (int j = 0; j <= NY; ++j)
    for (int i = 0; i <= NX; ++i) {
      double x, y;
      grid_xy(i, j, jiggle, &x, &y);
      if (!v4) fprintf(f, "%ld ", node2(i, j));
      fprintf(f, "%.17g %.17g 0\n", x, y);
    }
  fprintf(f, "$EndNodes\n$Elements\n");
  const long per = tri ? 2 : 1, half = (long)(NX / 2) * NY * per;
  const long total = 2 * NY + 2 * half;
  long tag = 1;
  if (v4)
    fprintf(f, "4 %ld 1 %ld\n", total, total);
  else
    fprintf(f, "%ld\n", total);
  for (int c = 0; c < 2; ++c) { /* the curves */
    if (v4) fprintf(f, "1 %d 1 %d\n", c + 1, NY);
    for (int j = 0; j < NY; ++j, ++tag) {
      const int i = c ? NX : 0;
      if (v4)
        fprintf(f, "%ld %ld %ld\n", tag, node2(i, j), node2(i, j + 1));
      else
        fprintf(f, "%ld 1 2 %d %d %ld %ld\n", tag, c + 1, c + 1, node2(i, j), node2(i, j + 1));
    }
  }
  for (int srf = 0; srf < 2; ++srf) {
    if (v4) fprintf(f, "2 %d %d %ld\n", srf + 1, tri ? 2 : 3, half);
    for (int j = 0; j < NY; ++j)
      for (int i = srf ? NX / 2 : 0; i < (srf ? NX : NX / 2); ++i) {
        const long a = node2(i, j), b = node2(i + 1, j), c = node2(i + 1, j + 1),
                   d = node2(i, j + 1);
        const char *pre2 = srf ? "4 4" : "3 3";
        if (tri) {
          if (v4)
            fprintf(f, "%ld %ld %ld %ld\n%ld %ld %ld %ld\n", tag, a, b, c, tag + 1, a, c, d);
          else
            fprintf(f, "%ld 2 2 %s %ld %ld %ld\n%ld 2 2 %s %ld %ld %ld\n", tag, pre2, a, b, c,
                    tag + 1, pre2, a, c, d);
          tag += 2;
        } else {
          if (v4)
            fprintf(f, "%ld %ld %ld %ld %ld\n", tag, a, b, c, d);
          else
            fprintf(f, "%ld 3 2 %s %ld %ld %ld %ld\n", tag, pre2, a, b, c, d);
          tag += 1;
        }
      }
  }
  fprintf(f, "$EndElements\n");
  T_ASSERT(fclose(f) == 0, "cannot write %s", name);
}

/* A 4 x 4 x 6 box of 1 mm cubes: hexahedra, or 6 tetrahedra per cube with interior nodes moved. */
static void write_box(const char *name, int tets, double jiggle) {
  enum { BX = 4, BY = 4, BZ = 6 };
  FILE *f = work_open(name);
  const long nn = (long)(BX + 1) * (BY + 1) * (BZ + 1);
  fprintf(f, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n"
             "1 0 0 0 0.004 0.004 0.006 0 0\n$EndEntities\n");
  fprintf(f, "$Nodes\n1 %ld 1 %ld\n3 1 0 %ld\n", nn, nn, nn);
  for (long t = 1; t <= nn; ++t)
    fprintf(f, "%ld\n", t);
  for (int k = 0; k <= BZ; ++k)
    for (int j = 0; j <= BY; ++j)
      for (int i = 0; i <= BX; ++i) {
        double x = i * H, y = j * H, z = k * H;
        if (jiggle > 0 && i > 0 && i < BX && j > 0 && j < BY && k > 0 && k < BZ) {
          x += jiggle * H * sin(1.7 * i + 2.3 * j + 0.7 * k);
          y += jiggle * H * cos(2.9 * i - 1.1 * j + 0.3 * k);
          z += jiggle * H * sin(0.9 * i + 1.3 * j - 2.1 * k);
        }
        fprintf(f, "%.17g %.17g %.17g\n", x, y, z);
      }
  const long cells = (long)BX * BY * BZ, ne = tets ? 6 * cells : cells;
  fprintf(f, "$EndNodes\n$Elements\n1 %ld 1 %ld\n3 1 %d %ld\n", ne, ne, tets ? 4 : 5, ne);
  long tag = 1;
#define ND(i, j, k) (1 + (i) + (long)(j) * (BX + 1) + (long)(k) * (BX + 1) * (BY + 1))
  for (int k = 0; k < BZ; ++k)
    for (int j = 0; j < BY; ++j)
      for (int i = 0; i < BX; ++i) {
        const long v[8] = {
            ND(i, j, k),     ND(i + 1, j, k),     ND(i + 1, j + 1, k),     ND(i, j + 1, k),
            ND(i, j, k + 1), ND(i + 1, j, k + 1), ND(i + 1, j + 1, k + 1), ND(i, j + 1, k + 1)};
        if (!tets) {
          fprintf(f, "%ld %ld %ld %ld %ld %ld %ld %ld %ld\n", tag++, v[0], v[1], v[2], v[3], v[4],
                  v[5], v[6], v[7]);
          continue;
        }
        static const int t6[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                     {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
        for (int q = 0; q < 6; ++q)
          fprintf(f, "%ld %ld %ld %ld %ld\n", tag++, v[t6[q][0]], v[t6[q][1]], v[t6[q][2]],
                  v[t6[q][3]]);
      }
#undef ND
  fprintf(f, "$EndElements\n");
  T_ASSERT(fclose(f) == 0, "cannot write %s", name);
}

static const char scene2[] =
    "name: body\ndimension: 2\n"
    "geometry: {%s, spacing: 1.0e-3, thickness: 2.0e-3}\n"
    "material: {density: 8000, bulk_modulus: 1.0e9}\n%s"
    "model: {kind: pmb}\n%s"
    "boundary_conditions:\n  - {set: left, type: displacement, x: 0, y: 0}\n"
    "  - {set: right, type: displacement, x: 1.0e-5, y: 0}\n"
    "solver: {type: newton, load_steps: 1}\noutput: {reactions: [right]}\n";
static const char mats[] = "materials:\n  - {name: soft, density: 8000, bulk_modulus: 0.5e9}\n";
static const char lattice_sets[] = "sets:\n  - {name: left, box: {lo: [-1, -1], hi: [0.001, 1]}}\n"
                                   "  - {name: right, box: {lo: [0.029, -1], hi: [1, 1]}}\n";
static const char scene3[] = "name: box\ndimension: 3\n"
                             "geometry: {%s, spacing: 1.0e-3}\n"
                             "material: {density: 8000, bulk_modulus: 1.0e9}\n"
                             "model: {kind: pmb}\nsolver: {steps: 1}\n";

static pdk_sim *load(pdk_ctx *ctx, const char *file, const char *text, pdk_scene **scene) {
  write_file(file, text);
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", work, file);
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, scene));
  T_OK(ctx, pdk_sim_create(ctx, *scene, &sim));
  return sim;
}

/* Particle order by position: lattice cell (i, j, k) of each particle. */
static long cell_of(pdk_particles *p, pdk_index i) {
  long c = 0;
  for (int a = pdk_particles_dim(p) - 1; a >= 0; --a)
    c = c * 64 + (long)floor(pdk_particles_X(p, a)[i] / H);
  return c;
}

/* a and b hold the same particles (matched by cell): positions within dx, volumes within dv
 * relative; when `same`, the sets and material fields named in fields[] agree too. */
static void same_particles(const char *label, pdk_particles *a, pdk_particles *b, double dx,
                           double dv, const char *const *fields) {
  const pdk_index n = pdk_particles_count(a);
  T_ASSERT(pdk_particles_count(b) == n, "%s: %ld particles against %ld", label,
           (long)pdk_particles_count(b), (long)n);
  long *map = calloc(64 * 64 * 64, sizeof *map);
  for (pdk_index i = 0; i < n; ++i)
    map[cell_of(b, i)] = (long)i + 1;
  for (pdk_index i = 0; i < n; ++i) {
    const long j = map[cell_of(a, i)] - 1;
    T_ASSERT(j >= 0, "%s: particle %ld at (%g, %g) has no partner", label, (long)i,
             pdk_particles_X(a, 0)[i], pdk_particles_X(a, 1)[i]);
    for (int d = 0; d < pdk_particles_dim(a); ++d)
      T_NEAR(pdk_particles_X(b, d)[j], pdk_particles_X(a, d)[i], 0, dx, "%s: X[%d] of %ld", label,
             d, (long)i);
    T_NEAR(pdk_particles_volume(b)[j], pdk_particles_volume(a)[i], dv, 0, "%s: volume of %ld",
           label, (long)i);
    for (int k = 0; fields && fields[k]; ++k) {
      const int mat = !strcmp(fields[k], "material");
      const void *fa = pdk_particles_field_data(a, fields[k], 0);
      const void *fb = pdk_particles_field_data(b, fields[k], 0);
      T_ASSERT(fa && fb, "%s: no field %s", label, fields[k]);
      const long va = mat ? ((const int32_t *)fa)[i] : ((const uint8_t *)fa)[i];
      const long vb = mat ? ((const int32_t *)fb)[j] : ((const uint8_t *)fb)[j];
      T_ASSERT(va == vb, "%s: %s of particle %ld: %ld against %ld", label, fields[k], (long)i, va,
               vb);
    }
  }
  free(map);
}

static double total_volume(pdk_particles *p) {
  double v = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    v += pdk_particles_volume(p)[i];
  return v;
}

/* The scene over mesh file `mesh` (text written unless NULL) must fail with each of want[]. */
static void bad(pdk_ctx *ctx, const char *label, const char *mesh, const char *geom,
                const char *extra, const char *const *want) {
  if (mesh) write_file("bad.msh", mesh);
  char text[4096], path[1024];
  snprintf(text, sizeof text, scene2, geom, extra, "");
  write_file("bad.yaml", text);
  snprintf(path, sizeof path, "%s/bad.yaml", work);
  pdk_scene *scene = NULL;
  const int err = pdk_scene_load(ctx, path, NULL, 0, &scene);
  T_ASSERT(err != 0 && scene == NULL, "%s: the scene loaded", label);
  const char *msg = pdk_ctx_error_message(ctx);
  for (int k = 0; want[k]; ++k)
    T_ASSERT(strstr(msg, want[k]) != NULL, "%s: the message lacks '%s': %s", label, want[k], msg);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  work_init("t252_scene_mesh");
  char text[4096];

  /* 1. */
  write_rect("quads.msh", 1, 0, 0.0);
  write_rect("quads22.msh", 0, 0, 0.0);
  pdk_scene *sl = NULL, *sm = NULL, *s2 = NULL;
  snprintf(text, sizeof text, scene2, "box: {lo: [0, 0], hi: [0.03, 0.006]}", "", lattice_sets);
  pdk_sim *lat = load(ctx, "lattice.yaml", text, &sl);
  snprintf(text, sizeof text, scene2, "mesh: quads.msh", mats, "");
  pdk_sim *msh = load(ctx, "mesh.yaml", text, &sm);
  snprintf(text, sizeof text, scene2, "mesh: quads22.msh", mats, "");
  pdk_sim *m22 = load(ctx, "mesh22.yaml", text, &s2);
  pdk_particles *pl = pdk_sim_particles(lat), *pm = pdk_sim_particles(msh);
  same_particles("quads vs lattice", pl, pm, 1e-17, 1e-13,
                 (const char *const[]){"set:left", "set:right", NULL});
  same_particles(
      "MSH 2.2 vs 4.1", pm, pdk_sim_particles(m22), 0, 0,
      (const char *const[]){"set:left", "set:right", "set:steel", "set:soft", "material", NULL});
  {
    const int32_t *mat = pdk_particles_field_data(pm, "material", 0);
    const uint8_t *steel = pdk_particles_field_data(pm, "set:steel", 0);
    const uint8_t *soft = pdk_particles_field_data(pm, "set:soft", 0);
    T_ASSERT(mat && steel && soft, "the mesh body lacks material, set:steel or set:soft");
    for (pdk_index i = 0; i < pdk_particles_count(pm); ++i) {
      const int right = pdk_particles_X(pm, 0)[i] > 0.015;
      T_ASSERT(mat[i] == right && soft[i] == right && steel[i] == !right,
               "particle at x = %g: material %d, steel %d, soft %d", pdk_particles_X(pm, 0)[i],
               (int)mat[i], steel[i], soft[i]);
    }
  }
  {
    pdk_run_opts o = pdk_run_opts_default();
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/mesh_run", work);
    o.dir = dir;
    o.plot = 0;
    pdk_run_report rep;
    T_OK(ctx, pdk_sim_run(msh, sm, &o, &rep));
    T_ASSERT(rep.last.reaction[0][0] > 0, "the pulled curve's reaction is %g",
             rep.last.reaction[0][0]);
  }
  pdk_sim_destroy(&lat);
  pdk_sim_destroy(&msh);
  pdk_sim_destroy(&m22);
  pdk_scene_destroy(&sl);
  pdk_scene_destroy(&sm);
  pdk_scene_destroy(&s2);

  /* 2. */
  write_rect("tris.msh", 1, 1, 0.3);
  snprintf(text, sizeof text, scene2, "mesh: tris.msh", mats, "");
  pdk_scene *st = NULL;
  pdk_sim *tri = load(ctx, "tris.yaml", text, &st);
  T_ASSERT(pdk_particles_count(pdk_sim_particles(tri)) == 2 * NX * NY, "triangles: %ld particles",
           (long)pdk_particles_count(pdk_sim_particles(tri)));
  T_NEAR(total_volume(pdk_sim_particles(tri)), 0.03 * 0.006 * 2e-3, 1e-13, 0,
         "the triangles' volumes against area x thickness");
  pdk_sim_destroy(&tri);
  pdk_scene_destroy(&st);
  write_box("tets.msh", 1, 0.3);
  write_box("hexes.msh", 0, 0.0);
  pdk_scene *s3 = NULL, *s4 = NULL, *s5 = NULL;
  snprintf(text, sizeof text, scene3, "mesh: tets.msh");
  pdk_sim *tets = load(ctx, "tets.yaml", text, &s3);
  T_NEAR(total_volume(pdk_sim_particles(tets)), 0.004 * 0.004 * 0.006, 1e-13, 0,
         "the tetrahedra's volumes against the box's");
  snprintf(text, sizeof text, scene3, "mesh: hexes.msh");
  pdk_sim *hexes = load(ctx, "hexes.yaml", text, &s4);
  snprintf(text, sizeof text, scene3, "box: {lo: [0, 0, 0], hi: [0.004, 0.004, 0.006]}");
  pdk_sim *cube = load(ctx, "cube.yaml", text, &s5);
  same_particles("hexahedra vs lattice", pdk_sim_particles(cube), pdk_sim_particles(hexes), 1e-17,
                 1e-13, NULL);
  pdk_sim_destroy(&tets);
  pdk_sim_destroy(&hexes);
  pdk_sim_destroy(&cube);
  pdk_scene_destroy(&s3);
  pdk_scene_destroy(&s4);
  pdk_scene_destroy(&s5);

  /* 3. */
  const char *head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  const char *nodes =
      "$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1e-3 0 0\n1e-3 1e-3 0\n0 1e-3 0\n"
      "$EndNodes\n";
  char m[2048];
  bad(ctx, "binary", "$MeshFormat\n4.1 1 8\n", "mesh: bad.msh", "",
      (const char *[]){"geometry.mesh", "bad.msh:2", "binary", "Mesh.Binary = 0", NULL});
  bad(ctx, "version", "$MeshFormat\n3.0 0 8\n", "mesh: bad.msh", "",
      (const char *[]){"bad.msh:2", "version 3.0", "4.1 and 2.2", NULL});
  snprintf(m, sizeof m, "%s%s$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 4 1 2\n$EndElements\n", head,
           nodes);
  bad(ctx, "element type", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:19", "element type 9", "Mesh.ElementOrder = 1", NULL});
  snprintf(m, sizeof m, "%s$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 4\n$EndElements\n", head);
  bad(ctx, "no nodes", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:4", "$Elements comes before $Nodes", NULL});
  snprintf(m, sizeof m, "%s$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0.0x1 0\n$EndNodes\n", head);
  bad(ctx, "bad number", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:8", "'0.0x1'", "not a finite number", NULL});
  snprintf(m, sizeof m, "%s%s$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 7\n$EndElements\n", head, nodes);
  bad(ctx, "undefined node", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:19", "node 7", "does not define", NULL});
  snprintf(m, sizeof m, "%s%s$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n", head, nodes);
  bad(ctx, "3-D element", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:19", "3-D element", "dimension: 3", NULL});
  snprintf(m, sizeof m, "%s$PhysicalNames\n1\n2 1 \"my body\"\n$EndPhysicalNames\n", head);
  bad(ctx, "name", m, "mesh: bad.msh", "",
      (const char *[]){"bad.msh:6", "\"my body\"", "rename", NULL});
  snprintf(
      m, sizeof m,
      "%s$PhysicalNames\n2\n2 1 \"soft\"\n2 2 \"hard\"\n$EndPhysicalNames\n$Entities\n0 0 1 0\n"
      "1 0 0 0 1 1 0 2 1 2 0\n$EndEntities\n%s$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 4\n"
      "$EndElements\n",
      head, nodes);
  bad(ctx, "two materials", m, "mesh: bad.msh",
      "materials:\n  - {name: soft, density: 1, bulk_modulus: 1.0e9}\n"
      "  - {name: hard, density: 1, bulk_modulus: 2.0e9}\n",
      (const char *[]){"geometry.mesh", "'soft' and 'hard'", "one material", NULL});
  bad(ctx, "box beside", NULL, "mesh: quads.msh, box: {lo: [0, 0], hi: [1, 1]}", "",
      (const char *[]){"geometry.box", "geometry.mesh gives the particles", NULL});
  bad(ctx, "points beside", NULL, "mesh: quads.msh, points: x.csv", "",
      (const char *[]){"geometry.mesh", "geometry.points", "remove one", NULL});
  pdk_ctx_destroy(&ctx);
  return 0;
}
