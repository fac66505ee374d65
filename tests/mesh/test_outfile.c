/* test_outfile.c — ss_outfile: output files written whole or not at all.
 * A commit replaces the target; an abort or a failed write (a file size limit,
 * write() failing with EFBIG) leaves no file, no temporary file, and an
 * existing target as it was. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ss_outfile.h"
#include "ss_test.h"

static char dir[] = "/tmp/ss_test_outfile_XXXXXX";

static const char *in_dir(const char *name) {
  static char buf[256];
  snprintf(buf, sizeof buf, "%s/%s", dir, name);
  return buf;
}

/* The number of entries in dir (without . and ..). */
static int entries(void) {
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  if (d) closedir(d);
  return n;
}

/* The file's text (first 255 bytes), "" if it cannot be read. */
static const char *text(const char *path) {
  static char buf[256];
  buf[0] = '\0';
  FILE *f = fopen(path, "r");
  if (!f) return buf;
  const size_t n = fread(buf, 1, sizeof buf - 1, f);
  buf[n] = '\0';
  fclose(f);
  return buf;
}

static void put(const char *path, const char *s) {
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(s, f);
    fclose(f);
  }
}

int main(void) {
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  ss_error err = {0};
  ss_outfile *o = NULL;

  /* commit: a new file, whole; nothing else left */
  CHECK(ss_outfile_open(in_dir("a.txt"), &o, &err) == SS_OK, "open: %s", err.msg);
  if (o) {
    CHECK(!strcmp(ss_outfile_path(o), in_dir("a.txt")), "path %s", ss_outfile_path(o));
    fputs("hello\n", ss_outfile_file(o));
    CHECK(access(in_dir("a.txt"), F_OK) != 0, "the target appears only on commit");
    CHECK(entries() == 1, "one temporary file while writing: %d entries", entries());
    CHECK(ss_outfile_commit(o, &err) == SS_OK, "commit: %s", err.msg);
  }
  CHECK(!strcmp(text(in_dir("a.txt")), "hello\n"), "content '%s'", text(in_dir("a.txt")));
  CHECK(entries() == 1, "only the target left: %d entries", entries());

  /* abort: the old file stays, the temporary file goes */
  CHECK(ss_outfile_open(in_dir("a.txt"), &o, &err) == SS_OK, "open: %s", err.msg);
  if (o) {
    fputs("half", ss_outfile_file(o));
    ss_outfile_abort(o);
  }
  CHECK(!strcmp(text(in_dir("a.txt")), "hello\n"), "abort kept the old file");
  CHECK(entries() == 1, "abort left %d entries", entries());
  ss_outfile_abort(NULL);
  CHECK(ss_outfile_commit(NULL, &err) == SS_OK, "commit(NULL)");

  /* a failed write: a 1 KiB file size limit, SIGXFSZ ignored (EFBIG) */
  put(in_dir("b.txt"), "old\n");
  chmod(in_dir("b.txt"), 0640);
  struct rlimit rl, lim;
  getrlimit(RLIMIT_FSIZE, &rl);
  lim = rl;
  lim.rlim_cur = 1024;
  signal(SIGXFSZ, SIG_IGN);
  if (setrlimit(RLIMIT_FSIZE, &lim) == 0) {
    for (int keep = 0; keep < 2; keep++) {
      const char *p = in_dir(keep ? "b.txt" : "c.txt");
      CHECK(ss_outfile_open(p, &o, &err) == SS_OK, "open: %s", err.msg);
      if (!o) continue;
      for (int i = 0; i < 1000; i++)
        fputs("0123456789abcdef\n", ss_outfile_file(o));
      err = (ss_error){0};
      CHECK(ss_outfile_commit(o, &err) == SS_EIO && strstr(err.msg, p) &&
                strstr(err.msg, strerror(EFBIG)),
            "a write beyond the limit fails naming the file and the reason: %s", err.msg);
    }
    setrlimit(RLIMIT_FSIZE, &rl);
    CHECK(!strcmp(text(in_dir("b.txt")), "old\n"), "the old file kept: '%s'",
          text(in_dir("b.txt")));
    CHECK(access(in_dir("c.txt"), F_OK) != 0, "no new file after a failed write");
    CHECK(entries() == 2, "no temporary file left: %d entries", entries());
  } else {
    fprintf(stderr, "setrlimit: %s (size limit checks skipped)\n", strerror(errno));
  }

  /* the replaced file keeps its mode */
  CHECK(ss_outfile_open(in_dir("b.txt"), &o, &err) == SS_OK, "open: %s", err.msg);
  if (o) {
    fputs("new\n", ss_outfile_file(o));
    CHECK(ss_outfile_commit(o, &err) == SS_OK, "commit: %s", err.msg);
  }
  struct stat sb;
  CHECK(stat(in_dir("b.txt"), &sb) == 0 && (sb.st_mode & 0777) == 0640, "mode %o",
        (unsigned)(sb.st_mode & 0777));
  CHECK(!strcmp(text(in_dir("b.txt")), "new\n"), "replaced");

  /* bad targets: a missing folder, a folder */
  err = (ss_error){0};
  CHECK(ss_outfile_open(in_dir("no/x.txt"), &o, &err) == SS_EIO &&
            strstr(err.msg, in_dir("no/x.txt")),
        "missing folder: %s", err.msg);
  err = (ss_error){0};
  CHECK(ss_outfile_open(dir, &o, &err) == SS_EIO && strstr(err.msg, dir), "a folder: %s",
        err.msg);

  /* a device is written in place */
  CHECK(ss_outfile_open("/dev/null", &o, &err) == SS_OK, "/dev/null: %s", err.msg);
  if (o) {
    fputs("x", ss_outfile_file(o));
    CHECK(ss_outfile_commit(o, &err) == SS_OK, "/dev/null commit: %s", err.msg);
  }
  CHECK(ss_outfile_open("/dev/full", &o, &err) == SS_OK, "/dev/full: %s", err.msg);
  if (o) {
    fputs("x", ss_outfile_file(o));
    err = (ss_error){0};
    CHECK(ss_outfile_commit(o, &err) == SS_EIO && strstr(err.msg, strerror(ENOSPC)),
          "/dev/full commit fails: %s", err.msg);
  }

  /* the reason survives a dropped buffer: glibc's own stream forgets it once
   * a large write has failed and reports EIO or nothing */
  CHECK(ss_outfile_open("/dev/full", &o, &err) == SS_OK, "/dev/full: %s", err.msg);
  if (o) {
    static char big[100000];
    memset(big, 'x', sizeof big);
    fwrite(big, 1, sizeof big, ss_outfile_file(o));
    fputs("tail", ss_outfile_file(o));
    err = (ss_error){0};
    CHECK(ss_outfile_commit(o, &err) == SS_EIO && strstr(err.msg, strerror(ENOSPC)),
          "/dev/full after a large write: %s", err.msg);
  }
  int e = 0;
  int fd = dup(STDERR_FILENO);
  FILE *f = fd >= 0 ? ss_outfile_fdopen(fd, &e) : NULL;
  CHECK(f != NULL, "ss_outfile_fdopen");
  if (f) {
    e = EBADF; /* a failure recorded before: every write fails with it */
    fputs("never shown\n", f);
    CHECK(fflush(f) != 0 && ferror(f) && e == EBADF, "sticky failure: e = %d", e);
    fclose(f);
  }

  unlink(in_dir("a.txt"));
  unlink(in_dir("b.txt"));
  rmdir(dir);
  return ss_test_done("outfile");
}
