/* archive_read.c: the reading side of the HDF5 archive (see include/autobal/archive.h):
 * opening an archive for reading, attributes, shapes and values of datasets, listing groups,
 * attributes and dimension scales.  Every entry point takes the process-wide HDF5 lock
 * (autobal_archive_h5_enter_), as the writing side does (archive.c).
 *
 * May use: archive_internal.h (handle layout, HDF5 lock and errors, paths), HDF5, core
 * (internal.h).  No physics. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include "archive/archive_internal.h"
#include "autobal/archive.h"
#include "internal.h"


/* ------------------------------------------------------------------------ */
/* Reading                                                                     */
/* ------------------------------------------------------------------------ */

/* Read a scalar string attribute (vlen or fixed) into a malloc'ed string. */
static int get_attr_string(autobal_error *err, hid_t o, const char *where, const char *name, char **value) {
  hid_t attr = -1, ft = -1, mt = -1, sp = -1;
  int rc = AUTOBAL_SUCCESS;
  *value = NULL;
  attr = H5Aopen(o, name, H5P_DEFAULT);
  if (attr < 0) return autobal_archive_h5fail_(err, "cannot open attribute '%s' of '%s'", name, where);
  ft = H5Aget_type(attr);
  sp = H5Aget_space(attr);
  if (ft < 0 || sp < 0) {
    rc = autobal_archive_h5fail_(err, "cannot inspect attribute '%s' of '%s'", name, where);
    goto done;
  }
  if (H5Tget_class(ft) != H5T_STRING || H5Sget_simple_extent_npoints(sp) != 1) {
    rc = autobal_error_set(err, AUTOBAL_EFORMAT, "attribute '%s' of '%s' is not a string", name, where);
    goto done;
  }
  mt = H5Tcopy(H5T_C_S1);
  if (mt < 0 || H5Tset_cset(mt, H5Tget_cset(ft)) < 0) {
    rc = autobal_archive_h5fail_(err, "cannot read attribute '%s' of '%s'", name, where);
    goto done;
  }
  if (H5Tis_variable_str(ft) > 0) {
    char *p = NULL;
    if (H5Tset_size(mt, H5T_VARIABLE) < 0 || H5Aread(attr, mt, &p) < 0) {
      rc = autobal_archive_h5fail_(err, "cannot read attribute '%s' of '%s'", name, where);
      goto done;
    }
    *value = autobal_archive_dup_str_(p ? p : "");
    if (p != NULL) (void)H5free_memory(p);
  } else {
    size_t sz = H5Tget_size(ft);
    char *p = (char *)calloc(sz + 1, 1);
    if (p == NULL) {
      rc = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory reading attribute '%s'", name);
      goto done;
    }
    if (H5Tset_size(mt, sz) < 0 || H5Tset_strpad(mt, H5Tget_strpad(ft)) < 0 || H5Aread(attr, mt, p) < 0) {
      rc = autobal_archive_h5fail_(err, "cannot read attribute '%s' of '%s'", name, where);
      free(p);
      goto done;
    }
    p[sz] = '\0';
    *value = p;
  }
  if (*value == NULL) rc = autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory reading attribute '%s'", name);
done:
  if (mt >= 0) (void)H5Tclose(mt);
  if (ft >= 0) (void)H5Tclose(ft);
  if (sp >= 0) (void)H5Sclose(sp);
  (void)H5Aclose(attr);
  return rc;
}

/* "<name>.partial-<pid>[-<k>]": the temporary file of autobal_archive_create.  One that cannot be
 * read is what a killed run (SIGKILL, power loss) leaves: HDF5 had not written its metadata. */
static int is_partial_name(const char *path) {
  const char *p = strstr(path, ".partial-"), *q;
  if (!p) return 0;
  for (q = p + 9; *q && ((*q >= '0' && *q <= '9') || *q == '-'); q++) {
  }
  return *q == '\0' && q > p + 9;
}
#define PARTIAL_MSG                                                                                      \
  "'%s' is the temporary file of a run that did not finish (killed before it could close its "          \
  "archive): HDF5 had not written the file's metadata, so it cannot be read; repeat the run (an "       \
  "interrupted run, SIGINT/SIGTERM/SIGHUP, closes an archive marked incomplete instead)"

