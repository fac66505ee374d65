/* ss_cli_analyze_print.c — analyze's text, TSV and JSON output of one case
 * (ss_cli_analyze.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_analyze.h"
#include "ss_report_case.h"

const char *ss_cli_case_param(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                              char *buf, size_t n) {
  const ss_case_resolved *c = &p->c;
  if (c->kind == SS_CASE_VERTEX || c->kind == SS_CASE_EDGE_POINT) return c->text;
  if (c->kind == SS_CASE_FACE) return "";
  if (c->cls && o->format != FMT_TSV) /* TSV: the valence column stays a number */
    snprintf(buf, n, "%d, 4-8 class %d", c->valence, c->cls);
  else
    snprintf(buf, n, "%d", c->valence);
  return buf;
}

int ss_cli_print_json(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                      json_object *eigvec) {
  ss_error err = {0};
  json_object *r = NULL;
  if (ss_report_case_json(p, o->neig, eigvec, &r, &err)) {
    fprintf(stderr, "subspectra %s: %s\n", o->cmd, err.msg);
    return ss_cli_exit_status(err.status);
  }
  printf("%s\n", json_object_to_json_string_ext(r, SS_CLI_JSON_FLAGS));
  json_object_put(r);
  return SS_EXIT_OK;
}

static void print_value(FILE *f, const ss_eigval *v) {
  if (v->im == 0.0)
    fprintf(f, "%.12g", v->re);
  else
    fprintf(f, "%.12g%+.12gi", v->re, v->im);
}

void ss_cli_print_tsv(const ss_cli_analyze_opts *o, const ss_pipeline *p, int header) {
  const ss_eig *e = p->e;
  const ss_regularity *reg = &p->reg;
  if (header) {
    printf("scheme\tcase\tlink_or_valence\ttwo_ring\tone_ring");
    for (int i = 0; i < o->neig; i++)
      printf("\tlambda%d", i);
    printf("\teigen_condition\treason\ttolerance\tregularity\tregularity_reason\t"
           "min_scaled_jacobian\tinjectivity\tinjectivity_reason\teigen_certified\t"
           "regularity_certified\n");
  }
  char buf[32];
  printf("%s\t%s\t%s\t%zu\t%zu", ss_scheme_name(p->scheme), ss_case_name(p->c.kind),
         ss_cli_case_param(o, p, buf, sizeof buf), p->M->n2, p->M->n1);
  for (int i = 0; i < o->neig; i++) {
    putchar('\t');
    if ((size_t)i < e->n) print_value(stdout, e->val + i);
  }
  const ss_verdict *cond = &p->v.cond; /* the exact path's with --certify */
  printf("\t%s\t%s\t%g\t%s\t%s\t", ss_verdict_name(cond->verdict), cond->reason, e->tol,
         ss_verdict_name(p->v.reg.verdict), p->v.reg.reason);
  if (isfinite(reg->min_scaled_jacobian)) printf("%.6g", reg->min_scaled_jacobian);
  printf("\t%s\t%s\t%d\t%d\n", ss_verdict_name(p->v.inj.verdict), p->v.inj.reason,
         cond->certified, p->v.reg.certified);
}

/* The case line of the text output. */
static void print_case(const ss_pipeline *p) {
  const ss_case_resolved *c = &p->c;
  const ss_local *M = p->M;
  printf("scheme %s, %s case", ss_scheme_name(p->scheme), ss_case_name(c->kind));
  if (c->kind == SS_CASE_EDGE_POINT)
    printf(", link %s (k = %d): the bipyramid over %d, a point on an edge of valence %d, "
           "analysed as --edge %d\n",
           c->text, c->k, c->valence, c->valence, c->valence);
  else if (c->kind == SS_CASE_VERTEX)
    printf(", link %s (k = %d, %d %s)\n", c->text, c->k, 2 * c->k - 4,
           ss_cell_plural(M->cell));
  else if (c->kind == SS_CASE_FACE)
    printf(" (two tets sharing a face)\n");
  else if (M->cell == SS_TRIANGLE && c->cls)
    printf(", valence %d, 4-8 class %d%s\n", c->valence, c->cls,
           c->cls == 4 ? " (S is class 8's with twice the valence: after one step "
                         "the vertex is of class 8)"
                       : "");
  else
    printf(", valence %d\n", c->valence);
}

