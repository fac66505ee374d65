/* ss_cli_reproduce_md.c — NAME.md of a `reproduce` table: the cases with
 * their eigenvalues and verdicts, each row marked match / differ / not quoted
 * against the papers; the counts per k of an exhaustive table; other schemes
 * on the same cases side by side; every quoted value with its source. */
#include <limits.h>
#include <math.h>
#include <string.h>

#include "ss_cli_reproduce.h"
#include "ss_report_exhaustive.h"

/* The title, how to regenerate the table, its note and the rules by which
 * verdicts and matches are decided (tolerance tol, Jacobian depth). */
static void md_head(ss_strbuf *md, const ss_reproduce_table *t,
                    const ss_reproduce_results *l, double tol, int depth) {
  ss_sb_printf(md, "# %s\n\n", t->title);
  ss_sb_printf(md,
               "Regenerate: `subspectra reproduce` (the cases: `%s`; raw results in "
               "`data/%s.jsonl`, the comparison with the papers in `%s.tsv`).\n\n",
               t->command, t->name, t->name);
  if (t->note) ss_sb_printf(md, "%s\n\n", t->note);
  ss_sb_printf(
      md,
      "Verdicts: eigenvalues equal within relative tolerance %g; hex Jacobian test "
      "to subdivision depth %d. Quoted values (data/reference/*.tsv): a decimal "
      "matches when \\|computed − quoted\\| ≤ half a unit in its last digit, an "
      "exact value (fraction, integer formula) within %g, a verdict when equal; "
      "the column *paper* says whether every value quoted for the row matches.\n\n",
      tol, depth, SS_REF_EXACT_TOL);
  ss_sb_printf(
      md,
      "Regularity is judged on the characteristic map's ring (ring levels up to "
      "%d, a fold persisting when its share of the cells does not halve); "
      "injectivity by the degree about ψ(p) and the overlaps of the ring's "
      "piecewise-linear image (exact predicates on the double-precision net).%s\n\n",
      l->o.ring_levels,
      l->o.certify
          ? " ✓ marks a proven verdict: the exact spectrum of the rational matrix "
            "(FLINT), the subdominant basis enclosed in ball arithmetic (arb) and "
            "the ring's Jacobians in interval arithmetic; a verdict that could not "
            "be proven is undecided, \"not certified\", with the double-precision "
            "verdict in its reason."
          : " Verdicts are double precision (`reproduce --certify` proves them).");
  if (l->o.psi_depth > 0 && !strcmp(t->scheme, "boxspline"))
    ss_sb_printf(
        md,
        "ψ itself is judged where the net does not pass (`analyze --psi-depth %d`): at "
        "the ring's regular vertices, where the regular lattice's tangent masks read "
        "det Dψ from the refined net%s.  The spokes are not judged (they are matched to "
        "the edge cases for tetoct only).  A regularity verdict whose reason begins "
        "\"psi folds\" is a statement about ψ (two regular vertices with det Dψ of "
        "opposite signs); any other is about the control net.\n\n",
        l->o.psi_depth,
        l->o.certify ? " (exact masks, the net enclosed: a fold of ψ marked ✓ is proven)"
                     : " (double precision)");
  else if (l->o.psi_depth > 0 && !strcmp(t->scheme, "tetoct"))
    ss_sb_printf(
        md,
        "ψ itself is judged where the net does not pass (`analyze --psi-depth %d`): at "
        "the ring's regular vertices, where the regular lattice's tangent masks read "
        "det Dψ from the refined net%s, and on the spokes by the edge cases' modes "
        "(%s).  A regularity verdict whose reason begins \"psi folds\", or \"psi o "
        "sigma = psi\", is a statement about ψ (two regular vertices with det Dψ of "
        "opposite signs, or a symmetry of ψ); any other is about the control "
        "net.\n\n",
        l->o.psi_depth,
        l->o.certify ? " (exact masks, the net enclosed: a fold of ψ marked ✓ is proven)"
                     : " (double precision)",
        l->o.certify ? "evidence only: under `--certify` it decides nothing, its finding "
                       "appended to the net's reason"
                     : "evidence in double precision: a pass by it says \"by evidence\"");
  else if (l->o.psi_depth > 0)
    ss_sb_printf(
        md,
        "ψ itself is judged on its polynomial pieces (boxes of the ring to side 1/%d; "
        "`analyze --psi-depth %d`): where a box is a tricubic B-spline piece the "
        "Bernstein form of det Dψ decides its sign%s.  A regularity verdict whose "
        "reason begins \"psi folds\", or \"psi o sigma = psi\", is a statement about "
        "ψ (two points with det Dψ of opposite signs, or a symmetry of ψ); any other "
        "is about the control net, and a fold of the net that ψ does not show is "
        "no longer %s.\n\n",
        1 << l->o.psi_depth, l->o.psi_depth,
        l->o.certify ? ", the pieces carried in interval arithmetic from the enclosed "
                       "basis, so a fold of ψ marked ✓ is proven"
                     : " (double precision)",
        l->o.certify ? "proven (undecided)" : "certified");
}

