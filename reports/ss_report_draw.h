/* ss_report_draw.h — pictures of a characteristic map's two-ring (issue 5):
 * raster (PNG) and vector (SVG, PDF) drawings through cairo, and legacy VTK
 * for ParaView.  In vector pictures the text is text: PDF embeds the font
 * subset (selectable, searchable), SVG gets <text> elements (ss_report_text;
 * cairo itself would draw SVG glyphs as outlines).
 *
 * The frame.  The control net is normalised (ss_charmap.h), which fixes it up
 * to an orthogonal map when the subdominant eigenvalues tie and the basis is
 * arbitrary; the pictures fix that too, so that the same case gives the same
 * picture whatever LAPACK's basis: psi(p) is moved to the origin and the
 * net expressed in the orthonormal frame e1, e2, e3 = e1 x e2, where e1 points
 * to the first two-ring point (in the order of the exact labels) not at
 * psi(p), and e2 is the next point not parallel to e1, made orthogonal to it
 * (surfaces: e1 and its right-handed normal).  Only a mirror image in z3
 * remains (an orientation-reversing basis).  VTK keeps the normalised net.
 *
 * A drawing has two panels side by side:
 *   left   the two-ring's cells in 3D projection (orthographic, from the
 *          direction given by azimuth and elevation), faces painted back to
 *          front with depth cues (faces further away lighter and greyer, shading
 *          by the angle to the viewer), cell edges drawn, the one-ring's cells
 *          emphasised, and cells that are not regular (ss_jac verdict folded,
 *          undecided, or of the minority sign) filled in a warning colour
 *          (red; undecided orange); the centre p (point 0, at the origin of
 *          the map) marked;
 *   right  the planar cross-section of the control net through psi(p) by
 *          the plane z3 = 0 (the cells' edges cut by the plane, each cut cell
 *          as a polygon, warning colours as on the left), with axes z1, z2
 *          and ticks.
 * Surface cases (dim 2) are drawn in one panel, flat, as the planar map, with
 * axes.  The 3D panel shows the frame's axes as a small triad.  A colour
 * legend names the cell colours.  A caption (when o->caption is set) states
 * the case, lambda1..m, the verdict and the minimum scaled Jacobian; without
 * one (NULL) the picture has no text besides axes, legend and panel titles,
 * for a report that captions it itself.
 *
 * VTK: an UNSTRUCTURED_GRID (ASCII, legacy format 3.0) with the points
 * (z1, z2, z3; surfaces with z3 = 0) and cells (hexes, tets, octahedra as two
 * VTK_PYRAMIDs on their equator, quads, triangles; vertex order of ss_cx.h)
 * of two parts: the two-ring's cells, and after them the cells of the ring
 * level that decided the verdict (ss_charmap.h: the cells analyze judges),
 * with their own points.  The numbers are analyze's, in the map's
 * orientation (analyze orients the map as a whole; a map whose cells are
 * all negatively oriented is regular, and its cells are shown +1):
 *   FIELD FieldData  "min_scaled_jacobian" (double: analyze's
 *                    regularity.min_scaled_jacobian, 0 without one),
 *                    "orientation" (int: +1 or -1, analyze's, 0 none),
 *                    "ring_level" (int: the deciding level, -1 none);
 *   CELL_DATA        "jacobian_sign" (int: 1 of the map's orientation, -1
 *                    inverted against it, 0 folded, 2 undecided, 3 flat),
 *                    "min_scaled_jacobian" (double: ss_charmap_cell_measure,
 *                    whose minimum over the part-2 cells is the field's
 *                    value), "part" (int: 0 two-ring cell around p, whose
 *                    folds decide nothing; 1 other two-ring cell; 2 cell of
 *                    the deciding ring level);
 *   POINT_DATA       "one_ring" (int 0/1). */
#ifndef SS_REPORT_DRAW_H
#define SS_REPORT_DRAW_H

#include <cairo.h>

#include "ss_api.h"
#include "ss_charmap.h"
#include "ss_outfile.h"

SS_BEGIN_DECLS

