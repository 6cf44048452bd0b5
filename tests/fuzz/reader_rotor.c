/* reader_rotor.c: exposes the static configuration reader of `autobal rotor transient`
 * (apps/cmd_rotor.c: read_rotor_config, i.e. [rotor] [supports] [lumped] [initial] [plane1]
 * [plane2] [transient]) to the fuzz targets, by including that file.  Not part of the apps. */
#include "../../apps/cmd_rotor.c"

#include "fuzz_readers.h"

int fuzz_read_rotor_transient(cli_ctx *ctx, autobal_rotor_params *p, void **storage) {
  rotor_cfg *c = calloc(1, sizeof *c);
  int rc;
  *storage = NULL;
  if (!c) return CLI_EXIT_INTERNAL;
  rc = read_rotor_config(ctx, c);
  if (rc) {
    free(c);
    return rc;
  }
  *p = c->p; /* ball arrays point into c */
  *storage = c;
  return CLI_EXIT_OK;
}
