/* ss_mesh_gmsh.c — gmsh .msh files (versions 2 and 4, ASCII and binary), read
 * through gmsh's own C API (gmshc.h, Debian libgmsh-dev) rather than a parser
 * of our own: gmsh knows every variant of its format.
 *
 * gmsh's API is one global model behind global state, and not thread-safe,
 * so every read holds one process-wide mutex from gmshInitialize to
 * gmshFinalize (the only mutable static in the library, there because gmsh's
 * own state is static).  Initialising per read and finalising after it leaves
 * nothing behind between reads.  gmsh 4.8 crashes (SIGSEGV) on some
 * malformed binary files, so it reads in a child process (fork) that sends
 * the complex back through a pipe: a crash is a message, not the caller's
 * death.  gmsh turns its terminal output on when
 * initialised (General.Terminal 1): it is switched off at once, with
 * General.Verbosity 0, so a library read prints nothing; errors arrive as
 * ierr, their text from gmshLoggerGetLastError.  gmshInitialize also sets
 * the process locale (setlocale(LC_ALL, "")): the caller's is restored.
 *
 * libgmsh is not linked: it is opened with dlopen in that child, when a
 * .msh is read.  Linked, its ~90 shared libraries (OpenCASCADE, FLTK, X11…)
 * and their relocations and constructors cost every start of the program
 * ~60 ms of CPU, even `subspectra --version`, and every program or Python
 * process that loads libsubspectra; opened in the child they cost only the
 * reads of .msh files, and the parent's address space never holds them.
 *
 * Without gmsh (meson -Dgmsh=disabled, or libgmsh-dev missing) the reader
 * is a stub that refuses .msh with a message saying how to convert. */
#include "ss_mesh.h"

#include <errno.h>
#include <string.h>

#if SS_HAVE_GMSH
#include "ss_mesh_gmsh_api.h"
#include "ss_mesh_gmsh_scan.h"

#include <gmshc.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

/* Version 4.0 ("4", "4.0"; gmsh reads every version below 4.1 that way):
 * gmsh's reader would take it, but its entity blocks are laid out otherwise
 * than 4.1's and the scan (ss_mesh_gmsh_scan.c) does not check them, so a
 * file that lies about its blocks would lose cells; refused, saying how to
 * convert. */
static int is_v40(const char *ver) {
  char *end;
  const double v = strtod(ver, &end);
  return end != ver && !*end && v >= 4 && v < 4.05;
}

/* The first two lines of a .msh file: "$MeshFormat" and "version type size".
 * gmsh decides by content, not by extension, and runs any file that is not a
 * mesh as a .geo script (which can run shell commands: System "..."), so only
 * files that begin as a version 2 or 4 mesh are handed to it. */
static ss_status check_header(const char *path, ss_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  char line[128] = "", ver[128] = "";
  int type = -1, size = -1;
  const int got = fgets(line, sizeof line, f) != NULL;
  line[strcspn(line, "\r\n")] = '\0';
  ss_status st = SS_OK;
  if (!got || strcmp(line, "$MeshFormat"))
    st = ss_error_set(err, SS_EINPUT,
                      "%s:1: not a gmsh mesh: '$MeshFormat' expected on the first line",
                      path);
  else if (!fgets(line, sizeof line, f) ||
           sscanf(line, "%127s %d %d", ver, &type, &size) != 3 ||
           (type != 0 && type != 1))
    st = ss_error_set(err, SS_EINPUT,
                      "%s:2: malformed $MeshFormat: 'VERSION 0|1 DATA-SIZE' expected",
                      path);
  else if (is_v40(ver))
    st = ss_error_set(
        err, SS_EINPUT,
        "%s:2: MSH 4.0 is not supported; re-save as 4.1 (gmsh -format msh41) "
        "or 2.2",
        path);
  else if (strncmp(ver, "2.", 2) && strncmp(ver, "4.", 2))
    st = ss_error_set(err, SS_EINPUT,
                      "%s:2: MSH version %.20s is not read (versions 2 and 4 are; "
                      "`gmsh %s -0 -format msh41 -o NEW.msh` converts)",
                      path, ver, path);
  fclose(f);
  return st;
}

