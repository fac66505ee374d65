/* ss_cli_reproduce_spec.c — the tables and figures `subspectra reproduce`
 * makes, read from a JSON file (data/reproduce/tables.json; its format in
 * data/reproduce/README.md).  They are data, not code: a new table is an
 * entry there.  Every key is checked, so that a misspelt one is an error and
 * not a silent default. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli_reproduce.h"

static const char *const source_names[] = {"links", "random",  "valences",
                                           "face",  "quasi48", "list"};

/* The case kinds a table or figure may name (edge-point is a result only). */
static int parse_kind(const char *name, ss_case_kind *out) {
  ss_case_kind k;
  if (ss_case_kind_parse(name, &k) || k == SS_CASE_EDGE_POINT) return -1;
  *out = k;
  return 0;
}

/* Reading one entry: the file and entry named in every message. */
typedef struct {
  const char *path; /* the file */
  const char *what; /* "table" or "figure" */
  size_t index;     /* 1-based entry number */
  json_object *o;   /* the entry */
  ss_error *err;    /* where messages go */
} entry;

static ss_status bad(const entry *e, const char *key, const char *problem) {
  return ss_error_set(e->err, SS_EINPUT, "%s: %s %zu: %s%s%s", e->path, e->what, e->index,
                      key ? key : "", key ? ": " : "", problem);
}

/* Every key of e is one of keys (NULL-terminated). */
static ss_status known_keys(const entry *e, const char *const *keys) {
  json_object_object_foreach(e->o, key, val) {
    (void)val;
    const char *const *k = keys;
    while (*k && strcmp(*k, key))
      k++;
    if (!*k) return bad(e, key, "unknown key");
  }
  return SS_OK;
}

/* The string at key (NULL when absent and optional). */
static ss_status get_string(const entry *e, const char *key, int required,
                            const char **out) {
  json_object *v;
  *out = NULL;
  if (!json_object_object_get_ex(e->o, key, &v) || json_object_is_type(v, json_type_null))
    return required ? bad(e, key, "missing") : SS_OK;
  if (!json_object_is_type(v, json_type_string) || !json_object_get_string_len(v))
    return bad(e, key, "not a non-empty string");
  *out = json_object_get_string(v);
  return SS_OK;
}

/* The integer at key in [lo, hi] (def when absent and optional). */
static ss_status get_int(const entry *e, const char *key, int required, int def, int lo,
                         int hi, int *out) {
  json_object *v;
  *out = def;
  if (!json_object_object_get_ex(e->o, key, &v))
    return required ? bad(e, key, "missing") : SS_OK;
  if (!json_object_is_type(v, json_type_int)) return bad(e, key, "not an integer");
  const int64_t x = json_object_get_int64(v);
  if (x < lo || x > hi)
    return ss_error_set(e->err, SS_EINPUT, "%s: %s %zu: %s: %lld not in %d..%d", e->path,
                        e->what, e->index, key, (long long)x, lo, hi);
  *out = (int)x;
  return SS_OK;
}

static ss_status get_kind(const entry *e, ss_case_kind *out) {
  const char *s;
  ss_status st = get_string(e, "case", 1, &s);
  if (!st && parse_kind(s, out))
    st = bad(e, "case", "not vertex, edge, face or surface-vertex");
  return st;
}

static ss_status get_diag(const entry *e, ss_diag_mode *out) {
  const char *s;
  *out = SS_DIAG_BFS;
  ss_status st = get_string(e, "diagonals", 0, &s);
  if (!st && s && ss_diag_parse(s, out))
    st = bad(e, "diagonals", "not bfs, skew, center or proper");
  return st;
}

/* "beside": an array of at most SS_REPRODUCE_MAXVS scheme names. */
static ss_status get_beside(const entry *e, ss_reproduce_table *t) {
  json_object *v;
  t->nvs = 0;
  if (!json_object_object_get_ex(e->o, "beside", &v)) return SS_OK;
  if (!json_object_is_type(v, json_type_array) ||
      json_object_array_length(v) > SS_REPRODUCE_MAXVS)
    return bad(e, "beside", "not an array of at most 2 scheme names");
  for (size_t i = 0; i < json_object_array_length(v); i++) {
    json_object *n = json_object_array_get_idx(v, i);
    if (!json_object_is_type(n, json_type_string) || !json_object_get_string_len(n))
      return bad(e, "beside", "not an array of at most 2 scheme names");
    t->vs[t->nvs++] = json_object_get_string(n);
  }
  return SS_OK;
}

/* The case kinds each source yields. */
static int source_fits(ss_reproduce_source src, ss_case_kind kind) {
  switch (src) {
  case SS_REPRODUCE_LINKS:
  case SS_REPRODUCE_RANDOM:
  case SS_REPRODUCE_LIST:
    return kind == SS_CASE_VERTEX;
  case SS_REPRODUCE_VALENCES:
    return kind == SS_CASE_EDGE || kind == SS_CASE_SURFACE_VERTEX;
  case SS_REPRODUCE_FACE:
    return kind == SS_CASE_FACE;
  case SS_REPRODUCE_QUASI48:
    return kind == SS_CASE_SURFACE_VERTEX;
  }
  return 0;
}

