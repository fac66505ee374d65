/* ss_mesh_vtu_read.c — VTK XML unstructured grids (.vtu) read through
 * libxml2 (the XML) and zlib (vtkZLibDataCompressor blocks); Debian
 * libxml2-dev and zlib1g-dev.
 *
 * VTK's own reader (libvtk9-dev) would read every variant, but in Debian 12
 * it brings 208 packages (a JDK, Qt, GDAL, ffmpeg, HDF5 with MPI) into a
 * build that has none of them; the format's container is XML and its binary
 * blocks zlib, so the two libraries that VTK itself uses for them do the
 * work here.  What is ours: the walk over the VTK elements, the block
 * headers, byte order and the base64 of inline binary arrays (libxml2
 * exposes no base64 decoder; a 4-character group decoder, 30 lines).
 *
 * Appended raw data (<AppendedData encoding="raw">_bytes) are not XML: the
 * document is parsed up to that element, closed there, and the bytes after
 * its '_' are read at each array's offset, as VTK's own reader does.
 *
 * Read: one Piece; DataArray formats ascii, binary (base64) and appended
 * (raw or base64), header_type UInt32 or UInt64, either byte order, numeric
 * types Int8..UInt64, Float32, Float64, uncompressed or zlib.  Refused with a
 * message: other compressors (LZ4, LZMA), other dataset types, several
 * pieces.  Without libxml2 (meson -Dvtu=disabled) the reader is a stub. */
#include "ss_mesh.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if SS_HAVE_LIBXML2
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdint.h>
#include <zlib.h>

#include "ss_mesh_vtk_impl.h"
#endif

int ss_mesh_vtu_available(void) {
  return SS_HAVE_LIBXML2;
}

#if !SS_HAVE_LIBXML2

ss_status ss_mesh_read_vtu(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err) {
  (void)names;
  *out = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  fclose(f);
  return ss_error_set(err, SS_EINPUT,
                      "%s: this subspectra was built without libxml2, so .vtu files are "
                      "not read (rebuild with libxml2-dev and zlib1g-dev); it reads %s",
                      path, ss_mesh_readable_list());
}

#else

/* The file and what is known of its layout. */
typedef struct {
  const char *path;         /* for messages */
  const unsigned char *app; /* the appended data after '_', or NULL */
  size_t app_len;           /* its bytes */
  int app_b64;              /* the appended data are base64 */
  int swap;                 /* the file's byte order is not ours */
  int head8;                /* header_type UInt64 (else UInt32) */
  int zlib;                 /* vtkZLibDataCompressor */
  ss_error *err;            /* failures */
} vtu_file;

/* A byte source: raw bytes or base64 text decoded by 4-character groups
 * (padding may end any group, so a header and its data encoded apart read
 * as one stream, as VTK writes them). */
typedef struct {
  const unsigned char *p; /* next unread byte or character */
  const unsigned char *e; /* end */
  int b64;                /* base64 text */
  unsigned char carry[3]; /* decoded bytes not yet taken */
  int ncarry, icarry;     /* how many, the next */
} bsrc;

static int b64val(unsigned char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  return c == '+' ? 62 : c == '/' ? 63 : c == '=' ? 64 : -1;
}

/* n bytes from s into out; -1 if s ends first or holds a bad character. */
static int take(bsrc *s, unsigned char *out, size_t n) {
  if (!s->b64) {
    if ((size_t)(s->e - s->p) < n) return -1;
    memcpy(out, s->p, n);
    s->p += n;
    return 0;
  }
  for (size_t k = 0; k < n;) {
    if (s->icarry < s->ncarry) {
      out[k++] = s->carry[s->icarry++];
      continue;
    }
    int q[4], m = 0;
    while (m < 4) {
      if (s->p == s->e) return -1;
      const unsigned char c = *s->p++;
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
      if ((q[m++] = b64val(c)) < 0) return -1;
    }
    if (q[0] == 64 || q[1] == 64 || (q[2] == 64 && q[3] != 64)) return -1;
    const unsigned v = (unsigned)q[0] << 18 | (unsigned)q[1] << 12 |
                       (unsigned)(q[2] & 63) << 6 | (unsigned)(q[3] & 63);
    s->carry[0] = (unsigned char)(v >> 16);
    s->carry[1] = (unsigned char)(v >> 8);
    s->carry[2] = (unsigned char)v;
    s->ncarry = q[2] == 64 ? 1 : q[3] == 64 ? 2 : 3;
    s->icarry = 0;
  }
  return 0;
}

