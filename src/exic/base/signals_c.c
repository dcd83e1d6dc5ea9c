/* The C side of exic_base_signals (src/exic/base/signals.f90): sigaction(2) handlers for
 * SIGINT, SIGTERM, SIGUSR1 and SIGUSR2 that only record which signal came (one
 * volatile sig_atomic_t per signal: the only thing an asynchronous handler may safely do),
 * and the call that reads and clears those records. The run polls them once per step. */
#include <signal.h>
#include <string.h>

static volatile sig_atomic_t exic_pending[4];

static int slot_of(int sig)
{
    switch (sig) {
    case SIGINT: return 0;
    case SIGTERM: return 1;
    case SIGUSR1: return 2;
    case SIGUSR2: return 3;
    default: return -1;
    }
}

static void exic_on_signal(int sig)
{
    int k = slot_of(sig);
    if (k >= 0) exic_pending[k] = 1;
}

/* Install the handler for the four signals (SA_RESTART: interrupted reads and writes resume).
 * Signals already recorded stay recorded (installing twice loses none). Returns 0 on success,
 * -1 when sigaction fails. */
int exic_c_signals_install(void)
{
    static const int sigs[4] = {SIGINT, SIGTERM, SIGUSR1, SIGUSR2};
    struct sigaction sa;
    int k;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = exic_on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    for (k = 0; k < 4; k++)
        if (sigaction(sigs[k], &sa, NULL) != 0) return -1;
    return 0;
}

/* Bits of the signals received since the last call (1 SIGINT, 2 SIGTERM, 4 SIGUSR1,
 * 8 SIGUSR2), cleared. */
int exic_c_signals_take(void)
{
    int bits = 0, k;
    for (k = 0; k < 4; k++) {
        if (exic_pending[k]) {
            exic_pending[k] = 0;
            bits |= 1 << k;
        }
    }
    return bits;
}

/* Ignore SIGXFSZ: a write beyond RLIMIT_FSIZE then fails with EFBIG instead of killing. */
int exic_c_ignore_sigxfsz(void)
{
    return signal(SIGXFSZ, SIG_IGN) == SIG_ERR ? -1 : 0;
}

/* The same bits as exic_c_signals_take, without clearing them. */
int exic_c_signals_peek(void)
{
    int bits = 0, k;
    for (k = 0; k < 4; k++)
        if (exic_pending[k]) bits |= 1 << k;
    return bits;
}
