/* status.c: status messages and error records. */
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
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

int autobal_check_param(autobal_error *err, const char *name, double value, double lo, int lo_open,
                        double hi, int hi_open, const char *unit) {
  int ok = isfinite(value);
  if (ok) ok = lo_open ? value > lo : value >= lo;
  if (ok) ok = hi_open ? value < hi : value <= hi;
  if (ok) return AUTOBAL_SUCCESS;
  {
    char lo_s[32], hi_s[32];
    if (isinf(lo)) snprintf(lo_s, sizeof lo_s, "-inf");
    else snprintf(lo_s, sizeof lo_s, "%.6g", lo);
    if (isinf(hi)) snprintf(hi_s, sizeof hi_s, "inf");
    else snprintf(hi_s, sizeof hi_s, "%.6g", hi);
    return autobal_error_set(err, AUTOBAL_EINVAL, "parameter %s = %.16g%s%s is out of range: allowed %c%s, %s%c",
                             name, value, unit && unit[0] ? " " : "", unit ? unit : "",
                             lo_open ? '(' : '[', lo_s, hi_s, hi_open ? ')' : ']');
  }
}
