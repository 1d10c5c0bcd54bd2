/* Run output, the field snapshot: <name>_fields.csv, one row per particle of the last field
 * output (3-D: one layer), read back from the .h5, and <name>_fields.gp drawing it
 * (src/io/output.c, src/io/output_impl.h).
 */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/output.h"
#include "pdk/particles.h"

/* ---- field snapshot -----------------------------------------------------------------------------
 */

/* Reads rows [r0, r0 + rows) of dataset `path` ([n] or [n][cols]) as doubles into buf. */
static int read_rows(pdk_output *o, const char *path, int cols, hsize_t r0, hsize_t rows,
                     double *buf) {
  const hsize_t start[2] = {r0, 0}, count[2] = {rows, (hsize_t)cols};
  return pdk_h5_read_block(o->ctx, o->file, path, H5T_NATIVE_DOUBLE, cols > 1 ? 2 : 1, start, count,
                           buf);
}

/* <name>_fields.csv: id, X, Y (, Z) and every component of every field of the last field output,
 * read back from the .h5 (still open), one row per particle in store order, 10 significant
 * digits. A vector gives <f>_x, <f>_y (, <f>_z), a tensor <f>_xx, <f>_xy, ... (its dim x dim
 * components), other fields <f>_0, ... In 3-D only one layer is written: the particles whose
 * reference z lies within half their own size (cube root of the volume) of z_s, the reference z of
 * the particle nearest the middle of the body's z extent; on a lattice, the layer nearest the
 * mid-plane. Fills *snap with what the plot draws: the current in-plane positions (x when
 * written, else X + u when u is, else X) and up to SNAP_MAX_PANELS scalar fields and |u|, in the
 * listed order. */
