/* test_status.c: status codes, messages, and the range-check helper. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int main(void) {
  autobal_error err;
  CHECK("success message", strcmp(autobal_strerror(AUTOBAL_SUCCESS), "success") == 0);
  CHECK("EINVAL name", strcmp(autobal_status_name(AUTOBAL_EINVAL), "AUTOBAL_EINVAL") == 0);
  CHECK("unknown status", strcmp(autobal_strerror(12345), "unknown status") == 0);
  CHECK("every failure code is negative", AUTOBAL_EINVAL < 0 && AUTOBAL_EIO < 0 && AUTOBAL_WARNING > 0);

  autobal_error_clear(&err);
  CHECK_STATUS("in range", autobal_check_param(&err, "R_m", 0.1, 0.0, 1, 0.5, 1, ""), AUTOBAL_SUCCESS);
  CHECK_STATUS("upper open end", autobal_check_param(&err, "R_m", 0.5, 0.0, 1, 0.5, 1, ""), AUTOBAL_EINVAL);
  CHECK_MSG("names the parameter", err.message, "R_m");
  CHECK_MSG("states the range", err.message, "(0, 0.5)");
  CHECK_STATUS("NaN rejected", autobal_check_param(&err, "mass", NAN, 0.0, 1, INFINITY, 1, "kg"), AUTOBAL_EINVAL);
  CHECK_MSG("NaN message has unit", err.message, "kg");
  CHECK_STATUS("record keeps status", err.status, AUTOBAL_EINVAL);
  /* the broken bound first, then the whole range; numbers in the shortest text that reads back */
  CHECK_STATUS("above an open upper end", autobal_check_param(&err, "R_m", 0.7, 0.0, 1, 0.5, 1, ""), AUTOBAL_EINVAL);
  CHECK_MSG("names the upper bound, then the range", err.message,
            "parameter R_m = 0.7 is too large: must be < 0.5 (allowed range (0, 0.5))");
  CHECK_STATUS("below a closed lower end", autobal_check_param(&err, "c", -1.0, 0.0, 0, INFINITY, 1, "N/m"),
               AUTOBAL_EINVAL);
  CHECK_MSG("names the lower bound with its unit", err.message,
            "parameter c = -1 N/m is too small: must be >= 0 N/m (allowed range [0, inf))");
  CHECK_STATUS("at an open lower end", autobal_check_param(&err, "M", 0.0, 0.0, 1, INFINITY, 1, "kg"), AUTOBAL_EINVAL);
  CHECK_MSG("open lower end: strict", err.message, "is too small: must be > 0 kg");
  CHECK_STATUS("above a closed upper end", autobal_check_param(&err, "k", 1.0000001, 0.0, 0, 1.0, 0, ""),
               AUTOBAL_EINVAL);
  CHECK_MSG("closed upper end: <=", err.message, "k = 1.0000001 is too large: must be <= 1 (allowed range [0, 1])");
  CHECK_STATUS("infinity", autobal_check_param(&err, "h", INFINITY, 0.0, 0, INFINITY, 1, ""), AUTOBAL_EINVAL);
  CHECK_MSG("infinity is not finite", err.message, "parameter h = inf is not a finite number (allowed range [0, inf))");
  /* 0.1 + 0.2 needs 17 significant digits to read back (0.30000000000000004); pi/2 needs 17
   * (1.5707963267948966); 0.3 needs one */
  CHECK_STATUS("0.1 + 0.2 above 0.3", autobal_check_param(&err, "x", 0.1 + 0.2, 0.0, 0, 0.3, 0, ""), AUTOBAL_EINVAL);
  CHECK_MSG("17 digits where needed, 1 where enough", err.message,
            "x = 0.30000000000000004 is too large: must be <= 0.3 (allowed");
  CHECK_STATUS("pi/2 at an open end", autobal_check_param(&err, "psi0", M_PI / 2, 0.0, 0, M_PI / 2, 1, "rad"),
               AUTOBAL_EINVAL);
  CHECK_MSG("value and bound both exact", err.message,
            "psi0 = 1.5707963267948966 rad is too large: must be < 1.5707963267948966 rad");
  {
    /* every value printed reads back as itself */
    const double v[] = {1.0 / 3.0, 2.0 / 3.0, 1e-300 * 1.1, 6.02214076e23, 0.1 * 3, -7.0 / 9.0, 5e-324};
    size_t i;
    int all = 1;
    for (i = 0; i < sizeof v / sizeof v[0]; i++) {
      const char *eq;
      autobal_check_param(&err, "v", v[i], 1.0, 1, 1.0, 1, "");
      eq = strstr(err.message, "v = ");
      if (!eq || strtod(eq + 4, NULL) != v[i]) all = 0;
      printf("     %.17g -> \"%s\"\n", v[i], err.message);
    }
    CHECK("values read back exactly from the message", all);
  }
  CHECK_STATUS("NULL record allowed", autobal_check_param(NULL, "x", -1.0, 0.0, 0, 1.0, 0, ""), AUTOBAL_EINVAL);
  CHECK("version string", strlen(autobal_version()) > 0 && strcmp(autobal_version(), AUTOBAL_VERSION_STRING) == 0);
  {
    char buf[32];
    autobal_hdf5_version(buf, sizeof buf);
    CHECK("hdf5 version", buf[0] >= '1' && buf[0] <= '9');
  }
  return check_summary();
}
