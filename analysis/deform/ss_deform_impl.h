/* ss_deform_impl.h — the reference shapes' tables, shared by the files of
 * analysis/deform/ (not installed). */
#ifndef SS_DEFORM_IMPL_H
#define SS_DEFORM_IMPL_H

#include "ss_deform.h"

/* Reference point of corner k of a cell of type t (ss_deform.h). */
void ss_deform_ref_corner(ss_cell_type t, int k, double p[3]);
/* The interpolant's weights of the corners at parameters r (8 entries; the
 * unused ones 0). */
void ss_deform_weights(ss_cell_type t, const double r[3], double w[8]);
/* How far r lies outside the reference shape (<= 0 inside), in parameters. */
double ss_deform_violation(ss_cell_type t, const double r[3]);
/* r moved onto the reference shape (for points within the tolerance). */
void ss_deform_clamp(ss_cell_type t, double r[3]);
/* Solve m x = b (3x3, m[row][col]); 0 if singular. */
int ss_deform_solve3(const double m[3][3], const double b[3], double x[3]);

#endif
