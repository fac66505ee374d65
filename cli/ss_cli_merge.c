/* ss_cli_merge.c — `subspectra merge`: copy the results of stores (the
 * parts of a sweep split with --part) into one, matching schemes by
 * identity; conflicts reported or resolved by --prefer (ss_store_merge). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_store.h"

static const char *const merge_usage =
    "usage: subspectra merge [--prefer new|old] OUT.db IN.db...\n"
    "\n"
    "Copy every result of the stores IN.db... into OUT.db (created if missing),\n"
    "matching schemes by identity; for the stores of a sweep split with --part.\n"
    "A case OUT.db already has with the same values is left alone.  A conflict\n"
    "is a case both hold with different values (any stored column but the\n"
    "timing, compared exactly):\n"
    "  (default)         OUT.db's row is kept, and the conflicts are reported\n"
    "                    (how many, the first keys): exit status 1\n"
    "  --prefer old      OUT.db's row is kept\n"
    "  --prefer new      IN.db's row replaces it\n"
    "Each IN.db is merged in one transaction; IN.db is only read (it may be on a\n"
    "read-only medium).  Exit status 0, 1 conflicts without --prefer, 2 bad usage\n"
    "or a file that is not a subspectra results store, cannot be read or\n"
    "written, or is OUT.db itself (nothing is copied from it).\n";

int ss_cli_merge(int argc, char **argv) {
  ss_store_prefer prefer = SS_STORE_PREFER_NONE;
  char **files = calloc((size_t)argc, sizeof *files);
  int nfiles = 0;
  if (!files) {
    fprintf(stderr, "subspectra merge: out of memory\n");
    return SS_EXIT_FAIL;
  }
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      free(files);
      fputs(merge_usage, stdout);
      return SS_EXIT_OK;
    }
    if (!strcmp(a, "--")) {
      while (++i < argc)
        files[nfiles++] = argv[i];
      break;
    }
    if (!strncmp(a, "--prefer=", 9) || !strcmp(a, "--prefer")) {
      const char *v = a[8] == '=' ? a + 9 : i + 1 < argc ? argv[++i] : "";
      if (strcmp(v, "new") && strcmp(v, "old")) {
        free(files);
        return ss_cli_usage_error("merge", "--prefer: expected new or old, not '%s'", v);
      }
      prefer = !strcmp(v, "new") ? SS_STORE_PREFER_NEW : SS_STORE_PREFER_OLD;
      continue;
    }
    if (a[0] == '-' && a[1]) {
      free(files);
      return ss_cli_usage_error("merge", "unknown option '%s'", a);
    }
    files[nfiles++] = argv[i];
  }
  if (nfiles < 2) {
    free(files);
    return ss_cli_usage_error("merge", "need OUT.db and at least one IN.db");
  }
  ss_error err = {0};
  ss_store *out = NULL;
  const char *outname = files[0];
  if (ss_store_open(outname, SS_STORE_WRITE, &out, &err)) {
    free(files);
    fprintf(stderr, "subspectra merge: %s\n", err.msg);
    return err.status == SS_ENOMEM ? SS_EXIT_FAIL : SS_EXIT_USAGE;
  }
  int rc = SS_EXIT_OK;
  for (int i = 1; i < nfiles; i++) {
    ss_store_merge_stats ms;
    if (ss_store_merge(out, files[i], prefer, &ms, &err)) {
      fprintf(stderr, "subspectra merge: %s\n", err.msg);
      rc = SS_EXIT_USAGE;
      continue;
    }
    fprintf(stderr, "subspectra merge: %s: %zu results added, %zu already in %s",
            files[i], ms.added, ms.present, outname);
    if (ms.conflicts && prefer == SS_STORE_PREFER_NEW)
      fprintf(stderr, ", %zu conflicting results replaced (--prefer new)", ms.replaced);
    else if (ms.conflicts && prefer == SS_STORE_PREFER_OLD)
      fprintf(stderr, ", %zu conflicting results kept as in %s (--prefer old)",
              ms.conflicts, outname);
    fputc('\n', stderr);
    if (ms.conflicts && prefer == SS_STORE_PREFER_NONE) {
      fprintf(stderr,
              "subspectra merge: %s: %zu conflict%s with %s (the same case with other "
              "values; first: ",
              files[i], ms.conflicts, ms.conflicts == 1 ? "" : "s", outname);
      for (size_t j = 0; j < ms.conflicts && j < SS_STORE_NKEYS; j++)
        fprintf(stderr, "%s%s", j ? "; " : "", ms.first[j]);
      fprintf(stderr,
              "%s): %s's rows kept; --prefer new takes those of %s, --prefer old keeps "
              "them\n",
              ms.conflicts > SS_STORE_NKEYS ? "; ..." : "", outname, files[i]);
      if (rc == SS_EXIT_OK) rc = SS_EXIT_FAIL;
    }
  }
  ss_store_close(out);
  free(files);
  return rc;
}
