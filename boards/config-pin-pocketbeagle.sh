#!/bin/sh
# The BiSS-C pins on a PocketBeagle image with the universal cape: MA on
# P1_33 (pr1_pru0_pru_r30_1), SL on P1_36 (pr1_pru0_pru_r31_0).
#
# PRU1 (--pru 1) cannot take an encoder on the PocketBeagle: its R31 bit 0
# (pr1_pru1_pru_r31_0, the only input the shift mode samples) is on the
# AM335x's lcd_data0 ball and R30 bit 1 on lcd_data1 (SPRS717L, Signal
# Descriptions, PRU1 table: ZCZ balls R1 and R2 only), and neither ball is
# on P1 or P2 (PocketBeagle System Reference Manual, section 7 "Connectors",
# "P1 Header Pinout" and "P2 Header Pinout": the "Proc Ball" column has no
# R1 or R2). The script says so instead of setting other pins.
set -e
usage() {
	echo "usage: $0 [--pru 0]" >&2
	exit 2
}
pru=0
case "$#:$1" in
0:) ;;
2:--pru) pru=$2 ;;
*) usage ;;
esac
case "$pru" in
0)
	config-pin P1_33 pruout
	config-pin P1_36 pruin
	config-pin -q P1_33
	config-pin -q P1_36
	;;
1)
	echo "$0: PRU1's R31 bit 0 (lcd_data0) and R30 bit 1 (lcd_data1) are not on the PocketBeagle's P1/P2 headers: a second encoder needs a BeagleBone (P8_45/P8_46)" >&2
	exit 1
	;;
*) usage ;;
esac
