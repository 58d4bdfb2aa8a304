/* SIGINT and SIGTERM for long runs: the first signal raises a flag the run
 * framework reads at its next safe point (the end of an iteration), where
 * the run saves a checkpoint, marks its manifest interrupted and exits with
 * 128 + the signal number; SA_RESETHAND makes a second signal end the
 * process at once (files stay whole: every write is atomic). */
#include <signal.h>
#include <string.h>
#include "cli.h"

static volatile sig_atomic_t stop_flag;

static void on_signal(int signo) { stop_flag = signo; }

volatile sig_atomic_t *cli_stop_flag_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  return &stop_flag;
}

int cli_signal_exit_code(int signo) { return 128 + signo; }