int pdk_out_write_snapshot_csv(pdk_output *o, out_snapshot *snap) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  const int nf = o->num_last;
  FILE *f = NULL;
  double **buf = calloc((size_t)nf + 3, sizeof *buf); /* fields, then id, X, volume */
  int *cols = calloc((size_t)nf + 1, sizeof *cols), *ncomp = calloc((size_t)nf + 1, sizeof *ncomp);
  int(*col_of)[9] = calloc((size_t)nf + 1, sizeof *col_of);
  out_layout *layout = calloc((size_t)nf + 1, sizeof *layout);
  char path[2 * OUT_NAME_MAX + 32];
  double *row = NULL;
  static const char *const tsuf[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
  const int dim = o->dim, c_fields = 2 + dim; /* first field column (1-based) */
  PDK_CHECK_GOTO(buf && cols && ncomp && col_of && layout, ctx, PDK_ERR_MEMORY, "out of memory");
  const pdk_index block = o->n < OUT_CHUNK_ROWS ? o->n : OUT_CHUNK_ROWS;
  for (int k = 0; k < nf + 3; ++k) {
    buf[k] = malloc((size_t)block * 9 * sizeof(double));
    PDK_CHECK_GOTO(buf[k], ctx, PDK_ERR_MEMORY, "out of memory for the field snapshot");
  }
  f = fopen(o->part[OUT_FCSV], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_FCSV], strerror(errno));

  memset(snap, 0, sizeof *snap);
  snap->slice_z = NAN;
  if (dim == 3) { /* the layer: z_s nearest the middle of the reference z extent */
    double zlo = INFINITY, zhi = -INFINITY, best = INFINITY;
    for (int pass = 0; pass < 2; ++pass)
      for (pdk_index r0 = 0; r0 < o->n; r0 += block) {
        const pdk_index rows = o->n - r0 < block ? o->n - r0 : block;
        PDK_CALL_GOTO(read_rows(o, "/static/X", 3, (hsize_t)r0, (hsize_t)rows, buf[nf + 1]));
        for (pdk_index i = 0; i < rows; ++i) {
          const double z = buf[nf + 1][3 * i + 2];
          if (pass == 0) {
            zlo = fmin(zlo, z);
            zhi = fmax(zhi, z);
          } else if (fabs(z - 0.5 * (zlo + zhi)) < best) {
            best = fabs(z - 0.5 * (zlo + zhi));
            snap->slice_z = z;
          }
        }
      }
  }

  /* header; column numbers (1-based) for the plot */
  fprintf(f, "id,X [%s],Y [%s]", o->unit_length, o->unit_length);
  if (dim == 3) fprintf(f, ",Z [%s]", o->unit_length);
  int col = c_fields, x_col = 0, u_col = 0, failed_col = 0;
  for (int k = 0; k < nf; ++k) {
    pdk_type type;
    PDK_CALL_GOTO(pdk_particles_field_info(o->p, o->last_field[k], &type, &ncomp[k]));
    layout[k] = pdk_out_field_layout(dim, ncomp[k], &cols[k], col_of[k]);
    const char *dn = o->last_dname[k];
    if (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "x")) x_col = col;
    if (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "u")) u_col = col;
    if (layout[k] == OUT_SCALAR && !strcmp(o->last_field[k], "failed")) failed_col = col;
    if ((layout[k] == OUT_SCALAR || (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "u"))) &&
        snap->num_panels < SNAP_MAX_PANELS) {
      const int q = snap->num_panels++;
      snap->col[q] = col;
      snap->norm[q] = layout[k] == OUT_VECTOR ? dim : 0;
      snprintf(snap->title[q], sizeof snap->title[q], snap->norm[q] ? "|%s|" : "%s", dn);
      char ubuf[64];
      const char *unit = pdk_out_field_unit(o, o->last_field[k], ubuf, sizeof ubuf);
      snprintf(snap->unit[q], sizeof snap->unit[q], "%s", unit ? unit : "");
    }
    for (int c = 0; c < ncomp[k]; ++c, ++col) {
      if (layout[k] == OUT_SCALAR)
        fprintf(f, ",%s", dn);
      else if (layout[k] == OUT_VECTOR)
        fprintf(f, ",%s_%s", dn, axis_name[c]);
      else if (layout[k] == OUT_TENSOR)
        fprintf(f, ",%s_%s", dn, tsuf[col_of[k][c]]);
      else
        fprintf(f, ",%s_%d", dn, c);
    }
  }
  fprintf(f, "\n");
  const int num_cols = col - 1;
  snap->failed_col = failed_col;
  row = malloc((size_t)(num_cols + 1) * sizeof *row); /* row[c]: CSV column c (1-based) */
  PDK_CHECK_GOTO(row, ctx, PDK_ERR_MEMORY, "out of memory");
  for (int c = 0; c < 2; ++c) {
    snap->pos_col[c] = x_col ? x_col + c : 2 + c;
    snap->pos_add[c] = !x_col && u_col ? u_col + c : 0;
    snap->lo[c] = snap->ref_lo[c] = INFINITY;
    snap->hi[c] = snap->ref_hi[c] = -INFINITY;
  }
  for (int q = 0; q < snap->num_panels; ++q) {
    snap->vlo[q] = INFINITY;
    snap->vhi[q] = -INFINITY;
  }

  for (pdk_index r0 = 0; r0 < o->n; r0 += block) {
    const pdk_index rows = o->n - r0 < block ? o->n - r0 : block;
    PDK_CALL_GOTO(read_rows(o, "/static/id", 1, (hsize_t)r0, (hsize_t)rows, buf[nf]));
    PDK_CALL_GOTO(read_rows(o, "/static/X", 3, (hsize_t)r0, (hsize_t)rows, buf[nf + 1]));
    if (dim == 3)
      PDK_CALL_GOTO(read_rows(o, "/static/volume", 1, (hsize_t)r0, (hsize_t)rows, buf[nf + 2]));
    for (int k = 0; k < nf; ++k) {
      snprintf(path, sizeof path, OUT_STEP_GROUP "/%s", (long)o->num_steps - 1, o->last_dname[k]);
      PDK_CALL_GOTO(read_rows(o, path, cols[k], (hsize_t)r0, (hsize_t)rows, buf[k]));
    }
    for (pdk_index i = 0; i < rows; ++i) {
      if (dim == 3 && !(fabs(buf[nf + 1][3 * i + 2] - snap->slice_z) <= 0.5 * cbrt(buf[nf + 2][i])))
        continue;
      snap->num_rows++;
      row[1] = buf[nf][i];
      for (int c = 0; c < dim; ++c)
        row[2 + c] = buf[nf + 1][3 * i + c];
      for (int k = 0, c0 = c_fields; k < nf; c0 += ncomp[k], ++k)
        for (int c = 0; c < ncomp[k]; ++c)
          row[c0 + c] = buf[k][(size_t)i * cols[k] + col_of[k][c]];
      fprintf(f, "%.0f", row[1]);
      for (int c = 2; c <= num_cols; ++c)
        fprintf(f, ",%.10g", row[c]);
      fprintf(f, "\n");
      for (int c = 0; c < 2; ++c) {
        snap->ref_lo[c] = fmin(snap->ref_lo[c], row[2 + c]);
        snap->ref_hi[c] = fmax(snap->ref_hi[c], row[2 + c]);
      }
      if (failed_col && row[failed_col] != 0.0) continue;
      snap->num_shown++;
      for (int c = 0; c < 2; ++c) {
        const double x = row[snap->pos_col[c]] + (snap->pos_add[c] ? row[snap->pos_add[c]] : 0.0);
        snap->lo[c] = fmin(snap->lo[c], x);
        snap->hi[c] = fmax(snap->hi[c], x);
      }
      for (int q = 0; q < snap->num_panels; ++q) {
        const int c = snap->col[q];
        double v = row[c];
        if (snap->norm[q]) {
          v = 0.0;
          for (int a = 0; a < snap->norm[q]; ++a)
            v += row[c + a] * row[c + a];
          v = sqrt(v);
        }
        snap->vlo[q] = fmin(snap->vlo[q], v);
        snap->vhi[q] = fmax(snap->vhi[q], v);
      }
    }
  }
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_FCSV], strerror(errno));
cleanup:
  if (f && fclose(f) != 0 && !err)
    err = pdk_ctx_error_set(ctx, PDK_ERR_IO, __func__, "cannot write '%s': %s", o->part[OUT_FCSV],
                            strerror(errno));
  if (buf)
    for (int k = 0; k < nf + 3; ++k)
      free(buf[k]);
  free(buf);
  free(cols);
  free(ncomp);
  free(col_of);
  free(layout);
  free(row);
  return err;
}