int autobal_archive_open_read(const char *path, autobal_archive **out, autobal_error *err) {
  autobal_archive *a;
  struct stat st;
  autobal_archive_quiet_ q;
  htri_t is;
  char *conv = NULL;
  int rc = AUTOBAL_SUCCESS;
  if (out == NULL) return autobal_error_set(err, AUTOBAL_EINVAL, "archive_open_read: out is NULL");
  *out = NULL;
  if (path == NULL || path[0] == '\0')
    return autobal_error_set(err, AUTOBAL_EINVAL, "archive path is NULL or empty");
  if (stat(path, &st) != 0)
    return autobal_error_set(err, AUTOBAL_EIO, "cannot open archive '%s': %s", path, strerror(errno));
  if (S_ISDIR(st.st_mode))
    return autobal_error_set(err, AUTOBAL_EIO, "cannot open archive '%s': is a directory", path);
  if (!S_ISREG(st.st_mode)) /* a FIFO would block the open forever */
    return autobal_error_set(err, AUTOBAL_EIO,
                             "cannot open archive '%s': not a regular file (a FIFO, device or "
                             "socket); an archive is a regular HDF5 file",
                             path);
  if (access(path, R_OK) != 0)
    return autobal_error_set(err, AUTOBAL_EIO, "cannot open archive '%s': %s", path, strerror(errno));
  a = (autobal_archive *)calloc(1, sizeof *a);
  if (a == NULL) return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory opening '%s'", path);
  a->file = -1;
  a->path = autobal_archive_dup_str_(path);
  if (a->path == NULL) {
    autobal_archive_free_handle_(a);
    return autobal_error_set(err, AUTOBAL_ENOMEM, "out of memory opening '%s'", path);
  }
  autobal_archive_h5_enter_(&q);
  is = H5Fis_hdf5(path);
  if (is <= 0) {
    rc = autobal_error_set(err, AUTOBAL_EFORMAT, "'%s' is not an HDF5 file (not an autobal archive)", path);
    goto done;
  }
  a->file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (a->file < 0 && is_partial_name(path)) {
    rc = autobal_error_set(err, AUTOBAL_EFORMAT, PARTIAL_MSG, path);
    goto done;
  }
  if (a->file < 0) {
    (void)autobal_archive_h5fail_(err, "'%s' is a damaged or truncated HDF5 file", path);
    if (err) err->status = AUTOBAL_EFORMAT;
    rc = AUTOBAL_EFORMAT;
    goto done;
  }
  if (H5Aexists(a->file, "Conventions") <= 0) {
    if (is_partial_name(path))
      rc = autobal_error_set(err, AUTOBAL_EFORMAT, PARTIAL_MSG, path);
    else
      rc = autobal_error_set(err, AUTOBAL_EFORMAT, "'%s' is an HDF5 file but not an autobal archive "
                             "(no root attribute Conventions)", path);
    goto done;
  }
  rc = get_attr_string(err, a->file, "/", "Conventions", &conv);
  if (rc != AUTOBAL_SUCCESS) {
    if (err) err->status = AUTOBAL_EFORMAT;
    rc = AUTOBAL_EFORMAT;
    goto done;
  }
  if (!autobal_archive_conventions_include_(conv, AUTOBAL_ARCHIVE_CONVENTION))
    rc = autobal_error_set(err, AUTOBAL_EFORMAT, "'%.200s' has Conventions = '%.100s', which does not include '%s'",
                           path, conv, AUTOBAL_ARCHIVE_CONVENTION);
done:
  free(conv);
  if (rc != AUTOBAL_SUCCESS && a->file >= 0) {
    (void)H5Fclose(a->file);
    a->file = -1;
  }
  autobal_archive_h5_leave_(&q);
  if (rc != AUTOBAL_SUCCESS) {
    autobal_archive_free_handle_(a);
    return rc;
  }
  autobal_error_clear(err);
  *out = a;
  return AUTOBAL_SUCCESS;
}

