/* ss_cli_draw.c — `subspectra draw`: the picture of one case's
 * characteristic map, with exactly analyze's numbers (ss_cli_analyze.h). */
#include <stdio.h>

#include "ss_cli.h"
#include "ss_cli_analyze.h"

int ss_cli_draw_case(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                     const char *where) {
  ss_error err = {0};
  const ss_regularity *reg = &p->reg;
  if (!p->cm) {
    fprintf(stderr, "subspectra draw: %snothing to draw: %s\n", where,
            reg->verdict.reason);
    return SS_EXIT_FAIL;
  }
  char caption[600], buf[32];
  char dtext[128] = "";
  if (p->has_diag)
    snprintf(dtext, sizeof dtext, ", diagonals %s (%zu of %zu pairs improper)",
             ss_diag_name(p->c.asked.diag), p->improper, p->pairs);
  snprintf(
      caption, sizeof caption, "%s, %s %s%s%s", ss_scheme_name(p->scheme),
      ss_case_name(p->c.kind),
      p->c.kind == SS_CASE_FACE ? "" : ss_cli_case_param(o, p, buf, sizeof buf), dtext,
      p->forced ? "; forced: NOT a characteristic map (the eigenvalue condition fails)"
                : "");
  ss_report_draw_opts dopt = o->draw;
  dopt.caption = o->nocaption ? NULL : caption;
  if (ss_report_draw(p->cm, reg, &dopt, o->out, &err)) {
    fprintf(stderr, "subspectra draw: %s\n", err.msg);
    return SS_EXIT_USAGE; /* bad file, i/o or out of memory */
  }
  fprintf(stderr, "subspectra draw: wrote %s (%s %s%s%s)\n", o->out,
          p->forced ? "forced map, eigenvalue condition fails; its cells:" : "regularity",
          ss_verdict_name(reg->verdict.verdict), reg->verdict.reason[0] ? ": " : "",
          reg->verdict.reason);
  return p->forced ? SS_EXIT_FAIL : SS_EXIT_OK;
}
