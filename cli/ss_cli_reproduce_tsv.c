/* ss_cli_reproduce_tsv.c — NAME.tsv of a `reproduce` table: the comparison
 * with the papers, machine-readable: one line per quoted value (and one per
 * row that none speaks of) under a commented header with the rules and the
 * summary. */
#include "ss_cli_reproduce.h"

void ss_reproduce_tsv(ss_strbuf *tsv, const ss_reproduce_table *t,
                      const ss_reproduce_results *l, const ss_reproduce_cmps *cmp,
                      const ss_reproduce_tally *ty) {
  const double tol = l->n ? l->r[0].tol : ss_result_defaults().tol;
  const int depth = l->n ? l->r[0].depth : ss_result_defaults().depth;
  ss_sb_printf(tsv,
               "# %s\n# produced by: subspectra reproduce (the cases: %s)\n"
               "# verdicts: relative tolerance %g, hex Jacobian depth %d; match rule: "
               "decimals within half a unit in the last digit, exact values within %g, "
               "verdicts equal\n"
               "# summary: %zu of %zu cases pass both conditions; %zu quoted values: %zu "
               "match, %zu differ; %zu rows not quoted\n"
               "table\trow\tcase\tlink\tquantity\tquoted\tcomputed\tdifference\t"
               "tolerance\tstatus\tpaper\tlocation\treference\n",
               t->title, t->command, tol, depth, SS_REF_EXACT_TOL, ty->pass, ty->cases,
               ty->quoted, ty->match, ty->quoted - ty->match, ty->unquoted);
  for (size_t i = 0, j = 0; i < l->n; i++) {
    char buf[32];
    const ss_result *r = l->r + i;
    if (!cmp->row_status[i])
      ss_sb_printf(tsv, "%s\t%zu\t%s\t%s\t-\t-\t-\t-\t-\tnot quoted\t-\t-\t-\n", t->name,
                   i + 1, ss_reproduce_case_label(r, buf, sizeof buf),
                   r->link[0] ? r->link : "-");
    for (; j < cmp->n && cmp->c[j].row == i; j++) {
      const ss_reproduce_cmp *c = cmp->c + j;
      ss_sb_printf(tsv, "%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s:%ld\n",
                   t->name, i + 1,
                   c->what[0] ? c->what : ss_reproduce_case_label(r, buf, sizeof buf),
                   r->link[0] ? r->link : "-", c->ref->quantity, c->quoted, c->computed,
                   c->diff, c->tol, c->match ? "match" : "differ", c->ref->paper,
                   c->ref->location, c->ref->file, c->ref->line);
    }
  }
  for (size_t j = 0; j < cmp->n; j++) { /* about the whole table: row "-" */
    const ss_reproduce_cmp *c = cmp->c + j;
    if (c->row == SS_REPRODUCE_TABLE_ROW)
      ss_sb_printf(tsv, "%s\t-\t%s\t-\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s:%ld\n", t->name,
                   c->what, c->ref->quantity, c->quoted, c->computed, c->diff, c->tol,
                   c->match ? "match" : "differ", c->ref->paper, c->ref->location,
                   c->ref->file, c->ref->line);
  }
}
