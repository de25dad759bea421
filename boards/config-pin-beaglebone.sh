#!/bin/sh
# The BiSS-C pins on an image with the universal cape (cape-universal,
# config-pin), instead of the overlays. BeagleBone Black:
#   PRU0 (default):  MA on P9_29 (pr1_pru0_pru_r30_1), SL on P9_31 (pr1_pru0_pru_r31_0)
#   --pru 1:         MA on P8_46 (pr1_pru1_pru_r30_1), SL on P8_45 (pr1_pru1_pru_r31_0)
# (BB-BISS-PRU01-00A0.dts has the sources.) PRU0's pins are McASP0: HDMI
# audio must be off (disable_uboot_overlay_audio=1 in /boot/uEnv.txt).
# PRU1's are LCD data 0 and 1, wired to the HDMI framer: HDMI video must be
# off (disable_uboot_overlay_video=1).
set -e
usage() {
	echo "usage: $0 [--pru 0|1]" >&2
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
	config-pin P9_29 pruout
	config-pin P9_31 pruin
	config-pin -q P9_29
	config-pin -q P9_31
	;;
1)
	config-pin P8_46 pruout
	config-pin P8_45 pruin
	config-pin -q P8_46
	config-pin -q P8_45
	;;
*) usage ;;
esac
