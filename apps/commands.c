/* commands.c: the table of subcommands.  To add one: write apps/cmd_<name>.c with a
 * `int cli_cmd_<name>(cli_ctx *)` declared in cli.h and a help text, and add a row here.  The
 * summaries are one line each (`autobal --help`, `autobal MODEL --help`); equation numbers belong
 * in the help texts (apps/help.h), which name the document they refer to. */
#include "commands.h"
#include "help.h"


const cli_command cli_commands[] = {
    {"pendulum roots", "characteristic roots and eigenvalues of the linearization, stability verdict", HELP_PENDULUM_ROOTS,
     cli_cmd_pendulum_roots},
    {"pendulum critical", "critical speeds of the undamped balancer (closed forms, series), curves vs R_m",
     HELP_PENDULUM_CRITICAL, cli_cmd_pendulum_critical},
    {"pendulum map", "stability map over any two parameters (default (R_m, R_w)), one k or every unbalance",
     HELP_PENDULUM_MAP, cli_cmd_pendulum_map},
    {"pendulum sweep", "stability along any parameter (R_w, R_m, H, h, k, psi0, H/h, or a physical key); critical values",
     HELP_PENDULUM_SWEEP, cli_cmd_pendulum_sweep},
    {"pendulum transient", "transient of the two-pendulum autobalancer: time series, time to balance",
     HELP_PENDULUM_TRANSIENT, cli_cmd_pendulum_transient},
    {"rotor transient", "transient of the rotor with ball autobalancers, 1 or 2 planes",
     HELP_ROTOR_TRANSIENT, cli_cmd_rotor_transient},
    {"rotor stability", "balanced motion: stability (Delta, closed matrix, full model, Floquet), critical speeds",
     HELP_ROTOR_STABILITY, cli_cmd_rotor_stability},
    {"rotor sweep", "stability margin along omega or any numeric config key; critical values",
     HELP_ROTOR_SWEEP, cli_cmd_rotor_sweep},
    {"rotor map", "stability map over any two parameters (e.g. omega x ball damping), OpenMP-parallel", HELP_ROTOR_MAP,
     cli_cmd_rotor_map},
    {"rotor campbell", "natural frequencies, Campbell diagram, unbalance response, resonance speeds",
     HELP_ROTOR_CAMPBELL, cli_cmd_rotor_campbell},
    {"rotor ensemble", "many transients over initial ball angles or parameters: basin map, P(balance); OpenMP/MPI",
     HELP_ROTOR_ENSEMBLE, cli_cmd_rotor_ensemble},
    {"rotor design", "size a balancer: stable for every unbalance over a speed range with a margin; ranked designs",
     HELP_ROTOR_DESIGN, cli_cmd_rotor_design},
    {"pendulum ensemble", "many pendulum transients over initial angles or parameters: basin map, P(balance)",
     HELP_PENDULUM_ENSEMBLE, cli_cmd_pendulum_ensemble},
    {"info", "FILE.h5: what an archive holds: command, parameters, results, datasets", HELP_INFO, cli_cmd_info},
    {"rerun", "FILE.h5 -o NEW.h5: repeat the recorded run (same data, bit for bit)", HELP_RERUN, cli_cmd_rerun},
    {"plot", "FILE.h5 [-o DIR]: matplotlib pictures of an archive (tools/autobal_plot.py)", HELP_PLOT,
     cli_cmd_plot},
};
const size_t cli_ncommands = sizeof cli_commands / sizeof cli_commands[0];
