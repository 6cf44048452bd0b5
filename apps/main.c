/* main.c: placeholder entry point replaced by the CLI. */
#include <stdio.h>
#include "autobal.h"
int main(void) { printf("autobal %s\n", autobal_version()); return 0; }
