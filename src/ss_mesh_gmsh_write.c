/* ss_mesh_gmsh_write.c — gmsh .msh 4.1 (ASCII) written through gmsh's own C
 * API (ss_mesh_gmsh_api.h), as ss_mesh_gmsh.c reads it: the complex becomes
 * a discrete model, gmshWrite writes it and gmshViewWrite appends its fields
 * as $NodeData.
 *
 * Layout: node k is vertex k - 1 (3 coordinates, z = 0 for a plane); the
 * cells of each dimension and reference r sit on one discrete entity of
 * that dimension, in the physical group r when r > 0 (gmsh's groups are
 * positive; a cell of reference <= 0 reads back with its entity's tag); an
 * element's tag is its place among all cells in type order, so the reader,
 * which orders a type's cells by tag, gets them back in the complex's order.
 * Fields (ss_mesh_fields) are views of node data, one per scalar, and one
 * 3-component view NAME for three consecutive fields NAME_x, NAME_y, NAME_z
 * (the reader splits it again).  gmsh has no octahedron: refused.
 *
 * As the reader, gmsh runs in a child process (fork; its state is global,
 * and it dies on some inputs), under the process-wide lock, and writes a
 * temporary file whose bytes are copied to the caller's stream. */
#include "ss_mesh.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#if SS_HAVE_GMSH
#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ss_mesh_gmsh_api.h"

/* gmsh's element type of each ss_cell_type (0: none). */
static const int gmsh_type[SS_NCELLTYPES] = {15, 1, 2, 3, 4, 5, 0};

/* Whether fields i, i+1, i+2 are NAME_x, NAME_y, NAME_z; *len: NAME's. */
static int vector_at(const ss_mesh_fields *nm, int i, size_t *len) {
  if (i + 2 >= nm->n) return 0;
  const size_t n = strlen(nm->name[i]);
  if (n < 3 || strcmp(nm->name[i] + n - 2, "_x")) return 0;
  for (int c = 1; c < 3; c++)
    if (strncmp(nm->name[i + c], nm->name[i], n - 1) ||
        nm->name[i + c][n - 1] != "xyz"[c] || nm->name[i + c][n])
      return 0;
  *len = n - 2;
  return 1;
}

/* SS_EINPUT with gmsh's last error. */
static ss_status gmsh_failed(const ss_gmsh_api *g, const char *path, ss_error *err) {
  char msg[300];
  ss_gmsh_last_error(g, msg, sizeof msg);
  return ss_error_set(err, SS_EINPUT, "%s: gmsh: %s", path, msg);
}

/* The cells of dimension d and reference r, type by type, on entity etag. */
static int add_cells(const ss_gmsh_api *g, const ss_cx *cx, int d, int32_t r, int etag,
                     size_t *et, size_t *nt) {
  int ierr = 0;
  size_t first = 0;
  for (int t = 0; t < SS_NCELLTYPES && !ierr; t++) {
    const size_t k = (size_t)ss_cell_nverts((ss_cell_type)t);
    size_t m = 0;
    if (ss_cell_dim((ss_cell_type)t) == d && gmsh_type[t])
      for (size_t i = 0; i < cx->nc[t]; i++) {
        if (cx->cref[t][i] != r) continue;
        et[m] = first + i + 1;
        for (size_t j = 0; j < k; j++)
          nt[m * k + j] = (size_t)ss_cx_cell(cx, (ss_cell_type)t, i)[j] + 1;
        m++;
      }
    if (m) g->gmshModelMeshAddElementsByType(etag, gmsh_type[t], et, m, nt, m * k, &ierr);
    first += cx->nc[t];
  }
  return ierr;
}

