/* ss_cli_eigvec.h — writing the leading eigenvectors and limit masks of a
 * local matrix (`analyze --eigenvectors K --format json`, `matrix
 * --eigenvectors K [--left]`; issue 21). */
#ifndef SS_CLI_EIGVEC_H
#define SS_CLI_EIGVEC_H

#include <stdio.h>

#include <json-c/json.h>

#include "ss_eigvec.h"
#include "ss_local.h"

/* A point's exact coordinates relative to the centre, "(0:1 2:-1)", into buf
 * (truncated to n bytes). */
void ss_cli_label_text(const ss_star_coord *c, char *buf, size_t n);

/* The JSON object of analyze's "eigenvectors" key: points (labels), the
 * eigenvalues with their groups, right and left vectors (one array per
 * eigenvalue; "right_im"/"left_im" when one is complex) and "limit_masks":
 * the limit-position mask (left vector of lambda_0) and the tangent masks (left
 * vectors of lambda_1..lambda_dim) when masks_ok (the eigenvalue condition
 * holds and ss_eigvec_has_limit), else null with "limit_masks_reason".
 * NULL on no memory. */
json_object *ss_cli_eigvec_json(const ss_eigvec *v, const ss_local *M, int dim,
                                int masks_ok, const char *why_not);

#endif