/* One header integer (UInt32 or UInt64, the file's byte order). */
static int take_head(const vtu_file *f, bsrc *s, uint64_t *v) {
  unsigned char b[8];
  const int n = f->head8 ? 8 : 4;
  if (take(s, b, (size_t)n)) return -1;
  *v = 0;
  for (int i = 0; i < n; i++) /* little-endian value unless swapped */
    *v |= (uint64_t)b[f->swap ? n - 1 - i : i] << (8 * i);
  return 0;
}

/* The element types of DataArray type="...": size and kind (0 signed
 * integer, 1 unsigned, 2 float). */
static int type_of(const char *t, int *size, int *kind) {
  static const struct {
    const char *name;
    int size, kind;
  } types[] = {{"Int8", 1, 0},    {"UInt8", 1, 1},  {"Int16", 2, 0}, {"UInt16", 2, 1},
               {"Int32", 4, 0},   {"UInt32", 4, 1}, {"Int64", 8, 0}, {"UInt64", 8, 1},
               {"Float32", 4, 2}, {"Float64", 8, 2}};
  for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
    if (!strcmp(t, types[i].name)) {
      *size = types[i].size;
      *kind = types[i].kind;
      return 0;
    }
  return -1;
}

/* n values of `size` bytes and kind from raw bytes b (the file's order). */
static void convert(const vtu_file *f, const unsigned char *b, size_t n, int size,
                    int kind, double *out) {
  for (size_t i = 0; i < n; i++) {
    unsigned char e[8];
    for (int k = 0; k < size; k++) /* to our byte order */
      e[k] = b[i * (size_t)size + (size_t)(f->swap ? size - 1 - k : k)];
    if (kind == 2) {
      if (size == 4) {
        float x;
        memcpy(&x, e, 4);
        out[i] = x;
      } else {
        memcpy(&out[i], e, 8);
      }
      continue;
    }
    uint64_t u = 0; /* assemble in our order: memcpy into the right width */
    int64_t s = 0;
    switch (size) {
    case 1:
      u = e[0], s = (int8_t)e[0];
      break;
    case 2: {
      uint16_t v;
      memcpy(&v, e, 2);
      u = v, s = (int16_t)v;
      break;
    }
    case 4: {
      uint32_t v;
      memcpy(&v, e, 4);
      u = v, s = (int32_t)v;
      break;
    }
    default:
      memcpy(&u, e, 8);
      s = (int64_t)u;
    }
    out[i] = kind == 1 ? (double)u : (double)s;
  }
}

/* The bytes of a binary array (header, then data or zlib blocks) from s into
 * a new buffer *buf of exactly want bytes.  SS_EINPUT naming the array. */
static ss_status binary_bytes(const vtu_file *f, bsrc *s, const char *what, size_t want,
                              unsigned char **buf) {
  ss_status st = SS_OK;
  unsigned char *b = malloc(want + 1), *z = NULL;
  uint64_t *cs = NULL;
  if (!b) return ss_error_nomem(f->err, "VTU array");
  if (!f->zlib) {
    uint64_t n = 0;
    if (take_head(f, s, &n) || n != want || take(s, b, want))
      st = ss_error_set(
          f->err, SS_EINPUT, "%s: DataArray %s: %s (%zu bytes expected)", f->path, what,
          n != want ? "the block header gives another length" : "the data end early",
          want);
    goto done;
  }
  uint64_t nb, bs, last;
  if (take_head(f, s, &nb) || take_head(f, s, &bs) || take_head(f, s, &last) ||
      nb > want + 1 || (nb && (bs == 0 || (nb - 1) * bs + (last ? last : bs) != want))) {
    st = ss_error_set(f->err, SS_EINPUT,
                      "%s: DataArray %s: bad compression header (%zu bytes expected)",
                      f->path, what, want);
    goto done;
  }
  if (!(cs = malloc((nb + 1) * sizeof *cs))) {
    st = ss_error_nomem(f->err, "VTU blocks");
    goto done;
  }
  uint64_t zmax = 0;
  for (uint64_t i = 0; i < nb && !st; i++)
    if (take_head(f, s, &cs[i]) || cs[i] > ((uint64_t)1 << 40))
      st = ss_error_set(f->err, SS_EINPUT, "%s: DataArray %s: bad block size", f->path,
                        what);
    else if (cs[i] > zmax)
      zmax = cs[i];
  if (st) goto done;
  if (!(z = malloc(zmax + 1))) {
    st = ss_error_nomem(f->err, "VTU block");
    goto done;
  }
  size_t at = 0;
  for (uint64_t i = 0; i < nb; i++) {
    uLongf got = (uLongf)(i + 1 == nb && last ? last : bs);
    const uLongf full = got;
    if (take(s, z, cs[i]) || uncompress(b + at, &got, z, (uLong)cs[i]) != Z_OK ||
        got != full) {
      st = ss_error_set(f->err, SS_EINPUT,
                        "%s: DataArray %s: zlib block %llu does not inflate to %lu bytes",
                        f->path, what, (unsigned long long)i + 1, (unsigned long)full);
      goto done;
    }
    at += got;
  }
done:
  free(cs);
  free(z);
  if (st)
    free(b);
  else
    *buf = b;
  return st;
}

