/* test_archive.c: the HDF5 archive module.
 *
 * Without arguments: writes archives in the build's test directory and reads them back
 * with the plain HDF5 C API (independent of the library's reading side) and with the
 * library's reading side; compares exactly; provokes every error path.
 * With `--write FILE`: writes the sample archive checked by tests/archive_readback.py
 * (values there are recomputed from the same formulas, sample_* below). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include "autobal.h"
#include "check.h"

#ifndef AUTOBAL_TEST_TMP_DIR
#define AUTOBAL_TEST_TMP_DIR "."
#endif

static int exists(const char *p) {
  struct stat st;
  return stat(p, &st) == 0;
}

/* ---------------------------------------------------------------------- */
/* Plain HDF5 readers (independent of archive.c)                           */
/* ---------------------------------------------------------------------- */

/* Read a scalar vlen string attribute; returns malloc'ed copy or NULL.  *is_vlen_utf8
 * reports whether it is stored as a variable-length UTF-8 string. */
static char *h5_attr_str(hid_t file, const char *obj, const char *name, int *is_vlen_utf8) {
  hid_t o = -1, at = -1, ft = -1, mt = -1, sp = -1;
  char *p = NULL, *res = NULL;
  if (is_vlen_utf8) *is_vlen_utf8 = 0;
  o = H5Oopen(file, obj, H5P_DEFAULT);
  if (o < 0) return NULL;
  if (H5Aexists(o, name) <= 0) goto done;
  at = H5Aopen(o, name, H5P_DEFAULT);
  ft = H5Aget_type(at);
  sp = H5Aget_space(at);
  if (H5Tget_class(ft) != H5T_STRING || H5Tis_variable_str(ft) <= 0) goto done;
  if (is_vlen_utf8)
    *is_vlen_utf8 = H5Tget_cset(ft) == H5T_CSET_UTF8 && H5Sget_simple_extent_type(sp) == H5S_SCALAR;
  mt = H5Tcopy(H5T_C_S1);
  H5Tset_size(mt, H5T_VARIABLE);
  H5Tset_cset(mt, H5T_CSET_UTF8);
  if (H5Aread(at, mt, &p) < 0) goto done;
  res = malloc(strlen(p) + 1);
  if (res) strcpy(res, p);
  H5free_memory(p);
done:
  if (mt >= 0) H5Tclose(mt);
  if (sp >= 0) H5Sclose(sp);
  if (ft >= 0) H5Tclose(ft);
  if (at >= 0) H5Aclose(at);
  H5Oclose(o);
  return res;
}

static int h5_attr_str_is(hid_t file, const char *obj, const char *name, const char *want) {
  int vu = 0;
  char *s = h5_attr_str(file, obj, name, &vu);
  int ok = s != NULL && vu && strcmp(s, want) == 0;
  if (!ok) printf("     %s@%s = \"%s\" (vlen utf8 %d), want \"%s\"\n", obj, name, s ? s : "(missing)", vu, want);
  free(s);
  return ok;
}

static double h5_attr_double(hid_t file, const char *obj, const char *name) {
  double v = NAN;
  hid_t o = H5Oopen(file, obj, H5P_DEFAULT), at;
  if (o < 0) return v;
  at = H5Aopen(o, name, H5P_DEFAULT);
  if (at >= 0) {
    if (H5Aread(at, H5T_NATIVE_DOUBLE, &v) < 0) v = NAN;
    H5Aclose(at);
  }
  H5Oclose(o);
  return v;
}

/* Read a whole dataset as double; returns malloc'ed buffer, *n elements. */
static double *h5_read(hid_t file, const char *path, size_t *n) {
  hid_t ds = H5Dopen2(file, path, H5P_DEFAULT), sp;
  hssize_t np;
  double *buf;
  *n = 0;
  if (ds < 0) return NULL;
  sp = H5Dget_space(ds);
  np = H5Sget_simple_extent_npoints(sp);
  H5Sclose(sp);
  buf = malloc((size_t)(np > 0 ? np : 1) * sizeof *buf);
  if (buf && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    free(buf);
    buf = NULL;
  }
  H5Dclose(ds);
  *n = (size_t)np;
  return buf;
}

/* 1 if dimension scale `scale` is attached to dimension idx of `var`. */
static int h5_attached(hid_t file, const char *var, const char *scale, unsigned idx) {
  hid_t v = H5Dopen2(file, var, H5P_DEFAULT), s = H5Dopen2(file, scale, H5P_DEFAULT);
  int r = v >= 0 && s >= 0 && H5DSis_attached(v, s, idx) > 0;
  if (v >= 0) H5Dclose(v);
  if (s >= 0) H5Dclose(s);
  return r;
}

static int h5_scale_name_is(hid_t file, const char *path, const char *want) {
  char buf[256] = "";
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  int ok;
  if (d < 0) return 0;
  ok = H5DSis_scale(d) > 0 && H5DSget_scale_name(d, buf, sizeof buf) > 0 && strcmp(buf, want) == 0;
  H5Dclose(d);
  return ok;
}

/* Layout and number of filters of a dataset. */
static void h5_layout(hid_t file, const char *path, H5D_layout_t *layout, int *nfilters) {
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT), p;
  *layout = H5D_LAYOUT_ERROR;
  *nfilters = -1;
  if (d < 0) return;
  p = H5Dget_create_plist(d);
  *layout = H5Pget_layout(p);
  *nfilters = H5Pget_nfilters(p);
  H5Pclose(p);
  H5Dclose(d);
}

static int h5_maxdim_unlimited(hid_t file, const char *path) {
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT), sp;
  hsize_t cur = 0, mx = 0;
  int r;
  if (d < 0) return 0;
  sp = H5Dget_space(d);
  r = H5Sget_simple_extent_ndims(sp) == 1 && H5Sget_simple_extent_dims(sp, &cur, &mx) == 1 && mx == H5S_UNLIMITED;
  H5Sclose(sp);
  H5Dclose(d);
  return r;
}

/* ---------------------------------------------------------------------- */
/* The sample archive (also checked by archive_readback.py)                */
/* ---------------------------------------------------------------------- */

#define SAMPLE_NOMEGA 5
#define SAMPLE_NROOT 3
#define SAMPLE_NROWS 10000 /* > 2 series chunks */
static double sample_omega(size_t i) { return 10.0 * (double)(i + 1); }          /* rad/s */
static double sample_re(size_t i, size_t j) { return sample_omega(i) + 0.25 * (double)j; }
static int sample_flag(size_t i, size_t j) { return (int)(i * 10 + j) - 7; }

static int write_sample(const char *path) {
  autobal_archive *a = NULL;
  autobal_archive_series *s = NULL;
  autobal_error err;
  double omega[SAMPLE_NOMEGA], re[SAMPLE_NOMEGA * SAMPLE_NROOT], lam[SAMPLE_NOMEGA];
  int flag[SAMPLE_NOMEGA * SAMPLE_NROOT];
  const char *d2[2] = {"omega", "root"};
  const char *d1[1] = {"omega"};
  const char *names[2] = {"x", "y"}, *units[2] = {"m", "m"}, *lns[2] = {"displacement x", NULL};
  const char *argv[3] = {"test_archive", "--write", path};
  const double par2[2] = {1.5, -2.0};
  size_t i, j;
  int rc = 0;
  for (i = 0; i < SAMPLE_NOMEGA; i++) {
    omega[i] = sample_omega(i);
    lam[i] = -0.5 * omega[i];
    for (j = 0; j < SAMPLE_NROOT; j++) {
      re[i * SAMPLE_NROOT + j] = sample_re(i, j);
      flag[i * SAMPLE_NROOT + j] = sample_flag(i, j);
    }
  }
  rc |= autobal_archive_create(path, 1, &a, &err);
  if (rc) {
    fprintf(stderr, "create: %s\n", err.message);
    return 1;
  }
  rc |= autobal_archive_provenance(a, "archive sample", 3, argv);
  rc |= autobal_archive_group(a, "/pendulum/map");
  rc |= autobal_archive_attr_double(a, "/pendulum", "mass", 0.5, "kg");
  rc |= autobal_archive_attr_int(a, "/pendulum", "n_pendulums", 2);
  rc |= autobal_archive_attr_string(a, "/pendulum", "model", "two pendulums");
  rc |= autobal_archive_attr_double_array(a, "/pendulum", "pair", 2, par2, "1");
  rc |= autobal_archive_coord(a, "/pendulum/map", "omega", SAMPLE_NOMEGA, omega, "rad/s", "rotor speed");
  rc |= autobal_archive_dim(a, "/pendulum/map", "root", SAMPLE_NROOT, "root index");
  rc |= autobal_archive_var(a, "/pendulum/map", "re", 2, d2, re, "1/s", "real part");
  rc |= autobal_archive_var_int(a, "/pendulum/map", "flag", 2, d2, flag, "1", "flag");
  rc |= autobal_archive_var(a, "/pendulum/map", "omega_crit", 0, NULL, omega, "rad/s", "critical speed");
  rc |= autobal_archive_var(a, "/pendulum/map/sub", "lam", 1, d1, lam, "1/s", "uses parent dim");
  rc |= autobal_archive_series_open(a, "/rotor/transient", "time", "s", "time", 2, names, units, lns, &s);
  for (i = 0; i < SAMPLE_NROWS && rc == 0; i++) {
    double t = 1e-3 * (double)i, row[2];
    row[0] = (double)i;
    row[1] = -0.5 * (double)i;
    rc |= autobal_archive_series_append(s, 1, &t, row);
  }
  rc |= autobal_archive_series_close(s);
  if (rc) {
    fprintf(stderr, "writing the sample failed: %s\n", autobal_archive_errmsg(a));
    autobal_archive_discard(a);
    return 1;
  }
  if (autobal_archive_close(a, &err) != 0) {
    fprintf(stderr, "close: %s\n", err.message);
    return 1;
  }
  return 0;
}

/* ---------------------------------------------------------------------- */
/* Checks                                                                   */
/* ---------------------------------------------------------------------- */

static int silent_handler_calls = 0;
static herr_t counting_handler(hid_t estack, void *data) {
  (void)estack;
  (void)data;
  silent_handler_calls++;
  return 0;
}

static int list_count_cb(const char *name, int is_group, void *ctx) {
  int *c = (int *)ctx;
  (void)name;
  c[is_group ? 1 : 0]++;
  return 0;
}

static int list_stop_cb(const char *name, int is_group, void *ctx) {
  (void)is_group;
  (void)ctx;
  return strcmp(name, "b") == 0 ? 42 : 0;
}

static void copy_prefix(const char *src, const char *dst, long nbytes) {
  FILE *in = fopen(src, "rb"), *out = fopen(dst, "wb");
  long k;
  int c;
  for (k = 0; in && out && k < nbytes && (c = fgetc(in)) != EOF; k++) fputc(c, out);
  if (in) fclose(in);
  if (out) fclose(out);
}