int autobal_archive_has(autobal_archive *a, const char *obj, const char *attr) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_error scratch;
  autobal_archive_quiet_ q;
  int yes = 0;
  if (a == NULL || a->file < 0) return 0;
  if (autobal_archive_norm_path_(&scratch, "object", obj, path, sizeof path) != AUTOBAL_SUCCESS) return 0;
  autobal_archive_h5_enter_(&q);
  yes = autobal_archive_path_exists_(a->file, path);
  if (yes && attr != NULL) {
    hid_t o = H5Oopen(a->file, path, H5P_DEFAULT);
    yes = o >= 0 && H5Aexists(o, attr) > 0;
    if (o >= 0) (void)H5Oclose(o);
  }
  autobal_archive_h5_leave_(&q);
  return yes;
}

/* Open obj and check attribute exists. */
static int read_attr_begin(autobal_archive *a, const char *obj, const char *name, char *path, size_t size,
                           hid_t *o) {
  int rc;
  htri_t ex;
  *o = -1;
  if ((rc = autobal_archive_norm_path_(&a->err, "object", obj, path, size)) != AUTOBAL_SUCCESS) return rc;
  if (name == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "attribute name is NULL");
  if (!autobal_archive_path_exists_(a->file, path))
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "no object '%s' in '%s'", path, a->path);
  *o = H5Oopen(a->file, path, H5P_DEFAULT);
  if (*o < 0) return autobal_archive_h5fail_(&a->err, "cannot open '%s'", path);
  ex = H5Aexists(*o, name);
  if (ex < 0) return autobal_archive_h5fail_(&a->err, "cannot look up attribute '%.200s' of '%s'", name, path);
  if (ex == 0)
    return autobal_error_set(&a->err, AUTOBAL_EFORMAT, "'%s' has no attribute '%.200s' (in '%s')", path, name,
                             a->path);
  return AUTOBAL_SUCCESS;
}

int autobal_archive_read_attr_string(autobal_archive *a, const char *obj, const char *name, char *buf,
                                     size_t size, size_t *len) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  char *v = NULL;
  hid_t o;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (buf == NULL || size == 0)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "read_attr_string: buf is NULL or size is 0");
  buf[0] = '\0';
  autobal_archive_h5_enter_(&q);
  rc = read_attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) rc = get_attr_string(&a->err, o, path, name, &v);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  if (rc == AUTOBAL_SUCCESS) {
    size_t n = strlen(v);
    if (len != NULL) *len = n;
    if (n >= size) {
      memcpy(buf, v, size - 1);
      buf[size - 1] = '\0';
      rc = autobal_error_set(&a->err, AUTOBAL_WARNING, "attribute '%s' of '%s' truncated to %zu of %zu bytes",
                             name, path, size - 1, n);
    } else {
      memcpy(buf, v, n + 1);
    }
  }
  free(v);
  return rc;
}

/* Read all elements of numeric attribute `name` of `obj` into buf (memory type mt:
 * H5T_NATIVE_DOUBLE or H5T_NATIVE_INT64); integers_only for _int64s. */
