/* ss_report_exhaustive.h — exhaustive tables of vertex one-rings: the
 * verdicts of every link with k vertices counted per k, by the condition that
 * fails, and the list of the links that do not pass.
 *
 * One counting and one row format for both writers of such tables:
 * `subspectra reproduce` (its tables over every link of a range of k, from
 * results in memory) and `subspectra report --table exhaustive` (from a
 * results store written by `sweep`), so that the same cases give the same
 * rows, character for character, whichever path computed them.
 *
 * A link is counted once: as a vertex case, or as a point on an edge (kind
 * edge-point: a bipyramid link under a hex scheme, judged as that edge and
 * kept out of the vertex counts).  The failure classes are exclusive and
 * ordered: the eigenvalue condition fails; else the regularity fails; else
 * the injectivity fails ("injectivity only").
 *
 * Library code: the writers print to the FILE the caller passes and nothing
 * else. */
#ifndef SS_REPORT_EXHAUSTIVE_H
#define SS_REPORT_EXHAUSTIVE_H

#include <stdio.h>

#include "ss_api.h"
#include "ss_report_table.h"
#include "ss_result.h"

SS_BEGIN_DECLS

/* Room for one Markdown line of ss_report_exhaustive_md_head/_row. */
#define SS_REPORT_EXH_LINE 512

/* The verdicts of the links with k vertices. */
typedef struct {
  int k;                        /* link vertices */
  size_t links;                 /* links counted: vertex cases + edge points */
  size_t vertices;              /* of which judged as vertices */
  size_t pass;                  /* vertex cases passing all three verdicts */
  size_t fail_cond;             /* failing the eigenvalue condition */
  size_t fail_reg;              /* condition not failing, regularity failing */
  size_t fail_inj;              /* failing the injectivity only */
  size_t undecided;             /* neither passing nor failing */
  size_t centre;                /* passing, with folds in cells around p (which
                                   decide nothing: ss_charmap.h) */
  size_t cert_pass;             /* passes that are proven (ss_result_certified) */
  size_t cert_fail;             /* failures that are proven */
  size_t psi_pass;              /* vertex cases with a characteristic map
                                   whose sweep asked for psi (--psi-depth),
                                   by the regularity verdict when it is about
                                   psi (ss_result_psi): pass */
  size_t psi_fail;              /* fail */
  size_t psi_undecided;         /* neither (psi not judged, or judged
                                   without a decision) */
  size_t edge_points;           /* links judged as a point on an edge */
  int edge_valence;             /* the last such link's edge valence */
  ss_verdict_kind edge_verdict; /* and its combined verdict */
} ss_report_exh_k;

/* Zero g and set its k. */
void ss_report_exh_init(ss_report_exh_k *g, int k);

/* Count r (a vertex or edge-point result with r->k == g->k) into g.  Other
 * kinds are ignored.  psi_asked: r's sweep asked for psi (its identity has
 * psi-depth=N), so a vertex case with a characteristic map is counted in
 * the psi columns even where the judge found nothing to decide (tetoct and
 * boxspline judge psi only where the net does not pass, and record no psi
 * result when the ring's regular vertices show no fold). */
void ss_report_exh_add(ss_report_exh_k *g, const ss_result *r, int psi_asked);

/* Why r does not pass, in the classes of the table: "pass", "fail: eigenvalue
 * condition", "fail: regularity", "fail: injectivity only" or "undecided". */
const char *ss_report_exh_class(const ss_result *r);

/* Whether psi was judged for some case g counts (psi_pass + psi_fail +
 * psi_undecided > 0). */
int ss_report_exh_has_psi(const ss_report_exh_k *g);

/* The Markdown header of a per-k table (two lines, each ending in a line
 * break) into buf (n >= SS_REPORT_EXH_LINE); certify adds the columns
 * certified pass, certified fail and not certified, psi the columns on psi:
 * pass, fail, undecided. */
void ss_report_exh_md_head(int certify, int psi, char *buf, size_t n);

/* One Markdown row of g (ending in a line break) into buf
 * (n >= SS_REPORT_EXH_LINE), with the columns of ss_report_exh_md_head(certify,
 * psi) (on psi: "–" when g has none); an empty string when g counts no
 * link. */
void ss_report_exh_md_row(const ss_report_exh_k *g, int certify, int psi, char *buf,
                          size_t n);

/* Which of the exhaustive tables to write. */
typedef enum {
  SS_REPORT_EXH_COUNTS = 0, /* per scheme identity and k: the counts */
  SS_REPORT_EXH_LINKS       /* every vertex link that does not pass, with the
                               class, whether proven, and the three reasons */
} ss_report_exh_table;

/* Write table `which` of the vertex and edge-point rows of rows[0..n) (sorted
 * as ss_report_rows_load sorts them; other kinds are left out) to f.  Counts:
 * Markdown (a section per scheme identity, the certified columns when the
 * identity is certified, the columns on psi when psi was judged for some case
 * of it, then a legend), CSV (the columns on psi when psi was judged for some
 * case, empty in the rows of a k without) or JSON (the keys on psi for a k
 * where psi was judged); links: CSV or JSON.  Rows without psi give the
 * tables of stores before psi was kept, byte for byte.
 * Every number is a count and no timing is written, so equal stores give
 * equal bytes.  SS_EINPUT for another format, SS_EIO when writing to f
 * fails, SS_ENOMEM. */
ss_status ss_report_exh_write(FILE *f, ss_report_format fmt, ss_report_exh_table which,
                              const ss_report_row *rows, size_t n, ss_error *err);

SS_END_DECLS

#endif
