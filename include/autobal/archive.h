/* autobal/archive.h: the HDF5 archive (knows no physics).
 *
 * An archive is one HDF5 1.10 file laid out so that h5py and
 * `xarray.open_dataset(file, engine="h5netcdf", group=...)` show named
 * dimensions, coordinates and units:
 *
 *   /                      root attributes (see autobal_archive_provenance):
 *                          Conventions = "CF-1.8 autobal-1", status, title, history, source, versions, ...
 *   /<group>/...           groups created by autobal_archive_group()
 *   /<group>/<coord>       1-D coordinate = HDF5 dimension scale whose NAME is the
 *                          dimension name (= the dataset name); attributes units, long_name
 *   /<group>/<var>         N-D variable (rank 0..4) with its dimension scales attached
 *                          (DIMENSION_LIST); attributes units, long_name
 *   parameters             attributes NAME = value and NAME_units = "unit" on any group
 *                          or dataset ("1" marks a dimensionless quantity)
 *
 * Every dataset carries `units` and `long_name` (variable-length UTF-8 strings, read
 * as str by h5py and xarray).  Groups and datasets track the creation order of their
 * members and attributes (h5py lists attributes in the order written; see
 * autobal_archive_list_attrs) and keep up to 1024 attributes in the object header.  Datasets larger than 64 KiB are chunked and compressed
 * (shuffle + deflate level 4); smaller ones are contiguous.  Streamed time series use
 * an unlimited dimension and shuffle + deflate level 1 (see autobal_archive_series_open).
 * Only the standard HDF5 filters are used: every HDF5 reader (h5py, xarray, netCDF-4)
 * reads the files without plugins.
 *
 * Paths.  A `group` argument is a slash-separated group path; "/pendulum/map" and
 * "pendulum/map" are the same group, "/" (or "") is the root group.  An `obj`
 * argument names a group or a dataset the same way ("/pendulum/map/omega").
 * Names of groups, datasets and attributes are non-empty, contain no '/', no control
 * characters, are valid UTF-8 and at most AUTOBAL_ARCHIVE_NAME_MAX bytes long.
 * Attribute names reserved by HDF5 dimension scales and netCDF (CLASS, NAME,
 * DIMENSION_LIST, REFERENCE_LIST, names starting with "_Netcdf" or "_nc") are
 * rejected.  String values must be valid UTF-8.
 *
 * Atomic creation.  autobal_archive_create() writes to "<path>.partial-<pid>" in the
 * same directory; only autobal_archive_close() renames it to `path` (an existing file
 * of that name is replaced atomically when overwrite was allowed).  So a file under
 * the final name is always complete in the HDF5 sense; its root attribute `status`
 * says whether the computation was ("complete") or was not (e.g. "incomplete" with a
 * `status_reason` such as "interrupted by SIGINT").
 *
 * Errors.  Functions return an autobal status (0 success, < 0 failure).  A function
 * on a handle records the message in the handle (autobal_archive_errmsg); the
 * message names the path/object concerned and, for HDF5 failures, carries the HDF5
 * error-stack text (and the OS reason, e.g. "Permission denied").  HDF5's automatic
 * error printing is switched off during each call and restored on return, so the
 * library never prints and leaves the global HDF5 error handler as it found it.
 * After a failed write the archive stays usable and everything written before stays
 * readable; a failed call writes nothing partial that a reader would mistake for data
 * except as noted per function.
 *
 * Threads.  A handle (and its series) is used by one thread at a time; different
 * handles may be used from different threads at the same time.  Full buffers of
 * streamed series are written by a background thread of the archive (the "writer",
 * started at the first full series buffer and joined by _close/_discard), so that the
 * compression runs on another core while the caller computes; see
 * autobal_archive_series_open.  The writer blocks all signals.  HDF5 is not thread-safe
 * in every build (Debian 12's libhdf5 1.10.8 is built thread-safe, many others are not),
 * so every HDF5 call this module makes, in any thread and for any archive, holds one
 * process-wide lock (a statically initialised mutex inside archive.c; the only
 * process-wide object of the library; it holds no data).  So does the library's only
 * other HDF5 call, autobal_hdf5_version() (autobal/version.h; defined in archive.c).  A host program that calls
 * HDF5 itself while series are open should, with a non-thread-safe HDF5, do so only
 * after autobal_archive_series_flush() of every open series (the writer is then idle
 * until the next full buffer).  Do not fork() while series are open (a child would
 * inherit the lock possibly held).  Close archives before the process exits.
 *
 * Reading.  autobal_archive_open_read, then _has, _list (members), _list_attrs
 * (attributes with type class, rank and size), _read_attr_string, _read_attr_double,
 * _read_attr_doubles / _int64s (arrays), _var_shape, _var_describe (type, dimension
 * names), _read_var.  They work on files of other writers too (as long as the root
 * attribute Conventions includes "autobal-1"), also under the module's lock.
 *
 * Memory.  Handles are owned by the caller and freed by _close/_discard.  Input arrays
 * are only read during the call.  No allocation happens per appended row of a series
 * (its two row buffers are allocated at _series_open).
 */