/* A DataArray node's attribute (libxml2's copy), or NULL. */
static char *attr(xmlNode *n, const char *name) {
  return (char *)xmlGetProp(n, (const xmlChar *)name);
}

/* The n values (tuples times components) of DataArray node d into out. */
static ss_status read_array(const vtu_file *f, xmlNode *d, const char *what, size_t n,
                            int *integer, double *out) {
  ss_status st = SS_OK;
  char *type = attr(d, "type"), *fmt = attr(d, "format"), *off = attr(d, "offset");
  char *text = (char *)xmlNodeGetContent(d);
  unsigned char *bytes = NULL;
  int size, kind;
  if (!type || type_of(type, &size, &kind)) {
    st = ss_error_set(f->err, SS_EINPUT, "%s: DataArray %s: type '%s' is not read",
                      f->path, what, type ? type : "(none)");
    goto done;
  }
  *integer = kind != 2;
  if (!fmt || !strcmp(fmt, "ascii")) {
    char *p = text ? text : (char *)"", *end;
    for (size_t i = 0; i < n; i++, p = end) {
      out[i] = strtod(p, &end);
      if (end == p) {
        st = ss_error_set(f->err, SS_EINPUT,
                          "%s: DataArray %s: %zu values where %zu are needed", f->path,
                          what, i, n);
        goto done;
      }
    }
    goto done;
  }
  bsrc s = {0};
  if (!strcmp(fmt, "binary")) {
    s.p = (const unsigned char *)(text ? text : "");
    s.e = s.p + strlen((const char *)s.p);
    s.b64 = 1;
  } else if (!strcmp(fmt, "appended")) {
    char *end;
    const unsigned long long o = off ? strtoull(off, &end, 10) : 0;
    if (!f->app || !off || *end || o > f->app_len) {
      st = ss_error_set(f->err, SS_EINPUT, "%s: DataArray %s: appended, but %s", f->path,
                        what,
                        f->app ? "its offset is missing or beyond the data"
                               : "there is no AppendedData");
      goto done;
    }
    s.p = f->app + o;
    s.e = f->app + f->app_len;
    s.b64 = f->app_b64;
  } else {
    st = ss_error_set(f->err, SS_EINPUT, "%s: DataArray %s: format '%s' is not read",
                      f->path, what, fmt);
    goto done;
  }
  if (n > SIZE_MAX / 8) {
    st = ss_error_set(f->err, SS_EINPUT, "%s: DataArray %s is too large", f->path, what);
    goto done;
  }
  if (!(st = binary_bytes(f, &s, what, n * (size_t)size, &bytes)))
    convert(f, bytes, n, size, kind, out);
done:
  free(bytes);
  xmlFree(type);
  xmlFree(fmt);
  xmlFree(off);
  xmlFree(text);
  return st;
}

/* The element child of n named name, the k-th (from 0), or NULL. */
static xmlNode *child(xmlNode *n, const char *name, int k) {
  for (xmlNode *c = n ? n->children : NULL; c; c = c->next)
    if (c->type == XML_ELEMENT_NODE && !strcmp((const char *)c->name, name) && k-- == 0)
      return c;
  return NULL;
}

/* An integer attribute of n, >= 0; -1 if missing or malformed. */
static long long count_attr(xmlNode *n, const char *name, long long dflt) {
  char *v = attr(n, name), *end;
  if (!v) return dflt;
  errno = 0;
  const long long k = strtoll(v, &end, 10);
  const int bad = end == v || *end || errno || k < 0;
  xmlFree(v);
  return bad ? -1 : k;
}

/* A newly allocated array of n doubles read from DataArray d. */
static ss_status values(const vtu_file *f, xmlNode *d, const char *what, size_t n,
                        int *integer, double **out) {
  if (!d) return ss_error_set(f->err, SS_EINPUT, "%s: no DataArray %s", f->path, what);
  *out = malloc((n + 1) * sizeof **out);
  if (!*out) return ss_error_nomem(f->err, "VTU array");
  int dummy;
  return read_array(f, d, what, n, integer ? integer : &dummy, *out);
}

