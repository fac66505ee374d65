/* ss_outfile.c — output files written whole or not at all (ss_outfile.h). */
#define _GNU_SOURCE /* fopencookie: streams that remember why a write failed */
#include "ss_outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

struct ss_outfile {
  FILE *f;      /* the stream written: the temporary file, or the target itself */
  int fd;       /* f's descriptor (f is an ss_outfile_fdopen stream) */
  int errnum;   /* why a write to f failed (errno), 0 while none has */
  char *path;   /* the target as given, for messages */
  char *target; /* the file the rename replaces: path, or where its symlinks lead */
  char *tmp;    /* the temporary file beside target; NULL when written in place */
};

static void outfile_free(ss_outfile *o) {
  free(o->path);
  free(o->target);
  free(o->tmp);
  free(o);
}

/* Where the symbolic links at path lead (at most 40 of them, as the kernel
 * allows), as a malloc'd path: path itself when it is not a link; the missing
 * file a dangling link names (created there, as fopen would).  NULL without
 * memory. */
static char *follow_links(const char *path) {
  char *p = strdup(path);
  for (int depth = 0; p && depth < 40; depth++) {
    struct stat sb;
    if (lstat(p, &sb) != 0 || !S_ISLNK(sb.st_mode)) break;
    char buf[4096];
    const ssize_t n = readlink(p, buf, sizeof buf - 1);
    if (n <= 0) break;
    buf[n] = '\0';
    const char *slash = strrchr(p, '/');
    /* a relative link is relative to the link's folder */
    const size_t dir = buf[0] == '/' || !slash ? 0 : (size_t)(slash - p) + 1;
    char *q = malloc(dir + (size_t)n + 1);
    if (q) {
      memcpy(q, p, dir);
      memcpy(q + dir, buf, (size_t)n + 1);
    }
    free(p);
    p = q;
  }
  return p;
}

/* Six random name characters into s: getrandom, or the clock, the process id
 * and a counter if that fails (O_EXCL still prevents any collision). */
static void random_suffix(char *s) {
  static const char abc[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  static unsigned long counter;
  unsigned char r[6];
  if (getrandom(r, sizeof r, GRND_NONBLOCK) != (ssize_t)sizeof r) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t x = (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 20) ^
                 ((uint64_t)getpid() << 40) ^ (++counter * 0x9E3779B97F4A7C15u);
    for (int i = 0; i < 6; i++, x >>= 8)
      r[i] = (unsigned char)x;
  }
  for (int i = 0; i < 6; i++)
    s[i] = abc[r[i] % (sizeof abc - 1)];
  s[6] = '\0';
}

/* ---- streams that remember why they failed ---- */

typedef struct {
  int fd;      /* the descriptor written */
  int *errnum; /* the caller's slot for the first failure's errno */
} fd_cookie;

static ssize_t fd_write(void *cookie, const char *buf, size_t n) {
  fd_cookie *c = cookie;
  /* a short count (0 on error: never negative, glibc's fwrite would take it
   * as a huge count) sets the stream's error flag */
  if (*c->errnum) return 0; /* failed once: the output has a hole, stop */
  size_t done = 0;
  while (done < n) {
    const ssize_t w = write(c->fd, buf + done, n - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      *c->errnum = w < 0 ? errno : EIO;
      return (ssize_t)done;
    }
    done += (size_t)w;
  }
  return (ssize_t)n;
}

static int fd_close(void *cookie) {
  fd_cookie *c = cookie;
  const int rc = close(c->fd);
  if (rc != 0 && !*c->errnum) *c->errnum = errno;
  free(c);
  return rc;
}

FILE *ss_outfile_fdopen(int fd, int *errnum) {
  fd_cookie *c = malloc(sizeof *c);
  if (!c) return NULL;
  *c = (fd_cookie){fd, errnum};
  const cookie_io_functions_t io = {NULL, fd_write, NULL, fd_close};
  FILE *f = fopencookie(c, "w", io);
  if (!f) free(c);
  return f;
}