/* "links" of a table of source list: a non-empty array of objects, each
 * with exactly the non-empty strings "label" and "link". */
static ss_status get_list(const entry *e, ss_reproduce_table *t) {
  json_object *v;
  static const char *const msg = "not an array of {\"label\", \"link\"} objects";
  if (!json_object_object_get_ex(e->o, "links", &v))
    return t->src == SS_REPRODUCE_LIST ? bad(e, "links", "missing") : SS_OK;
  if (t->src != SS_REPRODUCE_LIST) return bad(e, "links", "only for source list");
  if (!json_object_is_type(v, json_type_array) || !json_object_array_length(v))
    return bad(e, "links", msg);
  for (size_t i = 0; i < json_object_array_length(v); i++) {
    json_object *it = json_object_array_get_idx(v, i), *x;
    if (!json_object_is_type(it, json_type_object) || json_object_object_length(it) != 2)
      return bad(e, "links", msg);
    for (int f = 0; f < 2; f++)
      if (!json_object_object_get_ex(it, f ? "link" : "label", &x) ||
          !json_object_is_type(x, json_type_string) || !json_object_get_string_len(x))
        return bad(e, "links", msg);
  }
  t->list = v;
  t->nlist = json_object_array_length(v);
  return SS_OK;
}

void ss_reproduce_list_item(const ss_reproduce_table *t, size_t i, const char **label,
                            const char **link) {
  json_object *it = json_object_array_get_idx(t->list, i), *x;
  json_object_object_get_ex(it, "label", &x);
  *label = json_object_get_string(x);
  json_object_object_get_ex(it, "link", &x);
  *link = json_object_get_string(x);
}

const char *ss_reproduce_case_tag(const ss_reproduce_table *t, size_t i) {
  const char *label = NULL, *link;
  if (t->src == SS_REPRODUCE_LIST && i < t->nlist)
    ss_reproduce_list_item(t, i, &label, &link);
  return label;
}

static ss_status read_table(const entry *e, ss_reproduce_table *t) {
  static const char *const keys[] = {"name", "title",  "scheme",    "case",    "source",
                                     "from", "to",     "diagonals", "lambdas", "command",
                                     "note", "beside", "psi_depth", "links",   NULL};
  const char *src = NULL;
  memset(t, 0, sizeof *t);
  ss_status st = known_keys(e, keys);
  if (!st) st = get_string(e, "name", 1, &t->name);
  if (!st && strchr(t->name, '/')) st = bad(e, "name", "a file stem may not hold '/'");
  if (!st) st = get_string(e, "title", 1, &t->title);
  if (!st) st = get_string(e, "scheme", 1, &t->scheme);
  if (!st) st = get_kind(e, &t->kind);
  if (!st) st = get_string(e, "source", 1, &src);
  if (!st) {
    size_t i = 0;
    while (i < sizeof source_names / sizeof *source_names && strcmp(src, source_names[i]))
      i++;
    if (i == sizeof source_names / sizeof *source_names)
      st = bad(e, "source", "not links, random, valences, face, quasi48 or list");
    t->src = (ss_reproduce_source)i;
  }
  if (!st && !source_fits(t->src, t->kind))
    st = bad(e, "case", "not a case kind this source yields");
  const int range = !st && t->src != SS_REPRODUCE_FACE && t->src != SS_REPRODUCE_LIST;
  if (range) st = get_int(e, "from", 1, 0, 1, 1000, &t->lo);
  if (range && !st) st = get_int(e, "to", 1, 0, t->lo, 1000, &t->hi);
  if (!st) st = get_diag(e, &t->diag);
  if (!st) st = get_int(e, "lambdas", 0, 0, 0, 15, &t->neig);
  if (!st) st = get_int(e, "psi_depth", 0, 0, 0, 8, &t->psi_depth);
  if (!st) st = get_string(e, "command", 1, &t->command);
  if (!st) st = get_string(e, "note", 0, &t->note);
  if (!st) st = get_beside(e, t);
  if (!st) st = get_list(e, t);
  return st;
}

static ss_status read_figure(const entry *e, ss_reproduce_figure *f) {
  static const char *const keys[] = {"file",    "scheme",    "case",  "link",
                                     "valence", "diagonals", "force", NULL};
  json_object *v;
  memset(f, 0, sizeof *f);
  ss_status st = known_keys(e, keys);
  if (!st) st = get_string(e, "file", 1, &f->file);
  if (!st && strchr(f->file, '/')) st = bad(e, "file", "a file name may not hold '/'");
  if (!st) st = get_string(e, "scheme", 1, &f->scheme);
  if (!st) st = get_kind(e, &f->kind);
  if (!st && f->kind == SS_CASE_VERTEX) st = get_string(e, "link", 1, &f->link);
  if (!st && (f->kind == SS_CASE_EDGE || f->kind == SS_CASE_SURFACE_VERTEX))
    st = get_int(e, "valence", 1, 0, 3, 1000, &f->n);
  if (!st) st = get_diag(e, &f->diag);
  if (!st && json_object_object_get_ex(e->o, "force", &v)) {
    if (!json_object_is_type(v, json_type_boolean))
      st = bad(e, "force", "not true or false");
    else
      f->force = json_object_get_boolean(v);
  }
  return st;
}

