/* biss_error.c - texts for the error codes and names for the enums. */
#include "libbiss.h"

#include "biss/biss_shm.h"

#include <stddef.h>
#include <string.h>

struct err_text {
    int code;
    const char *text;
};

static const struct err_text errors[] = {
    {BISS_OK, "success"},
    {BISS_E_INVAL, "invalid argument"},
    {BISS_E_NOMEM, "out of memory"},
    {BISS_E_TARGET, "unknown target (emu, am335x, am437x-icss0, am437x-icss1)"},
    {BISS_E_FIRMWARE_IO, "firmware image cannot be read"},
    {BISS_E_FIRMWARE_SIZE, "firmware image is empty, not whole 32-bit words, or too big for IRAM"},
    {BISS_E_DEVMEM, "the PRU-ICSS memory cannot be opened or mapped"},
    {BISS_E_PROFILE, "unknown emulator profile"},
    {BISS_E_SCENARIO, "scenario file cannot be read or is invalid"},
    {BISS_E_EMU, "emulator bench cannot be built"},
    {BISS_E_RATE_RANGE, "MA rate out of range (10 MHz down to 125 kHz, the slowest in whole Hz: "
                        "H = 10..1024 PRU cycles)"},
    {BISS_E_RATE_INEXACT, "MA rate is not 100 MHz divided by a whole number"},
    {BISS_E_RATE_SHIFT,
     "MA rate has no exact 8x shift clock (100 MHz / f must be a*b with 2 <= a, b <= 32)"},
    {BISS_E_NSLAVES, "slave count out of range (1..8)"},
    {BISS_E_DATA_BITS, "slave data bits out of range (1..64)"},
    {BISS_E_CRC_BITS, "slave CRC bits out of range (0..16)"},
    {BISS_E_CRC_POLY, "CRC polynomial's degree does not match the CRC bits (give it with its "
                      "top term, e.g. 0x43 for CRC6)"},
    {BISS_E_CRC_START, "CRC start value wider than the CRC"},
    {BISS_E_EW, "nE/nW position outside the data word"},
    {BISS_E_POS_BITS, "position bits do not fit in the data word above nE/nW"},
    {BISS_E_TRIGGER, "unknown trigger mode (host, iep, iep-follow, free)"},
    {BISS_E_IEP_PERIOD, "IEP period not a multiple of 5 ns or shorter than one frame"},
    {BISS_E_PROC_LIMIT, "processing-time limit above 65534 MA clocks"},
    {BISS_E_SSI, "SSI: one slave only, without CRC or nE/nW, delay at most 65535 ns"},
    {BISS_E_TIMEOUT, "timed out waiting for the firmware"},
    {BISS_E_NOT_RUNNING, "firmware not running (no magic in data RAM)"},
    {BISS_E_NO_SAMPLE, "no frame published yet"},
    {BISS_E_RETRY, "no consistent sample: the firmware kept publishing during the read"},
    {BISS_E_NOT_HOST_TRIG, "trigger needs host-trigger mode"},
    {BISS_E_NOT_CONFIGURED, "not configured"},
    {BISS_E_PRU_FAULT, "the PRU faulted or halted"},
    {BISS_E_IO, "access outside the mapped PRU-ICSS window"},
    {BISS_E_NOT_EMU, "only the emulator target can do this"},
    {BISS_E_STOPPED, "the PRU is stopped"},
    {BISS_E_CD_BUSY, "a control-communication program is still running"},
    {BISS_E_CD_WAIT, "the slave's start bit S did not come within the wait limit"},
    {BISS_E_CD_FRAME, "a frame failed during control communication"},
    {BISS_E_CD_STEPS, "control-communication program length out of range (1..1024)"},
    {BISS_E_CD_CRC, "register data came back with a wrong CRC4"},
    {BISS_E_CD_ECHO, "the write was not echoed as sent"},
    {BISS_E_CD_WITHHELD, "IDA test failed: the command was withheld"},
    {BISS_E_CD_NO_ECHO, "no slave took the control frame (wrong ID or header CRC)"},
    {BISS_E_CD_IDA, "the command's IDA answers differ from the addressed slaves"},
    {BISS_E_FW_NSLAVES, "firmware refused the configuration: slave count"},
    {BISS_E_FW_HALF, "firmware refused the configuration: MA half period"},
    {BISS_E_FW_DATA_BITS, "firmware refused the configuration: data bits"},
    {BISS_E_FW_CRC_BITS, "firmware refused the configuration: CRC bits"},
    {BISS_E_FW_TRIGGER, "firmware refused the configuration: trigger mode"},
    {BISS_E_FW_EW, "firmware refused the configuration: nE/nW position"},
    {BISS_E_FW_IEP_PERIOD, "firmware refused the configuration: IEP period"},
    {BISS_E_FW_SSI, "firmware refused the configuration: SSI"},
    {BISS_E_FW_UNKNOWN, "firmware refused the configuration (unknown reason)"},
    {BISS_E_NOT_POWERED, "the PRU-ICSS is not powered (load/enable the pruss driver)"},
    {BISS_E_BUSY, "the PRU is in use by another process"},
    {BISS_E_RPROC, "no usable remoteproc instance for this PRU"},
    {BISS_E_RPROC_BUSY, "the PRU's remoteproc instance runs another firmware"},
    {BISS_E_FW_ID, "no image identification block in data RAM (not this firmware)"},
    {BISS_E_SHM_VERSION, "the firmware's shared-memory version differs from this library's"},
    {BISS_E_FW_IMAGE, "the running firmware image is not the expected one (CRC-32 differs)"},
    {BISS_E_SHM_CONFIG, "the configuration block read back from data RAM is invalid"},
    {BISS_E_SHM_RESULT, "data RAM holds a result or status word the firmware never writes "
                        "(junk; biss_shm_problem names it)"},
    {BISS_E_SAFETY_LIFE, "life-counter check: no such slave, or a width outside 1..32 or wider "
                         "than the bits below nE/nW and the position"},
    {BISS_E_SAFETY_PAIR, "pair check: a slave outside the chain or paired with itself, too "
                         "many pairs, or a shifted position over 64 bits"},
    {BISS_E_SAFETY_CRC, "pair check of two channels: both CRCs have the same polynomial and "
                        "start value (the channels must differ)"},
    {BISS_E_SAFETY_EW, "nE/nW check (a slave that never sets them): no such slave, or the "
                       "slave sends no nE/nW"},
    {BISS_E_IEP_OWNED, "the other PRU's channel owns the IEP (trigger iep): use iep-follow"},
    {BISS_E_FW_PRU, "the image was assembled for the other PRU (PRU0: biss_master, "
                    "PRU1: biss_master_pru1)"},
    {BISS_E_SAFETY_SPEED, "speed check (max_speed): no such slave in the chain, or the speed "
                          "is not a finite number above 0"},
    {BISS_E_LINE_TIMEOUT, "the slave's timeout is below 55 % of the MA period (iC-MB4 I306): "
                          "choose a faster rate"},
    {BISS_E_LINE_DELAY, "the line's round trip is beyond the 40 us the firmware waits for the "
                        "ACK"},
    {BISS_E_ENC_LC_BITS, "encoder: a life counter over 32 bits"},
    {BISS_E_ENC_ID, "encoder: an ID over 7, or two answering slaves with one ID"},
    {BISS_E_ENC_TABLE, "encoder: table entries past the table's 128"},
    {BISS_E_ENC_BANKS, "encoder: register banks past the pool's 16"},
    {BISS_E_ENC_TIMEOUT, "encoder: timeout 0 or over 1.31 ms, or an adaptive factor (1..255 "
                         "sixteenths) or minimum out of range"},
    {BISS_E_ENC_BUSY, "encoder: processing time over 83 ms or 65535 clocks"},
    {BISS_E_ENC_REG_WAIT, "encoder: register processing time over 255 frames, or an execute "
                          "bit other than 0 or 1"},
    {BISS_E_ENC_REFUSED, "the encoder firmware refused the configuration"},
    {BISS_E_TRIGGER_PENDING, "the last trigger has not started its frame yet"},
    {BISS_E_SSI_NO_CONTROL, "an SSI encoder has no control communication (registers, commands; "
                            "a program running when SSI was configured ends with this)"},
};

