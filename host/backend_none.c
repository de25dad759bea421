/* backend_none.c - the emulator entry points for a build without the
 * emulator (a board's bissctl, scripts/cross-bissctl.sh): the target
 * "emu" is refused. */
#include "biss_priv.h"

int biss_emu_backend_open(const struct biss_open_params *p, struct biss_backend *be) {
    (void)p;
    (void)be;
    return BISS_E_TARGET;
}

int biss_config_from_emu(biss_t *h, struct biss_config *c) {
    (void)h;
    (void)c;
    return BISS_E_NOT_EMU;
}
