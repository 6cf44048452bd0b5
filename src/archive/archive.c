/* archive.c: the HDF5 archive (see include/autobal/archive.h).
 *
 * Knows no physics: groups, datasets, dimension scales (netCDF-4 / h5netcdf
 * conventions: a coordinate is a dataset made a dimension scale whose NAME is the
 * dimension name, variables have the scales attached), units/long_name attributes,
 * provenance, atomic creation through a temporary file.  This file is the writing side
 * and what both sides share (declared in archive_internal.h); the reading side is
 * archive_read.c.
 *
 * May use: HDF5, POSIX threads and files, core (internal.h, autobal/version.h).  No model, no
 * analysis, no study: nothing of src/ but core.
 *
 * HDF5 error handling: every public entry point takes the process-wide HDF5 lock and
 * switches HDF5's automatic error printing off (autobal_archive_h5_enter_), and restores the caller's
 * handler and releases the lock on return (autobal_archive_h5_leave_).  A failing HDF5 call is
 * translated into AUTOBAL_EIO by autobal_archive_h5fail_(), which walks the HDF5 error stack
 * immediately (before any other HDF5 API call clears it) and appends its text to the
 * message.  Every hid_t is closed on every path.
 *
 * Threads.  Streamed series are written by one background thread per archive (the
 * "writer", started at the first full series buffer): _series_append copies rows into
 * the series' fill buffer (one of two, both allocated at _series_open) and, when it is
 * full, hands it to the writer and goes on filling the other one; the writer extends
 * the datasets and writes (HDF5 runs the shuffle + deflate filters there, on another
 * core).  A caller waits only when the writer has not finished the previous buffer of
 * the same series.  HDF5 is not thread-safe in every build (Debian 12's 1.10.8 is built
 * with --enable-threadsafe and has one error stack and automatic error handler per
 * thread; many builds have no locking at all), so every HDF5 call of this module, in
 * any thread and for any archive, is made holding autobal_archive_h5_lock_ (below), and the writer
 * silences HDF5's error printing in its own thread too (autobal_archive_h5_enter_).  Lock
 * order: autobal_archive_h5_lock_ may be held while taking an archive's mutex `m`, never the reverse,
 * and nobody waits for the writer while holding autobal_archive_h5_lock_.  Writer failures are kept in
 * the series (werr, wfailed) and reported by the caller's next call on it. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include "autobal/archive.h"
#include "autobal/version.h"
#include "archive/archive_internal.h"
#include "internal.h"

#define CHUNK_TARGET (256u * 1024u) /* bytes per chunk of a compressed fixed-size dataset */
#define DEFLATE_LEVEL 4u        /* fixed-size datasets (_var, _coord, _dim) */
#define SERIES_DEFLATE_LEVEL 1u /* series: 1/3 less CPU than level 4, files ~5% larger */
#define SERIES_BUF_CHUNKS 1u /* chunks of AUTOBAL_ARCHIVE_SERIES_ROWS rows per series buffer (2 and
                              * 4 measured no faster) */

/* The one lock for all HDF5 calls of the process made by this module (all archives,
 * the callers' threads and the series writers), for HDF5 builds without thread safety.
 * Statically initialised; it holds no data, so it is not mutable global state in the
 * sense of the conventions.  Held only for the duration of HDF5 calls (never while
 * waiting for a writer). */
pthread_mutex_t autobal_archive_h5_lock_ = PTHREAD_MUTEX_INITIALIZER;


/* ------------------------------------------------------------------------ */
/* HDF5 error handling                                                        */
/* ------------------------------------------------------------------------ */

static void quiet_begin(autobal_archive_quiet_ *q) {
  q->func = NULL;
  q->data = NULL;
  q->saved = H5Eget_auto2(H5E_DEFAULT, &q->func, &q->data) >= 0;
  (void)H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

static void quiet_end(const autobal_archive_quiet_ *q) {
  if (q->saved) (void)H5Eset_auto2(H5E_DEFAULT, q->func, q->data);
}

/* Take the HDF5 lock and silence HDF5's error printing; autobal_archive_h5_leave_ undoes both. */
void autobal_archive_h5_enter_(autobal_archive_quiet_ *q) {
  (void)pthread_mutex_lock(&autobal_archive_h5_lock_);
  quiet_begin(q);
}

void autobal_archive_h5_leave_(const autobal_archive_quiet_ *q) {
  quiet_end(q);
  (void)pthread_mutex_unlock(&autobal_archive_h5_lock_);
}

/* "MAJOR.MINOR.RELEASE" of the HDF5 library in use; caller holds autobal_archive_h5_lock_. */
static void hdf5_version_locked(char *buf, size_t size) {
  unsigned maj = 0, min = 0, rel = 0;
  if (H5get_libversion(&maj, &min, &rel) < 0) snprintf(buf, size, "unknown");
  else snprintf(buf, size, "%u.%u.%u", maj, min, rel);
}

/* Declared in autobal/version.h; here because it calls HDF5 (under autobal_archive_h5_lock_, like every
 * HDF5 call of the library: a series writer may be running in another thread). */
void autobal_hdf5_version(char *buf, unsigned long size) {
  autobal_archive_quiet_ q;
  if (buf == NULL || size == 0) return;
  autobal_archive_h5_enter_(&q);
  hdf5_version_locked(buf, (size_t)size);
  autobal_archive_h5_leave_(&q);
}

typedef struct {
  char outer[200]; /* the API function's description */
  char inner[280]; /* the most specific description */
  int n;
} h5walk_ctx;

static herr_t h5walk_cb(unsigned n, const H5E_error2_t *e, void *vctx) {
  h5walk_ctx *w = (h5walk_ctx *)vctx;
  const char *desc = (e->desc != NULL && e->desc[0] != '\0') ? e->desc : "(no description)";
  char *p;
  if (n == 0) snprintf(w->outer, sizeof w->outer, "%s", desc);
  snprintf(w->inner, sizeof w->inner, "%s", desc);
  /* Drop what is noise for a user: the tails ", flags = ..." (open failures) and
   * ", buf = 0x..." (write failures), the "time = <ctime>\n, " part of write
   * failures; flatten any remaining control characters. */
  if ((p = strstr(w->inner, ", flags = ")) != NULL) *p = '\0';
  if ((p = strstr(w->inner, ", buf = ")) != NULL) *p = '\0';
  if ((p = strstr(w->inner, "time = ")) != NULL) {
    char *q = strchr(p, '\n');
    if (q != NULL) {
      q++;
      if (q[0] == ',' && q[1] == ' ') q += 2;
      memmove(p, q, strlen(q) + 1);
    }
  }
  for (p = w->inner; *p; p++)
    if ((unsigned char)*p < 0x20u) *p = ' ';
  w->n++;
  return 0;
}

/* Text of the current HDF5 error stack: "<most specific> [<API-level>]".  Must be
 * called right after the failing HDF5 call (any other API call clears the stack). */
static void h5stack(char *buf, size_t size) {
  h5walk_ctx w;
  memset(&w, 0, sizeof w);
  (void)H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, h5walk_cb, &w);
  if (w.n == 0) snprintf(buf, size, "HDF5 error (no details)");
  else if (w.n == 1 || strcmp(w.inner, w.outer) == 0) snprintf(buf, size, "HDF5: %s", w.inner);
  else snprintf(buf, size, "HDF5: %.270s [%.190s]", w.inner, w.outer);
}

/* Record an HDF5 failure: "<context>: HDF5: ...".  Must be called right after the
 * failing HDF5 call.  Returns AUTOBAL_EIO. */
int autobal_archive_h5fail_(autobal_error *err, const char *fmt, ...) {
  char ctx[AUTOBAL_ERRMSG_SIZE], stack[AUTOBAL_ERRMSG_SIZE];
  va_list ap;
  h5stack(stack, sizeof stack);
  va_start(ap, fmt);
  vsnprintf(ctx, sizeof ctx, fmt, ap);
  va_end(ap);
  return autobal_error_set(err, AUTOBAL_EIO, "%.250s: %.250s", ctx, stack);
}

/* ------------------------------------------------------------------------ */
/* Names, paths, strings                                                      */
/* ------------------------------------------------------------------------ */