/* The DataArray of Cells named name. */
static xmlNode *named(xmlNode *parent, const char *name) {
  for (int k = 0;; k++) {
    xmlNode *d = child(parent, "DataArray", k);
    if (!d) return NULL;
    char *nm = attr(d, "Name");
    const int hit = nm && !strcmp(nm, name);
    xmlFree(nm);
    if (hit) return d;
  }
}

/* Point or cell data (parent PointData/CellData, tuples each) into *list. */
static ss_status read_data(const vtu_file *f, xmlNode *parent, size_t tuples,
                           ss_vtk_array **list, size_t *n) {
  ss_status st = SS_OK;
  xmlNode *d;
  for (int k = 0; !st && (d = child(parent, "DataArray", k)); k++) {
    char *nm = attr(d, "Name");
    const long long nc = count_attr(d, "NumberOfComponents", 1);
    ss_vtk_array *a;
    if (!nm || nc < 1 || nc > SS_MAXDIM)
      st = ss_error_set(f->err, SS_EINPUT, "%s: a %s DataArray %s%s%s has %s", f->path,
                        (const char *)parent->name, nm ? "'" : "", nm ? nm : "",
                        nm ? "'" : "", !nm ? "no Name" : "a bad NumberOfComponents");
    else if (!(st = ss_vtk_array_add(f->path, list, n, nm, (int)nc, &a, f->err)))
      st = values(f, d, nm, tuples * (size_t)nc, &a->integer, &a->val);
    xmlFree(nm);
  }
  return st;
}

/* The Piece's points, cells and data into g. */
static ss_status read_piece(const vtu_file *f, xmlNode *piece, ss_vtk_grid *g) {
  const long long np = count_attr(piece, "NumberOfPoints", -1);
  const long long nc = count_attr(piece, "NumberOfCells", -1);
  if (np < 0 || nc < 0 || np >= (long long)SS_IDX_NONE || nc > (1LL << 40))
    return ss_error_set(f->err, SS_EINPUT,
                        "%s: Piece needs NumberOfPoints and NumberOfCells (counts)",
                        f->path);
  g->np = (size_t)np;
  g->nc = (size_t)nc;
  xmlNode *cells = child(piece, "Cells", 0);
  double *off = NULL, *conn = NULL, *types = NULL;
  ss_status st = values(f, child(child(piece, "Points", 0), "DataArray", 0), "of Points",
                        3 * g->np, NULL, &g->pts);
  if (!st) st = values(f, named(cells, "offsets"), "offsets", g->nc, NULL, &off);
  if (!st) st = values(f, named(cells, "types"), "types", g->nc, NULL, &types);
  double last = 0;
  for (size_t i = 0; !st && i < g->nc; last = off[i++])
    if (off[i] < last || off[i] > 1e12 || off[i] != floor(off[i]))
      st = ss_error_set(f->err, SS_EINPUT,
                        "%s: offsets: cell %zu ends at %g, before the cell before it or "
                        "not a count",
                        f->path, i, off[i]);
  if (!st)
    st = values(f, named(cells, "connectivity"), "connectivity", (size_t)last, NULL,
                &conn);
  if (!st && (!(g->offsets = malloc((g->nc + 1) * sizeof *g->offsets)) ||
              !(g->types = malloc((g->nc + 1) * sizeof *g->types)) ||
              !(g->conn = malloc(((size_t)last + 1) * sizeof *g->conn))))
    st = ss_error_nomem(f->err, "VTU cells");
  for (size_t i = 0; !st && i < g->nc; i++) {
    g->offsets[i] = (int64_t)off[i];
    g->types[i] = types[i] >= 0 && types[i] < 256 ? (int)types[i] : -1;
  }
  for (size_t i = 0; !st && i < (size_t)last; i++)
    g->conn[i] = conn[i] >= -1 && conn[i] < 1e15 ? (int64_t)conn[i] : -1;
  free(off);
  free(conn);
  free(types);
  if (!st) st = read_data(f, child(piece, "PointData", 0), g->np, &g->pdata, &g->npd);
  if (!st) st = read_data(f, child(piece, "CellData", 0), g->nc, &g->cdata, &g->ncd);
  return st;
}