#if !SS_HAVE_GMSH

ss_status ss_mesh_read_gmsh(const char *path, ss_cx **out, ss_error *err) {
  *out = NULL;
  ss_status st = check_header(path, err);
  if (st == SS_EIO) return st;
  return ss_error_set(err, SS_EINPUT,
                      "%s: this subspectra was built without gmsh, so .msh files are "
                      "not read (rebuild with libgmsh-dev and -Dgmsh=enabled, or "
                      "convert: `gmsh %s -0 -o MESH.mesh`); it reads %s",
                      path, path, ss_mesh_readable_list());
}

ss_status ss_mesh_read_gmsh_fields(const char *path, ss_cx **out, ss_mesh_fields *names,
                                   ss_error *err) {
  if (names) memset(names, 0, sizeof *names);
  return ss_mesh_read_gmsh(path, out, err);
}

#else

typedef ss_gmsh_api gmsh_api;

static int cmp_size(const void *a, const void *b) {
  const size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return x < y ? -1 : x > y;
}

/* One element, gathered before the cells are added so that cells of a type
 * keep the file's order (by element tag) whatever entities they sit on. */
typedef struct {
  size_t tag;                /* gmsh element tag */
  int32_t ref;               /* reference: physical group, else entity tag */
  ss_idx v[SS_MAXCELLVERTS]; /* vertex indices */
} elem;

static int cmp_elem(const void *a, const void *b) {
  const elem *x = a, *y = b;
  return x->tag < y->tag ? -1 : x->tag > y->tag;
}

/* The nodes' tags, ascending: vertex k is the node of tag sorted[k]. */
typedef struct {
  size_t *sorted; /* n tags (owned) */
  size_t n;       /* nodes */
} node_tags;

/* The elements gathered so far, per cell type. */
typedef struct {
  elem *el[SS_NCELLTYPES];   /* the elements of each type (owned) */
  size_t n[SS_NCELLTYPES];   /* how many */
  size_t cap[SS_NCELLTYPES]; /* room in el[t] */
} elem_lists;

/* The nodes of the model gmsh holds as the vertices of a new complex *out:
 * vertex k is the node of the k-th smallest tag (the tags into nd); 2
 * coordinates when the model has no 3D element and every z is 0, else 3. */
static ss_status read_nodes(const gmsh_api *g, const char *path, node_tags *nd,
                            ss_cx **out, ss_error *err) {
  ss_status st = SS_OK;
  int ierr = 0;
  size_t *ntag = NULL, nn = 0, ncoord = 0, npar = 0;
  double *coord = NULL, *par = NULL;
  size_t *order = NULL, *sorted = NULL;
  ss_cx *cx = NULL;

  g->gmshModelMeshGetNodes(&ntag, &nn, &coord, &ncoord, &par, &npar, -1, -1, 0, 0, &ierr);
  if (ierr || ncoord != 3 * nn) {
    st = ss_error_set(err, SS_EINPUT, "%s: gmsh read no nodes", path);
    goto done;
  }
  if (nn == 0) {
    st = ss_error_set(err, SS_EINPUT, "%s: no nodes: an empty mesh", path);
    goto done;
  }
  if (nn >= SS_IDX_NONE) {
    st = ss_error_set(err, SS_EINPUT, "%s: %zu nodes, more than a complex holds", path,
                      nn);
    goto done;
  }
  /* vertex k is the node of the k-th smallest tag */
  order = malloc(nn * sizeof *order);
  sorted = malloc(nn * sizeof *sorted);
  if (!order || !sorted) {
    st = ss_error_nomem(err, "gmsh nodes");
    goto done;
  }
  memcpy(sorted, ntag, nn * sizeof *sorted);
  qsort(sorted, nn, sizeof *sorted, cmp_size);
  for (size_t i = 1; i < nn; i++)
    if (sorted[i] == sorted[i - 1]) {
      st =
          ss_error_set(err, SS_EINPUT, "%s: node tag %zu appears twice", path, sorted[i]);
      goto done;
    }
  for (size_t i = 0; i < nn; i++) {
    const size_t *k = bsearch(ntag + i, sorted, nn, sizeof *sorted, cmp_size);
    order[k - sorted] = i;
  }
  const int mdim = g->gmshModelGetDimension(&ierr);
  int dim = 3;
  if (mdim <= 2) {
    dim = 2;
    for (size_t i = 0; i < nn && dim == 2; i++)
      if (coord[3 * i + 2] != 0.0) dim = 3;
  }
  if ((st = ss_cx_new(dim, &cx, err)) || (st = ss_cx_reserve_vertices(cx, nn, err)))
    goto done;
  for (size_t k = 0; k < nn; k++)
    if ((st = ss_cx_add_vertex(cx, coord + 3 * order[k], 0, err))) goto done;
  *nd = (node_tags){sorted, nn};
  sorted = NULL;
  *out = cx;
  cx = NULL;
done:
  g->gmshFree(ntag);
  g->gmshFree(coord);
  g->gmshFree(par);
  free(order);
  free(sorted);
  ss_cx_free(cx);
  return st;
}

