#!/bin/sh
# hal_biss under halrun, on the emulator: the firmware reads an encoder
# turning at 40960 counts/s (a 12-bit single turn: ten turns a second) whose
# SL line sticks low 6 s into the run (tests/turning-then-fault.json).
# The servo thread (1 ms) lets 1 ms of emulated time pass a period, so the
# fault comes no earlier than 6 s of wall time after the start. Checked on
# the pins: valid, positions that advance, the turns counted and scaled
# (scale 4096 counts a turn); then the fault: valid false, faults counted;
# then the component unloads and halrun ends cleanly.
#
# usage: halrun_check.sh HALRUN HAL_BISS.SO REDIRECT.SO SOURCE_DIR
#
# halrun loads modules from LinuxCNC's module folder only: the check
# preloads rtlib_redirect.so (REDIRECT) into it, which opens this build's
# hal_biss.so for that name. rtapi_app is set-user-ID root, so the preload
# holds only when the check runs as root; rtapi_app then refuses to run as
# root without a user to fall back to (RTAPI_UID): nobody's.
set -eu
halrun=$1
so=$(readlink -f "$2")
redirect=$(readlink -f "$3")
src=$4
if [ "$(id -u)" -ne 0 ]; then
    echo "FAIL: run as root (rtapi_app is set-user-ID root: a preload holds for root only)," \
         "or install $so into LinuxCNC's module folder and load it from there" >&2
    exit 1
fi
bindir=$(dirname "$so")
firmware=$bindir/../../pru_fw/biss_master.bin
dir=$(mktemp -d)
chmod 755 "$dir"
trap 'rm -rf "$dir"' EXIT

cat >"$dir/check.sh" <<'CHECK'
#!/bin/sh
# polls the pins (halcmd getp) until each stage is seen, or fails
get() { halcmd getp "hal-biss.0.$1"; }
wait_for() { # seconds, shell condition on the pins
    t=0
    while [ "$t" -lt "$1" ]; do
        if eval "$2"; then return 0; fi
        sleep 0.1; t=$((t + 1))
    done
    return 1
}
out=$1
fail() { echo "FAIL: $*" >"$out"; halcmd show pin hal-biss >>"$out"; exit 0; }
wait_for 300 '[ "$(get slave.0.valid)" = TRUE ] && [ "$(get slave.0.turns)" -ge 2 ]' ||
    fail "no valid positions over two turns"
# the pins held still while they are read together (the servo thread
# stopped: no emulated time passes either)
halcmd stop
f1=$(get frame); faults=$(get slave.0.faults); crc=$(get slave.0.crc-errors)
eye=$(get link-eye); lw=$(get link-warning)
raw=$(get slave.0.raw); turns=$(get slave.0.turns); p1=$(get slave.0.position)
halcmd start
# frames are 45.1 us apart (1 MHz): frame 100000 is 4.5 s into the run,
# before the fault at 6 s, however slowly the emulator ran
[ "$(($f1))" -lt 100000 ] || fail "the first look came at frame $(($f1)), too late to be before the fault"
[ "$faults" -eq 0 ] || fail "faults before the line fault"
[ "$crc" -eq 0 ] || fail "CRC errors on a clean line"
[ "$eye" -ge 3 ] && [ "$lw" = FALSE ] || fail "a clean line's eye $eye/8, link warning $lw"
awk -v r="$(($raw))" -v t="$turns" -v p="$p1" 'BEGIN { d = p - (t + r / 4096); exit !(d < 0.01 && d > -0.01) }' ||
    fail "position $p1 is not turns $turns + raw $raw / 4096"
sleep 0.3
p2=$(get slave.0.position); f2=$(get frame)
awk -v a="$p1" -v b="$p2" 'BEGIN { exit !(b > a && a >= 2) }' ||
    fail "the scaled position did not advance past two turns: $p1 then $p2"
[ "$(($f2))" -gt "$(($f1))" ] || fail "no new frames: $f1 then $f2"
wait_for 600 '[ "$(get slave.0.valid)" = FALSE ] && [ "$(get slave.0.faults)" -gt 0 ]' ||
    fail "the line fault never showed"
[ "$(get running)" = TRUE ] || fail "the master stopped at the fault"
echo "PASS: frame $(($f1)): $turns turns, no fault; then $(get slave.0.faults) faulty frames" >"$out"
CHECK

cat >"$dir/test.hal" <<HAL
loadrt threads name1=servo period1=1000000
loadrt hal_biss target=emu scenario=$src/tests/turning-then-fault.json firmware=$firmware
setp hal-biss.0.slave.0.scale 4096
setp hal-biss.0.slave.0.turn-bits 12
addf hal-biss.0.read servo
start
loadusr -w sh $dir/check.sh $dir/result
stop
unload all
HAL

mkdir "$dir/run" && chmod 1777 "$dir/run" # rtapi_app makes its socket there as RTAPI_UID
export RTAPI_FIFO_PATH="$dir/run/fifo"
export RTAPI_UID=65534 BISS_HAL_MODULE="$so" LD_PRELOAD="$redirect"
rc=0
"$halrun" -f "$dir/test.hal" >"$dir/log" 2>&1 || rc=$?
unset LD_PRELOAD
cat "$dir/log"
"$halrun" -U >/dev/null 2>&1 || true
cat "$dir/result" 2>/dev/null || { echo "FAIL: no result (halrun exit $rc)"; exit 1; }
grep -q '^PASS' "$dir/result" || exit 1
[ "$rc" -eq 0 ] || { echo "FAIL: halrun exit $rc"; exit 1; }
if grep -qi "error\|failed" "$dir/log"; then echo "FAIL: errors in halrun's log"; exit 1; fi