/* Length of the valid UTF-8 sequence starting at s, 0 if invalid. */
static size_t utf8_seq(const unsigned char *s) {
  unsigned c = s[0];
  size_t n, i;
  unsigned cp;
  if (c < 0x80u) return 1;
  if (c >= 0xC2u && c <= 0xDFu) { n = 2; cp = c & 0x1Fu; }
  else if (c >= 0xE0u && c <= 0xEFu) { n = 3; cp = c & 0x0Fu; }
  else if (c >= 0xF0u && c <= 0xF4u) { n = 4; cp = c & 0x07u; }
  else return 0;
  for (i = 1; i < n; i++) {
    if ((s[i] & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (s[i] & 0x3Fu);
  }
  if (n == 3 && (cp < 0x800u || (cp >= 0xD800u && cp <= 0xDFFFu))) return 0;
  if (n == 4 && (cp < 0x10000u || cp > 0x10FFFFu)) return 0;
  return n;
}

static int utf8_valid(const char *s) {
  const unsigned char *p = (const unsigned char *)s;
  while (*p) {
    size_t n = utf8_seq(p);
    if (n == 0) return 0;
    p += n;
  }
  return 1;
}

/* A name: 1..NAME_MAX bytes of valid UTF-8, no '/', no control characters, not "."/"..". */
static int check_name(autobal_error *err, const char *what, const char *name) {
  size_t len, i;
  if (name == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "%s is NULL", what);
  len = strlen(name);
  if (len == 0) return autobal_error_set(err, AUTOBAL_EINVAL, "%s is empty", what);
  if (len > AUTOBAL_ARCHIVE_NAME_MAX)
    return autobal_error_set(err, AUTOBAL_EINVAL, "%s '%.40s...' is too long (%zu bytes, at most %d)",
                             what, name, len, AUTOBAL_ARCHIVE_NAME_MAX);
  if (strcmp(name, ".") == 0 || strcmp(name, "..") == 0)
    return autobal_error_set(err, AUTOBAL_EINVAL, "%s '%s' is not allowed", what, name);
  for (i = 0; i < len; i++) {
    unsigned char c = (unsigned char)name[i];
    if (c == '/' || c < 0x20u || c == 0x7Fu)
      return autobal_error_set(err, AUTOBAL_EINVAL,
                               "%s '%.200s' contains '/' or a control character", what, name);
  }
  if (!utf8_valid(name))
    return autobal_error_set(err, AUTOBAL_EINVAL, "%s is not valid UTF-8", what);
  return AUTOBAL_SUCCESS;
}

/* Attribute names that belong to HDF5 dimension scales and netCDF: never written,
 * not listed by autobal_archive_list_attrs. */
int autobal_archive_reserved_attr_name_(const char *name) {
  return strcmp(name, "CLASS") == 0 || strcmp(name, "NAME") == 0 || strcmp(name, "DIMENSION_LIST") == 0 ||
         strcmp(name, "REFERENCE_LIST") == 0 || strncmp(name, "_Netcdf", 7) == 0 || strncmp(name, "_nc", 3) == 0 ||
         strcmp(name, "_NCProperties") == 0;
}

static int check_attr_name(autobal_error *err, const char *name) {
  int rc = check_name(err, "attribute name", name);
  if (rc != AUTOBAL_SUCCESS) return rc;
  if (autobal_archive_reserved_attr_name_(name))
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "attribute name '%s' is reserved (HDF5 dimension scales / netCDF)", name);
  return AUTOBAL_SUCCESS;
}

static int check_text(autobal_error *err, const char *what, const char *s) {
  if (s == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "%s is NULL", what);
  if (!utf8_valid(s)) return autobal_error_set(err, AUTOBAL_EINVAL, "%s is not valid UTF-8", what);
  return AUTOBAL_SUCCESS;
}

/* Normalise a slash-separated path: "a//b/" -> "/a/b", "" or "/" -> "/". */
int autobal_archive_norm_path_(autobal_error *err, const char *what, const char *in, char *out,
                               size_t size) {
  size_t o = 0;
  const char *p = in;
  if (in == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "%s is NULL", what);
  out[0] = '/';
  out[1] = '\0';
  o = 0;
  while (*p) {
    const char *q;
    size_t len;
    char comp[AUTOBAL_ARCHIVE_NAME_MAX + 1];
    int rc;
    while (*p == '/') p++;
    if (*p == '\0') break;
    q = p;
    while (*q && *q != '/') q++;
    len = (size_t)(q - p);
    if (len > AUTOBAL_ARCHIVE_NAME_MAX)
      return autobal_error_set(err, AUTOBAL_EINVAL, "%s '%.100s...': a component is too long", what, in);
    memcpy(comp, p, len);
    comp[len] = '\0';
    rc = check_name(err, what, comp);
    if (rc != AUTOBAL_SUCCESS) return rc;
    if (o + 1 + len + 1 > size)
      return autobal_error_set(err, AUTOBAL_EINVAL, "%s '%.100s...' is too long", what, in);
    out[o++] = '/';
    memcpy(out + o, comp, len);
    o += len;
    out[o] = '\0';
    p = q;
  }
  if (o == 0) {
    out[0] = '/';
    out[1] = '\0';
  }
  return AUTOBAL_SUCCESS;
}

/* out = group + "/" + name (group normalised). */
static int join_path(autobal_error *err, const char *group, const char *name, char *out, size_t size) {
  int n = strcmp(group, "/") == 0 ? snprintf(out, size, "/%s", name) : snprintf(out, size, "%s/%s", group, name);
  if (n < 0 || (size_t)n >= size)
    return autobal_error_set(err, AUTOBAL_EINVAL, "path '%.100s/%.100s' is too long", group, name);
  return AUTOBAL_SUCCESS;
}

/* 1 if every component of the normalised path exists (links), 0 otherwise. */
int autobal_archive_path_exists_(hid_t file, const char *path) {
  char buf[AUTOBAL_ARCHIVE_PATH_MAX];
  size_t i, len = strlen(path);
  if (strcmp(path, "/") == 0) return 1;
  if (len >= sizeof buf) return 0;
  memcpy(buf, path, len + 1);
  for (i = 1; i <= len; i++) {
    if (buf[i] == '/' || buf[i] == '\0') {
      char save = buf[i];
      htri_t ex;
      buf[i] = '\0';
      ex = H5Lexists(file, buf, H5P_DEFAULT);
      buf[i] = save;
      if (ex <= 0) return 0;
    }
  }
  return 1;
}

/* Type of the object at a normalised path: H5I_GROUP, H5I_DATASET, other, or
 * H5I_BADID if it does not exist. */
H5I_type_t autobal_archive_path_type_(hid_t file, const char *path) {
  hid_t o;
  H5I_type_t t;
  if (!autobal_archive_path_exists_(file, path)) return H5I_BADID;
  o = H5Oopen(file, path, H5P_DEFAULT);
  if (o < 0) return H5I_BADID;
  t = H5Iget_type(o);
  (void)H5Oclose(o);
  return t;
}

/* ------------------------------------------------------------------------ */
/* Low-level writers (record HDF5 failures in err)                            */
/* ------------------------------------------------------------------------ */

static hid_t utf8_vlen_type(void) {
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0) return t;
  if (H5Tset_size(t, H5T_VARIABLE) < 0 || H5Tset_cset(t, H5T_CSET_UTF8) < 0) {
    (void)H5Tclose(t);
    return -1;
  }
  return t;
}

/* Create (replacing) attribute `name` on the open object o. */
static int put_attr(autobal_error *err, hid_t o, const char *where, const char *name, hid_t ftype,
                    hid_t mtype, hid_t space, const void *buf) {
  hid_t attr = -1;
  htri_t ex;
  int rc = AUTOBAL_SUCCESS;
  ex = H5Aexists(o, name);
  if (ex < 0) return autobal_archive_h5fail_(err, "cannot query attribute '%s' of '%s'", name, where);
  if (ex > 0 && H5Adelete(o, name) < 0)
    return autobal_archive_h5fail_(err, "cannot replace attribute '%s' of '%s'", name, where);
  attr = H5Acreate2(o, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) return autobal_archive_h5fail_(err, "cannot create attribute '%s' of '%s'", name, where);
  if (H5Awrite(attr, mtype, buf) < 0) rc = autobal_archive_h5fail_(err, "cannot write attribute '%s' of '%s'", name, where);
  if (H5Aclose(attr) < 0 && rc == AUTOBAL_SUCCESS)
    rc = autobal_archive_h5fail_(err, "cannot close attribute '%s' of '%s'", name, where);
  return rc;
}

static int put_attr_string(autobal_error *err, hid_t o, const char *where, const char *name,
                           const char *value) {
  hid_t t = -1, s = -1;
  int rc;
  t = utf8_vlen_type();
  if (t < 0) return autobal_archive_h5fail_(err, "cannot make a string type for attribute '%s' of '%s'", name, where);
  s = H5Screate(H5S_SCALAR);
  if (s < 0) {
    rc = autobal_archive_h5fail_(err, "cannot make a dataspace for attribute '%s' of '%s'", name, where);
    (void)H5Tclose(t);
    return rc;
  }
  rc = put_attr(err, o, where, name, t, t, s, &value);
  (void)H5Sclose(s);
  (void)H5Tclose(t);
  return rc;
}

static int put_attr_scalar(autobal_error *err, hid_t o, const char *where, const char *name,
                           hid_t ftype, hid_t mtype, const void *buf) {
  hid_t s = H5Screate(H5S_SCALAR);
  int rc;
  if (s < 0) return autobal_archive_h5fail_(err, "cannot make a dataspace for attribute '%s' of '%s'", name, where);
  rc = put_attr(err, o, where, name, ftype, mtype, s, buf);
  (void)H5Sclose(s);
  return rc;
}

/* Object creation properties of every group and dataset (and the root group): the
 * creation order of attributes is tracked (autobal_archive_list_attrs), and attributes
 * stay in the object header (compact storage) up to ATTR_MAX_COMPACT of them: dense
 * storage (a fractal heap and a B-tree per object, as HDF5 does by default above 8
 * attributes in the object headers that track creation order) costs ~1 KiB per group. */
#define ATTR_MAX_COMPACT 1024u
static herr_t set_attr_order(hid_t ocpl) {
  if (H5Pset_attr_creation_order(ocpl, H5P_CRT_ORDER_TRACKED) < 0) return -1;
  return H5Pset_attr_phase_change(ocpl, ATTR_MAX_COMPACT, 0);
}

