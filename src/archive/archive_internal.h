/* archive_internal.h: what the writing side (archive.c) and the reading side
 * (archive_read.c) of the HDF5 archive share (not installed): the layout of the handles, the
 * process-wide HDF5 lock, HDF5 error handling, object names and paths.  Layer: archive
 * (docs/architecture.md): HDF5 and core only, no physics.  Includes no other private header
 * but internal.h. */
#ifndef AUTOBAL_ARCHIVE_INTERNAL_H
#define AUTOBAL_ARCHIVE_INTERNAL_H

#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>

#include <hdf5.h>

#include "autobal/archive.h"
#include "internal.h"

#define AUTOBAL_ARCHIVE_PATH_MAX 2048 /* longest object path inside the file */

/* The one lock for all HDF5 calls of the process made by this module (defined in archive.c,
 * see there). */
extern pthread_mutex_t autobal_archive_h5_lock_;

struct autobal_archive_series {
  autobal_archive *a;
  autobal_archive_series *next; /* list of open series of the archive (caller's thread) */
  size_t nvars;
  size_t cap; /* rows each of the two buffers holds (= the chunk length) */
  /* Caller's side. */
  double *fill;     /* buffer being filled: cap rows of (t, v_0 .. v_nvars-1), row-major
                     * (one contiguous store stream for the caller; the writer gathers
                     * the columns) */
  size_t nbuf;      /* rows in fill */
  size_t limit;     /* fill is handed to the writer at this many rows (<= cap), so that
                     * every write after a partial flush ends on a chunk boundary */
  size_t nappended; /* rows appended: in the file + in flight + in fill */
  int broken;       /* a write failed: refuse further appends */
  /* The buffer handed to the writer and what it updates; owned by the writer while
   * `pending`, by the caller otherwise. */
  double *wbuf;          /* buffer in flight (when not pending: the free one) */
  size_t wrows;          /* rows in wbuf */
  size_t nwritten;       /* rows in the file */
  autobal_error werr;    /* the writer's failure */
  atomic_int wfailed;    /* set (release) by the writer after filling werr */
  /* Guarded by a->m. */
  int pending;                   /* wbuf is queued or being written */
  autobal_archive_series *qnext; /* writer queue link */
  hid_t *dsets;    /* nvars + 1: [0] the dimension coordinate, [1+j] variable j */
  double *mem;     /* the two buffers */
  double *col;     /* one column (cap doubles), gathered by whoever writes */
  char where[AUTOBAL_ARCHIVE_PATH_MAX + 64]; /* "group/dim" for messages */
};

struct autobal_archive {
  hid_t file;
  int writable;
  int overwrite;
  char *path;     /* final name */
  char *tmp_path; /* temporary name (write mode) */
  char final_status[64];
  char reason[256];
  int has_reason;
  autobal_archive_series *series;
  autobal_error err;
  /* Series writer (write handles). */
  int sync_ok;          /* m, work, done initialised */
  int writer;           /* 0 not started, 1 running, -1 could not start (writes in the caller) */
  pthread_t thread;
  pthread_mutex_t m;    /* guards stop, the queue and each series' pending/qnext */
  pthread_cond_t work;  /* to the writer: a buffer was queued, or stop */
  pthread_cond_t done;  /* to callers: a buffer was written */
  int stop;
  autobal_archive_series *qhead, *qtail;
};

/* HDF5's automatic error handler of the calling thread, saved while silenced. */
typedef struct {
  H5E_auto2_t func;
  void *data;
  int saved;
} autobal_archive_quiet_;

/* Take the HDF5 lock and silence HDF5's error printing; _h5_leave_ undoes both. */
void autobal_archive_h5_enter_(autobal_archive_quiet_ *q);
void autobal_archive_h5_leave_(const autobal_archive_quiet_ *q);
/* Record AUTOBAL_EIO with the formatted message and the text of HDF5's error stack. */
int autobal_archive_h5fail_(autobal_error *err, const char *fmt, ...) AUTOBAL_PRINTF(2, 3);
/* Attribute names that belong to HDF5 dimension scales and netCDF: never written, not listed
 * by autobal_archive_list_attrs. */
int autobal_archive_reserved_attr_name_(const char *name);
/* Normalise a slash-separated path: "a//b/" -> "/a/b", "" or "/" -> "/". */
int autobal_archive_norm_path_(autobal_error *err, const char *what, const char *in, char *out,
                               size_t size);
/* 1 if every component of the normalised path exists (links), 0 otherwise. */
int autobal_archive_path_exists_(hid_t file, const char *path);
/* Type of the object at a normalised path: H5I_GROUP, H5I_DATASET, other, or H5I_BADID if it
 * does not exist. */
H5I_type_t autobal_archive_path_type_(hid_t file, const char *path);
/* malloc'ed copy of s (NULL when out of memory). */
char *autobal_archive_dup_str_(const char *s);
/* Free the handle: its synchronisation objects, paths and itself (the file is closed by the
 * caller). */
void autobal_archive_free_handle_(autobal_archive *a);
/* Whether the blank- or comma-separated tokens of a Conventions attribute include `token`. */
int autobal_archive_conventions_include_(const char *conv, const char *token);

#endif
