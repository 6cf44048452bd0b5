/* units_parse_check: read unit strings, one per line, from stdin; print each that UDUNITS-2
 * (through apps/units.c, the parser autobal's configuration uses) cannot parse; exit 1 if any.
 * Used by tests/app/cf.sh on every units attribute of the archives. */
#include <stdio.h>
#include <string.h>

#include "units.h"

int main(void) {
  char err[256], line[1024];
  int bad = 0, n = 0;
  cli_units *u = cli_units_new(err, sizeof err);
  if (!u) {
    fprintf(stderr, "units_parse_check: %s\n", err);
    return 2;
  }
  while (fgets(line, sizeof line, stdin)) {
    line[strcspn(line, "\n")] = '\0';
    n++;
    if (!cli_units_parses(u, line)) {
      printf("does not parse: '%s'\n", line);
      bad = 1;
    }
  }
  printf("%d unit strings checked\n", n);
  cli_units_free(u);
  return bad;
}