/* The model: entities, nodes, elements, physical groups. */
static ss_status build(const ss_gmsh_api *g, const char *path, const ss_cx *cx,
                       ss_error *err) {
  int ierr = 0, nodes_on = -1;
  size_t most = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (cx->nc[t] > most) most = cx->nc[t];
  size_t *et = malloc((most + 1) * sizeof *et);
  size_t *nt = malloc((most * SS_MAXCELLVERTS + 1) * sizeof *nt);
  size_t *tags = malloc((cx->nv + 1) * sizeof *tags);
  double *xyz = malloc((3 * cx->nv + 1) * sizeof *xyz);
  int32_t *refs = malloc((ss_cx_ncells(cx) + 1) * sizeof *refs);
  ss_status st =
      et && nt && tags && xyz && refs ? SS_OK : ss_error_nomem(err, "gmsh model");
  g->gmshModelAdd("subspectra", &ierr);
  for (int d = 3, etag = 1; d >= 0 && !st && !ierr; d--) {
    size_t nr = 0; /* the distinct references of dimension d, in order of appearance */
    for (int t = 0; t < SS_NCELLTYPES; t++)
      if (ss_cell_dim((ss_cell_type)t) == d)
        for (size_t i = 0; i < cx->nc[t]; i++) {
          size_t j = 0;
          while (j < nr && refs[j] != cx->cref[t][i])
            j++;
          if (j == nr) refs[nr++] = cx->cref[t][i];
        }
    for (size_t j = 0; j < nr && !ierr; j++, etag++) {
      g->gmshModelAddDiscreteEntity(d, etag, NULL, 0, &ierr);
      if (nodes_on < 0 && !ierr) { /* every node on the first entity */
        nodes_on = etag;
        for (size_t v = 0; v < cx->nv; v++) {
          tags[v] = v + 1;
          for (int a = 0; a < 3; a++)
            xyz[3 * v + (size_t)a] =
                a < cx->dim ? cx->x[v * (size_t)cx->dim + (size_t)a] : 0;
        }
        g->gmshModelMeshAddNodes(d, etag, tags, cx->nv, xyz, 3 * cx->nv, NULL, 0, &ierr);
      }
      if (!ierr) ierr = add_cells(g, cx, d, refs[j], etag, et, nt);
      int e = etag;
      if (!ierr && refs[j] > 0) g->gmshModelAddPhysicalGroup(d, &e, 1, refs[j], &ierr);
    }
  }
  if (!st && !ierr && nodes_on < 0)
    st = ss_error_set(err, SS_EINPUT, "%s: a mesh without cells: gmsh keeps no nodes",
                      path);
  if (!st && ierr) st = gmsh_failed(g, path, err);
  free(et);
  free(nt);
  free(tags);
  free(xyz);
  free(refs);
  return st;
}

/* The fields as views appended to file. */
static ss_status views(const ss_gmsh_api *g, const char *path, const char *file,
                       const ss_cx *cx, const ss_mesh_fields *nm, ss_error *err) {
  int ierr = 0;
  const size_t dim = (size_t)cx->dim;
  size_t *tags = malloc((cx->nv + 1) * sizeof *tags);
  double *val = malloc((3 * cx->nv + 1) * sizeof *val);
  ss_status st = tags && val ? SS_OK : ss_error_nomem(err, "gmsh views");
  for (int i = 0; !st && !ierr && i < nm->n;) {
    size_t len = 0;
    const int nc = vector_at(nm, i, &len) ? 3 : 1;
    char name[SS_FIELD_NAME_MAX];
    snprintf(name, sizeof name, "%.*s", nc == 3 ? (int)len : SS_FIELD_NAME_MAX,
             nm->name[i]);
    for (size_t v = 0; v < cx->nv; v++) {
      tags[v] = v + 1;
      for (int c = 0; c < nc; c++)
        val[v * (size_t)nc + (size_t)c] = cx->x[v * dim + 3 + (size_t)(i + c)];
    }
    const int vt = g->gmshViewAdd(name, -1, &ierr);
    if (!ierr)
      g->gmshViewAddHomogeneousModelData(vt, 0, "subspectra", "NodeData", tags, cx->nv,
                                         val, cx->nv * (size_t)nc, 0.0, nc, -1, &ierr);
    if (!ierr) g->gmshViewWrite(vt, file, 1, &ierr);
    i += nc;
  }
  if (!st && ierr) st = gmsh_failed(g, path, err);
  free(tags);
  free(val);
  return st;
}

/* In the child: the model written to file by gmsh. */
static ss_status write_here(const char *path, const char *file, const ss_cx *cx,
                            const ss_mesh_fields *nm, ss_error *err) {
  ss_gmsh_api api = {0}, *g = &api;
  char *saved = NULL;
  ss_status st = ss_gmsh_api_load(g, path, err);
  if (st || (st = ss_gmsh_begin(g, path, &saved, err))) return st;
  int ierr = 0;
  g->gmshOptionSetNumber("Mesh.MshFileVersion", 4.1, &ierr);
  g->gmshOptionSetNumber("Mesh.Binary", 1, &ierr); /* exact doubles */
  g->gmshOptionSetNumber("Mesh.SaveAll", 1, &ierr);
  /* the views alone after the mesh, not the mesh again with each */
  g->gmshOptionSetNumber("PostProcessing.SaveMesh", 0, &ierr);
  if (!(st = build(g, path, cx, err))) {
    g->gmshWrite(file, &ierr);
    st = ierr ? gmsh_failed(g, path, err) : views(g, path, file, cx, nm, err);
  }
  ss_gmsh_end(g, saved);
  return st;
}