#ifndef AUTOBAL_ARCHIVE_H
#define AUTOBAL_ARCHIVE_H

#include <stddef.h>
#include <stdint.h>

#include "autobal/export.h"
#include "autobal/status.h"

AUTOBAL_BEGIN_DECLS

/* Value of the root attribute `Conventions`: netCDF-CF 1.8 (where CF has a word for it: units
 * that UDUNITS-2 parses, long_name, coordinates as dimension scales, title, history, source,
 * references) and autobal's own layout, version 1. */
#define AUTOBAL_ARCHIVE_CONVENTIONS "CF-1.8 autobal-1"
/* The token of `Conventions` that identifies an autobal archive: readers accept any Conventions
 * whose blank- or comma-separated tokens include it (archives written before 0.2 have
 * Conventions = "autobal-1" alone). */
#define AUTOBAL_ARCHIVE_CONVENTION "autobal-1"
/* Highest rank of a variable. */
#define AUTOBAL_ARCHIVE_MAX_RANK 4
/* Longest name (group component, dataset, attribute), in bytes. */
#define AUTOBAL_ARCHIVE_NAME_MAX 255
/* Datasets with more bytes than this are chunked and compressed. */
#define AUTOBAL_ARCHIVE_COMPRESS_BYTES 65536
/* Rows of each of the two buffers of a series (= the series chunk length). */
#define AUTOBAL_ARCHIVE_SERIES_ROWS 4096

typedef struct autobal_archive autobal_archive;               /* opaque */
typedef struct autobal_archive_series autobal_archive_series; /* opaque streaming table */

/* ------------------------------------------------------------------------ */
/* Writing                                                                   */
/* ------------------------------------------------------------------------ */

/* Create an archive that will be named `path`.  Data goes to the temporary file
 * "<path>.partial-<pid>" in the same directory (if that name is taken, "-2", "-3", ...
 * is appended), renamed to `path` by autobal_archive_close().  The new file has the
 * root attributes Conventions = "CF-1.8 autobal-1" and status = "incomplete".
 * Returns
 *   AUTOBAL_SUCCESS  *out is the new handle;
 *   AUTOBAL_EINVAL   path NULL/empty, out NULL;
 *   AUTOBAL_EEXIST   `path` exists and overwrite == 0 (nothing is created);
 *   AUTOBAL_EIO      `path` is a directory, a dangling symbolic link, or exists and is not a
 *                    regular file (only regular files are ever replaced);
 *   AUTOBAL_EIO      the temporary file cannot be created (unwritable or missing
 *                    directory): the message names the path and gives the OS/HDF5 reason;
 *   AUTOBAL_ENOMEM.
 * On failure *out is NULL, nothing is left on disk, and err (may be NULL) holds the
 * message. */
AUTOBAL_API int autobal_archive_create(const char *path, int overwrite, autobal_archive **out,
                                       autobal_error *err);

/* Last error message of the handle, "" if none (never NULL; "" for a NULL handle).
 * Owned by the handle, valid until the next call on it. */
AUTOBAL_API const char *autobal_archive_errmsg(const autobal_archive *a);
/* Last status of the handle (AUTOBAL_SUCCESS if none). */
AUTOBAL_API int autobal_archive_status(const autobal_archive *a);