/* Whether any result of l reports major diagonals (a column of its own). */
static int any_diag(const ss_reproduce_results *l) {
  int has_diag = 0;
  for (size_t i = 0; i < l->n; i++)
    has_diag |= l->r[i].has_diag;
  return has_diag;
}

/* The header row of the cases table and its alignment row; m = the
 * eigenvalues the eigenvalue condition reads (2 surfaces, 3 volumes). */
static void md_columns(ss_strbuf *md, const ss_reproduce_table *t, int has_diag, int m) {
  if (t->kind == SS_CASE_VERTEX)
    ss_sb_printf(md, "| # | link | k | cells |");
  else if (t->kind == SS_CASE_FACE)
    ss_sb_printf(md, "| case |");
  else
    ss_sb_printf(md, "| valence |");
  if (has_diag) ss_sb_printf(md, " improper pairs |");
  ss_sb_printf(md, " two-ring | one-ring |");
  if (t->neig)
    for (int i = 1; i <= t->neig; i++)
      ss_sb_printf(md, " λ%d |", i);
  else {
    for (int i = 1; i <= m; i++)
      ss_sb_printf(md, " λ%d |", i);
    ss_sb_printf(md, " \\|λ%d\\| |", m + 1);
  }
  ss_sb_printf(md,
               " eigenvalue condition | regularity | injectivity | min scaled Jacobian "
               "| paper |\n|");
  const int ncol = (t->kind == SS_CASE_VERTEX ? 4 : 1) + has_diag + 2 +
                   (t->neig ? t->neig : m + 1) + 5;
  for (int i = 0; i < ncol; i++)
    ss_sb_printf(md, "---|");
  ss_sb_printf(md, "\n");
}

/* One row of the cases table: result r, number i, its comparison status
 * (0 not quoted, 1 match, 2 differ). */
static void md_row(ss_strbuf *md, const ss_reproduce_table *t, const ss_result *r,
                   size_t i, int has_diag, int m, int status) {
  char buf[64];
  const char *tag = ss_reproduce_case_tag(t, i);
  if (tag)
    ss_sb_printf(md, "| %s | `%s`%s | %d | %zu |", tag, r->link,
                 r->kind == SS_CASE_EDGE_POINT ? " (edge point)" : "", r->k, r->cells);
  else if (ss_result_has_link(r))
    ss_sb_printf(md, "| %zu | `%s`%s | %d | %zu |", i + 1, r->link,
                 r->kind == SS_CASE_EDGE_POINT ? " (edge point)" : "", r->k, r->cells);
  else if (r->kind == SS_CASE_FACE)
    ss_sb_printf(md, "| face |");
  else
    ss_sb_printf(md, "| %d |", r->k);
  if (has_diag) {
    if (r->has_diag)
      ss_sb_printf(md, " %zu of %zu |", r->improper, r->pairs);
    else
      ss_sb_printf(md, " – |");
  }
  ss_sb_printf(md, " %zu | %zu |", r->two_ring, r->one_ring);
  const int shown = t->neig ? t->neig : m;
  for (int e = 1; e <= shown; e++) {
    if (e < r->neig) {
      ss_reproduce_eig_text(r->eig + e, buf, sizeof buf);
      ss_sb_printf(md, " %s |", buf);
    } else
      ss_sb_printf(md, " |");
  }
  if (!t->neig) {
    if (m + 1 < r->neig)
      ss_sb_printf(md, " %.6f |", hypot(r->eig[m + 1].re, r->eig[m + 1].im));
    else
      ss_sb_printf(md, " |");
  }
  ss_sb_printf(md, " ");
  ss_sb_verdict(md, &r->v.cond, r->v.cond.certified);
  ss_sb_printf(md, " | ");
  ss_sb_verdict(md, &r->v.reg, r->v.reg.certified);
  ss_sb_printf(md, " | ");
  if (r->v.inj.verdict == SS_PASS)
    ss_sb_printf(md, "pass (degree %d)", r->inj_degree);
  else
    ss_sb_verdict(md, &r->v.inj, r->v.inj.certified);
  if (isfinite(r->min_sj))
    ss_sb_printf(md, " | %.4f |", r->min_sj);
  else
    ss_sb_printf(md, " | – |");
  ss_sb_printf(md, " %s |\n",
               status == 0   ? "not quoted"
               : status == 1 ? "match"
                             : "**differ**");
}