/* The document's root checks, then the piece. */
static ss_status read_doc(vtu_file *f, xmlDoc *doc, ss_vtk_grid *g) {
  xmlNode *root = xmlDocGetRootElement(doc);
  if (!root || strcmp((const char *)root->name, "VTKFile"))
    return ss_error_set(f->err, SS_EINPUT, "%s: not a VTK XML file (no VTKFile element)",
                        f->path);
  char *type = attr(root, "type"), *order = attr(root, "byte_order"),
       *head = attr(root, "header_type"), *comp = attr(root, "compressor");
  const uint16_t one = 1;
  const int little = *(const unsigned char *)&one == 1;
  ss_status st = SS_OK;
  if (!type || strcmp(type, "UnstructuredGrid"))
    st = ss_error_set(f->err, SS_EINPUT,
                      "%s: VTKFile type '%s' is not read (UnstructuredGrid is)", f->path,
                      type ? type : "(none)");
  else if (head && strcmp(head, "UInt32") && strcmp(head, "UInt64"))
    st = ss_error_set(f->err, SS_EINPUT, "%s: header_type '%s' is not UInt32 or UInt64",
                      f->path, head);
  else if (comp && strcmp(comp, "vtkZLibDataCompressor"))
    st = ss_error_set(f->err, SS_EINPUT,
                      "%s: compressor %s is not read (vtkZLibDataCompressor is, or none)",
                      f->path, comp);
  f->swap = order && !strcmp(order, little ? "BigEndian" : "LittleEndian");
  f->head8 = head && !strcmp(head, "UInt64");
  f->zlib = comp != NULL;
  xmlFree(type);
  xmlFree(order);
  xmlFree(head);
  xmlFree(comp);
  if (st) return st;
  xmlNode *grid = child(root, "UnstructuredGrid", 0), *piece = child(grid, "Piece", 0);
  if (!piece)
    return ss_error_set(f->err, SS_EINPUT, "%s: no UnstructuredGrid Piece", f->path);
  if (child(grid, "Piece", 1))
    return ss_error_set(f->err, SS_EINPUT,
                        "%s: several Pieces; one is read (merge them first)", f->path);
  return read_piece(f, piece, g);
}

/* Cut the appended data out of the text buf[0..*len): f->app points at the
 * bytes after '_', and the text is closed after <AppendedData ...> so that
 * libxml2 parses XML only. */
static void cut_appended(vtu_file *f, char *buf, size_t *len) {
  char *a = NULL;
  for (char *p = buf; p + 13 <= buf + *len; p++)
    if (!memcmp(p, "<AppendedData", 13)) {
      a = p;
      break;
    }
  if (!a) return;
  char *gt = memchr(a, '>', (size_t)(buf + *len - a));
  if (!gt) return;
  char *u = memchr(gt, '_', (size_t)(buf + *len - gt));
  if (!u) return;
  *gt = '\0';
  f->app_b64 = strstr(a, "base64") != NULL;
  *gt = '>';
  f->app = (const unsigned char *)u + 1;
  f->app_len = (size_t)(buf + *len - (u + 1));
  *len = (size_t)(gt + 1 - buf); /* the XML: up to <AppendedData ...> */
}

ss_status ss_mesh_read_vtu(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err) {
  *out = NULL;
  char *buf = NULL, *xml = NULL;
  size_t len = 0;
  ss_status st = ss_vtk_slurp(path, &buf, &len, err);
  if (st) return st;
  vtu_file f = {.path = path, .err = err};
  cut_appended(&f, buf, &len);
  static const char close[] = "</AppendedData></VTKFile>";
  ss_vtk_grid g;
  memset(&g, 0, sizeof g);
  xmlDoc *doc = NULL;
  if (!(xml = malloc(len + sizeof close))) {
    st = ss_error_nomem(err, "VTU text");
    goto done;
  }
  memcpy(xml, buf, len);
  if (f.app) memcpy(xml + len, close, sizeof close - 1);
  const size_t xlen = len + (f.app ? sizeof close - 1 : 0);
  doc = xmlReadMemory(xml, (int)xlen, path, NULL,
                      XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING |
                          XML_PARSE_HUGE);
  if (!doc) {
    const xmlError *e = xmlGetLastError();
    const char *m = e && e->message ? e->message : "libxml2 failed";
    st = ss_error_set(err, SS_EINPUT, "%s:%d: not well-formed XML: %.*s", path,
                      e ? e->line : 0, (int)strcspn(m, "\n"), m);
    goto done;
  }
  if (!(st = read_doc(&f, doc, &g))) st = ss_vtk_build(path, &g, out, names, err);
done:
  ss_vtk_grid_done(&g);
  xmlFreeDoc(doc);
  free(xml);
  free(buf);
  return st;
}

#endif