/* ", certified" for a proven verdict; with --certify ", not certified" for a
 * decided one that is not (JSON's certified: false; an undecided verdict
 * says why itself); otherwise nothing, as before --certify existed. */
static const char *certified_text(const ss_pipeline *p, const ss_verdict *v) {
  if (v->certified) return ", certified";
  return p->opts.certify && v->verdict != SS_UNDECIDED ? ", not certified" : "";
}

/* The eigenvalues and the condition, in doubles and (--certify) exactly. */
static void print_spectrum(const ss_cli_analyze_opts *o, const ss_pipeline *p) {
  const ss_eig *e = p->e;
  printf("\n    #  eigenvalue            mult  rcond     block\n");
  for (size_t i = 0; i < e->n && i < (size_t)o->neig; i++) {
    char v[64];
    if (e->val[i].im == 0.0)
      snprintf(v, sizeof v, "%.12g", e->val[i].re);
    else
      snprintf(v, sizeof v, "%.8g%+.8gi", e->val[i].re, e->val[i].im);
    printf("  %3zu  %-20s  %4d  %-8.2e  %s\n", i, v, e->val[i].mult, e->val[i].rcond,
           e->val[i].block ? "outer" : "one-ring");
  }
  printf("\neigenvalue condition: %s%s%s (equal within relative tolerance %.1e",
         ss_verdict_name(e->cond.verdict), e->cond.reason[0] ? ": " : "", e->cond.reason,
         e->tol);
  if (e->tol > e->tol_requested)
    printf(": the requested %.1e is below the eigenvalues' rounding error bound",
           e->tol_requested);
  printf(")\n");
  if (p->opts.certify) {
    const ss_verdict *cond = &p->v.cond;
    /* proven without an exact spectrum: the Fourier blocks in balls
     * (ss_fourier.h, surface vertices and edges with irrational weights) or
     * the balls and Schur's lemma (ss_schur.h, volume vertices) */
    const char *how = p->route ? p->route : "exact";
    printf("eigenvalue condition, %s (%.2f s): %s%s%s%s\n", how, p->exact_seconds,
           ss_verdict_name(cond->verdict), certified_text(p, cond),
           cond->reason[0] ? ": " : "", cond->reason);
    size_t nr = 0;
    const ss_exact_root *x = p->ex ? ss_exact_roots(p->ex, &nr) : NULL;
    for (size_t i = 0; i < nr && i < 6; i++) {
      char poly[160];
      printf("    %-20.12g %+.3gi  mult %d  radius %.1e  minimal polynomial %s\n",
             x[i].re, x[i].im, x[i].mult, x[i].rad,
             ss_exact_minpoly(p->ex, i, poly, sizeof poly));
    }
  }
}