/* The node field of view `tag` (its first step, nc components per node) as
 * coordinates appended to those of cx's vertices (nd: their tags): *out a
 * new complex of max(3, dim) + nc coordinates (z = 0 for a plane), vertices
 * only.  SS_EINPUT for a node without a value or a value that is not
 * finite; SS_ENOMEM. */
static ss_status field_complex(const char *path, const node_tags *nd, const ss_cx *cx,
                               const size_t *tags, size_t ntags, const double *data,
                               int nc, ss_cx **out, ss_error *err) {
  ss_status st = SS_OK;
  ss_cx *f = NULL;
  const size_t n = (size_t)nc;
  double *w = malloc((cx->nv * n + 1) * sizeof *w);
  if (!w) return ss_error_nomem(err, "gmsh node field");
  for (size_t v = 0; v < cx->nv * n; v++)
    w[v] = NAN;
  for (size_t i = 0; i < ntags; i++) {
    const size_t *k = bsearch(tags + i, nd->sorted, nd->n, sizeof *nd->sorted, cmp_size);
    if (!k) continue; /* a node no element uses (version 2 drops it) */
    for (size_t c = 0; c < n; c++) {
      if (!isfinite(data[i * n + c])) {
        st = ss_error_set(
            err, SS_EINPUT,
            "%s: $NodeData: the value of node %zu is %g, not a finite number", path,
            tags[i], data[i * n + c]);
        goto done;
      }
      w[(size_t)(k - nd->sorted) * n + c] = data[i * n + c];
    }
  }
  for (size_t v = 0; v < cx->nv; v++)
    if (isnan(w[v * n])) {
      st = ss_error_set(err, SS_EINPUT,
                        "%s: $NodeData gives node %zu no value (a field needs one per "
                        "node)",
                        path, nd->sorted[v]);
      goto done;
    }
  const int d0 = cx->dim < 3 ? 3 : cx->dim;
  if (d0 + nc > SS_MAXDIM) {
    st = ss_error_set(
        err, SS_EINPUT,
        "%s: the $NodeData views have more than %d components in all; a mesh "
        "carries at most %d fields",
        path, SS_MAXDIM - 3, SS_MAXDIM - 3);
    goto done;
  }
  if ((st = ss_cx_new(d0 + nc, &f, err)) || (st = ss_cx_reserve_vertices(f, cx->nv, err)))
    goto done;
  for (size_t v = 0; v < cx->nv; v++) {
    double x[SS_MAXDIM] = {0};
    for (int d = 0; d < cx->dim; d++)
      x[d] = cx->x[v * (size_t)cx->dim + (size_t)d];
    for (size_t c = 0; c < n; c++)
      x[(size_t)d0 + c] = w[v * n + c];
    if ((st = ss_cx_add_vertex(f, x, cx->vref[v], err))) goto done;
  }
done:
  free(w);
  if (st)
    ss_cx_free(f);
  else
    *out = f;
  return st;
}

/* The name of view `tag` into names->name[k] (and k + 1, k + 2 with the
 * suffixes _x, _y, _z for a vector). */
