/* status.c: status messages and error records. */
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *autobal_strerror(int status) {
  switch (status) {
#define AUTOBAL_X_CASE(name, value, msg) \
  case value:                            \
    return msg;
    AUTOBAL_STATUS_LIST(AUTOBAL_X_CASE)
#undef AUTOBAL_X_CASE
    default:
      return "unknown status";
  }
}

const char *autobal_status_name(int status) {
  switch (status) {
#define AUTOBAL_X_NAME(name, value, msg) \
  case value:                            \
    return #name;
    AUTOBAL_STATUS_LIST(AUTOBAL_X_NAME)
#undef AUTOBAL_X_NAME
    default:
      return "AUTOBAL_UNKNOWN";
  }
}

void autobal_error_clear(autobal_error *err) {
  if (err == NULL) return;
  err->status = AUTOBAL_SUCCESS;
  err->message[0] = '\0';
}

int autobal_error_set(autobal_error *err, int status, const char *fmt, ...) {
  if (err != NULL) {
    va_list ap;
    va_start(ap, fmt);
    err->status = status;
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
  }
  return status;
}

/* The shortest "%.*g" text of v that reads back as exactly v (at most 17 digits). */
static void shortest_g(char *buf, size_t len, double v) {
  int prec;
  if (!isfinite(v)) {
    snprintf(buf, len, isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
    return;
  }
  for (prec = 1; prec < 17; prec++) {
    snprintf(buf, len, "%.*g", prec, v);
    if (strtod(buf, NULL) == v) return;
  }
  snprintf(buf, len, "%.17g", v);
}

int autobal_check_param(autobal_error *err, const char *name, double value, double lo, int lo_open,
                        double hi, int hi_open, const char *unit) {
  int below = isfinite(value) && (lo_open ? !(value > lo) : !(value >= lo));
  int above = isfinite(value) && (hi_open ? !(value < hi) : !(value <= hi));
  if (isfinite(value) && !below && !above) return AUTOBAL_SUCCESS;
  {
    /* the broken bound first, then the whole range:
     * "parameter R_m = 0.7 is too large: must be < 0.5 (allowed range (0, 0.5))" */
    char v_s[32], lo_s[32], hi_s[32], why[96];
    const char *sp = unit && unit[0] ? " " : "", *u = unit ? unit : "";
    shortest_g(v_s, sizeof v_s, value);
    shortest_g(lo_s, sizeof lo_s, lo);
    shortest_g(hi_s, sizeof hi_s, hi);
    if (below)
      snprintf(why, sizeof why, "is too small: must be %s %s%s%s", lo_open ? ">" : ">=", lo_s, sp, u);
    else if (above)
      snprintf(why, sizeof why, "is too large: must be %s %s%s%s", hi_open ? "<" : "<=", hi_s, sp, u);
    else
      snprintf(why, sizeof why, "is not a finite number");
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter %s = %s%s%s %s (allowed range %c%s, %s%c)", name, v_s, sp,
                             u, why, lo_open ? '(' : '[', lo_s, hi_s, hi_open ? ')' : ']');
  }
}
