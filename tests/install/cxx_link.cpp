/* cxx_link.cpp — libsubspectra from C++ (issue 33): every installed header in
 * one C++ translation unit, linked against the shared library through the
 * installed pkg-config file, and run.
 *
 * Without `extern "C"` in the headers (SS_BEGIN_DECLS, ss_api.h) this would
 * compile and then fail to link: g++ would look for C++-mangled names such as
 * ss_scheme_new(char const*, ss_scheme**, ss_error*).
 *
 * ss_all_headers.h is written by test_install.sh: one #include <subspectra/...>
 * per installed header, so a header added later is covered without editing
 * this file.
 *
 * Checks, each against a closed form or a definition, not against the
 * program's own output:
 *   - ss_version() equals SS_VERSION_STRING and "MAJOR.MINOR.PATCH" of the
 *     macros; it is printed for the script to compare with pkg-config
 *     --modversion;
 *   - ss_scheme_names() lists "mlca"; ss_scheme_new("mlca") is named "mlca";
 *     an unknown scheme is SS_EINPUT with a message;
 *   - MLCA at a regular edge (valence n = 4: the regular grid, where MLCA is
 *     the tricubic B-spline): two-ring 5^3 = 125 points, one-ring 3^3 = 27;
 *     the leading eigenvalue 1 (simple: the constants) and the subdominant
 *     1/2, three times (the linear functions x, y, z: the cubic B-spline
 *     curve's 1, 1/2, 1/4 in each direction, tensored);
 *   - a C++ lambda as the progress callback of the eigen-solve is called.
 * Output: "version LIB" and one "ok: ..." line per check; exit 0 when all
 * hold, 1 otherwise. */
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ss_all_headers.h"

#include <subspectra/ss_eig.h>
#include <subspectra/ss_error.h>
#include <subspectra/ss_local.h>
#include <subspectra/ss_scheme.h>
#include <subspectra/ss_version.h>

namespace {

int failures = 0;

void check(bool ok, const std::string &what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  if (!ok) ++failures;
}

bool near(double a, double b) {
  return std::fabs(a - b) <= 1e-9 * std::fabs(b) + 1e-12;
}

void check_version() {
  const std::string lib = ss_version();
  const std::string macros = std::to_string(SS_VERSION_MAJOR) + "." +
                             std::to_string(SS_VERSION_MINOR) + "." +
                             std::to_string(SS_VERSION_PATCH);
  std::printf("version %s\n", lib.c_str());
  check(lib == SS_VERSION_STRING,
        "ss_version() " + lib + " == SS_VERSION_STRING " + SS_VERSION_STRING);
  check(macros == SS_VERSION_STRING,
        "SS_VERSION_MAJOR.MINOR.PATCH " + macros + " == SS_VERSION_STRING");
}

void check_schemes() {
  std::vector<std::string> names;
  for (const char *const *p = ss_scheme_names(); *p; ++p)
    names.emplace_back(*p);
  bool mlca = false;
  for (const auto &n : names)
    mlca = mlca || n == "mlca";
  check(mlca, "ss_scheme_names() lists mlca among " + std::to_string(names.size()));

  ss_error err{};
  ss_scheme *s = nullptr;
  const ss_status st = ss_scheme_new("no-such-scheme", &s, &err);
  check(st == SS_EINPUT && !s && err.msg[0] != '\0',
        std::string("an unknown scheme: ") + ss_status_name(st) + " (" + err.msg + ")");
}

void check_edge() {
  ss_error err{};
  ss_scheme *s = nullptr;
  ss_local *M = nullptr;
  ss_eig *e = nullptr;
  if (ss_scheme_new("mlca", &s, &err) != SS_OK) {
    check(false, std::string("ss_scheme_new(mlca): ") + err.msg);
    return;
  }
  check(std::strcmp(ss_scheme_name(s), "mlca") == 0, "ss_scheme_name is mlca");

  ss_case c{}; /* zero: default diagonals, no link, no 4-8 class */
  c.kind = SS_CASE_EDGE;
  c.n = 4;
  if (ss_local_new(s, &c, &M, &err) != SS_OK) {
    check(false, std::string("ss_local_new(mlca, edge 4): ") + err.msg);
    ss_scheme_free(s);
    return;
  }
  check(M->n2 == 125 && M->n1 == 27, "edge 4: two-ring " + std::to_string(M->n2) +
                                         " = 5^3, one-ring " + std::to_string(M->n1) +
                                         " = 3^3");

  size_t steps = 0;
  ss_eig_opts o = ss_eig_defaults(M->dim);
  o.progress.fn = [](void *ctx, const char *, size_t, size_t) {
    ++*static_cast<size_t *>(ctx);
  };
  o.progress.ctx = &steps;
  if (ss_eig_new(M->S, M->n2, M->n1, &o, &e, &err) != SS_OK) {
    check(false, std::string("ss_eig_new: ") + err.msg);
  } else {
    check(e->n == M->n2 && e->n >= 4, "eigenvalues: " + std::to_string(e->n));
    check(near(e->val[0].re, 1) && e->val[0].im == 0 && e->val[0].mult == 1,
          "lambda0 = " + std::to_string(e->val[0].re) + " (1, simple)");
    bool half = true;
    for (int i = 1; i <= 3; i++)
      half = half && near(e->val[i].re, 0.5) && near(e->val[i].im, 0);
    check(half && e->val[1].mult == 3, "lambda1..3 = " + std::to_string(e->val[1].re) +
                                           " x" + std::to_string(e->val[1].mult) +
                                           " (1/2, three times)");
    check(steps > 0,
          "the C++ progress callback was called " + std::to_string(steps) + " times");
  }
  ss_eig_free(e);
  ss_local_free(M);
  ss_scheme_free(s);
}

} // namespace

int main() {
  check_version();
  check_schemes();
  check_edge();
  return failures ? 1 : 0;
}