static void view_name(const gmsh_api *g, int tag, int nc, ss_mesh_fields *names, int k) {
  int ierr = 0;
  const int idx = g->gmshViewGetIndex(tag, &ierr);
  char opt[64], *name = NULL;
  snprintf(opt, sizeof opt, "View[%d].Name", idx);
  if (!ierr) g->gmshOptionGetString(opt, &name, &ierr);
  const char *nm = !ierr && name && *name ? name : "field";
  for (int c = 0; c < nc; c++)
    if (nc == 1)
      snprintf(names->name[k + c], SS_FIELD_NAME_MAX, "%.48s", nm);
    else
      snprintf(names->name[k + c], SS_FIELD_NAME_MAX, "%.48s_%c", nm, "xyz"[c]);
  g->gmshFree(name);
}

/* Fields per node: gmsh makes each $NodeData section (by name) a view.
 * Each view of node data with 1 or 3 components (a scalar, a vector), its
 * first step, becomes coordinates appended to the vertices in *cx (replaced),
 * in the order of gmsh's views: a scalar alone is a 4th coordinate as in a
 * Medit "Dimension 4"; names->name the views' names (a vector's NAME_x, _y,
 * _z).  Views of element data or of tensors are not read.  SS_EINPUT as
 * field_complex; SS_ENOMEM. */
static ss_status read_field(const gmsh_api *g, const char *path, const node_tags *nd,
                            ss_cx **cx, ss_mesh_fields *names, ss_error *err) {
  ss_status st = SS_OK;
  int *vt = NULL, ierr = 0;
  size_t nvt = 0;
  names->n = 0;
  g->gmshViewGetTags(&vt, &nvt, &ierr);
  if (ierr)
    return ss_error_set(err, SS_EINPUT, "%s: gmsh could not list its views", path);
  for (size_t i = 0; i < nvt && !st; i++) {
    char *type = NULL;
    size_t *tags = NULL, ntags = 0, ndata = 0;
    double *data = NULL, time = 0.0;
    int ncomp = 0;
    g->gmshViewGetHomogeneousModelData(vt[i], 0, &type, &tags, &ntags, &data, &ndata,
                                       &time, &ncomp, &ierr);
    if (!ierr && type && !strcmp(type, "NodeData") && (ncomp == 1 || ncomp == 3) &&
        ndata == ntags * (size_t)ncomp) {
      ss_cx *f = NULL;
      if (!(st = field_complex(path, nd, *cx, tags, ntags, data, ncomp, &f, err))) {
        ss_cx_free(*cx);
        *cx = f;
        view_name(g, vt[i], ncomp, names, names->n);
        names->n += ncomp;
      }
    }
    g->gmshFree(type);
    g->gmshFree(tags);
    g->gmshFree(data);
  }
  g->gmshFree(vt);
  return st;
}

/* gmsh's element block of one type, `type`, on one entity: count elements,
 * tags[i] and their nodes nodes[i * nv ..], nnodes in all; into es with
 * reference ref, their nodes as vertex indices (nd).  SS_EINPUT for a type
 * that has no cell here, a block whose node count does not match, or a node
 * that is not in the file; SS_ENOMEM. */