/* Write the provenance root attributes (all strings):
 *   title            `title` ("" if NULL)
 *   autobal_version  git_revision  gsl_version  hdf5_version   (of the running library)
 *   command_line     argv[0..argc-1] joined by spaces with POSIX-shell quoting, so that it
 *                    can be pasted into a shell ("" if argc == 0; bytes that are not
 *                    valid UTF-8 are replaced by '?')
 *   created          time of this call, ISO 8601 UTC, "YYYY-MM-DDThh:mm:ssZ"
 *   status           "incomplete" (until close)
 *   Conventions      "CF-1.8 autobal-1" (AUTOBAL_ARCHIVE_CONVENTIONS)
 *   history          "<created> <command_line>" (CF: how the data were made)
 *   source           "autobal <version> (<git revision>)" (CF: the software that made the data)
 *   references       where the models are documented (the repository's docs/ pages)
 * May be called again (attributes are replaced).  argc < 0, or argc > 0 with argv NULL
 * or an argv[i] NULL: AUTOBAL_EINVAL.  AUTOBAL_EIO on HDF5 failure. */
AUTOBAL_API int autobal_archive_provenance(autobal_archive *a, const char *title, int argc,
                                           const char *const *argv);

/* Set the status autobal_archive_close() will write (default "complete"), and an
 * optional reason (NULL: none) written as the root attribute `status_reason`.
 * E.g. ("incomplete", "interrupted by SIGINT").  Nothing is written before close;
 * until then the file says "incomplete".  status must be a non-empty UTF-8 string of at
 * most 63 bytes, reason at most 255 bytes: AUTOBAL_EINVAL otherwise. */
AUTOBAL_API int autobal_archive_set_status(autobal_archive *a, const char *status,
                                           const char *reason);

/* Create group `group` and any missing parents ("/pendulum/map").  Idempotent: an
 * existing group is fine.  AUTOBAL_EINVAL for a bad name or when a component exists
 * but is not a group; AUTOBAL_EIO on HDF5 failure. */
AUTOBAL_API int autobal_archive_group(autobal_archive *a, const char *group);

/* Attributes on an existing group or dataset `obj`.  An attribute of the same name is
 * replaced.  A parameter is written as attribute NAME = value plus attribute
 * NAME_units = units (a string; omitted when units is NULL; use "1" for dimensionless).
 *   _double       64-bit float scalar; value may be any double (NaN/inf are stored as is)
 *   _int          64-bit signed integer scalar
 *   _string       variable-length UTF-8 string scalar (value NULL: AUTOBAL_EINVAL)
 *   _double_array 1-D array of n >= 1 doubles (copied)
 * AUTOBAL_EINVAL: obj does not exist, bad/reserved name, n == 0, NULL pointers.
 * AUTOBAL_EIO: HDF5 failure. */
AUTOBAL_API int autobal_archive_attr_double(autobal_archive *a, const char *obj, const char *name,
                                            double value, const char *units);
AUTOBAL_API int autobal_archive_attr_int(autobal_archive *a, const char *obj, const char *name,
                                         long value);
AUTOBAL_API int autobal_archive_attr_string(autobal_archive *a, const char *obj, const char *name,
                                            const char *value);
AUTOBAL_API int autobal_archive_attr_double_array(autobal_archive *a, const char *obj,
                                                  const char *name, size_t n, const double *v,
                                                  const char *units);

/* A 1-D coordinate variable: dataset `name` in `group` (created if missing) with the n
 * values (float64), made a dimension scale whose dimension name is `name`, with
 * attributes units (required, non-NULL; "1" for dimensionless) and long_name (NULL:
 * `name`).  n >= 1.  The dimension then exists for variables in this group and its
 * subgroups (netCDF scoping).  AUTOBAL_EINVAL: bad name, NULL values/units, n == 0,
 * `name` already exists in the group.  AUTOBAL_EIO: HDF5 failure. */
AUTOBAL_API int autobal_archive_coord(autobal_archive *a, const char *group, const char *name,
                                      size_t n, const double *values, const char *units,
                                      const char *long_name);

/* A dimension without physical coordinate values (a root index, a channel): a
 * dimension scale `name` of int32 values 0..n-1 with units "1" and long_name (NULL:
 * `name`).  Same rules and errors as autobal_archive_coord. */
AUTOBAL_API int autobal_archive_dim(autobal_archive *a, const char *group, const char *name,
                                    size_t n, const char *long_name);

