/* ss_store.h — the results store: one SQLite database per sweep (or per
 * project), one row per analysed case (DESIGN sections 2 and 8).
 *
 * Schema (version 3; docs/sweep.md shows it in full):
 *   meta(key, value)       program = subspectra, schema = 3, created = UTC time
 *   scheme(id, identity, name, stencil, stencil_hash, tol, depth, ring_levels,
 *          certify, diagonals, psi_depth)
 *                          identity is unique: the scheme name or the hash of
 *                          its stencil file, with every analysis parameter
 *                          that can change a verdict (ss_store_identity)
 *   result(scheme_id, kind, k, link, ..., eigen_on, regularity_on,
 *          injectivity_on, psi_verdict, psi_covered, psi_uncovered,
 *          psi_pieces)         primary key (scheme_id, kind, k, link): a case
 *                          is stored at most once per identity.  *_on: what
 *                          each verdict was judged on (ss_judged_on_name),
 *                          NULL when not judged or not recorded; psi_*: psi
 *                          judged on its pieces (ss_result_psi), NULL when
 *                          it was not
 *   cases                  a view: result joined with its scheme's name and
 *                          identity, plus the combined verdict; what `report
 *                          --where` filters
 * The file is marked with PRAGMA application_id = SS_STORE_APP_ID and
 * user_version = SS_STORE_SCHEMA, so a foreign SQLite file is recognised.
 *
 * Versions.  Version 3 added the columns *_on and psi_* of result (last, in
 * that order) and scheme.psi_depth.  A store of version 2 opened to write is
 * upgraded in one transaction (its rows keep NULL there: not recorded); opened
 * read-only it is read as it is, the file untouched: temporary views of the
 * connection show the missing columns as NULL (and psi_depth 0), so `report`
 * and `merge` read it like an upgraded one.  Other versions, older or newer,
 * are refused with a message naming both versions.
 *
 * Durability: journal_mode WAL, synchronous NORMAL.  Every ss_store_put is its
 * own committed transaction, so a process killed at any moment (SIGKILL
 * included) loses at most the case it was computing, never a stored one, and
 * the next open recovers the write-ahead log.  Several processes may write one
 * store (SQLite's locking, with a busy timeout); one ss_store handle must not
 * be used by two threads at once (sweep serialises its writes).
 *
 * Library code: nothing here prints; failures come back as ss_status with a
 * message naming the file. */
#ifndef SS_STORE_H
#define SS_STORE_H

#include <stddef.h>
#include <stdint.h>

#include "ss_api.h"
#include "ss_diag.h"
#include "ss_result.h"

SS_BEGIN_DECLS

#define SS_STORE_APP_ID 0x53537370 /* "SSsp" */
#define SS_STORE_SCHEMA 3

typedef struct ss_store ss_store; /* an open database and its statements */

typedef enum {
  SS_STORE_READ = 0, /* an existing store, read only */
  SS_STORE_WRITE     /* create the file if missing, else open it to add rows */
} ss_store_mode;

/* What the scheme column of a result means. */
typedef struct {
  const char *name;      /* scheme name (a stencil file's [scheme] name) */
  const char *stencil;   /* the stencil file as given, or NULL for a built-in
                            scheme (informative only: the hash identifies) */
  uint64_t stencil_hash; /* FNV-1a 64 of the stencil file's bytes (ss_stencil) */
  int reads_diagonals;   /* 1 if the scheme reads major diagonals */
  ss_diag_mode diag;     /* with reads_diagonals: the choice */
  ss_result_opts opts;   /* tolerance, hex depth, ring levels, certify, psi
                            depth */
} ss_store_scheme;

/* One stored row, as ss_store_each hands it out (pointers valid during the
 * visit only). */
typedef struct {
  const char *scheme;   /* scheme name */
  const char *identity; /* scheme identity (ss_store_identity) */
  ss_result r;          /* the result, as computed (r.link borrowed) */
} ss_store_row;

/* Return nonzero to stop the iteration early. */
typedef int (*ss_store_visit)(const ss_store_row *row, void *ctx);

/* The identity text of sc into buf (n bytes, >= 128 is always enough):
 * "NAME tol=T depth=D rings=R[ certified][ diagonals=X][ psi-depth=P]" for a
 * built-in scheme, "stencil:HASH16 tol=T depth=D rings=R[ certified][
 * diagonals=X][ psi-depth=P]" for a stencil file ("certified": the exact path,
 * --certify; psi-depth only when not 0, so identities of psi_depth 0 are
 * those of stores written before it existed).  T is the shortest
 * of "%.6g".."%.17g" that reads back as the tolerance exactly, so distinct
 * tolerances are distinct identities (1e-06, 1.0000006e-06). */
void ss_store_identity(const ss_store_scheme *sc, char *buf, size_t n);

