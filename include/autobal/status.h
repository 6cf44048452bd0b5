/* autobal/status.h: status codes, their messages, and the error record.
 *
 * Every library function that can fail returns an int status:
 *   0          AUTOBAL_SUCCESS
 *   < 0        a failure (the operation did not complete; see each function
 *              for the state it leaves behind)
 *   > 0        informational (the operation completed, with something to note)
 * Names and messages come from one list, AUTOBAL_STATUS_LIST, so that
 * autobal_strerror() and autobal_status_name() can never disagree with the
 * enum.  The library never prints, never aborts and never calls exit().
 *
 * GSL: the library validates inputs before calling GSL and checks every GSL
 * return code, but GSL's default error handler aborts the process on some
 * internal failures.  A host program should call gsl_set_error_handler_off()
 * once at start-up (the autobal apps do); the library never changes global
 * GSL state itself.
 */
#ifndef AUTOBAL_STATUS_H
#define AUTOBAL_STATUS_H

#include <stddef.h>
#include "autobal/export.h"

AUTOBAL_BEGIN_DECLS

/* X(name, value, message) */
#define AUTOBAL_STATUS_LIST(X)                                                        \
  X(AUTOBAL_SUCCESS,     0, "success")                                                \
  X(AUTOBAL_WARNING,     1, "completed with a warning (see the error message)")       \
  X(AUTOBAL_EVENT,       2, "stopped at a requested event")                           \
  X(AUTOBAL_EINVAL,     -1, "invalid argument or parameter out of range")             \
  X(AUTOBAL_ENOMEM,     -2, "out of memory")                                          \
  X(AUTOBAL_ENUMERIC,   -3, "numerical failure (singular matrix, no convergence)")    \
  X(AUTOBAL_ESTEP,      -4, "ODE step size underflow or stepper failure")             \
  X(AUTOBAL_EMAXSTEPS,  -5, "maximum number of ODE steps reached")                    \
  X(AUTOBAL_ERHS,       -6, "right-hand side evaluation failed")                      \
  X(AUTOBAL_EIO,        -7, "input/output error (file or HDF5)")                      \
  X(AUTOBAL_ECONFIG,    -8, "invalid configuration")                                  \
  X(AUTOBAL_ECANCELLED, -9, "cancelled by the caller")                                \
  X(AUTOBAL_EFORMAT,   -10, "not an autobal archive, or a damaged one")               \
  X(AUTOBAL_EEXIST,    -11, "output file exists")                                     \
  X(AUTOBAL_EUNSUPPORTED, -12, "not supported for these parameters")

typedef enum autobal_status {
#define AUTOBAL_X_ENUM(name, value, msg) name = value,
  AUTOBAL_STATUS_LIST(AUTOBAL_X_ENUM)
#undef AUTOBAL_X_ENUM
  AUTOBAL_STATUS_END_ = -9999
} autobal_status;

/* Static message of a status code ("unknown status" for other values).
 * Never NULL; the string is owned by the library. */
AUTOBAL_API const char *autobal_strerror(int status);
/* Name of a status code, e.g. "AUTOBAL_EINVAL"; "AUTOBAL_UNKNOWN" otherwise.
 * Never NULL; a static string owned by the library. */
AUTOBAL_API const char *autobal_status_name(int status);

/* An error record: the last status and a human-readable message that names
 * the parameter, its value and the allowed range (or carries the GSL/HDF5
 * text it came from).  Plain data, owned by the caller or embedded in a
 * handle; functions that take an `autobal_error *` accept NULL. */
#define AUTOBAL_ERRMSG_SIZE 512
typedef struct autobal_error {
  int status;
  char message[AUTOBAL_ERRMSG_SIZE];
} autobal_error;

/* Reset an error record to AUTOBAL_SUCCESS with an empty message (nothing
 * for NULL).  Messages longer than AUTOBAL_ERRMSG_SIZE - 1 characters are
 * truncated when recorded; message is always NUL-terminated. */
AUTOBAL_API void autobal_error_clear(autobal_error *err);

AUTOBAL_END_DECLS

#endif
