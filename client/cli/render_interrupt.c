/* render_interrupt.c — see render_interrupt.h. A signal handler can only leave
 * a flag: `received` is this file's one piece of process-wide state, as
 * signals need. */
#include "render_interrupt.h"

#include <signal.h>
#include <string.h>

static volatile sig_atomic_t received;

static void on_signal(int signal_number)
{
    received = signal_number;
}

void fc_render_interrupt_install(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    action.sa_flags = (int)SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, NULL);
    sigaction(SIGTERM, &action, NULL);
}

int fc_render_interrupted(void)
{
    return (int)received;
}