static ss_status add_block(const gmsh_api *g, const char *path, int type, size_t count,
                           const size_t *tags, size_t nnodes, const size_t *nodes,
                           int32_t ref, const node_tags *nd, elem_lists *es,
                           ss_error *err) {
  ss_status st = SS_OK;
  ss_cell_type ct;
  if (!ss_mesh_gmsh_cell_type(type, &ct)) { /* the scan refused these */
    char *name = NULL;
    int edim, order_, nnod, nprim, ierr2 = 0;
    double *lc = NULL;
    size_t nlc = 0;
    g->gmshModelMeshGetElementProperties(type, &name, &edim, &order_, &nnod, &lc, &nlc,
                                         &nprim, &ierr2);
    st = ss_error_set(err, SS_EINPUT,
                      "%s: %zu elements of gmsh type %d (%s) have no cell here "
                      "(read: points, lines, triangles, quadrangles, "
                      "tetrahedra, hexahedra, of first order)",
                      path, count, type, !ierr2 && name ? name : "unknown");
    g->gmshFree(name);
    g->gmshFree(lc);
    return st;
  }
  const int nv = ss_cell_nverts(ct);
  if (nnodes != count * (size_t)nv)
    return ss_error_set(err, SS_EINPUT, "%s: gmsh gave %zu nodes for %zu %s", path,
                        nnodes, count, ss_cell_plural(ct));
  if (es->n[ct] + count > es->cap[ct]) {
    size_t c = 2 * es->cap[ct] + count;
    elem *p = realloc(es->el[ct], c * sizeof *p);
    if (!p) return ss_error_nomem(err, "gmsh elements");
    es->el[ct] = p;
    es->cap[ct] = c;
  }
  for (size_t i = 0; i < count; i++) {
    elem *x = es->el[ct] + es->n[ct]++;
    x->tag = tags[i];
    x->ref = ref;
    for (int j = 0; j < nv; j++) {
      const size_t *k = bsearch(nodes + i * (size_t)nv + j, nd->sorted, nd->n,
                                sizeof *nd->sorted, cmp_size);
      if (!k)
        return ss_error_set(err, SS_EINPUT,
                            "%s: element %zu refers to node %zu, which is not "
                            "in the file",
                            path, x->tag, nodes[i * (size_t)nv + j]);
      x->v[j] = (ss_idx)(k - nd->sorted);
    }
  }
  return SS_OK;
}

/* The elements of entity (d, etag), block by block, into es; their
 * reference is the entity's first physical group, else its tag. */
static ss_status add_entity(const gmsh_api *g, const char *path, int d, int etag,
                            const node_tags *nd, elem_lists *es, ss_error *err) {
  ss_status st = SS_OK;
  int ierr = 0;
  int *phys = NULL, *types = NULL;
  size_t nphys = 0, ntypes = 0, **etags = NULL, *etags_n = NULL, etags_nn = 0;
  size_t **enodes = NULL, *enodes_n = NULL, enodes_nn = 0;
  g->gmshModelGetPhysicalGroupsForEntity(d, etag, &phys, &nphys, &ierr);
  const int32_t ref = nphys ? phys[0] : etag;
  g->gmshFree(phys);
  g->gmshModelMeshGetElements(&types, &ntypes, &etags, &etags_n, &etags_nn, &enodes,
                              &enodes_n, &enodes_nn, d, etag, &ierr);
  for (size_t t = 0; t < ntypes && !st && !ierr; t++)
    st = add_block(g, path, types[t], etags_n[t], etags[t], enodes_n[t], enodes[t], ref,
                   nd, es, err);
  for (size_t t = 0; t < ntypes; t++) {
    g->gmshFree(etags[t]);
    g->gmshFree(enodes[t]);
  }
  g->gmshFree(types);
  g->gmshFree(etags);
  g->gmshFree(etags_n);
  g->gmshFree(enodes);
  g->gmshFree(enodes_n);
  if (!st && ierr)
    st = ss_error_set(err, SS_EINPUT, "%s: gmsh lists no elements of entity (%d, %d)",
                      path, d, etag);
  return st;
}

/* The elements of every entity of the model, dimension 0 to 3, into es. */
static ss_status gather_elements(const gmsh_api *g, const char *path, const node_tags *nd,
                                 elem_lists *es, ss_error *err) {
  ss_status st = SS_OK;
  int ierr = 0;
  int *ents = NULL;
  size_t nents = 0;
  for (int d = 0; d <= 3 && !st; d++) {
    g->gmshFree(ents);
    ents = NULL;
    g->gmshModelGetEntities(&ents, &nents, d, &ierr);
    if (ierr) {
      st = ss_error_set(err, SS_EINPUT, "%s: gmsh lists no entities of dimension %d",
                        path, d);
      break;
    }
    for (size_t e = 0; e < nents / 2 && !st; e++)
      st = add_entity(g, path, d, ents[2 * e + 1], nd, es, err);
  }
  g->gmshFree(ents);
  return st;
}

/* The gathered elements as cells of cx, type by type in the file's order
 * (by element tag).  SS_EINPUT for a degenerate cell; SS_ENOMEM. */
