/* ss_store_impl.h — internals of the results store shared by its files: the
 * open database (ss_store.c) and its schema, created, upgraded or read in an
 * older version (ss_store_schema.c). */
#ifndef SS_STORE_IMPL_H
#define SS_STORE_IMPL_H

#include <stdint.h>

#include <sqlite3.h>

#include "ss_error.h"
#include "ss_store.h"

struct ss_store {
  sqlite3 *db;       /* the connection */
  char *path;        /* the file, for messages */
  sqlite3_stmt *has; /* the verdicts of one key */
  sqlite3_stmt *put; /* INSERT OR IGNORE INTO result */
  int readonly;      /* opened with SS_STORE_READ */
};

/* SS_EIO: "PATH: what: SQLite's message", saying so when another process
 * holds the store. */
ss_status ss_store_db_error(ss_store *st, ss_error *err, const char *what);

/* sqlite3_exec without callback; SQLite's status. */
int ss_store_exec(ss_store *st, const char *sql);

/* One integer from a one-row query (*rc SQLite's status); -1 on error. */
int64_t ss_store_query_int(ss_store *st, const char *sql, int *rc);

/* Create the schema of version SS_STORE_SCHEMA in an empty database.
 * Another process may have opened the same new file at the same moment (the
 * parts of a sweep sharing one store): whoever takes the write lock first
 * creates, and *raced = 1 tells the others to validate what it made
 * instead.  SS_EIO. */
ss_status ss_store_schema_create(ss_store *st, int *raced, ss_error *err);

/* A store of schema version 2 made readable as version SS_STORE_SCHEMA.
 * Opened to write: upgraded in one transaction (the new columns added, NULL
 * in every existing row; the view recreated; user_version and meta's schema
 * set), unless another process has just done it.  Opened read-only: the file
 * is left as it is, and temporary views named like the tables (SQLite looks
 * in temp first) show the missing columns as NULL.  SS_EIO. */
ss_status ss_store_schema_upgrade(ss_store *st, ss_error *err);

/* Every row of the store valid: each column of the type, range or names
 * ss_store_put and ss_store_scheme_id write, each result's scheme row there
 * (ss_store_check.c).  SS_EINPUT naming the store and the first invalid rows
 * (table, row, column, value, what it should be); SS_EIO, SS_ENOMEM. */
ss_status ss_store_check_rows(ss_store *st, ss_error *err);

#endif