/* An N-D variable `name` in `group` (created if missing), rank 0..4, over the
 * dimensions dims[0..rank-1]: each is the name of a coordinate/dimension made by
 * _coord/_dim/_series_open in `group` or one of its parent groups (the nearest wins),
 * or an absolute path to one ("/pendulum/omega").  The shape is taken from those
 * dimensions (an unlimited series dimension contributes its current length); `data`
 * holds the product of the sizes in C (row-major) order.  rank 0 is a scalar (dims
 * may be NULL).  The dimension scales are attached, and units (required) and
 * long_name (NULL: `name`) written.  Above AUTOBAL_ARCHIVE_COMPRESS_BYTES the dataset
 * is chunked (about 256 KiB chunks) and compressed (shuffle + deflate 4).
 *   _var      float64 values
 *   _var_int  int32 values
 * AUTOBAL_EINVAL: bad name or rank, unknown dimension, `name` exists, NULL data or
 * units.  AUTOBAL_EIO: HDF5 failure (the half-made dataset is removed). */
AUTOBAL_API int autobal_archive_var(autobal_archive *a, const char *group, const char *name,
                                    int rank, const char *const *dims, const double *data,
                                    const char *units, const char *long_name);
AUTOBAL_API int autobal_archive_var_int(autobal_archive *a, const char *group, const char *name,
                                        int rank, const char *const *dims, const int *data,
                                        const char *units, const char *long_name);

/* ------------------------------------------------------------------------ */
/* Streaming time series                                                      */
/* ------------------------------------------------------------------------ */

/* Open a table in `group` (created if missing) with an unlimited dimension `dim` (a
 * float64 coordinate, e.g. "time" in "s", long_name dim_long_name, NULL: dim) and
 * nvars >= 1 float64 variables names[i] along it with units[i] (required) and
 * long_names[i] (long_names NULL or long_names[i] NULL: the name).  Rows are appended
 * with _series_append into one of two buffers of AUTOBAL_ARCHIVE_SERIES_ROWS rows
 * (allocated here with one column of scratch, the only allocation: (2 nvars + 3) x
 * AUTOBAL_ARCHIVE_SERIES_ROWS doubles; the writer thread, started once per archive, has
 * the default thread stack).  A full buffer is handed to the archive's writer thread,
 * which extends the datasets and writes it (HDF5 compresses it there), while appends go
 * on into the other buffer; an append waits only if the writer has not finished the
 * previous buffer of this series.  The rest is written by _series_flush, _series_close,
 * autobal_archive_close and before autobal_archive_var/_var_int (so that a variable
 * over the series dimension sees every row appended).  Memory does not grow with the
 * run length.  Chunks are AUTOBAL_ARCHIVE_SERIES_ROWS rows, shuffle + deflate level 1
 * (a third less CPU than level 4 for files ~5% larger on smooth transients); after a
 * _series_flush the next buffer is handed over early so that writes stay aligned with
 * the chunks.  If the writer thread cannot be started, buffers are written in the
 * caller's thread (the same results).  Errors are recorded in the archive
 * (autobal_archive_errmsg).
 * AUTOBAL_EINVAL: bad or duplicate names, existing `dim` or variable, NULL arrays,
 * nvars == 0.  AUTOBAL_EIO: HDF5 failure (whatever this call made is removed again).
 * The series belongs to the archive: it must be closed before the archive, or is
 * closed (flushed and freed) by autobal_archive_close/_discard, after which the
 * series pointer is invalid. */
AUTOBAL_API int autobal_archive_series_open(autobal_archive *a, const char *group, const char *dim,
                                            const char *dim_units, const char *dim_long_name,
                                            size_t nvars, const char *const *names,
                                            const char *const *units,
                                            const char *const *long_names,
                                            autobal_archive_series **out);
/* Append nrows rows: t[0..nrows-1] are the values of the dimension coordinate, rows is
 * nrows x nvars in row-major order (rows[i*nvars + j] = variable j at t[i]).  nrows may
 * be 0.  Values are copied (bit for bit: NaN payloads, -0 and subnormals are kept).
 * AUTOBAL_EINVAL for NULL arrays (nrows > 0).  AUTOBAL_EIO when writing a buffer
 * failed: the message is the HDF5 failure ("series '<group>/<dim>': cannot write ...
 * HDF5: ... File too large").  As buffers are written in the background, the failure of
 * a buffer comes back from a later call on the series: the first _append after the
 * writer failed (at the latest the one that fills the next buffer), or _series_flush,
 * _series_close or autobal_archive_close.  Then the rows appended since the last
 * written buffer are dropped, the series keeps the rows written before (its length
 * becomes that number) and refuses further appends, flushes and closes (AUTOBAL_EIO,
 * "unusable after an earlier write failure"); autobal_archive_close then returns
 * AUTOBAL_EIO. */
