/* version.c: versions for provenance records. */
#include <stdio.h>

#include <gsl/gsl_version.h>
#include <hdf5.h>

#include "autobal/version.h"

#ifndef AUTOBAL_GIT_REVISION
#define AUTOBAL_GIT_REVISION "unknown"
#endif

const char *autobal_version(void) { return AUTOBAL_VERSION_STRING; }
const char *autobal_git_revision(void) { return AUTOBAL_GIT_REVISION; }
const char *autobal_gsl_version(void) { return gsl_version; }

void autobal_hdf5_version(char *buf, unsigned long size) {
  unsigned maj = 0, min = 0, rel = 0;
  if (buf == NULL || size == 0) return;
  if (H5get_libversion(&maj, &min, &rel) < 0) {
    snprintf(buf, (size_t)size, "unknown");
    return;
  }
  snprintf(buf, (size_t)size, "%u.%u.%u", maj, min, rel);
}