static ss_status add_cells(ss_cx *cx, const char *path, elem_lists *es, ss_error *err) {
  ss_status st = SS_OK;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (!es->n[t]) continue;
    const ss_cell_type ct = (ss_cell_type)t;
    if (ss_cell_dim(ct) > cx->dim) /* unreachable: 3D cells make dim 3 */
      return ss_error_set(err, SS_EINPUT, "%s: %s in a plane", path, ss_cell_plural(ct));
    qsort(es->el[t], es->n[t], sizeof *es->el[t], cmp_elem);
    if ((st = ss_cx_reserve_cells(cx, ct, es->n[t], err))) return st;
    for (size_t i = 0; i < es->n[t]; i++) {
      const elem *x = &es->el[t][i];
      const char *defect = ss_cell_defect(ct, x->v, cx->nv);
      if (defect)
        return ss_error_set(err, SS_EINPUT, "%s: element %zu (a %s) is %s", path, x->tag,
                            ss_cell_name(ct), defect);
      if ((st = ss_cx_add_cell(cx, ct, x->v, x->ref, err))) return st;
    }
  }
  return SS_OK;
}

/* Read the model gmsh holds into a new complex: its nodes, then the
 * elements of every entity, then those as cells. */
static ss_status extract(const gmsh_api *g, const char *path, ss_cx **out,
                         ss_mesh_fields *names, ss_error *err) {
  node_tags nd = {NULL, 0};
  elem_lists es;
  memset(&es, 0, sizeof es);
  ss_cx *cx = NULL;
  *out = NULL;
  ss_status st = read_nodes(g, path, &nd, &cx, err);
  if (!st) st = read_field(g, path, &nd, &cx, names, err);
  if (!st) st = gather_elements(g, path, &nd, &es, err);
  if (!st) st = add_cells(cx, path, &es, err);
  if (!st) {
    *out = cx;
    cx = NULL;
  }
  free(nd.sorted);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    free(es.el[t]);
  ss_cx_free(cx);
  return st;
}

/* Read path with gmsh in this process (the child of ss_mesh_read_gmsh). */
static ss_status read_here(const char *path, ss_cx **out, ss_mesh_fields *names,
                           ss_error *err) {
  gmsh_api api = {0}, *g = &api;
  char *saved = NULL;
  ss_status st = ss_gmsh_api_load(g, path, err);
  if (st || (st = ss_gmsh_begin(g, path, &saved, err))) return st;
  int ierr = 0;
  g->gmshOpen(path, &ierr);
  if (ierr) {
    char msg[300];
    ss_gmsh_last_error(g, msg, sizeof msg);
    st = ss_error_set(err, SS_EINPUT, "%s: %s", path, msg);
  } else {
    st = extract(g, path, out, names, err);
  }
  ss_gmsh_end(g, saved);
  return st;
}

/* ---- the child's answer through a pipe: status, then the message or the
 * complex (dim, nv, x, vref, then per cell type nc, cells, cref) ---- */

static int put_all(int fd, const void *p, size_t n) {
  const char *c = p;
  while (n) {
    const ssize_t w = write(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    c += w;
    n -= (size_t)w;
  }
  return 0;
}

static void send_answer(int fd, ss_status st, const ss_cx *cx,
                        const ss_mesh_fields *names, const ss_error *err) {
  int32_t s = (int32_t)st;
  if (put_all(fd, &s, sizeof s)) return;
  if (st) {
    put_all(fd, err->msg, strlen(err->msg));
    return;
  }
  int32_t dim = cx->dim;
  uint64_t nv = cx->nv;
  if (put_all(fd, &dim, sizeof dim) || put_all(fd, &nv, sizeof nv) ||
      put_all(fd, cx->x, cx->nv * (size_t)cx->dim * sizeof *cx->x) ||
      put_all(fd, cx->vref, cx->nv * sizeof *cx->vref))
    return;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    uint64_t nc = cx->nc[t];
    if (put_all(fd, &nc, sizeof nc) ||
        put_all(fd, cx->cells[t],
                cx->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t) * sizeof(ss_idx)) ||
        put_all(fd, cx->cref[t], cx->nc[t] * sizeof(int32_t)))
      return;
  }
  int32_t n = names->n;
  if (put_all(fd, &n, sizeof n)) return;
  put_all(fd, names->name, (size_t)n * SS_FIELD_NAME_MAX);
}