AUTOBAL_API int autobal_archive_series_append(autobal_archive_series *s, size_t nrows,
                                              const double *t, const double *rows);
/* Wait for the writer, write the buffered rows to the file now and flush HDF5 buffers
 * to disk.  Reports a failure of the writer (AUTOBAL_EIO, see _series_append). */
AUTOBAL_API int autobal_archive_series_flush(autobal_archive_series *s);
/* Rows appended so far (written + being written + buffered); after a write failure the
 * rows in the file; 0 for NULL. */
AUTOBAL_API size_t autobal_archive_series_length(const autobal_archive_series *s);
/* Wait for the writer, flush, close the datasets and free the series (NULL:
 * AUTOBAL_SUCCESS).  The series is freed even when the flush fails or the writer had
 * failed (AUTOBAL_EIO returned, message in the archive). */
AUTOBAL_API int autobal_archive_series_close(autobal_archive_series *s);

/* ------------------------------------------------------------------------ */
/* Finishing                                                                  */
/* ------------------------------------------------------------------------ */

/* Wait for the series writer and stop it, close the open series (flushing them; a
 * failure of the writer is reported here if no call reported it before), write the
 * final root attribute status (see
 * _set_status, default "complete") and status_reason, close the file and rename the
 * temporary file to the final path.  Frees `a` in all cases (NULL: AUTOBAL_SUCCESS).
 * On failure the temporary file is left in place for inspection, and err (may be
 * NULL) names it and says why (AUTOBAL_EIO).  For a handle from
 * autobal_archive_open_read this just closes the file.
 *
 * Known HDF5 1.10 defect (h5py issue #914; fixed upstream in HDF5 1.14.1 by
 * HDFGroup/hdf5 PR #2291): when HDF5 cannot write the file any more (disk full, file
 * size limit), the failed close leaves a broken file object inside HDF5 that makes the
 * process crash in HDF5's atexit handler.  The library cannot repair that.  A host
 * program that gets AUTOBAL_EIO from autobal_archive_close (or any write failure whose
 * message mentions errno 27/28) should report it, fflush its streams and leave with
 * _exit(status) rather than exit(). */
AUTOBAL_API int autobal_archive_close(autobal_archive *a, autobal_error *err);

/* Abandon: wait for the series writer and stop it, close the series and the file and
 * delete the temporary file; nothing is left under either name (an existing file at the
 * final path is untouched).  Frees `a` (NULL ok).  For a read handle: just closes. */
AUTOBAL_API void autobal_archive_discard(autobal_archive *a);

/* ------------------------------------------------------------------------ */
/* Reading                                                                    */
/* ------------------------------------------------------------------------ */

/* Open an existing archive read-only.  AUTOBAL_EIO if the file does not exist or
 * cannot be read; AUTOBAL_EFORMAT if it is not an HDF5 file (also a truncated or
 * damaged one) or its root attribute Conventions is missing or does not include "autobal-1".  The
 * message names the path.  On failure *out is NULL.  Close with autobal_archive_close
 * (or _discard, which for a read handle only closes).  Write functions on a read handle
 * return AUTOBAL_EINVAL. */
AUTOBAL_API int autobal_archive_open_read(const char *path, autobal_archive **out,
                                          autobal_error *err);

/* 1 if `obj` (group or dataset path) exists and, when attr is not NULL, has attribute
 * `attr`; 0 otherwise (also for bad arguments).  Works on read and write handles. */
AUTOBAL_API int autobal_archive_has(autobal_archive *a, const char *obj, const char *attr);

/* Read string attribute `name` of `obj` into buf (size bytes, NUL-terminated).  If
 * len is not NULL it receives the full length of the value in bytes (without NUL), so
 * a first call with a small buf tells the size to allocate.  Fixed-length and
 * variable-length strings are read (a fixed-length value keeps its padding except
 * NULs).  Returns AUTOBAL_SUCCESS; AUTOBAL_WARNING if the value was truncated to fit;
 * AUTOBAL_EINVAL if obj does not exist, name is NULL, buf is NULL or size == 0;
 * AUTOBAL_EFORMAT if the attribute does not exist or is not a scalar string (the
 * message names object and attribute); AUTOBAL_EIO on an HDF5 read failure. */
