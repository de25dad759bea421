/* bissctl_target.c - the target bissctl uses when --target is not given:
 * the board it runs on, from the device tree's root "compatible" (a list
 * of NUL-terminated strings, most specific first; the kernel shows the
 * tree at /sys/firmware/devicetree/base, /proc/device-tree links there).
 * AM335x boards' trees end in "ti,am33xx" (am33xx.dtsi); AM437x boards'
 * in "ti,am4372", "ti,am43" (am4372.dtsi, e.g. the IDK's
 * "ti,am437x-idk-evm","ti,am4372","ti,am43"). On an AM437x the default is
 * ICSS0, the instance TIDEP0022 and the IDK overlay use (ICSS1 is the
 * IDK's PRU Ethernet). Anything else, or no device tree (a PC), is the
 * emulator. */
#include "bissctl.h"

#include <stdio.h>
#include <string.h>

static bool has(const char *list, size_t n, const char *want) {
    for (size_t i = 0; i < n; i += strlen(list + i) + 1) {
        if (strcmp(list + i, want) == 0) {
            return true;
        }
    }
    return false;
}

enum biss_target bissctl_default_target(const char *sysfs_root) {
    char path[4096], list[1024];
    snprintf(path, sizeof path, "%s/firmware/devicetree/base/compatible",
             sysfs_root && *sysfs_root ? sysfs_root : "/sys");
    FILE *f = fopen(path, "rb");
    if (!f) {
        return BISS_TARGET_EMU;
    }
    size_t n = fread(list, 1, sizeof list - 1, f);
    fclose(f);
    list[n] = '\0'; /* a last string cut short still ends */
    if (has(list, n, "ti,am33xx")) {
        return BISS_TARGET_AM335X;
    }
    if (has(list, n, "ti,am4372") || has(list, n, "ti,am43")) {
        return BISS_TARGET_AM437X_ICSS0;
    }
    return BISS_TARGET_EMU;
}
