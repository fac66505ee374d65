/* ss_cli_reproduce_figures.c — the pictures of characteristic maps that
 * `reproduce` draws (DIR/figures/NAME.png, those reports/README.md shows) and
 * their captions (DIR/figures/README.md): the report captions the pictures,
 * they carry no text of their own besides axes and legend. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli_reproduce.h"
#include "ss_link.h"
#include "ss_pipeline.h"
#include "ss_report_draw.h"

/* Draw figure f into path, as `subspectra draw --no-caption` does, and append
 * its caption (the case, lambda1..m, the regularity verdict) to cap, the
 * Markdown of figures/README.md: the report captions the pictures, they carry
 * no text of their own besides axes and legend. */
static ss_status draw_figure(const ss_reproduce_figure *f, const char *path,
                             ss_strbuf *cap, ss_error *err) {
  ss_scheme *s = NULL;
  ss_link *l = NULL;
  ss_pipeline *p = NULL;
  ss_status st = ss_scheme_new(f->scheme, &s, err);
  if (!st && f->kind == SS_CASE_VERTEX) st = ss_link_parse(f->link, &l, err);
  /* the case as analyze judges it: the canonical link, an edge point as its
   * edge, the same verdicts (ss_pipeline) */
  const ss_case c = {f->kind, l, f->n, f->diag, 0};
  ss_pipeline_opts po = ss_pipeline_defaults();
  po.force = f->force;
  if (!st) st = ss_pipeline_compute(s, &c, &po, SS_PIPE_VERDICTS, NULL, &p, err);
  if (!st && !p->cm)
    st = ss_error_set(err, SS_EINTERNAL, "%s: no characteristic map to draw: %s", path,
                      p->reg.verdict.reason);
  if (!st) {
    const ss_regularity *reg = &p->reg;
    char caption[600], param[32] = "", dtext[128] = "";
    if (p->c.kind == SS_CASE_EDGE || p->c.kind == SS_CASE_SURFACE_VERTEX)
      snprintf(param, sizeof param, "%d", p->c.valence);
    if (p->has_diag)
      snprintf(dtext, sizeof dtext, ", diagonals %s (%zu of %zu pairs improper)",
               ss_diag_name(f->diag), p->improper, p->pairs);
    snprintf(caption, sizeof caption, "%s, %s %s%s%s", f->scheme, ss_case_name(p->c.kind),
             p->c.text[0] ? p->c.text : param, dtext,
             p->forced
                 ? "; forced: NOT a characteristic map (the eigenvalue condition fails)"
                 : "");
    const ss_report_draw_opts o = ss_report_draw_defaults(); /* no caption */
    st = ss_report_draw(p->cm, reg, &o, path, err);
    int bad = ss_sb_printf(cap, "## %s\n\n![%s](%s)\n\n", f->file, f->file, f->file);
    ss_sb_cell(cap, caption);
    bad |= ss_sb_printf(cap, ".  λ1..%d =", p->cm->dim);
    for (int i = 0; i < p->cm->dim; i++)
      bad |= ss_sb_printf(cap, " %.6f", p->cm->lambda[i]);
    bad |= ss_sb_printf(cap, "; regularity: %s, minimum scaled Jacobian %.4f%s",
                        ss_verdict_name(reg->verdict.verdict), reg->min_scaled_jacobian,
                        reg->verdict.reason[0] ? ": " : "");
    ss_sb_cell(cap, reg->verdict.reason);
    bad |= ss_sb_printf(cap, ".\n\n");
    if (!st && bad) st = ss_error_nomem(err, "figure captions");
  }
  ss_pipeline_free(p);
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