/* How to draw. */
typedef struct {
  int width, height;   /* picture size in pixels (PNG) or points (SVG) */
  double azimuth;      /* view direction: degrees about the z3 axis */
  double elevation;    /* view direction: degrees above the z1-z2 plane */
  const char *caption; /* first caption line (the case); NULL: no caption at all */
} ss_report_draw_opts;

/* Defaults: 1200 x 600, azimuth 30, elevation 25, no caption. */
ss_report_draw_opts ss_report_draw_defaults(void);

/* Draw cm (judged by ss_charmap_regularity, verdict r) into the file at path;
 * the format follows the extension: .png, .svg, .pdf or .vtk.  The file is written
 * whole or not at all (ss_outfile.h).  SS_EINPUT for another extension or bad
 * options, SS_EIO when the file cannot be written (message names the file),
 * SS_ENOMEM. */
ss_status ss_report_draw(const ss_charmap *cm, const ss_regularity *r,
                         const ss_report_draw_opts *o, const char *path, ss_error *err);

/* The net as the pictures show it (the frame above): x (cm->n * cm->dim
 * doubles, caller's) receives cm's points with psi(p) at the origin in the
 * frame e1, e2 (, e3), coordinates within 1e-12 of the net's size snapped to
 * 0; a net spanning fewer directions than its dimension is copied as it is.
 * The same for any orthogonal change of cm's basis, up to the sign of z3. */
void ss_report_draw_frame(const ss_charmap *cm, double *x);

/* 1 if path ends in ext (lower case, with the dot), ignoring case. */
int ss_report_has_ext(const char *path, const char *ext);

/* Picture formats of ss_report_canvas. */
typedef enum { SS_PIC_PNG = 0, SS_PIC_SVG, SS_PIC_PDF } ss_pic_format;

/* The picture format of path by its extension (.png, .svg, .pdf, any case)
 * into *fmt; -1 for another extension. */
int ss_report_pic_format(const char *path, ss_pic_format *fmt);

/* A growing byte buffer. */
typedef struct {
  char *s;       /* the bytes (not NUL-terminated) */
  size_t n, cap; /* used and allocated lengths */
} ss_report_bytes;

/* A picture being drawn into a file (shared by the pictures and the plots):
 * the file is written whole or not at all (ss_outfile.h). */
typedef struct {
  cairo_t *cr;          /* the context to draw with */
  cairo_surface_t *s;   /* an image surface (PNG), or an SVG or PDF surface
                           streaming to out (SVG: to svg first) */
  ss_outfile *out;      /* the temporary file beside the target, renamed on success */
  ss_pic_format fmt;    /* PNG, SVG or PDF */
  int werrno;           /* errno of the first failed write into out, 0 if none */
  int nomem;            /* 1 if a buffer below could not grow */
  ss_report_bytes svg;  /* SVG: cairo's document, held until the text is added */
  ss_report_bytes text; /* SVG: the <text> elements (ss_report_text) */
} ss_report_canvas;

/* Show s at the current point in the current font size and colour, as
 * cairo_show_text does; in an SVG canvas as a <text> element (x, y, size and
 * fill in device units; no rotated text is drawn here), so that the text is
 * text.  cr must come from ss_report_cairo_open. */
void ss_report_text(cairo_t *cr, const char *s);

/* Open a picture of width x height pixels (points for SVG and PDF) into *c:
 * the temporary file beside path, an image surface for PNG (written by
 * ss_report_cairo_close), a PDF surface streaming into the file or an SVG
 * surface into memory (written with its text on closing), and a context on
 * it.  c must
 * stay at its address until closed (the SVG stream writes through it).
 * SS_EIO naming path if the file or the surface cannot be made (nothing is
 * then left to close). */
ss_status ss_report_cairo_open(const char *path, ss_pic_format fmt, int width, int height,
                               ss_report_canvas *c, ss_error *err);

/* Close a picture opened by ss_report_cairo_open: check the context's status,
 * write a PNG surface into the file (an SVG surface writes as it goes and
 * ends when finished), finish and destroy both, then rename the file over
 * its target -- or, on any failure, remove it and leave the target as it
 * was.  st is the status so far (not SS_OK: the drawing is abandoned);
 * returns the first failure (SS_EIO naming the target). */
ss_status ss_report_cairo_close(ss_report_canvas *c, ss_status st, ss_error *err);

SS_END_DECLS

#endif
