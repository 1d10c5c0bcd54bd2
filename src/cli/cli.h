/* The pdk command's subcommands. */
#ifndef PDK_CLI_H
#define PDK_CLI_H

/* prog: how pdk was invoked (argv[0]), for commands the output suggests */
int pdk_cli_run(const char *prog, int argc, char **argv);
int pdk_cli_check(const char *prog, int argc, char **argv);
extern const char *pdk_cli_usage_run;
extern const char *pdk_cli_usage_check;

#endif