/* The verdicts of an exhaustive table counted per k: which condition fails,
 * and how many passing maps fold in cells around p (which decide nothing,
 * ss_charmap.h).  The rows are ss_report_exhaustive's, as `report --table
 * exhaustive` writes them from a sweep's store. */
static void per_k(ss_strbuf *md, const ss_reproduce_results *l) {
  char line[SS_REPORT_EXH_LINE];
  /* (no columns on psi: reproduce does not judge psi on its pieces) */
  ss_report_exh_md_head(l->o.certify, 0, line, sizeof line);
  ss_sb_printf(md, "\n%s", line);
  int lo = INT_MAX, hi = 0;
  for (size_t i = 0; i < l->n; i++) {
    lo = l->r[i].k < lo ? l->r[i].k : lo;
    hi = l->r[i].k > hi ? l->r[i].k : hi;
  }
  for (int k = lo; k <= hi; k++) { /* the enumeration interleaves the k */
    ss_report_exh_k g;
    ss_report_exh_init(&g, k);
    for (size_t i = 0; i < l->n; i++)
      if (l->r[i].k == k) ss_report_exh_add(&g, l->r + i, 0);
    ss_report_exh_md_row(&g, l->o.certify, 0, line, sizeof line);
    ss_sb_printf(md, "%s", line);
  }
}

/* The verdict of r in a few words: "pass", or the first condition that does
 * not pass and how. */
static const char *verdict_words(const ss_result *r) {
  const ss_verdict_kind v = ss_result_verdict(r);
  if (v == SS_PASS) return "pass";
  const int und = v == SS_UNDECIDED;
  if (r->v.cond.verdict != SS_PASS)
    return und ? "undecided: eigenvalue condition" : "fail: eigenvalue condition";
  if (r->v.reg.verdict != SS_PASS)
    return und ? "undecided: regularity" : "fail: regularity";
  return und ? "undecided: injectivity" : "fail: injectivity";
}

/* lambda1..lambda3 and |lambda4| of r as Markdown cells. */
static void sb_leading(ss_strbuf *md, const ss_result *r) {
  char buf[64];
  for (int e = 1; e <= 3; e++) {
    if (e < r->neig) {
      ss_reproduce_eig_text(r->eig + e, buf, sizeof buf);
      ss_sb_printf(md, " %s |", buf);
    } else
      ss_sb_printf(md, " |");
  }
  if (4 < r->neig)
    ss_sb_printf(md, " %.6f |", hypot(r->eig[4].re, r->eig[4].im));
  else
    ss_sb_printf(md, " |");
}

/* The section of table t that shows the results l of t's scheme beside the
 * results v of scheme vs (one of t->vs) on the same cases (same order). */