/* Create all missing groups of a normalised path (link creation order tracked). */
static int make_group(autobal_error *err, hid_t file, const char *path) {
  char buf[AUTOBAL_ARCHIVE_PATH_MAX];
  size_t i, len = strlen(path);
  hid_t gcpl;
  int rc = AUTOBAL_SUCCESS;
  if (strcmp(path, "/") == 0) return AUTOBAL_SUCCESS;
  if (len >= sizeof buf) return autobal_error_set(err, AUTOBAL_EINVAL, "group path too long");
  memcpy(buf, path, len + 1);
  gcpl = H5Pcreate(H5P_GROUP_CREATE);
  if (gcpl < 0) return autobal_archive_h5fail_(err, "cannot create group '%s'", path);
  if (H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0 ||
      set_attr_order(gcpl) < 0) {
    rc = autobal_archive_h5fail_(err, "cannot create group '%s'", path);
    (void)H5Pclose(gcpl);
    return rc;
  }
  for (i = 1; i <= len && rc == AUTOBAL_SUCCESS; i++) {
    if (buf[i] == '/' || buf[i] == '\0') {
      char save = buf[i];
      htri_t ex;
      buf[i] = '\0';
      ex = H5Lexists(file, buf, H5P_DEFAULT);
      if (ex < 0) {
        rc = autobal_archive_h5fail_(err, "cannot look up group '%s'", buf);
      } else if (ex > 0) {
        hid_t o = H5Oopen(file, buf, H5P_DEFAULT);
        if (o < 0) {
          rc = autobal_archive_h5fail_(err, "cannot open '%s'", buf);
        } else {
          if (H5Iget_type(o) != H5I_GROUP)
            rc = autobal_error_set(err, AUTOBAL_EINVAL, "'%s' exists and is not a group", buf);
          (void)H5Oclose(o);
        }
      } else {
        hid_t g = H5Gcreate2(file, buf, H5P_DEFAULT, gcpl, H5P_DEFAULT);
        if (g < 0) rc = autobal_archive_h5fail_(err, "cannot create group '%s'", buf);
        else if (H5Gclose(g) < 0) rc = autobal_archive_h5fail_(err, "cannot close group '%s'", buf);
      }
      buf[i] = save;
    }
  }
  (void)H5Pclose(gcpl);
  return rc;
}

/* Dataset creation property list: chunked, shuffled and deflated at `level` when
 * `chunked`. */
static hid_t make_dcpl(int rank, const hsize_t *chunk, int chunked, unsigned level) {
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (dcpl < 0) return dcpl;
  /* attributes listed in creation order (autobal_archive_list_attrs) */
  if (set_attr_order(dcpl) < 0) goto fail;
  if (chunked && rank > 0) {
    if (H5Pset_chunk(dcpl, rank, chunk) < 0) goto fail;
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      if (H5Pset_shuffle(dcpl) < 0 || H5Pset_deflate(dcpl, level) < 0) goto fail;
    }
  }
  return dcpl;
fail:
  (void)H5Pclose(dcpl);
  return -1;
}

/* Chunk shape of about CHUNK_TARGET bytes for a fixed-size dataset: halve the leading
 * dimensions first (C order keeps the trailing, fastest-varying extent whole). */
static void chunk_shape(int rank, const hsize_t *dims, size_t elsize, hsize_t *chunk) {
  int i;
  hsize_t bytes = (hsize_t)elsize;
  for (i = 0; i < rank; i++) {
    chunk[i] = dims[i] > 0 ? dims[i] : 1;
    bytes *= chunk[i];
  }
  for (i = 0; i < rank && bytes > CHUNK_TARGET; i++) {
    while (bytes > CHUNK_TARGET && chunk[i] > 1) {
      hsize_t c = (chunk[i] + 1) / 2;
      bytes = bytes / chunk[i] * c;
      chunk[i] = c;
    }
  }
}

/* Create a dataset at a normalised path.  maxdims NULL: fixed size.  chunk_req: chunk
 * shape (NULL: chosen here when compressed); level: deflate level of chunked datasets;
 * dapl: access properties of the returned id.  Returns the open dataset id or -1
 * (message in err). */
static hid_t create_dataset(autobal_error *err, hid_t file, const char *path, hid_t ftype, int rank,
                            const hsize_t *dims, const hsize_t *maxdims, const hsize_t *chunk_req,
                            size_t elsize, unsigned level, hid_t dapl) {
  hid_t space = -1, dcpl = -1, ds = -1;
  hsize_t chunk[AUTOBAL_ARCHIVE_MAX_RANK];
  int chunked = 0, i;
  hsize_t bytes = (hsize_t)elsize;
  for (i = 0; i < rank; i++) bytes *= dims[i];
  space = rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, maxdims);
  if (space < 0) {
    (void)autobal_archive_h5fail_(err, "cannot make the dataspace of '%s'", path);
    return -1;
  }
  if (chunk_req != NULL) {
    for (i = 0; i < rank; i++) chunk[i] = chunk_req[i];
    chunked = 1;
  } else if (rank > 0 && bytes > AUTOBAL_ARCHIVE_COMPRESS_BYTES) {
    chunk_shape(rank, dims, elsize, chunk);
    chunked = 1;
  }
  dcpl = make_dcpl(rank, chunk, chunked, level);
  if (dcpl < 0) {
    (void)autobal_archive_h5fail_(err, "cannot set up the storage of '%s'", path);
    (void)H5Sclose(space);
    return -1;
  }
  ds = H5Dcreate2(file, path, ftype, space, H5P_DEFAULT, dcpl, dapl);
  if (ds < 0) (void)autobal_archive_h5fail_(err, "cannot create dataset '%s'", path);
  (void)H5Pclose(dcpl);
  (void)H5Sclose(space);
  return ds;
}

/* units (required) and long_name (NULL: the name) on an open dataset. */
static int put_units_long_name(autobal_error *err, hid_t ds, const char *path, const char *name,
                               const char *units, const char *long_name) {
  int rc = put_attr_string(err, ds, path, "units", units);
  if (rc == AUTOBAL_SUCCESS) rc = put_attr_string(err, ds, path, "long_name", long_name ? long_name : name);
  return rc;
}

/* Remove a half-made dataset after a failure (best effort; err already set). */
static void remove_link(hid_t file, const char *path) {
  if (H5Lexists(file, path, H5P_DEFAULT) > 0) (void)H5Ldelete(file, path, H5P_DEFAULT);
}

/* ------------------------------------------------------------------------ */
/* Handle helpers                                                              */
/* ------------------------------------------------------------------------ */

static int writable(autobal_archive *a) {
  if (!a->writable)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "archive '%s' is open read-only", a->path);
  return AUTOBAL_SUCCESS;
}

char *autobal_archive_dup_str_(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = (char *)malloc(n);
  if (d != NULL) memcpy(d, s, n);
  return d;
}

void autobal_archive_free_handle_(autobal_archive *a) {
  if (a == NULL) return;
  if (a->sync_ok) {
    (void)pthread_cond_destroy(&a->done);
    (void)pthread_cond_destroy(&a->work);
    (void)pthread_mutex_destroy(&a->m);
  }
  free(a->path);
  free(a->tmp_path);
  free(a);
}

const char *autobal_archive_errmsg(const autobal_archive *a) { return a ? a->err.message : ""; }
int autobal_archive_status(const autobal_archive *a) { return a ? a->err.status : AUTOBAL_SUCCESS; }

/* ------------------------------------------------------------------------ */
/* Create                                                                      */
/* ------------------------------------------------------------------------ */

static int write_root_string(autobal_archive *a, const char *name, const char *value) {
  return put_attr_string(&a->err, a->file, "/", name, value);
}

