/* replay_main.c: a main() for the fuzz targets without libFuzzer: runs every file named on the
 * command line (or every file in the directories named) through LLVMFuzzerTestOneInput once.
 * Used by CTest (fuzz_config_replay) to replay the checked-in corpus in the normal and the
 * sanitizer builds; prints one line per input and exits 0 when all inputs ran (a finding
 * aborts). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int run_file(const char *path) {
  FILE *f = fopen(path, "rb");
  unsigned char *buf;
  long n;
  if (!f) {
    printf("FAIL cannot open %s\n", path);
    return 1;
  }
  if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    printf("FAIL cannot size %s\n", path);
    return 1;
  }
  buf = malloc((size_t)n + 1);
  if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) {
    free(buf);
    fclose(f);
    printf("FAIL cannot read %s\n", path);
    return 1;
  }
  fclose(f);
  LLVMFuzzerTestOneInput(buf, (size_t)n);
  free(buf);
  return 0;
}

static int cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

int main(int argc, char **argv) {
  int i, failed = 0, ran = 0;
  LLVMFuzzerInitialize(&argc, &argv);
  for (i = 1; i < argc; i++) {
    struct stat sb;
    if (stat(argv[i], &sb) == 0 && S_ISDIR(sb.st_mode)) {
      DIR *d = opendir(argv[i]);
      struct dirent *e;
      char **names = NULL;
      size_t n = 0, cap = 0, k;
      if (!d) {
        printf("FAIL cannot open directory %s\n", argv[i]);
        failed++;
        continue;
      }
      while ((e = readdir(d)) != NULL) {
        char *path;
        if (e->d_name[0] == '.') continue;
        if (n == cap) {
          char **q = realloc(names, (cap = cap ? 2 * cap : 64) * sizeof *q);
          if (!q) break;
          names = q;
        }
        path = malloc(strlen(argv[i]) + strlen(e->d_name) + 2);
        if (!path) break;
        sprintf(path, "%s/%s", argv[i], e->d_name);
        names[n++] = path;
      }
      closedir(d);
      qsort(names, n, sizeof *names, cmp); /* deterministic order */
      for (k = 0; k < n; k++) {
        failed += run_file(names[k]);
        ran++;
        free(names[k]);
      }
      free(names);
    } else {
      failed += run_file(argv[i]);
      ran++;
    }
  }
  printf("%d inputs replayed, %d could not be read\n", ran, failed);
  return failed != 0 || ran == 0;
}
