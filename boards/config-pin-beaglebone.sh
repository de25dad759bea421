#!/bin/sh
# The BiSS-C pins on an image with the universal cape (cape-universal,
# config-pin), instead of BB-BISS-PRU0-00A0.dtbo. BeagleBone Black: MA on
# P9_29 (pr1_pru0_pru_r30_1), SL on P9_31 (pr1_pru0_pru_r31_0). HDMI audio
# must be off (disable_uboot_overlay_audio=1 in /boot/uEnv.txt).
set -e
config-pin P9_29 pruout
config-pin P9_31 pruin
config-pin -q P9_29
config-pin -q P9_31
