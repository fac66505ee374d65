/* ss_cli_check_out.c — `check`'s reports: the text lines, JSON, JUnit XML,
 * and the comparison with a baseline run's JSON (ss_cli_check.h). */
#include "ss_cli.h"
#include "ss_cli_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

static const char *const outcome_names[4] = {"pass", "fail", "undecided", "error"};

const char *ss_check_outcome_name(ss_check_outcome o) {
  return outcome_names[o];
}

void ss_check_print_case(const ss_check_case *k) {
  if (k->outcome == SS_CHECK_ERROR)
    printf("error      %s: %s\n", k->name, k->reason);
  else if (k->outcome != SS_CHECK_PASS)
    printf("%-10s %s: %s: %s\n", k->outcome == SS_CHECK_UNDECIDED ? "undecided" : "fail",
           k->name, k->condition, k->reason);
}

/* obj[key] = a new string, or -1 out of memory. */
static int put_string(json_object *obj, const char *key, const char *s) {
  json_object *v = json_object_new_string(s);
  return v && !json_object_object_add(obj, key, v) ? 0 : -1;
}

static int put_int(json_object *obj, const char *key, long n) {
  json_object *v = json_object_new_int64(n);
  return v && !json_object_object_add(obj, key, v) ? 0 : -1;
}

/* The JSON object of one case, or NULL out of memory. */
static json_object *case_json(const ss_check_case *k, int with_regression) {
  json_object *o = json_object_new_object();
  int bad = !o || put_string(o, "name", k->name) ||
            put_string(o, "outcome", outcome_names[k->outcome]);
  if (!bad && k->condition) bad = put_string(o, "condition", k->condition);
  if (!bad && k->outcome != SS_CHECK_PASS) bad = put_string(o, "reason", k->reason);
  if (!bad && with_regression) {
    json_object *b = json_object_new_boolean(k->regression);
    bad = !b || json_object_object_add(o, "regression", b);
  }
  json_object *t = bad ? NULL : json_object_new_double(k->seconds);
  bad = bad || !t || json_object_object_add(o, "seconds", t);
  if (bad) {
    json_object_put(o);
    return NULL;
  }
  return o;
}

int ss_check_write_json(const ss_check_run *r) {
  json_object *doc = json_object_new_object(), *cases = json_object_new_array();
  json_object *sum = json_object_new_object();
  int bad = !doc || !cases || !sum;
  if (r->stencil)
    bad = bad || put_string(doc, "stencil", r->stencil);
  else /* a built-in scheme: null */
    bad = bad || json_object_object_add(doc, "stencil", NULL);
  bad = bad || put_string(doc, "scheme", r->scheme);
  json_object *tol = bad ? NULL : json_object_new_double(r->tol);
  json_object *cert = bad ? NULL : json_object_new_boolean(r->certify);
  bad = bad || !tol || json_object_object_add(doc, "tol", tol) || !cert ||
        json_object_object_add(doc, "certify", cert) || put_int(doc, "depth", r->depth);
  bad = bad || put_int(sum, "cases", (long)r->ncases);
  for (int o = 0; !bad && o < 4; o++)
    bad = put_int(sum, outcome_names[o], r->count[o]);
  const int with_regression = r->regressions >= 0;
  if (!bad && with_regression) bad = put_int(sum, "regressions", r->regressions);
  for (size_t i = 0; !bad && i < r->ncases; i++) {
    json_object *k = case_json(r->cases + i, with_regression);
    bad = !k || json_object_array_add(cases, k);
    if (bad) json_object_put(k);
  }
  if (!bad) {
    bad = json_object_object_add(doc, "summary", sum);
    sum = NULL;
  }
  if (!bad) {
    bad = json_object_object_add(doc, "cases", cases);
    cases = NULL;
  }
  if (!bad) printf("%s\n", json_object_to_json_string_ext(doc, SS_CLI_JSON_FLAGS));
  json_object_put(sum);
  json_object_put(cases);
  json_object_put(doc);
  return bad ? -1 : 0;
}