const char *biss_strerror(int err) {
    for (size_t i = 0; i < sizeof errors / sizeof errors[0]; i++) {
        if (errors[i].code == err) {
            return errors[i].text;
        }
    }
    return "unknown error";
}

static const char *const target_names[] = {
    [BISS_TARGET_EMU] = "emu",
    [BISS_TARGET_AM335X] = "am335x",
    [BISS_TARGET_AM437X_ICSS0] = "am437x-icss0",
    [BISS_TARGET_AM437X_ICSS1] = "am437x-icss1",
};

int biss_target_from_name(const char *name, enum biss_target *t) {
    if (!name || !t) {
        return BISS_E_INVAL;
    }
    for (size_t i = 0; i < sizeof target_names / sizeof target_names[0]; i++) {
        if (strcmp(name, target_names[i]) == 0) {
            *t = (enum biss_target)i;
            return BISS_OK;
        }
    }
    /* the architecture's short name: ICSS0, as TIDEP0022 on the AM437x IDK
     * (whose device tree gives ICSS1 to PRU Ethernet) */
    if (strcmp(name, "am437x") == 0) {
        *t = BISS_TARGET_AM437X_ICSS0;
        return BISS_OK;
    }
    return BISS_E_TARGET;
}

const char *biss_target_name(enum biss_target t) {
    if ((unsigned)t >= sizeof target_names / sizeof target_names[0]) {
        return "?";
    }
    return target_names[t];
}