/* Copy file's bytes to f. */
static ss_status copy(const char *path, const char *file, FILE *f, ss_error *err) {
  FILE *in = fopen(file, "rb");
  if (!in)
    return ss_error_set(err, SS_EIO, "%s: gmsh wrote no file: %s", path, strerror(errno));
  char buf[65536];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, f) != n) break;
  const int bad = ferror(in) || ferror(f);
  fclose(in);
  return bad ? ss_error_set(err, SS_EIO, "%s: write error", path) : SS_OK;
}

/* The child's answer: its status and message. */
static ss_status run_child(const char *path, const char *file, const ss_cx *cx,
                           const ss_mesh_fields *nm, ss_error *err) {
  int fd[2];
  if (pipe(fd))
    return ss_error_set(err, SS_EIO, "%s: no pipe for the gmsh writer: %s", path,
                        strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]);
    close(fd[1]);
    return ss_error_set(err, SS_EIO, "%s: cannot start the gmsh writer: %s", path,
                        strerror(errno));
  }
  if (pid == 0) {
    close(fd[0]);
    ss_error e = {0};
    const int32_t s = (int32_t)write_here(path, file, cx, nm, &e);
    if (write(fd[1], &s, sizeof s) == sizeof s && s)
      if (write(fd[1], e.msg, strlen(e.msg)) < 0) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  char msg[sizeof err->msg] = "";
  int32_t s = -1;
  size_t got = 0;
  ssize_t r;
  while ((r = read(fd[0], got < sizeof s ? (char *)&s + got : msg + got - sizeof s,
                   got < sizeof s ? sizeof s - got : sizeof msg - 1 - (got - sizeof s))) >
             0 ||
         (r < 0 && errno == EINTR))
    if (r > 0) got += (size_t)r;
  close(fd[0]);
  int wst = 0;
  while (waitpid(pid, &wst, 0) < 0 && errno == EINTR) {
  }
  if (got < sizeof s)
    return ss_error_set(err, SS_EINPUT, "%s: gmsh crashed writing it (%s %d)", path,
                        WIFSIGNALED(wst) ? "signal" : "exit status",
                        WIFSIGNALED(wst) ? WTERMSIG(wst) : WEXITSTATUS(wst));
  return s ? ss_error_set(err, (ss_status)s, "%s", msg) : SS_OK;
}

ss_status ss_mesh_write_gmsh(FILE *f, const char *path, const ss_cx *cx,
                             const ss_mesh_write_opts *opts, ss_error *err) {
  if (cx->nc[SS_OCT])
    return ss_error_set(err, SS_EINPUT,
                        "%s: gmsh has no octahedron element (%zu octahedra): write .mesh "
                        "(4 tetrahedra each) or .vtu (2 pyramids each)",
                        path, cx->nc[SS_OCT]);
  ss_mesh_fields tmp;
  const ss_mesh_fields *nm = opts && opts->fields && opts->fields->n >= cx->dim - 3
                                 ? opts->fields
                                 : (ss_mesh_fields_default(cx->dim, &tmp), &tmp);
  char dir[] = "/tmp/subspectra-gmsh-XXXXXX", file[sizeof dir + 16];
  if (!mkdtemp(dir))
    return ss_error_set(err, SS_EIO, "%s: no temporary directory for gmsh: %s", path,
                        strerror(errno));
  snprintf(file, sizeof file, "%s/out.msh", dir);
  ss_gmsh_lock();
  ss_status st = run_child(path, file, cx, nm, err);
  ss_gmsh_unlock();
  if (!st) st = copy(path, file, f, err);
  remove(file);
  rmdir(dir);
  return st;
}

#else

ss_status ss_mesh_write_gmsh(FILE *f, const char *path, const ss_cx *cx,
                             const ss_mesh_write_opts *opts, ss_error *err) {
  (void)f;
  (void)cx;
  (void)opts;
  return ss_error_set(err, SS_EINPUT,
                      "%s: this subspectra was built without gmsh, so .msh files are not "
                      "written; it writes %s",
                      path, ss_mesh_writable_list());
}

#endif