int autobal_archive_create(const char *path, int overwrite, autobal_archive **out, autobal_error *err) {
  autobal_archive *a = NULL;
  struct stat st;
  autobal_archive_quiet_ q;
  hid_t fcpl = -1;
  size_t len;
  int rc = AUTOBAL_SUCCESS, k;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "archive_create: out is NULL");
  *out = NULL;
  if (path == NULL || path[0] == '\0')
    return autobal_error_set(err, AUTOBAL_EINVAL, "archive path is NULL or empty");
  len = strlen(path);
  /* the temporary "<path>.partial-<pid>" (at most 19 more bytes) must fit in PATH_MAX = 4096
   * bytes with its NUL */
  if (len > 4076)
    return autobal_error_set(err, AUTOBAL_EINVAL,
                             "archive path is too long (%zu bytes; at most 4076, so that the temporary "
                             "'<path>.partial-<pid>' fits in PATH_MAX = 4096)",
                             len);
  if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode) && stat(path, &st) != 0)
    return autobal_error_set(err, AUTOBAL_EIO, "archive path '%s' is a dangling symbolic link", path);
  if (stat(path, &st) == 0) {
    if (S_ISDIR(st.st_mode))
      return autobal_error_set(err, AUTOBAL_EIO, "archive path '%s' is a directory", path);
    if (!S_ISREG(st.st_mode))
      return autobal_error_set(err, AUTOBAL_EIO,
                               "archive path '%s' exists and is not a regular file (a device, FIFO or socket): "
                               "refusing to replace it",
                               path);
    if (!overwrite)
      return autobal_error_set(err, AUTOBAL_EEXIST, "archive '%s' exists (overwrite not allowed)", path);
  }
  a = (autobal_archive *)calloc(1, sizeof *a);
  if (a == NULL) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory creating archive '%s'", path);
  a->file = -1;
  a->writable = 1;
  a->overwrite = overwrite != 0;
  snprintf(a->final_status, sizeof a->final_status, "complete");
  a->path = autobal_archive_dup_str_(path);
  a->tmp_path = (char *)malloc(len + 64);
  if (a->path == NULL || a->tmp_path == NULL) {
    autobal_archive_free_handle_(a);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory creating archive '%s'", path);
  }
  if (pthread_mutex_init(&a->m, NULL) != 0) {
    autobal_archive_free_handle_(a);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "cannot create archive '%s': no mutex", path);
  }
  if (pthread_cond_init(&a->work, NULL) != 0) {
    (void)pthread_mutex_destroy(&a->m);
    autobal_archive_free_handle_(a);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "cannot create archive '%s': no condition variable", path);
  }
  if (pthread_cond_init(&a->done, NULL) != 0) {
    (void)pthread_cond_destroy(&a->work);
    (void)pthread_mutex_destroy(&a->m);
    autobal_archive_free_handle_(a);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "cannot create archive '%s': no condition variable", path);
  }
  a->sync_ok = 1;

  autobal_archive_h5_enter_(&q);
  fcpl = H5Pcreate(H5P_FILE_CREATE);
  if (fcpl < 0 || H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0 ||
      set_attr_order(fcpl) < 0) {
    rc = autobal_archive_h5fail_(err, "cannot create archive '%s'", path);
    goto done;
  }
  /* "<path>.partial-<pid>", or with "-2", "-3", ... if that name is taken. */
  for (k = 1; k <= 100; k++) {
    if (k == 1) snprintf(a->tmp_path, len + 64, "%s.partial-%ld", path, (long)getpid());
    else snprintf(a->tmp_path, len + 64, "%s.partial-%ld-%d", path, (long)getpid(), k);
    if (stat(a->tmp_path, &st) != 0) break;
  }
  if (k > 100) {
    rc = autobal_error_set(err, AUTOBAL_EIO, "cannot create archive '%s': temporary names all taken", path);
    goto done;
  }
  /* Claim the temporary name with a plain open() and write a block into it first: a missing or
   * read-only directory, or a full disk, is then reported with the OS's reason and leaves no
   * file (HDF5 failing to write a new file's superblock left a 0-byte file, said "File exists"
   * and could not close its library at exit). */
  {
    char blk[4096];
    ssize_t w;
    int fd = open(a->tmp_path, O_WRONLY | O_CREAT | O_EXCL, 0666), e;
    if (fd < 0) {
      rc = autobal_error_set(err, AUTOBAL_EIO, "cannot create archive '%.300s': %s", path, strerror(errno));
      goto done;
    }
    memset(blk, 0, sizeof blk);
    w = write(fd, blk, sizeof blk);
    e = errno;
    if (w == (ssize_t)sizeof blk && fsync(fd) != 0) w = -1, e = errno;
    (void)close(fd);
    if (w != (ssize_t)sizeof blk) {
      (void)unlink(a->tmp_path);
      rc = autobal_error_set(err, AUTOBAL_EIO, "cannot create archive '%.300s': %s", path,
                             strerror(w < 0 ? e : ENOSPC));
      goto done;
    }
  }
  a->file = H5Fcreate(a->tmp_path, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  if (a->file < 0) {
    char stack[AUTOBAL_ERRMSG_SIZE];
    h5stack(stack, sizeof stack);
    (void)unlink(a->tmp_path);
    rc = autobal_error_set(err, AUTOBAL_EIO, "cannot create archive '%.150s' (temporary file '%.150s'; %.150s)",
                           path, a->tmp_path, stack);
    goto done;
  }
  rc = write_root_string(a, "Conventions", AUTOBAL_ARCHIVE_CONVENTIONS);
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "status", "incomplete");
  if (rc != AUTOBAL_SUCCESS) {
    autobal_error_set(err, rc, "cannot create archive '%.200s': %.280s", path, a->err.message);
    (void)H5Fclose(a->file);
    a->file = -1;
    (void)remove(a->tmp_path);
  }
done:
  if (fcpl >= 0) (void)H5Pclose(fcpl);
  autobal_archive_h5_leave_(&q);
  if (rc != AUTOBAL_SUCCESS) {
    autobal_archive_free_handle_(a);
    return rc;
  }
  autobal_error_clear(&a->err);
  *out = a;
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Provenance and status                                                      */
/* ------------------------------------------------------------------------ */

static int shell_safe(const char *s) {
  if (*s == '\0') return 0;
  for (; *s; s++) {
    unsigned char c = (unsigned char)*s;
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
          strchr("_@%+=:,./-", (int)c) != NULL))
      return 0;
  }
  return 1;
}

/* argv joined with POSIX shell quoting; invalid UTF-8 bytes become '?'.  malloc'ed. */
static char *join_command_line(int argc, const char *const *argv) {
  size_t need = 1, o = 0;
  int i;
  char *s;
  for (i = 0; i < argc; i++) {
    const char *p;
    need += strlen(argv[i]) + 3;
    for (p = argv[i]; *p; p++)
      if (*p == '\'') need += 3;
  }
  s = (char *)malloc(need);
  if (s == NULL) return NULL;
  for (i = 0; i < argc; i++) {
    const char *p = argv[i];
    int quote = !shell_safe(p);
    if (i > 0) s[o++] = ' ';
    if (quote) s[o++] = '\'';
    while (*p) {
      size_t n = utf8_seq((const unsigned char *)p);
      if (n == 0) {
        s[o++] = '?';
        p++;
      } else if (*p == '\'') {
        memcpy(s + o, "'\\''", 4);
        o += 4;
        p++;
      } else {
        memcpy(s + o, p, n);
        o += n;
        p += n;
      }
    }
    if (quote) s[o++] = '\'';
  }
  s[o] = '\0';
  return s;
}

/* Whether the blank- or comma-separated tokens of a Conventions attribute include `token`. */
int autobal_archive_conventions_include_(const char *conv, const char *token) {
  size_t n = strlen(token);
  const char *p = conv;
  while (*p) {
    size_t k;
    while (*p == ' ' || *p == ',' || *p == '\t') p++;
    k = strcspn(p, " ,\t");
    if (k == n && strncmp(p, token, n) == 0) return 1;
    p += k;
  }
  return 0;
}

int autobal_archive_provenance(autobal_archive *a, const char *title, int argc, const char *const *argv) {
  autobal_archive_quiet_ q;
  char hdf5v[32], created[32], *cmd;
  time_t now;
  struct tm tmv;
  int rc, i;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if (argc < 0 || (argc > 0 && argv == NULL))
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "provenance: argc = %d with argv %s", argc,
                             argv ? "set" : "NULL");
  for (i = 0; i < argc; i++)
    if (argv[i] == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "provenance: argv[%d] is NULL", i);
  if (title == NULL) title = "";
  if ((rc = check_text(&a->err, "title", title)) != AUTOBAL_SUCCESS) return rc;
  cmd = join_command_line(argc, argv);
  if (cmd == NULL) return autobal_error_set(&a->err, AUTOBAL_ENOMEM, "provenance: out of memory");
  now = time(NULL);
  if (gmtime_r(&now, &tmv) == NULL || strftime(created, sizeof created, "%Y-%m-%dT%H:%M:%SZ", &tmv) == 0)
    snprintf(created, sizeof created, "unknown");
  autobal_archive_h5_enter_(&q);
  hdf5_version_locked(hdf5v, sizeof hdf5v);
  rc = write_root_string(a, "title", title);
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "autobal_version", autobal_version());
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "git_revision", autobal_git_revision());
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "gsl_version", autobal_gsl_version());
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "hdf5_version", hdf5v);
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "command_line", cmd);
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "created", created);
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "status", "incomplete");
  if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "Conventions", AUTOBAL_ARCHIVE_CONVENTIONS);
  if (rc == AUTOBAL_SUCCESS) { /* CF: history, source, references */
    size_t n = strlen(created) + strlen(cmd) + 2;
    char *hist = malloc(n), src[160];
    if (hist == NULL) {
      rc = autobal_error_set(&a->err, AUTOBAL_ENOMEM, "provenance: out of memory");
    } else {
      snprintf(hist, n, "%s %s", created, cmd);
      rc = write_root_string(a, "history", hist);
      free(hist);
    }
    snprintf(src, sizeof src, "autobal %s (%s)", autobal_version(), autobal_git_revision());
    if (rc == AUTOBAL_SUCCESS) rc = write_root_string(a, "source", src);
    if (rc == AUTOBAL_SUCCESS)
      rc = write_root_string(a, "references",
                             "autobal model documentation: docs/rotor.md (rotor with ball autobalancers), "
                             "docs/pendulum.md (two-pendulum autobalancer), docs/units.md (units) and "
                             "docs/archive.md (the archive layout) of the autobal repository");
  }
  autobal_archive_h5_leave_(&q);
  free(cmd);
  return rc;
}

int autobal_archive_set_status(autobal_archive *a, const char *status, const char *reason) {
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = check_text(&a->err, "status", status)) != AUTOBAL_SUCCESS) return rc;
  if (status[0] == '\0' || strlen(status) >= sizeof a->final_status)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "status must have 1 to %zu bytes",
                             sizeof a->final_status - 1);
  if (reason != NULL) {
    if ((rc = check_text(&a->err, "status reason", reason)) != AUTOBAL_SUCCESS) return rc;
    if (strlen(reason) >= sizeof a->reason)
      return autobal_error_set(&a->err, AUTOBAL_EINVAL, "status reason is longer than %zu bytes",
                               sizeof a->reason - 1);
  }
  snprintf(a->final_status, sizeof a->final_status, "%s", status);
  a->has_reason = reason != NULL;
  snprintf(a->reason, sizeof a->reason, "%s", reason ? reason : "");
  return AUTOBAL_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Groups and attributes                                                      */
