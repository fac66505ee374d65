/* ss_cli_enumerate_random.c — placeholder until `enumerate random` lands. */
#include "ss_cli.h"

int ss_cli_enumerate_random(int argc, char **argv) {
  (void)argc;
  (void)argv;
  return ss_cli_usage_error("enumerate", "'enumerate random' is not implemented yet");
}