AUTOBAL_API int autobal_archive_read_attr_string(autobal_archive *a, const char *obj,
                                                 const char *name, char *buf, size_t size,
                                                 size_t *len);
/* Read a numeric scalar (or 1-element) attribute as double (integers are converted).
 * AUTOBAL_EINVAL: no object `obj`, NULL name/value; AUTOBAL_EFORMAT: no such attribute,
 * not numeric or not exactly one element; AUTOBAL_EIO: HDF5 read failure. */
AUTOBAL_API int autobal_archive_read_attr_double(autobal_archive *a, const char *obj,
                                                 const char *name, double *value);

/* Shape of dataset `path`: *rank (0..AUTOBAL_ARCHIVE_MAX_RANK) and dims[0..rank-1]
 * (dims must hold AUTOBAL_ARCHIVE_MAX_RANK entries); *count (may be NULL) receives the
 * number of elements.  AUTOBAL_EINVAL: no such dataset; AUTOBAL_EUNSUPPORTED: rank > 4. */
AUTOBAL_API int autobal_archive_var_shape(autobal_archive *a, const char *path, int *rank,
                                          size_t *dims, size_t *count);
/* Read all elements of the numeric dataset `path` into buf (n >= number of elements),
 * as double, C order.  AUTOBAL_EINVAL: no such dataset or n too small (the message
 * gives the size needed); AUTOBAL_EFORMAT: not numeric.  AUTOBAL_EIO: read failure. */
AUTOBAL_API int autobal_archive_read_var(autobal_archive *a, const char *path, double *buf,
                                         size_t n);

/* Call fn(name, is_group, ctx) for each direct member of `group` (groups and
 * datasets), in creation order where the file tracks it (files written by this library
 * do), else by name.  A non-zero return from fn stops the iteration and is returned.
 * The names are collected first and fn is called after HDF5's iteration, so fn may
 * call functions of this module.  AUTOBAL_EINVAL: no such group; AUTOBAL_ENOMEM. */
typedef int (*autobal_archive_list_fn)(const char *name, int is_group, void *ctx);
AUTOBAL_API int autobal_archive_list(autobal_archive *a, const char *group,
                                     autobal_archive_list_fn fn, void *ctx);

/* A number identifying the group or dataset `obj` within the open archive (its address in
 * the file): two paths give the same number exactly when they name the same object (hard
 * links), so a reader that walks the groups can visit each object once, even in a file
 * whose links form a cycle.  AUTOBAL_EINVAL: no such object, NULL arguments. */
AUTOBAL_API int autobal_archive_object_id(autobal_archive *a, const char *obj, uint64_t *id);

/* Type classes of attributes and datasets as the reading functions see them. */
typedef enum autobal_archive_class {
  AUTOBAL_ARCHIVE_CLASS_FLOAT = 1,   /* IEEE floating point (read as double) */
  AUTOBAL_ARCHIVE_CLASS_INTEGER = 2, /* signed or unsigned integer (read as int64 or double) */
  AUTOBAL_ARCHIVE_CLASS_STRING = 3,  /* fixed- or variable-length string */
  AUTOBAL_ARCHIVE_CLASS_OTHER = 4    /* compound, enum, reference, ...: not read by this API */
} autobal_archive_class;

/* Iteration orders of autobal_archive_list_attrs. */
#define AUTOBAL_ARCHIVE_ORDER_NAME 0     /* byte-wise by name */
#define AUTOBAL_ARCHIVE_ORDER_CREATION 1 /* order of creation (where the object tracks it) */

/* What autobal_archive_list_attrs tells about one attribute, enough to choose a reader:
 * FLOAT/INTEGER -> autobal_archive_read_attr_doubles (or _int64s for INTEGER; a
 * 1-element one also autobal_archive_read_attr_double), STRING with count 1 ->
 * autobal_archive_read_attr_string. */
typedef struct autobal_archive_attr_info {
  const char *name; /* the attribute's name; valid during the callback only */
  int type_class;   /* an autobal_archive_class */
  int rank;         /* 0 for a scalar (and for an empty attribute), else 1..32 */
  size_t count;     /* number of elements: 1 for a scalar, 0 for an empty (null) attribute */
  size_t size;      /* bytes per element in the file; 0 for a variable-length string */
  int is_unsigned;  /* 1 for an unsigned integer type, else 0 */
} autobal_archive_attr_info;