static int read_attr_array(autobal_archive *a, const char *obj, const char *name, hid_t mt, int integers_only,
                           int scalar, void *buf, size_t n, size_t *count) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t o, attr = -1, ft = -1, sp = -1;
  int rc;
  if (count != NULL) *count = 0;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (buf == NULL && n > 0)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "read_attr_%s: buf is NULL with n = %zu",
                             integers_only ? "int64s" : "doubles", n);
  autobal_archive_h5_enter_(&q);
  rc = read_attr_begin(a, obj, name, path, sizeof path, &o);
  if (rc == AUTOBAL_SUCCESS) {
    attr = H5Aopen(o, name, H5P_DEFAULT);
    if (attr < 0) rc = autobal_archive_h5fail_(&a->err, "cannot open attribute '%s' of '%s'", name, path);
  }
  if (rc == AUTOBAL_SUCCESS) {
    ft = H5Aget_type(attr);
    sp = H5Aget_space(attr);
    if (ft < 0 || sp < 0) rc = autobal_archive_h5fail_(&a->err, "cannot inspect attribute '%s' of '%s'", name, path);
  }
  if (rc == AUTOBAL_SUCCESS) {
    H5T_class_t c = H5Tget_class(ft);
    hssize_t np = H5Sget_simple_extent_npoints(sp);
    if (np < 0) {
      rc = autobal_archive_h5fail_(&a->err, "cannot get the size of attribute '%s' of '%s'", name, path);
    } else if (scalar && ((c != H5T_INTEGER && c != H5T_FLOAT) || np != 1)) {
      rc = autobal_error_set(&a->err, AUTOBAL_EFORMAT, "attribute '%s' of '%s' is not a numeric scalar", name,
                             path);
    } else if (c != H5T_INTEGER && (integers_only || c != H5T_FLOAT)) {
      rc = autobal_error_set(&a->err, AUTOBAL_EFORMAT, "attribute '%s' of '%s' is %s, not %s", name, path,
                             c == H5T_FLOAT ? "floating point" : c == H5T_STRING ? "a string" : "not numeric",
                             integers_only ? "an integer" : "numeric");
    } else {
      if (count != NULL) *count = (size_t)np;
      if ((size_t)np > n && !(buf == NULL && n == 0))
        rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "attribute '%s' of '%s' has %zu elements, the buffer holds %zu",
                               name, path, (size_t)np, n);
      else if (buf != NULL && np > 0 && H5Aread(attr, mt, buf) < 0)
        rc = autobal_archive_h5fail_(&a->err, "cannot read attribute '%s' of '%s'", name, path);
    }
  }
  if (ft >= 0) (void)H5Tclose(ft);
  if (sp >= 0) (void)H5Sclose(sp);
  if (attr >= 0) (void)H5Aclose(attr);
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_read_attr_double(autobal_archive *a, const char *obj, const char *name, double *value) {
  if (a == NULL) return AUTOBAL_EINVAL;
  if (value == NULL) {
    autobal_error_clear(&a->err);
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "read_attr_double: value is NULL");
  }
  return read_attr_array(a, obj, name, H5T_NATIVE_DOUBLE, 0, 1, value, 1, NULL);
}

/* Open a dataset for reading; *ds = -1 on failure. */
static int open_dataset(autobal_archive *a, const char *p, char *path, size_t size, hid_t *ds) {
  int rc;
  *ds = -1;
  if ((rc = autobal_archive_norm_path_(&a->err, "dataset", p, path, size)) != AUTOBAL_SUCCESS) return rc;
  if (autobal_archive_path_type_(a->file, path) != H5I_DATASET)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "no dataset '%s' in '%s'", path, a->path);
  *ds = H5Dopen2(a->file, path, H5P_DEFAULT);
  if (*ds < 0) return autobal_archive_h5fail_(&a->err, "cannot open dataset '%s'", path);
  return AUTOBAL_SUCCESS;
}

/* Shape of an open dataset. */
static int shape_of(autobal_archive *a, hid_t ds, const char *path, int *rank, size_t *dims, size_t *count) {
  hsize_t d[H5S_MAX_RANK];
  hid_t sp = H5Dget_space(ds);
  int r, i, rc = AUTOBAL_SUCCESS;
  size_t c = 1;
  if (sp < 0) return autobal_archive_h5fail_(&a->err, "cannot get the shape of '%s'", path);
  r = H5Sget_simple_extent_ndims(sp);
  if (r < 0 || H5Sget_simple_extent_dims(sp, d, NULL) < 0) {
    rc = autobal_archive_h5fail_(&a->err, "cannot get the shape of '%s'", path);
  } else if (r > AUTOBAL_ARCHIVE_MAX_RANK) {
    rc = autobal_error_set(&a->err, AUTOBAL_EUNSUPPORTED, "'%s' has rank %d > %d", path, r,
                           AUTOBAL_ARCHIVE_MAX_RANK);
  } else {
    *rank = r;
    for (i = 0; i < r; i++) {
      if (dims != NULL) dims[i] = (size_t)d[i];
      c *= (size_t)d[i];
    }
    if (count != NULL) *count = c;
  }
  (void)H5Sclose(sp);
  return rc;
}

