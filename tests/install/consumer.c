/* consumer.c: what a legacy C code does with an installed autobal.
 *
 * It touches the three parts of the library that need outside libraries, so that a link
 * line missing one of them fails: the pendulum verdict (pendulum.c, built with OpenMP),
 * GSL, and the HDF5 archive.  Usage: consumer [ARCHIVE.h5]; with a path it writes the
 * verdicts of a few R_w into ARCHIVE.h5 and reads them back through the library (the
 * install test reads the file once more with h5py). */
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include <autobal.h>

#define NW 3

static int write_archive(const char *path, const double *rw, const int *verdict) {
  autobal_archive *a = NULL;
  autobal_error err;
  const char *dims[1] = {"R_w"};
  const char *argv[1] = {"consumer"};
  double back[NW];
  int st, i;
  st = autobal_archive_create(path, 1, &a, &err);
  if (st != AUTOBAL_SUCCESS) {
    fprintf(stderr, "archive: %s\n", err.message);
    return 1;
  }
  st = autobal_archive_provenance(a, "install test consumer", 1, argv);
  if (st == AUTOBAL_SUCCESS) st = autobal_archive_group(a, "/consumer");
  if (st == AUTOBAL_SUCCESS)
    st = autobal_archive_coord(a, "/consumer", "R_w", NW, rw, "1", "relative speed");
  if (st == AUTOBAL_SUCCESS)
    st = autobal_archive_var_int(a, "/consumer", "verdict", 1, dims, verdict, "1",
                                 "verdict (autobal_verdict)");
  if (st != AUTOBAL_SUCCESS) {
    fprintf(stderr, "archive: %s\n", autobal_archive_errmsg(a));
    autobal_archive_discard(a);
    return 1;
  }
  if (autobal_archive_close(a, &err) != AUTOBAL_SUCCESS) {
    fprintf(stderr, "archive close: %s\n", err.message);
    return 1;
  }
  /* read back through the library */
  st = autobal_archive_open_read(path, &a, &err);
  if (st != AUTOBAL_SUCCESS) {
    fprintf(stderr, "archive open: %s\n", err.message);
    return 1;
  }
  st = autobal_archive_read_var(a, "/consumer/verdict", back, NW);
  if (st != AUTOBAL_SUCCESS) fprintf(stderr, "archive read: %s\n", autobal_archive_errmsg(a));
  autobal_archive_close(a, NULL);
  if (st != AUTOBAL_SUCCESS) return 1;
  for (i = 0; i < NW; i++)
    if (back[i] != (double)verdict[i]) {
      fprintf(stderr, "archive: verdict[%d] read back as %g, written %d\n", i, back[i], verdict[i]);
      return 1;
    }
  printf("archive %s written and read back (%d verdicts)\n", path, NW);
  return 0;
}

int main(int argc, char **argv) {
  autobal_pendulum_params p;
  autobal_error err;
  const double rw[NW] = {2.0, 3.0, 4.0};
  int verdict[NW], st, i;
  gsl_set_error_handler_off();
  /* a bad parameter is reported, not aborted on */
  st = autobal_pendulum_params_from_k(3.0, 0.7, 0.1, 0.5, 0.5, &p, &err);
  if (st != AUTOBAL_EINVAL || strstr(err.message, "R_m") == NULL) {
    fprintf(stderr, "expected EINVAL naming R_m, got %d '%s'\n", st, err.message);
    return 1;
  }
  for (i = 0; i < NW; i++) {
    st = autobal_pendulum_params_from_k(rw[i], 0.1, 0.1, 0.5, 0.5, &p, &err);
    if (st == AUTOBAL_SUCCESS) st = autobal_pendulum_verdict(&p, &verdict[i], NULL, &err);
    if (st != AUTOBAL_SUCCESS) {
      fprintf(stderr, "autobal: %s\n", err.message);
      return 1;
    }
  }
  printf("autobal %s: main motion at R_w = 3 is %s\n", autobal_version(),
         autobal_verdict_name(verdict[1]));
  if (verdict[1] != AUTOBAL_VERDICT_STABLE) return 1;
  return argc > 1 ? write_archive(argv[1], rw, verdict) : 0;
}