static ss_status read_table_item(const entry *e, void *item) {
  return read_table(e, item);
}

static ss_status read_figure_item(const entry *e, void *item) {
  return read_figure(e, item);
}

/* The array at key of the top object: each entry read by read into *items
 * (n of them, of size sz each). */
static ss_status read_array(const char *path, json_object *doc, const char *key,
                            const char *what, size_t sz,
                            ss_status (*read)(const entry *, void *), void **items,
                            size_t *n, ss_error *err) {
  json_object *a;
  *items = NULL;
  *n = 0;
  if (!json_object_object_get_ex(doc, key, &a) ||
      !json_object_is_type(a, json_type_array))
    return ss_error_set(err, SS_EINPUT, "%s: no array \"%s\"", path, key);
  const size_t len = json_object_array_length(a);
  char *out = calloc(len ? len : 1, sz);
  if (!out) return ss_error_nomem(err, "reproduce tables");
  *items = out;
  for (size_t i = 0; i < len; i++) {
    entry e = {path, what, i + 1, json_object_array_get_idx(a, i), err};
    if (!json_object_is_type(e.o, json_type_object))
      return bad(&e, NULL, "not an object");
    const ss_status st = read(&e, out + i * sz);
    if (st) return st;
    *n = i + 1;
  }
  return SS_OK;
}

/* The whole file at path as one JSON value into *doc; SS_EIO when it cannot
 * be read, SS_EINPUT naming the line where it stops being JSON. */
static ss_status parse_file(const char *path, json_object **doc, ss_error *err) {
  *doc = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  char *text = NULL;
  size_t n = 0, cap = 0;
  ss_status st = SS_OK;
  for (;;) {
    if (n + 4096 > cap) {
      char *nt = realloc(text, cap = cap ? 2 * cap : 65536);
      if (!nt) {
        st = ss_error_nomem(err, "reproduce tables");
        break;
      }
      text = nt;
    }
    const size_t got = fread(text + n, 1, cap - n - 1, f);
    n += got;
    if (got == 0) break;
  }
  if (!st && ferror(f)) st = ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  fclose(f);
  json_tokener *tok = st ? NULL : json_tokener_new();
  if (!st && !tok) st = ss_error_nomem(err, "reproduce tables");
  if (!st) {
    text[n] = '\0';
    *doc = json_tokener_parse_ex(tok, text, (int)n + 1); /* the NUL ends the value */
    const size_t end = json_tokener_get_parse_end(tok);
    size_t trail = end;
    while (trail < n && strchr(" \t\r\n", text[trail]))
      trail++;
    if (!*doc || trail < n) {
      long line = 1;
      const size_t at = *doc ? trail : end;
      for (size_t i = 0; i < at && i < n; i++)
        line += text[i] == '\n';
      st = ss_error_set(err, SS_EINPUT, "%s:%ld: not JSON: %s", path, line,
                        *doc ? "text after the value"
                             : json_tokener_error_desc(json_tokener_get_error(tok)));
      json_object_put(*doc);
      *doc = NULL;
    }
  }
  json_tokener_free(tok);
  free(text);
  return st;
}

ss_status ss_reproduce_spec_load(const char *path, ss_reproduce_spec *spec,
                                 ss_error *err) {
  memset(spec, 0, sizeof *spec);
  json_object *doc;
  ss_status st = parse_file(path, &doc, err);
  if (st) return st;
  spec->doc = doc;
  if (!json_object_is_type(doc, json_type_object))
    st = ss_error_set(err, SS_EINPUT, "%s: not a JSON object", path);
  json_object_object_foreach(doc, key, val) {
    (void)val;
    if (!st && strcmp(key, "tables") && strcmp(key, "figures"))
      st = ss_error_set(err, SS_EINPUT, "%s: unknown key \"%s\"", path, key);
  }
  void *items = NULL;
  if (!st) {
    st = read_array(path, doc, "tables", "table", sizeof(ss_reproduce_table),
                    read_table_item, &items, &spec->ntables, err);
    spec->table = items;
  }
  if (!st) {
    st = read_array(path, doc, "figures", "figure", sizeof(ss_reproduce_figure),
                    read_figure_item, &items, &spec->nfigures, err);
    spec->figure = items;
  }
  for (size_t i = 0; !st && i < spec->ntables; i++)
    for (size_t j = 0; j < i; j++)
      if (!strcmp(spec->table[i].name, spec->table[j].name)) {
        st = ss_error_set(err, SS_EINPUT, "%s: table %zu: name: '%s' again (table %zu)",
                          path, i + 1, spec->table[i].name, j + 1);
        break;
      }
  if (st) ss_reproduce_spec_free(spec);
  return st;
}

void ss_reproduce_spec_free(ss_reproduce_spec *spec) {
  free(spec->table);
  free(spec->figure);
  json_object_put(spec->doc);
  memset(spec, 0, sizeof *spec);
}