int autobal_archive_var_shape(autobal_archive *a, const char *p, int *rank, size_t *dims, size_t *count) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t ds;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (rank == NULL || dims == NULL)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL, "var_shape: rank or dims is NULL");
  autobal_archive_h5_enter_(&q);
  rc = open_dataset(a, p, path, sizeof path, &ds);
  if (rc == AUTOBAL_SUCCESS) rc = shape_of(a, ds, path, rank, dims, count);
  if (ds >= 0) (void)H5Dclose(ds);
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_read_var(autobal_archive *a, const char *p, double *buf, size_t n) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  size_t dims[AUTOBAL_ARCHIVE_MAX_RANK], count = 0;
  autobal_archive_quiet_ q;
  hid_t ds, ft = -1;
  int rc, rank = 0;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (buf == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "read_var: buf is NULL");
  autobal_archive_h5_enter_(&q);
  rc = open_dataset(a, p, path, sizeof path, &ds);
  if (rc == AUTOBAL_SUCCESS) rc = shape_of(a, ds, path, &rank, dims, &count);
  if (rc == AUTOBAL_SUCCESS && count > n)
    rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "read_var: '%s' has %zu elements, buffer holds %zu", path,
                           count, n);
  if (rc == AUTOBAL_SUCCESS) {
    H5T_class_t c;
    ft = H5Dget_type(ds);
    c = ft >= 0 ? H5Tget_class(ft) : H5T_NO_CLASS;
    if (ft < 0) rc = autobal_archive_h5fail_(&a->err, "cannot get the type of '%s'", path);
    else if (c != H5T_INTEGER && c != H5T_FLOAT)
      rc = autobal_error_set(&a->err, AUTOBAL_EFORMAT, "dataset '%s' is not numeric", path);
  }
  if (rc == AUTOBAL_SUCCESS && count > 0 && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot read '%s'", path);
  if (ft >= 0) (void)H5Tclose(ft);
  if (ds >= 0) (void)H5Dclose(ds);
  autobal_archive_h5_leave_(&q);
  return rc;
}

/* Members collected by list_cb: entries "<is_group byte><name>\0" one after another.
 * The caller's callback runs after the iteration, outside autobal_archive_h5_lock_, so that it may call
 * this module again. */
typedef struct {
  char *buf;
  size_t len, cap;
  int nomem;
} list_ctx;

static herr_t list_cb(hid_t g, const char *name, const H5L_info_t *info, void *vctx) {
  list_ctx *c = (list_ctx *)vctx;
  size_t n = strlen(name) + 2;
  hid_t o;
  int is_group = 0;
  (void)info;
  if (c->cap - c->len < n) {
    size_t cap = c->cap ? 2 * c->cap : 1024;
    char *p;
    while (cap - c->len < n) cap *= 2;
    p = (char *)realloc(c->buf, cap);
    if (p == NULL) {
      c->nomem = 1;
      return 1; /* stop */
    }
    c->buf = p;
    c->cap = cap;
  }
  o = H5Oopen(g, name, H5P_DEFAULT);
  if (o >= 0) {
    is_group = H5Iget_type(o) == H5I_GROUP;
    (void)H5Oclose(o);
  }
  c->buf[c->len] = is_group ? '\1' : '\0';
  memcpy(c->buf + c->len + 1, name, n - 1);
  c->len += n;
  return 0;
}

int autobal_archive_object_id(autobal_archive *a, const char *obj, uint64_t *id) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  H5O_info_t oi;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (id == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "object_id: id is NULL");
  if ((rc = autobal_archive_norm_path_(&a->err, "obj", obj, path, sizeof path)) != AUTOBAL_SUCCESS) return rc;
  autobal_archive_h5_enter_(&q);
  if (autobal_archive_path_type_(a->file, path) < 0)
    rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "no object '%s' in '%s'", path, a->path);
  else if (H5Oget_info_by_name2(a->file, path, &oi, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot identify object '%s'", path);
  else
    *id = (uint64_t)oi.addr;
  autobal_archive_h5_leave_(&q);
  return rc;
}

int autobal_archive_list(autobal_archive *a, const char *group, autobal_archive_list_fn fn, void *ctx) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  list_ctx c;
  hid_t g = -1, gcpl = -1;
  unsigned flags = 0;
  hsize_t idx = 0;
  size_t off;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (fn == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "list: callback is NULL");
  if ((rc = autobal_archive_norm_path_(&a->err, "group", group, path, sizeof path)) != AUTOBAL_SUCCESS) return rc;
  memset(&c, 0, sizeof c);
  autobal_archive_h5_enter_(&q);
  if (autobal_archive_path_type_(a->file, path) != H5I_GROUP) {
    rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "no group '%s' in '%s'", path, a->path);
    goto done;
  }
  g = H5Gopen2(a->file, path, H5P_DEFAULT);
  if (g < 0) {
    rc = autobal_archive_h5fail_(&a->err, "cannot open group '%s'", path);
    goto done;
  }
  gcpl = H5Gget_create_plist(g);
  if (gcpl >= 0 && H5Pget_link_creation_order(gcpl, &flags) < 0) flags = 0;
  if (H5Literate(g, (flags & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME, H5_ITER_INC, &idx,
                 list_cb, &c) < 0)
    rc = autobal_archive_h5fail_(&a->err, "cannot list group '%s'", path);
  else if (c.nomem)
    rc = autobal_error_set(&a->err, AUTOBAL_ENOMEM, "list: out of memory listing group '%s'", path);
done:
  if (gcpl >= 0) (void)H5Pclose(gcpl);
  if (g >= 0) (void)H5Gclose(g);
  autobal_archive_h5_leave_(&q);
  for (off = 0; rc == AUTOBAL_SUCCESS && off < c.len; off += strlen(c.buf + off + 1) + 2)
    rc = fn(c.buf + off + 1, c.buf[off] != '\0', ctx);
  free(c.buf);
  return rc;
}

