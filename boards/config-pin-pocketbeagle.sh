#!/bin/sh
# The BiSS-C pins on a PocketBeagle image with the universal cape: MA on
# P1_33 (pr1_pru0_pru_r30_1), SL on P1_36 (pr1_pru0_pru_r31_0).
set -e
config-pin P1_33 pruout
config-pin P1_36 pruin
config-pin -q P1_33
config-pin -q P1_36