/* s with XML's special characters escaped, on stdout. */
static void xml_text(const char *s) {
  for (; *s; s++)
    switch (*s) {
    case '<':
      fputs("&lt;", stdout);
      break;
    case '>':
      fputs("&gt;", stdout);
      break;
    case '&':
      fputs("&amp;", stdout);
      break;
    case '"':
      fputs("&quot;", stdout);
      break;
    case '\'':
      fputs("&apos;", stdout);
      break;
    default:
      if ((unsigned char)*s < 0x20 && *s != '\n' && *s != '\t')
        putchar(' '); /* control characters are not XML 1.0 */
      else
        putchar(*s);
    }
}

int ss_check_write_junit(const ss_check_run *r) {
  const long failures = r->count[SS_CHECK_FAIL] + r->count[SS_CHECK_UNDECIDED];
  double total = 0.0;
  for (size_t i = 0; i < r->ncases; i++)
    total += r->cases[i].seconds;
  printf("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  printf("<testsuites name=\"subspectra check\" tests=\"%zu\" failures=\"%ld\" "
         "errors=\"%ld\" time=\"%.3f\">\n",
         r->ncases, failures, r->count[SS_CHECK_ERROR], total);
  printf("  <testsuite name=\"");
  xml_text(r->stencil ? r->stencil : r->scheme);
  printf(
      "\" tests=\"%zu\" failures=\"%ld\" errors=\"%ld\" skipped=\"0\" time=\"%.3f\">\n",
      r->ncases, failures, r->count[SS_CHECK_ERROR], total);
  for (size_t i = 0; i < r->ncases; i++) {
    const ss_check_case *k = r->cases + i;
    printf("    <testcase classname=\"check.%s\" name=\"",
           k->c.kind == SS_CASE_VERTEX           ? "vertex"
           : k->c.kind == SS_CASE_EDGE           ? "edge"
           : k->c.kind == SS_CASE_SURFACE_VERTEX ? "surface-vertex"
                                                 : "face");
    xml_text(k->name);
    printf("\" time=\"%.3f\"", k->seconds);
    if (k->outcome == SS_CHECK_PASS) {
      printf("/>\n");
      continue;
    }
    const char *tag = k->outcome == SS_CHECK_ERROR ? "error" : "failure";
    printf(">\n      <%s type=\"%s\" message=\"", tag, outcome_names[k->outcome]);
    if (k->condition) {
      xml_text(k->condition);
      printf(": ");
    }
    xml_text(k->reason);
    printf("\">");
    xml_text(outcome_names[k->outcome]);
    printf(" %s", k->regression ? "(a regression: passed in the baseline) " : "");
    xml_text(k->name);
    printf("</%s>\n    </testcase>\n", tag);
  }
  printf("  </testsuite>\n</testsuites>\n");
  return 0;
}

int ss_check_baseline(ss_check_run *r, const char *path, char *msg, size_t msgsize) {
  json_object *doc = json_object_from_file(path);
  json_object *cases = NULL;
  if (!doc || !json_object_object_get_ex(doc, "cases", &cases) ||
      !json_object_is_type(cases, json_type_array)) {
    snprintf(msg, msgsize,
             "--baseline %s: not the JSON of a `check --format json` run%s%s", path,
             doc ? "" : ": ", doc ? "" : json_util_get_last_err());
    json_object_put(doc);
    return -1;
  }
  /* the baseline's passing cases by name */
  const size_t nb = json_object_array_length(cases);
  r->regressions = 0;
  for (size_t i = 0; i < r->ncases; i++) {
    ss_check_case *k = r->cases + i;
    k->regression = 0;
    if (k->outcome == SS_CHECK_PASS) continue;
    for (size_t j = 0; j < nb; j++) {
      json_object *c = json_object_array_get_idx(cases, j), *name, *out;
      if (!json_object_object_get_ex(c, "name", &name) ||
          !json_object_object_get_ex(c, "outcome", &out)) {
        snprintf(msg, msgsize, "--baseline %s: case %zu lacks a name or an outcome", path,
                 j);
        json_object_put(doc);
        return -1;
      }
      if (strcmp(json_object_get_string(name), k->name)) continue;
      k->regression = !strcmp(json_object_get_string(out), "pass");
      break;
    }
    r->regressions += k->regression;
  }
  json_object_put(doc);
  return 0;
}