/* ------------------------------------------------------------------------ */
/* Reading: attributes listed and read as arrays, datasets described          */
/* ------------------------------------------------------------------------ */

/* Class, element size and signedness of an HDF5 type. */
static void type_info(hid_t t, int *cls, size_t *size, int *is_unsigned) {
  H5T_class_t c = H5Tget_class(t);
  *is_unsigned = 0;
  *size = 0;
  switch (c) {
    case H5T_FLOAT:
      *cls = AUTOBAL_ARCHIVE_CLASS_FLOAT;
      *size = H5Tget_size(t);
      break;
    case H5T_INTEGER:
      *cls = AUTOBAL_ARCHIVE_CLASS_INTEGER;
      *size = H5Tget_size(t);
      *is_unsigned = H5Tget_sign(t) == H5T_SGN_NONE;
      break;
    case H5T_STRING:
      *cls = AUTOBAL_ARCHIVE_CLASS_STRING;
      *size = H5Tis_variable_str(t) > 0 ? 0 : H5Tget_size(t);
      break;
    default:
      *cls = AUTOBAL_ARCHIVE_CLASS_OTHER;
      *size = H5Tget_size(t);
      break;
  }
}

/* The attributes found by attr_list_cb: their infos, names in one buffer (name_off[i]
 * is the offset of info[i]'s name; the pointers are set after the iteration). */
typedef struct {
  autobal_archive_attr_info *info;
  size_t *name_off;
  size_t n, cap;
  char *names;
  size_t len, ncap;
  int nomem;
  int bad;             /* an attribute could not be inspected (h5 error stack kept) */
  char bad_name[128];  /* ... its name */
} attr_list_ctx;

static void attr_list_reset(attr_list_ctx *c) {
  free(c->info);
  free(c->name_off);
  free(c->names);
  memset(c, 0, sizeof *c);
}

