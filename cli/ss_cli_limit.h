/* ss_cli_limit.h — the interface of `subspectra limit`'s files, private to
 * the command-line tool.  ss_cli_limit.c parses the command line, makes the
 * points and evaluates them, each with its status; ss_cli_limit_write.c
 * writes them as text, JSON, legacy VTK or VTU (which merges the samples that
 * neighbouring cells share).
 *
 * A batch never stops at a point that cannot be evaluated: every point is
 * written with its status (the vocabulary below), its missing values NaN
 * (null in JSON), and the command exits 1 after writing.  A run in which
 * every point is evaluated writes exactly what it wrote before statuses
 * existed: no status column, key or array (VTU, new, always has its status
 * array). */
#ifndef SS_CLI_LIMIT_H
#define SS_CLI_LIMIT_H

#include <stdio.h>

#include "ss_cx.h"
#include "ss_limit.h"
#include "ss_mesh.h"

/* A point's status: its code in VTK/VTU point data; its name in text and
 * JSON (ss_cli_limit_status_name). */
typedef enum {
  SS_LIMIT_CLI_OK = 0,             /* evaluated: the point (and Jacobian) */
  SS_LIMIT_CLI_NO_DERIVATIVES = 1, /* the point and field values, but not the
                                     Jacobian or field gradients asked for:
                                     unbounded or undefined there */
  SS_LIMIT_CLI_FAILED = 2,         /* numerical failure: no value */
  SS_LIMIT_CLI_REFUSED = 3,        /* not a point of the mesh's limit the
                                     evaluator takes (unknown cell, parameter
                                     outside [0,1] or not a number, a cell whose
                                     patch is not supported): no value */
  SS_LIMIT_CLI_NSTATUS = 4         /* number of statuses; not a status */
} ss_limit_cli_status;

/* One point to evaluate and its result. */
typedef struct {
  size_t cell;      /* 0-based */
  double x[3];      /* parameters */
  double weight;    /* Gauss weight on [0,1]^3, or 0 */
  ss_limit_point r; /* result (NaN where there is none) */
  double *f;        /* the fields' values (nf; in fields.val), or NULL */
  double (*df)[3];  /* their derivatives d/dU, d/dV, d/dW (nf rows), or NULL */
  int status;       /* an ss_limit_cli_status */
  char *why;        /* the evaluator's reason when status != OK (owned), or NULL */
} ss_limit_cli_point;

/* The mesh's fields: its coordinates past the third. */
typedef struct {
  size_t nf;                               /* how many (0..SS_MAXDIM - 3) */
  char name[SS_MAXDIM][SS_FIELD_NAME_MAX]; /* their names (ss_mesh_fields: the
                                              file's, a Medit 4th coordinate
                                              is "w") */
  double *val;                             /* npts * nf values (owned) */
  double (*grad)[3];                       /* npts * nf derivatives (owned) */
} ss_limit_cli_fields;

/* What a writer writes: the points and how they were made. */
typedef struct {
  const ss_limit_cli_point *pts; /* the points, in order */
  size_t n;                      /* how many */
  int samples;                   /* --samples N (points cell by cell, i fastest), or 0 */
  int derivs;                    /* --derivatives */
  int with_status;               /* some point failed: write statuses (text, JSON, VTK) */
  const ss_limit_cli_fields *fl; /* the fields */
  const ss_cx *mesh;             /* the hexahedra (VTU's merge of shared samples) */
} ss_limit_cli_out;

/* "ok", "no_derivatives", "failed", "refused". */
const char *ss_cli_limit_status_name(int status);

/* Text: CELL U V W X Y Z [9 Jacobian entries] [fields] [field gradients]
 * [status], NaN written "nan". */
void ss_cli_limit_write_text(FILE *f, const ss_limit_cli_out *o);

/* JSON lines: one object per point, null where there is no value. */
void ss_cli_limit_write_json(FILE *f, const ss_limit_cli_out *o);

/* Legacy VTK: with samples >= 2 the sampled volume as hexahedra (every
 * cell's own points), else vertex cells. */
void ss_cli_limit_write_vtk(FILE *f, const ss_limit_cli_out *o);

/* VTU (VTK XML, ASCII): as legacy VTK, but a sample that neighbouring cells
 * share is one point, and the point data always hold status and, with
 * derivatives, the Jacobian as a 9-component tensor.  SS_ENOMEM. */
ss_status ss_cli_limit_write_vtu(FILE *f, const ss_limit_cli_out *o, ss_error *err);

#endif