/* A cursor over the child's answer. */
typedef struct {
  const char *p; /* next unread byte */
  size_t left;   /* bytes left */
} cursor;

static int take(cursor *c, void *dst, size_t n) {
  if (n > c->left) return -1;
  memcpy(dst, c->p, n);
  c->p += n;
  c->left -= n;
  return 0;
}

/* Rebuild the complex the child sent; -1 if the answer is short or garbled,
 * -2 out of memory. */
static int decode(cursor *c, ss_cx **out, ss_mesh_fields *names, ss_error *err) {
  int32_t dim;
  uint64_t nv;
  if (take(c, &dim, sizeof dim) || take(c, &nv, sizeof nv) || dim < 1 ||
      dim > SS_MAXDIM || nv > c->left / (sizeof(double) * (size_t)dim))
    return -1;
  ss_cx *cx = NULL;
  if (ss_cx_new(dim, &cx, err) || ss_cx_reserve_vertices(cx, (size_t)nv, err)) {
    ss_cx_free(cx);
    return -2;
  }
  const char *xs = c->p;
  if (nv * (uint64_t)dim * sizeof(double) > c->left) goto bad;
  c->p += nv * (size_t)dim * sizeof(double);
  c->left -= nv * (size_t)dim * sizeof(double);
  for (uint64_t i = 0; i < nv; i++) {
    double x[SS_MAXDIM];
    int32_t ref;
    memcpy(x, xs + i * (size_t)dim * sizeof(double), (size_t)dim * sizeof(double));
    if (take(c, &ref, sizeof ref)) goto bad;
    if (ss_cx_add_vertex(cx, x, ref, err)) goto nomem;
  }
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    uint64_t nc;
    const int k = ss_cell_nverts((ss_cell_type)t);
    if (take(c, &nc, sizeof nc) ||
        nc > c->left / ((size_t)k * sizeof(ss_idx) + sizeof(int32_t)))
      goto bad;
    if (ss_cx_reserve_cells(cx, (ss_cell_type)t, (size_t)nc, err)) goto nomem;
    const char *vs = c->p;
    c->p += nc * (size_t)k * sizeof(ss_idx);
    c->left -= nc * (size_t)k * sizeof(ss_idx);
    for (uint64_t i = 0; i < nc; i++) {
      ss_idx v[SS_MAXCELLVERTS];
      int32_t ref;
      memcpy(v, vs + i * (size_t)k * sizeof(ss_idx), (size_t)k * sizeof(ss_idx));
      if (take(c, &ref, sizeof ref) || ss_cell_defect((ss_cell_type)t, v, cx->nv))
        goto bad;
      if (ss_cx_add_cell(cx, (ss_cell_type)t, v, ref, err)) goto nomem;
    }
  }
  int32_t n;
  if (take(c, &n, sizeof n) || n != (cx->dim > 3 ? cx->dim - 3 : 0) ||
      take(c, names->name, (size_t)n * SS_FIELD_NAME_MAX) || c->left)
    goto bad;
  names->n = n;
  for (int32_t i = 0; i < n; i++)
    names->name[i][SS_FIELD_NAME_MAX - 1] = '\0';
  *out = cx;
  return 0;
bad:
  ss_cx_free(cx);
  return -1;
nomem:
  ss_cx_free(cx);
  return -2;
}

/* What gmsh read (cx) against what the file declares (the scan): every
 * element a cell, no node beyond those declared (version 2 drops the nodes
 * no element uses).  gmsh's reader is lenient, and a difference is cells
 * lost without a word. */
static ss_status check_counts(const char *path, const ss_gmsh_decl *d, const ss_cx *cx,
                              ss_error *err) {
  size_t total = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    total += cx->nc[t];
    if (cx->nc[t] != d->cells[t])
      return ss_error_set(err, SS_EINPUT,
                          "%s: gmsh read %zu %s where $Elements declares %zu: refused "
                          "rather than lose or invent cells",
                          path, cx->nc[t], ss_cell_plural((ss_cell_type)t), d->cells[t]);
  }
  if (total != d->elements)
    return ss_error_set(err, SS_EINPUT,
                        "%s: gmsh read %zu cells where $Elements declares %zu: refused "
                        "rather than lose or invent cells",
                        path, total, d->elements);
  if (cx->nv > d->nodes)
    return ss_error_set(err, SS_EINPUT,
                        "%s: gmsh read %zu nodes where $Nodes declares %zu", path, cx->nv,
                        d->nodes);
  return SS_OK;
}