/* ---- output files ---- */

ss_status ss_outfile_open(const char *path, ss_outfile **out, ss_error *err) {
  *out = NULL;
  ss_outfile *o = calloc(1, sizeof *o);
  if (!o || !(o->path = strdup(path))) {
    free(o);
    return ss_error_nomem(err, "output file");
  }
  ss_status st = SS_OK;
  struct stat sb;
  const int exists = stat(path, &sb) == 0;
  if (exists && S_ISDIR(sb.st_mode)) {
    st = ss_error_set(err, SS_EIO, "%s: cannot write: %s", path, strerror(EISDIR));
    goto done;
  }
  if (exists && !S_ISREG(sb.st_mode)) {
    /* a device or a FIFO: nothing to replace, written in place */
    o->fd = open(path, O_WRONLY | O_TRUNC);
    if (o->fd < 0)
      st = ss_error_set(err, SS_EIO, "%s: cannot open for writing: %s", path,
                        strerror(errno));
    else if (!(o->f = ss_outfile_fdopen(o->fd, &o->errnum))) {
      st = ss_error_nomem(err, "output file");
      close(o->fd);
    }
    goto done;
  }
  o->target = follow_links(path);
  const size_t n = o->target ? strlen(o->target) : 0;
  o->tmp = o->target ? malloc(n + sizeof ".tmp.XXXXXX") : NULL;
  if (!o->tmp) {
    st = ss_error_nomem(err, "output file");
    goto done;
  }
  memcpy(o->tmp, o->target, n);
  memcpy(o->tmp + n, ".tmp.", 5);
  int fd = -1;
  for (int tries = 0; fd < 0 && tries < 100; tries++) {
    random_suffix(o->tmp + n + 5);
    /* 0666 less the umask, as fopen(path, "w") would create it */
    fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    st = ss_error_set(err, SS_EIO, "%s: cannot open for writing: %s", path,
                      strerror(errno));
    free(o->tmp);
    o->tmp = NULL;
    goto done;
  }
  /* a replaced file keeps its mode (best effort, as fopen keeps it too) */
  if (exists) (void)fchmod(fd, sb.st_mode & 07777);
  o->fd = fd;
  if (!(o->f = ss_outfile_fdopen(fd, &o->errnum))) {
    st = ss_error_nomem(err, "output file");
    close(fd);
    unlink(o->tmp);
  }
done:
  if (st) {
    outfile_free(o);
    return st;
  }
  *out = o;
  return SS_OK;
}

FILE *ss_outfile_file(const ss_outfile *o) {
  return o->f;
}

const char *ss_outfile_path(const ss_outfile *o) {
  return o->path;
}

ss_status ss_outfile_commit(ss_outfile *o, ss_error *err) {
  if (!o) return SS_OK;
  int bad = fflush(o->f) != 0 || ferror(o->f);
  if (!bad && o->tmp && fsync(o->fd) != 0 && !o->errnum) o->errnum = errno;
  if (fclose(o->f) != 0) bad = 1; /* closes fd; a failure's errno in o->errnum */
  if (o->errnum) bad = 1;
  ss_status st = SS_OK;
  if (bad) {
    st = ss_error_set(err, SS_EIO, "%s: cannot write: %s", o->path,
                      strerror(o->errnum ? o->errnum : EIO));
    if (o->tmp) unlink(o->tmp);
  } else if (o->tmp && rename(o->tmp, o->target) != 0) {
    st = ss_error_set(err, SS_EIO, "%s: cannot replace it with the written file: %s",
                      o->path, strerror(errno));
    unlink(o->tmp);
  }
  outfile_free(o);
  return st;
}

void ss_outfile_abort(ss_outfile *o) {
  if (!o) return;
  fclose(o->f);
  if (o->tmp) unlink(o->tmp);
  outfile_free(o);
}
