/* fuzz_readers.h: the commands' configuration readers, made callable for the fuzz targets. */
#ifndef AUTOBAL_FUZZ_READERS_H
#define AUTOBAL_FUZZ_READERS_H

#include "autobal.h"
#include "cli.h"

/* read_rotor_config() of apps/cmd_rotor.c; on success free(*storage) after the last use of *p. */
int fuzz_read_rotor_transient(cli_ctx *ctx, autobal_rotor_params *p, void **storage);
/* read_config() of apps/cmd_pendulum_transient.c. */
int fuzz_read_pendulum_transient(cli_ctx *ctx, autobal_pendulum_params *p, double y0[8], double *t_end,
                                 double *dt_out);

#endif
