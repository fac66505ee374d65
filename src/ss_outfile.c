/* ss_outfile.c — output files written whole or not at all (ss_outfile.h). */
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
 * allows), as a malloc'd path; a copy of path when it is not a link or the
 * chain cannot be read (the rename then replaces the link, the old fopen
 * behaviour aside).  NULL without memory. */
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
    if (!(o->f = fopen(path, "w")))
      st = ss_error_set(err, SS_EIO, "%s: cannot open for writing: %s", path,
                        strerror(errno));
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
  if (!(o->f = fdopen(fd, "w"))) {
    st = ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
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
  /* glibc keeps the bytes a failed write could not store, so the flush
   * repeats the failure and its errno; EIO stands in for a lost one */
  errno = 0;
  int bad = fflush(o->f) != 0;
  int e = errno;
  if (ferror(o->f)) bad = 1;
  if (!bad && o->tmp && fsync(fileno(o->f)) != 0) bad = 1, e = errno;
  errno = 0;
  if (fclose(o->f) != 0 && !bad) bad = 1, e = errno;
  ss_status st = SS_OK;
  if (bad) {
    st =
        ss_error_set(err, SS_EIO, "%s: cannot write: %s", o->path, strerror(e ? e : EIO));
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