/* ------------------------------------------------------------------------ */

int autobal_archive_group(autobal_archive *a, const char *group) {
  char g[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = autobal_archive_norm_path_(&a->err, "group", group, g, sizeof g)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = make_group(&a->err, a->file, g);
  autobal_archive_h5_leave_(&q);
  return rc;
}

/* Common part of the attribute writers: validate, open obj. */
static int attr_begin(autobal_archive *a, const char *obj, const char *name, char *path, size_t size,
                      hid_t *o) {
  int rc;
  *o = -1;
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = autobal_archive_norm_path_(&a->err, "object", obj, path, size)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = check_attr_name(&a->err, name)) != AUTOBAL_SUCCESS) return rc;
  if (!autobal_archive_path_exists_(a->file, path))
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "cannot set attribute '%s': no object '%s' in '%s'",
                             name, path, a->path);
  *o = H5Oopen(a->file, path, H5P_DEFAULT);
  if (*o < 0) return autobal_archive_h5fail_(&a->err, "cannot open '%s' to set attribute '%s'", path, name);
  return AUTOBAL_SUCCESS;
}

/* NAME_units attribute. */
static int put_units_attr(autobal_archive *a, hid_t o, const char *path, const char *name, const char *units) {
  char un[AUTOBAL_ARCHIVE_NAME_MAX + 16];
  if (units == NULL) return AUTOBAL_SUCCESS;
  snprintf(un, sizeof un, "%s_units", name);
  return put_attr_string(&a->err, o, path, un, units);
}

int autobal_archive_attr_double(autobal_archive *a, const char *obj, const char *name, double value,
                                const char *units) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t o;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (units != NULL && (rc = check_text(&a->err, "units", units)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) rc = put_attr_scalar(&a->err, o, path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
  if (rc == AUTOBAL_SUCCESS) rc = put_units_attr(a, o, path, name, units);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_attr_int(autobal_archive *a, const char *obj, const char *name, long value) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t o;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  autobal_archive_h5_enter_(&q);
  rc = attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) rc = put_attr_scalar(&a->err, o, path, name, H5T_STD_I64LE, H5T_NATIVE_LONG, &value);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_attr_string(autobal_archive *a, const char *obj, const char *name, const char *value) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t o;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if ((rc = check_text(&a->err, "attribute value", value)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) rc = put_attr_string(&a->err, o, path, name, value);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_attr_double_array(autobal_archive *a, const char *obj, const char *name, size_t n,
                                      const double *v, const char *units) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t o, s;
  hsize_t dim = (hsize_t)n;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (n == 0 || v == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "attribute '%s': array %s", name ? name : "(null)",
                             v == NULL ? "is NULL" : "is empty (n = 0)");
  if (units != NULL && (rc = check_text(&a->err, "units", units)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) {
    s = H5Screate_simple(1, &dim, NULL);
    if (s < 0) {
      rc = autobal_archive_h5fail_(&a->err, "cannot make a dataspace for attribute '%s' of '%s'", name, path);
    } else {
      rc = put_attr(&a->err, o, path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, s, v);
      (void)H5Sclose(s);
    }
  }
  if (rc == AUTOBAL_SUCCESS) rc = put_units_attr(a, o, path, name, units);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* Coordinates, dimensions, variables                                         */
/* ------------------------------------------------------------------------ */

/* Validate group+name for a new dataset, create the group, build the full path. */
static int new_dataset_path(autobal_archive *a, const char *group, const char *name, char *g, char *path,
                            size_t size) {
  int rc;
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = autobal_archive_norm_path_(&a->err, "group", group, g, size)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = check_name(&a->err, "dataset name", name)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = join_path(&a->err, g, name, path, size)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = make_group(&a->err, a->file, g)) != AUTOBAL_SUCCESS) return rc;
  if (autobal_archive_path_exists_(a->file, path))
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "'%s' already exists in '%s'", path, a->path);
  return AUTOBAL_SUCCESS;
}

