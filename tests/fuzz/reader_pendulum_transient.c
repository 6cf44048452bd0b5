/* reader_pendulum_transient.c: exposes the static configuration reader of `autobal pendulum
 * transient` (apps/cmd_pendulum_transient.c: read_config, i.e. [pendulum] [initial] [transient])
 * to the fuzz targets, by including that file.  Not part of the apps. */
#include "../../apps/cmd_pendulum_transient.c"

#include "fuzz_readers.h"

int fuzz_read_pendulum_transient(cli_ctx *ctx, autobal_pendulum_params *p, double y0[8], double *t_end,
                                 double *dt_out) {
  ptr_cfg c;
  int rc;
  memset(&c, 0, sizeof c);
  rc = read_config(ctx, &c);
  if (rc) return rc;
  *p = c.p;
  memcpy(y0, c.y0, sizeof c.y0);
  *t_end = c.t_end;
  *dt_out = c.dt_out;
  return CLI_EXIT_OK;
}
