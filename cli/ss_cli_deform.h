/* ss_cli_deform.h — the interface of `subspectra deform`'s files, private to
 * the command-line tool.  ss_cli_deform.c parses the command line, makes and
 * embeds the points, moves the control net and evaluates; ss_cli_deform_write.c
 * writes the result as text, JSON, legacy VTK, VTU or PNG. */
#ifndef SS_CLI_DEFORM_H
#define SS_CLI_DEFORM_H

#include <stdio.h>

#include "ss_cx.h"
#include "ss_deform.h"

/* A point's status: its code in VTK/VTU point data, its name in text and JSON
 * (ss_cli_deform_status_name). */
typedef enum {
  SS_DEFORM_CLI_OK = 0,      /* embedded and evaluated */
  SS_DEFORM_CLI_OUTSIDE = 1, /* in no cell of the base mesh: no value */
  SS_DEFORM_CLI_FAILED = 2   /* embedded, but the evaluator refused it: no value */
} ss_deform_cli_status;

/* One pattern point and its images. */
typedef struct {
  double x[3];       /* the point as given (base mesh's space) */
  int status;        /* an ss_deform_cli_status */
  ss_deform_loc loc; /* its cell and parameters (status != OUTSIDE) */
  double base[3];    /* its image under the base mesh's limit (NaN if none) */
  double p[3];       /* its image under the moved mesh's limit (NaN if none) */
  double est;        /* levels path: the error estimate of p; NaN on the exact path */
  double rate;       /* levels path: the contraction the estimate used; NaN otherwise */
  int label;         /* checker: the square's colour 0/1; -1 otherwise */
  long line;         /* grid: the grid line it samples (0-based); -1 otherwise */
} ss_deform_cli_point;

/* What a writer writes. */
typedef struct {
  const ss_deform_cli_point *pt; /* the points in order */
  size_t n;                      /* how many */
  int exact;                     /* 1: the exact limit; 0: `levels` levels */
  int levels;                    /* levels of subdivision (0 on the exact path) */
  const char *scheme;            /* the scheme's name */
  const ss_cx *net;              /* the moved control net (drawn in the PNG) */
} ss_deform_cli_out;

/* Formats of --format. */
enum {
  SS_DEFORM_FMT_TEXT,
  SS_DEFORM_FMT_JSON,
  SS_DEFORM_FMT_VTK,
  SS_DEFORM_FMT_VTU,
  SS_DEFORM_FMT_PNG
};

/* "ok", "outside", "failed". */
const char *ss_cli_deform_status_name(int status);
/* Write o to f in a text format (text, json, vtk, vtu).  SS_ENOMEM. */
ss_status ss_cli_deform_write_text(FILE *f, const ss_deform_cli_out *o, int format,
                                   ss_error *err);
/* Draw o as a PNG (cairo) on f: the deformed pattern in a fixed oblique
 * projection over the moved net's edges.  SS_EIO or SS_ENOMEM. */
ss_status ss_cli_deform_write_png(FILE *f, const ss_deform_cli_out *o, ss_error *err);

#endif