static void side_by_side(ss_strbuf *md, const ss_reproduce_table *t, const char *vs,
                         const ss_reproduce_results *l, const ss_reproduce_results *v) {
  size_t both = 0, only_a = 0, only_b = 0;
  ss_sb_printf(md,
               "\n## Beside %s\n\nThe same cases with `--scheme %s`: λ1..λ3 and \\|λ4\\| "
               "after λ0 = 1 and the verdict of each.\n\n| # | case | %s λ1 | λ2 | λ3 | "
               "\\|λ4\\| | %s verdict | %s λ1 | λ2 | λ3 | \\|λ4\\| | %s verdict |\n"
               "|--:|---|--:|--:|--:|--:|---|--:|--:|--:|--:|---|\n",
               vs, vs, t->scheme, t->scheme, vs, vs);
  for (size_t i = 0; i < l->n && i < v->n; i++) {
    const ss_result *a = l->r + i, *b = v->r + i;
    char buf[64];
    if (ss_result_has_link(a))
      ss_sb_printf(md, "| %zu | `%s`%s |", i + 1, a->link,
                   a->kind == SS_CASE_EDGE_POINT ? " (edge point)" : "");
    else
      ss_sb_printf(md, "| %zu | %s |", i + 1,
                   ss_reproduce_case_label(a, buf, sizeof buf));
    sb_leading(md, a);
    ss_sb_printf(md, " %s |", verdict_words(a));
    sb_leading(md, b);
    ss_sb_printf(md, " %s |\n", verdict_words(b));
    const int pa = ss_result_verdict(a) == SS_PASS, pb = ss_result_verdict(b) == SS_PASS;
    both += (size_t)(pa && pb);
    only_a += (size_t)(pa && !pb);
    only_b += (size_t)(!pa && pb);
  }
  ss_sb_printf(
      md,
      "\n**Side by side:** of %zu cases %zu pass under both schemes, %zu under %s "
      "only, %zu under %s only.\n",
      l->n, both, only_a, t->scheme, only_b, vs);
}

/* Every quoted value beside the computed one, then their sources as numbered
 * footnotes (or a line saying nothing is quoted). */
static void md_quoted(ss_strbuf *md, const ss_reproduce_results *l,
                      const ss_reproduce_cmps *cmp) {
  if (cmp->n) {
    ss_sb_printf(md, "\n## Quoted values\n\n| # | case | quantity | quoted | computed | "
                     "computed − quoted | tolerance | status | source |\n"
                     "|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < cmp->n; i++) {
      const ss_reproduce_cmp *c = cmp->c + i;
      char buf[32], num[24] = "–";
      const int whole = c->row == SS_REPRODUCE_TABLE_ROW;
      if (!whole) snprintf(num, sizeof num, "%zu", c->row + 1);
      ss_sb_printf(md, "| %s | %s | %s | %s | %s | %s | %s | %s | [%d] |\n", num,
                   c->what[0] ? c->what
                              : ss_reproduce_case_label(l->r + c->row, buf, sizeof buf),
                   c->ref->quantity, c->quoted, c->computed, c->diff, c->tol,
                   c->match ? "match" : "**differ**", c->note);
    }
    ss_sb_printf(md, "\nSources:\n\n");
    for (size_t u = 0; u < cmp->nused; u++) {
      const ss_ref_row *q = cmp->used[u];
      ss_sb_printf(md, "%zu. %s, %s: “", u + 1, q->paper, q->location);
      ss_sb_cell(md, q->quote);
      ss_sb_printf(md, "” — ");
      ss_sb_cell(md, q->note);
      ss_sb_printf(md, " (`%s:%ld`)\n", q->file, q->line);
    }
  } else {
    ss_sb_printf(md, "\nNo value in this table is quoted by the papers "
                     "(data/reference/*.tsv).\n");
  }
}

void ss_reproduce_md(ss_strbuf *md, const ss_reproduce_table *t,
                     const ss_reproduce_results *l, const ss_reproduce_results *vs,
                     const ss_reproduce_cmps *cmp, const ss_reproduce_tally *ty) {
  const double tol = l->n ? l->r[0].tol : ss_result_defaults().tol;
  const int depth = l->n ? l->r[0].depth : ss_result_defaults().depth;
  const int m = t->kind == SS_CASE_SURFACE_VERTEX ? 2 : 3;
  const int has_diag = any_diag(l);
  md_head(md, t, l, tol, depth);
  md_columns(md, t, has_diag, m);
  for (size_t i = 0; i < l->n; i++)
    md_row(md, t, l->r + i, i, has_diag, m, cmp->row_status[i]);
  ss_sb_printf(
      md,
      "\n**Summary:** %zu of %zu cases pass both conditions; %zu quoted values: "
      "%zu match, %zu differ; %zu of %zu rows not quoted (relative tolerance %g).\n",
      ty->pass, ty->cases, ty->quoted, ty->match, ty->quoted - ty->match, ty->unquoted,
      ty->cases, tol);
  if (t->src == SS_REPRODUCE_LINKS) per_k(md, l);
  for (int k = 0; vs && k < t->nvs; k++)
    side_by_side(md, t, t->vs[k], l, vs + k);
  md_quoted(md, l, cmp);
}
