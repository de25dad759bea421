/*
 * biss_soc.h - the PRU-ICSS and SoC memory map the host side of the
 * firmware uses: where each supported PRU-ICSS sits, its sizes, and the
 * offsets of PRU0's data RAM, CONTROL register and instruction RAM inside
 * it (docs/pru-facts.md §5.4; Linux am33xx-l4.dtsi / am4372.dtsi for the
 * clock controls and remoteproc names).
 */
#ifndef BISS_SOC_H
#define BISS_SOC_H

#include "pruss/pruss_map.h"

#include <stdint.h>

/* PRU-ICSS layout, offsets from its base (same for AM335x and AM437x). */
#define ICSS_DRAM0        PRUSS_OFS_DRAM0
#define ICSS_CTRL0        PRUSS_OFS_CTRL0 /* PRU0 CONTROL */
#define ICSS_IRAM0        PRUSS_OFS_IRAM0
#define ICSS_WINDOW       PRUSS_AM335X_WINDOW /* the largest PRU-ICSS (AM335x) */
#define ICSS_CTRL_RESET_N (1u << 0)
#define ICSS_CTRL_ENABLE  (1u << 1)

/* ... and those of PRU n (0 or 1): PRU1's data RAM, CONTROL and IRAM sit
 * 0x2000, 0x2000 and 0x4000 above PRU0's (docs/pru-facts.md §5.4). */
#define ICSS_DRAM(n) (PRUSS_OFS_DRAM0 + (n) * (PRUSS_OFS_DRAM1 - PRUSS_OFS_DRAM0))
#define ICSS_CTRL(n) (PRUSS_OFS_CTRL0 + (n) * (PRUSS_OFS_CTRL1 - PRUSS_OFS_CTRL0))
#define ICSS_IRAM(n) (PRUSS_OFS_IRAM0 + (n) * (PRUSS_OFS_IRAM1 - PRUSS_OFS_IRAM0))

/* One PRU-ICSS of a SoC, as the host sees it. */
struct biss_soc_icss {
    uint32_t base;       /* physical address of the PRU-ICSS */
    uint32_t window;     /* its size */
    uint32_t iram_bytes; /* PRU0 instruction RAM */
    uint32_t dram_bytes; /* PRU0 data RAM */
    uint32_t clkctrl;    /* CM_PER_PRU_ICSS_CLKCTRL (AM437x: AM4_PRUSS_CLKCTRL) */
    uint32_t iram_phys;  /* PRU0 IRAM: pru_rproc names the instance after it */
    const char *fw_name; /* the firmware name the kernel's device tree gives PRU0 */

    /* ... and PRU1 (its instance is named after its IRAM, iram_phys + 0x4000) */
    const char *fw_name1;
};

/* AM335x: one 512 KB PRU-ICSS. AM437x: ICSS1 at 0x54400000 and ICSS0 at
 * 0x54440000, 256 KB each, one clock control for both. */
#define BISS_SOC_AM335X                                                                            \
    {                                                                                              \
        PRUSS_AM335X_BASE, PRUSS_AM335X_WINDOW, PRUSS_AM335X_IRAM0_BYTES,                          \
            PRUSS_AM335X_DRAM0_BYTES, 0x44E000E8u, PRUSS_AM335X_BASE + PRUSS_OFS_IRAM0,            \
            "am335x-pru0-fw", "am335x-pru1-fw"                                                     \
    }
#define BISS_SOC_AM437X_ICSS1                                                                      \
    {                                                                                              \
        PRUSS_AM437X_ICSS1_BASE, PRUSS_AM437X_ICSS1_WINDOW, PRUSS_AM437X_ICSS1_IRAM0_BYTES,        \
            PRUSS_AM437X_ICSS1_DRAM0_BYTES, 0x44DF8B20u,                                           \
            PRUSS_AM437X_ICSS1_BASE + PRUSS_OFS_IRAM0, "am437x-pru1_0-fw", "am437x-pru1_1-fw"      \
    }
#define BISS_SOC_AM437X_ICSS0                                                                      \
    {                                                                                              \
        PRUSS_AM437X_ICSS0_BASE, PRUSS_AM437X_ICSS0_WINDOW, PRUSS_AM437X_ICSS0_IRAM0_BYTES,        \
            PRUSS_AM437X_ICSS0_DRAM0_BYTES, 0x44DF8B20u,                                           \
            PRUSS_AM437X_ICSS0_BASE + PRUSS_OFS_IRAM0, "am437x-pru0_0-fw", "am437x-pru0_1-fw"      \
    }

#endif
