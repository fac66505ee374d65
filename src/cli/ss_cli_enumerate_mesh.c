/* ss_cli_enumerate_mesh.c — placeholder until `enumerate mesh` lands. */
#include "ss_cli.h"

int ss_cli_enumerate_mesh(int argc, char **argv) {
  (void)argc;
  (void)argv;
  return ss_cli_usage_error("enumerate", "'enumerate mesh' is not implemented yet");
}
