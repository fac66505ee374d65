/* ss_outfile.h — output files written whole or not at all.
 *
 * An output file is written into a temporary file beside its target (same
 * directory, the target's name + ".tmp." + a random suffix, created with
 * O_EXCL so concurrent runs never share one), then flushed, checked, synced
 * and renamed over the target.  Any failure removes the temporary file and
 * leaves the target as it was: a reader sees the old file or the whole new
 * one, never a truncated one.
 *
 * A target that exists and is not a regular file (a device such as /dev/null
 * or /dev/stdout, a FIFO) cannot be replaced by a rename: it is written in
 * place, with the same checks.  A symbolic link is followed: the file it
 * points to is replaced, the link kept.  A new file gets the mode fopen(3)
 * would give it (0666 less the umask); a replaced file keeps its mode.
 *
 * Usage:
 *   ss_outfile *o;
 *   if ((st = ss_outfile_open(path, &o, err))) return st;
 *   ... write to ss_outfile_file(o) ...
 *   st = failed ? (ss_outfile_abort(o), st) : ss_outfile_commit(o, err);
 */
#ifndef SS_OUTFILE_H
#define SS_OUTFILE_H

#include <stdio.h>

#include "ss_api.h"
#include "ss_error.h"

SS_BEGIN_DECLS

/* An output file being written (opaque). */
typedef struct ss_outfile ss_outfile;

/* Start writing the file at path: create the temporary file beside it (*out,
 * finished by exactly one of ss_outfile_commit or ss_outfile_abort).  SS_EIO
 * naming path when the temporary file cannot be created (no such folder, no
 * permission, path is a folder), SS_ENOMEM. */
ss_status ss_outfile_open(const char *path, ss_outfile **out, ss_error *err);

/* The stream to write to (owned by o; do not close it). */
FILE *ss_outfile_file(const ss_outfile *o);

/* The target path, as given to ss_outfile_open (owned by o). */
const char *ss_outfile_path(const ss_outfile *o);

/* Finish: flush, check the stream's error flag, fsync, close, and rename the
 * temporary file over the target.  On any failure the temporary file is
 * removed, the target left untouched, and SS_EIO returned with "PATH: cannot
 * write: REASON" (strerror of the failed call).  Frees o in every case;
 * o == NULL is SS_OK. */
ss_status ss_outfile_commit(ss_outfile *o, ss_error *err);

/* Give up: close and remove the temporary file, leave the target untouched,
 * free o.  NULL is a no-op. */
void ss_outfile_abort(ss_outfile *o);

/* A write-only stream on the open descriptor fd that remembers why it failed:
 * the errno of the first failed write(2) (or of the close) goes to *errnum,
 * which must outlive the stream, and every later write fails too.  glibc's
 * own streams drop a failed buffer and forget the reason, so a later fflush
 * or fclose can report success; the output files above and the tool's
 * standard output are written through this.  A nonzero *errnum at the start
 * makes every write fail with it.  fclose closes fd.  fileno() is -1 on it.
 * NULL (errno set) without memory. */
FILE *ss_outfile_fdopen(int fd, int *errnum);

SS_END_DECLS

#endif