/* Open path (see ss_store_mode).  An existing file must be a subspectra store
 * of this schema version or of version 2 (upgraded when opened to write, read
 * as it is when read-only: see "Versions" above) and pass SQLite's
 * quick_check, and every row must be valid: each column of the type, range or
 * names this program writes, each result's scheme row there.  *out is owned
 * by the caller (ss_store_close).  SS_EINPUT: not SQLite, corrupt, a foreign
 * database, another schema version, or invalid rows (a hand edit: the
 * message names the table, row, column and value of the first ones); SS_EIO: the
 * file cannot be opened or created, or (SS_STORE_WRITE) this process cannot
 * write it or create its -wal and -shm files (a read-only file system, the
 * file's or directory's permissions), or another process has held it
 * locked for 5 seconds (the message says which); SS_ENOMEM. */
ss_status ss_store_open(const char *path, ss_store_mode mode, ss_store **out,
                        ss_error *err);

/* Close (NULL is a no-op); checkpoints the write-ahead log. */
void ss_store_close(ss_store *st);

/* The id of scheme sc in st, inserting it if new.  SS_EIO on a database
 * error. */
ss_status ss_store_scheme_id(ss_store *st, const ss_store_scheme *sc, int64_t *id,
                             ss_error *err);

/* *found = 1 if the case (kind, k, canonical link or "") is stored for scheme
 * id, and then *verdict (may be NULL) is its combined verdict
 * (ss_result_verdict).  A vertex case is found as an edge-point row too (a
 * result's kind says how the vertex was judged).  SS_EIO. */
ss_status ss_store_has(ss_store *st, int64_t id, ss_case_kind kind, int k,
                       const char *link, int *found, ss_verdict_kind *verdict,
                       ss_error *err);

/* Store r for scheme id and commit.  A row already there is kept (results are
 * deterministic), *added = 0 then, else 1 (added may be NULL).  SS_EIO. */
ss_status ss_store_put(ss_store *st, int64_t id, const ss_result *r, int *added,
                       ss_error *err);

/* Rows of scheme id by kind (*nk[kind]), for progress (ids < 0: all
 * schemes).  nk has SS_NCASEKINDS entries, indexed by ss_case_kind.  SS_EIO. */
ss_status ss_store_count(ss_store *st, int64_t id, size_t nk[SS_NCASEKINDS],
                         ss_error *err);

/* Visit the rows whose view row satisfies `where` (an SQL expression over the
 * columns of the view `cases`, or NULL for all), ordered by scheme identity,
 * kind, k and link.  SS_EINPUT if where does not compile (SQLite's message),
 * SS_EIO on a database error, SS_ENOMEM. */
ss_status ss_store_each(ss_store *st, const char *where, ss_store_visit visit, void *ctx,
                        ss_error *err);

/* What to do with a conflict: a case (scheme identity, kind, k, link) that
 * both stores hold with different values (any column but the key and
 * `seconds`, compared exactly; a column of version 3 that one of them holds as
 * NULL, not recorded by a store of version 2, is no conflict). */
typedef enum {
  SS_STORE_PREFER_NONE = 0, /* keep st's row; the caller reports the conflicts */
  SS_STORE_PREFER_OLD,      /* keep st's row */
  SS_STORE_PREFER_NEW       /* replace it by src's row */
} ss_store_prefer;

enum {
  SS_STORE_NKEYS = 3,    /* conflict keys kept by ss_store_merge_stats */
  SS_STORE_KEYLEN = 640, /* room for one key: identity, kind, k, a k = 20 link */
};

/* What one ss_store_merge did. */
typedef struct {
  size_t added;     /* results whose key st did not have: copied */
  size_t present;   /* results st had with equal values: nothing to do */
  size_t conflicts; /* results st had with other values */
  size_t replaced;  /* conflicts replaced by src's row (SS_STORE_PREFER_NEW) */
  char first[SS_STORE_NKEYS][SS_STORE_KEYLEN]; /* the first min(conflicts,
                       SS_STORE_NKEYS) conflict keys, "(IDENTITY) KIND K[ LINK]",
                       in the order identity, kind, k, link */
} ss_store_merge_stats;

/* Copy every scheme and result of the store at src into st in one
 * transaction: new keys are added, equal rows left alone, conflicts resolved
 * by prefer (SS_STORE_PREFER_NONE keeps st's rows, as OLD does: the caller
 * decides what a conflict means).  src is opened read-only like
 * ss_store_open(READ), so a store on a read-only medium or in a directory the
 * user may not write is merged too.  *stats (may be NULL) says what was done;
 * all zero after a failure, when nothing is changed.  SS_EINPUT for a bad
 * src, or src being st's own file under any name (symbolic or hard link);
 * SS_EIO for a database error (reading src or writing st: the message says
 * which file); SS_ENOMEM. */
ss_status ss_store_merge(ss_store *st, const char *src, ss_store_prefer prefer,
                         ss_store_merge_stats *stats, ss_error *err);

SS_END_DECLS

#endif
