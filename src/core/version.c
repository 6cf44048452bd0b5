/* version.c: versions for provenance records. */
#include <gsl/gsl_version.h>

#include "autobal/version.h"

#ifndef AUTOBAL_GIT_REVISION
#define AUTOBAL_GIT_REVISION "unknown"
#endif

const char *autobal_version(void) { return AUTOBAL_VERSION_STRING; }
const char *autobal_git_revision(void) { return AUTOBAL_GIT_REVISION; }
const char *autobal_gsl_version(void) { return gsl_version; }

/* autobal_hdf5_version() is defined in src/archive/archive.c: it calls HDF5, which this library does
 * only under the archive module's process-wide HDF5 lock. */
