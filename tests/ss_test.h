/* ss_test.h — minimal checking macros for the unit tests.
 *
 * Each test is a small executable; CHECK records a failure with file, line and
 * a printf-style explanation and carries on, so one run reports every broken
 * property.  ss_test_done() prints "N checks, M failed" and returns the exit
 * status for meson (0 only if every check held and at least one ran). */
#ifndef SS_TEST_H
#define SS_TEST_H

#include <math.h>
#include <stdio.h>

static long ss_test_checks_;
static long ss_test_failures_;

#define CHECK(cond, ...)                                                                 \
  do {                                                                                   \
    ss_test_checks_++;                                                                   \
    if (!(cond)) {                                                                       \
      ss_test_failures_++;                                                               \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);           \
      fprintf(stderr, __VA_ARGS__);                                                      \
      fputc('\n', stderr);                                                               \
    }                                                                                    \
  } while (0)

/* |a - b| <= tol * max(1, |b|): tolerances are relative for values above 1 and
 * absolute below, which suits weights in [0, 1]. */
#define CHECK_CLOSE(a, b, tol, ...)                                                      \
  do {                                                                                   \
    double ss_a_ = (a), ss_b_ = (b);                                                     \
    double ss_s_ = fabs(ss_b_) > 1.0 ? fabs(ss_b_) : 1.0;                                \
    ss_test_checks_++;                                                                   \
    if (!(fabs(ss_a_ - ss_b_) <= (tol)*ss_s_)) {                                         \
      ss_test_failures_++;                                                               \
      fprintf(stderr, "%s:%d: %s = %.17g, expected %s = %.17g (tol %g): ", __FILE__,     \
              __LINE__, #a, ss_a_, #b, ss_b_, (double)(tol));                            \
      fprintf(stderr, __VA_ARGS__);                                                      \
      fputc('\n', stderr);                                                               \
    }                                                                                    \
  } while (0)

/* Abort the test (with failure) if a library call did not return SS_OK. */
#define REQUIRE_OK(call, errp)                                                           \
  do {                                                                                   \
    int ss_st_ = (int)(call);                                                            \
    if (ss_st_ != 0) {                                                                   \
      fprintf(stderr, "%s:%d: %s failed (status %d): %s\n", __FILE__, __LINE__, #call,   \
              ss_st_, (errp)->msg);                                                      \
      return 1;                                                                          \
    }                                                                                    \
  } while (0)

/* As REQUIRE_OK, for test functions returning void: records a failure and
 * returns from the function. */
#define REQUIRE_OK_VOID(call, errp)                                                      \
  do {                                                                                   \
    int ss_st_ = (int)(call);                                                            \
    if (ss_st_ != 0) {                                                                   \
      ss_test_checks_++;                                                                 \
      ss_test_failures_++;                                                               \
      fprintf(stderr, "%s:%d: %s failed (status %d): %s\n", __FILE__, __LINE__, #call,   \
              ss_st_, (errp)->msg);                                                      \
      return;                                                                            \
    }                                                                                    \
  } while (0)

static inline int ss_test_done(const char *name) {
  printf("%s: %ld checks, %ld failed\n", name, ss_test_checks_, ss_test_failures_);
  return (ss_test_failures_ == 0 && ss_test_checks_ > 0) ? 0 : 1;
}

#endif