int biss_trigger_from_name(const char *name, enum biss_trigger *t) {
    if (!name || !t) {
        return BISS_E_INVAL;
    }
    if (strcmp(name, "host") == 0) {
        *t = BISS_TRIGGER_HOST;
    } else if (strcmp(name, "iep") == 0) {
        *t = BISS_TRIGGER_IEP;
    } else if (strcmp(name, "iep-follow") == 0) {
        *t = BISS_TRIGGER_IEP_FOLLOW;
    } else if (strcmp(name, "free") == 0 || strcmp(name, "freerun") == 0) {
        *t = BISS_TRIGGER_FREERUN;
    } else {
        return BISS_E_TRIGGER;
    }
    return BISS_OK;
}

const char *biss_trigger_name(enum biss_trigger t) {
    switch (t) {
    case BISS_TRIGGER_HOST:
        return "host";
    case BISS_TRIGGER_IEP:
        return "iep";
    case BISS_TRIGGER_IEP_FOLLOW:
        return "iep-follow";
    case BISS_TRIGGER_FREERUN:
        return "free";
    }
    return "?";
}

const char *biss_fw_state_name(uint32_t state) {
    switch (state) {
    case BISS_STATE_STOPPED:
        return "stopped";
    case BISS_STATE_RUNNING:
        return "running";
    case BISS_STATE_CFG_ERROR:
        return "config-error";
    case BISS_STATE_NO_SLAVE:
        return "no-slave";
    default:
        return "unknown";
    }
}

int biss_loader_from_name(const char *name, enum biss_loader *l) {
    if (!name || !l) {
        return BISS_E_INVAL;
    }
    if (strcmp(name, "remoteproc") == 0) {
        *l = BISS_LOADER_REMOTEPROC;
    } else if (strcmp(name, "devmem") == 0) {
        *l = BISS_LOADER_DEVMEM;
    } else {
        return BISS_E_INVAL;
    }
    return BISS_OK;
}
