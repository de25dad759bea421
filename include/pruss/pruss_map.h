/*
 * pruss_map.h - where the PRU-ICSS blocks sit, as the ARM host sees them,
 * and the PRU-ICSS instances of the supported SoCs (docs/pru-facts.md
 * §5.4). The one source of these facts: the host side (proto/biss_soc.h)
 * and the emulator's memory map (emulator/core) both take them from here.
 */
#ifndef BISS_PRUSS_MAP_H
#define BISS_PRUSS_MAP_H

/* Offsets from a PRU-ICSS base (AM335x and AM437x alike). */
#define PRUSS_OFS_DRAM0  0x00000u
#define PRUSS_OFS_DRAM1  0x02000u
#define PRUSS_OFS_SHARED 0x10000u
#define PRUSS_OFS_INTC   0x20000u
#define PRUSS_OFS_CTRL0  0x22000u /* PRU0 CONTROL */
#define PRUSS_OFS_DEBUG0 0x22400u
#define PRUSS_OFS_CTRL1  0x24000u
#define PRUSS_OFS_CFG    0x26000u
#define PRUSS_OFS_IEP    0x2E000u
#define PRUSS_OFS_IRAM0  0x34000u
#define PRUSS_OFS_IRAM1  0x38000u

/* The instances: base, size of the window, PRU0's IRAM and data RAM, the
 * shared RAM. AM335x: one 512 KB PRU-ICSS. AM437x: ICSS1 at 0x54400000 and
 * ICSS0 at 0x54440000, 256 KB each; ICSS0 has no shared RAM. */
#define PRUSS_AM335X_BASE         0x4A300000u
#define PRUSS_AM335X_WINDOW       0x80000u
#define PRUSS_AM335X_IRAM0_BYTES  8192u
#define PRUSS_AM335X_DRAM0_BYTES  8192u
#define PRUSS_AM335X_SHARED_BYTES 12288u

#define PRUSS_AM437X_ICSS1_BASE         0x54400000u
#define PRUSS_AM437X_ICSS1_WINDOW       0x40000u
#define PRUSS_AM437X_ICSS1_IRAM0_BYTES  12288u
#define PRUSS_AM437X_ICSS1_DRAM0_BYTES  8192u
#define PRUSS_AM437X_ICSS1_SHARED_BYTES 32768u

#define PRUSS_AM437X_ICSS0_BASE         0x54440000u
#define PRUSS_AM437X_ICSS0_WINDOW       0x40000u
#define PRUSS_AM437X_ICSS0_IRAM0_BYTES  4096u
#define PRUSS_AM437X_ICSS0_DRAM0_BYTES  4096u
#define PRUSS_AM437X_ICSS0_SHARED_BYTES 0u

#endif