static herr_t attr_list_cb(hid_t loc, const char *name, const H5A_info_t *ainfo, void *vctx) {
  attr_list_ctx *c = (attr_list_ctx *)vctx;
  autobal_archive_attr_info *in;
  size_t nlen = strlen(name) + 1;
  hid_t attr, ft = -1, sp = -1;
  hssize_t np;
  int nd;
  (void)ainfo;
  if (autobal_archive_reserved_attr_name_(name)) return 0;
  if (c->n == c->cap) {
    size_t cap = c->cap ? 2 * c->cap : 16;
    autobal_archive_attr_info *pi = (autobal_archive_attr_info *)realloc(c->info, cap * sizeof *pi);
    size_t *po;
    if (pi == NULL) goto nomem;
    c->info = pi;
    po = (size_t *)realloc(c->name_off, cap * sizeof *po);
    if (po == NULL) goto nomem;
    c->name_off = po;
    c->cap = cap;
  }
  if (c->ncap - c->len < nlen) {
    size_t cap = c->ncap ? 2 * c->ncap : 1024;
    char *p;
    while (cap - c->len < nlen) cap *= 2;
    p = (char *)realloc(c->names, cap);
    if (p == NULL) goto nomem;
    c->names = p;
    c->ncap = cap;
  }
  in = &c->info[c->n];
  memset(in, 0, sizeof *in);
  attr = H5Aopen(loc, name, H5P_DEFAULT);
  if (attr >= 0) {
    ft = H5Aget_type(attr);
    sp = H5Aget_space(attr);
  }
  np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  nd = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
  if (attr < 0 || ft < 0 || sp < 0 || np < 0 || nd < 0) {
    if (ft >= 0) (void)H5Tclose(ft);
    if (sp >= 0) (void)H5Sclose(sp);
    if (attr >= 0) (void)H5Aclose(attr);
    c->bad = 1;
    snprintf(c->bad_name, sizeof c->bad_name, "%s", name);
    return -1; /* stop; the error stack tells why */
  }
  type_info(ft, &in->type_class, &in->size, &in->is_unsigned);
  in->rank = nd;
  in->count = (size_t)np;
  (void)H5Tclose(ft);
  (void)H5Sclose(sp);
  (void)H5Aclose(attr);
  memcpy(c->names + c->len, name, nlen);
  c->name_off[c->n] = c->len;
  c->len += nlen;
  c->n++;
  return 0;
nomem:
  c->nomem = 1;
  return 1; /* stop */
}

/* Whether the object o tracks the creation order of its attributes. */
static int attr_order_tracked(hid_t o) {
  H5I_type_t t = H5Iget_type(o);
  hid_t pl = t == H5I_GROUP ? H5Gget_create_plist(o) : t == H5I_DATASET ? H5Dget_create_plist(o) : -1;
  unsigned flags = 0;
  int yes;
  if (pl < 0) return 0;
  yes = H5Pget_attr_creation_order(pl, &flags) >= 0 && (flags & H5P_CRT_ORDER_TRACKED) != 0;
  (void)H5Pclose(pl);
  return yes;
}

int autobal_archive_list_attrs(autobal_archive *a, const char *obj, int order, autobal_archive_attr_fn fn,
                               void *ctx) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  attr_list_ctx c;
  hid_t o = -1;
  hsize_t idx = 0;
  size_t i;
  int rc;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (fn == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "list_attrs: callback is NULL");
  if (order != AUTOBAL_ARCHIVE_ORDER_NAME && order != AUTOBAL_ARCHIVE_ORDER_CREATION)
    return autobal_error_set(&a->err, AUTOBAL_EINVAL,
                             "list_attrs: order = %d is not AUTOBAL_ARCHIVE_ORDER_NAME (%d) or _CREATION (%d)", order,
                             AUTOBAL_ARCHIVE_ORDER_NAME, AUTOBAL_ARCHIVE_ORDER_CREATION);
  if ((rc = autobal_archive_norm_path_(&a->err, "object", obj, path, sizeof path)) != AUTOBAL_SUCCESS) return rc;
  memset(&c, 0, sizeof c);
  autobal_archive_h5_enter_(&q);
  if (a->file < 0 || !autobal_archive_path_exists_(a->file, path)) {
    rc = autobal_error_set(&a->err, AUTOBAL_EINVAL, "no object '%s' in '%s'", path, a->path);
    goto done;
  }
  o = H5Oopen(a->file, path, H5P_DEFAULT);
  if (o < 0) {
    rc = autobal_archive_h5fail_(&a->err, "cannot open '%s'", path);
    goto done;
  }
  if (order == AUTOBAL_ARCHIVE_ORDER_CREATION && !attr_order_tracked(o)) order = AUTOBAL_ARCHIVE_ORDER_NAME;
  if (H5Aiterate2(o, order == AUTOBAL_ARCHIVE_ORDER_CREATION ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME, H5_ITER_INC,
                  &idx, attr_list_cb, &c) < 0) {
    if (c.bad) rc = autobal_archive_h5fail_(&a->err, "cannot inspect attribute '%s' of '%s'", c.bad_name, path);
    else rc = autobal_archive_h5fail_(&a->err, "cannot list the attributes of '%s'", path);
  } else if (c.nomem) {
    rc = autobal_error_set(&a->err, AUTOBAL_ENOMEM, "list_attrs: out of memory listing the attributes of '%s'",
                           path);
  }
