/* commands.h: the table of subcommands (apps/commands.c). */
#ifndef AUTOBAL_APPS_COMMANDS_H
#define AUTOBAL_APPS_COMMANDS_H

#include <stddef.h>

#include "cli.h"

typedef struct cli_command {
  const char *name;    /* "model action" */
  const char *summary; /* one line for `autobal --help` and `autobal MODEL --help` */
  const char *help;    /* the command's configuration keys, for `autobal CMD --help` (= `autobal help CMD`) */
  cli_command_fn run;
} cli_command;

extern const cli_command cli_commands[];
extern const size_t cli_ncommands;

#endif