/* The regularity and injectivity verdicts with the ring's levels. */
static void print_map(const ss_cli_analyze_opts *o, const ss_pipeline *p) {
  const ss_regularity *reg = &p->reg;
  const ss_verdict *rv = p->forced ? &reg->verdict : &p->v.reg, *iv = &p->v.inj;
  printf("regularity: %s%s%s%s\n", ss_verdict_name(rv->verdict), certified_text(p, rv),
         rv->reason[0] ? ": " : "", rv->reason);
  if (p->psi.ran) {
    const ss_psi_result *q = &p->psi;
    if (q->by_masks)
      printf(
          "  psi at its regular vertices (the regular lattice's tangent masks, %s): %s; "
          "%zu regular vertices, %zu positive, %zu negative\n",
          q->verdict.certified ? "proven on the exact basis's enclosure"
                               : "double precision",
          ss_verdict_name(q->verdict.verdict), q->nregular, q->nregular_pos,
          q->nregular_neg);
    else if (q->by_spokes)
      printf("  psi by its spokes alone (no polynomial pieces; the edge cases' modes on "
             "the ring's points): %s\n",
             ss_verdict_name(q->verdict.verdict));
    else
      printf(
          "  psi on its polynomial pieces (boxes to side 1/%d, %s): %s; "
          "%zu pieces, of one sign on %.2f %% of the ring, opposite %.2f %%, folded or "
          "in doubt %.2f %%, uncovered %.2f %% (round the spokes)\n",
          1 << q->maxdepth,
          q->verdict.certified ? "proven on the exact basis's enclosure"
          : q->enclosed && q->verdict.verdict != SS_UNDECIDED
              ? "double precision, not proven"
              : "double precision",
          ss_verdict_name(q->verdict.verdict), q->pieces, 100.0 * q->covered,
          100.0 * q->opposite, 100.0 * q->doubtful, 100.0 * q->uncovered);
    if (q->spokes)
      printf("  its %zu spokes by det[a' | B] along them (double precision, evidence): "
             "%zu of one sign, %zu changing sign, %zu degenerate\n",
             q->nspokes, q->nspoke_one, q->nspoke_change, q->nspoke_deg);
    else if (q->spoke_why[0])
      printf("  its spokes: %s\n", q->spoke_why);
    if (!p->forced && p->v.reg.on == SS_ON_PSI && reg->verdict.verdict != rv->verdict)
      printf("  the control net's verdict: %s%s%s\n",
             ss_verdict_name(reg->verdict.verdict), reg->verdict.reason[0] ? ": " : "",
             reg->verdict.reason);
  }
  if (reg->nlevels > 0) {
    printf(
        "  judged on the ring (cells not touching the centre), levels 0..%d of at most "
        "%d; fold shrink ratio %.2f:\n",
        reg->nlevels - 1, o->ring_levels, reg->shrink);
    for (int l = 0; l < reg->nlevels; l++) {
      const ss_ring_level *L = reg->level + l;
      printf(
          "    level %d: %zu cells: %zu positive, %zu negative, %zu folded (%zu inverted "
          "whole), %zu undecided, %zu flat; minimum scaled Jacobian %.6g\n",
          l, L->cells, L->positive, L->negative, L->folded, L->inverted, L->undecided,
          L->degenerate, L->min_scaled_jacobian);
    }
    printf(
        "  minimum scaled Jacobian %.6g (level %d, ring cell %zu; hex subdivision depth "
        "limit %d)\n"
        "  cells around the centre: %zu of %zu not of the ring's sign "
        "(centre_corner_folds; they decide nothing)\n",
        reg->min_scaled_jacobian, reg->ring_level, reg->worst_cell, reg->depth,
        reg->centre_corner_folds, p->M->ncentre);
  }
  printf("injectivity: %s%s%s%s\n", ss_verdict_name(iv->verdict), certified_text(p, iv),
         iv->reason[0] ? ": " : "", iv->reason);
  if (iv->verdict == SS_PASS)
    printf("  degree %d about psi(p); no two ring cells without a common vertex meet "
           "(piecewise-linear images, exact predicates)\n",
           p->inj.degree);
}

void ss_cli_print_text(const ss_cli_analyze_opts *o, const ss_pipeline *p) {
  const ss_local *M = p->M;
  print_case(p);
  printf(
      "two-ring %zu points, one-ring %zu (read on level %d); outer part in %zu blocks, "
      "the largest %zu\n",
      M->n2, M->n1, M->level, p->e->nblocks, p->e->largest_block);
  if (p->has_diag)
    printf("major diagonals: %s; %zu of %zu face-adjacent pairs improper (Definition 3.2 "
           "as read in docs/schemes.md)\n",
           ss_diag_name(p->c.asked.diag), p->improper, p->pairs);
  print_spectrum(o, p);
  if (p->e->basis_kind[0]) printf("subdominant basis: %s\n", p->e->basis_kind);
  print_map(o, p);
}
