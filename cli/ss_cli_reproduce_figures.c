/* ss_cli_reproduce_figures.c — the pictures of characteristic maps that
 * `reproduce` draws (DIR/figures/NAME.png, those reports/README.md shows) and
 * their captions (DIR/figures/README.md): the report captions the pictures,
 * they carry no text of their own besides axes and legend. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_charmap.h"
#include "ss_cli_reproduce.h"
#include "ss_eig.h"
#include "ss_link.h"
#include "ss_report_draw.h"

/* Draw figure f into path, as `subspectra draw --no-caption` does, and append
 * its caption (the case, lambda1..m, the regularity verdict) to cap, the
 * Markdown of figures/README.md: the report captions the pictures, they carry
 * no text of their own besides axes and legend. */
static ss_status draw_figure(const ss_reproduce_figure *f, const char *path,
                             ss_strbuf *cap, ss_error *err) {
  ss_scheme *s = NULL;
  ss_link *l = NULL, *cl = NULL;
  char *canon = NULL;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_star *star = NULL;
  ss_status st = ss_scheme_new(f->scheme, &s, err);
  if (!st && f->kind == SS_CASE_VERTEX) {
    st = ss_link_parse(f->link, &l, err);
    if (!st) st = ss_link_canonical(l, &cl, NULL, err);
    if (!st) st = ss_link_format(cl, &canon, err);
  }
  ss_case c = {f->kind, l, f->n, f->diag, 0};
  if (!st) st = ss_local_new(s, &c, &M, err);
  size_t pairs = 0, improper = 0;
  const int diag = !st && ss_scheme_reads_diagonals(s) && M->cell == SS_TET;
  if (diag) {
    st = ss_case_star(s, &c, &star, err);
    if (!st) st = ss_diag_improper(star->cx, &pairs, &improper, err);
  }
  if (!st) {
    ss_eig_opts eo = ss_eig_defaults(M->dim);
    eo.tol = ss_result_defaults().tol;
    eo.force = f->force;
    st = ss_eig_new(M->S, M->n2, M->n1, &eo, &e, err);
  }
  ss_regularity reg;
  const ss_charmap_opts co = ss_charmap_defaults();
  if (!st) st = ss_charmap_judge(s, &c, M, e, &co, &cm, &reg, err);
  int forced = 0;
  if (!st && !cm && f->force && e->basis) {
    st = ss_charmap_new(M, e, &cm, err);
    if (!st) st = ss_charmap_regularity(cm, M, &co, &reg, err);
    forced = 1;
  }
  if (!st && !cm)
    st = ss_error_set(err, SS_EINTERNAL, "%s: no characteristic map to draw: %s", path,
                      reg.verdict.reason);
  if (!st) {
    char caption[600], param[32] = "", dtext[128] = "";
    if (f->kind == SS_CASE_EDGE || f->kind == SS_CASE_SURFACE_VERTEX)
      snprintf(param, sizeof param, "%d", f->n);
    if (diag)
      snprintf(dtext, sizeof dtext, ", diagonals %s (%zu of %zu pairs improper)",
               ss_diag_name(f->diag), improper, pairs);
    snprintf(caption, sizeof caption, "%s, %s %s%s%s", f->scheme, ss_case_name(f->kind),
             canon ? canon : param, dtext,
             forced
                 ? "; forced: NOT a characteristic map (the eigenvalue condition fails)"
                 : "");
    const ss_report_draw_opts o = ss_report_draw_defaults(); /* no caption */
    st = ss_report_draw(cm, &reg, &o, path, err);
    int bad = ss_sb_printf(cap, "## %s\n\n![%s](%s)\n\n", f->file, f->file, f->file);
    ss_sb_cell(cap, caption);
    bad |= ss_sb_printf(cap, ".  λ1..%d =", cm->dim);
    for (int i = 0; i < cm->dim; i++)
      bad |= ss_sb_printf(cap, " %.6f", cm->lambda[i]);
    bad |= ss_sb_printf(cap, "; regularity: %s, minimum scaled Jacobian %.4f%s",
                        ss_verdict_name(reg.verdict.verdict), reg.min_scaled_jacobian,
                        reg.verdict.reason[0] ? ": " : "");
    ss_sb_cell(cap, reg.verdict.reason);
    bad |= ss_sb_printf(cap, ".\n\n");
    if (!st && bad) st = ss_error_nomem(err, "figure captions");
  }
  ss_star_free(star);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  free(canon);
  ss_link_free(cl);
  ss_link_free(l);
  ss_scheme_free(s);
  return st;
}

ss_status ss_reproduce_figures(const ss_reproduce_spec *spec, const char *dir,
                               ss_error *err) {
  ss_strbuf cap = {0};
  char *path = NULL;
  ss_status st = SS_OK;
  if (ss_sb_printf(
          &cap, "# Figures\n\nWritten by `subspectra reproduce` (as `subspectra draw "
                "--no-caption`); the captions are here, not in the pictures.  Each "
                "picture: the characteristic map's control net on the two-ring in 3D "
                "beside its cross-section z3 = 0 through psi(p) (surfaces: the planar "
                "map), in the frame fixed by the case (psi(p) at the origin, z1 toward "
                "the first two-ring point; see `subspectra draw --help`).\n\n")) {
    st = ss_error_nomem(err, "figure captions");
    goto done;
  }
  for (size_t i = 0; i < spec->nfigures && !st; i++) {
    const ss_reproduce_figure *f = spec->figure + i;
    free(path);
    path = malloc(strlen(dir) + strlen(f->file) + 32);
    if (!path) {
      st = ss_error_nomem(err, "path");
      goto done;
    }
    sprintf(path, "%s/figures/%s", dir, f->file);
    st = draw_figure(f, path, &cap, err);
  }
  if (!st) {
    free(path);
    path = malloc(strlen(dir) + 32);
    if (!path) {
      st = ss_error_nomem(err, "path");
      goto done;
    }
    sprintf(path, "%s/figures/README.md", dir);
    st = ss_sb_write_file(path, &cap, err);
  }
done:
  free(path);
  free(cap.s);
  return st;
}
