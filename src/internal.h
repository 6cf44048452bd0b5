/* internal.h: helpers shared by the library's source files (not installed). */
#ifndef AUTOBAL_INTERNAL_H
#define AUTOBAL_INTERNAL_H

#include <math.h>
#include "autobal/status.h"

#if defined(__GNUC__)
#define AUTOBAL_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define AUTOBAL_PRINTF(a, b)
#endif

/* Record status and a formatted message in err (may be NULL); returns status. */
int autobal_error_set(autobal_error *err, int status, const char *fmt, ...) AUTOBAL_PRINTF(3, 4);

/* Range check: value must be finite and inside the interval from lo to hi
 * (lo_open / hi_open: 1 for an open end).  On failure records
 * "parameter NAME = VALUE UNIT is out of range: allowed (lo, hi]" and
 * returns AUTOBAL_EINVAL; AUTOBAL_SUCCESS otherwise.  Use -INFINITY/INFINITY
 * for unbounded ends. */
int autobal_check_param(autobal_error *err, const char *name, double value, double lo, int lo_open,
                        double hi, int hi_open, const char *unit);

#endif