done:
  if (o >= 0) (void)H5Oclose(o);
  autobal_archive_h5_leave_(&q);
  for (i = 0; rc == AUTOBAL_SUCCESS && i < c.n; i++) {
    c.info[i].name = c.names + c.name_off[i];
    rc = fn(&c.info[i], ctx);
  }
  attr_list_reset(&c);
  return rc;
}

int autobal_archive_read_attr_doubles(autobal_archive *a, const char *obj, const char *name, double *buf, size_t n,
                                      size_t *count) {
  return read_attr_array(a, obj, name, H5T_NATIVE_DOUBLE, 0, 0, buf, n, count);
}

int autobal_archive_read_attr_int64s(autobal_archive *a, const char *obj, const char *name, int64_t *buf, size_t n,
                                     size_t *count) {
  return read_attr_array(a, obj, name, H5T_NATIVE_INT64, 1, 0, buf, n, count);
}

/* Copy a name into a buffer of AUTOBAL_ARCHIVE_NAME_MAX + 1 bytes (longer names cut). */
static void copy_name(char *out, const char *name) {
  size_t n = strlen(name);
  if (n > AUTOBAL_ARCHIVE_NAME_MAX) n = AUTOBAL_ARCHIVE_NAME_MAX;
  memcpy(out, name, n);
  out[n] = '\0';
}

/* H5DSiterate_scales callback: the last path component of the first scale attached. */
static herr_t first_scale_cb(hid_t did, unsigned dim, hid_t dsid, void *data) {
  char *out = (char *)data, p[AUTOBAL_ARCHIVE_PATH_MAX];
  const char *base;
  ssize_t len;
  (void)did;
  (void)dim;
  len = H5Iget_name(dsid, p, sizeof p);
  if (len <= 0 || (size_t)len >= sizeof p) return 0; /* anonymous: try the next one */
  base = strrchr(p, '/');
  base = base != NULL ? base + 1 : p;
  copy_name(out, base);
  return 1;
}

int autobal_archive_var_describe(autobal_archive *a, const char *p, autobal_archive_var_info *info) {
  char path[AUTOBAL_ARCHIVE_PATH_MAX];
  autobal_archive_quiet_ q;
  hid_t ds, ft = -1;
  int rc, d;
  if (a == NULL) return AUTOBAL_EINVAL;
  autobal_error_clear(&a->err);
  if (info == NULL) return autobal_error_set(&a->err, AUTOBAL_EINVAL, "var_describe: info is NULL");
  memset(info, 0, sizeof *info);
  autobal_archive_h5_enter_(&q);
  rc = open_dataset(a, p, path, sizeof path, &ds);
  if (rc == AUTOBAL_SUCCESS) rc = shape_of(a, ds, path, &info->rank, info->dims, &info->count);
  if (rc == AUTOBAL_SUCCESS) {
    ft = H5Dget_type(ds);
    if (ft < 0) rc = autobal_archive_h5fail_(&a->err, "cannot get the type of '%s'", path);
    else type_info(ft, &info->type_class, &info->size, &info->is_unsigned);
  }
  if (rc == AUTOBAL_SUCCESS) {
    htri_t sc = H5DSis_scale(ds);
    if (sc < 0) rc = autobal_archive_h5fail_(&a->err, "cannot tell whether '%s' is a dimension scale", path);
    info->is_coordinate = sc > 0;
  }
  for (d = 0; rc == AUTOBAL_SUCCESS && d < info->rank; d++) {
    if (info->is_coordinate && info->rank == 1) {
      const char *base = strrchr(path, '/');
      copy_name(info->dim_names[d], base != NULL ? base + 1 : path);
    } else {
      int ns = H5DSget_num_scales(ds, (unsigned)d);
      if (ns > 0 && H5DSiterate_scales(ds, (unsigned)d, NULL, first_scale_cb, info->dim_names[d]) < 0)
        rc = autobal_archive_h5fail_(&a->err, "cannot read the dimension scales of '%s'", path);
    }
  }
  if (ft >= 0) (void)H5Tclose(ft);
  if (ds >= 0) (void)H5Dclose(ds);
  autobal_archive_h5_leave_(&q);
  if (rc != AUTOBAL_SUCCESS) memset(info, 0, sizeof *info);
  return rc;
}