/* <name>_fields.gp: one panel per plotted field, the particles as dots coloured by the value, in
 * the positions of the snapshot, equal axes. */
int pdk_out_write_snapshot_script(pdk_output *o, const out_snapshot *snap) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  char *stem = pdk_out_gnuplot_quote(o->name), *title = NULL;
  FILE *f = NULL;
  PDK_CHECK_GOTO(stem, ctx, PDK_ERR_MEMORY, "out of memory");
  f = fopen(o->part[OUT_FGP], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_FGP], strerror(errno));
  /* Panel size from the body's aspect; the dot size from the mean spacing in pixels. */
  /* (every particle failed: no box, the view and the scales are gnuplot's automatic ones) */
  const int have_box = snap->num_shown > 0;
  double bw = have_box ? snap->hi[0] - snap->lo[0] : 1.0,
         bh = have_box ? snap->hi[1] - snap->lo[1] : 1.0;
  if (!(bw > 0)) bw = bh > 0 ? bh : 1.0;
  if (!(bh > 0)) bh = bw;
  /* Side by side, or stacked when the body is wide (a bar): pixels per panel */
  const int wide = bw > 1.5 * bh, np = snap->num_panels;
  const int pw = wide ? 900 : 440;
  int ph = (int)((wide ? 0.7 : 0.78) * pw * bh / bw) + 110;
  ph = ph < (wide ? 260 : 300) ? (wide ? 260 : 300) : ph > 1000 ? 1000 : ph;
  char slice[96] = "";
  if (!isnan(snap->slice_z))
    snprintf(slice, sizeof slice, ", layer Z = %.6g [%s]", snap->slice_z, o->unit_length);
  title = pdk_str_printf("%s, step %ld, t = %.6g [%s]%s%s", stem, o->last_step, o->last_time,
                         o->unit_time, slice,
                         snap->pos_col[0] != 2 || snap->pos_add[0] ? ", current positions" : "");
  PDK_CHECK_GOTO(title, ctx, PDK_ERR_MEMORY, "out of memory");
  int width = wide ? pw : pw * np; /* at least the title's width, about 8 pixels a character */
  if (width < 8 * (int)strlen(title) + 60) width = 8 * (int)strlen(title) + 60;
  const int height = wide ? ph * np : ph;
  const double scale = fmin((wide ? 0.7 : 0.62) * pw / bw, (ph - 110.0) / bh); /* px per length */
  const double h = sqrt(bw * bh / (double)(snap->num_rows > 0 ? snap->num_rows : 1));
  double ps = 1.6 * scale * h / 6.0; /* pt 7 at pointsize 1 is about 6 pixels across */
  ps = ps < 0.05 ? 0.05 : ps > 3.0 ? 3.0 : ps;
  fprintf(f,
          "# pdk field plot of the last field output (step %ld, t = %.6g); rerun with: gnuplot "
          "%s%s_fields.gp (in this directory)\n",
          o->last_step, o->last_time, o->name[0] == '-' ? "./" : "", o->name);
  fprintf(f, "if (!exists(\"outfile\")) outfile = '%s_fields.png'\n", stem);
  fprintf(f,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size %d,%d noenhanced\n} else {\n"
          "  set terminal png size %d,%d noenhanced\n}\n",
          width, height, width, height);
  fprintf(f,
          "set output outfile\nset datafile separator ','\nunset key\nset size ratio -1\n"
          "set format x '%%g'\nset format y '%%g'\nset format cb '%%g'\n"
          "set xtics rotate by 30 right\nset xlabel '[%s]'\n",
          o->unit_length);
  fprintf(f, "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', "
             "4 '#fde725')\n");
  fprintf(f, "if (!exists(\"data\")) data = '%s_fields.csv'\ntitle = '%s'\n", stem, title);
  char view[256] = "set autoscale xy\n";
  if (have_box) {
    const double m = 0.03 * fmax(bw, bh);
    snprintf(view, sizeof view, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n",
             snap->lo[0] - m, snap->lo[0] + bw + m, snap->lo[1] - m, snap->lo[1] + bh + m);
    fputs(view, f);
  }
  fprintf(f, "set multiplot layout %d,%d title title\n", wide ? np : 1, wide ? 1 : np);
  char xs[64], ys[64], xs_unfailed[96];
  for (int c = 0; c < 2; ++c) {
    char *dst = c ? ys : xs;
    if (snap->pos_add[c])
      snprintf(dst, 64, "($%d+$%d)", snap->pos_col[c], snap->pos_add[c]);
    else
      snprintf(dst, 64, "($%d)", snap->pos_col[c]);
  }
  /* a failed particle's x undefined: gnuplot skips the point (a NaN colour would be drawn) */
  snprintf(xs_unfailed, sizeof xs_unfailed, "($%d != 0 ? NaN : %s)", snap->failed_col, xs);
  for (int q = 0; q < snap->num_panels; ++q) {
    char *pt = pdk_out_gnuplot_quote(snap->title[q]);
    PDK_CHECK_GOTO(pt, ctx, PDK_ERR_MEMORY, "out of memory");
    const int fc = snap->failed_col;
    if (fc && snap->col[q] == fc) {
      /* where the body broke: every particle at its reference position, the failed ones (1)
       * drawn over the others (0), in the view of the reference positions */
      fprintf(f, "set title '%s, reference positions'\n", pt);
      free(pt);
      const double rw = snap->ref_hi[0] - snap->ref_lo[0], rh = snap->ref_hi[1] - snap->ref_lo[1];
      if (snap->num_rows > 0) {
        const double m = 0.03 * fmax(rw, rh) + (rw > 0 || rh > 0 ? 0.0 : 1.0);
        fprintf(f, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n", snap->ref_lo[0] - m,
                snap->ref_hi[0] + m, snap->ref_lo[1] - m, snap->ref_hi[1] + m);
      }
      fprintf(f,
              "set cbrange [0:1]\nplot data skip 1 using ($%d != 0 ? NaN : $2):($3):(0) with "
              "points pt 7 ps %.3g lc palette, data skip 1 using ($%d == 0 ? NaN : $2):($3):(1) "
              "with points pt 7 ps %.3g lc palette\n%s",
              fc, ps, fc, ps, view);
      continue;
    }
    /* the panel's title carries the colour scale's unit ("1": dimensionless, none) */
    if (snap->unit[q][0] && strcmp(snap->unit[q], "1")) {
      char *u = pdk_out_gnuplot_quote(snap->unit[q]);
      PDK_CHECK_GOTO(u, ctx, PDK_ERR_MEMORY, "out of memory");
      fprintf(f, "set title '%s [%s]'\n", pt, u);
      free(u);
    } else {
      fprintf(f, "set title '%s'\n", pt);
    }
    free(pt);
    if (have_box && snap->vhi[q] > snap->vlo[q])
      fprintf(f, "set cbrange [%.10g:%.10g]\n", snap->vlo[q], snap->vhi[q]);
    else
      fprintf(f, "set autoscale cb\n");
    char v[96];
    if (snap->norm[q] == 3)
      snprintf(v, sizeof v, "(sqrt($%d**2+$%d**2+$%d**2))", snap->col[q], snap->col[q] + 1,
               snap->col[q] + 2);
    else if (snap->norm[q])
      snprintf(v, sizeof v, "(sqrt($%d**2+$%d**2))", snap->col[q], snap->col[q] + 1);
    else
      snprintf(v, sizeof v, "($%d)", snap->col[q]);
    /* (the failed panel took the branch above: every other panel leaves failed particles out) */
    fprintf(f, "plot data skip 1 using %s:%s:%s with points pt 7 ps %.3g lc palette\n",
            fc ? xs_unfailed : xs, ys, v, ps);
  }
  fprintf(f, "unset multiplot\nset output\n");
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_FGP], strerror(errno));
cleanup:
  if (f) fclose(f);
  free(stem);
  free(title);
  return err;
}
