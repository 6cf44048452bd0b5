/* main_renamed.c: apps/main.c as a function for fuzz_cli.c: main() becomes autobal_cli_main()
 * and the signal handlers are not installed (libFuzzer keeps its own). */
#define main autobal_cli_main
#define cli_signals_install fuzz_no_signals
#include "../../apps/main.c"
