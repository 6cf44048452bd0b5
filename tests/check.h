/* check.h: a minimal check harness for the test programs.
 * Every check prints what it compared and the tolerance; the program's exit
 * status is the number of failed checks (capped), so CTest sees failures. */
#ifndef AUTOBAL_TEST_CHECK_H
#define AUTOBAL_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failures_ = 0;
static int check_count_ = 0;

/* |got - want| <= atol + rtol*|want| */
#define CHECK_CLOSE(what, got, want, rtol, atol)                                                   \
  do {                                                                                             \
    double g_ = (double)(got), w_ = (double)(want);                                                \
    double tol_ = (double)(atol) + (double)(rtol) * fabs(w_);                                      \
    int ok_ = isfinite(g_) && fabs(g_ - w_) <= tol_;                                               \
    check_count_++;                                                                                \
    if (!ok_) check_failures_++;                                                                   \
    printf("%s %s: got %.15g want %.15g |diff| %.3g tol %.3g\n", ok_ ? "ok  " : "FAIL", (what), g_, \
           w_, fabs(g_ - w_), tol_);                                                               \
  } while (0)

#define CHECK(what, cond)                                          \
  do {                                                             \
    int ok_ = (cond) ? 1 : 0;                                      \
    check_count_++;                                                \
    if (!ok_) check_failures_++;                                   \
    printf("%s %s  [%s]\n", ok_ ? "ok  " : "FAIL", (what), #cond); \
  } while (0)

#define CHECK_STATUS(what, got, want)                                                            \
  do {                                                                                           \
    int g_ = (got), w_ = (want);                                                                 \
    check_count_++;                                                                              \
    if (g_ != w_) check_failures_++;                                                             \
    printf("%s %s: status %d want %d\n", g_ == w_ ? "ok  " : "FAIL", (what), g_, w_);            \
  } while (0)

/* The error message must mention `needle` (e.g. the parameter's name). */
#define CHECK_MSG(what, msg, needle)                                                           \
  do {                                                                                         \
    int ok_ = strstr((msg), (needle)) != NULL;                                                 \
    check_count_++;                                                                            \
    if (!ok_) check_failures_++;                                                               \
    printf("%s %s: message \"%s\" mentions \"%s\"\n", ok_ ? "ok  " : "FAIL", (what), (msg),    \
           (needle));                                                                          \
  } while (0)

static inline int check_summary(void) {
  printf("%d checks, %d failed\n", check_count_, check_failures_);
  return check_failures_ > 100 ? 100 : check_failures_;
}

#endif