typedef int (*autobal_archive_attr_fn)(const autobal_archive_attr_info *info, void *ctx);

/* Call fn(info, ctx) for each attribute of the group or dataset `obj` ("/" the root),
 * in `order`: AUTOBAL_ARCHIVE_ORDER_NAME, or AUTOBAL_ARCHIVE_ORDER_CREATION, which
 * falls back to name order for objects that do not track the creation order of their
 * attributes (files written by this library track it; files of other writers may
 * not).  The attributes that belong to the file format and are rejected by the
 * writers (CLASS, NAME, DIMENSION_LIST, REFERENCE_LIST, _Netcdf..., _nc...,
 * _NCProperties) are not listed.  As for autobal_archive_list, the attributes are
 * inspected first and fn is called afterwards, outside HDF5's iteration and outside the
 * module's lock, so fn may call the reading functions of this module on the same handle
 * (which then overwrite the handle's message).  A non-zero return from fn stops the
 * iteration and is returned.  Works on read and write handles.
 * AUTOBAL_EINVAL: no object `obj`, bad path, fn NULL, order not one of the two;
 * AUTOBAL_ENOMEM; AUTOBAL_EIO: HDF5 failure (nothing was passed to fn then). */
AUTOBAL_API int autobal_archive_list_attrs(autobal_archive *a, const char *obj, int order,
                                           autobal_archive_attr_fn fn, void *ctx);

/* Read all elements of the numeric attribute `name` of `obj` (any rank, C order):
 *   _doubles  as double (integers are converted; beyond 2^53 they are rounded);
 *   _int64s   as int64_t, for integer attributes only (unsigned values above INT64_MAX
 *             are clipped to INT64_MAX by HDF5's conversion).
 * buf holds n elements.  *count (may be NULL) receives the number of elements of the
 * attribute, also when the call fails because n is too small; buf may be NULL when n
 * is 0 (a size query: AUTOBAL_SUCCESS with *count set and nothing read, for a
 * numeric attribute).  Returns AUTOBAL_SUCCESS; AUTOBAL_EINVAL: no object `obj`, NULL
 * name, buf NULL with n > 0, or n smaller than the number of elements (nothing is
 * read; the message gives the size needed); AUTOBAL_EFORMAT: no attribute `name`, or
 * it is not numeric (_int64s: not an integer), the message naming object, attribute
 * and its type; AUTOBAL_EIO: HDF5 read failure. */
AUTOBAL_API int autobal_archive_read_attr_doubles(autobal_archive *a, const char *obj,
                                                  const char *name, double *buf, size_t n,
                                                  size_t *count);
AUTOBAL_API int autobal_archive_read_attr_int64s(autobal_archive *a, const char *obj,
                                                 const char *name, int64_t *buf, size_t n,
                                                 size_t *count);

/* Description of a dataset (autobal_archive_var_describe). */
typedef struct autobal_archive_var_info {
  int rank;                                /* 0..AUTOBAL_ARCHIVE_MAX_RANK */
  size_t dims[AUTOBAL_ARCHIVE_MAX_RANK];   /* current extents (a series: its length) */
  size_t count;                            /* number of elements */
  int type_class;                          /* an autobal_archive_class */
  size_t size;                             /* bytes per element; 0: variable-length string */
  int is_unsigned;                         /* unsigned integer type */
  int is_coordinate;                       /* the dataset is a dimension scale (a coordinate
                                            * or index dimension made by _coord, _dim or
                                            * _series_open) */
  /* Name of each dimension: the name of the first dimension scale attached to it (its
   * last path component); a coordinate of rank 1 is its own dimension; "" where none
   * is attached. */
  char dim_names[AUTOBAL_ARCHIVE_MAX_RANK][AUTOBAL_ARCHIVE_NAME_MAX + 1];
} autobal_archive_var_info;

/* Describe dataset `path`: shape, element type and dimension names, into *info.
 * AUTOBAL_EINVAL: no such dataset, info NULL; AUTOBAL_EUNSUPPORTED: rank > 4;
 * AUTOBAL_EIO: HDF5 failure.  On failure *info is zeroed. */
AUTOBAL_API int autobal_archive_var_describe(autobal_archive *a, const char *path,
                                             autobal_archive_var_info *info);

AUTOBAL_END_DECLS

#endif