/* Write a 1-D dimension-scale dataset (double or int32 values). */
static int write_scale(autobal_archive *a, const char *group, const char *name, size_t n, const void *values,
                       hid_t ftype, hid_t mtype, size_t elsize, const char *units, const char *long_name) {
  char g[AUTOBAL_ARCHIVE_PATH_MAX], path[AUTOBAL_ARCHIVE_PATH_MAX];
  hsize_t dim = (hsize_t)n;
  hid_t ds;
  int rc;
  if ((rc = new_dataset_path(a, group, name, g, path, sizeof path)) != AUTOBAL_SUCCESS) return rc;
  ds = create_dataset(&a->err, a->file, path, ftype, 1, &dim, NULL, NULL, elsize, DEFLATE_LEVEL, H5P_DEFAULT);
  if (ds < 0) return AUTOBAL_EIO;
  if (H5Dwrite(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot write '%s'", path);
  if (rc == AUTOBAL_SUCCESS && H5DSset_scale(ds, name) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot make '%s' a dimension scale", path);
  if (rc == AUTOBAL_SUCCESS) rc = put_units_long_name(&a->err, ds, path, name, units, long_name);
  if (H5Dclose(ds) < 0 && rc == AUTOBAL_SUCCESS) rc = autobal_archive_h5fail_(&a->err, "cannot close '%s'", path);
  if (rc != AUTOBAL_SUCCESS) remove_link(a->file, path);
  return rc;
}

int autobal_archive_coord(autobal_archive *a, const char *group, const char *name, size_t n,
                          const double *values, const char *units, const char *long_name) {
  autobal_archive_quiet_ q;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (n == 0 || values == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "coordinate '%s': values %s", name ? name : "(null)",
                             values == NULL ? "NULL" : "empty (n = 0)");
  if ((rc = check_text(&a->err, "units", units)) != AUTOBAL_SUCCESS) return rc;
  if (long_name != NULL && (rc = check_text(&a->err, "long_name", long_name)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = write_scale(a, group, name, n, values, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, sizeof(double), units,
                   long_name);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_dim(autobal_archive *a, const char *group, const char *name, size_t n,
                        const char *long_name) {
  autobal_archive_quiet_ q;
  int32_t *idx;
  size_t i;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (n == 0 || n > (size_t)INT32_MAX)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "dimension '%s': size %zu out of range [1, %ld]",
                             name ? name : "(null)", n, (long)INT32_MAX);
  if (long_name != NULL && (rc = check_text(&a->err, "long_name", long_name)) != AUTOBAL_SUCCESS) return rc;
  idx = (int32_t *)malloc(n * sizeof *idx);
  if (idx == NULL) return autobal_error_set(&a->err, AUTOBAL_ENOMEM, "dimension '%s': out of memory", name);
  for (i = 0; i < n; i++) idx[i] = (int32_t)i;
  autobal_archive_h5_enter_(&q);
  rc = write_scale(a, group, name, n, idx, H5T_STD_I32LE, H5T_NATIVE_INT32, sizeof(int32_t), "1", long_name);
  autobal_archive_h5_leave_(&q);
  free(idx);
  return rc;
}

static int series_flush_all(autobal_archive *a, autobal_archive_quiet_ *q);

/* Find dimension `dim` for a variable in normalised group g: absolute path, or the
 * nearest of g, its parents.  Returns the open scale dataset in *ds. */
static int find_dim(autobal_archive *a, const char *g, const char *dim, char *found, size_t size, hid_t *ds) {
  char scope[AUTOBAL_ARCHIVE_PATH_MAX];
  int rc;
  *ds = -1;
  if (dim == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "a dimension name is NULL");
  if (strchr(dim, '/') != NULL) {
    if ((rc = autobal_archive_norm_path_(&a->err, "dimension", dim, found, size)) != AUTOBAL_SUCCESS) return rc;
    if (autobal_archive_path_type_(a->file, found) != H5I_DATASET) found[0] = '\0';
  } else {
    if ((rc = check_name(&a->err, "dimension name", dim)) != AUTOBAL_SUCCESS) return rc;
    snprintf(scope, sizeof scope, "%s", g);
    found[0] = '\0';
    for (;;) {
      char *slash;
      if (join_path(&a->err, scope, dim, found, size) == AUTOBAL_SUCCESS &&
          autobal_archive_path_type_(a->file, found) == H5I_DATASET)
        break;
      found[0] = '\0';
      if (strcmp(scope, "/") == 0) break;
      slash = strrchr(scope, '/');
      if (slash == scope) scope[1] = '\0';
      else *slash = '\0';
    }
  }
  if (found[0] == '\0')
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "unknown dimension '%s' for group '%s' (make it with "
                             "autobal_archive_coord or autobal_archive_dim first)", dim, g);
  *ds = H5Dopen2(a->file, found, H5P_DEFAULT);
  if (*ds < 0) return autobal_archive_h5fail_(&a->err, "cannot open dimension '%s'", found);
  if (H5DSis_scale(*ds) <= 0) {
    (void)H5Dclose(*ds);
    *ds = -1;
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "'%s' is a variable, not a dimension", found);
  }
  return AUTOBAL_SUCCESS;
}

/* Called holding the HDF5 lock (q from autobal_archive_h5_enter_); releases it for a while to wait for
 * the series writer. */
static int write_var(autobal_archive *a, autobal_archive_quiet_ *q, const char *group, const char *name, int rank,
                     const char *const *dims, const void *data, hid_t ftype, hid_t mtype, size_t elsize,
                     const char *units, const char *long_name) {
  char g[AUTOBAL_ARCHIVE_PATH_MAX], path[AUTOBAL_ARCHIVE_PATH_MAX], found[AUTOBAL_ARCHIVE_PATH_MAX];
  hid_t scales[AUTOBAL_ARCHIVE_MAX_RANK] = {-1, -1, -1, -1};
  hsize_t shape[AUTOBAL_ARCHIVE_MAX_RANK];
  hid_t ds = -1;
  size_t count = 1;
  int rc, i, nattached = 0;
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if (rank < 0 || rank > AUTOBAL_ARCHIVE_MAX_RANK)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "variable '%s': rank %d out of range [0, %d]",
                             name ? name : "(null)", rank, AUTOBAL_ARCHIVE_MAX_RANK);
  if (rank > 0 && dims == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "variable '%s': dims is NULL for rank %d",
                             name ? name : "(null)", rank);
  if (data == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "variable '%s': data is NULL", name ? name : "(null)");
  if ((rc = check_text(&a->err, "units", units)) != AUTOBAL_SUCCESS) return rc;
  if (long_name != NULL && (rc = check_text(&a->err, "long_name", long_name)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = new_dataset_path(a, group, name, g, path, sizeof path)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = series_flush_all(a, q)) != AUTOBAL_SUCCESS) return rc;
  for (i = 0; i < rank && rc == AUTOBAL_SUCCESS; i++) {
    rc = find_dim(a, g, dims[i], found, sizeof found, &scales[i]);
    if (rc == AUTOBAL_SUCCESS) {
      hid_t sp = H5Dget_space(scales[i]);
      hsize_t cur = 0;
      if (sp < 0 || H5Sget_simple_extent_ndims(sp) != 1 || H5Sget_simple_extent_dims(sp, &cur, NULL) < 0)
        rc = autobal_archive_h5fail_(&a->err, "cannot get the size of dimension '%s'", found);
      if (sp >= 0) (void)H5Sclose(sp);
      shape[i] = cur;
      if (rc == AUTOBAL_SUCCESS) {
        if (cur > 0 && count > SIZE_MAX / elsize / (size_t)cur)
          rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "variable '%s' is too large", path);
        count *= (size_t)cur;
      }
    }
  }
  if (rc == AUTOBAL_SUCCESS) {
    ds = create_dataset(&a->err, a->file, path, ftype, rank, shape, NULL, NULL, elsize, DEFLATE_LEVEL,
                        H5P_DEFAULT);
    if (ds < 0) rc = AUTOBAL_EIO;
  }
  if (rc == AUTOBAL_SUCCESS && count > 0 && H5Dwrite(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot write '%s'", path);
  for (i = 0; i < rank && rc == AUTOBAL_SUCCESS; i++) {
    if (H5DSattach_scale(ds, scales[i], (unsigned)i) < 0)
      rc = autobal_archive_h5fail_(&a->err, "cannot attach dimension '%s' to '%s'", dims[i], path);
    else nattached = i + 1;
  }
  if (rc == AUTOBAL_SUCCESS) rc = put_units_long_name(&a->err, ds, path, name, units, long_name);
  /* After a failure, detach the scales so their REFERENCE_LIST does not point at the
   * dataset removed below. */
  for (i = 0; i < nattached && rc != AUTOBAL_SUCCESS; i++) (void)H5DSdetach_scale(ds, scales[i], (unsigned)i);
  if (ds >= 0 && H5Dclose(ds) < 0 && rc == AUTOBAL_SUCCESS) rc = autobal_archive_h5fail_(&a->err, "cannot finish writing '%s'", path);
  for (i = 0; i < rank; i++)
    if (scales[i] >= 0) (void)H5Dclose(scales[i]);
  if (rc != AUTOBAL_SUCCESS && ds >= 0) remove_link(a->file, path);
  return rc;
}

int autobal_archive_var(autobal_archive *a, const char *group, const char *name, int rank,
                        const char *const *dims, const double *data, const char *units, const char *long_name) {
  autobal_archive_quiet_ q;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  autobal_archive_h5_enter_(&q);
  rc = write_var(a, &q, group, name, rank, dims, data, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, sizeof(double), units,
                 long_name);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_var_int(autobal_archive *a, const char *group, const char *name, int rank,
                            const char *const *dims, const int *data, const char *units, const char *long_name) {
  autobal_archive_quiet_ q;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  autobal_archive_h5_enter_(&q);
  rc = write_var(a, &q, group, name, rank, dims, data, H5T_STD_I32LE, H5T_NATIVE_INT, sizeof(int), units, long_name);
  autobal_archive_h5_leave_(&q);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* Series                                                                      */
/* ------------------------------------------------------------------------ */

/* Write nrows rows of buf (row-major, nvars + 1 values a row) after the s->nwritten
 * rows in the file: extend each column, gather it into s->col and write it.  Called holding the HDF5 lock, by the writer
 * or by the caller when the series is idle.  On failure the message goes to err and
 * nwritten is unchanged (columns may have been extended). */
static int series_write_rows(autobal_archive_series *s, const double *buf, size_t nrows, autobal_error *err) {
  hsize_t start, count, newsize;
  size_t k;
  int rc = AUTOBAL_SUCCESS;
  if (nrows == 0) return AUTOBAL_SUCCESS;
  start = (hsize_t)s->nwritten;
  count = (hsize_t)nrows;
  newsize = start + count;
  for (k = 0; k <= s->nvars && rc == AUTOBAL_SUCCESS; k++) {
    const size_t stride = s->nvars + 1;
    hid_t fs = -1, ms = -1;
    size_t r;
    for (r = 0; r < nrows; r++) s->col[r] = buf[r * stride + k];
    if (H5Dset_extent(s->dsets[k], &newsize) < 0) {
      rc = autobal_archive_h5fail_(err, "series '%s': cannot extend column %zu to %llu rows", s->where, k,
                                   (unsigned long long)newsize);
      break;
    }
    fs = H5Dget_space(s->dsets[k]);
    ms = H5Screate_simple(1, &count, NULL);
    if (fs < 0 || ms < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL) < 0)
      rc = autobal_archive_h5fail_(err, "series '%s': cannot select rows of column %zu", s->where, k);
    else if (H5Dwrite(s->dsets[k], H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, s->col) < 0)
      rc = autobal_archive_h5fail_(err, "series '%s': cannot write %zu rows of column %zu", s->where, nrows, k);
    if (ms >= 0) (void)H5Sclose(ms);
    if (fs >= 0) (void)H5Sclose(fs);
  }
  if (rc == AUTOBAL_SUCCESS) s->nwritten += nrows;
  return rc;
}

/* Write the handed-off buffer wbuf (in the writer thread, or in the caller's thread when
 * there is no writer).  A failure is recorded in werr and flagged in wfailed. */
static void series_write_job(autobal_archive_series *s) {
  autobal_archive_quiet_ q;
  int rc;
  autobal_archive_h5_enter_(&q);
  rc = series_write_rows(s, s->wbuf, s->wrows, &s->werr);
  autobal_archive_h5_leave_(&q);
  if (rc != AUTOBAL_SUCCESS) atomic_store_explicit(&s->wfailed, 1, memory_order_release);
}

/* The writer thread: write queued buffers in order until told to stop. */
static void *writer_main(void *arg) {
  autobal_archive *a = (autobal_archive *)arg;
  (void)pthread_mutex_lock(&a->m);
  for (;;) {
    autobal_archive_series *s;
    while (a->qhead == NULL && !a->stop) (void)pthread_cond_wait(&a->work, &a->m);
    if (a->qhead == NULL) break; /* stop, nothing left */
    s = a->qhead;
    a->qhead = s->qnext;
    if (a->qhead == NULL) a->qtail = NULL;
    s->qnext = NULL;
    (void)pthread_mutex_unlock(&a->m);
    series_write_job(s);
    (void)pthread_mutex_lock(&a->m);
    s->pending = 0;
    (void)pthread_cond_broadcast(&a->done);
  }
  (void)pthread_mutex_unlock(&a->m);
  return NULL;
}

/* Start the writer of the archive if not yet tried; 1 if it runs.  The thread blocks
 * all signals (they go to the caller's threads; a write beyond a file-size limit
 * then fails with EFBIG instead of raising SIGXFSZ there). */
static int writer_start(autobal_archive *a) {
  sigset_t all, old;
  if (a->writer != 0) return a->writer > 0;
  a->writer = -1;
  if (!a->sync_ok) return 0;
  a->stop = 0;
  if (sigfillset(&all) != 0 || pthread_sigmask(SIG_SETMASK, &all, &old) != 0) return 0;
  if (pthread_create(&a->thread, NULL, writer_main, a) == 0) a->writer = 1;
  (void)pthread_sigmask(SIG_SETMASK, &old, NULL);
  return a->writer > 0;
}

/* Stop and join the writer (every series must be idle).  Never holding autobal_archive_h5_lock_. */
static void writer_stop(autobal_archive *a) {
  if (a->writer <= 0) return;
  (void)pthread_mutex_lock(&a->m);
  a->stop = 1;
  (void)pthread_cond_signal(&a->work);
  (void)pthread_mutex_unlock(&a->m);
  (void)pthread_join(a->thread, NULL);
  a->writer = 0;
}

/* Wait until the writer has finished the series' buffer in flight.  Never call it
 * holding autobal_archive_h5_lock_. */
static void series_idle(autobal_archive_series *s) {
  autobal_archive *a = s->a;
  if (a->writer <= 0) return;
  (void)pthread_mutex_lock(&a->m);
  while (s->pending) (void)pthread_cond_wait(&a->done, &a->m);
  (void)pthread_mutex_unlock(&a->m);
}

/* On an idle series: report a write failure of the writer (once; the series is then
 * broken: its buffered rows are dropped, its length is the rows in the file) or an
 * earlier one.  Message in the archive. */
static int series_check(autobal_archive_series *s) {
  autobal_archive *a = s->a;
  if (atomic_load_explicit(&s->wfailed, memory_order_acquire)) {
    atomic_store_explicit(&s->wfailed, 0, memory_order_relaxed);
    s->broken = 1;
    s->nbuf = 0;
    s->nappended = s->nwritten;
    return autobal_error_set(&a->err, s->werr.status, "%s", s->werr.message);
  }
  if (s->broken)
    return autobal_error_set(&a->err, AUTOBAL_EIO, "series '%s' is unusable after an earlier write failure",
                             s->where);
  return AUTOBAL_SUCCESS;
}

/* The next fill ends on a chunk boundary of the file. */
static void series_restart_fill(autobal_archive_series *s) {
  s->nbuf = 0;
  s->limit = s->cap - s->nappended % AUTOBAL_ARCHIVE_SERIES_ROWS;
}

/* fill is full: wait for the previous buffer (reporting its failure), hand fill to the
 * writer (or write it here if there is none) and fill the other buffer. */
static int series_handoff(autobal_archive_series *s) {
  autobal_archive *a = s->a;
  double *tmp;
  int rc;
  series_idle(s);
  if ((rc = series_check(s)) != AUTOBAL_SUCCESS) return rc;
  tmp = s->wbuf;
  s->wbuf = s->fill;
  s->wrows = s->nbuf;
  s->fill = tmp;
  series_restart_fill(s);
  if (writer_start(a)) {
    (void)pthread_mutex_lock(&a->m);
    s->pending = 1;
    s->qnext = NULL;
    if (a->qtail != NULL) a->qtail->qnext = s;
    else a->qhead = s;
    a->qtail = s;
    (void)pthread_cond_signal(&a->work);
    (void)pthread_mutex_unlock(&a->m);
    return AUTOBAL_SUCCESS;
  }
  series_write_job(s);
  return series_check(s);
}

/* Write the rows of fill now.  The series must be idle and checked; called holding
 * autobal_archive_h5_lock_.  A failure breaks the series (message in the archive). */
static int series_write_fill(autobal_archive_series *s) {
  int rc = series_write_rows(s, s->fill, s->nbuf, &s->a->err);
  if (rc != AUTOBAL_SUCCESS) {
    s->broken = 1;
    s->nappended = s->nwritten;
  }
  series_restart_fill(s);
  return rc;
}

/* Everything appended to the archive's series goes to the file (before a variable is
 * made over a series dimension).  Called holding autobal_archive_h5_lock_ (q from autobal_archive_h5_enter_), which is
 * released while waiting for the writer. */
static int series_flush_all(autobal_archive *a, autobal_archive_quiet_ *q) {
  autobal_archive_series *s;
  int rc;
  if (a->series == NULL) return AUTOBAL_SUCCESS;
  autobal_archive_h5_leave_(q);
  for (s = a->series; s != NULL; s = s->next) series_idle(s);
  autobal_archive_h5_enter_(q);
  for (s = a->series; s != NULL; s = s->next) {
    if ((rc = series_check(s)) != AUTOBAL_SUCCESS) return rc;
    if ((rc = series_write_fill(s)) != AUTOBAL_SUCCESS) return rc;
  }
  return AUTOBAL_SUCCESS;
}

/* Close the datasets, unlink from the archive, free.  No flushing.  The series must be
 * idle; called holding autobal_archive_h5_lock_. */
static void series_free(autobal_archive_series *s) {
  autobal_archive_series **pp;
  size_t k;
  if (s == NULL) return;
  for (pp = &s->a->series; *pp != NULL; pp = &(*pp)->next)
    if (*pp == s) {
      *pp = s->next;
      break;
    }
  if (s->dsets != NULL)
    for (k = 0; k <= s->nvars; k++)
      if (s->dsets[k] >= 0) (void)H5Dclose(s->dsets[k]);
  free(s->dsets);
  free(s->mem);
  free(s->col);
  free(s);
}

/* Create one unlimited 1-D column.  It has no chunk cache (dapl), so that each chunk is
 * filtered and written by the H5Dwrite that completes it, i.e. in the writer thread, not
 * later when the dataset is closed. */
static hid_t series_column(autobal_archive *a, const char *path, const char *name, const char *units,
                           const char *long_name, hid_t scale, hid_t dapl) {
  hsize_t zero = 0, unl = H5S_UNLIMITED, chunk = AUTOBAL_ARCHIVE_SERIES_ROWS;
  hid_t ds = create_dataset(&a->err, a->file, path, H5T_IEEE_F64LE, 1, &zero, &unl, &chunk, sizeof(double),
                            SERIES_DEFLATE_LEVEL, dapl);
  int rc = AUTOBAL_SUCCESS;
  if (ds < 0) return -1;
  if (scale < 0) {
    if (H5DSset_scale(ds, name) < 0) rc = autobal_archive_h5fail_(&a->err, "cannot make '%s' a dimension scale", path);
  } else if (H5DSattach_scale(ds, scale, 0) < 0) {
    rc = autobal_archive_h5fail_(&a->err, "cannot attach the series dimension to '%s'", path);
    scale = -1;
  }
  if (rc == AUTOBAL_SUCCESS) rc = put_units_long_name(&a->err, ds, path, name, units, long_name);
  if (rc != AUTOBAL_SUCCESS) {
    if (scale >= 0) (void)H5DSdetach_scale(ds, scale, 0);
    (void)H5Dclose(ds);
    return -1;
  }
  return ds;
}

int autobal_archive_series_open(autobal_archive *a, const char *group, const char *dim, const char *dim_units,
                                const char *dim_long_name, size_t nvars, const char *const *names,
                                const char *const *units, const char *const *long_names,
                                autobal_archive_series **out) {
  char g[AUTOBAL_ARCHIVE_PATH_MAX], path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_series *s = NULL;
  autobal_archive_quiet_ q;
  hid_t dapl = -1;
  size_t j, k;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (out == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series_open: out is NULL");
  *out = NULL;
  if ((rc = writable(a)) != AUTOBAL_SUCCESS) return rc;
  if (nvars == 0 || names == NULL || units == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series_open: %s",
                             nvars == 0 ? "nvars = 0 (need at least one variable)" : "names or units is NULL");
  if ((rc = autobal_archive_norm_path_(&a->err, "group", group, g, sizeof g)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = check_name(&a->err, "series dimension name", dim)) != AUTOBAL_SUCCESS) return rc;
  if ((rc = check_text(&a->err, "series dimension units", dim_units)) != AUTOBAL_SUCCESS) return rc;
  if (dim_long_name != NULL && (rc = check_text(&a->err, "long_name", dim_long_name)) != AUTOBAL_SUCCESS)
    return rc;
  for (j = 0; j < nvars; j++) {
    if ((rc = check_name(&a->err, "series variable name", names[j])) != AUTOBAL_SUCCESS) return rc;
    if (units[j] == NULL)
      return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series variable '%s': units is NULL", names[j]);
    if ((rc = check_text(&a->err, "units", units[j])) != AUTOBAL_SUCCESS) return rc;
    if (long_names != NULL && long_names[j] != NULL &&
        (rc = check_text(&a->err, "long_name", long_names[j])) != AUTOBAL_SUCCESS)
      return rc;
    if (strcmp(names[j], dim) == 0)
      return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series variable '%s' has the name of the dimension",
                               names[j]);
    for (k = 0; k < j; k++)
      if (strcmp(names[j], names[k]) == 0)
        return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series variable '%s' appears twice", names[j]);
  }
  if (nvars > (SIZE_MAX / sizeof(double)) / (SERIES_BUF_CHUNKS * AUTOBAL_ARCHIVE_SERIES_ROWS) / 2 - 1)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series_open: nvars = %zu too large", nvars);

  s = (autobal_archive_series *)calloc(1, sizeof *s);
  if (s == NULL) return autobal_error_set(&a->err, AUTOBAL_ENOMEM, "series_open: out of memory");
  s->a = a;
  s->nvars = nvars;
  s->cap = SERIES_BUF_CHUNKS * AUTOBAL_ARCHIVE_SERIES_ROWS;
  s->limit = s->cap;
  atomic_init(&s->wfailed, 0);
  s->dsets = (hid_t *)malloc((nvars + 1) * sizeof *s->dsets);
  s->mem = (double *)malloc(2 * (nvars + 1) * s->cap * sizeof *s->mem);
  s->col = (double *)malloc(s->cap * sizeof *s->col);
  if (s->dsets == NULL || s->mem == NULL || s->col == NULL) {
    free(s->dsets);
    free(s->mem);
    free(s->col);
    free(s);
    return autobal_error_set(&a->err, AUTOBAL_ENOMEM, "series_open: out of memory");
  }
  s->fill = s->mem;
  s->wbuf = s->mem + (nvars + 1) * s->cap;
  for (k = 0; k <= nvars; k++) s->dsets[k] = -1;
  s->next = a->series;
  a->series = s;

  autobal_archive_h5_enter_(&q);
  dapl = H5Pcreate(H5P_DATASET_ACCESS);
  if (dapl < 0 || H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, H5D_CHUNK_CACHE_W0_DEFAULT) < 0)
    rc = autobal_archive_h5fail_(&a->err, "series_open: cannot set up the dataset access properties");
  if (rc == AUTOBAL_SUCCESS) rc = make_group(&a->err, a->file, g);
  if (rc == AUTOBAL_SUCCESS) rc = join_path(&a->err, g, dim, path, sizeof path);
  if (rc == AUTOBAL_SUCCESS) snprintf(s->where, sizeof s->where, "%s", path);
  for (k = 0; k <= nvars && rc == AUTOBAL_SUCCESS; k++) {
    const char *nm = k == 0 ? dim : names[k - 1];
    rc = join_path(&a->err, g, nm, path, sizeof path);
    if (rc == AUTOBAL_SUCCESS && autobal_archive_path_exists_(a->file, path))
      rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "'%s' already exists in '%s'", path, a->path);
  }
  k = 0; /* columns 0..k-1 were attempted */
  if (rc == AUTOBAL_SUCCESS) {
    for (; k <= nvars && rc == AUTOBAL_SUCCESS; k++) {
      const char *nm = k == 0 ? dim : names[k - 1];
      const char *un = k == 0 ? dim_units : units[k - 1];
      const char *ln = k == 0 ? dim_long_name : (long_names ? long_names[k - 1] : NULL);
      rc = join_path(&a->err, g, nm, path, sizeof path);
      if (rc == AUTOBAL_SUCCESS) {
        s->dsets[k] = series_column(a, path, nm, un, ln, k == 0 ? -1 : s->dsets[0], dapl);
        if (s->dsets[k] < 0) rc = AUTOBAL_EIO;
      }
    }
  }
  if (dapl >= 0) (void)H5Pclose(dapl);
  if (rc != AUTOBAL_SUCCESS) {
    /* Remove what this call made (the names did not exist before): variables first
     * (detached from the scale), then the scale. */
    size_t made = k;
    for (k = 1; k <= nvars; k++)
      if (s->dsets[k] >= 0 && s->dsets[0] >= 0) (void)H5DSdetach_scale(s->dsets[k], s->dsets[0], 0);
    series_free(s);
    for (k = made; k-- > 0;) {
      char p[AUTOBAL_ARCHIVE_PATH_MAX];
      autobal_error scratch;
      if (join_path(&scratch, g, k == 0 ? dim : names[k - 1], p, sizeof p) == AUTOBAL_SUCCESS)
        remove_link(a->file, p);
    }
  } else {
    *out = s;
  }
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_series_append(autobal_archive_series *s, size_t nrows, const double *t, const double *rows) {
  autobal_archive *a;
  size_t i = 0, k;
  const size_t nvars = s != NULL ? s->nvars : 0;
  if (s == NULL) return AUTOBAL_EINVAL;
  a = s->a;
  autobal_error_clear(&a->err);
  if (nrows == 0) return AUTOBAL_SUCCESS;
  if (t == NULL || rows == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "series '%s': append of %zu rows with %s NULL", s->where,
                             nrows, t == NULL ? "t" : "rows");
  if (s->broken || atomic_load_explicit(&s->wfailed, memory_order_relaxed)) {
    /* The writer failed on an earlier buffer: report it (EIO), drop these rows. */
    series_idle(s);
    return series_check(s);
  }
  while (i < nrows) {
    size_t m = s->limit - s->nbuf;
    double *b = s->fill + s->nbuf * (nvars + 1);
    if (m > nrows - i) m = nrows - i;
    for (k = 0; k < m; k++, b += nvars + 1) {
      b[0] = t[i + k];
      memcpy(b + 1, rows + (i + k) * nvars, nvars * sizeof *b);
    }
    s->nbuf += m;
    s->nappended += m;
    i += m;
    if (s->nbuf == s->limit) {
      int rc = series_handoff(s);
      if (rc != AUTOBAL_SUCCESS) return rc;
    }
  }
  return AUTOBAL_SUCCESS;
}

int autobal_archive_series_flush(autobal_archive_series *s) {
  autobal_archive_quiet_ q;
  int rc;
  if (s == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&s->a->err);
  series_idle(s);
  if ((rc = series_check(s)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  rc = series_write_fill(s);
  if (rc == AUTOBAL_SUCCESS && H5Fflush(s->a->file, H5F_SCOPE_LOCAL) < 0)
    rc = autobal_archive_h5fail_(&s->a->err, "series '%s': cannot flush '%s'", s->where, s->a->tmp_path);
  autobal_archive_h5_leave_(&q);
  return rc;
}

size_t autobal_archive_series_length(const autobal_archive_series *s) { return s ? s->nappended : 0; }

int autobal_archive_series_close(autobal_archive_series *s) {
  autobal_archive_quiet_ q;
  int rc;
  if (s == NULL) return AUTOBAL_SUCCESS;
  autobal_error_clear(&s->a->err);
  series_idle(s);
  rc = series_check(s);
  autobal_archive_h5_enter_(&q);
  if (rc == AUTOBAL_SUCCESS) rc = series_write_fill(s);
  series_free(s);
  autobal_archive_h5_leave_(&q);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* Close, discard                                                              */
/* ------------------------------------------------------------------------ */

/* Move tmp to path: no-clobber (link + unlink) unless overwrite. */
static int publish(autobal_archive *a) {
  if (!a->overwrite) {
    if (link(a->tmp_path, a->path) == 0) {
      if (unlink(a->tmp_path) != 0)
        return autobal_error_set(&a->err, AUTOBAL_EIO, "archive '%s' written but temporary '%s' not removed: %s",
                                 a->path, a->tmp_path, strerror(errno));
      return AUTOBAL_SUCCESS;
    }
    if (errno == EEXIST)
      return autobal_error_set(&a->err, AUTOBAL_EEXIST,
                               "archive '%s' appeared while writing (overwrite not allowed); data kept in '%s'",
                               a->path, a->tmp_path);
    /* No hard links on this file system: fall back to rename after a check. */
    if (access(a->path, F_OK) == 0)
      return autobal_error_set(&a->err, AUTOBAL_EEXIST,
                               "archive '%s' appeared while writing (overwrite not allowed); data kept in '%s'",
                               a->path, a->tmp_path);
  }
  if (rename(a->tmp_path, a->path) != 0)
    return autobal_error_set(&a->err, AUTOBAL_EIO, "cannot rename '%s' to '%s': %s", a->tmp_path, a->path,
                             strerror(errno));
  return AUTOBAL_SUCCESS;
}

int autobal_archive_close(autobal_archive *a, autobal_error *err) {
  autobal_archive_series *s;
  autobal_archive_quiet_ q;
  int rc = AUTOBAL_SUCCESS, r;
  if (a == NULL) return AUTOBAL_SUCCESS;
  autobal_error_clear(&a->err);
  /* Let the writer finish what it has (not holding autobal_archive_h5_lock_), then stop it. */
  for (s = a->series; s != NULL; s = s->next) series_idle(s);
  writer_stop(a);
  autobal_archive_h5_enter_(&q);
  while (a->series != NULL) {
    s = a->series;
    r = series_check(s);
    if (r == AUTOBAL_SUCCESS) r = series_write_fill(s);
    if (r != AUTOBAL_SUCCESS && rc == AUTOBAL_SUCCESS) rc = r;
    series_free(s);
  }
  if (a->writable && rc == AUTOBAL_SUCCESS) {
    rc = write_root_string(a, "status", a->final_status);
    if (rc == AUTOBAL_SUCCESS && a->has_reason) rc = write_root_string(a, "status_reason", a->reason);
  }
  if (a->file >= 0 && H5Fclose(a->file) < 0 && rc == AUTOBAL_SUCCESS)
    rc = autobal_archive_h5fail_(&a->err, "cannot close '%s'", a->writable ? a->tmp_path : a->path);
  a->file = -1;
  autobal_archive_h5_leave_(&q);
  if (a->writable) {
    if (rc == AUTOBAL_SUCCESS) rc = publish(a);
    if (rc != AUTOBAL_SUCCESS && access(a->tmp_path, F_OK) == 0 && strstr(a->err.message, a->tmp_path) == NULL) {
      char msg[AUTOBAL_ERRMSG_SIZE];
      snprintf(msg, sizeof msg, "%s", a->err.message);
      autobal_error_set(&a->err, rc, "%.380s (data kept in '%.100s')", msg, a->tmp_path);
    }
  }
  if (rc != AUTOBAL_SUCCESS) autobal_error_set(err, rc, "%s", a->err.message);
  else autobal_error_clear(err);
  autobal_archive_free_handle_(a);
  return rc;
}

void autobal_archive_discard(autobal_archive *a) {
  autobal_archive_series *s;
  autobal_archive_quiet_ q;
  if (a == NULL) return;
  for (s = a->series; s != NULL; s = s->next) series_idle(s);
  writer_stop(a);
  autobal_archive_h5_enter_(&q);
  while (a->series != NULL) series_free(a->series);
  if (a->file >= 0) (void)H5Fclose(a->file);
  autobal_archive_h5_leave_(&q);
  if (a->writable && a->tmp_path != NULL) (void)unlink(a->tmp_path);
  autobal_archive_free_handle_(a);
}
