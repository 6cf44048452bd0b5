/* test_status.c: status codes, messages, and the range-check helper. */
#include <math.h>
#include <string.h>

#include "autobal.h"
#include "check.h"
#include "internal.h"

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
  CHECK_STATUS("NULL record allowed", autobal_check_param(NULL, "x", -1.0, 0.0, 0, 1.0, 0, ""), AUTOBAL_EINVAL);
  CHECK("version string", strlen(autobal_version()) > 0 && strcmp(autobal_version(), AUTOBAL_VERSION_STRING) == 0);
  {
    char buf[32];
    autobal_hdf5_version(buf, sizeof buf);
    CHECK("hdf5 version", buf[0] >= '1' && buf[0] <= '9');
  }
  return check_summary();
}
