/* commands.c: the table of subcommands.  To add one: write apps/cmd_<name>.c with a
 * `int cli_cmd_<name>(cli_ctx *)` declared in cli.h and a help text, and add a row here. */
#include "commands.h"
#include "help.h"

const cli_command cli_commands[] = {
    {"pendulum roots", "characteristic roots (6) and eigenvalues of (5), stability verdict", HELP_PENDULUM_ROOTS,
     cli_cmd_pendulum_roots},
    {"pendulum critical", "critical speeds of the undamped balancer (10)-(18), curves vs R_m",
     HELP_PENDULUM_CRITICAL, cli_cmd_pendulum_critical},
    {"pendulum map", "stability map over (R_m, R_w) for one k or every unbalance", HELP_PENDULUM_MAP,
     cli_cmd_pendulum_map},
    {"pendulum transient", "transient of the two-pendulum autobalancer (1): time series, time to balance",
     HELP_PENDULUM_TRANSIENT, cli_cmd_pendulum_transient},
    {"rotor transient", "transient of the rotor with ball autobalancers (3.2)/(3.4), 1 or 2 planes",
     HELP_ROTOR_TRANSIENT, cli_cmd_rotor_transient},
};
const size_t cli_ncommands = sizeof cli_commands / sizeof cli_commands[0];
