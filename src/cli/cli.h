/* The pdk command's subcommands. */
#ifndef PDK_CLI_H
#define PDK_CLI_H

int pdk_cli_run(int argc, char **argv);
int pdk_cli_check(int argc, char **argv);
extern const char *pdk_cli_usage_run;
extern const char *pdk_cli_usage_check;

#endif
