/* ss_report_plot.h — a figure of a results store's cases against k (PNG or
 * SVG through cairo).
 *
 * One figure per scheme identity.  It has one column of two panels per case
 * kind present (vertex: k = link vertices; edge, edge point and surface
 * vertex: the valence n; face: one position; ss_report_plot_x), x axis with
 * integer ticks:
 *   top     |lambda1|..|lambda4| of the two-ring matrix: for each k and index
 *           i, a bar from the smallest to the largest |lambda_i| over the
 *           cases with that k and a marker at every distinct value (within a
 *           pixel), one colour and marker shape per index, placed side by
 *           side around k; a legend;
 *   bottom  the minimum scaled Jacobian of each case, points spread evenly
 *           (deterministically) around k, the zero line drawn; passing cases
 *           blue, failing (either condition) red, undecided orange; a case
 *           without a characteristic map as a cross on the panel's floor.
 * The title names the identity and the number of cases. */
#ifndef SS_REPORT_PLOT_H
#define SS_REPORT_PLOT_H

#include "ss_api.h"
#include "ss_report_table.h"

SS_BEGIN_DECLS

/* How to plot. */
typedef struct {
  int width;            /* picture width in pixels (PNG) or points (SVG); 0:
                           560 per case kind plus margins */
  int height;           /* picture height; 0: 720 */
  const char *identity; /* plot the rows of this scheme identity; NULL: the
                           identity of the first row */
} ss_report_plot_opts;

/* Defaults: automatic size, the first row's identity. */
ss_report_plot_opts ss_report_plot_defaults(void);

/* The abscissa of a result in its panel: k, the link's vertices, for a
 * vertex; the valence n for an edge, a surface vertex and an edge point (a
 * vertex whose link is the bipyramid over n: its k is n + 2); 0 for the
 * face. */
int ss_report_plot_x(const ss_result *r);

/* The label under the x axis of a column of case kind `kind`, naming what
 * ss_report_plot_x plots there: "k (vertices of the link)" for vertices,
 * "valence n ..." for edges, edge points and surface vertices, "" for the
 * face (its one position is labelled "face").  A constant string. */
const char *ss_report_plot_xlabel(ss_case_kind kind);

/* Plot the rows of rows[0..n) whose identity is o->identity (see
 * ss_report_plot_opts) into the file at path, PNG or SVG by its extension
 * (.png, .svg, any case).  *plotted (may be NULL) receives the number of rows
 * plotted.  No rows: a figure that says so.  rows are not kept.  SS_EINPUT
 * for another extension or a size outside 200..10000; SS_EIO when the file
 * cannot be written (the message names it); SS_ENOMEM. */
ss_status ss_report_plot(const ss_report_row *rows, size_t n,
                         const ss_report_plot_opts *o, const char *path, size_t *plotted,
                         ss_error *err);

SS_END_DECLS

#endif