ss_status ss_mesh_read_gmsh(const char *path, ss_cx **out, ss_error *err) {
  return ss_mesh_read_gmsh_fields(path, out, NULL, err);
}

ss_status ss_mesh_read_gmsh_fields(const char *path, ss_cx **out, ss_mesh_fields *names,
                                   ss_error *err) {
  ss_mesh_fields tmp;
  if (!names) names = &tmp;
  memset(names, 0, sizeof *names);
  *out = NULL;
  ss_status st = check_header(path, err);
  ss_gmsh_decl decl;
  if (!st) st = ss_mesh_gmsh_scan(path, &decl, err);
  if (st) return st;
  /* gmsh 4.8 dereferences bad node tags in some malformed binary files and
   * dies of SIGSEGV: it reads in a child process, whose death becomes a
   * message.  The lock is held across fork, so the child (one thread) never
   * waits for it, and no two reads overlap. */
  ss_gmsh_lock();
  int fd[2];
  if (pipe(fd)) {
    ss_gmsh_unlock();
    return ss_error_set(err, SS_EIO, "%s: no pipe for the gmsh reader: %s", path,
                        strerror(errno));
  }
  const pid_t pid = fork();
  if (pid < 0) {
    const int e = errno;
    close(fd[0]);
    close(fd[1]);
    ss_gmsh_unlock();
    return ss_error_set(err, SS_EIO, "%s: cannot start the gmsh reader: %s", path,
                        strerror(e));
  }
  if (pid == 0) { /* the child: read, answer, and leave without atexit or stdio */
    close(fd[0]);
    ss_error e = {0};
    ss_cx *cx = NULL;
    ss_mesh_fields nm;
    memset(&nm, 0, sizeof nm);
    const ss_status cst = read_here(path, &cx, &nm, &e);
    send_answer(fd[1], cst, cx, &nm, &e);
    _exit(0);
  }
  close(fd[1]);
  char *buf = NULL;
  size_t len = 0, cap = 0;
  int nomem = 0;
  for (;;) {
    if (len == cap) {
      char *b = realloc(buf, cap = cap ? 2 * cap : 65536);
      if (!b) {
        nomem = 1;
        break;
      }
      buf = b;
    }
    const ssize_t r = read(fd[0], buf + len, cap - len);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    len += (size_t)r;
  }
  close(fd[0]); /* a child still writing gets EPIPE and ends */
  int wst = 0;
  while (waitpid(pid, &wst, 0) < 0 && errno == EINTR) {
  }
  ss_gmsh_unlock();
  cursor c = {buf, len};
  int32_t s;
  if (nomem) {
    st = ss_error_nomem(err, "gmsh reader's answer");
  } else if (WIFSIGNALED(wst)) {
    st = ss_error_set(err, SS_EINPUT,
                      "%s: gmsh crashed reading it (signal %d): a malformed file", path,
                      WTERMSIG(wst));
  } else if (take(&c, &s, sizeof s)) { /* e.g. a sanitizer caught the crash */
    st = ss_error_set(err, SS_EINPUT,
                      "%s: gmsh crashed reading it (exit status %d, no answer): a "
                      "malformed file",
                      path, WIFEXITED(wst) ? WEXITSTATUS(wst) : -1);
  } else if (s) {
    st = ss_error_set(err, (ss_status)s, "%.*s", (int)(c.left < 511 ? c.left : 511), c.p);
  } else {
    const int d = decode(&c, out, names, err);
    st = d == 0 ? SS_OK
         : d == -2
             ? ss_error_nomem(err, "mesh from gmsh")
             : ss_error_set(err, SS_EINPUT, "%s: the gmsh reader's answer is cut", path);
  }
  free(buf);
  if (!st && (st = check_counts(path, &decl, *out, err))) {
    ss_cx_free(*out);
    *out = NULL;
  }
  return st;
}

#endif