static long file_size(const char *p) {
  struct stat st;
  return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

/* ---------------------------------------------------------------------- */
/* The series writer thread (archive.c writes full series buffers in a      */
/* background thread; every HDF5 call of the module holds one process lock) */
/* ---------------------------------------------------------------------- */
/* Also run under ThreadSanitizer (no OpenMP: libgomp is not instrumented):
 *   cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAUTOBAL_OPENMP=OFF \
 *     -DAUTOBAL_BUILD_APPS=OFF "-DCMAKE_C_FLAGS=-fsanitize=thread -g -O1" \
 *     -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread
 *   cmake --build build-tsan --target test_archive
 *   TSAN_OPTIONS=halt_on_error=1 build-tsan/tests/test_archive
 * HDF5 itself is not instrumented: TSan checks the module's own hand-over between the
 * caller and the writer (it reports races when series_idle does not wait). */

#define W_NV 6
#define W_ROWS 100003 /* 24 full buffers of AUTOBAL_ARCHIVE_SERIES_ROWS and a partial one */
#define W_CAP AUTOBAL_ARCHIVE_SERIES_ROWS

/* Values of row i: exact binary fractions, and in the last variable an arbitrary 64-bit
 * pattern (NaNs with payloads, infinities, subnormals, -0 among them): the file must
 * hold the appended bits. */
static uint64_t w_mix(uint64_t x) { /* splitmix64 */
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
static double w_time(size_t i, unsigned salt) { return 0.5 * (double)i + (double)salt; }
static double w_value(size_t i, size_t j, size_t nv, unsigned salt) {
  if (j == nv - 1) {
    uint64_t x = w_mix((uint64_t)i ^ ((uint64_t)salt << 40));
    double d;
    memcpy(&d, &x, sizeof d);
    return d;
  }
  return (double)i * (double)(j + 1) + 0.125 * (double)j - (double)salt;
}
static void w_row(size_t i, size_t nv, unsigned salt, double *row) {
  size_t j;
  for (j = 0; j < nv; j++) row[j] = w_value(i, j, nv, salt);
}

/* 1 if dataset `path` holds exactly (bitwise) n values f(i) of the series. */
static int w_column_is(hid_t f, const char *path, size_t n, size_t j, size_t nv, unsigned salt) {
  size_t got = 0, i;
  double *v = h5_read(f, path, &got);
  int ok = v != NULL && got == n;
  for (i = 0; ok && i < n; i++) {
    double want = j == (size_t)-1 ? w_time(i, salt) : w_value(i, j, nv, salt);
    ok = memcmp(&v[i], &want, sizeof want) == 0;
    if (!ok) printf("     %s[%zu] differs\n", path, i);
  }
  free(v);
  return ok;
}

/* A second archive written by another thread while the main thread streams its own:
 * one row per append, then close.  Returns 0 or the first failing status. */
typedef struct {
  char path[1100];
  int status;
  char msg[AUTOBAL_ERRMSG_SIZE];
  size_t length;
} w_other;

static void *w_other_main(void *arg) {
  w_other *o = (w_other *)arg;
  const char *nm[3] = {"p", "q", "r"}, *un[3] = {"m", "1", "1"};
  autobal_archive *a = NULL;
  autobal_archive_series *s = NULL;
  autobal_error err;
  size_t i;
  int rc = autobal_archive_create(o->path, 1, &a, &err);
  if (rc != AUTOBAL_SUCCESS) {
    o->status = rc;
    snprintf(o->msg, sizeof o->msg, "%s", err.message);
    return NULL;
  }
  rc = autobal_archive_series_open(a, "/other", "t", "s", NULL, 3, nm, un, NULL, &s);
  for (i = 0; i < W_ROWS && rc == AUTOBAL_SUCCESS; i++) {
    double t = w_time(i, 7), row[3];
    w_row(i, 3, 7, row);
    rc = autobal_archive_series_append(s, 1, &t, row);
    /* many small HDF5 operations from this thread while the writers compress */
    if (rc == AUTOBAL_SUCCESS && i % 64 == 0) rc = autobal_archive_attr_int(a, "/other", "rows", (long)i);
  }
  o->length = autobal_archive_series_length(s);
  if (rc != AUTOBAL_SUCCESS) snprintf(o->msg, sizeof o->msg, "%s", autobal_archive_errmsg(a));
  if (rc == AUTOBAL_SUCCESS) rc = autobal_archive_close(a, &err);
  else autobal_archive_discard(a);
  if (rc != AUTOBAL_SUCCESS && o->msg[0] == '\0') snprintf(o->msg, sizeof o->msg, "%s", err.message);
  o->status = rc;
  return NULL;
}

/* List callback that calls the archive again (the HDF5 lock must not be held). */
typedef struct {
  autobal_archive *a;
  int n, has_units;
} w_list_ctx;
static int w_list_cb(const char *name, int is_group, void *vctx) {
  w_list_ctx *c = (w_list_ctx *)vctx;
  char p[300];
  (void)is_group;
  snprintf(p, sizeof p, "/w/a/%s", name);
  c->n++;
  c->has_units += autobal_archive_has(c->a, p, "units");
  return 0;
}

/* Write failures inside the writer thread, in a child process (see the file-size limit
 * test in main for why).  mode 0: the failure comes back from _series_flush; mode 1:
 * from _series_append. */
static void w_failure_child(const char *p, int mode) {
  autobal_archive *a = NULL;
  autobal_archive_series *s = NULL;
  autobal_error err;
  struct rlimit old_lim, lim;
  const char *nm[2] = {"u", "v"}, *un[2] = {"1", "1"};
  char tmp[1200];
  size_t i, n_ok = 0, len;
  int rc = AUTOBAL_SUCCESS;
  char errpath[1200];
  int errfd, savefd;
  snprintf(tmp, sizeof tmp, "%s.partial-%ld", p, (long)getpid());
  /* HDF5 keeps one error stack and automatic handler per thread (thread-safe builds):
   * the writer thread starts with HDF5's printing handler, which the library must
   * silence there too.  Catch anything printed on stderr. */
  snprintf(errpath, sizeof errpath, "%s.stderr-%ld", p, (long)getpid());
  fflush(stderr);
  savefd = dup(2);
  errfd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (errfd >= 0) {
    dup2(errfd, 2);
    close(errfd);
  }
  signal(SIGXFSZ, SIG_IGN);
  if (getrlimit(RLIMIT_FSIZE, &old_lim) != 0 || autobal_archive_create(p, 1, &a, &err) != AUTOBAL_SUCCESS ||
      autobal_archive_series_open(a, "/e", "t", "s", NULL, 2, nm, un, NULL, &s) != AUTOBAL_SUCCESS) {
    CHECK("[writer child] set up", 0);
    return;
  }
  /* one buffer of incompressible rows (the last variable is random bits) fits */
  for (i = 0; i < W_CAP && rc == AUTOBAL_SUCCESS; i++) {
    double t = w_time(i, 0), row[2];
    w_row(i, 2, 0, row);
    rc = autobal_archive_series_append(s, 1, &t, row);
  }
  CHECK_STATUS("[writer child] first buffer appended", rc, AUTOBAL_SUCCESS);
  CHECK_STATUS("[writer child] and flushed", autobal_archive_series_flush(s), AUTOBAL_SUCCESS);
  lim = old_lim;
  lim.rlim_cur = (rlim_t)file_size(tmp) + (mode == 0 ? 1024 : 200 * 1024);
  CHECK("[writer child] file-size limit set", file_size(tmp) > 0 && setrlimit(RLIMIT_FSIZE, &lim) == 0);
  if (mode == 0) {
    /* A full buffer is handed to the writer: the append cannot know yet that the write
     * fails (it would in a synchronous design); the flush waits and reports it. */
    for (i = W_CAP; i < 2 * W_CAP && rc == AUTOBAL_SUCCESS; i++) {
      double t = w_time(i, 0), row[2];
      w_row(i, 2, 0, row);
      rc = autobal_archive_series_append(s, 1, &t, row);
    }
    CHECK_STATUS("[writer child] append of the buffer that will fail returns (written in the background)", rc,
                 AUTOBAL_SUCCESS);
    rc = autobal_archive_series_flush(s);
    printf("     flush after a failed background write: %d %s\n", rc, autobal_archive_errmsg(a));
    CHECK_STATUS("[writer child] flush reports the writer's failure", rc, AUTOBAL_EIO);
    len = autobal_archive_series_length(s);
    CHECK("[writer child] length: the rows in the file before the failure", len == W_CAP);
  } else {
    /* Rows one at a time until an append reports the failure of a buffer written in
     * the background.  It is the buffer after the `len` rows in the file; the caller
     * cannot have appended more than that buffer and a full second one. */
    for (i = W_CAP; i < 200 * W_CAP; i++) {
      double t = w_time(i, 0), row[2];
      w_row(i, 2, 0, row);
      rc = autobal_archive_series_append(s, 1, &t, row);
      if (rc != AUTOBAL_SUCCESS) break;
      n_ok = i + 1;
    }
    printf("     append after a failed background write (row %zu): %d %s\n", i, rc, autobal_archive_errmsg(a));
    CHECK_STATUS("[writer child] an append reports the writer's failure", rc, AUTOBAL_EIO);
    len = autobal_archive_series_length(s);
    printf("     rows accepted %zu, rows in the file %zu\n", n_ok, len);
    CHECK("[writer child] length: whole buffers written before the failure", len >= W_CAP && len % W_CAP == 0);
    CHECK("[writer child] reported no earlier than the failing buffer was handed over", n_ok >= len + W_CAP);
    CHECK("[writer child] reported no later than the next buffer was handed over", n_ok < len + 2 * W_CAP);
  }
  CHECK_MSG("[writer child] names the series", autobal_archive_errmsg(a), "series '/e/t'");
  CHECK_MSG("[writer child] with the HDF5 text", autobal_archive_errmsg(a), "HDF5");
  CHECK_MSG("[writer child] with the OS reason", autobal_archive_errmsg(a), "File too large");
  CHECK("[writer child] message on one line", strchr(autobal_archive_errmsg(a), '\n') == NULL);
  {
    double t = 0.0, row[2] = {0.0, 0.0};
    CHECK_STATUS("[writer child] later appends refused", autobal_archive_series_append(s, 1, &t, row),
                 AUTOBAL_EIO);
    CHECK_MSG("[writer child] as unusable", autobal_archive_errmsg(a), "unusable after an earlier write failure");
    CHECK("[writer child] length unchanged", autobal_archive_series_length(s) == len);
  }
  CHECK_STATUS("[writer child] flush refused", autobal_archive_series_flush(s), AUTOBAL_EIO);
  rc = autobal_archive_close(a, &err);
  printf("     close: %s\n", err.message);
  CHECK_STATUS("[writer child] close fails with EIO", rc, AUTOBAL_EIO);
  CHECK("[writer child] temporary kept for inspection", exists(tmp) && !exists(p));
  CHECK("[writer child] no HDF5 auto-handler call", silent_handler_calls == 0);
  setrlimit(RLIMIT_FSIZE, &old_lim);
  fflush(stderr);
  if (savefd >= 0) {
    dup2(savefd, 2);
    close(savefd);
  }
  printf("     stderr while failing: %ld bytes\n", file_size(errpath));
  CHECK("[writer child] nothing printed on stderr (HDF5 silenced in the writer thread too)",
        errfd >= 0 && file_size(errpath) == 0);
  remove(errpath);
  remove(tmp);
}

static void test_series_writer(const char *base) {
  char pa[1100], pc[1100], tmpc[1200];
  w_other other;
  pthread_t th;
  int th_ok;
  autobal_archive *a = NULL, *c = NULL;
  autobal_archive_series *s1 = NULL, *s2 = NULL, *sc = NULL;
  autobal_error err;
  const char *nm[W_NV] = {"v0", "v1", "v2", "v3", "v4", "bits"};
  const char *un[W_NV] = {"m", "m", "1", "1", "s", "1"};
  static const size_t batches[] = {1, 7, 4095, 4096, 4097, 1, 12289, 333, 2, 8191};
  static double rows[12289 * W_NV], t[12289], rows2[12289 * 2], *tcopy;
  size_t done = 0, done2 = 0, b = 0, i;
  int rc = AUTOBAL_SUCCESS, rc2 = AUTOBAL_SUCCESS, flushed = 0, varred = 0;

  printf("---- series writer thread ----\n");
  snprintf(pa, sizeof pa, "%s.writer_a", base);
  snprintf(other.path, sizeof other.path, "%s.writer_b", base);
  snprintf(pc, sizeof pc, "%s.writer_c", base);
  other.status = -1000;
  other.msg[0] = '\0';
  other.length = 0;
  tcopy = malloc(W_ROWS * sizeof *tcopy);
  CHECK("allocated", tcopy != NULL);
  if (tcopy == NULL) return;
  for (i = 0; i < W_ROWS; i++) tcopy[i] = w_time(i, 0);

  /* archive B from a second thread, concurrently */
  th_ok = pthread_create(&th, NULL, w_other_main, &other) == 0;
  CHECK("second writing thread started", th_ok);

  CHECK_STATUS("create A", autobal_archive_create(pa, 1, &a, &err), AUTOBAL_SUCCESS);
  if (a == NULL) {
    if (th_ok) pthread_join(th, NULL);
    free(tcopy);
    return;
  }
  CHECK_STATUS("series 1 (6 variables)", autobal_archive_series_open(a, "/w/a", "t", "s", NULL, W_NV, nm, un, NULL, &s1),
               AUTOBAL_SUCCESS);
  CHECK_STATUS("series 2 (2 variables)", autobal_archive_series_open(a, "/w/b", "t", "s", NULL, 2, nm, un, NULL, &s2),
               AUTOBAL_SUCCESS);
  /* Batches of 1 row to 3 buffers, the two series interleaved; meanwhile a flush at a
   * row count that is not a chunk multiple, attributes, a variable over the series
   * dimension (it must see every row appended before it) and a listing. */
  while (done < W_ROWS && rc == AUTOBAL_SUCCESS && rc2 == AUTOBAL_SUCCESS) {
    size_t n = batches[b++ % (sizeof batches / sizeof batches[0])], n2;
    if (n > W_ROWS - done) n = W_ROWS - done;
    for (i = 0; i < n; i++) {
      t[i] = w_time(done + i, 0);
      w_row(done + i, W_NV, 0, rows + i * W_NV);
    }
    rc = autobal_archive_series_append(s1, n, t, rows);
    n2 = n / 2 + 1;
    for (i = 0; i < n2; i++) {
      t[i] = w_time(done2 + i, 3);
      w_row(done2 + i, 2, 3, rows2 + i * 2);
    }
    rc2 = autobal_archive_series_append(s2, n2, t, rows2);
    done += n;
    done2 += n2;
    if (rc == AUTOBAL_SUCCESS && !flushed && done > 3 * W_CAP) {
      rc = autobal_archive_series_flush(s1);
      flushed = 1;
      printf("     flushed series 1 at %zu rows\n", done);
    }
    for (i = 0; i < 64 && rc == AUTOBAL_SUCCESS; i++)
      rc = autobal_archive_attr_double(a, "/w", "rows", (double)done, "1");
    if (rc == AUTOBAL_SUCCESS && !varred && done > W_ROWS / 2) {
      const char *d1[1] = {"t"};
      rc = autobal_archive_var(a, "/w/a", "tcopy", 1, d1, tcopy, "s", NULL);
      varred = (int)done;
    }
  }
  CHECK_STATUS("streamed series 1", rc, AUTOBAL_SUCCESS);
  CHECK_STATUS("streamed series 2", rc2, AUTOBAL_SUCCESS);
  if (rc != AUTOBAL_SUCCESS || rc2 != AUTOBAL_SUCCESS) printf("     %s\n", autobal_archive_errmsg(a));
  CHECK("series 1 length", autobal_archive_series_length(s1) == W_ROWS);
  CHECK("series 2 length", autobal_archive_series_length(s2) == done2);
  {
    w_list_ctx lc = {a, 0, 0};
    CHECK_STATUS("list while streaming, callback calling the archive",
                 autobal_archive_list(a, "/w/a", w_list_cb, &lc), AUTOBAL_SUCCESS);
    CHECK("listed t, 6 variables, tcopy; all with units", lc.n == W_NV + 2 && lc.has_units == W_NV + 2);
  }
  CHECK_STATUS("close series 1", autobal_archive_series_close(s1), AUTOBAL_SUCCESS);
  /* series 2 stays open: closed by archive_close, which waits for the writer */
  CHECK_STATUS("close A", autobal_archive_close(a, &err), AUTOBAL_SUCCESS);
  if (th_ok) pthread_join(th, NULL);
  CHECK_STATUS("archive B written by another thread meanwhile", other.status, AUTOBAL_SUCCESS);
  if (other.status != AUTOBAL_SUCCESS) printf("     %s\n", other.msg);
  CHECK("archive B series length", other.length == W_ROWS);

  /* read back with plain HDF5 */
  {
    hid_t f = H5Fopen(pa, H5F_ACC_RDONLY, H5P_DEFAULT);
    char p[64];
    size_t j, n = 0;
    double *v;
    int ok = f >= 0;
    CHECK("A opens", f >= 0);
    if (ok) {
      CHECK("series 1 t: every row, bitwise", w_column_is(f, "/w/a/t", W_ROWS, (size_t)-1, W_NV, 0));
      for (j = 0; j < W_NV; j++) {
        char what[100];
        snprintf(p, sizeof p, "/w/a/%s", nm[j]);
        snprintf(what, sizeof what, "series 1 %s: every row, bitwise", nm[j]);
        CHECK(what, w_column_is(f, p, W_ROWS, j, W_NV, 0));
      }
      CHECK("series 2 t: every row, bitwise", w_column_is(f, "/w/b/t", done2, (size_t)-1, 2, 3));
      CHECK("series 2 v0: every row, bitwise", w_column_is(f, "/w/b/v0", done2, 0, 2, 3));
      CHECK("series 2 v1: every row, bitwise", w_column_is(f, "/w/b/v1", done2, 1, 2, 3));
      v = h5_read(f, "/w/a/tcopy", &n);
      printf("     variable made at %d rows has %zu\n", varred, n);
      CHECK("variable over the series dim made mid-stream has the rows appended before it",
            v != NULL && varred > 0 && n == (size_t)varred);
      free(v);
      {
        hid_t d = H5Dopen2(f, "/w/a/v1", H5P_DEFAULT), pl = d >= 0 ? H5Dget_create_plist(d) : -1;
        hsize_t ch = 0;
        int ok2 = pl >= 0 && H5Pget_layout(pl) == H5D_CHUNKED && H5Pget_chunk(pl, 1, &ch) == 1 &&
                  ch == W_CAP && H5Pget_nfilters(pl) == 2;
        if (ok2) {
          unsigned flags, cd[4];
          size_t ncd = 4;
          ok2 = H5Pget_filter2(pl, 0, &flags, &ncd, cd, 0, NULL, NULL) == H5Z_FILTER_SHUFFLE;
          ncd = 4;
          ok2 = ok2 && H5Pget_filter2(pl, 1, &flags, &ncd, cd, 0, NULL, NULL) == H5Z_FILTER_DEFLATE;
        }
        CHECK("series columns: chunks of AUTOBAL_ARCHIVE_SERIES_ROWS rows, shuffle + deflate", ok2);
        if (pl >= 0) H5Pclose(pl);
        if (d >= 0) H5Dclose(d);
      }
      H5Fclose(f);
      /* the random-bits column is incompressible; the rest compresses */
      printf("     A: %ld bytes for %zu raw\n", file_size(pa), (size_t)(W_ROWS * (W_NV + 1) + done2 * 3) * 8);
      CHECK("A is compressed", file_size(pa) > 0 && (size_t)file_size(pa) < (W_ROWS * (W_NV + 1) + done2 * 3) * 8 / 2);
    }
    f = H5Fopen(other.path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK("B opens", f >= 0);
    if (f >= 0) {
      CHECK("B t: every row, bitwise", w_column_is(f, "/other/t", W_ROWS, (size_t)-1, 3, 7));
      CHECK("B p: every row, bitwise", w_column_is(f, "/other/p", W_ROWS, 0, 3, 7));
      CHECK("B q: every row, bitwise", w_column_is(f, "/other/q", W_ROWS, 1, 3, 7));
      CHECK("B r: every row, bitwise", w_column_is(f, "/other/r", W_ROWS, 2, 3, 7));
      H5Fclose(f);
    }
  }
  remove(pa);
  remove(other.path);

  /* discard while buffers are in flight: waits for the writer, leaves nothing */
  CHECK_STATUS("create C", autobal_archive_create(pc, 1, &c, &err), AUTOBAL_SUCCESS);
  if (c != NULL) {
    rc = autobal_archive_series_open(c, "/c", "t", "s", NULL, W_NV, nm, un, NULL, &sc);
    for (i = 0; i < 6 * W_CAP && rc == AUTOBAL_SUCCESS; i++) {
      double tt = w_time(i, 0), row[W_NV];
      w_row(i, W_NV, 0, row);
      rc = autobal_archive_series_append(sc, 1, &tt, row);
    }
    CHECK_STATUS("C: 6 buffers appended", rc, AUTOBAL_SUCCESS);
    autobal_archive_discard(c);
    snprintf(tmpc, sizeof tmpc, "%s.partial-%ld", pc, (long)getpid());
    CHECK("C discarded mid-stream: no final file, no temporary", !exists(pc) && !exists(tmpc));
  }
  free(tcopy);

  /* failures inside the writer come back to the caller */
  {
    int mode;
    for (mode = 0; mode < 2; mode++) {
      pid_t pid;
      int wst = 0;
      fflush(stdout);
      pid = fork();
      if (pid == 0) {
        check_failures_ = 0;
        w_failure_child(pc, mode);
        fflush(stdout);
        _exit(check_failures_ == 0 ? 0 : 1);
      }
      CHECK("fork for the writer-failure test", pid > 0);
      if (pid > 0) {
        waitpid(pid, &wst, 0);
        CHECK(mode == 0 ? "writer failure reported by flush: checks in the child passed"
                        : "writer failure reported by append: checks in the child passed",
              WIFEXITED(wst) && WEXITSTATUS(wst) == 0);
      }
    }
  }
}

#define NX 300
#define NY 200
#define NROWS 20000
#define NV 5

/* ---------------------------------------------------------------------- */
/* Reading side: attribute listing, array attributes, dataset descriptions */
/* ---------------------------------------------------------------------- */

#define AR_MAX 64
typedef struct {
  size_t n;
  char name[AR_MAX][64];
  autobal_archive_attr_info info[AR_MAX];
  autobal_archive *a; /* when set, each callback reads the attribute (re-entrancy) */
  const char *obj;
  int reads_ok;
} attr_rec;

static int attr_rec_cb(const autobal_archive_attr_info *ai, void *vctx) {
  attr_rec *r = vctx;
  if (r->n < AR_MAX) {
    snprintf(r->name[r->n], sizeof r->name[r->n], "%s", ai->name);
    r->info[r->n] = *ai;
    r->info[r->n].name = r->name[r->n];
    r->n++;
  }
  if (r->a != NULL && ai->type_class != AUTOBAL_ARCHIVE_CLASS_OTHER && ai->count > 0) {
    /* reading from inside the callback must work (no lock held, no HDF5 iteration active) */
    char b[512];
    double d[8];
    size_t c = 0;
    int st = ai->type_class == AUTOBAL_ARCHIVE_CLASS_STRING
                 ? autobal_archive_read_attr_string(r->a, r->obj, ai->name, b, sizeof b, NULL)
                 : autobal_archive_read_attr_doubles(r->a, r->obj, ai->name, NULL, 0, &c);
    if (st < 0 || (ai->type_class != AUTOBAL_ARCHIVE_CLASS_STRING && c != ai->count)) r->reads_ok = 0;
    (void)d;
  }
  return 0;
}

static int attr_stop_cb(const autobal_archive_attr_info *ai, void *vctx) {
  int *calls = vctx;
  (void)ai;
  return ++*calls == 2 ? 77 : 0;
}

static int cmp_cstr(const void *x, const void *y) { return strcmp((const char *)x, (const char *)y); }

static const autobal_archive_attr_info *attr_rec_find(const attr_rec *r, const char *name) {
  size_t i;
  for (i = 0; i < r->n; i++)
    if (strcmp(r->name[i], name) == 0) return &r->info[i];
  return NULL;
}

/* Attributes written by the library in a known creation order, listed in both orders
 * (the name order recomputed here with qsort/strcmp), read as arrays; every error path. */
static void test_attr_reading(const char *base) {
  char path[1100], buf[64];
  /* creation order: deliberately not alphabetical; 20 of them (more than HDF5's default
   * 8 compact attributes) */
  static const char *const names[] = {"zeta", "alpha", "Mid", "arr", "k", "k_units", "big", "b0", "_x", "y1",
                                      "y10", "y2", "a", "omega", "omega_units", "count", "flag", "s", "z", "m"};
  const size_t nn = sizeof names / sizeof names[0];
  char sorted[20][64];
  autobal_archive *a = NULL, *r = NULL;
  autobal_error err;
  static double bigv[20000];
  double arr[5] = {1.5, -2.25, 0.0, 1e300, -0.0}, dv[8], om[4] = {1, 2, 3, 4}, m[4 * 3];
  int64_t iv[8];
  const long big_int = 9007199254740993L; /* 2^53 + 1: not a double */
  size_t i, c = 0;
  int rc, ok;
  attr_rec rec;

  snprintf(path, sizeof path, "%s.attrs.h5", base);
  remove(path);
  for (i = 0; i < 20000; i++) bigv[i] = (double)i * 0.5 - 7.0;
  for (i = 0; i < 12; i++) m[i] = (double)i;
  rc = autobal_archive_create(path, 1, &a, &err);
  CHECK_STATUS("attrs: create", rc, AUTOBAL_SUCCESS);
  if (rc != AUTOBAL_SUCCESS) return;
  rc = autobal_archive_group(a, "/g");
  for (i = 0; i < nn && rc == AUTOBAL_SUCCESS; i++) {
    const char *n = names[i];
    if (!strcmp(n, "alpha")) rc = autobal_archive_attr_int(a, "/g", n, -1234567890123L);
    else if (!strcmp(n, "count")) rc = autobal_archive_attr_int(a, "/g", n, big_int);
    else if (!strcmp(n, "arr")) rc = autobal_archive_attr_double_array(a, "/g", n, 5, arr, NULL);
    else if (!strcmp(n, "big")) rc = autobal_archive_attr_double_array(a, "/g", n, 20000, bigv, NULL);
    else if (!strcmp(n, "Mid") || !strcmp(n, "s") || strstr(n, "_units")) rc = autobal_archive_attr_string(a, "/g", n, "kg m^2");
    else rc = autobal_archive_attr_double(a, "/g", n, (double)i + 0.25, NULL);
  }
  CHECK_STATUS("attrs: 20 attributes (one of 160 kB) written", rc, AUTOBAL_SUCCESS);
  if (rc == AUTOBAL_SUCCESS) rc = autobal_archive_coord(a, "/g", "omega", 4, om, "rad/s", "speed");
  if (rc == AUTOBAL_SUCCESS) rc = autobal_archive_dim(a, "/g", "comp", 3, NULL);
  if (rc == AUTOBAL_SUCCESS) {
    const char *dims[2] = {"omega", "comp"};
    rc = autobal_archive_var(a, "/g", "m", 2, dims, m, "N", NULL);
  }
  if (rc == AUTOBAL_SUCCESS) rc = autobal_archive_attr_double(a, "/g/m", "scale", 2.0, "1");
  CHECK_STATUS("attrs: coordinate, index dimension, variable", rc, AUTOBAL_SUCCESS);
  /* a write handle lists too */
  memset(&rec, 0, sizeof rec);
  CHECK_STATUS("attrs: list on a write handle",
               autobal_archive_list_attrs(a, "/g", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec), AUTOBAL_SUCCESS);
  CHECK("attrs: write handle sees all 20", rec.n == nn);
  rc = autobal_archive_close(a, &err);
  CHECK_STATUS("attrs: close", rc, AUTOBAL_SUCCESS);

  rc = autobal_archive_open_read(path, &r, &err);
  CHECK_STATUS("attrs: open_read", rc, AUTOBAL_SUCCESS);
  if (r == NULL) return;
  /* creation order = the order written */
  memset(&rec, 0, sizeof rec);
  rc = autobal_archive_list_attrs(r, "/g", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec);
  CHECK_STATUS("attrs: list in creation order", rc, AUTOBAL_SUCCESS);
  ok = rec.n == nn;
  for (i = 0; ok && i < nn; i++) ok = strcmp(rec.name[i], names[i]) == 0;
  CHECK("attrs: creation order is the order of writing (20 names)", ok);
  /* name order = strcmp order, computed independently */
  for (i = 0; i < nn; i++) snprintf(sorted[i], sizeof sorted[i], "%s", names[i]);
  qsort(sorted, nn, sizeof sorted[0], cmp_cstr);
  memset(&rec, 0, sizeof rec);
  rec.a = r;
  rec.obj = "/g";
  rec.reads_ok = 1;
  rc = autobal_archive_list_attrs(r, "g", AUTOBAL_ARCHIVE_ORDER_NAME, attr_rec_cb, &rec);
  CHECK_STATUS("attrs: list in name order (relative path)", rc, AUTOBAL_SUCCESS);
  ok = rec.n == nn;
  for (i = 0; ok && i < nn; i++) ok = strcmp(rec.name[i], sorted[i]) == 0;
  CHECK("attrs: name order is strcmp order", ok);
  CHECK("attrs: the callback may read the attributes it is given", rec.reads_ok);
  {
    const autobal_archive_attr_info *x;
    x = attr_rec_find(&rec, "zeta");
    CHECK("attrs: zeta float64 scalar", x && x->type_class == AUTOBAL_ARCHIVE_CLASS_FLOAT && x->rank == 0 &&
                                            x->count == 1 && x->size == 8 && !x->is_unsigned);
    x = attr_rec_find(&rec, "alpha");
    CHECK("attrs: alpha int64 scalar", x && x->type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER && x->rank == 0 &&
                                           x->count == 1 && x->size == 8 && !x->is_unsigned);
    x = attr_rec_find(&rec, "arr");
    CHECK("attrs: arr float64 1-D of 5", x && x->type_class == AUTOBAL_ARCHIVE_CLASS_FLOAT && x->rank == 1 &&
                                             x->count == 5 && x->size == 8);
    x = attr_rec_find(&rec, "big");
    CHECK("attrs: big 1-D of 20000", x && x->rank == 1 && x->count == 20000);
    x = attr_rec_find(&rec, "Mid");
    CHECK("attrs: Mid variable-length string scalar",
          x && x->type_class == AUTOBAL_ARCHIVE_CLASS_STRING && x->rank == 0 && x->count == 1 && x->size == 0);
  }
  /* a coordinate's and a variable's attributes: the format's own (CLASS, NAME,
   * REFERENCE_LIST, DIMENSION_LIST) are not listed */
  memset(&rec, 0, sizeof rec);
  rc = autobal_archive_list_attrs(r, "/g/omega", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec);
  CHECK("attrs: coordinate lists units, long_name only",
        rc == 0 && rec.n == 2 && !strcmp(rec.name[0], "units") && !strcmp(rec.name[1], "long_name"));
  CHECK("attrs: (the coordinate does have CLASS and NAME)", autobal_archive_has(r, "/g/omega", "CLASS") &&
                                                                autobal_archive_has(r, "/g/omega", "NAME"));
  memset(&rec, 0, sizeof rec);
  rc = autobal_archive_list_attrs(r, "/g/m", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec);
  CHECK("attrs: variable lists units, long_name, scale, scale_units (no DIMENSION_LIST)",
        rc == 0 && rec.n == 4 && !strcmp(rec.name[2], "scale") && !strcmp(rec.name[3], "scale_units") &&
            autobal_archive_has(r, "/g/m", "DIMENSION_LIST"));
  memset(&rec, 0, sizeof rec);
  rc = autobal_archive_list_attrs(r, "/", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec);
  CHECK("attrs: root in creation order starts with Conventions, status",
        rc == 0 && rec.n >= 2 && !strcmp(rec.name[0], "Conventions") && !strcmp(rec.name[1], "status"));

  /* arrays */
  rc = autobal_archive_read_attr_doubles(r, "/g", "arr", dv, 8, &c);
  CHECK_STATUS("attrs: read_attr_doubles arr", rc, AUTOBAL_SUCCESS);
  CHECK("attrs: arr bit for bit, count 5", c == 5 && memcmp(dv, arr, sizeof arr) == 0);
  {
    double *bb = malloc(20000 * sizeof *bb);
    c = 0;
    rc = bb ? autobal_archive_read_attr_doubles(r, "/g", "big", bb, 20000, &c) : -99;
    CHECK("attrs: big attribute (160 kB) read back exactly",
          rc == AUTOBAL_SUCCESS && c == 20000 && memcmp(bb, bigv, 20000 * sizeof *bb) == 0);
    free(bb);
  }
  rc = autobal_archive_read_attr_int64s(r, "/g", "count", iv, 1, &c);
  CHECK("attrs: int64 2^53+1 exact through _int64s", rc == AUTOBAL_SUCCESS && c == 1 && iv[0] == big_int);
  rc = autobal_archive_read_attr_doubles(r, "/g", "count", dv, 1, &c);
  CHECK("attrs: ... and rounded to a double through _doubles",
        rc == AUTOBAL_SUCCESS && dv[0] == (double)big_int && (int64_t)dv[0] != big_int);
  rc = autobal_archive_read_attr_int64s(r, "/g", "alpha", iv, 8, &c);
  CHECK("attrs: alpha = -1234567890123", rc == AUTOBAL_SUCCESS && c == 1 && iv[0] == -1234567890123LL);
  rc = autobal_archive_read_attr_doubles(r, "/g", "zeta", dv, 1, NULL);
  CHECK("attrs: scalar via _doubles (count NULL)", rc == AUTOBAL_SUCCESS && dv[0] == 0.25);
  c = 0;
  rc = autobal_archive_read_attr_doubles(r, "/g", "arr", NULL, 0, &c);
  CHECK("attrs: size query (buf NULL, n 0)", rc == AUTOBAL_SUCCESS && c == 5);
  /* errors */
  c = 0;
  rc = autobal_archive_read_attr_doubles(r, "/g", "arr", dv, 4, &c);
  CHECK_STATUS("attrs: buffer too small", rc, AUTOBAL_EINVAL);
  CHECK("attrs: ... count still reported", c == 5);
  CHECK_MSG("attrs: ... message gives the size", autobal_archive_errmsg(r), "has 5 elements");
  CHECK_STATUS("attrs: buf NULL with n > 0", autobal_archive_read_attr_doubles(r, "/g", "arr", NULL, 3, &c),
               AUTOBAL_EINVAL);
  CHECK_STATUS("attrs: missing attribute", autobal_archive_read_attr_doubles(r, "/g", "nosuch", dv, 8, &c),
               AUTOBAL_EFORMAT);
  CHECK_MSG("attrs: ... named", autobal_archive_errmsg(r), "nosuch");
  CHECK_STATUS("attrs: missing attribute (_int64s)", autobal_archive_read_attr_int64s(r, "/g", "nosuch2", iv, 8, &c),
               AUTOBAL_EFORMAT);
  CHECK_MSG("attrs: ... named", autobal_archive_errmsg(r), "nosuch2");
  CHECK_STATUS("attrs: string as doubles", autobal_archive_read_attr_doubles(r, "/g", "Mid", dv, 8, &c),
               AUTOBAL_EFORMAT);
  CHECK_MSG("attrs: ... names it and says string", autobal_archive_errmsg(r), "'Mid' of '/g' is a string");
  CHECK_STATUS("attrs: float as int64s", autobal_archive_read_attr_int64s(r, "/g", "zeta", iv, 8, &c),
               AUTOBAL_EFORMAT);
  CHECK_MSG("attrs: ... says floating point", autobal_archive_errmsg(r), "floating point");
  CHECK_STATUS("attrs: missing object", autobal_archive_read_attr_doubles(r, "/nope", "x", dv, 8, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("attrs: NULL name", autobal_archive_read_attr_doubles(r, "/g", NULL, dv, 8, &c), AUTOBAL_EINVAL);
  CHECK_STATUS("attrs: missing string attribute", autobal_archive_read_attr_string(r, "/g", "nosuch3", buf, sizeof buf, NULL),
               AUTOBAL_EFORMAT);
  CHECK_MSG("attrs: ... named", autobal_archive_errmsg(r), "nosuch3");
  CHECK_STATUS("attrs: NULL handle", autobal_archive_read_attr_doubles(NULL, "/g", "arr", dv, 8, &c), AUTOBAL_EINVAL);
  memset(&rec, 0, sizeof rec);
  CHECK_STATUS("attrs: list, bad order", autobal_archive_list_attrs(r, "/g", 2, attr_rec_cb, &rec), AUTOBAL_EINVAL);
  CHECK_MSG("attrs: ... message", autobal_archive_errmsg(r), "order = 2");
  CHECK_STATUS("attrs: list, NULL callback", autobal_archive_list_attrs(r, "/g", 0, NULL, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("attrs: list, missing object", autobal_archive_list_attrs(r, "/g/nope", 0, attr_rec_cb, &rec),
               AUTOBAL_EINVAL);
  CHECK_MSG("attrs: ... named", autobal_archive_errmsg(r), "/g/nope");
  CHECK_STATUS("attrs: list, bad path", autobal_archive_list_attrs(r, "/g/\x01", 0, attr_rec_cb, &rec), AUTOBAL_EINVAL);
  CHECK_STATUS("attrs: list, NULL handle", autobal_archive_list_attrs(NULL, "/g", 0, attr_rec_cb, &rec), AUTOBAL_EINVAL);
  CHECK("attrs: nothing passed to the callback on failure", rec.n == 0);
  {
    int calls = 0;
    CHECK_STATUS("attrs: list stops with the callback's value",
                 autobal_archive_list_attrs(r, "/g", AUTOBAL_ARCHIVE_ORDER_NAME, attr_stop_cb, &calls), 77);
    CHECK("attrs: ... after 2 calls", calls == 2);
  }

  /* datasets described */
  {
    autobal_archive_var_info vi;
    rc = autobal_archive_var_describe(r, "/g/m", &vi);
    CHECK_STATUS("describe m", rc, AUTOBAL_SUCCESS);
    CHECK("describe m: 4 x 3 float64 over (omega, comp), not a coordinate",
          vi.rank == 2 && vi.dims[0] == 4 && vi.dims[1] == 3 && vi.count == 12 &&
              vi.type_class == AUTOBAL_ARCHIVE_CLASS_FLOAT && vi.size == 8 && !vi.is_coordinate &&
              !strcmp(vi.dim_names[0], "omega") && !strcmp(vi.dim_names[1], "comp"));
    rc = autobal_archive_var_describe(r, "g/omega", &vi);
    CHECK("describe omega: a coordinate, its own dimension",
          rc == 0 && vi.is_coordinate && vi.rank == 1 && vi.dims[0] == 4 && !strcmp(vi.dim_names[0], "omega"));
    rc = autobal_archive_var_describe(r, "/g/comp", &vi);
    CHECK("describe comp: int32 index dimension",
          rc == 0 && vi.is_coordinate && vi.type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER && vi.size == 4 &&
              !vi.is_unsigned && vi.count == 3);
    CHECK_STATUS("describe a group", autobal_archive_var_describe(r, "/g", &vi), AUTOBAL_EINVAL);
    CHECK("describe failure zeroes info", vi.rank == 0 && vi.count == 0 && vi.dim_names[0][0] == '\0');
    CHECK_STATUS("describe missing", autobal_archive_var_describe(r, "/g/zz", &vi), AUTOBAL_EINVAL);
    CHECK_MSG("describe missing: named", autobal_archive_errmsg(r), "/g/zz");
    CHECK_STATUS("describe NULL info", autobal_archive_var_describe(r, "/g/m", NULL), AUTOBAL_EINVAL);
  }
  autobal_archive_close(r, NULL);
  remove(path);
}

/* A file written with plain HDF5 (no creation-order tracking, other types): the reading
 * side must cope and classify everything. */
static void test_foreign_reading(const char *base) {
  char path[1100], sbuf[64];
  hid_t f, g, sp, at, t, ds;
  hsize_t d23[2] = {2, 3}, d3 = 3, d6[5] = {1, 1, 1, 1, 2};
  float f23[6] = {0.5f, -1.25f, 2.0f, 3.0f, 4.5f, -8.0f};
  unsigned char u8 = 255;
  short i16[3] = {-32768, 0, 32767};
  uint64_t u64 = UINT64_C(18446744073709551615);
  const char *vs[2] = {"one", "two"};
  struct { int a; double b; } cmp = {1, 2.0};
  unsigned short u16[3] = {1, 2, 65535};
  double d6v[2] = {1, 2};
  autobal_archive *r = NULL;
  autobal_error err;
  attr_rec rec;
  double dv[8];
  int64_t iv[8];
  size_t c = 0, i;
  int rc, ok;

  snprintf(path, sizeof path, "%s.foreign.h5", base);
  remove(path);
  f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  CHECK("foreign: created with plain HDF5", f >= 0);
  if (f < 0) return;
  /* root: Conventions as a fixed-length string, to be accepted as an archive */
  t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, 9);
  sp = H5Screate(H5S_SCALAR);
  at = H5Acreate2(f, "Conventions", t, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, t, "autobal-1");
  H5Aclose(at);
  H5Sclose(sp);
  H5Tclose(t);
  g = H5Gcreate2(f, "/x", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  /* written in non-alphabetical order: z_f32 (2x3 float32), u8, i16[3], fix (fixed string
   * "abc" padded to 8 with spaces), vs[2], cmp (compound), null (H5S_NULL int), u64 */
  sp = H5Screate_simple(2, d23, NULL);
  at = H5Acreate2(g, "z_f32", H5T_IEEE_F32LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, H5T_NATIVE_FLOAT, f23);
  H5Aclose(at);
  H5Sclose(sp);
  sp = H5Screate(H5S_SCALAR);
  at = H5Acreate2(g, "u8", H5T_STD_U8LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, H5T_NATIVE_UCHAR, &u8);
  H5Aclose(at);
  at = H5Acreate2(g, "u64", H5T_STD_U64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, H5T_NATIVE_UINT64, &u64);
  H5Aclose(at);
  t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, 8);
  H5Tset_strpad(t, H5T_STR_SPACEPAD);
  at = H5Acreate2(g, "fix", t, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, t, "abc     ");
  H5Aclose(at);
  H5Tclose(t);
  t = H5Tcreate(H5T_COMPOUND, sizeof cmp);
  H5Tinsert(t, "a", 0, H5T_NATIVE_INT);
  H5Tinsert(t, "b", sizeof(double), H5T_NATIVE_DOUBLE);
  at = H5Acreate2(g, "cmp", t, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, t, &cmp);
  H5Aclose(at);
  H5Tclose(t);
  H5Sclose(sp);
  sp = H5Screate_simple(1, &d3, NULL);
  at = H5Acreate2(g, "i16", H5T_STD_I16LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, H5T_NATIVE_SHORT, i16);
  H5Aclose(at);
  H5Sclose(sp);
  sp = H5Screate_simple(1, d23, NULL); /* 2 strings */
  t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  at = H5Acreate2(g, "vs", t, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(at, t, vs);
  H5Aclose(at);
  H5Tclose(t);
  H5Sclose(sp);
  sp = H5Screate(H5S_NULL);
  at = H5Acreate2(g, "null", H5T_STD_I32LE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Aclose(at);
  H5Sclose(sp);
  /* datasets: uint16 without scales, rank 5 */
  sp = H5Screate_simple(1, &d3, NULL);
  ds = H5Dcreate2(g, "u16", H5T_STD_U16LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_USHORT, H5S_ALL, H5S_ALL, H5P_DEFAULT, u16);
  H5Dclose(ds);
  H5Sclose(sp);
  sp = H5Screate_simple(5, d6, NULL);
  ds = H5Dcreate2(g, "r5", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d6v);
  H5Dclose(ds);
  H5Sclose(sp);
  H5Gclose(g);
  H5Fclose(f);

  rc = autobal_archive_open_read(path, &r, &err);
  CHECK_STATUS("foreign: open_read", rc, AUTOBAL_SUCCESS);
  if (r == NULL) return;
  memset(&rec, 0, sizeof rec);
  rc = autobal_archive_list_attrs(r, "/x", AUTOBAL_ARCHIVE_ORDER_CREATION, attr_rec_cb, &rec);
  CHECK_STATUS("foreign: list (creation order not tracked)", rc, AUTOBAL_SUCCESS);
  {
    static const char *const want[8] = {"cmp", "fix", "i16", "null", "u64", "u8", "vs", "z_f32"};
    ok = rec.n == 8;
    for (i = 0; ok && i < 8; i++) ok = strcmp(rec.name[i], want[i]) == 0;
    CHECK("foreign: creation order falls back to name order", ok);
  }
  {
    const autobal_archive_attr_info *x;
    x = attr_rec_find(&rec, "z_f32");
    CHECK("foreign: z_f32 float, 4 bytes, rank 2, 6 elements",
          x && x->type_class == AUTOBAL_ARCHIVE_CLASS_FLOAT && x->size == 4 && x->rank == 2 && x->count == 6);
    x = attr_rec_find(&rec, "u8");
    CHECK("foreign: u8 unsigned integer, 1 byte, scalar",
          x && x->type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER && x->size == 1 && x->is_unsigned && x->rank == 0);
    x = attr_rec_find(&rec, "i16");
    CHECK("foreign: i16 signed, 2 bytes, 3 elements",
          x && x->type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER && x->size == 2 && !x->is_unsigned && x->count == 3);
    x = attr_rec_find(&rec, "fix");
    CHECK("foreign: fix fixed-length string of 8", x && x->type_class == AUTOBAL_ARCHIVE_CLASS_STRING && x->size == 8);
    x = attr_rec_find(&rec, "vs");
    CHECK("foreign: vs 2 variable-length strings",
          x && x->type_class == AUTOBAL_ARCHIVE_CLASS_STRING && x->size == 0 && x->count == 2 && x->rank == 1);
    x = attr_rec_find(&rec, "cmp");
    CHECK("foreign: cmp compound is OTHER", x && x->type_class == AUTOBAL_ARCHIVE_CLASS_OTHER && x->count == 1);
    x = attr_rec_find(&rec, "null");
    CHECK("foreign: null dataspace: 0 elements, rank 0", x && x->count == 0 && x->rank == 0);
  }
  rc = autobal_archive_read_attr_doubles(r, "/x", "z_f32", dv, 8, &c);
  ok = rc == AUTOBAL_SUCCESS && c == 6;
  for (i = 0; ok && i < 6; i++) ok = dv[i] == (double)f23[i];
  CHECK("foreign: float32 2x3 read as doubles exactly, C order", ok);
  rc = autobal_archive_read_attr_int64s(r, "/x", "i16", iv, 8, &c);
  CHECK("foreign: int16 read as int64", rc == 0 && c == 3 && iv[0] == -32768 && iv[1] == 0 && iv[2] == 32767);
  rc = autobal_archive_read_attr_int64s(r, "/x", "u8", iv, 1, &c);
  CHECK("foreign: uint8 255", rc == 0 && iv[0] == 255);
  rc = autobal_archive_read_attr_int64s(r, "/x", "u64", iv, 1, &c);
  CHECK("foreign: uint64 max clipped to INT64_MAX (documented)", rc == 0 && iv[0] == INT64_MAX);
  rc = autobal_archive_read_attr_doubles(r, "/x", "null", dv, 8, &c);
  CHECK("foreign: null attribute: 0 elements", rc == 0 && c == 0);
  CHECK_STATUS("foreign: compound as doubles", autobal_archive_read_attr_doubles(r, "/x", "cmp", dv, 8, &c),
               AUTOBAL_EFORMAT);
  CHECK_MSG("foreign: ... not numeric", autobal_archive_errmsg(r), "not numeric");
  CHECK_STATUS("foreign: string array as doubles", autobal_archive_read_attr_doubles(r, "/x", "vs", dv, 8, &c),
               AUTOBAL_EFORMAT);
  rc = autobal_archive_read_attr_string(r, "/x", "fix", sbuf, sizeof sbuf, &c);
  CHECK("foreign: fixed-length string read (space padding kept)", rc == 0 && strcmp(sbuf, "abc     ") == 0 && c == 8);
  CHECK_STATUS("foreign: string array as string", autobal_archive_read_attr_string(r, "/x", "vs", sbuf, sizeof sbuf, NULL),
               AUTOBAL_EFORMAT);
  {
    autobal_archive_var_info vi;
    rc = autobal_archive_var_describe(r, "/x/u16", &vi);
    CHECK("foreign: u16 dataset: unsigned 2 bytes, no scales, no dimension names",
          rc == 0 && vi.type_class == AUTOBAL_ARCHIVE_CLASS_INTEGER && vi.size == 2 && vi.is_unsigned &&
              !vi.is_coordinate && vi.rank == 1 && vi.dim_names[0][0] == '\0');
    CHECK_STATUS("foreign: rank-5 dataset", autobal_archive_var_describe(r, "/x/r5", &vi), AUTOBAL_EUNSUPPORTED);
  }
  autobal_archive_close(r, NULL);
  remove(path);
}

typedef struct {
  autobal_archive_series *s;
  volatile int stop;
  int st;
  size_t rows;
} ver_writer;

static void *ver_writer_main(void *arg) {
  ver_writer *w = arg;
  double row[4], tt;
  size_t i;
  for (i = 0; !w->stop && w->st == 0 && i < 2000000; i++) {
    tt = (double)i;
    row[0] = tt;
    row[1] = -tt;
    row[2] = tt * 0.5;
    row[3] = 1.0;
    w->st = autobal_archive_series_append(w->s, 1, &tt, row);
    w->rows = i + 1;
  }
  return NULL;
}

/* autobal_hdf5_version: the value H5get_libversion gives, snprintf-like truncation, and
 * calls from one thread while another streams a series (every HDF5 call of the library
 * is under one lock; with a non-thread-safe HDF5 and without the lock this races). */
static void test_hdf5_version(const char *base) {
  char v[64], want[64], small[4], path[1100];
  unsigned maj, min, rel;
  autobal_archive *a = NULL;
  autobal_error err;
  ver_writer w;
  pthread_t th;
  int i, same = 1;
  static const char *const names[4] = {"a", "b", "c", "d"};
  static const char *const units[4] = {"1", "1", "1", "1"};
  H5get_libversion(&maj, &min, &rel);
  snprintf(want, sizeof want, "%u.%u.%u", maj, min, rel);
  autobal_hdf5_version(v, sizeof v);
  CHECK("hdf5 version = H5get_libversion", strcmp(v, want) == 0);
  memset(small, 'x', sizeof small);
  autobal_hdf5_version(small, sizeof small);
  CHECK("hdf5 version truncated like snprintf", strncmp(small, want, 3) == 0 && small[3] == '\0');
  small[0] = 'q';
  autobal_hdf5_version(small, 0);
  autobal_hdf5_version(NULL, 10);
  CHECK("hdf5 version: size 0 and NULL buf do nothing", small[0] == 'q');

  snprintf(path, sizeof path, "%s.version.h5", base);
  memset(&w, 0, sizeof w);
  if (autobal_archive_create(path, 1, &a, &err) != AUTOBAL_SUCCESS) {
    CHECK("hdf5 version: create archive", 0);
    return;
  }
  if (autobal_archive_series_open(a, "/ts", "t", "s", NULL, 4, names, units, NULL, &w.s) != AUTOBAL_SUCCESS ||
      pthread_create(&th, NULL, ver_writer_main, &w) != 0) {
    CHECK("hdf5 version: series and thread", 0);
    autobal_archive_discard(a);
    return;
  }
  for (i = 0; i < 20000; i++) {
    autobal_hdf5_version(v, sizeof v);
    if (strcmp(v, want) != 0) same = 0;
  }
  w.stop = 1;
  pthread_join(th, NULL);
  CHECK("hdf5 version: 20000 calls during streaming all right", same);
  CHECK_STATUS("hdf5 version: the streaming thread's appends", w.st, AUTOBAL_SUCCESS);
  printf("     (%zu rows streamed meanwhile)\n", w.rows);
  CHECK_STATUS("hdf5 version: archive closes", autobal_archive_close(a, &err), AUTOBAL_SUCCESS);
  remove(path);
}

int main(int argc, char **argv) {
  char path[1024], tmp[1100], p2[1024], buf[256];
  autobal_archive *a = NULL, *r = NULL;
  autobal_archive_series *s = NULL;
  autobal_error err;
  H5E_auto2_t old_func = NULL;
  void *old_data = NULL;
  static double x[NX], y[NY], big[NX * NY], series_rows[NROWS * NV], t[NROWS];
  double small[NX], omega[50], m2[50 * 4];
  int im2[50 * 4];
  size_t i, j;
  int rc;

  setvbuf(stdout, NULL, _IOLBF, 0); /* keep the log complete if something crashes */
  if (argc == 3 && strcmp(argv[1], "--write") == 0) return write_sample(argv[2]);
  if (argc != 1) {
    fprintf(stderr, "usage: %s [--write FILE]\n", argv[0]);
    return 2;
  }

  /* A counting HDF5 error handler: the library must never trigger it (no printing)
   * and must leave it installed. */
  H5Eset_auto2(H5E_DEFAULT, counting_handler, NULL);

  snprintf(path, sizeof path, "%s/test_archive_%ld.h5", AUTOBAL_TEST_TMP_DIR, (long)getpid());
  snprintf(tmp, sizeof tmp, "%s.partial-%ld", path, (long)getpid());
  remove(path);
  remove(tmp);

  /* ---- creation, temporary name ---------------------------------------- */
  rc = autobal_archive_create(path, 0, &a, &err);
  CHECK_STATUS("create", rc, AUTOBAL_SUCCESS);
  if (a == NULL) return check_summary() + 1;
  CHECK("final name absent before close", !exists(path));
  CHECK("temporary <path>.partial-<pid> exists", exists(tmp));
  CHECK("errmsg empty after success", strcmp(autobal_archive_errmsg(a), "") == 0);

  {
    const char *av[6] = {"autobal", "run", "my file.ini", "it's", "", "--x=1,2"};
    const char *avnull[2] = {"autobal", NULL};
    CHECK_STATUS("provenance argc < 0", autobal_archive_provenance(a, "t", -1, av), AUTOBAL_EINVAL);
    CHECK_STATUS("provenance argv NULL", autobal_archive_provenance(a, "t", 2, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("provenance argv[1] NULL", autobal_archive_provenance(a, "t", 2, avnull), AUTOBAL_EINVAL);
    CHECK_MSG("names argv[1]", autobal_archive_errmsg(a), "argv[1]");
    CHECK_STATUS("provenance title not UTF-8", autobal_archive_provenance(a, "\xc3", 0, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("provenance", autobal_archive_provenance(a, "a title", 6, av), AUTOBAL_SUCCESS);
  }

  /* ---- groups ------------------------------------------------------------ */
  CHECK_STATUS("group with parents", autobal_archive_group(a, "/pendulum/map"), AUTOBAL_SUCCESS);
  CHECK_STATUS("group idempotent", autobal_archive_group(a, "pendulum//map/"), AUTOBAL_SUCCESS);
  CHECK_STATUS("root group", autobal_archive_group(a, "/"), AUTOBAL_SUCCESS);
  CHECK_STATUS("group name with control char", autobal_archive_group(a, "/bad\tname"), AUTOBAL_EINVAL);
  CHECK_STATUS("group name '..'", autobal_archive_group(a, "/a/../b"), AUTOBAL_EINVAL);
  CHECK_STATUS("group NULL", autobal_archive_group(a, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("group invalid UTF-8", autobal_archive_group(a, "/caf\xe9"), AUTOBAL_EINVAL);
  CHECK_MSG("invalid UTF-8 message", autobal_archive_errmsg(a), "UTF-8");

  /* ---- coordinates, dims, variables ------------------------------------ */
  for (i = 0; i < 50; i++) omega[i] = 0.1 * (double)i;
  for (i = 0; i < 50; i++)
    for (j = 0; j < 4; j++) {
      m2[i * 4 + j] = 10.0 * (double)i + (double)j + 0.5;
      im2[i * 4 + j] = (int)(i * 4 + j) - 100;
    }
  CHECK_STATUS("coord omega", autobal_archive_coord(a, "/pendulum/map", "omega", 50, omega, "rad/s", "speed"),
               AUTOBAL_SUCCESS);
  CHECK_STATUS("dim root", autobal_archive_dim(a, "/pendulum/map", "root", 4, NULL), AUTOBAL_SUCCESS);
  {
    const char *d2[2] = {"omega", "root"};
    const char *dabs[2] = {"/pendulum/map/omega", "root"};
    const char *dbad[2] = {"omega", "nosuch"};
    const char *dvar[1] = {"m2"};
    CHECK_STATUS("var m2(omega,root)", autobal_archive_var(a, "/pendulum/map", "m2", 2, d2, m2, "1/s", NULL),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("var_int", autobal_archive_var_int(a, "/pendulum/map", "im2", 2, d2, im2, "1", "ints"),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("var with absolute dim path",
                 autobal_archive_var(a, "/pendulum/map", "m2b", 2, dabs, m2, "1/s", NULL), AUTOBAL_SUCCESS);
    CHECK_STATUS("var in subgroup uses parent's dim",
                 autobal_archive_var(a, "/pendulum/map/deep/er", "v", 1, d2, omega, "rad/s", NULL), AUTOBAL_SUCCESS);
    {
      const char *drr[2] = {"root", "root"};
      double sq[16];
      for (i = 0; i < 16; i++) sq[i] = (double)i;
      CHECK_STATUS("square var over (root, root)", autobal_archive_var(a, "/pendulum/map", "sq", 2, drr, sq, "1", NULL),
                   AUTOBAL_SUCCESS);
    }
    CHECK_STATUS("scalar var", autobal_archive_var(a, "/pendulum", "s0", 0, NULL, &omega[3], "rad/s", "scalar"),
                 AUTOBAL_SUCCESS);
    /* errors */
    CHECK_STATUS("unknown dimension", autobal_archive_var(a, "/pendulum/map", "z", 2, dbad, m2, "1", NULL),
                 AUTOBAL_EINVAL);
    CHECK_MSG("unknown dimension named", autobal_archive_errmsg(a), "nosuch");
    CHECK("failed var not created (no half-made dataset)",
          !autobal_archive_has(a, "/pendulum/map/z", NULL));
    CHECK_STATUS("dimension that is a variable", autobal_archive_var(a, "/pendulum/map", "z", 1, dvar, m2, "1", NULL),
                 AUTOBAL_EINVAL);
    CHECK_MSG("not-a-dimension message", autobal_archive_errmsg(a), "not a dimension");
    CHECK_STATUS("dimension not visible from a sibling group",
                 autobal_archive_var(a, "/rotor", "z", 1, d2, m2, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("duplicate variable", autobal_archive_var(a, "/pendulum/map", "m2", 2, d2, m2, "1/s", NULL),
                 AUTOBAL_EINVAL);
    CHECK_MSG("duplicate message", autobal_archive_errmsg(a), "already exists");
    CHECK_STATUS("rank 5", autobal_archive_var(a, "/pendulum/map", "z", 5, d2, m2, "1", NULL), AUTOBAL_EINVAL);
    CHECK_MSG("rank message", autobal_archive_errmsg(a), "rank 5");
    CHECK_STATUS("rank -1", autobal_archive_var(a, "/pendulum/map", "z", -1, d2, m2, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("NULL units", autobal_archive_var(a, "/pendulum/map", "z", 2, d2, m2, NULL, NULL), AUTOBAL_EINVAL);
    CHECK_MSG("NULL units message", autobal_archive_errmsg(a), "units");
    CHECK_STATUS("NULL data", autobal_archive_var(a, "/pendulum/map", "z", 2, d2, NULL, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("NULL dims", autobal_archive_var(a, "/pendulum/map", "z", 2, NULL, m2, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("name with slash", autobal_archive_var(a, "/pendulum/map", "a/b", 2, d2, m2, "1", NULL),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("empty name", autobal_archive_coord(a, "/pendulum/map", "", 50, omega, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("coord n = 0", autobal_archive_coord(a, "/pendulum/map", "q", 0, omega, "1", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("coord NULL values", autobal_archive_coord(a, "/pendulum/map", "q", 3, NULL, "1", NULL),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("coord NULL units", autobal_archive_coord(a, "/pendulum/map", "q", 3, omega, NULL, NULL),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("coord exists", autobal_archive_coord(a, "/pendulum/map", "omega", 3, omega, "1", NULL),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("dim n = 0", autobal_archive_dim(a, "/pendulum/map", "q", 0, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("group over a dataset", autobal_archive_group(a, "/pendulum/map/m2/x"), AUTOBAL_EINVAL);
    CHECK_MSG("not-a-group message", autobal_archive_errmsg(a), "not a group");
  }
  /* large variable: chunked + compressed; small one contiguous */
  for (i = 0; i < NX; i++) x[i] = 1e-3 * (double)i;
  for (j = 0; j < NY; j++) y[j] = -2.0 + 0.01 * (double)j;
  for (i = 0; i < NX; i++)
    for (j = 0; j < NY; j++) big[i * NY + j] = x[i] * 1000.0 + y[j] * 0.5 + (double)((i * 7 + j * 13) % 11);
  for (i = 0; i < NX; i++) small[i] = (double)i * 0.125;
  {
    const char *dxy[2] = {"x", "y"}, *dx[1] = {"x"};
    CHECK_STATUS("coord x", autobal_archive_coord(a, "/big", "x", NX, x, "m", "x position"), AUTOBAL_SUCCESS);
    CHECK_STATUS("coord y", autobal_archive_coord(a, "/big", "y", NY, y, "m", "y position"), AUTOBAL_SUCCESS);
    CHECK_STATUS("big var (480 kB)", autobal_archive_var(a, "/big", "field", 2, dxy, big, "Pa", "a field"),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("small var (2.4 kB)", autobal_archive_var(a, "/big", "small", 1, dx, small, "1", NULL),
                 AUTOBAL_SUCCESS);
  }

  /* ---- attributes -------------------------------------------------------- */
  {
    const double arr[3] = {1.0, -2.5, 1e-300};
    CHECK_STATUS("attr double", autobal_archive_attr_double(a, "/pendulum", "mass", 0.25, "kg"), AUTOBAL_SUCCESS);
    CHECK_STATUS("attr double replaced", autobal_archive_attr_double(a, "/pendulum", "mass", 0.5, "kg"),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("attr double dimensionless", autobal_archive_attr_double(a, "/pendulum", "zeta", 0.01, "1"),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("attr double no units", autobal_archive_attr_double(a, "/pendulum", "plain", 3.0, NULL),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("attr int", autobal_archive_attr_int(a, "/pendulum", "n", -1234567890123L), AUTOBAL_SUCCESS);
    CHECK_STATUS("attr string on dataset", autobal_archive_attr_string(a, "/pendulum/map/m2", "note", "h\xc3\xa9llo"),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("attr array", autobal_archive_attr_double_array(a, "/", "arr", 3, arr, "m"), AUTOBAL_SUCCESS);
    CHECK_STATUS("attr on missing object", autobal_archive_attr_double(a, "/nope", "q", 1.0, NULL), AUTOBAL_EINVAL);
    CHECK_MSG("missing object named", autobal_archive_errmsg(a), "/nope");
    CHECK_STATUS("reserved attr CLASS", autobal_archive_attr_string(a, "/pendulum", "CLASS", "x"), AUTOBAL_EINVAL);
    CHECK_MSG("reserved message", autobal_archive_errmsg(a), "reserved");
    CHECK_STATUS("reserved attr _Netcdf4Dimid", autobal_archive_attr_int(a, "/pendulum", "_Netcdf4Dimid", 1),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("attr string NULL", autobal_archive_attr_string(a, "/pendulum", "s", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("attr string invalid UTF-8", autobal_archive_attr_string(a, "/pendulum", "s", "\xff"),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("attr array n = 0", autobal_archive_attr_double_array(a, "/", "arr", 0, arr, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("attr array NULL", autobal_archive_attr_double_array(a, "/", "arr", 2, NULL, NULL), AUTOBAL_EINVAL);
  }

  /* ---- series: 20000 rows x 5 variables (> 4 buffers / chunks) ---------- */
  {
    const char *names[NV] = {"a", "b", "c", "d", "e"};
    const char *units[NV] = {"m", "m/s", "rad", "rad/s", "N"};
    const char *dup[2] = {"a", "a"}, *clash[1] = {"time"}, *uu[2] = {"1", "1"};
    const char *nullu[2] = {"1", NULL};
    size_t done = 0, batches[5] = {1, 7, 4089, 9000, NROWS - 1 - 1 - 7 - 4089 - 9000};
    for (i = 0; i < NROWS; i++) {
      t[i] = 0.5e-3 * (double)i;
      for (j = 0; j < NV; j++) series_rows[i * NV + j] = (double)i * (double)(j + 1) - 0.25 * (double)j;
    }
    CHECK_STATUS("series duplicate names",
                 autobal_archive_series_open(a, "/ts", "time", "s", NULL, 2, dup, uu, NULL, &s), AUTOBAL_EINVAL);
    CHECK("series NULL on failure", s == NULL);
    CHECK_STATUS("series var named like dim",
                 autobal_archive_series_open(a, "/ts", "time", "s", NULL, 1, clash, uu, NULL, &s), AUTOBAL_EINVAL);
    CHECK_STATUS("series NULL unit",
                 autobal_archive_series_open(a, "/ts", "time", "s", NULL, 2, names, nullu, NULL, &s), AUTOBAL_EINVAL);
    CHECK_STATUS("series nvars 0", autobal_archive_series_open(a, "/ts", "time", "s", NULL, 0, names, units, NULL, &s),
                 AUTOBAL_EINVAL);
    CHECK_STATUS("series over existing dataset",
                 autobal_archive_series_open(a, "/pendulum/map", "omega", "s", NULL, 1, names, units, NULL, &s),
                 AUTOBAL_EINVAL);
    CHECK("nothing left by failed opens", !autobal_archive_has(a, "/ts/time", NULL));
    CHECK_STATUS("series open", autobal_archive_series_open(a, "/ts", "time", "s", "time", NV, names, units, NULL, &s),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("append 0 rows", autobal_archive_series_append(s, 0, NULL, NULL), AUTOBAL_SUCCESS);
    CHECK_STATUS("append NULL", autobal_archive_series_append(s, 3, NULL, series_rows), AUTOBAL_EINVAL);
    for (i = 0; i < 5; i++) {
      rc = autobal_archive_series_append(s, batches[i], t + done, series_rows + done * NV);
      if (rc != AUTOBAL_SUCCESS) break;
      done += batches[i];
      if (i == 2) CHECK_STATUS("series flush mid-way", autobal_archive_series_flush(s), AUTOBAL_SUCCESS);
    }
    CHECK_STATUS("series appends", rc, AUTOBAL_SUCCESS);
    CHECK("series length after batches", autobal_archive_series_length(s) == NROWS - 1);
    /* a variable over the series dimension sees the rows appended so far */
    {
      const char *dt[1] = {"time"};
      CHECK_STATUS("var over the series dim", autobal_archive_var(a, "/ts", "tcopy", 1, dt, t, "s", NULL),
                   AUTOBAL_SUCCESS);
    }
    rc = autobal_archive_series_append(s, 1, t + NROWS - 1, series_rows + (NROWS - 1) * NV);
    CHECK_STATUS("last row", rc, AUTOBAL_SUCCESS);
    CHECK("series length", autobal_archive_series_length(s) == NROWS);
    CHECK_STATUS("series close", autobal_archive_series_close(s), AUTOBAL_SUCCESS);
    CHECK_STATUS("series close NULL", autobal_archive_series_close(NULL), AUTOBAL_SUCCESS);
    CHECK("series length NULL", autobal_archive_series_length(NULL) == 0);
    /* a second series left open: closed (flushed) by archive_close */
    CHECK_STATUS("series 2 open", autobal_archive_series_open(a, "/ts2", "t", "s", NULL, 1, names, units, NULL, &s),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("series 2 append", autobal_archive_series_append(s, 3, t, series_rows), AUTOBAL_SUCCESS);
  }

  /* ---- status ------------------------------------------------------------ */
  CHECK_STATUS("set_status empty", autobal_archive_set_status(a, "", NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("set_status NULL", autobal_archive_set_status(a, NULL, NULL), AUTOBAL_EINVAL);
  CHECK_STATUS("set_status too long",
               autobal_archive_set_status(a, "0123456789012345678901234567890123456789012345678901234567890123456789", NULL),
               AUTOBAL_EINVAL);
  CHECK_STATUS("set_status", autobal_archive_set_status(a, "incomplete", "interrupted by SIGINT"), AUTOBAL_SUCCESS);
  CHECK("still no final name", !exists(path));
  rc = autobal_archive_close(a, &err);
  a = NULL;
  CHECK_STATUS("close", rc, AUTOBAL_SUCCESS);
  CHECK("final name exists after close", exists(path));
  CHECK("temporary gone after close", !exists(tmp));

  /* ---- read back with the plain HDF5 API ------------------------------- */
  {
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    size_t n;
    double *v;
    H5D_layout_t lay;
    int nf, ok;
    char *created;
    CHECK("HDF5 opens the archive", f >= 0);
    CHECK("Conventions", h5_attr_str_is(f, "/", "Conventions", "CF-1.8 autobal-1"));
    CHECK("status written by close", h5_attr_str_is(f, "/", "status", "incomplete"));
    CHECK("status_reason", h5_attr_str_is(f, "/", "status_reason", "interrupted by SIGINT"));
    CHECK("title", h5_attr_str_is(f, "/", "title", "a title"));
    CHECK("autobal_version", h5_attr_str_is(f, "/", "autobal_version", AUTOBAL_VERSION_STRING));
    CHECK("git_revision", h5_attr_str_is(f, "/", "git_revision", autobal_git_revision()));
    CHECK("gsl_version", h5_attr_str_is(f, "/", "gsl_version", autobal_gsl_version()));
    {
      unsigned maj, mn, rel;
      char hv[32];
      H5get_libversion(&maj, &mn, &rel);
      snprintf(hv, sizeof hv, "%u.%u.%u", maj, mn, rel);
      CHECK("hdf5_version", h5_attr_str_is(f, "/", "hdf5_version", hv));
    }
    /* POSIX shell quoting: safe words bare, others in '...', ' as '\'' */
    CHECK("command_line shell-quoted",
          h5_attr_str_is(f, "/", "command_line", "autobal run 'my file.ini' 'it'\\''s' '' --x=1,2"));
    created = h5_attr_str(f, "/", "created", NULL);
    ok = created != NULL && strlen(created) == 20 && created[4] == '-' && created[7] == '-' && created[10] == 'T' &&
         created[13] == ':' && created[16] == ':' && created[19] == 'Z';
    if (ok) {
      /* within a day of now (UTC date of the test run) */
      struct tm tmv;
      time_t now = time(NULL);
      int yy, mo, dd;
      gmtime_r(&now, &tmv);
      ok = sscanf(created, "%4d-%2d-%2d", &yy, &mo, &dd) == 3 && yy == tmv.tm_year + 1900 && mo >= 1 && mo <= 12;
    }
    CHECK("created is ISO 8601 UTC of this year", ok);
    free(created);

    v = h5_read(f, "/pendulum/map/omega", &n);
    ok = v != NULL && n == 50;
    for (i = 0; ok && i < 50; i++) ok = v[i] == omega[i];
    CHECK("omega values exact", ok);
    free(v);
    v = h5_read(f, "/pendulum/map/root", &n);
    ok = v != NULL && n == 4;
    for (i = 0; ok && i < 4; i++) ok = v[i] == (double)i;
    CHECK("root dim = 0..3", ok);
    free(v);
    v = h5_read(f, "/pendulum/map/m2", &n);
    ok = v != NULL && n == 200;
    for (i = 0; ok && i < 200; i++) ok = v[i] == m2[i];
    CHECK("m2 values exact (C order)", ok);
    free(v);
    v = h5_read(f, "/pendulum/map/im2", &n);
    ok = v != NULL && n == 200;
    for (i = 0; ok && i < 200; i++) ok = v[i] == (double)im2[i];
    CHECK("im2 values exact", ok);
    free(v);
    {
      hid_t d = H5Dopen2(f, "/pendulum/map/im2", H5P_DEFAULT), ty = H5Dget_type(d);
      CHECK("im2 stored as 32-bit integer", H5Tget_class(ty) == H5T_INTEGER && H5Tget_size(ty) == 4);
      H5Tclose(ty);
      H5Dclose(d);
    }
    v = h5_read(f, "/pendulum/s0", &n);
    CHECK("scalar var", v != NULL && n == 1 && v[0] == omega[3]);
    free(v);
    CHECK("omega is a dimension scale named omega", h5_scale_name_is(f, "/pendulum/map/omega", "omega"));
    CHECK("root is a dimension scale named root", h5_scale_name_is(f, "/pendulum/map/root", "root"));
    CHECK("m2 dim 0 = omega", h5_attached(f, "/pendulum/map/m2", "/pendulum/map/omega", 0));
    CHECK("m2 dim 1 = root", h5_attached(f, "/pendulum/map/m2", "/pendulum/map/root", 1));
    CHECK("m2 dim 0 is not root", !h5_attached(f, "/pendulum/map/m2", "/pendulum/map/root", 0));
    CHECK("sq dims 0 and 1 = root", h5_attached(f, "/pendulum/map/sq", "/pendulum/map/root", 0) &&
                                       h5_attached(f, "/pendulum/map/sq", "/pendulum/map/root", 1));
    CHECK("m2b (absolute dim) dim 0 = omega", h5_attached(f, "/pendulum/map/m2b", "/pendulum/map/omega", 0));
    CHECK("subgroup var attached to parent's omega",
          h5_attached(f, "/pendulum/map/deep/er/v", "/pendulum/map/omega", 0));
    CHECK("m2 units", h5_attr_str_is(f, "/pendulum/map/m2", "units", "1/s"));
    CHECK("m2 long_name defaults to name", h5_attr_str_is(f, "/pendulum/map/m2", "long_name", "m2"));
    CHECK("omega units", h5_attr_str_is(f, "/pendulum/map/omega", "units", "rad/s"));
    CHECK("omega long_name", h5_attr_str_is(f, "/pendulum/map/omega", "long_name", "speed"));
    CHECK("root units 1", h5_attr_str_is(f, "/pendulum/map/root", "units", "1"));
    CHECK("root long_name", h5_attr_str_is(f, "/pendulum/map/root", "long_name", "root"));
    CHECK("string attr on dataset (UTF-8)", h5_attr_str_is(f, "/pendulum/map/m2", "note", "h\xc3\xa9llo"));
    CHECK_CLOSE("mass replaced", h5_attr_double(f, "/pendulum", "mass"), 0.5, 0, 0);
    CHECK("mass_units", h5_attr_str_is(f, "/pendulum", "mass_units", "kg"));
    CHECK("zeta_units", h5_attr_str_is(f, "/pendulum", "zeta_units", "1"));
    CHECK("no plain_units", h5_attr_str(f, "/pendulum", "plain_units", NULL) == NULL);
    CHECK_CLOSE("int attr", h5_attr_double(f, "/pendulum", "n"), -1234567890123.0, 0, 0);
    {
      hid_t o = H5Oopen(f, "/", H5P_DEFAULT), at = H5Aopen(o, "arr", H5P_DEFAULT), sp = H5Aget_space(at);
      double arr[3] = {0, 0, 0};
      hsize_t nn = 0;
      H5Sget_simple_extent_dims(sp, &nn, NULL);
      H5Aread(at, H5T_NATIVE_DOUBLE, arr);
      CHECK("array attr", nn == 3 && arr[0] == 1.0 && arr[1] == -2.5 && arr[2] == 1e-300);
      H5Sclose(sp);
      H5Aclose(at);
      H5Oclose(o);
      CHECK("arr_units", h5_attr_str_is(f, "/", "arr_units", "m"));
    }
    v = h5_read(f, "/big/field", &n);
    ok = v != NULL && n == NX * NY;
    for (i = 0; ok && i < NX * NY; i++) ok = v[i] == big[i];
    CHECK("big field exact", ok);
    free(v);
    h5_layout(f, "/big/field", &lay, &nf);
    CHECK("big field chunked", lay == H5D_CHUNKED);
    CHECK("big field shuffle + deflate", nf == 2);
    h5_layout(f, "/big/small", &lay, &nf);
    CHECK("small var contiguous, unfiltered", lay == H5D_CONTIGUOUS && nf == 0);
    {
      long sz = file_size(path);
      printf("     archive size %ld bytes (uncompressed payload > %ld)\n", sz,
             (long)(sizeof big + sizeof series_rows + sizeof t));
      CHECK("compression made the file smaller than the raw payload",
            sz > 0 && sz < (long)(sizeof big + sizeof series_rows + sizeof t));
    }
    /* series */
    v = h5_read(f, "/ts/time", &n);
    ok = v != NULL && n == NROWS;
    for (i = 0; ok && i < NROWS; i++) ok = v[i] == t[i];
    CHECK("series time: 20000 rows exact", ok);
    free(v);
    for (j = 0; j < NV; j++) {
      char p[16], what[96];
      snprintf(p, sizeof p, "/ts/%c", (char)('a' + j));
      v = h5_read(f, p, &n);
      ok = v != NULL && n == NROWS;
      for (i = 0; ok && i < NROWS; i++) ok = v[i] == series_rows[i * NV + j];
      snprintf(what, sizeof what, "series column %s exact", p);
      CHECK(what, ok);
      free(v);
      snprintf(what, sizeof what, "series column %s attached to time", p);
      CHECK(what, h5_attached(f, p, "/ts/time", 0));
    }
    CHECK("series d units", h5_attr_str_is(f, "/ts/d", "units", "rad/s"));
    CHECK("series time units", h5_attr_str_is(f, "/ts/time", "units", "s"));
    CHECK("series time is unlimited", h5_maxdim_unlimited(f, "/ts/time"));
    CHECK("series time is a scale", h5_scale_name_is(f, "/ts/time", "time"));
    h5_layout(f, "/ts/a", &lay, &nf);
    CHECK("series chunked + compressed", lay == H5D_CHUNKED && nf == 2);
    v = h5_read(f, "/ts/tcopy", &n);
    CHECK("var over series dim has the rows appended before it", v != NULL && n == NROWS - 1 && v[7] == t[7]);
    free(v);
    v = h5_read(f, "/ts2/a", &n);
    CHECK("unclosed series flushed by archive_close", v != NULL && n == 3 && v[2] == series_rows[2]);
    free(v);
    H5Fclose(f);
  }

  /* ---- read back with the library's reading side ----------------------- */
  rc = autobal_archive_open_read(path, &r, &err);
  CHECK_STATUS("open_read", rc, AUTOBAL_SUCCESS);
  if (r != NULL) {
    size_t len = 0, dims[AUTOBAL_ARCHIVE_MAX_RANK], count = 0;
    double dv = 0, rb[200];
    int rank = -1, cnt[2] = {0, 0};
    CHECK_STATUS("read status", autobal_archive_read_attr_string(r, "/", "status", buf, sizeof buf, &len),
                 AUTOBAL_SUCCESS);
    CHECK("status value", strcmp(buf, "incomplete") == 0 && len == 10);
    CHECK_STATUS("truncating read", autobal_archive_read_attr_string(r, "/", "status", buf, 5, &len), AUTOBAL_WARNING);
    CHECK("truncated to 4 chars, full length reported", strcmp(buf, "inco") == 0 && len == 10);
    CHECK_STATUS("read fixed-length NAME attr of a scale",
                 autobal_archive_read_attr_string(r, "/pendulum/map/omega", "NAME", buf, sizeof buf, NULL),
                 AUTOBAL_SUCCESS);
    CHECK("NAME = omega", strcmp(buf, "omega") == 0);
    CHECK_STATUS("read double", autobal_archive_read_attr_double(r, "/pendulum", "mass", &dv), AUTOBAL_SUCCESS);
    CHECK_CLOSE("mass", dv, 0.5, 0, 0);
    CHECK_STATUS("read int as double", autobal_archive_read_attr_double(r, "/pendulum", "n", &dv), AUTOBAL_SUCCESS);
    CHECK_CLOSE("n", dv, -1234567890123.0, 0, 0);
    CHECK_STATUS("string as double", autobal_archive_read_attr_double(r, "/pendulum", "mass_units", &dv),
                 AUTOBAL_EFORMAT);
    CHECK_STATUS("array as double", autobal_archive_read_attr_double(r, "/", "arr", &dv), AUTOBAL_EFORMAT);
    CHECK_STATUS("double as string", autobal_archive_read_attr_string(r, "/pendulum", "mass", buf, sizeof buf, NULL),
                 AUTOBAL_EFORMAT);
    CHECK_STATUS("missing attr", autobal_archive_read_attr_double(r, "/pendulum", "nosuch", &dv), AUTOBAL_EFORMAT);
    CHECK_MSG("missing attr named", autobal_archive_errmsg(r), "nosuch");
    CHECK_STATUS("missing object", autobal_archive_read_attr_double(r, "/x/y", "mass", &dv), AUTOBAL_EINVAL);
    CHECK_STATUS("shape", autobal_archive_var_shape(r, "/pendulum/map/m2", &rank, dims, &count), AUTOBAL_SUCCESS);
    CHECK("shape 50 x 4", rank == 2 && dims[0] == 50 && dims[1] == 4 && count == 200);
    CHECK_STATUS("shape scalar", autobal_archive_var_shape(r, "/pendulum/s0", &rank, dims, &count), AUTOBAL_SUCCESS);
    CHECK("rank 0, 1 element", rank == 0 && count == 1);
    CHECK_STATUS("shape of a group", autobal_archive_var_shape(r, "/pendulum", &rank, dims, NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("read_var", autobal_archive_read_var(r, "/pendulum/map/im2", rb, 200), AUTOBAL_SUCCESS);
    CHECK("read_var int -> double exact", rb[0] == -100.0 && rb[199] == 99.0);
    CHECK_STATUS("read_var buffer too small", autobal_archive_read_var(r, "/pendulum/map/m2", rb, 199), AUTOBAL_EINVAL);
    CHECK_MSG("size needed in message", autobal_archive_errmsg(r), "200");
    CHECK_STATUS("read_var missing", autobal_archive_read_var(r, "/none", rb, 200), AUTOBAL_EINVAL);
    CHECK("has group", autobal_archive_has(r, "/pendulum/map", NULL) == 1);
    CHECK("has attr", autobal_archive_has(r, "/", "command_line") == 1);
    CHECK("has not", autobal_archive_has(r, "/pendulum/zzz", NULL) == 0 && autobal_archive_has(r, "/", "zz") == 0);
    CHECK_STATUS("list /pendulum/map", autobal_archive_list(r, "/pendulum/map", list_count_cb, cnt), AUTOBAL_SUCCESS);
    /* omega root m2 im2 m2b sq (datasets) + deep (group) */
    CHECK("list counts 6 datasets, 1 group", cnt[0] == 6 && cnt[1] == 1);
    CHECK_STATUS("list missing group", autobal_archive_list(r, "/nope", list_count_cb, cnt), AUTOBAL_EINVAL);
    CHECK_STATUS("write on read handle", autobal_archive_group(r, "/x"), AUTOBAL_EINVAL);
    CHECK_MSG("read-only message", autobal_archive_errmsg(r), "read-only");
    CHECK_STATUS("set_status on read handle", autobal_archive_set_status(r, "complete", NULL), AUTOBAL_EINVAL);
    CHECK_STATUS("close read handle", autobal_archive_close(r, &err), AUTOBAL_SUCCESS);
    CHECK("file still there after closing a read handle", exists(path));
    r = NULL;
    CHECK_STATUS("open_read again", autobal_archive_open_read(path, &r, &err), AUTOBAL_SUCCESS);
    autobal_archive_discard(r);
    r = NULL;
    CHECK("discarding a read handle keeps the file", exists(path));
  }

  /* ---- EEXIST, overwrite -------------------------------------------------- */
  autobal_error_clear(&err);
  rc = autobal_archive_create(path, 0, &a, &err);
  CHECK_STATUS("existing file without overwrite", rc, AUTOBAL_EEXIST);
  CHECK("out NULL on failure", a == NULL);
  CHECK_MSG("EEXIST names path", err.message, path);
  CHECK("no temporary left", !exists(tmp));
  rc = autobal_archive_create(path, 1, &a, &err);
  CHECK_STATUS("overwrite allowed", rc, AUTOBAL_SUCCESS);
  CHECK_STATUS("provenance new title", autobal_archive_provenance(a, "second", 0, NULL), AUTOBAL_SUCCESS);
  CHECK("old file still in place while writing", exists(path) && exists(tmp));
  {
    /* old content intact until close */
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK("old title readable during rewrite", f >= 0 && h5_attr_str_is(f, "/", "title", "a title"));
    if (f >= 0) H5Fclose(f);
  }
  CHECK_STATUS("close overwrite", autobal_archive_close(a, NULL), AUTOBAL_SUCCESS);
  {
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK("replaced: new title", f >= 0 && h5_attr_str_is(f, "/", "title", "second"));
    CHECK("default final status complete", f >= 0 && h5_attr_str_is(f, "/", "status", "complete"));
    CHECK("no status_reason by default", f >= 0 && h5_attr_str(f, "/", "status_reason", NULL) == NULL);
    CHECK("empty command line", f >= 0 && h5_attr_str_is(f, "/", "command_line", ""));
    if (f >= 0) H5Fclose(f);
  }

  /* ---- the final name appearing while writing (no overwrite) ------------ */
  snprintf(p2, sizeof p2, "%s/test_archive_race_%ld.h5", AUTOBAL_TEST_TMP_DIR, (long)getpid());
  remove(p2);
  rc = autobal_archive_create(p2, 0, &a, &err);
  CHECK_STATUS("create p2", rc, AUTOBAL_SUCCESS);
  {
    FILE *fp = fopen(p2, "w");
    char tmp2[1100];
    if (fp) {
      fputs("someone else's file\n", fp);
      fclose(fp);
    }
    snprintf(tmp2, sizeof tmp2, "%s.partial-%ld", p2, (long)getpid());
    rc = autobal_archive_close(a, &err);
    CHECK_STATUS("close refuses to clobber a file that appeared", rc, AUTOBAL_EEXIST);
    CHECK_MSG("message names the kept temporary", err.message, tmp2);
    CHECK("temporary kept for inspection", exists(tmp2));
    CHECK("other file untouched", file_size(p2) == 20);
    remove(tmp2);
    remove(p2);
  }

  /* ---- a command line that is not UTF-8: bad bytes become '?' ----------- */
  rc = autobal_archive_create(p2, 1, &a, &err);
  CHECK_STATUS("create p2 (argv)", rc, AUTOBAL_SUCCESS);
  {
    const char *av[3] = {"autobal", "caf\xe9", "a\"b"};
    CHECK_STATUS("provenance with a non-UTF-8 argument", autobal_archive_provenance(a, "x", 3, av),
                 AUTOBAL_SUCCESS);
    CHECK_STATUS("close p2", autobal_archive_close(a, NULL), AUTOBAL_SUCCESS);
    {
      hid_t f = H5Fopen(p2, H5F_ACC_RDONLY, H5P_DEFAULT);
      CHECK("invalid byte replaced, double quote single-quoted",
            f >= 0 && h5_attr_str_is(f, "/", "command_line", "autobal 'caf?' 'a\"b'"));
      if (f >= 0) H5Fclose(f);
    }
    remove(p2);
  }

  /* ---- discard ------------------------------------------------------------ */
  rc = autobal_archive_create(p2, 0, &a, &err);
  CHECK_STATUS("create for discard", rc, AUTOBAL_SUCCESS);
  {
    const char *nm[1] = {"q"}, *un[1] = {"1"};
    autobal_archive_coord(a, "/g", "c", 3, omega, "1", NULL);
    autobal_archive_series_open(a, "/g", "t", "s", NULL, 1, nm, un, NULL, &s);
    autobal_archive_series_append(s, 2, t, series_rows);
  }
  autobal_archive_discard(a);
  a = NULL;
  {
    char tmp2[1100];
    snprintf(tmp2, sizeof tmp2, "%s.partial-%ld", p2, (long)getpid());
    CHECK("discard leaves no final file", !exists(p2));
    CHECK("discard leaves no temporary", !exists(tmp2));
  }
  autobal_archive_discard(NULL);
  CHECK_STATUS("close NULL", autobal_archive_close(NULL, NULL), AUTOBAL_SUCCESS);

  /* ---- unwritable paths ---------------------------------------------------- */
  rc = autobal_archive_create("/nonexistent-autobal-dir/x.h5", 0, &a, &err);
  CHECK_STATUS("missing directory", rc, AUTOBAL_EIO);
  CHECK("no handle", a == NULL);
  CHECK_MSG("names the path", err.message, "/nonexistent-autobal-dir/x.h5");
  CHECK_MSG("gives the OS reason", err.message, "No such file or directory");
  rc = autobal_archive_create("/proc/autobal.h5", 0, &a, &err);
  CHECK_STATUS("/proc/autobal.h5", rc, AUTOBAL_EIO);
  CHECK_MSG("names the path", err.message, "/proc/autobal.h5");
  rc = autobal_archive_create(AUTOBAL_TEST_TMP_DIR, 1, &a, &err);
  CHECK_STATUS("a directory", rc, AUTOBAL_EIO);
  CHECK_STATUS("empty path", autobal_archive_create("", 0, &a, &err), AUTOBAL_EINVAL);
  CHECK_STATUS("NULL out", autobal_archive_create(path, 1, NULL, NULL), AUTOBAL_EINVAL);

  /* ---- open_read on foreign / damaged files -------------------------------- */
  {
    char q[1100];
    FILE *fp;
    char sample[1100];
    long full;
    /* a real archive with data to truncate: the sample */
    snprintf(sample, sizeof sample, "%s.sample", path);
    CHECK("sample archive written", write_sample(sample) == 0);
    full = file_size(sample);
    rc = autobal_archive_open_read("/nonexistent-autobal-dir/x.h5", &r, &err);
    CHECK_STATUS("open_read missing file", rc, AUTOBAL_EIO);
    CHECK("no handle", r == NULL);
    snprintf(q, sizeof q, "%s.txt", path);
    fp = fopen(q, "w");
    if (fp) {
      fputs("[rotor]\nmass = 1\n", fp);
      fclose(fp);
    }
    rc = autobal_archive_open_read(q, &r, &err);
    CHECK_STATUS("text file", rc, AUTOBAL_EFORMAT);
    CHECK_MSG("says not HDF5", err.message, "not an HDF5 file");
    CHECK_MSG("names the file", err.message, q);
    remove(q);
    snprintf(q, sizeof q, "%s.trunc", path);
    rc = autobal_archive_open_read(sample, &r, &err);
    CHECK_STATUS("the untruncated sample opens", rc, AUTOBAL_SUCCESS);
    autobal_archive_close(r, NULL);
    r = NULL;
    copy_prefix(sample, q, full - 1);
    CHECK_STATUS("truncated archive (one byte short)", autobal_archive_open_read(q, &r, &err), AUTOBAL_EFORMAT);
    copy_prefix(sample, q, full / 2);
    rc = autobal_archive_open_read(q, &r, &err);
    CHECK_STATUS("truncated archive (half)", rc, AUTOBAL_EFORMAT);
    printf("     message: %s\n", err.message);
    CHECK_MSG("truncated: names the file", err.message, q);
    copy_prefix(sample, q, 200);
    CHECK_STATUS("truncated archive (200 bytes)", autobal_archive_open_read(q, &r, &err), AUTOBAL_EFORMAT);
    copy_prefix(sample, q, 4);
    CHECK_STATUS("truncated archive (4 bytes)", autobal_archive_open_read(q, &r, &err), AUTOBAL_EFORMAT);
    copy_prefix(sample, q, 0);
    CHECK_STATUS("empty file", autobal_archive_open_read(q, &r, &err), AUTOBAL_EFORMAT);
    remove(q);
    remove(sample);
    /* a foreign HDF5 file: no Conventions, then a wrong one */
    snprintf(q, sizeof q, "%s.foreign", path);
    {
      hid_t f = H5Fcreate(q, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      H5Fclose(f);
    }
    rc = autobal_archive_open_read(q, &r, &err);
    CHECK_STATUS("HDF5 without Conventions", rc, AUTOBAL_EFORMAT);
    CHECK_MSG("says Conventions", err.message, "Conventions");
    {
      hid_t f = H5Fopen(q, H5F_ACC_RDWR, H5P_DEFAULT);
      H5LTset_attribute_string(f, "/", "Conventions", "CF-1.8");
      H5Fclose(f);
    }
    rc = autobal_archive_open_read(q, &r, &err);
    CHECK_STATUS("HDF5 with other Conventions", rc, AUTOBAL_EFORMAT);
    CHECK_MSG("quotes the value", err.message, "CF-1.8");
    remove(q);
  }

  /* ---- write failures inside HDF5: a file-size limit (like a full disk) ----
   * Run in a child process: HDF5 1.10 leaves a file whose close failed in a state
   * that crashes H5_term_library at exit (h5py#914, fixed upstream in HDF5 1.14 by
   * HDFGroup/hdf5#2291); the child leaves with _exit(), skipping that handler. */
  {
    pid_t pid;
    int wst = 0;
    fflush(stdout);
    pid = fork();
    if (pid == 0) {
      struct rlimit old_lim, lim;
      char tmp2[1100];
      unsigned long long state = 12345u;
      const char *dxy[2] = {"x", "y"}, *nm[1] = {"q"}, *un[1] = {"1"};
      check_failures_ = 0;
      snprintf(tmp2, sizeof tmp2, "%s.partial-%ld", p2, (long)getpid());
      remove(p2);
      for (i = 0; i < NX * NY; i++) { /* incompressible: a linear congruential sequence */
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        big[i] = (double)(state >> 11) * 0x1.0p-53;
      }
      signal(SIGXFSZ, SIG_IGN); /* write() then fails with EFBIG instead of killing us */
      if (getrlimit(RLIMIT_FSIZE, &old_lim) == 0 && autobal_archive_create(p2, 0, &a, &err) == AUTOBAL_SUCCESS) {
        lim = old_lim;
        lim.rlim_cur = 65536;
        autobal_archive_coord(a, "/f", "x", NX, x, "m", NULL);
        autobal_archive_coord(a, "/f", "y", NY, y, "m", NULL);
        autobal_archive_series_open(a, "/f", "t", "s", NULL, 1, nm, un, NULL, &s);
        autobal_archive_series_append(s, 10, t, series_rows);
        CHECK("[child] file-size limit set", setrlimit(RLIMIT_FSIZE, &lim) == 0);
        rc = autobal_archive_var(a, "/f", "noise", 2, dxy, big, "1", NULL);
        printf("     var under a 64 KiB file-size limit: %d %s\n", rc, autobal_archive_errmsg(a));
        if (rc == AUTOBAL_SUCCESS) rc = autobal_archive_series_flush(s);
        CHECK_STATUS("[child] HDF5 write failure becomes EIO", rc, AUTOBAL_EIO);
        CHECK_MSG("[child] with the HDF5 text", autobal_archive_errmsg(a), "HDF5");
        CHECK_MSG("[child] with the OS reason", autobal_archive_errmsg(a), "File too large");
        CHECK("[child] message on one line", strchr(autobal_archive_errmsg(a), '\n') == NULL);
        rc = autobal_archive_close(a, &err);
        printf("     close: %s\n", err.message);
        CHECK_STATUS("[child] close fails with EIO", rc, AUTOBAL_EIO);
        CHECK_MSG("[child] close names the kept temporary", err.message, tmp2);
        CHECK("[child] final name not created", !exists(p2));
        CHECK("[child] temporary kept for inspection", exists(tmp2));
        CHECK("[child] no HDF5 auto-handler call", silent_handler_calls == 0);
        setrlimit(RLIMIT_FSIZE, &old_lim);
        remove(tmp2);
      } else {
        CHECK("[child] set up the file-size limit test", 0);
      }
      fflush(stdout);
      _exit(check_failures_ == 0 ? 0 : 1);
    }
    CHECK("fork for the write-failure test", pid > 0);
    if (pid > 0) {
      waitpid(pid, &wst, 0);
      CHECK("write-failure checks in the child passed", WIFEXITED(wst) && WEXITSTATUS(wst) == 0);
    }
  }

  /* ---- the series writer thread ---------------------------------------------- */
  test_series_writer(path);

  /* ---- attributes listed and read as arrays, datasets described, HDF5 version ---- */
  test_attr_reading(path);
  test_foreign_reading(path);
  test_hdf5_version(path);

  /* ---- no printing, handler restored, no leaked HDF5 ids ------------------ */
  {
    H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
    CHECK("HDF5 error handler restored", old_func == counting_handler);
    printf("     HDF5 automatic error handler calls: %d\n", silent_handler_calls);
    CHECK("HDF5 never reported an error through the auto handler", silent_handler_calls == 0);
    CHECK("no open HDF5 objects left", H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL) == 0);
  }
  /* list: early stop returns the callback's value */
  rc = autobal_archive_create(p2, 1, &a, &err);
  if (rc == AUTOBAL_SUCCESS) {
    autobal_archive_group(a, "/a");
    autobal_archive_group(a, "/b");
    autobal_archive_group(a, "/c");
    CHECK_STATUS("list stops with the callback's value", autobal_archive_list(a, "/", list_stop_cb, NULL), 42);
    autobal_archive_discard(a);
  }

  remove(path);
  return check_summary();
}
